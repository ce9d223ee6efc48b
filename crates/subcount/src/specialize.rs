//! Closed forms with a mesh's numbers substituted: `formula --base icosahedron` prints
//! `V(s) = 10*4^s + 2` under the symbolic `V(s) = V0 + (4^s - 1)/3 * E0`.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use recurrence::{ClosedForm, Coefficient, Eigenvalue};

/// One line per component, `name(var) = ...` with the initial values `x0` substituted, or
/// `None` when some term is not rational (quadratic surds and numeric forms stay symbolic).
pub(crate) fn specialized_lines(
    form: &ClosedForm,
    x0: &[BigInt],
    var: &str,
) -> Option<Vec<String>> {
    let mut lines = Vec::new();
    for component in form.components() {
        if !component.exact {
            return None;
        }
        let mut terms: Vec<(BigRational, u32, BigRational)> = Vec::new();
        for term in &component.terms {
            let Eigenvalue::Rational(lambda) = &term.eigenvalue else {
                return None;
            };
            let mut c = BigRational::zero();
            for (coefficient, x) in term.coefficients.iter().zip(x0) {
                let Coefficient::Rational(r) = coefficient else {
                    return None;
                };
                c += r * BigRational::from_integer(x.clone());
            }
            if !c.is_zero() {
                terms.push((c, term.s_power, lambda.clone()));
            }
        }
        let mut line = format!("{}({var}) = {}", component.name, render_sum(&terms, var));
        if component.valid_from > 0 {
            let early: Vec<String> = component
                .early_levels
                .iter()
                .map(|e| {
                    let v: BigInt = e.coefficients.iter().zip(x0).map(|(c, x)| c * x).sum();
                    format!("{}({}) = {v}", component.name, e.level)
                })
                .collect();
            line.push_str(&format!(
                " for {var} >= {}; {}",
                component.valid_from,
                early.join(", ")
            ));
        }
        lines.push(line);
    }
    Some(lines)
}

/// `c1*s^k1*l1^s + c2*... `, largest eigenvalue first as the closed form lists them.
fn render_sum(terms: &[(BigRational, u32, BigRational)], var: &str) -> String {
    if terms.is_empty() {
        return "0".to_string();
    }
    let mut out = String::new();
    for (i, (c, k, lambda)) in terms.iter().enumerate() {
        let negative = c.is_negative();
        if i == 0 {
            if negative {
                out.push('-');
            }
        } else {
            out.push_str(if negative { " - " } else { " + " });
        }
        let magnitude = c.abs();
        let mut factors: Vec<String> = Vec::new();
        if *k > 0 {
            factors.push(if *k == 1 {
                var.to_string()
            } else {
                format!("{var}^{k}")
            });
        }
        if !lambda.is_one() {
            let base = if lambda.is_integer() && !lambda.is_negative() {
                lambda.to_string()
            } else {
                format!("({lambda})")
            };
            factors.push(format!("{base}^{var}"));
        }
        let coefficient = if magnitude.is_integer() {
            magnitude.to_string()
        } else {
            format!("({magnitude})")
        };
        if factors.is_empty() {
            out.push_str(&coefficient);
        } else if magnitude.is_one() {
            out.push_str(&factors.join("*"));
        } else {
            out.push_str(&format!("{coefficient}*{}", factors.join("*")));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use recurrence::Recurrence;

    fn lines(matrix: &str, names: &[&str], x0: &[i64]) -> Vec<String> {
        let r = Recurrence::with_names(matrix.parse().unwrap(), names.iter().copied()).unwrap();
        let x0: Vec<BigInt> = x0.iter().map(|&x| BigInt::from(x)).collect();
        specialized_lines(&r.closed_form(), &x0, "s").unwrap()
    }

    #[test]
    fn icosahedron_under_loop() {
        assert_eq!(
            lines("[[1,1],[0,4]]", &["V", "E"], &[12, 30]),
            ["V(s) = 10*4^s + 2", "E(s) = 30*4^s"]
        );
    }

    #[test]
    fn jordan_block_zero_eigenvalue_and_fractions() {
        assert_eq!(
            lines("[[2,1],[0,2]]", &["A", "B"], &[1, 1]),
            ["A(s) = (1/2)*s*2^s + 2^s", "B(s) = 2^s"]
        );
        // Doo-Sabin-like: V forgets its initial value after one step.
        let l = lines("[[0,2,0],[0,4,0],[1,1,1]]", &["V", "E", "F"], &[8, 12, 6]);
        assert_eq!(l[0], "V(s) = 6*4^s for s >= 1; V(0) = 8");
        assert_eq!(l[1], "E(s) = 12*4^s");
    }

    #[test]
    fn irrational_forms_stay_symbolic() {
        let r = Recurrence::new("[[1,1],[1,0]]".parse().unwrap());
        assert!(
            specialized_lines(&r.closed_form(), &[BigInt::from(1), BigInt::from(0)], "s").is_none()
        );
    }
}
