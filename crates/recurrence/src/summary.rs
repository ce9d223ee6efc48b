//! Digit summaries of huge counts: the exact number of decimal digits, the leading digits
//! and the exact trailing digits, without writing the number out in decimal (and, for closed
//! forms with integer eigenvalues, without computing it at all).
//!
//! Leading digits come from a binary floating-point approximation with a few hundred bits
//! of mantissa (`m * 2^e`, powers by squaring with truncation), checked against its error
//! bound and recomputed with more bits when a digit boundary is too close. Trailing digits
//! are exact: a closed form's value is `N / D` with integer `N`, so `N mod (D * 10^k)`,
//! computed by modular powering, divided by `D` is the value mod `10^k`.

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Pow, Signed, ToPrimitive, Zero};

use crate::closed_form::{dot, FastEigenvalue};
use crate::{ClosedForm, Error, Result};

/// The decimal digits of a (possibly huge) integer, summarized.
///
/// `leading` and `trailing` hold the first and last `min(k, digits)` digits of `|n|` (so
/// for numbers of at most `k` digits both are the whole number).
///
/// ```
/// use num_bigint::BigInt;
/// use recurrence::digit_summary;
///
/// let n = BigInt::from(2).pow(100u32); // 1267650600228229401496703205376
/// let d = digit_summary(&n, 5);
/// assert_eq!((d.digits, d.leading.as_str(), d.trailing.as_str()), (31, "12676", "05376"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct DigitSummary {
    /// Whether the number is negative (the digits are those of its absolute value).
    pub negative: bool,
    /// The number of decimal digits of `|n|` (`1` for zero).
    pub digits: u64,
    /// The first digits.
    pub leading: String,
    /// The last digits, with leading zeros where they fall inside the number.
    pub trailing: String,
}

/// A binary floating-point number `m * 2^e`.
#[derive(Clone, Debug)]
struct BigFloat {
    m: BigInt,
    e: i64,
}

impl BigFloat {
    fn from_int(n: &BigInt, prec: u64) -> Self {
        BigFloat { m: n.clone(), e: 0 }.normalize(prec)
    }

    fn normalize(mut self, prec: u64) -> Self {
        let bits = self.m.bits();
        if bits > prec {
            let shift = bits - prec;
            let neg = self.m.is_negative();
            let mag = self.m.magnitude() >> shift;
            self.m = if neg {
                -BigInt::from(mag)
            } else {
                BigInt::from(mag)
            };
            self.e += shift as i64;
        }
        self
    }

    fn mul(&self, o: &BigFloat, prec: u64) -> BigFloat {
        BigFloat {
            m: &self.m * &o.m,
            e: self.e + o.e,
        }
        .normalize(prec)
    }

    fn add(&self, o: &BigFloat, prec: u64) -> BigFloat {
        if self.m.is_zero() {
            return o.clone();
        }
        if o.m.is_zero() {
            return self.clone();
        }
        let (hi, lo) = if self.top() >= o.top() {
            (self, o)
        } else {
            (o, self)
        };
        if hi.top() - lo.top() > prec as i64 + 64 {
            return hi.clone();
        }
        let e = hi.e.min(lo.e);
        let m = (&hi.m << (hi.e - e) as usize) + (&lo.m << (lo.e - e) as usize);
        BigFloat { m, e }.normalize(prec)
    }

    fn div(&self, o: &BigFloat, prec: u64) -> BigFloat {
        let shift = prec + o.m.bits();
        BigFloat {
            m: (&self.m << shift as usize) / &o.m,
            e: self.e - o.e - shift as i64,
        }
        .normalize(prec)
    }

    /// `base^s` by squaring, truncating to `prec` bits at every step.
    fn pow(base: &BigInt, mut s: u64, prec: u64) -> BigFloat {
        let mut result = BigFloat::from_int(&BigInt::one(), prec);
        let mut b = BigFloat::from_int(base, prec);
        while s > 0 {
            if s & 1 == 1 {
                result = result.mul(&b, prec);
            }
            s >>= 1;
            if s > 0 {
                b = b.mul(&b, prec);
            }
        }
        result
    }

    /// Position of the top bit: `|value| < 2^top`.
    fn top(&self) -> i64 {
        self.e + self.m.bits() as i64
    }

    /// `log10 |value|`, to `f64` accuracy.
    fn log10(&self) -> f64 {
        let bits = self.m.bits();
        let shift = bits.saturating_sub(60);
        let top = (self.m.magnitude() >> shift).to_f64().unwrap_or(1.0);
        top.log10() + (self.e + shift as i64) as f64 * std::f64::consts::LOG10_2
    }

    /// `floor(|value|)` and whether the fractional part is closer than `2^-(slack)` relative
    /// to an integer boundary.
    fn floor_abs(&self, eff_bits: u64) -> (BigInt, bool) {
        let mag = BigInt::from(self.m.magnitude().clone());
        let (int, frac_bits) = if self.e >= 0 {
            (&mag << self.e as usize, 0u64)
        } else {
            let sh = (-self.e) as u64;
            (&mag >> sh as usize, sh)
        };
        if frac_bits == 0 {
            return (int, true);
        }
        // Absolute error of the value in units of 2^-frac_bits: |value| * 2^-eff_bits.
        let err_shift = self.m.bits().saturating_sub(eff_bits);
        let err = BigInt::one() << err_shift as usize;
        let frac = &mag - (&int << frac_bits as usize);
        let one = BigInt::one() << frac_bits as usize;
        let near = frac <= err || (&one - &frac) <= err;
        (int, near)
    }
}

fn pad(n: &BigInt, width: usize) -> String {
    format!("{:0>width$}", n.to_string())
}

/// The [`DigitSummary`] of `n` with `k` leading and trailing digits.
///
/// Exact for every `n`: the digit count and leading digits come from a floating-point
/// approximation whose rare ambiguous cases are settled with exact big-integer arithmetic,
/// and the trailing digits from `|n| mod 10^k`. No full decimal conversion is done for large
/// numbers.
///
/// # Panics
///
/// Panics if `k` is zero.
pub fn digit_summary(n: &BigInt, k: usize) -> DigitSummary {
    assert!(k > 0, "a digit summary needs at least one digit");
    let negative = n.is_negative();
    let mag = n.abs();
    if mag.bits() <= 4096 {
        let s = mag.to_string();
        let lead: String = s.chars().take(k).collect();
        let trail: String = s[s.len().saturating_sub(k)..].to_string();
        return DigitSummary {
            negative,
            digits: s.len() as u64,
            leading: lead,
            trailing: trail,
        };
    }
    let ten_k = BigInt::from(10).pow(k as u32);
    let trailing = &mag % &ten_k;
    let prec = 256u64 + 4 * k as u64;
    let approx = BigFloat::from_int(&mag, prec);
    let eff = prec - 2;
    let (digits, leading) = match digits_and_leading(&approx, eff, k, &trailing) {
        Some(x) => x,
        None => {
            // Ambiguous even so: settle with exact arithmetic.
            let est = (approx.log10().floor() as u64).max(1);
            let mut d = est;
            while mag >= BigInt::from(10).pow(d as u32) {
                d += 1;
            }
            while d > 1 && mag < BigInt::from(10).pow((d - 1) as u32) {
                d -= 1;
            }
            let lead = if d as usize <= k {
                mag.clone()
            } else {
                &mag / BigInt::from(10).pow((d - k as u64) as u32)
            };
            (d, lead)
        }
    };
    summary_from(negative, digits, &leading, &trailing, k)
}

fn summary_from(
    negative: bool,
    digits: u64,
    leading: &BigInt,
    trailing_mod: &BigInt,
    k: usize,
) -> DigitSummary {
    let shown = (digits as usize).min(k);
    DigitSummary {
        negative,
        digits,
        leading: if (digits as usize) <= k {
            pad(trailing_mod, shown)
        } else {
            leading.to_string()
        },
        trailing: pad(trailing_mod, shown),
    }
}

/// The digit count and the leading `k` digits of `|v|` from an approximation with `eff`
/// correct bits, or `None` when too close to call. `trailing` is `|v| mod 10^k`.
fn digits_and_leading(
    v: &BigFloat,
    eff: u64,
    k: usize,
    trailing: &BigInt,
) -> Option<(u64, BigInt)> {
    if v.m.is_zero() {
        return Some((1, BigInt::zero()));
    }
    let prec = eff + 8;
    let lg = v.log10();
    // digits = floor(log10 v) + 1; settle the floor by comparing with 10^q.
    let mut q = lg.floor().max(0.0) as u64;
    for _ in 0..3 {
        let p = BigFloat::pow(&BigInt::from(10), q, prec);
        let ratio = BigFloat {
            m: v.m.abs(),
            e: v.e,
        }
        .div(&p, prec);
        // ratio in [1, 10) means q is right.
        let (int, near) = ratio.floor_abs(eff.saturating_sub(4));
        if int.is_zero() {
            if near {
                return None;
            }
            q = q.checked_sub(1)?;
            continue;
        }
        if int >= BigInt::from(10) {
            if int == BigInt::from(10) && near {
                return None;
            }
            q += 1;
            continue;
        }
        if int == BigInt::from(9) && near {
            return None;
        }
        if int == BigInt::one() && near && ratio.m.bits() as i64 + ratio.e <= 1 {
            // Within error of exactly 10^q.
            return None;
        }
        let digits = q + 1;
        if digits as usize <= k {
            return Some((digits, trailing.clone()));
        }
        let j = digits - k as u64;
        let p = BigFloat::pow(&BigInt::from(10), j, prec);
        let lead = BigFloat {
            m: v.m.abs(),
            e: v.e,
        }
        .div(&p, prec);
        let (int, near) = lead.floor_abs(eff.saturating_sub(8 + 4 * k as u64));
        if !near {
            return Some((digits, int));
        }
        // The value sits within error of a multiple of 10^j: the trailing digits settle it
        // when they cover the whole fractional part.
        if j as usize <= k {
            let low = trailing % BigInt::from(10).pow(j as u32);
            let ten_j = BigFloat::pow(&BigInt::from(10), j, prec);
            let frac = BigFloat::from_int(&low, prec).div(&ten_j, prec);
            let whole = lead.add(
                &BigFloat {
                    m: -frac.m,
                    e: frac.e,
                },
                prec,
            );
            // `whole` is within error of the integer floor(v / 10^j).
            let (w, _) = whole
                .add(
                    &BigFloat {
                        m: BigInt::one(),
                        e: -2,
                    },
                    prec,
                )
                .floor_abs(eff);
            return Some((digits, w));
        }
        return None;
    }
    None
}

impl ClosedForm {
    /// A [`DigitSummary`] of every component at level `s` with `k` leading and trailing
    /// digits, computed from the closed form without materializing huge numbers: `s =
    /// 10^12` works for forms with integer eigenvalues.
    ///
    /// The digit count and the trailing digits are exact. The leading digits are exact
    /// unless the digits right after them are a run of hundreds of zeros or nines, a case
    /// the precision escalation cannot separate; then the nearest candidate is returned.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] for a wrong-length `x0`; [`Error::NotExact`] for numeric
    /// forms; [`Error::TooLarge`] for surd forms at levels too high to compute exactly.
    ///
    /// # Panics
    ///
    /// Panics if `k` is zero.
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use recurrence::{IntMatrix, Recurrence};
    ///
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// let form = r.closed_form();
    /// let x0 = [12, 30].map(BigInt::from);
    /// let at = form.summary_at(&x0, 1_000_000_000_000, 20)?;
    /// // E = 30 * 4^(10^12) has floor(log10(30) + 2*10^12*log10(2)) + 1 digits.
    /// assert_eq!(at[1].digits, 602_059_991_330);
    /// assert_eq!(at[1].leading, "27511336074359412431");
    /// assert!(at[1].trailing.ends_with("0"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn summary_at(&self, x0: &[BigInt], s: u64, k: usize) -> Result<Vec<DigitSummary>> {
        assert!(k > 0, "a digit summary needs at least one digit");
        if x0.len() != self.names().len() {
            return Err(Error::InitialLength {
                got: x0.len(),
                expected: self.names().len(),
            });
        }
        const SMALL_BITS: f64 = 200_000.0;
        let mut out = Vec::with_capacity(x0.len());
        for (i, fast) in self.fast().iter().enumerate() {
            let Some(fast) = fast else {
                return Err(Error::NotExact {
                    component: self.names()[i].clone(),
                });
            };
            if s < fast.valid_from {
                out.push(digit_summary(&dot(&fast.early[s as usize], x0), k));
                continue;
            }
            // Size estimate of the largest term.
            let mut bits = 0.0f64;
            for (e, p, _) in &fast.rational {
                if let FastEigenvalue::Integer { value, .. } = &self.powers()[*e] {
                    let lb = value.to_f64().map_or(64.0, |x| x.abs().log2());
                    bits = bits.max(s as f64 * lb + f64::from(*p) * (s.max(1) as f64).log2());
                }
            }
            for (e, _, _) in &fast.surd {
                if let FastEigenvalue::Surd(q) = &self.powers()[*e] {
                    bits = bits.max(s as f64 * q.to_f64().norm().log2().max(0.0));
                }
            }
            if bits <= SMALL_BITS {
                out.push(digit_summary(&self.evaluate_component(x0, s, i)?, k));
                continue;
            }
            if !fast.surd.is_empty() {
                return Err(Error::TooLarge {
                    level: s,
                    bits: bits as u64,
                });
            }
            out.push(self.rational_summary(fast, x0, s, k)?);
        }
        Ok(out)
    }

    fn rational_summary(
        &self,
        fast: &crate::closed_form::FastComponent,
        x0: &[BigInt],
        s: u64,
        k: usize,
    ) -> Result<DigitSummary> {
        let s_big = BigInt::from(s);
        // Integer parts of each term: c * s^p and the eigenvalue.
        let parts: Vec<(BigInt, BigInt)> = fast
            .rational
            .iter()
            .filter_map(|(e, p, nums)| {
                let c = dot(nums, x0);
                if c.is_zero() {
                    return None;
                }
                let c = c * Pow::pow(&s_big, *p);
                match &self.powers()[*e] {
                    FastEigenvalue::Integer { value, .. } => Some((c, value.clone())),
                    _ => None,
                }
            })
            .collect();
        let d = &fast.denominator;
        // Trailing digits: N mod (D 10^k) / D = v mod 10^k.
        let ten_k = BigInt::from(10).pow(k as u32);
        let modulus = d * &ten_k;
        let mut r = BigInt::zero();
        for (c, lambda) in &parts {
            let mut pw = lambda.abs().modpow(&s_big, &modulus);
            if lambda.is_negative() && s % 2 == 1 {
                pw = -pw;
            }
            r = (r + c * pw).mod_floor(&modulus);
        }
        let v_mod = &r / d; // v mod 10^k, in [0, 10^k)
                            // Leading digits and sign from a floating-point sum, with escalating precision.
        let mut prec = 256u64 + 4 * k as u64;
        loop {
            let mut sum = BigFloat::from_int(&BigInt::zero(), prec);
            let mut max_top = i64::MIN;
            for (c, lambda) in &parts {
                let mut pw = BigFloat::pow(&lambda.abs(), s, prec);
                if lambda.is_negative() && s % 2 == 1 {
                    pw.m = -pw.m;
                }
                let term = pw.mul(&BigFloat::from_int(c, prec), prec);
                max_top = max_top.max(term.top());
                sum = sum.add(&term, prec);
            }
            let v = sum.div(&BigFloat::from_int(d, prec), prec);
            // Relative precision left after cancellation, with room for rounding errors.
            let cancel = if sum.m.is_zero() {
                prec as i64
            } else {
                (max_top - sum.top()).max(0)
            };
            let eff = prec as i64 - cancel - 16 - 2 * (64 - s.leading_zeros() as i64);
            if eff >= 64 + 4 * k as i64 && !sum.m.is_zero() {
                let negative = v.m.is_negative();
                let trailing = if negative {
                    (&ten_k - &v_mod).mod_floor(&ten_k)
                } else {
                    v_mod.clone()
                };
                if let Some((digits, leading)) = digits_and_leading(&v, eff as u64, k, &trailing) {
                    return Ok(summary_from(negative, digits, &leading, &trailing, k));
                }
            }
            if prec > 1 << 15 {
                // Heavy cancellation or a value sitting on a decimal boundary: the value is
                // small compared to its terms, so compute it exactly if that is affordable.
                let est = self.evaluate_bits_estimate(&parts, s);
                if est <= 4_000_000 {
                    let i = self
                        .fast()
                        .iter()
                        .position(|f| f.as_ref().is_some_and(|f| std::ptr::eq(f, fast)))
                        .unwrap_or(0);
                    return Ok(digit_summary(&self.evaluate_component(x0, s, i)?, k));
                }
                return Err(Error::TooLarge {
                    level: s,
                    bits: est,
                });
            }
            prec *= 2;
        }
    }

    fn evaluate_bits_estimate(&self, parts: &[(BigInt, BigInt)], s: u64) -> u64 {
        parts
            .iter()
            .map(|(c, l)| c.bits().saturating_add(s.saturating_mul(l.bits())))
            .max()
            .unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{IntMatrix, Recurrence};

    fn brute(n: &BigInt, k: usize) -> DigitSummary {
        let s = n.abs().to_string();
        DigitSummary {
            negative: n.is_negative(),
            digits: s.len() as u64,
            leading: s.chars().take(k).collect(),
            trailing: s[s.len().saturating_sub(k)..].to_string(),
        }
    }

    #[test]
    fn huge_levels_without_materializing() {
        let r = Recurrence::new("[[1,1],[0,4]]".parse::<IntMatrix>().unwrap());
        let form = r.closed_form();
        let x0 = [BigInt::from(12), BigInt::from(30)];
        let s = 1_000_000_000_000u64;
        let at = form.summary_at(&x0, s, 20).unwrap();
        // E(s) = 30 * 4^s.
        let log = 30f64.log10() + 2.0 * s as f64 * std::f64::consts::LOG10_2;
        assert_eq!(at[1].digits, log.floor() as u64 + 1);
        let lead = 10f64.powf(log.fract() + 2.0).floor() as u64; // first three digits
        assert_eq!(at[1].leading[..3], lead.to_string());
        let m = BigInt::from(10).pow(20u32);
        let trailing = (BigInt::from(4).modpow(&BigInt::from(s), &m) * 30) % &m;
        assert_eq!(at[1].trailing, format!("{trailing:0>20}"));
        // V(s) = 12 + (4^s - 1) * 10 = 10 * 4^s + 2.
        let log_v = 1.0 + 2.0 * s as f64 * std::f64::consts::LOG10_2;
        assert_eq!(at[0].digits, log_v.floor() as u64 + 1);
        let tv = (BigInt::from(4).modpow(&BigInt::from(s), &m) * 10 + 2) % &m;
        assert_eq!(at[0].trailing, format!("{tv:0>20}"));
    }

    #[test]
    fn small_components_beside_huge_ones() {
        // V - E/3 stays constant while E explodes: V0 + (4^s - 1)/3 E0 and a constant.
        let r = Recurrence::new("[[1,1,0],[0,4,0],[0,0,1]]".parse::<IntMatrix>().unwrap());
        let form = r.closed_form();
        let x0 = [BigInt::from(12), BigInt::from(30), BigInt::from(-7)];
        let at = form.summary_at(&x0, 1_000_000_000_000, 20).unwrap();
        assert_eq!(
            at[2],
            DigitSummary {
                negative: true,
                digits: 1,
                leading: "7".into(),
                trailing: "7".into()
            }
        );
        assert_eq!(at[1].digits, 602_059_991_330);
    }

    #[test]
    fn runs_of_nines_fall_back_to_exact_arithmetic() {
        // x(s) = 10^s - 1 sits just below a power of ten.
        let r = Recurrence::new("[[10,1],[0,1]]".parse::<IntMatrix>().unwrap());
        let form = r.closed_form();
        let x0 = [BigInt::zero(), BigInt::from(9)];
        let f = form.fast()[0].as_ref().unwrap();
        let d = form.rational_summary(f, &x0, 5000, 20).unwrap();
        assert_eq!(d.digits, 5000);
        assert_eq!(d.leading, "9".repeat(20));
        assert_eq!(d.trailing, "9".repeat(20));
    }

    #[test]
    fn digit_summary_matches_decimal_strings() {
        let cases = [
            BigInt::zero(),
            BigInt::from(7),
            BigInt::from(-123_456_789),
            BigInt::from(10).pow(5000u32),
            BigInt::from(10).pow(5000u32) - 1,
            -(BigInt::from(3).pow(20_000u32)),
            BigInt::from(2).pow(30_000u32) * 7 + 1,
            BigInt::from(10).pow(6000u32) * 12_345 + BigInt::from(10).pow(10u32),
        ];
        for n in &cases {
            for k in [1, 5, 20] {
                assert_eq!(digit_summary(n, k), brute(n, k), "k = {k}");
            }
        }
    }

    #[test]
    fn closed_form_summary_matches_exact_values() {
        for (m, x0) in [
            ("[[1,1],[0,4]]", vec![12, 30]),
            ("[[1,1,1],[0,2,4],[0,0,4]]", vec![8, 12, 6]),
            ("[[-3,1],[0,2]]", vec![5, -7]),
            ("[[10,1],[0,1]]", vec![0, 9]),
            ("[[2,1],[0,2]]", vec![1, 1]),
        ] {
            let r = Recurrence::new(m.parse::<IntMatrix>().unwrap());
            let x0: Vec<BigInt> = x0.into_iter().map(BigInt::from).collect();
            let form = r.closed_form();
            for s in [0u64, 1, 7, 100, 3001] {
                let exact = r.state_at(&x0, s).unwrap();
                let want: Vec<DigitSummary> = exact.iter().map(|v| brute(v, 20)).collect();
                let mut got = Vec::new();
                for (i, f) in form.fast().iter().enumerate() {
                    let f = f.as_ref().unwrap();
                    got.push(if s < f.valid_from {
                        digit_summary(&exact[i], 20)
                    } else {
                        form.rational_summary(f, &x0, s, 20).unwrap()
                    });
                }
                assert_eq!(got, want, "{m} at level {s}");
                assert_eq!(
                    form.summary_at(&x0, s, 20).unwrap(),
                    want,
                    "{m} at level {s}"
                );
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 64, failure_persistence: None, ..Default::default() })]

        #[test]
        fn forced_float_path_matches_decimal_strings(
            upper in proptest::collection::vec(-6i64..=6, 6),
            x0 in proptest::collection::vec(-50i64..=50, 3),
            s in 0u64..400,
            k in 1usize..=25,
        ) {
            let m = vec![
                vec![upper[0], upper[1], upper[2]],
                vec![0, upper[3], upper[4]],
                vec![0, 0, upper[5]],
            ];
            let r = Recurrence::new(IntMatrix::try_from_rows(m).unwrap());
            let x0: Vec<BigInt> = x0.into_iter().map(BigInt::from).collect();
            let form = r.closed_form();
            let exact = r.state_at(&x0, s).unwrap();
            for (i, f) in form.fast().iter().enumerate() {
                let f = f.as_ref().unwrap();
                if s < f.valid_from {
                    continue;
                }
                proptest::prop_assert_eq!(form.rational_summary(f, &x0, s, k).unwrap(), brute(&exact[i], k));
            }
        }
    }
}
