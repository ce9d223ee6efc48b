//! The index-based half-edge mesh: typed `u32` handles into parallel arrays.
//!
//! Layout (after pmp-library's `SurfaceMesh`): half-edges are stored in pairs, so the twin of
//! half-edge `h` is `h ^ 1`, its edge is `h >> 1`, and edge `e` has half-edges `2e` and `2e + 1`.
//! There is no twin array and no edge array. A boundary half-edge has no face (stored as the
//! sentinel `u32::MAX`, returned as `None`); boundary half-edges are linked by `next`/`prev`
//! around each hole, so every `next` cycle is either a face or a boundary loop.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `build.rs` and `mesh.rs`: `HalfEdgeMesh` stores typed `u32` handles in parallel arrays;
//! half-edges come in pairs, so the twin of `h` is `h ^ 1` and its edge is `h >> 1` (as in
//! pmp-library). Construction validates once (range, degenerate and duplicate faces, non-manifold
//! edges and vertices, orientation) and reports the first problem with the face it names, so
//! circulators never spin.

use glam::DVec3;
use schemes::MeshCounts;

use crate::descriptor::Descriptor;
use crate::error::{Error, Result};

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
/// consistently oriented; every `next` cycle closes within the half-edge count. Build one
/// with [`HalfEdgeMesh::try_from_polygons`] or `HalfEdgeMesh::try_from(&PolygonMesh)`.
///
/// # Panics
///
/// Accessors and circulators panic when given a handle that does not belong to this mesh
/// (index out of range): that is a bug in the caller, never a property of the input.
///
/// # Example
///
/// ```
/// use halfedge::{shapes, HalfEdgeMesh};
///
/// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
/// assert_eq!((cube.n_vertices(), cube.n_edges(), cube.n_halfedges(), cube.n_faces()), (8, 12, 24, 6));
/// for h in cube.halfedges() {
///     assert_eq!(cube.from_vertex(cube.next(h)), cube.to_vertex(h));
///     assert_eq!(cube.to_vertex(h.twin()), cube.from_vertex(h));
///     assert!(cube.face(h).is_some());
/// }
/// assert!(cube.vertices().all(|v| cube.valence(v) == 3));
/// cube.check_invariants()?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
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
    /// Vertices of the source face list that no face referenced (dropped on construction).
    pub(crate) unreferenced_vertices: u64,
    /// What the mesh's file says about its subdivision (`TryFrom<&PolygonMesh>`).
    pub(crate) descriptor: Option<Box<Descriptor>>,
    /// The counts of a mesh built from a face list, counted by its build
    /// ([`HalfEdgeMesh::counts`] returns them).
    pub(crate) counts: Option<Box<MeshCounts>>,
}

impl HalfEdgeMesh {
    /// What the mesh's file says about its subdivision: creases, corners, holes, options and
    /// UVs ([`crate::descriptor`]), which every subdivision of the mesh honours by default;
    /// `None` for a mesh built without them (a subdivided level, a generated shape, a file
    /// without tags or UVs, [`HalfEdgeMesh::try_from_polygon_mesh`]).
    pub fn descriptor(&self) -> Option<&Descriptor> {
        self.descriptor.as_deref()
    }

    /// Replaces what the mesh carries ([`HalfEdgeMesh::descriptor`]); a descriptor of another
    /// mesh is refused when a subdivision reads it ([`Error::SharpnessMismatch`],
    /// [`Error::HoleOutOfRange`], [`Error::UvLayoutMismatch`]).
    ///
    pub fn set_descriptor(&mut self, descriptor: Option<Descriptor>) {
        self.descriptor = descriptor.map(Box::new);
    }

    /// Keeps `counts` as the mesh's [`HalfEdgeMesh::counts`]: those of its structure, counted
    /// as it was built.
    pub(crate) fn set_counts(&mut self, counts: MeshCounts) {
        self.counts = Some(Box::new(counts));
    }

    /// Assembles a mesh from its arrays without validating them (for subdivision output, which
    /// is correct by construction). Debug builds check [`HalfEdgeMesh::check_invariants`].
    ///
    /// `halfedges` holds the four half-edge arrays: target vertex, face, next, prev.
    ///
    /// # Panics
    ///
    /// In debug builds, when the arrays break an invariant (a bug in the caller).
    pub(crate) fn from_raw_parts(
        positions: Vec<DVec3>,
        vertex_halfedge: Vec<u32>,
        halfedges: [Vec<u32>; 4],
        face_halfedge: Vec<u32>,
    ) -> HalfEdgeMesh {
        let [halfedge_vertex, halfedge_face, halfedge_next, halfedge_prev] = halfedges;
        let mesh = HalfEdgeMesh {
            positions,
            vertex_halfedge,
            halfedge_vertex,
            halfedge_face,
            halfedge_next,
            halfedge_prev,
            face_halfedge,
            unreferenced_vertices: 0,
            descriptor: None,
            counts: None,
        };
        debug_assert!(
            mesh.check_invariants().is_ok(),
            "from_raw_parts: {}",
            mesh.check_invariants()
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default()
        );
        mesh
    }

    /// Number of vertices (every vertex is used by at least one face).
    #[inline]
    pub fn n_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of undirected edges (half the number of half-edges).
    #[inline]
    pub fn n_edges(&self) -> usize {
        self.halfedge_vertex.len() / 2
    }

    /// Number of half-edges, boundary half-edges included (twice the number of edges).
    #[inline]
    pub fn n_halfedges(&self) -> usize {
        self.halfedge_vertex.len()
    }

    /// Number of faces.
    #[inline]
    pub fn n_faces(&self) -> usize {
        self.face_halfedge.len()
    }

    /// How many vertices of the source face list no face referenced; they were dropped when
    /// the mesh was built (0 for generated and subdivided meshes).
    #[inline]
    pub fn unreferenced_vertices(&self) -> u64 {
        self.unreferenced_vertices
    }

    /// The position of vertex `v`.
    ///
    /// # Panics
    ///
    /// When `v` is not a vertex of this mesh.
    #[inline]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.idx()]
    }

    /// All vertex positions, indexed by [`VertexId`].
    #[inline]
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// Iterator over all vertex handles.
    pub fn vertices(&self) -> impl ExactSizeIterator<Item = VertexId> + '_ {
        (0..self.positions.len() as u32).map(VertexId)
    }

    /// Iterator over all half-edge handles.
    pub fn halfedges(&self) -> impl ExactSizeIterator<Item = HalfedgeId> + '_ {
        (0..self.halfedge_vertex.len() as u32).map(HalfedgeId)
    }

    /// Iterator over all edge handles.
    pub fn edges(&self) -> impl ExactSizeIterator<Item = EdgeId> + '_ {
        (0..(self.halfedge_vertex.len() / 2) as u32).map(EdgeId)
    }

    /// Iterator over all face handles.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = FaceId> + '_ {
        (0..self.face_halfedge.len() as u32).map(FaceId)
    }

    /// The vertex half-edge `h` points to.
    #[inline]
    pub fn to_vertex(&self, h: HalfedgeId) -> VertexId {
        VertexId(self.halfedge_vertex[h.idx()])
    }

    /// The vertex half-edge `h` starts from (the target of its twin).
    #[inline]
    pub fn from_vertex(&self, h: HalfedgeId) -> VertexId {
        VertexId(self.halfedge_vertex[h.twin().idx()])
    }

    /// The next half-edge around the face (or boundary loop) of `h`.
    #[inline]
    pub fn next(&self, h: HalfedgeId) -> HalfedgeId {
        HalfedgeId(self.halfedge_next[h.idx()])
    }

    /// The previous half-edge around the face (or boundary loop) of `h`.
    #[inline]
    pub fn prev(&self, h: HalfedgeId) -> HalfedgeId {
        HalfedgeId(self.halfedge_prev[h.idx()])
    }

    /// The opposite half-edge of `h` (same as [`HalfedgeId::twin`]).
    #[inline]
    pub fn twin(&self, h: HalfedgeId) -> HalfedgeId {
        h.twin()
    }

    /// The face of half-edge `h`, `None` for a boundary half-edge.
    #[inline]
    pub fn face(&self, h: HalfedgeId) -> Option<FaceId> {
        let f = self.halfedge_face[h.idx()];
        (f != INVALID).then_some(FaceId(f))
    }

    /// Whether `h` is a boundary half-edge (it has no face).
    #[inline]
    pub fn is_boundary(&self, h: HalfedgeId) -> bool {
        self.halfedge_face[h.idx()] == INVALID
    }

    /// Whether edge `e` is on the boundary (one of its half-edges has no face).
    #[inline]
    pub fn is_boundary_edge(&self, e: EdgeId) -> bool {
        self.is_boundary(e.halfedge(0)) || self.is_boundary(e.halfedge(1))
    }

    /// One outgoing half-edge of `v`; for a boundary vertex, its outgoing boundary half-edge.
    #[inline]
    pub fn vertex_halfedge(&self, v: VertexId) -> HalfedgeId {
        HalfedgeId(self.vertex_halfedge[v.idx()])
    }

    /// One half-edge of face `f`: the one from the face's first vertex to its second.
    #[inline]
    pub fn face_halfedge(&self, f: FaceId) -> HalfedgeId {
        HalfedgeId(self.face_halfedge[f.idx()])
    }

    /// Whether `v` lies on the boundary.
    #[inline]
    pub fn is_boundary_vertex(&self, v: VertexId) -> bool {
        self.is_boundary(self.vertex_halfedge(v))
    }

    /// The outgoing half-edges of `v`, counterclockwise (seen from outside, with
    /// counterclockwise faces), starting at [`HalfEdgeMesh::vertex_halfedge`]: for a boundary
    /// vertex the outgoing boundary half-edge comes first, then the half-edges in the faces
    /// from the one beside the incoming boundary edge to the one beside the outgoing boundary
    /// edge.
    pub fn vertex_outgoing_halfedges(&self, v: VertexId) -> VertexOutgoingHalfedges<'_> {
        let start = self.vertex_halfedge(v);
        VertexOutgoingHalfedges {
            mesh: self,
            start,
            current: Some(start),
        }
    }

    /// The number of edges at `v`.
    pub fn valence(&self, v: VertexId) -> usize {
        self.vertex_outgoing_halfedges(v).count()
    }

    /// The half-edges of face `f` in order, starting at [`HalfEdgeMesh::face_halfedge`].
    pub fn face_halfedges(&self, f: FaceId) -> FaceHalfedges<'_> {
        let start = self.face_halfedge(f);
        FaceHalfedges {
            mesh: self,
            start,
            current: Some(start),
        }
    }

    /// The vertices of face `f` in order (the order of the source face list).
    pub fn face_vertices(&self, f: FaceId) -> impl Iterator<Item = VertexId> + '_ {
        self.face_halfedges(f).map(|h| self.from_vertex(h))
    }

    /// The number of vertices (and edges) of face `f`.
    pub fn face_degree(&self, f: FaceId) -> usize {
        self.face_halfedges(f).count()
    }

    /// Whether every face is a triangle.
    pub fn is_triangle_mesh(&self) -> bool {
        self.faces().all(|f| self.face_degree(f) == 3)
    }

    /// Whether every face is a quad.
    pub fn is_quad_mesh(&self) -> bool {
        self.faces().all(|f| self.face_degree(f) == 4)
    }

    /// Whether the mesh has no boundary.
    pub fn is_closed(&self) -> bool {
        self.halfedge_face.iter().all(|&f| f != INVALID)
    }

    /// Checks every structural invariant of the layout: array lengths, indices in range,
    /// `next`/`prev` inverse to each other and consistent with the vertices, every cycle closing,
    /// faces of at least 3 distinct vertices, one fan per vertex (at most one outgoing boundary
    /// half-edge, which is the vertex's half-edge), no unused vertex, no two edges joining the
    /// same pair of vertices.
    ///
    /// Meshes built by this crate always pass; tests use this to check subdivision output.
    ///
    /// # Errors
    ///
    /// [`Error::BrokenInvariant`] describing the first violation found.
    pub fn check_invariants(&self) -> Result<()> {
        let broken = |what: String| Err(Error::BrokenInvariant { what });
        let nv = self.positions.len();
        let nh = self.halfedge_vertex.len();
        let nf = self.face_halfedge.len();
        if self.vertex_halfedge.len() != nv {
            return broken(format!(
                "{} vertex half-edges for {nv} vertices",
                self.vertex_halfedge.len()
            ));
        }
        if nh % 2 != 0 {
            return broken(format!("odd number of half-edges ({nh})"));
        }
        for (name, len) in [
            ("face", self.halfedge_face.len()),
            ("next", self.halfedge_next.len()),
            ("prev", self.halfedge_prev.len()),
        ] {
            if len != nh {
                return broken(format!(
                    "{len} half-edge {name} entries for {nh} half-edges"
                ));
            }
        }
        if u32::try_from(nh).is_err() || u32::try_from(nv).is_err() || u32::try_from(nf).is_err() {
            return broken("more elements than u32 handles can address".to_string());
        }
        for h in 0..nh {
            let (v, f, n, p) = (
                self.halfedge_vertex[h],
                self.halfedge_face[h],
                self.halfedge_next[h],
                self.halfedge_prev[h],
            );
            if v as usize >= nv {
                return broken(format!("half-edge {h} points to vertex {v} of {nv}"));
            }
            if f != INVALID && f as usize >= nf {
                return broken(format!("half-edge {h} has face {f} of {nf}"));
            }
            if n as usize >= nh || p as usize >= nh {
                return broken(format!("half-edge {h} has next {n} / prev {p} of {nh}"));
            }
            if self.halfedge_prev[n as usize] as usize != h {
                return broken(format!("prev(next({h})) != {h}"));
            }
            if self.halfedge_next[p as usize] as usize != h {
                return broken(format!("next(prev({h})) != {h}"));
            }
            if self.halfedge_face[n as usize] != f {
                return broken(format!(
                    "half-edge {h} and its next {n} have different faces"
                ));
            }
            if self.halfedge_vertex[n as usize ^ 1] != v {
                return broken(format!(
                    "half-edge {h} ends at vertex {v} but its next {n} starts elsewhere"
                ));
            }
            if v == self.halfedge_vertex[h ^ 1] {
                return broken(format!("half-edge {h} is a loop at vertex {v}"));
            }
            if f == INVALID && self.halfedge_face[h ^ 1] == INVALID {
                return broken(format!("edge {} has no face", h >> 1));
            }
        }
        // Faces: every face half-edge leads around a cycle of >= 3 distinct vertices, each
        // half-edge of a face is visited once.
        let mut seen = vec![false; nh];
        let mut face_vertex_mark = vec![u32::MAX; nv];
        for f in 0..nf {
            let start = self.face_halfedge[f];
            if start as usize >= nh || self.halfedge_face[start as usize] as usize != f {
                return broken(format!("face {f} has half-edge {start} of another face"));
            }
            let mut h = start as usize;
            let mut degree = 0usize;
            loop {
                if seen[h] {
                    return broken(format!("face {f}: half-edge {h} visited twice"));
                }
                seen[h] = true;
                let v = self.halfedge_vertex[h] as usize;
                if face_vertex_mark[v] == f as u32 {
                    return broken(format!("face {f} repeats vertex {v}"));
                }
                face_vertex_mark[v] = f as u32;
                degree += 1;
                h = self.halfedge_next[h] as usize;
                if h == start as usize {
                    break;
                }
                if degree > nh {
                    return broken(format!("face {f}: next cycle does not close"));
                }
            }
            if degree < 3 {
                return broken(format!("face {f} has {degree} vertices"));
            }
        }
        for (h, (&f, &seen)) in self.halfedge_face.iter().zip(&seen).enumerate() {
            if f != INVALID && !seen {
                return broken(format!(
                    "half-edge {h} claims a face whose cycle does not contain it"
                ));
            }
        }
        // Vertices: the rotation around each vertex visits all its outgoing half-edges, with
        // at most one boundary half-edge (the vertex's own).
        let mut visited = 0usize;
        let mut neighbour_mark = vec![u32::MAX; nv];
        for v in 0..nv {
            let start = self.vertex_halfedge[v];
            if start as usize >= nh {
                return broken(format!("vertex {v} has no half-edge"));
            }
            if self.halfedge_vertex[start as usize ^ 1] as usize != v {
                return broken(format!(
                    "vertex {v}: its half-edge {start} does not start there"
                ));
            }
            let mut h = start as usize;
            let mut boundary = 0usize;
            loop {
                visited += 1;
                if visited > nh {
                    return broken(format!("vertex {v}: rotation does not close"));
                }
                if self.halfedge_face[h] == INVALID {
                    boundary += 1;
                }
                let w = self.halfedge_vertex[h] as usize;
                if neighbour_mark[w] == v as u32 {
                    return broken(format!("two edges join vertices {v} and {w}"));
                }
                neighbour_mark[w] = v as u32;
                h = self.halfedge_prev[h] as usize ^ 1;
                if h == start as usize {
                    break;
                }
            }
            if boundary > 1 {
                return broken(format!(
                    "vertex {v} has {boundary} outgoing boundary half-edges"
                ));
            }
            if boundary == 1 && self.halfedge_face[start as usize] != INVALID {
                return broken(format!(
                    "boundary vertex {v}: its half-edge is not on the boundary"
                ));
            }
        }
        if visited != nh {
            return broken(format!(
                "the vertex rotations visit {visited} of {nh} half-edges (a vertex with several fans)"
            ));
        }
        Ok(())
    }
}

/// Iterator over the outgoing half-edges of a vertex; see
/// [`HalfEdgeMesh::vertex_outgoing_halfedges`].
#[derive(Clone, Debug)]
pub struct VertexOutgoingHalfedges<'a> {
    mesh: &'a HalfEdgeMesh,
    start: HalfedgeId,
    current: Option<HalfedgeId>,
}

impl Iterator for VertexOutgoingHalfedges<'_> {
    type Item = HalfedgeId;

    #[inline]
    fn next(&mut self) -> Option<HalfedgeId> {
        let h = self.current?;
        let next = self.mesh.prev(h).twin();
        self.current = (next != self.start).then_some(next);
        Some(h)
    }
}

/// Iterator over the half-edges of a face; see [`HalfEdgeMesh::face_halfedges`].
#[derive(Clone, Debug)]
pub struct FaceHalfedges<'a> {
    mesh: &'a HalfEdgeMesh,
    start: HalfedgeId,
    current: Option<HalfedgeId>,
}

impl Iterator for FaceHalfedges<'_> {
    type Item = HalfedgeId;

    #[inline]
    fn next(&mut self) -> Option<HalfedgeId> {
        let h = self.current?;
        let next = self.mesh.next(h);
        self.current = (next != self.start).then_some(next);
        Some(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn circulators_of_a_quad_grid() {
        // 2x1 quad grid: vertices 0 1 2 (bottom row), 3 4 5 (top row).
        let mesh = HalfEdgeMesh::try_from(&shapes::quad_grid(2, 1).expect("grid")).expect("valid");
        assert_eq!(
            (
                mesh.n_vertices(),
                mesh.n_edges(),
                mesh.n_halfedges(),
                mesh.n_faces()
            ),
            (6, 7, 14, 2)
        );
        let f1: Vec<u32> = mesh.face_vertices(FaceId(1)).map(|v| v.0).collect();
        assert_eq!(f1, [1, 2, 5, 4]);
        assert_eq!(mesh.face_degree(FaceId(0)), 4);
        // Vertex 1 (bottom middle) is on the boundary with valence 3; its outgoing half-edges
        // start with the boundary one (to vertex 2: the boundary runs clockwise, 0 <- 1 <- 2
        // seen from +z... i.e. the hole's loop goes 1 -> 0) and then turn counterclockwise.
        let v1 = VertexId(1);
        assert!(mesh.is_boundary_vertex(v1));
        assert_eq!(mesh.valence(v1), 3);
        let out: Vec<(u32, Option<u32>)> = mesh
            .vertex_outgoing_halfedges(v1)
            .map(|h| (mesh.to_vertex(h).0, mesh.face(h).map(|f| f.0)))
            .collect();
        assert_eq!(out, [(0, None), (2, Some(1)), (4, Some(0))]);
        for h in mesh.vertex_outgoing_halfedges(v1) {
            assert_eq!(mesh.from_vertex(h), v1);
            assert_eq!(mesh.next(mesh.prev(h)), h);
            assert_eq!(mesh.twin(h).twin(), h);
            assert_eq!(h.edge(), mesh.twin(h).edge());
            assert_eq!(h.edge().halfedge(h.0 & 1), h);
        }
        // Interior vertices of a closed mesh: valence 5 on the icosahedron, no boundary.
        let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("valid");
        assert!(ico.is_closed() && ico.is_triangle_mesh() && !ico.is_quad_mesh());
        for v in ico.vertices() {
            assert!(!ico.is_boundary_vertex(v));
            assert_eq!(ico.valence(v), 5);
            let faces: Vec<Option<FaceId>> = ico
                .vertex_outgoing_halfedges(v)
                .map(|h| ico.face(h))
                .collect();
            assert!(faces.iter().all(Option::is_some));
        }
        assert_eq!(ico.edges().filter(|&e| ico.is_boundary_edge(e)).count(), 0);
        assert_eq!(ico.halfedges().filter(|&h| ico.is_boundary(h)).count(), 0);
        // The boundary loop of the grid: 6 boundary half-edges linked by next.
        let b = mesh.vertex_halfedge(v1);
        let mut h = b;
        let mut loop_len = 0;
        loop {
            assert!(mesh.is_boundary(h));
            loop_len += 1;
            h = mesh.next(h);
            if h == b {
                break;
            }
        }
        assert_eq!(loop_len, 6);
    }

    #[test]
    fn check_invariants_catches_broken_arrays() {
        let good = HalfEdgeMesh::try_from(&shapes::tetrahedron()).expect("valid");
        assert!(good.check_invariants().is_ok());
        let mut bad = good.clone();
        bad.halfedge_next.swap(0, 1);
        assert!(matches!(
            bad.check_invariants(),
            Err(Error::BrokenInvariant { .. })
        ));
        let mut bad = good.clone();
        bad.vertex_halfedge[0] = bad.vertex_halfedge[1];
        let err = bad.check_invariants().unwrap_err().to_string();
        assert!(err.contains("vertex 0"), "{err}");
        let mut bad = good.clone();
        bad.halfedge_face[3] = 7;
        assert!(bad.check_invariants().is_err());
        let mut bad = good;
        bad.positions.pop();
        assert!(bad.check_invariants().is_err());
    }
}
