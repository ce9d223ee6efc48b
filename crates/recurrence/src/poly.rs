//! Polynomials: the public integer [`Polynomial`] (characteristic polynomials) and the
//! field-generic helpers the eigenvalue search and the spectral decomposition use.

use std::fmt;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::field::Field;
use crate::IntMatrix;

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
    let a: Vec<BigInt> = m.rows().flatten().map(|&x| BigInt::from(x)).collect();
    let mut coeffs = vec![BigInt::zero(); n + 1];
    coeffs[n] = BigInt::one();
    // mk = M_k, starting with M_0 = 0.
    let mut mk = vec![BigInt::zero(); n * n];
    for k in 1..=n {
        // M_k = A M_{k-1} + c_{n-k+1} I
        let mut next = vec![BigInt::zero(); n * n];
        for i in 0..n {
            for j in 0..n {
                let mut acc = BigInt::zero();
                for l in 0..n {
                    if !a[i * n + l].is_zero() && !mk[l * n + j].is_zero() {
                        acc += &a[i * n + l] * &mk[l * n + j];
                    }
                }
                next[i * n + j] = acc;
            }
        }
        for i in 0..n {
            next[i * n + i] += &coeffs[n - k + 1];
        }
        // c_{n-k} = -tr(A M_k) / k
        let mut tr = BigInt::zero();
        for i in 0..n {
            for l in 0..n {
                tr += &a[i * n + l] * &next[l * n + i];
            }
        }
        let (q, r) = tr.div_rem(&BigInt::from(k));
        debug_assert!(r.is_zero(), "Faddeev-LeVerrier division is exact");
        coeffs[n - k] = -q;
        mk = next;
    }
    Polynomial::from_coefficients(coeffs)
}

pub(crate) fn trim<F: Field>(p: &mut Vec<F>) {
    while p.last().is_some_and(Field::is_field_zero) {
        p.pop();
    }
}

/// Quotient and remainder of `p / q` over an exact field; `q` must be non-zero and trimmed.
pub(crate) fn div_rem<F: Field>(p: &[F], q: &[F]) -> (Vec<F>, Vec<F>) {
    let mut r: Vec<F> = p.to_vec();
    trim(&mut r);
    let dq = q.len() - 1;
    let lead = &q[dq];
    if r.len() < q.len() {
        return (Vec::new(), r);
    }
    let mut quot = vec![F::field_zero(); r.len() - dq];
    while r.len() > dq && !r.is_empty() {
        let k = r.len() - 1 - dq;
        let c = r[r.len() - 1].div(lead);
        for (i, qc) in q.iter().enumerate() {
            r[k + i] = r[k + i].sub(&c.mul(qc));
        }
        quot[k] = c;
        r.pop();
        trim(&mut r);
    }
    (quot, r)
}

pub(crate) fn derivative<F: Field>(p: &[F]) -> Vec<F> {
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(k, c)| {
            let kf = F::from_rational(&BigRational::from_integer(BigInt::from(k)));
            c.mul(&kf)
        })
        .collect()
}

fn monic<F: Field>(p: &[F]) -> Vec<F> {
    match p.last() {
        Some(lead) => p.iter().map(|c| c.div(lead)).collect(),
        None => Vec::new(),
    }
}

pub(crate) fn gcd<F: Field>(a: &[F], b: &[F]) -> Vec<F> {
    let mut a = a.to_vec();
    let mut b = b.to_vec();
    trim(&mut a);
    trim(&mut b);
    while !b.is_empty() {
        let (_, r) = div_rem(&a, &b);
        a = b;
        b = r;
    }
    monic(&a)
}

/// Yun's square-free factorization over `Q` of a monic polynomial: pairs `(f, m)` of monic,
/// square-free, pairwise coprime factors of degree at least one, with `p = prod f^m`.
pub(crate) fn square_free_factors(p: &[BigRational]) -> Vec<(Vec<BigRational>, usize)> {
    let mut out = Vec::new();
    let dp = derivative(p);
    let a0 = gcd(p, &dp);
    let mut b = div_rem(p, &a0).0;
    let mut c = div_rem(&dp, &a0).0;
    let mut d = sub(&c, &derivative(&b));
    let mut i = 1;
    while b.len() > 1 {
        let a = gcd(&b, &d);
        if a.len() > 1 {
            out.push((a.clone(), i));
        }
        b = div_rem(&b, &a).0;
        c = div_rem(&d, &a).0;
        d = sub(&c, &derivative(&b));
        i += 1;
    }
    out
}

fn sub<F: Field>(a: &[F], b: &[F]) -> Vec<F> {
    let n = a.len().max(b.len());
    let mut out: Vec<F> = (0..n)
        .map(|i| match (a.get(i), b.get(i)) {
            (Some(x), Some(y)) => x.sub(y),
            (Some(x), None) => x.clone(),
            (None, Some(y)) => y.neg(),
            (None, None) => F::field_zero(),
        })
        .collect();
    trim(&mut out);
    out
}

/// `p / (x - lambda)` by synthetic division, dropping the remainder.
pub(crate) fn divide_by_root<F: Field>(p: &[F], lambda: &F) -> Vec<F> {
    if p.len() <= 1 {
        return Vec::new();
    }
    let n = p.len() - 1;
    let mut q = vec![F::field_zero(); n];
    let mut carry = F::field_zero();
    for k in (0..n).rev() {
        carry = p[k + 1].add(&carry.mul(lambda));
        q[k] = carry.clone();
    }
    q
}

/// The first `count` Taylor coefficients of `p` at `lambda`: `p(lambda + t) = sum h_k t^k`.
pub(crate) fn taylor_coefficients<F: Field>(p: &[F], lambda: &F, count: usize) -> Vec<F> {
    let mut out = Vec::with_capacity(count);
    let mut cur = p.to_vec();
    for _ in 0..count {
        let mut value = F::field_zero();
        for c in cur.iter().rev() {
            value = value.mul(lambda).add(c);
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

    #[test]
    fn square_free_factorization() {
        // (x - 2)^2 (x - 1) = x^3 - 5x^2 + 8x - 4
        let f = square_free_factors(&int_poly(&[-4, 8, -5, 1]));
        assert_eq!(f, vec![(int_poly(&[-1, 1]), 1), (int_poly(&[-2, 1]), 2)]);
        // x^2 (x^2 - x - 1)
        let f = square_free_factors(&int_poly(&[0, 0, -1, -1, 1]));
        assert_eq!(f, vec![(int_poly(&[-1, -1, 1]), 1), (int_poly(&[0, 1]), 2)]);
    }

    #[test]
    fn taylor_and_division() {
        // p = x^2 at lambda = 3: 9 + 6t + t^2
        let p = int_poly(&[0, 0, 1]);
        assert_eq!(
            taylor_coefficients(&p, &BigRational::from_integer(3.into()), 3),
            int_poly(&[9, 6, 1])
        );
        let (q, r) = div_rem(&int_poly(&[-4, 8, -5, 1]), &int_poly(&[-2, 1]));
        assert_eq!(q, int_poly(&[2, -3, 1]));
        assert!(r.is_empty());
    }
}
