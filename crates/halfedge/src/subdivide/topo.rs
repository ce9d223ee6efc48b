//! Raw-index helpers on the input mesh (the hot loops work on `u32` ids, not typed handles).

use glam::DVec3;

use crate::mesh::{HalfEdgeMesh, INVALID};

/// Read-only raw view of a [`HalfEdgeMesh`].
#[derive(Clone, Copy)]
pub(crate) struct Topo<'a> {
    pub(crate) m: &'a HalfEdgeMesh,
}

impl<'a> Topo<'a> {
    pub(crate) fn new(m: &'a HalfEdgeMesh) -> Self {
        Topo { m }
    }
    #[inline]
    pub(crate) fn nv(&self) -> usize {
        self.m.positions.len()
    }
    #[inline]
    pub(crate) fn ne(&self) -> usize {
        self.m.halfedge_vertex.len() / 2
    }
    #[inline]
    pub(crate) fn nf(&self) -> usize {
        self.m.face_halfedge.len()
    }
    #[inline]
    pub(crate) fn pos(&self, v: u32) -> DVec3 {
        self.m.positions[v as usize]
    }
    #[inline]
    pub(crate) fn target(&self, h: u32) -> u32 {
        self.m.halfedge_vertex[h as usize]
    }
    #[inline]
    pub(crate) fn source(&self, h: u32) -> u32 {
        self.m.halfedge_vertex[(h ^ 1) as usize]
    }
    #[inline]
    pub(crate) fn next(&self, h: u32) -> u32 {
        self.m.halfedge_next[h as usize]
    }
    #[inline]
    pub(crate) fn prev(&self, h: u32) -> u32 {
        self.m.halfedge_prev[h as usize]
    }
    #[inline]
    pub(crate) fn face(&self, h: u32) -> u32 {
        self.m.halfedge_face[h as usize]
    }
    #[inline]
    pub(crate) fn is_boundary(&self, h: u32) -> bool {
        self.m.halfedge_face[h as usize] == INVALID
    }
    #[inline]
    pub(crate) fn is_boundary_edge(&self, e: u32) -> bool {
        self.is_boundary(2 * e) || self.is_boundary(2 * e + 1)
    }
    #[inline]
    pub(crate) fn face_halfedge(&self, f: u32) -> u32 {
        self.m.face_halfedge[f as usize]
    }
    #[inline]
    pub(crate) fn vertex_halfedge(&self, v: u32) -> u32 {
        self.m.vertex_halfedge[v as usize]
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
        self.m
            .halfedge_face
            .iter()
            .filter(|&&f| f == INVALID)
            .count()
    }
    /// The first face that is not a triangle, with its degree.
    pub(crate) fn first_non_triangle(&self) -> Option<(u32, usize)> {
        (0..self.nf() as u32)
            .map(|f| (f, self.face_degree(f)))
            .find(|&(_, d)| d != 3)
    }
    /// For each face, the index of its first corner in a face-by-face numbering of the corners
    /// (`F + 1` entries, the last one is `H`, the number of face corners).
    pub(crate) fn corner_offsets(&self) -> Vec<u32> {
        let mut off = Vec::with_capacity(self.nf() + 1);
        let mut acc = 0u32;
        for f in 0..self.nf() as u32 {
            off.push(acc);
            acc += self.face_degree(f) as u32;
        }
        off.push(acc);
        off
    }
}
