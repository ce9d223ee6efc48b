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
