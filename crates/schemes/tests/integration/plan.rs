//! Composition `A:k,B`: parsing, class checks, state mapping, phases.

use num_bigint::BigInt;
use schemes::{builtin, CountsInput, Error, Plan, Scheme};

use crate::meshes::*;

fn big(v: &[i64]) -> Vec<BigInt> {
    v.iter().map(|&x| BigInt::from(x)).collect()
}

#[test]
fn single_scheme_plan_matches_the_scheme() {
    let plan = Plan::parse("loop-boundary").unwrap();
    let scheme = builtin("loop-boundary").unwrap();
    assert!(plan.is_single());
    assert_eq!(plan.name(), "loop-boundary");
    for level in 0..8 {
        assert_eq!(
            plan.counts_at(&triangle_strip(), level).unwrap(),
            scheme.counts_at(&triangle_strip(), level).unwrap()
        );
    }
    assert_eq!(plan.phases(), scheme.phases());
}

#[test]
fn catmull_clark_then_quad_rule_on_a_triangle() {
    // Triangle -> 3 quads (V 7, IE 3, BE 6, F 3) -> 12 quads (V 19, E 30, F 12).
    // Level 3 under catmull-clark-quad from (19, 30, 12): V 61, E 108, F 48.
    let plan = Plan::parse("catmull-clark:2,catmull-clark-quad").unwrap();
    assert_eq!(plan.name(), "catmull-clark:2,catmull-clark-quad");
    let x0 = plan.initial_state(&triangle()).unwrap();
    assert_eq!(plan.state_at(&x0, 2).unwrap(), big(&[19, 18, 12, 12, 48]));
    assert_eq!(plan.state_names_at(2).unwrap(), ["V", "IE", "BE", "F", "H"]);
    assert_eq!(plan.state_at(&x0, 3).unwrap(), big(&[61, 108, 48]));
    assert_eq!(plan.state_names_at(3).unwrap(), ["V", "E", "F"]);
    // One table for the whole composition: every stage's state, then the missing V, E, F;
    // a level leaves empty the columns its stage does not count.
    let counter = schemes::Counter::from(plan.clone());
    assert_eq!(counter.columns(), ["V", "IE", "BE", "F", "H", "E"]);
    let some = |v: &[i64]| big(v).into_iter().map(Some).collect::<Vec<_>>();
    assert_eq!(
        counter.row_at(&x0, 2).unwrap().values,
        some(&[19, 18, 12, 12, 48, 30])
    );
    let row = counter.row_at(&x0, 3).unwrap().values;
    assert_eq!(
        row,
        [
            Some(61.into()),
            None,
            None,
            Some(48.into()),
            None,
            Some(108.into())
        ]
    );
    // The composition gives the same V, E, F as catmull-clark alone, at every level.
    let cc = builtin("catmull-clark").unwrap();
    let seq = plan.states_up_to(&x0, 7).unwrap();
    for level in 0..=7u64 {
        let a = plan.level_counts(&x0, level).unwrap();
        let b = cc.level_counts(&x0, level).unwrap();
        assert_eq!(
            [&a.vertices, &a.edges, &a.faces],
            [&b.vertices, &b.edges, &b.faces]
        );
        assert_eq!(seq[level as usize], a.state);
    }
}

#[test]
fn loop_then_loop_boundary_and_back() {
    // Closed octahedron: loop:2 ends at (66, 192); loop-boundary needs (V, IE, BE) =
    // (66, 192, 0) from the closed-mesh identities; loop-general (V, E, F) = (66, 192, 128).
    let plan = Plan::parse("loop:2,loop-boundary:1,loop-general").unwrap();
    let x0 = plan.initial_state(&octahedron()).unwrap();
    assert_eq!(plan.state_at(&x0, 2).unwrap(), big(&[66, 192]));
    assert_eq!(plan.state_at(&x0, 3).unwrap(), big(&[258, 768, 0]));
    assert_eq!(plan.state_at(&x0, 4).unwrap(), big(&[1026, 3072, 2048]));
    let single = builtin("loop").unwrap();
    for level in 0..7 {
        assert_eq!(
            plan.level_counts(&x0, level).unwrap().vertices,
            single.level_counts(&x0, level).unwrap().vertices
        );
    }
    // loop-boundary on a closed mesh, then loop: BE = 0 is known from the state.
    let plan = Plan::parse("loop-boundary:1, loop").unwrap();
    let x0 = plan.initial_state(&tetrahedron()).unwrap();
    assert_eq!(plan.state_at(&x0, 2).unwrap(), big(&[34, 96]));
}

#[test]
fn refused_compositions() {
    let err = Plan::parse("catmull-clark:1,loop").unwrap_err();
    assert_eq!(
        err.to_string(),
        "loop needs a triangle mesh, but catmull-clark produces quads; use catmull-clark"
    );
    let err = Plan::parse("doo-sabin:1,catmull-clark-quad").unwrap_err();
    assert_eq!(
        err.to_string(),
        "catmull-clark-quad needs a quad mesh, but doo-sabin produces polygons; use catmull-clark"
    );
    // After loop-boundary the mesh still has its boundary: loop is refused with the value.
    let plan = Plan::parse("loop-boundary:2,loop").unwrap();
    let x0 = plan.initial_state(&triangle()).unwrap();
    assert_eq!(
        plan.state_at(&x0, 3).unwrap_err().to_string(),
        "loop needs a closed mesh, but after 2 levels of loop-boundary BE = 12; use loop-boundary"
    );
    // The levels before the switch are still available.
    assert_eq!(plan.state_at(&x0, 2).unwrap(), big(&[15, 18, 12]));
    // loop-general does not count boundary edges, so a closed-mesh scheme cannot follow.
    let plan = Plan::parse("loop-general:1,loop").unwrap();
    let x0 = plan.initial_state(&tetrahedron()).unwrap();
    assert_eq!(
        plan.state_at(&x0, 2).unwrap_err().to_string(),
        "loop needs every edge to have one or two faces, but after 1 level of loop-general the \
         non-manifold edges are not known; use loop-general"
    );
    // Syntax.
    for (text, expected) in [
        ("loop,loop-boundary", "scheme plan `loop,loop-boundary`: `loop` is followed by another scheme, so it needs a level count (`loop:k`)"),
        ("loop:x,loop", "scheme plan `loop:x,loop`: `x` after `loop:` is not a level count"),
        ("loop:2,", "scheme plan `loop:2,`: scheme 2 has no name"),
    ] {
        assert_eq!(Plan::parse(text).unwrap_err().to_string(), expected);
    }
    assert!(matches!(
        Plan::parse("loop:1,nope"),
        Err(Error::UnknownScheme { .. })
    ));
    // A bounded last stage.
    let plan = Plan::parse("loop:1,loop-general:2").unwrap();
    assert_eq!(plan.last_level(), Some(3));
    let x0 = plan.initial_state(&tetrahedron()).unwrap();
    assert!(matches!(
        plan.state_at(&x0, 4),
        Err(Error::LevelBeyondPlan { level: 4, last: 3 })
    ));
}

#[test]
fn phases_of_periodic_and_composed_plans() {
    let plan = Plan::parse("loop-boundary:3,sqrt3-boundary").unwrap();
    let phases = plan.phases();
    let d: Vec<&str> = phases.iter().map(|p| p.description.as_str()).collect();
    assert_eq!(d, ["s = t, s <= 3", "s = 2t + 3", "s = 2t + 4"]);
    let x0 = plan.initial_state(&triangle_strip()).unwrap();
    // Each phase's recurrence reproduces the plan's states at its levels.
    for phase in &phases {
        let init = plan.phase_initial(phase, &x0).unwrap();
        for t in 0..5u64 {
            let s = phase.first_level + phase.period * t;
            if phase.last_level.is_some_and(|l| s > l) {
                break;
            }
            let expected = if phase.stage == 1 && s == 3 {
                // At the boundary level the plan reports the earlier stage's state; the phase
                // starts from it mapped into the later stage's names.
                init.clone()
            } else {
                plan.state_at(&x0, s).unwrap()
            };
            assert_eq!(
                phase.recurrence.state_at(&init, t).unwrap(),
                expected,
                "{}",
                phase.description
            );
        }
    }
    assert_eq!(phases[1].recurrence.names(), ["V", "IE", "BE", "F"]);
}

#[test]
fn custom_schemes_in_plans() {
    let text = builtin("catmull-clark")
        .unwrap()
        .to_toml()
        .replace("name = \"catmull-clark\"", "name = \"my-cc\"");
    let mine = Scheme::from_toml(&text).unwrap();
    let resolve = |name: &str| {
        if name == "my-cc" {
            Ok(mine.clone())
        } else {
            builtin(name)
        }
    };
    let plan = Plan::parse_with("my-cc:1,catmull-clark-quad", resolve).unwrap();
    let x0 = plan
        .state_from_input(&"V=3,IE=0,BE=3,F=1,H=3".parse::<CountsInput>().unwrap())
        .unwrap();
    assert_eq!(plan.state_at(&x0, 2).unwrap(), big(&[19, 30, 12]));
}
