//! Level queries on a linear functional `f(s) = w . M^s x0`: the largest level that stays
//! within a limit, the smallest level that reaches a target.
//!
//! Every value compared is exact (closed-form evaluation or powering); the closed form only
//! bounds the search. Past `valid_from`, `f(s) = sum a p(s) l^s`. Splitting the levels by
//! parity, `g_e(t) = f(2t + e)` has the eigenvalues `l^2`, which are positive for every real
//! `l`, so its dominant term decides its fate: growing (then `g_e` is increasing from a level
//! found by a dominance bound on `g_e(t+1) - g_e(t)`, and the first crossing is found by
//! galloping and bisection), falling, or settling to a constant. Levels below the bound are
//! scanned one by one. Only forms whose dominant eigenvalues are complex fall back to a
//! capped scan.

use nalgebra::Complex;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::closed_form::{Coefficient, Term};
use crate::eigen::Eigenvalue;
use crate::field::{Field, QuadraticSurd};
use crate::power::RingMatrix;
use crate::{ClosedForm, Error, Recurrence, Result};

/// The answer of [`Recurrence::largest_level_within`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LevelBound {
    /// Levels `0..=s` all stay within the limit, and level `s + 1` exceeds it.
    Level(u64),
    /// Level 0 already exceeds the limit.
    NoneFits,
    /// Every level `s: u64` stays within the limit (proven from the closed form).
    Unbounded,
}

/// Levels scanned one by one at most when the closed form cannot bound the search.
const SCAN_CAP: u64 = 10_000;

/// A coefficient, exact where the closed form is.
#[derive(Clone, Debug)]
enum Value {
    Exact(QuadraticSurd),
    Approx(Complex<f64>),
}

impl Value {
    fn to_complex(&self) -> Complex<f64> {
        match self {
            Value::Exact(q) => q.to_f64(),
            Value::Approx(z) => *z,
        }
    }

    fn is_zero(&self) -> bool {
        match self {
            Value::Exact(q) => q.is_field_zero(),
            Value::Approx(z) => z.norm() < 1e-9,
        }
    }

    fn add(&self, o: &Value) -> Value {
        match (self, o) {
            (Value::Exact(a), Value::Exact(b))
                if a.is_rational() || b.is_rational() || a.d == b.d =>
            {
                Value::Exact(a.add(b))
            }
            _ => Value::Approx(self.to_complex() + o.to_complex()),
        }
    }

    fn mul(&self, o: &Value) -> Value {
        match (self, o) {
            (Value::Exact(a), Value::Exact(b))
                if a.is_rational() || b.is_rational() || a.d == b.d =>
            {
                Value::Exact(a.mul(b))
            }
            _ => Value::Approx(self.to_complex() * o.to_complex()),
        }
    }

    fn rational(r: BigRational) -> Value {
        Value::Exact(QuadraticSurd::rational(r))
    }

    /// Natural log of the modulus, robust to magnitudes beyond `f64`.
    fn ln_abs(&self) -> f64 {
        match self {
            Value::Exact(q) if q.is_rational() => ln_rational(&q.a),
            Value::Exact(q) => {
                let z = q.to_f64();
                if z.norm().is_finite() && z.norm() > 0.0 {
                    z.norm().ln()
                } else {
                    ln_rational(&q.a.abs())
                        .max(ln_rational(&q.b.abs()) + 0.5 * ln_bigint(&q.d.abs()))
                }
            }
            Value::Approx(z) => z.norm().ln(),
        }
    }

    /// The sign of a real value (`0` when not clearly real and non-zero).
    fn sign(&self) -> i32 {
        match self {
            Value::Exact(q) if q.is_rational() => {
                if q.a.is_positive() {
                    1
                } else if q.a.is_negative() {
                    -1
                } else {
                    0
                }
            }
            Value::Exact(q) if q.d.is_positive() => {
                // a + b sqrt(d): compare a^2 with b^2 d when the signs differ.
                let sa = q.a.signum();
                let sb = q.b.signum();
                if sa == sb || q.a.is_zero() {
                    if sb.is_positive() {
                        1
                    } else {
                        -1
                    }
                } else {
                    let a2 = &q.a * &q.a;
                    let b2d = &q.b * &q.b * BigRational::from_integer(q.d.clone());
                    let a_wins = a2 > b2d;
                    let positive = if a_wins {
                        sa.is_positive()
                    } else {
                        sb.is_positive()
                    };
                    if positive {
                        1
                    } else {
                        -1
                    }
                }
            }
            _ => {
                let z = self.to_complex();
                if z.im.abs() > 1e-9 * z.norm() {
                    0
                } else if z.re > 0.0 {
                    1
                } else if z.re < 0.0 {
                    -1
                } else {
                    0
                }
            }
        }
    }
}

fn ln_bigint(n: &BigInt) -> f64 {
    let bits = n.bits();
    if bits < 1000 {
        return n.to_f64().map_or(f64::NAN, |x| x.abs().ln());
    }
    let shift = bits - 60;
    let top = (n.abs() >> shift).to_f64().unwrap_or(1.0);
    top.ln() + shift as f64 * std::f64::consts::LN_2
}

fn ln_rational(r: &BigRational) -> f64 {
    ln_bigint(r.numer()) - ln_bigint(r.denom())
}

/// `sum_k coef * t^power * base^t`, one entry per (base, power).
#[derive(Clone, Debug)]
struct ScalarTerm {
    base: Value,
    power: u32,
    coef: Value,
}

fn same_base(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Exact(x), Value::Exact(y)) => x == y,
        _ => (a.to_complex() - b.to_complex()).norm() <= 1e-9 * (1.0 + a.to_complex().norm()),
    }
}

fn push_merged(terms: &mut Vec<ScalarTerm>, base: Value, power: u32, coef: Value) {
    match terms
        .iter_mut()
        .find(|t| t.power == power && same_base(&t.base, &base))
    {
        Some(t) => t.coef = t.coef.add(&coef),
        None => terms.push(ScalarTerm { base, power, coef }),
    }
}

fn eigen_value(e: &Eigenvalue) -> Value {
    match e.to_surd() {
        Some(q) => Value::Exact(q),
        None => Value::Approx(e.to_complex()),
    }
}

fn coef_value(c: &Coefficient) -> Value {
    match c {
        Coefficient::Rational(r) => Value::rational(r.clone()),
        Coefficient::Surd(q) => Value::Exact(q.clone()),
        Coefficient::Numeric(z) => Value::Approx(*z),
    }
}

fn binomial(n: u32, k: u32) -> BigInt {
    let mut r = BigInt::one();
    for i in 0..k {
        r = r * BigInt::from(n - i) / BigInt::from(i + 1);
    }
    r
}

/// `g_e(t) = f(2t + e)` from the terms of `f`.
fn parity_terms(f: &[(Eigenvalue, u32, Value)], e: u32) -> Vec<ScalarTerm> {
    let mut out = Vec::new();
    for (lambda, p, a) in f {
        let l = eigen_value(lambda);
        let base = l.mul(&l);
        let mut c = a.clone();
        if e == 1 {
            c = c.mul(&l);
        }
        // (2t + e)^p = sum_k C(p, k) 2^k e^(p-k) t^k
        for k in 0..=*p {
            if e == 0 && k != *p {
                continue;
            }
            let factor = binomial(*p, k) * (BigInt::one() << k);
            let ck = c.mul(&Value::rational(BigRational::from_integer(factor)));
            push_merged(&mut out, base.clone(), k, ck);
        }
    }
    out.retain(|t| !t.coef.is_zero());
    out
}

/// `g(t + 1) - g(t)`.
fn difference(g: &[ScalarTerm]) -> Vec<ScalarTerm> {
    let mut out = Vec::new();
    for t in g {
        // c (t+1)^p mu^(t+1) - c t^p mu^t = mu^t [c mu sum_k C(p,k) t^k - c t^p]
        let cm = t.coef.mul(&t.base);
        for k in 0..=t.power {
            let ck = cm.mul(&Value::rational(BigRational::from_integer(binomial(
                t.power, k,
            ))));
            push_merged(&mut out, t.base.clone(), k, ck);
        }
        push_merged(
            &mut out,
            t.base.clone(),
            t.power,
            t.coef
                .mul(&Value::rational(BigRational::from_integer(-BigInt::one()))),
        );
    }
    out.retain(|t| !t.coef.is_zero());
    out
}

/// Index of the unique dominant term (largest `|base|`, then largest power), if it is unique
/// and its base is a positive real.
fn positive_dominant(g: &[ScalarTerm]) -> Option<usize> {
    let modulus = |t: &ScalarTerm| t.base.to_complex().norm();
    let best = (0..g.len()).max_by(|&a, &b| {
        modulus(&g[a])
            .total_cmp(&modulus(&g[b]))
            .then(g[a].power.cmp(&g[b].power))
    })?;
    let rb = modulus(&g[best]);
    let ties = g
        .iter()
        .filter(|t| (modulus(t) - rb).abs() <= 1e-12 * rb.max(1.0) && t.power == g[best].power)
        .count();
    (ties == 1 && g[best].base.sign() > 0).then_some(best)
}

/// A level from which the dominant term outweighs twice the sum of all others, for every
/// later level (computed in logarithms, with a factor-2 margin).
fn dominance_start(g: &[ScalarTerm], dom: usize) -> u64 {
    let others = g.len().saturating_sub(1);
    if others == 0 {
        return 0;
    }
    let d = &g[dom];
    let ln_d = d.coef.ln_abs();
    let ln_mu = d.base.to_complex().norm().ln();
    let ln_k = (2.0 * others as f64).ln();
    let mut start = 1u64;
    for (i, t) in g.iter().enumerate() {
        if i == dom {
            continue;
        }
        let ratio = ln_mu - t.base.to_complex().norm().ln(); // >= 0
        let dp = f64::from(d.power) - f64::from(t.power);
        let c = ln_d - t.coef.ln_abs() - ln_k;
        // h(s) = c + dp ln s + s ratio must be > 0 from some s on; h is increasing for
        // s >= s_min.
        let s_min = if ratio > 1e-15 && dp < 0.0 {
            (-dp / ratio).ceil().max(1.0)
        } else {
            1.0
        };
        let h = |s: f64| c + dp * s.ln() + s * ratio;
        let mut hi = s_min;
        while h(hi) <= 0.0 {
            hi *= 2.0;
            if hi > 1e18 {
                return u64::MAX;
            }
        }
        let mut lo = s_min;
        if h(lo) <= 0.0 {
            while hi - lo > 1.0 {
                let mid = ((lo + hi) / 2.0).floor();
                if h(mid) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
        }
        let s_i = if h(lo) > 0.0 { lo } else { hi };
        start = start.max(s_i as u64 + 1);
    }
    start
}

/// Exact values of the functional, with cheap sequential stepping.
struct Functional<'a> {
    rec: &'a Recurrence,
    form: &'a ClosedForm,
    matrix: RingMatrix<BigInt>,
    x0: &'a [BigInt],
    weights: &'a [BigInt],
    last: Option<(u64, Vec<BigInt>)>,
}

impl Functional<'_> {
    fn state(&mut self, s: u64) -> Result<Vec<BigInt>> {
        let state = match self.last.take() {
            Some((l, x)) if l == s => x,
            Some((l, x)) if l + 1 == s => self
                .matrix
                .checked_apply(&x)
                .expect("big integers do not overflow"),
            _ => {
                if self.form.is_exact() {
                    self.form.evaluate(self.x0, s)?
                } else {
                    self.rec.state_at(self.x0, s)?
                }
            }
        };
        self.last = Some((s, state.clone()));
        Ok(state)
    }

    fn value(&mut self, s: u64) -> Result<BigInt> {
        let x = self.state(s)?;
        Ok(self.weights.iter().zip(&x).map(|(w, x)| w * x).sum())
    }
}

impl Recurrence {
    /// The largest level `s` such that `weights . x_k <= limit` for every `k <= s` (the
    /// highest level reachable level by level within a budget).
    ///
    /// `weights` is a linear functional of the state: a unit vector picks one component, and
    /// bytes per vertex/face give a memory size.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] or [`Error::WeightsLength`] for wrong lengths;
    /// [`Error::SearchLimit`] in the rare case that the closed form cannot bound the search
    /// (dominant complex eigenvalues that neither grow nor settle).
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use recurrence::{IntMatrix, LevelBound, Recurrence};
    ///
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// let x0 = [12, 30].map(BigInt::from);
    /// let v = [1, 0].map(BigInt::from);
    /// // V: 12, 42, 162, 642, 2562, ...
    /// assert_eq!(r.largest_level_within(&x0, &v, &BigInt::from(642))?, LevelBound::Level(3));
    /// assert_eq!(r.largest_level_within(&x0, &v, &BigInt::from(11))?, LevelBound::NoneFits);
    /// let u32_max = BigInt::from(u32::MAX);
    /// assert_eq!(r.largest_level_within(&x0, &v, &u32_max)?, LevelBound::Level(14));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn largest_level_within(
        &self,
        x0: &[BigInt],
        weights: &[BigInt],
        limit: &BigInt,
    ) -> Result<LevelBound> {
        Ok(match self.first_level_above(x0, weights, limit)? {
            None => LevelBound::Unbounded,
            Some(0) => LevelBound::NoneFits,
            Some(s) => LevelBound::Level(s - 1),
        })
    }

    /// The smallest level `s` with `weights . x_s >= target`, or `None` when no level
    /// `s: u64` reaches it (proven from the closed form).
    ///
    /// # Errors
    ///
    /// As for [`largest_level_within`](Self::largest_level_within).
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use recurrence::{IntMatrix, Recurrence};
    ///
    /// let r = Recurrence::new("[[1, 1], [0, 4]]".parse::<IntMatrix>()?);
    /// let x0 = [12, 30].map(BigInt::from);
    /// assert_eq!(r.smallest_level_reaching(&x0, &[1, 0].map(BigInt::from), &BigInt::from(643))?, Some(4));
    /// // A constant functional never grows: V - E/3 stays 2.
    /// let w = [3, -1].map(BigInt::from);
    /// assert_eq!(r.smallest_level_reaching(&x0, &w, &BigInt::from(7))?, None);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn smallest_level_reaching(
        &self,
        x0: &[BigInt],
        weights: &[BigInt],
        target: &BigInt,
    ) -> Result<Option<u64>> {
        self.first_level_above(x0, weights, &(target - 1))
    }

    /// The least `s` with `weights . x_s > threshold`, `None` if none.
    fn first_level_above(
        &self,
        x0: &[BigInt],
        weights: &[BigInt],
        threshold: &BigInt,
    ) -> Result<Option<u64>> {
        if x0.len() != self.dim() {
            return Err(Error::InitialLength {
                got: x0.len(),
                expected: self.dim(),
            });
        }
        if weights.len() != self.dim() {
            return Err(Error::WeightsLength {
                got: weights.len(),
                expected: self.dim(),
            });
        }
        let form = self.closed_form();
        let mut f = Functional {
            rec: self,
            form: &form,
            matrix: RingMatrix::from_int(self.matrix()).expect("big integers do not overflow"),
            x0,
            weights,
            last: None,
        };
        // Scalar terms of f for s >= valid.
        let mut valid = 0u64;
        let mut terms: Vec<(Eigenvalue, u32, Value)> = Vec::new();
        for (comp, w) in form.components().iter().zip(weights) {
            if w.is_zero() {
                continue;
            }
            valid = valid.max(comp.valid_from);
            let wv = Value::rational(BigRational::from_integer(w.clone()));
            for Term {
                eigenvalue,
                s_power,
                coefficients,
            } in &comp.terms
            {
                let mut a = Value::rational(BigRational::zero());
                for (c, x) in coefficients.iter().zip(x0) {
                    if !x.is_zero() {
                        a = a.add(
                            &coef_value(c)
                                .mul(&Value::rational(BigRational::from_integer(x.clone()))),
                        );
                    }
                }
                let a = a.mul(&wv);
                match terms
                    .iter_mut()
                    .find(|(e, p, _)| e == eigenvalue && p == s_power)
                {
                    Some((_, _, acc)) => *acc = acc.add(&a),
                    None => terms.push((eigenvalue.clone(), *s_power, a)),
                }
            }
        }
        terms.retain(|(_, _, a)| !a.is_zero());

        // Roots of unity only (orders dividing 12 are all that Q and Q(sqrt d) hold): f is
        // periodic from `valid` on, so one period decides.
        let periodic = terms.iter().all(|(e, p, _)| {
            *p == 0
                && e.to_surd().is_some_and(|q| {
                    crate::closed_form::surd_pow(&q, 12) == QuadraticSurd::field_one()
                })
        });
        if periodic {
            for s in 0..valid.saturating_add(12) {
                if &f.value(s)? > threshold {
                    return Ok(Some(s));
                }
            }
            return Ok(None);
        }

        // Plan per parity class: scan up to a bound, then gallop (growing) or stop.
        let mut scan_to = valid;
        let mut gallop: Vec<u32> = Vec::new();
        let mut settled = true;
        for e in 0..2u32 {
            let g = parity_terms(&terms, e);
            let t0 = valid.div_ceil(2);
            if g.is_empty() {
                continue;
            }
            match positive_dominant(&g) {
                Some(dom) => {
                    let d = &g[dom];
                    let growing = d.base.to_complex().norm() > 1.0 + 1e-12 || d.power > 0;
                    if growing {
                        let dg = difference(&g);
                        let start = match positive_dominant(&dg) {
                            Some(ddom) => dominance_start(&dg, ddom),
                            None => u64::MAX,
                        };
                        let start = start.max(t0);
                        scan_to = scan_to.max(start.saturating_mul(2).saturating_add(1));
                        if d.coef.sign() > 0 {
                            gallop.push(e);
                        }
                    } else if g.len() == 1 && (d.base.to_complex().norm() - 1.0).abs() < 1e-12 {
                        // Constant from t0 on: scanning t0 decides.
                        scan_to = scan_to.max(2 * t0 + 1);
                    } else {
                        settled = false;
                    }
                }
                None => settled = false,
            }
        }
        if !settled {
            return self.capped_scan(&mut f, threshold);
        }
        if scan_to > valid.saturating_add(10 * SCAN_CAP) {
            return Err(Error::SearchLimit { levels: scan_to });
        }
        for s in 0..=scan_to {
            if &f.value(s)? > threshold {
                return Ok(Some(s));
            }
        }
        // Beyond scan_to each galloping class is increasing.
        let mut best: Option<u64> = None;
        for e in gallop {
            let at = |t: u64| t.checked_mul(2).and_then(|s| s.checked_add(u64::from(e)));
            // g_e(lo) <= threshold: level 2 lo + e <= scan_to was scanned.
            let mut lo = scan_to.saturating_sub(u64::from(e)) / 2;
            let mut step = 1u64;
            let hi = loop {
                let t = lo.saturating_add(step);
                let Some(s) = at(t) else {
                    // Beyond u64 levels: check the last representable one.
                    let t_max = (u64::MAX - u64::from(e)) / 2;
                    if t_max > lo && &f.value(2 * t_max + u64::from(e))? > threshold {
                        break t_max;
                    }
                    break u64::MAX;
                };
                if &f.value(s)? > threshold {
                    break t;
                }
                lo = t;
                step = step.saturating_mul(2);
            };
            if hi == u64::MAX {
                continue;
            }
            let (mut lo, mut hi) = (lo, hi);
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if &f.value(2 * mid + u64::from(e))? > threshold {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let s = 2 * hi + u64::from(e);
            best = Some(best.map_or(s, |b| b.min(s)));
        }
        Ok(best)
    }

    fn capped_scan(&self, f: &mut Functional<'_>, threshold: &BigInt) -> Result<Option<u64>> {
        for s in 0..SCAN_CAP {
            if &f.value(s)? > threshold {
                return Ok(Some(s));
            }
        }
        Err(Error::SearchLimit { levels: SCAN_CAP })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::IntMatrix;

    fn r(m: &str) -> Recurrence {
        Recurrence::new(m.parse::<IntMatrix>().unwrap())
    }

    fn b(v: &[i64]) -> Vec<BigInt> {
        v.iter().map(|&x| BigInt::from(x)).collect()
    }

    /// The answer by brute force over levels `0..n`.
    fn brute(
        rec: &Recurrence,
        x0: &[BigInt],
        w: &[BigInt],
        threshold: &BigInt,
        n: u64,
    ) -> Option<u64> {
        rec.states_up_to(x0, n)
            .unwrap()
            .iter()
            .position(|x| &w.iter().zip(x).map(|(w, x)| w * x).sum::<BigInt>() > threshold)
            .map(|p| p as u64)
    }

    #[test]
    fn matches_brute_force_on_small_cases() {
        let cases = [
            ("[[1,1],[0,4]]", vec![12, 30], vec![1, 0]),
            ("[[1,1],[0,4]]", vec![12, 30], vec![3, -1]),
            ("[[1,1],[0,4]]", vec![12, 30], vec![-1, 0]),
            ("[[-2,0],[0,1]]", vec![1, 5], vec![1, 1]),
            ("[[-2,0],[0,2]]", vec![1, 1], vec![1, 1]),
            ("[[-2,0],[0,2]]", vec![1, -1], vec![1, 1]),
            ("[[1,1],[0,1]]", vec![0, 3], vec![1, 0]),
            ("[[1,1],[0,1]]", vec![0, -3], vec![1, 0]),
            ("[[0,1],[0,0]]", vec![5, 9], vec![1, 1]),
            ("[[1,1],[1,0]]", vec![1, 0], vec![1, 0]),
            ("[[-1,0],[0,1]]", vec![4, 1], vec![1, 1]),
            ("[[2,-1],[0,1]]", vec![0, 100], vec![1, 0]),
            ("[[0,0,1],[1,0,0],[0,1,0]]", vec![1, 7, 3], vec![1, 0, 0]),
        ];
        for (m, x0, w) in cases {
            let rec = r(m);
            let (x0, w) = (b(&x0), b(&w));
            for threshold in [-500i64, -3, 0, 1, 5, 6, 40, 100, 1000, 100_000] {
                let t = BigInt::from(threshold);
                let got = rec.first_level_above(&x0, &w, &t).unwrap();
                let want = brute(&rec, &x0, &w, &t, 1000);
                match got {
                    Some(s) if s > 1000 => {
                        // Beyond brute force: check the crossing itself.
                        assert_eq!(want, None);
                        let f = |s| {
                            w.iter()
                                .zip(&rec.state_at(&x0, s).unwrap())
                                .map(|(w, x)| w * x)
                                .sum::<BigInt>()
                        };
                        assert!(
                            f(s) > t && f(s - 1) <= t,
                            "{m} threshold {threshold} level {s}"
                        );
                    }
                    _ => assert_eq!(got, want, "{m} x0 {x0:?} w {w:?} threshold {threshold}"),
                }
            }
        }
    }

    #[test]
    fn polynomial_growth_beyond_brute_force() {
        // n(s) = s * 3: the first level above 10^30 is 10^30/3 + 1 > u64::MAX, so none.
        let rec = r("[[1,1],[0,1]]");
        let t = BigInt::from(10).pow(30);
        assert_eq!(
            rec.first_level_above(&b(&[0, 3]), &b(&[1, 0]), &t).unwrap(),
            None
        );
        let t = BigInt::from(10).pow(15);
        assert_eq!(
            rec.first_level_above(&b(&[0, 3]), &b(&[1, 0]), &t).unwrap(),
            Some(333_333_333_333_334)
        );
    }

    #[test]
    fn wrong_lengths_are_errors() {
        let rec = r("[[1,1],[0,4]]");
        assert_eq!(
            rec.largest_level_within(&b(&[1, 2]), &b(&[1]), &BigInt::from(5)),
            Err(Error::WeightsLength {
                got: 1,
                expected: 2
            })
        );
    }
}
