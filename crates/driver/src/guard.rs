//! The memory guards of real subdivision: a prediction of the kernel
//! ([`halfedge::memory`]) against half the memory the system says this process may still
//! allocate ([`crate::system::peak_limit`]), unless lifted.

use halfedge::{PolygonMesh, Rule};
use num_bigint::BigInt;

/// `need` if it fits the limit (half the available memory; no limit with `allow_large`),
/// else [`halfedge::Error::OverMemoryLimit`] naming `scheme` and `levels`.
///
/// # Errors
///
/// `need`'s own error, or the refusal.
pub fn guard_memory(
    need: halfedge::Result<BigInt>,
    scheme: &str,
    levels: u32,
    allow_large: bool,
) -> halfedge::Result<BigInt> {
    need.and_then(|need| halfedge::memory::within_limit(need, scheme, levels, limit(allow_large)))
}

/// The guards' limit: half the available memory, or none with `allow_large`.
pub(crate) fn limit(allow_large: bool) -> u128 {
    if allow_large {
        u128::MAX
    } else {
        crate::system::peak_limit()
    }
}

/// What refining the UV layout of `poly` adds to the memory guard's need
/// ([`halfedge::memory::predicted_uv_bytes`] of its layout's statistics); 0 for a rule without
/// a face-varying rule (it writes without UVs) or a mesh without a layout.
///
/// # Errors
///
/// The prediction's errors.
pub fn uv_bytes(
    poly: &PolygonMesh,
    rule: Rule,
    levels: u32,
    scalar_bytes: usize,
    holes: bool,
) -> halfedge::Result<BigInt> {
    let Some(layout) = halfedge::stats::uv_layout_counts(poly) else {
        return Ok(BigInt::from(0));
    };
    match halfedge::memory::predicted_uv_bytes(rule, &layout, levels, scalar_bytes, holes) {
        Err(halfedge::Error::UvsNotSupported { .. }) => Ok(BigInt::from(0)),
        bytes => bytes,
    }
}
