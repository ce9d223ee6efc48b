//! Tags resolved on a mesh's edges and vertices: the constructors of
//! [`Sharpness`] (the topology layer: they look edges up on a [`HalfEdgeMesh`]; the type and
//! the rules that read it are in [`sdc`](crate::subdivide::sdc)).

use crate::mesh::{EdgeId, VertexId};
use crate::subdivide::sdc::sharpness::Sharpness;
use crate::subdivide::topo::Topo;
use crate::tags::Tags;
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result};

/// `v` when a mesh of `vertices` vertices has it, else [`Error::TagVertexOutOfRange`] for the
/// tag kind `what`.
fn tag_vertex(what: &'static str, v: u32, vertices: usize) -> Result<u32> {
    if (v as usize) < vertices {
        Ok(v)
    } else {
        Err(Error::TagVertexOutOfRange {
            what,
            vertex: v,
            vertices,
        })
    }
}

impl Sharpness {
    /// No sharpness on `mesh`: every edge and vertex smooth.
    pub fn smooth(mesh: &HalfEdgeMesh) -> Sharpness {
        Sharpness {
            edges: vec![0.0; mesh.n_edges()],
            vertices: vec![0.0; mesh.n_vertices()],
        }
    }

    /// The creases and corners of `tags` on `mesh`, whose vertex indices are the mesh's (the
    /// file's, when no vertex of the file was dropped for being in no face; else see
    /// [`Sharpness::from_tags_of`]). A later value for the same edge or vertex replaces an
    /// earlier one. Holes and options are not read.
    ///
    /// # Errors
    ///
    /// [`Error::TagVertexOutOfRange`] for a vertex the mesh does not have;
    /// [`Error::CreaseNotAnEdge`] for a crease whose two vertices no edge joins.
    pub fn from_tags(mesh: &HalfEdgeMesh, tags: &Tags) -> Result<Sharpness> {
        Sharpness::resolve(mesh, tags, Some)
    }

    /// As [`Sharpness::from_tags`], for tags numbering the vertices of `source`, the face
    /// list `mesh` was built from (which drops the vertices no face uses, renumbering the
    /// others in order). A corner on a vertex in no face has no effect and is skipped.
    ///
    /// # Errors
    ///
    /// As [`Sharpness::from_tags`] (vertices counted in `source`, a crease on a vertex in no
    /// face is not an edge); [`Error::SharpnessMismatch`] when `mesh` was not built from
    /// `source`.
    pub fn from_tags_of(
        source: &PolygonMesh,
        mesh: &HalfEdgeMesh,
        tags: &Tags,
    ) -> Result<Sharpness> {
        let mut used = vec![false; source.n_vertices()];
        for &v in source.face_indices() {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
        let mut new_of_old = Vec::with_capacity(used.len());
        let mut next = 0u32;
        for &u in &used {
            new_of_old.push(u.then_some(next));
            next += u32::from(u);
        }
        if next as usize != mesh.n_vertices() {
            return Err(Error::SharpnessMismatch {
                edges: mesh.n_edges(),
                vertices: next as usize,
                mesh_edges: mesh.n_edges(),
                mesh_vertices: mesh.n_vertices(),
            });
        }
        let n = source.n_vertices();
        let check = |what: &'static str, v: u32| tag_vertex(what, v, n);
        for c in tags.creases() {
            check("crease", c.a)?;
            check("crease", c.b)?;
            if new_of_old[c.a as usize].is_none() || new_of_old[c.b as usize].is_none() {
                return Err(Error::CreaseNotAnEdge { a: c.a, b: c.b });
            }
        }
        for c in tags.corners() {
            check("corner", c.vertex)?;
        }
        Sharpness::resolve(mesh, tags, |v| new_of_old[v as usize])
    }

    fn resolve(
        mesh: &HalfEdgeMesh,
        tags: &Tags,
        to_mesh: impl Fn(u32) -> Option<u32>,
    ) -> Result<Sharpness> {
        let t = Topo::new(mesh);
        let nv = mesh.n_vertices();
        let mut sharpness = Sharpness::smooth(mesh);
        let in_range = |what: &'static str, v: u32| tag_vertex(what, v, nv);
        for c in tags.creases() {
            let not_an_edge = Error::CreaseNotAnEdge { a: c.a, b: c.b };
            let (Some(a), Some(b)) = (to_mesh(c.a), to_mesh(c.b)) else {
                return Err(not_an_edge);
            };
            let (a, b) = (in_range("crease", a)?, in_range("crease", b)?);
            let mut edge = None;
            t.for_outgoing(a, |h| {
                if t.target(h) == b {
                    edge = Some(h >> 1);
                }
            });
            let Some(e) = edge else {
                return Err(not_an_edge);
            };
            sharpness.edges[e as usize] = c.sharpness;
        }
        for c in tags.corners() {
            if let Some(v) = to_mesh(c.vertex) {
                let v = in_range("corner", v)?;
                sharpness.vertices[v as usize] = c.sharpness;
            }
        }
        Ok(sharpness)
    }

    /// The sharpness of every edge, indexed by [`EdgeId`].
    pub fn edges(&self) -> &[f32] {
        &self.edges
    }

    /// The sharpness of every vertex, indexed by [`VertexId`].
    pub fn vertices(&self) -> &[f32] {
        &self.vertices
    }

    /// The sharpness of edge `e` (0 beyond the mesh).
    pub fn edge(&self, e: EdgeId) -> f32 {
        self.edges.get(e.idx()).copied().unwrap_or(0.0)
    }

    /// The sharpness of vertex `v` (0 beyond the mesh).
    pub fn vertex(&self, v: VertexId) -> f32 {
        self.vertices.get(v.idx()).copied().unwrap_or(0.0)
    }
}
