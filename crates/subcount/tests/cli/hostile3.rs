//! Hostile input, round 3 (issue 24): faces before their vertices under an address-space
//! limit, non-finite UVs, huge sharpness, control characters and counts past 2^64 in
//! messages, and output names of mesh formats that are not written.

use crate::hostile::Files;
use crate::util::{fails, file_names, ok, subcount};

/// Runs `subcount` under `prlimit --as=BYTES` (util-linux, on every Linux machine this
/// project builds on: a missing `prlimit` fails the test).
fn under_address_space(bytes: u64, args: &[&str]) -> crate::util::Run {
    let output = std::process::Command::new("prlimit")
        .arg(format!("--as={bytes}"))
        .arg(env!("CARGO_BIN_EXE_subcount"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("prlimit (util-linux) runs");
    crate::util::Run {
        code: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8(output.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(output.stderr).expect("stderr is UTF-8"),
    }
}

/// Item 1: 2,000,000 `f 1 2 3` lines before their three `v` lines aborted (exit 134,
/// "memory allocation of ... bytes failed"): the reader kept 16 bytes a corner of forward
/// references outside its budget. They are kept only when they rise and counted, so the
/// reader either reads the file or refuses it with exit 4 where it got to.
#[test]
fn faces_before_their_vertices_are_refused_not_aborted() {
    let files = Files::new();
    let mut text = "f 1 2 3\n".repeat(2_000_000);
    text.push_str("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    let path = files.write("forward.obj", text.as_bytes());
    // 100 MB: the reader refuses where it got to; 150 MB (the report's): the reader gets
    // through and the analysis that follows is refused before it allocates; none aborts.
    for (limit, needle) in [
        (100_000_000, "the mesh read so far needs more than "),
        (
            150_000_000,
            "analysing the mesh (2000000 faces, 6000000 corners) needs about",
        ),
        (250_000_000, "analysing the mesh"),
    ] {
        let run = under_address_space(limit, &["stats", "--mesh", &path]);
        assert_eq!(run.code, 4, "{limit}: {}", run.stderr);
        assert!(
            run.stderr.starts_with("error: ") && run.stderr.contains("forward.obj: "),
            "{limit}: {}",
            run.stderr
        );
        assert!(run.stderr.contains(needle), "{limit}: {}", run.stderr);
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    }
    // Without a limit the same faces are read (a face list of 2 M identical faces).
    let small = format!("{}v 0 0 0\nv 1 0 0\nv 0 1 0\n", "f 1 2 3\n".repeat(1000));
    let small = files.write("forward-small.obj", small.as_bytes());
    let out = subcount(&["stats", "--mesh", &small, "--format", "json"]);
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.contains("\"F\": 1000"), "{}", out.stdout);
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

/// Item 5: `vt 1e39 0` is finite in `f64` but not in `f32`: every refine-once run (and
/// `--levels 0`) wrote `vt inf`. Refused with exit 3 naming the level and the UV value, and
/// no file is left.
#[test]
fn uvs_beyond_f32_are_refused_and_nothing_is_written() {
    let files = Files::new();
    let quad = files.write(
        "quad.obj",
        format!("{QUAD}vt 1e39 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n").as_bytes(),
    );
    let tri = files.write(
        "tri.obj",
        format!("{TRIANGLE}vt 1e39 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n").as_bytes(),
    );
    let out = files.path("out.obj").display().to_string();
    for (mesh, scheme, levels) in [
        (&quad, "catmull-clark", "1"),
        (&quad, "catmull-clark", "0"),
        (&quad, "doo-sabin", "1"),
        (&quad, "mid-edge", "1"),
        (&tri, "loop", "1"),
        (&tri, "sqrt3-boundary", "1"),
    ] {
        let args = [
            "subdivide",
            "--mesh",
            mesh,
            "--scheme",
            scheme,
            "--levels",
            levels,
            "--precision",
            "f32",
            "-o",
            &out,
        ];
        let err = fails(&args, 3, "level 0: UV value 0 (the input value, beyond the range of f32) would be at (inf, 0), not a finite point");
        assert!(!err.contains('\u{1b}'), "{err}");
    }
    // Values near f32::MAX whose sums overflow in f32.
    let near = files.write(
        "near.obj",
        format!("{QUAD}vt 3e38 0\nvt 3e38 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n").as_bytes(),
    );
    fails(
        &[
            "subdivide", "--mesh", &near, "--scheme", "catmull-clark", "--levels", "1",
            "--precision", "f32", "-o", &out,
        ],
        3,
        "catmull-clark level 1: UV value 4 (computed in f32) would be at (inf, 0), not a finite point",
    );
    assert_eq!(file_names(files.dir()), ["near.obj", "quad.obj", "tri.obj"]);
    // In f64 the same files are fine.
    ok(&[
        "subdivide",
        "--mesh",
        &quad,
        "--scheme",
        "catmull-clark",
        "--levels",
        "1",
        "-o",
        &out,
    ]);
}

/// Item 5 in `f64`: `vt 1.7e308` whose Loop weights overflow wrote `vt inf` (the one-shot
/// face-list output); refused with exit 3, nothing written.
#[test]
fn uvs_that_overflow_in_f64_are_refused() {
    let files = Files::new();
    let strip = files.write(
        "strip.obj",
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n\
          vt 1.7e308 0\nvt 1.7e308 0\nvt 1.7e308 1\nvt 1.7e308 1\nvt 1 0\nvt 1 1\n\
          f 1/1 2/2 3/3\nf 1/1 3/3 4/4\nf 2/2 5/5 6/6\nf 2/2 6/6 3/3\n",
    );
    let out = files.path("out.obj").display().to_string();
    fails(
        &[
            "subdivide",
            "--mesh",
            &strip,
            "--scheme",
            "loop",
            "--levels",
            "1",
            "-o",
            &out,
        ],
        3,
        "loop level 1: UV value 0 (computed in f64) would be at (inf, 0.125), not a finite point",
    );
    assert_eq!(file_names(files.dir()), ["strip.obj"]);
    // --normals writes unit normals (or +Z) even for such positions: always finite.
    let huge = files.write(
        "huge.obj",
        b"v 1e200 0 0\nv 0 1e200 0\nv 0 0 1e200\nv 1e200 1e200 0\nf 1 2 3\nf 2 4 3\n",
    );
    ok(&[
        "subdivide",
        "--mesh",
        &huge,
        "--scheme",
        "loop",
        "--levels",
        "0",
        "--normals",
        "-o",
        &out,
    ]);
    let text = std::fs::read_to_string(&out).expect("written");
    assert!(text.lines().any(|l| l.starts_with("vn ")), "{text}");
    assert!(!text.contains("inf") && !text.contains("NaN"), "{text}");
}

/// Item 8: sharpness is read in `f64` and clamped to 10 (infinitely sharp) as OpenSubdiv
/// clamps: `1e308` was refused while `3.4e38` was accepted; both now give the surface of 10.
#[test]
fn huge_sharpness_is_infinitely_sharp() {
    let files = Files::new();
    let square = |s: &str| format!("{QUAD}f 1 2 3 4\nt crease 2/1/0 0 1 {s}\n");
    let out10 = files.path("ten.obj").display().to_string();
    let ten = files.write("ten-in.obj", square("10").as_bytes());
    ok(&[
        "subdivide",
        "--mesh",
        &ten,
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "-o",
        &out10,
    ]);
    let expected = std::fs::read_to_string(&out10).expect("written");
    for s in ["1e308", "3.4e38", "1e39"] {
        let mesh = files.write("huge.obj", square(s).as_bytes());
        let out = files.path("huge-out.obj").display().to_string();
        ok(&[
            "subdivide",
            "--mesh",
            &mesh,
            "--scheme",
            "catmull-clark",
            "--levels",
            "2",
            "-o",
            &out,
        ]);
        assert_eq!(
            std::fs::read_to_string(&out).expect("written"),
            expected,
            "{s}"
        );
    }
    for s in ["1e309", "nan", "-1"] {
        let mesh = files.write("bad.obj", square(s).as_bytes());
        fails(
            &["stats", "--mesh", &mesh],
            3,
            &format!("line 6: tag `crease`: sharpness `{s}` is not valid (expected a finite number >= 0)"),
        );
    }
}

/// Item 9: control characters from a file are escaped in every message (a tag's name, a
/// coordinate, the file's name); a crease line declaring counts that sum to 2^64 says so.
#[test]
fn messages_escape_control_characters_and_count_past_u64() {
    let files = Files::new();
    let tag = files.write(
        "tag.obj",
        format!("{TRIANGLE}f 1 2 3\nt \u{1b}[2Jevil 0/0/0\n").as_bytes(),
    );
    let run = subcount(&["stats", "--mesh", &tag]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    for text in [&run.stdout, &run.stderr] {
        assert!(!text.contains('\u{1b}'), "{text:?}");
    }
    assert!(run.stderr.contains("\\u{1b}[2Jevil (1)"), "{}", run.stderr);
    let coordinate = files.write(
        "coordinate.obj",
        b"v 0 \x1b[2J 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let err = fails(
        &["stats", "--mesh", &coordinate],
        3,
        "line 1: `\\u{1b}[2J` is not a valid coordinate",
    );
    assert!(!err.contains('\u{1b}'), "{err:?}");
    let form = files.write(
        "form.obj",
        format!("{TRIANGLE}f 1 2 3\nt crease 2/1/0 0 1 \u{7}x\n").as_bytes(),
    );
    fails(
        &["stats", "--mesh", &form],
        3,
        "`\\u{7}x` is not a valid sharpness",
    );
    // A file name with an escape sequence.
    let named = files.write("e\u{1b}[2J.obj", b"v 0 0 0\nf 1 2 3\n");
    let err = fails(
        &["stats", "--mesh", &named],
        3,
        "e\\u{1b}[2J.obj: line 2: face index 2",
    );
    assert!(!err.contains('\u{1b}'), "{err:?}");
    // Declared counts summing to 2^64: the true total.
    let counts = files.write(
        "counts.obj",
        format!("{TRIANGLE}f 1 2 3\nt crease 18446744073709551615/1/0 0 1\n").as_bytes(),
    );
    fails(
        &["stats", "--mesh", &counts],
        3,
        "tag `crease` declares 18446744073709551616 values but the line has 2",
    );
}

/// Item 9: `subdivide --scheme-file` refusing a scheme (its `topology` does not apply to the
/// mesh) names the mesh file, as `verify` does.
#[test]
fn a_scheme_file_that_does_not_apply_names_the_mesh_in_subdivide() {
    let files = Files::new();
    let quad = files.write("quad.obj", format!("{QUAD}f 1 2 3 4\n").as_bytes());
    let scheme = files.write(
        "loopish.toml",
        b"name = \"loopish\"\nstate = [\"V\", \"E\", \"F\"]\ntopology = \"loop\"\nmatrix = [[1, 1, 0], [0, 2, 3], [0, 0, 4]]\n",
    );
    let needle =
        format!("{quad}: loop needs a triangle mesh, but this mesh has 1 face of degree 4");
    for command in ["verify", "subdivide"] {
        fails(
            &[
                command,
                "--mesh",
                &quad,
                "--scheme-file",
                &scheme,
                "--levels",
                "1",
            ],
            3,
            &needle,
        );
    }
}

/// Item 11: `-o out.ply` wrote OBJ text with exit 0. A mesh format other than OBJ and PLY is
/// a usage error naming what is written; `.obj` and other names keep writing OBJ, `.ply` (any
/// case) writes binary PLY (issue 27).
#[test]
fn outputs_named_for_other_mesh_formats_are_refused() {
    let files = Files::new();
    let quad = files.write("quad.obj", format!("{QUAD}f 1 2 3 4\n").as_bytes());
    for ext in [
        "stl", "off", "glb", "gltf", "fbx", "usd", "usda", "usdc", "3ds", "dae", "STL",
    ] {
        let out = files.path(&format!("out.{ext}")).display().to_string();
        fails(
            &[
                "subdivide",
                "--mesh",
                &quad,
                "--scheme",
                "catmull-clark",
                "--levels",
                "1",
                "-o",
                &out,
            ],
            2,
            &format!(
                "subdivide does not write {} files; it writes OBJ and PLY",
                ext.to_ascii_uppercase()
            ),
        );
    }
    assert_eq!(file_names(files.dir()), ["quad.obj"]);
    for name in ["out.obj", "out.txt", "out"] {
        let out = files.path(name).display().to_string();
        ok(&[
            "subdivide",
            "--mesh",
            &quad,
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "-o",
            &out,
        ]);
        let text = std::fs::read_to_string(&out).expect("written");
        assert!(text.starts_with("v "), "{name}: {text}");
    }
    for name in ["out.ply", "out.PLY"] {
        let out = files.path(name).display().to_string();
        ok(&[
            "subdivide",
            "--mesh",
            &quad,
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "-o",
            &out,
        ]);
        let bytes = std::fs::read(&out).expect("written");
        assert!(
            bytes.starts_with(b"ply\nformat binary_little_endian 1.0\n"),
            "{name}"
        );
    }
}

/// Every pass is linear in a vertex's valence under every scheme: a bipyramid whose two apexes
/// have valence 16,000 (UVs included), subdivided to level 2 by each scheme that applies to it. The modified
/// butterfly summed each apex's ring once per edge (10.5 s in release); its wide rings are
/// summed once per level now (0.19 s). A quadratic pass in any scheme breaks the bound.
#[test]
fn high_valence_vertices_cost_linear_time_under_every_scheme() {
    let files = Files::new();
    let k = 16_000;
    let text = crate::hostile_dual::bipyramid(k);
    let mesh = files.write("bipyramid.obj", text.as_bytes());
    for scheme in [
        "loop",
        "butterfly",
        "midpoint",
        "icosphere",
        "sqrt3",
        "catmull-clark",
        "doo-sabin",
        "mid-edge",
        "loop-general",
        "catmull-clark-general",
    ] {
        let start = std::time::Instant::now();
        let summary = ok(&[
            "subdivide",
            "--mesh",
            &mesh,
            "--scheme",
            scheme,
            "--levels",
            "2",
        ]);
        let seconds = start.elapsed().as_secs_f64();
        assert!(summary.starts_with("level 2: "), "{scheme}: {summary}");
        assert!(seconds < 4.0, "{scheme} took {seconds:.1} s on valence {k}");
    }
}
