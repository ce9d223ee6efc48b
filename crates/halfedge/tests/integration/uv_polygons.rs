//! UVs through the face-list subdividers (`subdivide_polygons`): the layout refined as a face
//! list by the same rule, its value counts against `schemes::uv`'s recurrences on a
//! non-manifold book and on grids with seams, and the values placed linearly, as positions.

use halfedge::glam::{DVec2, DVec3};
use halfedge::subdivide::{subdivide_polygons, SubdivideOptions};
use halfedge::uv::Uvs;
use halfedge::{shapes, stats, PolygonMesh, Rule};
use schemes::uv::uv_scheme;
use schemes::BigInt;

/// Three quads on the edge 0-1 (non-manifold); each quad has its own `vt` at every corner
/// except that the first two agree along the shared edge when `agree`.
fn quad_book(agree: bool) -> PolygonMesh {
    let p = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::Y,
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::NEG_Y,
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::Z,
    ];
    let mut mesh = PolygonMesh::from_faces(p, [[0, 1, 2, 3], [1, 0, 5, 4], [0, 1, 6, 7]]);
    let coords: Vec<DVec2> = (0..12)
        .map(|i| DVec2::new(0.1 * f64::from(i), 0.05 * f64::from(i * i % 7)))
        .collect();
    let corners = if agree {
        vec![0, 1, 2, 3, 1, 0, 6, 7, 8, 9, 10, 11]
    } else {
        vec![0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]
    };
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("a vt per corner");
    mesh
}

/// A `w` x `h` grid (quads or triangles) whose UV is its position's `x, y`, with a seam along
/// the column `x = seam` when `seam` is given (the faces right of it use their own `vt`,
/// offset by 10 in `u`).
fn grid(w: u32, h: u32, triangles: bool, seam: Option<u32>) -> PolygonMesh {
    let mut mesh = if triangles {
        shapes::grid(w, h)
    } else {
        shapes::quad_grid(w, h)
    }
    .expect("a grid");
    let n = mesh.n_vertices() as u32;
    let mut coords: Vec<DVec2> = mesh.positions.iter().map(|p| p.truncate()).collect();
    coords.extend(
        mesh.positions
            .iter()
            .map(|p| p.truncate() + DVec2::X * 10.0),
    );
    let positions = mesh.positions.clone();
    let mut corners = Vec::new();
    for face in mesh.faces() {
        let centre = face.iter().fold(DVec2::ZERO, |acc, &v| {
            acc + positions[v as usize].truncate()
        }) / face.len() as f64;
        let right = seam.is_some_and(|s| centre.x > positions[s as usize].x);
        for &v in face {
            corners.push(if right { n + v } else { v });
        }
    }
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("a vt per corner");
    mesh
}

/// The distinct values the corners of `mesh` use.
fn used_values(mesh: &PolygonMesh) -> u64 {
    let uvs = mesh.uvs().expect("UVs written");
    (uvs.coords().len() - uvs.unreferenced()) as u64
}

fn check_counts(mesh: &PolygonMesh, rule: Rule, what: &str) {
    let layout = mesh.uv_layout().expect("a layout");
    let uv = stats::uv_counts(mesh).expect("uv counts");
    assert_eq!(uv.split_values, 0, "{what}: no sibling values");
    let scheme = uv_scheme(rule).expect("a UV scheme");
    let opts = SubdivideOptions::default().with_uvs(&layout);
    for level in 1..=3 {
        let out = subdivide_polygons(mesh, rule, level, &opts).expect("subdivides");
        let predicted = scheme.values_at(&uv, u64::from(level)).expect("predicted");
        assert_eq!(
            BigInt::from(used_values(&out)),
            predicted,
            "{what}, {rule}, level {level}"
        );
        assert_eq!(out.uvs().unwrap().corners().len(), out.n_corners());
        // Without UVs asked, the same mesh, no UVs.
        let bare = subdivide_polygons(mesh, rule, level, &SubdivideOptions::default()).unwrap();
        assert!(bare.uvs().is_none());
        assert_eq!(bare.positions, out.positions);
        assert_eq!(bare.face_indices(), out.face_indices());
    }
}

#[test]
fn uv_polygons_nonmanifold_book_counts() {
    for agree in [false, true] {
        let book = quad_book(agree);
        assert!(stats::face_list_counts(&book).nonmanifold_edges > 0);
        check_counts(
            &book,
            Rule::CatmullClark,
            &format!("quad book agree={agree}"),
        );
    }
    // The triangles of a book: three on one edge.
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y];
    let mut tri = PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    let coords = (0..9)
        .map(|i| DVec2::new(f64::from(i), 0.5 * f64::from(i % 3)))
        .collect();
    tri.set_uvs(Some(
        Uvs::new(coords, vec![0, 1, 2, 1, 0, 3, 4, 5, 6]).unwrap(),
    ))
    .unwrap();
    for rule in [Rule::Loop, Rule::Midpoint, Rule::TriSplit(3)] {
        check_counts(&tri, rule, "triangle book");
    }
}

#[test]
fn uv_polygons_grids_with_seams_counts() {
    for seam in [None, Some(2)] {
        check_counts(&grid(4, 3, false, seam), Rule::CatmullClark, "quad grid");
        for rule in [Rule::Loop, Rule::TriSplit(2), Rule::TriSplit(3)] {
            check_counts(&grid(4, 3, true, seam), rule, "triangle grid");
        }
    }
}

/// On a planar grid whose UV is its position, linear refinement puts every child value
/// where its child vertex is (midpoints, centroids, points on the flat triangles).
#[test]
fn uv_polygons_values_follow_positions() {
    for (mesh, rules) in [
        (grid(3, 2, false, None), vec![Rule::CatmullClark]),
        (
            grid(3, 2, true, None),
            vec![Rule::Loop, Rule::TriSplit(3), Rule::TriSplit(4)],
        ),
    ] {
        let layout = mesh.uv_layout().unwrap();
        let opts = SubdivideOptions::default().with_uvs(&layout);
        for rule in rules {
            let out = subdivide_polygons(&mesh, rule, 2, &opts).unwrap();
            let uvs = out.uvs().unwrap();
            for (&v, &t) in out.face_indices().iter().zip(uvs.corners()) {
                let p = out.positions[v as usize].truncate();
                let uv = uvs.coords()[t as usize];
                assert!((p - uv).length() < 1e-12, "{rule}: {p} vs {uv}");
            }
        }
    }
}

/// A seam keeps the two sides' values apart: the corners right of the seam keep the offset.
#[test]
fn uv_polygons_seam_sides_stay_apart() {
    let mesh = grid(4, 2, false, Some(2));
    let layout = mesh.uv_layout().unwrap();
    let out = subdivide_polygons(
        &mesh,
        Rule::CatmullClark,
        2,
        &SubdivideOptions::default().with_uvs(&layout),
    )
    .unwrap();
    let uvs = out.uvs().unwrap();
    for (f, face) in out.faces().enumerate() {
        let start = out.face_offsets()[f];
        let centre = face
            .iter()
            .map(|&v| out.positions[v as usize].x)
            .sum::<f64>()
            / 4.0;
        let offset = if centre > 2.0 { 10.0 } else { 0.0 };
        for (k, &v) in face.iter().enumerate() {
            let uv = uvs.coords()[uvs.corners()[start + k] as usize];
            let p = out.positions[v as usize].truncate();
            assert!((uv - p - DVec2::X * offset).length() < 1e-12, "face {f}");
        }
    }
}

/// With holes the written faces carry their values alone (renumbered), counted by the layout
/// of the written faces: a non-manifold book and grids with a seam.
#[test]
fn uv_polygons_holes_write_the_written_faces_values() {
    for (mesh, rule, hole) in [
        (quad_book(false), Rule::CatmullClark, 1),
        (grid(4, 3, false, Some(2)), Rule::CatmullClark, 5),
        (grid(4, 3, true, Some(2)), Rule::TriSplit(3), 7),
    ] {
        let holes = halfedge::holes::HoleSet::new(mesh.n_faces(), [hole]).unwrap();
        let layout = mesh.uv_layout().unwrap();
        let opts = SubdivideOptions::default()
            .with_uvs(&layout)
            .with_holes(&holes);
        let uv = holes.written_uv_counts(&mesh).expect("uv counts");
        assert_eq!(uv.split_values, 0);
        let scheme = uv_scheme(rule).unwrap();
        for level in 1..=2 {
            let out = subdivide_polygons(&mesh, rule, level, &opts).unwrap();
            let uvs = out.uvs().expect("UVs written");
            assert_eq!(uvs.unreferenced(), 0);
            assert_eq!(uvs.corners().len(), out.n_corners());
            assert_eq!(
                BigInt::from(used_values(&out)),
                scheme.values_at(&uv, u64::from(level)).unwrap(),
                "{rule}, level {level}"
            );
        }
    }
}
