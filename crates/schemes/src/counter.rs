//! [`Counter`]: the one counting object. It wraps a bare matrix with named components or a
//! scheme [`Plan`] (a built-in, a custom scheme or a composition) and owns everything that
//! counts: the choice between powering and the closed form, the table's columns and rows,
//! size estimates for resource guards, digit summaries of levels too high to materialize,
//! and closed forms with an initial state substituted.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `Counter` (`counter.rs`) is **the counting object**: a bare matrix with named components
//! (`Counter::Matrix`) or a `Plan` (`Counter::Plan`), and the one owner of
//!
//! - counting: `state_at` powers the matrix, or past level 64 evaluates the exact closed form
//!   (powers of two become shifts), within `CLOSED_FORM_LIMIT`;
//! - table columns and rows: `columns` (every stage's state, then the V, E, F it lacks),
//!   `row_from_state`, `row_at`, `rows`;
//! - size estimates for resource guards: `estimated_log10`, exact up to 64 levels past the last
//!   change of rule of the stage that produces the level, then `ClosedForm::estimated_bits` of
//!   that stage's steady rule (a later stage starting from counts of more than 10^5 digits grows
//!   from the estimate there; nothing huge is materialized, no level arithmetic wraps);
//! - digit summaries of levels too high to materialize: `summaries` (derived V, E, F through an
//!   augmented recurrence `y_(s+1) = c M x_s` and an exact division of the summary);
//! - closed forms with an initial state substituted: `specialized_text`, and
//!   `specialized_lines` in any variable name (`s`, or `t` within a phase).
//!
//! Owner of counting (a matrix, a scheme, a custom scheme or a composition): powering vs closed
//! form, table columns and rows, size estimates, digit summaries of huge levels, closed forms with
//! a state substituted: `schemes::Counter` (`crates/schemes/src/counter.rs`).

use std::ops::RangeInclusive;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use recurrence::{ClosedForm, Coefficient, DigitSummary, Eigenvalue, IntMatrix, Recurrence};

use crate::{Plan, Result, Scheme};

/// The largest [`Recurrence::closed_form_cost`] a [`Counter`] computes unasked (about 20
/// components with entries up to 10^4, a second or two in a debug build). Above it, counts
/// come from powering, which is exact too.
pub const CLOSED_FORM_LIMIT: u64 = 1 << 22;

/// Digits kept of each end of a [`Counter::summaries`] summary.
pub const SUMMARY_DIGITS: usize = 20;

/// Up to this level (past the last change of rule), counts are computed exactly by powering
/// rather than through the closed form, and size estimates are exact.
const EXACT_LEVELS: u64 = 64;

/// Past this many steps, [`Counter::estimated_log10`] grows by the closed form's rate per
/// step rather than asking it for the bits at the level (which saturate at `u64::MAX`).
const RATE_STEPS: u64 = 1 << 40;

/// The largest count (as a log10) from which [`Counter::estimated_log10`] computes a later
/// stage's state exactly; past it, the stage grows from the estimate at its first level.
const AFFORDABLE_LOG10: f64 = 1e5;

/// One row of a counts table: a level and one value per [`Counter::columns`] entry (`None`
/// where the level's scheme has no such count).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    /// The level.
    pub level: u64,
    /// One value per column.
    pub values: Vec<Option<BigInt>>,
}

/// What is counted: a bare matrix or a scheme plan.
///
/// # Example
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::{Counter, Plan};
///
/// let counter = Counter::from(Plan::parse("loop")?);
/// assert_eq!(counter.columns(), ["V", "E", "F"]);
/// let x0 = [12, 30].map(BigInt::from);
/// let row = counter.row_at(&x0, 2)?;
/// assert_eq!(row.values, [162, 480, 320].map(|v| Some(BigInt::from(v))));
/// // At a level far beyond memory, the closed form summarizes every count.
/// let sums = counter.summaries(&x0, 1_000_000_000_000, false).unwrap();
/// assert_eq!(sums[0].as_ref().unwrap().digits, 602_059_991_329);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Counter {
    /// A bare matrix with named components.
    Matrix(Recurrence),
    /// A scheme, a custom scheme or a composition.
    Plan(Plan),
}

impl From<Recurrence> for Counter {
    fn from(r: Recurrence) -> Counter {
        Counter::Matrix(r)
    }
}

impl From<Plan> for Counter {
    fn from(plan: Plan) -> Counter {
        Counter::Plan(plan)
    }
}

impl From<Scheme> for Counter {
    fn from(scheme: Scheme) -> Counter {
        Counter::Plan(Plan::single(scheme))
    }
}

impl Counter {
    /// The plan, when this counts a scheme.
    pub fn plan(&self) -> Option<&Plan> {
        match self {
            Counter::Matrix(_) => None,
            Counter::Plan(plan) => Some(plan),
        }
    }

    /// The names of the initial state.
    pub fn state_names(&self) -> &[String] {
        match self {
            Counter::Matrix(r) => r.names(),
            Counter::Plan(plan) => plan.state_names(),
        }
    }

    /// The number of components of the initial state.
    pub fn dim(&self) -> usize {
        self.state_names().len()
    }

    /// The columns of a counts table: the state in order, then whichever of V, E, F the state
    /// lacks (for a composition, every stage's state in order of appearance).
    ///
    /// ```
    /// let plan = schemes::Plan::parse("loop-boundary:1,catmull-clark")?;
    /// assert_eq!(schemes::Counter::from(plan).columns(), ["V", "IE", "BE", "F", "H", "E"]);
    /// # Ok::<(), schemes::Error>(())
    /// ```
    pub fn columns(&self) -> Vec<String> {
        let plan = match self {
            Counter::Matrix(r) => return r.names().to_vec(),
            Counter::Plan(plan) => plan,
        };
        let mut cols: Vec<String> = Vec::new();
        for stage in plan.stages() {
            for name in stage.scheme().state_names() {
                if !cols.contains(name) {
                    cols.push(name.clone());
                }
            }
        }
        if plan.has_mesh_counts() {
            for vef in ["V", "E", "F"] {
                if !cols.iter().any(|c| c == vef) {
                    cols.push(vef.to_string());
                }
            }
        }
        cols
    }

    /// The UV values of a mesh whose UV layout has the statistics `uv`, counted by this
    /// counter's plan ([`UvCounter`](crate::uv::UvCounter)); the `UV` column of its tables.
    ///
    /// # Errors
    ///
    /// [`NotCounted`](crate::uv::NotCounted) for a bare matrix and for a plan with a stage
    /// without a UV recurrence (a scheme without a rule, a composition of a dual rule with a
    /// rule of the other kind: [`NotCounted`](crate::uv::NotCounted)).
    pub fn uv_counter(
        &self,
        uv: &crate::uv::UvCounts,
    ) -> std::result::Result<crate::uv::UvCounter, crate::uv::NotCounted> {
        match self {
            Counter::Matrix(_) => Err(crate::uv::NotCounted::rule(None)),
            Counter::Plan(plan) => crate::uv::UvCounter::new(plan, uv.clone()),
        }
    }

    /// The closed form that gives the state at every level directly, when there is one (a
    /// bare matrix, or a single scheme without a first step or a cycle) and its
    /// [`closed_form_cost`](Recurrence::closed_form_cost) is within `cost_limit`.
    pub fn direct_form(&self, cost_limit: u64) -> Option<ClosedForm> {
        match self {
            Counter::Matrix(r) => r.closed_form_within(cost_limit).ok(),
            Counter::Plan(plan) => match plan.phases().as_slice() {
                [only]
                    if only.first_level == 0 && only.period == 1 && only.last_level.is_none() =>
                {
                    only.recurrence.closed_form_within(cost_limit).ok()
                }
                _ => None,
            },
        }
    }

    /// The recurrences whose closed forms `formula` renders: the matrix, or one per phase of
    /// the plan (with the phase's description when there are several).
    pub fn form_recurrences(&self) -> Vec<(Option<String>, Recurrence)> {
        match self {
            Counter::Matrix(r) => vec![(None, r.clone())],
            Counter::Plan(plan) => {
                let phases = plan.phases();
                let single = phases.len() == 1;
                phases
                    .into_iter()
                    .map(|p| ((!single).then_some(p.description), p.recurrence))
                    .collect()
            }
        }
    }

    /// The state at level `s`, by the fastest exact path: past level 64 the closed form when
    /// all its eigenvalues are integers (powers of two become shifts), matrix powering
    /// otherwise (a quadratic surd's powers are rationals whose reductions cost quadratic
    /// time in their digits: 24 s at level 40,000 where powering takes milliseconds).
    ///
    /// # Errors
    ///
    /// A wrong-length state, or a level beyond a bounded plan.
    pub fn state_at(&self, x0: &[BigInt], s: u64) -> Result<Vec<BigInt>> {
        if s > EXACT_LEVELS {
            if let Some(form) = self.direct_form(CLOSED_FORM_LIMIT).filter(integer_spectrum) {
                if let Ok(state) = form.evaluate(x0, s) {
                    return Ok(state);
                }
            }
        }
        match self {
            Counter::Matrix(r) => Ok(r.state_at(x0, s)?),
            Counter::Plan(plan) => plan.state_at(x0, s),
        }
    }

    /// The row of [`columns`](Self::columns) at `level`, given the state there.
    ///
    /// # Errors
    ///
    /// A level beyond a bounded plan, or derived counts that are not integers.
    pub fn row_from_state(&self, level: u64, state: Vec<BigInt>) -> Result<Row> {
        let plan = match self {
            Counter::Matrix(_) => {
                return Ok(Row {
                    level,
                    values: state.into_iter().map(Some).collect(),
                })
            }
            Counter::Plan(plan) => plan,
        };
        let names = plan.state_names_at(level)?;
        let vef = if plan.has_mesh_counts() {
            Some(plan.vef(level, &state)?)
        } else {
            None
        };
        let values = self
            .columns()
            .iter()
            .map(|col| {
                if let Some(i) = names.iter().position(|n| n == col) {
                    return Some(state[i].clone());
                }
                let k = ["V", "E", "F"].iter().position(|v| v == col)?;
                vef.as_ref().map(|v| v[k].clone())
            })
            .collect();
        Ok(Row { level, values })
    }

    /// The row at one level.
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at) and [`row_from_state`](Self::row_from_state).
    pub fn row_at(&self, x0: &[BigInt], s: u64) -> Result<Row> {
        let state = self.state_at(x0, s)?;
        self.row_from_state(s, state)
    }

    /// The rows for a range of levels, one matrix-vector product per level.
    ///
    /// # Errors
    ///
    /// As [`row_at`](Self::row_at).
    pub fn rows(&self, x0: &[BigInt], levels: RangeInclusive<u64>) -> Result<Vec<Row>> {
        let (start, end) = (*levels.start(), *levels.end());
        let states: Vec<(u64, Vec<BigInt>)> = match self {
            Counter::Matrix(r) => {
                let first = r.state_at(x0, start)?;
                let states = r.states_up_to(&first, end - start)?;
                (start..=end).zip(states).collect()
            }
            Counter::Plan(plan) if start <= EXACT_LEVELS => {
                let states = plan.states_up_to(x0, end)?;
                (0..=end).zip(states).skip(start as usize).collect()
            }
            Counter::Plan(plan) => (start..=end)
                .map(|s| plan.state_at(x0, s).map(|x| (s, x)))
                .collect::<Result<_>>()?,
        };
        states
            .into_iter()
            .map(|(s, x)| self.row_from_state(s, x))
            .collect()
    }

    /// An estimate of log10 of the largest count at level `s`, for resource guards: exact up
    /// to 64 levels past the last change of rule of the stage that produces `s`, then the
    /// largest count there grown by [`ClosedForm::estimated_bits`] of that stage's steady
    /// rule (one full cycle of a periodic scheme); when that closed form would cost more
    /// than [`CLOSED_FORM_LIMIT`], by the largest absolute row sum of the matrix, an upper
    /// bound of its growth. A later stage whose first level holds counts of more than 10^5
    /// digits grows from the estimate there, so nothing huge is materialized.
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at).
    pub fn estimated_log10(&self, x0: &[BigInt], s: u64) -> Result<f64> {
        let plan = match self {
            Counter::Matrix(r) => {
                if s <= EXACT_LEVELS {
                    return Ok(largest_log10(&r.state_at(x0, s)?).max(0.0));
                }
                let start = largest_log10(&r.state_at(x0, 0)?);
                return Ok(grown(start, r, s));
            }
            Counter::Plan(plan) => plan,
        };
        // The stage that produces level `s`, from its first level `a` on; its rule settles
        // after a first step and one cycle.
        let i = plan.stage_index_at(s)?;
        let stages = plan.stages();
        let a = stages[..i]
            .iter()
            .map(|st| st.levels().unwrap_or(0))
            .fold(0u64, u64::saturating_add);
        let scheme = stages[i].scheme();
        let base = a.saturating_add(scheme.period()).saturating_add(1);
        // A later stage starts from an exact state only when that state is affordable;
        // otherwise from the estimate at its first level.
        let exact_start = i == 0 || self.estimated_log10(x0, a)? <= AFFORDABLE_LOG10;
        if exact_start && s <= base.saturating_add(EXACT_LEVELS) {
            return Ok(largest_log10(&plan.state_at(x0, s)?).max(0.0));
        }
        let (from, start) = if exact_start {
            (base, largest_log10(&plan.state_at(x0, base)?))
        } else {
            (a, self.estimated_log10(x0, a)?)
        };
        let steps = (s - from).div_ceil(scheme.period().max(1));
        Ok(grown(start, &cycle_recurrence(scheme), steps))
    }

    /// Digit summaries ([`SUMMARY_DIGITS`] each end) of every column at level `s`, from the
    /// exact direct closed form, whatever the level; `None` when there is none (a periodic
    /// or composed scheme, an irrational eigenvalue (its summaries cost quadratic time in the
    /// digits: the caller powers under its digit guard instead), or a closed form costing more than
    /// [`CLOSED_FORM_LIMIT`] without `allow_large`), or when some derived column cannot be
    /// summarized. Columns the counter does not count are `None` inside.
    ///
    /// A derived count `c . x_s / k` is summarized through the recurrence over `(x, y)` with
    /// `y_(s+1) = c M x_s`, which keeps `y_s = c . x_s`, and an exact division of `y`'s
    /// summary by `k`.
    pub fn summaries(
        &self,
        x0: &[BigInt],
        s: u64,
        allow_large: bool,
    ) -> Option<Vec<Option<DigitSummary>>> {
        let limit = if allow_large {
            u64::MAX
        } else {
            CLOSED_FORM_LIMIT
        };
        let form = self.direct_form(limit).filter(integer_spectrum)?;
        let state = form.summary_at(x0, s, SUMMARY_DIGITS).ok()?;
        let plan = match self {
            Counter::Matrix(_) => return Some(state.into_iter().map(Some).collect()),
            Counter::Plan(plan) => plan,
        };
        let scheme = plan.first();
        let names = scheme.state_names();
        let derivations = scheme.derivations();
        let mut out = Vec::new();
        for column in self.columns() {
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
            let summary = derived_summary(scheme.matrix(), d.coefficients(), d.divisor(), x0, s);
            out.push(Some(summary?));
        }
        Some(out)
    }

    /// The closed forms with the initial values `x0` substituted, as text: a heading
    /// `# with V(0) = 12, E(0) = 30`, then one line per component (`V(s) = 10*4^s + 2`), in
    /// one block per phase for a periodic or composed scheme (in the phase variable `t`).
    pub fn specialized_text(&self, x0: &[BigInt]) -> String {
        let given: Vec<String> = self
            .state_names()
            .iter()
            .zip(x0)
            .map(|(n, v)| format!("{n}(0) = {v}"))
            .collect();
        let mut text = format!("# with {}\n", given.join(", "));
        let symbolic = "(not rational: see the symbolic form above)".to_string();
        let plan = match self {
            Counter::Matrix(r) => {
                let lines = specialized_lines(&r.closed_form(), x0, "s");
                text.push_str(&lines.map_or(symbolic, |l| l.join("\n")));
                return text;
            }
            Counter::Plan(plan) => plan,
        };
        let phases = plan.phases();
        let single = phases.len() == 1 && phases[0].first_level == 0 && phases[0].period == 1;
        for phase in &phases {
            let var = if single { "s" } else { "t" };
            let start = match plan.phase_initial(phase, x0) {
                Ok(start) => start,
                Err(e) => {
                    text.push_str(&format!("{}: {e}\n", phase.description));
                    continue;
                }
            };
            if !single {
                text.push_str(&format!("{}:\n", phase.description));
            }
            let lines = specialized_lines(&phase.recurrence.closed_form(), &start, var);
            text.push_str(&lines.map_or(symbolic.clone(), |l| l.join("\n")));
            text.push('\n');
        }
        text
    }
}

/// log10 |v| (negative infinity for zero), from the top 60 bits.
///
/// ```
/// use num_bigint::BigInt;
/// assert!((schemes::log10_abs(&BigInt::from(-1000)) - 3.0).abs() < 1e-12);
/// assert_eq!(schemes::log10_abs(&BigInt::from(0)), f64::NEG_INFINITY);
/// ```
pub fn log10_abs(v: &BigInt) -> f64 {
    let bits = v.bits();
    if bits == 0 {
        return f64::NEG_INFINITY;
    }
    let shift = bits.saturating_sub(60);
    // At most 60 bits: exact in u64, and within f64's relative precision.
    let top = u64::try_from(v.magnitude() >> shift).map_or(1.0, |t| t as f64);
    top.log10() + shift as f64 * std::f64::consts::LOG10_2
}

/// log10 of the largest magnitude in `state` (negative infinity when every entry is zero).
fn largest_log10(state: &[BigInt]) -> f64 {
    state
        .iter()
        .map(log10_abs)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// `start` (a log10) grown by `steps` steps of `steady`: by [`ClosedForm::estimated_bits`]
/// of its closed form, or, when that would cost more than [`CLOSED_FORM_LIMIT`], by the
/// largest absolute row sum of the matrix, an upper bound of its growth. Zero counts stay
/// zero (an estimate of 0 digits).
fn grown(start: f64, steady: &Recurrence, steps: u64) -> f64 {
    if start == f64::NEG_INFINITY {
        return 0.0;
    }
    let bits = match steady.closed_form_within(CLOSED_FORM_LIMIT) {
        // `estimated_bits` saturates at `u64::MAX` bits: past 2^40 steps, grow by its
        // rate over 2^40 steps instead (exact to about 2^-40 bits a step).
        Ok(form) if steps > RATE_STEPS => {
            form.estimated_bits(RATE_STEPS) as f64 / RATE_STEPS as f64 * steps as f64
        }
        Ok(form) => form.estimated_bits(steps) as f64,
        Err(_) => {
            let norm = steady
                .matrix()
                .rows()
                .map(|r| r.iter().map(|x| x.unsigned_abs() as f64).sum::<f64>())
                .fold(1.0, f64::max);
            steps as f64 * norm.log2()
        }
    };
    (start + bits * std::f64::consts::LOG10_2).max(0.0)
}

/// The matrix of one full cycle of a scheme (its steady matrix when it is not periodic).
fn cycle_recurrence(scheme: &Scheme) -> Recurrence {
    let mut product = scheme.cycle()[0].clone();
    for m in &scheme.cycle()[1..] {
        // Only used for size estimates: on overflow, fall back to the steady matrix.
        match m.checked_mul(&product) {
            Some(p) => product = p,
            None => return scheme.recurrence().clone(),
        }
    }
    Recurrence::new(product)
}

/// The summary of `c . x_s / k` where `x_s = M^s x0` (see [`Counter::summaries`]).
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
        return form.summary_at(&init, s, SUMMARY_DIGITS).ok()?.pop();
    }
    for wide in [80usize, 200, 600] {
        let y = form.summary_at(&init, s, wide).ok()?.pop()?;
        if let Some(d) = divide_summary(&y, k, wide) {
            return Some(d);
        }
    }
    None
}

/// The summary ([`SUMMARY_DIGITS`] each end) of `y / k`, given `y`'s summary with `wide`
/// digits each end and that `k` divides `y`; `None` in the rare case the leading digits
/// cannot be settled from `wide` digits.
fn divide_summary(y: &DigitSummary, k: u64, wide: usize) -> Option<DigitSummary> {
    const D: usize = SUMMARY_DIGITS;
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
        return Some(recurrence::digit_summary(&q, D));
    }
    // Leading digits: y = L 10^e + r with 0 <= r < 10^e, e = digits - wide > D.
    let e = y.digits - wide as u64;
    if e <= D as u64 {
        return None;
    }
    let l: BigInt = y.leading.parse().ok()?;
    let scale = BigInt::from(10u32).pow(D as u32);
    let lo = (&l * &scale) / &kb;
    let hi = ((&l + 1u32) * &scale - 1u32) / &kb;
    let (lo_s, hi_s) = (lo.to_string(), hi.to_string());
    if lo_s.len() != hi_s.len() || lo_s.len() < D || lo_s[..D] != hi_s[..D] {
        return None;
    }
    let digits = lo_s.len() as u64 + (e - D as u64);
    // Trailing digits: with k = k1 k2, k2 = 2^a 5^b and k1 coprime to 10, y mod 10^T
    // (T = D + max(a, b)) gives (y / k2) mod 10^D, and dividing by k1 is multiplying by its
    // inverse mod 10^D.
    let (mut k1, mut a, mut b) = (k, 0u32, 0u32);
    while k1 % 2 == 0 {
        k1 /= 2;
        a += 1;
    }
    while k1 % 5 == 0 {
        k1 /= 5;
        b += 1;
    }
    let t_digits = D + a.max(b) as usize;
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
    let g = BigInt::from(k1).extended_gcd(&scale);
    if !g.gcd.is_one() {
        return None;
    }
    let trailing = (y_over_k2 * g.x.mod_floor(&scale)).mod_floor(&scale);
    Some(DigitSummary {
        negative: y.negative,
        digits,
        leading: lo_s[..D].to_string(),
        trailing: format!("{:0>width$}", trailing.to_string(), width = D),
    })
}

/// One line per component of `form`, `name(var) = ...` in the variable `var`, with the
/// initial values `x0` substituted; `None` when some term is not rational (quadratic surds
/// and numeric forms stay symbolic).
///
/// ```
/// use num_bigint::BigInt;
/// use recurrence::Recurrence;
///
/// let r = Recurrence::with_names("[[1,1],[0,4]]".parse()?, ["V", "E"])?;
/// let x0 = [12, 30].map(BigInt::from);
/// let lines = schemes::specialized_lines(&r.closed_form(), &x0, "t").unwrap();
/// assert_eq!(lines, ["V(t) = 10*4^t + 2", "E(t) = 30*4^t"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn specialized_lines(form: &ClosedForm, x0: &[BigInt], var: &str) -> Option<Vec<String>> {
    form.components()
        .iter()
        .map(|c| specialized_component(c, x0, var, c.valid_from, &[]))
        .collect()
}

/// The line of component `index` of [`specialized_lines`] for a quantity that the component
/// gives from level `max(valid_from, the component's valid_from)` on and that is the integer
/// of `early` at the levels listed there (the component's own early levels, evaluated at
/// `x0`, at the other levels below its `valid_from`): the UV values, which the recurrence's
/// `UV` gives from level 1 on while level 0 counts the `vt` used. `None` when there is no
/// such component or a term is not rational.
///
/// ```
/// use num_bigint::BigInt;
/// use recurrence::Recurrence;
///
/// let r = Recurrence::with_names("[[1,1],[0,4]]".parse()?, ["V", "E"])?;
/// let x0 = [12, 30].map(BigInt::from);
/// let early = [(0, BigInt::from(11))];
/// let line = schemes::specialized_line_from(&r.closed_form(), 0, &x0, "s", 1, &early).unwrap();
/// assert_eq!(line, "V(s) = 10*4^s + 2 for s >= 1; V(0) = 11");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn specialized_line_from(
    form: &ClosedForm,
    index: usize,
    x0: &[BigInt],
    var: &str,
    valid_from: u64,
    early: &[(u64, BigInt)],
) -> Option<String> {
    let c = form.components().get(index)?;
    specialized_component(c, x0, var, valid_from.max(c.valid_from), early)
}

fn specialized_component(
    component: &recurrence::ComponentForm,
    x0: &[BigInt],
    var: &str,
    valid_from: u64,
    fixed: &[(u64, BigInt)],
) -> Option<String> {
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
    if valid_from > 0 {
        let early: Vec<String> = (0..valid_from)
            .filter_map(|l| {
                let v: BigInt = if let Some((_, v)) = fixed.iter().find(|(k, _)| *k == l) {
                    v.clone()
                } else {
                    let e = component.early_levels.iter().find(|e| e.level == l)?;
                    e.coefficients.iter().zip(x0).map(|(c, x)| c * x).sum()
                };
                Some(format!("{}({l}) = {v}", component.name))
            })
            .collect();
        line.push_str(&format!(" for {var} >= {valid_from}; {}", early.join(", ")));
    }
    Some(line)
}

/// `c1*s^k1*l1^s + c2*...`, largest eigenvalue first as the closed form lists them.
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

/// Whether every term of `form` has an integer eigenvalue: then evaluating it at a level costs
/// about as much as writing the result (powers of integers), unlike quadratic surds (exact
/// rationals in `Q(sqrt d)`, reduced at every product) or numeric eigenvalues.
fn integer_spectrum(form: &ClosedForm) -> bool {
    form.components().iter().all(|c| {
        c.terms
            .iter()
            .all(|t| matches!(t.eigenvalue, Eigenvalue::Rational(_)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;

    fn big(v: &[i64]) -> Vec<BigInt> {
        v.iter().map(|&x| BigInt::from(x)).collect()
    }

    fn specialized(matrix: &str, names: &[&str], x0: &[i64], var: &str) -> Vec<String> {
        let r = Recurrence::with_names(matrix.parse().unwrap(), names.iter().copied()).unwrap();
        specialized_lines(&r.closed_form(), &big(x0), var).unwrap()
    }

    #[test]
    fn division_of_summaries_is_exact() {
        for k in [3u64, 6, 12, 15, 40, 7 * 16, 1000] {
            let exact =
                BigInt::from(7u32).pow(300u32) * BigInt::from(10u32).pow(5u32) + 123456789u64;
            let y = &exact * BigInt::from(k);
            let got = divide_summary(&recurrence::digit_summary(&y, 80), k, 80).expect("settled");
            assert_eq!(
                got,
                recurrence::digit_summary(&exact, SUMMARY_DIGITS),
                "k = {k}"
            );
        }
        // Small values are known fully; a remainder means the input was not a multiple.
        let small = recurrence::digit_summary(&BigInt::from(60), 80);
        assert_eq!(divide_summary(&small, 3, 80).unwrap().leading, "20");
        assert_eq!(divide_summary(&small, 7, 80), None);
    }

    /// Summaries of state and derived columns (F = 2E/3 for Loop, derived E and F for
    /// loop-boundary) agree with the exact counts at levels where both can be computed.
    #[test]
    fn summaries_match_exact_powering() {
        let cases = [
            ("loop", big(&[12, 30])),
            ("loop-boundary", big(&[4, 1, 4])),
            ("catmull-clark-quad", big(&[8, 12, 6])),
        ];
        for (name, x0) in cases {
            let counter = Counter::from(builtin(name).unwrap());
            for s in [0u64, 1, 7, 65, 300, 2000] {
                let row = counter.row_at(&x0, s).unwrap();
                let sums = counter.summaries(&x0, s, false).expect(name);
                assert_eq!(sums.len(), row.values.len());
                for (sum, value) in sums.iter().zip(&row.values) {
                    let expected = value
                        .as_ref()
                        .map(|v| recurrence::digit_summary(v, SUMMARY_DIGITS));
                    assert_eq!(sum, &expected, "{name} at level {s}");
                }
            }
        }
        // Periodic and composed schemes have no direct closed form.
        let periodic = Counter::from(builtin("sqrt3-boundary").unwrap());
        assert_eq!(periodic.summaries(&big(&[4, 1, 4, 2]), 10, false), None);
    }

    /// Past level 64 the closed form counts; the result equals powering.
    #[test]
    fn state_at_agrees_with_powering_past_the_switch() {
        let r = Recurrence::with_names("[[1,1],[0,4]]".parse().unwrap(), ["V", "E"]).unwrap();
        let counter = Counter::from(r.clone());
        let x0 = big(&[12, 30]);
        for s in [0u64, 64, 65, 500] {
            assert_eq!(
                counter.state_at(&x0, s).unwrap(),
                r.state_at(&x0, s).unwrap()
            );
        }
        let rows = counter.rows(&x0, 63..=66).unwrap();
        assert_eq!(rows.len(), 4);
        assert_eq!(
            rows[3].values[0],
            Some(r.state_at(&x0, 66).unwrap()[0].clone())
        );
    }

    #[test]
    fn estimates_track_exact_digits() {
        let r = Recurrence::with_names("[[1,1],[0,4]]".parse().unwrap(), ["V", "E"]).unwrap();
        let counter = Counter::from(r.clone());
        let x0 = big(&[12, 30]);
        for s in [0u64, 1, 5, 100, 1000] {
            let digits = r.state_at(&x0, s).unwrap()[1].to_string().len() as f64;
            let estimate = counter.estimated_log10(&x0, s).unwrap();
            assert!(
                estimate + 1.0 >= digits && estimate <= digits + 1.0,
                "s={s}: {estimate}"
            );
        }
        let huge = counter.estimated_log10(&x0, 1_000_000_000_000).unwrap();
        assert!((huge - 1e12 * 4f64.log10()).abs() < 1e3);
        // A periodic scheme grows by its cycle: sqrt3-boundary triples F every level.
        let periodic = Counter::from(builtin("sqrt3-boundary").unwrap());
        let f = periodic
            .estimated_log10(&big(&[4, 1, 4, 2]), 1_000_000)
            .unwrap();
        assert!((f - 1e6 * 3f64.log10()).abs() < 10.0, "{f}");
        assert_eq!(
            Counter::from(r)
                .estimated_log10(&big(&[0, 0]), 1000)
                .unwrap(),
            0.0
        );
    }

    /// Issue 11: compositions, cycles and first steps past level 64 (`loop:2,sqrt3` at
    /// level 67 panicked in the old CLI model). `state_at`, `row_at` and `rows` equal one
    /// matrix-vector product per level with each stage's own step matrices.
    #[test]
    fn plans_past_level_64_equal_stepping_through_the_stage_matrices() {
        let cases = [
            ("loop:2,sqrt3", big(&[12, 30])),
            ("sqrt3-boundary", big(&[4, 1, 4, 2])),
            ("loop-boundary:1,sqrt3-boundary", big(&[4, 1, 4])),
            ("catmull-clark:3,doo-sabin", big(&[8, 12, 0, 6, 24])),
            ("catmull-clark", big(&[4, 0, 4, 1, 4])),
        ];
        for (text, x0) in cases {
            let plan = Plan::parse(text).unwrap();
            let counter = Counter::from(plan.clone());
            // The last stage starts where the earlier ones end (0 for a single scheme).
            let start = plan.stages()[..plan.stages().len() - 1]
                .iter()
                .map(|s| s.levels().unwrap())
                .sum::<u64>();
            let last = plan.stages().last().unwrap().scheme();
            // The first level in the last stage's names: 0 for a single scheme, else the
            // level after the switch (the switch level belongs to the earlier stage).
            let begin = if plan.is_single() { 0 } else { start + 1 };
            let mut x = plan.state_at(&x0, begin).unwrap();
            let mut expected = vec![(begin, x.clone())];
            for level in begin + 1..=130 {
                x = crate::scheme::apply(last.rule().matrix_of_step(level - start), &x);
                expected.push((level, x.clone()));
            }
            for (level, state) in &expected {
                if [63, 64, 65, 66, 67, 68, 128, 130].contains(level) {
                    assert_eq!(
                        &counter.state_at(&x0, *level).unwrap(),
                        state,
                        "{text} at {level}"
                    );
                    let row = counter.row_at(&x0, *level).unwrap();
                    assert_eq!(row, counter.row_from_state(*level, state.clone()).unwrap());
                }
            }
            let rows = counter.rows(&x0, 60..=70).unwrap();
            let high = counter.rows(&x0, 66..=70).unwrap();
            assert_eq!(rows[6..], high[..], "{text}");
            for row in rows {
                let state = &expected[(row.level - begin) as usize].1;
                assert_eq!(
                    row,
                    counter.row_from_state(row.level, state.clone()).unwrap()
                );
            }
        }
    }

    /// Issue 11: a composition's estimate follows the stage that produces the level (it used
    /// the last stage's growth from level 2, and overflowed `u64` for a bounded last stage of
    /// `u64::MAX` levels), without materializing a huge early stage.
    #[test]
    fn composition_estimates_follow_the_stage_of_the_level() {
        let x0 = big(&[12, 30]);
        let (l4, l3) = (4f64.log10(), 3f64.log10());
        let cases: [(&str, u64, f64); 5] = [
            ("loop:1000000000000,sqrt3", 1_000_000_000, 1e9 * l4),
            (
                "loop:1000000000000,sqrt3",
                1_000_000_000_100,
                1e12 * l4 + 100.0 * l3,
            ),
            ("loop:100,sqrt3", 1_000_000, 100.0 * l4 + (1e6 - 100.0) * l3),
            (
                "loop:18446744073709551615,sqrt3",
                u64::MAX,
                u64::MAX as f64 * l4,
            ),
            ("loop:18446744073709551615", u64::MAX, u64::MAX as f64 * l4),
        ];
        for (text, s, expected) in cases {
            let counter = Counter::from(Plan::parse(text).unwrap());
            let estimate = counter.estimated_log10(&x0, s).unwrap();
            assert!(
                (estimate - expected).abs() <= 1e-6 * expected + 10.0,
                "{text} at {s}: {estimate} vs {expected}"
            );
        }
        let bounded = Counter::from(Plan::parse("loop:18446744073709551615").unwrap());
        let exact = bounded.estimated_log10(&x0, 5).unwrap();
        assert!((exact - 30720f64.log10()).abs() < 1e-12, "{exact}");
    }

    proptest::proptest! {
        /// Levels and stage lengths anywhere up to `u64::MAX`: the estimate of
        /// `loop:k,sqrt3` at level `s` never overflows and follows Loop up to `k`, then
        /// sqrt3 (within the rounding of a float and the few digits of the start).
        #[test]
        fn composition_estimates_at_any_level(
            k in proptest::prop_oneof![0u64..200, (u64::MAX - 1000)..=u64::MAX, proptest::num::u64::ANY],
            s in proptest::prop_oneof![0u64..200, (u64::MAX - 1000)..=u64::MAX, proptest::num::u64::ANY],
        ) {
            let counter = Counter::from(Plan::parse(&format!("loop:{k},sqrt3")).unwrap());
            let estimate = counter.estimated_log10(&big(&[12, 30]), s).unwrap();
            let (l4, l3) = (4f64.log10(), 3f64.log10());
            let expected = if s <= k {
                s as f64 * l4
            } else {
                k as f64 * l4 + (s - k) as f64 * l3
            };
            proptest::prop_assert!(
                estimate.is_finite() && (estimate - expected).abs() <= 1e-6 * expected + 5.0,
                "loop:{},sqrt3 at {}: {} vs {}", k, s, estimate, expected
            );
        }

        /// Issue 11: size estimates at levels near `u64::MAX` grow by the dominant
        /// eigenvalue (log10(4) a level for Loop, log10(3) for sqrt3, periodic or composed),
        /// rather than saturating at `u64::MAX` bits (`log10(2) u64::MAX` digits).
        #[test]
        fn estimates_near_u64_max_follow_the_growth_rate(back in 0u64..1 << 62) {
            let s = u64::MAX - back;
            let cases = [
                ("loop", big(&[12, 30]), 4f64),
                ("sqrt3-boundary", big(&[4, 1, 4, 2]), 3.0),
                ("loop:2,sqrt3", big(&[12, 30]), 3.0),
            ];
            for (text, x0, rate) in cases {
                let counter = Counter::from(Plan::parse(text).unwrap());
                let estimate = counter.estimated_log10(&x0, s).unwrap();
                let expected = s as f64 * rate.log10();
                proptest::prop_assert!(
                    estimate.is_finite() && (estimate - expected).abs() <= 1e-6 * expected,
                    "{} at {}: {} vs {}", text, s, estimate, expected
                );
            }
        }
    }

    #[test]
    fn rendering_in_another_variable() {
        assert_eq!(
            specialized("[[1,1],[0,4]]", &["V", "E"], &[12, 30], "s"),
            ["V(s) = 10*4^s + 2", "E(s) = 30*4^s"]
        );
        assert_eq!(
            specialized("[[2,1],[0,2]]", &["A", "B"], &[1, 1], "t"),
            ["A(t) = (1/2)*t*2^t + 2^t", "B(t) = 2^t"]
        );
        // Doo-Sabin-like: V forgets its initial value after one step.
        let l = specialized(
            "[[0,2,0],[0,4,0],[1,1,1]]",
            &["V", "E", "F"],
            &[8, 12, 6],
            "u",
        );
        assert_eq!(l[0], "V(u) = 6*4^u for u >= 1; V(0) = 8");
        let fib = Recurrence::new("[[1,1],[1,0]]".parse().unwrap());
        assert!(specialized_lines(&fib.closed_form(), &big(&[1, 0]), "s").is_none());
    }

    #[test]
    fn specialized_text_of_a_composition_uses_the_phase_variable() {
        let counter = Counter::from(Plan::parse("loop:2,loop").unwrap());
        let text = counter.specialized_text(&big(&[12, 30]));
        assert!(text.starts_with("# with V(0) = 12, E(0) = 30\n"), "{text}");
        assert!(text.contains("V(t) = 10*4^t + 2"), "{text}");
        assert!(text.contains("V(t) = 160*4^t + 2"), "{text}");
    }

    /// A matrix with quadratic-surd eigenvalues is counted by powering, not through its
    /// closed form, whose exact rational powers cost quadratic time in their digits (found by
    /// the `large_matrix` fuzz target: 24 s at level 40,000): the state is still exact, and
    /// `summaries` leaves it to the caller's digit guard.
    #[test]
    fn surd_spectra_are_powered_not_evaluated() {
        let m: IntMatrix = "[[4351, 65536, 512], [256, 0, 0], [0, 0, 0]]"
            .parse()
            .unwrap();
        let r = Recurrence::new(m);
        assert!(r.closed_form().is_exact());
        assert!(!integer_spectrum(&r.closed_form()));
        let counter = Counter::Matrix(r.clone());
        let x0 = vec![BigInt::from(1); 3];
        assert_eq!(
            counter.state_at(&x0, 300).unwrap(),
            r.state_at(&x0, 300).unwrap()
        );
        assert!(counter.summaries(&x0, 300, false).is_none());
        let loop_counter = Counter::Matrix(Recurrence::new("[[1, 1], [0, 4]]".parse().unwrap()));
        let ico = [12, 30].map(BigInt::from);
        assert!(integer_spectrum(
            &loop_counter.direct_form(CLOSED_FORM_LIMIT).unwrap()
        ));
        assert!(loop_counter.summaries(&ico, 300, false).is_some());
    }
}
