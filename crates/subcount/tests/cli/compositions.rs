//! `verify` and `subdivide` of a composition (`--scheme loop:1,sqrt3`): each stage in turn,
//! every level checked against the composition's prediction (the counts `table` prints),
//! UVs carried from stage to stage; what no stage after the first can follow is refused.

use crate::util::{data, fails, ok, subcount};

/// `table`'s row at `level` as JSON.
fn table_row(source: &[&str], scheme: &str, level: u32) -> serde_json::Value {
    let level = format!("{level}..={level}");
    let mut args = vec![
        "table", "--scheme", scheme, "--levels", &level, "--format", "json",
    ];
    args.extend_from_slice(source);
    let rows: serde_json::Value = serde_json::from_str(&ok(&args)).expect("table's JSON");
    rows[0].clone()
}

/// The count `name` of a table row.
fn count(row: &serde_json::Value, name: &str) -> u64 {
    row.get(name)
        .and_then(|v| {
            v.as_u64()
                .or_else(|| v.as_str().and_then(|s| s.parse().ok()))
        })
        .unwrap_or_else(|| panic!("{name} in {row}"))
}

#[test]
fn verify_checks_every_level_of_a_composition() {
    let cases: [(&[&str], &str, &str); 4] = [
        (&["--base", "icosahedron"], "loop:1,sqrt3", "4"),
        (
            &["--base", "grid:3x3"],
            "loop-boundary:2,sqrt3-boundary",
            "4",
        ),
        (&["--base", "cube"], "catmull-clark:1,doo-sabin", "3"),
        (
            &["--base", "quad-grid:2x2"],
            "catmull-clark:2,mid-edge",
            "3",
        ),
    ];
    for (source, scheme, levels) in cases {
        let mut args = vec!["verify", "--scheme", scheme, "--levels", levels];
        args.extend_from_slice(source);
        let text = ok(&args);
        assert!(
            text.ends_with("all counts match the prediction\n"),
            "{text}"
        );
        args.extend_from_slice(&["--format", "json"]);
        let reports: serde_json::Value = serde_json::from_str(&ok(&args)).expect("JSON");
        let reports = reports.as_array().expect("one report per level");
        assert_eq!(
            reports.len(),
            levels.parse::<usize>().unwrap() + 1,
            "{scheme}"
        );
        for r in reports {
            assert_eq!(r["match"], true, "{r}");
            let level = r["level"].as_u64().unwrap() as u32;
            // The prediction is the composition's, as `table` counts it.
            let row = table_row(source, scheme, level);
            assert_eq!(r["predicted"]["F"], row["F"], "{scheme} level {level}");
            assert_eq!(r["measured"]["V"], row["V"], "{scheme} level {level}");
        }
    }
}

#[test]
fn subdivide_writes_a_composition_with_the_counts_table_gives() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.obj");
    let out = out.to_str().unwrap();
    let tri = data("uv_cube_tri.obj");
    let cases: [(&[&str], &str, u32); 4] = [
        (&["--base", "icosahedron"], "loop:1,sqrt3", 3),
        (&["--mesh", &tri], "loop:1,sqrt3", 3),
        (&["--mesh", &tri], "sqrt3:1,loop", 2),
        (&["--mesh", &tri], "loop:1,tri-split-2", 2),
    ];
    for (source, scheme, levels) in cases {
        let level = levels.to_string();
        let mut args = vec![
            "subdivide",
            "--scheme",
            scheme,
            "--levels",
            &level,
            "-o",
            out,
        ];
        args.extend_from_slice(source);
        let summary = ok(&args);
        let written = std::fs::read_to_string(out).unwrap();
        let lines = |p: &str| written.lines().filter(|l| l.starts_with(p)).count() as u64;
        let row = table_row(source, scheme, levels);
        let at = format!("{scheme} {source:?}: {summary}");
        assert_eq!(lines("v "), count(&row, "V"), "{at}");
        assert_eq!(lines("f "), count(&row, "F"), "{at}");
        assert!(
            summary.contains(&format!("E = {},", count(&row, "E"))),
            "{at}"
        );
        if row.get("UV").is_some() {
            assert_eq!(lines("vt "), count(&row, "UV"), "{at}");
            assert!(
                summary.contains(&format!("UV = {}", count(&row, "UV"))),
                "{at}"
            );
        }
    }
}

#[test]
fn a_composition_within_its_first_stage_is_that_scheme() {
    // Written in f32: the refine-once path, which only a single scheme has.
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.obj"), dir.path().join("b.obj"));
    let cube = data("uv_cube_tri.obj");
    for (scheme, first) in [
        ("catmull-clark:2,doo-sabin", "catmull-clark"),
        ("loop:3,sqrt3", "loop"),
    ] {
        let run = |s: &str, out: &std::path::Path| {
            let r = subcount(&[
                "subdivide",
                "--mesh",
                &cube,
                "--scheme",
                s,
                "--levels",
                "2",
                "--precision",
                "f32",
                "-o",
                out.to_str().unwrap(),
            ]);
            assert_eq!(r.code, 0, "{s}: {}", r.stderr);
        };
        run(scheme, &a);
        run(first, &b);
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    }
}

#[test]
fn a_composition_refuses_what_its_later_stages_cannot_follow() {
    // Creases and corners, beyond the first stage.
    let dir = tempfile::tempdir().unwrap();
    let creased = dir.path().join("creased.obj");
    let cube = std::fs::read_to_string(data("uv_cube.obj")).unwrap();
    std::fs::write(&creased, format!("{cube}t crease 2/1/0 0 1 2.5\n")).unwrap();
    let creased = creased.to_str().unwrap();
    for command in ["verify", "subdivide"] {
        fails(
            &[
                command,
                "--mesh",
                creased,
                "--scheme",
                "catmull-clark:1,doo-sabin",
                "--levels",
                "2",
            ],
            2,
            "a composition does not carry creases and corners",
        );
    }
    // Holes.
    let holed = data("uv_cube_hole.obj");
    fails(
        &[
            "subdivide",
            "--mesh",
            &holed,
            "--scheme",
            "catmull-clark:1,catmull-clark",
            "--levels",
            "2",
        ],
        2,
        "holes",
    );
    // One refinement of one scheme.
    fails(
        &[
            "subdivide",
            "--base",
            "icosahedron",
            "--scheme",
            "loop:1,sqrt3",
            "--levels",
            "2",
            "--precision",
            "f32",
        ],
        2,
        "is a composition",
    );
    // A stage that does not suit what the one before wrote.
    fails(
        &[
            "verify",
            "--base",
            "cube",
            "--scheme",
            "catmull-clark:1,loop",
            "--levels",
            "2",
        ],
        3,
        "loop needs a triangle mesh, but catmull-clark produces quads",
    );
}

/// The memory guard of a composition (one per stage) predicts within -10 % / +2x of the peak,
/// with and without UVs.
#[test]
fn the_guard_predicts_a_composition_within_bounds() {
    use crate::hostile_dual::{assert_predicted, timed};
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.obj");
    let out = out.to_str().unwrap();
    let tri = data("uv_cube_tri.obj");
    for (source, scheme, levels) in [
        (&["--base", "icosahedron"][..], "loop:3,sqrt3", "8"),
        (&["--mesh", &tri][..], "loop:3,sqrt3", "8"),
        (&["--mesh", &tri, "--no-uv"][..], "sqrt3:2,loop", "7"),
    ] {
        let mut args = vec!["--scheme", scheme, "--levels", levels, "-o", out];
        args.extend_from_slice(source);
        let (_, peak, predicted) = timed(&args);
        assert_predicted(&format!("{scheme} {source:?}"), peak, predicted);
    }
}
