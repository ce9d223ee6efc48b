//! `fit` (vertex, edge, face and memory budgets) and `density` (the paper's eq. (1)).

use crate::util::{data, fails, ok};

const ICO: [&str; 4] = ["--scheme", "loop", "--base", "icosahedron"];

fn with(extra: &[&'static str]) -> Vec<&'static str> {
    let mut v = ICO.to_vec();
    v.extend_from_slice(extra);
    v
}

fn fit(extra: &[&'static str]) -> String {
    let mut args = vec!["fit"];
    args.extend(with(extra));
    ok(&args)
}

#[test]
fn fit_u32_vertex_indices_on_the_icosahedron() {
    // The example: V(14) = 2684354562 <= 2^32 - 1 < V(15) = 10737418242.
    let args = [
        "fit",
        "--scheme",
        "loop",
        "--counts",
        "V=12,E=30,F=20",
        "--max-vertices",
        "4294967295",
    ];
    assert_eq!(
        ok(&args),
        "highest level within the budget: 14\nV = 2684354562\nE = 8053063680\nF = 5368709120\n"
    );
    let mut json = args.to_vec();
    json.extend(["--format", "json"]);
    assert_eq!(
        ok(&json),
        "{\"level\": 14, \"V\": 2684354562, \"E\": 8053063680, \"F\": 5368709120}\n"
    );
    // One below V(14) gives level 13; exactly V(14) still fits.
    assert!(
        fit(&["--max-vertices", "2684354561", "--format", "json"]).starts_with("{\"level\": 13,")
    );
    assert!(
        fit(&["--max-vertices", "2684354562", "--format", "json"]).starts_with("{\"level\": 14,")
    );
}

#[test]
fn fit_edges_faces_and_the_tightest_limit() {
    assert_eq!(
        fit(&[
            "--max-edges",
            "480",
            "--max-faces",
            "1000",
            "--format",
            "json"
        ]),
        "{\"level\": 2, \"V\": 162, \"E\": 480, \"F\": 320}\n"
    );
    assert_eq!(
        fit(&["--max-faces", "1279", "--format", "json"]),
        "{\"level\": 2, \"V\": 162, \"E\": 480, \"F\": 320}\n"
    );
    assert_eq!(
        fit(&["--max-faces", "1280", "--format", "json"]),
        "{\"level\": 3, \"V\": 642, \"E\": 1920, \"F\": 1280}\n"
    );
}

#[test]
fn fit_memory_budget_in_binary_and_decimal_units() {
    // Level 11 needs 12 * 41943042 + 12 * 83886080 = 1509949464 bytes, level 12 far more.
    let level11 = "{\"level\": 11, \"V\": 41943042, \"E\": 125829120, \"F\": 83886080}\n";
    assert_eq!(
        fit(&[
            "--memory",
            "2GiB",
            "--bytes-per-vertex",
            "12",
            "--bytes-per-face",
            "12",
            "--format",
            "json"
        ]),
        level11
    );
    assert_eq!(
        fit(&["--memory", "1509949464", "--format", "json"]),
        level11
    );
    assert!(fit(&["--memory", "1509949463", "--format", "json"]).starts_with("{\"level\": 10,"));
    // GiB = 2^30 and GB = 10^9: 3 bytes per face at level 12 is 1006632960, between the two.
    let level12 = "{\"level\": 12, \"V\": 167772162, \"E\": 503316480, \"F\": 335544320}\n";
    assert_eq!(
        fit(&[
            "--memory",
            "1GiB",
            "--bytes-per-vertex",
            "0",
            "--bytes-per-face",
            "3",
            "--format",
            "json"
        ]),
        level12
    );
    assert_eq!(
        fit(&[
            "--memory",
            "1GB",
            "--bytes-per-vertex",
            "0",
            "--bytes-per-face",
            "3",
            "--format",
            "json"
        ]),
        level11
    );
    // Bytes per edge count too: 8 bytes per edge, E(11) = 125829120 -> 1006632960 bytes.
    assert_eq!(
        fit(&[
            "--memory",
            "1GiB",
            "--bytes-per-vertex",
            "0",
            "--bytes-per-face",
            "0",
            "--bytes-per-edge",
            "8",
            "--format",
            "json"
        ]),
        level11
    );
}

#[test]
fn fit_reports_null_when_every_level_fits() {
    // A custom scheme whose counts never change: no limit is ever reached.
    let constant = data("constant.toml");
    let args = [
        "fit",
        "--scheme-file",
        &constant,
        "--counts",
        "V=12,E=30,F=20",
        "--max-vertices",
        "100",
        "--format",
        "json",
    ];
    let out = ok(&args);
    assert!(
        out.starts_with("{\"level\": null, \"note\": \"every level fits"),
        "{out}"
    );
    assert!(
        out.ends_with(", \"V\": 12, \"E\": 30, \"F\": 20}\n"),
        "{out}"
    );
    let v: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    assert!(v["level"].is_null());
    let text = ok(&args[..args.len() - 2]);
    assert!(text.starts_with("every level fits"), "{text}");
    assert!(text.ends_with("V = 12\nE = 30\nF = 20\n"), "{text}");
}

#[test]
fn fit_errors() {
    // Level 0 already over the budget: exit 3.
    fails(
        &[
            "fit",
            "--scheme",
            "loop",
            "--base",
            "icosahedron",
            "--max-vertices",
            "11",
        ],
        3,
        "level 0 does not fit: V = 12 > 11",
    );
    fails(
        &[
            "fit",
            "--scheme",
            "loop",
            "--base",
            "icosahedron",
            "--memory",
            "100",
        ],
        3,
        "level 0 does not fit: bytes = 384 > 100",
    );
    let constant = data("constant.toml");
    fails(
        &[
            "fit",
            "--scheme-file",
            &constant,
            "--counts",
            "V=12,E=30,F=20",
            "--max-faces",
            "19",
        ],
        3,
        "level 0 does not fit",
    );
    // Usage errors: exit 2.
    fails(
        &["fit", "--scheme", "loop", "--base", "icosahedron"],
        2,
        "fit needs a limit",
    );
    fails(
        &[
            "fit",
            "--scheme",
            "loop",
            "--base",
            "icosahedron",
            "--memory",
            "2XB",
        ],
        2,
        "invalid --memory: byte size `2XB`: unknown unit",
    );
    fails(
        &[
            "fit",
            "--scheme",
            "loop",
            "--base",
            "icosahedron",
            "--max-faces",
            "-5",
        ],
        2,
        "invalid --max-faces: `-5` is negative",
    );
    fails(
        &[
            "fit",
            "--scheme",
            "loop",
            "--base",
            "icosahedron",
            "--max-edges",
            "many",
        ],
        2,
        "invalid --max-edges: `many` is not a whole number",
    );
    fails(
        &[
            "fit",
            "--matrix",
            "[[2]]",
            "--init",
            "1",
            "--max-vertices",
            "5",
        ],
        2,
        "fit needs a scheme",
    );
}

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&ok(args)).expect("valid JSON")
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn density_at_a_level() {
    let mut args = vec!["density"];
    args.extend(with(&[
        "--level", "3", "--radius", "2", "--tau", "0.001", "--format", "json",
    ]));
    let v = json(&args);
    assert_eq!(v["level"], 3);
    assert_eq!(v["V"], 642);
    assert_eq!(v["radius"], 2.0);
    let area = 4.0 * std::f64::consts::PI * 4.0 / 642.0;
    assert!(close(v["mean_area"].as_f64().unwrap(), area), "{v}");
    assert_eq!(v["tau"], 0.001);
    assert!(
        close(v["phi"].as_f64().unwrap(), (0.001 / area).sqrt()),
        "{v}"
    );
    let keys: Vec<&String> = v.as_object().unwrap().keys().collect();
    assert_eq!(keys, ["level", "V", "radius", "mean_area", "tau", "phi"]);

    let mut args = vec!["density"];
    args.extend(with(&["--level", "3", "--radius", "2", "--tau", "0.001"]));
    assert_eq!(
        ok(&args),
        "level 3\nV = 642\nmean co-volume area 4 pi r^2 / V = 7.829514401469889e-2\nscale factor phi = sqrt(tau / area) = 1.1301408842761419e-1\n"
    );
    // Without --tau there is no phi.
    let mut args = vec!["density"];
    args.extend(with(&["--level", "0", "--format", "json"]));
    let v = json(&args);
    assert!(v.get("phi").is_none(), "{v}");
    assert!(close(
        v["mean_area"].as_f64().unwrap(),
        4.0 * std::f64::consts::PI / 12.0
    ));
}

#[test]
fn density_for_a_target_area() {
    // 4 pi / 642 = 0.0196 > 0.01 >= 4 pi / 2562 = 0.0049: level 4.
    let mut args = vec!["density"];
    args.extend(with(&["--target-area", "0.01", "--format", "json"]));
    let v = json(&args);
    assert_eq!(v["level"], 4);
    assert_eq!(v["V"], 2562);
    assert_eq!(v["target_area"], 0.01);
    assert!(close(
        v["mean_area"].as_f64().unwrap(),
        4.0 * std::f64::consts::PI / 2562.0
    ));
    // Exactly the area of level 2 is reached at level 2.
    let area2 = format!("{:e}", 4.0 * std::f64::consts::PI / 162.0 * 1.000_000_001);
    let mut args: Vec<&str> = vec!["density"];
    args.extend(ICO);
    args.extend(["--target-area", &area2, "--format", "json"]);
    assert_eq!(json(&args)["level"], 2);
}

#[test]
fn density_errors() {
    let mut args = vec!["density"];
    args.extend(with(&["--level", "3", "--target-area", "0.1"]));
    fails(&args, 2, "cannot be used with");
    let mut args = vec!["density"];
    args.extend(ICO);
    fails(&args, 2, "--level");
    let mut args = vec!["density"];
    args.extend(with(&["--level", "2", "--radius", "-1"]));
    fails(&args, 2, "the radius must be positive, got -1");
    let mut args = vec!["density"];
    args.extend(with(&["--target-area", "0"]));
    fails(&args, 2, "the target area must be positive, got 0");
    let mut args = vec!["density"];
    args.extend(with(&["--level", "-2"]));
    fails(&args, 2, "negative");
}
