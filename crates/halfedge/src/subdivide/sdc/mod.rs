//! Creases and corners under Loop and Catmull-Clark, by OpenSubdiv 3.5's `Sdc` rules: the
//! smooth, dart, crease and corner vertex rules, semi-sharp edges and vertices whose
//! sharpness decays level by level (uniformly or by Chaikin's rule), the fractional blending
//! of two rules where a sharpness decays to zero, Catmark's smooth-triangle rule and the
//! vertex boundary interpolation modes.
//!
//! A [`Sharpness`] is a mesh's tags ([`Tags`]) resolved on its edges and vertices; it goes to
//! [`Refinement::new`](crate::Refinement::new) through
//! [`SubdivideOptions::with_sharpness`](super::SubdivideOptions::with_sharpness), with the
//! options in [`SubdivideOptions::subdivision`](super::SubdivideOptions::subdivision).
//!
//! ```
//! use halfedge::refine::Refinement;
//! use halfedge::subdivide::{Sharpness, SubdivideOptions};
//! use halfedge::tags::{CreaseMethod, SubdivisionOptions, Tags, INFINITELY_SHARP};
//! use halfedge::{shapes, HalfEdgeMesh, Rule};
//!
//! let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
//! let mut tags = Tags::default();
//! tags.add_crease(0, 1, INFINITELY_SHARP)?; // a hard edge
//! tags.add_crease(1, 3, 1.5)?; // a semi-sharp one
//! tags.add_corner(7, 2.0)?;
//! let sharpness = Sharpness::from_tags(&cube, &tags)?;
//! assert_eq!(sharpness.n_sharp_edges(), 2);
//!
//! let options = SubdivideOptions::default()
//!     .with_sharpness(&sharpness)
//!     .with_subdivision(SubdivisionOptions::default().with_crease_method(CreaseMethod::Chaikin));
//! let refinement = Refinement::new(&cube, Rule::CatmullClark, 2, &options)?;
//! let base: Vec<[f64; 3]> = cube.positions().iter().map(|p| p.to_array()).collect();
//! let mut out = vec![[0.0; 3]; refinement.n_vertices(2)];
//! refinement.evaluate(&base, &mut out)?;
//! // A sharp corner vertex of sharpness 2 stays where it is for two levels.
//! assert_eq!(out[7], base[7]);
//!
//! // A crease that is not an edge is refused, naming it.
//! let mut bad = Tags::default();
//! bad.add_crease(0, 6, 1.0)?;
//! let err = Sharpness::from_tags(&cube, &bad).unwrap_err();
//! assert_eq!(err.to_string(), "crease (0, 6) is not an edge of the mesh");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # What OpenSubdiv does, and so this module
//!
//! - Boundary edges are infinitely sharp under every boundary mode (`Sdc::Crease::
//!   SharpenBoundaryEdge`). `edge` (`VTX_BOUNDARY_EDGE_ONLY`) stops there;
//!   `edge-and-corner` also makes every boundary vertex of one face an infinitely sharp
//!   corner; `none` computes the same positions as `edge` (OpenSubdiv only tags the faces
//!   around boundary vertices as holes, which changes what is output, not where the vertices
//!   go; holes are not handled here).
//! - Sharpness values are `f32`; each level subtracts 1 from semi-sharp values (the vertex
//!   sharpness always, edges under [`CreaseMethod::Uniform`]) or, for edges under
//!   [`CreaseMethod::Chaikin`], takes 3/4 of the edge's value plus 1/4 of the average of the
//!   other semi-sharp edges at the child's end vertex, less 1. Values of 10 and above are
//!   infinite and stay.
//! - A vertex's rule: corner when the vertex is sharp or has more than two sharp edges, crease
//!   with two, dart with one, smooth with none. The crease mask is `3/4, 1/8, 1/8` along the
//!   two sharp edges, the corner mask keeps the vertex, dart and smooth vertices take the
//!   scheme's smooth mask. When the child's rule differs, the two masks are blended by the
//!   average of the sharpness values that decay to zero (clamped to 1).
//! - An edge's point is the midpoint while both its children are sharp, the smooth point
//!   where the edge is smooth, and a blend of the two weighted by the edge's sharpness
//!   otherwise.
//! - [`TriangleRule::Smooth`] (Catmull-Clark only) weights the face points of an edge next to
//!   a triangle by 0.47 instead of 0.25.
//!
//! The weights are computed in `f64` from the `f32` sharpness values and fractional weights,
//! as OpenSubdiv's `PrimvarRefinerReal<double>` does; positions agree with it to about 1e-15
//! of the bounding box (`tests/opensubdiv.rs`).
//!
//! # The rules layer
//!
//! This module is OpenSubdiv's `Sdc`: rules only, as functions of a vertex's or an edge's
//! neighbourhood, with no mesh and no level (`cargo xtask tidy` refuses a file here that
//! names the topology or the refinement). `crease.rs` is the `f32` sharpness arithmetic
//! (vertex rules, uniform and Chaikin decay, fractional weights), `masks.rs` the vertex and
//! edge masks of Loop and Catmull-Clark, `limit.rs` their limit masks (`ComputeVertexLimitMask`
//! with both tangents, scaled as OpenSubdiv scales them; `refine/limit.rs` applies them),
//! `sharpness.rs` the [`Sharpness`] type. Above it, the
//! topology layer resolves tags on a mesh (`subdivide/sharpness.rs`: [`Sharpness::from_tags`])
//! and the refinement layer applies the rules level by level (`refine/creases/`: each
//! level's `LevelSharpness`, the `LevelBuilder` that walks its topology into a sparse
//! `WeightTable` of the child vertices, the `Creases` a refinement keeps).
//!
//! `Refinement::new` takes a `Sharpness` and `SubdivisionOptions` from `SubdivideOptions`;
//! when they change something on the mesh (`Creases::new` decides), each level keeps its
//! flattened tables (or, for a face-varying channel under `all`, linear ones) and a sparse
//! `WeightTable` of the child vertices whose crease mask differs from the rule's, written over
//! the tables' values (`LevelTable::Overrides`); a level where they are more than half the
//! rows, or the two together exceed the bound of `predicted_bytes_with_creases`, is one dense
//! `WeightTable` instead (Catmull-Clark's face points expanded), except on a level with a face
//! of more than 32 sides (`DENSE_MAX_DEGREE`), where an overriding row names such a face by
//! its child point, so that rows and the guard's bound stay linear in the degree. The next
//! level's sharpness is read off the child's edges by their end vertices. The differential
//! tests hold it to OpenSubdiv on the tagged shared meshes and generated grids
//! (`tests/opensubdiv.rs`); `tests/integration/creases.rs` keeps values recorded from
//! OpenSubdiv for `cargo test` alone.

pub(crate) mod crease;
pub(crate) mod limit;
pub(crate) mod masks;
pub(crate) mod sharpness;

pub(crate) use self::crease::is_infinite;
pub use self::sharpness::Sharpness;

#[cfg(doc)]
use crate::tags::{CreaseMethod, Tags, TriangleRule};
