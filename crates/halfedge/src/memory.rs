//! How many bytes a [`HalfEdgeMesh`] occupies, exactly and from predicted counts, so that
//! resource guards can refuse a subdivision before it starts.

use crate::{HalfEdgeMesh, PolygonMesh};

/// Bytes per vertex: a `DVec3` position (24) and one outgoing half-edge (`u32`, 4).
pub const BYTES_PER_VERTEX: u64 = 24 + 4;
/// Bytes per edge: two half-edges, each with target vertex, face, next and prev (`u32` each).
pub const BYTES_PER_EDGE: u64 = 2 * 4 * 4;
/// Bytes per face: one half-edge (`u32`).
pub const BYTES_PER_FACE: u64 = 4;

impl HalfEdgeMesh {
    /// The bytes of the arrays of a mesh with `vertices`, `edges` and `faces` elements
    /// (exact for this crate's layout; capacity equals length when preallocated).
    ///
    /// ```
    /// use halfedge::HalfEdgeMesh;
    /// let ico = HalfEdgeMesh::try_from(&halfedge::shapes::icosahedron())?;
    /// assert_eq!(ico.heap_bytes() as u128, HalfEdgeMesh::bytes_for(12, 30, 20));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn bytes_for(vertices: u64, edges: u64, faces: u64) -> u128 {
        u128::from(vertices) * u128::from(BYTES_PER_VERTEX)
            + u128::from(edges) * u128::from(BYTES_PER_EDGE)
            + u128::from(faces) * u128::from(BYTES_PER_FACE)
    }

    /// The bytes this mesh's arrays occupy (their lengths; see [`bytes_for`](Self::bytes_for)).
    pub fn heap_bytes(&self) -> usize {
        self.positions.len() * std::mem::size_of::<glam::DVec3>()
            + (self.vertex_halfedge.len()
                + self.halfedge_vertex.len()
                + self.halfedge_face.len()
                + self.halfedge_next.len()
                + self.halfedge_prev.len()
                + self.face_halfedge.len())
                * std::mem::size_of::<u32>()
    }
}

impl PolygonMesh {
    /// The bytes of the arrays of a face list with `vertices` positions (a `DVec3`, 24 bytes
    /// each), `faces` faces (one `usize` offset each, plus one) and `corners` face corners in
    /// all (a `u32` each), as [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list)
    /// builds it (no file lines).
    ///
    /// ```
    /// use halfedge::PolygonMesh;
    /// let cube = halfedge::shapes::cube();
    /// assert_eq!(cube.heap_bytes() as u128, PolygonMesh::bytes_for(8, 6, 24));
    /// ```
    pub fn bytes_for(vertices: u64, faces: u64, corners: u64) -> u128 {
        u128::from(vertices) * 24
            + (u128::from(faces) + 1) * std::mem::size_of::<usize>() as u128
            + u128::from(corners) * 4
    }

    /// The bytes this face list's arrays occupy (their lengths, file lines included; see
    /// [`bytes_for`](Self::bytes_for)).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(self.positions.as_slice())
            + std::mem::size_of_val(self.face_offsets())
            + std::mem::size_of_val(self.face_indices())
            + self.face_lines_len() * std::mem::size_of::<u64>()
    }
}
