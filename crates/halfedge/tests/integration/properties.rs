//! Property tests: validation agrees with the defect counts on random face lists, nothing
//! panics, and every accepted mesh is consistent with its face list (its counts equal the
//! face list's, and both agree with what the half-edge structure shows directly).

use glam::DVec3;
use halfedge::{shapes, stats, Error, HalfEdgeMesh, PolygonMesh};
use proptest::prelude::*;

/// Random face soups over a few vertices: faces of degree 3 to 5, sometimes with a
/// repeated vertex.
fn face_soup() -> impl Strategy<Value = PolygonMesh> {
    (4u32..9).prop_flat_map(|n| {
        prop::collection::vec(prop::collection::vec(0..n, 3..6), 1..9).prop_map(move |faces| {
            let positions = (0..n).map(|i| DVec3::new(f64::from(i), 0.0, 0.0)).collect();
            PolygonMesh::from_faces(positions, faces)
        })
    })
}

/// A valid base mesh, damaged a little: faces removed, flipped, duplicated or rewired.
fn damaged_shape() -> impl Strategy<Value = PolygonMesh> {
    let names = prop::sample::select(vec![
        "tetrahedron",
        "octahedron",
        "icosahedron",
        "cube",
        "torus:1",
        "grid:3x2",
        "quad-grid:2x2",
        "mixed",
    ]);
    (
        names,
        prop::collection::vec(
            (
                0u8..5,
                any::<prop::sample::Index>(),
                any::<prop::sample::Index>(),
            ),
            0..4,
        ),
    )
        .prop_map(|(name, edits)| {
            let base = shapes::from_name(name).expect("shape");
            let mut faces: Vec<Vec<u32>> = base.faces().map(<[u32]>::to_vec).collect();
            let n = base.n_vertices();
            for (kind, a, b) in edits {
                if faces.len() < 2 {
                    break;
                }
                let f = a.index(faces.len());
                match kind {
                    0 => {
                        faces.remove(f);
                    }
                    1 => faces[f].reverse(),
                    2 => {
                        let copy = faces[f].clone();
                        faces.push(copy);
                    }
                    3 => {
                        let k = faces[f].len();
                        faces[f][b.index(k)] = b.index(n) as u32;
                    }
                    _ => {
                        let g = b.index(faces.len());
                        faces.swap(f, g);
                    }
                }
            }
            PolygonMesh::from_faces(base.positions, faces)
        })
}

/// A named shape with random parameters, possibly subdivided once or twice.
fn parametrized_shape() -> impl Strategy<Value = PolygonMesh> {
    let name = prop_oneof![
        (1u32..4, 1u32..4).prop_map(|(w, h)| format!("grid:{w}x{h}")),
        (1u32..4, 1u32..4).prop_map(|(w, h)| format!("quad-grid:{w}x{h}")),
        (1u32..4).prop_map(|g| format!("torus:{g}")),
        (1u32..5).prop_map(|k| format!("icosahedron-holes:{k}")),
        prop::sample::select(vec![
            "tetrahedron",
            "octahedron",
            "icosahedron",
            "cube",
            "mixed"
        ])
        .prop_map(str::to_string),
    ];
    let scheme = prop::sample::select(vec!["catmull-clark", "doo-sabin", "mid-edge", "sqrt3"]);
    (name, scheme, 0u32..3).prop_map(|(name, scheme, levels)| {
        let base = shapes::from_name(&name).expect("shape");
        let mesh = HalfEdgeMesh::try_from(&base).expect("valid shape");
        let opts = halfedge::subdivide::SubdivideOptions::default();
        let rule = halfedge::schemes::builtin(scheme)
            .ok()
            .and_then(|s| s.subdivision_rule())
            .expect("a built-in rule");
        halfedge::subdivide::subdivide(&mesh, rule, levels, &opts)
            .map_or(base, |m| m.to_polygon_mesh())
    })
}

/// The counts of a valid mesh against what its half-edges show without any counting code:
/// element numbers, boundary half-edges, cycles of boundary half-edges.
fn check_structure(mesh: &HalfEdgeMesh, counts: &schemes::MeshCounts) -> Result<(), TestCaseError> {
    let boundary: Vec<_> = mesh.halfedges().filter(|&h| mesh.is_boundary(h)).collect();
    let mut seen = std::collections::HashSet::new();
    let mut cycles = 0u64;
    for &h in &boundary {
        if seen.contains(&h) {
            continue;
        }
        cycles += 1;
        let mut g = h;
        while seen.insert(g) {
            g = mesh.next(g);
        }
    }
    prop_assert_eq!(counts.vertices, mesh.n_vertices() as u64);
    prop_assert_eq!(counts.edges, mesh.n_edges() as u64);
    prop_assert_eq!(counts.faces, mesh.n_faces() as u64);
    prop_assert_eq!(counts.boundary_edges, boundary.len() as u64);
    prop_assert_eq!(counts.corners, (mesh.n_halfedges() - boundary.len()) as u64);
    prop_assert_eq!(counts.boundary_loops, cycles);
    prop_assert_eq!(counts.nonmanifold_edges, 0);
    prop_assert_eq!(counts.unreferenced_vertices, mesh.unreferenced_vertices());
    Ok(())
}

fn check_agreement(mesh: &PolygonMesh) -> Result<(), TestCaseError> {
    let problems = stats::face_list_problems(mesh);
    let counts = stats::face_list_counts(mesh);
    match HalfEdgeMesh::try_from(mesh) {
        Ok(built) => {
            prop_assert!(problems.is_empty(), "accepted with {problems:?}");
            prop_assert!(built.check_invariants().is_ok());
            prop_assert_eq!(built.counts(), counts.clone());
            prop_assert_eq!(stats::genus(&counts), Some(built.genus()));
            check_structure(&built, &counts)?;
        }
        Err(err) => {
            // The first failing check, in the documented order, is the one reported.
            let expected = if problems.faces_with_repeated_vertex > 0 {
                "repeated"
            } else if problems.duplicate_faces > 0 {
                "duplicate"
            } else if problems.nonmanifold_edges > 0 {
                "edge"
            } else if problems.inconsistently_oriented_edges > 0 {
                "orientation"
            } else {
                "vertex"
            };
            let kind = match err {
                Error::RepeatedVertex { .. } => "repeated",
                Error::DuplicateFace { .. } => "duplicate",
                Error::NonManifoldEdge { .. } => "edge",
                Error::InconsistentOrientation { .. } | Error::NonOrientable { .. } => {
                    "orientation"
                }
                Error::NonManifoldVertex { .. } => "vertex",
                ref other => return Err(TestCaseError::fail(format!("unexpected error {other}"))),
            };
            prop_assert_eq!(kind, expected, "{} with {:?}", err, problems);
            prop_assert!(!problems.is_empty());
        }
    }
    Ok(())
}

proptest! {
    #[test]
    fn validation_agrees_with_defect_counts_on_face_soups(mesh in face_soup()) {
        check_agreement(&mesh)?;
    }

    #[test]
    fn validation_agrees_with_defect_counts_on_damaged_shapes(mesh in damaged_shape()) {
        check_agreement(&mesh)?;
    }

    #[test]
    fn half_edge_counts_equal_face_list_counts_on_shapes(mesh in parametrized_shape()) {
        let built = HalfEdgeMesh::try_from(&mesh).expect("shapes and their subdivisions are valid");
        let counts = stats::face_list_counts(&mesh);
        prop_assert_eq!(built.counts(), counts.clone());
        check_structure(&built, &counts)?;
    }

    #[test]
    fn half_edge_counts_keep_the_unreferenced_vertices(
        mesh in damaged_shape(),
        extra in 0usize..4,
    ) {
        // Unused positions at the end and (by rewiring) in the middle.
        let mut positions = mesh.positions.clone();
        positions.extend(std::iter::repeat(DVec3::ONE).take(extra));
        let padded = PolygonMesh::from_faces(positions, mesh.faces());
        let counts = stats::face_list_counts(&padded);
        prop_assert_eq!(
            counts.unreferenced_vertices,
            stats::face_list_counts(&mesh).unreferenced_vertices + extra as u64
        );
        if let Ok(built) = HalfEdgeMesh::try_from(&padded) {
            prop_assert_eq!(built.counts(), counts.clone());
            check_structure(&built, &counts)?;
        }
    }

    #[test]
    fn the_obj_reader_never_panics(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        let _ = halfedge::io::read_obj_from(bytes.as_slice(), "fuzz.obj");
        let _ = halfedge::io::read_off_from(bytes.as_slice(), "fuzz.off");
    }

    #[test]
    fn obj_like_text_never_panics(lines in prop::collection::vec(
        prop::sample::select(vec![
            "v 0 0 0", "v 1 2 3", "v nan 0 0", "v 1", "f 1 2 3", "f -1 -2 -3", "f 1/2/3 2//4 3/1",
            "f 0 1 2", "f 1 2", "f 4294967295 1 2", "f 99999999999999999999 1 2", "g x", "# c",
            "f 1 2 3 \\", "", "vt 0 0", "OFF", "3 1 0", "3 0 1 2",
        ]), 0..12)) {
        let text = lines.join("\n");
        if let Ok(mesh) = halfedge::io::read_obj_from(text.as_bytes(), "fuzz.obj") {
            let _ = stats::face_list_counts(&mesh);
            let _ = stats::face_list_problems(&mesh);
            let _ = HalfEdgeMesh::try_from(&mesh);
        }
        let _ = halfedge::io::read_off_from(text.as_bytes(), "fuzz.off");
    }
}

/// One duplicate-face check: the face-list subdividers refuse triangles on one vertex set
/// naming the same (smallest) pair the half-edge build names.
#[test]
fn duplicate_triangles_name_the_smallest_pair_on_every_path() {
    use halfedge::subdivide::{subdivide_polygons, SubdivideOptions};
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE];
    // Faces 0 and 3 share a vertex set, faces 1 and 2 share a set that sorts first: the
    // smallest pair is (0, 3) (the face-list path once named (1, 2), the first set's).
    let faces = [[1, 3, 4], [0, 1, 2], [1, 2, 0], [3, 1, 4]];
    let mesh = PolygonMesh::from_faces(p, faces);
    let built = HalfEdgeMesh::try_from(&mesh).unwrap_err();
    let opts = SubdivideOptions::default();
    let split = subdivide_polygons(&mesh, halfedge::Rule::Loop, 1, &opts).unwrap_err();
    for err in [&built, &split] {
        match err {
            Error::DuplicateFace { first, second, .. } => assert_eq!((*first, *second), (0, 3)),
            other => panic!("{other}"),
        }
    }
    assert_eq!(built.to_string(), split.to_string());
}

/// Quads on one vertex set are duplicates whatever their cycle (`0 1 2 3` and `0 2 1 3`
/// share no edge in the same direction), also among 41 quads around one vertex (the pair
/// shares edges in that vertex's crowded bucket and in quiet ones: either finds it).
#[test]
fn duplicate_quads_are_found_whatever_their_cycle() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::ONE, DVec3::Y];
    let mesh = PolygonMesh::from_faces(p, [[0u32, 1, 2, 3], [0, 2, 1, 3]]);
    match HalfEdgeMesh::try_from(&mesh).unwrap_err() {
        Error::DuplicateFace { first, second, .. } => assert_eq!((first, second), (0, 1)),
        other => panic!("{other}"),
    }
    // A fan of 40 quads around vertex 0 (a closed strip of a cone), one of them repeated
    // with its cycle reversed at the end.
    let n = 40u32;
    let mut positions = vec![DVec3::Z];
    for k in 0..2 * n {
        let angle = std::f64::consts::TAU * f64::from(k) / f64::from(2 * n);
        positions.push(DVec3::new(angle.cos(), angle.sin(), 0.0));
    }
    let ring = |k: u32| 1 + k % (2 * n);
    let mut faces: Vec<[u32; 4]> = (0..n)
        .map(|k| [0, ring(2 * k), ring(2 * k + 1), ring(2 * k + 2)])
        .collect();
    faces.push([0, ring(16), ring(15), ring(14)]);
    let mesh = PolygonMesh::from_faces(positions, faces);
    match HalfEdgeMesh::try_from(&mesh).unwrap_err() {
        Error::DuplicateFace { first, second, .. } => assert_eq!((first, second), (7, n)),
        other => panic!("{other}"),
    }
}
