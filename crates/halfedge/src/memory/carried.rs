//! What carrying a mesh's groups and vertex colors, and writing PLY, add to a peak.

use num_bigint::BigInt;
use schemes::{MeshCounts, Scheme};

use crate::{PolygonMesh, Result, Rule};

/// How a run carries a mesh's groups and colors to its last level, and what it writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Carrying {
    /// The run is on the raw face list (colors: a second run of the levels).
    pub face_list: bool,
    /// The positions' refinement, kept, evaluates the colors too, in scalars of this many
    /// bytes; `None`: a refinement of their own (the one-shot half-edge path, a composition's
    /// stage).
    pub refinement_scalar: Option<usize>,
    /// The output is PLY, whose writer holds a value per vertex of the UVs, if any (records
    /// are formatted in chunks of a few megabytes, not counted).
    pub ply: bool,
}

/// What carrying `poly`'s groups and colors to level `levels` of `scheme` (rule `rule`, on a
/// mesh with `counts`) adds to a run's peak, the way `how` says:
///
/// - groups: the base face of each output face (4 bytes, becoming its class);
/// - colors: on the raw face list a second run of the levels ([`super::predicted_peak_bytes`]);
///   with the positions' refinement the colors of the base (24 bytes a vertex) and of the last
///   level (3 scalars a vertex), and under the icosphere rule a varying refinement (the
///   midpoint rule's); otherwise a refinement of their own
///   ([`super::predicted_refinement_peak_bytes`]);
/// - a PLY output: the UVs as one value per vertex (32 bytes an edge bounds them).
///
/// # Errors
///
/// The scheme's refusal of `counts`.
pub fn carried_bytes(
    poly: &PolygonMesh,
    (scheme, rule): (&Scheme, Rule),
    counts: &MeshCounts,
    levels: u32,
    how: Carrying,
) -> Result<BigInt> {
    let last = scheme.counts_at(counts, u64::from(levels))?;
    let mut bytes = BigInt::from(0);
    if poly.groups().is_some() {
        bytes += &last.faces * 4u32;
    }
    if poly.colors().is_some() {
        let refinement =
            |rule| super::predicted_refinement_peak_bytes(rule, counts, levels, 8, false, false);
        bytes += match (how.face_list, how.refinement_scalar) {
            (true, _) => super::predicted_peak_bytes(scheme, counts, levels, None)?,
            (false, Some(scalar)) => {
                let own = &last.vertices * (3 * scalar) + BigInt::from(poly.n_vertices()) * 24u32;
                match rule {
                    Rule::Icosphere => own + refinement(Rule::Midpoint)?,
                    _ => own,
                }
            }
            (false, None) => refinement(rule)?,
        };
    }
    if how.ply {
        let uvs = if poly.uvs().is_some() {
            &last.edges * 32u32
        } else {
            BigInt::from(0)
        };
        bytes += uvs;
    }
    Ok(bytes)
}
