//! Property tests over random integer matrices (strategies in `util`).

use nalgebra::{Complex, DMatrix};
use num_bigint::BigInt;
use proptest::prelude::*;
use recurrence::{Error, Recurrence};

use crate::util::{big, exact_spectrum_matrix, matrix_and_state};

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn closed_form_equals_powering((m, x0) in matrix_and_state(-4..=4, 1..=6, -9..=9)) {
        let r = Recurrence::new(m);
        let form = r.closed_form();
        let states = r.states_up_to(&x0, 60).unwrap();
        for (i, c) in form.components().iter().enumerate() {
            if !c.exact {
                continue;
            }
            for (s, state) in states.iter().enumerate() {
                // Evaluate per component through the whole form when every component is exact.
                if form.is_exact() {
                    let got = form.evaluate(&x0, s as u64).unwrap();
                    prop_assert_eq!(&got[i], &state[i], "matrix {} level {}", r.matrix(), s);
                }
            }
        }
        if form.is_exact() {
            prop_assert_eq!(form.evaluate(&x0, 61).unwrap(), r.state_at(&x0, 61).unwrap());
        }
    }

    #[test]
    fn exact_spectrum_closed_form_equals_powering(
        m in exact_spectrum_matrix(1..=6),
        x0 in proptest::collection::vec(-9i64..=9, 6),
    ) {
        let r = Recurrence::new(m);
        let x0 = big(&x0[..r.dim()]);
        let form = r.closed_form();
        prop_assert!(form.is_exact(), "matrix {} has an exact spectrum", r.matrix());
        for (s, state) in r.states_up_to(&x0, 60).unwrap().iter().enumerate() {
            prop_assert_eq!(&form.evaluate(&x0, s as u64).unwrap(), state, "matrix {} level {}", r.matrix(), s);
        }
    }

    #[test]
    fn powering_equals_repeated_multiplication((m, x0) in matrix_and_state(-4..=4, 1..=6, -9..=9), s in 0u64..=40) {
        let r = Recurrence::new(m);
        let states = r.states_up_to(&x0, s).unwrap();
        prop_assert_eq!(&r.state_at(&x0, s).unwrap(), &states[s as usize]);
    }

    #[test]
    fn i128_path_equals_bigint_or_reports_overflow((m, x0) in matrix_and_state(-4..=4, 1..=6, -9..=9), s in 0u64..=80) {
        let r = Recurrence::new(m);
        let big = r.state_at(&x0, s).unwrap();
        let small: Vec<i128> = x0.iter().map(|x| i128::try_from(x).unwrap()).collect();
        match r.state_at_i128(&small, s) {
            Ok(v) => prop_assert_eq!(v.into_iter().map(BigInt::from).collect::<Vec<_>>(), big),
            Err(Error::Overflow { level, .. }) => {
                prop_assert_eq!(level, s);
                // Overflow is reported only when some power of M overflows i128 on the way,
                // which needs numbers beyond 2^100 somewhere; the exact result may fit, but
                // an entry of M^(2^k) must not.
                let p = r.checked_matrix_power::<BigInt>(s.next_power_of_two()).unwrap();
                let biggest = p.iter().flatten().map(BigInt::bits).max().unwrap_or(0)
                    .max(big.iter().map(BigInt::bits).max().unwrap_or(0));
                prop_assert!(biggest > 60, "overflow reported with {} bit numbers", biggest);
            }
            Err(e) => prop_assert!(false, "unexpected error {}", e),
        }
    }

    #[test]
    fn numeric_eigenvalues_agree_with_exact_ones((m, _x0) in matrix_and_state(-4..=4, 1..=6, 0..=0)) {
        let r = Recurrence::new(m.clone());
        let n = m.dim();
        let dm = DMatrix::from_fn(n, n, |i, j| m.get(i, j) as f64);
        let numeric: Vec<Complex<f64>> = dm.complex_eigenvalues().iter().copied().collect();
        let mut used = vec![false; n];
        let infos = r.eigenvalues();
        prop_assert_eq!(infos.iter().map(|e| e.multiplicity).sum::<usize>(), n);
        for info in infos {
            let z = info.eigenvalue.to_complex();
            let z = Complex::new(z.re, z.im);
            let tol = (1.0 + z.norm()) * 1e-6f64.powf(1.0 / info.multiplicity as f64);
            for _ in 0..info.multiplicity {
                let best = (0..n)
                    .filter(|&k| !used[k])
                    .min_by(|&a, &b| (numeric[a] - z).norm().total_cmp(&(numeric[b] - z).norm()))
                    .unwrap();
                prop_assert!((numeric[best] - z).norm() < tol, "{} vs {} in {}", info.eigenvalue, numeric[best], m);
                used[best] = true;
            }
        }
    }
}
