//! Fallible allocation of the large subdivision buffers: a refused allocation (an
//! address-space or cgroup limit tighter than the resource guard estimated) is
//! [`Error::AllocationFailed`], not an abort of the process.

use crate::error::{Error, Result};

fn failed<T>(n: usize, what: &str, e: std::collections::TryReserveError) -> Error {
    Error::AllocationFailed {
        what: what.to_string(),
        bytes: n as u128 * std::mem::size_of::<T>() as u128,
        reason: e.to_string(),
    }
}

/// Room for `faces` faces of `corners` corners in all in `mesh`.
pub(crate) fn reserve_faces(
    mesh: &mut crate::PolygonMesh,
    faces: usize,
    corners: usize,
) -> Result<()> {
    mesh.try_reserve_faces(faces, corners)
        .map_err(|e| Error::AllocationFailed {
            what: "the faces".to_string(),
            bytes: faces as u128 * std::mem::size_of::<usize>() as u128 + corners as u128 * 4,
            reason: e.to_string(),
        })
}

/// An empty vector with room for exactly `n` elements (`what` names it in the error).
pub(crate) fn with_capacity<T>(n: usize, what: &str) -> Result<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|e| failed::<T>(n, what, e))?;
    Ok(v)
}

/// A vector of `n` copies of `value`, allocated exactly.
pub(crate) fn filled<T: Clone>(value: T, n: usize, what: &str) -> Result<Vec<T>> {
    let mut v = with_capacity(n, what)?;
    v.resize(n, value);
    Ok(v)
}

/// `n` zeroed `u32`s in each of `K` arrays. The zeroed allocation (`vec![0; n]`, whose pages
/// come zeroed from the system without a pass over them) has no fallible form in stable Rust,
/// so the whole size is first reserved fallibly and released, then allocated zeroed: a
/// refusal by the address-space or cgroup limit shows in the probe.
pub(crate) fn zeroed_u32<const K: usize>(n: usize, what: &str) -> Result<[Vec<u32>; K]> {
    let probe: Vec<u32> = with_capacity(n.saturating_mul(K), what)?;
    drop(probe);
    Ok(std::array::from_fn(|_| vec![0u32; n]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_impossible_allocation_is_an_error() {
        let err = with_capacity::<u64>(usize::MAX / 16, "test buffer").unwrap_err();
        assert!(
            err.to_string().starts_with(&format!(
                "cannot allocate {} bytes for test buffer: ",
                (usize::MAX / 16) as u128 * 8
            )),
            "{err}"
        );
        assert!(err.is_resource_limit());
        assert!(filled(0u8, usize::MAX / 2, "x").is_err());
        assert!(zeroed_u32::<4>(usize::MAX / 8, "x").is_err());
        assert_eq!(filled(7u8, 3, "x").expect("small"), [7, 7, 7]);
        let [a, b] = zeroed_u32::<2>(2, "x").expect("small");
        assert_eq!((a, b), (vec![0, 0], vec![0, 0]));
    }
}
