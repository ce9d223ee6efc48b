//! UV values in every count: `stats` prints the UV layout (a text line, the `"uv"` JSON
//! object), `table`, `at`, `plot` and `fit` gain a `UV` column for a mesh with a UV layout,
//! `formula --mesh` a `UV(s)` closed form, `fit` the `--max-uv` and `--bytes-per-uv` limits.
//! A mesh without `vt` prints what it always printed; a mesh with `vt` at only some corners
//! has no layout (one line in `stats`, `"uv": null`, no column elsewhere).
//!
//! spot_control_mesh's numbers are issue 14's: its layout `V = 267, E = 438, BE = 144`, 72
//! seam edges, 13 charts, and OpenSubdiv's 267, 885, 3225, 12297, 48009 values at levels 0-4
//! under Catmull-Clark.

use crate::util::{fails, ok, subcount};

/// A temporary folder holding one file.
fn file(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("the fixture is written");
    let path = path.to_string_lossy().into_owned();
    (dir, path)
}

/// The cube's eight corners.
const CUBE_V: &str =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n";

/// The cube cut into six charts: each face has its own four `vt` (24 in all).
fn cube_of_charts() -> String {
    let faces = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 4, 8, 7],
        [4, 1, 5, 8],
    ];
    let mut text = CUBE_V.to_string();
    for i in 0..24 {
        text.push_str(&format!("vt {} 0\n", f64::from(i) / 24.0));
    }
    for (f, face) in faces.iter().enumerate() {
        let corners: Vec<String> = face
            .iter()
            .enumerate()
            .map(|(k, v)| format!("{v}/{}", 4 * f + k + 1))
            .collect();
        text.push_str(&format!("f {}\n", corners.join(" ")));
    }
    text
}

/// The same cube without any `vt`.
fn plain_cube() -> String {
    format!("{CUBE_V}f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n")
}

/// Each quad refines on its own: `6 (2^s + 1)^2` values at level `s`.
fn charts_at(s: u32) -> u64 {
    6 * (2u64.pow(s) + 1).pow(2)
}

#[test]
fn stats_prints_the_uv_layout_of_a_mesh_with_uvs() {
    let (_dir, cube) = file("charts.obj", &cube_of_charts());
    let text = ok(&["stats", "--mesh", &cube]);
    assert!(
        text.contains(
            "\nUV layout: V = 24, E = 24, BE = 24, seam edges = 12, boundary loops = 6, charts = 6, unreferenced = 0\napplicable schemes: "
        ),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["stats", "--mesh", &cube, "--format", "json"])).unwrap();
    assert_eq!(
        json["uv"],
        serde_json::json!({"V": 24, "E": 24, "BE": 24, "seam_edges": 12, "boundary_loops": 6, "charts": 6, "unreferenced": 0})
    );
}

#[test]
fn a_mesh_without_vt_has_no_uv_anywhere() {
    let (_dir, cube) = file("cube.obj", &plain_cube());
    let stats = ok(&["stats", "--mesh", &cube]);
    assert!(!stats.contains("UV"), "{stats}");
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["stats", "--mesh", &cube, "--format", "json"])).unwrap();
    assert!(json.get("uv").is_none(), "{json}");
    let table = ok(&[
        "table",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "0..=2",
        "--format",
        "csv",
    ]);
    assert_eq!(table.lines().next(), Some("level,V,IE,BE,F,H,E"), "{table}");
    let at = ok(&[
        "at",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--level",
        "2",
        "--format",
        "json",
    ]);
    assert!(!at.contains("UV"), "{at}");
    let formula = ok(&["formula", "--mesh", &cube, "--scheme", "catmull-clark"]);
    assert!(!formula.contains("UV"), "{formula}");
}

#[test]
fn a_mesh_with_vt_at_some_corners_has_no_layout() {
    let text = format!("{CUBE_V}vt 0 0\nvt 1 0\nvt 1 1\nf 1/1 4/2 3/3 2/1\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
    let (_dir, cube) = file("partial.obj", &text);
    let stats = ok(&["stats", "--mesh", &cube]);
    assert!(
        stats.contains("\n4 of 24 face corners have texture coordinates: no UV layout\n"),
        "{stats}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["stats", "--mesh", &cube, "--format", "json"])).unwrap();
    assert_eq!(json["uv"], serde_json::Value::Null, "{json}");
    // Elsewhere no column, and one note on stderr saying why.
    let run = subcount(&[
        "table",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "0..=1",
        "--format",
        "csv",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        run.stdout.lines().next(),
        Some("level,V,IE,BE,F,H,E"),
        "{}",
        run.stdout
    );
    assert_eq!(
        run.stderr,
        format!("note: {cube}: 4 of 24 face corners have texture coordinates: no UV layout: no UV column\n")
    );
    fails(
        &[
            "fit",
            "--mesh",
            &cube,
            "--scheme",
            "catmull-clark",
            "--max-uv",
            "100",
        ],
        2,
        "has no UV layout",
    );
}

#[test]
fn table_at_and_plot_gain_a_uv_column() {
    let (dir, cube) = file("charts.obj", &cube_of_charts());
    let csv = ok(&[
        "table",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "0..=3",
        "--format",
        "csv",
    ]);
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("level,V,IE,BE,F,H,E,UV"), "{csv}");
    for (s, line) in lines.enumerate() {
        let uv = line.rsplit(',').next().unwrap();
        assert_eq!(uv, charts_at(s as u32).to_string(), "{csv}");
    }
    let text = ok(&[
        "table",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "0..=2",
    ]);
    assert!(
        text.lines().next().unwrap().trim_end().ends_with("UV"),
        "{text}"
    );
    let json: serde_json::Value = serde_json::from_str(&ok(&[
        "table",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "0..=2",
        "--format",
        "json",
    ]))
    .unwrap();
    let rows = json
        .as_array()
        .map_or_else(|| json["rows"].clone(), |_| json.clone());
    let uv: Vec<u64> = rows
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r["UV"]
                .as_u64()
                .or_else(|| r["UV"].as_str()?.parse().ok())
                .unwrap()
        })
        .collect();
    assert_eq!(uv, [charts_at(0), charts_at(1), charts_at(2)]);

    let at = ok(&[
        "at",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--level",
        "3",
    ]);
    assert!(at.ends_with(&format!("UV = {}\n", charts_at(3))), "{at}");
    let summary = ok(&[
        "at",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--level",
        "3",
        "--summary",
    ]);
    assert!(
        summary.lines().last().unwrap().starts_with("UV: "),
        "{summary}"
    );
    let at_json: serde_json::Value = serde_json::from_str(&ok(&[
        "at",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--level",
        "3",
        "--format",
        "json",
    ]))
    .unwrap();
    assert_eq!(
        at_json["UV"].to_string().trim_matches('"'),
        charts_at(3).to_string()
    );

    // The plain cube draws its 5 positive components (BE is 0); the charted one one more.
    let plain = dir.path().join("plain.obj");
    std::fs::write(&plain, plain_cube()).unwrap();
    let plot = |mesh: &str, out: &str| {
        let out = dir.path().join(out);
        ok(&[
            "plot",
            "--mesh",
            mesh,
            "--scheme",
            "catmull-clark",
            "--levels",
            "0..=4",
            "-o",
            out.to_str().unwrap(),
        ])
    };
    assert!(plot(plain.to_str().unwrap(), "plain.svg").contains("(5 series, levels 0..=4)"));
    assert!(plot(&cube, "charts.svg").contains("(6 series, levels 0..=4)"));
    let svg = std::fs::read_to_string(dir.path().join("charts.svg")).unwrap();
    assert!(
        svg.contains(">\nUV\n</text>"),
        "the legend names the UV series"
    );
}

#[test]
fn schemes_without_uv_counts_print_no_column_and_say_why() {
    // The charted cube's faces triangulated, and a scheme without a subdivision rule (every
    // built-in rule counts UV values).
    let (_scheme_dir, still) = file(
        "still.toml",
        "name = \"still\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n",
    );
    let mut text = CUBE_V.to_string();
    let quads = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 4, 8, 7],
        [4, 1, 5, 8],
    ];
    for i in 0..24 {
        text.push_str(&format!("vt {i} 0\n"));
    }
    for (f, q) in quads.iter().enumerate() {
        let c = |k: usize| format!("{}/{}", q[k], 4 * f + k + 1);
        text.push_str(&format!(
            "f {} {} {}\nf {} {} {}\n",
            c(0),
            c(1),
            c(2),
            c(0),
            c(2),
            c(3)
        ));
    }
    let (_dir, mesh) = file("tris.obj", &text);
    let run = subcount(&[
        "table",
        "--mesh",
        &mesh,
        "--scheme-file",
        &still,
        "--levels",
        "0..=2",
        "--format",
        "csv",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        run.stdout.lines().next(),
        Some("level,V,E,F"),
        "{}",
        run.stdout
    );
    assert_eq!(
        run.stderr,
        "note: a scheme without a subdivision rule does not count UV values: no UV column\n"
    );
    // sqrt3 counts them: 24 values, 24 layout boundary edges, 12 seam edges (the cube's
    // edges; the diagonals lie inside a chart), 12 faces: UV' = UV + 2 S + F.
    let sqrt3 = ok(&[
        "table", "--mesh", &mesh, "--scheme", "sqrt3", "--levels", "0..=2", "--format", "csv",
    ]);
    assert_eq!(
        sqrt3,
        "level,V,E,F,UV\n0,8,18,12,24\n1,20,54,36,60\n2,56,162,108,168\n"
    );
    // Loop counts them.
    let loop_csv = ok(&[
        "table", "--mesh", &mesh, "--scheme", "loop", "--levels", "0..=1", "--format", "csv",
    ]);
    assert!(
        loop_csv.lines().next().unwrap().ends_with(",UV"),
        "{loop_csv}"
    );
    fails(
        &[
            "fit",
            "--mesh",
            &mesh,
            "--scheme-file",
            &still,
            "--max-uv",
            "100",
        ],
        2,
        "--max-uv: a scheme without a subdivision rule does not count UV values",
    );
}

#[test]
fn fit_limits_uv_values_and_refuses_without_a_layout() {
    let (_dir, cube) = file("charts.obj", &cube_of_charts());
    // 24, 54, 150, 486, 1734 values.
    let text = ok(&[
        "fit",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--max-uv",
        "486",
    ]);
    assert!(
        text.starts_with("highest level within the budget: 3\n"),
        "{text}"
    );
    assert!(text.ends_with("UV = 486\n"), "{text}");
    let json: serde_json::Value = serde_json::from_str(&ok(&[
        "fit",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--max-uv",
        "485",
        "--format",
        "json",
    ]))
    .unwrap();
    assert_eq!(json["level"], 2, "{json}");
    // Bytes: 12 V + 12 F + 8 UV; level 2 (98 V, 96 F, 150 UV) is 3528 bytes.
    let memory = |bytes: &str| {
        ok(&[
            "fit",
            "--mesh",
            &cube,
            "--scheme",
            "catmull-clark",
            "--memory",
            bytes,
            "--bytes-per-uv",
            "8",
        ])
    };
    assert!(memory("3528").starts_with("highest level within the budget: 2\n"));
    assert!(memory("3527").starts_with("highest level within the budget: 1\n"));
    // Without the UV flags the budget is what it was (the answer gains its UV line).
    let plain = ok(&[
        "fit",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--memory",
        "2328",
    ]);
    assert!(
        plain.starts_with("highest level within the budget: 2\n"),
        "{plain}"
    );

    fails(
        &["fit", "--scheme", "loop", "--counts", "V=12,E=30,F=20", "--max-uv", "100"],
        2,
        "--max-uv counts UV values, which needs --mesh FILE with texture coordinates (`vt`) at every face corner, but no mesh is given",
    );
    let (_plain_dir, plain_cube) = file("cube.obj", &plain_cube());
    fails(
        &[
            "fit",
            "--mesh",
            &plain_cube,
            "--scheme",
            "catmull-clark",
            "--memory",
            "1MiB",
            "--bytes-per-uv",
            "8",
        ],
        2,
        "--bytes-per-uv counts UV values",
    );
}

#[test]
fn formula_gives_uv_of_s_in_every_format() {
    let (_dir, cube) = file("charts.obj", &cube_of_charts());
    let args = |format: &'static str| -> Vec<String> {
        [
            "formula",
            "--mesh",
            &cube,
            "--scheme",
            "catmull-clark",
            "--format",
            format,
        ]
        .map(String::from)
        .to_vec()
    };
    let run = |format: &'static str| {
        let a = args(format);
        ok(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let text = run("text");
    assert!(text.contains("\nUV(s) = UV0 + "), "{text}");
    assert!(text.contains("UE0"), "{text}");
    assert!(text.contains("UBE0"), "{text}");
    // 6 (2^s + 1)^2 = 6*4^s + 12*2^s + 6.
    assert!(text.contains("\nUV(s) = 6*4^s + 12*2^s + 6"), "{text}");
    let latex = run("latex");
    assert!(latex.contains("\nUV(s) = "), "{latex}");
    assert!(latex.contains("{UE}_0"), "{latex}");
    let rust = run("rust");
    assert!(
        rust.contains("pub fn catmull_clark_uv_counts(x0: [i128; 5], s: u64)"),
        "{rust}"
    );
    let json: serde_json::Value = serde_json::from_str(&run("json")).unwrap();
    let last = json
        .as_array()
        .and_then(|a| a.last())
        .expect("a list of components");
    assert_eq!(last["component"], "UV", "{json}");
    assert!(
        last["terms"][0]["coefficients"].get("UE").is_some(),
        "{json}"
    );
}

/// The dual rules count UVs over the layout and its seams: the cube of charts has 12 seam
/// edges, so Doo-Sabin gives `V(s) + 2 * 3^(s-1) * 12 = 6*4^s + 8*3^s` and mid-edge
/// `E(s-1) + S(s-1) = 12*2^s` from level 1 on; `table`, `at` and `formula` agree.
#[test]
fn the_dual_rules_count_uv_values_in_table_at_and_formula() {
    let (_dir, cube) = file("charts.obj", &cube_of_charts());
    for (scheme, uv, form) in [
        (
            "doo-sabin",
            [24, 48, 168, 600],
            "\nUV(s) = 6*4^s + 8*3^s for s >= 1; UV(0) = 24",
        ),
        (
            "mid-edge",
            [24, 24, 48, 96],
            "\nUV(s) = 12*2^s for s >= 1; UV(0) = 24",
        ),
    ] {
        let csv = ok(&[
            "table", "--mesh", &cube, "--scheme", scheme, "--levels", "0..=3", "--format", "csv",
        ]);
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some("level,V,E,F,UV"), "{csv}");
        let column: Vec<u64> = lines
            .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
            .collect();
        assert_eq!(column, uv, "{scheme}");
        let at = ok(&["at", "--mesh", &cube, "--scheme", scheme, "--level", "3"]);
        assert!(at.ends_with(&format!("UV = {}\n", uv[3])), "{at}");
        let text = ok(&["formula", "--mesh", &cube, "--scheme", scheme]);
        assert!(text.contains(form), "{text}");
        assert!(text.contains("S0 seam edges"), "{text}");
        assert!(text.contains("S0 = 12"), "{text}");
        let rust = ok(&[
            "formula", "--mesh", &cube, "--scheme", scheme, "--format", "rust",
        ]);
        assert!(rust.contains("the state (UV, UE, UBE, S)"), "{rust}");
    }
    // Chained with a rule of the other kind: no UV column, and why.
    let run = subcount(&[
        "table",
        "--mesh",
        &cube,
        "--scheme",
        "doo-sabin:1,catmull-clark",
        "--levels",
        "2",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(!run.stdout.contains("UV"), "{}", run.stdout);
    assert_eq!(
        run.stderr,
        "note: doo-sabin does not count UV values composed with catmull-clark (their UV states do not convert): no UV column\n"
    );
    // Two dual stages share the state.
    let csv = ok(&[
        "table",
        "--mesh",
        &cube,
        "--scheme",
        "doo-sabin:1,mid-edge",
        "--levels",
        "0..=2",
        "--format",
        "csv",
    ]);
    let last: Vec<&str> = csv.lines().map(|l| l.rsplit(',').next().unwrap()).collect();
    // Level 2: mid-edge on Doo-Sabin's level 1 (48 edges, 36 seams).
    assert_eq!(last, ["UV", "24", "48", "84"], "{csv}");
}

// ---- spot_control_mesh ($SUBCOUNT_MESHES) ----

fn spot() -> String {
    testdata::mesh("spot_control_mesh.obj")
        .to_string_lossy()
        .into_owned()
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_control_mesh_prints_issue_14s_layout_and_counts() {
    let spot = spot();
    let text = ok(&["stats", "--mesh", &spot]);
    assert!(
        text.contains("\nUV layout: V = 267, E = 438, BE = 144, seam edges = 72, boundary loops = 13, charts = 13, unreferenced = 0\n"),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["stats", "--mesh", &spot, "--format", "json"])).unwrap();
    // The keys exact, in this order.
    assert_eq!(
        json["uv"].to_string(),
        r#"{"V":267,"E":438,"BE":144,"seam_edges":72,"boundary_loops":13,"charts":13,"unreferenced":0}"#
    );
    let csv = ok(&[
        "table",
        "--mesh",
        &spot,
        "--scheme",
        "catmull-clark",
        "--levels",
        "0..=4",
        "--format",
        "csv",
    ]);
    let uv: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(uv, ["267", "885", "3225", "12297", "48009"], "{csv}");
    let formula = ok(&["formula", "--mesh", &spot, "--scheme", "catmull-clark"]);
    assert!(
        formula.contains("\nUV(s) = 183*4^s + 72*2^s + 9 for s >= 1"),
        "{formula}"
    );
    let fit = ok(&[
        "fit",
        "--mesh",
        &spot,
        "--scheme",
        "catmull-clark",
        "--max-uv",
        "12296",
    ]);
    assert!(
        fit.starts_with("highest level within the budget: 2\n"),
        "{fit}"
    );
    assert!(fit.ends_with("UV = 3225\n"), "{fit}");
}

/// A fan of four triangles whose centre uses `vt` 1, 2, 1, 2 around it: `verify` matches its
/// UV counts (and every other count) for every triangle rule and Catmull-Clark, levels 0-2.
#[test]
fn verify_counts_a_vertex_with_two_vt_alternating_for_every_rule() {
    let mesh = crate::util::data("uv_abab_fan.obj");
    for scheme in [
        "tri-split-2",
        "midpoint",
        "butterfly",
        "loop",
        "catmull-clark",
    ] {
        let out = ok(&[
            "verify", "--mesh", &mesh, "--scheme", scheme, "--levels", "2",
        ]);
        assert!(out.contains("all counts match"), "{scheme}: {out}");
        let uv_rows = out.lines().filter(|l| l.contains(" UV ")).count();
        assert_eq!(uv_rows, 3, "{scheme}: {out}");
    }
}

/// A tetrahedron whose every corner uses the one `vt`: four (vertex, `vt`) pairs, one `vt`.
const TETRA_ONE_VT: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nf 1/1 3/1 2/1\nf 1/1 2/1 4/1\nf 2/1 3/1 4/1\nf 1/1 4/1 3/1\n";

/// `UV(s)` holds from level 1 on (`UvScheme::VALID_FROM`) and level 0 is the number of `vt`
/// the faces use, in every format: Loop on the tetrahedron with one `vt` (the form gives 4 at
/// level 0, the table 1), Catmull-Clark on the cube with one `vt` (whose form has an early
/// level of its own, 8 pairs, replaced by the 1 `vt`).
#[test]
fn formula_states_uv_level_0_and_validity_in_every_format() {
    let (_dir, tetra) = file("tetra.obj", TETRA_ONE_VT);
    let table = ok(&[
        "table", "--mesh", &tetra, "--scheme", "loop", "--levels", "0..2",
    ]);
    let uv_column: Vec<&str> = table
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().last().unwrap())
        .collect();
    assert_eq!(uv_column[..2], ["1", "10"], "{table}");
    let formula = |mesh: &str, scheme: &str, format: &str| {
        ok(&[
            "formula", "--mesh", mesh, "--scheme", scheme, "--format", format,
        ])
    };
    let text = formula(&tetra, "loop", "text");
    assert!(
        text.contains("\nUV(s) = 2*4^s + 2 for s >= 1; UV(0) = 1\n"),
        "{text}"
    );
    assert!(
        text.contains(
            "\nUV(s) = UV0 + (2^s - 1) * UE0 + (4^s - 3*2^s + 2)/2 * F0 for s >= 1; UV(0) = 1\n"
        ),
        "{text}"
    );
    let latex = formula(&tetra, "loop", "latex");
    assert!(
        latex.contains(" \\quad (s \\ge 1), \\quad UV(0) = 1"),
        "{latex}"
    );
    let rust = formula(&tetra, "loop", "rust");
    assert!(
        rust.contains("pub fn loop_uv_values(x0: [i128; 4], used_vt: i128, s: u64) -> Option<i128> {\n    if s < 1 {\n        return Some(used_vt);\n    }\n    loop_uv_counts(x0, s).map(|x| x[0])\n}"),
        "{rust}"
    );
    let json: serde_json::Value = serde_json::from_str(&formula(&tetra, "loop", "json")).unwrap();
    let uv = json.as_array().and_then(|a| a.last()).expect("a list");
    assert_eq!(uv["component"], "UV", "{json}");
    assert_eq!(uv["valid_from"], 1, "{json}");
    assert_eq!(
        uv["early_levels"],
        serde_json::json!([{ "level": 0, "value": "1" }]),
        "{json}"
    );

    let one_vt_cube = format!(
        "{CUBE_V}vt 0 0\nf 1/1 4/1 3/1 2/1\nf 5/1 6/1 7/1 8/1\nf 1/1 2/1 6/1 5/1\nf 2/1 3/1 7/1 6/1\nf 3/1 4/1 8/1 7/1\nf 4/1 1/1 5/1 8/1\n"
    );
    let (_dir2, cube) = file("cube.obj", &one_vt_cube);
    let text = formula(&cube, "catmull-clark", "text");
    let last = text.trim_end().lines().last().unwrap();
    assert!(last.ends_with(" for s >= 1; UV(0) = 1"), "{text}");
    assert!(!text.contains("UV(0) = 8"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&formula(&cube, "catmull-clark", "json")).unwrap();
    let uv = json.as_array().and_then(|a| a.last()).expect("a list");
    assert_eq!(uv["valid_from"], 1, "{json}");
    assert_eq!(
        uv["early_levels"][0],
        serde_json::json!({ "level": 0, "value": "1" }),
        "{json}"
    );
}

/// The cube's faces as triangle pairs, each face its own chart (its four `vt`), without the
/// faces `dropped` (an open cube).
fn triangulated_charts(dropped: &[usize]) -> String {
    let quads = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 4, 8, 7],
        [4, 1, 5, 8],
    ];
    let mut text = CUBE_V.to_string();
    for i in 0..24 {
        text.push_str(&format!("vt {} {}\n", i % 4, i / 4));
    }
    for (f, q) in quads.iter().enumerate() {
        if dropped.contains(&f) {
            continue;
        }
        let c = |k: usize| format!("{}/{}", q[k], 4 * f + k + 1);
        text.push_str(&format!(
            "f {} {} {}\nf {} {} {}\n",
            c(0),
            c(1),
            c(2),
            c(0),
            c(2),
            c(3)
        ));
    }
    text
}

/// √3's UV counts: `sqrt3` one form over `UV0, UBE0, S0, F0`, `sqrt3-boundary` one per phase
/// (steps A and B alternate), with the states they start from; `table` and `at` agree.
#[test]
fn sqrt3_uv_formulas_per_phase() {
    let (_dir, closed) = file("closed.obj", &triangulated_charts(&[]));
    let text = ok(&["formula", "--mesh", &closed, "--scheme", "sqrt3"]);
    assert!(
        text.contains("UV(s) = UV0 + (3^s - 1) * S0 + (3^s - 1)/2 * F0 for s >= 1; UV(0) = 24\n"),
        "{text}"
    );
    assert!(
        text.ends_with("# with UV0 = 24, UBE0 = 24, S0 = 12, F0 = 12; the real count at level 0 is the 24 vt the faces use\nUV(s) = 18*3^s + 6 for s >= 1; UV(0) = 24\n"),
        "{text}"
    );
    // The open cube: 5 charts, 8 seam edges, 4 boundary edges.
    let (_dir, open) = file("open.obj", &triangulated_charts(&[1]));
    let text = ok(&["formula", "--mesh", &open, "--scheme", "sqrt3-boundary"]);
    assert!(
        text.contains("# s = 2t + 1: level s = 1 + 2t; X0 below means the count X at level 1\nUV(t) = UV0 + (3^t - 1)/2 * UBE0 + (9^t - 3^t) * S0 + (9^t - 1)/2 * F0\n"),
        "{text}"
    );
    assert!(
        text.ends_with("# s = 2t: UV0 = 20, UBE0 = 20, S0 = 8, F0 = 10\n# s = 2t + 1: UV0 = 46, UBE0 = 52, S0 = 24, F0 = 30\n"),
        "{text}"
    );
    // UV(3) from the phase s = 2t + 1 at t = 1: 46 + 52 + 8 * 24 ... as the table steps it.
    let csv = ok(&[
        "table",
        "--mesh",
        &open,
        "--scheme",
        "sqrt3-boundary",
        "--levels",
        "0..=5",
        "--format",
        "csv",
    ]);
    let uv: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(uv, ["20", "46", "128", "362", "1076", "3182"], "{csv}");
    let at = ok(&[
        "at",
        "--mesh",
        &open,
        "--scheme",
        "sqrt3-boundary",
        "--level",
        "5",
        "--format",
        "json",
    ]);
    assert!(at.contains("\"UV\": 3182"), "{at}");
    let json = ok(&[
        "formula",
        "--mesh",
        &open,
        "--scheme",
        "sqrt3-boundary",
        "--format",
        "json",
    ]);
    let value: serde_json::Value = serde_json::from_str(&json).expect("json");
    let uv = value
        .as_array()
        .and_then(|a| a.last())
        .map(|c| c["UV"]["phases"].as_array().map(Vec::len));
    assert_eq!(uv, Some(Some(2)), "{json}");
}
