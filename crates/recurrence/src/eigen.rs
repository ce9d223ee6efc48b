//! Eigenvalues with multiplicities: exact integers and quadratic surds where they exist,
//! numeric (labelled so) otherwise.
//!
//! The characteristic polynomial is split exactly into square-free, pairwise coprime factors
//! (Yun). The roots of each factor are located numerically (eigenvalues of its companion
//! matrix with nalgebra), and then confirmed exactly: a near-real root is rounded to an
//! integer candidate (refined by exact Newton steps) and kept when polynomial division leaves
//! no remainder; the remaining roots are paired and kept as a quadratic surd when the integer
//! quadratic `x^2 - (r1 + r2) x + r1 r2` divides exactly. Divisors of the constant term are
//! never enumerated. Whatever is left stays numeric.

use std::cmp::Ordering;
use std::fmt;

use nalgebra::{Complex, DMatrix};

use crate::Complex64;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{FromPrimitive, One, Pow, Signed, Zero};

use crate::field::{rational_to_f64, QuadraticSurd};
use crate::poly::{derivative_int, divide_monic_exact, square_free_factors, Polynomial};

/// An eigenvalue of a recurrence matrix, exact when possible.
///
/// Eigenvalues of integer matrices that are rational are integers; they are
/// [`Eigenvalue::Rational`]. Roots of an integer quadratic factor are
/// [`Eigenvalue::QuadraticSurd`], exact in `Q(sqrt d)` (negative `d` for complex pairs).
/// Anything else is [`Eigenvalue::Numeric`]: an `f64` approximation, never shown as exact.
#[derive(Clone, Debug, PartialEq)]
pub enum Eigenvalue {
    /// An exact rational (in fact integer) eigenvalue.
    Rational(BigRational),
    /// The exact quadratic irrational `a + b*sqrt(d)` (`b != 0`, `d` not a square).
    QuadraticSurd {
        /// The rational part.
        a: BigRational,
        /// The coefficient of `sqrt(d)`.
        b: BigRational,
        /// The radicand, square-free where small factors could be found.
        d: BigInt,
    },
    /// A numeric approximation (complex in general), for roots of higher-degree factors.
    Numeric(Complex64),
}

impl Eigenvalue {
    /// Whether the value is exact (rational or quadratic surd).
    pub fn is_exact(&self) -> bool {
        !matches!(self, Eigenvalue::Numeric(_))
    }

    /// The rational value, if the eigenvalue is rational.
    pub fn as_rational(&self) -> Option<&BigRational> {
        match self {
            Eigenvalue::Rational(r) => Some(r),
            _ => None,
        }
    }

    /// The exact value as an element of `Q(sqrt d)` (rationals have `b = 0`), if exact.
    pub fn to_surd(&self) -> Option<QuadraticSurd> {
        match self {
            Eigenvalue::Rational(r) => Some(QuadraticSurd::rational(r.clone())),
            Eigenvalue::QuadraticSurd { a, b, d } => {
                Some(QuadraticSurd::new(a.clone(), b.clone(), d.clone()))
            }
            Eigenvalue::Numeric(_) => None,
        }
    }

    /// The value as a complex `f64`.
    pub fn to_complex(&self) -> Complex64 {
        match self {
            Eigenvalue::Rational(r) => Complex64::new(rational_to_f64(r), 0.0),
            Eigenvalue::QuadraticSurd { a, b, d } => {
                QuadraticSurd::new(a.clone(), b.clone(), d.clone()).to_f64()
            }
            Eigenvalue::Numeric(z) => *z,
        }
    }

    /// The modulus `|lambda|` as an `f64` (the growth rate of its terms).
    pub fn modulus(&self) -> f64 {
        self.to_complex().norm()
    }

    /// Whether this is the exact integer zero.
    pub fn is_zero(&self) -> bool {
        matches!(self, Eigenvalue::Rational(r) if r.is_zero())
    }

    /// Total order used for listing: larger modulus first, then larger real part, then
    /// larger imaginary part.
    pub(crate) fn listing_order(&self, other: &Self) -> Ordering {
        let (a, b) = (self.to_complex(), other.to_complex());
        b.norm()
            .total_cmp(&a.norm())
            .then(b.re.total_cmp(&a.re))
            .then(b.im.total_cmp(&a.im))
    }
}

impl fmt::Display for Eigenvalue {
    /// Rationals as `p` or `p/q`, surds as `a+b*sqrt(d)`, numeric values as `re+imi` with 12
    /// significant digits.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Eigenvalue::Rational(r) => write!(f, "{r}"),
            Eigenvalue::QuadraticSurd { a, b, d } => {
                write!(f, "{}", QuadraticSurd::new(a.clone(), b.clone(), d.clone()))
            }
            Eigenvalue::Numeric(z) => write!(f, "{z}"),
        }
    }
}

/// An eigenvalue with its algebraic multiplicity.
#[derive(Clone, Debug, PartialEq)]
pub struct EigenvalueInfo {
    /// The eigenvalue.
    pub eigenvalue: Eigenvalue,
    /// How often it is a root of the characteristic polynomial.
    pub multiplicity: usize,
}

/// The eigenvalues of the matrix whose characteristic polynomial is `p`, in listing order.
pub(crate) fn eigenvalues(p: &Polynomial) -> Vec<EigenvalueInfo> {
    let mut out = Vec::new();
    for (factor, multiplicity) in square_free_factors(p.coefficients()) {
        for eigenvalue in roots_of_square_free(&factor) {
            out.push(EigenvalueInfo {
                eigenvalue,
                multiplicity,
            });
        }
    }
    out.sort_by(|a, b| a.eigenvalue.listing_order(&b.eigenvalue));
    out
}

/// Numeric roots of a monic polynomial given by its coefficients (lowest first).
pub(crate) fn numeric_roots(f: &[BigInt]) -> Vec<Complex<f64>> {
    let n = f.len() - 1;
    if n == 0 {
        return Vec::new();
    }
    let coeffs: Vec<f64> = f
        .iter()
        .map(|c| rational_to_f64(&BigRational::from_integer(c.clone())))
        .collect();
    if n == 1 {
        return vec![Complex::new(-coeffs[0], 0.0)];
    }
    let mut companion = DMatrix::<f64>::zeros(n, n);
    for i in 1..n {
        companion[(i, i - 1)] = 1.0;
    }
    for i in 0..n {
        companion[(i, n - 1)] = -coeffs[i];
    }
    match nalgebra::linalg::Schur::try_new(companion, f64::EPSILON, schur_iterations(n)) {
        Some(schur) => schur.complex_eigenvalues().iter().copied().collect(),
        None => durand_kerner(&coeffs),
    }
}

/// The most QR iterations the Schur decomposition of a degree-`n` companion matrix may take:
/// LAPACK's `dlahqr` allows `30 max(10, n)`; this allows `100 max(10, n)`. Each iteration
/// costs `O(n^2)`, and a decomposition that has not converged by then does not converge at
/// all (badly scaled companions of degree 28 and more), so the cap keeps the cost `O(n^3)`
/// before [`durand_kerner`] takes over.
fn schur_iterations(n: usize) -> usize {
    100 * n.max(10)
}

/// Durand-Kerner iteration, the fallback when the Schur decomposition does not converge.
fn durand_kerner(coeffs: &[f64]) -> Vec<Complex<f64>> {
    let n = coeffs.len() - 1;
    let eval = |z: Complex<f64>| {
        coeffs
            .iter()
            .rev()
            .fold(Complex::new(0.0, 0.0), |acc, &c| acc * z + c)
    };
    let radius = 1.0 + coeffs[..n].iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let mut z: Vec<Complex<f64>> = (0..n)
        .map(|k| {
            Complex::from_polar(
                radius,
                0.4 + 2.0 * std::f64::consts::PI * k as f64 / n as f64,
            )
        })
        .collect();
    for _ in 0..2000 {
        let mut delta = 0.0f64;
        for i in 0..n {
            let mut denom = Complex::new(1.0, 0.0);
            for j in 0..n {
                if i != j {
                    denom *= z[i] - z[j];
                }
            }
            let step = eval(z[i]) / denom;
            z[i] -= step;
            delta = delta.max(step.norm());
        }
        if delta < 1e-15 {
            break;
        }
    }
    z
}

fn eval_int(f: &[BigInt], x: &BigInt) -> BigInt {
    f.iter().rev().fold(BigInt::zero(), |acc, c| acc * x + c)
}

/// An integer root of `f` that exact Newton steps reach from `start` (each step rounded to
/// an integer, every candidate confirmed by exact evaluation), if any.
fn integer_root_from(f: &[BigInt], start: BigInt) -> Option<BigInt> {
    let df: Vec<BigInt> = f
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, c)| c * BigInt::from(k))
        .collect();
    let mut c = start;
    // Newton's steps at least halve the distance to a root once close; from a root bound
    // of b bits they need about b of them (double roots are divided out beforehand).
    let steps = 64 + 2 * f.iter().map(BigInt::bits).max().unwrap_or(0);
    for _ in 0..steps {
        for delta in [0, 1, -1] {
            let cand: BigInt = &c + delta;
            if eval_int(f, &cand).is_zero() {
                return Some(cand);
            }
        }
        let d = eval_int(&df, &c);
        if d.is_zero() {
            return None;
        }
        let step = BigRational::new(eval_int(f, &c), d).round().to_integer();
        if step.is_zero() {
            return None;
        }
        c -= step;
    }
    None
}

/// The integer roots of the square-free monic `f`, and `f` with them divided out: searched
/// by Newton's method from the numeric roots and from both [`root_bound`]s (started outside
/// every root it converges to the largest or smallest real root even when the `f64`
/// estimates are poor, as for entries beyond `2^53`), then by Sturm isolation for large
/// coefficients.
fn integer_roots(f: &[BigInt]) -> (Vec<BigInt>, Vec<BigInt>) {
    let mut rest = f.to_vec();
    let mut found = Vec::new();
    // Degree two and below are solved exactly by the caller.
    'search: while rest.len() > 3 {
        let bound = root_bound(&rest);
        let mut seeds: Vec<BigInt> = numeric_roots(&rest)
            .iter()
            .filter(|z| z.im.abs() <= 1e-6 * z.norm().max(1.0))
            .filter_map(|z| BigInt::from_f64(z.re.round()))
            .collect();
        seeds.push(bound.clone());
        seeds.push(-bound);
        for seed in seeds {
            if let Some(c) = integer_root_from(&rest, seed) {
                if let Some(q) = divide_exact(&rest, &[-c.clone(), BigInt::one()]) {
                    rest = q;
                    found.push(c);
                    continue 'search;
                }
            }
        }
        break;
    }
    // Beyond 2^50 the f64 estimates may miss integer roots altogether (two roots near 2^63
    // merge into one estimate): find every remaining one exactly.
    if rest.len() > 3 && rest.iter().any(|c| c.bits() > 50) {
        for c in sturm_integer_roots(&rest) {
            if let Some(q) = divide_exact(&rest, &[-c.clone(), BigInt::one()]) {
                rest = q;
                found.push(c);
            }
        }
    }
    (found, rest)
}

/// A bound every root of the monic `f` stays below in modulus: Fujiwara's
/// `2 max_k |c_(n-k)|^(1/k)`, with each root rounded up, plus one. It follows the size of the
/// roots rather than of the coefficients (roots near `2^64` of a polynomial whose constant
/// has 1,000 bits), which keeps the bisections short.
fn root_bound(f: &[BigInt]) -> BigInt {
    let n = f.len().saturating_sub(1);
    let largest = (1..=n)
        .map(|k| {
            let c = f[n - k].abs();
            // `k <= n` is a matrix dimension: it fits in `u32`.
            let r = c.nth_root(u32::try_from(k).unwrap_or(u32::MAX));
            if Pow::pow(&r, k) < c {
                r + 1
            } else {
                r
            }
        })
        .max()
        .unwrap_or_default();
    largest * 2 + 1
}

/// `f` scaled by a positive rational to a primitive integer polynomial (signs kept).
fn primitive(f: &[BigRational]) -> Vec<BigInt> {
    let lcm = f.iter().fold(BigInt::one(), |l, c| l.lcm(c.denom()));
    let ints: Vec<BigInt> = f.iter().map(|c| (c * &lcm).to_integer()).collect();
    let gcd = ints.iter().fold(BigInt::zero(), |g, c| g.gcd(c));
    if gcd.is_zero() {
        return ints;
    }
    ints.into_iter().map(|c| c / &gcd).collect()
}

/// The remainder of `a` divided by `b` (integer coefficients, lowest first), over the
/// rationals and made primitive by a positive factor.
fn remainder(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut r: Vec<BigRational> = a.iter().cloned().map(BigRational::from_integer).collect();
    let lead = BigRational::from_integer(b[b.len() - 1].clone());
    while r.len() >= b.len() {
        let q = &r[r.len() - 1] / &lead;
        let shift = r.len() - b.len();
        for (k, c) in b.iter().enumerate() {
            r[shift + k] -= &q * c;
        }
        r.pop();
        while r.last().is_some_and(Zero::is_zero) {
            r.pop();
        }
    }
    primitive(&r)
}

/// Every integer root of the square-free `f`, by exact real root isolation: Sturm's chain
/// counts the real roots in an interval, bisection over integers narrows each interval to
/// width one, and only its integer end can be a root. About `deg f * log2(bound)`
/// evaluations of the chain, independent of how well `f64` would do.
fn sturm_integer_roots(f: &[BigInt]) -> Vec<BigInt> {
    let mut chain = vec![f.to_vec(), derivative_int(f)];
    loop {
        let n = chain.len();
        let r = remainder(&chain[n - 2], &chain[n - 1]);
        if r.is_empty() {
            break;
        }
        chain.push(r.into_iter().map(|c| -c).collect());
    }
    let changes = |x: &BigInt| -> usize {
        let signs: Vec<bool> = chain
            .iter()
            .map(|p| eval_int(p, x))
            .filter(|v| !v.is_zero())
            .map(|v| v.is_negative())
            .collect();
        signs.windows(2).filter(|w| w[0] != w[1]).count()
    };
    let bound = root_bound(f);
    let mut roots = Vec::new();
    // (lo, hi, V(lo), V(hi)): V(lo) - V(hi) roots lie in (lo, hi].
    let lo = -&bound - 1;
    let (v_lo, v_hi) = (changes(&lo), changes(&bound));
    let mut stack = vec![(lo, bound, v_lo, v_hi)];
    while let Some((lo, hi, v_lo, v_hi)) = stack.pop() {
        if v_lo <= v_hi {
            continue;
        }
        if &hi - &lo <= BigInt::one() {
            // The only integer in (lo, hi] is hi.
            if eval_int(f, &hi).is_zero() {
                roots.push(hi);
            }
            continue;
        }
        let mid = (&lo + &hi).div_floor(&BigInt::from(2));
        let v_mid = changes(&mid);
        stack.push((lo, mid.clone(), v_lo, v_mid));
        stack.push((mid, hi, v_mid, v_hi));
    }
    roots
}

/// Divides `f` by the monic integer polynomial `g` if the division is exact.
fn divide_exact(f: &[BigInt], g: &[BigInt]) -> Option<Vec<BigInt>> {
    divide_monic_exact(f, g)
}

/// The roots of a square-free monic integer polynomial: exact where they are rational or
/// quadratic surds that the search finds, numeric otherwise.
///
/// A factor of degree one or two (the whole polynomial, or what is left once the integer
/// roots are divided out) gets its roots symbolically from its coefficients, whatever their
/// size: the `f64` roots only guide the search for integer roots (each confirmed by exact
/// evaluation) and for quadratic factors of higher-degree polynomials (each confirmed by
/// exact division).
fn roots_of_square_free(f: &[BigInt]) -> Vec<Eigenvalue> {
    if let Some(exact) = low_degree_roots(f) {
        return exact;
    }
    let (integers, mut rest) = integer_roots(f);
    // The numeric roots left, in the order of `f`'s roots closest to an integer first (the
    // order in which the terms are listed), each integer root taking out its nearest one.
    let mut numeric = numeric_roots(f);
    numeric.sort_by(|a, b| {
        let da = (a.re - a.re.round()).abs() + a.im.abs();
        let db = (b.re - b.re.round()).abs() + b.im.abs();
        da.total_cmp(&db)
    });
    let mut found = Vec::with_capacity(f.len());
    for c in integers {
        let x = rational_to_f64(&BigRational::from_integer(c.clone()));
        let nearest = (0..numeric.len()).min_by(|&a, &b| {
            let da = (numeric[a] - Complex::new(x, 0.0)).norm();
            let db = (numeric[b] - Complex::new(x, 0.0)).norm();
            da.total_cmp(&db)
        });
        if let Some(k) = nearest {
            numeric.remove(k);
        }
        found.push(Eigenvalue::Rational(BigRational::from_integer(c)));
    }
    if let Some(exact) = low_degree_roots(&rest) {
        found.extend(exact);
        return found;
    }
    // Quadratic factors, from pairs of the remaining roots (conjugates first).
    let mut i = 0;
    'outer: while i < numeric.len() {
        let mut partners: Vec<usize> = (i + 1..numeric.len()).collect();
        let zi = numeric[i];
        partners.sort_by(|&a, &b| {
            (numeric[a] - zi.conj())
                .norm()
                .total_cmp(&(numeric[b] - zi.conj()).norm())
        });
        for j in partners {
            let (sum, prod) = (zi + numeric[j], zi * numeric[j]);
            let tol = 1e-6 * (1.0 + sum.norm().max(prod.norm()));
            // The pair's sum and product must be integers, not just round to ones: two roots
            // of different factors can round to another factor's coefficients (-5.14 and
            // 0.646, roots of x^2 + 3x - 11 and x^2 + 4x - 3, round to the latter's -4, -3).
            let off = |x: f64| (x - x.round()).abs();
            if sum.im.abs() > tol || prod.im.abs() > tol || off(sum.re) > tol || off(prod.re) > tol
            {
                continue;
            }
            let (Some(s), Some(p)) = (
                BigInt::from_f64(sum.re.round()),
                BigInt::from_f64(prod.re.round()),
            ) else {
                continue;
            };
            let quad = [p.clone(), -s.clone(), BigInt::one()];
            if let Some(q) = divide_exact(&rest, &quad) {
                rest = q;
                found.extend(quadratic_roots(&s, &p));
                numeric.remove(j);
                numeric.remove(i);
                continue 'outer;
            }
        }
        i += 1;
    }
    found.extend(
        numeric
            .into_iter()
            .map(|z| Eigenvalue::Numeric(Complex64::from_nalgebra(z))),
    );
    found
}

/// The exact roots of a monic integer polynomial of degree at most two (none for a
/// constant), or `None` for a higher degree.
fn low_degree_roots(f: &[BigInt]) -> Option<Vec<Eigenvalue>> {
    match f {
        [_] => Some(Vec::new()),
        [c0, _] => Some(vec![Eigenvalue::Rational(BigRational::from_integer(-c0))]),
        [c0, c1, _] => Some(quadratic_roots(&-c1, c0)),
        _ => None,
    }
}

/// The two roots of `x^2 - s x + p`.
fn quadratic_roots(s: &BigInt, p: &BigInt) -> Vec<Eigenvalue> {
    let disc: BigInt = s * s - p * 4;
    let two = BigInt::from(2);
    if !disc.is_negative() {
        let r = disc.sqrt();
        if &r * &r == disc {
            return [s + &r, s - &r]
                .into_iter()
                .map(|x| Eigenvalue::Rational(BigRational::new(x, two.clone())))
                .collect();
        }
    }
    let (k, d) = split_square(&disc);
    let a = BigRational::new(s.clone(), two.clone());
    let b = BigRational::new(k, two);
    vec![
        Eigenvalue::QuadraticSurd {
            a: a.clone(),
            b: b.clone(),
            d: d.clone(),
        },
        Eigenvalue::QuadraticSurd { a, b: -b, d },
    ]
}

/// Writes `n = k^2 d` pulling out the square factors of the primes below 1000 (enough to make
/// `d` square-free for every radicand that small matrices produce).
fn split_square(n: &BigInt) -> (BigInt, BigInt) {
    let mut k = BigInt::one();
    let mut d = n.clone();
    let mut p = 2u32;
    while p < 1000 {
        let pp = BigInt::from(p * p);
        if pp > d.abs() {
            break;
        }
        while (&d % &pp).is_zero() {
            d /= &pp;
            k *= p;
        }
        p += 1;
    }
    (k, d)
}

/// `|lambda| = 2^k` for an integer eigenvalue: returns `k`.
pub(crate) fn power_of_two_exponent(lambda: &BigInt) -> Option<u64> {
    let m = lambda.magnitude();
    if m.is_zero() {
        return None;
    }
    let tz = m.trailing_zeros()?;
    (m >> tz).is_one().then_some(tz)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::poly::characteristic_polynomial;
    use crate::IntMatrix;

    fn eig(m: &str) -> Vec<(String, usize)> {
        let m: IntMatrix = m.parse().unwrap();
        eigenvalues(&characteristic_polynomial(&m))
            .into_iter()
            .map(|e| (e.eigenvalue.to_string(), e.multiplicity))
            .collect()
    }

    fn owned(v: &[(&str, usize)]) -> Vec<(String, usize)> {
        v.iter().map(|(s, m)| (s.to_string(), *m)).collect()
    }

    #[test]
    fn exact_eigenvalues() {
        assert_eq!(eig("[[1, 1], [0, 4]]"), owned(&[("4", 1), ("1", 1)]));
        assert_eq!(
            eig("[[1, 1, 1], [0, 4, 1], [0, 0, 2]]"),
            owned(&[("4", 1), ("2", 1), ("1", 1)])
        );
        assert_eq!(eig("[[2, 1], [0, 2]]"), owned(&[("2", 2)]));
        assert_eq!(eig("[[0, 1], [0, 0]]"), owned(&[("0", 2)]));
        assert_eq!(
            eig("[[1, 1], [1, 0]]"),
            owned(&[("1/2+1/2*sqrt(5)", 1), ("1/2-1/2*sqrt(5)", 1)])
        );
        assert_eq!(
            eig("[[0, 8], [1, 0]]"),
            owned(&[("2*sqrt(2)", 1), ("-2*sqrt(2)", 1)])
        );
        assert_eq!(eig("[[-3, 0], [5, 1]]"), owned(&[("-3", 1), ("1", 1)]));
        assert_eq!(
            eig("[[0, 0, 1], [1, 0, 0], [0, 1, 0]]"),
            owned(&[("1", 1), ("-1/2+1/2*sqrt(-3)", 1), ("-1/2-1/2*sqrt(-3)", 1)])
        );
    }

    /// Two irrational quadratic factors, (x^2 + 3x - 11)(x^2 + 4x - 3): a root of each
    /// (-5.14 and 0.646) sum and multiply to about -4.49 and -3.32, which round to the second
    /// factor's coefficients; the pair must not be taken for it (found by the property test
    /// `numeric_eigenvalues_agree_with_exact_ones`).
    #[test]
    fn roots_of_two_factors_are_not_paired_by_rounding() {
        let e = eig("[[-1, -1, -2, 3], [0, -4, 3, -4], [-1, 0, -4, 3], [-1, 0, 3, 2]]");
        let mut names: Vec<&str> = e.iter().map(|(name, _)| name.as_str()).collect();
        names.sort_unstable();
        assert_eq!(
            names,
            [
                "-2+sqrt(7)",
                "-2-sqrt(7)",
                "-3/2+1/2*sqrt(53)",
                "-3/2-1/2*sqrt(53)"
            ]
        );
    }

    #[test]
    fn large_integer_roots_need_no_divisor_enumeration() {
        // Eigenvalues 999999937 * 1000003 and -(2^40 + 15): divisor enumeration is hopeless.
        let a = 999_999_937i64 * 1_000_003;
        let b = -(1i64 << 40) - 15;
        let m = format!("[[{a}, 1], [0, {b}]]");
        let e = eig(&m);
        assert_eq!(e, owned(&[(&a.to_string(), 1), (&b.to_string(), 1)]));
    }

    #[test]
    fn five_cycle_is_partly_numeric() {
        let e = eigenvalues(&characteristic_polynomial(
            &"[[0,0,0,0,1],[1,0,0,0,0],[0,1,0,0,0],[0,0,1,0,0],[0,0,0,1,0]]"
                .parse()
                .unwrap(),
        ));
        assert_eq!(e.len(), 5);
        assert_eq!(e.iter().filter(|e| e.eigenvalue.is_exact()).count(), 1);
        for info in &e {
            assert!((info.eigenvalue.modulus() - 1.0).abs() < 1e-9);
        }
    }

    #[test]
    fn split_square_pulls_out_squares() {
        assert_eq!(split_square(&BigInt::from(20)), (2.into(), 5.into()));
        assert_eq!(split_square(&BigInt::from(-12)), (2.into(), (-3).into()));
        assert_eq!(power_of_two_exponent(&BigInt::from(-8)), Some(3));
        assert_eq!(power_of_two_exponent(&BigInt::from(6)), None);
    }
}
