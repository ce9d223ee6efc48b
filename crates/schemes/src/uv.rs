//! Exact UV counts: the statistics of a mesh's UV layout ([`UvCounts`]) and, per rule, the
//! recurrence of its UV values ([`UvScheme`]).
//!
//! # Definitions
//!
//! Texture coordinates are face-varying data: a `vt` per face corner, discontinuous across
//! UV seams. The **UV layout** has the mesh's faces with **values** as corners, a value being
//! a distinct (vertex, `vt`) pair that some corner uses (OpenSubdiv keeps one value per such
//! pair from level 1 on: a `vt` used at several vertices is one value per vertex). A surface
//! edge is a **seam** when its faces do not agree on the values at both of its ends; a seam
//! edge of two faces is two boundary edges of the layout.
//!
//! The layout is a mesh of its own, and its statistics are counted by the one implementation,
//! [`MeshCounts::from_face_list`], on the faces written with value indices: `V` the values
//! used, `E` and `BE` its edges and boundary edges, `boundary_loops`, and `charts` its
//! connected components. `seam_edges` counts surface edges (once each, however many layout
//! edges they split into), `unreferenced` the `vt` entries no corner uses.
//!
//! # Counting UV values
//!
//! Every rule whose faces refine on their own and carry UVs within each face (the 4:1 family,
//! `tri-split-N`, Catmull-Clark in OpenSubdiv's face-varying refinement) refines the layout
//! *as a mesh*: a child value sits on a parent value, on a layout edge or in a face, exactly as
//! a child vertex sits on a parent vertex, edge or face. Two faces that disagree at an end of
//! their common edge give it one child value each, which is the edge's two layout edges; two
//! that agree give it one. So the UV values follow the rule's matrix for any face list (its
//! `-general` scheme) applied to the layout's statistics, with the layout's boundary edges
//! added (each splits into `N` boundary edges): see [`UvScheme`] for each rule's matrix.
//!
//! **OpenSubdiv's sibling values.** Before refining, OpenSubdiv numbers the values at each
//! vertex along its faces in their order around it; while it knows exactly two it compares a
//! new run only with the first, so the order A, B, A, B makes the second run of B a value of
//! its own, kept at every level ([`UvCounts::split_values`] counts them; osd_catmark_bishop
//! has 39, so its 3244 (vertex, `vt`) pairs give 7991 values at level 1, not 7952). Loop and
//! Catmull-Clark, OpenSubdiv's rules, start from `UV0 = V + split_values`; the other rules
//! refine the layout as a mesh and start from `UV0 = V` ([`UvScheme::splits_siblings`]). In
//! a composition only the first stage starts from split values.
//!
//! **Level 0** is the number of `vt` entries some corner uses ([`UvCounts::used_vt`]); the
//! recurrence's `UV` component starts from `UV0` and equals the real count from level 1 on
//! ([`UvScheme::VALID_FROM`]); the two agree at level 0 too when no `vt` is shared by two
//! vertices and nothing is split. OpenSubdiv's level 0 is the whole `vt`
//! list, used or not (`used_vt + unreferenced`): its `GetNumFVarValues(0)` counts what the
//! file gives, ours what the faces use. From level 1 on OpenSubdiv also keeps one value at
//! each bare vertex (a position no face uses), which no face uses either; ours counts the
//! values faces use, as `V` counts the vertices they use. Every shared mesh with UVs agrees
//! with OpenSubdiv under these two rules at levels 0-2 in every mode
//! (`crates/halfedge/tests/uv_count_reference`).
//!
//! With holes, what is written at level `s` is level `s` of the written faces (the children of
//! a hole are holes, [`crate::holes`]), so their layout (the written faces with their corners'
//! values) counts the written UV values exactly, as [`MeshCounts`] of the written faces count
//! `V`, `E`, `F`; their split values are the siblings of the whole mesh (holes are refined
//! too) that written faces use ([`UvCounts::kept_split_values`]).
//!
//! **The dual rules** (Doo-Sabin, mid-edge) do not refine the layout as a mesh: their faces
//! straddle the old edges and vertices, so their UVs are propagated corner by corner on the
//! surface's own refinement (`halfedge::refine::face_varying`), and their values follow the
//! surface's counts plus what the seams add. Their state is the layout's `UE`, `UBE` and the
//! seam edges `S` ([`UV_SEAM_STATE`]; the surface's `E = UE - S` and `BE = UBE - 2 S`), see
//! [`UvScheme`]. A composition chaining a dual rule with a rule of the other kind is not
//! counted (one state does not give the other: [`NotCounted::composed_with`]).
//!
//! √3 does not refine faces on their own; its UV rule (linear, every new face in one chart,
//! seam midpoints) counts over the layout's values, boundary edges, seam edges and faces
//! ([`SQRT3_UV_STATE`]; the derivation is in [`uv_scheme`]'s √3 matrices, [`UvScheme`]),
//! alternating two matrices with the boundary (`sqrt3-boundary`).
//!
//! A scheme without a rule is [`NotCounted`].
//!
//! # Example: a cube with one seam
//!
//! ```
//! use schemes::uv::{uv_scheme, UvCounts};
//! use schemes::{BigInt, Rule};
//!
//! // The cube's six quads; the top face (face 1) has its own vt at every corner, so its four
//! // edges are seams.
//! let faces: [[u32; 4]; 6] = [
//!     [0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0],
//! ];
//! let vertex_corners: Vec<u32> = faces.iter().flatten().copied().collect();
//! let offsets: Vec<usize> = (0..=6).map(|f| 4 * f).collect();
//! // Value of a corner: its vertex, except on face 1, whose corners get values 8..12.
//! let value_corners: Vec<u32> = (0..24)
//!     .map(|c| if (4..8).contains(&c) { 8 + (c as u32 - 4) } else { vertex_corners[c] })
//!     .collect();
//! let value_vts: Vec<u32> = (0..12).collect();
//! let uv = UvCounts::from_layout(&offsets, &vertex_corners, &value_corners, &value_vts, 0)?;
//! assert_eq!((uv.values, uv.edges, uv.boundary_edges, uv.seam_edges), (12, 16, 8, 4));
//! assert_eq!((uv.boundary_loops, uv.charts), (2, 2));
//!
//! let cc = uv_scheme(Rule::CatmullClark)?;
//! assert_eq!(cc.recurrence().names(), ["UV", "UE", "UBE", "F", "H"]);
//! // Level 1: a value per old value, per layout edge and per face.
//! assert_eq!(cc.values_at(&uv, 1)?, BigInt::from(12 + 16 + 6));
//! assert!(uv_scheme(Rule::TriSplit(1)).is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of UV counting: the UV layout's statistics (`UvCounts`: values, layout edges and boundary
//! edges, seam edges, boundary loops, charts, unused `vt`; through `MeshCounts::from_face_list` on
//! the layout's faces), OpenSubdiv's sibling values (`UvCounts::split_values`: the values its
//! face-varying refinement splits off where a vertex's faces use two `vt` in the order A, B, A, B;
//! `kept_split_values` with holes), each rule's UV recurrence (`UvScheme`, `uv_scheme`: over the
//! layout's `UV, UE, UBE, F[, H]`, for the dual rules over `UV, UE, UBE, S` with `S` the seam
//! edges, for √3 over `UV, UBE, S, F`, periodic (steps A and B) under `sqrt3-boundary`:
//! `UvScheme::period`, `phases`; `NotCounted` for a scheme without a rule and for a composition
//! chaining a dual rule with a rule of the other kind), the UV values under a plan and the `UV`
//! column of a counter's rows (`UvCounter`, `Counter::uv_counter`): `schemes::uv`
//! (`crates/schemes/src/uv.rs`); a mesh's layout statistics: `halfedge::stats::uv_counts` (the
//! layout as a mesh of its own, `MeshCounts`: `uv_layout_counts`), of the written faces with
//! holes: `HoleSet::written_uv_counts`.

use std::fmt;

use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};
use serde::Serialize;

use crate::catalog::{catmull_clark_general, loop_general, tri_split};
use crate::{Error, MeshCounts, Plan, Result, Row, Rule, Scheme, StepRule};

/// The statistics of a UV layout (module docs for the definitions), computed by
/// [`UvCounts::from_layout`].
///
/// Serializes to the `"uv"` object of `subcount stats --format json`: `V` (the (vertex, `vt`)
/// pairs), `E`, `BE`,
/// `seam_edges`, `boundary_loops`, `charts`, `unreferenced` (the fields that are not
/// layout statistics, `used_vt`, `faces` and `corners`, are skipped).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct UvCounts {
    /// `V`: the UV values used: the distinct (vertex, `vt`) pairs of the corners (not the
    /// `vt` entries used, which are [`used_vt`](Self::used_vt)).
    #[serde(rename = "V")]
    pub values: u64,
    /// `E`: edges of the layout.
    #[serde(rename = "E")]
    pub edges: u64,
    /// `BE`: boundary edges of the layout (one face side), seams counted on both sides.
    #[serde(rename = "BE")]
    pub boundary_edges: u64,
    /// Surface edges whose faces disagree on the values at either end, once per surface edge.
    pub seam_edges: u64,
    /// Connected components of the layout's boundary edges.
    pub boundary_loops: u64,
    /// Connected components of the layout (faces joined through shared values).
    pub charts: u64,
    /// `vt` entries that no corner uses.
    pub unreferenced: u64,
    /// `vt` entries that some corner uses: the UV values at level 0.
    #[serde(skip)]
    pub used_vt: u64,
    /// The values OpenSubdiv's face-varying refinement adds to `V` before level 1 (its
    /// "sibling" values): at a vertex whose faces, in OpenSubdiv's order around it, use two
    /// values in the order A, B, A, B, the second run of B is a value of its own. Loop and Catmull-Clark count from `V + split_values` (module docs).
    #[serde(skip)]
    pub split_values: u64,
    /// Faces of the layout (the mesh's faces).
    #[serde(skip)]
    pub faces: u64,
    /// Corners of the layout (the mesh's corners, `H`).
    #[serde(skip)]
    pub corners: u64,
}

impl UvCounts {
    /// The statistics of the layout whose faces are `face_offsets` (face `f` has the corners
    /// `face_offsets[f]..face_offsets[f + 1]`), with the vertex of every corner in
    /// `vertex_corners`, its value in `value_corners`, the `vt` of every value in `value_vts`
    /// (so the values are `0..value_vts.len()`) and `unreferenced` the `vt` entries no corner
    /// uses.
    ///
    /// The layout's `V`, `E`, `BE`, boundary loops and charts are those of
    /// [`MeshCounts::from_face_list`] on the faces written with value indices (the one
    /// implementation); seam edges are found by sorting the faces' sides. Runs in
    /// `O(H log H)` for `H` corners.
    ///
    /// # Errors
    ///
    /// [`Error::BadUvLayout`] when the offsets do not start at 0, decrease or do not end at the
    /// number of corners, when the two corner slices differ in length, when a corner names a
    /// value beyond `value_vts`, or when one value is used at two different vertices.
    pub fn from_layout(
        face_offsets: &[usize],
        vertex_corners: &[u32],
        value_corners: &[u32],
        value_vts: &[u32],
        unreferenced: u64,
    ) -> Result<UvCounts> {
        check_layout(face_offsets, vertex_corners, value_corners, value_vts.len())?;
        let faces = face_offsets.windows(2).map(|w| &value_corners[w[0]..w[1]]);
        let layout = MeshCounts::from_face_list(faces, 0);

        let mut used = vec![false; value_vts.len()];
        for &v in value_corners {
            used[v as usize] = true;
        }
        let mut vts: Vec<u32> = value_vts
            .iter()
            .zip(&used)
            .filter(|(_, &u)| u)
            .map(|(&t, _)| t)
            .collect();
        vts.sort_unstable();
        vts.dedup();

        let siblings = sibling_values(face_offsets, vertex_corners, value_corners);
        let split_values = split_values_of(value_corners, &siblings, |_| true);

        Ok(UvCounts {
            split_values,
            values: layout.vertices,
            edges: layout.edges,
            boundary_edges: layout.boundary_edges,
            seam_edges: seam_edges(face_offsets, vertex_corners, value_corners),
            boundary_loops: layout.boundary_loops,
            charts: layout.components,
            unreferenced,
            used_vt: vts.len() as u64,
            faces: layout.faces,
            corners: layout.corners,
        })
    }
}

impl UvCounts {
    /// [`split_values`](Self::split_values) of the faces `f` with `keep(f)` of a layout (the
    /// arguments of [`from_layout`](Self::from_layout)), the values at each vertex being
    /// those of all its faces: OpenSubdiv refines hole faces too, so which faces are written
    /// does not change a vertex's values, only which of them are used.
    ///
    /// # Errors
    ///
    /// As [`from_layout`](Self::from_layout).
    pub fn kept_split_values(
        face_offsets: &[usize],
        vertex_corners: &[u32],
        value_corners: &[u32],
        n_values: usize,
        keep: impl Fn(usize) -> bool,
    ) -> Result<u64> {
        check_layout(face_offsets, vertex_corners, value_corners, n_values)?;
        let mut kept = vec![false; vertex_corners.len()];
        for (f, w) in face_offsets.windows(2).enumerate() {
            if keep(f) {
                kept[w[0]..w[1]].fill(true);
            }
        }
        let siblings = sibling_values(face_offsets, vertex_corners, value_corners);
        Ok(split_values_of(value_corners, &siblings, |c| kept[c]))
    }
}

/// The checks of [`UvCounts::from_layout`]; afterwards every slice index is in range.
fn check_layout(
    offsets: &[usize],
    vertex_corners: &[u32],
    value_corners: &[u32],
    n_values: usize,
) -> Result {
    let bad = |reason: String| Err(Error::BadUvLayout { reason });
    if vertex_corners.len() != value_corners.len() {
        return bad(format!(
            "{} vertex corners but {} value corners",
            vertex_corners.len(),
            value_corners.len()
        ));
    }
    match (offsets.first(), offsets.last()) {
        (Some(0), Some(&end)) if end == vertex_corners.len() => {}
        (first, last) => {
            return bad(format!(
                "face offsets must run from 0 to the {} corners, but run from {} to {}",
                vertex_corners.len(),
                first.map_or("nothing".into(), usize::to_string),
                last.map_or("nothing".into(), usize::to_string),
            ))
        }
    }
    if let Some(f) = offsets.windows(2).position(|w| w[1] < w[0]) {
        return bad(format!(
            "face {f} ends at corner {} before it starts at corner {}",
            offsets[f + 1],
            offsets[f]
        ));
    }
    let mut vertex_of: Vec<Option<u32>> = vec![None; n_values];
    for (corner, (&vertex, &value)) in vertex_corners.iter().zip(value_corners).enumerate() {
        let Some(slot) = vertex_of.get_mut(value as usize) else {
            return bad(format!(
                "corner {corner} uses value {value}, but there are {n_values} values"
            ));
        };
        match *slot {
            Some(first) if first != vertex => {
                return bad(format!(
                    "value {value} is used at vertex {first} and, at corner {corner}, at vertex {vertex}"
                ))
            }
            _ => *slot = Some(vertex),
        }
    }
    Ok(())
}

/// OpenSubdiv's values at a vertex before its first refinement ("siblings"), one id per face
/// corner of a checked layout: corners with the same id are one value.
///
/// `Vtr::internal::FVarLevel::completeTopologyFromFaceValues` (OpenSubdiv 3.5) walks the faces
/// around each vertex in the order of `Vtr::internal::Level::orderVertexFacesAndEdges`: for a
/// vertex whose faces form one consistently oriented fan, from its first face (in face order)
/// for an interior vertex, from the face whose side leaving the vertex is a boundary edge for
/// a boundary vertex, then to the face across the side entering the vertex in the current
/// one; for any other vertex, its faces in face order. Along that order it numbers the
/// distinct values, but when exactly two are known it only compares a new run's value with
/// the first: in the order A, B, A, B the second run of B gets a value of its own. So a vertex
/// has as many values as distinct `vt` plus one when its runs start A, B, A, B. The refinement
/// keeps every one of them (one child value per sibling), which is how osd_catmark_bishop's
/// 3244 (vertex, `vt`) pairs are 3283 values at the start of level 1.
fn sibling_values(offsets: &[usize], vertex_corners: &[u32], value_corners: &[u32]) -> Vec<u32> {
    const NONE: usize = usize::MAX;
    let n = vertex_corners.len();
    let (mut next, mut prev) = (vec![0usize; n], vec![0usize; n]);
    for w in offsets.windows(2) {
        let (start, end) = (w[0], w[1]);
        for c in start..end {
            next[c] = if c + 1 == end { start } else { c + 1 };
            prev[c] = if c == start { end - 1 } else { c - 1 };
        }
    }
    let n_vertices = vertex_corners.iter().max().map_or(0, |&v| v as usize + 1);
    // Vertices whose faces OpenSubdiv does not order: at an edge of three or more sides or
    // a side from a vertex to itself.
    let mut unordered = vec![false; n_vertices];
    let pair = |a: u32, b: u32| (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
    let mut sides: Vec<(u64, usize)> = Vec::with_capacity(n);
    for c in 0..n {
        let (a, b) = (vertex_corners[c], vertex_corners[next[c]]);
        if a == b {
            unordered[a as usize] = true;
        } else {
            sides.push((pair(a, b), c));
        }
    }
    sides.sort_unstable();
    // The other side of the edge of the side starting at each corner (`NONE`: a boundary).
    let mut partner = vec![NONE; n];
    for group in sides.chunk_by(|x, y| x.0 == y.0) {
        match group {
            [(_, c), (_, d)] => {
                partner[*c] = *d;
                partner[*d] = *c;
            }
            [_] => {}
            more => {
                for &(_, c) in more {
                    unordered[vertex_corners[c] as usize] = true;
                    unordered[vertex_corners[next[c]] as usize] = true;
                }
            }
        }
    }
    let mut by_vertex: Vec<usize> = (0..n).collect();
    by_vertex.sort_by_key(|&c| vertex_corners[c]);

    let mut ids = vec![0u32; n];
    let mut visited = vec![false; n];
    let (mut order, mut unique, mut sibling) = (Vec::new(), Vec::new(), Vec::new());
    let mut next_id = 0u32;
    for around in by_vertex.chunk_by(|&c, &d| vertex_corners[c] == vertex_corners[d]) {
        let v = vertex_corners[around[0]];
        order.clear();
        let fan = !unordered[v as usize] && {
            let mut leading = around.iter().filter(|&&c| partner[c] == NONE);
            let start = match (leading.next(), leading.next()) {
                (None, _) => Some(around[0]),
                (Some(&c), None) => Some(c),
                (Some(_), Some(_)) => None,
            };
            let mut ok = start.is_some();
            if let Some(start) = start {
                order.push(start);
                visited[start] = true;
                let mut current = start;
                // The face across the side entering `v`, whose corner there starts the side.
                while ok && order.len() < around.len() {
                    let q = partner[prev[current]];
                    ok = q != NONE && vertex_corners[q] == v && !visited[q];
                    if ok {
                        visited[q] = true;
                        order.push(q);
                        current = q;
                    }
                }
            }
            for &c in &order {
                visited[c] = false;
            }
            ok
        };
        if !fan {
            order.clear();
            order.extend_from_slice(around);
        }
        // The distinct values along the order, as OpenSubdiv numbers them.
        unique.clear();
        sibling.clear();
        for (i, &c) in order.iter().enumerate() {
            let value = value_corners[c];
            if i == 0 {
                unique.push(value);
                sibling.push(0);
            } else if value == value_corners[order[i - 1]] {
                sibling.push(sibling[i - 1]);
            } else if unique.len() == 1 || (unique.len() == 2 && unique[0] != value) {
                sibling.push(unique.len());
                unique.push(value);
            } else if let Some(k) = unique.iter().position(|&u| u == value) {
                sibling.push(k);
            } else {
                sibling.push(unique.len());
                unique.push(value);
            }
        }
        for (&c, &k) in order.iter().zip(&sibling) {
            ids[c] = next_id + k as u32;
        }
        next_id += unique.len() as u32;
    }
    ids
}

/// The sibling values ([`sibling_values`]) of the corners with `keep(corner)` beyond their
/// distinct values.
fn split_values_of(value_corners: &[u32], siblings: &[u32], keep: impl Fn(usize) -> bool) -> u64 {
    let distinct = |ids: &mut dyn Iterator<Item = u32>| {
        let mut seen: Vec<bool> = Vec::new();
        let mut count = 0u64;
        for id in ids {
            let i = id as usize;
            if i >= seen.len() {
                seen.resize(i + 1, false);
            }
            if !seen[i] {
                seen[i] = true;
                count += 1;
            }
        }
        count
    };
    let kept = |ids: &[u32]| -> Vec<u32> {
        ids.iter()
            .enumerate()
            .filter(|&(c, _)| keep(c))
            .map(|(_, &i)| i)
            .collect()
    };
    let (values, sibs) = (kept(value_corners), kept(siblings));
    distinct(&mut sibs.into_iter()) - distinct(&mut values.into_iter())
}

/// The surface edges whose sides do not all carry the same pair of values (checked layout).
fn seam_edges(offsets: &[usize], vertex_corners: &[u32], value_corners: &[u32]) -> u64 {
    let pair = |a: u32, b: u32| (u64::from(a) << 32) | u64::from(b);
    // (surface edge, its values in the order of its vertices) for every side.
    let mut sides: Vec<(u64, u64)> = Vec::with_capacity(vertex_corners.len());
    for w in offsets.windows(2) {
        let (start, end) = (w[0], w[1]);
        for c in start..end {
            let n = if c + 1 == end { start } else { c + 1 };
            let (a, b) = (vertex_corners[c], vertex_corners[n]);
            let (p, q) = (value_corners[c], value_corners[n]);
            match a.cmp(&b) {
                std::cmp::Ordering::Less => sides.push((pair(a, b), pair(p, q))),
                std::cmp::Ordering::Greater => sides.push((pair(b, a), pair(q, p))),
                std::cmp::Ordering::Equal => {}
            }
        }
    }
    sides.sort_unstable();
    sides.dedup();
    // After dedup, a surface edge appearing twice carries two different value pairs.
    sides
        .chunk_by(|a, b| a.0 == b.0)
        .filter(|same_edge| same_edge.len() > 1)
        .count() as u64
}

/// The names of a [`UvScheme`]'s state: `UV` values, `UE` layout edges, `UBE` layout
/// boundary edges, `F` faces and, for Catmull-Clark, `H` corners.
pub const UV_STATE: [&str; 5] = ["UV", "UE", "UBE", "F", "H"];

/// The recurrence of the UV values under one rule, over the layout's statistics.
///
/// The matrix is the rule's matrix for any face list applied to the layout (module docs),
/// with the layout's boundary edges as a component of their own:
///
/// - **4:1 split** (Loop, midpoint, butterfly, icosphere): one value per old value and per
///   layout edge; each layout edge splits in two and each triangle adds three interior edges;
///   a triangle becomes four. State `(UV, UE, UBE, F)`:
///   `UV' = UV + UE`, `UE' = 2 UE + 3 F`, `UBE' = 2 UBE`, `F' = 4 F`.
/// - **`tri-split-N`** (1:N² split, UVs linear within each face): `N - 1` values per layout
///   edge, `(N-1)(N-2)/2` inside each triangle; a layout edge splits into `N`, each triangle
///   adds `3N(N-1)/2` interior edges. State `(UV, UE, UBE, F)`:
///   `UV' = UV + (N-1) UE + (N-1)(N-2)/2 F`, `UE' = N UE + 3N(N-1)/2 F`, `UBE' = N UBE`,
///   `F' = N² F`.
/// - **Catmull-Clark** (OpenSubdiv's face-varying refinement, every linear-interpolation mode
///   alike: the mode changes the values, not their number): one value per face point, per
///   layout edge and per old value; each face of degree `n` adds `n` interior edges and becomes
///   `n` quads. State `(UV, UE, UBE, F, H)`, `H` the corners:
///   `UV' = UV + UE + F`, `UE' = 2 UE + H`, `UBE' = 2 UBE`, `F' = H`, `H' = 4 H`.
///
/// The dual rules carry UVs corner by corner on the surface's refinement (the rules in
/// `halfedge::refine::face_varying`), so the count is the surface's plus what the seams add.
/// Write `S` for the seam edges (interior edges whose two faces disagree at either end;
/// surface boundary edges are not seams), `E`, `BE` for the surface's edges and boundary
/// edges; the layout has `UE = E + S` edges (a seam is two layout edges) and
/// `UBE = BE + 2 S` boundary edges (both sides of every seam). State `(UV, UE, UBE, S)`
/// ([`UV_SEAM_STATE`]), from the layout's `V`, `E`, `BE` and `seam_edges`:
///
/// - **Doo-Sabin** (`doo-sabin`, `doo-sabin-boundary`): one value per new vertex (a face
///   corner's Doo-Sabin point in its face's chart, a boundary Chaikin point in the chart of
///   its edge's face): `V' = 2E + BE`; the edge face of a seam edge takes the chart of one of
///   its faces, whose Chaikin points replace the two corners from the other face: 2 more per
///   seam, so `UV' = 2E + BE + 2S`. Seams of the next level: each seam edge's edge face
///   disagrees with the other face's shrunken face along one edge and with the two vertex
///   faces at its ends along one edge each (they keep the corners' own values); non-seam and
///   boundary edges give none: `S' = 3S`. With `E' = 4E + BE`, `BE' = 2BE`:
///   `UV' = 2UE + UBE - 2S`, `UE' = 4UE + UBE - 3S`, `UBE' = 2UBE + 2S`, `S' = 3S`, so
///   `UV(s) = V(s) + 2 * 3^(s-1) * S0` for `s >= 1`.
/// - **Mid-edge** (`mid-edge`, `mid-edge-boundary`): one value per (edge, side), the
///   midpoint in that face's chart, one for an edge that is not a seam and two for a seam
///   (`UE`), and with boundary one per kept boundary vertex (its value unchanged): `UV' = E +
///   S + BE`. Seams of the next level: the vertex face at `v` takes the value of each edge on
///   the side of the face of the half-edge leaving `v` along it, so the new edge between a
///   face face and a vertex face is a seam exactly when the old edge it crosses is: two per
///   seam, `S' = 2S`. With `E' = 2E + BE`, `BE' = 2BE`: `UV' = UE + UBE - 2S`,
///   `UE' = 2UE + UBE - 2S`, `UBE' = 2UBE`, `S' = 2S`.
///
/// Without seams both give the surface's vertices from level 1 on. The `UV` column of the
/// matrix is zero (the values of a level follow from the level before's edges and seams).
///
/// The `UV` component equals the real count from level [`UvScheme::VALID_FROM`] on; level 0
/// is [`UvCounts::used_vt`] ([`UvScheme::values_at`] gives both).
///
/// ```
/// use schemes::uv::{uv_scheme, UvCounts};
/// use schemes::{BigInt, Rule};
///
/// // spot_control_mesh's layout: 267 values, 438 edges, 144 boundary edges; 180 faces, 732
/// // corners. OpenSubdiv counts 885, 3225, 12297, 48009 values at levels 1-4.
/// let spot = UvCounts { values: 267, edges: 438, boundary_edges: 144, used_vt: 267,
///                       faces: 180, corners: 732, ..UvCounts::default() };
/// let cc = uv_scheme(Rule::CatmullClark)?;
/// let uv: Vec<BigInt> = (1..=4).map(|s| cc.values_at(&spot, s)).collect::<Result<_, _>>()?;
/// assert_eq!(uv, [885, 3225, 12297, 48009].map(BigInt::from));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UvScheme {
    rule: Rule,
    /// The recurrence over one period (the step matrix unless the rule alternates steps).
    recurrence: Recurrence,
    /// Whether the values start from OpenSubdiv's sibling values ([`UvScheme::splits_siblings`]).
    siblings: bool,
    /// The step matrices in turn (one, that of `recurrence`, unless the rule alternates).
    steps: StepRule,
    /// Whether the state is [`UV_SEAM_STATE`] (the dual rules) rather than [`UV_STATE`].
    seams: bool,
}

/// A rule (or a scheme) whose UV values are not counted: schemes without a subdivision rule,
/// `TriSplit(n)` with `n < 2`, and compositions that chain a dual rule (Doo-Sabin, mid-edge)
/// with a rule of the other kind (their UV states do not convert: [`UvCounter`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub struct NotCounted {
    /// The rule, when there is one.
    pub rule: Option<Rule>,
    /// In a composition, the rule of the other kind chained with `rule`.
    pub composed_with: Option<Rule>,
}

impl NotCounted {
    /// `rule` (or a scheme without a rule) does not count UV values.
    pub fn rule(rule: Option<Rule>) -> NotCounted {
        NotCounted {
            rule,
            composed_with: None,
        }
    }
}

impl fmt::Display for NotCounted {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.rule, self.composed_with) {
            (Some(rule), Some(other)) => write!(
                f,
                "{rule} does not count UV values composed with {other} (their UV states do not convert)"
            ),
            (Some(rule), None) => write!(f, "{rule} does not count UV values (no UV rule yet)"),
            (None, _) => f.write_str("a scheme without a subdivision rule does not count UV values"),
        }
    }
}

/// The UV recurrence of `rule` ([`UvScheme`]).
///
/// # Errors
///
/// [`NotCounted`] for `TriSplit(n)` with `n < 2` or too large for its matrix.
///
/// √3 is the cycle `[A, B]` of `sqrt3-boundary` over [`SQRT3_UV_STATE`] (on a closed mesh
/// both steps count alike; [`UvScheme::for_scheme`] gives `sqrt3` step A alone):
///
/// ```
/// use schemes::uv::{uv_scheme, UvCounts};
/// use schemes::{BigInt, Rule};
///
/// // One triangle, its own chart: 3 values, 3 boundary edges, no seam.
/// let tri = UvCounts { values: 3, edges: 3, boundary_edges: 3, used_vt: 3, faces: 1,
///                      corners: 3, ..UvCounts::default() };
/// let sqrt3 = uv_scheme(Rule::Sqrt3)?;
/// assert_eq!(sqrt3.recurrence().names(), ["UV", "UBE", "S", "F"]);
/// assert_eq!(sqrt3.period(), 2);
/// // Step A adds the centroid; step B the 3 centroids less the 3 boundary faces, plus two
/// // trisection points on each: as the surface's vertices without seams.
/// let uv: Vec<BigInt> = (1..=3).map(|s| sqrt3.values_at(&tri, s)).collect::<Result<_, _>>()?;
/// assert_eq!(uv, [4, 10, 19].map(BigInt::from));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn uv_scheme(rule: Rule) -> std::result::Result<UvScheme, NotCounted> {
    let not = NotCounted::rule(Some(rule));
    // The rule's scheme for any face list, and how many boundary edges a layout boundary
    // edge splits into.
    let (general, split): (Scheme, i64) = match rule {
        Rule::Loop | Rule::Midpoint | Rule::Butterfly | Rule::Icosphere => (loop_general(), 2),
        Rule::TriSplit(n) => (tri_split(u64::from(n)).map_err(|_| not)?, i64::from(n)),
        Rule::CatmullClark => (catmull_clark_general(), 2),
        Rule::Sqrt3 => return sqrt3_uv_scheme(&[sqrt3_step_a(), sqrt3_step_b()]).ok_or(not),
        Rule::DooSabin => return dual_uv_scheme(rule, &DOO_SABIN_UV),
        Rule::MidEdge => return dual_uv_scheme(rule, &MID_EDGE_UV),
    };
    let recurrence = with_boundary_edges(general.matrix(), split).ok_or(not)?;
    Ok(UvScheme {
        rule,
        steps: StepRule::single(recurrence.matrix().clone()),
        recurrence,
        siblings: matches!(rule, Rule::Loop | Rule::CatmullClark),
        seams: false,
    })
}

/// The names of the UV state of the dual rules (Doo-Sabin, mid-edge): `UV` values, `UE`
/// layout edges, `UBE` layout boundary edges, `S` seam edges.
pub const UV_SEAM_STATE: [&str; 4] = ["UV", "UE", "UBE", "S"];

/// Doo-Sabin's UV matrix over [`UV_SEAM_STATE`] ([`UvScheme`]).
const DOO_SABIN_UV: [[i64; 4]; 4] = [[0, 2, 1, -2], [0, 4, 1, -3], [0, 0, 2, 2], [0, 0, 0, 3]];

/// Mid-edge's UV matrix over [`UV_SEAM_STATE`] ([`UvScheme`]).
const MID_EDGE_UV: [[i64; 4]; 4] = [[0, 1, 1, -2], [0, 2, 1, -2], [0, 0, 2, 0], [0, 0, 0, 2]];

fn dual_uv_scheme(rule: Rule, rows: &[[i64; 4]; 4]) -> std::result::Result<UvScheme, NotCounted> {
    let matrix = IntMatrix::from_fn(4, |i, j| rows[i][j]);
    let recurrence =
        Recurrence::with_names(matrix, UV_SEAM_STATE).map_err(|_| NotCounted::rule(Some(rule)))?;
    Ok(UvScheme {
        rule,
        steps: StepRule::single(recurrence.matrix().clone()),
        recurrence,
        siblings: false,
        seams: true,
    })
}

/// The names of √3's UV state: `UV` values, `UBE` layout boundary edges, `S` seam edges and
/// `F` faces.
pub const SQRT3_UV_STATE: [&str; 4] = ["UV", "UBE", "S", "F"];

/// √3's plain step (`sqrt3`, and step A of `sqrt3-boundary`) over [`SQRT3_UV_STATE`]:
/// `UV' = UV + 2 S + F`, `UBE' = UBE + 4 S`, `S' = 3 S`, `F' = 3 F` ([`sqrt3_uv_scheme`]).
fn sqrt3_step_a() -> IntMatrix {
    rows4([[1, 0, 2, 1], [0, 1, 4, 0], [0, 0, 3, 0], [0, 0, 0, 3]])
}

/// √3's step B (boundary edges trisected) over [`SQRT3_UV_STATE`]:
/// `UV' = UV + UBE + F`, `UBE' = 3 UBE`, `S' = 3 S`, `F' = 3 F` ([`sqrt3_uv_scheme`]).
fn sqrt3_step_b() -> IntMatrix {
    rows4([[1, 1, 0, 1], [0, 3, 0, 0], [0, 0, 3, 0], [0, 0, 0, 3]])
}

/// A 4x4 matrix from its rows.
fn rows4(rows: [[i64; 4]; 4]) -> IntMatrix {
    IntMatrix::from_fn(4, |i, j| rows[i][j])
}

/// The UV recurrence of √3 (Kobbelt's rule, UVs linear), over the state
/// `(UV, UBE, S, F)` ([`SQRT3_UV_STATE`]): `steps` are `[A]` for `sqrt3` (closed meshes) and
/// `[A, B]` for `sqrt3-boundary` (steps A and B alternate, A first).
///
/// **The UV rule** (`halfedge::refine::face_varying`): old values stay; the centroid of a
/// face gets the mean of its three values; the triangle of an interior half-edge `g` (its
/// target, `rep(g)`, `rep(twin g)`) lies in one chart, that of `g`'s face in a plain step or
/// step A and that of the face across `g` in step B, and its point from the other face is
/// replaced by the midpoint of the edge in its own chart when the edge is a **seam** (its
/// faces disagree at either end; a boundary edge is none). Step B's trisection points of a
/// boundary edge `a -> b` get `(2a + b)/3` and `(a + 2b)/3` in their face's chart.
///
/// **Plain step / step A.** Every face adds its centroid (`F` values) and every seam edge two
/// midpoints, one per side (`2 S`); every old value stays used (a corner at `v` of face `f` is
/// a corner of the triangle of `f`'s half-edge ending at `v`, or of a boundary triangle). A new
/// edge is a seam when it is the flip of a seam edge, or the spoke from a corner `v` of `f` to
/// its centroid when `f`'s edge leaving `v` is a seam: `S' = 3 S`. Boundary edges stay
/// (`BE' = BE`) and the layout's boundary is the surface's plus both sides of every seam,
/// `UBE = BE + 2 S`: `UBE' = UBE + 4 S`. So `UV' = UV + 2 S + F`, `F' = 3 F`.
///
/// **Step B.** A face with a boundary edge (one each after step A: `BE` of them) adds two
/// trisection points instead of a centroid: `F - BE + 2 BE` values, and `2 S` midpoints, so
/// `UV' = UV + F + BE + 2 S = UV + UBE + F`. Homes: in step B the triangle of `g` takes the
/// chart of the face across `g`, so a corner is unused only at the source `a` of a boundary
/// edge `a -> b` in its face; that face is the last of the fan around `a`, and after step A
/// the last two faces of every boundary fan are one old face's and share its value, so every
/// old value stays used (with the chart of `g`'s own face the first face of each fan would
/// lose its corner, and its value when no other face at the vertex has it). Seams: flips of
/// seams, and the spoke at `v` when the face's edge entering `v` is a seam; on a trisected
/// face the edge entering `a` is the spoke of step A from `a` to the centroid beside the
/// boundary edge, never a seam, so again `S' = 3 S`; `BE' = 3 BE`, so `UBE' = 3 UBE`.
///
/// On a closed mesh `UBE = 2 S` and both steps give the same counts. Each step holds from
/// level 1 on from `UV0 = V` (no sibling values); the `F` and `BE` of the surface follow
/// [`crate::catalog::sqrt3_boundary`]. Holes are refused with √3 (its faces do not nest).
///
/// ```text
///        A = [1 0 2 1]        B = [1 1 0 1]
///            [0 1 4 0]            [0 3 0 0]
///            [0 0 3 0]            [0 0 3 0]
///            [0 0 0 3]            [0 0 0 3]
/// ```
fn sqrt3_uv_scheme(steps: &[IntMatrix]) -> Option<UvScheme> {
    let steps = StepRule::try_new(None, steps.to_vec()).ok()?;
    let period = steps.rotated_product(0)?;
    Some(UvScheme {
        rule: Rule::Sqrt3,
        recurrence: Recurrence::with_names(period, SQRT3_UV_STATE).ok()?,
        siblings: false,
        steps,
        seams: false,
    })
}

/// The general matrix over `V, E, F[, H]` with `BE` inserted after `E` (its own component,
/// multiplied by `split`), renamed to [`UV_STATE`].
fn with_boundary_edges(general: &IntMatrix, split: i64) -> Option<Recurrence> {
    let dim = general.dim() + 1;
    // Old index of each new component; `None` for UBE.
    let old = |i: usize| match i {
        0 | 1 => Some(i),
        2 => None,
        _ => Some(i - 1),
    };
    let matrix = IntMatrix::from_fn(dim, |i, j| match (old(i), old(j)) {
        (Some(a), Some(b)) => general.get(a, b),
        (None, None) => split,
        _ => 0,
    });
    Recurrence::with_names(matrix, UV_STATE[..dim].iter().copied()).ok()
}

impl UvScheme {
    /// The first level at which the `UV` component of the recurrence is the real count of UV
    /// values (level 0 counts the `vt` entries used, which differ when a `vt` is shared by two
    /// vertices).
    pub const VALID_FROM: u64 = 1;

    /// The UV recurrence of a scheme's rule ([`uv_scheme`]). A scheme for any face list (one
    /// whose [`MeshClass`](crate::MeshClass) does not need a manifold mesh: `loop-general`,
    /// `catmull-clark-general`, `catmull-clark-quad`) is run by the face-list subdividers, which refine the layout as
    /// a mesh: its values start from `V`, without OpenSubdiv's sibling values.
    ///
    /// # Errors
    ///
    /// [`NotCounted`] for a scheme without a rule or whose rule has no UV recurrence.
    ///
    /// √3 alternates its steps A and B only on meshes with a boundary (`sqrt3-boundary`); a
    /// scheme of period 1 with the √3 rule (`sqrt3`, closed meshes) counts with step A alone.
    pub fn for_scheme(scheme: &Scheme) -> std::result::Result<UvScheme, NotCounted> {
        let rule = scheme.subdivision_rule().ok_or(NotCounted::rule(None))?;
        if rule == Rule::Sqrt3 && scheme.period() == 1 {
            return sqrt3_uv_scheme(&[sqrt3_step_a()]).ok_or(NotCounted::rule(Some(rule)));
        }
        let mut uv = uv_scheme(rule)?;
        uv.siblings &= scheme.mesh_class().needs_manifold();
        Ok(uv)
    }

    /// The rule.
    pub fn rule(&self) -> Rule {
        self.rule
    }

    /// The recurrence over `UV, UE, UBE, F` (and `H` for Catmull-Clark; `UV, UBE, S, F` for
    /// √3, [`SQRT3_UV_STATE`]): the step matrix, or for a rule that alternates steps
    /// ([`period`](Self::period) > 1) the matrix over one period (see [`phases`](Self::phases)).
    pub fn recurrence(&self) -> &Recurrence {
        &self.recurrence
    }

    /// The number of step matrices applied in turn: 2 for `sqrt3-boundary`, else 1.
    pub fn period(&self) -> u64 {
        self.steps.period()
    }

    /// The matrix of step `i` (from level `i - 1` to level `i`, `i >= 1`).
    ///
    /// # Panics
    ///
    /// Panics if `i` is zero.
    pub fn matrix_of_step(&self, i: u64) -> &IntMatrix {
        self.steps.matrix_of_step(i)
    }

    /// One closed-form phase per residue class of the period, as [`Scheme::phases`]: for
    /// `s = first_level + period t` the state is the phase's recurrence powered `t` times from
    /// the state at `first_level` ([`state_at`](Self::state_at)).
    pub fn phases(&self) -> Vec<crate::Phase> {
        let p = self.period();
        (0..p)
            .filter_map(|r| {
                let m = self.steps.rotated_product(r as usize)?;
                Some(crate::Phase {
                    description: crate::scheme::phase_text(p, r),
                    recurrence: Recurrence::with_names(m, self.recurrence.names().iter()).ok()?,
                    first_level: r,
                    period: p,
                    last_level: None,
                    stage: 0,
                })
            })
            .collect()
    }

    /// `state` advanced by `steps` steps from the start of the cycle.
    fn advance(&self, state: &[BigInt], steps: u64) -> Result<Vec<BigInt>> {
        let p = self.period();
        let mut x = self.recurrence.state_at(state, steps / p)?;
        for m in &self.steps.cycle()[..(steps % p) as usize] {
            x = crate::scheme::apply(m, &x);
        }
        Ok(x)
    }

    /// Whether the face-varying refinement is OpenSubdiv's (Loop and Catmull-Clark on a
    /// manifold mesh), which starts from its sibling values ([`UvCounts::split_values`]); the
    /// other rules, and the face-list schemes ([`UvScheme::for_scheme`]), refine the layout as
    /// a mesh, from its values `V`.
    pub fn splits_siblings(&self) -> bool {
        self.siblings
    }

    /// The initial state from the layout's statistics: `[UV0, E, BE, F]` or
    /// `[UV0, E, BE, F, H]`, `UV0` being `V + split_values` for Loop and Catmull-Clark
    /// ([`splits_siblings`](Self::splits_siblings)) and `V` for the other rules; for the dual
    /// rules `[V, E, BE, seam_edges]`.
    pub fn initial_state(&self, uv: &UvCounts) -> Vec<BigInt> {
        let split = if self.splits_siblings() {
            uv.split_values
        } else {
            0
        };
        if self.rule == Rule::Sqrt3 {
            return [uv.values, uv.boundary_edges, uv.seam_edges, uv.faces]
                .map(BigInt::from)
                .to_vec();
        }
        if self.seams {
            return [uv.values, uv.edges, uv.boundary_edges, uv.seam_edges]
                .iter()
                .map(|&x| BigInt::from(x))
                .collect();
        }
        [
            uv.values + split,
            uv.edges,
            uv.boundary_edges,
            uv.faces,
            uv.corners,
        ][..self.recurrence.dim()]
            .iter()
            .map(|&x| BigInt::from(x))
            .collect()
    }

    /// The state at `level` (its `UV` component is the count from level 1 on).
    ///
    /// # Errors
    ///
    /// None in practice (the state has the recurrence's length); [`Error::Recurrence`] from
    /// the powering.
    pub fn state_at(&self, uv: &UvCounts, level: u64) -> Result<Vec<BigInt>> {
        self.advance(&self.initial_state(uv), level)
    }

    /// The number of UV values at `level`: [`UvCounts::used_vt`] at level 0, the recurrence's
    /// `UV` from level 1 on.
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at).
    pub fn values_at(&self, uv: &UvCounts, level: u64) -> Result<BigInt> {
        if level < Self::VALID_FROM {
            return Ok(BigInt::from(uv.used_vt));
        }
        let mut state = self.state_at(uv, level)?;
        Ok(state.swap_remove(0))
    }
}

/// The UV values of a mesh under a scheme plan: the [`UvScheme`] of every stage's rule from
/// the layout's statistics, chained across the stages of a composition, as
/// [`Counter`](crate::Counter) counts `V`, `E`, `F` ([`Counter::uv_counter`](crate::Counter::uv_counter)
/// builds one). It adds the `UV` column to a counter's rows ([`extend_rows`](Self::extend_rows)).
///
/// At a stage boundary the next stage starts from the state reached, the corners `H` (when
/// the next stage is Catmull-Clark and the previous one a triangle split) being `3 F`: a
/// triangle split makes triangles.
/// The dual rules' state ([`UV_SEAM_STATE`]) converts between Doo-Sabin and mid-edge
/// stages only.
///
/// ```
/// use schemes::uv::UvCounts;
/// use schemes::{BigInt, Counter, Plan};
///
/// let spot = UvCounts { values: 267, edges: 438, boundary_edges: 144, used_vt: 267,
///                       faces: 180, corners: 732, ..UvCounts::default() };
/// let counter = Counter::from(Plan::parse("catmull-clark")?);
/// let uv = counter.uv_counter(&spot)?;
/// assert_eq!(uv.values_at(2)?, BigInt::from(3225));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UvCounter {
    /// Each stage's UV scheme and its number of levels (`None`: unbounded).
    stages: Vec<(UvScheme, Option<u64>)>,
    uv: UvCounts,
}

impl UvCounter {
    /// The UV values of the layout `uv` under `plan`.
    ///
    /// # Errors
    ///
    /// [`NotCounted`] for the first stage whose scheme has no UV recurrence, and for a
    /// composition of a dual rule with a rule of the other kind.
    pub fn new(plan: &Plan, uv: UvCounts) -> std::result::Result<UvCounter, NotCounted> {
        let stages: Vec<(UvScheme, Option<u64>)> = plan
            .stages()
            .iter()
            .map(|st| Ok((UvScheme::for_scheme(st.scheme())?, st.levels())))
            .collect::<std::result::Result<_, NotCounted>>()?;
        // The dual rules' state (seams) and the others' (faces, corners) do not convert.
        if let (Some(dual), Some(other)) = (
            stages.iter().find(|(s, _)| s.seams),
            stages.iter().find(|(s, _)| !s.seams),
        ) {
            return Err(NotCounted {
                rule: Some(dual.0.rule),
                composed_with: Some(other.0.rule),
            });
        }
        Ok(UvCounter { stages, uv })
    }

    /// The dimension of the last stage's UV recurrence (the order of its UV values).
    pub fn dim(&self) -> usize {
        self.stages.last().map_or(0, |(s, _)| s.recurrence.dim())
    }

    /// The layout's statistics counted from.
    pub fn uv_counts(&self) -> &UvCounts {
        &self.uv
    }

    /// The single stage's UV scheme, when the plan is one scheme.
    pub fn single(&self) -> Option<&UvScheme> {
        match self.stages.as_slice() {
            [(only, None)] => Some(only),
            _ => None,
        }
    }

    /// The index of the stage producing `level`, its first level and the state there.
    fn stage_state(&self, level: u64) -> Result<(usize, u64, Vec<BigInt>)> {
        let mut state = self.stages[0].0.initial_state(&self.uv);
        let mut start = 0u64;
        // The surface's seam edges at `start` (for a √3 stage after another).
        let mut seams = BigInt::from(self.uv.seam_edges);
        for (i, (scheme, levels)) in self.stages.iter().enumerate() {
            let end = levels.map_or(u64::MAX, |k| start.saturating_add(k));
            if level <= end {
                return Ok((i, start, state));
            }
            let Some((next, _)) = self.stages.get(i + 1) else {
                return Err(Error::LevelBeyondPlan { level, last: end });
            };
            let reached = scheme.advance(&state, end - start)?;
            if next.rule == Rule::Sqrt3 {
                let k = u32::try_from(end - start).map_err(|_| Error::LevelBeyondPlan {
                    level,
                    last: u64::from(u32::MAX),
                })?;
                seams *= BigInt::from(seam_factor(scheme.rule)).pow(k);
            }
            state = next.convert(scheme.recurrence.names(), reached, &seams);
            start = end;
        }
        // The last stage is unbounded or has returned the error above.
        Err(Error::LevelBeyondPlan { level, last: start })
    }

    /// The state at `level`, in the names of the stage that produced it.
    ///
    /// # Errors
    ///
    /// [`Error::LevelBeyondPlan`] past a bounded plan; [`Error::Recurrence`] from powering.
    pub fn state_at(&self, level: u64) -> Result<Vec<BigInt>> {
        let (i, start, state) = self.stage_state(level)?;
        self.stages[i].0.advance(&state, level - start)
    }

    /// The number of UV values at `level` ([`UvCounts::used_vt`] at level 0).
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at).
    pub fn values_at(&self, level: u64) -> Result<BigInt> {
        if level < UvScheme::VALID_FROM {
            return Ok(BigInt::from(self.uv.used_vt));
        }
        Ok(self.state_at(level)?.swap_remove(0))
    }

    /// Adds the `UV` column to a table of `columns` and `rows` (from
    /// [`Counter::columns`](crate::Counter::columns) and [`Counter::rows`](crate::Counter::rows)),
    /// each row's value at its level.
    ///
    /// # Errors
    ///
    /// As [`values_at`](Self::values_at).
    pub fn extend_rows(&self, columns: &mut Vec<String>, rows: &mut [Row]) -> Result {
        columns.push(UV_COLUMN.to_string());
        // The last level of each stage; a level at a boundary belongs to the earlier stage.
        let mut ends = Vec::with_capacity(self.stages.len());
        let mut end = 0u64;
        for (_, levels) in &self.stages {
            end = levels.map_or(u64::MAX, |k| end.saturating_add(k));
            ends.push(end);
        }
        // Consecutive levels of one stage step its recurrence once instead of powering.
        let mut previous: Option<(u64, usize, Vec<BigInt>)> = None;
        for row in rows {
            let level = row.level;
            if level < UvScheme::VALID_FROM {
                row.values.push(Some(BigInt::from(self.uv.used_vt)));
                continue;
            }
            let stage = ends.iter().position(|&e| level <= e);
            let state = match (&previous, stage) {
                (Some((l, i, state)), Some(stage)) if l + 1 == level && *i == stage => {
                    // Step `level - start` of the stage.
                    let start = if stage == 0 { 0 } else { ends[stage - 1] };
                    let m = self.stages[stage].0.matrix_of_step(level - start);
                    crate::scheme::apply(m, state)
                }
                _ => self.state_at(level)?,
            };
            row.values.push(Some(state[0].clone()));
            previous = stage.map(|i| (level, i, state));
        }
        Ok(())
    }

    /// A digit summary ([`SUMMARY_DIGITS`](crate::SUMMARY_DIGITS) each end) of the UV values
    /// at `level` from the exact closed form, for a single scheme; `None` for a composition.
    pub fn summary_at(&self, level: u64) -> Option<recurrence::DigitSummary> {
        if level < UvScheme::VALID_FROM {
            let v = BigInt::from(self.uv.used_vt);
            return Some(recurrence::digit_summary(&v, crate::SUMMARY_DIGITS));
        }
        let single = self.single()?;
        // The phase of `level` (the only one unless the rule alternates steps).
        let p = single.period();
        let phase = single.phases().into_iter().nth((level % p) as usize)?;
        let x0 = single.state_at(&self.uv, phase.first_level).ok()?;
        let form = phase.recurrence.closed_form();
        let mut sums = form
            .summary_at(&x0, level / p, crate::SUMMARY_DIGITS)
            .ok()?;
        Some(sums.swap_remove(0))
    }

    /// An estimate of log10 of the largest component of the UV state at `level` (at least the
    /// UV values'), for resource guards: the state at the producing stage's first level exactly, then [`Counter::estimated_log10`](crate::Counter::estimated_log10)
    /// of that stage's recurrence.
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at).
    pub fn estimated_log10(&self, level: u64) -> Result<f64> {
        let (i, start, state) = self.stage_state(level)?;
        let scheme = &self.stages[i].0;
        let counter = crate::Counter::from(scheme.recurrence.clone());
        // Whole periods of the stage's recurrence, rounded up: at least the state reached.
        let p = scheme.period();
        counter.estimated_log10(&state, (level - start).div_ceil(p))
    }
}

/// The name of the UV column of a counts table (`"UV"` in text, CSV and JSON).
pub const UV_COLUMN: &str = "UV";

impl UvScheme {
    /// `state` (another UV scheme's, over `names`) in this scheme's names: the common
    /// components kept, `H = 3 F` added when missing (a triangle split's output), `H`
    /// dropped when unused; into √3's state the surface's `seams` (`S`), out of it
    /// `UE = (3 F + UBE) / 2` (a layout of triangles).
    fn convert(&self, names: &[String], state: Vec<BigInt>, seams: &BigInt) -> Vec<BigInt> {
        let get = |name: &str| {
            names
                .iter()
                .position(|n| n == name)
                .map(|i| state[i].clone())
        };
        let faces = get("F").unwrap_or_default();
        self.recurrence
            .names()
            .iter()
            .map(|name| {
                get(name).unwrap_or_else(|| match name.as_str() {
                    "H" => BigInt::from(3) * &faces,
                    "S" => seams.clone(),
                    "UE" => (BigInt::from(3) * &faces + get("UBE").unwrap_or_default()) / 2,
                    _ => BigInt::default(),
                })
            })
            .collect()
    }
}

/// How many seam edges each seam edge of the surface becomes in one step of `rule`: the
/// face-refining rules split it in `N` (their other new edges lie inside one face and join
/// values of that face), √3 makes three of it ([`sqrt3_uv_scheme`]), Doo-Sabin three and
/// mid-edge two ([`UvScheme`]).
fn seam_factor(rule: Rule) -> u32 {
    match rule {
        Rule::Loop
        | Rule::Midpoint
        | Rule::Butterfly
        | Rule::Icosphere
        | Rule::CatmullClark
        | Rule::MidEdge => 2,
        Rule::TriSplit(n) => n,
        Rule::Sqrt3 | Rule::DooSabin => 3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;

    fn layout(faces: &[&[u32]], values: &[&[u32]], vts: &[u32]) -> Result<UvCounts> {
        let mut offsets = vec![0];
        for f in faces {
            offsets.push(offsets.last().unwrap() + f.len());
        }
        let vc: Vec<u32> = faces.iter().flat_map(|f| f.iter().copied()).collect();
        let uc: Vec<u32> = values.iter().flat_map(|f| f.iter().copied()).collect();
        UvCounts::from_layout(&offsets, &vc, &uc, vts, 0)
    }

    #[test]
    fn seams_are_counted_once_per_surface_edge() {
        // Two triangles sharing the edge 0-2; the second has its own value at vertex 2.
        let uv = layout(
            &[&[0, 1, 2], &[0, 2, 3]],
            &[&[0, 1, 2], &[0, 4, 3]],
            &[0, 1, 2, 3, 2],
        )
        .unwrap();
        assert_eq!((uv.values, uv.edges, uv.boundary_edges), (5, 6, 6));
        assert_eq!((uv.seam_edges, uv.boundary_loops, uv.charts), (1, 1, 1));
        // Values 2 and 4 share vt 2: four vt are used.
        assert_eq!((uv.used_vt, uv.faces, uv.corners), (4, 2, 6));
        // No seam when the faces agree.
        let uv = layout(
            &[&[0, 1, 2], &[0, 2, 3]],
            &[&[0, 1, 2], &[0, 2, 3]],
            &[0, 1, 2, 3],
        )
        .unwrap();
        assert_eq!((uv.seam_edges, uv.edges, uv.boundary_edges), (0, 5, 4));
    }

    /// Four quads around vertex 4 (a 3x3 grid), the centre's value in each face given.
    fn around_centre(centre: [u32; 4]) -> UvCounts {
        let faces: [&[u32]; 4] = [&[0, 1, 4, 3], &[1, 2, 5, 4], &[4, 5, 8, 7], &[3, 4, 7, 6]];
        let [a, b, c, d] = centre;
        let values: [&[u32]; 4] = [&[0, 1, a, 3], &[1, 2, 5, b], &[c, 5, 8, 7], &[3, d, 7, 6]];
        layout(&faces, &values, &[0, 1, 2, 3, 4, 5, 6, 7, 8, 4, 4, 4]).unwrap()
    }

    #[test]
    fn a_value_used_twice_apart_around_a_vertex_is_split_once() {
        // Faces 0, 1, 2, 3 are in order around the centre: values A, B, A, B.
        let abab = around_centre([4, 9, 4, 9]);
        assert_eq!((abab.values, abab.split_values), (10, 1));
        let cc = uv_scheme(Rule::CatmullClark).unwrap();
        assert_eq!(cc.initial_state(&abab)[0], BigInt::from(11));
        assert_eq!(
            cc.values_at(&abab, 1).unwrap(),
            BigInt::from(11 + abab.edges + 4)
        );
        // Rules that refine the layout as a mesh do not split.
        let butterfly = uv_scheme(Rule::Butterfly).unwrap();
        assert!(!butterfly.splits_siblings());
        assert_eq!(butterfly.initial_state(&abab)[0], BigInt::from(10));
        // Contiguous runs, or a third value, split nothing.
        for centre in [[4, 4, 9, 9], [4, 9, 4, 10], [4, 9, 10, 9], [4, 4, 4, 4]] {
            assert_eq!(around_centre(centre).split_values, 0, "{centre:?}");
        }
        // Left out faces keep the vertex's values. In OpenSubdiv's order (faces 0, 1, 2, 3,
        // from face 0) face 3 has the second value of B: without face 0 both B values are
        // still written, without face 3 (or face 1) one is.
        let faces: Vec<u32> = [[0, 1, 4, 3], [1, 2, 5, 4], [4, 5, 8, 7], [3, 4, 7, 6]].concat();
        let values: Vec<u32> = [[0, 1, 4, 3], [1, 2, 5, 9], [4, 5, 8, 7], [3, 9, 7, 6]].concat();
        let offsets = [0, 4, 8, 12, 16];
        let kept = |keep: &dyn Fn(usize) -> bool| {
            UvCounts::kept_split_values(&offsets, &faces, &values, 10, keep).unwrap()
        };
        assert_eq!(kept(&|_| true), 1);
        assert_eq!(kept(&|f| f != 0), 1);
        assert_eq!(kept(&|f| f != 3), 0);
        assert_eq!(kept(&|f| f != 1), 0);
    }

    #[test]
    fn bad_layouts_are_named() {
        let err = |offsets: &[usize], vc: &[u32], uc: &[u32], n: usize| {
            UvCounts::from_layout(offsets, vc, uc, &vec![0; n], 0)
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            err(&[0, 3], &[0, 1, 2], &[0, 1], 3),
            "UV layout: 3 vertex corners but 2 value corners"
        );
        assert_eq!(
            err(&[0, 2], &[0, 1, 2], &[0, 1, 2], 3),
            "UV layout: face offsets must run from 0 to the 3 corners, but run from 0 to 2"
        );
        assert_eq!(
            err(&[], &[], &[], 0),
            "UV layout: face offsets must run from 0 to the 0 corners, but run from nothing to nothing"
        );
        assert_eq!(
            err(&[0, 4, 3, 3], &[0, 1, 2], &[0, 1, 2], 3),
            "UV layout: face 1 ends at corner 3 before it starts at corner 4"
        );
        assert_eq!(
            err(&[0, 3], &[0, 1, 2], &[0, 1, 5], 3),
            "UV layout: corner 2 uses value 5, but there are 3 values"
        );
        assert_eq!(
            err(&[0, 3, 6], &[0, 1, 2, 2, 1, 3], &[0, 1, 2, 2, 0, 3], 4),
            "UV layout: value 0 is used at vertex 0 and, at corner 4, at vertex 1"
        );
    }

    /// The UV matrices are the general schemes' matrices on `V, E, F[, H]` plus `BE`.
    #[test]
    fn uv_matrices_extend_the_general_schemes() {
        let rows = |r: Rule| uv_scheme(r).unwrap().recurrence().matrix().to_rows();
        assert_eq!(
            rows(Rule::Loop),
            [[1, 1, 0, 0], [0, 2, 0, 3], [0, 0, 2, 0], [0, 0, 0, 4]]
        );
        assert_eq!(rows(Rule::TriSplit(2)), rows(Rule::Butterfly));
        assert_eq!(
            rows(Rule::TriSplit(3)),
            [[1, 2, 0, 1], [0, 3, 0, 9], [0, 0, 3, 0], [0, 0, 0, 9]]
        );
        assert_eq!(
            rows(Rule::CatmullClark),
            [
                [1, 1, 0, 1, 0],
                [0, 2, 0, 0, 1],
                [0, 0, 2, 0, 0],
                [0, 0, 0, 0, 1],
                [0, 0, 0, 0, 4]
            ]
        );
        assert_eq!(
            rows(Rule::Sqrt3),
            // B A: one period of sqrt3-boundary.
            [[1, 1, 6, 4], [0, 3, 12, 0], [0, 0, 9, 0], [0, 0, 0, 9]]
        );
        assert_eq!(
            uv_scheme(Rule::TriSplit(1)),
            Err(NotCounted::rule(Some(Rule::TriSplit(1))))
        );
        assert_eq!(
            NotCounted::rule(Some(Rule::Sqrt3)).to_string(),
            "sqrt3 does not count UV values (no UV rule yet)"
        );
        // The dual rules count over the layout and its seams.
        assert_eq!(
            rows(Rule::DooSabin),
            [[0, 2, 1, -2], [0, 4, 1, -3], [0, 0, 2, 2], [0, 0, 0, 3]]
        );
        assert_eq!(
            rows(Rule::MidEdge),
            [[0, 1, 1, -2], [0, 2, 1, -2], [0, 0, 2, 0], [0, 0, 0, 2]]
        );
        for rule in [Rule::DooSabin, Rule::MidEdge] {
            let uv = uv_scheme(rule).unwrap();
            assert_eq!(uv.recurrence().names(), UV_SEAM_STATE);
            assert!(!uv.splits_siblings());
        }
        // A custom scheme without a `topology` key has no rule.
        let fib = Scheme::from_toml(
            "name = \"fib\"\nstate = [\"a\", \"b\"]\nmatrix = [[1, 1], [1, 0]]\n",
        )
        .unwrap();
        assert_eq!(UvScheme::for_scheme(&fib), Err(NotCounted::rule(None)));
        let cc = builtin("catmull-clark-quad").unwrap();
        assert_eq!(
            UvScheme::for_scheme(&cc).unwrap().rule(),
            Rule::CatmullClark
        );
        // OpenSubdiv's sibling values on a manifold mesh only: the face-list schemes refine
        // the layout as a mesh.
        for name in ["catmull-clark", "loop", "loop-boundary"] {
            let manifold = builtin(name).unwrap();
            assert!(
                UvScheme::for_scheme(&manifold).unwrap().splits_siblings(),
                "{name}"
            );
        }
        for name in [
            "catmull-clark-quad",
            "catmull-clark-general",
            "loop-general",
        ] {
            let general = builtin(name).unwrap();
            assert!(
                !UvScheme::for_scheme(&general).unwrap().splits_siblings(),
                "{name}"
            );
        }
    }

    /// A layout without seams is the mesh itself: the UV values are the scheme's vertices.
    #[test]
    fn a_layout_without_seams_counts_like_the_mesh() {
        // An open 2x1 quad strip and its triangulation.
        let quads: [&[u32]; 2] = [&[0, 1, 4, 3], &[1, 2, 5, 4]];
        let tris: [&[u32]; 4] = [&[0, 1, 4], &[0, 4, 3], &[1, 2, 5], &[1, 5, 4]];
        let vts = [0, 1, 2, 3, 4, 5];
        for (faces, rule) in [
            (&quads[..], Rule::CatmullClark),
            (&tris[..], Rule::Loop),
            (&tris[..], Rule::TriSplit(4)),
            (&quads[..], Rule::DooSabin),
            (&tris[..], Rule::DooSabin),
            (&quads[..], Rule::MidEdge),
            (&tris[..], Rule::MidEdge),
        ] {
            let uv = layout(faces, faces, &vts).unwrap();
            assert_eq!(uv.seam_edges, 0);
            let mesh = MeshCounts::from_polygons(faces).unwrap();
            let scheme = rule.scheme_for(&mesh).unwrap();
            let uvs = uv_scheme(rule).unwrap();
            for s in 0..5 {
                assert_eq!(
                    uvs.values_at(&uv, s).unwrap(),
                    scheme.counts_at(&mesh, s).unwrap().vertices,
                    "{rule} level {s}"
                );
            }
        }
    }

    #[test]
    fn level_zero_counts_the_used_vt() {
        // One vt used at all three corners of a triangle: three values, one vt.
        let uv = layout(&[&[0, 1, 2]], &[&[0, 1, 2]], &[0, 0, 0]).unwrap();
        assert_eq!((uv.values, uv.used_vt), (3, 1));
        let loop_uv = uv_scheme(Rule::Loop).unwrap();
        assert_eq!(loop_uv.values_at(&uv, 0).unwrap(), BigInt::from(1));
        assert_eq!(loop_uv.values_at(&uv, 1).unwrap(), BigInt::from(6));
    }

    /// Across a composition the UV values of a layout without seams are the plan's vertices.
    #[test]
    fn a_composition_counts_like_the_mesh_without_seams() {
        let tris: [&[u32]; 4] = [&[0, 1, 4], &[0, 4, 3], &[1, 2, 5], &[1, 5, 4]];
        let uv = layout(&tris, &tris, &[0, 1, 2, 3, 4, 5]).unwrap();
        let mesh = MeshCounts::from_polygons(&tris).unwrap();
        for text in [
            "loop-boundary:2,catmull-clark",
            "tri-split-3:1,loop-general:1,catmull-clark-general",
        ] {
            let plan = Plan::parse(text).unwrap();
            let counter = crate::Counter::from(plan.clone());
            let uvc = counter.uv_counter(&uv).unwrap();
            assert_eq!(uvc.single(), None);
            let last = plan.last_level().unwrap_or(5);
            for s in 0..=last {
                assert_eq!(
                    uvc.values_at(s).unwrap(),
                    plan.counts_at(&mesh, s).unwrap().vertices,
                    "{text} level {s}"
                );
            }
            assert!(uvc.estimated_log10(last).unwrap() > 1.0);
            let x0 = plan.initial_state(&mesh).unwrap();
            let mut rows = counter.rows(&x0, 0..=last).unwrap();
            let mut columns = counter.columns();
            uvc.extend_rows(&mut columns, &mut rows).unwrap();
            assert_eq!(columns.last().map(String::as_str), Some(UV_COLUMN));
            for row in &rows {
                let v = counter.columns().iter().position(|c| c == "V").unwrap();
                assert_eq!(row.values.last(), Some(&row.values[v].clone()), "{text}");
            }
        }
        let bounded = crate::Counter::from(Plan::parse("loop-boundary:2").unwrap());
        let err = bounded.uv_counter(&uv).unwrap().values_at(3).unwrap_err();
        assert_eq!(err, Error::LevelBeyondPlan { level: 3, last: 2 });
        let matrix = crate::Counter::from(Recurrence::new(IntMatrix::identity(2)));
        assert_eq!(matrix.uv_counter(&uv), Err(NotCounted::rule(None)));
        // A dual rule chained with a rule of the other kind: their states do not convert.
        let mixed =
            crate::Counter::from(Plan::parse("loop-boundary:1,doo-sabin-boundary").unwrap());
        let err = mixed.uv_counter(&uv).unwrap_err();
        assert_eq!(
            err,
            NotCounted {
                rule: Some(Rule::DooSabin),
                composed_with: Some(Rule::Loop)
            }
        );
        assert_eq!(
            err.to_string(),
            "doo-sabin does not count UV values composed with loop (their UV states do not convert)"
        );
    }

    /// √3 without seams counts the surface's vertices, alone, periodic, and composed with
    /// the other rules both ways (the seams carried across a stage boundary, `UE` rebuilt from
    /// a triangle layout).
    #[test]
    fn sqrt3_without_seams_counts_like_the_mesh() {
        let strip: [&[u32]; 4] = [&[0, 1, 4], &[0, 4, 3], &[1, 2, 5], &[1, 5, 4]];
        let tetra: [&[u32]; 4] = [&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[0, 3, 2]];
        for (faces, plans) in [
            (
                &strip[..],
                &[
                    "sqrt3-boundary",
                    "loop-boundary:1,sqrt3-boundary",
                    "sqrt3-boundary:3,loop-boundary",
                    "sqrt3-boundary:1,loop-boundary:1,sqrt3-boundary",
                ][..],
            ),
            (
                &tetra[..],
                &["sqrt3", "sqrt3:2,catmull-clark", "loop:1,sqrt3"][..],
            ),
        ] {
            let uv = layout(faces, faces, &[0, 1, 2, 3, 4, 5][..faces.len() + 2]).unwrap();
            assert_eq!(uv.seam_edges, 0);
            let mesh = MeshCounts::from_polygons(faces).unwrap();
            for text in plans {
                let plan = Plan::parse(text).unwrap();
                let uvc = crate::Counter::from(plan.clone()).uv_counter(&uv).unwrap();
                let counter = crate::Counter::from(plan.clone());
                let x0 = plan.initial_state(&mesh).unwrap();
                let mut rows = counter.rows(&x0, 0..=7).unwrap();
                let mut columns = counter.columns();
                uvc.extend_rows(&mut columns, &mut rows).unwrap();
                let v = columns.iter().position(|c| c == "V").unwrap();
                for s in 0..=7 {
                    let vertices = plan.counts_at(&mesh, s).unwrap().vertices;
                    assert_eq!(uvc.values_at(s).unwrap(), vertices, "{text} level {s}");
                    let row = &rows[s as usize];
                    assert_eq!(
                        row.values.last(),
                        Some(&row.values[v].clone()),
                        "{text} {s}"
                    );
                }
            }
        }
    }

    /// √3 with seams: step by step by hand, the periodic closed forms and the summaries
    /// agree with powering.
    #[test]
    fn sqrt3_counts_seams_per_step() {
        // Two triangles of the strip, the second its own chart along their common edge 0-4:
        // one seam, 6 values, 6 layout boundary edges, 2 faces.
        let uv = layout(
            &[&[0, 1, 4], &[0, 4, 3]],
            &[&[0, 1, 2], &[3, 4, 5]],
            &[0, 1, 2, 3, 4, 5],
        )
        .unwrap();
        assert_eq!(
            (uv.values, uv.boundary_edges, uv.seam_edges, uv.faces),
            (6, 6, 1, 2)
        );
        let scheme = uv_scheme(Rule::Sqrt3).unwrap();
        assert_eq!(scheme.initial_state(&uv), [6, 6, 1, 2].map(BigInt::from));
        // A: 6 + 2 (seam midpoints) + 2 (centroids); B: + 6 (UBE) + 6 (F).
        let mut expected = vec![BigInt::from(6)];
        let mut x = [6i64, 6, 1, 2];
        for step in 1..=9u64 {
            x = if step % 2 == 1 {
                [x[0] + 2 * x[2] + x[3], x[1] + 4 * x[2], 3 * x[2], 3 * x[3]]
            } else {
                [x[0] + x[1] + x[3], 3 * x[1], 3 * x[2], 3 * x[3]]
            };
            expected.push(BigInt::from(x[0]));
        }
        assert_eq!(expected[1..3], [BigInt::from(10), BigInt::from(26)]);
        let counter = crate::Counter::from(builtin("sqrt3-boundary").unwrap());
        let uvc = counter.uv_counter(&uv).unwrap();
        for (s, e) in expected.iter().enumerate().skip(1) {
            assert_eq!(&scheme.values_at(&uv, s as u64).unwrap(), e, "level {s}");
            assert_eq!(&uvc.values_at(s as u64).unwrap(), e, "level {s}");
            let sum = uvc.summary_at(s as u64).unwrap();
            assert_eq!(
                sum,
                recurrence::digit_summary(e, crate::SUMMARY_DIGITS),
                "{s}"
            );
            let log = uvc.estimated_log10(s as u64).unwrap();
            assert!(log >= crate::log10_abs(e) - 1e-9, "{s}: {log}");
        }
        // The phases: s = 2t from level 0, s = 2t + 1 from level 1.
        let phases = scheme.phases();
        assert_eq!(phases.len(), 2);
        for phase in &phases {
            let x0 = scheme.state_at(&uv, phase.first_level).unwrap();
            for t in 0..4u64 {
                let s = phase.first_level + 2 * t;
                let form = phase.closed_form().evaluate(&x0, t).unwrap();
                assert_eq!(
                    form,
                    scheme.state_at(&uv, s).unwrap(),
                    "{}",
                    phase.description
                );
            }
        }
        // `sqrt3` (closed meshes) is step A alone.
        let closed = UvScheme::for_scheme(&builtin("sqrt3").unwrap()).unwrap();
        assert_eq!(closed.period(), 1);
        assert_eq!(
            closed.values_at(&uv, 2).unwrap(),
            BigInt::from(10 + 2 * 3 + 6)
        );
        // A √3 stage after a rule whose seams are not derived here is not counted.
        let dual = Plan::parse("doo-sabin:1,sqrt3");
        if let Ok(plan) = dual {
            assert!(crate::Counter::from(plan).uv_counter(&uv).is_err());
        }
    }

    #[test]
    fn summaries_and_estimates_follow_the_closed_form() {
        let spot = UvCounts {
            values: 267,
            edges: 438,
            boundary_edges: 144,
            used_vt: 267,
            faces: 180,
            corners: 732,
            ..UvCounts::default()
        };
        let counter = crate::Counter::from(builtin("catmull-clark").unwrap());
        let uvc = counter.uv_counter(&spot).unwrap();
        // UV(s) = 183*4^s + 72*2^s + 9 for s >= 1.
        let at = |s: u32| {
            BigInt::from(183) * BigInt::from(4).pow(s)
                + BigInt::from(72) * BigInt::from(2).pow(s)
                + 9
        };
        assert_eq!(uvc.values_at(30).unwrap(), at(30));
        let sum = uvc.summary_at(1000).unwrap();
        assert_eq!(
            sum,
            recurrence::digit_summary(&at(1000), crate::SUMMARY_DIGITS)
        );
        assert_eq!(uvc.summary_at(0).unwrap().leading, "267");
        let estimate = uvc.estimated_log10(1000).unwrap();
        // The largest component (H = 4^s H0 = 732 * 4^1000) bounds UV from above.
        let uv_log10 = crate::log10_abs(&at(1000));
        assert!(
            estimate >= uv_log10 && estimate < uv_log10 + 1.0,
            "{estimate}"
        );
    }
}
