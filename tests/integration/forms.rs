//! The Rust rendering of every built-in scheme's closed forms compiles and is right:
//! `generated_forms.rs` is the checked-in output of `ClosedForm::to_rust` for every phase
//! (`UPDATE_EXPECT=1 cargo test -p subcount-tests` rewrites it), included here as code and
//! compared with powering for levels 0 to 20.

use halfedge::{shapes, stats};
use num_bigint::BigInt;
use subcount_tests::{applies, generated_forms_source, BASE_MESHES};

#[allow(unreachable_pub, clippy::all)]
mod generated {
    include!("generated_forms.rs");
}

use generated::FORMS;

/// `generated_forms.rs` is what the code generates (`UPDATE_EXPECT=1` rewrites it).
#[test]
fn generated_forms_are_current() {
    expect_test::expect_file!["generated_forms.rs"].assert_eq(&generated_forms_source());
}

/// Every phase of every built-in scheme has a generated function, in order.
#[test]
fn every_phase_has_a_function() -> Result<(), Box<dyn std::error::Error>> {
    let mut expected = Vec::new();
    for s in schemes::builtins() {
        for i in 0..s.phases().len() {
            expected.push((s.name().to_string(), i));
        }
    }
    let have: Vec<(String, usize)> = FORMS.iter().map(|(n, i, _)| (n.to_string(), *i)).collect();
    assert_eq!(have, expected);
    assert!(have.iter().any(|(n, i)| n == "sqrt3-boundary" && *i == 1));
    Ok(())
}

fn to_i128(x: &[BigInt]) -> Vec<i128> {
    x.iter()
        .map(|v| i128::try_from(v).unwrap_or_else(|_| panic!("{v} does not fit i128")))
        .collect()
}

/// Each generated function equals the phase's recurrence powered, for the state of every base
/// mesh the scheme applies to and for an arbitrary integer state, at t = 0..=20; and on a mesh
/// it gives the scheme's own counts at levels `first_level + period * t`.
#[test]
fn generated_forms_equal_powering() -> Result<(), Box<dyn std::error::Error>> {
    for &(name, index, form) in FORMS {
        let scheme = schemes::builtin(name)?;
        let phases = scheme.phases();
        let phase = &phases[index];
        let dim = scheme.dim();
        let mut starts: Vec<Vec<BigInt>> =
            vec![(0..dim).map(|i| BigInt::from(3 * i + 2)).collect()];
        let mut meshes = 0;
        for mesh in BASE_MESHES {
            let counts = stats::face_list_counts(&shapes::from_name(mesh)?);
            if !applies(&scheme, &counts) {
                continue;
            }
            meshes += 1;
            let x0 = scheme.initial_state(&counts)?;
            let at_first = scheme.state_at(&x0, phase.first_level)?;
            for t in 0..=20u64 {
                let level = phase.first_level + phase.period * t;
                let got = form(&to_i128(&at_first), t);
                assert_eq!(
                    got,
                    Some(to_i128(&scheme.state_at(&x0, level)?)),
                    "{name} phase {index} on {mesh} at t = {t} (level {level})"
                );
            }
            starts.push(at_first);
        }
        assert!(meshes > 0, "no base mesh for {name}");
        for x in &starts {
            for t in 0..=20u64 {
                let want = phase.recurrence.state_at(x, t)?;
                assert_eq!(
                    form(&to_i128(x), t),
                    Some(to_i128(&want)),
                    "{name} phase {index} from {x:?} at t = {t}"
                );
            }
        }
        // A wrong length is refused, not misread.
        assert_eq!(form(&vec![1; dim + 1], 1), None);
    }
    Ok(())
}
