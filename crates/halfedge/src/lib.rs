//! Half-edge meshes: OBJ in and out, statistics, real subdivision.
#![deny(missing_docs)]

mod build;
mod error;
pub mod io;
mod mesh;
mod polygon;
pub mod shapes;
pub mod stats;
pub mod subdivide;

pub use crate::error::{Error, FaceVertices, ParseError, Result};
pub use crate::mesh::{
    EdgeId, FaceHalfedges, FaceId, HalfEdgeMesh, HalfedgeId, VertexId, VertexOutgoingHalfedges,
};
pub use crate::polygon::{PolygonFaces, PolygonMesh};
