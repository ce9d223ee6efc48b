//! Exact evaluation of a [`ClosedForm`]: integer eigenvalues as shifts or powers over one
//! common denominator, quadratic surds in their field, numeric forms refused (or powered).

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Pow, Signed, Zero};

use super::{ClosedForm, Coefficient, ComponentForm, FastComponent, FastEigenvalue};
use crate::eigen::{Eigenvalue, EigenvalueInfo};
use crate::field::QuadraticSurd;
use crate::{Error, Result};

impl ClosedForm {
    /// The exact state at level `s` by the fastest exact path: [`evaluate`](Self::evaluate)
    /// when every component's form is exact, powering of the matrix otherwise.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] for a wrong-length `x0`.
    ///
    /// ```
    /// # use num_bigint::BigInt;
    /// # use recurrence::{IntMatrix, Recurrence};
    /// // A 5-cycle has a numeric closed form, but its counts stay exact.
    /// let r = Recurrence::new("[[0,0,0,0,1],[1,0,0,0,0],[0,1,0,0,0],[0,0,1,0,0],[0,0,0,1,0]]".parse::<IntMatrix>()?);
    /// let x0 = [1, 2, 3, 4, 5].map(BigInt::from);
    /// assert_eq!(r.closed_form().state_at(&x0, 7)?, [4, 5, 1, 2, 3].map(BigInt::from));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn state_at(&self, x0: &[BigInt], s: u64) -> Result<Vec<BigInt>> {
        if self.is_exact() {
            self.evaluate(x0, s)
        } else {
            if x0.len() != self.names.len() {
                return Err(Error::InitialLength {
                    got: x0.len(),
                    expected: self.names.len(),
                });
            }
            Ok(crate::power::checked_power_apply(&self.matrix, x0, s)
                .expect("big integers do not overflow"))
        }
    }

    /// The exact state at level `s` from the closed form; agrees with
    /// [`Recurrence::state_at`](crate::Recurrence::state_at) for every `s`.
    ///
    /// Powers of eigenvalues `+-2^k` are shifts, and each component is summed over a common
    /// denominator and divided once, exactly.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] for a wrong-length `x0`; [`Error::NotExact`] when a component's
    /// form is numeric (compute those counts by powering, which is always exact, or call
    /// [`state_at`](Self::state_at)); [`Error::TooLarge`] when a count would need more than
    /// 2^37 bits (16 GiB), see [`estimated_bits`](Self::estimated_bits).
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use recurrence::{IntMatrix, Recurrence};
    ///
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// let form = r.closed_form();
    /// let x0 = [12, 30].map(BigInt::from);
    /// assert_eq!(form.evaluate(&x0, 4)?, [2562, 7680].map(BigInt::from));
    /// assert_eq!(form.evaluate(&x0, 300)?, r.state_at(&x0, 300)?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn evaluate(&self, x0: &[BigInt], s: u64) -> Result<Vec<BigInt>> {
        self.evaluate_selected(x0, s, None)
    }

    /// The value of component `i` alone at level `s` (see [`evaluate`](Self::evaluate)).
    pub(crate) fn evaluate_component(&self, x0: &[BigInt], s: u64, i: usize) -> Result<BigInt> {
        let mut v = self.evaluate_selected(x0, s, Some(i))?;
        Ok(v.pop().expect("one component was evaluated"))
    }

    fn evaluate_selected(&self, x0: &[BigInt], s: u64, only: Option<usize>) -> Result<Vec<BigInt>> {
        if x0.len() != self.names.len() {
            return Err(Error::InitialLength {
                got: x0.len(),
                expected: self.names.len(),
            });
        }
        let bits = match only {
            Some(i) => self.component_bits(i, s),
            None => self.estimated_bits(s),
        };
        if bits > MAX_EVALUATION_BITS {
            return Err(Error::TooLarge { level: s, bits });
        }
        let mut cache: Vec<Option<PowerValue>> = vec![None; self.powers.len()];
        let s_big = BigInt::from(s);
        let mut out = Vec::with_capacity(self.names.len());
        for (i, fast) in self.fast.iter().enumerate() {
            if only.is_some_and(|o| o != i) {
                continue;
            }
            let Some(fast) = fast else {
                return Err(Error::NotExact {
                    component: self.names[i].clone(),
                });
            };
            if s < fast.valid_from {
                out.push(dot(&fast.early[s as usize], x0));
                continue;
            }
            let mut acc = BigInt::zero();
            for (e, p, nums) in &fast.rational {
                let mut c = dot(nums, x0);
                if c.is_zero() {
                    continue;
                }
                if *p > 0 {
                    c *= Pow::pow(&s_big, *p);
                }
                match &self.powers[*e] {
                    FastEigenvalue::Integer {
                        value,
                        shift: Some(k),
                    } => {
                        c <<= usize::try_from(k.saturating_mul(s))
                            .map_err(|_| too_large(s, k.saturating_mul(s)))?;
                        if value.is_negative() && s % 2 == 1 {
                            c = -c;
                        }
                    }
                    FastEigenvalue::Integer { value, shift: None } => {
                        let pw =
                            cache[*e].get_or_insert_with(|| PowerValue::Int(Pow::pow(value, s)));
                        if let PowerValue::Int(pw) = pw {
                            c *= &*pw;
                        }
                    }
                    FastEigenvalue::Surd(_) | FastEigenvalue::Numeric => {}
                }
                // Moves rather than copies the (possibly huge) term into the sum.
                acc = if acc.is_zero() { c } else { acc + c };
            }
            if fast.surd.is_empty() {
                // The common denominator divides the sum exactly: one division, no rationals.
                let value = if fast.denominator.is_one() {
                    acc
                } else {
                    debug_assert!((&acc % &fast.denominator).is_zero(), "exact division");
                    // Powers of two in the denominator are a shift (exact, so the rounding
                    // of `>>` on negative numbers never applies); only the odd part divides.
                    let tz = fast.denominator.trailing_zeros().unwrap_or(0);
                    let acc = if tz > 0 { acc >> tz } else { acc };
                    let odd = &fast.denominator >> tz;
                    if odd.is_one() {
                        acc
                    } else {
                        acc / odd
                    }
                };
                out.push(value);
                continue;
            }
            let (q, r) = acc.div_rem(&fast.denominator);
            let mut value =
                BigRational::new(r, fast.denominator.clone()) + BigRational::from_integer(q);
            {
                // One running sum per quadratic field, keyed by the eigenvalue's radicand:
                // conjugate terms cancel within each. (Keyed by the running value instead, a
                // sum that had just become rational took the next field's term and left two
                // sums with irrational parts that cancel only together.)
                let mut sums: Vec<(BigInt, QuadraticSurd)> = Vec::new();
                for (e, p, coeffs) in &fast.surd {
                    let c = coeffs
                        .iter()
                        .zip(x0)
                        .fold(QuadraticSurd::zero(), |acc, (c, x)| {
                            &acc + &(c * &QuadraticSurd::rational(BigRational::from_integer(
                                x.clone(),
                            )))
                        });
                    if c.is_zero() {
                        continue;
                    }
                    let FastEigenvalue::Surd(lambda) = &self.powers[*e] else {
                        continue;
                    };
                    let pw = cache[*e].get_or_insert_with(|| PowerValue::Surd(surd_pow(lambda, s)));
                    let PowerValue::Surd(pw) = pw else { continue };
                    let sp =
                        QuadraticSurd::rational(BigRational::from_integer(Pow::pow(&s_big, *p)));
                    let term = &(&c * pw) * &sp;
                    match sums.iter_mut().find(|(d, _)| *d == lambda.d) {
                        Some((_, q)) => *q = &*q + &term,
                        None => sums.push((lambda.d.clone(), term)),
                    }
                }
                for (_, sum) in sums {
                    debug_assert!(sum.is_rational(), "conjugate terms cancel");
                    value += sum.a;
                }
            }
            debug_assert!(
                value.is_integer(),
                "closed forms of integer recurrences give integers"
            );
            out.push(value.to_integer());
        }
        Ok(out)
    }
}

/// Counts beyond this many bits (16 GiB each) are refused rather than attempted.
const MAX_EVALUATION_BITS: u64 = 1 << 37;

fn too_large(level: u64, bits: u64) -> Error {
    Error::TooLarge { level, bits }
}

#[derive(Clone, Debug)]
enum PowerValue {
    Int(BigInt),
    Surd(QuadraticSurd),
}

pub(crate) fn dot(c: &[BigInt], x: &[BigInt]) -> BigInt {
    c.iter()
        .zip(x)
        .filter(|(c, _)| !c.is_zero())
        .map(|(c, x)| c * x)
        .sum()
}

fn surd_pow(base: &QuadraticSurd, mut s: u64) -> QuadraticSurd {
    let mut result = QuadraticSurd::one();
    let mut b = base.clone();
    while s > 0 {
        if s & 1 == 1 {
            result = &result * &b;
        }
        s >>= 1;
        if s > 0 {
            b = &b * &b;
        }
    }
    result
}

/// The integer data for evaluating an exact component, `None` for numeric ones.
pub(super) fn build_fast(
    comp: &ComponentForm,
    eigenvalues: &[EigenvalueInfo],
) -> Option<FastComponent> {
    if !comp.exact {
        return None;
    }
    let index_of = |e: &Eigenvalue| eigenvalues.iter().position(|x| &x.eigenvalue == e);
    let mut denominator = BigInt::one();
    for t in &comp.terms {
        for c in &t.coefficients {
            if let Coefficient::Rational(r) = c {
                if t.eigenvalue.as_rational().is_some() {
                    denominator = denominator.lcm(r.denom());
                }
            }
        }
    }
    let mut rational = Vec::new();
    let mut surd = Vec::new();
    for t in &comp.terms {
        let e = index_of(&t.eigenvalue)?;
        match &t.eigenvalue {
            Eigenvalue::Rational(_) => {
                let nums = t
                    .coefficients
                    .iter()
                    .map(|c| match c {
                        Coefficient::Rational(r) => Some((r * &denominator).to_integer()),
                        _ => None,
                    })
                    .collect::<Option<Vec<_>>>()?;
                rational.push((e, t.s_power, nums));
            }
            Eigenvalue::QuadraticSurd { .. } => {
                let cs = t
                    .coefficients
                    .iter()
                    .map(|c| match c {
                        Coefficient::Rational(r) => Some(QuadraticSurd::rational(r.clone())),
                        Coefficient::Surd(q) => Some(q.clone()),
                        Coefficient::Numeric(_) => None,
                    })
                    .collect::<Option<Vec<_>>>()?;
                surd.push((e, t.s_power, cs));
            }
            Eigenvalue::Numeric(_) => return None,
        }
    }
    Some(FastComponent {
        denominator,
        rational,
        surd,
        valid_from: comp.valid_from,
        early: comp
            .early_levels
            .iter()
            .map(|l| l.coefficients.clone())
            .collect(),
    })
}
