//! Sharpness and subdivision options: creases, corners, holes and OpenSubdiv's `Sdc::Options`,
//! as a typed description that a file's tags fill in (OpenSubdiv's OBJ `t` lines) or that one
//! builds in code.
//!
//! The names follow OpenSubdiv 3.5's `Sdc` (`Sdc::Options`, `Sdc::Crease`):
//!
//! | here | OpenSubdiv | command line |
//! |---|---|---|
//! | [`BoundaryInterpolation`] | `VtxBoundaryInterpolation` | `--boundary edge\|edge-and-corner\|none` |
//! | [`FaceVaryingInterpolation`] | `FVarLinearInterpolation` | `--uv-interpolation none\|corners-only\|corners-plus1\|corners-plus2\|boundaries\|all` ([`SubdivideOptions::uvs`](crate::subdivide::SubdivideOptions::uvs), [`refine::face_varying`](crate::refine::face_varying)) |
//! | [`CreaseMethod`] | `CreasingMethod` | `--crease-method uniform\|chaikin` |
//! | [`TriangleRule`] | `TriangleSubdivision` | `--triangle-rule catmark\|smooth` |
//!
//! [`crate::io`] reads OpenSubdiv's OBJ tags into a [`Tags`] on the mesh it returns
//! ([`crate::PolygonMesh::tags`]; the tag grammar is in the `io` docs); in code,
//! [`crate::PolygonMesh::set_tags`] sets them, checked by [`Tags::check_against`]. The options
//! a file's tags set ([`TagOptions`], each `None` where the file says nothing) apply over the
//! defaults or a caller's choice with [`TagOptions::over`], giving the [`SubdivisionOptions`]
//! of a run.
//!
//! Sharpness values are `f32`, as in OpenSubdiv, so that their decay from level to level is
//! computed with the same arithmetic: 0 is smooth, 10 and above ([`INFINITELY_SHARP`]) is
//! infinitely sharp, values between are semi-sharp. The OBJ reader reads a tag's sharpness in
//! `f64` and clamps values above 10 to 10, as OpenSubdiv clamps to `[0, 10]` (the surface is
//! the same: 10 and above is infinitely sharp either way).
//!
//! ```
//! use halfedge::tags::{BoundaryInterpolation, CreaseMethod, Tags};
//!
//! let mut tags = Tags::default();
//! tags.add_crease(0, 1, 2.5)?;
//! tags.add_corner(3, 10.0)?;
//! tags.add_hole(7);
//! tags.options.crease_method = Some(CreaseMethod::Chaikin);
//! assert_eq!(tags.creases().len(), 1);
//! assert_eq!("edge-and-corner".parse::<BoundaryInterpolation>()?, BoundaryInterpolation::EdgeAndCorner);
//! assert!(tags.add_crease(1, 2, f32::NAN).is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of creases, corners, holes and subdivision options as a type (`Tags`, `TagOptions`,
//! `SubdivisionOptions` and their command-line names): `halfedge::tags` (`tags.rs`).

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

/// Sharpness at or above which an edge or vertex is infinitely sharp
/// (`Sdc::Crease::SHARPNESS_INFINITE`).
pub const INFINITELY_SHARP: f32 = 10.0;

/// Generates a fieldless option enum with its command-line names, `FromStr` and `Display`.
macro_rules! named_enum {
    (
        $(#[$meta:meta])*
        $name:ident, $what:literal {
            $($(#[$vmeta:meta])* $variant:ident => $text:literal,)+
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
        pub enum $name {
            $($(#[$vmeta])* $variant,)+
        }

        impl $name {
            /// Every value, in declaration order.
            pub const ALL: &'static [$name] = &[$($name::$variant,)+];

            /// The command-line name.
            pub fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl FromStr for $name {
            type Err = UnknownName;

            fn from_str(s: &str) -> Result<Self, UnknownName> {
                $name::ALL
                    .iter()
                    .copied()
                    .find(|v| v.name() == s)
                    .ok_or_else(|| UnknownName {
                        what: $what,
                        given: s.to_owned(),
                        expected: $name::ALL.iter().map(|v| v.name()).collect(),
                    })
            }
        }
    };
}

named_enum! {
    /// How the boundary of the vertex data is interpolated (`Sdc::Options::VtxBoundaryInterpolation`).
    #[doc = ""]
    #[doc = "The default is [`BoundaryInterpolation::Edge`] (OpenSubdiv's `VTX_BOUNDARY_EDGE_ONLY`)."]
    BoundaryInterpolation, "boundary interpolation" {
        /// Boundary edges are infinitely sharp, corners smooth (`VTX_BOUNDARY_EDGE_ONLY`).
        #[default]
        Edge => "edge",
        /// Boundary edges and valence-2 boundary vertices are infinitely sharp
        /// (`VTX_BOUNDARY_EDGE_AND_CORNER`, USD's default).
        EdgeAndCorner => "edge-and-corner",
        /// No boundary interpolation: the faces on the boundary become holes
        /// (`VTX_BOUNDARY_NONE`).
        None => "none",
    }
}

named_enum! {
    /// How face-varying data (UVs) is linearly interpolated
    /// (`Sdc::Options::FVarLinearInterpolation`); `None` means fully smooth.
    #[doc = ""]
    #[doc = "The default is [`FaceVaryingInterpolation::CornersPlus1`] (USD's and RenderMan's); \
             OpenSubdiv's own `Sdc::Options()` default is `All`."]
    FaceVaryingInterpolation, "face-varying interpolation" {
        /// Smooth everywhere (`FVAR_LINEAR_NONE`).
        None => "none",
        /// Sharpen corners only (`FVAR_LINEAR_CORNERS_ONLY`).
        CornersOnly => "corners-only",
        /// Corners plus junctions (`FVAR_LINEAR_CORNERS_PLUS1`).
        #[default]
        CornersPlus1 => "corners-plus1",
        /// `CornersPlus1` plus darts and concave corners (`FVAR_LINEAR_CORNERS_PLUS2`).
        CornersPlus2 => "corners-plus2",
        /// Linear along boundaries (`FVAR_LINEAR_BOUNDARIES`).
        Boundaries => "boundaries",
        /// Linear everywhere (`FVAR_LINEAR_ALL`).
        All => "all",
    }
}

named_enum! {
    /// How semi-sharp creases decay from level to level (`Sdc::Options::CreasingMethod`).
    CreaseMethod, "crease method" {
        /// Each level subtracts 1 (`CREASE_UNIFORM`).
        #[default]
        Uniform => "uniform",
        /// Chaikin's rule: a child edge's sharpness averages its parent's neighbours
        /// (`CREASE_CHAIKIN`).
        Chaikin => "chaikin",
    }
}

named_enum! {
    /// Catmull-Clark's rule for triangles (`Sdc::Options::TriangleSubdivision`); Loop-family
    /// schemes have no such choice.
    TriangleRule, "triangle rule" {
        /// The ordinary Catmull-Clark rule (`TRI_SUB_CATMARK`).
        #[default]
        Catmark => "catmark",
        /// The modified weights that smooth triangles (`TRI_SUB_SMOOTH`).
        Smooth => "smooth",
    }
}

impl BoundaryInterpolation {
    /// The value of OpenSubdiv's `interpolateboundary` tag: 0 none, 1 edge-and-corner,
    /// 2 edge-only.
    pub fn tag_value(self) -> i64 {
        match self {
            BoundaryInterpolation::None => 0,
            BoundaryInterpolation::EdgeAndCorner => 1,
            BoundaryInterpolation::Edge => 2,
        }
    }

    /// The option an `interpolateboundary` tag value names (`None` outside `0..=2`).
    pub fn from_tag_value(value: i64) -> Option<BoundaryInterpolation> {
        BoundaryInterpolation::ALL
            .iter()
            .copied()
            .find(|b| b.tag_value() == value)
    }
}

impl FaceVaryingInterpolation {
    /// The value of OpenSubdiv's `facevaryinginterpolateboundary` tag: 0 none, 1 corners-only,
    /// 2 corners-plus1, 3 corners-plus2, 4 boundaries, 5 all (the declaration order).
    pub fn tag_value(self) -> i64 {
        FaceVaryingInterpolation::ALL
            .iter()
            .position(|&f| f == self)
            .map_or(0, |i| i as i64)
    }

    /// The option a `facevaryinginterpolateboundary` tag value names (`None` outside `0..=5`).
    pub fn from_tag_value(value: i64) -> Option<FaceVaryingInterpolation> {
        usize::try_from(value)
            .ok()
            .and_then(|i| FaceVaryingInterpolation::ALL.get(i).copied())
    }
}

impl CreaseMethod {
    /// The string of OpenSubdiv's `creasemethod` tag: `normal` (uniform) or `chaikin`.
    pub fn tag_name(self) -> &'static str {
        match self {
            CreaseMethod::Uniform => "normal",
            CreaseMethod::Chaikin => "chaikin",
        }
    }

    /// The method a `creasemethod` tag string names.
    pub fn from_tag_name(name: &str) -> Option<CreaseMethod> {
        CreaseMethod::ALL
            .iter()
            .copied()
            .find(|m| m.tag_name() == name)
    }
}

impl TriangleRule {
    /// The string of OpenSubdiv's `smoothtriangles` tag: `catmark` or `smooth` (the
    /// command-line names).
    pub fn tag_name(self) -> &'static str {
        self.name()
    }

    /// The rule a `smoothtriangles` tag string names.
    pub fn from_tag_name(name: &str) -> Option<TriangleRule> {
        name.parse().ok()
    }
}

/// A name that is not one of an option's values.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} `{given}` (expected one of: {})", expected.join(", "))]
pub struct UnknownName {
    /// The option ("crease method", ...).
    pub what: &'static str,
    /// The name given.
    pub given: String,
    /// The valid names.
    pub expected: Vec<&'static str>,
}

/// The subdivision options as resolved for one run: every choice made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub struct SubdivisionOptions {
    /// Boundary interpolation of the vertex data.
    pub boundary: BoundaryInterpolation,
    /// Linear interpolation of face-varying data.
    pub face_varying: FaceVaryingInterpolation,
    /// Decay of semi-sharp creases.
    pub crease_method: CreaseMethod,
    /// Catmull-Clark's triangle rule.
    pub triangle_rule: TriangleRule,
}

impl SubdivisionOptions {
    with_setters! {
        /// Sets [`SubdivisionOptions::boundary`].
        with_boundary(boundary: BoundaryInterpolation);
        /// Sets [`SubdivisionOptions::face_varying`].
        with_face_varying(face_varying: FaceVaryingInterpolation);
        /// Sets [`SubdivisionOptions::crease_method`].
        with_crease_method(crease_method: CreaseMethod);
        /// Sets [`SubdivisionOptions::triangle_rule`].
        with_triangle_rule(triangle_rule: TriangleRule);
    }
}

/// The options a file's tags set; `None` where the file says nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub struct TagOptions {
    /// `interpolateboundary` (0 none, 1 edge-and-corner, 2 edge-only).
    pub boundary: Option<BoundaryInterpolation>,
    /// `facevaryinginterpolateboundary` (0-5).
    pub face_varying: Option<FaceVaryingInterpolation>,
    /// `creasemethod` (`normal` is uniform, `chaikin`).
    pub crease_method: Option<CreaseMethod>,
    /// `smoothtriangles` (`catmark`, `smooth`).
    pub triangle_rule: Option<TriangleRule>,
}

impl TagOptions {
    /// `true` when no option is set.
    pub fn is_empty(&self) -> bool {
        *self == TagOptions::default()
    }

    /// The options with these tags applied over `defaults`.
    pub fn over(&self, defaults: SubdivisionOptions) -> SubdivisionOptions {
        SubdivisionOptions {
            boundary: self.boundary.unwrap_or(defaults.boundary),
            face_varying: self.face_varying.unwrap_or(defaults.face_varying),
            crease_method: self.crease_method.unwrap_or(defaults.crease_method),
            triangle_rule: self.triangle_rule.unwrap_or(defaults.triangle_rule),
        }
    }
}

/// A sharp or semi-sharp edge, named by its two vertices (0-based, either order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crease {
    /// One end.
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// Its sharpness (finite, `>= 0`; [`INFINITELY_SHARP`] and above: infinitely sharp).
    pub sharpness: f32,
}

/// A sharp or semi-sharp vertex (0-based).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// The vertex.
    pub vertex: u32,
    /// Its sharpness (finite, `>= 0`).
    pub sharpness: f32,
}

/// A sharpness that is negative, NaN or infinite.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("sharpness {value} is not valid (expected a finite number >= 0)")]
pub struct InvalidSharpness {
    /// The value given.
    pub value: f32,
}

/// Creases, corners, holes and options of a mesh: what OpenSubdiv's tags describe.
///
/// Creases and corners are kept in the order given; a later value for the same edge or
/// vertex replaces the earlier one when the sharpness is resolved on a mesh (as OpenSubdiv's
/// loader does). Holes are face indices (0-based).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Tags {
    creases: Vec<Crease>,
    corners: Vec<Corner>,
    holes: Vec<u32>,
    /// The options the tags set.
    pub options: TagOptions,
}

impl Tags {
    /// Adds a crease on the edge `(a, b)`.
    ///
    /// # Errors
    ///
    /// [`InvalidSharpness`] for a negative or non-finite sharpness.
    pub fn add_crease(&mut self, a: u32, b: u32, sharpness: f32) -> Result<(), InvalidSharpness> {
        check_sharpness(sharpness)?;
        self.creases.push(Crease { a, b, sharpness });
        Ok(())
    }

    /// Adds a corner on `vertex`.
    ///
    /// # Errors
    ///
    /// [`InvalidSharpness`] for a negative or non-finite sharpness.
    pub fn add_corner(&mut self, vertex: u32, sharpness: f32) -> Result<(), InvalidSharpness> {
        check_sharpness(sharpness)?;
        self.corners.push(Corner { vertex, sharpness });
        Ok(())
    }

    /// Room for `creases`, `corners` and `holes` more entries, or the allocator's refusal
    /// (the OBJ reader reserves a tag line's entries before adding them).
    pub(crate) fn try_reserve(
        &mut self,
        creases: usize,
        corners: usize,
        holes: usize,
    ) -> Result<(), std::collections::TryReserveError> {
        self.creases.try_reserve(creases)?;
        self.corners.try_reserve(corners)?;
        self.holes.try_reserve(holes)
    }

    /// Marks face `face` as a hole.
    pub fn add_hole(&mut self, face: u32) {
        self.holes.push(face);
    }

    /// The creases, in the order given.
    pub fn creases(&self) -> &[Crease] {
        &self.creases
    }

    /// The corners, in the order given.
    pub fn corners(&self) -> &[Corner] {
        &self.corners
    }

    /// The hole faces, in the order given.
    pub fn holes(&self) -> &[u32] {
        &self.holes
    }

    /// `true` when there are no creases, corners, holes or options.
    pub fn is_empty(&self) -> bool {
        self.creases.is_empty()
            && self.corners.is_empty()
            && self.holes.is_empty()
            && self.options.is_empty()
    }
}

impl Tags {
    /// The sharp edges: one crease per edge (its vertices in increasing order), the last
    /// sharpness given for it, edges whose sharpness is 0 left out; sorted by vertices.
    pub fn sharp_edges(&self) -> Vec<Crease> {
        let mut last: BTreeMap<(u32, u32), f32> = BTreeMap::new();
        for c in &self.creases {
            last.insert((c.a.min(c.b), c.a.max(c.b)), c.sharpness);
        }
        last.into_iter()
            .filter(|&(_, s)| s > 0.0)
            .map(|((a, b), sharpness)| Crease { a, b, sharpness })
            .collect()
    }

    /// The sharp vertices: one corner per vertex, the last sharpness given for it, vertices
    /// whose sharpness is 0 left out; sorted by vertex.
    pub fn sharp_vertices(&self) -> Vec<Corner> {
        let mut last: BTreeMap<u32, f32> = BTreeMap::new();
        for c in &self.corners {
            last.insert(c.vertex, c.sharpness);
        }
        last.into_iter()
            .filter(|&(_, s)| s > 0.0)
            .map(|(vertex, sharpness)| Corner { vertex, sharpness })
            .collect()
    }

    /// The hole faces, each once, sorted.
    pub fn hole_faces(&self) -> Vec<u32> {
        let mut faces = self.holes.clone();
        faces.sort_unstable();
        faces.dedup();
        faces
    }

    /// The bytes the lists occupy on the heap (for memory budgets).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(self.creases.as_slice())
            + std::mem::size_of_val(self.corners.as_slice())
            + std::mem::size_of_val(self.holes.as_slice())
    }
}

/// A tag that names what a mesh does not have (see [`Tags::check_against`]); `entry` is the
/// position of the crease, corner or hole in its list.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TagError {
    /// A crease or corner on a vertex the mesh does not have.
    #[error("tag `{tag}`: vertex {vertex} is out of range (the mesh has {vertices} vertices; tag indices are 0-based)")]
    VertexOutOfRange {
        /// `crease` or `corner`.
        tag: &'static str,
        /// The entry's position in its list.
        entry: usize,
        /// The vertex.
        vertex: u32,
        /// The number of vertices of the mesh.
        vertices: usize,
    },
    /// A hole on a face the mesh does not have.
    #[error("tag `hole`: face {face} is out of range (the mesh has {faces} faces; tag indices are 0-based)")]
    FaceOutOfRange {
        /// The entry's position in [`Tags::holes`].
        entry: usize,
        /// The face.
        face: u32,
        /// The number of faces of the mesh.
        faces: usize,
    },
    /// A crease on two vertices that no face joins by a side.
    #[error("tag `crease`: vertices {a} and {b} are not an edge of the mesh's faces")]
    NotAnEdge {
        /// The entry's position in [`Tags::creases`].
        entry: usize,
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
    },
}

/// A tag of a file that this crate does not interpret (`vertexedit`, `facevaryingpropagatecorners`,
/// ...): its name and how many lines had it. The reader returns them
/// ([`crate::PolygonMesh::ignored_tags`]) instead of printing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IgnoredTag {
    /// The tag's name.
    pub name: String,
    /// The number of lines with this name.
    pub count: u64,
}

fn check_sharpness(value: f32) -> Result<(), InvalidSharpness> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(InvalidSharpness { value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_names_list_the_valid_ones() {
        for &b in BoundaryInterpolation::ALL {
            assert_eq!(b.name().parse::<BoundaryInterpolation>(), Ok(b));
        }
        for &f in FaceVaryingInterpolation::ALL {
            assert_eq!(f.to_string().parse::<FaceVaryingInterpolation>(), Ok(f));
        }
        let err = "sharp".parse::<CreaseMethod>().unwrap_err();
        assert_eq!(
            err.to_string(),
            "unknown crease method `sharp` (expected one of: uniform, chaikin)"
        );
        assert_eq!("smooth".parse::<TriangleRule>(), Ok(TriangleRule::Smooth));
    }

    #[test]
    fn defaults_are_opensubdivs_edge_only_uniform_catmark_and_usds_corners_plus1() {
        let d = SubdivisionOptions::default();
        assert_eq!(d.boundary, BoundaryInterpolation::Edge);
        assert_eq!(d.crease_method, CreaseMethod::Uniform);
        assert_eq!(d.triangle_rule, TriangleRule::Catmark);
        assert_eq!(d.face_varying, FaceVaryingInterpolation::CornersPlus1);
    }

    #[test]
    fn tag_options_apply_over_defaults_only_where_set() {
        let tags = TagOptions {
            crease_method: Some(CreaseMethod::Chaikin),
            ..TagOptions::default()
        };
        let base = SubdivisionOptions::default().with_boundary(BoundaryInterpolation::None);
        let r = tags.over(base);
        assert_eq!(r.crease_method, CreaseMethod::Chaikin);
        assert_eq!(r.boundary, BoundaryInterpolation::None);
        assert!(TagOptions::default().is_empty() && !tags.is_empty());
    }

    #[test]
    fn invalid_sharpness_is_refused() {
        let mut t = Tags::default();
        assert!(t.add_crease(0, 1, -1.0).is_err());
        assert!(t.add_corner(0, f32::INFINITY).is_err());
        assert!(t.is_empty());
        t.add_corner(0, 0.0).unwrap();
        t.add_hole(3);
        assert_eq!((t.corners().len(), t.holes()), (1, &[3][..]));
    }
}
