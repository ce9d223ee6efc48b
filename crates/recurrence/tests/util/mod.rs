//! Shared helpers and proptest strategies for the integration tests.
#![allow(dead_code)]

use num_bigint::BigInt;
use proptest::prelude::*;
use recurrence::{IntMatrix, Recurrence};

/// A recurrence from a bracketed matrix and comma-separated names.
pub(crate) fn rec(matrix: &str, names: &str) -> Recurrence {
    let m: IntMatrix = matrix.parse().expect("test matrices parse");
    if names.is_empty() {
        Recurrence::new(m)
    } else {
        Recurrence::with_names(m, names.split(',')).expect("test names are valid")
    }
}

/// Big integers from small ones.
pub(crate) fn big(v: &[i64]) -> Vec<BigInt> {
    v.iter().map(|&x| BigInt::from(x)).collect()
}

/// Asserts that the closed form agrees with powering for levels `0..=last`.
pub(crate) fn assert_form_matches_powering(r: &Recurrence, x0: &[BigInt], last: u64) {
    let form = r.closed_form();
    let states = r.states_up_to(x0, last).expect("lengths match");
    for (s, state) in states.iter().enumerate() {
        assert_eq!(
            &form.evaluate(x0, s as u64).expect("exact form"),
            state,
            "matrix {} at level {s}",
            r.matrix()
        );
    }
}

/// Square integer matrices of dimension in `dims` with entries in `entries`, the way
/// nalgebra's `proptest::matrix` strategy is written.
pub(crate) fn int_matrix(
    entries: std::ops::RangeInclusive<i64>,
    dims: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = IntMatrix> {
    dims.prop_flat_map(move |n| {
        proptest::collection::vec(entries.clone(), n * n).prop_map(move |e| {
            IntMatrix::try_from_rows(e.chunks(n).map(<[i64]>::to_vec).collect())
                .expect("square by construction")
        })
    })
}

/// A matrix together with an initial vector of matching length.
pub(crate) fn matrix_and_state(
    entries: std::ops::RangeInclusive<i64>,
    dims: std::ops::RangeInclusive<usize>,
    init: std::ops::RangeInclusive<i64>,
) -> impl Strategy<Value = (IntMatrix, Vec<BigInt>)> {
    int_matrix(entries, dims).prop_flat_map(move |m| {
        let n = m.dim();
        (
            Just(m),
            proptest::collection::vec(init.clone(), n).prop_map(|v| big(&v)),
        )
    })
}

/// Integer matrices with an exact spectrum: a block upper triangular matrix (1x1 blocks with
/// small integer eigenvalues, repeated ones giving Jordan blocks, and optionally a 2x2 block
/// with quadratic eigenvalues) conjugated by a few unimodular elementary operations.
pub(crate) fn exact_spectrum_matrix(
    dims: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = IntMatrix> {
    dims.prop_flat_map(|n| {
        (
            proptest::collection::vec(-3i64..=3, n),
            proptest::collection::vec(-2i64..=2, n * n),
            proptest::collection::vec((0..n, 0..n, -2i64..=2), 0..=4),
            proptest::option::of((-2i64..=2, -2i64..=2, -2i64..=2, -2i64..=2)),
        )
            .prop_map(move |(diag, upper, ops, block)| {
                let mut t = vec![vec![0i64; n]; n];
                for i in 0..n {
                    t[i][i] = diag[i];
                    for j in i + 1..n {
                        t[i][j] = upper[i * n + j];
                    }
                }
                if let (Some((a, b, c, d)), true) = (block, n >= 2) {
                    t[0][0] = a;
                    t[0][1] = b;
                    t[1][0] = c;
                    t[1][1] = d;
                }
                for (i, j, k) in ops {
                    if i == j {
                        continue;
                    }
                    // T <- E T E^-1 with E = I + k e_i e_j^T.
                    let source = t[j].clone();
                    for (dst, src) in t[i].iter_mut().zip(&source) {
                        *dst += k * src;
                    }
                    for row in t.iter_mut() {
                        row[j] -= k * row[i];
                    }
                }
                IntMatrix::try_from_rows(t).expect("square by construction")
            })
    })
}
