//! Level queries against brute force.

use num_bigint::BigInt;
use proptest::prelude::*;
use recurrence::{Error, LevelBound, Recurrence};

use crate::util::{big, exact_spectrum_matrix, rec};

fn functional(r: &Recurrence, x0: &[BigInt], w: &[BigInt], s: u64) -> BigInt {
    w.iter()
        .zip(&r.state_at(x0, s).unwrap())
        .map(|(w, x)| w * x)
        .sum()
}

#[test]
fn icosahedron_budgets() {
    // (V, E, F) under 4:1 subdivision, the icosahedron (12, 30, 20).
    let r = rec("[[1,1,0],[0,2,3],[0,0,4]]", "V,E,F");
    let x0 = big(&[12, 30, 20]);
    let v = big(&[1, 0, 0]);
    assert_eq!(
        r.largest_level_within(&x0, &v, &BigInt::from(u32::MAX))
            .unwrap(),
        LevelBound::Level(14)
    );
    // 12 bytes per vertex (3 f32) + 12 bytes per face (3 u32 indices) within 2 GiB.
    let bytes = big(&[12, 0, 12]);
    let level = r
        .largest_level_within(&x0, &bytes, &(BigInt::from(2u64) << 30))
        .unwrap();
    assert_eq!(level, LevelBound::Level(11));
    assert!(functional(&r, &x0, &bytes, 11) <= BigInt::from(2u64 << 30));
    assert!(functional(&r, &x0, &bytes, 12) > BigInt::from(2u64 << 30));
    assert_eq!(
        r.smallest_level_reaching(&x0, &v, &BigInt::from(1_000_000))
            .unwrap(),
        Some(9)
    );
    // Euler characteristic V - E + F = 2 at every level: never reaches 3, always within 2.
    let chi = big(&[1, -1, 1]);
    assert_eq!(
        r.smallest_level_reaching(&x0, &chi, &BigInt::from(3))
            .unwrap(),
        None
    );
    assert_eq!(
        r.largest_level_within(&x0, &chi, &BigInt::from(2)).unwrap(),
        LevelBound::Unbounded
    );
    assert_eq!(
        r.largest_level_within(&x0, &chi, &BigInt::from(1)).unwrap(),
        LevelBound::NoneFits
    );
}

#[test]
fn dominant_eigenvalues() {
    assert_eq!(
        rec("[[1,1,1],[0,2,4],[0,0,4]]", "")
            .dominant_eigenvalue()
            .unwrap()
            .to_string(),
        "4"
    );
    assert_eq!(
        rec("[[1,1],[1,0]]", "")
            .dominant_eigenvalue()
            .unwrap()
            .to_string(),
        "1/2+1/2*sqrt(5)"
    );
    assert_eq!(
        rec("[[-3,0],[0,2]]", "")
            .dominant_eigenvalue()
            .unwrap()
            .to_string(),
        "-3"
    );
    assert_eq!(rec("[[0,1],[0,0]]", "").dominant_eigenvalue(), None);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn queries_match_brute_force(
        m in exact_spectrum_matrix(1..=4),
        x0 in proptest::collection::vec(-9i64..=9, 4),
        w in proptest::collection::vec(-3i64..=3, 4),
        threshold in -1000i64..=100_000,
    ) {
        let r = Recurrence::new(m);
        let n = r.dim();
        let (x0, w) = (big(&x0[..n]), big(&w[..n]));
        let t = BigInt::from(threshold);
        let brute = r
            .states_up_to(&x0, 300)
            .unwrap()
            .iter()
            .position(|x| w.iter().zip(x).map(|(w, x)| w * x).sum::<BigInt>() >= t)
            .map(|p| p as u64);
        match r.smallest_level_reaching(&x0, &w, &t) {
            Ok(Some(s)) if s > 300 => {
                prop_assert_eq!(brute, None);
                prop_assert!(functional(&r, &x0, &w, s) >= t);
                prop_assert!(functional(&r, &x0, &w, s - 1) < t);
            }
            Ok(got) => prop_assert_eq!(got, brute, "matrix {}", r.matrix()),
            Err(Error::SearchLimit { .. }) => {
                // Allowed only with non-real eigenvalues.
                prop_assert!(r.eigenvalues().iter().any(|e| e.eigenvalue.to_complex().im != 0.0));
            }
            Err(e) => prop_assert!(false, "unexpected error {}", e),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn queries_on_random_matrices(
        (m, x0) in crate::util::matrix_and_state(-4..=4, 1..=4, -9..=9),
        w in proptest::collection::vec(0i64..=3, 4),
        threshold in -1000i64..=100_000,
    ) {
        let r = Recurrence::new(m);
        let n = r.dim();
        let w = big(&w[..n]);
        let t = BigInt::from(threshold);
        let brute = r
            .states_up_to(&x0, 300)
            .unwrap()
            .iter()
            .position(|x| w.iter().zip(x).map(|(w, x)| w * x).sum::<BigInt>() >= t)
            .map(|p| p as u64);
        match r.smallest_level_reaching(&x0, &w, &t) {
            Ok(Some(s)) if s > 300 => {
                prop_assert_eq!(brute, None);
                prop_assert!(functional(&r, &x0, &w, s) >= t);
                prop_assert!(functional(&r, &x0, &w, s - 1) < t);
            }
            Ok(got) => prop_assert_eq!(got, brute, "matrix {}", r.matrix()),
            Err(Error::SearchLimit { .. }) => {
                prop_assert_eq!(brute, None);
                prop_assert!(r.eigenvalues().iter().any(|e| e.eigenvalue.to_complex().im != 0.0));
            }
            Err(e) => prop_assert!(false, "unexpected error {}", e),
        }
    }
}
