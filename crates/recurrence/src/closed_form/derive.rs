//! Exact closed forms from the spectral decomposition
//! `M^s = sum_l sum_(k < m_l) C(s, k) l^(s-k) N_l^k P_l`.
//!
//! For an exact eigenvalue `l` (rational or in `Q(sqrt d)`) of multiplicity `m`, the
//! projector and the nilpotent parts come fraction-free from the generalized eigenspaces, the
//! kernels of `(M - l I)^m` and of its transpose, in the ring `Z[sqrt d]`
//! ([`exact_spectrum`]): integers throughout, one rational per entry at the end. For a numeric
//! eigenvalue, write `p(x) = (x - l)^m h(x)`: the spectral projector is `P_l = h(M) v(M)`
//! where `v` is the inverse of `h` modulo `(x - l)^m`, read off the Taylor series of `1/h` at
//! `l`, and the nilpotent part is `N_l = (M - l I) P_l`, in complex `f64`
//! ([`spectral_parts`], also the exact path's fallback and test reference). `C(s, k) l^(-k)`
//! is then expanded into powers of `s`, which gives each component as `sum p_l(s) l^s`.
//!
//! The zero eigenvalue contributes `N_0^s P_0`, which vanishes from level `m_0` on; per
//! component, `valid_from` is the least `k` with `e_i^T N_0^k P_0 = 0`, and the levels below
//! it are stored as rows of `M^k`.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};

use super::eval::build_fast;
use super::{ClosedForm, Coefficient, ComponentForm, EarlyLevel, FastEigenvalue, Term};
use crate::eigen::{power_of_two_exponent, Eigenvalue};
use crate::field::{kernel, scaled_inverse, Field, FieldMatrix, QuadraticSurd, RingElem};
use crate::poly::{divide_by_root, taylor_coefficients};
use crate::{Complex64, IntMatrix, Matrix, Recurrence};

/// The matrices `N^k P` for `k < mult` of the eigenvalue `lambda` of `m`, whose
/// characteristic polynomial is `p` (rational coefficients, lowest first).
fn spectral_parts<F: Field>(
    m: &IntMatrix,
    p: &[BigRational],
    lambda: &F,
    mult: usize,
) -> Vec<Matrix<F>> {
    let mut h: Vec<F> = p.iter().map(F::from_rational).collect();
    for _ in 0..mult {
        h = divide_by_root(&h, lambda);
    }
    let t = taylor_coefficients(&h, lambda, mult);
    // Inverse power series of h at lambda, to order mult.
    let inv0 = F::one() / t[0].clone();
    let mut c: Vec<F> = vec![inv0.clone()];
    for k in 1..mult {
        let mut acc = F::zero();
        for j in 1..=k {
            if let Some(tj) = t.get(j) {
                acc = acc + tj.clone() * c[k - j].clone();
            }
        }
        c.push(-(acc * inv0.clone()));
    }
    let mf = m.map(|&x| F::from_rational(&BigRational::from_integer(BigInt::from(x))));
    let a = mf.add_scalar(&-lambda.clone());
    let projector = F::eval_poly_at_int(m, &h).mul(&a.eval_poly(&c));
    let mut parts = vec![projector];
    for _ in 1..mult {
        let next = a.mul(parts.last().expect("parts is not empty"));
        parts.push(next);
    }
    parts
}

/// The projector, the matrices `C_t` of [`power_coefficients`] (non-zero `lambda`) and,
/// for `lambda = 0`, per row the least `k` with a zero row `i` of `N^k P`, all from
/// [`spectral_parts`]: the fallback of [`exact_spectrum`] and its test reference.
fn spectrum_from_parts<F: Field>(
    m: &IntMatrix,
    p: &[BigRational],
    lambda: &F,
    mult: usize,
) -> (Matrix<F>, Vec<Matrix<F>>, Vec<u64>) {
    let parts = spectral_parts::<F>(m, p, lambda, mult);
    if lambda.is_zero() {
        let valid = (0..m.dim())
            .map(|i| {
                (0..mult)
                    .find(|&k| parts[k].row(i).iter().all(Zero::is_zero))
                    .unwrap_or(mult) as u64
            })
            .collect();
        (parts[0].clone(), Vec::new(), valid)
    } else {
        let coefficients = power_coefficients(&parts, lambda);
        (parts[0].clone(), coefficients, Vec::new())
    }
}

/// A field whose elements the fraction-free computation produces as `numerator /
/// denominator` in `Z[sqrt d]`.
trait ExactField: Field {
    /// `num / den`, `den` non-zero, given its conjugate and norm.
    fn from_ring(num: &RingElem, den: &RingElem, den_conj: &RingElem, den_norm: &BigInt) -> Self;
}

impl ExactField for BigRational {
    fn from_ring(num: &RingElem, den: &RingElem, _: &RingElem, _: &BigInt) -> Self {
        // Rational eigenvalues keep every value in `Z`.
        BigRational::new(num.x.clone(), den.x.clone())
    }
}

impl ExactField for QuadraticSurd {
    fn from_ring(num: &RingElem, _: &RingElem, den_conj: &RingElem, den_norm: &BigInt) -> Self {
        let p = num * den_conj;
        QuadraticSurd::new(
            BigRational::new(p.x, den_norm.clone()),
            BigRational::new(p.y, den_norm.clone()),
            p.d,
        )
    }
}

/// What the closed form needs of one exact eigenvalue `l` of multiplicity `mult`: the
/// projector `P_l`, the matrices `C_t` of [`power_coefficients`] (non-zero `l`), and for
/// `l = 0` whether row `i` of `N^k P` vanishes.
struct ExactSpectrum<F> {
    projector: Matrix<F>,
    coefficients: Vec<Matrix<F>>,
    valid_from: Vec<u64>,
}

/// The spectral data of the exact eigenvalue `lambda` (rational, or in `Q(sqrt d)`) of
/// multiplicity `mult`, computed fraction-free from generalized eigenspaces instead of
/// polynomials in `M`:
///
/// with `c` the least common denominator of `lambda`'s parts, `mu = c lambda` and
/// `B = c M - mu I` (entries in `Z[sqrt d]`), the columns of `R` span the kernel of `B^mult`
/// (the generalized eigenspace) and those of `L` the kernel of its transpose, so
/// `P = R (L^T R)^(-1) L^T = R X L^T / D` with `G X = D I`, `G = L^T R`, and
/// `N^k P = B^k R X L^T / (D c^k)`. Every `C_t = sum_k C(s, k)[s^t] l^(-k) N^k P` is then one
/// integer matrix over the common denominator `D (mult-1)! mu^(mult-1)`, turned into
/// rationals once. Cost: `O(n^3 log mult)` for `B^mult`, two `n x n` eliminations, and
/// `O(n^2 mult^2)` for the `C_t`, all in integers the size of minors of `B^mult`.
///
/// `None` when an internal consistency check fails (a kernel of the wrong dimension, a
/// singular `G`, an inexact division): the caller then uses [`spectral_parts`].
fn exact_spectrum<F: ExactField>(
    m: &IntMatrix,
    lambda: &QuadraticSurd,
    mult: usize,
) -> Option<ExactSpectrum<F>> {
    let n = m.dim();
    let c = lambda.a.denom().lcm(lambda.b.denom());
    let mu = RingElem::new(
        (&lambda.a * BigRational::from_integer(c.clone())).to_integer(),
        (&lambda.b * BigRational::from_integer(c.clone())).to_integer(),
        &lambda.d,
    );
    let b = m
        .map(|&x| RingElem::int(BigInt::from(x) * &c))
        .checked_add_scalar(&-&mu)?;
    let power = b.checked_pow(u64::try_from(mult).ok()?)?;
    let transposed = power.transpose();
    let right = kernel(power)?;
    let left = kernel(transposed)?;
    if right.len() != mult || left.len() != mult {
        return None;
    }
    // R as n x mult, L^T as mult x n.
    let r0 = Matrix::from_vec(
        n,
        mult,
        (0..n * mult)
            .map(|k| right[k % mult][k / mult].clone())
            .collect(),
    );
    let lt = Matrix::from_vec(mult, n, left.into_iter().flatten().collect());
    let g = lt.checked_mul(&r0)?;
    let (x, d) = scaled_inverse(&g)?;
    let y = x.checked_mul(&lt)?;
    // R_k = B^k R for k < mult.
    let mut rk = vec![r0];
    for _ in 1..mult {
        let next = b.checked_mul(rk.last()?)?;
        rk.push(next);
    }
    let to_field = |num: &Matrix<RingElem>, den: &RingElem| -> Matrix<F> {
        let conj = den.conj();
        let norm = den.norm();
        num.map(|z| {
            if z.is_zero() {
                F::zero()
            } else {
                F::from_ring(z, den, &conj, &norm)
            }
        })
    };
    let projector = to_field(&rk[0].checked_mul(&y)?, &d);
    let mut valid_from = Vec::new();
    let mut coefficients = Vec::new();
    if lambda.is_zero() {
        // Row i of N^k P = R_k Y / D vanishes iff row i of R_k does (Y has full row rank).
        valid_from = (0..n)
            .map(|i| {
                (0..mult)
                    .find(|&k| rk[k].row(i).iter().all(RingElem::is_zero))
                    .unwrap_or(mult) as u64
            })
            .collect();
    } else {
        let top = mult - 1;
        // mu^j for j <= top, and (top!/k!) for k <= top.
        let mut mu_pow = vec![RingElem::one()];
        for _ in 0..top {
            let next = mu_pow.last()? * &mu;
            mu_pow.push(next);
        }
        let mut fall = vec![BigInt::one(); mult]; // fall[k] = top! / k!
        for k in (0..top).rev() {
            fall[k] = &fall[k + 1] * BigInt::from(k + 1);
        }
        let den = &(&d * &RingElem::int(fall[0].clone())) * &mu_pow[top];
        let stirling: Vec<Vec<BigInt>> = (0..mult)
            .map(|k| {
                binomial_poly(k)
                    .iter()
                    .map(|q| {
                        (q * BigRational::from_integer(fall[0].clone() / &fall[k])).to_integer()
                    })
                    .collect()
            })
            .collect();
        coefficients = (0..mult)
            .map(|t| {
                let mut s = Matrix::<RingElem>::zeros(n, mult);
                for k in t..mult {
                    let coef = &RingElem::int(&stirling[k][t] * &fall[k]) * &mu_pow[top - k];
                    if coef.is_zero() {
                        continue;
                    }
                    for (acc, v) in s.entries_mut().iter_mut().zip(rk[k].entries()) {
                        if !v.is_zero() {
                            *acc = &*acc + &(&coef * v);
                        }
                    }
                }
                Some(to_field(&s.checked_mul(&y)?, &den))
            })
            .collect::<Option<Vec<_>>>()?;
    }
    Some(ExactSpectrum {
        projector,
        coefficients,
        valid_from,
    })
}

/// The entrywise conjugate `a - b sqrt(d)` of a matrix over `Q(sqrt d)`.
fn conjugate_matrix(m: &Matrix<QuadraticSurd>) -> Matrix<QuadraticSurd> {
    m.map(QuadraticSurd::conjugate)
}

/// Coefficients of `C(s, k) = s (s-1) ... (s-k+1) / k!` as a polynomial in `s`.
fn binomial_poly(k: usize) -> Vec<BigRational> {
    let mut poly = vec![BigRational::one()];
    for j in 0..k {
        // multiply by (s - j) / (j + 1)
        let mut next = vec![BigRational::zero(); poly.len() + 1];
        let div = BigRational::from_integer(BigInt::from(j + 1));
        for (t, c) in poly.iter().enumerate() {
            next[t + 1] += c / &div;
            next[t] -= c * BigRational::from_integer(BigInt::from(j)) / &div;
        }
        poly = next;
    }
    poly
}

/// Matrices `C_t` with `M^s P_l = sum_t s^t l^s C_t` for a non-zero eigenvalue.
fn power_coefficients<F: Field>(parts: &[Matrix<F>], lambda: &F) -> Vec<Matrix<F>> {
    let mult = parts.len();
    let dim = parts[0].dim();
    let inv = F::one() / lambda.clone();
    let mut out = Vec::with_capacity(mult);
    for t in 0..mult {
        let mut acc = Matrix::scalar(dim, &F::zero());
        let mut inv_k = F::one();
        for (k, part) in parts.iter().enumerate() {
            if k >= t {
                let c = F::from_rational(&binomial_poly(k)[t]) * inv_k.clone();
                let scaled = part.map(|e| e.clone() * c.clone());
                acc = acc.add(&scaled);
            }
            inv_k = inv_k * inv.clone();
        }
        out.push(acc);
    }
    out
}

pub(crate) fn closed_form(rec: &Recurrence) -> ClosedForm {
    let m = rec.matrix();
    let n = m.dim();
    let p = rec.characteristic_polynomial().to_rational();
    let eigenvalues = rec.eigenvalues();
    let mut terms: Vec<Vec<Term>> = vec![Vec::new(); n];
    let mut valid_from = vec![0u64; n];
    // Sum of the exact projectors (rational parts: conjugate projectors are conjugate, so
    // their sum is twice the rational part), to tell which components avoid numeric terms.
    let mut exact_sum = Matrix::<BigRational>::scalar(n, &BigRational::zero());
    let any_numeric = eigenvalues.iter().any(|e| !e.eigenvalue.is_exact());
    let mut powers = Vec::with_capacity(eigenvalues.len());
    type SurdData = (
        QuadraticSurd,
        Matrix<QuadraticSurd>,
        Vec<Matrix<QuadraticSurd>>,
    );
    let mut surd_cache: Vec<SurdData> = Vec::new();
    for info in &eigenvalues {
        let mult = info.multiplicity;
        match &info.eigenvalue {
            Eigenvalue::Rational(l) => {
                let fast =
                    exact_spectrum::<BigRational>(m, &QuadraticSurd::rational(l.clone()), mult);
                let (projector, coefficients, zero_valid) = match fast {
                    Some(spec) => (spec.projector, spec.coefficients, spec.valid_from),
                    None => spectrum_from_parts::<BigRational>(m, &p, l, mult),
                };
                if any_numeric {
                    exact_sum = exact_sum.add(&projector);
                }
                if l.is_zero() {
                    valid_from = zero_valid;
                } else {
                    push_terms(&mut terms, &info.eigenvalue, &coefficients, |c| {
                        Coefficient::Rational(c.clone())
                    });
                }
            }
            Eigenvalue::QuadraticSurd { .. } => {
                let l = info
                    .eigenvalue
                    .to_surd()
                    .expect("surd eigenvalues are exact");
                // The conjugate eigenvalue's data are the entrywise conjugates (the Galois
                // automorphism of Q(sqrt d) fixes M): computed once per pair.
                let conjugate = l.conjugate();
                let cached =
                    surd_cache
                        .iter()
                        .find(|(k, _, _)| *k == conjugate)
                        .map(|(_, p, c)| {
                            (
                                conjugate_matrix(p),
                                c.iter().map(conjugate_matrix).collect(),
                            )
                        });
                let (projector, coefficients): (_, Vec<_>) = match cached {
                    Some(found) => found,
                    None => match exact_spectrum::<QuadraticSurd>(m, &l, mult) {
                        Some(spec) => (spec.projector, spec.coefficients),
                        None => {
                            let parts = spectral_parts::<QuadraticSurd>(m, &p, &l, mult);
                            let coefficients = power_coefficients(&parts, &l);
                            (
                                parts.into_iter().next().expect("one part per multiplicity"),
                                coefficients,
                            )
                        }
                    },
                };
                surd_cache.push((l.clone(), projector.clone(), coefficients.clone()));
                if any_numeric {
                    let rational_part = projector.map(|q| q.a.clone());
                    exact_sum = exact_sum.add(&rational_part);
                }
                push_terms(&mut terms, &info.eigenvalue, &coefficients, |c| {
                    if c.is_rational() {
                        Coefficient::Rational(c.a.clone())
                    } else {
                        Coefficient::Surd(c.clone())
                    }
                });
            }
            Eigenvalue::Numeric(z) => {
                let parts = spectral_parts::<Complex64>(m, &p, z, mult);
                push_terms(
                    &mut terms,
                    &info.eigenvalue,
                    &power_coefficients(&parts, z),
                    |c| Coefficient::Numeric(*c),
                );
            }
        }
        powers.push(match &info.eigenvalue {
            Eigenvalue::Rational(l) => FastEigenvalue::Integer {
                value: l.to_integer(),
                shift: power_of_two_exponent(&l.to_integer()),
            },
            Eigenvalue::QuadraticSurd { .. } => FastEigenvalue::Surd(
                info.eigenvalue
                    .to_surd()
                    .expect("surd eigenvalues are exact"),
            ),
            Eigenvalue::Numeric(_) => FastEigenvalue::Numeric,
        });
    }
    // Components with no numeric part: rows of I - sum of exact projectors vanish.
    let mut exact = vec![true; n];
    if any_numeric {
        for (i, ex) in exact.iter_mut().enumerate() {
            *ex = (0..n).all(|j| {
                let target = if i == j {
                    BigRational::one()
                } else {
                    BigRational::zero()
                };
                exact_sum.row(i)[j] == target
            });
        }
    }
    let max_valid = valid_from.iter().copied().max().unwrap_or(0);
    // Rows of M^k for the early levels, by repeated multiplication.
    let big = m.map(|&x| BigInt::from(x));
    let mut powers_of_m: Vec<Matrix<BigInt>> = Vec::new();
    for _ in 0..max_valid {
        let next = match powers_of_m.last() {
            None => Matrix::identity(n),
            Some(prev) => prev
                .checked_mul(&big)
                .expect("big integers do not overflow"),
        };
        powers_of_m.push(next);
    }
    let mut components = Vec::with_capacity(n);
    for i in 0..n {
        let mut ts = std::mem::take(&mut terms[i]);
        if exact[i] {
            ts.retain(|t| t.eigenvalue.is_exact());
        }
        let early_levels = (0..valid_from[i])
            .map(|k| EarlyLevel {
                level: k,
                coefficients: powers_of_m[k as usize].row(i).to_vec(),
            })
            .collect();
        components.push(ComponentForm {
            name: rec.names()[i].clone(),
            valid_from: valid_from[i],
            exact: exact[i],
            terms: ts,
            early_levels,
        });
    }
    let fast = components
        .iter()
        .map(|c| build_fast(c, &eigenvalues))
        .collect();
    let mut form = ClosedForm {
        names: rec.names().to_vec(),
        matrix: m.clone(),
        eigenvalues,
        components,
        fast,
        powers,
        inaccurate: None,
    };
    form.inaccurate = first_inaccuracy(rec, &form);
    form
}

/// The value of a coefficient as a complex `f64`.
fn coefficient_f64(c: &Coefficient) -> Complex64 {
    match c {
        Coefficient::Rational(r) => Complex64::new(crate::field::rational_to_f64(r), 0.0),
        Coefficient::Surd(q) => q.to_f64(),
        Coefficient::Numeric(z) => *z,
    }
}

/// The first `(component, level)` at which a component with numeric terms fails to
/// reproduce exact powering, to within `10^-6` of the largest entry of its row of `M^s`;
/// `None` when every numeric component passes at the levels checked (`valid_from` plus 0,
/// 1, 2 and `n`). Exact components are exact by construction and not checked.
///
/// The `f64` eigenvalues of a badly conditioned characteristic polynomial (entries beyond
/// `2^53`, nearly equal large roots) can be wrong in every digit, or missing: this check is
/// what keeps such a form from being shown as if it held.
fn first_inaccuracy(rec: &Recurrence, form: &ClosedForm) -> Option<(usize, u64)> {
    let n = rec.dim();
    let numeric: Vec<usize> = (0..n).filter(|&i| !form.components[i].exact).collect();
    if numeric.is_empty() {
        return None;
    }
    // columns[j][s] = M^s e_j for every level checked: n^2 products per level, computed once.
    let last = numeric
        .iter()
        .map(|&i| form.components[i].valid_from)
        .max()
        .unwrap_or(0)
        + n as u64;
    let mut columns = Vec::with_capacity(n);
    for j in 0..n {
        let basis: Vec<BigInt> = (0..n).map(|k| BigInt::from(u8::from(k == j))).collect();
        match rec.states_up_to(&basis, last) {
            Ok(states) => columns.push(states),
            Err(_) => return Some((numeric[0], 0)),
        }
    }
    for &i in &numeric {
        let c = &form.components[i];
        for s in [0, 1, 2, n as u64].map(|d| c.valid_from + d) {
            // Row i of M^s.
            let row: Vec<f64> = columns
                .iter()
                .map(|states| {
                    let entry = BigRational::from_integer(states[s as usize][i].clone());
                    crate::field::rational_to_f64(&entry)
                })
                .collect();
            let scale = row.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (j, exact) in row.iter().enumerate() {
                let mut approx = Complex64::new(0.0, 0.0);
                for t in &c.terms {
                    let mut v = coefficient_f64(&t.coefficients[j]);
                    let lambda = t.eigenvalue.to_complex();
                    for _ in 0..s {
                        v = v * lambda;
                    }
                    for _ in 0..t.s_power {
                        v = v * Complex64::new(s as f64, 0.0);
                    }
                    approx = approx + v;
                }
                let error = (approx - Complex64::new(*exact, 0.0)).norm();
                // A NaN or an infinity fails too.
                if !error.is_finite() || !scale.is_finite() || error > 1e-6 * scale {
                    return Some((i, s));
                }
            }
        }
    }
    None
}

fn push_terms<F: Field>(
    terms: &mut [Vec<Term>],
    eigenvalue: &Eigenvalue,
    coeffs: &[Matrix<F>],
    convert: impl Fn(&F) -> Coefficient,
) {
    for (i, comp) in terms.iter_mut().enumerate() {
        for (t, c) in coeffs.iter().enumerate().rev() {
            let coefficients: Vec<Coefficient> = c.row(i).iter().map(&convert).collect();
            if coefficients.iter().all(Coefficient::is_zero) {
                continue;
            }
            comp.push(Term {
                eigenvalue: eigenvalue.clone(),
                s_power: t as u32,
                coefficients,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// The reference: polynomials in `M` over the field (Horner), as before the
    /// fraction-free path. Returns the projector, the `C_t` and the zero-eigenvalue rows.
    fn reference<F: Field>(
        m: &IntMatrix,
        lambda: &F,
        mult: usize,
        zero: bool,
    ) -> (Matrix<F>, Vec<Matrix<F>>, Vec<u64>) {
        let p = Recurrence::new(m.clone())
            .characteristic_polynomial()
            .to_rational();
        assert_eq!(zero, lambda.is_zero());
        spectrum_from_parts::<F>(m, &p, lambda, mult)
    }

    fn same<F: Field + PartialEq>(a: &Matrix<F>, b: &Matrix<F>) -> bool {
        a == b
    }

    /// Checks every exact eigenvalue of `m`: the fraction-free path is taken (no fallback)
    /// and gives exactly the reference's matrices.
    fn check(m: &IntMatrix) -> std::result::Result<(), TestCaseError> {
        let r = Recurrence::new(m.clone());
        for info in r.eigenvalues() {
            let mult = info.multiplicity;
            match &info.eigenvalue {
                Eigenvalue::Rational(l) => {
                    let spec =
                        exact_spectrum::<BigRational>(m, &QuadraticSurd::rational(l.clone()), mult);
                    prop_assert!(spec.is_some(), "fallback for {l} in {m}");
                    let spec = spec.unwrap();
                    let (p, c, v) = reference::<BigRational>(m, l, mult, l.is_zero());
                    prop_assert!(same(&spec.projector, &p), "projector of {l} in {m}");
                    prop_assert_eq!(spec.coefficients.len(), c.len());
                    for (a, b) in spec.coefficients.iter().zip(&c) {
                        prop_assert!(same(a, b), "C_t of {} in {}", l, m);
                    }
                    prop_assert_eq!(spec.valid_from, v);
                }
                Eigenvalue::QuadraticSurd { .. } => {
                    let l = info.eigenvalue.to_surd().unwrap();
                    let spec = exact_spectrum::<QuadraticSurd>(m, &l, mult);
                    prop_assert!(spec.is_some(), "fallback for {l} in {m}");
                    let spec = spec.unwrap();
                    let (p, c, _) = reference::<QuadraticSurd>(m, &l, mult, false);
                    prop_assert!(same(&spec.projector, &p), "projector of {l} in {m}");
                    for (a, b) in spec.coefficients.iter().zip(&c) {
                        prop_assert!(same(a, b), "C_t of {} in {}", l, m);
                    }
                }
                Eigenvalue::Numeric(_) => {}
            }
        }
        Ok(())
    }

    fn matrix(rows: Vec<Vec<i64>>) -> IntMatrix {
        IntMatrix::try_from_rows(rows).unwrap()
    }

    /// The Jordan matrix with one block of size `k` for eigenvalue `l` per `(l, k)`.
    fn jordan(blocks: &[(i64, usize)]) -> Vec<Vec<i64>> {
        let n: usize = blocks.iter().map(|b| b.1).sum();
        let mut j = vec![vec![0i64; n]; n];
        let mut o = 0;
        for &(l, k) in blocks {
            for a in 0..k {
                j[o + a][o + a] = l;
                if a + 1 < k {
                    j[o + a][o + a + 1] = 1;
                }
            }
            o += k;
        }
        j
    }

    /// `E J E^-1` for elementary `E = I + k e_i e_j^T` applied in sequence: the same Jordan
    /// structure, dense entries.
    fn conjugated(mut m: Vec<Vec<i64>>, ops: &[(usize, usize, i64)]) -> IntMatrix {
        let n = m.len();
        for &(i, j, k) in ops {
            let (i, j) = (i % n, j % n);
            if i == j {
                continue;
            }
            let source = m[j].clone();
            for (target, x) in m[i].iter_mut().zip(&source) {
                *target += k * x;
            }
            for row in m.iter_mut() {
                row[j] -= k * row[i];
            }
        }
        matrix(m)
    }

    #[test]
    fn fraction_free_spectra_match_the_reference_on_jordan_forms() {
        type Case = (Vec<(i64, usize)>, Vec<(usize, usize, i64)>);
        let cases: Vec<Case> = vec![
            (
                vec![(2, 3), (2, 1), (1, 2)],
                vec![(0, 3, 1), (4, 1, -1), (2, 5, 1), (5, 0, 2)],
            ),
            (
                vec![(0, 3), (0, 1), (3, 2)],
                vec![(1, 4, 1), (3, 0, -2), (5, 2, 1)],
            ),
            (
                vec![(-1, 4), (4, 2)],
                vec![(0, 5, 1), (5, 1, 1), (2, 4, -1), (3, 0, 1)],
            ),
            (
                vec![(5, 6)],
                vec![(0, 5, 1), (1, 4, -1), (2, 3, 1), (5, 0, 1)],
            ),
        ];
        for (blocks, ops) in cases {
            check(&conjugated(jordan(&blocks), &ops)).unwrap();
        }
        // Quadratic eigenvalues, repeated: two Fibonacci blocks and a Pell block.
        let fib2 = matrix(vec![
            vec![1, 1, 0, 0, 1],
            vec![1, 0, 0, 0, 0],
            vec![0, 0, 1, 1, 0],
            vec![0, 0, 1, 0, 0],
            vec![0, 0, 0, 0, 3],
        ]);
        check(&fib2).unwrap();
        check(&matrix(vec![vec![0, 2, 1], vec![1, 0, 1], vec![0, 0, 2]])).unwrap();
    }

    /// Two different quadratic fields next to numeric eigenvalues: the exact projectors are
    /// summed by their rational parts (adding `Q(sqrt 5)` entries to `Q(sqrt 2)` ones would mix
    /// fields), and exactly the components of the 5-cycle are numeric.
    #[test]
    fn two_quadratic_fields_beside_numeric_eigenvalues() {
        let mut rows = vec![vec![0i64; 9]; 9];
        rows[0][0] = 1;
        rows[0][1] = 1;
        rows[1][0] = 1;
        rows[2][3] = 2;
        rows[3][2] = 1;
        for i in 0..5 {
            rows[4 + (i + 1) % 5][4 + i] = 1;
        }
        let form = Recurrence::new(matrix(rows)).closed_form();
        let exact: Vec<bool> = form.components().iter().map(|c| c.exact).collect();
        assert_eq!(
            exact,
            [true, true, true, true, false, false, false, false, false]
        );
        let fields: Vec<String> = form
            .eigenvalues()
            .iter()
            .filter_map(|e| match &e.eigenvalue {
                Eigenvalue::QuadraticSurd { d, .. } => Some(d.to_string()),
                _ => None,
            })
            .collect();
        assert_eq!(fields.len(), 4, "{fields:?}");
        assert!(fields.contains(&"5".to_string()) && fields.contains(&"2".to_string()));
    }

    fn small_matrix() -> impl Strategy<Value = IntMatrix> {
        (1usize..=5).prop_flat_map(|n| {
            proptest::collection::vec(-3i64..=3, n * n)
                .prop_map(move |e| matrix(e.chunks(n).map(<[i64]>::to_vec).collect()))
        })
    }

    fn jordan_like() -> impl Strategy<Value = IntMatrix> {
        (
            proptest::collection::vec((-2i64..=3, 1usize..=3), 1..=3),
            proptest::collection::vec((0usize..8, 0usize..8, -1i64..=1), 0..8),
        )
            .prop_map(|(blocks, ops)| conjugated(jordan(&blocks), &ops))
    }

    /// Entries near `i64::MAX` and `i64::MIN`, small ones and anything in between.
    fn hostile_entry() -> impl Strategy<Value = i64> {
        prop_oneof![
            (i64::MAX - 1000)..=i64::MAX,
            i64::MIN..=(i64::MIN + 1000),
            (1i64 << 53)..=(1i64 << 53) + 10,
            -3i64..=3,
            any::<i64>(),
        ]
    }

    /// Evaluation equals exact powering at several levels, for every initial state tried.
    fn evaluates_exactly(
        form: &ClosedForm,
        m: &IntMatrix,
    ) -> std::result::Result<(), TestCaseError> {
        let r = Recurrence::new(m.clone());
        let n = m.dim();
        for x0 in [vec![1i64; n], (0..n as i64).map(|i| 3 - 2 * i).collect()] {
            let x0: Vec<BigInt> = x0.into_iter().map(BigInt::from).collect();
            for s in [0u64, 1, 2, 3, 7, 20] {
                prop_assert_eq!(
                    form.evaluate(&x0, s).unwrap(),
                    r.state_at(&x0, s).unwrap(),
                    "level {}",
                    s
                );
            }
        }
        Ok(())
    }

    #[test]
    fn large_entries_keep_exact_quadratic_roots() {
        // The example of the report: eigenvalues (a +- sqrt(a^2 + 4)) / 2, a = 2^53 + 1.
        let m = matrix(vec![vec![9_007_199_254_740_993, 1], vec![1, 0]]);
        let form = Recurrence::new(m.clone()).closed_form();
        assert!(form.is_exact());
        assert!(form
            .to_text()
            .starts_with("x0(s) = ((1/2+9007199254740993/"));
        evaluates_exactly(&form, &m).unwrap();
        // An integer root next to a quadratic pair, all near i64::MAX.
        let m = matrix(vec![
            vec![i64::MAX, 1, 0],
            vec![1, 0, 0],
            vec![0, 0, i64::MAX - 1],
        ]);
        let form = Recurrence::new(m.clone()).closed_form();
        assert!(form.is_exact());
        evaluates_exactly(&form, &m).unwrap();
    }

    #[test]
    fn ill_conditioned_numeric_forms_are_refused() {
        // x^3 - a x^2 - a x - 1 with a = 2^63 - 1 is irreducible: numeric roots, which f64
        // cannot separate.
        let m = matrix(vec![
            vec![i64::MAX, i64::MAX, 1],
            vec![1, 0, 0],
            vec![0, 1, 0],
        ]);
        let r = Recurrence::new(m);
        let form = r.closed_form();
        assert!(!form.is_exact());
        assert_eq!(
            form.verify(),
            Err(crate::Error::InaccurateClosedForm {
                component: "x0".into(),
                level: 0
            })
        );
        assert!(r.verified_closed_form().is_err());
        assert!(r.closed_form_within(u64::MAX).is_err());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        #[test]
        fn two_by_two_forms_are_exact_whatever_the_entries(e in proptest::collection::vec(hostile_entry(), 4)) {
            let m = matrix(vec![vec![e[0], e[1]], vec![e[2], e[3]]]);
            let form = Recurrence::new(m.clone()).closed_form();
            prop_assert!(form.is_exact());
            prop_assert!(form.verify().is_ok());
            evaluates_exactly(&form, &m)?;
        }

        #[test]
        fn three_by_three_forms_with_an_integer_root_are_exact(
            e in proptest::collection::vec(hostile_entry(), 7),
        ) {
            // Block triangular: the eigenvalues of the 2x2 block and e[4].
            let m = matrix(vec![
                vec![e[0], e[1], 0],
                vec![e[2], e[3], 0],
                vec![e[5], e[6], e[4]],
            ]);
            let form = Recurrence::new(m.clone()).closed_form();
            prop_assert!(form.is_exact(), "{:?}", form.eigenvalues());
            evaluates_exactly(&form, &m)?;
        }

        #[test]
        fn three_by_three_forms_are_exact_or_refused(e in proptest::collection::vec(hostile_entry(), 9)) {
            let m = matrix(e.chunks(3).map(<[i64]>::to_vec).collect());
            let form = Recurrence::new(m.clone()).closed_form();
            if form.is_exact() {
                prop_assert!(form.verify().is_ok());
                evaluates_exactly(&form, &m)?;
            } else if form.verify().is_ok() {
                // A numeric form that passed the check: its exact components still evaluate
                // exactly, and the rest are marked numeric.
                let r = Recurrence::new(m.clone());
                let x0 = vec![BigInt::one(); 3];
                for s in [0u64, 1, 5] {
                    prop_assert_eq!(form.state_at(&x0, s).unwrap(), r.state_at(&x0, s).unwrap());
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn fraction_free_spectra_match_the_reference(m in small_matrix()) {
            check(&m)?;
        }

        #[test]
        fn fraction_free_spectra_match_the_reference_with_repeats(m in jordan_like()) {
            check(&m)?;
        }
    }
}
