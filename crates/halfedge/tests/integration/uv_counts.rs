//! UV layout statistics and UV counts: spot_control_mesh's layout is the one the issue pins,
//! and the UV recurrences give OpenSubdiv's measured value counts (Catmull-Clark on
//! spot_control_mesh, Loop on spot_triangulated); the written faces of a mesh with holes have
//! the layout of the mesh made of them alone.

use std::path::Path;

use halfedge::glam::{DVec2, DVec3};
use halfedge::holes::HoleSet;
use halfedge::uv::Uvs;
use halfedge::{io, shapes, stats, PolygonMesh, Rule};
use schemes::uv::{uv_scheme, UvCounts};
use schemes::BigInt;

/// The mesh of an OBJ file, with its texture coordinates.
fn read_with_uvs(path: &Path) -> PolygonMesh {
    let mesh = io::read_obj(path).unwrap_or_else(|e| panic!("{e}"));
    assert!(mesh.uvs().is_some(), "{}: no uvs", path.display());
    mesh
}

pub(crate) fn values(
    rule: Rule,
    uv: &UvCounts,
    levels: std::ops::RangeInclusive<u64>,
) -> Vec<BigInt> {
    let scheme = uv_scheme(rule).unwrap_or_else(|e| panic!("{e}"));
    levels
        .map(|s| scheme.values_at(uv, s).unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_control_mesh_has_the_pinned_layout_and_opensubdivs_counts() {
    let mesh = read_with_uvs(&testdata::mesh("spot_control_mesh.obj"));
    let uv = stats::uv_counts(&mesh).expect("spot has UVs");
    let json = serde_json::to_string(&uv).expect("serializes");
    assert_eq!(
        json,
        r#"{"V":267,"E":438,"BE":144,"seam_edges":72,"boundary_loops":13,"charts":13,"unreferenced":0}"#
    );
    assert_eq!((uv.used_vt, uv.faces, uv.corners), (267, 180, 732));
    // OpenSubdiv 3.5's GetNumFVarValues at levels 0-4.
    assert_eq!(
        values(Rule::CatmullClark, &uv, 0..=4),
        [267, 885, 3225, 12297, 48009].map(BigInt::from)
    );
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_triangulated_counts_opensubdivs_loop_values() {
    let mesh = read_with_uvs(&testdata::mesh("spot_triangulated.obj"));
    let uv = stats::uv_counts(&mesh).expect("spot has UVs");
    assert_eq!(
        values(Rule::Loop, &uv, 0..=2),
        [3225, 12297, 48009].map(BigInt::from)
    );
}

/// OpenSubdiv's sibling values: the pawn's and bishop's 4 `vt` are used by every quad at its
/// four corners in turn, and at 39 of the bishop's vertices the faces around use two `vt` in
/// the order A, B, A, B, each a value of its own at level 1. Counts are OpenSubdiv 3.5's
/// `GetNumFVarValues` (tools/osd-driver/README.md).
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn sibling_values_give_opensubdivs_counts_on_the_shared_meshes() {
    let cases: [(&str, u64, u64, &[u64]); 5] = [
        ("osd_catmark_pawn.obj", 2281, 0, &[4, 5221, 14629]),
        ("osd_catmark_bishop.obj", 3244, 39, &[4, 7991, 22951]),
        (
            "spot_control_mesh.obj",
            267,
            0,
            &[267, 885, 3225, 12297, 48009],
        ),
        ("blub_control_mesh.obj", 141, 0, &[141, 501, 1885]),
        ("cylinder_ngon.obj", 271, 0, &[271, 943, 3563]),
    ];
    for (name, pairs, split, expected) in cases {
        let mesh = read_with_uvs(&testdata::mesh(name));
        let uv = stats::uv_counts(&mesh).expect("a layout");
        assert_eq!((uv.values, uv.split_values), (pairs, split), "{name}");
        let last = expected.len() as u64 - 1;
        assert_eq!(
            values(Rule::CatmullClark, &uv, 0..=last),
            expected
                .iter()
                .map(|&x| BigInt::from(x))
                .collect::<Vec<_>>(),
            "{name}"
        );
    }
}

/// The cube with every face its own chart (a `vt` per corner): every edge is a seam.
fn cube_of_charts() -> PolygonMesh {
    let mut cube = shapes::cube();
    let coords: Vec<DVec2> = (0..24).map(|i| DVec2::new(f64::from(i), 0.0)).collect();
    cube.set_uvs(Some(Uvs::new(coords, (0..24).collect()).expect("in range")))
        .expect("one vt per corner");
    cube
}

#[test]
fn a_cube_of_separate_charts() {
    let uv = stats::uv_counts(&cube_of_charts()).expect("a layout");
    assert_eq!(
        (uv.values, uv.edges, uv.boundary_edges, uv.seam_edges),
        (24, 24, 24, 12)
    );
    assert_eq!((uv.boundary_loops, uv.charts, uv.unreferenced), (6, 6, 0));
    // Each quad refines on its own: (2^s + 1)^2 values per face.
    let expected: Vec<BigInt> = (0..4u32)
        .map(|s| BigInt::from(6 * (2u64.pow(s) + 1).pow(2)))
        .collect();
    assert_eq!(values(Rule::CatmullClark, &uv, 0..=3), expected);
}

#[test]
fn written_faces_have_the_layout_of_the_mesh_made_of_them() {
    let cube = cube_of_charts();
    let holes = HoleSet::new(cube.n_faces(), [0, 3]).expect("faces of the cube");
    let written = holes.written_uv_counts(&cube).expect("a layout");
    // The four written faces alone, with their vt.
    let kept: Vec<usize> = (0..6).filter(|f| ![0, 3].contains(f)).collect();
    let mut alone = PolygonMesh::from_faces(
        cube.positions.clone(),
        kept.iter().map(|&f| cube.face(f).to_vec()),
    );
    let vts: Vec<u32> = kept
        .iter()
        .flat_map(|&f| (4 * f as u32)..(4 * f as u32 + 4))
        .collect();
    let coords = cube.uvs().expect("uvs").coords().to_vec();
    alone
        .set_uvs(Some(Uvs::new(coords, vts).expect("in range")))
        .expect("one vt per corner");
    assert_eq!(Some(written.clone()), stats::uv_counts(&alone));
    assert_eq!(
        (written.values, written.charts, written.unreferenced),
        (16, 4, 8)
    );
    // No UVs, no layout.
    assert_eq!(holes.written_uv_counts(&shapes::cube()), None);
}

/// A `w` x `h` grid of quads (optionally each split into two triangles) whose corners use
/// `vt` chosen by `picks`: 0 the corner's vertex's own `vt`, 1-3 one of three `vt` shared by
/// every vertex (as the pawn's four), so seams and shared `vt` fall anywhere.
pub(crate) fn grid_with_seams(w: u32, h: u32, triangles: bool, picks: &[u8]) -> PolygonMesh {
    grid_with_shared_runs(w, h, triangles, picks, &[false])
}

/// [`grid_with_seams`], and at every vertex `v` with `checker[v % checker.len()]` all corners
/// use the shared `vt` 0 or 1 by the checkerboard parity of their face (of their quad, plus
/// the triangle's index in it), so an interior vertex of the quad grid sees A, B, A, B
/// around it and the triangle grid's see longer alternations.
pub(crate) fn grid_with_shared_runs(
    w: u32,
    h: u32,
    triangles: bool,
    picks: &[u8],
    checker: &[bool],
) -> PolygonMesh {
    let n = (w + 1) * (h + 1);
    let positions: Vec<DVec3> = (0..n)
        .map(|i| DVec3::new(f64::from(i % (w + 1)), f64::from(i / (w + 1)), 0.0))
        .collect();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut parity: Vec<u32> = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let a = y * (w + 1) + x;
            let (b, c, d) = (a + 1, a + w + 2, a + w + 1);
            if triangles {
                faces.push(vec![a, b, c]);
                faces.push(vec![a, c, d]);
                parity.extend([(x + y) % 2, (x + y + 1) % 2]);
            } else {
                faces.push(vec![a, b, c, d]);
                parity.push((x + y) % 2);
            }
        }
    }
    let corners: Vec<u32> = faces
        .iter()
        .zip(&parity)
        .flat_map(|(f, &p)| f.iter().map(move |&v| (v, p)))
        .enumerate()
        .map(|(i, (v, p))| {
            if checker[v as usize % checker.len()] {
                return p;
            }
            match picks[i % picks.len()] {
                0 => 3 + v,
                k => u32::from(k - 1),
            }
        })
        .collect();
    let coords = vec![DVec2::ZERO; 3 + n as usize];
    let mut mesh = PolygonMesh::from_faces(positions, faces);
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("one vt per corner");
    mesh
}

/// The UV values the real face-varying refinement writes at `level`: the distinct indices of
/// [`halfedge::refine::Refinement::write_uv_indices`] (checked against `n_uvs`).
pub(crate) fn written_values(mesh: &PolygonMesh, rule: Rule, level: u32) -> Result<u64, String> {
    use halfedge::refine::Refinement;
    use halfedge::subdivide::SubdivideOptions;
    let layout = mesh.uv_layout().expect("a layout");
    let half = halfedge::HalfEdgeMesh::try_from(mesh).map_err(|e| e.to_string())?;
    let opts = SubdivideOptions::default().with_uvs(&layout);
    let r = Refinement::new(&half, rule, level, &opts).map_err(|e| format!("{rule}: {e}"))?;
    let mut indices = vec![0u32; r.n_corners(level)];
    r.write_uv_indices(&mut indices)
        .map_err(|e| format!("{rule}: {e}"))?;
    indices.sort_unstable();
    indices.dedup();
    if indices.len() != r.n_uvs(level) {
        return Err(format!(
            "{rule} level {level}: {} indices written, n_uvs {}",
            indices.len(),
            r.n_uvs(level)
        ));
    }
    Ok(indices.len() as u64)
}

/// Every rule with a UV scheme: Catmull-Clark on any grid, the triangle rules on triangles.
fn uv_rules(triangles: bool) -> Vec<Rule> {
    let mut rules = vec![Rule::CatmullClark];
    if triangles {
        rules.extend([
            Rule::Loop,
            Rule::Midpoint,
            Rule::Butterfly,
            Rule::Icosphere,
            Rule::TriSplit(2),
            Rule::TriSplit(3),
        ]);
    }
    rules
}

proptest::proptest! {
    #![proptest_config(proptest::test_runner::Config::with_cases(96))]
    /// The UV recurrences count the values the real face-varying channel writes (distinct
    /// indices of `write_uv_indices`), for every rule with UVs, at levels 1-3, on grids with
    /// random seams and shared `vt`, with vertices whose faces alternate two shared `vt`
    /// (A, B, A, B: OpenSubdiv's sibling values).
    #[test]
    fn uv_recurrences_count_the_written_uv_values(
        w in 1u32..5,
        h in 1u32..4,
        triangles in proptest::bool::ANY,
        picks in proptest::collection::vec(0u8..4, 1..40),
        checker in proptest::collection::vec(proptest::bool::weighted(0.4), 1..8),
    ) {
        let mesh = grid_with_shared_runs(w, h, triangles, &picks, &checker);
        let uv = stats::uv_counts(&mesh).expect("a layout");
        for rule in uv_rules(triangles) {
            let levels = if matches!(rule, Rule::TriSplit(_)) { 2 } else { 3 };
            for s in 1..=levels {
                let written = written_values(&mesh, rule, s)
                    .map_err(proptest::test_runner::TestCaseError::fail)?;
                proptest::prop_assert_eq!(
                    values(rule, &uv, u64::from(s)..=u64::from(s)),
                    vec![BigInt::from(written)],
                    "{} level {} split {}", rule, s, uv.split_values
                );
            }
        }
    }
}

/// Four triangles around a vertex whose corners there use `vt` 1, 2, 1, 2 (the reviewer's
/// fan): every rule with UVs writes the values its recurrence counts, at levels 1-2.
#[test]
fn a_fan_with_two_shared_vt_alternating_is_counted_for_every_rule() {
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::NEG_X, DVec3::NEG_Y];
    let faces = vec![vec![0, 1, 2], vec![0, 2, 3], vec![0, 3, 4], vec![0, 4, 1]];
    let corners = vec![0, 2, 3, 1, 3, 4, 0, 4, 5, 1, 5, 2];
    let mut mesh = PolygonMesh::from_faces(positions, faces);
    mesh.set_uvs(Some(
        Uvs::new(vec![DVec2::ZERO; 6], corners).expect("in range"),
    ))
    .expect("one vt per corner");
    let uv = stats::uv_counts(&mesh).expect("a layout");
    assert_eq!((uv.values, uv.edges, uv.split_values), (6, 12, 1));
    for rule in uv_rules(true) {
        for s in 1..=2u32 {
            assert_eq!(
                values(rule, &uv, u64::from(s)..=u64::from(s)),
                vec![BigInt::from(written_values(&mesh, rule, s).unwrap())],
                "{rule} level {s}"
            );
        }
    }
}

/// The UV values of the real face-varying refinement ([`halfedge::refine::Refinement`] with
/// the layout) at levels `1..=levels`.
fn refined_values(mesh: &PolygonMesh, rule: Rule, levels: u32) -> Vec<BigInt> {
    use halfedge::refine::Refinement;
    use halfedge::subdivide::SubdivideOptions;
    let layout = mesh.uv_layout().expect("a layout");
    let half = halfedge::HalfEdgeMesh::try_from(mesh).unwrap_or_else(|e| panic!("{e}"));
    let opts = SubdivideOptions::default().with_uvs(&layout);
    let r = Refinement::new(&half, rule, levels, &opts).unwrap_or_else(|e| panic!("{rule}: {e}"));
    (1..=levels).map(|s| BigInt::from(r.n_uvs(s))).collect()
}

proptest::proptest! {
    #![proptest_config(proptest::test_runner::Config::with_cases(64))]
    /// The predicted UV values are those of the real face-varying refinement (Loop,
    /// Catmull-Clark), sibling values included, on grids with random seams and shared `vt`.
    #[test]
    fn uv_recurrences_count_the_real_face_varying_refinement(
        w in 1u32..5,
        h in 1u32..4,
        triangles in proptest::bool::ANY,
        picks in proptest::collection::vec(0u8..4, 1..40),
    ) {
        let mesh = grid_with_seams(w, h, triangles, &picks);
        let uv = stats::uv_counts(&mesh).expect("a layout");
        let mut rules = vec![Rule::CatmullClark];
        if triangles {
            rules.push(Rule::Loop);
        }
        for rule in rules {
            proptest::prop_assert_eq!(
                values(rule, &uv, 1..=3),
                refined_values(&mesh, rule, 3),
                "{} split {}", rule, uv.split_values
            );
        }
    }
}

/// The predicted UV values are those of the real face-varying refinement on the shared
/// meshes with UVs that the half-edge mesh accepts (Catmull-Clark, and Loop on triangle
/// meshes), levels 1-2: the bishop's 39 sibling values included.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn uv_counts_are_the_real_face_varying_refinements_on_the_shared_meshes() {
    let dir = testdata::meshes_dir();
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| {
            let name = e.ok()?.file_name().to_string_lossy().into_owned();
            name.ends_with(".obj").then_some(name)
        })
        .collect();
    names.sort();
    let mut checked = Vec::new();
    for name in names {
        let path = dir.join(&name);
        let mesh = io::read_obj(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let Some(uv) = stats::uv_counts(&mesh) else {
            continue;
        };
        if halfedge::HalfEdgeMesh::try_from(&mesh).is_err() {
            continue;
        }
        let mut rules = vec![Rule::CatmullClark];
        if mesh.faces().all(|f| f.len() == 3) {
            rules.push(Rule::Loop);
        }
        for rule in rules {
            assert_eq!(
                values(rule, &uv, 1..=2),
                refined_values(&mesh, rule, 2),
                "{name} {rule}"
            );
        }
        checked.push(name);
    }
    assert!(
        checked.iter().any(|n| n == "osd_catmark_bishop.obj") && checked.len() >= 12,
        "{checked:?}"
    );
}

/// Four quads around a vertex using two shared `vt` in the order A, B, A, B around it: one
/// sibling value split off, in the prediction and in the real refinement alike.
#[test]
fn a_split_sibling_value_is_counted_by_the_real_refinement_too() {
    // Corners 2, 7, 12, 9 are the centre's in faces 0, 1, 3, 2 (OpenSubdiv's order there).
    let picks = [0, 0, 1, 0, 0, 0, 0, 2, 0, 2, 0, 0, 1, 0, 0, 0];
    let mesh = grid_with_seams(2, 2, false, &picks);
    let uv = stats::uv_counts(&mesh).expect("a layout");
    assert_eq!((uv.values, uv.split_values), (10, 1));
    let predicted = values(Rule::CatmullClark, &uv, 1..=3);
    assert_eq!(predicted, refined_values(&mesh, Rule::CatmullClark, 3));
    // One more than the layout refined as a face list.
    assert_eq!(predicted[0], BigInt::from(10 + 1 + uv.edges + 4));
}

/// With holes the prediction from the written faces' layout (`HoleSet::written_uv_counts`,
/// sibling values of the whole mesh) is the number of values the written faces of the real
/// refinement use, at each last level; on the bishop too, whose sibling values holes can
/// leave unused.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn written_uv_values_with_holes_are_the_real_refinements() {
    use halfedge::refine::Refinement;
    use halfedge::subdivide::SubdivideOptions;
    for (name, holes) in [
        ("spot_control_mesh.obj", vec![0u32, 1, 2, 40, 41]),
        ("osd_catmark_bishop.obj", (0..968).step_by(3).collect()),
    ] {
        let mesh = read_with_uvs(&testdata::mesh(name));
        let holes = HoleSet::new(mesh.n_faces(), holes).expect("faces of the mesh");
        let uv = holes.written_uv_counts(&mesh).expect("a layout");
        let layout = mesh.uv_layout().expect("a layout");
        let half = halfedge::HalfEdgeMesh::try_from(&mesh).unwrap_or_else(|e| panic!("{e}"));
        let opts = SubdivideOptions::default()
            .with_uvs(&layout)
            .with_holes(&holes);
        for levels in 1..=2u32 {
            let r = Refinement::new(&half, Rule::CatmullClark, levels, &opts)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(
                values(
                    Rule::CatmullClark,
                    &uv,
                    u64::from(levels)..=u64::from(levels)
                ),
                [BigInt::from(r.n_uvs(levels))],
                "{name} level {levels}, split {}",
                uv.split_values
            );
        }
    }
}
