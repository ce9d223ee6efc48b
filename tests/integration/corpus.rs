//! Hostile input, replayed on stable: every file of `tests/corpus/<target>/` goes through the
//! code path of the fuzz target of that name (`fuzz/src/lib.rs`, compiled in here), and
//! property tests feed arbitrary bytes to the mesh and scheme loaders.
//!
//! Each input must come back as a value or a typed error (a panic fails the test), and the
//! work done must stay proportional to the input: the exercise functions count work units
//! (elements built, digits produced) and the tests bound that count, not the wall time.
//!
//! To add a crash or timeout found by `cargo fuzz run TARGET` (see `fuzz/README.md`), copy the
//! artifact into `tests/corpus/TARGET/` under a name that says what it is.

use std::path::{Path, PathBuf};

use proptest::prelude::*;

#[allow(unreachable_pub, dead_code)]
#[path = "../../fuzz/src/lib.rs"]
mod exercise;

/// Work units allowed per input byte (plus a constant) before a path counts as runaway.
const WORK_PER_BYTE: u64 = 64;
const WORK_BASE: u64 = 1 << 16;

fn corpus(target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(target);
    let mut files: Vec<(PathBuf, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| {
            let path = entry.expect("a readable corpus entry").path();
            let bytes = std::fs::read(&path).expect("a readable corpus file");
            (path, bytes)
        })
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no inputs", dir.display());
    files
}

/// Replays one corpus folder through `run`, asserting each input's work stays bounded.
fn replay(target: &str, run: fn(&[u8]) -> u64) {
    for (path, bytes) in corpus(target) {
        let work = run(&bytes);
        let bound = WORK_BASE + WORK_PER_BYTE * bytes.len() as u64;
        assert!(
            work <= bound,
            "{}: {work} work units for {} bytes (bound {bound})",
            path.display(),
            bytes.len()
        );
    }
}

/// An error message as the CLI prints it: one line, no trailing period, not empty.
fn assert_one_line(message: &str, input: &str) {
    assert!(!message.is_empty(), "{input}: empty error message");
    assert!(
        !message.contains('\n'),
        "{input}: multi-line error {message:?}"
    );
    assert!(
        !message.ends_with('.'),
        "{input}: trailing period in {message:?}"
    );
}

#[test]
fn obj_corpus() {
    replay("obj", exercise::obj);
    for (path, bytes) in corpus("obj") {
        if let Err(e) = halfedge::io::read_obj_from(bytes.as_slice(), "corpus.obj") {
            let message = e.to_string();
            assert_one_line(&message, &path.display().to_string());
            assert!(
                message.starts_with("corpus.obj"),
                "{message:?} does not name the file"
            );
        }
    }
}

#[test]
fn off_corpus() {
    replay("off", exercise::off);
    for (path, bytes) in corpus("off") {
        if let Err(e) = halfedge::io::read_off_from(bytes.as_slice(), "corpus.off") {
            let message = e.to_string();
            assert_one_line(&message, &path.display().to_string());
            assert!(
                message.starts_with("corpus.off"),
                "{message:?} does not name the file"
            );
        }
    }
}

#[test]
fn ply_corpus() {
    replay("ply", exercise::ply);
    for (path, bytes) in corpus("ply") {
        if let Err(e) = halfedge::io::read_ply_from(bytes.as_slice(), "corpus.ply") {
            let message = e.to_string();
            assert_one_line(&message, &path.display().to_string());
            assert!(
                message.starts_with("corpus.ply"),
                "{message:?} does not name the file"
            );
        }
    }
}

#[test]
fn scheme_toml_corpus() {
    replay("scheme_toml", exercise::scheme_toml);
    for (path, bytes) in corpus("scheme_toml") {
        let text = String::from_utf8_lossy(&bytes);
        if let Err(e) = schemes::Scheme::from_toml(&text) {
            assert_one_line(&e.to_string(), &path.display().to_string());
        }
    }
}

#[test]
fn matrix_corpus() {
    replay("matrix", exercise::matrix);
    for (path, bytes) in corpus("matrix") {
        let text = String::from_utf8_lossy(&bytes);
        if let Err(e) = recurrence::IntMatrix::parse(&text) {
            assert_one_line(&e.to_string(), &path.display().to_string());
        }
    }
}

/// Closed forms of 2x2 and 3x3 matrices with entries near `i64::MAX` (exact or refused,
/// never wrong) and digit summaries at levels near `u64::MAX` (values or typed errors).
#[test]
fn large_matrix_corpus() {
    replay("large_matrix", exercise::large_matrix);
}

#[test]
fn counts_corpus() {
    replay("counts", exercise::counts);
    for (path, bytes) in corpus("counts") {
        let text = String::from_utf8_lossy(&bytes);
        if let Err(e) = schemes::CountsInput::parse(&text) {
            assert_one_line(&e.to_string(), &path.display().to_string());
        }
        if let Err(e) = schemes::Plan::parse(&text) {
            assert_one_line(&e.to_string(), &path.display().to_string());
        }
    }
}

/// The corpus seeds are what they say: a few loads that must succeed or fail in a known way.
#[test]
fn corpus_seeds_load_as_expected() {
    let load = |name: &str| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("corpus/obj")
            .join(name);
        halfedge::io::read_obj(&path).map_err(|e| e.to_string())
    };
    let err = load("index-beyond-u64.obj").unwrap_err();
    assert!(
        err.ends_with("line 4: face index `18446744073709551616` is too large"),
        "{err}"
    );
    let err = load("index-i64-min.obj").unwrap_err();
    assert!(
        err.ends_with("line 4: face index `-9223372036854775808` is too large"),
        "{err}"
    );
    let err = load("overflowing-coordinate.obj").unwrap_err();
    assert!(
        err.ends_with("line 2: coordinate `1e400` is not finite"),
        "{err}"
    );
    let mobius = load("mobius.obj").expect("a Möbius strip is a valid face list");
    let err = halfedge::HalfEdgeMesh::try_from(&mobius)
        .unwrap_err()
        .to_string();
    assert!(err.contains("not orientable"), "{err}");
    for name in ["continuation-at-end.obj", "empty.obj"] {
        assert!(
            load(name).unwrap_err().ends_with("the file has no faces"),
            "{name}"
        );
    }
    let tagged = load("tags-every-kind.obj").expect("every tag kind, valid");
    let tags = tagged.tags();
    assert_eq!(
        (
            tags.sharp_edges().len(),
            tags.sharp_vertices().len(),
            tags.hole_faces()
        ),
        (2, 2, vec![0])
    );
    assert_eq!(tagged.ignored_tags().len(), 1);
    let err = load("tags-counts-overflow.obj").unwrap_err();
    assert!(
        err.ends_with(
            "line 6: tag `crease` declares 55340232221128654845 values but the line has 1"
        ),
        "{err}"
    );
    // Issue 24: the true total of declared counts past 2^64, huge sharpness clamped to 10,
    // escaped control characters, a vt beyond f32 read (refused later, when converted), and
    // faces before their vertices.
    let err = load("tags-counts-sum-2-pow-64.obj").unwrap_err();
    assert!(
        err.ends_with(
            "line 5: tag `crease` declares 18446744073709551616 values but the line has 2"
        ),
        "{err}"
    );
    let err = load("tags-crease-huge-sharpness.obj").unwrap_err();
    assert!(
        err.ends_with(
            "line 8: tag `crease`: sharpness `1e309` is not valid (expected a finite number >= 0)"
        ),
        "{err}"
    );
    let names = load("tags-control-characters-in-name.obj").expect("unknown tags are ignored");
    let names: Vec<&str> = names
        .ignored_tags()
        .iter()
        .map(|t| t.name.as_str())
        .collect();
    assert_eq!(names, ["\\u{1b}[2Jevil", "crease\\u{7}"]);
    let vt = load("vt-1e39.obj").expect("1e39 is finite in f64");
    assert_eq!(vt.uvs().expect("uvs").coords()[0].x, 1e39);
    let forward = load("faces-before-vertices-forward-references.obj").expect("valid");
    assert_eq!(forward.n_faces(), 201);
    let err = load("tags-crease-not-an-edge.obj").unwrap_err();
    assert!(
        err.ends_with("line 6: tag `crease`: vertices 0 and 2 are not an edge of the mesh's faces"),
        "{err}"
    );
    let before = load("tags-before-faces.obj").expect("tags may precede the faces");
    assert_eq!(before.tags().hole_faces(), [0]);
    // Texture coordinates: every corner form, negative and forward indices, partial, unused.
    let vts = |name: &str| {
        let mesh = load(name).unwrap_or_else(|e| panic!("{e}"));
        let uvs = mesh.uvs().unwrap_or_else(|| panic!("{name}: no uvs"));
        (uvs.corners().to_vec(), uvs.unreferenced())
    };
    assert_eq!(vts("vt-corner-forms.obj"), (vec![0, 1, 2, 3, 0, 2, 3], 0));
    assert_eq!(vts("vt-negative-indices.obj"), (vec![0, 1, 2, 3, 2, 0], 0));
    assert_eq!(vts("vt-unused-entries.obj"), (vec![0, 1, 4], 2));
    let partial = load("vt-partial.obj").expect("a partial layout is no error");
    assert_eq!(
        partial.partial_uvs().map(|p| p.to_string()).as_deref(),
        Some("3 of 6 face corners have texture coordinates: no UV layout")
    );
    for (name, end) in [
        ("vt-index-out-of-range.obj", "line 6: corner 3: texture coordinate index 3 is out of range (the file has 2 texture coordinates)"),
        ("vt-forward-and-negative-out-of-range.obj", "line 5: corner 1: texture coordinate index -9 is out of range (the file has 0 texture coordinates)"),
        ("vt-one-value.obj", "line 4: texture coordinate has 1 values, expected u v (and an optional w)"),
        ("vt-index-zero.obj", "line 5: corner 2: `0` is not a valid texture coordinate index (expected a non-zero integer; negative ones count back)"),
    ] {
        let err = load(name).unwrap_err();
        assert!(err.ends_with(end), "{name}: {err}");
    }
}

/// OBJ-ish text: statements built from a small vocabulary, so the fuzzing reaches the face
/// and topology code instead of stopping at the first bad token.
fn obj_text() -> impl Strategy<Value = String> {
    let index = prop_oneof![
        (1i64..8).prop_map(|i| i.to_string()),
        (-8i64..0).prop_map(|i| i.to_string()),
        Just("0".to_string()),
        Just("4294967296".to_string()),
        (1i64..8).prop_map(|i| format!("{i}/1/1")),
        (1i64..8).prop_map(|i| format!("{i}//2")),
        (1i64..8, -4i64..6).prop_map(|(i, t)| format!("{i}/{t}")),
        (-8i64..0, 1i64..4).prop_map(|(i, t)| format!("{i}/{t}/1")),
    ];
    let coordinate = prop_oneof![
        (-3i32..3).prop_map(|x| x.to_string()),
        Just("nan".to_string()),
        Just("1e999".to_string()),
        Just("x".to_string()),
    ];
    let statement = prop_oneof![
        4 => prop::collection::vec(coordinate.clone(), 0..5).prop_map(|c| format!("v {}", c.join(" "))),
        6 => prop::collection::vec(index, 0..6).prop_map(|i| format!("f {}", i.join(" "))),
        3 => prop::collection::vec(coordinate.clone(), 0..4).prop_map(|c| format!("vt {}", c.join(" "))),
        1 => Just("g part".to_string()),
        1 => Just("# comment".to_string()),
        1 => Just("f 1 2 \\".to_string()),
        3 => tag_statement(),
    ];
    prop::collection::vec(statement, 0..24).prop_map(|lines| lines.join("\n"))
}

/// OpenSubdiv tag lines, well-formed and not: known and unknown names, counts that match
/// the values or not, indices in and out of range, sharpness and option values.
fn tag_statement() -> impl Strategy<Value = String> {
    let name = prop_oneof![
        Just("crease"),
        Just("corner"),
        Just("hole"),
        Just("interpolateboundary"),
        Just("facevaryinginterpolateboundary"),
        Just("creasemethod"),
        Just("smoothtriangles"),
        Just("vertexedit"),
    ];
    let value = prop_oneof![
        (0i64..9).prop_map(|i| i.to_string()),
        Just("-1".to_string()),
        Just("4294967295".to_string()),
        Just("2.5".to_string()),
        Just("nan".to_string()),
        Just("chaikin".to_string()),
        Just("smooth".to_string()),
    ];
    (
        name,
        0u8..4,
        0u8..3,
        0u8..2,
        prop::collection::vec(value, 0..7),
    )
        .prop_map(|(name, ints, floats, strings, values)| {
            format!("t {name} {ints}/{floats}/{strings} {}", values.join(" "))
        })
}

/// Scheme-file-ish text: lines of valid and broken scheme statements.
fn scheme_text() -> impl Strategy<Value = String> {
    let line = prop_oneof![
        Just("name = \"x\"".to_string()),
        Just("state = [\"V\", \"E\"]".to_string()),
        Just("state = [\"V\", \"V\"]".to_string()),
        Just("state = []".to_string()),
        Just("matrix = [[1, 1], [0, 4]]".to_string()),
        Just("matrix = [[1, 1], [0]]".to_string()),
        Just("matrix = [[9223372036854775807, 1], [0, -9223372036854775808]]".to_string()),
        Just("cycle = [[[1, 1], [0, 4]], [[2, 0], [0, 2]]]".to_string()),
        Just("first_step = [[1, 0], [0, 1]]".to_string()),
        Just("requires = [\"triangles\"]".to_string()),
        Just("produces = \"quads\"".to_string()),
        Just("[derive]".to_string()),
        Just("F = { E = 2, divide_by = 3 }".to_string()),
        Just("F = { E = 2, divide_by = 0 }".to_string()),
        Just("G = { Q = 1 }".to_string()),
        (-5i64..50).prop_map(|x| format!("matrix = [[{x}]]")),
    ];
    prop::collection::vec(line, 0..10).prop_map(|lines| lines.join("\n"))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn any_bytes_as_large_matrix_are_exact_or_refused(bytes in prop::collection::vec(any::<u8>(), 0..90)) {
        let work = exercise::large_matrix(&bytes);
        prop_assert!(work <= WORK_BASE + WORK_PER_BYTE * bytes.len() as u64);
    }

    #[test]
    fn any_bytes_as_obj_load_or_fail_typed(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        let work = exercise::obj(&bytes);
        prop_assert!(work <= WORK_BASE + WORK_PER_BYTE * bytes.len() as u64);
        if let Err(e) = halfedge::io::read_obj_from(bytes.as_slice(), "p.obj") {
            prop_assert!(e.to_string().starts_with("p.obj"));
        }
    }

    #[test]
    fn any_bytes_as_off_load_or_fail_typed(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        let work = exercise::off(&bytes);
        prop_assert!(work <= WORK_BASE + WORK_PER_BYTE * bytes.len() as u64);
    }

    #[test]
    fn obj_like_text_loads_or_fails_typed(text in obj_text()) {
        let work = exercise::obj(text.as_bytes());
        prop_assert!(work <= WORK_BASE + WORK_PER_BYTE * text.len() as u64);
        if let Err(e) = halfedge::io::read_obj_from(text.as_bytes(), "p.obj") {
            let message = e.to_string();
            prop_assert!(message.starts_with("p.obj") && !message.contains('\n'), "{}", message);
        }
    }

    #[test]
    fn any_bytes_as_scheme_file_load_or_fail_typed(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        let _ = exercise::scheme_toml(&bytes);
        if let Ok(text) = std::str::from_utf8(&bytes) {
            if let Err(e) = schemes::Scheme::from_toml(text) {
                prop_assert!(!e.to_string().contains('\n'));
            }
        }
    }

    #[test]
    fn scheme_like_text_loads_or_fails_typed(text in scheme_text()) {
        let _ = exercise::scheme_toml(text.as_bytes());
        if let Err(e) = schemes::Scheme::from_toml(&text) {
            let message = e.to_string();
            prop_assert!(!message.is_empty() && !message.contains('\n'), "{}", message);
        }
    }
}
