//! Half-edge meshes: OBJ in and out, statistics, real subdivision.
#![deny(missing_docs)]

mod error;
pub mod io;
mod mesh;
pub mod shapes;
mod stats;
pub mod subdivide;

pub use crate::error::{Error, FaceVertices, ParseError, Result};
pub use crate::mesh::{
    EdgeId, FaceHalfedges, FaceId, HalfEdgeMesh, HalfedgeId, VertexId, VertexOutgoingHalfedges,
};
