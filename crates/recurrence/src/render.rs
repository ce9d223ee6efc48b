//! Rendering closed forms: plain text, LaTeX and Rust source (JSON: `json.rs`, behind the
//! `json` feature).
//!
//! Text and LaTeX group each component's terms by initial component, like the paper: the
//! coefficient of each initial value is a sum of `n * s^p * l^s` over a common denominator,
//! so `[[1, 1], [0, 4]]` named `V, E` gives `V(s) = V0 + (4^s - 1)/3 * E0`.

use std::fmt::Write as _;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::closed_form::{ClosedForm, Coefficient, ComponentForm};
use crate::eigen::Eigenvalue;

#[derive(Clone, Copy, PartialEq, Eq)]
enum Style {
    Text,
    Latex,
}

/// One signed monomial `n * s^p * l^s` with an integer `n`.
struct Monomial {
    numerator: BigInt,
    atom: String,
}

impl ClosedForm {
    /// The closed forms as plain text, one line per component, joined by `\n`.
    ///
    /// Terms are grouped by initial component over a common denominator (`V0`, `E0` are the
    /// level-0 values); powers read `4^s`, `s*2^s`, `(-1)^s`. A component with a zero
    /// eigenvalue states its range and its early levels (`... for s >= 1; F(0) = F0`).
    /// Components with numeric eigenvalues use `≈` and decimal numbers.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// assert_eq!(r.closed_form().to_text(), "V(s) = V0 + (4^s - 1)/3 * E0\nE(s) = 4^s * E0");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_text(&self) -> String {
        self.to_text_in("s")
    }

    /// [`to_text`](Self::to_text) with the level written `level` instead of `s`: in the
    /// left-hand sides, the powers and the ranges (`V(t) = V0 + (4^t - 1)/3 * E0`). Phases of
    /// periodic schemes read in `t`, the number of periods.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::with_names("[[2, 1], [0, 2]]".parse::<IntMatrix>()?, ["A", "B"])?;
    /// assert_eq!(
    ///     r.closed_form().to_text_in("t"),
    ///     "A(t) = 2^t * A0 + t*2^t/2 * B0\nB(t) = 2^t * B0"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_text_in(&self, level: &str) -> String {
        self.lines(Style::Text, level)
    }

    fn lines(&self, style: Style, level: &str) -> String {
        self.components()
            .iter()
            .map(|c| component_line(c, self.names(), style, level))
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The closed forms as LaTeX, one equation per line (no surrounding environment).
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// assert_eq!(
    ///     r.closed_form().to_latex(),
    ///     "V(s) = V_0 + \\frac{4^{s} - 1}{3} E_0\nE(s) = 4^{s} E_0"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_latex(&self) -> String {
        self.to_latex_in("s")
    }

    /// [`to_latex`](Self::to_latex) with the level written `level` instead of `s`.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// assert_eq!(
    ///     r.closed_form().to_latex_in("t"),
    ///     "V(t) = V_0 + \\frac{4^{t} - 1}{3} E_0\nE(t) = 4^{t} E_0"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_latex_in(&self, level: &str) -> String {
        self.lines(Style::Latex, level)
    }

    /// A compilable Rust function `fn_name(x0: [i128; n], s: u64) -> Option<[i128; n]>`
    /// that computes the state with checked arithmetic and returns `None` on overflow.
    ///
    /// Forms whose eigenvalues are all integers are written out term by term; otherwise
    /// (surds, numeric eigenvalues) the function embeds the matrix and uses checked
    /// exponentiation by squaring, which is exact.
    ///
    /// # Panics
    ///
    /// Panics if `fn_name` is not a valid Rust identifier (a caller bug).
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// let code = r.closed_form().to_rust("loop_counts");
    /// assert!(code.contains("pub fn loop_counts(x0: [i128; 2], s: u64) -> Option<[i128; 2]>"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_rust(&self, fn_name: &str) -> String {
        assert!(
            fn_name
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && fn_name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_'),
            "`{fn_name}` is not a Rust identifier"
        );
        let integer_only = self.is_exact()
            && self.components().iter().all(|c| {
                c.terms
                    .iter()
                    .all(|t| matches!(t.eigenvalue, Eigenvalue::Rational(_)))
            });
        if integer_only {
            rust_closed_form(self, fn_name)
        } else {
            rust_powering(self, fn_name)
        }
    }
}

impl std::fmt::Display for ClosedForm {
    /// The same text as [`ClosedForm::to_text`].
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.to_text())
    }
}

fn variable(name: &str, style: Style) -> String {
    match style {
        Style::Text if name.ends_with(|c: char| c.is_ascii_digit()) => format!("{name}_0"),
        Style::Text => format!("{name}0"),
        Style::Latex => {
            let escaped = name.replace('_', "\\_");
            if escaped.chars().count() == 1 {
                format!("{escaped}_0")
            } else {
                format!("{{{escaped}}}_0")
            }
        }
    }
}

fn lhs(name: &str, style: Style, level: &str) -> String {
    match style {
        Style::Text => format!("{name}({level})"),
        Style::Latex => format!("{}({level})", name.replace('_', "\\_")),
    }
}

/// `s^p l^s` as text or LaTeX, with the level written `level`; empty for the constant
/// `p = 0, l = 1`.
fn atom(eigenvalue: &Eigenvalue, s_power: u32, style: Style, level: &str) -> String {
    let base = match eigenvalue {
        Eigenvalue::Rational(r) if r.is_one() => String::new(),
        Eigenvalue::Rational(r) if r.is_negative() => format!("({r})"),
        Eigenvalue::Rational(r) => r.to_string(),
        Eigenvalue::QuadraticSurd { a, b, d } => {
            let q = crate::QuadraticSurd::new(a.clone(), b.clone(), d.clone());
            format!("({})", surd_string(&q, style))
        }
        Eigenvalue::Numeric(_) => format!("({})", eigenvalue),
    };
    let lam = if base.is_empty() {
        String::new()
    } else {
        match style {
            Style::Text => format!("{base}^{level}"),
            Style::Latex => {
                let b = if base.starts_with('(') {
                    format!("\\left{}\\right)", &base[..base.len() - 1])
                } else {
                    base
                };
                format!("{b}^{{{level}}}")
            }
        }
    };
    let sp = match (s_power, style) {
        (0, _) => String::new(),
        (1, _) => level.to_string(),
        (p, Style::Text) => format!("{level}^{p}"),
        (p, Style::Latex) => format!("{level}^{{{p}}}"),
    };
    match (sp.is_empty(), lam.is_empty()) {
        (true, _) => lam,
        (false, true) => sp,
        (false, false) => match style {
            Style::Text => format!("{sp}*{lam}"),
            Style::Latex => format!("{sp} \\, {lam}"),
        },
    }
}

fn rational_string(r: &BigRational, style: Style) -> String {
    match style {
        Style::Text => r.to_string(),
        Style::Latex if r.is_integer() => r.to_string(),
        Style::Latex => {
            let sign = if r.is_negative() { "-" } else { "" };
            format!("{sign}\\frac{{{}}}{{{}}}", r.numer().abs(), r.denom())
        }
    }
}

fn surd_string(q: &crate::QuadraticSurd, style: Style) -> String {
    match style {
        Style::Text => q.to_string(),
        Style::Latex => {
            if q.is_rational() {
                return rational_string(&q.a, style);
            }
            let mut out = String::new();
            if !q.a.is_zero() {
                out.push_str(&rational_string(&q.a, style));
                out.push_str(if q.b.is_negative() { " - " } else { " + " });
            } else if q.b.is_negative() {
                out.push('-');
            }
            let b = q.b.abs();
            if !b.is_one() {
                out.push_str(&rational_string(&b, style));
            }
            let _ = write!(out, "\\sqrt{{{}}}", q.d);
            out
        }
    }
}

/// `|n| * atom` without sign.
fn monomial_body(m: &Monomial, style: Style) -> String {
    let n = m.numerator.abs();
    if m.atom.is_empty() {
        n.to_string()
    } else if n.is_one() {
        m.atom.clone()
    } else {
        match style {
            Style::Text => format!("{n}*{}", m.atom),
            Style::Latex => format!("{n} \\cdot {}", m.atom),
        }
    }
}

/// Signed sum of monomials, the first sign as a leading `-`.
fn sum_string(monomials: &[Monomial], style: Style) -> String {
    let mut out = String::new();
    for (i, m) in monomials.iter().enumerate() {
        let neg = m.numerator.is_negative();
        if i == 0 {
            if neg {
                out.push('-');
            }
        } else {
            out.push_str(if neg { " - " } else { " + " });
        }
        out.push_str(&monomial_body(m, style));
    }
    out
}

/// The coefficient of one initial value as `(negative, body)`; `body` already includes
/// the variable.
fn group_string(
    monomials: Vec<Monomial>,
    denominator: &BigInt,
    var: &str,
    style: Style,
) -> (bool, String) {
    let mut monomials = monomials;
    let negative = monomials.iter().all(|m| m.numerator.is_negative());
    if negative {
        for m in &mut monomials {
            m.numerator = -&m.numerator;
        }
    }
    let single = monomials.len() == 1;
    let body = if denominator.is_one() {
        if single {
            let b = monomial_body(&monomials[0], style);
            if b == "1" {
                var.to_string()
            } else {
                match style {
                    Style::Text => format!("{b} * {var}"),
                    Style::Latex => format!("{b} {var}"),
                }
            }
        } else {
            let inner = sum_string(&monomials, style);
            match style {
                Style::Text => format!("({inner}) * {var}"),
                Style::Latex => format!("\\left({inner}\\right) {var}"),
            }
        }
    } else {
        let inner = sum_string(&monomials, style);
        match style {
            Style::Text if single => format!("{inner}/{denominator} * {var}"),
            Style::Text => format!("({inner})/{denominator} * {var}"),
            Style::Latex => format!("\\frac{{{inner}}}{{{denominator}}} {var}"),
        }
    };
    (negative, body)
}

/// A group whose terms involve surds or numbers: `(c1*a1 + c2*a2) * X0`.
fn general_group(items: &[(&Coefficient, String)], var: &str, style: Style) -> String {
    let parts: Vec<String> = items
        .iter()
        .map(|(c, atom)| {
            let cs = match c {
                Coefficient::Rational(r) => rational_string(r, style),
                Coefficient::Surd(q) => surd_string(q, style),
                Coefficient::Numeric(_) => c.to_string(),
            };
            let cs = if matches!(c, Coefficient::Rational(_)) {
                cs
            } else {
                match style {
                    Style::Text => format!("({cs})"),
                    Style::Latex => format!("\\left({cs}\\right)"),
                }
            };
            match (atom.is_empty(), style) {
                (true, _) => cs,
                (false, Style::Text) => format!("{cs}*{atom}"),
                (false, Style::Latex) => format!("{cs} \\, {atom}"),
            }
        })
        .collect();
    let inner = parts.join(" + ");
    match style {
        Style::Text => format!("({inner}) * {var}"),
        Style::Latex => format!("\\left({inner}\\right) {var}"),
    }
}

fn component_rhs(c: &ComponentForm, names: &[String], style: Style, level: &str) -> String {
    let mut groups: Vec<(bool, String)> = Vec::new();
    for (j, name) in names.iter().enumerate() {
        let var = variable(name, style);
        let items: Vec<(&Coefficient, &crate::Term)> = c
            .terms
            .iter()
            .map(|t| (&t.coefficients[j], t))
            .filter(|(coef, _)| !coef.is_zero())
            .collect();
        if items.is_empty() {
            continue;
        }
        let rational = items.iter().all(|(coef, t)| {
            matches!(coef, Coefficient::Rational(_))
                && matches!(t.eigenvalue, Eigenvalue::Rational(_))
        });
        if rational {
            let denominator = items.iter().fold(BigInt::one(), |d, (coef, _)| match coef {
                Coefficient::Rational(r) => d.lcm(r.denom()),
                _ => d,
            });
            let monomials = items
                .iter()
                .map(|(coef, t)| Monomial {
                    numerator: match coef {
                        Coefficient::Rational(r) => (r * &denominator).to_integer(),
                        _ => BigInt::zero(),
                    },
                    atom: atom(&t.eigenvalue, t.s_power, style, level),
                })
                .collect();
            groups.push(group_string(monomials, &denominator, &var, style));
        } else {
            let list: Vec<(&Coefficient, String)> = items
                .iter()
                .map(|(coef, t)| (*coef, atom(&t.eigenvalue, t.s_power, style, level)))
                .collect();
            groups.push((false, general_group(&list, &var, style)));
        }
    }
    join_groups(&groups)
}

fn join_groups(groups: &[(bool, String)]) -> String {
    if groups.is_empty() {
        return "0".to_string();
    }
    let mut out = String::new();
    for (i, (neg, body)) in groups.iter().enumerate() {
        if i == 0 {
            if *neg {
                out.push('-');
            }
        } else {
            out.push_str(if *neg { " - " } else { " + " });
        }
        out.push_str(body);
    }
    out
}

/// An integer combination of the initial values, e.g. `V0 + 2 * E0`.
fn integer_combination(coeffs: &[BigInt], names: &[String], style: Style) -> String {
    let groups: Vec<(bool, String)> = coeffs
        .iter()
        .zip(names)
        .filter(|(c, _)| !c.is_zero())
        .map(|(c, name)| {
            let var = variable(name, style);
            let mag = c.abs();
            let body = if mag.is_one() {
                var
            } else {
                match style {
                    Style::Text => format!("{mag} * {var}"),
                    Style::Latex => format!("{mag} {var}"),
                }
            };
            (c.is_negative(), body)
        })
        .collect();
    join_groups(&groups)
}

impl ClosedForm {
    /// The line of component `index` in [`to_text_in`](Self::to_text_in) (or, with `latex`,
    /// [`to_latex_in`](Self::to_latex_in)) for a quantity that the component gives from level
    /// `max(valid_from, the component's valid_from)` on, and that is the integer of `early` at
    /// the levels listed there (the component's own early levels, combinations of the initial
    /// values, at the other levels below its `valid_from`). `None` when there is no such
    /// component.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// # use num_bigint::BigInt;
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// let form = r.closed_form();
    /// assert_eq!(
    ///     form.component_line_from(0, "s", false, 1, &[(0, BigInt::from(7))]).unwrap(),
    ///     "V(s) = V0 + (4^s - 1)/3 * E0 for s >= 1; V(0) = 7"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn component_line_from(
        &self,
        index: usize,
        level: &str,
        latex: bool,
        valid_from: u64,
        early: &[(u64, BigInt)],
    ) -> Option<String> {
        let c = self.components().get(index)?;
        let style = if latex { Style::Latex } else { Style::Text };
        Some(component_line_with(
            c,
            self.names(),
            style,
            level,
            valid_from.max(c.valid_from),
            early,
        ))
    }
}

fn component_line(c: &ComponentForm, names: &[String], style: Style, level: &str) -> String {
    component_line_with(c, names, style, level, c.valid_from, &[])
}

/// [`component_line`] with the range starting at `valid_from` (at least `c.valid_from`) and
/// the levels of `fixed` given as their integers.
fn component_line_with(
    c: &ComponentForm,
    names: &[String],
    style: Style,
    level: &str,
    valid_from: u64,
    fixed: &[(u64, BigInt)],
) -> String {
    let eq = match (c.exact, style) {
        (true, _) => "=",
        (false, Style::Text) => "≈",
        (false, Style::Latex) => "\\approx",
    };
    let mut line = format!(
        "{} {eq} {}",
        lhs(&c.name, style, level),
        component_rhs(c, names, style, level)
    );
    if valid_from > 0 {
        let (range, separator, name) = match style {
            Style::Text => (
                format!(" for {level} >= {valid_from}"),
                "; ",
                c.name.clone(),
            ),
            Style::Latex => (
                format!(" \\quad ({level} \\ge {valid_from})"),
                ", \\quad ",
                c.name.replace('_', "\\_"),
            ),
        };
        line.push_str(&range);
        for l in 0..valid_from {
            let value = if let Some((_, v)) = fixed.iter().find(|(k, _)| *k == l) {
                v.to_string()
            } else if let Some(e) = c.early_levels.iter().find(|e| e.level == l) {
                integer_combination(&e.coefficients, names, style)
            } else {
                continue;
            };
            let _ = write!(line, "{separator}{name}({l}) = {value}");
        }
    }
    line
}

fn snake(name: &str) -> String {
    let s: String = name.to_lowercase();
    let ident = if s.chars().next().is_some_and(|c| c.is_ascii_alphabetic()) {
        s
    } else {
        format!("c_{s}")
    };
    match ident.as_str() {
        "s" | "x0" | "si" | "dot" | "pow" | "as" | "fn" | "if" | "in" | "let" | "use" | "mod"
        | "ref" | "mut" | "pub" | "for" | "dyn" | "box" | "try" | "type" | "loop" | "self"
        | "impl" | "move" | "true" | "enum" | "else" | "false" | "match" | "const" | "crate"
        | "super" | "trait" | "where" | "while" | "async" | "await" | "break" | "struct"
        | "static" | "return" | "extern" | "unsafe" | "continue" | "gen" | "become" | "do"
        | "final" | "macro" | "override" | "priv" | "typeof" | "unsized" | "virtual" | "yield"
        | "abstract" => format!("{ident}_"),
        _ => ident,
    }
}

/// Distinct local variable names for the components (names differing only in case, such
/// as `V` and `v`, would otherwise collide).
fn rust_variables(form: &ClosedForm) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for (i, c) in form.components().iter().enumerate() {
        let mut v = snake(&c.name);
        if out.contains(&v) {
            v = format!("{v}_{i}");
        }
        out.push(v);
    }
    out
}

fn rust_header(form: &ClosedForm, fn_name: &str, how: &str) -> String {
    let n = form.names().len();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "/// The state ({}) at level `s` from the level-0 state `x0`, {how}.",
        form.names().join(", ")
    );
    let _ = writeln!(out, "///");
    let _ = writeln!(
        out,
        "/// Generated by the `recurrence` crate from the matrix `{}`.",
        form.matrix()
    );
    let _ = writeln!(out, "/// Returns `None` when a value overflows `i128`.");
    let _ = writeln!(
        out,
        "pub fn {fn_name}(x0: [i128; {n}], s: u64) -> Option<[i128; {n}]> {{"
    );
    out
}

fn rust_closed_form(form: &ClosedForm, fn_name: &str) -> String {
    let n = form.names().len();
    let mut out = rust_header(form, fn_name, "by its exact closed form");
    out.push_str(
        "    fn dot(c: &[i128], x: &[i128]) -> Option<i128> {\n        c.iter().zip(x).try_fold(0i128, |acc, (c, x)| acc.checked_add(c.checked_mul(*x)?))\n    }\n",
    );
    let uses_pow = form
        .components()
        .iter()
        .flat_map(|c| &c.terms)
        .any(|t| t.eigenvalue.as_rational().is_some_and(|r| !r.is_one()));
    if uses_pow {
        out.push_str(
        "    fn pow(base: i128, s: u64) -> Option<i128> {\n        match base {\n            0 => Some(i128::from(s == 0)),\n            1 => Some(1),\n            -1 => Some(if s % 2 == 0 { 1 } else { -1 }),\n            _ => base.checked_pow(u32::try_from(s).ok()?),\n        }\n    }\n",
    );
    }
    let mut uses_s = false;
    let mut bodies = Vec::new();
    let vars = rust_variables(form);
    for (c, var) in form.components().iter().zip(&vars) {
        let mut denominator = BigInt::one();
        for t in &c.terms {
            for coef in &t.coefficients {
                if let Coefficient::Rational(r) = coef {
                    denominator = denominator.lcm(r.denom());
                }
            }
        }
        let mut expr = String::from("0i128");
        for t in &c.terms {
            let nums: Vec<String> = t
                .coefficients
                .iter()
                .map(|coef| match coef {
                    Coefficient::Rational(r) => (r * &denominator).to_integer().to_string(),
                    _ => "0".to_string(),
                })
                .collect();
            let lambda = t
                .eigenvalue
                .as_rational()
                .map(|r| r.to_integer())
                .unwrap_or_default();
            let mut term = format!("dot(&[{}], &x0)?", nums.join(", "));
            if t.s_power > 0 {
                uses_s = true;
                if t.s_power == 1 {
                    term.push_str(".checked_mul(si)?");
                } else {
                    let _ = write!(term, ".checked_mul(si.checked_pow({})?)?", t.s_power);
                }
            }
            if !lambda.is_one() {
                let _ = write!(term, ".checked_mul(pow({lambda}, s)?)?");
            }
            expr = if expr == "0i128" {
                term
            } else {
                format!("{expr}.checked_add({term})?")
            };
        }
        if !denominator.is_one() {
            expr = format!("{expr}.checked_div({denominator})?");
        }
        let mut body = String::new();
        if c.valid_from > 0 {
            for l in &c.early_levels {
                let coeffs: Vec<String> = l.coefficients.iter().map(BigInt::to_string).collect();
                let kw = if l.level == 0 { "if" } else { "} else if" };
                let _ = writeln!(
                    body,
                    "    {kw} s == {} {{\n        dot(&[{}], &x0)?",
                    l.level,
                    coeffs.join(", ")
                );
            }
            let _ = writeln!(body, "    }} else {{\n        {expr}\n    }};");
            bodies.push(format!("    let {var} = {}", body.trim_start()));
        } else {
            bodies.push(format!("    let {var} = {expr};\n"));
        }
    }
    if uses_s {
        out.push_str("    let si = i128::from(s);\n");
    }
    for b in bodies {
        out.push_str(&b);
    }
    let _ = writeln!(out, "    Some([{}])", vars.join(", "));
    out.push_str("}\n");
    debug_assert_eq!(vars.len(), n);
    out
}

fn rust_powering(form: &ClosedForm, fn_name: &str) -> String {
    let n = form.names().len();
    let mut out = rust_header(
        form,
        fn_name,
        "by checked exponentiation by squaring (its closed form is not over the integers)",
    );
    let rows: Vec<String> = form
        .matrix()
        .rows()
        .map(|r| {
            format!(
                "[{}]",
                r.iter().map(i64::to_string).collect::<Vec<_>>().join(", ")
            )
        })
        .collect();
    let _ = writeln!(
        out,
        "    const M: [[i128; {n}]; {n}] = [{}];",
        rows.join(", ")
    );
    let _ = writeln!(out, "    type Mat = [[i128; {n}]; {n}];");
    out.push_str(
        "    fn mul(a: &Mat, b: &Mat) -> Option<Mat> {\n        let mut c = [[0i128; N]; N];\n        for (ci, ai) in c.iter_mut().zip(a) {\n            for (j, cij) in ci.iter_mut().enumerate() {\n                *cij = ai.iter().zip(b).try_fold(0i128, |acc, (x, bk)| acc.checked_add(x.checked_mul(bk[j])?))?;\n            }\n        }\n        Some(c)\n    }\n",
    );
    let _ = writeln!(out, "    const N: usize = {n};");
    out.push_str(
        "    let mut x = x0;\n    let mut base = M;\n    let mut e = s;\n    while e > 0 {\n        if e & 1 == 1 {\n            let mut y = [0i128; N];\n            for (yi, row) in y.iter_mut().zip(&base) {\n                *yi = row.iter().zip(&x).try_fold(0i128, |acc, (m, v)| acc.checked_add(m.checked_mul(*v)?))?;\n            }\n            x = y;\n        }\n        e >>= 1;\n        if e > 0 {\n            base = mul(&base, &base)?;\n        }\n    }\n    Some(x)\n}\n",
    );
    out
}
