//! Custom schemes: the shipped example files, broken files, export and re-import.

use std::path::PathBuf;

use num_bigint::BigInt;
use schemes::{builtin, builtins, CountsInput, Error, Scheme};

use crate::meshes::*;

fn example(name: &str) -> Scheme {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/schemes")
        .join(name);
    let text = std::fs::read_to_string(&path).expect("example file exists");
    Scheme::from_toml(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn big(v: &[i64]) -> Vec<BigInt> {
    v.iter().map(|&x| BigInt::from(x)).collect()
}

#[test]
fn example_fibonacci() {
    let fib = example("fibonacci.toml");
    assert_eq!(fib.state_names(), ["a", "b"]);
    assert!(!fib.has_mesh_counts());
    let x = fib.state_at(&big(&[1, 0]), 10).unwrap();
    assert_eq!(x, big(&[89, 55]));
    assert!(matches!(
        fib.vef(&x),
        Err(Error::NoMeshCounts { what, .. }) if what == "V"
    ));
    // Its state is not a mesh statistic: counts must name it.
    let x0 = fib
        .state_from_input(&"a=1,b=0".parse::<CountsInput>().unwrap())
        .unwrap();
    assert_eq!(x0, big(&[1, 0]));
    let err = fib.initial_state(&tetrahedron()).unwrap_err();
    assert!(matches!(err, Error::MissingComponents { .. }));
}

#[test]
fn example_loop_boundary_matches_the_builtin() {
    let mine = example("loop-boundary.toml");
    let builtin = builtin("loop-boundary").unwrap();
    assert_eq!(mine.name(), "my-loop-boundary");
    assert_eq!(mine.matrix(), builtin.matrix());
    for mesh in [triangle(), triangle_strip(), octahedron()] {
        for level in 0..6 {
            let a = mine.counts_at(&mesh, level).unwrap();
            let b = builtin.counts_at(&mesh, level).unwrap();
            assert_eq!(a, b);
        }
    }
    assert_eq!(
        mine.initial_state(&cube()).unwrap_err().to_string(),
        "my-loop-boundary needs a triangle mesh, but this mesh has 6 faces of degree 4"
    );
}

#[test]
fn derived_counts_must_be_integers_for_an_initial_state() {
    let text = "name = \"x\"\nstate = [\"V\", \"E\"]\nmatrix = [[1, 1], [0, 4]]\n[derive]\nF = { E = 1, divide_by = 2 }\n";
    let s = Scheme::from_toml(text).unwrap();
    let err = s
        .state_from_input(&"V=3,E=3".parse::<CountsInput>().unwrap())
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "F = E/2 = 3/2 is not an integer for this state of x"
    );
    assert_eq!(
        s.state_from_input(&"V=3,E=4".parse::<CountsInput>().unwrap())
            .unwrap(),
        big(&[3, 4])
    );
}

#[test]
fn example_periodic_sqrt3_boundary_matches_the_builtin() {
    let mine = example("sqrt3-boundary.toml");
    let builtin = builtin("sqrt3-boundary").unwrap();
    assert_eq!(mine.period(), 2);
    assert_eq!(mine.phases().len(), 2);
    for level in 0..9 {
        assert_eq!(
            mine.counts_at(&triangle_strip(), level).unwrap(),
            builtin.counts_at(&triangle_strip(), level).unwrap()
        );
    }
}

#[test]
fn example_first_step_catmull_clark_on_triangles() {
    let cc = example("catmull-clark-triangles.toml");
    let general = builtin("catmull-clark-general").unwrap();
    // Tetrahedron: level 1 = 14 V, 24 E, 12 F; level 2 = 50, 96, 48 (as catmull-clark).
    assert_eq!(
        cc.counts_at(&tetrahedron(), 1).unwrap().state,
        big(&[14, 24, 12])
    );
    assert_eq!(
        cc.counts_at(&tetrahedron(), 2).unwrap().state,
        big(&[50, 96, 48])
    );
    for mesh in [tetrahedron(), triangle_strip(), book()] {
        for level in 0..7 {
            let a = cc.counts_at(&mesh, level).unwrap();
            let b = general.counts_at(&mesh, level).unwrap();
            assert_eq!(
                [&a.vertices, &a.edges, &a.faces],
                [&b.vertices, &b.edges, &b.faces]
            );
        }
    }
    // Phases: levels 1 + t follow the steady matrix.
    let phases = cc.phases();
    assert_eq!(phases.len(), 1);
    assert_eq!(phases[0].description, "s = t + 1");
    assert_eq!(phases[0].first_level, 1);
}

#[test]
fn every_builtin_round_trips_through_toml() {
    for s in builtins() {
        let text = s.to_toml();
        let again =
            Scheme::from_toml(&text).unwrap_or_else(|e| panic!("{}: {e}\n{text}", s.name()));
        assert_eq!(again.name(), s.canonical_name());
        assert_eq!(again.description(), s.description());
        assert_eq!(again.state_names(), s.state_names());
        assert_eq!(again.rule(), s.rule());
        assert_eq!(again.mesh_class(), s.mesh_class());
        assert_eq!(again.produces(), s.produces());
        assert_eq!(again.derived(), s.derived());
        assert_eq!(again.subdivision_rule(), s.subdivision_rule());
        assert_eq!(again.to_toml(), text);
    }
    let text = builtin("loop").unwrap().to_toml();
    assert_eq!(
        text,
        "# subdivision scheme `loop`\n\
         name = \"loop\"\n\
         description = \"4:1 triangle split (Loop topology) on closed triangle meshes, paper Theorem 5.1\"\n\
         state = [\"V\", \"E\"]\n\
         requires = [\"triangles\", \"closed\"]\n\
         produces = \"triangles\"\n\
         topology = \"loop\"\n\
         matrix = [\n  [1, 1],\n  [0, 4],\n]\n\
         \n[derive]\nF = { E = 2, divide_by = 3 }\n"
    );
}

/// Broken files and the exact error each gives.
#[test]
fn broken_files() {
    let head = "name = \"x\"\nstate = [\"V\", \"E\"]\n";
    let cases: Vec<(String, &str)> = vec![
        (format!("{head}matrix = [[1, 1], [0, 4, 1]]\n"),
         "line 3, column 19: row 2 has 3 entries, but the matrix has 2 rows (it must be square)"),
        (format!("{head}matrix = [[1, 1, 0], [0, 4, 0], [0, 0, 1]]\n"),
         "line 3, column 10: the matrix is 3x3, but the state has 2 components"),
        (format!("{head}matrix = []\n"), "line 3, column 10: the matrix is empty"),
        (format!("{head}matrix = [[1, 1], [0, 9223372036854775808]]\n"),
         "line 3, column 23: number too large to fit in target type"),
        (format!("{head}matrix = [[1, 1], [0, 4]]\ncolour = \"red\"\n"),
         "line 4, column 1: unknown field `colour`, expected one of `name`, `description`, `state`, `matrix`, `cycle`, `first_step`, `derive`, `requires`, `produces`, `topology`"),
        ("name = \"x\"\nstate = [\"V\", \"V\"]\nmatrix = [[1, 1], [0, 4]]\n".into(),
         "line 2, column 15: state name `V` is used twice"),
        ("name = \"x\"\nstate = []\nmatrix = [[1]]\n".into(), "line 2, column 9: the state is empty"),
        ("name = \"x\"\nstate = [\"2V\"]\nmatrix = [[1]]\n".into(),
         "line 2, column 10: state name `2V` is not valid (use letters, digits and `_`, starting with a letter)"),
        (format!("{head}matrix = [[1, 1], [0, 4]]\ncycle = [[[1, 1], [0, 4]]]\n"),
         "line 4, column 9: give either `matrix` or `cycle`, not both"),
        (head.to_string(), "line 3, column 1: missing `matrix` (or `cycle` for a periodic scheme)"),
        (format!("{head}matrix = [[1, 1], [0, 4]]\n[derive]\nF = {{ IE = 2 }}\n"),
         "line 5, column 7: `derive.F` names `IE`, which is not a state component (V, E)"),
        (format!("{head}matrix = [[1, 1], [0, 4]]\n[derive]\nE = {{ V = 2 }}\n"),
         "line 5, column 1: E is a state component; `derive` is for V, E, F outside the state"),
        (format!("{head}matrix = [[1, 1], [0, 4]]\nrequires = [\"watertight\"]\n"),
         "line 4, column 13: unknown requirement `watertight`; use triangles, quads, closed, manifold"),
        ("name = \"x\"\nstate = [\"V\", \"k\"]\nrequires = [\"closed\"]\nmatrix = [[1, 1], [0, 4]]\n".into(),
         "line 2, column 15: state `k` is not a mesh statistic (V, E, IE, BE, NME, F, H), so a mesh cannot supply it; drop `requires` for a state given by hand"),
        (format!("{head}matrix = [[1, 1], [0, 4.5]]\n"),
         "line 3, column 23: invalid type: floating point `4.5`, expected i64"),
        (format!("{head}matrix = [[1, 1], [0, 4]\n"),
         "line 4, column 1: invalid array; expected `]`"),
        ("name = \"a b\"\nstate = [\"V\"]\nmatrix = [[1]]\n".into(),
         "line 1, column 8: scheme name `a b` may only use letters, digits, `-` and `_`"),
        (format!("{head}first_step = [[1]]\nmatrix = [[1, 1], [0, 4]]\n"),
         "line 3, column 14: first_step is 1x1, but the state has 2 components"),
        (format!("{head}cycle = [[[1, 1], [0, 4]], [[1]]]\n"),
         "line 3, column 28: matrix 2 of the cycle is 1x1, but the state has 2 components"),
        ("state = [\"V\"]\nmatrix = [[1]]\n".into(), "line 1, column 1: missing field `name`"),
    ];
    let mut failures = Vec::new();
    for (text, expected) in &cases {
        match Scheme::from_toml(text) {
            Ok(_) => failures.push(format!("accepted:\n{text}")),
            Err(e) => {
                assert!(matches!(e, Error::SchemeFile { .. }), "{e:?}");
                if e.to_string() != *expected {
                    failures.push(format!("{text}\n  got:      {e}\n  expected: {expected}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn first_step_then_cycle() {
    let text = "name = \"mixed\"\nstate = [\"a\", \"b\"]\n\
                first_step = [[2, 0], [1, 1]]\n\
                cycle = [[[1, 1], [0, 1]], [[1, 0], [2, 3]], [[3, 0], [0, 1]]]\n";
    let s = Scheme::from_toml(text).unwrap();
    assert_eq!(s.period(), 3);
    let x0 = big(&[1, 2]);
    // Step 1: first_step: (2, 3). Step 2: cycle[0]: (5, 3). Step 3: cycle[1]: (5, 19).
    // Step 4: cycle[2]: (15, 19). Step 5: cycle[0] again: (34, 19).
    let seq = s.states_up_to(&x0, 12).unwrap();
    assert_eq!(
        seq[1..=5],
        [
            big(&[2, 3]),
            big(&[5, 3]),
            big(&[5, 19]),
            big(&[15, 19]),
            big(&[34, 19])
        ]
    );
    for (level, x) in seq.iter().enumerate() {
        assert_eq!(&s.state_at(&x0, level as u64).unwrap(), x, "level {level}");
    }
    let phases = s.phases();
    let d: Vec<&str> = phases.iter().map(|p| p.description.as_str()).collect();
    assert_eq!(d, ["s = 3t + 1", "s = 3t + 2", "s = 3t + 3"]);
    for p in &phases {
        let init = s.state_at(&x0, p.first_level).unwrap();
        for t in 0..4u64 {
            let level = p.first_level + 3 * t;
            assert_eq!(
                p.recurrence.state_at(&init, t).unwrap(),
                seq[level as usize]
            );
        }
    }
}
