//! Small meshes built in code, shared by the test modules.

use schemes::MeshCounts;

pub(crate) fn counts(faces: &[&[u32]]) -> MeshCounts {
    MeshCounts::from_polygons(faces).expect("test meshes are valid")
}

/// Tetrahedron: V 4, E 6, F 4.
pub(crate) fn tetrahedron() -> MeshCounts {
    counts(&[&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[2, 0, 3]])
}

/// Octahedron: V 6, E 12, F 8.
pub(crate) fn octahedron() -> MeshCounts {
    counts(&[
        &[0, 2, 4],
        &[2, 1, 4],
        &[1, 3, 4],
        &[3, 0, 4],
        &[2, 0, 5],
        &[1, 2, 5],
        &[3, 1, 5],
        &[0, 3, 5],
    ])
}

/// Icosahedron: V 12, E 30, F 20.
pub(crate) fn icosahedron() -> MeshCounts {
    counts(&[
        &[0, 11, 5],
        &[0, 5, 1],
        &[0, 1, 7],
        &[0, 7, 10],
        &[0, 10, 11],
        &[1, 5, 9],
        &[5, 11, 4],
        &[11, 10, 2],
        &[10, 7, 6],
        &[7, 1, 8],
        &[3, 9, 4],
        &[3, 4, 2],
        &[3, 2, 6],
        &[3, 6, 8],
        &[3, 8, 9],
        &[4, 9, 5],
        &[2, 4, 11],
        &[6, 2, 10],
        &[8, 6, 7],
        &[9, 8, 1],
    ])
}

/// Cube: V 8, E 12, F 6 quads, H 24.
pub(crate) fn cube() -> MeshCounts {
    counts(&[
        &[0, 1, 2, 3],
        &[4, 7, 6, 5],
        &[0, 4, 5, 1],
        &[1, 5, 6, 2],
        &[2, 6, 7, 3],
        &[3, 7, 4, 0],
    ])
}

/// One triangle: V 3, IE 0, BE 3, F 1.
pub(crate) fn triangle() -> MeshCounts {
    counts(&[&[0, 1, 2]])
}

/// One quad: V 4, IE 0, BE 4, F 1, H 4.
pub(crate) fn quad() -> MeshCounts {
    counts(&[&[0, 1, 2, 3]])
}

/// One pentagon: V 5, IE 0, BE 5, F 1, H 5.
pub(crate) fn pentagon() -> MeshCounts {
    counts(&[&[0, 1, 2, 3, 4]])
}

/// An open strip of three quads in a row (a 4 x 2 grid of vertices):
/// V 8, IE 2, BE 8, F 3, H 12.
pub(crate) fn quad_strip() -> MeshCounts {
    counts(&[&[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6]])
}

/// An open strip of four triangles: vertices 0..3 on top, 4..5 below... laid out as
/// (0,3,1), (1,3,4), (1,4,2), (2,4,5): V 6, IE 3, BE 6, F 4.
pub(crate) fn triangle_strip() -> MeshCounts {
    counts(&[&[0, 3, 1], &[1, 3, 4], &[1, 4, 2], &[2, 4, 5]])
}

/// Three triangles on one edge (a "book"): V 5, E 7, NME 1, BE 6, F 3.
pub(crate) fn book() -> MeshCounts {
    counts(&[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4]])
}

/// A cube with one triangle-split face: 5 quads and 2 triangles, closed.
/// V 8, E 13, F 7, H 26.
pub(crate) fn mixed_closed() -> MeshCounts {
    counts(&[
        &[0, 1, 2],
        &[0, 2, 3],
        &[4, 7, 6, 5],
        &[0, 4, 5, 1],
        &[1, 5, 6, 2],
        &[2, 6, 7, 3],
        &[3, 7, 4, 0],
    ])
}
