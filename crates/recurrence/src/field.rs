//! The fields the closed-form machinery computes in: the rationals, quadratic fields
//! `Q(sqrt d)` (exact), and `f64` complex numbers (numeric, for everything else).
//!
//! The spectral decomposition is written once over the crate-private [`Field`] trait and run
//! with the field that holds the eigenvalue at hand.

use std::fmt;

use nalgebra::Complex;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// The arithmetic of a field, as the spectral decomposition needs it.
pub(crate) trait Field: Clone + fmt::Debug {
    fn field_zero() -> Self;
    fn field_one() -> Self;
    /// Whether the value is zero (exact fields), or negligibly small (numeric fields).
    fn is_field_zero(&self) -> bool;
    fn add(&self, rhs: &Self) -> Self;
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
    pub fn to_f64(&self) -> Complex<f64> {
        let a = rational_to_f64(&self.a);
        let b = rational_to_f64(&self.b);
        let d = self.d.to_f64().unwrap_or(f64::NAN);
        if d >= 0.0 {
            Complex::new(a + b * d.sqrt(), 0.0)
        } else {
            Complex::new(a, b * (-d).sqrt())
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
