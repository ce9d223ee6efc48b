//! [`MeshCounts`]: the statistics of a mesh that subdivision counting needs.

use std::collections::BTreeMap;

/// The statistics of a polygon mesh, as plain numbers.
///
/// Computed by the `halfedge` crate from a real mesh, or typed in by hand. Every field is a
/// plain count; nothing here is checked for consistency (see [`MeshCounts::check_identities`]
/// ... when implemented by the schemes crate).
///
/// Field names follow the short names used on the command line and in JSON:
/// `V`, `E`, `IE`, `BE`, `NME`, `F`, `H`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshCounts {
    /// `V`: vertices referenced by at least one face.
    pub vertices: u64,
    /// `E`: distinct undirected edges (unordered pairs of consecutive face corners).
    pub edges: u64,
    /// `IE`: edges with exactly two incident faces.
    pub interior_edges: u64,
    /// `BE`: edges with exactly one incident face.
    pub boundary_edges: u64,
    /// `NME`: edges with three or more incident faces (non-manifold edges).
    pub nonmanifold_edges: u64,
    /// `F`: faces.
    pub faces: u64,
    /// `H`: the sum of face degrees (the number of face corners, or half-edges).
    pub corners: u64,
    /// Number of faces of each degree (3 for triangles, 4 for quads, ...).
    pub faces_by_degree: BTreeMap<u32, u64>,
    /// Connected components of the boundary-edge graph (holes of a manifold mesh).
    pub boundary_loops: u64,
    /// Connected components of the mesh (faces joined through shared vertices).
    pub components: u64,
    /// `V - E + F` over referenced vertices.
    pub euler_characteristic: i64,
    /// Vertices in the file that no face references (not counted in `V`).
    pub unreferenced_vertices: u64,
}
