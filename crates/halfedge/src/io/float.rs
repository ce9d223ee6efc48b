//! Decimal text to `f64`, exactly as `str::parse::<f64>` reads it, faster for the plain forms
//! mesh files hold (`-0.35165546140493487`: a sign, digits, a point, digits).
//!
//! Such a token with at most 19 significant digits and at most 27 after the point is read
//! here: by Clinger's fast path when its digits fit 53 bits (one exact division), else by the
//! Eisel-Lemire algorithm (a 128-bit product with a power of five), the two steps std's own
//! parser takes for it (a correctly rounded result is unique, so they agree to the bit; the
//! tests compare them on random and tie-breaking cases). Anything else (an exponent, `inf`,
//! more digits, an ambiguous product) is std's.

/// `token.parse::<f64>()`: the same value, or the same error.
#[inline]
pub(super) fn parse_f64(token: &str) -> std::result::Result<f64, std::num::ParseFloatError> {
    match plain(token.as_bytes()) {
        Some(x) => Ok(x),
        None => token.parse(),
    }
}

/// The value of `bytes` when they are `[+-]digits[.digits]` read here, else `None`.
#[inline]
fn plain(bytes: &[u8]) -> Option<f64> {
    prefix(bytes).and_then(|(x, n)| (n == bytes.len()).then_some(x))
}

/// The value of the longest start of `bytes` of the form `[+-]digits[.digits]` (at least one
/// digit) and its length, when it is read here (`None` when std's slower steps are needed
/// for it); whether the token ends there is the caller's question. A token that does is
/// `std`'s value: a finite `f64`.
#[inline]
pub(super) fn prefix(bytes: &[u8]) -> Option<(f64, usize)> {
    let (negative, s) = match *bytes.first()? {
        b'-' => (true, &bytes[1..]),
        b'+' => (false, &bytes[1..]),
        _ => (false, bytes),
    };
    // The digits before the point one at a time (a coordinate has few), those after it
    // eight at a time.
    let mut w = 0u64;
    let mut i = one_by_one(s, 0, &mut w);
    let whole = i;
    let mut fraction = 0;
    if s.get(i) == Some(&b'.') {
        let start = i + 1;
        i = digits(s, start, &mut w);
        fraction = i - start;
    }
    if whole + fraction == 0 {
        return None;
    }
    if whole + fraction > 19 {
        // More than 19 digits: `w` may have wrapped, unless the extra ones lead.
        let leading = s[..i]
            .iter()
            .take_while(|&&b| b == b'0' || b == b'.')
            .count();
        let points = usize::from(leading > whole);
        if whole + fraction - (leading - points) > 19 {
            return None;
        }
    }
    let value = if w == 0 {
        0.0
    } else if fraction == 0 {
        // Correctly rounded (ties to even), as the conversion is defined.
        w as f64
    } else if w <= 1 << 53 && fraction <= 22 {
        // Both exact: one correctly rounded division.
        w as f64 / POWERS_OF_TEN[fraction]
    } else if fraction <= 27 {
        eisel_lemire(-(fraction as i32), w)?
    } else {
        return None;
    };
    let sign = bytes.len() - s.len();
    Some((if negative { -value } else { value }, sign + i))
}

/// Reads the digits of `s` from `i` into `w` (`w * 10 + digit`, wrapping); the index after
/// them.
#[inline]
fn digits(s: &[u8], mut i: usize, w: &mut u64) -> usize {
    // Eight bytes at a time (the digits among them), then one at a time near the end.
    while let Some(eight) = s.get(i..i + 8) {
        let (n, value) = leading_digits(eight);
        *w = w.wrapping_mul(POWERS_OF_TEN_INT[n]).wrapping_add(value);
        i += n;
        if n < 8 {
            return i;
        }
    }
    one_by_one(s, i, w)
}

/// Reads the digits of `s` from `i` on one at a time into `w` (`w = 10 w + digit`,
/// wrapping); the index after them.
#[inline]
pub(super) fn one_by_one(s: &[u8], mut i: usize, w: &mut u64) -> usize {
    while let Some(&b) = s.get(i) {
        let digit = b.wrapping_sub(b'0');
        if digit > 9 {
            break;
        }
        *w = w.wrapping_mul(10).wrapping_add(u64::from(digit));
        i += 1;
    }
    i
}

/// `10^n` for `n` in 0..=8.
const POWERS_OF_TEN_INT: [u64; 9] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
];

/// How many of the eight bytes `eight` are ASCII digits before the first that is not, and
/// the value of those digits.
#[inline]
pub(super) fn leading_digits(eight: &[u8]) -> (usize, u64) {
    let mut word = [0u8; 8];
    word.copy_from_slice(eight);
    let word = u64::from_le_bytes(word);
    // A byte that is not a digit has its high bit set in `a | b`, provided the bytes before
    // it are digits (no carry or borrow from them): the first such byte is found exactly.
    let a = word.wrapping_add(0x4646_4646_4646_4646);
    let b = word.wrapping_sub(0x3030_3030_3030_3030);
    let n = (((a | b) & 0x8080_8080_8080_8080).trailing_zeros() / 8) as usize;
    if n == 0 {
        return (0, 0);
    }
    // The digits moved to the end, `0`s before them.
    let padded = match n {
        8 => word,
        _ => (word << (64 - 8 * n)) | (0x3030_3030_3030_3030 >> (8 * n)),
    };
    (n, parse_eight(padded))
}

/// The value of eight ASCII digits (little-endian: the first digit in the lowest byte).
#[inline]
fn parse_eight(word: u64) -> u64 {
    const MASK: u64 = 0x0000_00FF_0000_00FF;
    const MUL1: u64 = 0x000F_4240_0000_0064; // 100 + (1_000_000 << 32)
    const MUL2: u64 = 0x0000_2710_0000_0001; // 1 + (10_000 << 32)
    let mut v = word.wrapping_sub(0x3030_3030_3030_3030);
    v = v.wrapping_mul(10).wrapping_add(v >> 8);
    let v1 = (v & MASK).wrapping_mul(MUL1);
    let v2 = ((v >> 16) & MASK).wrapping_mul(MUL2);
    u64::from(((v1.wrapping_add(v2)) >> 32) as u32)
}

/// `10^k` for `k` in 0..=22, each exact in `f64`.
const POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `w * 10^q` (`q` in -27..=-1, `w` not 0) correctly rounded by the Eisel-Lemire algorithm
/// (Lemire, "Number parsing at a gigabyte per second", 2021, as std implements it for
/// `f64`), or `None` where it cannot decide (std's slower steps do).
fn eisel_lemire(q: i32, w: u64) -> Option<f64> {
    const MANTISSA_BITS: i32 = 52;
    let lz = w.leading_zeros();
    let w = w << lz;
    let (hi5, lo5) = POWERS_OF_FIVE[(q + 27) as usize];
    // The product's high bits, a second product only when the first leaves them unsure.
    let mask = u64::MAX >> (MANTISSA_BITS + 3);
    let product = |a: u64, b: u64| {
        let r = u128::from(a) * u128::from(b);
        (r as u64, (r >> 64) as u64)
    };
    let (mut lo, mut hi) = product(w, hi5);
    if hi & mask == mask {
        let (_, second_hi) = product(w, lo5);
        lo = lo.wrapping_add(second_hi);
        if second_hi > lo {
            hi += 1;
        }
    }
    // (`lo == u64::MAX` is a failed approximation only outside -27..=55.)
    let upperbit = (hi >> 63) as i32;
    let shift = upperbit + 64 - MANTISSA_BITS - 3;
    let mut mantissa = hi >> shift;
    let power = ((q.wrapping_mul(152_170 + 65_536)) >> 16) + 63;
    let mut power2 = power + upperbit - lz as i32 + 1023;
    if power2 <= 0 {
        // Subnormal: not from these exponents; std's steps.
        return None;
    }
    // An exact tie rounds to even (only possible for -4 <= q).
    if lo <= 1 && q >= -4 && mantissa & 3 == 1 && (mantissa << shift) == hi {
        mantissa &= !1;
    }
    mantissa += mantissa & 1;
    mantissa >>= 1;
    if mantissa >= (2 << MANTISSA_BITS) {
        mantissa = 1 << MANTISSA_BITS;
        power2 += 1;
    }
    mantissa &= !(1 << MANTISSA_BITS);
    if power2 >= 0x7FF {
        return None;
    }
    Some(f64::from_bits(
        mantissa | ((power2 as u64) << MANTISSA_BITS),
    ))
}

/// `5^q` for `q` in -27..=-1, normalized to 128 bits (high word, low word), rounded up: the
/// first entries of std's (and fast_float's) table of powers of five.
const POWERS_OF_FIVE: [(u64, u64); 27] = [
    (0x9e74d1b791e07e48, 0x775ea264cf55347e), // 5^-27
    (0xc612062576589dda, 0x95364afe032a819e), // 5^-26
    (0xf79687aed3eec551, 0x3a83ddbd83f52205), // 5^-25
    (0x9abe14cd44753b52, 0xc4926a9672793543), // 5^-24
    (0xc16d9a0095928a27, 0x75b7053c0f178294), // 5^-23
    (0xf1c90080baf72cb1, 0x5324c68b12dd6339), // 5^-22
    (0x971da05074da7bee, 0xd3f6fc16ebca5e04), // 5^-21
    (0xbce5086492111aea, 0x88f4bb1ca6bcf585), // 5^-20
    (0xec1e4a7db69561a5, 0x2b31e9e3d06c32e6), // 5^-19
    (0x9392ee8e921d5d07, 0x3aff322e62439fd0), // 5^-18
    (0xb877aa3236a4b449, 0x09befeb9fad487c3), // 5^-17
    (0xe69594bec44de15b, 0x4c2ebe687989a9b4), // 5^-16
    (0x901d7cf73ab0acd9, 0x0f9d37014bf60a11), // 5^-15
    (0xb424dc35095cd80f, 0x538484c19ef38c95), // 5^-14
    (0xe12e13424bb40e13, 0x2865a5f206b06fba), // 5^-13
    (0x8cbccc096f5088cb, 0xf93f87b7442e45d4), // 5^-12
    (0xafebff0bcb24aafe, 0xf78f69a51539d749), // 5^-11
    (0xdbe6fecebdedd5be, 0xb573440e5a884d1c), // 5^-10
    (0x89705f4136b4a597, 0x31680a88f8953031), // 5^-9
    (0xabcc77118461cefc, 0xfdc20d2b36ba7c3e), // 5^-8
    (0xd6bf94d5e57a42bc, 0x3d32907604691b4d), // 5^-7
    (0x8637bd05af6c69b5, 0xa63f9a49c2c1b110), // 5^-6
    (0xa7c5ac471b478423, 0x0fcf80dc33721d54), // 5^-5
    (0xd1b71758e219652b, 0xd3c36113404ea4a9), // 5^-4
    (0x83126e978d4fdf3b, 0x645a1cac083126ea), // 5^-3
    (0xa3d70a3d70a3d70a, 0x3d70a3d70a3d70a4), // 5^-2
    (0xcccccccccccccccc, 0xcccccccccccccccd), // 5^-1
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::lines::testing::Rng;

    fn same(token: &str) {
        let std = token.parse::<f64>();
        let ours = parse_f64(token);
        match (std, ours) {
            (Ok(a), Ok(b)) => assert_eq!(a.to_bits(), b.to_bits(), "{token}: {a:?} {b:?}"),
            (Err(a), Err(b)) => assert_eq!(a, b, "{token}"),
            (a, b) => panic!("{token}: std {a:?}, ours {b:?}"),
        }
    }

    /// The number of leading digits of `eight` and their value, read by std.
    fn as_std_reads(eight: &[u8; 8]) -> (usize, u64) {
        let n = eight.iter().take_while(|b| b.is_ascii_digit()).count();
        let text = std::str::from_utf8(&eight[..n]).expect("ASCII digits");
        (n, text.parse().unwrap_or(0))
    }

    #[test]
    fn leading_digits_are_found_and_read() {
        for text in [
            "12345678",
            "1234567x",
            "1 2",
            "x1234567",
            "00000000",
            "9",
            "98 76543",
            "1/2/3000",
            "1234567\u{0}",
            "5\u{ff}\u{ff}\u{ff}\u{ff}\u{ff}\u{ff}",
        ] {
            let mut eight = [b' '; 8];
            let bytes = text.as_bytes();
            eight[..bytes.len().min(8)].copy_from_slice(&bytes[..bytes.len().min(8)]);
            assert_eq!(leading_digits(&eight), as_std_reads(&eight), "{text:?}");
        }
        let mut rng = Rng(0x5851_f42d_4c95_7f2d);
        for _ in 0..200_000 {
            let eight = rng.next().to_le_bytes().map(|b| match b % 4 {
                0 => b,
                _ => b'0' + b % 10,
            });
            assert_eq!(leading_digits(&eight), as_std_reads(&eight), "{eight:?}");
        }
    }

    #[test]
    fn every_form_reads_as_std_reads_it() {
        for token in [
            "0",
            "-0",
            "+0",
            "0.0",
            "-0.0",
            ".5",
            "5.",
            "-.5",
            "+.5",
            ".",
            "-",
            "+",
            "",
            "1e5",
            "1E-5",
            "inf",
            "-inf",
            "NaN",
            "nan",
            "infinity",
            "1.2.3",
            "1..2",
            "--1",
            "+-1",
            "0x10",
            "1_000",
            " 1",
            "1 ",
            "12345678901234567890",
            "1234567890123456789",
            "0.0000000000000000000000000001",
            "0000000000000000000001.5",
            "0.00000000000000000000000000012345678901234567890",
            "9007199254740993",
            "9007199254740992.5",
            "18446744073709551615",
            "18446744073709551616",
            "4503599627370496.5",
            "4503599627370497.5",
            "0.35165546140493487",
            "-0.3547204739446115",
            "179769313486231570000000000000000",
            "٣",
            "1\u{0}",
            "12345678.12345678",
            "99999999999999999999.9",
        ] {
            same(token);
        }
    }

    #[test]
    fn the_fast_steps_are_taken() {
        // Clinger's (16 digits), Eisel-Lemire's (17), a conversion (no point), a zero.
        for (token, q) in [
            ("-0.3547204739446115", None),
            ("0.35165546140493487", Some(-17)),
            ("12345678901234567.5", Some(-1)),
            ("1844674407370955161", None),
            ("-0.000", None),
        ] {
            assert_eq!(
                plain(token.as_bytes()),
                Some(token.parse().unwrap()),
                "{token}"
            );
            if let Some(q) = q {
                let w: u64 = token.replace('.', "").parse().unwrap();
                assert!(eisel_lemire(q, w).is_some(), "{token}");
            }
        }
        for token in [
            "1e5",
            "inf",
            "0.1234567890123456789012345678",
            "1.",
            "1.0e0",
        ] {
            assert_eq!(plain(token.as_bytes()).is_some(), token == "1.", "{token}");
        }
    }

    #[test]
    fn random_digits_read_as_std_reads_them() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let alphabet = b"0123456789012345678901234567890123456789.-+e";
        for _ in 0..400_000 {
            let len = 1 + rng.below(30);
            let token: String = (0..len)
                .map(|_| alphabet[rng.below(alphabet.len())] as char)
                .collect();
            same(&token);
        }
    }

    #[test]
    fn plain_decimals_read_as_std_reads_them() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        for _ in 0..400_000 {
            // Digits before and after the point, a sign, leading zeros.
            let whole = rng.below(22);
            let fraction = rng.below(30);
            let mut token = String::new();
            match rng.below(3) {
                0 => token.push('-'),
                1 => token.push('+'),
                _ => {}
            }
            let zeros = rng.below(4);
            for k in 0..whole {
                let d = if k < zeros { 0 } else { rng.below(10) };
                token.push(char::from(b'0' + d as u8));
            }
            token.push('.');
            for _ in 0..fraction {
                token.push(char::from(b'0' + rng.below(10) as u8));
            }
            same(&token);
            same(token.trim_end_matches('.'));
        }
        // Shortest round-trip texts of random doubles (what writers write), and fixed ones.
        for _ in 0..400_000 {
            let x = f64::from_bits(rng.next() >> 2) % 1e6;
            same(&format!("{x:?}"));
            same(&format!("{:.17}", x));
            same(&format!("{:.9}", -x / 7.0));
        }
    }

    #[test]
    fn ties_round_to_even_as_std_rounds_them() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        // Halfway between two doubles of spacing 2^-j: k 2^-j + 2^-(j+1), j + 1 digits after
        // the point; and the doubles next to them.
        for j in 0..5 {
            for _ in 0..50_000 {
                let k = (1u64 << 52) + rng.next() % (1 << 52);
                let base = k as f64 / f64::from(1u32 << j);
                let half = 0.5 / f64::from(1u32 << j);
                let text = format!("{:.*}", j + 1, base + half / 2.0);
                let text_tie = format!("{:.*}", j + 1, base);
                same(&text);
                same(&text_tie);
                // The exact tie, written out: base + half has j + 1 digits after the point.
                let exact = exact_decimal(k, j as u32);
                same(&exact);
            }
        }
    }

    /// `(2k + 1) / 2^(j+1)` written exactly (j + 1 digits after the point).
    fn exact_decimal(k: u64, j: u32) -> String {
        let numerator = u128::from(2 * k + 1);
        let scale = 10u128.pow(j + 1) / (1u128 << (j + 1));
        let digits = numerator * scale;
        let text = digits.to_string();
        let (whole, fraction) = text.split_at(text.len() - (j as usize + 1));
        format!("{whole}.{fraction}")
    }
}
