//! Raw-index helpers on a level's connectivity (the hot loops work on `u32` ids, not typed
//! handles), for a [`HalfEdgeMesh`] or for the positionless [`Connectivity`] a refinement
//! keeps.

use crate::mesh::{HalfEdgeMesh, INVALID};

/// The half-edge arrays of a level without its positions (what a refinement keeps per level;
/// the layout of [`HalfEdgeMesh`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Connectivity {
    pub(crate) vertex_halfedge: Vec<u32>,
    pub(crate) halfedge_vertex: Vec<u32>,
    pub(crate) halfedge_face: Vec<u32>,
    pub(crate) halfedge_next: Vec<u32>,
    pub(crate) halfedge_prev: Vec<u32>,
    pub(crate) face_halfedge: Vec<u32>,
}

impl Connectivity {
    /// The arrays of `vertex_halfedge`, the four half-edge arrays (target vertex, face, next,
    /// prev) and `face_halfedge`.
    pub(crate) fn from_parts(
        vertex_halfedge: Vec<u32>,
        halfedges: [Vec<u32>; 4],
        face_halfedge: Vec<u32>,
    ) -> Connectivity {
        let [halfedge_vertex, halfedge_face, halfedge_next, halfedge_prev] = halfedges;
        Connectivity {
            vertex_halfedge,
            halfedge_vertex,
            halfedge_face,
            halfedge_next,
            halfedge_prev,
            face_halfedge,
        }
    }

    /// The connectivity of `mesh` (its positions dropped).
    pub(crate) fn from_mesh(mesh: HalfEdgeMesh) -> Connectivity {
        Connectivity {
            vertex_halfedge: mesh.vertex_halfedge,
            halfedge_vertex: mesh.halfedge_vertex,
            halfedge_face: mesh.halfedge_face,
            halfedge_next: mesh.halfedge_next,
            halfedge_prev: mesh.halfedge_prev,
            face_halfedge: mesh.face_halfedge,
        }
    }

    /// A copy of the connectivity of `mesh`.
    pub(crate) fn of_mesh(mesh: &HalfEdgeMesh) -> Connectivity {
        Connectivity {
            vertex_halfedge: mesh.vertex_halfedge.clone(),
            halfedge_vertex: mesh.halfedge_vertex.clone(),
            halfedge_face: mesh.halfedge_face.clone(),
            halfedge_next: mesh.halfedge_next.clone(),
            halfedge_prev: mesh.halfedge_prev.clone(),
            face_halfedge: mesh.face_halfedge.clone(),
        }
    }

    /// The mesh with these arrays and `positions` (one per vertex, checked in debug builds).
    pub(crate) fn with_positions(self, positions: Vec<glam::DVec3>) -> HalfEdgeMesh {
        HalfEdgeMesh::from_raw_parts(
            positions,
            self.vertex_halfedge,
            [
                self.halfedge_vertex,
                self.halfedge_face,
                self.halfedge_next,
                self.halfedge_prev,
            ],
            self.face_halfedge,
        )
    }

    /// Bytes held by the arrays.
    pub(crate) fn bytes(&self) -> usize {
        4 * (self.vertex_halfedge.len() + 4 * self.halfedge_vertex.len() + self.face_halfedge.len())
    }

    pub(crate) fn topo(&self) -> Topo<'_> {
        Topo {
            vertex_halfedge: &self.vertex_halfedge,
            halfedge_vertex: &self.halfedge_vertex,
            halfedge_face: &self.halfedge_face,
            halfedge_next: &self.halfedge_next,
            halfedge_prev: &self.halfedge_prev,
            face_halfedge: &self.face_halfedge,
        }
    }
}

/// Read-only raw view of a level's connectivity.
#[derive(Clone, Copy)]
pub(crate) struct Topo<'a> {
    vertex_halfedge: &'a [u32],
    halfedge_vertex: &'a [u32],
    halfedge_face: &'a [u32],
    halfedge_next: &'a [u32],
    halfedge_prev: &'a [u32],
    face_halfedge: &'a [u32],
}

impl<'a> Topo<'a> {
    pub(crate) fn new(m: &'a HalfEdgeMesh) -> Self {
        Topo {
            vertex_halfedge: &m.vertex_halfedge,
            halfedge_vertex: &m.halfedge_vertex,
            halfedge_face: &m.halfedge_face,
            halfedge_next: &m.halfedge_next,
            halfedge_prev: &m.halfedge_prev,
            face_halfedge: &m.face_halfedge,
        }
    }
    #[inline]
    pub(crate) fn nv(&self) -> usize {
        self.vertex_halfedge.len()
    }
    #[inline]
    pub(crate) fn ne(&self) -> usize {
        self.halfedge_vertex.len() / 2
    }
    #[inline]
    pub(crate) fn nf(&self) -> usize {
        self.face_halfedge.len()
    }
    #[inline]
    pub(crate) fn target(&self, h: u32) -> u32 {
        self.halfedge_vertex[h as usize]
    }
    #[inline]
    pub(crate) fn source(&self, h: u32) -> u32 {
        self.halfedge_vertex[(h ^ 1) as usize]
    }
    #[inline]
    pub(crate) fn next(&self, h: u32) -> u32 {
        self.halfedge_next[h as usize]
    }
    #[inline]
    pub(crate) fn prev(&self, h: u32) -> u32 {
        self.halfedge_prev[h as usize]
    }
    #[inline]
    pub(crate) fn face(&self, h: u32) -> u32 {
        self.halfedge_face[h as usize]
    }
    #[inline]
    pub(crate) fn is_boundary(&self, h: u32) -> bool {
        self.halfedge_face[h as usize] == INVALID
    }
    #[inline]
    pub(crate) fn is_boundary_edge(&self, e: u32) -> bool {
        self.is_boundary(2 * e) || self.is_boundary(2 * e + 1)
    }
    #[inline]
    pub(crate) fn face_halfedge(&self, f: u32) -> u32 {
        self.face_halfedge[f as usize]
    }
    #[inline]
    pub(crate) fn vertex_halfedge(&self, v: u32) -> u32 {
        self.vertex_halfedge[v as usize]
    }
    /// Side `k` (0, 1 or 2) of triangle `f`: its half-edge, the next one, then the previous one.
    #[inline]
    pub(crate) fn triangle_side(&self, f: u32, k: u32) -> u32 {
        let h0 = self.face_halfedge(f);
        match k {
            0 => h0,
            1 => self.next(h0),
            _ => self.prev(h0),
        }
    }
    /// Whether vertex `v` is on the boundary (its half-edge is the outgoing boundary one).
    #[inline]
    pub(crate) fn is_boundary_vertex(&self, v: u32) -> bool {
        self.is_boundary(self.vertex_halfedge(v))
    }
    /// Calls `f` on every outgoing half-edge of `v` (clockwise: `h -> next(twin(h))`), starting
    /// with the vertex's half-edge (the outgoing boundary half-edge on the boundary).
    #[inline]
    pub(crate) fn for_outgoing(&self, v: u32, mut f: impl FnMut(u32)) {
        let start = self.vertex_halfedge(v);
        let mut h = start;
        loop {
            f(h);
            h = self.next(h ^ 1);
            if h == start {
                break;
            }
        }
    }
    /// Calls `f` on every half-edge of face `face`, in order.
    #[inline]
    pub(crate) fn for_face(&self, face: u32, mut f: impl FnMut(u32)) {
        let start = self.face_halfedge(face);
        let mut h = start;
        loop {
            f(h);
            h = self.next(h);
            if h == start {
                break;
            }
        }
    }
    pub(crate) fn valence(&self, v: u32) -> usize {
        let mut n = 0;
        self.for_outgoing(v, |_| n += 1);
        n
    }
    pub(crate) fn face_degree(&self, face: u32) -> usize {
        let mut n = 0;
        self.for_face(face, |_| n += 1);
        n
    }
    /// Number of boundary half-edges (= boundary edges).
    pub(crate) fn boundary_edges(&self) -> usize {
        self.halfedge_face.iter().filter(|&&f| f == INVALID).count()
    }
    /// Whether the level has no boundary.
    pub(crate) fn is_closed(&self) -> bool {
        self.halfedge_face.iter().all(|&f| f != INVALID)
    }
    /// Whether every face is a quad.
    pub(crate) fn is_quad_mesh(&self) -> bool {
        (0..self.nf() as u32).all(|f| self.face_degree(f) == 4)
    }
    /// The first face that is not a triangle, with its degree.
    pub(crate) fn first_non_triangle(&self) -> Option<(u32, usize)> {
        (0..self.nf() as u32)
            .map(|f| (f, self.face_degree(f)))
            .find(|&(_, d)| d != 3)
    }
}
