//! The peak of refining once and evaluating into caller buffers
//! ([`predicted_refinement_peak_bytes`]).

use super::*;

/// What the limit surface adds to [`predicted_refinement_peak_bytes`]
/// ([`SubdivideOptions::limit`](crate::subdivide::SubdivideOptions::limit)): the last level's
/// connectivity, built for its vertex rings (4 bytes per vertex and face, 32 per edge), the
/// limit table (8 bytes per vertex, 4 per entry: Loop `V + 2E` entries, Catmull-Clark
/// `V + 2E + 4F`; its masks are shared) and the whole last level, the limit positions and
/// two tangents in `scalar_bytes` per coordinate.
///
/// # Errors
///
/// [`Error::Scheme`](crate::Error::Scheme) when the rule does not apply.
pub fn predicted_limit_bytes(
    rule: crate::Rule,
    counts: &MeshCounts,
    levels: u32,
    scalar_bytes: usize,
) -> crate::Result<BigInt> {
    let scheme = rule.scheme_for(counts)?;
    let c = scheme.counts_at(counts, u64::from(levels))?;
    let (v, e, f) = (&c.vertices, &c.edges, &c.faces);
    let connectivity = v * 4u32 + e * 32u32 + f * 4u32;
    let faces = match rule {
        crate::Rule::CatmullClark => f * 4u32,
        _ => BigInt::from(0),
    };
    let table = v * 8u32 + (v + e * 2u32 + faces) * 4u32;
    let buffers = v * (4 * 3 * scalar_bytes);
    Ok(connectivity + table + buffers)
}

/// The peak of refining once ([`crate::Refinement`]) by `rule` to `levels` and evaluating
/// positions of `scalar_bytes` per coordinate into caller buffers: [`PROCESS_BYTES`], the
/// input's face list and the transients of building its half-edge mesh
/// ([`halfedge_build_bytes`]; a file's lines and UVs are the caller's, [`read_extra_bytes`]),
/// plus the larger of the arrays
/// alive while the levels are built (the input and the last two levels, the last as a face
/// list, as in [`predicted_peak_bytes`] without its process, face-list and freed-level terms)
/// and the input, the refinement kept ([`crate::Refinement::predicted_bytes`], or with
/// `creases` [`crate::Refinement::predicted_bytes_with_creases`]: a refinement under crease
/// rules) and the output positions and indices (with `frames`, a moved copy of the base and a
/// second output buffer). For √3, Doo-Sabin and mid-edge (no index formulas from level
/// `levels - 1`) the building side is at least the input, the refinement and the last level's
/// whole connectivity (4 bytes per vertex and face, 32 per edge); the kept side adds the freed
/// connectivity that stays resident below glibc's mmap threshold: that of the last level for
/// those rules, of every level below the last for Loop and Catmull-Clark. Measured on a
/// bipyramid of valence 16,000 in `f32` at levels 1-2: 1.00 to 1.26 of the peak (0.71 to 0.86
/// without these terms for √3, Doo-Sabin, mid-edge and Catmull-Clark level 2).
///
/// # Errors
///
/// [`Error::Scheme`](crate::Error::Scheme) when the rule does not apply.
pub fn predicted_refinement_peak_bytes(
    rule: crate::Rule,
    counts: &MeshCounts,
    levels: u32,
    scalar_bytes: usize,
    frames: bool,
    creases: bool,
) -> crate::Result<BigInt> {
    let scheme = rule.scheme_for(counts)?;
    let mut building = arrays_peak_bytes(&scheme, counts, levels, Some(4))?;
    if levels > 0
        && counts.boundary_edges > 0
        && matches!(rule, crate::Rule::DooSabin | crate::Rule::MidEdge)
    {
        // With a boundary the dual rules build each level face by face as a half-edge mesh
        // (on zero positions) and copy its connectivity.
        building += halfedge_bytes(&scheme, counts, u64::from(levels))?;
    }
    let kept = if creases {
        crate::Refinement::predicted_bytes_with_creases(rule, counts, levels)?
    } else {
        crate::Refinement::predicted_bytes(rule, counts, levels)?
    };
    let connectivity =
        |s: u32| -> Result<BigInt, schemes::Error> {
            let c = scheme.counts_at(counts, u64::from(s))?;
            Ok(BigInt::from(4) * &c.vertices
                + BigInt::from(32) * &c.edges
                + BigInt::from(4) * &c.faces)
        };
    let input = arrays_peak_bytes(&scheme, counts, 0, None)?;
    // Loop and Catmull-Clark keep flattened tables: the connectivity of every level below the
    // last (level `levels - 1` kept, the others dropped once flattened) and the transients of
    // flattening it are freed before the buffers are allocated, and below glibc's mmap
    // threshold they stay resident.
    let mut resident = BigInt::from(0);
    let flattened = matches!(rule, crate::Rule::Loop | crate::Rule::CatmullClark);
    if levels > 0 && flattened {
        for s in 0..levels {
            resident += connectivity_resident_bytes(&scheme, counts, s)?;
        }
    }
    // The rules whose last level is not written by index formulas from level `levels - 1`
    // (√3, Doo-Sabin, mid-edge) build its whole connectivity next to the kept levels and its
    // face list; freed before the buffers, it stays resident below the mmap threshold, and
    // the buffers do not all fit in its holes.
    if levels > 0 && !flattened && crate::subdivide::direct_face_degree(rule).is_none() {
        building = building.max(&input + &kept + connectivity(levels)?);
        resident += connectivity_resident_bytes(&scheme, counts, levels)?;
    }
    let c = scheme.counts_at(counts, u64::from(levels))?;
    let point = BigInt::from(3 * scalar_bytes);
    let copies = if frames { 2 } else { 1 };
    let buffers = &point * &c.vertices * copies
        + BigInt::from(4 * 4) * &c.faces
        + &point * counts.vertices * u32::from(frames);
    // While levels are built the refinement's tables are filled level by level; afterwards
    // the refinement and the buffers are alive with the input: the larger of the two. The
    // process, the input's face list (kept by the caller) and the transients of building its
    // half-edge mesh come on top of either.
    let c = scheme.counts_at(counts, 0)?;
    let input_faces = BigInt::from(24) * &c.vertices
        + BigInt::from(std::mem::size_of::<usize>()) * (&c.faces + 1)
        + BigInt::from(4) * counts.corners;
    let around = input_faces + halfedge_build_bytes(counts) + PROCESS_BYTES;
    Ok(building.max(kept + buffers + input + resident) + around)
}

/// The arrays of a refinement's connectivity of level `s` ([`crate::Refinement`], laid out as
/// a half-edge mesh's) that stay resident once freed ([`connectivity_resident`]).
fn connectivity_resident_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    s: u32,
) -> Result<BigInt, schemes::Error> {
    Ok(connectivity_resident(
        &scheme.counts_at(counts, u64::from(s))?,
    ))
}
