//! Hostile input end to end (SPEC section 9): every bad file or argument gets the exit code
//! of the CLI contract and a one-line `error: ...` that names what is wrong and where.
//!
//! Exit codes: 2 usage, 3 bad input or a scheme that does not apply, 4 resource guard.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::util::{fails, ok, subcount};

/// A temporary folder holding the files of one test.
pub(crate) struct Files {
    dir: tempfile::TempDir,
}

impl Files {
    pub(crate) fn new() -> Files {
        Files {
            dir: tempfile::tempdir().expect("a temporary folder"),
        }
    }

    /// Writes `bytes` to `name` in the folder and returns its path as text.
    pub(crate) fn write(&self, name: &str, bytes: &[u8]) -> String {
        let path = self.dir.path().join(name);
        std::fs::write(&path, bytes).expect("the test file is written");
        path.display().to_string()
    }

    pub(crate) fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    pub(crate) fn dir(&self) -> &Path {
        self.dir.path()
    }
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

/// `stats --mesh FILE` on a malformed OBJ: exit 3, the file, the line and the problem.
#[test]
fn malformed_obj_files_name_file_line_and_problem() {
    let files = Files::new();
    let cases: &[(&str, String, &str)] = &[
        (
            "truncated.obj",
            format!("{TRIANGLE}f 1 2"),
            "truncated.obj: line 4: face has 2 vertices, at least 3 are needed",
        ),
        (
            "out-of-range.obj",
            format!("{TRIANGLE}f 1 2 4\n"),
            "out-of-range.obj: line 4: face index 4 is out of range (the file has 3 vertices)",
        ),
        (
            "negative-out-of-range.obj",
            format!("{TRIANGLE}f 1 2 -4\n"),
            "negative-out-of-range.obj: line 4: face index -4 is out of range (the file has 3 vertices)",
        ),
        (
            "zero.obj",
            format!("{TRIANGLE}f 0 1 2\n"),
            "zero.obj: line 4: face index 0 is not valid (OBJ indices start at 1)",
        ),
        (
            "beyond-u64.obj",
            format!("{TRIANGLE}f 1 2 18446744073709551616\n"),
            "beyond-u64.obj: line 4: face index `18446744073709551616` is too large",
        ),
        (
            "beyond-u64-corner.obj",
            format!("{TRIANGLE}f 1/1 2/1 99999999999999999999999999/1\n"),
            "beyond-u64-corner.obj: line 4: face index `99999999999999999999999999` is too large",
        ),
        (
            "one-vertex.obj",
            format!("{TRIANGLE}f 1\n"),
            "one-vertex.obj: line 4: face has 1 vertices, at least 3 are needed",
        ),
        (
            "two-vertices.obj",
            format!("{TRIANGLE}f 1 2\n"),
            "two-vertices.obj: line 4: face has 2 vertices, at least 3 are needed",
        ),
        (
            "nan.obj",
            "v 0 0 0\nv NaN 0 0\nv 0 1 0\nf 1 2 3\n".to_string(),
            "nan.obj: line 2: coordinate `NaN` is not finite",
        ),
        (
            "inf.obj",
            "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n".to_string(),
            "inf.obj: line 3: coordinate `-inf` is not finite",
        ),
        (
            "overflow.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n".to_string(),
            "overflow.obj: line 3: coordinate `1e999` is not finite",
        ),
        (
            "short-vertex.obj",
            "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_string(),
            "short-vertex.obj: line 1: vertex has 2 coordinates, expected 3",
        ),
        ("empty.obj", String::new(), "empty.obj: the file has no faces"),
        (
            "comments-only.obj",
            "# nothing\n\n".to_string(),
            "comments-only.obj: the file has no faces",
        ),
    ];
    for (name, text, message) in cases {
        let path = files.write(name, text.as_bytes());
        let stderr = fails(&["stats", "--mesh", &path], 3, message);
        assert!(stderr.contains(&path), "{stderr:?} names the file");
    }
}

/// Binary garbage (deterministic bytes, no newline before the first invalid UTF-8).
#[test]
fn binary_garbage_is_not_a_mesh() {
    let files = Files::new();
    let mut state: u32 = 0x2545_f491;
    let mut bytes = vec![0xff_u8];
    bytes.extend((0..4096).map(|_| {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        (state >> 24) as u8
    }));
    let obj = files.write("garbage.obj", &bytes);
    fails(
        &["stats", "--mesh", &obj],
        3,
        "garbage.obj: line 1: not a text line (binary data?)",
    );
    let off = files.write("garbage.off", &bytes);
    fails(
        &["stats", "--mesh", &off],
        3,
        "garbage.off: line 1: not a text line (binary data?)",
    );
    let unknown = files.write("garbage.ply", &bytes);
    fails(&["stats", "--mesh", &unknown], 3, "garbage.ply");
}

#[test]
fn malformed_off_files_name_file_line_and_problem() {
    let files = Files::new();
    let cases: &[(&str, &str, &str)] = &[
        ("empty.off", "", "empty.off: the file has no faces"),
        (
            "truncated.off",
            "OFF\n3 1 0\n0 0 0\n1 0 0\n",
            "truncated.off: line 4: the file ends early: 2 of 3 vertices read",
        ),
        (
            "out-of-range.off",
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
            "out-of-range.off: line 6: face index 3 is out of range (the file has 3 vertices)",
        ),
        (
            "beyond-u64.off",
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 18446744073709551616\n",
            "beyond-u64.off: line 6: face index `18446744073709551616` is too large",
        ),
        (
            "two-vertices.off",
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
            "two-vertices.off: line 6: face has 2 vertices, at least 3 are needed",
        ),
        (
            "nan.off",
            "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n",
            "nan.off: line 4: coordinate `nan` is not finite",
        ),
        (
            "huge-counts.off",
            "OFF\n4294967295 4294967295 0\n",
            "huge-counts.off: line 2: the file ends early: 0 of 4294967295 vertices read",
        ),
    ];
    for (name, text, message) in cases {
        let path = files.write(name, text.as_bytes());
        fails(&["stats", "--mesh", &path], 3, message);
    }
}

/// A 200 MB file on one line: the reader stops at its line limit (16 MiB) instead of
/// buffering the whole line, and refuses the file with the line number.
#[test]
fn a_200_mb_single_line_is_refused_after_a_bounded_read() {
    let files = Files::new();
    let path = files.path("huge-line.obj");
    {
        let mut out = std::io::BufWriter::new(std::fs::File::create(&path).expect("created"));
        out.write_all(TRIANGLE.as_bytes()).expect("written");
        out.write_all(b"f").expect("written");
        let chunk = " 1 2 3".repeat(1 << 14);
        let mut written = 0usize;
        while written < 200 << 20 {
            out.write_all(chunk.as_bytes()).expect("written");
            written += chunk.len();
        }
        out.write_all(b"\n").expect("written");
        out.flush().expect("flushed");
    }
    assert!(std::fs::metadata(&path).expect("exists").len() > 200 << 20);
    let path = path.display().to_string();
    fails(
        &["stats", "--mesh", &path],
        3,
        "huge-line.obj: line 4: line is longer than 16777216 bytes",
    );
    fails(
        &["verify", "--mesh", &path, "--scheme", "loop"],
        3,
        "line 4: line is longer than 16777216 bytes",
    );
}

/// Topology the half-edge structure refuses: each error names the element and the file line.
#[test]
fn invalid_topology_names_the_element() {
    let files = Files::new();
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "non-manifold-edge.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
            "loop-boundary",
            "loop-boundary needs every edge to have one or two faces, but this mesh has 1 non-manifold edge",
        ),
        (
            "non-manifold-vertex.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n",
            "loop-boundary",
            "non-manifold-vertex.obj: vertex 0 is non-manifold: its faces form 2 separate fans",
        ),
        (
            "duplicate-face.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 2 3 1\n",
            "loop",
            "duplicate-face.obj: line 5: faces 0 and 1 have the same vertices (0, 1, 2)",
        ),
        (
            "inconsistent.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n",
            "loop-boundary",
            "inconsistent.obj: line 6: faces 0 and 1 both use edge 1 -> 2 in the same direction: inconsistent orientation",
        ),
    ];
    for (name, text, scheme, message) in cases {
        let path = files.write(name, text.as_bytes());
        fails(&["verify", "--mesh", &path, "--scheme", scheme], 3, message);
        fails(
            &[
                "subdivide",
                "--mesh",
                &path,
                "--scheme",
                scheme,
                "--levels",
                "1",
            ],
            3,
            message,
        );
    }
    // The face-list statistics still work on the non-manifold meshes and say why the
    // half-edge structure refuses them.
    let path = files.path("non-manifold-edge.obj").display().to_string();
    let out = ok(&["stats", "--mesh", &path]);
    assert!(
        out.contains("edge (0, 1) is shared by 3 faces (0, 1, 2): non-manifold edge"),
        "{out}"
    );
}

/// A Möbius strip of six quads: the half-edge build finds the orientation-reversing loop.
#[test]
fn a_moebius_strip_is_not_orientable() {
    let files = Files::new();
    let mut text = String::new();
    let n = 6;
    for i in 0..n {
        let t = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        for w in [-0.3, 0.3] {
            let r = 1.0 + w * (t / 2.0).cos();
            text += &format!(
                "v {} {} {}\n",
                r * t.cos(),
                r * t.sin(),
                w * (t / 2.0).sin()
            );
        }
    }
    for i in 0..n {
        let (a, b) = (2 * i + 1, 2 * i + 2);
        // The last quad joins the strip with a half twist.
        let (c, d) = if i + 1 < n {
            (2 * i + 3, 2 * i + 4)
        } else {
            (2, 1)
        };
        text += &format!("f {a} {b} {d} {c}\n");
    }
    let path = files.write("moebius.obj", text.as_bytes());
    let message = "moebius.obj: line 13: the surface is not orientable: flipping faces cannot make the orientation consistent";
    fails(
        &["verify", "--mesh", &path, "--scheme", "catmull-clark"],
        3,
        message,
    );
    fails(
        &[
            "subdivide",
            "--mesh",
            &path,
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
        ],
        3,
        message,
    );
}

/// A scheme file with each kind of mistake: exit 3, the file, line and column.
#[test]
fn scheme_file_mistakes_name_line_and_column() {
    let files = Files::new();
    let cases: &[(&str, &str)] = &[
        (
            "name = \"x\"\nstate = [\"V\"\nmatrix = [[1]]\n",
            "line 3, column 1: invalid array; expected `]`",
        ),
        (
            "name = \"x\"\nstate = [\"V\"]\nmatrix = [[1]]\ncolour = \"red\"\n",
            "line 4, column 1: unknown field `colour`",
        ),
        ("name = \"x\"\nstate = [\"V\"]\n", "line 3, column 1: missing `matrix` (or `cycle` for a periodic scheme)"),
        ("name = \"x y\"\nstate = [\"V\"]\nmatrix = [[1]]\n", "line 1, column 8: scheme name `x y` may only use letters, digits, `-` and `_`"),
        ("name = \"x\"\nstate = []\nmatrix = []\n", "line 2, column 9: the state is empty"),
        ("name = \"x\"\nstate = [\"1V\"]\nmatrix = [[1]]\n", "line 2, column 10: state name `1V` is not valid"),
        ("name = \"x\"\nstate = [\"V\", \"V\"]\nmatrix = [[1, 0], [0, 1]]\n", "line 2, column 15: state name `V` is used twice"),
        ("name = \"x\"\nstate = [\"V\", \"E\"]\nmatrix = [[1, 0], [0]]\n", "line 3, column 19: row 2 has 1 entry, but the matrix has 2 rows (it must be square)"),
        ("name = \"x\"\nstate = [\"V\", \"E\"]\nmatrix = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n", "line 3, column 10: the matrix is 3x3, but the state has 2 components"),
        ("name = \"x\"\nstate = [\"V\"]\nmatrix = [[99999999999999999999]]\n", "line 3, column 12: number too large to fit in target type"),
        ("name = \"x\"\nstate = [\"V\"]\nmatrix = [[1]]\ncycle = [[[1]]]\n", "line 4, column 9: give either `matrix` or `cycle`, not both"),
        ("name = \"x\"\nstate = [\"V\"]\ncycle = []\n", "line 3, column 9: the cycle is empty"),
        ("name = \"x\"\nstate = [\"V\"]\nmatrix = [[1]]\n[derive]\nF = { Q = 1 }\n", "line 5, column 7: `derive.F` names `Q`, which is not a state component (V)"),
        ("name = \"x\"\nstate = [\"V\"]\nmatrix = [[1]]\n[derive]\nF = { V = 1, divide_by = 0 }\n", "line 5, column 26: `divide_by` must be positive"),
        ("name = \"x\"\nstate = [\"V\"]\nmatrix = [[1]]\nrequires = [\"wings\"]\n", "line 4, column 13: unknown requirement `wings`; use triangles, quads, closed, manifold"),
    ];
    for (i, (text, message)) in cases.iter().enumerate() {
        let name = format!("mistake-{i}.toml");
        let path = files.write(&name, text.as_bytes());
        let stderr = fails(&["formula", "--scheme-file", &path], 3, message);
        assert!(stderr.contains(&name), "{stderr:?} names the file");
    }
    let path = files.write("binary.toml", &[0xff, 0xfe, 0x00, b'\n']);
    fails(&["formula", "--scheme-file", &path], 3, "binary.toml");
    let missing = files.path("missing.toml").display().to_string();
    fails(&["formula", "--scheme-file", &missing], 3, "missing.toml");
}

/// A 300 KB matrix (250 state components) is refused at once, not solved for hours.
#[test]
fn a_300_kb_scheme_matrix_is_refused_quickly() {
    let files = Files::new();
    let n = 250;
    let names: Vec<String> = (0..n).map(|i| format!("\"S{i}\"")).collect();
    let rows: Vec<String> = (0..n)
        .map(|i| {
            let row: Vec<String> = (0..n).map(|j| (1000 + i * j).to_string()).collect();
            format!("[{}]", row.join(","))
        })
        .collect();
    let text = format!(
        "name = \"big\"\nstate = [{}]\nmatrix = [\n{}\n]\n",
        names.join(", "),
        rows.join(",\n")
    );
    assert!(text.len() > 300_000, "{} bytes", text.len());
    let path = files.write("big.toml", text.as_bytes());
    let message = "big.toml: line 2, column 9: the state has 250 components; a scheme file may have at most 32";
    for command in ["formula", "table", "at"] {
        let mut args = vec![command, "--scheme-file", path.as_str()];
        if command == "at" {
            args.extend(["--level", "3"]);
        }
        fails(&args, 3, message);
    }
}

#[test]
fn schemes_and_counts_beyond_the_integer_types() {
    fails(
        &[
            "at",
            "--scheme",
            "tri-split-10000000000",
            "--counts",
            "V=12,E=30,F=20",
            "--level",
            "1",
        ],
        2,
        "`tri-split-10000000000`: the split factor is too large (matrix entries beyond i64)",
    );
    fails(
        &[
            "table",
            "--scheme",
            "tri-split-18446744073709551616",
            "--base",
            "icosahedron",
        ],
        2,
        "tri-split-18446744073709551616",
    );
    fails(
        &["at", "--counts", "V=-1", "--level", "2"],
        2,
        "count V=-1 is negative; counts are non-negative integers",
    );
    fails(
        &["table", "--counts", "V=12,E=-30,F=20"],
        2,
        "count E=-30 is negative",
    );
    fails(
        &["fit", "--max-vertices", "-5"],
        2,
        "invalid --max-vertices: `-5` is negative",
    );
    fails(
        &["fit", "--max-faces", "-1"],
        2,
        "invalid --max-faces: `-1` is negative",
    );
}

/// Budgets of zero are valid input that nothing fits: exit 3, naming the count that overflows.
#[test]
fn budgets_of_zero() {
    fails(
        &["fit", "--max-vertices", "0"],
        3,
        "level 0 does not fit: V = 12 > 0",
    );
    fails(
        &["fit", "--max-faces", "0"],
        3,
        "level 0 does not fit: F = 20 > 0",
    );
    fails(
        &["fit", "--memory", "0"],
        3,
        "level 0 does not fit: bytes = 384 > 0",
    );
    fails(
        &["table", "--levels", "0..0"],
        2,
        "invalid --levels: the level range `0..0` is empty",
    );
}

#[test]
fn inverted_and_negative_level_ranges() {
    fails(
        &["table", "--levels", "5..2"],
        2,
        "invalid --levels: the level range `5..2` is empty",
    );
    fails(
        &["table", "--levels", "5..=4"],
        2,
        "invalid --levels: the level range `5..=4` is inverted",
    );
    fails(
        &["plot", "--levels", "9..3", "-o", "never.svg"],
        2,
        "invalid --levels: the level range `9..3`",
    );
    fails(
        &[
            "verify",
            "--base",
            "icosahedron",
            "--scheme",
            "loop",
            "--levels",
            "-1",
        ],
        2,
        "invalid --levels: `-1` is negative",
    );
    fails(
        &[
            "subdivide",
            "--base",
            "icosahedron",
            "--scheme",
            "loop",
            "--levels",
            "-1",
        ],
        2,
        "invalid --levels: `-1` is negative",
    );
    assert!(!Path::new("never.svg").exists());
}

/// Every command that allocates in proportion to a count checks the guard first (exit 4).
#[test]
fn the_resource_guard_holds_for_every_command() {
    let digits = "would have about 6.021e11 decimal digits";
    fails(&["at", "--level", "1000000000000"], 4, digits);
    fails(&["table", "--levels", "1000000000000"], 4, digits);
    fails(
        &["table", "--levels", "999999999999..=1000000000000"],
        4,
        "decimal digits",
    );
    fails(&["density", "--level", "1000000000000"], 4, digits);
    // Level 40 passes the level cap; the memory guard refuses it.
    fails(
        &[
            "subdivide",
            "--base",
            "icosahedron",
            "--scheme",
            "loop",
            "--levels",
            "40",
        ],
        4,
        "loop to level 40 needs about",
    );
    fails(
        &[
            "verify",
            "--base",
            "icosahedron",
            "--scheme",
            "loop",
            "--levels",
            "1000",
        ],
        4,
        "--levels 1000: real subdivision stops at level 64",
    );
    fails(
        &[
            "subdivide",
            "--base",
            "icosahedron",
            "--scheme",
            "loop",
            "--levels",
            "1000",
        ],
        4,
        "--levels 1000: real subdivision stops at level 64",
    );
    fails(
        &[
            "verify",
            "--base",
            "icosahedron",
            "--scheme",
            "tri-split-1000000000",
            "--levels",
            "1",
        ],
        4,
        "tri-split-1000000000 to level 1 needs about",
    );
    fails(
        &[
            "subdivide",
            "--base",
            "icosahedron",
            "--scheme",
            "tri-split-1000000000",
            "--levels",
            "1",
        ],
        4,
        "tri-split-1000000000 to level 1 needs about",
    );
    fails(
        &[
            "at",
            "--base",
            "icosahedron",
            "--scheme",
            "tri-split-1000000000",
            "--level",
            "1000000",
        ],
        4,
        "the counts at level 1000000 would have about 1.800e7 decimal digits",
    );
    fails(
        &[
            "plot",
            "--base",
            "icosahedron",
            "--scheme",
            "tri-split-1000000000",
            "--levels",
            "999000..=999999",
            "-o",
            "never.svg",
        ],
        4,
        "the counts at level 999999 would have about 1.800e7 decimal digits",
    );
    assert!(!Path::new("never.svg").exists());
    // `fit` searches levels: V doubles while the limited E grows linearly, so the search
    // stops at its state-size limit instead of computing ever larger states.
    let files = Files::new();
    let lopsided = files.write(
        "lopsided.toml",
        b"name = \"lopsided\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[2, 0, 0], [0, 1, 1], [0, 0, 1]]\n",
    );
    let budget = format!("1{}", "0".repeat(30));
    fails(
        &["fit", "--scheme-file", &lopsided, "--counts", "V=1,E=1,F=1", "--max-edges", &budget],
        4,
        "the search reached level 83886080, where the state has 83886109 bits, without crossing the limit",
    );
    // `--summary` is exempt: digit counts and leading/trailing digits only.
    let out = ok(&["at", "--level", "1000000000000", "--summary"]);
    assert!(out.contains("602059991329 digits"), "{out}");
}

/// The refusal of `subdivide` leaves no output file behind.
#[test]
fn a_refused_subdivision_writes_nothing() {
    let files = Files::new();
    let out = files.path("out.obj").display().to_string();
    let run = subcount(&[
        "subdivide",
        "--base",
        "icosahedron",
        "--scheme",
        "loop",
        "--levels",
        "1000",
        "-o",
        &out,
    ]);
    assert_eq!(run.code, 4, "{}", run.stderr);
    assert!(!files.path("out.obj").exists());
    assert_eq!(
        std::fs::read_dir(files.dir.path()).expect("listed").count(),
        0
    );
}

/// Counts that grow like s^2 never reach a budget of 10^39 at a level a `u64` can name: the
/// search refuses (exit 4) instead of overflowing (it used to panic) or claiming every level
/// fits.
#[test]
fn fit_with_polynomial_growth_and_a_huge_budget() {
    let files = Files::new();
    let path = files.write(
        "slow.toml",
        b"name = \"slow\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 1, 0], [0, 1, 1], [0, 0, 1]]\n",
    );
    let budget = format!("1{}", "0".repeat(39));
    fails(
        &[
            "fit",
            "--scheme-file",
            &path,
            "--counts",
            "V=2,E=3,F=4",
            "--max-vertices",
            &budget,
        ],
        4,
        "the search reached level 18446744073709551615",
    );
    let out = ok(&[
        "fit",
        "--scheme-file",
        &path,
        "--counts",
        "V=2,E=3,F=4",
        "--max-vertices",
        "1000000000000",
    ]);
    assert!(
        out.contains("highest level within the budget: 707106"),
        "{out}"
    );
}

/// A table or plot of very many levels is refused before any row is computed: the guard
/// counts rows times columns times digits, not only the largest count.
#[test]
fn whole_tables_are_guarded() {
    crate::util::fails(
        &[
            "table",
            "--matrix",
            "[[1]]",
            "--init",
            "1",
            "--levels",
            "0..=100000000000",
        ],
        4,
        "would make a table of 100000000001 rows",
    );
    crate::util::fails(
        &[
            "table",
            "--scheme",
            "tri-split-1000000000",
            "--base",
            "icosahedron",
            "--levels",
            "0..=500000",
        ],
        4,
        "the limits are 10^7 cells and 10^8 digits",
    );
}

/// A face-list subdivider's refusal names the file and the line of the face.
#[test]
fn face_list_refusals_name_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dup.obj");
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\n").unwrap();
    let path = path.to_str().unwrap();
    let err = crate::util::fails(
        &["verify", "--mesh", path, "--scheme", "loop-general"],
        3,
        "dup.obj: line 5: ",
    );
    assert!(err.contains("have the same vertices"), "{err}");
}

/// A dense 32x32 matrix with entries up to 1000, as `[[...], ...]` rows.
fn dense_32() -> Vec<Vec<i64>> {
    (0..32i64)
        .map(|i| {
            (0..32i64)
                .map(|j| (i * 37 + j * 101 + i * j * 7) % 1001)
                .collect()
        })
        .collect()
}

fn bracketed(rows: &[Vec<i64>]) -> String {
    let rows: Vec<String> = rows
        .iter()
        .map(|r| {
            let r: Vec<String> = r.iter().map(i64::to_string).collect();
            format!("[{}]", r.join(","))
        })
        .collect();
    format!("[{}]", rows.join(","))
}

/// `M^level x0` in `i128` (small levels only).
fn power_apply(rows: &[Vec<i64>], x0: &[i128], level: u32) -> Vec<i128> {
    let mut x = x0.to_vec();
    for _ in 0..level {
        x = rows
            .iter()
            .map(|r| r.iter().zip(&x).map(|(a, b)| i128::from(*a) * b).sum())
            .collect();
    }
    x
}

/// Issue 6: a dense 32x32 matrix (from `--matrix` or a 32-component scheme file, the most
/// a scheme file may have) never starts an expensive closed form. `formula` refuses with
/// exit 4 at once (the cost estimate is `n^5 + n^3 w^2`), naming the matrix size and what to
/// do; `at` and `table` power the matrix instead and answer exactly, in well under a second.
#[test]
fn a_dense_32x32_matrix_is_refused_by_formula_and_powered_by_at_and_table() {
    let rows = dense_32();
    let matrix = bracketed(&rows);
    let ones = vec!["1"; 32].join(",");
    let x0 = vec![1i128; 32];
    let names: Vec<String> = (0..32).map(|i| format!("\"S{i}\"")).collect();
    let files = Files::new();
    let scheme = files.write(
        "dense32.toml",
        format!(
            "name = \"dense32\"\nstate = [{}]\nmatrix = {matrix}\n",
            names.join(", ")
        )
        .as_bytes(),
    );
    let cost = "the closed form of a 32x32 matrix would cost about 3.57e7 work units (estimated from its size and entries), more than the limit of 4194304 (about 20 components): use `at` or `table` for exact counts (they power the matrix), or --allow-large to compute it anyway";
    let sources: [(&[&str], String, String); 2] = [
        (
            &["--matrix", &matrix, "--init", &ones],
            format!("error: --matrix: {cost}"),
            "x".to_string(),
        ),
        (
            &["--scheme-file", &scheme, "--init", &ones],
            format!("error: scheme `dense32`: {cost}"),
            "S".to_string(),
        ),
    ];
    for (source, refusal, prefix) in &sources {
        for format in ["text", "latex", "rust", "json"] {
            let mut args = vec!["formula", "--format", format];
            args.extend_from_slice(source);
            let err = fails(&args, 4, refusal);
            assert_eq!(err.trim_end(), refusal.as_str());
        }
        // `at` below and above level 64 (above it, `at` would use the closed form if it
        // were cheap): exact, by powering.
        for level in [3u32, 100] {
            let mut args = vec!["at", "--level"];
            let text = level.to_string();
            args.push(&text);
            args.extend_from_slice(source);
            let out = ok(&args);
            let lines: Vec<&str> = out.lines().collect();
            assert_eq!(lines.len(), 33, "{out}");
            if level == 3 {
                let expected = power_apply(&rows, &x0, 3);
                for (i, v) in expected.iter().enumerate() {
                    assert_eq!(lines[i + 1], format!("{prefix}{i} = {v}"));
                }
            }
        }
        // At a level far beyond memory, `--summary` needs the closed form: the digit guard
        // refuses instead of computing it.
        let mut args = vec!["at", "--level", "1000000000000", "--summary"];
        args.extend_from_slice(source);
        fails(&args, 4, "decimal digits");
        let mut args = vec!["table", "--levels", "0..=3", "--format", "csv"];
        args.extend_from_slice(source);
        let out = ok(&args);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines.len(), 5, "{out}");
        let expected = power_apply(&rows, &x0, 3);
        let cells: Vec<&str> = lines[4].split(',').collect();
        assert_eq!(cells[0], "3");
        for (i, v) in expected.iter().enumerate() {
            assert_eq!(cells[i + 1], v.to_string(), "component {i}");
        }
    }
}

/// `--allow-large` lifts the closed-form guard: a 24x24 triangular matrix (cost estimate
/// 8.1e6, above the limit; eigenvalues 1, 2 and 4, each eight times, with Jordan blocks)
/// gets its exact closed form, one line per component.
#[test]
fn allow_large_computes_a_closed_form_above_the_limit() {
    let n = 24usize;
    let rows: Vec<Vec<i64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| match j.cmp(&i) {
                    std::cmp::Ordering::Equal => [1, 2, 4][i % 3],
                    std::cmp::Ordering::Greater => ((i * 7 + j * 3) % 5) as i64,
                    std::cmp::Ordering::Less => 0,
                })
                .collect()
        })
        .collect();
    let matrix = bracketed(&rows);
    fails(
        &["formula", "--matrix", &matrix],
        4,
        "24x24 matrix would cost about 8.09e6 work units",
    );
    let out = ok(&["formula", "--matrix", &matrix, "--allow-large"]);
    assert_eq!(out.lines().count(), n, "{out}");
    assert!(
        out.starts_with("x0(s) = x0_0 + "),
        "{}",
        &out[..200.min(out.len())]
    );
}

/// The names in a folder, sorted.
fn folder_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("listed")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

const SUBDIVIDE_TETRAHEDRON: [&str; 7] = [
    "subdivide",
    "--base",
    "tetrahedron",
    "--scheme",
    "loop",
    "--levels",
    "1",
];

/// Issue 11: `-o` on a read-only file (mode 444) used to replace it silently (renaming over a
/// file needs only the folder's permission). It is refused, exit 3, and left intact, as root
/// too.
#[test]
fn output_over_a_read_only_file_is_refused_and_left_intact() {
    use std::os::unix::fs::PermissionsExt;
    let files = Files::new();
    let target = files.write("ro.obj", b"keep\n");
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o444)).expect("chmod");
    let mut args = SUBDIVIDE_TETRAHEDRON.to_vec();
    args.extend(["-o", target.as_str()]);
    let stderr = fails(&args, 3, "ro.obj: refusing to write over it");
    assert_eq!(
        stderr,
        format!("error: {target}: refusing to write over it: it is read-only (mode 444)\n")
    );
    assert_eq!(std::fs::read_to_string(&target).expect("read"), "keep\n");
    assert_eq!(folder_names(files.dir.path()), ["ro.obj"]);
}

/// `-o -` writes the OBJ to standard output, and the summary to stderr.
#[test]
fn output_dash_is_standard_output() {
    let mut args = SUBDIVIDE_TETRAHEDRON.to_vec();
    args.extend(["-o", "-"]);
    let run = subcount(&args);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        run.stdout.lines().filter(|l| l.starts_with("v ")).count(),
        10
    );
    assert_eq!(
        run.stdout.lines().filter(|l| l.starts_with("f ")).count(),
        16
    );
    assert_eq!(
        run.stderr,
        "level 1: V = 10, E = 24, F = 16; wrote standard output\n"
    );
    assert!(!Path::new("-").exists());
}

/// `-o /dev/stdout` (a symbolic link to a pipe here) is written directly: the OBJ, then the
/// summary, on stdout; `/dev/stdout` is not renamed over (issue 11: as root it was).
#[test]
fn output_to_dev_stdout_is_written_directly() {
    let mut args = SUBDIVIDE_TETRAHEDRON.to_vec();
    args.extend(["-o", "/dev/stdout"]);
    let out = ok(&args);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 27, "{out}");
    assert_eq!(
        lines[26],
        "level 1: V = 10, E = 24, F = 16; wrote /dev/stdout"
    );
    let meta = std::fs::symlink_metadata("/dev/stdout").expect("stat");
    assert!(meta.file_type().is_symlink(), "/dev/stdout was replaced");
}

/// A symbolic link is written through to its target, and the link stays.
#[test]
fn output_through_a_symlink_replaces_its_target() {
    let files = Files::new();
    let real = files.write("real.obj", b"old\n");
    let link = files.path("link.obj");
    std::os::unix::fs::symlink("real.obj", &link).expect("link");
    let link = link.display().to_string();
    let mut args = SUBDIVIDE_TETRAHEDRON.to_vec();
    args.extend(["-o", link.as_str()]);
    ok(&args);
    let meta = std::fs::symlink_metadata(&link).expect("stat");
    assert!(meta.file_type().is_symlink());
    let text = std::fs::read_to_string(&real).expect("read");
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 16);
    assert_eq!(folder_names(files.dir.path()), ["link.obj", "real.obj"]);
}

/// A target name of 255 bytes (NAME_MAX) is written: the temporary file's name is short.
#[test]
fn output_names_of_255_bytes_are_written() {
    let files = Files::new();
    let name = format!("{}.obj", "m".repeat(251));
    assert_eq!(name.len(), 255);
    let target = files.path(&name).display().to_string();
    let mut args = SUBDIVIDE_TETRAHEDRON.to_vec();
    args.extend(["-o", target.as_str()]);
    ok(&args);
    assert_eq!(folder_names(files.dir.path()), [name]);
}

/// Issue 11: a `SIGTERM` or `SIGINT` during the write left the temporary file behind (376 MB).
/// It is removed, the target is untouched, and the process ends by the signal.
#[test]
fn a_signal_during_the_write_removes_the_temporary_file() {
    use std::os::unix::process::ExitStatusExt;
    // A signal this test process ignores (SIGINT under `cmd &` in a non-interactive shell, or
    // under nohup) is inherited as ignored, and subcount keeps it ignored, as nohup wants: the
    // write then completes whatever arrives.
    let ignored = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let hex = s.lines().find_map(|l| l.strip_prefix("SigIgn:"))?;
            u64::from_str_radix(hex.trim(), 16).ok()
        })
        .unwrap_or(0);
    for (signal, number) in [("TERM", 15), ("INT", 2)] {
        let inherited_ignore = ignored & (1 << (number - 1)) != 0;
        // The signal must land during the write; on a loaded machine it can arrive after the
        // process finished (then the run wrote its file and tested nothing): try again.
        let mut caught = false;
        for _attempt in 0..5 {
            let files = Files::new();
            let target = files.write("out.obj", b"previous\n");
            let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_subcount"))
                .args([
                    "subdivide",
                    "--base",
                    "icosahedron",
                    "--scheme",
                    "loop",
                    "--levels",
                    "8",
                    "-o",
                    &target,
                ])
                .stdin(std::process::Stdio::null())
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn()
                .expect("started");
            // Wait until the temporary file appears (the 60 MB write takes a while), then signal.
            let start = std::time::Instant::now();
            let mut seen = false;
            while start.elapsed() < std::time::Duration::from_secs(120) {
                if folder_names(files.dir.path()).len() > 1 {
                    seen = true;
                    break;
                }
                if child.try_wait().expect("polled").is_some() {
                    break;
                }
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            assert!(seen, "the temporary file never appeared");
            let killed = std::process::Command::new("kill")
                .args([format!("-{signal}"), child.id().to_string()])
                .status()
                .expect("kill runs");
            let status = child.wait().expect("waited");
            assert_eq!(folder_names(files.dir.path()), ["out.obj"], "{status:?}");
            if inherited_ignore {
                assert!(status.success(), "SIG{signal} is ignored here: {status:?}");
                assert_ne!(
                    std::fs::read_to_string(&target).expect("read"),
                    "previous\n"
                );
                caught = true;
                break;
            }
            if std::fs::read_to_string(&target).expect("read") != "previous\n" {
                // Too late: the complete file already replaced the target (the rename is the
                // last step), and no temporary file is left.
                assert!(
                    status.success() || status.signal() == Some(number),
                    "{status:?}"
                );
                continue;
            }
            assert!(killed.success());
            assert_eq!(status.signal(), Some(number), "{status:?}");
            caught = true;
            break;
        }
        assert!(
            caught,
            "SIG{signal} never arrived during the write in 5 attempts"
        );
    }
}

/// Runs `subcount` under `prlimit --as=BYTES` (util-linux), or returns `None` with a notice
/// when `prlimit` is missing.
fn subcount_with_address_space(bytes: u64, args: &[&str]) -> Option<crate::util::Run> {
    let output = std::process::Command::new("prlimit")
        .arg(format!("--as={bytes}"))
        .arg(env!("CARGO_BIN_EXE_subcount"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .output();
    match output {
        Ok(output) => Some(crate::util::Run {
            code: output.status.code().unwrap_or(-1),
            stdout: String::from_utf8(output.stdout).expect("stdout is UTF-8"),
            stderr: String::from_utf8(output.stderr).expect("stderr is UTF-8"),
        }),
        Err(e) => {
            eprintln!("note: prlimit cannot run ({e}); the address-space test is skipped");
            None
        }
    }
}

/// Issue 11: under `prlimit --as=2000000000`, `subdivide --levels 11` aborted (exit 134,
/// "memory allocation of 1006633008 bytes failed"): the guard took half of MemAvailable and
/// ignored the address-space limit. It now takes the least of MemAvailable, RLIMIT_AS minus
/// the address space in use and the cgroup limit.
#[test]
fn the_memory_guard_sees_the_address_space_limit() {
    let args = [
        "subdivide",
        "--base",
        "icosahedron",
        "--scheme",
        "loop",
        "--levels",
        "11",
    ];
    let Some(run) = subcount_with_address_space(2_000_000_000, &args) else {
        return;
    };
    assert_eq!(run.code, 4, "{}", run.stderr);
    assert!(
        run.stderr.starts_with(
            "error: loop to level 11 needs about 3.8 GiB of memory (levels 10 and 11 with the input), more than the limit of "
        ),
        "{}",
        run.stderr
    );
    assert!(run.stderr.ends_with(
        " MiB (half the available memory); use fewer levels, or --allow-large to try anyway\n"
    ));
}

/// With `--allow-large` past the limit, a failed allocation is a refusal (exit 4), not an
/// abort ("memory allocation of N bytes failed", exit 134). The limit is 1.5 GB rather than
/// the 2 GB because this is the debug binary, whose debug-only invariant check of
/// each level (`HalfEdgeMesh::from_raw_parts`) allocates before level 11's buffers would.
#[test]
fn a_failed_allocation_is_a_refusal_not_an_abort() {
    let args = [
        "subdivide",
        "--base",
        "icosahedron",
        "--scheme",
        "loop",
        "--levels",
        "11",
        "--allow-large",
    ];
    let Some(run) = subcount_with_address_space(1_500_000_000, &args) else {
        return;
    };
    assert_eq!(run.code, 4, "{}", run.stderr);
    assert!(
        run.stderr
            .starts_with("error: cannot allocate 1006632960 bytes for the half-edge arrays: "),
        "{}",
        run.stderr
    );
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    // The face-list subdividers (non-manifold schemes) too.
    let args = [
        "subdivide",
        "--base",
        "grid:3x3",
        "--scheme",
        "loop-general",
        "--levels",
        "12",
        "--allow-large",
    ];
    if let Some(run) = subcount_with_address_space(1_500_000_000, &args) {
        assert_eq!(run.code, 4, "{}", run.stderr);
        assert!(
            run.stderr.starts_with("error: cannot allocate "),
            "{}",
            run.stderr
        );
    }
}

/// A generated base mesh goes through the memory guard before it is allocated (exit 4); past
/// the cell cap it stays a usage error (exit 2, the message of old).
#[test]
fn base_meshes_are_guarded_before_they_are_built() {
    let args = ["stats", "--base", "grid:4096x4096"];
    if let Some(run) = subcount_with_address_space(1_000_000_000, &args) {
        assert_eq!(run.code, 4, "{}", run.stderr);
        assert!(
            run.stderr.starts_with("error: base mesh `grid:4096x4096` would need 1073938464 bytes of memory, more than the limit of "),
            "{}",
            run.stderr
        );
    }
    let args = ["table", "--scheme", "loop", "--base", "torus:1000000"];
    if let Some(run) = subcount_with_address_space(1_000_000_000, &args) {
        assert_eq!(run.code, 4, "{}", run.stderr);
        assert!(
            run.stderr
                .starts_with("error: base mesh `torus:1000000` would need "),
            "{}",
            run.stderr
        );
    }
    fails(
        &["stats", "--base", "grid:100000x100000"],
        2,
        "base mesh `grid:100000x100000`: 100000x100000 cells is more than the 16777216 allowed",
    );
}

/// A mesh file larger than the memory available is refused before it is read (a sparse
/// file of 4 GB: reading it would take minutes and fill memory).
#[test]
fn a_mesh_file_larger_than_memory_is_refused_before_reading() {
    let files = Files::new();
    let path = files.path("huge.obj");
    std::fs::File::create(&path)
        .and_then(|f| f.set_len(4_000_000_000))
        .expect("a sparse file");
    let path = path.display().to_string();
    let Some(run) = subcount_with_address_space(1_000_000_000, &["stats", "--mesh", &path]) else {
        return;
    };
    assert_eq!(run.code, 4, "{}", run.stderr);
    assert!(
        run.stderr.starts_with(&format!(
            "error: {path}: the file is 4000000000 bytes, more than the "
        )),
        "{}",
        run.stderr
    );
    assert!(run
        .stderr
        .ends_with(" bytes of memory available to this process\n"));
}

/// Issue 11: `table --scheme-file /dev/zero` read until memory ran out. Scheme files are
/// capped at 1 MiB, checked before reading it all (by length, or by a bounded read).
#[test]
fn scheme_files_are_capped() {
    fails(
        &["table", "--scheme-file", "/dev/zero"],
        3,
        "cannot read /dev/zero: the file is larger than the limit of 1048576 bytes",
    );
    let files = Files::new();
    let path = files.write("big.toml", &vec![b'#'; (1 << 20) + 1]);
    fails(
        &["formula", "--scheme-file", &path],
        3,
        "big.toml: the file is larger than the limit of 1048576 bytes",
    );
}

/// Issue 11: a UTF-8 byte-order mark made the reader drop the first line (then "face index 3
/// is out of range (the file has 2 vertices)"). It is skipped, in OBJ, OFF and scheme files.
#[test]
fn a_byte_order_mark_is_accepted() {
    let files = Files::new();
    let obj = files.write("bom.obj", format!("\u{feff}{TRIANGLE}f 1 2 3\n").as_bytes());
    let out = ok(&["stats", "--mesh", &obj]);
    assert!(
        out.starts_with("V = 3 (vertices used by faces; 0 unreferenced)"),
        "{out}"
    );
    let off = files.write(
        "bom.off",
        "\u{feff}OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n".as_bytes(),
    );
    let out = ok(&["stats", "--mesh", &off]);
    assert!(out.starts_with("V = 3 "), "{out}");
    let toml = ok(&["schemes", "--format", "toml", "loop"]);
    let scheme = files.write("bom.toml", format!("\u{feff}{toml}").as_bytes());
    let out = ok(&[
        "at",
        "--scheme-file",
        &scheme,
        "--counts",
        "V=12,E=30,F=20",
        "--level",
        "1",
    ]);
    assert!(out.contains("42"), "{out}");
}

/// Issue 11: `subdivide --scheme icosphere` on a triangle whose edge midpoint is the origin
/// wrote `v NaN NaN NaN` with exit 0. Every level's positions are checked: exit 3, naming the
/// vertex and the edge, and nothing is written. Coordinates near `f64::MAX` whose averages
/// overflow are refused the same way.
#[test]
fn non_finite_points_are_refused_and_nothing_is_written() {
    let files = Files::new();
    let origin = files.write("origin.obj", b"v 1 1 0\nv -1 -1 0\nv 0 1 1\nf 1 2 3\n");
    let out = files.path("out.obj").display().to_string();
    fails(
        &[
            "subdivide", "--mesh", &origin, "--scheme", "icosphere", "--levels", "1", "-o", &out,
        ],
        3,
        "icosphere level 1: vertex 3 (on edge (0, 1) of the input) would be at (NaN, NaN, NaN), not a finite point",
    );
    let huge = files.write(
        "huge.obj",
        b"v 1.7e308 0 0\nv 1.7e308 1 0\nv 0 0 1\nv 0 1 1\nf 1 2 3\nf 2 4 3\n",
    );
    fails(
        &[
            "subdivide",
            "--mesh",
            &huge,
            "--scheme",
            "loop-boundary",
            "--levels",
            "1",
            "-o",
            &out,
        ],
        3,
        "loop level 1: vertex 4 (on edge (0, 1) of the input) would be at (inf, ",
    );
    assert_eq!(folder_names(files.dir.path()), ["huge.obj", "origin.obj"]);
}

/// The JSON rows of `table` for `levels`.
fn table_rows(count: &[&str], levels: &str) -> Vec<serde_json::Value> {
    let out = ok(&[&["table"], count, &["--levels", levels, "--format", "json"]].concat());
    serde_json::from_str(&out).expect("table writes JSON")
}

/// Issue 11: `at --scheme loop:2,sqrt3 --level 67` (and `density`, `plot`) panicked from
/// level 67 on. Compositions, cycles (`sqrt3-boundary`) and first steps count exactly past
/// level 64: `at` (closed form or powering) equals `table` (one step at a time) at every
/// level around the switch, and `loop:2,sqrt3` on the icosahedron has
/// `V(s) = 2 + 160 3^(s-2)`, `F(s) = 320 3^(s-2)` (checked in Python).
#[test]
fn compositions_and_cycles_count_exactly_past_level_64() {
    let plans: [&[&str]; 5] = [
        &["--scheme", "loop:2,sqrt3", "--counts", "V=12,E=30,F=20"],
        &["--scheme", "sqrt3-boundary", "--counts", "V=4,E=5,F=2"],
        &[
            "--scheme",
            "loop-boundary:1,sqrt3-boundary",
            "--counts",
            "V=4,E=5,F=2",
        ],
        &[
            "--scheme",
            "catmull-clark",
            "--counts",
            "V=4,IE=0,BE=4,F=1,H=4",
        ],
        &[
            "--scheme",
            "catmull-clark:3,doo-sabin",
            "--counts",
            "V=8,E=12,F=6,BE=0,H=24",
        ],
    ];
    for count in plans {
        let rows = table_rows(count, "0..=130");
        for s in [63usize, 64, 65, 66, 67, 68, 128, 129, 130] {
            let at = ok(&[
                &["at"],
                count,
                &["--level", &s.to_string(), "--format", "json"],
            ]
            .concat());
            let at: serde_json::Value = serde_json::from_str(&at).unwrap();
            assert_eq!(at, rows[s], "{count:?} at level {s}");
        }
        let high = table_rows(count, "128..=130");
        assert_eq!(high[..], rows[128..=130], "{count:?}");
    }
    let ico = ["--scheme", "loop:2,sqrt3", "--counts", "V=12,E=30,F=20"];
    assert_eq!(
        ok(&[&["at"], &ico[..], &["--level", "67"]].concat()),
        "level 67\nV = 1648168233740405992635767562854882\nE = 4944504701221217977907302688564640\nF = 3296336467480811985271535125709760\n"
    );
    assert_eq!(
        ok(&[&["density"], &ico[..], &["--level", "67"]].concat()),
        "level 67\nV = 1648168233740405992635767562854882\nmean co-volume area 4 pi r^2 / V = 7.624446556551236e-33\n"
    );
    let files = Files::new();
    let svg = files.path("67.svg").display().to_string();
    ok(&[&["plot"], &ico[..], &["--levels", "60..=67", "-o", &svg]].concat());
    assert!(std::fs::metadata(&svg).unwrap().len() > 0);
    // 2 + 160 3^64 < 10^33 <= 2 + 160 3^65: the highest level within 10^33 vertices is 66.
    let fit = ok(&[
        &["fit"],
        &ico[..],
        &[
            "--max-vertices",
            "1000000000000000000000000000000000",
            "--format",
            "json",
        ],
    ]
    .concat());
    let fit: serde_json::Value = serde_json::from_str(&fit).unwrap();
    assert_eq!(fit["level"], 66, "{fit}");
}

/// Huge levels of compositions and cycles are refused by the digit guard (exit 4) with the
/// right size: log10(3) digits a level for sqrt3 (`8.801e18` at `u64::MAX`, where the
/// estimate saturated at `log10(2) u64::MAX = 5.553e18` before), and `table` refuses
/// ranges up to `u64::MAX` without computing a row.
#[test]
fn huge_levels_of_compositions_are_refused_with_the_right_size() {
    let ico = ["--scheme", "loop:2,sqrt3", "--counts", "V=12,E=30,F=20"];
    let cases = [
        ("9223372036854775808", "about 4.401e18 decimal digits"),
        ("18446744073709551615", "about 8.801e18 decimal digits"),
    ];
    for (level, size) in cases {
        for cmd in ["at", "density"] {
            fails(&[&[cmd], &ico[..], &["--level", level]].concat(), 4, size);
        }
    }
    // At level 10^6 `at` prints the counts, and `density`'s area is below a double.
    fails(
        &[&["density"], &ico[..], &["--level", "1000000"]].concat(),
        4,
        "is 0e0 in floating point (radius 1e0, tau 0e0, V = 10^477122.5)",
    );
    fails(
        &[
            &["table"],
            &ico[..],
            &["--levels", "0..=18446744073709551615"],
        ]
        .concat(),
        4,
        "at level 18446744073709551615 would have about 8.801e18 decimal digits",
    );
    fails(
        &[
            "table",
            "--matrix",
            "[[1]]",
            "--init",
            "1",
            "--levels",
            "0..=18446744073709551615",
        ],
        4,
        "levels 0..=18446744073709551615 would make a table of 18446744073709551616 rows",
    );
    fails(
        &[
            "at",
            "--scheme",
            "loop",
            "--counts",
            "V=12,E=30,F=20",
            "--level",
            "18446744073709551615",
        ],
        4,
        "about 1.111e19 decimal digits",
    );
}

/// Issue 11: `density`'s floating-point figures are refused (exit 4) when they are infinite
/// or zero, naming the figure; `--tau 0` (a zero scale factor) is a usage error.
#[test]
fn density_refuses_figures_outside_the_range_of_a_double() {
    let ico = ["--scheme", "loop", "--counts", "V=12,E=30,F=20"];
    let area = "density: the mean co-volume area 4 pi r^2 / V is ";
    let cases: [(&[&str], i32, &str); 7] = [
        (&["--level", "3", "--radius", "1e300"], 4, "is inf in floating point (radius 1e300, tau 0e0, V = 10^2.8), outside the range of a double"),
        (&["--level", "3", "--radius", "1e-300"], 4, "is 0e0 in floating point (radius 1e-300, tau 0e0, V = 10^2.8)"),
        (&["--level", "1000"], 4, "V = 10^603.1), outside the range of a double: ask for another level or radius"),
        (&["--level", "3", "--tau", "1e308"], 4, "density: the scale factor phi = sqrt(tau / area) is inf in floating point"),
        (&["--level", "3", "--tau", "0"], 2, "density: tau must be positive, got 0 (the scale factor phi = sqrt(tau / area) would be 0)"),
        (&["--target-area", "1e-320"], 4, "density: the vertex count needed, 4 pi r^2 / target area, is inf in floating point (radius 1e0, target area 1e-320)"),
        (&["--radius", "1e-300", "--target-area", "1"], 4, "density: the vertex count needed, 4 pi r^2 / target area, is 0e0 in floating point"),
    ];
    for (extra, code, needle) in cases {
        let err = fails(&[&["density"], &ico[..], extra].concat(), code, needle);
        if extra.contains(&"--radius") && !extra.contains(&"--target-area")
            || extra == ["--level", "1000"]
        {
            assert!(err.contains(area), "{err}");
        }
    }
}

/// Issue 11: `--threads 100000` hung starting threads. `--threads` above 256 is a usage
/// error naming the limit; 0 (every core) and 256 still run.
#[test]
fn threads_are_capped() {
    let files = Files::new();
    let out = files.path("out.obj").display().to_string();
    for (cmd, extra) in [("subdivide", vec!["-o", out.as_str()]), ("verify", vec![])] {
        let with_threads = |n: &str| -> Vec<String> {
            [
                cmd,
                "--base",
                "icosahedron",
                "--scheme",
                "loop",
                "--levels",
                "1",
                "--threads",
                n,
            ]
            .iter()
            .chain(&extra)
            .map(|a| a.to_string())
            .collect()
        };
        for n in ["257", "100000", "18446744073709551616"] {
            let needle = if n == "18446744073709551616" {
                "invalid value '18446744073709551616' for '--threads <N>': number too large to fit in target type"
            } else {
                "for '--threads <N>': at most 256 threads (0 uses every core)"
            };
            let args = with_threads(n);
            fails(
                &args.iter().map(String::as_str).collect::<Vec<_>>(),
                2,
                needle,
            );
        }
        for n in ["0", "256"] {
            let args = with_threads(n);
            ok(&args.iter().map(String::as_str).collect::<Vec<_>>());
        }
    }
}

/// Issue 11: a composition whose first stage runs for `u64::MAX` levels. `at` at level 5
/// panicked (`attempt to add with overflow` in the size estimate); at `u64::MAX` the guard
/// named sqrt3's growth instead of Loop's; `fit` computed Loop's state at level `u64::MAX`
/// until memory ran out (it now finds the crossing inside the first stage). A first stage
/// of 10^8 levels at level 1.8 10^7 has about 1.084e7-digit counts (Loop's log10(4) a
/// level), not sqrt3's 8.6e6 that passed the guard.
#[test]
fn long_first_stages_are_estimated_by_their_own_growth() {
    let ico = ["--counts", "V=12,E=30,F=20"];
    assert_eq!(
        ok(&[
            &[
                "at",
                "--scheme",
                "loop:18446744073709551615",
                "--level",
                "5"
            ],
            &ico[..]
        ]
        .concat()),
        "level 5\nV = 10242\nE = 30720\nF = 20480\n"
    );
    let long = ["--scheme", "loop:18446744073709551615,sqrt3"];
    fails(
        &[&["at"], &long[..], &ico[..], &["--level", "18446744073709551615"]].concat(),
        4,
        "the counts at level 18446744073709551615 would have about 1.111e19 decimal digits (4.0 EiB per count)",
    );
    // The crossing lies inside the long first stage: the same answer as Loop alone.
    for budget in ["1000000000000000000000000000000000000000", "1000000000000"] {
        let fit = |scheme: &str| {
            ok(&[
                &["fit", "--scheme", scheme],
                &ico[..],
                &["--max-faces", budget],
            ]
            .concat())
        };
        let alone = fit("loop");
        assert_eq!(fit("loop:18446744073709551615,sqrt3"), alone);
        assert_eq!(fit("loop:18446744073709551615"), alone);
    }
    fails(
        &[
            "at",
            "--scheme",
            "loop:100000000,sqrt3",
            "--counts",
            "V=12,E=30,F=20",
            "--level",
            "18000000",
        ],
        4,
        "the counts at level 18000000 would have about 1.084e7 decimal digits (4.3 MiB per count)",
    );
}

/// The table guard names the exact number of rows (it printed `1152921504606846976` for
/// `2^60 + 2` rows, rounded through a float).
#[test]
fn the_table_guard_counts_rows_exactly() {
    fails(
        &[
            "table",
            "--matrix",
            "[[1]]",
            "--init",
            "1",
            "--levels",
            "0..=1152921504606846977",
        ],
        4,
        "levels 0..=1152921504606846977 would make a table of 1152921504606846978 rows",
    );
}

/// Digit summaries at levels near `u64::MAX` are exact (reference values from 120-digit
/// decimal logarithms: E = 30 * 4^s has floor(log10 30 + 2 s log10 2) + 1 digits), and a
/// count with more than 2^64 digits is refused, not printed as one digit.
#[test]
fn summaries_at_levels_near_u64_max_are_exact() {
    let out = ok(&[
        "at",
        "--scheme",
        "loop",
        "--counts",
        "V=12,E=30,F=20",
        "--level",
        "18446744073709551615",
        "--summary",
    ]);
    assert_eq!(
        out,
        "level 18446744073709551615\n\
         V: 11106046577046714265 digits: 90913747023371454768...24151468139730698242\n\
         E: 11106046577046714266 digits: 27274124107011436430...72454404419192094720\n\
         F: 11106046577046714266 digits: 18182749404674290953...48302936279461396480\n"
    );
    let out = ok(&[
        "at",
        "--scheme",
        "loop",
        "--counts",
        "V=12,E=30,F=20",
        "--level",
        "9223372036854775807",
        "--summary",
    ]);
    assert!(
        out.contains(
            "E: 5553023288523357134 digits: 14302305087033550384...42559002285855211520\n"
        ),
        "{out}"
    );
    fails(
        &[
            "at",
            "--matrix",
            "[[16]]",
            "--init",
            "1",
            "--level",
            "18446744073709551615",
            "--summary",
        ],
        4,
        "the counts at level 18446744073709551615 would have about",
    );
}

/// Entries from 2^53 on keep their exact quadratic-surd eigenvalues; a numeric form that
/// floating point cannot get right is refused (exit 3) where its terms would be shown, and
/// `at` powers the matrix instead.
#[test]
fn closed_forms_of_large_entries_are_exact_or_refused() {
    let out = ok(&["formula", "--matrix", "[[9007199254740993,1],[1,0]]"]);
    assert!(
        out.starts_with("x0(s) = ((1/2+9007199254740993/162259276829213399420375029252106*sqrt(81129638414606699710187514626053))*"),
        "{out}"
    );
    assert!(!out.contains('≈'), "{out}");
    let json = ok(&[
        "formula",
        "--matrix",
        "[[9007199254740993,1],[1,0]]",
        "--format",
        "json",
    ]);
    assert!(!json.contains("\"terms\": []"), "{json}");
    let cubic = "[[9223372036854775807,9223372036854775807,1],[1,0,0],[0,1,0]]";
    for format in ["text", "json", "latex"] {
        fails(
            &["formula", "--matrix", cubic, "--format", format],
            3,
            "the closed form of component `x0` cannot be given: its numeric eigenvalues miss the exact count at level 0 (the characteristic polynomial is too ill-conditioned for floating point); use `at` or `table` for exact counts (they power the matrix)",
        );
    }
    // The Rust rendering of such a form powers the matrix: it needs no eigenvalues.
    let code = ok(&["formula", "--matrix", cubic, "--format", "rust"]);
    assert!(code.contains("fn mul(a: &Mat, b: &Mat)"), "{code}");
    let out = ok(&["at", "--matrix", cubic, "--init", "1,2,3", "--level", "3"]);
    assert_eq!(
        out,
        "level 3\n\
         x0 = 2353913150770005286268279850242405674306695987958128836608\n\
         x1 = 255211775190703847579084211500116606977\n\
         x2 = 27670116110564327424\n"
    );
}
