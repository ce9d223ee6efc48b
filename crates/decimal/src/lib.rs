//! Decimal text of big integers in subquadratic time: exactly num-bigint's `to_string`,
//! faster for numbers of hundreds of thousands of digits.
//!
//! num-bigint 0.4 converts to decimal by a divide and conquer whose divisions are schoolbook,
//! so its time grows quadratically with the number of digits: the 602,062-digit edge count of
//! Catmull-Clark at level `10^6` takes it about 150 ms, most of what `subcount at` spends
//! printing it. This crate gives the same text (the same digits, a `-` for negative numbers,
//! `0` for zero) through three entry points:
//!
//! - [`to_decimal`] returns a `String`;
//! - [`write_decimal`] writes into any [`std::fmt::Write`], a few dozen digits at a time;
//! - [`Decimal`] formats with `format!` and `write!`, widths and flags as the integer's own
//!   `Display` takes them, and streams into an [`std::io::Write`] without building the string.
//!
//! # Why a crate of its own
//!
//! Measured against the alternatives on a 601,173-digit number (issue 10): num-bigint's
//! `to_string` 149 ms, dashu 178 ms, ibig 219 ms, this crate 84-91 ms. The other big-integer
//! crates do not beat it, so the conversion stays; it lives here, apart from `recurrence`
//! (which is about recurrences), with its own benchmark against num-bigint
//! (`cargo bench -p decimal --bench to_decimal`; the figures are in BENCHMARKS.md).
//! It depends on num-bigint (and the num-traits and num-integer crates under it) only.
//!
//! # Example
//!
//! ```
//! use std::io::Write;
//! use num_bigint::BigInt;
//! use decimal::{to_decimal, Decimal};
//!
//! // 190,849 digits: past the size up to which num-bigint's own conversion is used.
//! let n = BigInt::from(3).pow(400_000u32);
//! let text = to_decimal(&n);
//! assert_eq!(text.len(), 190_849);
//! assert_eq!(text, n.to_string());
//!
//! let mut out: Vec<u8> = Vec::new();
//! write!(out, "F = {}", Decimal::from(&-&n))?;
//! assert_eq!(out, format!("F = -{text}").into_bytes());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # How
//!
//! The number is split recursively, `n = q 10^w + r`, along a tree of powers `10^(k 2^i)`,
//! down to leaves of at most 32,000 digits that num-bigint converts (zero-padded):
//!
//! - a power of ten `10^w = 5^w 2^w` divides as a shift and a division by `5^w`, which has
//!   30 % fewer bits;
//! - at the large levels the quotient comes from a Newton reciprocal of `5^w` (each level's
//!   from the square of the level below's and one Newton step) and two multiplications,
//!   then is corrected by a few units; the remainder needs `q 5^w` only modulo
//!   `2^(64 L) - 1`, a product half as long; products of 500 limbs and more use
//!   number-theoretic transforms (three 62-bit primes), since num-bigint's Toom-3 is what
//!   would dominate, and the transforms of `5^w` and its reciprocal are computed once per
//!   level;
//! - small levels use num-bigint's own division.
//!
//! Numbers of up to 160,000 digits go to num-bigint directly: its conversion is faster there,
//! and the Newton levels win only from a few hundred thousand digits on (see BENCHMARKS.md).
//! The thresholds (the private `Tuning::DEFAULT`) were measured on a 2-core AMD EPYC; the unit
//! tests run small ones so that every path meets small numbers.
#![deny(missing_docs)]

mod ntt;

use std::fmt;

use num_bigint::Sign;
/// The integer types the conversions take, re-exported so that a caller needs no second
/// dependency to name them.
pub use num_bigint::{BigInt, BigUint};
use num_traits::{ToPrimitive, Zero};

/// log10 of a positive integer, from its bit length and leading 64 bits (no overflow at any
/// size); `None` for zero and negative values, which a log scale cannot show.
pub fn log10(v: &BigInt) -> Option<f64> {
    if v.sign() != Sign::Plus {
        return None;
    }
    let bits = v.bits();
    let shift = bits.saturating_sub(64);
    let top = (v.magnitude() >> shift).to_u64()?;
    // `top` has at most 64 bits; f64 keeps its leading 53.
    Some((top as f64).log10() + shift as f64 * std::f64::consts::LOG10_2)
}

/// The decimal digits of `n`, exactly as `n.to_string()` gives them, in subquadratic time.
///
/// ```
/// use num_bigint::BigInt;
/// use decimal::to_decimal;
///
/// let n = BigInt::from(3).pow(100_000u32); // 47,713 digits
/// let text = to_decimal(&n);
/// assert_eq!(text.len(), 47_713);
/// assert_eq!(text, n.to_string());
///
/// let nines = BigInt::from(10).pow(50_000u32) - 1;
/// assert_eq!(to_decimal(&nines), "9".repeat(50_000));
/// assert_eq!(to_decimal(&BigInt::from(-42)), "-42");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn to_decimal(n: &BigInt) -> String {
    let mut out = String::with_capacity(decimal_digits_bound(n.magnitude()) as usize + 1);
    // Writing into a String cannot fail.
    let _ = write_decimal(&mut out, n);
    out
}

/// Writes the decimal digits of `n` (as [`to_decimal`] gives them) into `out`, a few dozen
/// digits at a time, without building the whole string.
///
/// For an [`std::io::Write`], use [`Decimal`] with `write!`.
///
/// # Errors
///
/// Whatever `out` returns.
///
/// ```
/// use num_bigint::BigInt;
/// use decimal::write_decimal;
///
/// let mut text = String::from("F = ");
/// write_decimal(&mut text, &(BigInt::from(20) << 200u32))?;
/// assert_eq!(text, "F = 32138760885179805510839241846823252050444059875655856706027520");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_decimal<W: fmt::Write + ?Sized>(out: &mut W, n: &BigInt) -> fmt::Result {
    if n.sign() == Sign::Minus {
        out.write_char('-')?;
    }
    write_magnitude(out, n.magnitude())
}

/// A big integer to format in decimal with the fast conversion: `format!("{}", ..)` and
/// `write!` give the same text as the integer's own `Display`, widths and `+` flags
/// included.
///
/// Without a width, the digits stream into the formatter piece by piece, so writing to an
/// [`std::io::Write`] builds no copy of the number.
///
/// ```
/// use std::io::Write;
/// use num_bigint::{BigInt, BigUint};
/// use decimal::Decimal;
///
/// let n = BigInt::from(7).pow(5000u32);
/// let mut out: Vec<u8> = Vec::new();
/// write!(out, "{}", Decimal::from(&n))?;
/// assert_eq!(out, n.to_string().into_bytes());
///
/// let small = BigUint::from(1234u32);
/// assert_eq!(format!("[{:>6}]", Decimal::from(&small)), "[  1234]");
/// assert_eq!(format!("{:+}", Decimal::from(&BigInt::from(-5))), "-5");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Decimal<'a> {
    negative: bool,
    magnitude: &'a BigUint,
}

impl<'a> From<&'a BigInt> for Decimal<'a> {
    fn from(n: &'a BigInt) -> Self {
        Decimal {
            negative: n.sign() == Sign::Minus,
            magnitude: n.magnitude(),
        }
    }
}

impl<'a> From<&'a BigUint> for Decimal<'a> {
    fn from(n: &'a BigUint) -> Self {
        Decimal {
            negative: false,
            magnitude: n,
        }
    }
}

impl fmt::Display for Decimal<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if f.width().is_none() && !f.sign_plus() && !f.sign_aware_zero_pad() {
            if self.negative {
                f.write_str("-")?;
            }
            return write_magnitude(f, self.magnitude);
        }
        let mut digits = String::with_capacity(decimal_digits_bound(self.magnitude) as usize);
        write_magnitude(&mut digits, self.magnitude)?;
        f.pad_integral(!self.negative, "", &digits)
    }
}

/// An upper bound on the number of decimal digits of `n`: `ceil(bits log10 2)`, at least 1.
fn decimal_digits_bound(n: &BigUint) -> u64 {
    // 30103 / 100000 > log10(2), so this never undercounts.
    (n.bits() * 30_103).div_ceil(100_000).max(1)
}

/// The thresholds of the conversion. [`Tuning::DEFAULT`] was measured on a 2-core AMD EPYC
/// (see BENCHMARKS.md); the tests run small ones so every path meets small numbers.
#[derive(Clone, Copy, Debug)]
struct Tuning {
    /// Leaves have at most this many digits (and more than half as many).
    leaf_max_digits: u64,
    /// Levels of at least this many digits divide with Newton reciprocals; smaller ones with
    /// num-bigint's schoolbook division.
    newton_min_digits: u64,
    /// Numbers of at most this many digits go to num-bigint directly.
    direct_max_digits: u64,
    /// Products whose shorter operand has at least this many 64-bit limbs use transforms.
    ntt_min_limbs: usize,
}

impl Tuning {
    const DEFAULT: Tuning = Tuning {
        leaf_max_digits: 32_000,
        newton_min_digits: 12_000,
        direct_max_digits: 160_000,
        ntt_min_limbs: 500,
    };
}

fn write_magnitude<W: fmt::Write + ?Sized>(out: &mut W, n: &BigUint) -> fmt::Result {
    write_magnitude_tuned(out, n, Tuning::DEFAULT)
}

fn write_magnitude_tuned<W: fmt::Write + ?Sized>(
    out: &mut W,
    n: &BigUint,
    tuning: Tuning,
) -> fmt::Result {
    let digits = decimal_digits_bound(n);
    if digits <= tuning.direct_max_digits.max(tuning.leaf_max_digits) {
        return match n.to_u128() {
            Some(v) => write!(out, "{v}"),
            None => write!(out, "{n}"),
        };
    }
    let tree = PowerTree::new(digits, tuning);
    let mut writer = DigitWriter { out, tree: &tree };
    writer.write(n, tree.levels.len() - 1, false)
}

/// Powers `10^(w_i)`, `w_i = k 2^i`, for the splits, with what each level's division needs.
struct PowerTree {
    /// Leaf width `k` in digits (at most [`Tuning::leaf_max_digits`]).
    leaf_digits: u64,
    tuning: Tuning,
    levels: Vec<Level>,
}

/// One level of the tree: numbers below `10^(2w)` split into two halves of `w` digits.
struct Level {
    /// `w`, the number of digits of the lower half.
    digits: u64,
    /// `5^w`.
    five: BigUint,
    /// For the Newton levels: `V ~ 2^(bits(5^w) + precision) / 5^w`.
    reciprocal: Option<Reciprocal>,
}

struct Reciprocal {
    value: BigUint,
    precision: u64,
    /// Transforms of `V` and `5^w` shared by the level's splits, for levels large enough.
    transforms: Option<LevelTransforms>,
}

struct LevelTransforms {
    /// `V` at a length that holds `(n >> t) V` whole.
    reciprocal: ntt::Transform,
    /// `5^w` at a length `L` with `2^(64 L) > 2^64 5^w`, for `q 5^w mod (2^(64 L) - 1)`.
    five: ntt::Transform,
    /// `2^(64 L) - 1`.
    modulus: BigUint,
}

impl Reciprocal {
    /// The reciprocal of `five = 5^w` for quotients below `10^w`, with transforms when
    /// `5^w` has at least `transform_min_limbs` limbs. With the level below (`5^(w/2)` and
    /// its reciprocal), one Newton step from the square of that reciprocal suffices.
    fn new(
        five: &BigUint,
        w: u64,
        below: Option<(&BigUint, &Reciprocal)>,
        transform_min_limbs: usize,
    ) -> Reciprocal {
        let precision = bits_of_pow10(w) + RECIPROCAL_GUARD_BITS;
        let value = match below {
            Some((five_below, r)) if 2 * five_below.bits() - five.bits() <= 1 => {
                // V'^2 ~ 2^(2 f' + 2 p') / 5^w with relative error ~2^(1 - p'): as an
                // approximation of 2^(f + h) / 5^w, h = p' - 2.
                let (f_below, p_below) = (five_below.bits(), r.precision);
                let h = p_below - 2;
                let square = ntt_aware_mul(&r.value, &r.value, transform_min_limbs);
                let v = square >> (2 * f_below + 2 * p_below - five.bits() - h);
                newton_step(five, v, h, precision, transform_min_limbs)
            }
            _ => reciprocal(five, precision, transform_min_limbs),
        };
        let transforms = (ntt::limbs(five) >= transform_min_limbs).then(|| {
            // n < 10^(2w): n >> w >> (bits(5^w) - 1) has at most this many bits.
            let top_bits = bits_of_pow10(2 * w) - w - (five.bits() - 1) + 1;
            let top_limbs = top_bits.div_ceil(64) as usize;
            let q_len = ntt::transform_len(top_limbs + ntt::limbs(&value));
            let r_len = ntt::transform_len(ntt::limbs(five) + 1);
            LevelTransforms {
                reciprocal: ntt::Transform::new(&value, q_len),
                five: ntt::Transform::new(five, r_len),
                modulus: (BigUint::from(1u32) << (64 * r_len as u64)) - 1u32,
            }
        });
        Reciprocal {
            value,
            precision,
            transforms,
        }
    }
}

impl PowerTree {
    /// The tree for numbers of at most `digits` digits.
    fn new(digits: u64, tuning: Tuning) -> PowerTree {
        // Smallest number of levels m + 1 with ceil(digits / 2^(m+1)) <= leaf_max_digits.
        let mut levels = 1u32;
        while digits.div_ceil(1 << levels) > tuning.leaf_max_digits {
            levels += 1;
        }
        let leaf_digits = digits.div_ceil(1 << levels);
        let mut out: Vec<Level> = Vec::with_capacity(levels as usize);
        for i in 0..levels {
            let w = leaf_digits << i;
            let five = match out.last() {
                None => BigUint::from(5u32).pow(w as u32),
                Some(prev) => ntt_aware_mul(&prev.five, &prev.five, tuning.ntt_min_limbs),
            };
            let below = out
                .last()
                .and_then(|l| l.reciprocal.as_ref().map(|r| (&l.five, r)));
            let reciprocal = (w >= tuning.newton_min_digits)
                .then(|| Reciprocal::new(&five, w, below, tuning.ntt_min_limbs));
            out.push(Level {
                digits: w,
                five,
                reciprocal,
            });
        }
        PowerTree {
            leaf_digits,
            tuning,
            levels: out,
        }
    }
}

/// `bits(10^w)` bound: `ceil(w log2 10)` (never an undercount).
fn bits_of_pow10(w: u64) -> u64 {
    // 332193 / 100000 > log2(10) = 3.3219280...
    (w * 332_193).div_ceil(100_000) + 1
}

struct DigitWriter<'a, W: ?Sized> {
    out: &'a mut W,
    tree: &'a PowerTree,
}

impl<W: fmt::Write + ?Sized> DigitWriter<'_, W> {
    /// Writes `n < 10^(2 w_level)`; `pad` writes exactly `2 w_level` digits.
    fn write(&mut self, n: &BigUint, level: usize, pad: bool) -> fmt::Result {
        let lvl = &self.tree.levels[level];
        if !pad && decimal_digits_bound(n) <= self.tree.tuning.leaf_max_digits {
            return self.leaf(n, 0, false);
        }
        let (q, r) = split(n, lvl, self.tree.tuning.ntt_min_limbs);
        if level == 0 {
            if !pad && q.is_zero() {
                return self.leaf(&r, 0, false);
            }
            self.leaf(&q, self.tree.leaf_digits, pad)?;
            return self.leaf(&r, self.tree.leaf_digits, true);
        }
        if pad || !q.is_zero() {
            self.write(&q, level - 1, pad)?;
            self.write(&r, level - 1, true)
        } else {
            self.write(&r, level - 1, false)
        }
    }

    /// Writes `n` with num-bigint's own conversion (quadratic, but the fastest for a few
    /// thousand digits), zero-padded to `width` digits if `pad`.
    fn leaf(&mut self, n: &BigUint, width: u64, pad: bool) -> fmt::Result {
        if pad {
            write!(self.out, "{n:0width$}", width = width as usize)
        } else {
            write!(self.out, "{n}")
        }
    }
}

/// `(q, r)` with `n = q 10^w + r`, `0 <= r < 10^w`, for `n < 10^(2w)`.
fn split(n: &BigUint, lvl: &Level, ntt_min_limbs: usize) -> (BigUint, BigUint) {
    let w = lvl.digits;
    let high = n >> w;
    let (q, r_high) = match &lvl.reciprocal {
        Some(recip) => div_newton(&high, &lvl.five, recip, ntt_min_limbs),
        None => num_integer::Integer::div_rem(&high, &lvl.five),
    };
    let r = (r_high << w) | low_bits(n, w);
    (q, r)
}

/// `n mod 2^k`.
fn low_bits(n: &BigUint, k: u64) -> BigUint {
    let words = k.div_ceil(32) as usize;
    let mut digits: Vec<u32> = n.iter_u32_digits().take(words).collect();
    if let Some(last) = digits.get_mut(words.wrapping_sub(1)) {
        let rem = k % 32;
        if rem != 0 {
            *last &= (1u32 << rem) - 1;
        }
    }
    BigUint::new(digits)
}

/// `a b`, by transforms when both have at least `ntt_min_limbs` limbs.
fn ntt_aware_mul(a: &BigUint, b: &BigUint, ntt_min_limbs: usize) -> BigUint {
    if ntt::limbs(a).min(ntt::limbs(b)) >= ntt_min_limbs {
        ntt::mul(a, b)
    } else {
        a * b
    }
}

/// `V ~ 2^(bits(d) + p) / d` with a relative error of a few `2^-p`.
fn reciprocal(d: &BigUint, p: u64, ntt_min_limbs: usize) -> BigUint {
    let f = d.bits();
    if f > p + 64 {
        // Only the leading p + 64 bits of d matter.
        return reciprocal(&(d >> (f - p - 64)), p, ntt_min_limbs);
    }
    if p <= 4_096 {
        return (BigUint::from(1u32) << (f + p)) / d;
    }
    let h = p.div_ceil(2) + 32;
    newton_step(d, reciprocal(d, h, ntt_min_limbs), h, p, ntt_min_limbs)
}

/// Guard bits of a level's reciprocal beyond the quotient's bits: enough for
/// [`newton_step`] from the square of the level below (`p <= 2 (p' - 2) - 64`).
const RECIPROCAL_GUARD_BITS: u64 = 80;

/// One Newton step `v (1 + e / 2^(f+h))`, `e = 2^(f+h) - d v`: from `v ~ 2^(f + h) / d`
/// with a relative error of a few `2^-h` to `~2^(f + p) / d` with a few `2^-p`, for
/// `p <= 2h - 64` (`f = bits(d)`).
fn newton_step(d: &BigUint, v: BigUint, h: u64, p: u64, ntt_min_limbs: usize) -> BigUint {
    debug_assert!(p + 64 <= 2 * h, "precision {p} from {h}");
    let f = d.bits();
    if f > p + 64 {
        // Only the leading p + 64 bits of d matter; v approximates the truncated quotient
        // 2^((f - s) + h) / (d >> s) just as well.
        return newton_step(&(d >> (f - p - 64)), v, h, p, ntt_min_limbs);
    }
    // |e| ~ d |v - 2^(f+h)/d| is below 2^(f + 8) or so: for big d it follows from d v
    // modulo M = 2^(64 L) - 1 with L > limbs(d), half the product's length.
    let d_limbs = ntt::limbs(d);
    let len = ntt::transform_len(d_limbs + 1);
    let (e, e_negative) = if d_limbs >= ntt_min_limbs && d_limbs + ntt::limbs(&v) > len {
        let modulus = (BigUint::from(1u32) << (64 * len as u64)) - 1u32;
        let dv = ntt::mul_cyclic(&v, &ntt::Transform::new(d, len));
        let one = BigUint::from(1u32) << ((f + h) % (64 * len as u64));
        let e = if one >= dv {
            one - dv
        } else {
            one + &modulus - dv
        };
        if e > (&modulus >> 1u32) {
            (modulus - e, true)
        } else {
            (e, false)
        }
    } else {
        let dv = ntt_aware_mul(d, &v, ntt_min_limbs);
        let one = BigUint::from(1u32) << (f + h);
        if one >= dv {
            (one - dv, false)
        } else {
            (dv - one, true)
        }
    };
    // The correction v e / 2^(f + 2h - p) needs only ~h + 64 leading bits of e.
    let cut = e.bits().saturating_sub(h + 64);
    let e = e >> cut;
    let shift = (f + 2 * h - p) - cut;
    let correction = ntt_aware_mul(&v, &e, ntt_min_limbs) >> shift;
    let base = v << (p - h);
    if e_negative {
        base - correction
    } else {
        base + correction
    }
}

/// `(n / d, n mod d)` for a quotient below `2^(recip.precision - 64)`, from the reciprocal
/// of `d`, corrected to the exact values.
fn div_newton(
    n: &BigUint,
    d: &BigUint,
    recip: &Reciprocal,
    ntt_min_limbs: usize,
) -> (BigUint, BigUint) {
    let f = d.bits();
    // q ~ n V / 2^(f + p); dropping the low f - 1 bits of n costs less than one unit.
    let t = f - 1;
    let top = n >> t;
    let shift = f + recip.precision - t;
    let Some(tr) = &recip.transforms else {
        let mut q = ntt_aware_mul(&top, &recip.value, ntt_min_limbs) >> shift;
        let mut qd = ntt_aware_mul(&q, d, ntt_min_limbs);
        while qd > *n {
            q -= 1u32;
            qd -= d;
        }
        let mut r = n - qd;
        while r >= *d {
            q += 1u32;
            r -= d;
        }
        return (q, r);
    };
    let product = if ntt::limbs(&top) + ntt::limbs(&recip.value) <= tr.reciprocal.len() {
        ntt::mul_cyclic(&top, &tr.reciprocal)
    } else {
        ntt::mul(&top, &recip.value)
    };
    let mut q = product >> shift;
    // r = n - q d is within a few d of [0, d), far less than M / 2 (M = 2^(64 L) - 1), so
    // it follows from n - q d mod M.
    let qd = ntt::mul_cyclic(&q, &tr.five);
    let nm = ntt::wrap(n.clone(), tr.five.len());
    let r_mod = if nm >= qd {
        nm - qd
    } else {
        nm + &tr.modulus - qd
    };
    let mut r = if r_mod > (&tr.modulus >> 1u32) {
        // negative: r = r_mod - M; step q down until r >= 0
        let mut deficit = &tr.modulus - r_mod;
        loop {
            q -= 1u32;
            if deficit <= *d {
                break d - deficit;
            }
            deficit -= d;
        }
    } else {
        r_mod
    };
    while r >= *d {
        q += 1u32;
        r -= d;
    }
    (q, r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::One;

    /// `log10(v)` is `want` within `tolerance`.
    fn log10_is(v: BigInt, want: f64, tolerance: f64) {
        let l = log10(&v).unwrap();
        assert!((l - want).abs() < tolerance, "{l}, not {want}");
    }

    #[test]
    fn log10_of_small_and_huge_counts() {
        assert_eq!(log10(&BigInt::from(1)), Some(0.0));
        assert_eq!(log10(&BigInt::from(0)), None);
        assert_eq!(log10(&BigInt::from(-5)), None);
        log10_is(BigInt::from(1000), 3.0, 1e-12);
        log10_is(BigInt::from(u64::MAX), 19.265_919_722_494_8, 1e-9);
        // 10^5000, 3 * 10^5000 and 2^100000: far beyond f64, exact to the plot's resolution.
        let big = BigInt::from(10).pow(5000u32);
        log10_is(big.clone(), 5000.0, 1e-9);
        log10_is(big * 3, 5000.0 + 3f64.log10(), 1e-9);
        let log = 100_000.0 * std::f64::consts::LOG10_2;
        log10_is(BigInt::from(2).pow(100_000u32), log, 1e-6);
        // Digit count agrees: floor(log10 n) + 1.
        let n: BigInt = BigInt::from(20) * BigInt::from(4).pow(1000u32);
        let digits = n.to_string().len() as f64;
        assert_eq!(log10(&n).unwrap().floor() + 1.0, digits);
    }

    /// Small thresholds, so numbers of a few hundred digits already take every path: the
    /// tree, Newton levels built from scratch (`SMALL`) or from the level below, transforms
    /// at every size, and the modular remainders.
    const SMALL: Tuning = Tuning {
        leaf_max_digits: 40,
        newton_min_digits: 150,
        direct_max_digits: 0,
        ntt_min_limbs: 4,
    };
    const SMALL_LATE_NEWTON: Tuning = Tuning {
        newton_min_digits: 1_500,
        ..SMALL
    };
    const SMALL_SCHOOLBOOK: Tuning = Tuning {
        newton_min_digits: u64::MAX,
        ..SMALL
    };

    fn check(n: &BigUint) {
        let expected = n.to_string();
        for tuning in [SMALL, SMALL_LATE_NEWTON, SMALL_SCHOOLBOOK, Tuning::DEFAULT] {
            let mut got = String::new();
            write_magnitude_tuned(&mut got, n, tuning).unwrap();
            assert_eq!(got, expected, "{} bits, {tuning:?}", n.bits());
        }
    }

    #[test]
    fn small_thresholds_edge_cases() {
        for k in (0..130).chain([150, 151, 299, 300, 301, 640, 641, 1_280, 2_560, 5_000]) {
            let p = BigUint::from(10u32).pow(k);
            check(&p);
            check(&(&p + 1u32));
            if k > 0 {
                check(&(&p - 1u32));
            }
        }
        for bits in [
            1, 63, 64, 65, 127, 128, 129, 1_000, 4_097, 10_000, 33_219, 33_220,
        ] {
            let p = BigUint::one() << bits;
            check(&p);
            check(&(p - 1u32));
        }
        check(&BigUint::zero());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig {
            cases: 32,
            failure_persistence: None,
            ..proptest::prelude::ProptestConfig::default()
        })]

        #[test]
        fn small_thresholds_agree_with_num_bigint(
            bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..6_000),
        ) {
            check(&BigUint::from_bytes_le(&bytes));
        }

        #[test]
        fn small_thresholds_on_runs_of_zeros_and_nines(
            a in 1u32..8_000,
            b in 1u32..8_000,
            c in 1u32..10,
        ) {
            // 10^a + c 10^b - 1 and 10^a + c 10^b + 1: long runs of 0s and 9s.
            let n = BigUint::from(10u32).pow(a.max(b) + 1) + BigUint::from(c) * BigUint::from(10u32).pow(a.min(b));
            check(&(&n - 1u32));
            check(&(&n + 1u32));
        }
    }

    #[test]
    fn ntt_products_match_num_bigint() {
        for (a, b) in [
            (3u32, 20_000u32),
            (7, 30_000),
            (10, 40_000),
            (2, 64 * 2048 - 1),
        ] {
            let x = BigUint::from(a).pow(b);
            let y = BigUint::from(b + 17).pow(b / 3) - 1u32;
            assert_eq!(ntt::mul(&x, &y), &x * &y, "{a}^{b}");
            assert_eq!(ntt::mul(&x, &x), &x * &x, "{a}^{b} squared");
        }
        let max = (BigUint::one() << (64 * 3000)) - 1u32;
        assert_eq!(ntt::mul(&max, &max), &max * &max);
        let one = BigUint::one();
        assert_eq!(ntt::mul(&max, &one), max);
        assert_eq!(ntt::mul(&max, &BigUint::zero()), BigUint::zero());
    }

    #[test]
    fn reciprocal_within_a_few_units() {
        let d = BigUint::from(5u32).pow(40_000u32);
        for p in [100, 5_000, 20_000, 150_000] {
            let v = reciprocal(&d, p, 8);
            let exact = (BigUint::one() << (d.bits() + p)) / &d;
            let diff = if v > exact { &v - &exact } else { &exact - &v };
            assert!(diff <= BigUint::from(4u32), "p = {p}: off by {diff}");
        }
    }

    #[test]
    fn newton_division_is_exact() {
        let w = 30_000u64;
        let five = BigUint::from(5u32).pow(w as u32);
        let ten_w = BigUint::from(10u32).pow(w as u32);
        for n in [
            BigUint::zero(),
            &five - 1u32,
            five.clone(),
            &ten_w - 1u32,
            BigUint::from(3u32).pow(60_000u32) >> w,
            (&ten_w * &ten_w - 1u32) >> w,
        ] {
            let expected = (&n / &five, &n % &five);
            for transform_min_limbs in [0, usize::MAX] {
                let recip = Reciprocal::new(&five, w, None, transform_min_limbs);
                assert_eq!(recip.transforms.is_some(), transform_min_limbs == 0);
                assert_eq!(div_newton(&n, &five, &recip, 8), expected);
            }
        }
    }
}
