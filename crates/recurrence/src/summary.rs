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

/// `log10(2)` to 60 decimal places: `LOG10_2_DIGITS / 10^LOG10_2_SCALE`, enough that the
/// product with any exponent this module meets (below `2^128`) is off by less than `10^-20`.
const LOG10_2_DIGITS: &str = "301029995663981195213738894724493026768189881462108541310427";
const LOG10_2_SCALE: u32 = 60;

/// A binary floating-point number `m * 2^e`.
///
/// The exponent is an `i128`: a mantissa of `b` bits raised to a level `s <= u64::MAX` has an
/// exponent below `b * 2^64`, far from `i128`'s range for any mantissa that fits in memory,
/// so no exponent arithmetic here can overflow.
#[derive(Clone, Debug)]
struct BigFloat {
    m: BigInt,
    e: i128,
}

/// A bit count or shift as an `i128` (lossless: `u64` fits).
fn wide(n: u64) -> i128 {
    i128::from(n)
}

/// A shift between mantissas of the same computation, which is bounded by a few times the
/// working precision; `None` if it is not (the caller then treats the case as ambiguous).
fn shift_amount(n: i128) -> Option<usize> {
    usize::try_from(n).ok()
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
            self.e += wide(shift);
        }
        self
    }

    fn neg(&self) -> BigFloat {
        BigFloat {
            m: -&self.m,
            e: self.e,
        }
    }

    fn abs(&self) -> BigFloat {
        BigFloat {
            m: self.m.abs(),
            e: self.e,
        }
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
        if hi.top() - lo.top() > wide(prec) + 64 {
            return hi.clone();
        }
        // Both mantissas have at most about `prec` bits and their tops are within
        // `prec + 64` bits, so the alignment shifts are small.
        let e = hi.e.min(lo.e);
        let (Some(sh_hi), Some(sh_lo)) = (shift_amount(hi.e - e), shift_amount(lo.e - e)) else {
            return hi.clone();
        };
        let m = (&hi.m << sh_hi) + (&lo.m << sh_lo);
        BigFloat { m, e }.normalize(prec)
    }

    fn div(&self, o: &BigFloat, prec: u64) -> BigFloat {
        let shift = prec + o.m.bits();
        BigFloat {
            m: (&self.m << shift) / &o.m,
            e: self.e - o.e - wide(shift),
        }
        .normalize(prec)
    }

    /// `base^s` by squaring, truncating to `prec` bits at every step. The relative error is
    /// below `2 s 2^-prec`: callers give `prec` about `2 log2 s` bits of headroom.
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
    fn top(&self) -> i128 {
        self.e + wide(self.m.bits())
    }

    /// An estimate of `floor(log10 |value|)` that is off by at most one, for any exponent.
    ///
    /// `log10 |value| = log10(t) + E log10(2)` with `t` the top 60 bits of the mantissa and
    /// `E` the exponent of its lowest bit. `E log10(2)` is computed exactly in integers from
    /// 60 decimal places of `log10(2)` (an `f64` product would be off by thousands once `E`
    /// reaches `10^19`); only the fractional parts, in `[0, 20)`, are added in `f64`.
    fn floor_log10_estimate(&self) -> i128 {
        let bits = self.m.bits();
        let shift = bits.saturating_sub(60);
        let top = (self.m.magnitude() >> shift)
            .to_f64()
            .unwrap_or(1.0)
            .max(1.0);
        let exponent = BigInt::from(self.e + wide(shift));
        let log2 = BigInt::parse_bytes(LOG10_2_DIGITS.as_bytes(), 10).unwrap_or_default();
        let scale = BigInt::from(10).pow(LOG10_2_SCALE);
        let (whole, frac) = (exponent * log2).div_mod_floor(&scale);
        let frac = frac.to_f64().unwrap_or(0.0) / scale.to_f64().unwrap_or(1.0);
        let whole = whole.to_i128().unwrap_or(0);
        // `top.log10() + frac` lies in [0, 20): its floor fits any integer type.
        whole + ((top.log10() + frac).floor() as i128)
    }

    /// `floor(|value|)` and whether the fractional part is closer than `2^-(slack)` relative
    /// to an integer boundary. A value too large to hold exactly counts as near a boundary.
    fn floor_abs(&self, eff_bits: u64) -> (BigInt, bool) {
        let mag = BigInt::from(self.m.magnitude().clone());
        if self.e >= 0 {
            return match shift_amount(self.e) {
                Some(sh) if sh <= 1 << 24 => (&mag << sh, true),
                _ => (BigInt::zero(), true),
            };
        }
        let Some(frac_bits) = shift_amount(-self.e) else {
            return (BigInt::zero(), true);
        };
        let int = &mag >> frac_bits;
        // Absolute error of the value in units of 2^-frac_bits: |value| * 2^-eff_bits.
        let err_shift = self.m.bits().saturating_sub(eff_bits);
        let err = BigInt::one() << err_shift;
        let frac = &mag - (&int << frac_bits);
        let one = BigInt::one() << frac_bits;
        let near = frac <= err || (&one - &frac) <= err;
        (int, near)
    }
}

/// The outcome of settling a digit count from an approximation.
enum Settled {
    /// The digit count and the leading `k` digits (the whole number if it has at most `k`).
    Known(u64, BigInt),
    /// Too close to a decimal boundary to call at this precision.
    Ambiguous,
    /// The number has more than `u64::MAX` decimal digits.
    BeyondU64,
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
    let ten_k = BigInt::from(10).pow(k);
    let trailing = &mag % &ten_k;
    let prec = 256u64 + 4 * k as u64;
    let approx = BigFloat::from_int(&mag, prec);
    let eff = prec - 2;
    let (digits, leading) = match digits_and_leading(&approx, eff, k, &trailing) {
        Settled::Known(digits, leading) => (digits, leading),
        // Ambiguous even so: settle with exact arithmetic. (A number held in memory has
        // fewer decimal digits than bits, so its count always fits in a `u64`.)
        Settled::Ambiguous | Settled::BeyondU64 => exact_digits_and_leading(&mag, &approx, k),
    };
    summary_from(negative, digits, &leading, &trailing, k)
}

/// The digit count and leading `k` digits of `mag >= 0` by exact comparison with powers of
/// ten, starting from `approx`'s estimate.
fn exact_digits_and_leading(mag: &BigInt, approx: &BigFloat, k: usize) -> (u64, BigInt) {
    let ten = BigInt::from(10);
    let mut d = u64::try_from(approx.floor_log10_estimate())
        .unwrap_or(0)
        .max(1);
    while *mag >= Pow::pow(&ten, d) {
        d += 1;
    }
    while d > 1 && *mag < Pow::pow(&ten, d - 1) {
        d -= 1;
    }
    let lead = if d <= k as u64 {
        mag.clone()
    } else {
        mag / Pow::pow(&ten, d - k as u64)
    };
    (d, lead)
}

fn summary_from(
    negative: bool,
    digits: u64,
    leading: &BigInt,
    trailing_mod: &BigInt,
    k: usize,
) -> DigitSummary {
    let shown = usize::try_from(digits).map_or(k, |d| d.min(k));
    DigitSummary {
        negative,
        digits,
        leading: if digits <= k as u64 {
            pad(trailing_mod, shown)
        } else {
            leading.to_string()
        },
        trailing: pad(trailing_mod, shown),
    }
}

/// The working precision for `10^q` next to a value with `eff` correct bits: powering by
/// squaring loses up to `2 log2 q` bits, which at `q` near `u64::MAX` is 128 bits.
fn power_precision(eff: u64, q: u64) -> u64 {
    eff + 16 + 2 * u64::from(64 - q.leading_zeros())
}

/// The digit count and the leading `k` digits of `|v|` from an approximation with `eff`
/// correct bits. `trailing` is `|v| mod 10^k`.
fn digits_and_leading(v: &BigFloat, eff: u64, k: usize, trailing: &BigInt) -> Settled {
    if v.m.is_zero() {
        return Settled::Known(1, BigInt::zero());
    }
    let v = v.abs();
    let ten = BigInt::from(10);
    let k64 = k as u64;
    // digits = floor(log10 v) + 1; the estimate is off by at most one, and the comparison
    // with 10^q settles it.
    let mut q = v.floor_log10_estimate().max(0);
    for _ in 0..4 {
        let Ok(q64) = u64::try_from(q) else {
            return Settled::BeyondU64;
        };
        let prec = power_precision(eff, q64);
        let ratio = v.div(&BigFloat::pow(&ten, q64, prec), prec);
        // ratio in [1, 10) means q is right.
        let (int, near) = ratio.floor_abs(eff.saturating_sub(4));
        if int.is_zero() {
            if near || q == 0 {
                return Settled::Ambiguous;
            }
            q -= 1;
            continue;
        }
        if int >= ten {
            if int == ten && near {
                return Settled::Ambiguous;
            }
            q += 1;
            continue;
        }
        if (int == BigInt::from(9) && near) || (int.is_one() && near && ratio.top() <= 1) {
            // Within error of exactly 10^(q+1) or 10^q.
            return Settled::Ambiguous;
        }
        let Some(digits) = q64.checked_add(1) else {
            return Settled::BeyondU64;
        };
        if digits <= k64 {
            return Settled::Known(digits, trailing.clone());
        }
        let j = digits - k64;
        let prec = power_precision(eff, j);
        let ten_j = BigFloat::pow(&ten, j, prec);
        let lead = v.div(&ten_j, prec);
        let (int, near) = lead.floor_abs(eff.saturating_sub(8 + 4 * k64));
        if !near {
            return Settled::Known(digits, int);
        }
        // The value sits within error of a multiple of 10^j: the trailing digits settle it
        // when they cover the whole fractional part.
        if j <= k64 {
            let low = trailing % Pow::pow(&ten, j);
            let frac = BigFloat::from_int(&low, prec).div(&ten_j, prec);
            let whole = lead.add(&frac.neg(), prec);
            // `whole` is within error of the integer floor(v / 10^j).
            let quarter = BigFloat {
                m: BigInt::one(),
                e: -2,
            };
            let (w, _) = whole.add(&quarter, prec).floor_abs(eff);
            return Settled::Known(digits, w);
        }
        return Settled::Ambiguous;
    }
    Settled::Ambiguous
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
    /// forms; [`Error::TooLarge`] for surd forms at levels too high to compute exactly;
    /// [`Error::DigitsOverflow`] for a count with more than `u64::MAX` decimal digits (an
    /// eigenvalue of 16 or more at a level near `u64::MAX`).
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
            out.push(self.rational_summary(i, fast, x0, s, k)?);
        }
        Ok(out)
    }

    /// The summary of component `i` (whose fast form is `fast`) from its integer
    /// eigenvalues, without materializing it.
    fn rational_summary(
        &self,
        i: usize,
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
        let ten_k = BigInt::from(10).pow(k);
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
            let mut max_top = i128::MIN;
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
                wide(prec)
            } else {
                (max_top - sum.top()).max(0)
            };
            let eff = wide(prec) - cancel - 16 - 2 * wide(u64::from(64 - s.leading_zeros()));
            let eff = u64::try_from(eff).unwrap_or(0);
            if eff >= 64 + 4 * k as u64 && !sum.m.is_zero() {
                let negative = v.m.is_negative();
                let trailing = if negative {
                    (&ten_k - &v_mod).mod_floor(&ten_k)
                } else {
                    v_mod.clone()
                };
                match digits_and_leading(&v, eff, k, &trailing) {
                    Settled::Known(digits, leading) => {
                        return Ok(summary_from(negative, digits, &leading, &trailing, k));
                    }
                    Settled::BeyondU64 => {
                        return Err(Error::DigitsOverflow {
                            component: self.names()[i].clone(),
                            level: s,
                        });
                    }
                    Settled::Ambiguous => {}
                }
            }
            if prec > 1 << 15 {
                // Heavy cancellation or a value sitting on a decimal boundary: the value is
                // small compared to its terms, so compute it exactly if that is affordable.
                let est = self.evaluate_bits_estimate(&parts, s);
                if est <= 4_000_000 {
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
        let d = form.rational_summary(0, f, &x0, 5000, 20).unwrap();
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
                        form.rational_summary(i, f, &x0, s, 20).unwrap()
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

    #[test]
    fn levels_near_u64_max_are_exact() {
        // Reference values from 120-digit decimal logarithms: E = 30 * 4^s, V = 10 * 4^s + 2.
        let r = Recurrence::new("[[1,1],[0,4]]".parse::<IntMatrix>().unwrap());
        let form = r.closed_form();
        let x0 = [BigInt::from(12), BigInt::from(30)];
        for (s, v, e) in [
            (
                u64::MAX,
                (
                    11_106_046_577_046_714_265,
                    "90913747023371454768",
                    "24151468139730698242",
                ),
                (
                    11_106_046_577_046_714_266,
                    "27274124107011436430",
                    "72454404419192094720",
                ),
            ),
            (
                u64::MAX - 1,
                (
                    11_106_046_577_046_714_265,
                    "22728436755842863692",
                    "81037867034932674562",
                ),
                (
                    11_106_046_577_046_714_265,
                    "68185310267528591076",
                    "43113601104798023680",
                ),
            ),
            (
                i64::MAX as u64,
                (
                    5_553_023_288_523_357_133,
                    "47674350290111834613",
                    "47519667428618403842",
                ),
                (
                    5_553_023_288_523_357_134,
                    "14302305087033550384",
                    "42559002285855211520",
                ),
            ),
        ] {
            let at = form.summary_at(&x0, s, 20).unwrap();
            for (got, (digits, leading, trailing)) in at.iter().zip([v, e]) {
                let want = DigitSummary {
                    negative: false,
                    digits,
                    leading: leading.into(),
                    trailing: trailing.into(),
                };
                assert_eq!(*got, want, "level {s}");
            }
        }
    }

    #[test]
    fn digit_counts_beyond_u64_are_refused() {
        // 16^s has about 1.2 s digits: beyond u64::MAX at s = u64::MAX.
        let r = Recurrence::with_names("[[16]]".parse::<IntMatrix>().unwrap(), ["F"]).unwrap();
        let err = r
            .closed_form()
            .summary_at(&[BigInt::one()], u64::MAX, 20)
            .unwrap_err();
        assert_eq!(
            err,
            Error::DigitsOverflow {
                component: "F".into(),
                level: u64::MAX
            }
        );
        assert_eq!(
            err.to_string(),
            "the count `F` at level 18446744073709551615 has more than 2^64 decimal digits, more than a digit summary can state"
        );
    }

    /// `floor(n log10 2)`, from 80 decimal places of `log10 2` (an interval of width
    /// `n 10^-80`), or `None` if an integer falls inside the interval.
    fn floor_n_log10_2(n: u128) -> Option<BigInt> {
        let digits =
            "30102999566398119521373889472449302676818988146210854131042746112710818927442451";
        let lo = BigInt::parse_bytes(digits.as_bytes(), 10).unwrap();
        let scale = BigInt::from(10).pow(80u32);
        let n = BigInt::from(n);
        let a = (&n * &lo).div_floor(&scale);
        let b = (&n * (lo + BigInt::one())).div_floor(&scale);
        (a == b).then_some(a)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 48, failure_persistence: None, ..Default::default() })]

        #[test]
        fn digit_counts_near_u64_max_match_exact_logarithms(
            log_lambda in 1u32..=3,
            a in 0u32..6,
            b in 0u32..12,
            s in proptest::prop_oneof![(u64::MAX - (1 << 40))..=u64::MAX, (1u64 << 62)..=u64::MAX],
        ) {
            // x(s) = 10^a 2^b lambda^s with lambda = 2^log_lambda: 10^a 2^(b + log_lambda s).
            let lambda = 1i64 << log_lambda;
            let r = Recurrence::new(IntMatrix::try_from_rows(vec![vec![lambda]]).unwrap());
            let c = BigInt::from(10).pow(a) << b;
            let got = r.closed_form().summary_at(std::slice::from_ref(&c), s, 20).unwrap();
            let n = u128::from(b) + u128::from(log_lambda) * u128::from(s);
            let Some(floor) = floor_n_log10_2(n) else {
                return Err(proptest::test_runner::TestCaseError::reject("on a boundary"));
            };
            let digits = floor + 1 + a;
            proptest::prop_assert_eq!(BigInt::from(got[0].digits), digits);
            let m = BigInt::from(10).pow(20u32);
            let trailing = (BigInt::from(lambda).modpow(&BigInt::from(s), &m) * &c) % &m;
            proptest::prop_assert_eq!(&got[0].trailing, &format!("{trailing:0>20}"));
            proptest::prop_assert_eq!(got[0].leading.len(), 20);
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
                proptest::prop_assert_eq!(form.rational_summary(i, f, &x0, s, k).unwrap(), brute(&exact[i], k));
            }
        }
    }
}
