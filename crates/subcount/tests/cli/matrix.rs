//! `table`, `at` and `formula` on a matrix given with `--matrix`.

use crate::util::{fails, ok};

const VEF: &[&str] = &[
    "--matrix",
    "[[1,1,0],[0,2,3],[0,0,4]]",
    "--names",
    "V,E,F",
    "--init",
    "12,30,20",
];

fn with(extra: &[&'static str]) -> Vec<&'static str> {
    let mut v: Vec<&str> = VEF.to_vec();
    v.extend_from_slice(extra);
    v
}

#[test]
fn table_default_is_the_icosahedron() {
    let out = ok(&["table"]);
    let v: Vec<&str> = out
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().nth(1).unwrap())
        .collect();
    assert_eq!(
        v,
        ["12", "42", "162", "642", "2562", "10242", "40962", "163842", "655362"]
    );
    assert!(out.starts_with("level"));
}

#[test]
fn table_json() {
    let mut args = vec!["table"];
    args.extend(with(&["--levels", "0..=2", "--format", "json"]));
    assert_eq!(
        ok(&args),
        "[\n{\"level\": 0, \"V\": 12, \"E\": 30, \"F\": 20},\n{\"level\": 1, \"V\": 42, \"E\": 120, \"F\": 80},\n{\"level\": 2, \"V\": 162, \"E\": 480, \"F\": 320}\n]\n"
    );
}

#[test]
fn table_csv_and_level_forms() {
    let mut args = vec!["table"];
    args.extend(with(&["--levels", "2..4", "--format", "csv"]));
    assert_eq!(ok(&args), "level,V,E,F\n2,162,480,320\n3,642,1920,1280\n");
    let mut args = vec!["table"];
    args.extend(with(&["--levels", "1", "--format", "csv"]));
    assert_eq!(ok(&args), "level,V,E,F\n0,12,30,20\n1,42,120,80\n");
}

#[test]
fn table_without_names_uses_x0_x1() {
    let out = ok(&[
        "table",
        "--matrix",
        "[[1,1],[1,0]]",
        "--init",
        "1,0",
        "--levels",
        "10",
        "--format",
        "csv",
    ]);
    assert!(out.starts_with("level,x0,x1\n"));
    assert!(out.ends_with("10,89,55\n"), "{out}");
}

#[test]
fn json_integers_of_any_size() {
    let out = ok(&["table", "--levels", "200..=200", "--format", "json"]);
    // F = 20 * 4^200: 122 digits, written as a bare JSON integer.
    let f = out
        .split("\"F\": ")
        .nth(1)
        .unwrap()
        .trim_end_matches(|c: char| !c.is_ascii_digit());
    assert_eq!(f.len(), 122);
    assert!(f.chars().all(|c| c.is_ascii_digit()));
}

#[test]
fn at_text_json_summary() {
    let mut args = vec!["at"];
    args.extend(with(&["--level", "3"]));
    assert_eq!(ok(&args), "level 3\nV = 642\nE = 1920\nF = 1280\n");
    let mut args = vec!["at"];
    args.extend(with(&["--level", "3", "--format", "json"]));
    assert_eq!(
        ok(&args),
        "{\"level\": 3, \"V\": 642, \"E\": 1920, \"F\": 1280}\n"
    );
    let mut args = vec!["at"];
    args.extend(with(&[
        "--level",
        "1000000",
        "--summary",
        "--format",
        "json",
    ]));
    let out = ok(&args);
    // F = 20 * 4^1000000 has floor(log10(20) + 10^6 log10(4)) + 1 = 602062 digits.
    assert!(
        out.starts_with("{\"level\": 1000000, \"V\": {\"digits\": 602061, "),
        "{out}"
    );
    assert!(out.contains("\"F\": {\"digits\": 602062, \"leading\": \"19604598754139134831\", \"trailing\": \"31093324874142187520\"}"), "{out}");
}

#[test]
fn usage_errors_exit_2() {
    fails(&["table", "--levels", "5..=2"], 2, "inverted");
    fails(&["table", "--levels", "-3"], 2, "negative");
    fails(
        &["table", "--matrix", "[[1,2],[3]]", "--init", "1,2"],
        2,
        "row 1 of the matrix has 1 entries, expected 2",
    );
    fails(&["table", "--matrix", "[[1,2],[3,4]]"], 2, "--init");
    fails(
        &["table", "--matrix", "[[1,2],[3,4]]", "--init", "1,2,3"],
        2,
        "--init has 3 values but the state has 2 components",
    );
    fails(
        &["table", "--matrix", "[[1,2],[3,4]]", "--init", "1,x"],
        2,
        "`x` is not an integer",
    );
    fails(
        &[
            "table",
            "--matrix",
            "[[1,2],[3,4]]",
            "--names",
            "A,A",
            "--init",
            "1,2",
        ],
        2,
        "used twice",
    );
    fails(&["table", "--no-such-flag"], 2, "--no-such-flag");
    fails(&["at"], 2, "--level");
    fails(&["at", "--level", "ten"], 2, "not a whole number");
    fails(&["frobnicate"], 2, "frobnicate");
}

#[test]
fn guard_refuses_huge_levels_with_exit_4() {
    let err = fails(&["at", "--level", "1000000000000"], 4, "decimal digits");
    assert!(err.contains("--summary"), "{err}");
}

/// The summary of a level far beyond memory comes from the closed form, derived columns
/// (loop's F = 2E/3) included; at a level that can also be materialized, both paths agree.
#[test]
fn summary_without_materializing_agrees_with_the_full_counts() {
    for scheme_args in [
        &["--scheme", "loop", "--counts", "V=12,E=30,F=20"][..],
        &["--scheme", "loop-boundary", "--base", "icosahedron-holes:2"][..],
        &["--scheme", "catmull-clark", "--base", "mixed"][..],
    ] {
        let mut summary = vec!["at", "--level", "3000", "--summary", "--format", "json"];
        summary.extend_from_slice(scheme_args);
        let mut full = vec!["at", "--level", "3000", "--format", "json"];
        full.extend_from_slice(scheme_args);
        let summary: serde_json::Value = serde_json::from_str(&ok(&summary)).unwrap();
        let full = ok(&full);
        // Parse the full counts as strings of digits.
        let body = full.trim().trim_start_matches('{').trim_end_matches('}');
        for pair in body.split(", ").skip(1) {
            let (key, value) = pair.split_once(": ").unwrap();
            let key = key.trim_matches('"');
            let s = &summary[key];
            assert_eq!(
                s["digits"].as_u64().unwrap() as usize,
                value.len(),
                "{scheme_args:?} {key}"
            );
            assert_eq!(s["leading"], value[..20], "{scheme_args:?} {key}");
            assert_eq!(
                s["trailing"],
                value[value.len() - 20..],
                "{scheme_args:?} {key}"
            );
        }
    }
}

#[test]
fn summary_at_a_trillion_levels() {
    let out = ok(&[
        "at",
        "--scheme",
        "loop",
        "--counts",
        "V=12,E=30,F=20",
        "--level",
        "1000000000000",
        "--summary",
    ]);
    // E = 30 * 4^(10^12): floor(log10 30 + 2 10^12 log10 2) + 1 digits; F = 2E/3 = 20 * 4^(10^12).
    assert!(
        out.contains("E: 602059991330 digits: 27511336074359412431..."),
        "{out}"
    );
    assert!(
        out.contains("F: 602059991330 digits: 18340890716239608287..."),
        "{out}"
    );
    // 4^(10^12) mod 10^20 times 20, and V = 12 + 30 (4^s - 1)/3 = 2 + 10 4^s ends in ...62.
    assert!(out.contains("V: 602059991329 digits: "), "{out}");
    let err = crate::util::fails(
        &[
            "at",
            "--scheme",
            "sqrt3-boundary",
            "--base",
            "grid:3x3",
            "--level",
            "1000000000000",
            "--summary",
        ],
        4,
        "exact closed form",
    );
    assert!(err.contains("--allow-large"));
}
