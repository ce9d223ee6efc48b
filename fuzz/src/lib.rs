//! The code paths the fuzz targets drive, one function per target.
//!
//! The same file is compiled into the stable regression test
//! `tests/integration/corpus.rs` (through `#[path]`), which feeds every input of
//! `tests/corpus/<target>/` to the function of that name, so a crash found by the fuzzer and
//! committed to the corpus is replayed in CI without nightly.
//!
//! Each function returns the number of "work units" it spent (elements built, digits
//! produced), so the regression tests can assert that work stays proportional to the input
//! instead of asserting wall-clock time. Every function must return normally for every input:
//! a panic is a bug in the library under test.

use halfedge::{io, stats, HalfEdgeMesh, PolygonMesh};
use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};
use schemes::{Budget, CountsInput, Plan, Scheme};

/// Largest matrix dimension the `matrix` and `scheme_toml` targets hand to the closed-form
/// solver (the CLI's own cap is the caller's business; the fuzzer looks for panics and hangs).
/// At 12, `Recurrence::closed_form_cost` is at most about 5.4e5 work units even for entries
/// near `i64::MAX` (a dense 12x12 closed form takes about 0.1 s in release).
pub const MAX_DIM: usize = 12;

/// Levels at which states are evaluated.
pub const LEVELS: [u64; 4] = [0, 1, 5, 40];

/// Loads OBJ bytes, then runs the half-edge construction and both face-list statistics; and
/// OpenSubdiv's tags: a file read with tags is read without them too (same positions and
/// faces, no tags), and the tags the reader accepted pass `Tags::check_against` on its mesh;
/// and texture coordinates: a `vt` per corner within the file's (then a UV layout and its
/// statistics), or a partial record consistent with the faces.
pub fn obj(data: &[u8]) -> u64 {
    let loaded = io::read_obj_from(data, "fuzz.obj");
    let mut work = 0;
    if let Ok(mesh) = &loaded {
        let tags = mesh.tags();
        assert_eq!(
            tags.check_against(mesh),
            Ok(()),
            "the reader checked the tags"
        );
        let sharp = tags.sharp_edges();
        assert!(sharp.iter().all(|c| c.a < c.b && c.sharpness > 0.0));
        assert!(sharp.len() <= tags.creases().len());
        assert!(tags.sharp_vertices().len() <= tags.corners().len());
        assert!(tags.hole_faces().len() <= tags.holes().len());
        work += (tags.creases().len() + tags.corners().len() + tags.holes().len()) as u64;
        let plain = io::read_obj_from_with(data, "fuzz.obj", &io::ReadOptions::without_tags())
            .expect("a file read with its tags reads without them");
        assert!(!plain.has_tags());
        assert_eq!(plain.positions, mesh.positions);
        assert_eq!(plain.face_indices(), mesh.face_indices());
        assert_eq!(plain.uvs(), mesh.uvs());
        if let Some(uvs) = mesh.uvs() {
            assert_eq!(uvs.corners().len(), mesh.n_corners(), "a vt per corner");
            assert!(uvs
                .corners()
                .iter()
                .all(|&t| (t as usize) < uvs.coords().len()));
            assert_eq!(mesh.partial_uvs(), None);
            let layout = mesh.uv_layout().expect("texture coordinates give a layout");
            assert!(layout.n_values() <= mesh.n_corners());
            let counts = stats::uv_counts(mesh).expect("texture coordinates give a layout");
            assert_eq!(counts.unreferenced, uvs.unreferenced() as u64);
            work += (uvs.coords().len() + layout.n_values()) as u64 + counts.edges;
        }
        if let Some(partial) = mesh.partial_uvs() {
            assert!(mesh.uvs().is_none());
            assert!(0 < partial.with_vt && partial.with_vt < partial.corners);
            assert_eq!(partial.corners, mesh.n_corners());
        }
        work += obj_round_trip(mesh);
    }
    work + mesh_work(loaded)
}

/// Issue 27: colors one per vertex (or a partial record), groups one class per face, and the
/// mesh written back as OBJ reads as the same positions, faces, colors, groups and `mtllib`
/// lines.
fn obj_round_trip(mesh: &PolygonMesh) -> u64 {
    use halfedge::groups::Statement;
    if let Some(colors) = mesh.colors() {
        assert_eq!(colors.len(), mesh.n_vertices(), "a color per vertex");
        assert!(mesh.partial_colors().is_none());
    }
    if let Some(partial) = mesh.partial_colors() {
        assert!(mesh.colors().is_none());
        assert!(partial.with_colors <= partial.vertices);
        assert_eq!(partial.vertices, mesh.n_vertices());
    }
    if let Some(groups) = mesh.groups() {
        assert_eq!(groups.n_faces(), mesh.n_faces(), "a class per face");
    }
    let mut out = Vec::new();
    io::write_polygon_obj(mesh, &mut out).expect("a mesh read is written");
    let back = io::read_obj_from(out.as_slice(), "back.obj").expect("what we write reads");
    assert_eq!(back.positions, mesh.positions);
    assert_eq!(back.face_offsets(), mesh.face_offsets());
    assert_eq!(back.face_indices(), mesh.face_indices());
    assert_eq!(back.colors(), mesh.colors());
    match (mesh.groups(), back.groups()) {
        (Some(a), Some(b)) => {
            assert_eq!(a.mtllib(), b.mtllib());
            for f in 0..mesh.n_faces() {
                for s in Statement::ALL {
                    // A value that was never set before a face is written as the default.
                    if let Some(value) = a.value(f, s) {
                        assert_eq!(b.value(f, s), Some(value), "face {f} {s:?}");
                    }
                }
            }
        }
        (None, None) => {}
        // Statements after the last face only (no face has them) write nothing back.
        (Some(a), None) => assert!(a.mtllib().is_empty()),
        (None, Some(_)) => panic!("groups appeared"),
    }
    mesh.n_faces() as u64
}

/// Loads OFF bytes, then as [`obj`].
pub fn off(data: &[u8]) -> u64 {
    mesh_work(io::read_off_from(data, "fuzz.off"))
}

/// Loads PLY bytes, then as [`off`]; and a mesh read is written back as binary PLY and read
/// again: the same positions and faces, the same texture coordinate at every corner, and the
/// same colors (within the rounding of `uchar` colors).
pub fn ply(data: &[u8]) -> u64 {
    let loaded = io::read_ply_from(data, "fuzz.ply");
    let mut work = 0;
    if let Ok(mesh) = &loaded {
        let corner_uvs = |m: &PolygonMesh| -> Option<Vec<[u64; 2]>> {
            let uvs = m.uvs()?;
            assert_eq!(uvs.corners().len(), m.n_corners(), "a UV value per corner");
            let value = |t: u32| uvs.coords()[t as usize].to_array().map(f64::to_bits);
            Some(uvs.corners().iter().map(|&t| value(t)).collect())
        };
        if let Some(colors) = mesh.colors() {
            assert_eq!(colors.len(), mesh.n_vertices(), "a color per vertex");
        }
        let mut out = Vec::new();
        io::write_polygon_ply(mesh, &mut out, &io::ObjWriteOptions::default())
            .expect("a mesh read is written");
        let back = io::read_ply_from(out.as_slice(), "back.ply").expect("what we write reads");
        assert_eq!(back.positions, mesh.positions);
        assert_eq!(back.face_offsets(), mesh.face_offsets());
        assert_eq!(back.face_indices(), mesh.face_indices());
        assert_eq!(corner_uvs(&back), corner_uvs(mesh));
        match (mesh.colors(), back.colors()) {
            (None, None) => {}
            (Some(a), Some(b)) => {
                let bytes = a.iter().flatten().all(|c| (0.0..=1.0).contains(c));
                for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
                    match bytes {
                        true => assert!((x - y).abs() <= 0.5 / 255.0 + 1e-12, "{x} {y}"),
                        false => assert_eq!((*x as f32).to_bits(), (*y as f32).to_bits()),
                    }
                }
            }
            (a, b) => panic!("colors {} written, {} read", a.is_some(), b.is_some()),
        }
        work += mesh.n_corners() as u64;
    }
    work + mesh_work(loaded)
}

fn mesh_work(loaded: halfedge::Result<PolygonMesh>) -> u64 {
    let Ok(mesh) = loaded else { return 1 };
    let counts = stats::face_list_counts(&mesh);
    let problems = stats::face_list_problems(&mesh);
    let _ = problems.is_manifold();
    let mut work = mesh.n_vertices() as u64 + mesh.n_corners() as u64 + counts.edges;
    if let Ok(he) = HalfEdgeMesh::try_from(&mesh) {
        work += he.n_halfedges() as u64;
        let _ = he.to_polygon_mesh();
    }
    work
}

/// `data` as UTF-8 text parsed by `parse`, or `None` when either fails (the harnesses count
/// that as one unit of work).
fn utf8_parsed<T, E>(data: &[u8], parse: impl FnOnce(&str) -> Result<T, E>) -> Option<T> {
    std::str::from_utf8(data)
        .ok()
        .and_then(|text| parse(text).ok())
}

/// Parses bytes (as UTF-8) as a scheme TOML file; when that succeeds, evaluates the scheme at
/// a few levels from an all-ones state, runs `fit` against a few budgets, and computes the
/// closed form of a small recurrence.
pub fn scheme_toml(data: &[u8]) -> u64 {
    let Some(scheme) = utf8_parsed(data, Scheme::from_toml) else {
        return 1;
    };
    let mut work = scheme.dim() as u64;
    let x0 = vec![BigInt::from(1); scheme.dim()];
    for level in LEVELS {
        if let Ok(state) = scheme.state_at(&x0, level) {
            work += digits(&state);
            let _ = scheme.vef(&state);
        }
    }
    // The budget searches of `fit` (exponential, polynomial, constant or shrinking counts).
    let plan = Plan::single(scheme.clone());
    for exponent in [0u32, 3, 40] {
        let budget = Budget {
            max_vertices: Some(BigInt::from(10).pow(exponent)),
            max_faces: Some(BigInt::from(7).pow(exponent)),
            ..Budget::default()
        };
        if let Ok(schemes::Fit::Level(counts)) = schemes::fit(&plan, &x0, &budget) {
            work += digits(&counts.state);
        }
    }
    if scheme.dim() <= MAX_DIM {
        let form = scheme.closed_form();
        let _ = (form.to_text(), form.to_latex(), form.to_rust("f"));
        work += closed_form_work(&form, &x0);
    }
    let _ = scheme.to_json();
    work
}

/// Parses text as an `--matrix` argument; when that succeeds and the matrix is at most
/// [`MAX_DIM`] square, builds its recurrence, its closed form, and evaluates both ways.
pub fn matrix(data: &[u8]) -> u64 {
    let Some(m) = utf8_parsed(data, IntMatrix::parse) else {
        return 1;
    };
    if m.dim() > MAX_DIM {
        return m.dim() as u64;
    }
    let r = Recurrence::new(m);
    let x0 = vec![BigInt::from(1); r.dim()];
    let mut work = r.dim() as u64;
    for level in LEVELS {
        if let Ok(state) = r.state_at(&x0, level) {
            work += digits(&state);
        }
    }
    let form = r.closed_form();
    let _ = (form.to_text(), form.to_latex(), form.to_rust("f"));
    work += exact_or_refused(&r, &form);
    for level in HUGE_LEVELS {
        let _ = form.summary_at(&x0, level, 20);
    }
    work + closed_form_work(&form, &x0)
}

/// Levels near `u64::MAX` at which digit summaries are asked for.
pub const HUGE_LEVELS: [u64; 3] = [1 << 40, i64::MAX as u64, u64::MAX];

/// Levels at which a closed form is checked against exact powering.
const CHECK_LEVELS: [u64; 5] = [0, 1, 2, 3, 7];

/// The closed-form contract: a form that verifies and is exact evaluates to exactly what
/// powering gives, at every level checked, and its digit summaries match the exact values'.
/// (A form that does not verify must be refused by its callers; nothing to check here.)
/// Panics on a violation: that is the bug the fuzzer looks for.
fn exact_or_refused(r: &Recurrence, form: &recurrence::ClosedForm) -> u64 {
    if form.verify().is_err() || !form.is_exact() {
        return 1;
    }
    let n = r.dim();
    let mut work = 0;
    for x0 in [
        vec![BigInt::from(1); n],
        (0..n).map(|i| BigInt::from(2 - i as i64)).collect(),
    ] {
        for level in CHECK_LEVELS {
            let (Ok(exact), Ok(closed)) = (r.state_at(&x0, level), form.evaluate(&x0, level))
            else {
                continue;
            };
            assert_eq!(
                exact, closed,
                "closed form differs from powering at level {level}"
            );
            if let Ok(sums) = form.summary_at(&x0, level, 20) {
                for (sum, value) in sums.iter().zip(&exact) {
                    assert_eq!(*sum, recurrence::digit_summary(value, 20), "level {level}");
                }
            }
            work += digits(&exact);
        }
    }
    work
}

/// Bytes as a 2x2 or 3x3 matrix of raw `i64` entries (so that entries near `i64::MAX`,
/// beyond `2^53`, are common) and a level: byte 0 picks the dimension (2 + its low bit),
/// bytes 1..9 are the level, then 8 bytes per entry, little-endian, row by row (missing
/// bytes read as zero). Checks the closed form against powering ([`exact_or_refused`]; a
/// 2x2 form is always exact) and asks for digit summaries at that level and at
/// [`HUGE_LEVELS`], which must come back as values or typed errors.
pub fn large_matrix(data: &[u8]) -> u64 {
    let word = |k: usize| -> [u8; 8] {
        let mut b = [0u8; 8];
        for (i, byte) in b.iter_mut().enumerate() {
            *byte = data.get(1 + 8 * k + i).copied().unwrap_or(0);
        }
        b
    };
    let n = 2 + usize::from(data.first().copied().unwrap_or(0) & 1);
    let level = u64::from_le_bytes(word(0));
    let rows: Vec<Vec<i64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| i64::from_le_bytes(word(1 + n * i + j)))
                .collect()
        })
        .collect();
    let Ok(m) = IntMatrix::try_from_rows(rows) else {
        return 1;
    };
    let r = Recurrence::new(m);
    let form = r.closed_form();
    if n == 2 {
        assert!(form.is_exact(), "a 2x2 closed form has exact eigenvalues");
    }
    let _ = (form.to_text(), form.to_latex(), form.to_rust("f"));
    let mut work = n as u64 + exact_or_refused(&r, &form);
    let x0 = vec![BigInt::from(1); n];
    for level in std::iter::once(level).chain(HUGE_LEVELS) {
        if let Ok(sums) = form.summary_at(&x0, level, 20) {
            work += sums.len() as u64;
        }
    }
    work
}

/// Parses text as a `--counts` argument and as a `--scheme` plan (`loop:2,catmull-clark`).
pub fn counts(data: &[u8]) -> u64 {
    let Ok(text) = std::str::from_utf8(data) else {
        return 1;
    };
    let mut work = 1;
    if let Ok(input) = CountsInput::parse(text) {
        work += input.iter().count() as u64;
        let _ = input.to_string();
    }
    if let Ok(plan) = Plan::parse(text) {
        work += plan.stages().len() as u64;
        let _ = plan.name();
        if let Some(last) = plan.last_level() {
            let _ = plan.scheme_at(last.min(1 << 20));
        }
    }
    work
}

fn closed_form_work(form: &recurrence::ClosedForm, x0: &[BigInt]) -> u64 {
    let mut work = 0;
    for level in LEVELS {
        if let Ok(state) = form.state_at(x0, level) {
            work += digits(&state);
        }
        if let Ok(state) = form.evaluate(x0, level) {
            work += digits(&state);
        }
    }
    work
}

fn digits(state: &[BigInt]) -> u64 {
    state.iter().map(|x| x.bits() / 3 + 1).sum()
}
