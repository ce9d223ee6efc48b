//! Exact counts by exponentiation by squaring, written once over a checked ring (the
//! products are [`Matrix`](crate::Matrix)'s).

use num_bigint::BigInt;
use num_traits::{CheckedAdd, CheckedMul, One, Zero};

use crate::IntMatrix;

/// The arithmetic that matrix powering needs: a ring whose operations report overflow, and
/// the conversion of `i64` matrix entries into it.
///
/// `i128` and `u64` return `None` on overflow; [`BigInt`] never does. Implemented for every
/// type with the right `num-traits` bounds.
pub trait CheckedRing: Clone + Zero + One + CheckedAdd + CheckedMul {
    /// Converts a matrix entry, or `None` if it does not fit.
    fn from_entry(x: i64) -> Option<Self>;
}

impl CheckedRing for BigInt {
    fn from_entry(x: i64) -> Option<Self> {
        Some(BigInt::from(x))
    }
}

impl CheckedRing for i128 {
    fn from_entry(x: i64) -> Option<Self> {
        Some(i128::from(x))
    }
}

impl CheckedRing for i64 {
    fn from_entry(x: i64) -> Option<Self> {
        Some(x)
    }
}

/// `m^s x0` by exponentiation by squaring over any [`CheckedRing`], or `None` on overflow.
///
/// The powers of `m` commute, so the vector is multiplied by `m^(2^k)` for each set bit `k` of
/// `s`, and the matrix is squared only while higher bits remain: about `log2 s` squarings and
/// `popcount(s)` matrix-vector products.
pub(crate) fn checked_power_apply<T: CheckedRing>(
    m: &IntMatrix,
    x0: &[T],
    mut s: u64,
) -> Option<Vec<T>> {
    debug_assert_eq!(x0.len(), m.dim());
    let mut x = x0.to_vec();
    if s == 0 {
        return Some(x);
    }
    let mut base = m.try_map(|&x| T::from_entry(x))?;
    loop {
        if s & 1 == 1 {
            x = base.checked_apply(&x)?;
        }
        s >>= 1;
        if s == 0 {
            return Some(x);
        }
        base = base.checked_mul(&base)?;
    }
}
