//! UVs through `subdivide` and `verify`: the refined UVs written with the summary's `UV = N`
//! (the count `table` predicts), `--uv-interpolation` (flag over tag over `corners-plus1`),
//! `--no-uv`, the notes for partial `vt` and for rules that do not carry UVs, `uv_s` in
//! `--timings`, and `verify`'s `UV` component.

use serde_json::Value;

use crate::util::{data, ok, subcount};

/// The names of `--uv-interpolation`, in OpenSubdiv's order.
const MODES: [&str; 6] = [
    "none",
    "corners-only",
    "corners-plus1",
    "corners-plus2",
    "boundaries",
    "all",
];

/// The `N` of `UV = N` in a summary line, if any.
fn summary_uv(summary: &str) -> Option<u64> {
    let start = summary.find("UV = ")? + "UV = ".len();
    let digits: String = summary[start..]
        .chars()
        .take_while(char::is_ascii_digit)
        .collect();
    digits.parse().ok()
}

/// The UV values `table` predicts at `level`.
fn predicted_uv(mesh: &str, scheme: &str, level: u64) -> u64 {
    let text = ok(&[
        "table",
        "--mesh",
        mesh,
        "--scheme",
        scheme,
        "--levels",
        &level.to_string(),
        "--format",
        "json",
    ]);
    let rows: Value = serde_json::from_str(&text).expect("table JSON");
    rows.as_array().and_then(|r| r.last()).expect("a row")["UV"]
        .as_u64()
        .expect("a UV column")
}

/// Runs `subdivide` on `mesh` with `args`, writing into a temporary folder: the summary
/// (stdout), stderr and the written file's text.
fn subdivide(mesh: &str, args: &[&str]) -> (String, String, String) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("out.obj");
    let out = out.to_str().expect("a UTF-8 path");
    let mut all = vec!["subdivide", "--mesh", mesh, "-o", out];
    all.extend_from_slice(args);
    let run = subcount(&all);
    assert_eq!(run.code, 0, "subcount {all:?}: {}", run.stderr);
    let text = std::fs::read_to_string(out).expect("the output file");
    (run.stdout.replace(out, "OUT"), run.stderr, text)
}

#[test]
fn the_summary_counts_the_uv_values_table_predicts() {
    let cube = data("uv_cube.obj");
    for (scheme, levels) in [("catmull-clark", 2), ("catmull-clark", 0)] {
        let predicted = predicted_uv(&cube, scheme, levels);
        for precision in ["f64", "f32"] {
            let (summary, stderr, _) = subdivide(
                &cube,
                &[
                    "--scheme",
                    scheme,
                    "--levels",
                    &levels.to_string(),
                    "--precision",
                    precision,
                ],
            );
            assert_eq!(stderr, "");
            assert_eq!(summary_uv(&summary), Some(predicted), "{summary}");
            assert!(
                summary.contains(&format!(", UV = {predicted}; wrote OUT")),
                "{summary}"
            );
        }
    }
    // 18 values, 21 layout edges, 6 faces: 18 + 21 + 6 at level 1.
    assert_eq!(predicted_uv(&cube, "catmull-clark", 1), 45);
}

#[test]
fn every_interpolation_mode_is_accepted_and_keeps_the_counts() {
    let cube = data("uv_cube.obj");
    let base = ["--scheme", "catmull-clark", "--levels", "2"];
    let (default, _, _) = subdivide(&cube, &base);
    for mode in MODES {
        let mut args = base.to_vec();
        args.extend(["--uv-interpolation", mode]);
        let (summary, stderr, _) = subdivide(&cube, &args);
        assert_eq!(stderr, "", "{mode}");
        assert_eq!(summary, default, "{mode}");
    }
    let run = subcount(&[
        "subdivide",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "1",
        "--uv-interpolation",
        "smooth",
    ]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr.contains("corners-plus1") && run.stderr.contains("boundaries"),
        "{}",
        run.stderr
    );
    let run = subcount(&[
        "subdivide",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "1",
        "--uv-interpolation",
        "all",
        "--no-uv",
    ]);
    assert_eq!(run.code, 2, "{}", run.stderr);
}

#[test]
fn the_flag_overrides_the_tag_with_a_note() {
    let tagged = data("uv_cube_tagged.obj");
    let (summary, stderr, _) = subdivide(
        &tagged,
        &[
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "--uv-interpolation",
            "none",
        ],
    );
    assert_eq!(summary_uv(&summary), Some(45));
    assert_eq!(
        stderr,
        format!("note: {tagged}: --uv-interpolation none overrides the tag facevaryinginterpolateboundary 5 (all)\n")
    );
    // The same value as the tag: no note.
    let (_, stderr, _) = subdivide(
        &tagged,
        &[
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "--uv-interpolation",
            "all",
        ],
    );
    assert_eq!(stderr, "");
}

#[test]
fn triangle_rules_write_the_uv_values_table_predicts() {
    let cube = data("uv_cube_tri.obj");
    for scheme in ["loop", "midpoint", "butterfly", "tri-split-3"] {
        let predicted = predicted_uv(&cube, scheme, 2);
        let (summary, stderr, _) = subdivide(&cube, &["--scheme", scheme, "--levels", "2"]);
        assert_eq!(stderr, "", "{scheme}");
        assert_eq!(summary_uv(&summary), Some(predicted), "{scheme}: {summary}");
    }
    // The 4:1 rules other than Loop refine UVs linearly: the mode flag says so.
    let (summary, stderr, _) = subdivide(
        &cube,
        &[
            "--scheme",
            "midpoint",
            "--levels",
            "1",
            "--uv-interpolation",
            "all",
        ],
    );
    assert_eq!(
        stderr,
        format!("note: {cube}: --uv-interpolation is a mode of loop and catmull-clark, not applied by midpoint\n")
    );
    assert_eq!(summary_uv(&summary), Some(45));
    // A base mesh has no UVs: the flag changes nothing and says nothing.
    let run = subcount(&[
        "subdivide",
        "--base",
        "icosahedron",
        "--scheme",
        "loop",
        "--levels",
        "1",
        "--uv-interpolation",
        "all",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(run.stderr, "");
    assert_eq!(
        run.stdout,
        "level 1: V = 42, E = 120, F = 80 (no -o: nothing written)\n"
    );
}

#[test]
fn holes_write_and_verify_the_uv_values_of_the_written_faces() {
    let holed = data("uv_cube_hole.obj");
    let predicted = predicted_uv(&holed, "catmull-clark", 2);
    for precision in ["f64", "f32"] {
        let (summary, stderr, _) = subdivide(
            &holed,
            &[
                "--scheme",
                "catmull-clark",
                "--levels",
                "2",
                "--precision",
                precision,
            ],
        );
        assert_eq!(stderr, "");
        assert_eq!(summary_uv(&summary), Some(predicted), "{summary}");
    }
    let rows = verify_uv(&holed, "catmull-clark", "2");
    assert_eq!(rows[2], (Value::from(predicted), Value::from(predicted)));
}

#[test]
fn no_uv_writes_what_a_mesh_without_vt_writes() {
    let cube = data("uv_cube.obj");
    let text = std::fs::read_to_string(&cube).expect("the fixture");
    // The same mesh without texture coordinates.
    let stripped: String = text
        .lines()
        .filter(|l| !l.starts_with("vt "))
        .map(|l| {
            if l.starts_with("f ") {
                l.split(' ')
                    .map(|c| c.split('/').next().unwrap_or(c))
                    .collect::<Vec<_>>()
                    .join(" ")
            } else {
                l.to_owned()
            }
        })
        .map(|l| l + "\n")
        .collect();
    let dir = tempfile::tempdir().expect("a temporary folder");
    let plain = dir.path().join("plain.obj");
    std::fs::write(&plain, stripped).expect("written");
    let plain = plain.to_str().expect("a UTF-8 path");
    for args in [
        &["--scheme", "catmull-clark", "--levels", "2"][..],
        &[
            "--scheme",
            "catmull-clark",
            "--levels",
            "2",
            "--precision",
            "f32",
        ],
        &["--scheme", "doo-sabin", "--levels", "1"],
    ] {
        let mut with_flag = args.to_vec();
        with_flag.push("--no-uv");
        let (summary, stderr, written) = subdivide(&cube, &with_flag);
        let (plain_summary, plain_stderr, plain_written) = subdivide(plain, args);
        assert_eq!(stderr, "");
        assert_eq!(plain_stderr, "");
        assert_eq!(summary, plain_summary, "{args:?}");
        assert!(!summary.contains("UV"), "{summary}");
        assert_eq!(written, plain_written, "{args:?}");
        assert!(!written.contains("vt "));
    }
}

#[test]
fn partial_texture_coordinates_are_written_without_uvs_saying_why() {
    let partial = data("uv_partial.obj");
    let (summary, stderr, written) =
        subdivide(&partial, &["--scheme", "catmull-clark", "--levels", "1"]);
    assert_eq!(
        stderr,
        format!("note: {partial}: 20 of 24 face corners have texture coordinates: no UV layout: writing without UVs\n")
    );
    assert_eq!(summary, "level 1: V = 26, E = 48, F = 24; wrote OUT\n");
    assert!(!written.contains("vt ") && !written.contains('/'));
}

#[test]
fn the_dual_rules_write_their_uvs() {
    // uv_cube has 9 seam edges (the top's and the bottom's sides, the strip's cut).
    let cube = data("uv_cube.obj");
    for (scheme, summary_line, values) in [
        (
            "doo-sabin",
            "level 1: V = 24, E = 48, F = 26, UV = 42; wrote OUT\n",
            42,
        ),
        (
            "mid-edge",
            "level 1: V = 12, E = 24, F = 14, UV = 21; wrote OUT\n",
            21,
        ),
    ] {
        let (summary, stderr, written) = subdivide(&cube, &["--scheme", scheme, "--levels", "1"]);
        assert_eq!(stderr, "", "{scheme}");
        assert_eq!(summary, summary_line);
        assert_eq!(
            written.lines().filter(|l| l.starts_with("vt ")).count(),
            values,
            "{scheme}"
        );
        assert!(
            written
                .lines()
                .filter(|l| l.starts_with("f "))
                .all(|l| l.split_whitespace().skip(1).all(|c| c.contains('/'))),
            "{scheme}"
        );
        // The same values when refined once into f32 buffers.
        let (summary, _, written) = subdivide(
            &cube,
            &["--scheme", scheme, "--levels", "1", "--precision", "f32"],
        );
        assert_eq!(summary, summary_line, "{scheme} f32");
        assert_eq!(
            written.lines().filter(|l| l.starts_with("vt ")).count(),
            values,
            "{scheme} f32"
        );
    }
    // A -general scheme runs on the raw face list, which refines the UVs linearly with it.
    let (summary, stderr, written) = subdivide(
        &cube,
        &["--scheme", "catmull-clark-general", "--levels", "1"],
    );
    assert_eq!(stderr, "");
    assert_eq!(
        summary,
        "level 1: V = 26, E = 48, F = 24, UV = 45; wrote OUT\n"
    );
    assert_eq!(written.lines().filter(|l| l.starts_with("vt ")).count(), 45);
}

#[test]
fn timings_gain_uv_s_when_uvs_are_refined() {
    let cube = data("uv_cube.obj");
    let keys = |stderr: &str| -> Vec<String> {
        let json = stderr
            .lines()
            .find_map(|l| l.strip_prefix("timings: "))
            .expect("a timings line");
        let object: Value = serde_json::from_str(json).expect("timings JSON");
        let map = object.as_object().expect("an object");
        map.keys().cloned().collect()
    };
    let base = [
        "load_s",
        "peak_bytes",
        "predicted_peak_bytes",
        "subdivide_s",
        "write_s",
    ];
    let with = |extra: &[&str]| -> Vec<String> {
        let mut k: Vec<String> = base.iter().chain(extra).map(|s| s.to_string()).collect();
        k.sort();
        k
    };
    let run = |args: &[&str]| {
        let mut all = vec!["--scheme", "catmull-clark", "--levels", "2", "--timings"];
        all.extend_from_slice(args);
        let (_, stderr, _) = subdivide(&cube, &all);
        let mut k = keys(&stderr);
        k.sort();
        k
    };
    assert_eq!(run(&[]), with(&["uv_s"]));
    assert_eq!(run(&["--no-uv"]), with(&[]));
    assert_eq!(
        run(&["--frames", "2"]),
        with(&["uv_s", "refine_topology_s", "evaluate_s"])
    );
}

/// `verify --format json` on `mesh`: per level, `(predicted UV, measured UV)`.
fn verify_uv(mesh: &str, scheme: &str, levels: &str) -> Vec<(Value, Value)> {
    let text = ok(&[
        "verify", "--mesh", mesh, "--scheme", scheme, "--levels", levels, "--format", "json",
    ]);
    let rows: Value = serde_json::from_str(&text).expect("verify JSON");
    rows.as_array()
        .expect("an array")
        .iter()
        .map(|r| {
            assert_eq!(r["match"], Value::Bool(true), "{r}");
            (r["predicted"]["UV"].clone(), r["measured"]["UV"].clone())
        })
        .collect()
}

#[test]
fn verify_checks_the_uv_values_of_every_level() {
    let cube = data("uv_cube.obj");
    let rows = verify_uv(&cube, "catmull-clark", "2");
    let predicted: Vec<Value> = (0..=2)
        .map(|l| Value::from(predicted_uv(&cube, "catmull-clark", l)))
        .collect();
    assert_eq!(
        rows,
        predicted
            .iter()
            .map(|p| (p.clone(), p.clone()))
            .collect::<Vec<_>>()
    );
    // Level 0 counts the vt used (18: no vt is used at two vertices).
    assert_eq!(rows[0].0, Value::from(18));
    let text = ok(&[
        "verify",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "1",
    ]);
    assert!(
        text.contains("    1         UV         45        45\n"),
        "{text}"
    );
    // The dual rules: predicted by their recurrences over the layout and its 9 seams,
    // measured on the corner channel.
    for (scheme, values) in [
        ("doo-sabin", [18, 42, 150, 546]),
        ("mid-edge", [18, 21, 42, 84]),
    ] {
        let rows = verify_uv(&cube, scheme, "3");
        let expected: Vec<(Value, Value)> = values
            .iter()
            .map(|&v| (Value::from(v), Value::from(v)))
            .collect();
        assert_eq!(rows, expected, "{scheme}");
        for (level, &v) in values.iter().enumerate() {
            assert_eq!(predicted_uv(&cube, scheme, level as u64), v, "{scheme}");
        }
    }
    // √3 on the triangulated cube of three charts (18 values, 9 seams, 12 faces): predicted
    // by UV' = UV + 2 S + F, measured on the corner channel.
    let tri = data("uv_cube_tri.obj");
    let values = [18, 48, 138, 408];
    let rows = verify_uv(&tri, "sqrt3", "3");
    let expected: Vec<(Value, Value)> = values
        .iter()
        .map(|&v| (Value::from(v), Value::from(v)))
        .collect();
    assert_eq!(rows, expected);
    for (level, &v) in values.iter().enumerate() {
        assert_eq!(predicted_uv(&tri, "sqrt3", level as u64), v);
    }
}

#[test]
fn a_non_manifold_face_list_is_subdivided_and_verified_with_uvs() {
    let book = data("uv_book.obj");
    // The face-list subdividers refine the layout with the faces: the UV rows are measured
    // on the written UVs and match the prediction.
    for (scheme, rows) in [
        (
            "tri-split-2",
            [
                "    1         UV         15        15\n",
                "    2         UV         40        40\n",
            ],
        ),
        (
            "tri-split-3",
            [
                "    1         UV         26        26\n",
                "    2         UV        155       155\n",
            ],
        ),
        (
            "loop-general",
            [
                "    1         UV         15        15\n",
                "    2         UV         40        40\n",
            ],
        ),
    ] {
        let run = subcount(&[
            "verify", "--mesh", &book, "--scheme", scheme, "--levels", "2",
        ]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        assert_eq!(run.stderr, "", "{scheme}");
        for row in rows {
            assert!(run.stdout.contains(row), "{scheme}: {}", run.stdout);
        }
    }
    let (summary, stderr, written) =
        subdivide(&book, &["--scheme", "tri-split-3", "--levels", "1"]);
    assert_eq!(stderr, "");
    assert_eq!(
        summary,
        "level 1: V = 22, E = 48, F = 27, UV = 26; wrote OUT\n"
    );
    assert_eq!(written.lines().filter(|l| l.starts_with("vt ")).count(), 26);
    let faces: Vec<&str> = written.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(faces.len(), 27);
    assert!(faces
        .iter()
        .all(|f| f.split(' ').skip(1).all(|c| c.contains('/'))));
    // --no-uv: as before, no UVs.
    let (summary, stderr, written) = subdivide(
        &book,
        &["--scheme", "tri-split-3", "--levels", "1", "--no-uv"],
    );
    assert_eq!(stderr, "");
    assert_eq!(summary, "level 1: V = 22, E = 48, F = 27; wrote OUT\n");
    assert!(!written.contains("vt "));
}

#[test]
fn a_mesh_without_vt_verifies_and_subdivides_as_before() {
    let tetra = data("tetra.obj");
    let text = ok(&[
        "verify", "--mesh", &tetra, "--scheme", "loop", "--levels", "1", "--format", "json",
    ]);
    assert!(!text.contains("UV"), "{text}");
    let (summary, stderr, written) = subdivide(&tetra, &["--scheme", "loop", "--levels", "1"]);
    assert_eq!(stderr, "");
    assert_eq!(summary, "level 1: V = 10, E = 24, F = 16; wrote OUT\n");
    assert!(!written.contains("vt ") && !written.contains('/'));
}

// ---- the shared test meshes ($SUBCOUNT_MESHES) ----

fn shared(name: &str) -> String {
    testdata::mesh(name).to_string_lossy().into_owned()
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_catmull_clark_level_2_writes_the_predicted_uv_values() {
    let spot = shared("spot_control_mesh.obj");
    let predicted = predicted_uv(&spot, "catmull-clark", 2);
    // OpenSubdiv's GetNumFVarValues(2) on spot_control_mesh.
    assert_eq!(predicted, 3225);
    let (summary, stderr, _) = subdivide(&spot, &["--scheme", "catmull-clark", "--levels", "2"]);
    assert_eq!(stderr, "");
    assert_eq!(
        summary,
        "level 2: V = 2930, E = 5856, F = 2928, UV = 3225; wrote OUT\n"
    );
    for mode in MODES {
        let (s, _, _) = subdivide(
            &spot,
            &[
                "--scheme",
                "catmull-clark",
                "--levels",
                "2",
                "--uv-interpolation",
                mode,
            ],
        );
        assert_eq!(s, summary, "{mode}");
    }
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn verify_matches_opensubdivs_uv_counts_on_spot() {
    let spot = shared("spot_control_mesh.obj");
    let counts = |rows: Vec<(Value, Value)>| -> Vec<u64> {
        rows.into_iter()
            .map(|(p, m)| {
                assert_eq!(p, m);
                p.as_u64().expect("a count")
            })
            .collect()
    };
    assert_eq!(
        counts(verify_uv(&spot, "catmull-clark", "2")),
        [267, 885, 3225]
    );
    let triangulated = shared("spot_triangulated.obj");
    assert_eq!(
        counts(verify_uv(&triangulated, "loop", "2")),
        [3225, 12297, 48009]
    );
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn sqrt3_on_spot_writes_its_uvs() {
    let triangulated = shared("spot_triangulated.obj");
    let (summary, stderr, written) =
        subdivide(&triangulated, &["--scheme", "sqrt3", "--levels", "1"]);
    assert_eq!(stderr, "");
    assert_eq!(
        summary,
        "level 1: V = 8786, E = 26352, F = 17568, UV = 9657; wrote OUT\n"
    );
    assert_eq!(
        written.lines().filter(|l| l.starts_with("vt ")).count(),
        9657
    );
    assert_eq!(predicted_uv(&triangulated, "sqrt3", 1), 9657);
    let rows = verify_uv(&triangulated, "sqrt3", "3");
    let uv: Vec<u64> = rows
        .iter()
        .map(|(p, m)| {
            assert_eq!(p, m);
            p.as_u64().expect("a count")
        })
        .collect();
    assert_eq!(uv, [3225, 9657, 28953, 86841]);
}

/// `sqrt3-boundary` (steps A and B) on the triangulated cube of three charts with two faces
/// left out: the UVs are written (`f v/vt`, one `vt` per value), the summary's `UV = N` is the
/// count `table` predicts, and `verify`'s UV rows match at every level.
#[test]
fn sqrt3_boundary_writes_and_verifies_its_uvs() {
    let text = std::fs::read_to_string(data("uv_cube_tri.obj")).expect("the fixture");
    let faces = text.lines().filter(|l| l.starts_with("f ")).count();
    let mut kept = 0;
    let open: String = text
        .lines()
        .filter(|l| {
            if !l.starts_with("f ") {
                return true;
            }
            kept += 1;
            kept <= faces - 2
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("open.obj");
    std::fs::write(&path, open).expect("written");
    let mesh = path.to_str().expect("a UTF-8 path");
    for level in 1..=3u64 {
        let (summary, stderr, written) = subdivide(
            mesh,
            &["--scheme", "sqrt3-boundary", "--levels", &level.to_string()],
        );
        assert_eq!(stderr, "");
        let uv = predicted_uv(mesh, "sqrt3-boundary", level);
        assert_eq!(summary_uv(&summary), Some(uv), "{summary}");
        assert_eq!(
            written.lines().filter(|l| l.starts_with("vt ")).count() as u64,
            uv
        );
        assert!(written
            .lines()
            .filter(|l| l.starts_with("f "))
            .all(|l| l.split_whitespace().skip(1).all(|c| c.contains('/'))));
    }
    let rows = verify_uv(mesh, "sqrt3-boundary", "4");
    assert_eq!(rows.len(), 5);
    assert!(rows.iter().all(|(p, m)| p == m), "{rows:?}");
}

/// The `vt`, `vn` and face lines of an OBJ text, and the forms of its face corners: how many
/// corners have a `vt` and how many a `vn`, of all corners.
struct ObjShape {
    vt: usize,
    vn: usize,
    faces: usize,
    corners: usize,
    with_vt: usize,
    with_vn: usize,
}

fn shape(text: &str) -> ObjShape {
    let mut s = ObjShape {
        vt: 0,
        vn: 0,
        faces: 0,
        corners: 0,
        with_vt: 0,
        with_vn: 0,
    };
    for line in text.lines() {
        if line.starts_with("vt ") {
            s.vt += 1;
        } else if line.starts_with("vn ") {
            s.vn += 1;
        } else if let Some(corners) = line.strip_prefix("f ") {
            s.faces += 1;
            for corner in corners.split_whitespace() {
                let parts: Vec<&str> = corner.split('/').collect();
                s.corners += 1;
                s.with_vt += usize::from(parts.get(1).is_some_and(|t| !t.is_empty()));
                s.with_vn += usize::from(parts.get(2).is_some_and(|n| !n.is_empty()));
            }
        }
    }
    s
}

/// The `vt` lines of an OBJ text.
fn vt_lines(text: &str) -> Vec<&str> {
    text.lines().filter(|l| l.starts_with("vt ")).collect()
}

#[test]
fn the_written_file_has_every_uv_value_and_a_vt_at_every_corner() {
    let cube = data("uv_cube.obj");
    for precision in ["f64", "f32"] {
        let (summary, _, text) = subdivide(
            &cube,
            &[
                "--scheme",
                "catmull-clark",
                "--levels",
                "2",
                "--precision",
                precision,
            ],
        );
        let n = summary_uv(&summary).expect("UV = N") as usize;
        let s = shape(&text);
        assert_eq!(s.vt, n, "{precision}");
        assert_eq!(
            (s.faces, s.corners, s.with_vt, s.with_vn),
            (96, 384, 384, 0)
        );
        // Read back: every corner has a vt, every vt is used, and each is one UV value.
        let mesh = halfedge::io::read_obj_from(text.as_bytes(), "out.obj").expect("readable");
        let uvs = mesh.uvs().expect("a vt at every corner");
        assert_eq!((uvs.coords().len(), uvs.unreferenced()), (n, 0));
        let layout = halfedge::stats::uv_counts(&mesh).expect("a layout");
        assert_eq!(layout.values as usize, n);
        assert_eq!(layout.charts, 3);
    }
}

#[test]
fn interpolation_modes_move_values_not_their_number() {
    let cube = data("uv_cube.obj");
    let written = |mode: Option<&str>| {
        let mut args = vec!["--scheme", "catmull-clark", "--levels", "2"];
        if let Some(mode) = mode {
            args.extend(["--uv-interpolation", mode]);
        }
        subdivide(&cube, &args).2
    };
    let default = written(None);
    assert_eq!(written(Some("corners-plus1")), default);
    let none = written(Some("none"));
    let all = written(Some("all"));
    assert_eq!(vt_lines(&none).len(), vt_lines(&all).len());
    assert_ne!(vt_lines(&none), vt_lines(&all));
    // Fully smooth UVs pull the chart corners in; bilinear ones keep the unit cube's corners.
    assert!(all.contains("\nvt 0.0 0.25\n"), "{all}");
    assert!(!none.contains("\nvt 0.0 0.25\n"));
    // The positions and faces do not depend on the mode.
    let geometry = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| l.starts_with("v ") || l.starts_with("f "))
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(geometry(&none), geometry(&all));
}

#[test]
fn the_tag_sets_the_default_mode() {
    let cube = data("uv_cube.obj");
    let tagged = data("uv_cube_tagged.obj");
    let args = ["--scheme", "catmull-clark", "--levels", "2"];
    let (_, stderr, from_tag) = subdivide(&tagged, &args);
    assert_eq!(stderr, "");
    let with = |file: &str, mode: &str| {
        let mut with = args.to_vec();
        with.extend(["--uv-interpolation", mode]);
        subdivide(file, &with).2
    };
    // The tag (5: `all`) is the file's default ...
    assert_eq!(from_tag, with(&cube, "all"));
    // ... which the flag overrides. (On this cube, whose strip's UVs are affine, the default
    // `corners-plus1` gives the same values as `all`: every rule reproduces affine data, so
    // the override is told apart with `none`, which smooths the chart corners.)
    let none = with(&tagged, "none");
    assert_eq!(none, with(&cube, "none"));
    assert_ne!(none, from_tag);
    assert_eq!(subdivide(&cube, &args).2, with(&cube, "corners-plus1"));
}

#[test]
fn normals_are_written_as_vn_at_every_corner() {
    let cube = data("uv_cube.obj");
    for precision in ["f64", "f32"] {
        let base = [
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "--precision",
            precision,
        ];
        let mut args = base.to_vec();
        args.push("--normals");
        let (summary, _, text) = subdivide(&cube, &args);
        let s = shape(&text);
        assert_eq!(
            (s.vn, s.corners, s.with_vt, s.with_vn),
            (26, 96, 96, 96),
            "{precision}"
        );
        assert_eq!(summary, subdivide(&cube, &base).0);
        args.push("--no-uv");
        let (_, _, text) = subdivide(&cube, &args);
        let s = shape(&text);
        assert_eq!(
            (s.vt, s.vn, s.with_vt, s.with_vn),
            (0, 26, 0, 96),
            "{precision}"
        );
        assert!(text.contains("//"));
        // Unit normals.
        for line in text.lines().filter(|l| l.starts_with("vn ")) {
            let n: Vec<f64> = line[3..]
                .split_whitespace()
                .map(|x| x.parse().expect("a number"))
                .collect();
            let length = n.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((length - 1.0).abs() < 1e-6, "{line}");
        }
    }
    // Without the flag, no normals.
    let (_, _, text) = subdivide(&cube, &["--scheme", "catmull-clark", "--levels", "1"]);
    assert_eq!(shape(&text).vn, 0);
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_level_2_reads_back_with_its_3225_uv_values() {
    let spot = shared("spot_control_mesh.obj");
    let (_, _, text) = subdivide(&spot, &["--scheme", "catmull-clark", "--levels", "2"]);
    let s = shape(&text);
    assert_eq!((s.vt, s.corners, s.with_vt), (3225, 11712, 11712));
    let mesh = halfedge::io::read_obj_from(text.as_bytes(), "spot2.obj").expect("readable");
    let uvs = mesh.uvs().expect("a vt at every corner");
    assert_eq!((uvs.coords().len(), uvs.unreferenced()), (3225, 0));
}

// ---- against OpenSubdiv ($SUBCOUNT_OSD_DRIVER, $SUBCOUNT_MESHES) ----

/// `subcount subdivide -o` of spot (Catmull-Clark, level 2) and spot_triangulated (Loop,
/// level 1) in every `--uv-interpolation` mode, in `f64` and `f32`, against OpenSubdiv's
/// `InterpolateFaceVarying` (the driver's `--fvar MODE`): the same UV values, and at every
/// face corner (faces matched through their positions) the same UV, to 1e-12 of the UV
/// bounding box's diagonal in `f64` and 1e-6 in `f32`.
#[test]
#[ignore = "needs the OpenSubdiv driver (SUBCOUNT_OSD_DRIVER) and SUBCOUNT_MESHES"]
fn written_uvs_match_opensubdiv_in_every_mode() {
    use crate::creases::osd_support::{self, fvar::corner_uv_error, fvar::opensubdiv_fvar};
    use halfedge::tags::FaceVaryingInterpolation;
    use osd_support::{bounding_box_diagonal, correspondence, without_bare_vertices, Osd};

    osd_support::driver();
    let dir = tempfile::tempdir().expect("a temporary folder");
    for (osd, scheme, file, level) in [
        (Osd::Catmark, "catmull-clark", "spot_control_mesh.obj", 2u32),
        (Osd::Loop, "loop", "spot_triangulated.obj", 1),
    ] {
        let path = testdata::mesh(file);
        let base = halfedge::io::read_mesh(&path).expect("readable");
        let diagonal = bounding_box_diagonal(&base.positions);
        for &mode in FaceVaryingInterpolation::ALL {
            let running = opensubdiv_fvar(&[], osd, level, &path, None, mode.into());
            let theirs = running.fvar_level();
            let their_mesh = without_bare_vertices(&theirs.mesh);
            for (precision, tolerance) in [("f64", 1e-12), ("f32", 1e-6)] {
                let what = format!("{file} {scheme} level {level} {} {precision}", mode.name());
                let out = dir
                    .path()
                    .join(format!("{scheme}-{}-{precision}.obj", mode.name()));
                let out = out.to_str().expect("UTF-8");
                let levels = level.to_string();
                ok(&[
                    "subdivide",
                    "--mesh",
                    path.to_str().expect("UTF-8"),
                    "--scheme",
                    scheme,
                    "--levels",
                    &levels,
                    "--uv-interpolation",
                    mode.name(),
                    "--precision",
                    precision,
                    "-o",
                    out,
                ]);
                let ours = halfedge::io::read_mesh(out).expect("subcount's output");
                let our_uvs = ours.uvs().expect("UVs written");
                assert_eq!(
                    our_uvs.coords().len(),
                    theirs.values().len(),
                    "{what}: values"
                );
                let to_ours = correspondence(&their_mesh, &ours, 1e-6 * diagonal)
                    .unwrap_or_else(|e| panic!("{what}: positions: {e}"));
                let offsets = ours.face_offsets();
                let (worst, at) = corner_uv_error(&theirs, &their_mesh, &ours, &to_ours, |g, k| {
                    our_uvs.coords()[our_uvs.corners()[offsets[g] + k] as usize]
                })
                .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert!(
                    worst <= tolerance,
                    "{what}: UVs differ by {worst:.3e} of the UV box's diagonal ({at})"
                );
                eprintln!("{what}: max UV deviation {worst:.3e}");
            }
        }
    }
}

/// The memory guard counts the UV channel: `--timings`' `predicted_peak_bytes` with UVs is
/// the one without (`--no-uv`) plus [`halfedge::memory::predicted_uv_bytes`] of the layout
/// (`f64` values on the one-shot path, the chosen precision when refining once; a rule
/// without a face-varying rule adds nothing).
#[test]
fn the_memory_guard_counts_the_uv_channel() {
    let cube = data("uv_cube.obj");
    let poly = halfedge::io::read_obj(&cube).expect("readable");
    let layout = halfedge::stats::uv_layout_counts(&poly).expect("a layout");
    let predicted = |args: &[&str]| -> u64 {
        let mut all = vec!["--levels", "3", "--timings"];
        all.extend_from_slice(args);
        let (_, stderr, _) = subdivide(&cube, &all);
        let json = stderr
            .lines()
            .find_map(|l| l.strip_prefix("timings: "))
            .expect("a timings line");
        let object: Value = serde_json::from_str(json).expect("timings JSON");
        object["predicted_peak_bytes"].as_u64().expect("a number")
    };
    let uv = |rule: halfedge::Rule, scalar: usize| -> u64 {
        let bytes = halfedge::memory::predicted_uv_bytes(rule, &layout, 3, scalar, false)
            .expect("a prediction");
        u64::try_from(bytes).expect("small")
    };
    let cc = ["--scheme", "catmull-clark"];
    let f32 = ["--scheme", "catmull-clark", "--precision", "f32"];
    let one_shot = predicted(&cc);
    assert!(one_shot > predicted(&[&cc[..], &["--no-uv"]].concat()));
    assert_eq!(
        one_shot - predicted(&[&cc[..], &["--no-uv"]].concat()),
        uv(halfedge::Rule::CatmullClark, 8)
    );
    assert_eq!(
        predicted(&f32) - predicted(&[&f32[..], &["--no-uv"]].concat()),
        uv(halfedge::Rule::CatmullClark, 4)
    );
    // Doo-Sabin's corner channel, on the one-shot path and refined once.
    let doo_sabin = ["--scheme", "doo-sabin"];
    assert_eq!(
        predicted(&doo_sabin) - predicted(&[&doo_sabin[..], &["--no-uv"]].concat()),
        uv(halfedge::Rule::DooSabin, 8)
    );
    let f32 = ["--scheme", "mid-edge", "--precision", "f32"];
    assert_eq!(
        predicted(&f32) - predicted(&[&f32[..], &["--no-uv"]].concat()),
        uv(halfedge::Rule::MidEdge, 4)
    );
}

#[test]
fn the_face_list_path_predicts_uv_values_without_sibling_splits() {
    // A, B, A, B around one vertex: OpenSubdiv's rules (catmull-clark, loop) split a sibling
    // value; the face-list subdividers refine the layout as a mesh and do not (UV0 = V).
    let fan = data("uv_abab_fan.obj");
    for (scheme, row) in [
        ("catmull-clark", "    1         UV         23        23\n"),
        (
            "catmull-clark-general",
            "    1         UV         22        22\n",
        ),
        ("loop", "    1         UV         19        19\n"),
        ("loop-general", "    1         UV         18        18\n"),
    ] {
        let run = subcount(&[
            "verify", "--mesh", &fan, "--scheme", scheme, "--levels", "2",
        ]);
        assert_eq!(run.code, 0, "{scheme}: {}{}", run.stdout, run.stderr);
        assert!(run.stdout.contains(row), "{scheme}: {}", run.stdout);
        assert!(
            run.stdout.ends_with("all counts match the prediction\n"),
            "{scheme}: {}",
            run.stdout
        ); // `table` counts the same values: the face-list schemes start from UV0 = V.
        let value = row.split_whitespace().nth(2).unwrap();
        let table = ok(&[
            "table", "--mesh", &fan, "--scheme", scheme, "--levels", "1", "--format", "csv",
        ]);
        let last = table.lines().last().unwrap();
        assert!(last.starts_with("1,"), "{scheme}: {table}");
        assert_eq!(last.rsplit(',').next(), Some(value), "{scheme}: {table}");
    }
}

#[test]
fn uv_interpolation_is_noted_as_not_applied_on_the_raw_face_list() {
    let book = data("uv_book.obj");
    let (summary, stderr, _) = subdivide(
        &book,
        &[
            "--scheme",
            "loop-general",
            "--levels",
            "1",
            "--uv-interpolation",
            "all",
        ],
    );
    assert_eq!(
        stderr,
        format!("note: {book}: --uv-interpolation is not applied on the raw face list, which refines UVs linearly\n")
    );
    assert_eq!(
        summary,
        "level 1: V = 12, E = 23, F = 12, UV = 15; wrote OUT\n"
    );
}
