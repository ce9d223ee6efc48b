//! Budgets and densities: the highest level that fits ([`fit`]), byte sizes
//! ([`parse_byte_size`]), and the paper's eq. (1) ([`density`], [`level_for_area`]).
//!
//! # The search, and why it ends
//!
//! [`fit`] and [`level_for_area`] look for the first level at which a quantity `q` (V, E, F
//! or bytes, each a linear function of the state) crosses a bound. They rely on one
//! assumption, which holds for every built-in scheme and is **checked numerically** along the
//! search for any plan (an [`Error::NotMonotone`] refusal otherwise): `q` never decreases
//! from level 1 on.
//!
//! The search probes windows of `W + 1` consecutive levels `h, h + 1, ..., h + W` at
//! doubling `h`, with `W = n * p` for the last stage (`n` state components, period `p`):
//!
//! - if a window crosses the bound, a binary search between the last level known below and
//!   the first known above finds the answer;
//! - if `q` is constant across a window, it is constant forever: the differences
//!   `q(s + 1) - q(s)` restricted to one residue class mod `p` have the form `c^T M^t v`
//!   for the `n x n` period matrix `M`, so by Cayley-Hamilton they satisfy a linear
//!   recurrence of order `n` with leading coefficient 1, and `n` consecutive zeros force
//!   all later ones to vanish. The answer is then "every level" ([`Fit::Unbounded`]) or
//!   "never" ([`Error::NeverReached`]), stated from the least level at which `q` settles:
//!   since `q` never decreases from level 1 on, the levels in `1..=h` where `q` already has
//!   its final value form an interval ending at `h`, found by bisection, and level 0 counts
//!   when level 1 does. A constant scheme settles at level 0.
//!
//! Otherwise `q`, an integer that never decreases and is not eventually constant, grows
//! without bound, so some probe crosses the bound: the search ends. (Levels are `u64`; and
//! as a resource guard, a probe whose state would exceed 2^26 bits is refused with
//! [`Error::SearchTooLarge`]: that happens only when the limited quantity grows
//! polynomially while another state component grows exponentially.)
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `fit.rs` holds **the one budget search** (`fit`, answering `Fit::Level`, `Fit::Unbounded` or
//! `Fit::NoneFits`; `Fit::highest_level` caps it for `subcount verify` and `cargo xtask verify`),
//! byte sizes and the paper's eq. (1) (`density`, `level_for_area`).

use num_bigint::BigInt;
use num_traits::{ToPrimitive, Zero};

use crate::uv::UvCounter;
use crate::{Error, LevelCounts, Plan, Result};

/// Limits for [`fit`]; every limit that is set must hold.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Budget {
    /// At most this many vertices.
    pub max_vertices: Option<BigInt>,
    /// At most this many edges.
    pub max_edges: Option<BigInt>,
    /// At most this many faces.
    pub max_faces: Option<BigInt>,
    /// At most this many UV values (needs a UV layout: [`fit_uv`]).
    pub max_uv: Option<BigInt>,
    /// At most this many bytes for a mesh layout.
    pub memory: Option<MemoryBudget>,
}

impl Budget {
    /// Whether a limit counts UV values (`max_uv`, or `bytes_per_uv` in the memory budget).
    pub fn limits_uv(&self) -> bool {
        self.max_uv.is_some() || self.memory.as_ref().is_some_and(|m| m.bytes_per_uv > 0)
    }
}

/// A byte budget `bytes_per_vertex * V + bytes_per_edge * E + bytes_per_face * F
/// + bytes_per_uv * UV <= bytes`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MemoryBudget {
    /// The budget in bytes.
    pub bytes: BigInt,
    /// Bytes per vertex (e.g. 12 for three `f32`).
    pub bytes_per_vertex: u64,
    /// Bytes per edge (0 for a face-vertex layout).
    pub bytes_per_edge: u64,
    /// Bytes per face (e.g. 12 for three `u32` indices).
    pub bytes_per_face: u64,
    /// Bytes per UV value (e.g. 8 for two `f32`; 0 without UVs). Needs a UV layout: [`fit_uv`].
    pub bytes_per_uv: u64,
}

/// The answer of [`fit`].
///
/// # Example: counts that settle
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::{fit, Budget, Fit, Plan, Scheme};
///
/// let budget = Budget { max_vertices: Some(BigInt::from(100)), ..Budget::default() };
/// let x0 = [10, 5, 3].map(BigInt::from);
/// // The identity never changes the counts: every level fits, from level 0 on.
/// let constant = Scheme::from_toml(
///     "name = \"constant\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n",
/// )?;
/// let Fit::Unbounded { counts } = fit(&Plan::from(constant), &x0, &budget)? else { panic!() };
/// assert_eq!((counts.level, counts.vertices), (0, BigInt::from(10)));
/// // V' = V + E, E' = F, F' = 0: V is 10, 15, 18, 18, ...: it settles at level 2.
/// let settles = Scheme::from_toml(
///     "name = \"settles\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 1, 0], [0, 0, 1], [0, 0, 0]]\n",
/// )?;
/// let Fit::Unbounded { counts } = fit(&Plan::from(settles), &x0, &budget)? else { panic!() };
/// assert_eq!((counts.level, counts.vertices), (2, BigInt::from(18)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Fit {
    /// The highest level within the budget, with its counts.
    Level(LevelCounts),
    /// Every level fits: the limited counts (those `budget` bounds) are the same at
    /// `counts.level` and at every later level, and `counts.level` is the least such level.
    /// It is 0 when the limited counts never change (a constant scheme, an empty mesh, or a
    /// state that is a fixed point), and `k` when they last change from level `k - 1` to `k`.
    Unbounded {
        /// The counts at the least level from which the limited counts never change.
        counts: LevelCounts,
    },
    /// Level 0 already exceeds a limit: no level fits.
    NoneFits {
        /// The counts at level 0.
        counts: LevelCounts,
        /// Each exceeded limit, `V = 42 > 40, F = 80 > 50`.
        detail: String,
    },
}

impl Fit {
    /// The highest level that fits, at most `cap`: `cap` when every level fits, `None` when
    /// none does. The one answer to "how many levels can I afford" for callers that stop at
    /// a cap (`subcount verify` without `--levels`, `cargo xtask verify`).
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use schemes::{fit, Budget, CountsInput, Plan};
    ///
    /// let plan = Plan::parse("loop")?;
    /// let x0 = plan.state_from_input(&"V=12,E=30,F=20".parse::<CountsInput>()?)?;
    /// let faces = |n: u64| Budget { max_faces: Some(BigInt::from(n)), ..Budget::default() };
    /// // 20, 80, 320, 1280, 5120 faces.
    /// assert_eq!(fit(&plan, &x0, &faces(5119))?.highest_level(64), Some(3));
    /// assert_eq!(fit(&plan, &x0, &faces(5119))?.highest_level(2), Some(2));
    /// assert_eq!(fit(&plan, &x0, &faces(19))?.highest_level(64), None);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn highest_level(&self, cap: u64) -> Option<u64> {
        match self {
            Fit::Level(c) => Some(c.level.min(cap)),
            Fit::Unbounded { .. } => Some(cap),
            Fit::NoneFits { .. } => None,
        }
    }

    /// The answer as a level's counts, with "no level fits" as [`Error::NothingFits`] (the
    /// counts of [`Fit::Unbounded`] are those from which nothing changes).
    ///
    /// # Errors
    ///
    /// [`Error::NothingFits`] for [`Fit::NoneFits`].
    pub fn counts(&self) -> Result<&LevelCounts> {
        match self {
            Fit::Level(counts) | Fit::Unbounded { counts } => Ok(counts),
            Fit::NoneFits { detail, .. } => Err(Error::NothingFits {
                detail: detail.clone(),
            }),
        }
    }
}

/// The largest state (in total bits) a search computes: 2^26 bits, 8 MiB.
const MAX_STATE_BITS: u64 = 1 << 26;

/// The counts a quantity weighs: `V, E, F, UV`.
type Counts4 = [BigInt; 4];

struct Quantity {
    name: String,
    bound: BigInt,
    weights: Counts4,
}

impl Quantity {
    fn value(&self, vef: &Counts4) -> BigInt {
        self.weights.iter().zip(vef).map(|(w, x)| w * x).sum()
    }
}

fn quantities(budget: &Budget) -> Vec<Quantity> {
    let one = |k: usize| {
        let mut w: Counts4 = Default::default();
        w[k] = BigInt::from(1);
        w
    };
    let mut out = Vec::new();
    for (name, bound, k) in [
        ("V", &budget.max_vertices, 0),
        ("E", &budget.max_edges, 1),
        ("F", &budget.max_faces, 2),
        ("UV", &budget.max_uv, 3),
    ] {
        if let Some(b) = bound {
            out.push(Quantity {
                name: name.into(),
                bound: b.clone(),
                weights: one(k),
            });
        }
    }
    if let Some(m) = &budget.memory {
        out.push(Quantity {
            name: "bytes".into(),
            bound: m.bytes.clone(),
            weights: [
                m.bytes_per_vertex,
                m.bytes_per_edge,
                m.bytes_per_face,
                m.bytes_per_uv,
            ]
            .map(BigInt::from),
        });
    }
    out
}

/// The outcome of the generic search.
enum Crossing {
    /// The first level at which the predicate holds.
    At(u64),
    /// The predicate never holds; the values are constant from this level on.
    Never(u64),
}

/// Values of the quantities at each level, with a cache-free evaluation through the plan.
struct Probe<'a> {
    plan: &'a Plan,
    x0: &'a [BigInt],
    /// The UV values, when a limit counts them.
    uv: Option<&'a UvCounter>,
    weights: Vec<Counts4>,
    names: Vec<String>,
}

impl Probe<'_> {
    /// The quantities from `V, E, F` and the UV values at `level` (0 without a UV limit).
    fn values_of(&self, vef: [BigInt; 3], level: u64) -> Result<Vec<BigInt>> {
        let uv = match self.uv {
            Some(uv) => uv.values_at(level)?,
            None => BigInt::zero(),
        };
        let [v, e, f] = vef;
        let counts: Counts4 = [v, e, f, uv];
        Ok(self
            .weights
            .iter()
            .map(|w| w.iter().zip(&counts).map(|(a, b)| a * b).sum())
            .collect())
    }

    fn at(&self, level: u64) -> Result<Vec<BigInt>> {
        let state = self.plan.state_at(self.x0, level)?;
        self.values_of(self.plan.vef(level, &state)?, level)
    }

    /// Refuses, before materializing it, a level whose largest count is estimated at more
    /// than four times [`MAX_STATE_BITS`] bits (a huge level of an early stage:
    /// `loop:18446744073709551615,sqrt3`). The search doubles its level, so on its ordinary
    /// path the exact check of the state ([`Error::SearchTooLarge`]) refuses first.
    fn check_affordable(&self, level: u64) -> Result {
        let counter = crate::Counter::from(self.plan.clone());
        let digits = counter.estimated_log10(self.x0, level)?;
        if digits * std::f64::consts::LOG2_10 > 4.0 * MAX_STATE_BITS as f64 {
            return Err(Error::SearchEstimateTooLarge {
                level,
                digits: format!("{digits:.3e}"),
            });
        }
        Ok(())
    }

    /// Values at `h..=h + w`, stepping within the last stage.
    fn window(&self, h: u64, w: u64) -> Result<Vec<Vec<BigInt>>> {
        self.check_affordable(h)?;
        let (scheme, start, _) = self.plan.tail();
        let mut state = self.plan.tail_state(self.x0, h)?;
        let bits: u64 = state.iter().map(BigInt::bits).sum();
        if bits > MAX_STATE_BITS {
            return Err(Error::SearchTooLarge { level: h, bits });
        }
        let mut out = vec![self.values_of(scheme.vef(&state)?, h)?];
        // `h..end` shifted by one: no overflow when the search reaches `u64::MAX`.
        for level in (h..h.saturating_add(w)).map(|l| l + 1) {
            state = crate::scheme::apply(scheme.rule().matrix_of_step(level - start), &state);
            out.push(self.values_of(scheme.vef(&state)?, level)?);
        }
        Ok(out)
    }

    fn check_order(&self, a: (u64, &[BigInt]), b: (u64, &[BigInt])) -> Result {
        if a.0 == 0 {
            return Ok(());
        }
        for (k, (x, y)) in a.1.iter().zip(b.1).enumerate() {
            if y < x {
                return Err(Error::NotMonotone {
                    what: self.names[k].clone(),
                    level: a.0,
                    next: b.0,
                    from: x.to_string(),
                    to: y.to_string(),
                });
            }
        }
        Ok(())
    }

    /// The first level where `hit` holds (`hit` must be monotone: once true, true after).
    fn first(&self, hit: &dyn Fn(&[BigInt]) -> bool) -> Result<Crossing> {
        let v0 = self.at(0)?;
        if hit(&v0) {
            return Ok(Crossing::At(0));
        }
        let (scheme, start, tail_start) = self.plan.tail();
        // Strictly after the start of the last stage, where the plan reports its own state.
        let mut h = tail_start.max(start.saturating_add(1));
        let end = self.plan.last_level().unwrap_or(h);
        if self.check_affordable(end).is_err() {
            // An earlier stage runs for so many levels that its end cannot be computed:
            // look for the crossing inside it first.
            if let Some(crossing) = self.gallop(hit, &v0, end)? {
                return Ok(crossing);
            }
        }
        if let Some(last) = self.plan.last_level() {
            return self.bounded(hit, last, v0);
        }
        // With UV values the quantities follow the two recurrences side by side: the window
        // covers the order of both.
        let uv_dim = self.uv.map_or(0, |uv| uv.dim() as u64);
        let w = (scheme.dim() as u64 + uv_dim).saturating_mul(scheme.period());
        let mut lo = (0u64, v0);
        loop {
            let values = self.window(h, w)?;
            self.check_order((lo.0, &lo.1), (h, &values[0]))?;
            for (j, pair) in values.windows(2).enumerate() {
                self.check_order((h + j as u64, &pair[0]), (h + j as u64 + 1, &pair[1]))?;
            }
            if let Some(j) = values.iter().position(|v| hit(v)) {
                let hi = h + j as u64;
                if j > 0 {
                    return Ok(Crossing::At(hi));
                }
                return self.bisect(hit, lo, (hi, values[0].clone()));
            }
            if values.len() > 1 && values.windows(2).all(|p| p[0] == p[1]) {
                return Ok(Crossing::Never(self.settled_from(h, &values[0])?));
            }
            let end = h.saturating_add(w);
            lo = (end, values[values.len() - 1].clone());
            let next = h.saturating_mul(2).max(end.saturating_add(1));
            if next == h || end == u64::MAX {
                // The counts still change but no level a `u64` can name crosses the limit
                // (polynomial growth against a huge budget): refuse rather than claim that
                // every level fits.
                let state = self.plan.tail_state(self.x0, end)?;
                let bits = state.iter().map(BigInt::bits).sum();
                return Err(Error::SearchTooLarge { level: end, bits });
            }
            h = next;
        }
    }

    /// The least level from which the values are `settled`, given that they equal `settled`
    /// at `h` and at every later level: 0 when they never change.
    ///
    /// From level 1 on the values never decrease (checked here as everywhere in the search),
    /// so the levels in `1..=h` whose values equal those at `h` form an interval ending at `h`,
    /// found by bisection; level 0 (before the monotone part) counts only when level 1 does.
    fn settled_from(&self, h: u64, settled: &[BigInt]) -> Result<u64> {
        if h == 0 {
            return Ok(0);
        }
        let v1 = self.at(1)?;
        self.check_order((1, &v1), (h, settled))?;
        if v1 == settled {
            return Ok(if self.at(0)? == settled { 0 } else { 1 });
        }
        // `lo` differs from `settled`, `hi` equals it.
        let (mut lo, mut hi) = ((1u64, v1), h);
        while hi - lo.0 > 1 {
            let mid = lo.0 + (hi - lo.0) / 2;
            let v = self.at(mid)?;
            self.check_order((lo.0, &lo.1), (mid, &v))?;
            self.check_order((mid, &v), (hi, settled))?;
            if v == settled {
                hi = mid;
            } else {
                lo = (mid, v);
            }
        }
        Ok(hi)
    }

    /// The crossing at levels `1, 2, 4, ...` below `end`, bisected between the last miss
    /// and the first hit; `None` when no affordable level below `end` hits.
    fn gallop(
        &self,
        hit: &dyn Fn(&[BigInt]) -> bool,
        v0: &[BigInt],
        end: u64,
    ) -> Result<Option<Crossing>> {
        let mut lo = (0u64, v0.to_vec());
        let mut level = 1u64;
        while level < end && self.check_affordable(level).is_ok() {
            let v = self.at(level)?;
            self.check_order((lo.0, &lo.1), (level, &v))?;
            if hit(&v) {
                return self.bisect(hit, lo, (level, v)).map(Some);
            }
            lo = (level, v);
            level = level.saturating_mul(2);
        }
        Ok(None)
    }

    fn bounded(
        &self,
        hit: &dyn Fn(&[BigInt]) -> bool,
        last: u64,
        v0: Vec<BigInt>,
    ) -> Result<Crossing> {
        self.check_affordable(last)?;
        let v_last = self.at(last)?;
        if !hit(&v_last) {
            return Ok(Crossing::Never(last));
        }
        self.bisect(hit, (0, v0), (last, v_last))
    }

    /// `lo` misses, `hi` hits: the first hit in `(lo, hi]`.
    fn bisect(
        &self,
        hit: &dyn Fn(&[BigInt]) -> bool,
        mut lo: (u64, Vec<BigInt>),
        mut hi: (u64, Vec<BigInt>),
    ) -> Result<Crossing> {
        while hi.0 - lo.0 > 1 {
            let mid = lo.0 + (hi.0 - lo.0) / 2;
            let v = self.at(mid)?;
            self.check_order((lo.0, &lo.1), (mid, &v))?;
            self.check_order((mid, &v), (hi.0, &hi.1))?;
            if hit(&v) {
                hi = (mid, v);
            } else {
                lo = (mid, v);
            }
        }
        Ok(Crossing::At(hi.0))
    }
}

/// The highest level whose counts stay within every limit of `budget`: the one budget
/// search of the workspace (`subcount fit`, `subcount verify` and `cargo xtask verify` use
/// it, through [`Fit::highest_level`] for the latter two).
///
/// # Errors
///
/// [`Error::NoLimit`] when `budget` sets nothing, [`Error::NotMonotone`] when a limited quantity decreases from level 1 on
/// (see the module documentation), and the errors of [`Plan::state_at`] and [`Plan::vef`].
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::{fit, Budget, CountsInput, Fit, Plan};
///
/// let plan = Plan::parse("loop")?;
/// let x0 = plan.state_from_input(&"V=12,E=30,F=20".parse::<CountsInput>()?)?;
/// let budget = Budget { max_vertices: Some(BigInt::from(u32::MAX)), ..Budget::default() };
/// let Fit::Level(c) = fit(&plan, &x0, &budget)? else { panic!("loop grows") };
/// // V(s) = 12 + 10 (4^s - 1): level 15 has 10737418242 > 2^32 - 1 vertices.
/// assert_eq!(c.level, 14);
/// assert_eq!(c.vertices, BigInt::from(2684354562u64));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit(plan: &Plan, x0: &[BigInt], budget: &Budget) -> Result<Fit> {
    if budget.limits_uv() {
        return Err(Error::NoUvLayout);
    }
    search(plan, x0, None, budget)
}

/// [`fit`] with the UV values of a mesh's layout (`uv`, from
/// [`Counter::uv_counter`](crate::Counter::uv_counter) for the same plan), so that
/// [`Budget::max_uv`] and [`MemoryBudget::bytes_per_uv`] count too: the highest level whose
/// `V`, `E`, `F`, UV values and bytes stay within every limit.
///
/// # Errors
///
/// As [`fit`].
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::uv::UvCounts;
/// use schemes::{fit_uv, Budget, Counter, Fit, MemoryBudget, Plan};
///
/// // spot_control_mesh: UV(s) = 183 4^s + 72 2^s + 9 from level 1 (885, 3225, 12297, ...).
/// let spot = UvCounts { values: 267, edges: 438, boundary_edges: 144, used_vt: 267,
///                       faces: 180, corners: 732, ..UvCounts::default() };
/// let plan = Plan::parse("catmull-clark")?;
/// let x0 = [188, 366, 0, 180, 732].map(BigInt::from);
/// let uv = Counter::from(plan.clone()).uv_counter(&spot)?;
/// let budget = Budget { max_uv: Some(BigInt::from(12296)), ..Budget::default() };
/// let Fit::Level(c) = fit_uv(&plan, &x0, &uv, &budget)? else { panic!("UV grows") };
/// assert_eq!(c.level, 2);
/// // 8 bytes per UV value on top of the default positions and faces.
/// let memory = MemoryBudget { bytes: BigInt::from(1 << 20), bytes_per_vertex: 12,
///                             bytes_per_face: 16, bytes_per_uv: 8, ..MemoryBudget::default() };
/// let budget = Budget { memory: Some(memory), ..Budget::default() };
/// assert_eq!(fit_uv(&plan, &x0, &uv, &budget)?.highest_level(64), Some(3));
/// // Without a layout a UV limit is refused.
/// assert!(schemes::fit(&plan, &x0, &budget).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_uv(plan: &Plan, x0: &[BigInt], uv: &UvCounter, budget: &Budget) -> Result<Fit> {
    search(plan, x0, Some(uv), budget)
}

/// The search of [`fit`] and [`fit_uv`].
fn search(plan: &Plan, x0: &[BigInt], uv: Option<&UvCounter>, budget: &Budget) -> Result<Fit> {
    let qs = quantities(budget);
    if qs.is_empty() {
        return Err(Error::NoLimit);
    }
    let probe = Probe {
        plan,
        x0,
        uv,
        weights: qs.iter().map(|q| q.weights.clone()).collect(),
        names: qs.iter().map(|q| q.name.clone()).collect(),
    };
    let bounds: Vec<BigInt> = qs.iter().map(|q| q.bound.clone()).collect();
    let exceeds = |v: &[BigInt]| v.iter().zip(&bounds).any(|(x, b)| x > b);
    match probe.first(&exceeds)? {
        Crossing::At(0) => {
            let c = plan.level_counts(x0, 0)?;
            let uv0 = match uv {
                Some(uv) => uv.values_at(0)?,
                None => BigInt::zero(),
            };
            let vef = [c.vertices.clone(), c.edges.clone(), c.faces.clone(), uv0];
            let detail: Vec<String> = qs
                .iter()
                .filter(|q| q.value(&vef) > q.bound)
                .map(|q| format!("{} = {} > {}", q.name, q.value(&vef), q.bound))
                .collect();
            Ok(Fit::NoneFits {
                counts: c,
                detail: detail.join(", "),
            })
        }
        Crossing::At(s) => Ok(Fit::Level(plan.level_counts(x0, s - 1)?)),
        Crossing::Never(s) => Ok(match plan.last_level() {
            Some(last) => Fit::Level(plan.level_counts(x0, last)?),
            None => Fit::Unbounded {
                counts: plan.level_counts(x0, s)?,
            },
        }),
    }
}

/// Parses a byte size: plain bytes (`1048576`), SI units (`kB`, `MB`, `GB`, `TB`, `PB`, `EB`:
/// powers of 1000) or binary units (`KiB`, `MiB`, `GiB`, `TiB`, `PiB`, `EiB`: powers of 1024),
/// with an optional `B` suffix, a decimal fraction if the result is a whole number of bytes
/// (`1.5GiB`), and optional spaces. Unit letters are case-insensitive.
///
/// # Errors
///
/// [`Error::ByteSize`] naming the problem.
///
/// ```
/// assert_eq!(schemes::parse_byte_size("2GiB")?, 2 << 30);
/// assert_eq!(schemes::parse_byte_size("2 GB")?, 2_000_000_000);
/// assert_eq!(schemes::parse_byte_size("1.5KiB")?, 1536);
/// assert_eq!(schemes::parse_byte_size("4096")?, 4096);
/// assert!(schemes::parse_byte_size("2 GiX").is_err());
/// # Ok::<(), schemes::Error>(())
/// ```
pub fn parse_byte_size(text: &str) -> Result<u128> {
    let bad = |reason: &str| Error::ByteSize {
        text: text.to_string(),
        reason: reason.to_string(),
    };
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = (t[..split].trim(), t[split..].trim());
    if number.is_empty() {
        return Err(bad("expected a number, e.g. 2GiB"));
    }
    let multiplier: u128 = match unit.to_ascii_lowercase().as_str() {
        "" | "b" => 1,
        "k" | "kb" => 1000,
        "m" | "mb" => 1000u128.pow(2),
        "g" | "gb" => 1000u128.pow(3),
        "t" | "tb" => 1000u128.pow(4),
        "p" | "pb" => 1000u128.pow(5),
        "e" | "eb" => 1000u128.pow(6),
        "ki" | "kib" => 1 << 10,
        "mi" | "mib" => 1 << 20,
        "gi" | "gib" => 1 << 30,
        "ti" | "tib" => 1 << 40,
        "pi" | "pib" => 1 << 50,
        "ei" | "eib" => 1 << 60,
        _ => {
            return Err(bad(
                "unknown unit (use B, kB, MB, GB, TB, PB, EB, KiB, MiB, GiB, TiB, PiB or EiB)",
            ))
        }
    };
    let (int, frac) = number.split_once('.').unwrap_or((number, ""));
    if frac.contains('.') || (int.is_empty() && frac.is_empty()) {
        return Err(bad("not a number"));
    }
    let digits = format!("{int}{frac}");
    let scaled: u128 = digits.parse().map_err(|_| bad("too large"))?;
    let den = 10u128
        .checked_pow(u32::try_from(frac.len()).map_err(|_| bad("too many decimals"))?)
        .ok_or_else(|| bad("too many decimals"))?;
    let total = scaled
        .checked_mul(multiplier)
        .ok_or_else(|| bad("too large"))?;
    if total % den != 0 {
        return Err(bad("not a whole number of bytes"));
    }
    Ok(total / den)
}

/// The paper's eq. (1) at one level: mean co-volume area and scale factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Density {
    /// `mu = 4 pi r^2 / N_V` (floating point: it involves pi).
    pub mean_area: f64,
    /// `phi = sqrt(tau / mu)`.
    pub phi: f64,
}

/// Eq. (1) of the paper: `mu = 4 pi r^2 / n_v` and `phi = sqrt(tau / mu)`.
///
/// # Errors
///
/// [`Error::Density`] when `n_v` is zero, `radius` is not positive and finite, or `tau` is
/// negative or not finite; [`Error::OutOfFloatRange`] when the area or the scale factor is
/// infinite or zero in floating point (a huge `n_v` or radius, a tiny radius, a huge `tau`)
/// although its exact value is positive and finite.
///
/// ```
/// use num_bigint::BigInt;
/// let d = schemes::density(&BigInt::from(642), 1.0, 0.5)?;
/// assert!((d.mean_area - 4.0 * std::f64::consts::PI / 642.0).abs() < 1e-15);
/// assert!((d.phi - (0.5 / d.mean_area).sqrt()).abs() < 1e-12);
/// # Ok::<(), schemes::Error>(())
/// ```
pub fn density(n_v: &BigInt, radius: f64, tau: f64) -> Result<Density> {
    let bad = |reason: String| Error::Density { reason };
    if n_v.is_zero() || n_v < &BigInt::zero() {
        return Err(bad(format!("the vertex count must be positive, got {n_v}")));
    }
    if !(radius.is_finite() && radius > 0.0) {
        return Err(bad(format!("the radius must be positive, got {radius}")));
    }
    if !(tau.is_finite() && tau >= 0.0) {
        return Err(bad(format!("tau must be non-negative, got {tau}")));
    }
    let n = n_v.to_f64().unwrap_or(f64::INFINITY);
    let mean_area = 4.0 * std::f64::consts::PI * radius * radius / n;
    let out_of_range = |what: &str, value: f64| {
        Error::OutOfFloatRange {
        what: what.to_string(),
        reason: format!(
            "is {value:e} in floating point (radius {radius:e}, tau {tau:e}, V = 10^{:.1}), outside the range of a double: ask for another level or radius",
            crate::log10_abs(n_v)
        ),
    }
    };
    if !(mean_area.is_finite() && mean_area > 0.0) {
        return Err(out_of_range(
            "the mean co-volume area 4 pi r^2 / V",
            mean_area,
        ));
    }
    let phi = (tau / mean_area).sqrt();
    if !phi.is_finite() || (phi == 0.0 && tau > 0.0) {
        return Err(out_of_range("the scale factor phi = sqrt(tau / area)", phi));
    }
    Ok(Density { mean_area, phi })
}

/// The smallest level whose mean co-volume area `4 pi r^2 / V` is at most `target_area`,
/// with its counts.
///
/// # Errors
///
/// [`Error::Density`] for a radius or target area that is not positive and finite,
/// [`Error::OutOfFloatRange`] when the vertex count it needs is infinite or zero in floating
/// point,
/// [`Error::NeverReached`] when `V` stops growing below the needed count, and the errors of
/// the search (see the module documentation).
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::{level_for_area, CountsInput, Plan};
/// let plan = Plan::parse("icosphere")?;
/// let x0 = plan.state_from_input(&"V=12,E=30,F=20".parse::<CountsInput>()?)?;
/// // 4 pi / 0.01 = 1256.6 vertices needed: level 3 has 642, level 4 has 2562.
/// let c = level_for_area(&plan, &x0, 1.0, 0.01)?;
/// assert_eq!((c.level, c.vertices), (4, BigInt::from(2562)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn level_for_area(
    plan: &Plan,
    x0: &[BigInt],
    radius: f64,
    target_area: f64,
) -> Result<LevelCounts> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(Error::Density {
            reason: format!("the radius must be positive, got {radius}"),
        });
    }
    if !(target_area.is_finite() && target_area > 0.0) {
        return Err(Error::Density {
            reason: format!("the target area must be positive, got {target_area}"),
        });
    }
    let needed = 4.0 * std::f64::consts::PI * radius * radius / target_area;
    if !(needed.is_finite() && needed > 0.0) {
        return Err(Error::OutOfFloatRange {
            what: "the vertex count needed, 4 pi r^2 / target area,".to_string(),
            reason: format!(
                "is {needed:e} in floating point (radius {radius:e}, target area {target_area:e}), outside the range of a double: use another radius or target area"
            ),
        });
    }
    let probe = Probe {
        plan,
        x0,
        uv: None,
        weights: vec![[1, 0, 0, 0].map(BigInt::from)],
        names: vec!["V".into()],
    };
    let reached = |v: &[BigInt]| v[0].to_f64().unwrap_or(f64::INFINITY) >= needed;
    match probe.first(&reached)? {
        Crossing::At(s) => plan.level_counts(x0, s),
        Crossing::Never(s) => {
            let c = plan.level_counts(x0, s)?;
            Err(Error::NeverReached {
                what: "V".into(),
                target: format!("{needed:.6e} (for a mean area of {target_area})"),
                value: c.vertices.to_string(),
                level: s,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{builtin, Scheme};

    fn custom(name: &str, state: &str, matrix: &str) -> Plan {
        let text = format!("name = \"{name}\"\nstate = {state}\nmatrix = {matrix}\n");
        Plan::single(Scheme::from_toml(&text).expect("valid scheme"))
    }

    fn state(values: &[i64]) -> Vec<BigInt> {
        values.iter().map(|&v| BigInt::from(v)).collect()
    }

    /// Issue 11: a first stage of `u64::MAX` levels is searched inside (its end cannot be
    /// computed): the same level as the scheme alone, bounded plan or not.
    #[test]
    fn a_crossing_inside_a_huge_first_stage_is_found() {
        let x0 = state(&[12, 30]);
        let alone = fit(&Plan::parse("loop").unwrap(), &x0, &max_vertices(1 << 40)).unwrap();
        for text in [
            "loop:18446744073709551615,sqrt3",
            "loop:18446744073709551615",
        ] {
            let plan = Plan::parse(text).unwrap();
            assert_eq!(
                fit(&plan, &x0, &max_vertices(1 << 40)).unwrap(),
                alone,
                "{text}"
            );
        }
    }

    /// Issue 11: eq. (1)'s figures are finite and positive, or refused: a count beyond a
    /// double, a radius whose square overflows or underflows, a `tau` whose scale factor
    /// overflows, a target area whose vertex count does.
    #[test]
    fn density_figures_outside_a_double_are_refused() {
        let out_of_range = |r: Result<Density>| matches!(r, Err(Error::OutOfFloatRange { .. }));
        let huge = BigInt::from(10u32).pow(400u32);
        assert!(out_of_range(density(&huge, 1.0, 0.0)));
        assert!(out_of_range(density(&BigInt::from(12), 1e300, 0.0)));
        assert!(out_of_range(density(&BigInt::from(12), 1e-300, 0.0)));
        let many = BigInt::from(10_000_000_000u64);
        assert!(out_of_range(density(&many, 1.0, f64::MAX)));
        let near = BigInt::from(10u32).pow(300u32);
        let d = density(&near, 1.0, 1e-300).unwrap();
        assert!(
            d.mean_area > 0.0 && d.phi > 0.0 && d.phi.is_finite(),
            "{d:?}"
        );
        let plan = Plan::single(builtin("loop").unwrap());
        let x0 = state(&[12, 30]);
        for (radius, area) in [(1.0, 1e-320), (1e200, 1e-200), (1e-300, 1.0)] {
            let r = level_for_area(&plan, &x0, radius, area);
            assert!(
                matches!(r, Err(Error::OutOfFloatRange { .. })),
                "{radius} {area}: {r:?}"
            );
        }
    }

    fn max_vertices(n: u64) -> Budget {
        Budget {
            max_vertices: Some(BigInt::from(n)),
            ..Budget::default()
        }
    }

    /// `(level, V)` of an unbounded answer.
    fn settled(answer: Result<Fit>) -> (u64, BigInt) {
        match answer {
            Ok(Fit::Unbounded { counts }) => (counts.level, counts.vertices),
            other => panic!("expected every level to fit, got {other:?}"),
        }
    }

    /// Counts that never change settle at level 0, not 1 (the search's first window starts
    /// at level 1, which used to be reported).
    #[test]
    fn constant_counts_settle_at_level_0() {
        let identity = custom(
            "constant",
            "[\"V\", \"E\", \"F\"]",
            "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]",
        );
        let x0 = state(&[12, 30, 20]);
        assert_eq!(
            settled(fit(&identity, &x0, &max_vertices(100))),
            (0, BigInt::from(12))
        );
        let every = Budget {
            max_edges: Some(BigInt::from(30)),
            max_faces: Some(BigInt::from(20)),
            memory: Some(MemoryBudget {
                bytes: BigInt::from(12 * 12 + 12 * 20),
                bytes_per_vertex: 12,
                bytes_per_edge: 0,
                bytes_per_face: 12,
                bytes_per_uv: 0,
            }),
            ..max_vertices(12)
        };
        assert_eq!(settled(fit(&identity, &x0, &every)), (0, BigInt::from(12)));
        // A growing scheme from a fixed point: Loop on counts with no edges (V' = V + E,
        // E' = 4E), and on an empty mesh.
        let plan = Plan::from(builtin("loop").expect("built-in"));
        assert_eq!(
            settled(fit(&plan, &state(&[5, 0]), &max_vertices(5))),
            (0, BigInt::from(5))
        );
        assert_eq!(
            settled(fit(&plan, &state(&[0, 0]), &max_vertices(0))),
            (0, BigInt::from(0))
        );
        // The same for the area search: V never reaches the target, from level 0 on.
        match level_for_area(&identity, &x0, 1.0, 1e-3) {
            Err(Error::NeverReached { level, value, .. }) => {
                assert_eq!((level, value.as_str()), (0, "12"));
            }
            other => panic!("expected NeverReached, got {other:?}"),
        }
    }

    /// Counts that really change before they settle report the level where they last
    /// change, before, inside and beyond the search's first window.
    #[test]
    fn settling_counts_report_their_last_change() {
        let vef = "[\"V\", \"E\", \"F\"]";
        // V' = V + E, E' = 0: V is 10, 15, 15, ...
        let one = custom("one", vef, "[[1, 1, 0], [0, 0, 0], [0, 0, 1]]");
        let x0 = state(&[10, 5, 3]);
        assert_eq!(
            settled(fit(&one, &x0, &max_vertices(100))),
            (1, BigInt::from(15))
        );
        // V' = V + E, E' = F, F' = 0: V is 10, 15, 18, 18, ...
        let two = custom("two", vef, "[[1, 1, 0], [0, 0, 1], [0, 0, 0]]");
        assert_eq!(
            settled(fit(&two, &x0, &max_vertices(100))),
            (2, BigInt::from(18))
        );
        match level_for_area(&two, &x0, 1.0, 1e-3) {
            Err(Error::NeverReached { level, value, .. }) => {
                assert_eq!((level, value.as_str()), (2, "18"));
            }
            other => panic!("expected NeverReached, got {other:?}"),
        }
        // A chain of seven: V settles at level 6, past the first window (levels 1..=8 are
        // not constant, the next window starts at 9), found by bisection.
        let chain = custom(
            "chain",
            "[\"V\", \"E\", \"F\", \"a\", \"b\", \"c\", \"d\"]",
            "[[1, 1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0, 0], [0, 0, 0, 1, 0, 0, 0], \
             [0, 0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 0, 1], \
             [0, 0, 0, 0, 0, 0, 0]]",
        );
        let x0 = state(&[1, 1, 1, 1, 1, 1, 1]);
        assert_eq!(
            settled(fit(&chain, &x0, &max_vertices(1000))),
            (6, BigInt::from(7))
        );
        // V drops at the first step (allowed before level 1), then stays: 100, 7, 7, ...
        let drops = custom("drops", vef, "[[0, 1, 0], [0, 1, 0], [0, 0, 1]]");
        assert_eq!(
            settled(fit(&drops, &state(&[100, 7, 0]), &max_vertices(100))),
            (1, BigInt::from(7))
        );
        // Two levels of Loop, then the identity: V is 12, 42, 162, 162, ...
        let identity = Scheme::from_toml(
            "name = \"constant\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n",
        )
        .expect("valid scheme");
        let plan = Plan::from(builtin("loop").expect("built-in"))
            .then(2, identity)
            .expect("any mesh suits the identity");
        assert_eq!(
            settled(fit(&plan, &state(&[12, 30]), &max_vertices(1000))),
            (2, BigInt::from(162))
        );
        // Growing counts are unchanged: the highest level within the budget.
        let plan = Plan::from(builtin("loop").expect("built-in"));
        match fit(&plan, &state(&[12, 30]), &max_vertices(641)) {
            Ok(Fit::Level(c)) => assert_eq!((c.level, c.vertices), (2, BigInt::from(162))),
            other => panic!("expected level 2, got {other:?}"),
        }
    }

    /// V grows like s^2: a budget beyond (2^64)^2 is never crossed at a level a `u64` can name.
    /// The search used to overflow `u64` (a panic); it must refuse with a typed error.
    #[test]
    fn polynomial_growth_against_a_huge_budget_is_refused_not_overflowed() {
        let text = "name = \"slow\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 1, 0], [0, 1, 1], [0, 0, 1]]\n";
        let plan = Plan::single(Scheme::from_toml(text).expect("valid scheme"));
        let x0 = [2, 3, 4].map(BigInt::from);
        let budget = Budget {
            max_vertices: Some(BigInt::from(10).pow(39)),
            ..Budget::default()
        };
        match fit(&plan, &x0, &budget) {
            Err(Error::SearchTooLarge { level, .. }) => assert_eq!(level, u64::MAX),
            other => panic!("expected SearchTooLarge, got {other:?}"),
        }
        // A budget the quadratic does cross is still found exactly: V(s) = 2 + 3s + 2s(s-1).
        let budget = Budget {
            max_vertices: Some(BigInt::from(10).pow(12)),
            ..Budget::default()
        };
        let Ok(Fit::Level(counts)) = fit(&plan, &x0, &budget) else {
            panic!("a level fits")
        };
        let v = |s: u64| {
            BigInt::from(2) + 3 * BigInt::from(s) + BigInt::from(s) * BigInt::from(s) * 2
                - 2 * BigInt::from(s)
        };
        let budget_v = BigInt::from(10).pow(12);
        assert!(
            v(counts.level) <= budget_v && v(counts.level + 1) > budget_v,
            "level {}",
            counts.level
        );
    }
}
