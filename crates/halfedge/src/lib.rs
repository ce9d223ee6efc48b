//! Half-edge meshes for `subcount`: read real meshes, validate them, count them, subdivide
//! them with every built-in scheme, write them back.
//!
//! - [`io`] reads OBJ and OFF into a [`PolygonMesh`] — the raw face list, polygons kept, every
//!   vertex kept — with errors that name the file and line, and writes OBJ into any `Write`.
//! - [`HalfEdgeMesh`] is the validated, index-based half-edge structure (`u32` handles into
//!   parallel arrays, half-edges stored in pairs, after pmp-library's `SurfaceMesh`). Building
//!   it from a face list checks everything a manifold, oriented surface needs and names the
//!   offending face, vertex or edge: [`Error::RepeatedVertex`], [`Error::NonManifoldEdge`],
//!   [`Error::InconsistentOrientation`], [`Error::NonOrientable`],
//!   [`Error::NonManifoldVertex`], [`Error::DuplicateFace`], ...
//! - [`stats`] gives [`schemes::MeshCounts`] (V, E, IE, BE, NME, F, H, faces by degree,
//!   boundary loops, components, Euler characteristic; and the genus) of any face list,
//!   non-manifold ones included, and of a half-edge mesh, both through
//!   [`schemes::MeshCounts::from_face_list`], and counts every defect of a face list.
//! - [`shapes`] generates base meshes in code (platonic solids, cube, tori of any genus,
//!   icosahedron with holes, grids, a mixed-polygon disk), also by name (`torus:3`).
//! - [`holes`] finds the faces that are holes and what is written around them.
//! - [`tags`] describes creases, corners, holes and OpenSubdiv's subdivision options, typed;
//!   [`io`] reads them from OpenSubdiv's OBJ `t` lines into [`PolygonMesh::tags`].
//! - [`uv`] holds texture coordinates as face-varying data ([`PolygonMesh::uvs`], read from
//!   OBJ `vt`); [`normals`] computes area-weighted vertex normals (written as OBJ `vn` on
//!   request).
//! - [`subdivide`] runs every built-in subdivision scheme for real, allocating its output
//!   exactly from the predicted counts.
//!
//! # Example: load, validate, count
//!
//! ```
//! use halfedge::{io, stats, Error, HalfEdgeMesh};
//!
//! let text = "\
//! v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n
//! f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 4 3 2 1\n";
//! let polygons = io::read_obj_from(text.as_bytes(), "pyramid.obj")?;
//! let mesh = HalfEdgeMesh::try_from(&polygons)?;
//! let counts = mesh.counts();
//! assert_eq!((counts.vertices, counts.edges, counts.faces, counts.corners), (5, 8, 5, 16));
//! assert_eq!((counts.euler_characteristic, mesh.genus()), (2, 0));
//! assert_eq!(stats::face_list_counts(&polygons), counts);
//!
//! // The same pyramid with its base flipped is refused, naming the faces and the edge.
//! let flipped = text.replace("f 4 3 2 1", "f 1 2 3 4");
//! let polygons = io::read_obj_from(flipped.as_bytes(), "pyramid.obj")?;
//! let err = HalfEdgeMesh::try_from(&polygons).unwrap_err();
//! assert!(matches!(err, Error::InconsistentOrientation { .. }));
//! assert_eq!(
//!     err.to_string(),
//!     "faces 0 and 4 both use edge 0 -> 1 in the same direction: inconsistent orientation (flip one of them)"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Example: walk the mesh
//!
//! ```
//! use halfedge::{shapes, HalfEdgeMesh, VertexId};
//!
//! let grid = HalfEdgeMesh::try_from(&shapes::quad_grid(2, 2)?)?;
//! let center = VertexId(4);
//! assert!(!grid.is_boundary_vertex(center));
//! assert_eq!(grid.valence(center), 4);
//! let neighbours: Vec<u32> =
//!     grid.vertex_outgoing_halfedges(center).map(|h| grid.to_vertex(h).0).collect();
//! assert_eq!(neighbours.len(), 4);
//! assert!(grid.faces().all(|f| grid.face_degree(f) == 4));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

/// The builder methods of an options struct, inside its `impl`: each `with_x(field: T)`
/// returns the options with `field` set (to `Some(value)` when written `field: Some(T)`).
macro_rules! with_setters {
    () => {};
    ($(#[$doc:meta])* $with:ident($field:ident: Some($ty:ty)); $($rest:tt)*) => {
        $(#[$doc])*
        pub fn $with(mut self, $field: $ty) -> Self {
            self.$field = Some($field);
            self
        }
        with_setters!($($rest)*);
    };
    ($(#[$doc:meta])* $with:ident($field:ident: $ty:ty); $($rest:tt)*) => {
        $(#[$doc])*
        pub fn $with(mut self, $field: $ty) -> Self {
            self.$field = $field;
            self
        }
        with_setters!($($rest)*);
    };
}

mod build;
pub mod descriptor;
mod error;
pub mod groups;
pub mod holes;
pub mod io;
pub mod memory;
mod mesh;
pub mod normals;
mod polygon;
pub mod shapes;
pub mod stats;
pub mod subdivide;
pub mod tags;
mod text;
pub mod uv;

pub use crate::memory::{BYTES_PER_EDGE, BYTES_PER_FACE, BYTES_PER_VERTEX};

pub use crate::descriptor::Descriptor;
pub use crate::error::{Error, FaceVertices, ParseError, Result};
pub use crate::mesh::{
    EdgeId, FaceHalfedges, FaceId, HalfEdgeMesh, HalfedgeId, VertexId, VertexOutgoingHalfedges,
};
pub use crate::polygon::{
    ColorError, PartialColors, PartsError, PolygonFaces, PolygonMesh, PolygonParts, Uncarried,
};
pub use crate::subdivide::refine::{self, Evaluator, Refinement, Scalar, StencilTable};
pub use crate::subdivide::Rule;

/// The vector types of the public API (`DVec3` positions).
pub use glam;
/// The exact counts of the public API.
pub use num_bigint::{self, BigInt};
/// The counting side: schemes, their matrices and predictions.
pub use schemes;
