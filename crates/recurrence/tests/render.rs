//! Snapshot tests of the text, LaTeX and JSON renderings (expected strings written by hand
//! and checked against powering in `paper.rs` and `closed_form.rs`).

use serde_json::json;

use crate::util::rec;

fn check_text(matrix: &str, names: &str, expected: &str) {
    assert_eq!(
        rec(matrix, names).closed_form().to_text(),
        expected,
        "matrix {matrix}"
    );
}

fn check_latex(matrix: &str, names: &str, expected: &str) {
    assert_eq!(
        rec(matrix, names).closed_form().to_latex(),
        expected,
        "matrix {matrix}"
    );
}

#[test]
fn text() {
    check_text(
        "[[1,1],[0,4]]",
        "V,E",
        "V(s) = V0 + (4^s - 1)/3 * E0\nE(s) = 4^s * E0",
    );
    check_text(
        "[[2,1],[0,2]]",
        "a,b",
        "a(s) = 2^s * a0 + s*2^s/2 * b0\nb(s) = 2^s * b0",
    );
    check_text(
        "[[0,1],[0,0]]",
        "a,b",
        "a(s) = 0 for s >= 2; a(0) = a0; a(1) = b0\nb(s) = 0 for s >= 1; b(0) = b0",
    );
    check_text(
        "[[0,2,0],[0,4,0],[1,1,1]]",
        "V,E,F",
        "V(s) = 4^s/2 * E0 for s >= 1; V(0) = V0\n\
         E(s) = 4^s * E0\n\
         F(s) = V0 + (4^s - 2)/2 * E0 + F0 for s >= 1; F(0) = F0",
    );
    check_text(
        "[[-2,1],[0,3]]",
        "a,b",
        "a(s) = (-2)^s * a0 + (3^s - (-2)^s)/5 * b0\nb(s) = 3^s * b0",
    );
    check_text("[[1,1],[0,1]]", "n,c", "n(s) = n0 + s * c0\nc(s) = c0");
    check_text("[[-1]]", "x", "x(s) = (-1)^s * x0");
    check_text(
        "[[3, 0], [0, 5]]",
        "",
        "x0(s) = 3^s * x0_0\nx1(s) = 5^s * x1_0",
    );
    check_text(
        "[[1,1],[1,0]]",
        "F,G",
        "F(s) = ((1/2+1/10*sqrt(5))*(1/2+1/2*sqrt(5))^s + (1/2-1/10*sqrt(5))*(1/2-1/2*sqrt(5))^s) * F0 \
         + ((1/5*sqrt(5))*(1/2+1/2*sqrt(5))^s + (-1/5*sqrt(5))*(1/2-1/2*sqrt(5))^s) * G0\n\
         G(s) = ((1/5*sqrt(5))*(1/2+1/2*sqrt(5))^s + (-1/5*sqrt(5))*(1/2-1/2*sqrt(5))^s) * F0 \
         + ((1/2-1/10*sqrt(5))*(1/2+1/2*sqrt(5))^s + (1/2+1/10*sqrt(5))*(1/2-1/2*sqrt(5))^s) * G0",
    );
}

#[test]
fn numeric_forms_say_so() {
    let text = rec(
        "[[0,0,0,0,1],[1,0,0,0,0],[0,1,0,0,0],[0,0,1,0,0],[0,0,0,1,0]]",
        "a,b,c,d,e",
    )
    .closed_form()
    .to_text();
    assert!(
        text.starts_with("a(s) ≈ ((0.2)*(-0.809016994375+0.587785252292i)^s"),
        "{text}"
    );
    assert_eq!(text.lines().count(), 5);
    assert!(text.lines().all(|l| l.contains(" ≈ ")));
}

#[test]
fn latex() {
    check_latex(
        "[[1,1],[0,4]]",
        "V,E",
        "V(s) = V_0 + \\frac{4^{s} - 1}{3} E_0\nE(s) = 4^{s} E_0",
    );
    check_latex(
        "[[1,1,1],[0,4,1],[0,0,2]]",
        "V,IE,BE",
        "V(s) = V_0 + \\frac{4^{s} - 1}{3} {IE}_0 + \\frac{4^{s} + 3 \\cdot 2^{s} - 4}{6} {BE}_0\n\
         IE(s) = 4^{s} {IE}_0 + \\frac{4^{s} - 2^{s}}{2} {BE}_0\n\
         BE(s) = 2^{s} {BE}_0",
    );
    check_latex(
        "[[1,1,1],[0,2,4],[0,0,4]]",
        "V,E,F",
        "V(s) = V_0 + \\left(2^{s} - 1\\right) E_0 + \\left(4^{s} - 2 \\cdot 2^{s} + 1\\right) F_0\n\
         E(s) = 2^{s} E_0 + \\left(2 \\cdot 4^{s} - 2 \\cdot 2^{s}\\right) F_0\n\
         F(s) = 4^{s} F_0",
    );
    check_latex(
        "[[0,2,0],[0,4,0],[1,1,1]]",
        "V,E,F",
        "V(s) = \\frac{4^{s}}{2} E_0 \\quad (s \\ge 1), \\quad V(0) = V_0\n\
         E(s) = 4^{s} E_0\n\
         F(s) = V_0 + \\frac{4^{s} - 2}{2} E_0 + F_0 \\quad (s \\ge 1), \\quad F(0) = F_0",
    );
    check_latex(
        "[[2,1],[0,2]]",
        "a,b",
        "a(s) = 2^{s} a_0 + \\frac{s \\, 2^{s}}{2} b_0\nb(s) = 2^{s} b_0",
    );
}

#[test]
fn json() {
    let form = rec("[[1,1],[0,4]]", "V,E").closed_form();
    assert_eq!(
        form.to_json(),
        json!([
            {
                "component": "V", "valid_from": 0, "exact": true,
                "terms": [
                    {"eigenvalue": "4", "s_power": 0, "coefficients": {"V": "0", "E": "1/3"}},
                    {"eigenvalue": "1", "s_power": 0, "coefficients": {"V": "1", "E": "-1/3"}}
                ],
                "early_levels": []
            },
            {
                "component": "E", "valid_from": 0, "exact": true,
                "terms": [
                    {"eigenvalue": "4", "s_power": 0, "coefficients": {"V": "0", "E": "1"}}
                ],
                "early_levels": []
            }
        ])
    );
    let doo = rec("[[0,2,0],[0,4,0],[1,1,1]]", "V,E,F")
        .closed_form()
        .to_json();
    assert_eq!(doo[0]["valid_from"], 1);
    assert_eq!(
        doo[0]["early_levels"],
        json!([{"level": 0, "coefficients": {"V": "1", "E": "0", "F": "0"}}])
    );
    let fib = rec("[[1,1],[1,0]]", "F,G").closed_form().to_json();
    assert_eq!(fib[0]["terms"][0]["eigenvalue"], "1/2+1/2*sqrt(5)");
    assert_eq!(fib[0]["terms"][0]["coefficients"]["F"], "1/2+1/10*sqrt(5)");
    assert_eq!(fib[0]["exact"], true);
    let cycle = rec(
        "[[0,0,0,0,1],[1,0,0,0,0],[0,1,0,0,0],[0,0,1,0,0],[0,0,0,1,0]]",
        "",
    )
    .closed_form()
    .to_json();
    assert_eq!(cycle[0]["exact"], false);
}

/// The JSON contract: component(s) = sum over terms of (sum of coefficient * x(0)) *
/// s^s_power * eigenvalue^s for s >= valid_from, and the early levels below.
#[test]
fn json_terms_reproduce_powering() {
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::Pow;

    for (m, names, x0) in [
        ("[[1,1,1],[0,4,1],[0,0,2]]", "V,IE,BE", vec![9, 10, 6]),
        ("[[0,2,0],[0,4,0],[1,1,1]]", "V,E,F", vec![8, 12, 6]),
        ("[[2,1],[0,2]]", "a,b", vec![3, -5]),
        ("[[-2,1],[0,3]]", "a,b", vec![1, 1]),
    ] {
        let r = rec(m, names);
        let json = r.closed_form().to_json();
        let names: Vec<&str> = names.split(',').collect();
        let x0 = crate::util::big(&x0);
        for s in 0..25u64 {
            let state = r.state_at(&x0, s).unwrap();
            for (i, comp) in json.as_array().unwrap().iter().enumerate() {
                let lin = |coeffs: &serde_json::Value| -> BigRational {
                    names
                        .iter()
                        .zip(&x0)
                        .map(|(n, x)| {
                            coeffs[n].as_str().unwrap().parse::<BigRational>().unwrap()
                                * BigRational::from_integer(x.clone())
                        })
                        .sum()
                };
                let value: BigRational = if s < comp["valid_from"].as_u64().unwrap() {
                    lin(&comp["early_levels"][s as usize]["coefficients"])
                } else {
                    comp["terms"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|t| {
                            let l: BigRational = t["eigenvalue"].as_str().unwrap().parse().unwrap();
                            let p = t["s_power"].as_u64().unwrap();
                            lin(&t["coefficients"])
                                * BigRational::from_integer(Pow::pow(BigInt::from(s), p))
                                * Pow::pow(l, s)
                        })
                        .sum()
                };
                assert_eq!(
                    value,
                    BigRational::from_integer(state[i].clone()),
                    "{m} component {i} level {s}"
                );
            }
        }
    }
}

#[test]
fn forms_render_in_a_chosen_variable() {
    // A Jordan block (powers of the level) and a nilpotent part (a range and an early level).
    let form = rec("[[2,1,0],[0,2,0],[0,0,0]]", "E,F,G").closed_form();
    let text = form.to_text_in("t");
    let latex = form.to_latex_in("t");
    for (rendered, in_s) in [(&text, form.to_text()), (&latex, form.to_latex())] {
        assert!(!rendered.contains('s'), "{rendered}");
        // Exactly the level is renamed: no other `t` appears in these forms.
        assert_eq!(*rendered, in_s.replace('s', "t"));
    }
    assert!(text.contains("t*2^t"), "{text}");
    assert!(latex.contains("t \\, 2^{t}"), "{latex}");
    let late = rec("[[0,1],[0,4]]", "F,H").closed_form();
    assert_eq!(
        late.to_latex_in("t"),
        late.to_latex().replace("(s", "(t").replace("{s}", "{t}")
    );
    assert!(
        late.to_latex_in("t").contains("(t \\ge 1)"),
        "{}",
        late.to_latex_in("t")
    );
    assert!(
        late.to_text_in("t").contains(" for t >= 1; F(0) = F0"),
        "{}",
        late.to_text_in("t")
    );
}
