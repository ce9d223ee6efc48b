//! Face-varying refinement of UVs: a [`UvLayout`] refined with the surface, as OpenSubdiv's
//! face-varying channels (`Far::PrimvarRefiner::InterpolateFaceVarying`).
//!
//! ```
//! use glam::DVec2;
//! use halfedge::refine::Refinement;
//! use halfedge::subdivide::SubdivideOptions;
//! use halfedge::tags::{FaceVaryingInterpolation, SubdivisionOptions};
//! use halfedge::uv::Uvs;
//! use halfedge::{shapes, HalfEdgeMesh, Rule};
//!
//! // A cube whose six faces each have their own UV square: every edge is a seam.
//! let mut cube = shapes::cube();
//! let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
//! let coords: Vec<DVec2> = (0..6).flat_map(|_| square).collect();
//! let corners: Vec<u32> = (0..24).collect();
//! cube.set_uvs(Some(Uvs::new(coords, corners)?))?;
//! let layout = cube.uv_layout().expect("every corner has a vt");
//! let mesh = HalfEdgeMesh::try_from(&cube)?;
//!
//! let subdivision = SubdivisionOptions::default().with_face_varying(FaceVaryingInterpolation::All);
//! let opts = SubdivideOptions::default().with_uvs(&layout).with_subdivision(subdivision);
//! let r = Refinement::new(&mesh, Rule::CatmullClark, 2, &opts)?;
//! assert!(r.has_uvs());
//! // Six separate 4 x 4 grids of quads: 6 * 25 values.
//! assert_eq!(r.n_uvs(2), 150);
//!
//! let base: Vec<[f64; 2]> = layout.values().iter().map(|v| v.to_array()).collect();
//! let mut uvs = vec![[0.0; 2]; r.n_uvs(2)];
//! r.evaluate_uvs(&base, &mut uvs)?;
//! let mut indices = vec![0u32; r.n_corners(2)];
//! r.write_uv_indices(&mut indices)?;
//! // Bilinear (`all`): the first child quad of the first face spans a quarter of its square.
//! let first: Vec<[f64; 2]> = indices[..4].iter().map(|&i| uvs[i as usize]).collect();
//! assert!(first.iter().all(|p| p[0] <= 0.5 && p[1] <= 0.5));
//!
//! // A buffer of the wrong length is refused, naming it.
//! let err = r.evaluate_uvs(&base[..3], &mut uvs).unwrap_err();
//! assert_eq!(err.to_string(), "uv base buffer has 3 entries, expected 24");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # The channel
//!
//! Two kinds. For the rules whose faces nest (the 4:1 family, the 1:N² splits,
//! Catmull-Clark) the layout is refined as a mesh of its own (below); for the dual rules
//! (Doo-Sabin, mid-edge), whose new faces straddle old edges and vertices, the values are
//! propagated corner by corner on the surface's own refinement ([the corner
//! channel](#the-corner-channel-doo-sabin-mid-edge)). [`Refinement::has_uvs`],
//! [`Refinement::n_uvs`], [`Refinement::evaluate_uvs`] and [`Refinement::write_uv_indices`]
//! (buffers `uv base`, `uv out`, `uv indices`) behave the same for both.
//!
//! For the rules whose faces nest, the layout is refined as a mesh of its own: its faces are the surface's faces with the
//! layout's values as corners, so its boundary is the surface's boundary plus both sides of
//! every seam. It is refined by the same rule, the same number of levels and the same
//! [`Refinement`] machinery (topology, flattened tables, crease weight tables, evaluation);
//! since the faces of the 4:1 family, the 1:N² splits and Catmull-Clark nest and are numbered
//! from their parent face and its first corner alone, the channel's faces at every level are
//! the surface's faces, in the same order, corner for corner: the UV index buffer
//! ([`Refinement::write_uv_indices`]) follows [`Refinement::write_triangles`] /
//! [`write_quads`](Refinement::write_quads) / [`write_polygons`](Refinement::write_polygons)
//! face for face, holes included (only written faces, and only the values they use).
//!
//! # Loop and Catmull-Clark: OpenSubdiv's linear-interpolation modes
//!
//! [`SubdivisionOptions::face_varying`] (`Sdc::Options::FVarLinearInterpolation`) chooses
//! which values are interpolated linearly. Every value is classified once, on the base mesh,
//! as OpenSubdiv's `FVarLevel::completeTopologyFromFaceValues` does, and the channel's
//! sharpness says it: a **corner** value is an infinitely sharp vertex of the channel (it
//! stays where it is at every level), a **crease** value is a boundary vertex of the channel
//! (the crease rule `3/4, 1/8, 1/8` along the layout's boundary), a value where the layout
//! matches the surface takes the surface's own mask (its creases and semi-sharp edges, its
//! sharp vertices: the channel's interior edges and vertices carry the surface's sharpness).
//! Edge points on seams and layout boundaries are midpoints (the channel's boundary edges are
//! infinitely sharp); elsewhere the surface's edge mask applies. Per mode:
//!
//! | mode | corners (stay) | OpenSubdiv |
//! |---|---|---|
//! | `none` | only the surface's sharp vertices and non-manifold values; fully smooth otherwise, boundaries included | `FVAR_LINEAR_NONE` |
//! | `corners-only` | also values of one face at a vertex (layout corners) | `FVAR_LINEAR_CORNERS_ONLY` |
//! | `corners-plus1` | also every value at a vertex with more than two values, and both values at a vertex of two when one of them is not contiguous | `FVAR_LINEAR_CORNERS_PLUS1` (USD's and RenderMan's default, and this crate's) |
//! | `corners-plus2` | also both values at a vertex of two when one is a corner, and darts (an interior vertex where a seam ends) | `FVAR_LINEAR_CORNERS_PLUS2` |
//! | `boundaries` | every value on the layout's boundary, at every level (boundaries linear, the interior smooth) | `FVAR_LINEAR_BOUNDARIES` |
//! | `all` | everything: bilinear (Catmull-Clark) or linear (Loop) | `FVAR_LINEAR_ALL`, the default of OpenSubdiv's `Sdc::Options()` |
//!
//! A value that appears around its vertex in more than one contiguous run (a `vt` shared
//! non-contiguously, A-B-A-B around a vertex; a single value cut by two seams) is a corner
//! in every mode; the channel, a manifold mesh, gives each run its own vertex (a sibling).
//! What is counted and written from level 1 on depends on the rule. Loop and Catmull-Clark
//! number the runs as OpenSubdiv does: a run is merged with an earlier run of the same
//! OpenSubdiv value, which at a vertex with two values compares a new run with the first
//! value only, so every run of the first value (A) is merged with it while, in the order
//! A, B, A, B, the second run of B is a value of its own, kept at every level
//! (`schemes::uv::UvCounts::split_values` counts these). The other rules (midpoint,
//! butterfly, the icosphere, the 1:N² splits) merge every run back into its (vertex, `vt`)
//! value, as `schemes::uv` counts them (`UvScheme::splits_siblings`). Level 0 is one value
//! per (vertex, `vt`) pair ([`UvLayout`]) for every rule; OpenSubdiv also counts unused
//! `vt` at level 0, this crate does not.
//!
//! # The other rules
//!
//! Midpoint, butterfly and the icosphere refine UVs linearly on the layout: each edge's
//! child is the midpoint of its two values, old values stay (the midpoint rule on the
//! channel: neither butterfly's weights nor the sphere projection apply to texture
//! coordinates). The 1:N² splits put each new value on the flat UV triangle of its face, as
//! they put positions. √3 runs on the corner channel (below).
//!
//! # The corner channel (Doo-Sabin, mid-edge, √3)
//!
//! At each level `s` every face corner has a value index, and every value of level `s + 1`
//! is an affine combination (a sparse row of weights summing to 1) of values of level `s`.
//! A rule supplies one step (the private `corner_step::CornerStep`), from the parent level's
//! topology and the value of each of its face corners (by half-edge: the corner at the
//! half-edge's source in its face): the new values' weight rows (a `sdc::WeightTable`, as the
//! crease rules use for positions) and the value of each child corner, asked as (child face,
//! child vertex) in the rule's numbering of faces and vertices (`subdivide/dual.rs`'s module
//! docs), so the step does not depend on the order in which a level's half-edges are written.
//! The channel runs the steps on the levels the surface's [`Refinement`] keeps, reads the
//! child corners off the child's half-edges (levels before the last) or off the last level's
//! face list (the order of [`Refinement::write_polygons`]), and checks that every value a
//! step creates is used by some corner and that every corner names a value of its level
//! (else [`Error::InvalidOutput`]: a bug). The values of a level are the distinct indices
//! written, so [`Refinement::n_uvs`] is the number of rows; [`Refinement::evaluate_uvs`]
//! applies the tables in turn. The UVs are linear (affine combinations of a face's own
//! values), not smoothed.
//!
//! Notation: `λ_f(v)` is the value of face `f`'s corner at vertex `v` (level `s`). A **seam**
//! is an interior edge whose two faces disagree at either end; surface boundary edges are
//! not seams. Edge `e` has the half-edges `2e` and `2e + 1`.
//!
//! **Doo-Sabin.**
//! (a) The corner of face `f` at `v` (the new vertex of that face half-edge) gets
//! `Σ w_j λ_f(p_j)` with the Doo-Sabin weights of the positions (`w_0 = (n + 5) / (4n)`,
//! `w_j = (3 + 2 cos(2πj/n)) / (4n)`): one value per face corner, used by the face's shrunken
//! face, the edge faces of its two sides and the vertex face. For a face of more than 32
//! sides the row is `λ_f(v)/4 + (3/4) mean + (1/2)(cos θ_i C + sin θ_i D)` over the face's
//! three sums (the mean and the `cos θ_j`- and `sin θ_j`-weighted means of its values,
//! `θ_j = 2πj/n`), computed once per face as the step's auxiliary values: the same weights up
//! to rounding, 4 per corner rather than `n` (`wide.rs`'s `DIRECT_MAX`).
//! (b) On a surface boundary edge of face `f` its two Chaikin points (new vertices) get
//! `(3 λ_f(x) + λ_f(y)) / 4` near end `x`, in `f`'s chart: one value each, shared by the
//! boundary quad and the vertex faces that use the same vertex.
//! (c) The edge face of a seam edge `e` takes the chart of the face `f` of half-edge `2e`:
//! its two corners from `f` keep their own values, its two corners from the other face are
//! replaced by the Chaikin points of `e` in `f`'s chart, `(3 λ_f(x) + λ_f(y)) / 4` at end
//! `x`: two new values per seam edge.
//! (d) A vertex face takes each corner's own value. **Limitation:** at a vertex where a seam
//! passes, its corners come from the faces around the vertex, so its UV polygon spans the
//! charts meeting there (on a seam between two distant charts it stretches across the
//! texture, and may be flipped). At level 1 the other faces lie in one chart each; from
//! level 2 on the faces descending from a straddling face (its shrunken face, the edge faces
//! beside it, whose values are combinations of its values) straddle too, over a shrinking
//! part of the surface. Measured on spot_control_mesh (UV diameter above 0.1 of the unit
//! square, where the base's faces reach 0.19): level 1, 57 of its 188 vertex faces and 1 of
//! the 546 other faces; level 2, 176 of 734 vertex faces and 104 of 2196 other faces.
//!
//! Counts: the values are the new vertices, `V_(s+1) = 2E_s` closed and `2E_s + BE_s` with
//! boundary, plus `2 S_s`; the seams of level `s + 1` are, per seam edge, the side its edge
//! face shares with the other face's shrunken face and the two sides it shares with the
//! vertex faces at its ends (which keep the corners' values), while edges that are not seams
//! give none: `S_(s+1) = 3 S_s`. So `UV(s) = V(s) + 2 * 3^(s-1) * S_0` for `s >= 1`, `S_0`
//! the layout's seam edges (`UE_0 - E_0`): `schemes::uv::uv_scheme(Rule::DooSabin)`.
//!
//! **Mid-edge.**
//! (a) One value per (edge, side): the midpoint `(λ_f(a) + λ_f(b)) / 2` of the edge's end
//! values in that face's chart: one for an interior edge that is not a seam and for a
//! boundary edge, two for a seam (`UE_s` values), used by the face faces.
//! (b) The vertex face at `v`: its corner at edge `e` takes `e`'s value on the side of the
//! face of the half-edge leaving `v` along `e`, or, when that half-edge is a surface boundary
//! half-edge, of its twin's face. **Limitation:** at a vertex where a seam passes, the vertex
//! face takes its corners from the faces around it and spans their charts (spot_control_mesh,
//! level 1: 60 of 188 vertex faces span more than 0.1 of the unit square); the face faces of
//! later levels inside such a face inherit it.
//! (c) With boundary, the kept boundary vertex `E + r` (the source `v` of boundary half-edge
//! `r`, `r` its rank among the boundary half-edges in increasing order) keeps `λ_f(v)`,
//! `f` the face of the boundary edge leaving `v` (the twin of half-edge `r`), unchanged
//! (linear: its position moves by the cubic B-spline rule, its UV does not): one value per
//! boundary vertex.
//!
//! Counts: `UV_(s+1) = UE_s + BE_s = E_s + S_s + BE_s`; the new edge between a face face and
//! a vertex face is a seam exactly when the old edge it crosses is (by (b), the vertex face
//! uses the other side's value there), two new edges per old edge: `S_(s+1) = 2 S_s`.
//!
//! Without seams (one value per vertex) both give one value per vertex from level 1 on, and
//! UVs that are an affine image of the positions stay one (mid-edge: except near the
//! boundary from level 2 on, since the kept boundary vertices keep their UVs). Holes are
//! refused by both rules ([`Error::HolesNeedNestedFaces`]), with UVs or without.
//!
//! **√3.** √3 flips every old edge, so its faces do not nest and its UVs run on the corner
//! channel too, with a linear rule (positions are smoothed, UVs are not). `λ_f(v)` is the value of face
//! `f`'s corner at `v`; an interior edge is a **seam** when its two faces disagree at either
//! end (surface boundary edges are not seams). Each old face half-edge `g` (face `f`, target
//! `v`) gives one new triangle (the numbering of `sqrt3.rs`): `(v, rep(g), rep(twin g))` for
//! an interior edge, `rep(g)` being the point of `f` the flipped edge reaches.
//!
//! - Old values stay, one per value; the centroid of `f` gets the mean of `f`'s three values.
//! - A plain step (`sqrt3`) and step A: the triangle of an interior `g` takes the chart of
//!   `g`'s face `f`: `v` gets `λ_f(v)`, `rep(g)` its own value, and `rep(twin g)`, a point of
//!   the other face, its own value when the edge is not a seam, else the midpoint of the edge
//!   in `f`'s chart, `(λ_f(a) + λ_f(b)) / 2`: two new values per seam edge. Step A's boundary
//!   triangle (an old boundary edge with the centroid) is in `f`'s chart.
//! - Step B (a boundary face `(a, b, c)`, boundary half-edge `a -> b`): `p1` and `p2` get
//!   `(2 λ_f(a) + λ_f(b)) / 3` and `(λ_f(a) + 2 λ_f(b)) / 3`; the middle triangle
//!   `(p1, p2, c)` is in `f`'s chart. The triangle of an interior `g` takes the chart of the
//!   face *across* `g` (its foreign point, `rep(g)`, replaced by the seam midpoint in that
//!   chart). The choice keeps every value: a step-B face's corner at one end of its boundary
//!   edge is used by none of its own triangles. With `g`'s own chart that corner is at `b`,
//!   in the first face around `b`, which is often the only face there with its value (a seam
//!   `b c`): the value would be lost. With the chart across `g` it is at `a`, in the last face
//!   around `a`, and after step A the last two faces around every boundary vertex are the two
//!   triangles of one old face at it (the triangle of its half-edge entering the vertex and
//!   the boundary triangle of its edge leaving it), in that face's chart, so the other one
//!   uses the value.
//!
//! Every face lies in one chart (its values are affine combinations of one parent face's),
//! and every value a step keeps or creates is used by a corner (the channel checks it). The
//! counts are `schemes::uv`'s √3 recurrence, from level 1 on: `UV' = UV + F + 2 S` (plain
//! step, step A) and `UV' = UV + F + BE + 2 S` (step B: the `BE` boundary faces get two
//! points instead of a centroid), and `S' = 3 S` for both (the flips of seams, and per seam
//! side one spoke of its face). √3 refuses holes, with and without UVs.
//!
//! # Memory
//!
//! The corner channel keeps, per level, its weight table (4 bytes per value, 12 per weight:
//! Doo-Sabin `n` weights per value of an `n`-gon's corner up to 32 sides, 4 beyond and 3 per
//! corner for the face's sums, mid-edge 2, √3 at most 3) and the last
//! level's value indices (4 bytes per corner); building it holds one level's corner values
//! (4 bytes per half-edge) at a time. It runs on the surface's refinement, which keeps every
//! level's connectivity for these rules anyway.
//!
//! The layout channel is a [`Refinement`] of the layout: its [heap](Refinement#memory) is that of a
//! refinement of a mesh with the layout's values as vertices (a little more than the surface's
//! vertices on meshes with seams), plus, when values have several runs, 4 bytes per value of
//! the last level (the merged numbering) and, with holes, 4 bytes per written corner (the
//! written UV indices). [`Refinement::evaluate_uvs`] allocates the channel's intermediate
//! levels on every call (as [`Refinement::evaluate`] does) and, with siblings or holes, the
//! whole last level of the channel.
//!
//! Under Loop and Catmull-Clark the channel's corners, seams and the surface's creases are
//! crease rules ([`sdc`](crate::subdivide::sdc)): each level keeps the flattened Loop or
//! Catmull-Clark tables and the rows of the few values whose mask differs (corners, values on
//! the surface's creases; seams and layout boundaries take the tables' boundary rule), or, under
//! `all`, linear tables (edge ends and face corners). Measured on spot_quadrangulated (2,928
//! quads, 3,225 values) under Catmull-Clark at level 3 (187,394 vertices, 189,705 UV values;
//! `cargo test` profile): the refinement holds 8.85 MB without UVs and 18.5 MB with them in the
//! modes `none` to `corners-plus2` (18.6 MB `boundaries`, 15.3 MB `all`); spot_triangulated
//! under Loop at level 3: 9.79 MB and 20.4 MB (17.2 MB `all`). In release (BENCHMARKS.md)
//! building it takes 9.7 ms with UVs against 3.2 ms without, and `evaluate_uvs` in `f32`
//! 1.4 ms where an [`Evaluator`](super::Evaluator) of `f32` positions takes 1.0 ms (Loop: 13 ms
//! against 4 ms, 1.6 ms against 1.0 ms).
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Face-varying UVs (`SubdivideOptions::uvs`, `refine/face_varying.rs`): the UV layout is refined
//! as a mesh of its own (its faces the surface's faces with values as corners, its boundary the
//! surface's plus both sides of every seam) by the same `Refinement` machinery and the same rule
//! (the midpoint rule for butterfly and the icosphere); the 4:1 family, the 1:N² splits and
//! Catmull-Clark number child faces from the parent face alone, so the channel's faces are the
//! surface's, corner for corner. Under Loop and Catmull-Clark each base value is classified once
//! as OpenSubdiv's `FVarLevel` does (corner, crease or matching the surface, per
//! `FaceVaryingInterpolation`) and the channel's sharpness says it (`Creases::for_channel`:
//! corners infinitely sharp, the surface's creases on the layout's interior edges, `Linear` for
//! `boundaries` and `all`); a value in several runs around its vertex is one vertex of the channel
//! per run, merged back when counted (OpenSubdiv's sibling values, its A-B-A-B quirk included).
//! Compared value for value with OpenSubdiv in `tests/opensubdiv_uv.rs`. Doo-Sabin and mid-edge,
//! whose faces do not nest, use the corner channel instead (`refine/corners.rs`): each rule's step
//! (`dual.rs`: `doo_sabin_uv_step`, `mid_edge_uv_step`) gives, from a level's topology and corner
//! values, the new values as weight rows and the value of each child corner by (child face, child
//! vertex); the channel runs it on the refinement's kept levels, checks that every value is used,
//! and evaluates the tables in turn (a step may first compute auxiliary values, numbered after the
//! parent's: Doo-Sabin's three face-wide sums of each face of more than 32 sides, so that its
//! corners are 4-entry rows and the tables stay linear in a face's degree). √3 runs on it too
//! (`sqrt3.rs`: `sqrt3_uv_step`, linear: centroids, step B's trisection points, two midpoints per
//! seam edge; in step B a triangle takes the chart of the face across its half-edge so that no
//! value goes unused).
//!
//! Owner of face-varying refinement of UVs (OpenSubdiv's linear-interpolation modes and value
//! classification, sibling values, the UV index buffer, linear UVs under the other triangle rules,
//! the corner channel of the dual rules): `halfedge::refine::face_varying`
//! (`subdivide/refine/face_varying.rs`: `UvChannel`, either the layout refined as its own
//! `Refinement` with `sdc::Creases::for_channel`, or, for √3, Doo-Sabin and mid-edge,
//! `refine/corners.rs`'s `CornerChannel`: values propagated corner by corner on the surface's own
//! levels, one `sdc::WeightTable` per level, the rules' steps in `sqrt3.rs` (`sqrt3_uv_step`) and
//! `dual.rs` next to their geometry); asked through `SubdivideOptions::uvs`, read through
//! `Refinement::evaluate_uvs` / `write_uv_indices`, written by `subdivide_to_face_list` into its
//! mesh's `uvs`.

use crate::mesh::INVALID;
use crate::subdivide::refine::creases::{boundary_first, ccw_ring, Creases, Linear};
use crate::subdivide::topo::Topo;
use crate::subdivide::SubdivideOptions;
use crate::tags::{BoundaryInterpolation, FaceVaryingInterpolation, INFINITELY_SHARP};
use crate::uv::UvLayout;
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result, Rule};

#[cfg(doc)]
use crate::tags::SubdivisionOptions;

use super::{check_len, Refinement, Scalar};

mod layout;

use self::layout::{corner_values, LayoutChannel};

/// How the UVs of a rule are refined.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ChannelKind {
    /// The layout refined as a mesh of its own by this rule.
    Layout(Rule),
    /// The corner channel on the surface's own refinement ([`super::corners`]).
    Corners,
}

/// How the UV layout is refined under `rule`: as a mesh of its own by the rule itself for
/// Loop, Catmull-Clark and the 1:N² splits, by the midpoint rule for the other 4:1 rules
/// (linear UVs); by the corner channel for √3, Doo-Sabin and mid-edge.
///
/// # Errors
///
/// None today: every rule carries UVs (the `Result` is the callers' refusal point).
pub(crate) fn channel_kind(rule: Rule) -> Result<ChannelKind> {
    match rule {
        Rule::Loop | Rule::CatmullClark | Rule::Midpoint | Rule::TriSplit(_) => {
            Ok(ChannelKind::Layout(rule))
        }
        Rule::Butterfly | Rule::Icosphere => Ok(ChannelKind::Layout(Rule::Midpoint)),
        Rule::Sqrt3 | Rule::DooSabin | Rule::MidEdge => Ok(ChannelKind::Corners),
    }
}

/// The UVs of the last level of `layout` on `mesh` refined by `rule` `levels` times (the
/// written faces' corners with holes): what [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list)
/// writes into its mesh, in `f64`.
pub(crate) fn refined_uvs(
    mesh: &HalfEdgeMesh,
    layout: &UvLayout,
    rule: Rule,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<crate::uv::Uvs> {
    let base: Vec<[f64; 2]> = layout.values().iter().map(|v| v.to_array()).collect();
    // The one-shot subdivision writes refined values: no limit (only `Refinement::new` reads
    // `SubdivideOptions::limit`).
    let opts = &SubdivideOptions {
        limit: false,
        ..*opts
    };
    let (values, indices) = match channel_kind(rule)? {
        ChannelKind::Layout(_) => {
            let channel = LayoutChannel::new(mesh, layout, rule, levels, opts)?;
            let mut values =
                crate::subdivide::alloc::filled([0.0; 2], channel.n_uvs(levels), "uv values")?;
            channel.evaluate(&base, &mut values)?;
            let corners = match &channel.written_corners {
                Some(c) => c.len(),
                None => channel.refinement.n_corners(levels),
            };
            let mut indices = crate::subdivide::alloc::filled(0u32, corners, "uv indices")?;
            channel.write_indices(&mut indices, corners)?;
            (values, indices)
        }
        ChannelKind::Corners => {
            // The surface's refinement carries the channel.
            let opts = SubdivideOptions {
                uvs: Some(layout),
                ..*opts
            };
            let r = Refinement::new(mesh, rule, levels, &opts)?;
            let mut values =
                crate::subdivide::alloc::filled([0.0; 2], r.n_uvs(levels), "uv values")?;
            r.evaluate_uvs(&base, &mut values)?;
            let mut indices =
                crate::subdivide::alloc::filled(0u32, r.n_corners(levels), "uv indices")?;
            r.write_uv_indices(&mut indices)?;
            (values, indices)
        }
    };
    // Huge `vt` values whose weighted sums overflow: refused as positions are.
    crate::subdivide::check_uvs(&rule.to_string(), levels, &values, "computed in f64")?;
    let coords = values.into_iter().map(glam::DVec2::from).collect();
    crate::uv::Uvs::new(coords, indices).map_err(|e| Error::UvLayoutMismatch {
        reason: e.to_string(),
    })
}

/// The face-varying channel of a refinement.
#[derive(Debug)]
pub(crate) enum UvChannel {
    /// The layout refined as a mesh of its own.
    Layout(Box<LayoutChannel>),
    /// Values propagated corner by corner on the surface's refinement.
    Corners(super::corners::CornerChannel),
}

impl UvChannel {
    /// The channel of `layout` on `mesh` under `rule` at `levels` with the surface's options;
    /// `surface` is the surface's refinement (the corner channel runs on its levels).
    pub(crate) fn new(
        mesh: &HalfEdgeMesh,
        layout: &UvLayout,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
        surface: &Refinement,
    ) -> Result<UvChannel> {
        Ok(match channel_kind(rule)? {
            ChannelKind::Layout(_) => UvChannel::Layout(Box::new(LayoutChannel::new(
                mesh, layout, rule, levels, opts,
            )?)),
            ChannelKind::Corners => {
                let t = Topo::new(mesh);
                let cv = corner_values(&t, layout, mesh.unreferenced_vertices())?;
                UvChannel::Corners(super::corners::CornerChannel::new(
                    surface,
                    rule,
                    cv,
                    layout.n_values(),
                )?)
            }
        })
    }

    /// The UV values of level `level`.
    pub(crate) fn n_uvs(&self, level: u32) -> usize {
        match self {
            UvChannel::Layout(c) => c.n_uvs(level),
            UvChannel::Corners(c) => c.n_uvs(level),
        }
    }

    pub(crate) fn heap_bytes(&self) -> usize {
        match self {
            UvChannel::Layout(c) => c.heap_bytes(),
            UvChannel::Corners(c) => c.heap_bytes(),
        }
    }

    pub(crate) fn evaluate<T: Scalar>(&self, base: &[[T; 2]], out: &mut [[T; 2]]) -> Result<()> {
        match self {
            UvChannel::Layout(c) => c.evaluate(base, out),
            UvChannel::Corners(c) => c.evaluate(base, out),
        }
    }

    /// The limit of the values (the layout refined as a mesh only).
    pub(crate) fn evaluate_limit<T: Scalar>(
        &self,
        base: &[[T; 2]],
        out: &mut [[T; 2]],
    ) -> Result<()> {
        match self {
            UvChannel::Layout(c) => c.values(base, out, true),
            // Unreachable: the rules of the corner channel have no limit masks, and a
            // refinement refuses the limit before it builds its channel.
            UvChannel::Corners(_) => Err(Error::InvalidOutput {
                scheme: "uv limit".into(),
                level: 0,
                what: "a corner channel has no limit masks".into(),
            }),
        }
    }

    pub(crate) fn write_indices(&self, out: &mut [u32], expected: usize) -> Result<()> {
        match self {
            UvChannel::Layout(c) => c.write_indices(out, expected),
            UvChannel::Corners(c) => c.write_indices(out, expected),
        }
    }
}

/// The UVs of a refinement: through its channel.
impl Refinement {
    /// Whether the refinement refines UVs ([`SubdivideOptions::uvs`](crate::subdivide::SubdivideOptions::uvs); [`face_varying`](self)).
    pub fn has_uvs(&self) -> bool {
        self.uvs.is_some()
    }

    /// The UV values of level `level` (`0..=levels`; 0 beyond the last level, and without
    /// UVs): level 0 is the layout's values, the last level's are the values its written
    /// faces use (with holes, fewer than the level has). Known when the refinement is built.
    pub fn n_uvs(&self, level: u32) -> usize {
        self.uvs.as_ref().map_or(0, |u| u.n_uvs(level))
    }

    /// Refines the UV values `base` (one per value of the layout,
    /// [`UvLayout::values`](crate::uv::UvLayout::values)) to the last level, into `out`
    /// (`n_uvs(levels)` entries), by the face-varying rules of [`face_varying`](self).
    ///
    /// # Errors
    ///
    /// [`Error::NoUvs`] without a layout; [`Error::BufferSize`] (`uv base`, `uv out`);
    /// [`Error::AllocationFailed`].
    pub fn evaluate_uvs<T: Scalar>(&self, base: &[[T; 2]], out: &mut [[T; 2]]) -> Result<()> {
        let uvs = self.uvs.as_ref().ok_or(Error::NoUvs)?;
        self.run(|| uvs.evaluate(base, out))
    }

    /// Writes the UV value of every face corner of the last level (`n_corners(levels)`
    /// entries), face after face in the order of [`Refinement::write_triangles`],
    /// [`write_quads`](Refinement::write_quads) and [`write_polygons`](Refinement::write_polygons)
    /// (with holes, the written faces only): index `i` names entry `i` of
    /// [`Refinement::evaluate_uvs`]' output.
    ///
    /// # Errors
    ///
    /// [`Error::NoUvs`] without a layout; [`Error::BufferSize`] (`uv indices`).
    pub fn write_uv_indices(&self, out: &mut [u32]) -> Result<()> {
        let uvs = self.uvs.as_ref().ok_or(Error::NoUvs)?;
        uvs.write_indices(out, self.n_corners(self.levels))
    }
}
