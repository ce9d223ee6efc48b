//! Digit summaries at levels too high to materialize (`at --level 1000000000000 --summary`),
//! from exact closed forms: state components directly, derived V, E, F through an augmented
//! recurrence and an exact division of the summary.

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use recurrence::{ClosedForm, DigitSummary, IntMatrix, Recurrence};
use schemes::Plan;

use crate::model::Dynamics;

/// Digits kept of each end of a summary.
pub(crate) const DIGITS: usize = 20;

/// The summaries of every column at level `s`, or `None` when some column has no exact
/// closed form (the caller then materializes the counts, under its resource guard).
pub(crate) fn summaries(
    dynamics: &Dynamics,
    form: &ClosedForm,
    x0: &[BigInt],
    s: u64,
) -> Option<Vec<Option<DigitSummary>>> {
    let state = form.summary_at(x0, s, DIGITS).ok()?;
    match dynamics {
        Dynamics::Matrix(_) => Some(state.into_iter().map(Some).collect()),
        Dynamics::Plan(plan) => plan_summaries(dynamics, plan, x0, s, state),
    }
}

fn plan_summaries(
    dynamics: &Dynamics,
    plan: &Plan,
    x0: &[BigInt],
    s: u64,
    state: Vec<DigitSummary>,
) -> Option<Vec<Option<DigitSummary>>> {
    let scheme = plan.first();
    let names = scheme.state_names();
    let derivations = scheme.derivations();
    let mut out = Vec::new();
    for column in dynamics.columns() {
        if let Some(i) = names.iter().position(|n| *n == column) {
            out.push(Some(state[i].clone()));
            continue;
        }
        let Some((_, d)) = derivations
            .iter()
            .find(|(stat, _)| stat.short_name() == column)
        else {
            out.push(None);
            continue;
        };
        out.push(Some(derived_summary(
            scheme.matrix(),
            d.coefficients(),
            d.divisor(),
            x0,
            s,
        )?));
    }
    Some(out)
}

/// The summary of `c . x_s / k` where `x_s = M^s x0`: the recurrence over `(x, y)` with
/// `y_(s+1) = c M x_s` keeps `y_s = c . x_s` at every level (from `y_0 = c . x0`), so its
/// closed form summarizes `y`; the exact quotient by `k` follows from enough digits of `y`.
fn derived_summary(
    m: &IntMatrix,
    c: &[i64],
    k: u64,
    x0: &[BigInt],
    s: u64,
) -> Option<DigitSummary> {
    let n = m.dim();
    let mut rows: Vec<Vec<i64>> = m
        .rows()
        .map(|r| r.iter().copied().chain([0]).collect())
        .collect();
    let mut last = Vec::with_capacity(n + 1);
    for j in 0..n {
        let mut acc: i64 = 0;
        for (i, ci) in c.iter().enumerate() {
            acc = acc.checked_add(ci.checked_mul(m.get(i, j))?)?;
        }
        last.push(acc);
    }
    last.push(0);
    rows.push(last);
    let augmented = Recurrence::new(IntMatrix::try_from_rows(rows).ok()?);
    let y0: BigInt = c
        .iter()
        .zip(x0)
        .map(|(ci, xi)| BigInt::from(*ci) * xi)
        .sum();
    let mut init = x0.to_vec();
    init.push(y0);
    let form = augmented.closed_form();
    if k == 1 {
        return form.summary_at(&init, s, DIGITS).ok()?.pop();
    }
    for wide in [80usize, 200, 600] {
        let y = form.summary_at(&init, s, wide).ok()?.pop()?;
        if let Some(d) = divide_summary(&y, k, wide) {
            return Some(d);
        }
    }
    None
}

/// The summary (DIGITS digits each end) of `y / k`, given `y`'s summary with `wide` digits
/// each end and that `k` divides `y`; `None` in the rare case the leading digits cannot be
/// settled from `wide` digits.
pub(crate) fn divide_summary(y: &DigitSummary, k: u64, wide: usize) -> Option<DigitSummary> {
    let kb = BigInt::from(k);
    if y.digits as usize <= wide {
        // Fully known.
        let mut v: BigInt = y.leading.parse().ok()?;
        if y.negative {
            v = -v;
        }
        let (q, r) = v.div_rem(&kb);
        if !r.is_zero() {
            return None;
        }
        return Some(recurrence::digit_summary(&q, DIGITS));
    }
    // Leading digits: y = L 10^e + r with 0 <= r < 10^e, e = digits - wide > DIGITS.
    let e = y.digits - wide as u64;
    if e <= DIGITS as u64 {
        return None;
    }
    let l: BigInt = y.leading.parse().ok()?;
    let scale = BigInt::from(10u32).pow(DIGITS as u32);
    let lo = (&l * &scale) / &kb;
    let hi = ((&l + 1u32) * &scale - 1u32) / &kb;
    let (lo_s, hi_s) = (lo.to_string(), hi.to_string());
    if lo_s.len() != hi_s.len() || lo_s.len() < DIGITS || lo_s[..DIGITS] != hi_s[..DIGITS] {
        return None;
    }
    let digits = lo_s.len() as u64 + (e - DIGITS as u64);
    // Trailing digits: with k = k1 k2, k2 = 2^a 5^b and k1 coprime to 10, y mod 10^(T)
    // (T = DIGITS + max(a, b)) gives (y / k2) mod 10^DIGITS, and dividing by k1 is
    // multiplying by its inverse mod 10^DIGITS.
    let (mut k1, mut a, mut b) = (k, 0u32, 0u32);
    while k1 % 2 == 0 {
        k1 /= 2;
        a += 1;
    }
    while k1 % 5 == 0 {
        k1 /= 5;
        b += 1;
    }
    let t_digits = DIGITS + a.max(b) as usize;
    if t_digits > wide {
        return None;
    }
    let k2 = BigInt::from(2u32).pow(a) * BigInt::from(5u32).pow(b);
    let tail: BigInt = y.trailing.parse().ok()?;
    let tail = tail % BigInt::from(10u32).pow(t_digits as u32);
    if !(&tail % &k2).is_zero() {
        return None;
    }
    let y_over_k2 = (tail / &k2) % &scale;
    let inverse = mod_inverse(&BigInt::from(k1), &scale)?;
    let trailing = (y_over_k2 * inverse).mod_floor(&scale);
    Some(DigitSummary {
        negative: y.negative,
        digits,
        leading: lo_s[..DIGITS].to_string(),
        trailing: format!("{:0>width$}", trailing.to_string(), width = DIGITS),
    })
}

fn mod_inverse(a: &BigInt, m: &BigInt) -> Option<BigInt> {
    let g = a.extended_gcd(m);
    if !g.gcd.is_one() {
        return None;
    }
    let x = g.x.mod_floor(m);
    Some(if x.is_negative() { x + m } else { x })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn division_of_summaries_is_exact() {
        // y = 3 * 7^300 * 10^5 / 1: check y / k for several k against the exact quotient.
        for k in [3u64, 6, 12, 15, 40, 7 * 16, 1000] {
            let d_exact =
                BigInt::from(7u32).pow(300u32) * BigInt::from(10u32).pow(5u32) + 123456789u64;
            let y = &d_exact * BigInt::from(k);
            let wide = 80;
            let ys = recurrence::digit_summary(&y, wide);
            let got = divide_summary(&ys, k, wide).expect("settled");
            assert_eq!(got, recurrence::digit_summary(&d_exact, DIGITS), "k = {k}");
        }
        // Small values are known fully.
        let ys = recurrence::digit_summary(&BigInt::from(60), 80);
        assert_eq!(divide_summary(&ys, 3, 80).unwrap().leading, "20");
    }
}
