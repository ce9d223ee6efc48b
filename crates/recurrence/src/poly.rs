//! Polynomials, the one module for them: the public integer [`Polynomial`] (characteristic
//! polynomials), integer square-free factorization with modular gcds, and the two
//! field-generic helpers the spectral decomposition uses (division by `x - l`, Taylor
//! coefficients).

use std::fmt;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::field::Field;
use crate::{IntMatrix, Matrix};

/// A polynomial in `x` with integer coefficients, such as a characteristic polynomial.
///
/// Displays lowest terms last, like `x^2 - 5*x + 4`.
///
/// ```
/// use recurrence::{IntMatrix, Recurrence};
///
/// let r = Recurrence::new("[[1, 1], [0, 4]]".parse::<IntMatrix>()?);
/// let p = r.characteristic_polynomial();
/// assert_eq!(p.to_string(), "x^2 - 5*x + 4");
/// assert_eq!(p.degree(), 2);
/// assert_eq!(p.eval(&4.into()), 0.into());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Polynomial {
    coeffs: Vec<BigInt>,
}

impl Polynomial {
    /// The polynomial with these coefficients, lowest degree first (trailing zeros dropped).
    pub fn from_coefficients(mut coeffs: Vec<BigInt>) -> Self {
        while coeffs.last().is_some_and(Zero::is_zero) {
            coeffs.pop();
        }
        Polynomial { coeffs }
    }

    /// The coefficients, lowest degree first; empty for the zero polynomial.
    pub fn coefficients(&self) -> &[BigInt] {
        &self.coeffs
    }

    /// The degree (`0` for constants, also for the zero polynomial).
    pub fn degree(&self) -> usize {
        self.coeffs.len().saturating_sub(1)
    }

    /// The value at `x`, by Horner's rule.
    pub fn eval(&self, x: &BigInt) -> BigInt {
        let mut acc = BigInt::zero();
        for c in self.coeffs.iter().rev() {
            acc = acc * x + c;
        }
        acc
    }

    pub(crate) fn to_rational(&self) -> Vec<BigRational> {
        self.coeffs
            .iter()
            .cloned()
            .map(BigRational::from_integer)
            .collect()
    }
}

impl fmt::Display for Polynomial {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.coeffs.is_empty() {
            return f.write_str("0");
        }
        let mut first = true;
        for (k, c) in self.coeffs.iter().enumerate().rev() {
            if c.is_zero() {
                continue;
            }
            let mag = c.abs();
            if first {
                if c.is_negative() {
                    f.write_str("-")?;
                }
            } else {
                f.write_str(if c.is_negative() { " - " } else { " + " })?;
            }
            first = false;
            let unit = mag.is_one();
            match k {
                0 => write!(f, "{mag}")?,
                _ => {
                    if !unit {
                        write!(f, "{mag}*")?;
                    }
                    if k == 1 {
                        f.write_str("x")?;
                    } else {
                        write!(f, "x^{k}")?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// The characteristic polynomial `det(x I - M)` by the Faddeev-LeVerrier recurrence in exact
/// integer arithmetic (every division in it is exact).
pub(crate) fn characteristic_polynomial(m: &IntMatrix) -> Polynomial {
    let n = m.dim();
    let a: Matrix<BigInt> = m.map(|&x| BigInt::from(x));
    let exact = "big integers do not overflow";
    let mut coeffs = vec![BigInt::zero(); n + 1];
    coeffs[n] = BigInt::one();
    // mk = M_k, starting with M_0 = 0.
    let mut mk = Matrix::<BigInt>::zeros(n, n);
    for k in 1..=n {
        // M_k = A M_{k-1} + c_{n-k+1} I
        mk = a
            .checked_mul(&mk)
            .and_then(|p| p.checked_add_scalar(&coeffs[n - k + 1]))
            .expect(exact);
        // c_{n-k} = -tr(A M_k) / k
        let tr: BigInt = (0..n)
            .map(|i| {
                a.row(i)
                    .iter()
                    .enumerate()
                    .map(|(l, x)| x * mk.entry(l, i))
                    .sum::<BigInt>()
            })
            .sum();
        let (q, r) = tr.div_rem(&BigInt::from(k));
        debug_assert!(r.is_zero(), "Faddeev-LeVerrier division is exact");
        coeffs[n - k] = -q;
    }
    Polynomial::from_coefficients(coeffs)
}

// Integer polynomials (coefficients lowest degree first) and their gcds by multi-modular
// arithmetic. Euclid's algorithm over `Q` makes the coefficients of the remainders explode
// (seconds for degree 24, minutes for 32); modulo 62-bit primes every operation is a machine
// multiplication, and the exact result is reconstructed by the Chinese remainder theorem and
// verified by exact division over `Z`.

fn trim_int(p: &mut Vec<BigInt>) {
    while p.last().is_some_and(Zero::is_zero) {
        p.pop();
    }
}

pub(crate) fn derivative_int(p: &[BigInt]) -> Vec<BigInt> {
    let mut d: Vec<BigInt> = p
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, c)| c * BigInt::from(k))
        .collect();
    trim_int(&mut d);
    d
}

fn sub_int(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let n = a.len().max(b.len());
    let zero = BigInt::zero();
    let mut out: Vec<BigInt> = (0..n)
        .map(|i| a.get(i).unwrap_or(&zero) - b.get(i).unwrap_or(&zero))
        .collect();
    trim_int(&mut out);
    out
}

/// `a / g` over `Z` for a monic `g` (trimmed, degree at least 0), when the division leaves
/// no remainder.
pub(crate) fn divide_monic_exact(a: &[BigInt], g: &[BigInt]) -> Option<Vec<BigInt>> {
    let mut r = a.to_vec();
    trim_int(&mut r);
    if r.is_empty() {
        return Some(Vec::new());
    }
    let dg = g.len().checked_sub(1)?;
    if r.len() <= dg {
        return None;
    }
    let mut quot = vec![BigInt::zero(); r.len() - dg];
    for k in (0..quot.len()).rev() {
        let c = std::mem::take(&mut r[k + dg]);
        if c.is_zero() {
            continue;
        }
        for (i, gi) in g[..dg].iter().enumerate() {
            if !gi.is_zero() {
                r[k + i] -= &c * gi;
            }
        }
        quot[k] = c;
    }
    r[..dg].iter().all(Zero::is_zero).then_some(quot)
}

fn mul_mod(a: u64, b: u64, q: u64) -> u64 {
    ((u128::from(a) * u128::from(b)) % u128::from(q)) as u64
}

fn pow_mod(mut b: u64, mut e: u64, q: u64) -> u64 {
    let mut r = 1 % q;
    while e > 0 {
        if e & 1 == 1 {
            r = mul_mod(r, b, q);
        }
        b = mul_mod(b, b, q);
        e >>= 1;
    }
    r
}

/// Deterministic Miller-Rabin for 64-bit integers.
fn is_prime_u64(n: u64) -> bool {
    if n < 2 {
        return false;
    }
    const BASES: [u64; 12] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37];
    for p in BASES {
        if n % p == 0 {
            return n == p;
        }
    }
    let s = (n - 1).trailing_zeros();
    let d = (n - 1) >> s;
    'bases: for a in BASES {
        let mut x = pow_mod(a, d, n);
        if x == 1 || x == n - 1 {
            continue;
        }
        for _ in 1..s {
            x = mul_mod(x, x, n);
            if x == n - 1 {
                continue 'bases;
            }
        }
        return false;
    }
    true
}

/// The primes below `2^62`, largest first.
fn large_primes() -> impl Iterator<Item = u64> {
    let mut n = (1u64 << 62) + 1;
    std::iter::from_fn(move || loop {
        n -= 2;
        if is_prime_u64(n) {
            return Some(n);
        }
    })
}

fn reduce_mod(p: &[BigInt], q: u64) -> Vec<u64> {
    let qb = BigInt::from(q);
    let mut out: Vec<u64> = p
        .iter()
        .map(|c| c.mod_floor(&qb).to_u64().unwrap_or(0))
        .collect();
    while out.last() == Some(&0) {
        out.pop();
    }
    out
}

/// The monic gcd of two polynomials over `F_q` (empty when both are zero).
fn gcd_mod(mut a: Vec<u64>, mut b: Vec<u64>, q: u64) -> Vec<u64> {
    while !b.is_empty() {
        // a <- a mod b
        let inv = pow_mod(b[b.len() - 1], q - 2, q);
        while a.len() >= b.len() {
            let shift = a.len() - b.len();
            let c = mul_mod(a[a.len() - 1], inv, q);
            for (i, bi) in b.iter().enumerate() {
                let t = mul_mod(c, *bi, q);
                let x = &mut a[shift + i];
                *x = if *x >= t { *x - t } else { *x + q - t };
            }
            while a.last() == Some(&0) {
                a.pop();
            }
        }
        std::mem::swap(&mut a, &mut b);
    }
    if let Some(&lead) = a.last() {
        let inv = pow_mod(lead, q - 2, q);
        for c in &mut a {
            *c = mul_mod(*c, inv, q);
        }
    }
    a
}

/// Most primes tried by [`gcd_monic`] before it falls back to Euclid over `Q` (never reached
/// in practice: only primes dividing a resultant can mislead it, and they are few).
const MAX_GCD_PRIMES: usize = 4096;

/// The monic gcd over `Q` of a monic integer polynomial `a` and an integer polynomial `b`
/// (both trimmed). It has integer coefficients (a monic factor of a monic integer
/// polynomial), each at most `2^deg(a) * sum |a_i|` in absolute value (Mignotte), so it is
/// found modulo enough primes and confirmed by exact division.
pub(crate) fn gcd_monic(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    if b.is_empty() {
        return a.to_vec();
    }
    if a.len() <= 1 || b.len() == 1 {
        return vec![BigInt::one()];
    }
    let norm: BigInt = a.iter().map(Signed::abs).sum();
    let bound_bits = norm.bits() + a.len() as u64 + 2;
    let mut best: Option<usize> = None; // degree of the modular gcds being combined
    let mut residues: Vec<BigInt> = Vec::new();
    let mut modulus = BigInt::one();
    let b_lead = &b[b.len() - 1];
    for q in large_primes().take(MAX_GCD_PRIMES) {
        if (b_lead % BigInt::from(q)).is_zero() {
            continue;
        }
        let g = gcd_mod(reduce_mod(a, q), reduce_mod(b, q), q);
        let deg = g.len() - 1;
        if deg == 0 {
            return vec![BigInt::one()];
        }
        match best {
            Some(d) if deg > d => continue,
            Some(d) if deg == d => {}
            _ => {
                best = Some(deg);
                residues = vec![BigInt::zero(); deg + 1];
                modulus = BigInt::one();
            }
        }
        // Garner: x <- x + m * ((r - x) / m mod q).
        let qb = BigInt::from(q);
        let m_inv = pow_mod(modulus.mod_floor(&qb).to_u64().unwrap_or(0), q - 2, q);
        for (x, r) in residues.iter_mut().zip(&g) {
            let xr = x.mod_floor(&qb).to_u64().unwrap_or(0);
            let diff = if *r >= xr { r - xr } else { r + q - xr };
            let t = mul_mod(diff, m_inv, q);
            *x += &modulus * BigInt::from(t);
        }
        modulus *= &qb;
        if modulus.bits() > bound_bits {
            let half = &modulus >> 1u32;
            let candidate: Vec<BigInt> = residues
                .iter()
                .map(|x| if x > &half { x - &modulus } else { x.clone() })
                .collect();
            if divide_monic_exact(a, &candidate).is_some()
                && divide_monic_exact(b, &candidate).is_some()
            {
                return candidate;
            }
        }
    }
    gcd_rational_fallback(a, b)
}

fn gcd_rational_fallback(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let to_q = |p: &[BigInt]| -> Vec<BigRational> {
        p.iter().cloned().map(BigRational::from_integer).collect()
    };
    let (mut a, mut b) = (to_q(a), to_q(b));
    while !b.is_empty() {
        let r = rational_rem(&a, &b);
        a = b;
        b = r;
    }
    let lead = a.last().cloned().unwrap_or_else(BigRational::one);
    a.iter().map(|c| (c / &lead).to_integer()).collect()
}

fn rational_rem(p: &[BigRational], q: &[BigRational]) -> Vec<BigRational> {
    let mut r = p.to_vec();
    let dq = q.len() - 1;
    while r.len() > dq && !r.is_empty() {
        let k = r.len() - 1 - dq;
        let c = &r[r.len() - 1] / &q[dq];
        for (i, qc) in q.iter().enumerate() {
            r[k + i] = &r[k + i] - &c * qc;
        }
        r.pop();
        while r.last().is_some_and(Zero::is_zero) {
            r.pop();
        }
    }
    r
}

/// Yun's square-free factorization of a monic integer polynomial: pairs `(f, m)` of monic,
/// square-free, pairwise coprime integer factors of degree at least one with `p = prod f^m`,
/// by increasing `m`. Every gcd is modular ([`gcd_monic`]) and every division exact over `Z`.
pub(crate) fn square_free_factors(p: &[BigInt]) -> Vec<(Vec<BigInt>, usize)> {
    let mut out = Vec::new();
    let mut p = p.to_vec();
    trim_int(&mut p);
    let dp = derivative_int(&p);
    let a0 = gcd_monic(&p, &dp);
    let exact = "a gcd divides its arguments";
    let mut b = divide_monic_exact(&p, &a0).expect(exact);
    let c = divide_monic_exact(&dp, &a0).expect(exact);
    let mut d = sub_int(&c, &derivative_int(&b));
    let mut i = 1;
    while b.len() > 1 {
        let a = gcd_monic(&b, &d);
        if a.len() > 1 {
            out.push((a.clone(), i));
        }
        b = divide_monic_exact(&b, &a).expect(exact);
        let c = divide_monic_exact(&d, &a).expect(exact);
        d = sub_int(&c, &derivative_int(&b));
        i += 1;
    }
    out
}

/// `p / (x - lambda)` by synthetic division, dropping the remainder.
pub(crate) fn divide_by_root<F: Field>(p: &[F], lambda: &F) -> Vec<F> {
    if p.len() <= 1 {
        return Vec::new();
    }
    let n = p.len() - 1;
    let mut q = vec![F::zero(); n];
    let mut carry = F::zero();
    for k in (0..n).rev() {
        carry = p[k + 1].clone() + carry * lambda.clone();
        q[k] = carry.clone();
    }
    q
}

/// The first `count` Taylor coefficients of `p` at `lambda`: `p(lambda + t) = sum h_k t^k`.
pub(crate) fn taylor_coefficients<F: Field>(p: &[F], lambda: &F, count: usize) -> Vec<F> {
    let mut out = Vec::with_capacity(count);
    let mut cur = p.to_vec();
    for _ in 0..count {
        let mut value = F::zero();
        for c in cur.iter().rev() {
            value = value * lambda.clone() + c.clone();
        }
        out.push(value);
        cur = divide_by_root(&cur, lambda);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn int_poly(c: &[i64]) -> Vec<BigRational> {
        c.iter()
            .map(|&x| BigRational::from_integer(x.into()))
            .collect()
    }

    #[test]
    fn characteristic_polynomials() {
        let cases = [
            ("[[1, 1], [0, 4]]", "x^2 - 5*x + 4"),
            (
                "[[1, 1, 1], [0, 2, 4], [0, 0, 4]]",
                "x^3 - 7*x^2 + 14*x - 8",
            ),
            ("[[1, 1], [1, 0]]", "x^2 - x - 1"),
            ("[[0, 1], [0, 0]]", "x^2"),
            ("[[0, 0, 1], [1, 0, 0], [0, 1, 0]]", "x^3 - 1"),
            ("[[7]]", "x - 7"),
            ("[[-2]]", "x + 2"),
        ];
        for (m, expected) in cases {
            let m: IntMatrix = m.parse().unwrap();
            assert_eq!(characteristic_polynomial(&m).to_string(), expected, "{m}");
        }
    }

    fn ints(c: &[i64]) -> Vec<BigInt> {
        c.iter().map(|&x| BigInt::from(x)).collect()
    }

    #[test]
    fn square_free_factorization() {
        // (x - 2)^2 (x - 1) = x^3 - 5x^2 + 8x - 4
        let f = square_free_factors(&ints(&[-4, 8, -5, 1]));
        assert_eq!(f, vec![(ints(&[-1, 1]), 1), (ints(&[-2, 1]), 2)]);
        // x^2 (x^2 - x - 1)
        let f = square_free_factors(&ints(&[0, 0, -1, -1, 1]));
        assert_eq!(f, vec![(ints(&[-1, -1, 1]), 1), (ints(&[0, 1]), 2)]);
    }

    /// `prod (x - r)` times `x^2 - x - 1` per `fib`, as integer coefficients.
    fn from_roots(roots: &[i64], fib: usize) -> Vec<BigInt> {
        let mut p = ints(&[1]);
        let mut mul = |f: &[BigInt]| {
            let mut out = vec![BigInt::zero(); p.len() + f.len() - 1];
            for (i, a) in p.iter().enumerate() {
                for (j, b) in f.iter().enumerate() {
                    out[i + j] += a * b;
                }
            }
            p = out;
        };
        for &r in roots {
            mul(&ints(&[-r, 1]));
        }
        for _ in 0..fib {
            mul(&ints(&[-1, -1, 1]));
        }
        p
    }

    fn product(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
        let mut out = vec![BigInt::zero(); a.len() + b.len() - 1];
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                out[i + j] += x * y;
            }
        }
        out
    }

    /// The factorization multiplies back to `p`, its factors are square-free and pairwise
    /// coprime with distinct, increasing multiplicities, and every modular gcd it relies on
    /// agrees with Euclid's algorithm over `Q`.
    #[test]
    fn modular_yun_factors_multiply_back() {
        let cases: Vec<Vec<BigInt>> = vec![
            from_roots(&[1, 1, 1, 2, 2, 4], 0),
            from_roots(&[0, 0, 0, 0, 3, -3, 3, 1_000_003], 2),
            from_roots(&[7; 9], 3),
            from_roots(&[-5, 6, 1 << 40, 1 << 40, 999_999_937], 1),
            from_roots(&[2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41], 0),
            ints(&[5, -3, 0, 11, -7, 1]),
            ints(&[-1, 0, 0, 0, 0, 1]),
        ];
        for p in cases {
            let dp = derivative_int(&p);
            assert_eq!(gcd_monic(&p, &dp), gcd_rational_fallback(&p, &dp), "{p:?}");
            let factors = square_free_factors(&p);
            let mut back = ints(&[1]);
            for (f, m) in &factors {
                for _ in 0..*m {
                    back = product(&back, f);
                }
                assert_eq!(
                    gcd_monic(f, &derivative_int(f)),
                    ints(&[1]),
                    "{f:?} of {p:?}"
                );
            }
            assert_eq!(back, p);
            for (i, (f, m)) in factors.iter().enumerate() {
                for (g, k) in &factors[i + 1..] {
                    assert!(m < k, "{p:?}");
                    assert_eq!(gcd_monic(f, g), ints(&[1]), "{p:?}");
                }
            }
        }
    }

    #[test]
    fn modular_gcd_and_exact_division() {
        let a = from_roots(&[1, 2, 2, 3], 1);
        let b = from_roots(&[2, 3, 5], 1);
        assert_eq!(gcd_monic(&a, &b), from_roots(&[2, 3], 1));
        assert_eq!(gcd_monic(&a, &ints(&[4, 1])), ints(&[1]));
        assert_eq!(gcd_rational_fallback(&a, &b), from_roots(&[2, 3], 1));
        assert_eq!(
            divide_monic_exact(&a, &from_roots(&[2, 2], 0)),
            Some(from_roots(&[1, 3], 1))
        );
        assert_eq!(divide_monic_exact(&a, &from_roots(&[5], 0)), None);
        assert!(is_prime_u64((1 << 61) - 1));
        assert!(!is_prime_u64((1 << 62) - 1));
        assert_eq!(large_primes().next(), Some((1 << 62) - 57));
    }

    #[test]
    fn taylor_and_division() {
        // p = x^2 at lambda = 3: 9 + 6t + t^2
        let p = int_poly(&[0, 0, 1]);
        assert_eq!(
            taylor_coefficients(&p, &BigRational::from_integer(3.into()), 3),
            int_poly(&[9, 6, 1])
        );
        assert_eq!(
            divide_by_root(
                &int_poly(&[-4, 8, -5, 1]),
                &BigRational::from_integer(2.into())
            ),
            int_poly(&[2, -3, 1])
        );
        assert_eq!(
            divide_monic_exact(&ints(&[-4, 8, -5, 1]), &ints(&[-2, 1])),
            Some(ints(&[2, -3, 1]))
        );
    }
}
