//! The fast decimal conversion agrees with num-bigint's `to_string`, digit for digit.

use std::fmt::Write as _;

use decimal::{to_decimal, write_decimal, Decimal};
use num_bigint::{BigInt, BigUint, Sign};
use num_traits::{One, Zero};
use proptest::prelude::*;

/// Asserts every entry point against num-bigint for `n` and `-n`.
fn check(n: &BigInt) {
    for n in [n.clone(), -n] {
        let expected = n.to_string();
        assert_eq!(to_decimal(&n), expected, "{} bits", n.bits());
        let mut streamed = String::new();
        write_decimal(&mut streamed, &n).unwrap();
        assert_eq!(streamed, expected);
        assert_eq!(format!("{}", Decimal::from(&n)), expected);
        if n.sign() != Sign::Minus {
            assert_eq!(format!("{}", Decimal::from(n.magnitude())), expected);
        }
    }
}

fn pow(base: u32, exp: u32) -> BigInt {
    BigInt::from(base).pow(exp)
}

#[test]
fn zero_one_and_small() {
    assert_eq!(to_decimal(&BigInt::zero()), "0");
    assert_eq!(to_decimal(&BigInt::one()), "1");
    assert_eq!(to_decimal(&BigInt::from(-1)), "-1");
    assert_eq!(format!("{}", Decimal::from(&BigUint::zero())), "0");
    for v in [9i128, 10, 99, 100, i128::from(u64::MAX), i128::MAX] {
        check(&BigInt::from(v));
    }
}

#[test]
fn powers_of_ten_and_neighbours() {
    // 10^k, 10^k - 1 and 10^k + 1 (the unit tests run these through every path with small
    // thresholds; at the default ones, numbers this small go to num-bigint directly).
    let ks = (1..=80)
        .chain([
            600, 601, 602, 603, 604, 1000, 1024, 2048, 3999, 4000, 4001, 8000, 12_345,
        ])
        .chain([16_384, 20_000, 33_333]);
    for k in ks {
        let p = pow(10, k);
        check(&p);
        check(&(&p - 1));
        check(&(&p + 1));
        assert_eq!(to_decimal(&p).len(), k as usize + 1);
        assert_eq!(to_decimal(&(&p - 1)), "9".repeat(k as usize));
    }
}

#[test]
fn powers_of_two_around_the_digit_bound() {
    // 2^b - 1 and 2^b: the digit bound ceil(b log10 2) is exact or one too many.
    for b in (1990..2020).chain([4096, 6643, 6644, 13_287, 13_288, 66_439, 66_440]) {
        let p = BigInt::one() << b;
        check(&p);
        check(&(&p - 1));
    }
}

#[test]
fn widths_and_signs_match_num_bigint() {
    let n = pow(7, 900); // 761 digits: the fast path
    for (ours, theirs) in [
        (format!("{:>800}", Decimal::from(&n)), format!("{n:>800}")),
        (
            format!("{:<800}|", Decimal::from(&-&n)),
            format!("{:<800}|", -&n),
        ),
        (format!("{:+}", Decimal::from(&n)), format!("{n:+}")),
        (
            format!("{:0800}", Decimal::from(&-&n)),
            format!("{:0800}", -&n),
        ),
        (
            format!("{:+}", Decimal::from(&BigInt::zero())),
            "+0".to_string(),
        ),
    ] {
        assert_eq!(ours, theirs);
    }
}

#[test]
fn streams_into_io_writers() {
    let n = pow(3, 40_000); // 19,086 digits
    let mut out = Vec::new();
    std::io::Write::write_fmt(&mut out, format_args!("[{}]", Decimal::from(&n))).unwrap();
    assert_eq!(out, format!("[{n}]").into_bytes());
    let mut s = String::from("x=");
    write!(s, "{}", Decimal::from(&n)).unwrap();
    assert_eq!(s, format!("x={n}"));
}

/// A count of the size issue 5 is about: the Catmull-Clark quad edge count of a cube at
/// level 10^6, `E = 12 4^(10^6)` (602,062 digits).
#[test]
fn six_hundred_thousand_digits() {
    let e = BigInt::from(12) << 2_000_000u32;
    let text = to_decimal(&e);
    assert_eq!(text.len(), 602_062);
    assert!(text.starts_with("11762759"), "{}", &text[..8]);
    assert!(text.ends_with("5312512"));
    assert_eq!(text, e.to_string());
}

fn big_int(max_bytes: usize) -> impl Strategy<Value = BigInt> {
    (
        any::<bool>(),
        proptest::collection::vec(any::<u8>(), 0..max_bytes),
    )
        .prop_map(|(negative, bytes)| {
            let sign = if negative { Sign::Minus } else { Sign::Plus };
            BigInt::from_bytes_le(sign, &bytes)
        })
}

/// Numbers whose decimal digits have long runs of 0 and 9 where the splits fall.
fn structured_int() -> impl Strategy<Value = BigInt> {
    (1u32..30_000, 1u32..30_000, -3i32..=3).prop_map(|(a, b, c)| {
        pow(10, a.max(b)) + pow(10, a.min(b)) * BigInt::from(c) + BigInt::from(c)
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn agrees_with_num_bigint(n in big_int(20_000)) {
        prop_assert_eq!(to_decimal(&n), n.to_string());
    }

    #[test]
    fn agrees_on_runs_of_zeros_and_nines(n in structured_int()) {
        prop_assert_eq!(to_decimal(&n), n.to_string());
    }
}
