//! Holes, counted exactly: on generated meshes (a single hole, adjacent holes, holes at the
//! boundary, a vertex surrounded by holes; Loop and Catmull-Clark, levels 1-3) what is
//! written is counted on the real output, and equals both the scheme on the written faces'
//! statistics and the whole mesh's counts less the hole recurrence's; the written vertices
//! sit exactly where the same run without holes puts them; the refinement writes the same
//! buffers; `verify` agrees.

use halfedge::glam::DVec3;
use halfedge::holes::{boundary_faces, HoleSet};
use halfedge::refine::Refinement;
use halfedge::subdivide::{
    subdivide, subdivide_polygons, subdivide_to_face_list, verify, verify_polygons,
    SubdivideOptions,
};
use halfedge::{shapes, stats, Error, HalfEdgeMesh, PolygonMesh, Rule};
use schemes::holes::hole_recurrence;
use schemes::BigInt;

/// `mesh` with every vertex lifted by a bump of its index, so no two levels coincide by
/// symmetry and positions differ between rules.
fn bumped(mut mesh: PolygonMesh) -> PolygonMesh {
    for (i, p) in mesh.positions.iter_mut().enumerate() {
        let t = i as f64;
        *p += DVec3::new(
            0.01 * (t * 0.7).sin(),
            0.02 * (t * 1.3).cos(),
            0.3 * (t * 0.9).sin(),
        );
    }
    mesh
}

/// The faces around vertex `v`.
fn faces_around(mesh: &PolygonMesh, v: u32) -> Vec<u32> {
    (0..mesh.n_faces())
        .filter(|&f| mesh.face(f).contains(&v))
        .map(|f| f as u32)
        .collect()
}

/// (name, mesh, rule, hole sets).
fn cases() -> Vec<(&'static str, PolygonMesh, Rule, Vec<Vec<u32>>)> {
    let quads = bumped(shapes::quad_grid(4, 4).unwrap());
    // Vertex 12 = (2, 2), interior: faces 5, 6, 9, 10.
    let around_quads = faces_around(&quads, 12);
    assert_eq!(around_quads, [5, 6, 9, 10]);
    let tris = bumped(shapes::grid(4, 4).unwrap());
    let around_tris = faces_around(&tris, 12);
    assert_eq!(around_tris.len(), 6);
    let ico = bumped(shapes::icosahedron());
    let cube = bumped(shapes::cube());
    let mixed = bumped(shapes::mixed());
    vec![
        (
            "quad grid",
            quads,
            Rule::CatmullClark,
            vec![
                vec![5],
                vec![5, 6],
                vec![0, 3, 12],
                around_quads.clone(),
                vec![0, 1, 4, 5],
                // Diagonal neighbours: the written faces meet at a vertex between holes.
                vec![5, 10],
            ],
        ),
        (
            "cube",
            cube,
            Rule::CatmullClark,
            vec![vec![0], vec![0, 2], vec![0, 1, 2, 3, 4]],
        ),
        (
            "mixed",
            mixed,
            Rule::CatmullClark,
            vec![vec![0], vec![1, 2]],
        ),
        (
            "triangle grid",
            tris.clone(),
            Rule::Loop,
            vec![vec![10], vec![10, 11], vec![0, 1, 7], around_tris.clone()],
        ),
        (
            "icosahedron",
            ico.clone(),
            Rule::Loop,
            vec![vec![3], vec![3, 4], faces_around(&ico, 0)],
        ),
        ("icosahedron", ico, Rule::Butterfly, vec![vec![3, 4]]),
        (
            "triangle grid",
            tris,
            Rule::TriSplit(3),
            vec![vec![10, 11], around_tris],
        ),
    ]
}

fn as_u64(x: &BigInt) -> u64 {
    u64::try_from(x).expect("a small count")
}

#[test]
fn written_counts_equal_the_prediction_and_the_hole_recurrence() {
    let opts = SubdivideOptions::default();
    for (name, poly, rule, hole_sets) in cases() {
        let mesh = HalfEdgeMesh::try_from(&poly).unwrap();
        let full_counts = stats::face_list_counts(&poly);
        let recurrence = hole_recurrence(rule).expect("a nesting rule");
        for faces in hole_sets {
            let holes = HoleSet::new(poly.n_faces(), faces.iter().copied()).unwrap();
            let written0 = holes.written_counts(&poly);
            let gone0 = holes.hole_counts(&poly);
            for level in 1..=3u32 {
                let what = format!("{name} {rule} holes {faces:?} level {level}");
                let with = subdivide_to_face_list(&mesh, rule, level, &opts.with_holes(&holes))
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                let real = stats::face_list_counts(&with.mesh);
                assert_eq!(real.unreferenced_vertices, 0, "{what}");
                assert_eq!(real.vertices as usize, with.mesh.n_vertices(), "{what}");
                assert_eq!(real.edges as usize, with.edges, "{what}");
                let predicted = HoleSet::written_level(rule, &written0, level).unwrap();
                assert_eq!(
                    [real.vertices, real.edges, real.faces],
                    [&predicted.vertices, &predicted.edges, &predicted.faces].map(as_u64),
                    "{what}: real against the scheme on the written faces"
                );
                // The whole mesh's counts less the holes' recurrence.
                let whole = rule
                    .scheme_for(&full_counts)
                    .unwrap()
                    .counts_at(&full_counts, u64::from(level))
                    .unwrap();
                let gone = recurrence
                    .state_at(&gone0.state(), u64::from(level))
                    .unwrap();
                assert_eq!(
                    [real.vertices, real.edges, real.faces],
                    [
                        &whole.vertices - &gone[0],
                        &whole.edges - &gone[1],
                        &whole.faces - &gone[2]
                    ]
                    .map(|x| as_u64(&x)),
                    "{what}: real against the hole recurrence"
                );
                // The boundary the holes open is counted too.
                if let Some(i) = predicted_index(rule, &written0, "BE") {
                    assert_eq!(
                        BigInt::from(real.boundary_edges),
                        predicted.state[i],
                        "{what}: BE"
                    );
                }
            }
        }
    }
}

/// The position of `name` in the state of the rule's scheme for `written`.
fn predicted_index(rule: Rule, written: &schemes::MeshCounts, name: &str) -> Option<usize> {
    let scheme = rule.scheme_for(written).ok()?;
    scheme.state_names().iter().position(|n| n == name)
}

#[test]
fn written_vertices_sit_where_the_run_without_holes_puts_them() {
    let opts = SubdivideOptions::default();
    for (name, poly, rule, hole_sets) in cases() {
        let mesh = HalfEdgeMesh::try_from(&poly).unwrap();
        let degrees: Vec<usize> = poly.faces().map(<[u32]>::len).collect();
        for level in 1..=3u32 {
            let full = subdivide_to_face_list(&mesh, rule, level, &opts).unwrap();
            for faces in &hole_sets {
                let what = format!("{name} {rule} holes {faces:?} level {level}");
                let holes = HoleSet::new(poly.n_faces(), faces.iter().copied()).unwrap();
                let with =
                    subdivide_to_face_list(&mesh, rule, level, &opts.with_holes(&holes)).unwrap();
                let mask = holes.written_at(rule, &degrees, level).unwrap();
                assert_eq!(mask.len(), full.mesh.n_faces(), "{what}");
                let kept: Vec<usize> = (0..mask.len()).filter(|&f| mask[f]).collect();
                assert_eq!(kept.len(), with.mesh.n_faces(), "{what}");
                // Face k of the output is the k-th written face of the whole level, corner by
                // corner, at the same positions to the bit; the renumbering keeps the order.
                let mut old_of = vec![u32::MAX; with.mesh.n_vertices()];
                for (k, &f) in kept.iter().enumerate() {
                    let (ours, whole) = (with.mesh.face(k), full.mesh.face(f));
                    assert_eq!(ours.len(), whole.len(), "{what}");
                    for (&a, &b) in ours.iter().zip(whole) {
                        assert_eq!(
                            with.mesh.positions[a as usize].to_array(),
                            full.mesh.positions[b as usize].to_array(),
                            "{what}: face {k}"
                        );
                        assert!(old_of[a as usize] == u32::MAX || old_of[a as usize] == b);
                        old_of[a as usize] = b;
                    }
                }
                assert!(old_of.windows(2).all(|w| w[0] < w[1]), "{what}: order kept");
                // The refinement writes the same buffers and positions.
                let r = Refinement::new(&mesh, rule, level, &opts.with_holes(&holes)).unwrap();
                assert_eq!(
                    (r.n_vertices(level), r.n_faces(level), r.n_edges(level)),
                    (with.mesh.n_vertices(), with.mesh.n_faces(), with.edges),
                    "{what}"
                );
                let mut offsets = vec![0u32; r.n_faces(level) + 1];
                let mut indices = vec![0u32; r.n_corners(level)];
                r.write_polygons(&mut offsets, &mut indices).unwrap();
                assert_eq!(
                    indices,
                    with.mesh.face_indices(),
                    "{what}: refinement indices"
                );
                let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
                let mut out = vec![[0f64; 3]; r.n_vertices(level)];
                r.evaluate(&base, &mut out).unwrap();
                let expected: Vec<[f64; 3]> =
                    with.mesh.positions.iter().map(|p| p.to_array()).collect();
                assert_eq!(out, expected, "{what}: refinement positions");
                if rule.is_linear() {
                    let table = r.stencils().unwrap();
                    assert_eq!(table.len(), r.n_vertices(level), "{what}: stencil rows");
                    assert_eq!(r.stencil_sizes().unwrap(), table.sizes(), "{what}");
                }
                let mut evaluator = r.evaluator::<f64, 3>();
                let mut again = vec![[0f64; 3]; r.n_vertices(level)];
                evaluator.evaluate(&base, &mut again).unwrap();
                assert_eq!(again, expected, "{what}: evaluator");
                let mut last = vec![[0f64; 3]; r.n_vertices(level)];
                let before = if level == 1 {
                    base.clone()
                } else {
                    let r1 = Refinement::new(&mesh, rule, level - 1, &opts).unwrap();
                    let mut b = vec![[0f64; 3]; r1.n_vertices(level - 1)];
                    r1.evaluate(&base, &mut b).unwrap();
                    b
                };
                r.evaluate_level(level, &before, &mut last).unwrap();
                assert_eq!(last, expected, "{what}: evaluate_level");
            }
        }
    }
}

#[test]
fn verify_counts_what_is_written_at_every_level() {
    let opts = SubdivideOptions::default();
    for (name, poly, rule, hole_sets) in cases() {
        let mesh = HalfEdgeMesh::try_from(&poly).unwrap();
        let counts = stats::face_list_counts(&poly);
        let scheme = rule.scheme_for(&counts).unwrap();
        for faces in hole_sets {
            let holes = HoleSet::new(poly.n_faces(), faces.iter().copied()).unwrap();
            let opts = opts.with_holes(&holes);
            let reports = verify(&mesh, &scheme, 3, &opts).unwrap();
            assert_eq!(reports.len(), 4);
            for r in &reports {
                assert!(r.is_match(), "{name} {rule} {faces:?}: {r:?}");
            }
            let written = holes.written_counts(&poly);
            let f0 = reports[0].measured.iter().find(|(n, _)| n == "F").unwrap();
            assert_eq!(f0.1, BigInt::from(written.faces));
            let polygons = verify_polygons(&poly, &scheme, 2, &opts).unwrap();
            assert!(polygons.iter().all(|r| r.is_match()), "{name} {faces:?}");
        }
    }
}

#[test]
fn the_half_edge_result_is_the_written_faces_when_they_are_a_manifold() {
    let poly = bumped(shapes::quad_grid(4, 4).unwrap());
    let mesh = HalfEdgeMesh::try_from(&poly).unwrap();
    let opts = SubdivideOptions::default();
    let holes = HoleSet::new(16, [5, 6]).unwrap();
    let opts_h = opts.with_holes(&holes);
    let he = subdivide(&mesh, Rule::CatmullClark, 2, &opts_h).unwrap();
    let fl = subdivide_to_face_list(&mesh, Rule::CatmullClark, 2, &opts_h).unwrap();
    assert_eq!(
        (he.n_vertices(), he.n_edges(), he.n_faces()),
        (fl.mesh.n_vertices(), fl.edges, fl.mesh.n_faces())
    );
    assert_eq!(he.to_polygon_mesh().face_indices(), fl.mesh.face_indices());
    // Diagonal holes leave two written fans meeting at one vertex: no half-edge mesh.
    let bowtie = HoleSet::new(16, [5, 10]).unwrap();
    let err = subdivide(&mesh, Rule::CatmullClark, 1, &opts.with_holes(&bowtie)).unwrap_err();
    assert!(matches!(err, Error::NonManifoldVertex { .. }), "{err}");
}

#[test]
fn face_list_subdividers_leave_the_holes_out() {
    // Three triangles on one edge (non-manifold) and a fourth: loop-general and tri-split.
    let p = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::NEG_Y,
        DVec3::ONE,
    ];
    let book = PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 5, 2]]);
    let holes = HoleSet::new(4, [1]).unwrap();
    let opts = SubdivideOptions::default();
    let degrees = vec![3; 4];
    for rule in [Rule::Loop, Rule::TriSplit(3), Rule::CatmullClark] {
        for level in 1..=2 {
            let full = subdivide_polygons(&book, rule, level, &opts).unwrap();
            let with = subdivide_polygons(&book, rule, level, &opts.with_holes(&holes)).unwrap();
            let mask = holes.written_at(rule, &degrees, level).unwrap();
            let kept: Vec<usize> = (0..mask.len()).filter(|&f| mask[f]).collect();
            assert_eq!(kept.len(), with.n_faces(), "{rule} {level}");
            for (k, &f) in kept.iter().enumerate() {
                let a: Vec<[f64; 3]> = with
                    .face(k)
                    .iter()
                    .map(|&v| with.positions[v as usize].to_array())
                    .collect();
                let b: Vec<[f64; 3]> = full
                    .face(f)
                    .iter()
                    .map(|&v| full.positions[v as usize].to_array())
                    .collect();
                assert_eq!(a, b, "{rule} {level} face {k}");
            }
            let counts = stats::face_list_counts(&with);
            let predicted =
                HoleSet::written_level(rule, &holes.written_counts(&book), level).unwrap();
            assert_eq!(BigInt::from(counts.faces), predicted.faces);
            assert_eq!(BigInt::from(counts.edges), predicted.edges);
            assert_eq!(BigInt::from(counts.vertices), predicted.vertices);
            assert_eq!(counts.unreferenced_vertices, 0);
        }
    }
}

#[test]
fn holes_need_nested_faces_and_faces_of_the_mesh() {
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).unwrap();
    let holes = HoleSet::new(20, [0]).unwrap();
    let opts = SubdivideOptions::default().with_holes(&holes);
    for rule in [Rule::Sqrt3, Rule::DooSabin, Rule::MidEdge] {
        let err = subdivide_to_face_list(&ico, rule, 1, &opts).unwrap_err();
        assert!(matches!(err, Error::HolesNeedNestedFaces { .. }), "{err}");
        assert!(err.to_string().contains(&rule.to_string()), "{err}");
        assert!(Refinement::new(&ico, rule, 1, &opts).is_err());
    }
    let beyond = HoleSet::new(30, [25]).unwrap();
    let err = subdivide_to_face_list(
        &ico,
        Rule::Loop,
        1,
        &SubdivideOptions::default().with_holes(&beyond),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "hole face 25 is out of range (the mesh has 20 faces)"
    );
    // An empty set changes nothing.
    let none = HoleSet::new(20, []).unwrap();
    let plain = subdivide_to_face_list(&ico, Rule::Loop, 2, &SubdivideOptions::default()).unwrap();
    let empty = subdivide_to_face_list(
        &ico,
        Rule::Loop,
        2,
        &SubdivideOptions::default().with_holes(&none),
    )
    .unwrap();
    assert_eq!(plain, empty);
}

#[test]
fn refinement_buffers_have_the_written_sizes() {
    let cube = HalfEdgeMesh::try_from(&shapes::cube()).unwrap();
    let holes = HoleSet::new(6, [0]).unwrap();
    let r = Refinement::new(
        &cube,
        Rule::CatmullClark,
        2,
        &SubdivideOptions::default().with_holes(&holes),
    )
    .unwrap();
    // 98 vertices, 96 quads without the hole; the hole removes 16 quads and the 9 vertices
    // strictly inside face 0.
    assert_eq!((r.n_vertices(2), r.n_faces(2)), (98 - 9, 96 - 16));
    let mut wrong = vec![0u32; 4 * 96];
    let err = r.write_quads(&mut wrong).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!(
            "quad indices buffer has {} entries, expected {}",
            4 * 96,
            4 * 80
        )
    );
    let base: Vec<[f32; 3]> = cube
        .positions()
        .iter()
        .map(|p| p.as_vec3().to_array())
        .collect();
    let mut out = vec![[0f32; 3]; 98];
    assert!(matches!(
        r.evaluate(&base, &mut out),
        Err(Error::BufferSize { expected: 89, .. })
    ));
    // Level 0 with holes: the base is whole, what is written is not.
    let r0 = Refinement::new(
        &cube,
        Rule::CatmullClark,
        0,
        &SubdivideOptions::default().with_holes(&holes),
    )
    .unwrap();
    assert_eq!((r0.n_vertices(0), r0.n_faces(0)), (8, 5));
    let mut out = vec![[0f32; 3]; 8];
    r0.evaluate(&base, &mut out).unwrap();
    assert_eq!(out, base);
}

#[test]
fn boundary_none_holes_are_the_faces_at_the_boundary() {
    // OpenSubdiv's VTX_BOUNDARY_NONE: on a 4x4 quad grid the 12 outer faces are holes, the
    // 2x2 centre is written, and it is where the edge-only run puts it.
    let poly = bumped(shapes::quad_grid(4, 4).unwrap());
    let holes = HoleSet::new(16, boundary_faces(&poly)).unwrap();
    assert_eq!(holes.faces().len(), 12);
    let mesh = HalfEdgeMesh::try_from(&poly).unwrap();
    let with = subdivide_to_face_list(
        &mesh,
        Rule::CatmullClark,
        2,
        &SubdivideOptions::default().with_holes(&holes),
    )
    .unwrap();
    assert_eq!(with.mesh.n_faces(), 4 * 16);
    let c = stats::face_list_counts(&with.mesh);
    assert_eq!((c.vertices, c.edges, c.boundary_edges), (81, 144, 32));
}
