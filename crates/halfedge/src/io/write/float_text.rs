//! The text of a coordinate: byte for byte what `{:?}` writes for an `f32` or `f64` (the
//! shortest digits that read back as the same value, the nearest of them to the value;
//! `0.000123`, `1.0`, `1e-5`, `1e16`), several times faster.
//!
//! The digits come from `zmij` (Schubfach: shortest, and of the shortest the nearest, like
//! std's Grisu with its Dragon fallback), which lays them out its own way (`0.00001`, `1e+16`)
//! and breaks an exact tie between two nearest candidates to even where std rounds the other
//! way (`f32` `-30619.0625`: `-30619.062` against std's `-30619.063`). So:
//!
//! - Between `1e-4` and `1e16` (std's decimal layout, compared in the value's own type as
//!   std compares) `zmij`'s decimal text is std's text and is copied; elsewhere (and where
//!   `zmij` writes an exponent std does not: `f32` from `1e13`) its digits and exponent are
//!   read back and laid out as std lays them out (`d.ddde-N`, `de16`, `ddd0000.0`).
//! - A tie is possible only when the value is exactly halfway between two candidates one unit
//!   of the last digit apart, so when its exact decimal expansion ends one place after the
//!   last digit written. A test on the bits rules that out for almost every coordinate
//!   (`may_tie_at_all`: the expansion of `m * 2^-k` has `digits(m * 5^k)` significant
//!   digits, at most one more than a shortest text can have); what it does not rule out is
//!   checked on the text: the value is `odd * 2^e` with `e == -(fraction digits + 1)` (a value
//!   `(2j + 1) * 5 * 10^-(t + 1)` has exactly that power of two). Those values are written by
//!   std's own `{:?}`, as are NaN and the infinities (which the writers never meet: positions
//!   are checked finite).
//!
//! `tests::matches_std_on_random_bits` and `tests::matches_std_on_edge_values` compare the
//! two on millions of bit patterns of both types; `tests::matches_std_on_every_f32` (ignored,
//! minutes in release) on all of `f32`.

use std::io::Write;

use crate::Scalar;

/// Appends the text `{:?}` gives `x` (in `T`'s precision) to `out`.
#[inline]
pub(crate) fn push<T: Scalar>(out: &mut Vec<u8>, x: T) {
    // `Scalar` is `f32` or `f64`, and `to_f64` is exact: an `f32` comes back unchanged.
    if std::mem::size_of::<T>() == 4 {
        push_float(out, x.to_f64() as f32);
    } else {
        push_float(out, x.to_f64());
    }
}

/// The eight decimal digits of `n < 10^8`, one per byte (not ASCII: 0 to 9), the most
/// significant first in memory (little-endian), split lane by lane with multiplications.
#[inline]
fn digits8(n: u32) -> u64 {
    // Two 4-digit halves in 32-bit lanes, then 2-digit quarters in 16-bit lanes, then digits
    // in bytes; each quotient by a multiplication exact in its lane's range.
    let x = u64::from(n / 10_000) | (u64::from(n % 10_000) << 32);
    let hundreds = ((x * 5243) >> 19) & 0x0000_007f_0000_007f;
    let x = hundreds | ((x - hundreds * 100) << 16);
    let tens = ((x * 103) >> 10) & 0x000f_000f_000f_000f;
    tens | ((x - tens * 10) << 8)
}

/// ASCII `'0'` in every byte.
const ASCII_ZEROS: u64 = 0x3030_3030_3030_3030;

/// Appends `n`'s decimal text: eight digits at a time computed in a register, stored whole
/// and cut back to the digits there are (no loop, no copy of variable length).
#[inline]
pub(crate) fn push_u64(out: &mut Vec<u8>, n: u64) {
    match u32::try_from(n) {
        Ok(n) if n < 100_000_000 => push_below_1e8(out, n),
        _ => push_large(out, n),
    }
}

/// [`push_u64`] of `n < 10^8`.
#[inline(always)]
fn push_below_1e8(out: &mut Vec<u8>, n: u32) {
    // The length from `n` itself, in parallel with the digits' chain of multiplications.
    let len = n.checked_ilog10().map_or(1, |l| l as usize + 1);
    let digits = digits8(n) >> (8 * (8 - len));
    let start = out.len();
    out.extend_from_slice(&(digits | ASCII_ZEROS).to_le_bytes());
    out.truncate(start + len);
}

/// [`push_u64`] of `n >= 10^8`: the digits above the last eight, then those eight.
#[inline(never)]
fn push_large(out: &mut Vec<u8>, n: u64) {
    let high = n / 100_000_000;
    match u32::try_from(high) {
        Ok(high) if high < 100_000_000 => push_below_1e8(out, high),
        _ => {
            // Below 1845: `u64::MAX` has 20 digits.
            push_below_1e8(out, (high / 100_000_000) as u32);
            let middle = digits8((high % 100_000_000) as u32);
            out.extend_from_slice(&(middle | ASCII_ZEROS).to_le_bytes());
        }
    }
    let low = digits8((n % 100_000_000) as u32);
    out.extend_from_slice(&(low | ASCII_ZEROS).to_le_bytes());
}

/// `f32` and `f64` as this module needs them.
pub(crate) trait Float: Copy + std::fmt::Debug + zmij::Float {
    /// The most significant digits of a shortest text (9 for `f32`, 17 for `f64`).
    const MAX_DIGITS: u32;
    /// Whether `{:?}` writes the value in exponential form (std's
    /// `already_rounded_value_should_use_exponential`, in the value's type).
    fn exponential(self) -> bool;
    /// Neither NaN nor infinite.
    fn finite(self) -> bool;
    /// `(m, e)` with `m` odd and the magnitude `m * 2^e`; `None` for zero.
    fn odd_mantissa(self) -> Option<(u64, i32)>;
}

/// `Float` for a type with `MAX_DIGITS`, its unsigned bits, the fraction's width and the
/// exponent of its smallest subnormal.
macro_rules! float_impl {
    ($t:ty, $digits:expr, $fraction:expr, $exponent_mask:expr, $subnormal:expr) => {
        impl Float for $t {
            const MAX_DIGITS: u32 = $digits;

            #[inline]
            fn exponential(self) -> bool {
                let abs = self.abs();
                (abs != 0.0 && abs < 1e-4) || abs >= 1e16
            }

            #[inline]
            fn finite(self) -> bool {
                self.is_finite()
            }

            #[inline]
            fn odd_mantissa(self) -> Option<(u64, i32)> {
                let bits = self.to_bits();
                let biased = ((bits >> $fraction) & $exponent_mask) as i32;
                let fraction = bits & ((1 << $fraction) - 1);
                let (mantissa, exponent) = match biased {
                    0 => (fraction, $subnormal),
                    _ => (fraction | 1 << $fraction, biased + $subnormal - 1),
                };
                let zeros = mantissa.trailing_zeros();
                (mantissa != 0).then(|| (u64::from(mantissa >> zeros), exponent + zeros as i32))
            }
        }
    };
}

float_impl!(f64, 17, 52, 0x7ff, -1074);
float_impl!(f32, 9, 23, 0xff, -149);

/// `5^k` for every `k` whose power is below `10^18`, and one more.
const POW5: [u64; 27] = {
    let mut pow = [1u64; 27];
    let mut k = 1;
    while k < pow.len() {
        pow[k] = pow[k - 1] * 5;
        k += 1;
    }
    pow
};

/// Whether `x` may be exactly halfway between two shortest candidates (a cheap necessary
/// condition, no text needed): such a value `m * 2^-k` (`m` odd, `k > 0`) has the exact
/// decimal expansion `m * 5^k * 10^-k`, whose `digits(m * 5^k)` significant digits are one
/// more than the shortest text's, so at most `MAX_DIGITS + 1`. A value that is an integer
/// (`k <= 0`) never ties: the candidates would be `10^(e + 1)` apart in an interval no wider
/// than `2^e`.
#[inline]
fn may_tie_at_all<F: Float>(x: F) -> bool {
    match x.odd_mantissa() {
        Some((m, e)) if e < 0 => {
            let k = e.unsigned_abs() as usize;
            k < POW5.len() && u128::from(m) * u128::from(POW5[k]) < 10u128.pow(F::MAX_DIGITS + 1)
        }
        _ => false,
    }
}

/// Appends `x`'s `{:?}` text to `out`.
#[inline]
pub(crate) fn push_float<F: Float>(out: &mut Vec<u8>, x: F) {
    if !x.finite() {
        return push_std(out, x);
    }
    let mut buffer = zmij::Buffer::new();
    let text = buffer.format_finite(x).as_bytes();
    let exponential = x.exponential();
    // `zmij`'s exponent, when it writes one, is in its last five bytes (`e-5`, `e+308`).
    let zmij_exponential = text[text.len().saturating_sub(5)..].contains(&b'e');
    if !exponential && !zmij_exponential && !may_tie_at_all(x) {
        out.extend_from_slice(text);
        return;
    }
    let lowest_bit = x.odd_mantissa().map(|(_, e)| e);
    if !lay_out(out, text, exponential, lowest_bit) {
        push_std(out, x);
    }
}

/// std's own text, for what the fast path does not take.
#[cold]
#[inline(never)]
fn push_std<F: Float>(out: &mut Vec<u8>, x: F) {
    // Writing into a `Vec` cannot fail.
    let _ = write!(out, "{x:?}");
}

/// Whether the digits written, whose last is at `10^-fraction_digits`, may be one of two
/// nearest candidates that tie (see the module's docs): then std decides.
#[inline]
fn may_tie(lowest_bit: Option<i32>, fraction_digits: i32) -> bool {
    lowest_bit == Some(-(fraction_digits + 1))
}

/// Reads `zmij`'s text (`[-]digits[.digits][e[+-]exponent]`) back as significant digits and
/// the place of the point, and writes std's form of them: exponential (`1e-5`, `-2.5e-7`,
/// `1.25e16`) or decimal (`12345680000000.0` for an `f32` `zmij` writes `1.234568e+13`);
/// `false` (nothing written) for text it does not expect or a possible tie.
#[inline(never)]
fn lay_out(out: &mut Vec<u8>, text: &[u8], exponential: bool, lowest_bit: Option<i32>) -> bool {
    let (negative, text) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, text),
    };
    let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
        Some(e) => {
            let written = &text[e + 1..];
            let digits = written.strip_prefix(b"+").unwrap_or(written);
            let (sign, digits) = match digits.strip_prefix(b"-") {
                Some(rest) => (-1, rest),
                None => (1, digits),
            };
            if digits.is_empty() || digits.len() > 4 || !digits.iter().all(u8::is_ascii_digit) {
                return false;
            }
            let value = digits
                .iter()
                .fold(0i32, |n, &d| n * 10 + i32::from(d - b'0'));
            (&text[..e], sign * value)
        }
        None => (text, 0),
    };
    // The significant digits, and where the point is: the value is `0.digits * 10^point`.
    let mut digits = [0u8; 40];
    let mut n = 0;
    let mut before_point = None;
    for &c in mantissa {
        match c {
            b'.' if before_point.is_none() => before_point = Some(n),
            b'0'..=b'9' if n < digits.len() => {
                digits[n] = c;
                n += 1;
            }
            _ => return false,
        }
    }
    let integer_digits = before_point.unwrap_or(n) as i32;
    let leading = digits[..n].iter().take_while(|&&c| c == b'0').count();
    let trailing = digits[leading..n]
        .iter()
        .rev()
        .take_while(|&&c| c == b'0')
        .count();
    let significant = &digits[leading..n - trailing];
    let Some((&first, rest)) = significant.split_first() else {
        return false;
    };
    let point = integer_digits - leading as i32 + exponent;
    let n = significant.len() as i32;
    if may_tie(lowest_bit, n - point) {
        return false;
    }
    if negative {
        out.push(b'-');
    }
    if exponential {
        out.push(first);
        if !rest.is_empty() {
            out.push(b'.');
            out.extend_from_slice(rest);
        }
        let exponent = point - 1;
        out.extend_from_slice(if exponent < 0 { b"e-" } else { b"e" });
        push_u64(out, u64::from(exponent.unsigned_abs()));
    } else if point <= 0 {
        out.extend_from_slice(b"0.");
        out.extend(std::iter::repeat(b'0').take(point.unsigned_abs() as usize));
        out.extend_from_slice(significant);
    } else if point < n {
        let (integer, fraction) = significant.split_at(point as usize);
        out.extend_from_slice(integer);
        out.push(b'.');
        out.extend_from_slice(fraction);
    } else {
        out.extend_from_slice(significant);
        out.extend(std::iter::repeat(b'0').take((point - n) as usize));
        out.extend_from_slice(b".0");
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::lines::testing::Rng;

    fn ours<F: Float>(x: F) -> String {
        let mut out = Vec::new();
        push_float(&mut out, x);
        String::from_utf8(out).expect("ASCII")
    }

    fn check_f64(x: f64) {
        assert_eq!(ours(x), format!("{x:?}"), "f64 bits {:#018x}", x.to_bits());
    }

    fn check_f32(x: f32) {
        assert_eq!(ours(x), format!("{x:?}"), "f32 bits {:#010x}", x.to_bits());
    }

    /// `1e{k}` for `k` in `range`, its negative and a few multiples, in `T`.
    fn decades<T>(range: std::ops::Range<i32>) -> Vec<T>
    where
        T: std::str::FromStr + Copy + From<f32> + std::ops::Neg<Output = T>,
        T: std::ops::Mul<Output = T> + std::ops::Div<Output = T>,
        T::Err: std::fmt::Debug,
    {
        let t = T::from;
        range
            .flat_map(|k| {
                let x: T = format!("1e{k}").parse().expect("a float");
                [x, -x, x * t(1.5), x * t(3.0), x * t(7.0) / t(9.0)]
            })
            .collect()
    }

    /// `bits` and the bit patterns next to it (wrapping).
    fn around(bits: u64) -> [u64; 3] {
        [bits, bits.wrapping_add(1), bits.wrapping_sub(1)]
    }

    /// Random bit patterns of both types, and random values in the ranges meshes have
    /// (coordinates near 1, f32 values of a few digits that tie often), equal to std's.
    #[test]
    fn matches_std_on_random_bits() {
        let mut bits = Rng(0x9e37_79b9_7f4a_7c15);
        for _ in 0..1_000_000 {
            let b = bits.next();
            check_f64(f64::from_bits(b));
            check_f32(f32::from_bits(b as u32));
            check_f32(f32::from_bits((b >> 32) as u32));
            // Exponents near 0 (|x| from about 1e-6 to 1e6): the mesh coordinates.
            let near = (b & 0x800f_ffff_ffff_ffff) | ((1003 + (b >> 52) % 40) << 52);
            check_f64(f64::from_bits(near));
            let near = (b as u32 & 0x807f_ffff) | ((107 + (b >> 40) as u32 % 40) << 23);
            check_f32(f32::from_bits(near));
            // Few significant bits: values on and near ties of both types.
            let short = (b >> 40) as i64 as f64 / f64::from(1u32 << (b % 24) as u32);
            check_f64(short);
            check_f32(short as f32);
        }
    }

    /// Zeros, subnormals, the extremes, the layout's thresholds, ties, non-finite values.
    #[test]
    fn matches_std_on_edge_values() {
        // The tie `zmij` breaks the other way, its exponent where std has none.
        assert_eq!(ours(-30_619.0f32 - 0.0625), "-30619.063");
        assert_eq!(
            zmij::Buffer::new().format(-30_619.0f32 - 0.0625),
            "-30619.062"
        );
        assert_eq!(ours(1.25e14f32), "125000000000000.0");
        assert_eq!(ours(1e-5f64), "1e-5");
        assert_eq!(ours(1e16f64), "1e16");
        let mut f64s = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1e-4,
            -1e-4,
            1e16,
            9.999_999_999_999_998e15,
            1e-5,
            1e15,
            1.5e16,
            123_456_789_012_345_680.0,
            1e-7,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            5e-324,
            // 2^50 + 1/4: a tie between `...624.2` and `...624.3`.
            1_125_899_906_842_624.0 + 0.25,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        f64s.extend(decades::<f64>(-330..310));
        for b in f64s.iter().flat_map(|x| around(x.to_bits())) {
            check_f64(f64::from_bits(b));
        }
        let mut f32s = vec![
            // A tie between `-30619.062` (`zmij`) and `-30619.063` (std).
            -30_619.0f32 - 0.0625,
            1e-4,
            1e16,
            f32::MIN_POSITIVE,
            f32::MAX,
            f32::MIN,
            1e-45,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        f32s.extend(decades::<f32>(-46..39));
        for b in f32s.iter().flat_map(|x| around(x.to_bits().into())) {
            // The low 32 bits: the f32 neighbours, wrapping as in `u32`.
            check_f32(f32::from_bits(b as u32));
        }
        // Every subnormal f32 with a short mantissa, every f32 of a few integer bits.
        for m in (0..1u32 << 23).step_by(4099) {
            check_f32(f32::from_bits(m));
            check_f32(f32::from_bits(m | 0x8000_0000));
        }
        for i in 0..1u32 << 17 {
            check_f32(i as f32 / 16.0);
            check_f64(f64::from(i) / 1024.0 + 1_125_899_906_842_624.0);
        }
    }

    /// Every `f32` (4.3 billion values; `cargo test --release -p halfedge --lib
    /// matches_std_on_every_f32 -- --ignored`, minutes on two cores).
    #[test]
    #[ignore = "every f32: minutes in release"]
    fn matches_std_on_every_f32() {
        let threads = std::thread::available_parallelism().map_or(2, |n| n.get() as u64);
        let span = (1u64 << 32).div_ceil(threads);
        std::thread::scope(|s| {
            for t in 0..threads {
                s.spawn(move || {
                    let (mut out, mut std) = (Vec::new(), String::new());
                    for b in t * span..((t + 1) * span).min(1 << 32) {
                        let x = f32::from_bits(b as u32);
                        out.clear();
                        std.clear();
                        push_float(&mut out, x);
                        std::fmt::Write::write_fmt(&mut std, format_args!("{x:?}"))
                            .expect("a String");
                        assert_eq!(out, std.as_bytes(), "f32 bits {b:#010x}");
                    }
                });
            }
        });
    }

    /// Random `f64` values (`cargo test --release -p halfedge --lib
    /// matches_std_on_many_f64 -- --ignored`: 600 million, about a minute on two cores;
    /// `SUBCOUNT_F64_VALUES` sets how many).
    #[test]
    #[ignore = "hundreds of millions of f64: about a minute in release"]
    fn matches_std_on_many_f64() {
        let total: u64 = std::env::var("SUBCOUNT_F64_VALUES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(600_000_000);
        let threads = std::thread::available_parallelism().map_or(2, |n| n.get() as u64);
        std::thread::scope(|s| {
            for t in 0..threads {
                s.spawn(move || {
                    let (mut out, mut std) = (Vec::new(), String::new());
                    let mut bits = Rng(0x9e37_79b9_7f4a_7c15 ^ (t + 1).wrapping_mul(0xff51_afd7));
                    for _ in 0..total / threads / 3 {
                        let b = bits.next();
                        let near = (b & 0x800f_ffff_ffff_ffff) | ((1003 + (b >> 52) % 40) << 52);
                        let short = (b >> 40) as i64 as f64 / f64::from(1u32 << (b % 24) as u32);
                        for x in [f64::from_bits(b), f64::from_bits(near), short] {
                            out.clear();
                            std.clear();
                            push_float(&mut out, x);
                            std::fmt::Write::write_fmt(&mut std, format_args!("{x:?}"))
                                .expect("a String");
                            assert_eq!(out, std.as_bytes(), "f64 bits {:#018x}", x.to_bits());
                        }
                    }
                });
            }
        });
    }

    /// Integers of every length, appended after text already there.
    #[test]
    fn integers() {
        let mut numbers: Vec<u64> = (0..100_000).chain([u64::MAX, 4_294_967_296]).collect();
        for k in 0..20 {
            let p = 10u64.pow(k);
            numbers.extend([
                p - 1,
                p,
                p + 1,
                p.saturating_mul(2) - 1,
                p.saturating_mul(7) - 3,
            ]);
        }
        let mut bits = Rng(7);
        numbers.extend((0..10_000).map(|_| bits.next() >> (bits.next() % 64)));
        for n in numbers {
            let mut out = b"f ".to_vec();
            push_u64(&mut out, n);
            assert_eq!(out, format!("f {n}").as_bytes());
        }
    }
}
