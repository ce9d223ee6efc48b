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
