//! The index-based half-edge mesh: typed `u32` handles into parallel arrays.
//!
//! Layout (after pmp-library's `SurfaceMesh`): half-edges are stored in pairs, so the twin of
//! half-edge `h` is `h ^ 1`, its edge is `h >> 1`, and edge `e` has half-edges `2e` and `2e + 1`.
//! There is no twin array and no edge array. A boundary half-edge has no face (stored as the
//! sentinel `u32::MAX`, returned as `None`); boundary half-edges are linked by `next`/`prev`
//! around each hole, so every `next` cycle is either a face or a boundary loop.

use glam::DVec3;

/// Sentinel stored for "no element" (a boundary half-edge's face, an isolated vertex's half-edge).
pub(crate) const INVALID: u32 = u32::MAX;

macro_rules! handle {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name(pub u32);

        impl $name {
            /// The index into the mesh's arrays.
            #[inline]
            pub fn idx(self) -> usize {
                self.0 as usize
            }
        }
    };
}

handle!(
    /// A vertex of a [`HalfEdgeMesh`].
    VertexId
);
handle!(
    /// A half-edge of a [`HalfEdgeMesh`]: directed, pointing to its target vertex.
    HalfedgeId
);
handle!(
    /// An undirected edge of a [`HalfEdgeMesh`]: the pair of half-edges `2e`, `2e + 1`.
    EdgeId
);
handle!(
    /// A face of a [`HalfEdgeMesh`].
    FaceId
);

impl HalfedgeId {
    /// The opposite half-edge of the same edge.
    #[inline]
    pub fn twin(self) -> HalfedgeId {
        HalfedgeId(self.0 ^ 1)
    }

    /// The undirected edge this half-edge belongs to.
    #[inline]
    pub fn edge(self) -> EdgeId {
        EdgeId(self.0 >> 1)
    }
}

impl EdgeId {
    /// Half-edge `i` (0 or 1) of this edge.
    #[inline]
    pub fn halfedge(self, i: u32) -> HalfedgeId {
        HalfedgeId((self.0 << 1) | (i & 1))
    }
}

/// A validated, oriented, manifold polygon mesh (boundary allowed) with vertex positions.
///
/// Every `HalfEdgeMesh` satisfies, by construction: every face has at least 3 distinct
/// vertices, every edge has one or two faces, and the faces around each vertex form one fan,
/// consistently oriented; every `next` cycle closes within the half-edge count.
#[derive(Clone, Debug, Default)]
pub struct HalfEdgeMesh {
    /// Vertex positions, indexed by [`VertexId`].
    pub(crate) positions: Vec<DVec3>,
    /// One outgoing half-edge per vertex; for a boundary vertex, the outgoing boundary
    /// half-edge (whose face is `INVALID`).
    pub(crate) vertex_halfedge: Vec<u32>,
    /// Target vertex of each half-edge.
    pub(crate) halfedge_vertex: Vec<u32>,
    /// Face of each half-edge, `INVALID` on the boundary.
    pub(crate) halfedge_face: Vec<u32>,
    /// Next half-edge around the face (or boundary loop).
    pub(crate) halfedge_next: Vec<u32>,
    /// Previous half-edge around the face (or boundary loop).
    pub(crate) halfedge_prev: Vec<u32>,
    /// One half-edge of each face.
    pub(crate) face_halfedge: Vec<u32>,
}
