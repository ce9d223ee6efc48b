//! What refining a UV layout with the surface adds to a peak ([`predicted_uv_bytes`]).

use super::*;

/// What refining a UV layout with the surface adds to a peak: the face-varying channel of
/// [`refine::face_varying`](crate::refine::face_varying) under `rule` to `levels`, on a layout
/// with the statistics `layout` (the mesh's faces with the layout's values as corners:
/// [`stats::uv_layout_counts`](crate::stats::uv_layout_counts)), its values of `scalar_bytes`
/// per coordinate. The same terms on both paths that refine UVs:
/// [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list) with
/// [`SubdivideOptions::uvs`](crate::subdivide::SubdivideOptions::uvs) (always `f64`: pass 8)
/// and a [`Refinement`](crate::Refinement) with UVs evaluated by
/// [`Refinement::evaluate_uvs`](crate::Refinement::evaluate_uvs) into the caller's buffers
/// (`scalar_bytes` of the caller's type). The sum of
///
/// - the channel, a refinement of the layout by its own rule (the rule itself for Loop,
///   Catmull-Clark and the 1:N² splits, midpoint for butterfly and the icosphere) under its
///   crease rules (the bound of [`Refinement::predicted_bytes_with_creases`](crate::Refinement::predicted_bytes_with_creases)
///   of the layout, with a face of degree `d` counting `d min(d, 32)` rather than `d²`: a
///   level with a face of more than 32 sides never gets the dense table, whose Catmull-Clark
///   rows expand the face points, and the channel's own rows are short; seams and layout
///   corners make the channel's vertices sharp), plus the
///   merged numbering of its last level and the corner buffer it is computed from (4 bytes per
///   vertex and per corner of the last level: kept when values have several runs around a
///   vertex, counted always);
/// - the evaluation: the base values and the output values (`2 * scalar_bytes` per value of
///   levels 0 and `levels`), the two intermediate buffers (the largest odd and even levels
///   below `levels`) and the whole last level before it is merged (counted always);
/// - the UV index of every corner of the last level (4 bytes each);
/// - with `holes`, the written corners' UV indices and the channel's last face list read to
///   find them (4 bytes per corner, twice, and per face);
/// - the channel's base, built before its levels: the layout as a face list and a half-edge
///   mesh, and the arrays that build the latter ([`halfedge_build_bytes`]): transient, but
///   the peak at low levels (at level 0 of a 314 MB quad grid with `vt`).
///
/// √3, Doo-Sabin and mid-edge carry UVs by the corner channel on the surface's own levels
/// instead, which the layout's statistics size only approximately (they do not separate
/// seams from the surface's boundary): the surface refinement the one-shot path builds for
/// it (bounded by the layout's), each level's weight table (4 bytes per value, 12 per
/// weight; values the larger of the two extreme layouts, no seam or every layout boundary
/// edge a seam side; 2 weights per value under mid-edge, 3 under √3, the largest base face
/// degree, at least 4, under Doo-Sabin, and 7 when a face has more than 32 sides: its
/// corners are 4-entry rows over three face-wide sums), 8 bytes per corner of the last level (its values and the
/// caller's index buffer) and 4 per corner of the level before (its values while the last
/// is built), and the evaluation buffers: an estimate, not a bound (on grids cut into four
/// charts, 1.6 to 2.6 times what the channel and the caller's buffers hold,
/// `tests/integration/uv_memory.rs`).
///
/// The last level's corners are `d` per face for the rules that write `d`-gons
/// ([`direct_face_degree`](crate::subdivide::direct_face_degree)), else bounded by `2E`.
/// Not counted: the layout's sibling values (a value used in several runs around a vertex is
/// a vertex of the channel per run, a few per mesh). Against the channel's heap and the
/// caller's buffers it is 1.5 to 3.2 times what is measured (`tests/integration/uv_memory.rs`:
/// at least it, at most four times; the base is transient, not in the heap): it
/// bounds the channel's crease tables by dense weight tables (a channel whose every edge is
/// semi-sharp), where seams and corners alone keep the flattened tables and a few rows.
/// Measured while the channel still kept dense tables (its heap has since fallen from 32.5 MB
/// to 18.5 MB on the first job below, from 30.7 MB to 20.4 MB on the second), as a peak
/// (`subcount subdivide --timings --threads 1`, debug build; more threads add
/// glibc's per-thread arenas, a few MB either way), the UVs' share (the peak with UVs minus
/// the peak with `--no-uv`): `spot_quadrangulated` at Catmull-Clark level 3, 36.3 MB on the
/// one-shot path and 31.1 MB with `--frames 2`, 38.3 MB predicted; `spot_triangulated` at
/// Loop level 3, 29.6 MB and 31.6 MB, 37.0 MB predicted.
///
/// ```
/// use halfedge::memory::predicted_uv_bytes;
/// use halfedge::Rule;
/// // A cube whose six faces each have their own UV square: six separate quads.
/// let faces: Vec<[u32; 4]> = (0..6u32).map(|f| [4 * f, 4 * f + 1, 4 * f + 2, 4 * f + 3]).collect();
/// let layout = schemes::MeshCounts::from_polygons(&faces)?;
/// let f64_bytes = predicted_uv_bytes(Rule::CatmullClark, &layout, 2, 8, false)?;
/// let f32_bytes = predicted_uv_bytes(Rule::CatmullClark, &layout, 2, 4, false)?;
/// // Values of levels 0, 1 and 2 (24, 54, 150), the last one twice: 4 bytes less per
/// // coordinate.
/// assert_eq!(f64_bytes - f32_bytes, (8 * (24 + 54 + 2 * 150)).into());
/// // √3 carries UVs on the corner channel: the layout of two triangles, each its own chart.
/// let two = schemes::MeshCounts::from_polygons(&[[0, 1, 2], [3, 4, 5]])?;
/// assert!(predicted_uv_bytes(Rule::Sqrt3, &two, 2, 8, false)? > 0.into());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`Error::Scheme`](crate::Error::Scheme) when the channel's rule does not apply to the
/// layout.
pub fn predicted_uv_bytes(
    rule: crate::Rule,
    layout: &MeshCounts,
    levels: u32,
    scalar_bytes: usize,
    holes: bool,
) -> crate::Result<BigInt> {
    use crate::refine::face_varying::{channel_kind, ChannelKind};
    let channel = match channel_kind(rule)? {
        ChannelKind::Layout(channel) => channel,
        ChannelKind::Corners => return corner_uv_bytes(rule, layout, levels, scalar_bytes),
    };
    let scheme = channel.scheme_for(layout)?;
    let heap = crate::Refinement::tables_bound(channel, layout, levels, true)?;
    let level = |s: u32| scheme.counts_at(layout, u64::from(s));
    let last = level(levels)?;
    let corners = match crate::subdivide::direct_face_degree(channel) {
        Some(degree) if levels > 0 => BigInt::from(degree) * &last.faces,
        _ if levels == 0 => BigInt::from(layout.corners),
        _ => BigInt::from(2) * &last.edges,
    };
    let value = BigInt::from(2 * scalar_bytes);
    // Evaluator::evaluate: odd intermediate levels in one buffer, even ones in the other.
    let mut scratch = [BigInt::from(0), BigInt::from(0)];
    for s in 1..levels {
        let v = level(s)?.vertices;
        let slot = &mut scratch[(s % 2) as usize];
        if v > *slot {
            *slot = v;
        }
    }
    let [even, odd] = scratch;
    let numbering = BigInt::from(4) * (&last.vertices + &corners);
    let evaluation =
        &value * (BigInt::from(layout.vertices) + BigInt::from(2) * &last.vertices + even + odd);
    let indices = BigInt::from(4) * &corners;
    let written = if holes {
        BigInt::from(4) * (BigInt::from(2) * &corners + &last.faces + 1)
    } else {
        BigInt::from(0)
    };
    // The channel's base, built before its levels: the layout as a face list and a half-edge
    // mesh, and the transients of building the latter (freed, but at low levels the peak).
    let base = BigInt::from(PolygonMesh::bytes_for(
        layout.vertices,
        layout.faces,
        layout.corners,
    )) + HalfEdgeMesh::bytes_for(layout.vertices, layout.edges, layout.faces)
        + halfedge_build_bytes(layout);
    Ok(heap + numbering + evaluation + indices + written + base)
}

/// [`predicted_uv_bytes`] of the corner channel (√3, Doo-Sabin, mid-edge: values propagated on
/// the surface's own refinement): an estimate from the layout's statistics alone, which do
/// not separate seams from the surface's boundary. The sum of
///
/// - the surface's refinement that the one-shot path builds to carry the channel
///   ([`Refinement::predicted_bytes`](crate::Refinement::predicted_bytes) of the layout as a
///   mesh, which has at least the surface's vertices, edges and faces; on the refined path it
///   is the caller's own refinement, counted twice);
/// - each level's weight table: 4 bytes per value and 12 per weight, the values being the
///   larger of the two extreme layouts (no seam; every layout boundary edge a side of a seam)
///   under [`schemes::uv::uv_scheme`], the weights per value 2 under mid-edge, 3 under √3
///   (a centroid) and, under
///   Doo-Sabin, the largest face degree of the base (at least 4: from level 1 on the faces
///   are quads but the face faces and the faces of the base vertices, whose degree is their
///   valence, not counted beyond it), or 7 when a face has more than 32 sides (a corner of
///   such a face is 4 weights over its value and the face's three sums, which take 3 weights
///   per corner: `wide.rs`'s `DIRECT_MAX`);
/// - the last level's corner values, the caller's index buffer and the corner values of the
///   level before it while it is refined (4 bytes per corner; corners bounded by `2E` of the
///   layout refined as a mesh);
/// - the evaluation: base and output values, two intermediate levels (`2 * scalar_bytes`
///   per value).
fn corner_uv_bytes(
    rule: crate::Rule,
    layout: &MeshCounts,
    levels: u32,
    scalar_bytes: usize,
) -> crate::Result<BigInt> {
    let not = || crate::Error::UvsNotSupported {
        rule: rule.to_string(),
    };
    let uv = schemes::uv::uv_scheme(rule).map_err(|_| not())?;
    let scheme = rule.scheme_for(layout)?;
    let extremes = [0, layout.boundary_edges / 2].map(|seams| schemes::uv::UvCounts {
        values: layout.vertices,
        edges: layout.edges,
        boundary_edges: layout.boundary_edges,
        seam_edges: seams,
        used_vt: layout.vertices,
        faces: layout.faces,
        corners: layout.corners,
        ..schemes::uv::UvCounts::default()
    });
    let values = |s: u32| -> crate::Result<BigInt> {
        let [a, b] = &extremes;
        let (a, b) = (
            uv.values_at(a, u64::from(s))?,
            uv.values_at(b, u64::from(s))?,
        );
        Ok(a.max(b))
    };
    let degree = layout
        .faces_by_degree
        .keys()
        .next_back()
        .map_or(4, |&d| d.max(4));
    // Doo-Sabin: a corner of a face of at most 32 sides is a row over the face's corners, one
    // of a wider face 4 weights and its share of the face's three sums (`dual.rs`).
    let wide = degree as usize > crate::subdivide::wide::DIRECT_MAX;
    let weights = BigInt::from(match rule {
        crate::Rule::DooSabin if wide => 7,
        crate::Rule::DooSabin => degree,
        crate::Rule::Sqrt3 => 3,
        _ => 2,
    });
    let mut bytes = crate::Refinement::predicted_bytes(rule, layout, levels)?;
    let mut intermediate = BigInt::from(0);
    for s in 1..=levels {
        let v = values(s)?;
        bytes += &v * 4u32 + &v * &weights * 12u32;
        if s < levels {
            intermediate = intermediate.max(v);
        }
    }
    let corners = |s: u32| -> crate::Result<BigInt> {
        Ok(if s == 0 {
            BigInt::from(layout.corners)
        } else {
            BigInt::from(2) * scheme.counts_at(layout, u64::from(s))?.edges
        })
    };
    bytes += corners(levels)? * 8u32 + corners(levels.saturating_sub(1))? * 4u32;
    let value = BigInt::from(2 * scalar_bytes);
    bytes += value * (BigInt::from(layout.vertices) + values(levels)? + intermediate * 2u32);
    Ok(bytes)
}
