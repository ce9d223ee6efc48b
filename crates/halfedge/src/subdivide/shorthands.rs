//! One function per rule, each [`subdivide`] with that rule (`loop_subdivide`, ...).

use super::{subdivide, Rule, SubdivideOptions};
use crate::{HalfEdgeMesh, Result};

/// Defines the public shorthands for [`subdivide`] with one rule; the string before the name
/// completes the "As [`subdivide`]" of the errors. (A macro: functions cannot define
/// functions.)
macro_rules! shorthands {
    ($($(#[doc = $doc:literal])* $errors:literal $fn:ident => $rule:expr;)*) => {$(
        $(#[doc = $doc])*
        ///
        /// # Errors
        ///
        #[doc = concat!("As [`subdivide`]", $errors, ".")]
        pub fn $fn(
            mesh: &HalfEdgeMesh,
            levels: u32,
            opts: &SubdivideOptions<'_>,
        ) -> Result<HalfEdgeMesh> {
            subdivide(mesh, $rule, levels, opts)
        }
    )*};
}

shorthands! {
    /// Loop subdivision ([`Rule::Loop`]): Loop's weights, boundary curves as cubic B-splines.
    ///
    /// ```
    /// use halfedge::subdivide::{loop_subdivide, SubdivideOptions};
    /// let grid = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::grid(2, 2)?)?;
    /// let out = loop_subdivide(&grid, 2, &SubdivideOptions::default())?;
    /// assert_eq!(out.n_faces(), 8 * 16);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    " (e.g. a face that is not a triangle)" loop_subdivide => Rule::Loop;

    /// Plain 4:1 split with edge midpoints ([`Rule::Midpoint`]), old vertices kept.
    "" midpoint_subdivide => Rule::Midpoint;

    /// 4:1 split with the edge midpoints projected onto the unit sphere ([`Rule::Icosphere`]).
    "" icosphere_subdivide => Rule::Icosphere;

    /// The modified butterfly scheme ([`Rule::Butterfly`], interpolating; boundary rules in
    /// the module docs).
    "" butterfly_subdivide => Rule::Butterfly;

    /// Catmull-Clark subdivision on any polygon mesh, with boundary rules
    /// ([`Rule::CatmullClark`]).
    ///
    /// ```
    /// use halfedge::subdivide::{catmull_clark_subdivide, SubdivideOptions};
    /// let mixed = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::mixed())?;
    /// let out = catmull_clark_subdivide(&mixed, 1, &SubdivideOptions::default())?;
    /// assert!(out.is_quad_mesh());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    "" catmull_clark_subdivide => Rule::CatmullClark;

    /// Kobbelt's √3 subdivision ([`Rule::Sqrt3`]), with Kobbelt's boundary rule when the mesh
    /// has a boundary.
    "" sqrt3_subdivide => Rule::Sqrt3;

    /// Doo-Sabin subdivision on polygon meshes ([`Rule::DooSabin`]), with Chaikin's boundary
    /// rule when the mesh has a boundary.
    " (an interior vertex of valence below 3)" doo_sabin_subdivide => Rule::DooSabin;

    /// Peters-Reif mid-edge subdivision on polygon meshes ([`Rule::MidEdge`]), with the cubic
    /// B-spline boundary rule when the mesh has a boundary.
    " (an interior vertex of valence below 3)" mid_edge_subdivide => Rule::MidEdge;
}
