//! Property tests: on random small meshes, every applicable scheme's real subdivision matches
//! the predicted counts (every state component) for 3 levels.

use std::collections::HashMap;

use glam::DVec3;
mod named;

use halfedge::subdivide::SubdivideOptions;
use halfedge::{shapes, HalfEdgeMesh, PolygonMesh};
use named::{subdivide, verify, verify_polygons};
use proptest::prelude::*;

const HALF_EDGE_SCHEMES: [&str; 13] = [
    "loop",
    "loop-boundary",
    "butterfly",
    "ternary",
    "catmull-clark",
    "catmull-clark-quad",
    "sqrt3",
    "sqrt3-boundary",
    "doo-sabin",
    "doo-sabin-boundary",
    "mid-edge",
    "mid-edge-boundary",
    "tri-split-2",
];

fn opts() -> SubdivideOptions<'static> {
    SubdivideOptions::default()
}

/// Mirrors what `subdivide` accepts: the scheme's class (`loop` and the 4:1 aliases count as
/// `loop-boundary` on a boundary, `doo-sabin` and `mid-edge` as their boundary twins) and,
/// for the dual schemes, no interior vertex of valence 2 (a boundary corner with one face is
/// fine).
fn admits(scheme: &str, mesh: &HalfEdgeMesh) -> bool {
    let counts = mesh.counts();
    let boundary = counts.boundary_edges > 0;
    let counted_as = match scheme {
        "loop" | "butterfly" if boundary => "loop-boundary",
        "doo-sabin" if boundary => "doo-sabin-boundary",
        "mid-edge" if boundary => "mid-edge-boundary",
        _ => scheme,
    };
    let class_ok = schemes::builtin(counted_as)
        .and_then(|s| s.initial_state(&counts))
        .is_ok();
    let dual = scheme.starts_with("doo-sabin") || scheme.starts_with("mid-edge");
    let valence_ok = !dual
        || mesh
            .vertices()
            .all(|v| mesh.valence(v) >= 3 || mesh.is_boundary_vertex(v));
    class_ok && valence_ok
}

/// Runs every applicable scheme for 3 levels and checks every component at every level.
fn check_all(mesh: &HalfEdgeMesh) -> Result<usize, TestCaseError> {
    let mut ran = 0;
    for scheme in HALF_EDGE_SCHEMES {
        if !admits(scheme, mesh) {
            prop_assert!(
                subdivide(mesh, scheme, 1, &opts()).is_err(),
                "{scheme} should refuse"
            );
            continue;
        }
        let reports = verify(mesh, scheme, 3, &opts())
            .map_err(|e| TestCaseError::fail(format!("{scheme}: {e}")))?;
        prop_assert_eq!(reports.len(), 4);
        for r in &reports {
            prop_assert!(
                r.is_match(),
                "{} level {}: predicted {:?}, measured {:?}",
                scheme,
                r.level,
                r.predicted,
                r.measured
            );
        }
        ran += 1;
    }
    Ok(ran)
}

/// Faces of a triangle grid with a random subset removed (at least one face kept).
fn mesh_with_boundary() -> impl Strategy<Value = PolygonMesh> {
    (1u32..=4, 1u32..=4)
        .prop_flat_map(|(w, h)| {
            let n = (2 * w * h) as usize;
            (Just((w, h)), proptest::collection::vec(any::<bool>(), n))
        })
        .prop_map(|((w, h), keep)| {
            let grid = shapes::grid(w, h).expect("grid");
            let mut out = PolygonMesh::with_positions(grid.positions.clone());
            for (face, &k) in grid.faces().zip(&keep) {
                if k {
                    out.push_face(face);
                }
            }
            if out.n_faces() == 0 {
                out.push_face(grid.face(0));
            }
            out
        })
}

/// For each edge with two faces, the pair (face, face), first face containing `a -> b`.
fn face_pairs(mesh: &PolygonMesh) -> Vec<(usize, usize, u32, u32)> {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for (f, face) in mesh.faces().enumerate() {
        for i in 0..face.len() {
            directed.insert((face[i], face[(i + 1) % face.len()]), f);
        }
    }
    let mut pairs: Vec<_> = directed
        .iter()
        .filter(|(&(a, b), _)| a < b)
        .filter_map(|(&(a, b), &f)| directed.get(&(b, a)).map(|&g| (f, g, a, b)))
        .collect();
    pairs.sort_unstable();
    pairs
}

/// Merges the triangles `f` (with `a -> b`) and `g` (with `b -> a`) into a quad.
fn merge(mesh: &PolygonMesh, f: usize, g: usize, a: u32, b: u32) -> Vec<u32> {
    let rot = |face: &[u32], start: u32| -> Vec<u32> {
        let i = face
            .iter()
            .position(|&v| v == start)
            .expect("vertex in face");
        (0..face.len())
            .map(|k| face[(i + k) % face.len()])
            .collect()
    };
    let t1 = rot(mesh.face(f), a); // a, b, c
    let t2 = rot(mesh.face(g), b); // b, a, d
    vec![a, t2[2], b, t1[2]]
}

/// Merges the polygons `f` (with `a -> b`) and `g` (with `b -> a`) across their shared edge;
/// `None` when the result would repeat a vertex (the faces share more than that edge).
fn merge_polygons(faces: &[Vec<u32>], f: usize, g: usize, a: u32, b: u32) -> Option<Vec<u32>> {
    let rot = |face: &[u32], start: u32| -> Vec<u32> {
        let i = face
            .iter()
            .position(|&v| v == start)
            .expect("vertex in face");
        (0..face.len())
            .map(|k| face[(i + k) % face.len()])
            .collect()
    };
    let mut merged = rot(&faces[f], b); // b, ..., a
    let other = rot(&faces[g], a); // a, ..., b
    merged.extend_from_slice(&other[1..other.len() - 1]);
    let mut sorted = merged.clone();
    sorted.sort_unstable();
    sorted.dedup();
    (sorted.len() == merged.len()).then_some(merged)
}

/// A triangle mesh (grid with boundary, a closed triangulated torus, the icosahedron) with
/// random pairs of faces merged, in two rounds, into quads, pentagons and hexagons.
fn mixed_polygon_mesh() -> impl Strategy<Value = PolygonMesh> {
    (
        prop_oneof![
            (1u32..=3, 1u32..=3).prop_map(|(w, h)| shapes::grid(w, h).expect("grid")),
            (1u32..=2).prop_map(|g| triangulate(&shapes::torus(g).expect("torus"))),
            Just(shapes::icosahedron()),
        ],
        proptest::collection::vec(any::<bool>(), 64),
    )
        .prop_map(|(mesh, picks)| {
            let mut current = mesh.clone();
            let mut pick = picks.iter().cycle();
            for _round in 0..2 {
                let faces: Vec<Vec<u32>> = current.faces().map(<[u32]>::to_vec).collect();
                let mut used = vec![false; faces.len()];
                let mut out: Vec<Vec<u32>> = Vec::new();
                for (f, g, a, b) in face_pairs(&current) {
                    if !*pick.next().expect("cycle") || used[f] || used[g] {
                        continue;
                    }
                    if let Some(m) = merge_polygons(&faces, f, g, a, b).filter(|m| m.len() <= 6) {
                        used[f] = true;
                        used[g] = true;
                        out.push(m);
                    }
                }
                out.extend(
                    faces
                        .iter()
                        .zip(&used)
                        .filter(|(_, &u)| !u)
                        .map(|(f, _)| f.clone()),
                );
                let merged = PolygonMesh::from_faces(current.positions.clone(), out);
                if HalfEdgeMesh::try_from(&merged).is_ok() {
                    current = merged;
                }
            }
            current
        })
}

/// Splits every quad into two triangles.
fn triangulate(mesh: &PolygonMesh) -> PolygonMesh {
    let mut out = PolygonMesh::with_positions(mesh.positions.clone());
    for face in mesh.faces() {
        if let [a, b, c, d] = *face {
            out.push_face(&[a, b, c]);
            out.push_face(&[a, c, d]);
        } else {
            out.push_face(face);
        }
    }
    out
}

/// Closed triangle meshes of genus 0..=3 with random edge flips (flips that would break the
/// mesh are skipped by the validation).
fn closed_mesh() -> impl Strategy<Value = PolygonMesh> {
    (
        prop_oneof![
            Just(shapes::octahedron()),
            Just(shapes::icosahedron()),
            (1u32..=3).prop_map(|g| triangulate(&shapes::torus(g).expect("torus"))),
        ],
        proptest::collection::vec(any::<proptest::sample::Index>(), 0..6),
    )
        .prop_map(|(mut mesh, flips)| {
            for pick in flips {
                let pairs = face_pairs(&mesh);
                let (f, g, a, b) = pairs[pick.index(pairs.len())];
                let quad = merge(&mesh, f, g, a, b); // a, d, b, c
                let (d, c) = (quad[1], quad[3]);
                let mut faces: Vec<Vec<u32>> = mesh
                    .faces()
                    .enumerate()
                    .filter(|&(k, _)| k != f && k != g)
                    .map(|(_, face)| face.to_vec())
                    .collect();
                faces.push(vec![c, a, d]);
                faces.push(vec![d, b, c]);
                let flipped = PolygonMesh::from_faces(mesh.positions.clone(), faces);
                if HalfEdgeMesh::try_from(&flipped).is_ok() {
                    mesh = flipped;
                }
            }
            mesh
        })
}

/// Random triangles on 8 vertices: non-manifold edges and vertices welcome.
fn triangle_soup() -> impl Strategy<Value = PolygonMesh> {
    proptest::collection::vec((0u32..8, 0u32..8, 0u32..8), 1..10).prop_map(|tris| {
        let positions = (0..8)
            .map(|i| DVec3::new(f64::from(i), f64::from(i * i % 5), f64::from(i % 3)))
            .collect();
        let faces: Vec<[u32; 3]> = tris
            .into_iter()
            .filter(|&(a, b, c)| a != b && b != c && a != c)
            .map(|(a, b, c)| [a, b, c])
            .collect();
        let faces = if faces.is_empty() {
            vec![[0, 1, 2]]
        } else {
            faces
        };
        PolygonMesh::from_faces(positions, faces)
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn boundary_meshes_match_predictions(polygons in mesh_with_boundary()) {
        let mesh = HalfEdgeMesh::try_from(&polygons);
        prop_assume!(mesh.is_ok(), "removing faces pinched a vertex");
        let mesh = mesh.expect("checked");
        let ran = check_all(&mesh)?;
        prop_assert!(ran >= 4, "only {ran} schemes ran");
    }

    #[test]
    fn mixed_polygon_meshes_match_predictions(polygons in mixed_polygon_mesh()) {
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("merges are validated");
        let ran = check_all(&mesh)?;
        prop_assert!(ran >= 1);
    }

    #[test]
    fn closed_meshes_match_predictions(polygons in closed_mesh()) {
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("flips are validated");
        prop_assert!(mesh.is_closed());
        let ran = check_all(&mesh)?;
        prop_assert!(ran >= 8, "only {ran} schemes ran");
    }

    #[test]
    fn face_lists_match_predictions(polygons in triangle_soup()) {
        let mut sets: Vec<[u32; 3]> = polygons.faces().map(|f| {
            let mut k = [f[0], f[1], f[2]];
            k.sort_unstable();
            k
        }).collect();
        sets.sort_unstable();
        let duplicates = sets.windows(2).any(|w| w[0] == w[1]);
        for scheme in ["loop-general", "tri-split-2", "ternary", "catmull-clark-general"] {
            if duplicates && scheme != "catmull-clark-general" {
                let refused = verify_polygons(&polygons, scheme, 1, &opts());
                prop_assert!(matches!(refused, Err(halfedge::Error::DuplicateFace { .. })), "{scheme}");
                continue;
            }
            let reports = verify_polygons(&polygons, scheme, 3, &opts())
                .map_err(|e| TestCaseError::fail(format!("{scheme}: {e}")))?;
            for r in &reports {
                prop_assert!(r.is_match(), "{} level {}: {:?} vs {:?}", scheme, r.level, r.predicted, r.measured);
            }
        }
    }
}

/// Every supported scheme on base meshes scaled towards `f64::MAX` or into the subnormals
/// (issue 11: `v NaN NaN NaN` was written with exit 0): the result has only finite positions,
/// or the subdivision is refused with `Error::NonFinitePosition` naming a vertex; never a
/// non-finite point. Far from the extremes every scheme gives finite points.
mod non_finite {
    use super::named::{subdivide_polygons, subdivide_to_face_list};
    use super::*;
    use halfedge::Error;

    const SCHEMES: [&str; 13] = [
        "loop",
        "loop-boundary",
        "midpoint",
        "icosphere",
        "butterfly",
        "ternary",
        "catmull-clark",
        "catmull-clark-quad",
        "sqrt3",
        "sqrt3-boundary",
        "doo-sabin",
        "mid-edge",
        "tri-split-2",
    ];

    fn bases() -> Vec<PolygonMesh> {
        let grid = shapes::grid(2, 2).expect("grid");
        let quads = shapes::quad_grid(2, 2).expect("quad grid");
        vec![
            shapes::tetrahedron(),
            shapes::cube(),
            shapes::icosahedron(),
            grid,
            quads,
        ]
    }

    /// Coordinates near the largest finite value, subnormal, or ordinary.
    fn scale() -> impl Strategy<Value = f64> {
        prop_oneof![
            (0.05f64..=1.0).prop_map(|u| f64::MAX * u),
            (1u64..=1 << 40).prop_map(f64::from_bits),
            (1e-3f64..1e3),
        ]
    }

    fn scaled(mesh: &PolygonMesh, s: [f64; 3]) -> PolygonMesh {
        let mut out = mesh.clone();
        for p in &mut out.positions {
            *p = DVec3::new(p.x * s[0], p.y * s[1], p.z * s[2]);
        }
        out
    }

    fn check(
        scheme: &str,
        result: halfedge::Result<Vec<DVec3>>,
        ordinary: bool,
    ) -> Result<(), TestCaseError> {
        match result {
            Ok(positions) => {
                prop_assert!(positions.iter().all(|p| p.is_finite()), "{scheme}");
            }
            Err(Error::NonFinitePosition { x, y, z, .. }) => {
                prop_assert!(!DVec3::new(x, y, z).is_finite());
                prop_assert!(!ordinary, "{scheme} refused ordinary coordinates");
            }
            // The scheme does not apply to this base mesh (class, valence).
            Err(_) => {}
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        #[test]
        fn positions_are_finite_or_refused(sx in scale(), sy in scale(), sz in scale()) {
            let ordinary = [sx, sy, sz].iter().all(|s| (1e-3..1e3).contains(s));
            for base in bases() {
                let poly = scaled(&base, [sx, sy, sz]);
                let Ok(mesh) = HalfEdgeMesh::try_from(&poly) else { continue };
                for scheme in SCHEMES {
                    let r = subdivide(&mesh, scheme, 2, &opts()).map(|m| m.positions().to_vec());
                    check(scheme, r, ordinary)?;
                    let r = subdivide_to_face_list(&mesh, scheme, 2, &opts())
                        .map(|l| l.mesh.positions.clone());
                    check(scheme, r, ordinary)?;
                }
                for scheme in ["loop-general", "catmull-clark-general"] {
                    let r = subdivide_polygons(&poly, scheme, 2, &opts()).map(|m| m.positions);
                    check(scheme, r, ordinary)?;
                }
            }
        }
    }

    #[test]
    fn a_midpoint_at_the_origin_is_refused_naming_the_edge() {
        let mut poly = PolygonMesh::with_positions(vec![
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(0.0, 1.0, 1.0),
        ]);
        poly.push_face(&[0, 1, 2]);
        let mesh = HalfEdgeMesh::try_from(&poly).expect("valid");
        let err = subdivide(&mesh, "icosphere", 1, &opts()).unwrap_err();
        assert_eq!(
            err.to_string(),
            "icosphere level 1: vertex 3 (on edge (0, 1) of the input) would be at (NaN, NaN, NaN), not a finite point"
        );
    }

    #[test]
    fn huge_and_tiny_points_reach_the_sphere() {
        for s in [f64::MAX / 2.0, 1e200, 1e-200, f64::from_bits(3)] {
            let poly = scaled(&shapes::icosahedron(), [s, s, s]);
            let mesh = HalfEdgeMesh::try_from(&poly).expect("valid");
            let out = subdivide(&mesh, "icosphere", 1, &opts()).expect("finite");
            for p in &out.positions()[12..] {
                assert!((p.length() - 1.0).abs() < 1e-12, "{s}: {p}");
            }
        }
    }
}
