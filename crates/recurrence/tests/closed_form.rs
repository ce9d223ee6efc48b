//! Closed forms of hand-picked matrices: every kind of eigenvalue structure.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::ToPrimitive;
use recurrence::{Coefficient, Eigenvalue, Error};

use crate::util::{assert_form_matches_powering, big, rec};

#[test]
fn paper_matrices_match_powering() {
    for (m, names, x0) in [
        ("[[1,1],[0,4]]", "V,E", vec![12, 30]),
        ("[[1,1,1],[0,4,1],[0,0,2]]", "V,IE,BE", vec![9, 10, 6]),
        ("[[1,1,1],[0,2,4],[0,0,4]]", "V,E,F", vec![8, 12, 6]),
    ] {
        assert_form_matches_powering(&rec(m, names), &big(&x0), 40);
    }
}

#[test]
fn jordan_block_gives_s_times_power() {
    let r = rec("[[2,1],[0,2]]", "a,b");
    let form = r.closed_form();
    // a(s) = 2^s a0 + s 2^(s-1) b0
    let a = &form.components()[0];
    assert_eq!(a.terms.len(), 2);
    assert_eq!(a.terms[0].s_power, 1);
    assert_eq!(
        a.terms[0].coefficients[1],
        Coefficient::Rational(BigRational::new(1.into(), 2.into()))
    );
    assert_eq!(a.terms[1].s_power, 0);
    assert_form_matches_powering(&r, &big(&[3, -5]), 50);
}

#[test]
fn nilpotent_matrix_is_all_early_levels() {
    let r = rec("[[0,1],[0,0]]", "a,b");
    let form = r.closed_form();
    let a = &form.components()[0];
    assert_eq!(a.valid_from, 2);
    assert!(a.terms.is_empty());
    assert_eq!(a.early_levels[0].coefficients, big(&[1, 0]));
    assert_eq!(a.early_levels[1].coefficients, big(&[0, 1]));
    assert_eq!(form.components()[1].valid_from, 1);
    assert_form_matches_powering(&r, &big(&[7, 11]), 10);
}

#[test]
fn zero_eigenvalue_inside_a_bigger_matrix() {
    // Doo-Sabin-like: F forgets itself after one step.
    let r = rec("[[0,2,0],[0,4,0],[1,1,1]]", "V,E,F");
    let form = r.closed_form();
    let valid: Vec<u64> = form.components().iter().map(|c| c.valid_from).collect();
    assert_eq!(valid, [1, 0, 1]);
    assert_form_matches_powering(&r, &big(&[8, 12, 6]), 40);
}

#[test]
fn negative_eigenvalue() {
    let r = rec("[[-2,1],[0,3]]", "");
    let form = r.closed_form();
    assert!(form
        .eigenvalues()
        .iter()
        .any(|e| e.eigenvalue == Eigenvalue::Rational(BigRational::from_integer((-2).into()))));
    assert_form_matches_powering(&r, &big(&[1, 1]), 40);
    assert_form_matches_powering(&rec("[[-1,0],[1,-1]]", ""), &big(&[2, -3]), 20);
}

#[test]
fn fibonacci_is_exact_in_sqrt5() {
    let r = rec("[[1,1],[1,0]]", "F,G");
    let form = r.closed_form();
    assert!(form.is_exact());
    let t = &form.components()[0].terms[0];
    assert_eq!(t.eigenvalue.to_string(), "1/2+1/2*sqrt(5)");
    assert!(matches!(t.coefficients[0], Coefficient::Surd(_)));
    assert_form_matches_powering(&r, &big(&[1, 0]), 90);
    let f = form.evaluate(&big(&[1, 0]), 1000).unwrap();
    assert_eq!(f, r.state_at(&big(&[1, 0]), 1000).unwrap());
}

#[test]
fn complex_quadratic_eigenvalues_are_exact() {
    // A 3-cycle: x^3 - 1 = (x - 1)(x^2 + x + 1), exact in Q(sqrt -3).
    let r = rec("[[0,0,1],[1,0,0],[0,1,0]]", "");
    assert!(r.closed_form().is_exact());
    assert_form_matches_powering(&r, &big(&[1, 2, 3]), 30);
}

/// Two real quadratic fields, `Q(sqrt 22)` and `Q(sqrt 29)`, whose terms interleave: the
/// per-field sums of the evaluation must not mix (found by `closed_form_equals_powering`
/// with more cases; the assertion that conjugate terms cancel fired in debug builds).
#[test]
fn interleaved_quadratic_fields_sum_per_field() {
    let r = rec("[[-3,-2,2,1],[-1,0,-3,0],[2,-3,0,-3],[3,-4,-3,-2]]", "");
    let fields: Vec<String> = r
        .eigenvalues()
        .iter()
        .map(|e| e.eigenvalue.to_string())
        .collect();
    assert_eq!(
        fields,
        [
            "-2-sqrt(22)",
            "-1/2-1/2*sqrt(29)",
            "-2+sqrt(22)",
            "-1/2+1/2*sqrt(29)"
        ]
    );
    for x0 in [big(&[0, 0, 0, -1]), big(&[1, -2, 3, 5])] {
        assert_form_matches_powering(&r, &x0, 61);
    }
}

#[test]
fn five_cycle_is_numeric_and_evaluate_refuses() {
    // x^5 - 1 = (x - 1)(x^4 + x^3 + x^2 + x + 1): the quartic is irreducible over Q.
    let r = rec(
        "[[0,0,0,0,1],[1,0,0,0,0],[0,1,0,0,0],[0,0,1,0,0],[0,0,0,1,0]]",
        "",
    );
    let form = r.closed_form();
    assert!(!form.is_exact());
    assert!(form.components().iter().all(|c| !c.exact));
    let x0 = big(&[1, 2, 3, 4, 5]);
    assert_eq!(
        form.evaluate(&x0, 3),
        Err(Error::NotExact {
            component: "x0".into()
        })
    );
    // The numeric terms still approximate the counts.
    for s in 0..12u64 {
        let exact = r.state_at(&x0, s).unwrap();
        for (i, c) in form.components().iter().enumerate() {
            let approx: f64 = c
                .terms
                .iter()
                .map(|t| {
                    let z = t.eigenvalue.to_complex();
                    let lam = nalgebra::Complex::new(z.re, z.im);
                    let coef = t.coefficients.iter().zip(&x0).fold(
                        nalgebra::Complex::new(0.0, 0.0),
                        |acc, (c, x)| {
                            let c = match c {
                                Coefficient::Numeric(z) => nalgebra::Complex::new(z.re, z.im),
                                Coefficient::Rational(r) => {
                                    nalgebra::Complex::new(r.to_f64().unwrap(), 0.0)
                                }
                                Coefficient::Surd(q) => {
                                    let z = q.to_f64();
                                    nalgebra::Complex::new(z.re, z.im)
                                }
                            };
                            acc + c * x.to_string().parse::<f64>().unwrap()
                        },
                    );
                    (coef * lam.powu(s as u32) * (s as f64).powi(t.s_power as i32)).re
                })
                .sum();
            let want: f64 = exact[i].to_string().parse().unwrap();
            assert!(
                (approx - want).abs() < 1e-6,
                "component {i} level {s}: {approx} vs {want}"
            );
        }
    }
}

#[test]
fn numeric_part_does_not_spoil_exact_components() {
    // Block diagonal: a 5-cycle on the first five components and 2 on the last.
    let r = rec(
        "[[0,0,0,0,1,0],[1,0,0,0,0,0],[0,1,0,0,0,0],[0,0,1,0,0,0],[0,0,0,1,0,0],[0,0,0,0,0,2]]",
        "",
    );
    let form = r.closed_form();
    let exact: Vec<bool> = form.components().iter().map(|c| c.exact).collect();
    assert_eq!(exact, [false, false, false, false, false, true]);
    let last = &form.components()[5];
    assert_eq!(last.terms.len(), 1);
    assert_eq!(last.terms[0].eigenvalue.to_string(), "2");
}

#[test]
fn wrong_length_initial_state_is_an_error() {
    let form = rec("[[1,1],[0,4]]", "V,E").closed_form();
    assert_eq!(
        form.evaluate(&big(&[1]), 3),
        Err(Error::InitialLength {
            got: 1,
            expected: 2
        })
    );
}

#[test]
fn huge_levels_with_power_of_two_eigenvalues() {
    let r = rec("[[1,1,1],[0,2,4],[0,0,4]]", "V,E,F");
    let form = r.closed_form();
    let x0 = big(&[8, 12, 6]);
    let s = 20_000;
    assert_eq!(form.evaluate(&x0, s).unwrap(), r.state_at(&x0, s).unwrap());
    let v: BigInt = form.evaluate(&x0, s).unwrap()[0].clone();
    assert!(v.bits() > 39_000);
}

#[test]
fn twelve_by_twelve() {
    // Block upper triangular: Jordan blocks for 3 and -2, a zero eigenvalue, sqrt(2) and
    // a 5-cycle-free mix, all within 12 components.
    let m = "[[3,1,0,0,0,0,0,0,0,0,0,1],\
              [0,3,1,0,0,0,0,0,0,0,1,0],\
              [0,0,3,0,0,0,0,0,0,1,0,0],\
              [0,0,0,-2,1,0,0,0,1,0,0,0],\
              [0,0,0,0,-2,0,0,1,0,0,0,0],\
              [0,0,0,0,0,0,1,0,0,0,0,0],\
              [0,0,0,0,0,0,0,0,0,0,0,0],\
              [0,0,0,0,0,0,0,1,2,0,0,0],\
              [0,0,0,0,0,0,0,1,1,0,0,0],\
              [0,0,0,0,0,0,0,0,0,4,1,0],\
              [0,0,0,0,0,0,0,0,0,0,1,0],\
              [0,0,0,0,0,0,0,0,0,0,0,5]]";
    let r = rec(m, "");
    let form = r.closed_form();
    assert!(form.is_exact());
    let mult: usize = form.eigenvalues().iter().map(|e| e.multiplicity).sum();
    assert_eq!(mult, 12);
    assert_form_matches_powering(&r, &big(&[1, -2, 3, -4, 5, -6, 7, -8, 9, -10, 11, -12]), 40);
}

#[test]
fn levels_beyond_memory_are_refused_not_attempted() {
    let form = rec("[[1,1],[0,4]]", "V,E").closed_form();
    assert_eq!(form.estimated_bits(1_000_000_000_000), 2_000_000_000_000);
    assert_eq!(
        form.evaluate(&big(&[12, 30]), 1_000_000_000_000),
        Err(Error::TooLarge {
            level: 1_000_000_000_000,
            bits: 2_000_000_000_000
        })
    );
    // A form whose eigenvalues are all 1 grows only polynomially: fine at any level.
    let linear = rec("[[1,1],[0,1]]", "n,c").closed_form();
    let s = u64::MAX;
    assert_eq!(
        linear.evaluate(&big(&[0, 3]), s).unwrap(),
        vec![BigInt::from(s) * 3, BigInt::from(3)]
    );
}
