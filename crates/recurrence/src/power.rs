//! Exact counts by exponentiation by squaring, written once over a checked ring.

use num_bigint::BigInt;
use num_traits::{CheckedAdd, CheckedMul, One, Zero};

use crate::IntMatrix;

/// The arithmetic that matrix powering needs: a ring whose operations report overflow.
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

/// A dense square matrix over a [`CheckedRing`], row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct RingMatrix<T> {
    pub(crate) dim: usize,
    pub(crate) entries: Vec<T>,
}

impl<T: CheckedRing> RingMatrix<T> {
    pub(crate) fn from_int(m: &IntMatrix) -> Option<Self> {
        let entries = m
            .rows()
            .flatten()
            .map(|&x| T::from_entry(x))
            .collect::<Option<Vec<_>>>()?;
        Some(RingMatrix {
            dim: m.dim(),
            entries,
        })
    }

    pub(crate) fn identity(dim: usize) -> Self {
        let mut entries = vec![T::zero(); dim * dim];
        for i in 0..dim {
            entries[i * dim + i] = T::one();
        }
        RingMatrix { dim, entries }
    }

    pub(crate) fn checked_mul(&self, rhs: &Self) -> Option<Self> {
        let n = self.dim;
        let mut entries = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let mut acc = T::zero();
                for k in 0..n {
                    let a = &self.entries[i * n + k];
                    let b = &rhs.entries[k * n + j];
                    if a.is_zero() || b.is_zero() {
                        continue;
                    }
                    acc = acc.checked_add(&a.checked_mul(b)?)?;
                }
                entries.push(acc);
            }
        }
        Some(RingMatrix { dim: n, entries })
    }

    pub(crate) fn checked_apply(&self, x: &[T]) -> Option<Vec<T>> {
        let n = self.dim;
        let mut out = Vec::with_capacity(n);
        for i in 0..n {
            let mut acc = T::zero();
            for (k, xk) in x.iter().enumerate() {
                let a = &self.entries[i * n + k];
                if a.is_zero() || xk.is_zero() {
                    continue;
                }
                acc = acc.checked_add(&a.checked_mul(xk)?)?;
            }
            out.push(acc);
        }
        Some(out)
    }

    /// `self^s` by squaring, or `None` on overflow.
    pub(crate) fn checked_pow(&self, mut s: u64) -> Option<Self> {
        let mut result = RingMatrix::identity(self.dim);
        let mut base = self.clone();
        while s > 0 {
            if s & 1 == 1 {
                result = result.checked_mul(&base)?;
            }
            s >>= 1;
            if s > 0 {
                base = base.checked_mul(&base)?;
            }
        }
        Some(result)
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
    let mut base = RingMatrix::<T>::from_int(m)?;
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
