//! The [`Sharpness`] type, apart from what resolves it on a mesh (`sdc/mod.rs`), so that a
//! mesh can carry one ([`crate::Descriptor`]) without naming the rules that read it.

/// The sharpness of a mesh's edges and vertices (`f32`, as OpenSubdiv's: 0 smooth,
/// [`INFINITELY_SHARP`](crate::tags::INFINITELY_SHARP) and above infinitely sharp), resolved
/// from [`Tags`](crate::tags::Tags) on a [`HalfEdgeMesh`](crate::HalfEdgeMesh) ([module docs](crate::subdivide::sdc)). Holes and the tags' options are
/// not part of it.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Sharpness {
    /// Per edge.
    pub(crate) edges: Vec<f32>,
    /// Per vertex.
    pub(crate) vertices: Vec<f32>,
}

impl Sharpness {
    /// The number of edges with a sharpness above 0.
    pub fn n_sharp_edges(&self) -> usize {
        self.edges.iter().filter(|&&s| s > 0.0).count()
    }

    /// The number of vertices with a sharpness above 0.
    pub fn n_sharp_vertices(&self) -> usize {
        self.vertices.iter().filter(|&&s| s > 0.0).count()
    }

    /// `true` when no edge or vertex is sharp.
    pub fn is_smooth(&self) -> bool {
        self.n_sharp_edges() == 0 && self.n_sharp_vertices() == 0
    }
}
