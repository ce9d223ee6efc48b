//! `schemes`, `--scheme-file` (examples, round trips, broken files), `table --scheme`, `fit`
//! when the counts stop changing, and the 4:1 aliases on meshes with boundary.

use std::path::Path;

use crate::util::{data, example_scheme, fails, ok, subcount};

const BUILTINS: [&str; 14] = [
    "loop",
    "loop-boundary",
    "loop-general",
    "catmull-clark-quad",
    "catmull-clark",
    "catmull-clark-general",
    "sqrt3",
    "sqrt3-boundary",
    "doo-sabin",
    "doo-sabin-boundary",
    "mid-edge",
    "mid-edge-boundary",
    "tri-split-2",
    "tri-split-3",
];

/// A base mesh each built-in applies to.
fn base_for(scheme: &str) -> &'static str {
    match scheme {
        "loop" | "sqrt3" | "tri-split-2" => "icosahedron",
        "catmull-clark-quad" => "quad-grid:2x2",
        "catmull-clark" | "catmull-clark-general" => "mixed",
        "doo-sabin" | "mid-edge" => "cube",
        "doo-sabin-boundary" | "mid-edge-boundary" => "mixed",
        _ => "grid:2x2",
    }
}

#[test]
fn schemes_text_lists_every_builtin_with_state_class_and_matrix() {
    let out = ok(&["schemes"]);
    let names: Vec<&str> = out.lines().filter(|l| !l.starts_with(' ')).collect();
    assert_eq!(names, BUILTINS);
    assert!(out.starts_with(
        "loop\n  4:1 triangle split (Loop topology) on closed triangle meshes, paper Theorem 5.1\n  state (V, E), for closed triangle mesh\n  matrix [[1, 1], [0, 4]]\n  F = 2E/3\nloop-boundary\n"
    ), "{out}");
    assert!(out.contains(
        "sqrt3-boundary\n  Kobbelt's sqrt(3) with boundary edges trisected every second step (periodic: steps A, B)\n  state (V, IE, BE, F), for triangle mesh with edges of one or two faces (boundary allowed)\n  step 1 of each cycle [[1, 0, 0, 1], [0, 1, 0, 3], [0, 0, 1, 0], [0, 0, 0, 3]]\n  step 2 of each cycle [[1, 0, 1, 1], [0, 1, -1, 3], [0, 0, 3, 0], [0, 0, 0, 3]]\n  E = IE + BE\n"
    ), "{out}");
    assert!(out.contains("tri-split-3\n  1:9 triangle split (3 segments per edge) on any triangle mesh\n  state (V, E, F), for any triangle mesh (boundary and non-manifold edges allowed)\n  matrix [[1, 2, 1], [0, 3, 9], [0, 0, 9]]\n"), "{out}");
    // One scheme by name, aliases resolved to their own entry.
    let one = ok(&["schemes", "catmull-clark"]);
    assert_eq!(
        one,
        "catmull-clark\n  Catmull-Clark on any polygon mesh whose edges have one or two faces\n  state (V, IE, BE, F, H), for polygon mesh with edges of one or two faces (boundary allowed)\n  matrix [[1, 1, 1, 1, 0], [0, 2, 0, 0, 1], [0, 0, 2, 0, 0], [0, 0, 0, 0, 1], [0, 0, 0, 0, 4]]\n  E = IE + BE\n"
    );
}

#[test]
fn schemes_json_is_an_array_of_objects_in_the_same_order() {
    let out = ok(&["schemes", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    let arr = v.as_array().expect("an array");
    let names: Vec<&str> = arr.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(names, BUILTINS);
    let lp = &arr[0];
    assert_eq!(
        lp["state"],
        serde_json::json!([{"name": "V", "meaning": "vertices"}, {"name": "E", "meaning": "edges"}])
    );
    assert_eq!(lp["matrix"], serde_json::json!([[1, 1], [0, 4]]));
    assert_eq!(lp["mesh_class"], "closed triangle mesh");
    assert_eq!(lp["requires"], serde_json::json!(["triangles", "closed"]));
    assert_eq!(lp["period"], 1);
    assert_eq!(lp["derive"], serde_json::json!({"F": "2E/3"}));
    let sqrt3b = &arr[7];
    assert_eq!(sqrt3b["name"], "sqrt3-boundary");
    assert_eq!(sqrt3b["period"], 2);
    assert_eq!(
        sqrt3b["cycle"],
        serde_json::json!([
            [[1, 0, 0, 1], [0, 1, 0, 3], [0, 0, 1, 0], [0, 0, 0, 3]],
            [[1, 0, 1, 1], [0, 1, -1, 3], [0, 0, 3, 0], [0, 0, 0, 3]]
        ])
    );
}

#[test]
fn schemes_toml_exports_a_template() {
    assert_eq!(
        ok(&["schemes", "--format", "toml", "loop"]),
        "# subdivision scheme `loop`\nname = \"loop\"\ndescription = \"4:1 triangle split (Loop topology) on closed triangle meshes, paper Theorem 5.1\"\nstate = [\"V\", \"E\"]\nrequires = [\"triangles\", \"closed\"]\nproduces = \"triangles\"\ntopology = \"loop\"\nmatrix = [\n  [1, 1],\n  [0, 4],\n]\n\n[derive]\nF = { E = 2, divide_by = 3 }\n"
    );
    fails(&["schemes", "--format", "toml"], 2, "name it");
    fails(
        &["schemes", "no-such-scheme"],
        2,
        "unknown scheme `no-such-scheme`",
    );
}

/// Every built-in exported as TOML and read back with --scheme-file counts exactly the same.
#[test]
fn toml_round_trip_through_scheme_file() {
    let dir = tempfile::tempdir().unwrap();
    for name in BUILTINS {
        let toml = ok(&["schemes", "--format", "toml", name]);
        let path = dir.path().join(format!("{name}.toml"));
        std::fs::write(&path, toml).unwrap();
        let path = path.to_str().unwrap();
        let base = base_for(name);
        let builtin = ok(&[
            "table", "--scheme", name, "--base", base, "--levels", "5", "--format", "csv",
        ]);
        let custom = ok(&[
            "table",
            "--scheme-file",
            path,
            "--base",
            base,
            "--levels",
            "5",
            "--format",
            "csv",
        ]);
        assert_eq!(builtin, custom, "{name} on {base}");
        assert_eq!(builtin.lines().count(), 7, "{name}: header and 6 levels");
        let builtin = ok(&["formula", "--scheme", name]);
        let custom = ok(&["formula", "--scheme-file", path]);
        assert_eq!(builtin, custom, "{name}: closed forms");
    }
}

#[test]
fn example_schemes_count_as_documented() {
    // Fibonacci: no mesh, the state given in order.
    let fib = example_scheme("fibonacci.toml");
    assert_eq!(
        ok(&["table", "--scheme-file", &fib, "--init", "1,0", "--levels", "10", "--format", "csv"]),
        "level,a,b\n0,1,0\n1,1,1\n2,2,1\n3,3,2\n4,5,3\n5,8,5\n6,13,8\n7,21,13\n8,34,21\n9,55,34\n10,89,55\n"
    );
    assert_eq!(
        ok(&[
            "at",
            "--scheme-file",
            &fib,
            "--init",
            "1,0",
            "--level",
            "100",
            "--format",
            "json"
        ]),
        "{\"level\": 100, \"a\": 573147844013817084101, \"b\": 354224848179261915075}\n"
    );
    let forms = ok(&["formula", "--scheme-file", &fib]);
    assert!(
        forms.starts_with("a(s) = ((1/2+1/10*sqrt(5))*(1/2+1/2*sqrt(5))^s"),
        "{forms}"
    );
    // Its state is not a mesh statistic: a mesh cannot supply it.
    fails(
        &["table", "--scheme-file", &fib, "--base", "cube"],
        3,
        "a, b",
    );

    // Catmull-Clark on triangles through a first step: the built-in's V, E, F.
    let cct = example_scheme("catmull-clark-triangles.toml");
    assert_eq!(
        ok(&["table", "--scheme-file", &cct, "--base", "icosahedron", "--levels", "3", "--format", "json"]),
        "[\n{\"level\": 0, \"V\": 12, \"E\": 30, \"F\": 20},\n{\"level\": 1, \"V\": 62, \"E\": 120, \"F\": 60},\n{\"level\": 2, \"V\": 242, \"E\": 480, \"F\": 240},\n{\"level\": 3, \"V\": 962, \"E\": 1920, \"F\": 960}\n]\n"
    );
    let builtin = ok(&[
        "table",
        "--scheme",
        "catmull-clark",
        "--base",
        "icosahedron",
        "--levels",
        "3",
        "--format",
        "csv",
    ]);
    assert!(
        builtin.ends_with("3,962,1920,0,960,3840,1920\n"),
        "{builtin}"
    );

    // The hand-written loop-boundary equals the built-in, and composes with it by name.
    let lb = example_scheme("loop-boundary.toml");
    let custom = ok(&[
        "table",
        "--scheme-file",
        &lb,
        "--base",
        "grid:2x2",
        "--levels",
        "4",
        "--format",
        "csv",
    ]);
    let builtin = ok(&[
        "table",
        "--scheme",
        "loop-boundary",
        "--base",
        "grid:2x2",
        "--levels",
        "4",
        "--format",
        "csv",
    ]);
    assert_eq!(custom, builtin);
    assert_eq!(
        ok(&[
            "table",
            "--scheme-file",
            &lb,
            "--scheme",
            "my-loop-boundary:1,loop-boundary",
            "--base",
            "grid:2x2",
            "--levels",
            "2",
            "--format",
            "csv"
        ]),
        "level,V,IE,BE,E,F\n0,9,8,8,16,8\n1,25,40,16,56,32\n2,81,176,32,208,128\n"
    );

    // The periodic example equals the built-in sqrt3-boundary.
    let s3 = example_scheme("sqrt3-boundary.toml");
    let custom = ok(&[
        "table",
        "--scheme-file",
        &s3,
        "--base",
        "grid:2x2",
        "--levels",
        "6",
        "--format",
        "csv",
    ]);
    let builtin = ok(&[
        "table",
        "--scheme",
        "sqrt3-boundary",
        "--base",
        "grid:2x2",
        "--levels",
        "6",
        "--format",
        "csv",
    ]);
    assert_eq!(custom, builtin);
}

/// Broken scheme files: exit 3, one line naming the file, the line (and column) and the fault.
#[test]
fn broken_scheme_files_name_file_and_line() {
    let cases = [
        ("bad_row_length.toml", "bad_row_length.toml: line 5, column 3: row 2 has 3 entries, but the matrix has 2 rows (it must be square)"),
        ("bad_unknown_field.toml", "bad_unknown_field.toml: line 4, column 1: unknown field `requirez`, expected one of"),
        ("bad_syntax.toml", "bad_syntax.toml: line 3, column 1: invalid array"),
        ("bad_duplicate_state.toml", "bad_duplicate_state.toml: line 2, column 15: state name `V` is used twice"),
        ("bad_names_size.toml", "bad_names_size.toml: line 3, column 10: the matrix is 2x2, but the state has 3 components"),
        ("bad_big_entry.toml", "bad_big_entry.toml: line 3, column 15: "),
        ("bad_empty_matrix.toml", "bad_empty_matrix.toml: line 2, column 9: the state is empty"),
    ];
    for (file, needle) in cases {
        let path = data(file);
        fails(
            &["table", "--scheme-file", &path, "--init", "1,2"],
            3,
            needle,
        );
        fails(&["formula", "--scheme-file", &path], 3, needle);
    }
    fails(
        &[
            "table",
            "--scheme-file",
            "/no/such/scheme.toml",
            "--init",
            "1",
        ],
        3,
        "cannot read /no/such/scheme.toml",
    );
}

#[test]
fn table_scheme_json_keeps_state_order_then_missing_vef() {
    // loop: state (V, E), then F.
    assert_eq!(
        ok(&["table", "--scheme", "loop", "--counts", "V=12,E=30,F=20", "--levels", "2", "--format", "json"]),
        "[\n{\"level\": 0, \"V\": 12, \"E\": 30, \"F\": 20},\n{\"level\": 1, \"V\": 42, \"E\": 120, \"F\": 80},\n{\"level\": 2, \"V\": 162, \"E\": 480, \"F\": 320}\n]\n"
    );
    // loop-boundary: state (V, IE, BE), then E and F.
    assert_eq!(
        ok(&["table", "--scheme", "loop-boundary", "--base", "grid:2x2", "--levels", "2", "--format", "json"]),
        "[\n{\"level\": 0, \"V\": 9, \"IE\": 8, \"BE\": 8, \"E\": 16, \"F\": 8},\n{\"level\": 1, \"V\": 25, \"IE\": 40, \"BE\": 16, \"E\": 56, \"F\": 32},\n{\"level\": 2, \"V\": 81, \"IE\": 176, \"BE\": 32, \"E\": 208, \"F\": 128}\n]\n"
    );
    // catmull-clark: state (V, IE, BE, F, H), then E.
    assert_eq!(
        ok(&["table", "--scheme", "catmull-clark", "--base", "cube", "--levels", "2", "--format", "json"]),
        "[\n{\"level\": 0, \"V\": 8, \"IE\": 12, \"BE\": 0, \"F\": 6, \"H\": 24, \"E\": 12},\n{\"level\": 1, \"V\": 26, \"IE\": 48, \"BE\": 0, \"F\": 24, \"H\": 96, \"E\": 48},\n{\"level\": 2, \"V\": 98, \"IE\": 192, \"BE\": 0, \"F\": 96, \"H\": 384, \"E\": 192}\n]\n"
    );
    assert_eq!(
        ok(&[
            "table",
            "--scheme",
            "catmull-clark",
            "--base",
            "cube",
            "--levels",
            "2",
            "--format",
            "csv"
        ]),
        "level,V,IE,BE,F,H,E\n0,8,12,0,6,24,12\n1,26,48,0,24,96,48\n2,98,192,0,96,384,192\n"
    );
    // sqrt3-boundary: periodic, boundary edges tripled every second step.
    assert_eq!(
        ok(&["table", "--scheme", "sqrt3-boundary", "--base", "grid:2x2", "--levels", "3", "--format", "json"]),
        "[\n{\"level\": 0, \"V\": 9, \"IE\": 8, \"BE\": 8, \"F\": 8, \"E\": 16},\n{\"level\": 1, \"V\": 17, \"IE\": 32, \"BE\": 8, \"F\": 24, \"E\": 40},\n{\"level\": 2, \"V\": 49, \"IE\": 96, \"BE\": 24, \"F\": 72, \"E\": 120},\n{\"level\": 3, \"V\": 121, \"IE\": 312, \"BE\": 24, \"F\": 216, \"E\": 336}\n]\n"
    );
    // tri-split-3 on the icosahedron: 10 N^2 + 2 = 92 vertices after one step.
    assert_eq!(
        ok(&[
            "table",
            "--scheme",
            "ternary",
            "--counts",
            "V=12,E=30,F=20",
            "--levels",
            "1",
            "--format",
            "csv"
        ]),
        "level,V,E,F\n0,12,30,20\n1,92,270,180\n"
    );
    // Doo-Sabin and mid-edge on the cube.
    assert_eq!(
        ok(&[
            "table",
            "--scheme",
            "doo-sabin",
            "--base",
            "cube",
            "--levels",
            "3",
            "--format",
            "csv"
        ]),
        "level,V,E,F\n0,8,12,6\n1,24,48,26\n2,96,192,98\n3,384,768,386\n"
    );
    assert_eq!(
        ok(&[
            "table", "--scheme", "mid-edge", "--base", "cube", "--levels", "2", "--format", "csv"
        ]),
        "level,V,E,F\n0,8,12,6\n1,12,24,14\n2,24,48,26\n"
    );
    // Counts of any size are bare JSON integers: F = 20 * 4^300 has 182 digits.
    let out = ok(&[
        "table",
        "--scheme",
        "loop",
        "--counts",
        "V=12,E=30,F=20",
        "--levels",
        "300..=300",
        "--format",
        "json",
    ]);
    let f = out
        .rsplit("\"F\": ")
        .next()
        .unwrap()
        .trim_end_matches(|c: char| !c.is_ascii_digit());
    assert_eq!(f.len(), 182);
    assert!(f.chars().all(|c| c.is_ascii_digit()), "{f}");
}

#[test]
fn init_is_accepted_with_a_scheme() {
    assert_eq!(
        ok(&["table", "--scheme", "loop", "--init", "12,30", "--levels", "1", "--format", "csv"]),
        "level,V,E,F\n0,12,30,20\n1,42,120,80\n"
    );
    fails(
        &["table", "--scheme", "loop", "--init", "12,30,20"],
        2,
        "--init has 3 values but the state has 2 components (V, E)",
    );
}

#[test]
fn composition_maps_the_state_between_stages() {
    assert_eq!(
        ok(&["table", "--scheme", "loop-boundary:2,sqrt3-boundary", "--base", "grid:2x2", "--levels", "4", "--format", "json"]),
        "[\n{\"level\": 0, \"V\": 9, \"IE\": 8, \"BE\": 8, \"F\": 8, \"E\": 16},\n{\"level\": 1, \"V\": 25, \"IE\": 40, \"BE\": 16, \"F\": 32, \"E\": 56},\n{\"level\": 2, \"V\": 81, \"IE\": 176, \"BE\": 32, \"F\": 128, \"E\": 208},\n{\"level\": 3, \"V\": 209, \"IE\": 560, \"BE\": 32, \"F\": 384, \"E\": 592},\n{\"level\": 4, \"V\": 625, \"IE\": 1680, \"BE\": 96, \"F\": 1152, \"E\": 1776}\n]\n"
    );
    // A mesh class that does not follow: Catmull-Clark makes quads, Loop needs triangles.
    fails(
        &[
            "table",
            "--scheme",
            "catmull-clark:1,loop",
            "--base",
            "cube",
        ],
        3,
        "loop needs a triangle mesh, but catmull-clark produces quads; use catmull-clark",
    );
    fails(
        &[
            "table",
            "--scheme",
            "catmull-clark:1,loop",
            "--counts",
            "V=8,IE=12,BE=0,F=6,H=24",
        ],
        3,
        "catmull-clark produces quads",
    );
}

#[test]
fn formula_text_for_schemes_and_phases() {
    assert_eq!(
        ok(&["formula", "--scheme", "loop"]),
        "V(s) = V0 + (4^s - 1)/3 * E0\nE(s) = 4^s * E0\n"
    );
    assert_eq!(
        ok(&["formula", "--scheme", "catmull-clark"]),
        "V(s) = V0 + (2^s - 1) * IE0 + (2^s - 1) * BE0 + F0 + (4^s - 2*2^s)/4 * H0 for s >= 1; V(0) = V0\nIE(s) = 2^s * IE0 + (4^s - 2^s)/2 * H0\nBE(s) = 2^s * BE0\nF(s) = 4^s/4 * H0 for s >= 1; F(0) = F0\nH(s) = 4^s * H0\n"
    );
    // Periodic: one form per residue class of the level.
    assert_eq!(
        ok(&["formula", "--scheme", "sqrt3-boundary"]),
        "# s = 2t: level s = 0 + 2t; X0 below means the count X at level 0\n\
V(t) = V0 + (3^t - 1)/2 * BE0 + (9^t - 1)/2 * F0\n\
IE(t) = IE0 + (-3^t + 1)/2 * BE0 + (3*9^t - 3)/2 * F0\n\
BE(t) = 3^t * BE0\n\
F(t) = 9^t * F0\n\
# s = 2t + 1: level s = 1 + 2t; X0 below means the count X at level 1\n\
V(t) = V0 + (3^t - 1)/2 * BE0 + (9^t - 1)/2 * F0\n\
IE(t) = IE0 + (-3^t + 1)/2 * BE0 + (3*9^t - 3)/2 * F0\n\
BE(t) = 3^t * BE0\n\
F(t) = 9^t * F0\n"
    );
    // Composition: one phase per stage (and per residue class of the periodic stage).
    let out = ok(&["formula", "--scheme", "loop-boundary:2,sqrt3-boundary"]);
    let headings: Vec<&str> = out.lines().filter(|l| l.starts_with('#')).collect();
    assert_eq!(
        headings,
        [
            "# s = t, s <= 2: level s = 0 + 1t up to level 2; X0 below means the count X at level 0",
            "# s = 2t + 2: level s = 2 + 2t; X0 below means the count X at level 2",
            "# s = 2t + 3: level s = 3 + 2t; X0 below means the count X at level 3",
        ]
    );
    // JSON of a phase list: one object per phase with its forms.
    let json: serde_json::Value = serde_json::from_str(&ok(&[
        "formula",
        "--scheme",
        "sqrt3-boundary",
        "--format",
        "json",
    ]))
    .unwrap();
    let phases = json.as_array().unwrap();
    assert_eq!(phases.len(), 2);
    assert_eq!(phases[1]["first_level"], 1);
    assert_eq!(phases[1]["period"], 2);
    assert_eq!(phases[1]["forms"][3]["component"], "F");
    assert_eq!(phases[1]["forms"][3]["terms"][0]["eigenvalue"], "9");
}

/// The periodic closed forms agree with the table: at s = 2t + 1 (t = 2, s = 5) from level 1.
#[test]
fn phase_forms_agree_with_the_table() {
    let csv = ok(&[
        "table",
        "--scheme",
        "sqrt3-boundary",
        "--base",
        "grid:2x2",
        "--levels",
        "5",
        "--format",
        "csv",
    ]);
    let rows: Vec<Vec<i64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let (v0, ie0, be0, f0) = (rows[1][1], rows[1][2], rows[1][3], rows[1][4]);
    let t = 2u32;
    let (p3, p9) = (3i64.pow(t), 9i64.pow(t));
    assert_eq!(rows[5][1], v0 + (p3 - 1) / 2 * be0 + (p9 - 1) / 2 * f0);
    assert_eq!(rows[5][2], ie0 + (1 - p3) / 2 * be0 + (3 * p9 - 3) / 2 * f0);
    assert_eq!(rows[5][3], p3 * be0);
    assert_eq!(rows[5][4], p9 * f0);
}

#[test]
fn counts_errors_are_usage_errors() {
    // Missing: exit 2, listing what is needed.
    fails(
        &["table", "--scheme", "loop", "--counts", "V=12"],
        2,
        "loop needs E in its initial state, which the given counts do not determine",
    );
    fails(
        &[
            "table",
            "--scheme",
            "catmull-clark",
            "--counts",
            "V=8,E=12,F=6",
        ],
        2,
        "catmull-clark needs IE, BE, H in its initial state",
    );
    // Contradiction: exit 2 naming both values.
    fails(
        &["table", "--scheme", "loop", "--counts", "V=12,E=30,F=21"],
        2,
        "the counts contradict each other: 2E = 60 but 3F = 63",
    );
    fails(
        &[
            "table",
            "--scheme",
            "loop-boundary",
            "--counts",
            "V=9,E=16,F=8,IE=9",
        ],
        2,
        "E + IE = 25 but 3F = 24",
    );
    fails(
        &[
            "table",
            "--scheme",
            "loop",
            "--counts",
            "V=12,E=30,F=20,Q=3",
        ],
        2,
        "unknown count `Q` for loop; use V, E, IE, BE, NME, F, H",
    );
    fails(
        &["table", "--scheme", "loop", "--counts", "V=12,V=13,E=30"],
        2,
        "count V is given twice",
    );
    fails(
        &["table", "--scheme", "loop"],
        2,
        "loop needs an initial state",
    );
    fails(
        &["table", "--scheme", "nope", "--counts", "V=1"],
        2,
        "unknown scheme `nope`",
    );
    fails(
        &[
            "table",
            "--scheme",
            "loop",
            "--counts",
            "V=12,E=30",
            "--init",
            "12,30",
        ],
        2,
        "give the initial state once",
    );
    fails(
        &[
            "table", "--matrix", "[[1]]", "--init", "1", "--scheme", "loop",
        ],
        2,
        "--matrix cannot be combined with --scheme",
    );
    // Identities fill what is missing: IE = 3F - E and BE = 2E - 3F for triangles.
    assert_eq!(
        ok(&[
            "table",
            "--scheme",
            "loop-boundary",
            "--counts",
            "F=8,V=9,E=16",
            "--levels",
            "1",
            "--format",
            "csv"
        ]),
        "level,V,IE,BE,E,F\n0,9,8,8,16,8\n1,25,40,16,56,32\n"
    );
    // Pure quads: H = 4F.
    assert_eq!(
        ok(&[
            "table",
            "--scheme",
            "catmull-clark-quad",
            "--counts",
            "V=8,E=12,F=6",
            "--levels",
            "1",
            "--format",
            "csv"
        ]),
        "level,V,E,F\n0,8,12,6\n1,26,48,24\n"
    );
    // A closed-mesh scheme on counts with boundary does not apply: exit 3, with the fix.
    fails(
        &[
            "table",
            "--scheme",
            "sqrt3",
            "--counts",
            "V=9,E=16,F=8,BE=8",
        ],
        3,
        "sqrt3 needs a closed mesh, but BE=8; use sqrt3-boundary",
    );
    // `loop` counts as `loop-boundary` on counts with BE > 0 (issue 12).
    assert_eq!(
        ok(&[
            "table",
            "--scheme",
            "loop",
            "--counts",
            "V=9,E=16,F=8,BE=8",
            "--levels",
            "1"
        ]),
        ok(&[
            "table",
            "--scheme",
            "loop-boundary",
            "--counts",
            "V=9,E=16,F=8,BE=8",
            "--levels",
            "1"
        ])
    );
}

#[test]
fn at_with_a_scheme_and_a_mesh() {
    // V(s) = 10 * 4^s + 2, E(s) = 30 * 4^s, F(s) = 20 * 4^s on the icosahedron.
    assert_eq!(
        ok(&[
            "at",
            "--scheme",
            "loop",
            "--base",
            "icosahedron",
            "--level",
            "20",
            "--format",
            "json"
        ]),
        "{\"level\": 20, \"V\": 10995116277762, \"E\": 32985348833280, \"F\": 21990232555520}\n"
    );
    // Digit summaries at level 1000 of loop-boundary on the 2x2 grid (checked by iterating
    // V' = V + IE + BE, IE' = 4IE + BE, BE' = 2BE); BE(1000) = 2^1003.
    let out = ok(&[
        "at",
        "--scheme",
        "loop-boundary",
        "--base",
        "grid:2x2",
        "--level",
        "1000",
        "--summary",
        "--format",
        "json",
    ]);
    assert!(out.starts_with("{\"level\": 1000, \"V\": {\"digits\": 603, \"leading\": \"45925227810970180969\", \"trailing\": \"12596088227268395009\"}, \"IE\": {\"digits\": 604, \"leading\": \"13777568343291054290\", \"trailing\": \"47598869391116075008\"}, \"BE\": {\"digits\": 302, \"leading\": \"85720688574901385675\", \"trailing\": \"95094697645344555008\"}, \"E\": "), "{out}");
}

/// `p/q` or `p` as an exact fraction.
fn fraction(text: &str) -> (i128, i128) {
    match text.split_once('/') {
        Some((p, q)) => (p.parse().unwrap(), q.parse().unwrap()),
        None => (text.parse().unwrap(), 1),
    }
}

/// The JSON closed forms of a scheme, evaluated exactly, equal the table (keys in state order).
#[test]
fn formula_json_evaluates_to_the_table() {
    let forms: serde_json::Value = serde_json::from_str(&ok(&[
        "formula",
        "--scheme",
        "loop-boundary",
        "--format",
        "json",
    ]))
    .unwrap();
    let forms = forms.as_array().unwrap();
    let names: Vec<&str> = forms
        .iter()
        .map(|f| f["component"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["V", "IE", "BE"]);
    let csv = ok(&[
        "table",
        "--scheme",
        "loop-boundary",
        "--base",
        "grid:2x2",
        "--levels",
        "12",
        "--format",
        "csv",
    ]);
    let rows: Vec<Vec<i128>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let x0 = [rows[0][1], rows[0][2], rows[0][3]];
    for (i, form) in forms.iter().enumerate() {
        assert_eq!(form["exact"], true);
        assert_eq!(form["valid_from"], 0);
        for (s, row) in rows.iter().enumerate() {
            // Sum over terms of (sum of coefficient * x0) * s^s_power * eigenvalue^s, exactly.
            let (mut num, mut den) = (0i128, 1i128);
            for term in form["terms"].as_array().unwrap() {
                let keys: Vec<&String> = term["coefficients"].as_object().unwrap().keys().collect();
                assert_eq!(keys, ["V", "IE", "BE"], "coefficients in state order");
                let lambda: i128 = term["eigenvalue"].as_str().unwrap().parse().unwrap();
                let power = term["s_power"].as_u64().unwrap() as u32;
                let scale = (s as i128).pow(power) * lambda.pow(s as u32);
                for (k, name) in ["V", "IE", "BE"].iter().enumerate() {
                    let (p, q) = fraction(term["coefficients"][name].as_str().unwrap());
                    num = num * q + p * x0[k] * scale * den;
                    den *= q;
                }
            }
            assert_eq!(num % den, 0, "{}: level {s}", names[i]);
            assert_eq!(num / den, row[i + 1], "{}: level {s}", names[i]);
        }
    }
    // Catmull-Clark: V and F take their closed forms from level 1 on; level 0 is explicit.
    let forms: serde_json::Value = serde_json::from_str(&ok(&[
        "formula",
        "--scheme",
        "catmull-clark",
        "--format",
        "json",
    ]))
    .unwrap();
    let valid: Vec<(&str, u64)> = forms
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            (
                f["component"].as_str().unwrap(),
                f["valid_from"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(valid, [("V", 1), ("IE", 0), ("BE", 0), ("F", 1), ("H", 0)]);
    assert_eq!(
        forms[0]["early_levels"],
        serde_json::json!([{"level": 0, "coefficients": {"V": "1", "IE": "0", "BE": "0", "F": "0", "H": "0"}}])
    );
    assert_eq!(
        ok(&["formula", "--scheme", "loop", "--format", "latex"]),
        "V(s) = V_0 + \\frac{4^{s} - 1}{3} E_0\nE(s) = 4^{s} E_0\n"
    );
    let rust = ok(&["formula", "--scheme", "loop", "--format", "rust"]);
    assert!(
        rust.contains("pub fn loop_counts(x0: [i128; 2], s: u64) -> Option<[i128; 2]>"),
        "{rust}"
    );
}

// ---- `fit` when the counts stop changing ----

/// `fit`'s text and JSON for a custom scheme file and counts, with `--max-vertices`.
fn fit_outputs(scheme_file: &str, counts: &str, max_vertices: &str) -> (String, String) {
    let args = [
        "fit",
        "--scheme-file",
        scheme_file,
        "--counts",
        counts,
        "--max-vertices",
        max_vertices,
    ];
    let text = ok(&args);
    let mut json_args = args.to_vec();
    json_args.extend(["--format", "json"]);
    (text, ok(&json_args))
}

/// Counts that never change fit at every level from level 0 on (the search used to report
/// level 1, its first probe); counts that settle report the level of their last change; the
/// growing case is unchanged.
#[test]
fn fit_reports_the_level_from_which_the_counts_never_change() {
    let dir = tempfile::tempdir().unwrap();
    // The identity: 12, 30, 20 at every level.
    let (text, json) = fit_outputs(&data("constant.toml"), "V=12,E=30,F=20", "100");
    assert_eq!(
        text,
        "every level fits: the limited counts never change (level 0 and every later level have the same counts)\nV = 12\nE = 30\nF = 20\n"
    );
    assert_eq!(
        json,
        "{\"level\": null, \"note\": \"every level fits: the limited counts never change (level 0 and every later level have the same counts)\", \"from_level\": 0, \"V\": 12, \"E\": 30, \"F\": 20}\n"
    );
    // A built-in from a fixed point: Loop on counts with no edges (V' = V + E, E' = 4E).
    assert_eq!(
        ok(&["fit", "--scheme", "loop", "--counts", "V=5,E=0,F=0", "--max-vertices", "5"]),
        "every level fits: the limited counts never change (level 0 and every later level have the same counts)\nV = 5\nE = 0\nF = 0\n"
    );
    // V' = V + E, E' = F, F' = 0 from (10, 5, 3): V is 10, 15, 18, 18, ...
    let settles = dir.path().join("settles.toml");
    std::fs::write(
        &settles,
        "name = \"settles\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 1, 0], [0, 0, 1], [0, 0, 0]]\n",
    )
    .unwrap();
    let settles = settles.to_str().unwrap();
    let (text, json) = fit_outputs(settles, "V=10,E=5,F=3", "100");
    assert_eq!(
        text,
        "every level fits: the limited counts stop changing at level 2 (level 2 and every later level have the same counts)\nV = 18\nE = 0\nF = 0\n"
    );
    assert_eq!(
        json,
        "{\"level\": null, \"note\": \"every level fits: the limited counts stop changing at level 2 (level 2 and every later level have the same counts)\", \"from_level\": 2, \"V\": 18, \"E\": 0, \"F\": 0}\n"
    );
    // From (10, 5, 0) V is 10, 15, 15, ...: it stops changing at level 1.
    let (_, json) = fit_outputs(settles, "V=10,E=5,F=0", "100");
    assert_eq!(
        json,
        "{\"level\": null, \"note\": \"every level fits: the limited counts stop changing at level 1 (level 1 and every later level have the same counts)\", \"from_level\": 1, \"V\": 15, \"E\": 0, \"F\": 0}\n"
    );
    // A budget level 2 exceeds: the highest level within it, as for growing counts.
    let (text, _) = fit_outputs(settles, "V=10,E=5,F=3", "17");
    assert_eq!(
        text,
        "highest level within the budget: 1\nV = 15\nE = 3\nF = 0\n"
    );
    // `density --target-area` names the same level when V never reaches the target.
    for (file, counts, needle) in [
        (
            data("constant.toml"),
            "V=12,E=30,F=20",
            "it is 12 from level 0 on and stays there",
        ),
        (
            settles.to_string(),
            "V=10,E=5,F=3",
            "it is 18 from level 2 on and stays there",
        ),
    ] {
        fails(
            &[
                "density",
                "--scheme-file",
                &file,
                "--counts",
                counts,
                "--radius",
                "1",
                "--target-area",
                "0.001",
            ],
            2,
            needle,
        );
    }
    // The growing case: V = 12, 42, 162, 642 under Loop.
    assert_eq!(
        ok(&[
            "fit",
            "--scheme",
            "loop",
            "--counts",
            "V=12,E=30,F=20",
            "--max-vertices",
            "641"
        ]),
        "highest level within the budget: 2\nV = 162\nE = 480\nF = 320\n"
    );
}

// ---- `loop` and the 4:1 aliases on meshes with boundary ----

/// `loop` and its 4:1 aliases: on a mesh with boundary all count as `loop-boundary` and
/// subdivide with Loop's boundary rules (issue 12; `loop` used to refuse the boundary).
const LOOP_ALIASES: [&str; 4] = ["loop", "midpoint", "butterfly", "icosphere"];

fn json(args: &[&str]) -> serde_json::Value {
    let out = ok(args);
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("subcount {args:?}: {e}: {out}"))
}

/// The counts every prediction must equal: V, E, F of `subdivide` to `level`.
fn subdivided(mesh: &[&str], scheme: &str, level: u64) -> [u64; 3] {
    let mut args = vec!["subdivide", "--scheme", scheme];
    args.extend(mesh);
    let level_text = level.to_string();
    args.extend(["--levels", &level_text]);
    let out = ok(&args);
    let rest = out
        .strip_prefix(&format!("level {level}: V = "))
        .and_then(|r| r.strip_suffix(" (no -o: nothing written)\n"))
        .unwrap_or_else(|| panic!("subdivide output: {out}"));
    let v: Vec<u64> = rest
        .split(", ")
        .enumerate()
        .map(|(i, part)| {
            let value = if i == 0 {
                Some(part)
            } else {
                part.split(" = ").nth(1)
            };
            value
                .and_then(|v| v.parse().ok())
                .unwrap_or_else(|| panic!("{out}"))
        })
        .collect();
    [v[0], v[1], v[2]]
}

/// Every count-predicting command gives, for an alias on `mesh` (which has a boundary),
/// exactly the counts `subdivide` builds and `verify` checks: those of `loop-boundary`.
fn check_alias_on_boundary(mesh: &[&str], levels: u64, plot_dir: &Path) {
    let with = |head: &[&str], scheme: &str, tail: &[&str]| -> Vec<String> {
        let mut v: Vec<String> = head.iter().map(|s| s.to_string()).collect();
        v.extend(["--scheme".to_string(), scheme.to_string()]);
        v.extend(mesh.iter().map(|s| s.to_string()));
        v.extend(tail.iter().map(|s| s.to_string()));
        v
    };
    let run =
        |args: Vec<String>| -> String { ok(&args.iter().map(String::as_str).collect::<Vec<_>>()) };
    let range = format!("0..={levels}");
    let table_args = |scheme: &str| {
        with(
            &["table"],
            scheme,
            &["--levels", &range, "--format", "json"],
        )
    };
    let expected: serde_json::Value =
        serde_json::from_str(&run(table_args("loop-boundary"))).unwrap();
    let row = |s: u64| &expected[s as usize];
    let count = |s: u64, key: &str| row(s)[key].as_u64().unwrap();
    let formula = run(with(&["formula"], "loop-boundary", &[]));
    assert!(formula.contains("IE(s) = "), "{formula}");
    for alias in LOOP_ALIASES {
        let table: serde_json::Value = serde_json::from_str(&run(table_args(alias))).unwrap();
        assert_eq!(table, expected, "{alias} on {mesh:?}");
        for s in 1..=levels {
            assert_eq!(
                subdivided(mesh, alias, s),
                [count(s, "V"), count(s, "E"), count(s, "F")],
                "{alias} on {mesh:?}: level {s}"
            );
        }
        let verify = run(with(&["verify"], alias, &["--levels", &levels.to_string()]));
        assert!(
            verify.ends_with("all counts match the prediction\n"),
            "{verify}"
        );
        let mut rows = 0;
        for line in verify.lines().skip(2).filter(|l| !l.starts_with("all ")) {
            let f: Vec<&str> = line.split_whitespace().collect();
            let s: u64 = f[0].parse().unwrap();
            assert_eq!(f[2], f[3], "{alias} on {mesh:?}: {line}");
            assert_eq!(
                f[2],
                row(s)[f[1]].to_string(),
                "{alias} on {mesh:?}: {line}"
            );
            rows += 1;
        }
        assert_eq!(rows, 5 * (levels + 1), "{verify}");
        let at = run(with(
            &["at"],
            alias,
            &["--level", &levels.to_string(), "--format", "json"],
        ));
        assert_eq!(
            serde_json::from_str::<serde_json::Value>(&at).unwrap(),
            *row(levels),
            "{alias}"
        );
        assert_eq!(run(with(&["formula"], alias, &[])), formula, "{alias}");
        let faces = count(levels, "F").to_string();
        let fit = run(with(
            &["fit"],
            alias,
            &["--max-faces", &faces, "--format", "json"],
        ));
        assert_eq!(
            serde_json::from_str::<serde_json::Value>(&fit).unwrap(),
            *row(levels),
            "{alias}"
        );
        let density = run(with(
            &["density"],
            alias,
            &[
                "--level",
                &levels.to_string(),
                "--radius",
                "1",
                "--format",
                "json",
            ],
        ));
        let density: serde_json::Value = serde_json::from_str(&density).unwrap();
        assert_eq!(density["V"], row(levels)["V"], "{alias}");
        let svg = plot_dir.join(format!("{alias}.svg"));
        let svg = svg.to_str().unwrap();
        let plot = run(with(&["plot"], alias, &["--levels", &range, "-o", svg]));
        assert_eq!(plot, format!("wrote {svg} (5 series, levels {range})\n"));
        assert!(std::fs::read_to_string(svg)
            .unwrap()
            .contains("\nBE (boundary edges)\n</text>"));
        // Typed-in counts of the same mesh: BE = 2E - 3F > 0.
        let counts = format!(
            "V={},E={},F={}",
            count(0, "V"),
            count(0, "E"),
            count(0, "F")
        );
        let typed = ok(&[
            "table", "--scheme", alias, "--counts", &counts, "--levels", &range, "--format", "json",
        ]);
        assert_eq!(
            serde_json::from_str::<serde_json::Value>(&typed).unwrap(),
            expected
        );
    }
    // `loop` subdivides the boundary with Loop's boundary rules: the very output of
    // `loop-boundary` (issue 12), and `verify` agrees.
    let out = |scheme: &str| {
        let file = plot_dir.join(format!("{scheme}.obj"));
        run(with(
            &["subdivide"],
            scheme,
            &["--levels", "1", "-o", file.to_str().unwrap()],
        ));
        std::fs::read(&file).unwrap()
    };
    assert_eq!(out("loop"), out("loop-boundary"));
    let verified = run(with(&["verify"], "loop", &["--levels", "1"]));
    assert!(!verified.contains("MISMATCH"), "{verified}");
}

/// `--scheme butterfly` (or `midpoint`, `icosphere`) on a mesh with boundary predicts what
/// `subdivide` builds (it used to be refused as `loop` by every command but `subdivide` and
/// `verify`).
#[test]
fn aliases_count_as_loop_boundary_on_generated_meshes_with_boundary() {
    let dir = tempfile::tempdir().unwrap();
    check_alias_on_boundary(&["--base", "grid:3x3"], 3, dir.path());
    check_alias_on_boundary(&["--base", "icosahedron-holes:2"], 2, dir.path());
    // The numbers, checked by hand on the 3x3 grid: V' = V + IE + BE, IE' = 4IE + BE,
    // BE' = 2BE from (16, 21, 12).
    for alias in LOOP_ALIASES {
        assert_eq!(
            ok(&["table", "--scheme", alias, "--base", "grid:3x3", "--levels", "3"]),
            "level    V    IE  BE     E     F\n    0   16    21  12    33    18\n    1   49    96  24   120    72\n    2  169   408  48   456   288\n    3  625  1680  96  1776  1152\n"
        );
        assert_eq!(
            subdivided(&["--base", "grid:3x3"], alias, 3),
            [625, 1776, 1152]
        );
    }
}

/// In a composition every `loop` or alias stage counts as `loop-boundary` on a mesh with
/// boundary.
#[test]
fn aliases_in_compositions_on_a_mesh_with_boundary() {
    let expected = ok(&[
        "table",
        "--scheme",
        "loop-boundary",
        "--base",
        "grid:3x3",
        "--levels",
        "3",
    ]);
    for plan in [
        "butterfly:1,loop-boundary",
        "loop-boundary:2,icosphere",
        "midpoint:1,butterfly",
        "butterfly:1,loop",
        "loop:1,loop-boundary",
    ] {
        assert_eq!(
            ok(&["table", "--scheme", plan, "--base", "grid:3x3", "--levels", "3"]),
            expected,
            "{plan}"
        );
    }
}

/// With a non-manifold edge next to the boundary an alias stays `loop` (as in `halfedge`'s
/// subdivision): every command refuses with the same message, naming the alias.
#[test]
fn aliases_refuse_non_manifold_edges_the_same_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    let fin = dir.path().join("fin.obj");
    // Three triangles on the edge 1-2: NME = 1, BE = 6.
    std::fs::write(
        &fin,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
    )
    .unwrap();
    let fin = fin.to_str().unwrap();
    for alias in LOOP_ALIASES {
        let needle = format!(
            "{fin}: {alias} needs every edge to have one or two faces, but this mesh has 1 non-manifold edge"
        );
        for command in [
            &["table"][..],
            &["at", "--level", "1"],
            &["verify", "--levels", "1"],
            &["subdivide", "--levels", "1"],
        ] {
            let mut args = command.to_vec();
            args.extend(["--scheme", alias, "--mesh", fin]);
            let err = fails(&args, 3, &needle);
            assert!(err.ends_with("; use loop-general\n"), "{err}");
        }
    }
}

/// On a closed mesh the aliases stay `loop`: state (V, E), the same table.
#[test]
fn aliases_count_as_loop_on_closed_meshes() {
    let expected = ok(&[
        "table",
        "--scheme",
        "loop",
        "--base",
        "icosahedron",
        "--levels",
        "3",
        "--format",
        "json",
    ]);
    assert!(
        expected.starts_with("[\n{\"level\": 0, \"V\": 12, \"E\": 30, \"F\": 20}"),
        "{expected}"
    );
    for alias in LOOP_ALIASES {
        let args = [
            "table",
            "--scheme",
            alias,
            "--base",
            "icosahedron",
            "--levels",
            "3",
            "--format",
            "json",
        ];
        assert_eq!(ok(&args), expected, "{alias}");
        assert_eq!(
            subdivided(&["--base", "icosahedron"], alias, 3),
            [642, 1920, 1280]
        );
        assert_eq!(
            ok(&["formula", "--scheme", alias, "--counts", "V=12,E=30,F=20"]),
            ok(&["formula", "--scheme", "loop", "--counts", "V=12,E=30,F=20"])
        );
    }
}

/// The shared meshes with boundary (`SUBCOUNT_MESHES`): an alias predicts what `subdivide`
/// builds, level by level, and the boundary doubles each level.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn aliases_on_shared_meshes_with_boundary() {
    for (file, levels) in [("planexy.obj", 3), ("face.obj", 2), ("eight_open.obj", 2)] {
        let path = testdata::mesh(file);
        let path = path.to_str().unwrap();
        let mesh = ["--mesh", path];
        let plot_dir = tempfile::tempdir().unwrap();
        check_alias_on_boundary(&mesh, levels, plot_dir.path());
        let stats = json(&["stats", "--mesh", path, "--format", "json"]);
        let table = json(&[
            "table",
            "--scheme",
            "butterfly",
            "--mesh",
            path,
            "--levels",
            &levels.to_string(),
            "--format",
            "json",
        ]);
        for s in 0..=levels {
            let be = stats["BE"].as_u64().unwrap() << s;
            assert_eq!(
                table[s as usize]["BE"].as_u64(),
                Some(be),
                "{file} level {s}"
            );
        }
    }
}

fn strs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// A scheme file's `topology` key names the rule that really subdivides it (issue 12):
/// `subdivide` runs that rule, `verify` compares the file's matrix with it (exit 1 on a wrong
/// matrix), and without the key both refuse, naming the key.
#[test]
fn custom_schemes_are_subdivided_by_their_topology() {
    let dir = tempfile::tempdir().unwrap();
    let template = ok(&["schemes", "--format", "toml", "loop-boundary"]);
    assert!(template.contains("\ntopology = \"loop\"\n"), "{template}");
    let write = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_owned()
    };
    let good = write(
        "good.toml",
        &template.replace("\"loop-boundary\"", "\"mine\""),
    );
    // IE' = 4 IE + 2 BE instead of 4 IE + BE: wrong on a mesh with boundary.
    let wrong = write(
        "wrong.toml",
        &template
            .replace("[0, 4, 1]", "[0, 4, 2]")
            .replace("\"loop-boundary\"", "\"wrong\""),
    );
    let bare = write(
        "bare.toml",
        &template
            .replace("topology = \"loop\"\n", "")
            .replace("\"loop-boundary\"", "\"bare\""),
    );
    let grid = ["--base", "grid:3x3"];
    let run = |head: &[&str], file: &str, tail: &[&str]| -> Vec<String> {
        let mut args: Vec<&str> = head.to_vec();
        args.extend(["--scheme-file", file]);
        args.extend(grid);
        args.extend(tail);
        args.iter().map(|s| s.to_string()).collect()
    };
    let verified = ok(&strs(&run(&["verify"], &good, &["--levels", "2"])));
    assert!(
        verified.starts_with("mine on grid:3x3 levels 0..=2\n"),
        "{verified}"
    );
    assert!(
        verified.ends_with("all counts match the prediction\n"),
        "{verified}"
    );
    let args = run(&["verify"], &wrong, &["--levels", "2"]);
    let mismatch = subcount(&strs(&args));
    assert_eq!(mismatch.code, 1, "{}", mismatch.stderr);
    assert!(
        mismatch
            .stdout
            .contains("    1         IE        108        96  MISMATCH\n"),
        "{}",
        mismatch.stdout
    );
    assert_eq!(
        mismatch.stderr,
        "error: wrong: real subdivision disagrees with the prediction\n"
    );
    // `subdivide` runs Loop's rule: the same file as the built-in.
    let out = |scheme_args: &[&str], name: &str| {
        let file = dir.path().join(name);
        let mut args = vec!["subdivide"];
        args.extend(scheme_args);
        args.extend(grid);
        args.extend(["--levels", "2", "-o", file.to_str().unwrap()]);
        ok(&args);
        std::fs::read(&file).unwrap()
    };
    assert_eq!(
        out(&["--scheme-file", &good], "mine.obj"),
        out(&["--scheme", "loop-boundary"], "builtin.obj")
    );
    for command in ["verify", "subdivide"] {
        fails(
            &strs(&run(&[command], &bare, &["--levels", "1"])),
            2,
            "no real subdivision for scheme `bare`: its matrix names no rule; add `topology = \"NAME\"`",
        );
    }
    fails(
        &strs(&run(
            &["verify", "--scheme", "other"],
            &good,
            &["--levels", "1"],
        )),
        2,
        "--scheme other is not the scheme of",
    );
}

/// Every example scheme file that names a `topology` is right: `verify` checks its matrix
/// against the real subdivision by that rule on meshes with boundary (exit 0).
#[test]
fn example_schemes_verify_against_their_topology() {
    for (file, base, levels) in [
        ("loop-boundary.toml", "grid:3x3", "3"),
        ("loop-boundary.toml", "icosahedron-holes:2", "3"),
        ("sqrt3-boundary.toml", "grid:3x3", "4"),
        ("catmull-clark-triangles.toml", "icosahedron-holes:1", "3"),
    ] {
        let path = example_scheme(file);
        let out = ok(&[
            "verify",
            "--scheme-file",
            &path,
            "--base",
            base,
            "--levels",
            levels,
        ]);
        assert!(
            out.ends_with("all counts match the prediction\n"),
            "{file} on {base}: {out}"
        );
    }
}
