//! The fields the closed-form machinery computes in: the rationals, quadratic fields
//! `Q(sqrt d)` (exact), and `f64` complex numbers (numeric, for everything else).
//!
//! The spectral decomposition is written once over the crate-private [`Field`] trait and run
//! with the field that holds the eigenvalue at hand.

use std::fmt;

use nalgebra::Complex;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::Complex64;

/// The arithmetic of a field, as the spectral decomposition needs it.
pub(crate) trait Field: Clone + fmt::Debug {
    fn field_zero() -> Self;
    fn field_one() -> Self;
    /// Whether the value is zero (exact fields), or negligibly small (numeric fields).
    fn is_field_zero(&self) -> bool;
    fn add(&self, rhs: &Self) -> Self;
    #[cfg_attr(not(test), allow(dead_code))]
    fn sub(&self, rhs: &Self) -> Self;
    fn mul(&self, rhs: &Self) -> Self;
    /// Division; the caller guarantees that `rhs` is not zero.
    fn div(&self, rhs: &Self) -> Self;
    fn neg(&self) -> Self;
    fn from_rational(r: &BigRational) -> Self;

    /// `q(M)` for an integer matrix `M`. The default runs Horner's rule in the field;
    /// the rationals override it with integer arithmetic when `q` has integer coefficients
    /// (as every cofactor of an integer eigenvalue does), which avoids a gcd per operation.
    fn eval_poly_at_int(m: &crate::IntMatrix, coeffs: &[Self]) -> FieldMatrix<Self> {
        FieldMatrix::<Self>::from_int(m).eval_poly(coeffs)
    }
}

impl Field for BigRational {
    fn field_zero() -> Self {
        Zero::zero()
    }
    fn field_one() -> Self {
        One::one()
    }
    fn is_field_zero(&self) -> bool {
        Zero::is_zero(self)
    }
    fn add(&self, rhs: &Self) -> Self {
        self + rhs
    }
    fn sub(&self, rhs: &Self) -> Self {
        self - rhs
    }
    fn mul(&self, rhs: &Self) -> Self {
        self * rhs
    }
    fn div(&self, rhs: &Self) -> Self {
        self / rhs
    }
    fn neg(&self) -> Self {
        -self
    }
    fn from_rational(r: &BigRational) -> Self {
        r.clone()
    }

    fn eval_poly_at_int(m: &crate::IntMatrix, coeffs: &[Self]) -> FieldMatrix<Self> {
        if !coeffs.iter().all(|c| c.is_integer()) {
            return FieldMatrix::<Self>::from_int(m).eval_poly(coeffs);
        }
        let n = m.dim();
        let a: Vec<BigInt> = m.rows().flatten().map(|&x| BigInt::from(x)).collect();
        let mut acc = vec![BigInt::zero(); n * n];
        for c in coeffs.iter().rev() {
            let mut next = vec![BigInt::zero(); n * n];
            for i in 0..n {
                for k in 0..n {
                    let x = &acc[i * n + k];
                    if x.is_zero() {
                        continue;
                    }
                    for j in 0..n {
                        let y = &a[k * n + j];
                        if !y.is_zero() {
                            next[i * n + j] += x * y;
                        }
                    }
                }
            }
            for i in 0..n {
                next[i * n + i] += c.to_integer();
            }
            acc = next;
        }
        FieldMatrix {
            dim: n,
            entries: acc.into_iter().map(BigRational::from_integer).collect(),
        }
    }
}

impl Field for Complex<f64> {
    fn field_zero() -> Self {
        Complex::new(0.0, 0.0)
    }
    fn field_one() -> Self {
        Complex::new(1.0, 0.0)
    }
    fn is_field_zero(&self) -> bool {
        self.norm() < 1e-12
    }
    fn add(&self, rhs: &Self) -> Self {
        self + rhs
    }
    fn sub(&self, rhs: &Self) -> Self {
        self - rhs
    }
    fn mul(&self, rhs: &Self) -> Self {
        self * rhs
    }
    fn div(&self, rhs: &Self) -> Self {
        self / rhs
    }
    fn neg(&self) -> Self {
        -self
    }
    fn from_rational(r: &BigRational) -> Self {
        Complex::new(rational_to_f64(r), 0.0)
    }
}

/// The nearest `f64` to a rational, also when numerator and denominator overflow `f64`.
pub(crate) fn rational_to_f64(r: &BigRational) -> f64 {
    if let Some(x) = r.to_f64() {
        if x.is_finite() {
            return x;
        }
    }
    let (n, d) = (r.numer(), r.denom());
    let shift = n.bits().max(d.bits()).saturating_sub(900);
    let n = (n >> shift).to_f64().unwrap_or(f64::NAN);
    let d = (d >> shift).to_f64().unwrap_or(f64::NAN);
    n / d
}

/// An exact element `a + b*sqrt(d)` of a quadratic field `Q(sqrt d)`.
///
/// `d` is an integer that is not a perfect square (negative `d` gives complex numbers, e.g.
/// `sqrt(-3)`); when `b` is zero the value is the rational `a` and `d` is `0`. Displays as
/// `a+b*sqrt(d)` with rationals as `p/q`, the form used in JSON output.
///
/// ```
/// use num_bigint::BigInt;
/// use num_rational::BigRational;
/// use recurrence::QuadraticSurd;
///
/// let half = BigRational::new(1.into(), 2.into());
/// let phi = QuadraticSurd::new(half.clone(), half, BigInt::from(5));
/// assert_eq!(phi.to_string(), "1/2+1/2*sqrt(5)");
/// assert!((phi.to_f64().re - 1.618_033_988_749_895).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct QuadraticSurd {
    /// The rational part.
    pub a: BigRational,
    /// The coefficient of `sqrt(d)`.
    pub b: BigRational,
    /// The radicand; `0` when `b` is zero.
    pub d: BigInt,
}

impl QuadraticSurd {
    /// `a + b*sqrt(d)`, normalized so that `d` is `0` when `b` is zero.
    pub fn new(a: BigRational, b: BigRational, d: BigInt) -> Self {
        if Zero::is_zero(&b) || Zero::is_zero(&d) {
            QuadraticSurd {
                a,
                b: Zero::zero(),
                d: Zero::zero(),
            }
        } else {
            QuadraticSurd { a, b, d }
        }
    }

    /// The rational number `a`.
    pub fn rational(a: BigRational) -> Self {
        QuadraticSurd::new(a, Zero::zero(), Zero::zero())
    }

    /// Whether the value is rational (`b == 0`).
    pub fn is_rational(&self) -> bool {
        Zero::is_zero(&self.b)
    }

    /// The conjugate `a - b*sqrt(d)`.
    pub fn conjugate(&self) -> Self {
        QuadraticSurd {
            a: self.a.clone(),
            b: -&self.b,
            d: self.d.clone(),
        }
    }

    /// The field norm `a^2 - b^2 d` (the product with the conjugate), a rational.
    pub fn norm(&self) -> BigRational {
        &self.a * &self.a - &self.b * &self.b * BigRational::from_integer(self.d.clone())
    }

    /// The value as a complex `f64` (real when `d >= 0`).
    pub fn to_f64(&self) -> Complex64 {
        let a = rational_to_f64(&self.a);
        let b = rational_to_f64(&self.b);
        let d = self.d.to_f64().unwrap_or(f64::NAN);
        if d >= 0.0 {
            Complex64::new(a + b * d.sqrt(), 0.0)
        } else {
            Complex64::new(a, b * (-d).sqrt())
        }
    }

    fn radicand(&self, rhs: &Self) -> BigInt {
        if self.is_rational() {
            rhs.d.clone()
        } else {
            debug_assert!(
                rhs.is_rational() || rhs.d == self.d,
                "mixed quadratic fields"
            );
            self.d.clone()
        }
    }
}

impl fmt::Display for QuadraticSurd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_rational() {
            return write!(f, "{}", self.a);
        }
        if !Zero::is_zero(&self.a) {
            write!(f, "{}", self.a)?;
            if !self.b.is_negative() {
                f.write_str("+")?;
            }
        }
        if self.b == One::one() {
            write!(f, "sqrt({})", self.d)
        } else if self.b == -<BigRational as One>::one() {
            write!(f, "-sqrt({})", self.d)
        } else {
            write!(f, "{}*sqrt({})", self.b, self.d)
        }
    }
}

impl Field for QuadraticSurd {
    fn field_zero() -> Self {
        QuadraticSurd::rational(Zero::zero())
    }
    fn field_one() -> Self {
        QuadraticSurd::rational(One::one())
    }
    fn is_field_zero(&self) -> bool {
        Zero::is_zero(&self.a) && Zero::is_zero(&self.b)
    }
    fn add(&self, rhs: &Self) -> Self {
        QuadraticSurd::new(&self.a + &rhs.a, &self.b + &rhs.b, self.radicand(rhs))
    }
    fn sub(&self, rhs: &Self) -> Self {
        QuadraticSurd::new(&self.a - &rhs.a, &self.b - &rhs.b, self.radicand(rhs))
    }
    fn mul(&self, rhs: &Self) -> Self {
        let d = self.radicand(rhs);
        let dr = BigRational::from_integer(d.clone());
        QuadraticSurd::new(
            &self.a * &rhs.a + &self.b * &rhs.b * dr,
            &self.a * &rhs.b + &self.b * &rhs.a,
            d,
        )
    }
    fn div(&self, rhs: &Self) -> Self {
        let n = rhs.norm();
        let p = self.mul(&rhs.conjugate());
        QuadraticSurd::new(&p.a / &n, &p.b / &n, p.d)
    }
    fn neg(&self) -> Self {
        QuadraticSurd {
            a: -&self.a,
            b: -&self.b,
            d: self.d.clone(),
        }
    }
    fn from_rational(r: &BigRational) -> Self {
        QuadraticSurd::rational(r.clone())
    }
}

/// Dense square matrices over a [`Field`], row-major.
#[derive(Clone, Debug)]
pub(crate) struct FieldMatrix<F> {
    pub(crate) dim: usize,
    pub(crate) entries: Vec<F>,
}

impl<F: Field> FieldMatrix<F> {
    pub(crate) fn from_int(m: &crate::IntMatrix) -> Self {
        let entries = m
            .rows()
            .flatten()
            .map(|&x| F::from_rational(&BigRational::from_integer(BigInt::from(x))))
            .collect();
        FieldMatrix {
            dim: m.dim(),
            entries,
        }
    }

    pub(crate) fn scalar(dim: usize, c: &F) -> Self {
        let mut entries = vec![F::field_zero(); dim * dim];
        for i in 0..dim {
            entries[i * dim + i] = c.clone();
        }
        FieldMatrix { dim, entries }
    }

    pub(crate) fn mul(&self, rhs: &Self) -> Self {
        let n = self.dim;
        let mut entries = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let mut acc = F::field_zero();
                for k in 0..n {
                    let a = &self.entries[i * n + k];
                    let b = &rhs.entries[k * n + j];
                    if a.is_field_zero() || b.is_field_zero() {
                        continue;
                    }
                    acc = acc.add(&a.mul(b));
                }
                entries.push(acc);
            }
        }
        FieldMatrix { dim: n, entries }
    }

    /// `self + c I`.
    pub(crate) fn add_scalar(&self, c: &F) -> Self {
        let mut out = self.clone();
        for i in 0..self.dim {
            out.entries[i * self.dim + i] = out.entries[i * self.dim + i].add(c);
        }
        out
    }

    pub(crate) fn add(&self, rhs: &Self) -> Self {
        let entries = self
            .entries
            .iter()
            .zip(&rhs.entries)
            .map(|(a, b)| a.add(b))
            .collect();
        FieldMatrix {
            dim: self.dim,
            entries,
        }
    }

    pub(crate) fn row(&self, i: usize) -> &[F] {
        &self.entries[i * self.dim..(i + 1) * self.dim]
    }

    /// `q(self)` for a polynomial with coefficients lowest degree first, by Horner's rule.
    pub(crate) fn eval_poly(&self, coeffs: &[F]) -> Self {
        let mut acc = FieldMatrix::scalar(self.dim, &F::field_zero());
        for c in coeffs.iter().rev() {
            acc = acc.mul(self).add_scalar(c);
        }
        acc
    }
}

/// An element `x + y*sqrt(d)` of the ring `Z[sqrt d]`, the `d` being held by the
/// [`SurdRing`] that does the arithmetic (`y` is zero throughout for plain integers).
///
/// The exact closed forms are computed fraction-free in this ring: a rational or quadratic
/// eigenvalue `l` scaled by the least common denominator `c` of its parts lies in it, and so
/// does every entry of `c M - c l I`, every minor (fraction-free elimination), and every
/// numerator of the spectral parts. Each rational number is then formed once, at the end,
/// instead of reducing a fraction after every operation.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct RingElem {
    pub(crate) x: BigInt,
    pub(crate) y: BigInt,
}

impl RingElem {
    pub(crate) fn int(x: BigInt) -> Self {
        RingElem {
            x,
            y: BigInt::zero(),
        }
    }

    pub(crate) fn is_zero(&self) -> bool {
        self.x.is_zero() && self.y.is_zero()
    }

    pub(crate) fn conj(&self) -> Self {
        RingElem {
            x: self.x.clone(),
            y: -&self.y,
        }
    }
}

/// The arithmetic of `Z[sqrt d]` (`d = 0`: the integers).
#[derive(Clone, Debug)]
pub(crate) struct SurdRing {
    pub(crate) d: BigInt,
}

impl SurdRing {
    pub(crate) fn add(&self, a: &RingElem, b: &RingElem) -> RingElem {
        RingElem {
            x: &a.x + &b.x,
            y: &a.y + &b.y,
        }
    }

    pub(crate) fn sub(&self, a: &RingElem, b: &RingElem) -> RingElem {
        RingElem {
            x: &a.x - &b.x,
            y: &a.y - &b.y,
        }
    }

    pub(crate) fn mul(&self, a: &RingElem, b: &RingElem) -> RingElem {
        if a.y.is_zero() && b.y.is_zero() {
            return RingElem::int(&a.x * &b.x);
        }
        RingElem {
            x: &a.x * &b.x + &a.y * &b.y * &self.d,
            y: &a.x * &b.y + &a.y * &b.x,
        }
    }

    /// The norm `x^2 - d y^2`, an integer (zero only for zero when `d` is not a square).
    pub(crate) fn norm(&self, a: &RingElem) -> BigInt {
        &a.x * &a.x - &a.y * &a.y * &self.d
    }

    /// `a / b` when it lies in the ring, `None` otherwise (or when `b` is zero).
    pub(crate) fn div_exact(&self, a: &RingElem, b: &RingElem) -> Option<RingElem> {
        if b.y.is_zero() {
            if b.x.is_zero() {
                return None;
            }
            let (qx, rx) = a.x.div_rem(&b.x);
            let (qy, ry) = a.y.div_rem(&b.x);
            return (rx.is_zero() && ry.is_zero()).then_some(RingElem { x: qx, y: qy });
        }
        let n = self.norm(b);
        if n.is_zero() {
            return None;
        }
        let p = self.mul(a, &b.conj());
        let (qx, rx) = p.x.div_rem(&n);
        let (qy, ry) = p.y.div_rem(&n);
        (rx.is_zero() && ry.is_zero()).then_some(RingElem { x: qx, y: qy })
    }

    /// The product of a `rows x inner` and an `inner x cols` matrix (row-major).
    pub(crate) fn mat_mul(
        &self,
        a: &[RingElem],
        b: &[RingElem],
        rows: usize,
        inner: usize,
        cols: usize,
    ) -> Vec<RingElem> {
        let mut out = vec![RingElem::default(); rows * cols];
        for i in 0..rows {
            for k in 0..inner {
                let x = &a[i * inner + k];
                if x.is_zero() {
                    continue;
                }
                for j in 0..cols {
                    let y = &b[k * cols + j];
                    if !y.is_zero() {
                        let t = self.mul(x, y);
                        let o = &mut out[i * cols + j];
                        o.x += t.x;
                        o.y += t.y;
                    }
                }
            }
        }
        out
    }

    /// Fraction-free Gauss-Jordan elimination (Bareiss' rule, each division exact by
    /// Sylvester's identity) of a `rows x cols` matrix in place: afterwards every pivot
    /// equals the last pivot `D` (a minor of the input), the pivot columns are `D` times unit
    /// vectors, and the rows past the rank are zero. Returns the pivot columns and `D`, or
    /// `None` if a division was not exact (which would be a bug; the caller falls back).
    pub(crate) fn rref(
        &self,
        a: &mut [RingElem],
        rows: usize,
        cols: usize,
    ) -> Option<(Vec<usize>, RingElem)> {
        let mut pivots = Vec::new();
        let mut prev = RingElem::int(BigInt::one());
        let mut r = 0;
        for col in 0..cols {
            if r == rows {
                break;
            }
            let Some(p) = (r..rows).find(|&i| !a[i * cols + col].is_zero()) else {
                continue;
            };
            if p != r {
                for j in 0..cols {
                    a.swap(p * cols + j, r * cols + j);
                }
            }
            let pivot = a[r * cols + col].clone();
            for i in 0..rows {
                if i == r {
                    continue;
                }
                let f = a[i * cols + col].clone();
                for j in 0..cols {
                    let v = self.sub(
                        &self.mul(&pivot, &a[i * cols + j]),
                        &self.mul(&f, &a[r * cols + j]),
                    );
                    a[i * cols + j] = if v.is_zero() {
                        v
                    } else {
                        self.div_exact(&v, &prev)?
                    };
                }
            }
            pivots.push(col);
            prev = pivot;
            r += 1;
        }
        Some((pivots, prev))
    }

    /// A basis of the kernel of a `rows x cols` matrix: one vector per non-pivot column,
    /// with entries in the ring.
    pub(crate) fn kernel(
        &self,
        mut a: Vec<RingElem>,
        rows: usize,
        cols: usize,
    ) -> Option<Vec<Vec<RingElem>>> {
        let (pivots, d) = self.rref(&mut a, rows, cols)?;
        let mut basis = Vec::new();
        for f in (0..cols).filter(|c| !pivots.contains(c)) {
            let mut v = vec![RingElem::default(); cols];
            v[f] = d.clone();
            for (r, &pc) in pivots.iter().enumerate() {
                let e = &a[r * cols + f];
                v[pc] = RingElem { x: -&e.x, y: -&e.y };
            }
            basis.push(v);
        }
        Some(basis)
    }

    /// `(X, D)` with `G X = D I` for an invertible `m x m` matrix `G`, or `None` when `G` is
    /// singular or a division was not exact.
    pub(crate) fn scaled_inverse(
        &self,
        g: &[RingElem],
        m: usize,
    ) -> Option<(Vec<RingElem>, RingElem)> {
        let cols = 2 * m;
        let mut a = vec![RingElem::default(); m * cols];
        for i in 0..m {
            for j in 0..m {
                a[i * cols + j] = g[i * m + j].clone();
            }
            a[i * cols + m + i] = RingElem::int(BigInt::one());
        }
        let (pivots, d) = self.rref(&mut a, m, cols)?;
        if pivots.len() != m || pivots.iter().enumerate().any(|(i, &c)| c != i) {
            return None;
        }
        let mut x = Vec::with_capacity(m * m);
        for i in 0..m {
            x.extend_from_slice(&a[i * cols + m..(i + 1) * cols]);
        }
        Some((x, d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    #[test]
    fn surd_arithmetic_is_exact() {
        let phi = QuadraticSurd::new(q(1, 2), q(1, 2), 5.into());
        let psi = phi.conjugate();
        assert_eq!(phi.add(&psi), QuadraticSurd::rational(q(1, 1)));
        assert_eq!(phi.mul(&psi), QuadraticSurd::rational(q(-1, 1)));
        // phi^2 = phi + 1
        assert_eq!(phi.mul(&phi), phi.add(&QuadraticSurd::field_one()));
        assert_eq!(phi.div(&phi), QuadraticSurd::field_one());
        assert_eq!(psi.to_string(), "1/2-1/2*sqrt(5)");
        let i = QuadraticSurd::new(q(0, 1), q(1, 1), (-1).into());
        assert_eq!(i.mul(&i), QuadraticSurd::rational(q(-1, 1)));
        assert_eq!(i.to_string(), "sqrt(-1)");
    }

    #[test]
    fn rational_to_f64_handles_huge_parts() {
        let big = BigInt::from(10).pow(400u32);
        let r = BigRational::new(&big * 3, big);
        assert_eq!(rational_to_f64(&r), 3.0);
    }
}
