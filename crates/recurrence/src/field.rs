//! The fields the closed-form machinery computes in: the rationals, quadratic fields
//! `Q(sqrt d)` (exact), and `f64` complex numbers (numeric, for everything else).
//!
//! The spectral decomposition is written once over `num_traits` bounds (the crate-private
//! [`Field`] adds only division and the rationals) and run with the field that holds the
//! eigenvalue at hand.

use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{CheckedAdd, CheckedMul, One, Signed, ToPrimitive, Zero};

use crate::{Complex64, IntMatrix, Matrix};

/// What the spectral decomposition needs of the field it computes in, beyond `num_traits`'
/// ring operations: division, negation and the embedding of the rationals. The checked
/// operations (by reference, so big numbers are not copied) never fail in these fields;
/// [`Matrix`]'s products use them.
pub(crate) trait Field:
    Clone
    + fmt::Debug
    + Zero
    + One
    + CheckedAdd
    + CheckedMul
    + Sub<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    fn from_rational(r: &BigRational) -> Self;

    /// `q(M)` for an integer matrix `M`. The default runs Horner's rule in the field;
    /// the rationals override it with integer arithmetic when `q` has integer coefficients
    /// (as every cofactor of an integer eigenvalue does), which avoids a gcd per operation.
    fn eval_poly_at_int(m: &IntMatrix, coeffs: &[Self]) -> Matrix<Self> {
        m.map(|&x| Self::from_rational(&BigRational::from_integer(BigInt::from(x))))
            .eval_poly(coeffs)
    }
}

impl Field for BigRational {
    fn from_rational(r: &BigRational) -> Self {
        r.clone()
    }

    fn eval_poly_at_int(m: &IntMatrix, coeffs: &[Self]) -> Matrix<Self> {
        if !coeffs.iter().all(|c| c.is_integer()) {
            return m
                .map(|&x| BigRational::from_integer(BigInt::from(x)))
                .eval_poly(coeffs);
        }
        let integer: Vec<BigInt> = coeffs.iter().map(BigRational::to_integer).collect();
        m.map(|&x| BigInt::from(x))
            .checked_eval_poly(&integer)
            .expect("big integers do not overflow")
            .map(|x| BigRational::from_integer(x.clone()))
    }
}

impl Field for Complex64 {
    fn from_rational(r: &BigRational) -> Self {
        Complex64::new(rational_to_f64(r), 0.0)
    }
}

/// Matrix arithmetic in a [`Field`], where [`Matrix`]'s checked operations never fail.
pub(crate) trait FieldMatrix<F> {
    /// `self * rhs`.
    fn mul(&self, rhs: &Self) -> Self;
    /// `self + rhs`.
    fn add(&self, rhs: &Self) -> Self;
    /// `self + c I`.
    fn add_scalar(&self, c: &F) -> Self;
    /// `q(self)` for a polynomial with coefficients lowest degree first, by Horner's rule.
    fn eval_poly(&self, coeffs: &[F]) -> Self;
}

const EXACT: &str = "field arithmetic does not overflow";

impl<F: Field> FieldMatrix<F> for Matrix<F> {
    fn mul(&self, rhs: &Self) -> Self {
        self.checked_mul(rhs).expect(EXACT)
    }

    fn add(&self, rhs: &Self) -> Self {
        self.checked_add(rhs).expect(EXACT)
    }

    fn add_scalar(&self, c: &F) -> Self {
        self.checked_add_scalar(c).expect(EXACT)
    }

    fn eval_poly(&self, coeffs: &[F]) -> Self {
        self.checked_eval_poly(coeffs).expect(EXACT)
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

impl Zero for QuadraticSurd {
    fn zero() -> Self {
        QuadraticSurd::rational(Zero::zero())
    }
    fn is_zero(&self) -> bool {
        Zero::is_zero(&self.a) && Zero::is_zero(&self.b)
    }
}

impl One for QuadraticSurd {
    fn one() -> Self {
        QuadraticSurd::rational(One::one())
    }
}

/// `+`, `-` and unary `-` on references of a type `p + q sqrt(d)` with parts `p`, `q` and
/// radicand `d`, part by part (`Type::new(p, q, radicand)` normalizes; `radicand` is the one
/// the two operands share), and its checked `+` and `*`, which never fail (exact arithmetic).
macro_rules! exact_ops {
    ($t:ident { $p:ident, $q:ident }) => {
        impl Add<&$t> for &$t {
            type Output = $t;
            fn add(self, rhs: &$t) -> $t {
                $t::new(&self.$p + &rhs.$p, &self.$q + &rhs.$q, self.radicand(rhs))
            }
        }

        impl Sub<&$t> for &$t {
            type Output = $t;
            fn sub(self, rhs: &$t) -> $t {
                $t::new(&self.$p - &rhs.$p, &self.$q - &rhs.$q, self.radicand(rhs))
            }
        }

        impl Neg for &$t {
            type Output = $t;
            fn neg(self) -> $t {
                $t {
                    $p: -&self.$p,
                    $q: -&self.$q,
                    d: self.d.clone(),
                }
            }
        }

        impl CheckedAdd for $t {
            fn checked_add(&self, rhs: &Self) -> Option<Self> {
                Some(self + rhs)
            }
        }

        impl CheckedMul for $t {
            fn checked_mul(&self, rhs: &Self) -> Option<Self> {
                Some(self * rhs)
            }
        }
    };
}
exact_ops!(QuadraticSurd { a, b });

impl Mul<&QuadraticSurd> for &QuadraticSurd {
    type Output = QuadraticSurd;
    fn mul(self, rhs: &QuadraticSurd) -> QuadraticSurd {
        let d = self.radicand(rhs);
        let dr = BigRational::from_integer(d.clone());
        QuadraticSurd::new(
            &self.a * &rhs.a + &self.b * &rhs.b * dr,
            &self.a * &rhs.b + &self.b * &rhs.a,
            d,
        )
    }
}

impl Div<&QuadraticSurd> for &QuadraticSurd {
    type Output = QuadraticSurd;
    /// Division; the caller guarantees that `rhs` is not zero.
    fn div(self, rhs: &QuadraticSurd) -> QuadraticSurd {
        let n = rhs.norm();
        let p = self * &rhs.conjugate();
        QuadraticSurd::new(&p.a / &n, &p.b / &n, p.d)
    }
}

impl Neg for QuadraticSurd {
    type Output = QuadraticSurd;
    fn neg(self) -> QuadraticSurd {
        -&self
    }
}

/// The by-value operators of `$t`, forwarded to the by-reference ones.
macro_rules! forward_by_value {
    ($t:ident: $($imp:ident $method:ident),*) => {$(
        impl $imp for $t {
            type Output = $t;
            fn $method(self, rhs: $t) -> $t {
                (&self).$method(&rhs)
            }
        }
    )*};
}
forward_by_value!(QuadraticSurd: Add add, Sub sub, Mul mul, Div div);

impl Field for QuadraticSurd {
    fn from_rational(r: &BigRational) -> Self {
        QuadraticSurd::rational(r.clone())
    }
}

/// An element `x + y*sqrt(d)` of the ring `Z[sqrt d]`; `d` is `0` whenever `y` is, so plain
/// integers carry no radicand (and cloning them copies no radicand).
///
/// The exact closed forms are computed fraction-free in this ring: a rational or quadratic
/// eigenvalue `l` scaled by the least common denominator `c` of its parts lies in it, and so
/// does every entry of `c M - c l I`, every minor (fraction-free elimination), and every
/// numerator of the spectral parts. Each rational number is then formed once, at the end,
/// instead of reducing a fraction after every operation. The products are [`Matrix`]'s.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct RingElem {
    pub(crate) x: BigInt,
    pub(crate) y: BigInt,
    pub(crate) d: BigInt,
}

impl RingElem {
    pub(crate) fn int(x: BigInt) -> Self {
        RingElem {
            x,
            y: BigInt::zero(),
            d: BigInt::zero(),
        }
    }

    /// `x + y sqrt(d)`, normalized so that `d` is `0` when `y` is.
    pub(crate) fn new(x: BigInt, y: BigInt, d: &BigInt) -> Self {
        if y.is_zero() {
            RingElem::int(x)
        } else {
            RingElem { x, y, d: d.clone() }
        }
    }

    /// The radicand shared by `self` and `rhs` (elements of one ring; integers have none).
    fn radicand<'a>(&'a self, rhs: &'a Self) -> &'a BigInt {
        if self.y.is_zero() {
            &rhs.d
        } else {
            &self.d
        }
    }

    pub(crate) fn conj(&self) -> Self {
        RingElem {
            x: self.x.clone(),
            y: -&self.y,
            d: self.d.clone(),
        }
    }

    /// The norm `x^2 - d y^2`, an integer (zero only for zero when `d` is not a square).
    pub(crate) fn norm(&self) -> BigInt {
        &self.x * &self.x - &self.y * &self.y * &self.d
    }

    /// `self / b` when it lies in the ring, `None` otherwise (or when `b` is zero).
    pub(crate) fn div_exact(&self, b: &RingElem) -> Option<RingElem> {
        let (p, n) = if b.y.is_zero() {
            (self.clone(), b.x.clone())
        } else {
            (self * &b.conj(), b.norm())
        };
        if n.is_zero() {
            return None;
        }
        let (qx, rx) = p.x.div_rem(&n);
        let (qy, ry) = p.y.div_rem(&n);
        (rx.is_zero() && ry.is_zero()).then(|| RingElem::new(qx, qy, &p.d))
    }
}

exact_ops!(RingElem { x, y });

impl Mul<&RingElem> for &RingElem {
    type Output = RingElem;
    fn mul(self, rhs: &RingElem) -> RingElem {
        if self.y.is_zero() && rhs.y.is_zero() {
            return RingElem::int(&self.x * &rhs.x);
        }
        let d = self.radicand(rhs);
        RingElem::new(
            &self.x * &rhs.x + &self.y * &rhs.y * d,
            &self.x * &rhs.y + &self.y * &rhs.x,
            d,
        )
    }
}

forward_by_value!(RingElem: Add add, Mul mul);

impl Zero for RingElem {
    fn zero() -> Self {
        RingElem::default()
    }
    fn is_zero(&self) -> bool {
        self.x.is_zero() && self.y.is_zero()
    }
}

impl One for RingElem {
    fn one() -> Self {
        RingElem::int(BigInt::one())
    }
}

/// Fraction-free Gauss-Jordan elimination (Bareiss' rule, each division exact by Sylvester's
/// identity) of a matrix in place: afterwards every pivot equals the last pivot `D` (a minor
/// of the input), the pivot columns are `D` times unit vectors, and the rows past the rank
/// are zero. Returns the pivot columns and `D`, or `None` if a division was not exact (which
/// would be a bug; the caller falls back).
pub(crate) fn rref(a: &mut Matrix<RingElem>) -> Option<(Vec<usize>, RingElem)> {
    let (rows, cols) = (a.dim(), a.ncols());
    let a = a.entries_mut();
    let mut pivots = Vec::new();
    let mut prev = RingElem::one();
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
                let v = &(&pivot * &a[i * cols + j]) - &(&f * &a[r * cols + j]);
                a[i * cols + j] = if v.is_zero() { v } else { v.div_exact(&prev)? };
            }
        }
        pivots.push(col);
        prev = pivot;
        r += 1;
    }
    Some((pivots, prev))
}

/// A basis of the kernel of a matrix: one vector per non-pivot column, with entries in the
/// ring.
pub(crate) fn kernel(mut a: Matrix<RingElem>) -> Option<Vec<Vec<RingElem>>> {
    let cols = a.ncols();
    let (pivots, d) = rref(&mut a)?;
    let mut basis = Vec::new();
    for f in (0..cols).filter(|c| !pivots.contains(c)) {
        let mut v = vec![RingElem::zero(); cols];
        v[f] = d.clone();
        for (r, &pc) in pivots.iter().enumerate() {
            v[pc] = -a.entry(r, f);
        }
        basis.push(v);
    }
    Some(basis)
}

/// `(X, D)` with `G X = D I` for an invertible square matrix `G`, or `None` when `G` is
/// singular or a division was not exact.
pub(crate) fn scaled_inverse(g: &Matrix<RingElem>) -> Option<(Matrix<RingElem>, RingElem)> {
    let m = g.dim();
    let cols = 2 * m;
    let mut a = Matrix::zeros(m, cols);
    for i in 0..m {
        for j in 0..m {
            a.entries_mut()[i * cols + j] = g.entry(i, j).clone();
        }
        a.entries_mut()[i * cols + m + i] = RingElem::one();
    }
    let (pivots, d) = rref(&mut a)?;
    if pivots.len() != m || pivots.iter().enumerate().any(|(i, &c)| c != i) {
        return None;
    }
    let x = a.rows().flat_map(|row| row[m..].iter().cloned()).collect();
    Some((Matrix::from_vec(m, m, x), d))
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
        assert_eq!(&phi + &psi, QuadraticSurd::rational(q(1, 1)));
        assert_eq!(&phi * &psi, QuadraticSurd::rational(q(-1, 1)));
        // phi^2 = phi + 1
        assert_eq!(&phi * &phi, &phi + &QuadraticSurd::one());
        assert_eq!(&phi / &phi, QuadraticSurd::one());
        assert_eq!(
            -(&phi - &psi),
            QuadraticSurd::new(q(0, 1), q(-1, 1), 5.into())
        );
        assert_eq!(psi.to_string(), "1/2-1/2*sqrt(5)");
        let i = QuadraticSurd::new(q(0, 1), q(1, 1), (-1).into());
        assert_eq!(&i * &i, QuadraticSurd::rational(q(-1, 1)));
        assert_eq!(i.to_string(), "sqrt(-1)");
    }

    #[test]
    fn rational_to_f64_handles_huge_parts() {
        let big = BigInt::from(10).pow(400u32);
        let r = BigRational::new(&big * 3, big);
        assert_eq!(rational_to_f64(&r), 3.0);
    }
}
