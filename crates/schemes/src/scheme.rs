//! The [`Scheme`] type: a subdivision rule whose counts evolve linearly.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::Zero;
use recurrence::{ClosedForm, IntMatrix, Recurrence};

use crate::class::{check_counts, Hints};
use crate::input::{linear_text, solve, Facts};
use crate::{CountsInput, Error, FaceKind, MeshClass, MeshCounts, Result, Rule, Stat};

/// One component of a scheme's state.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Component {
    /// Short name, e.g. `IE`; names equal to a [`Stat`] short name bind to that statistic.
    pub name: String,
    /// What it counts, e.g. `interior edges (two faces)`.
    pub meaning: String,
}

/// How the state advances: an optional first-step matrix, then a cycle of matrices applied in
/// turn (a single matrix is a cycle of length one).
///
/// Step `i` (from level `i - 1` to level `i`, `i >= 1`) applies `first_step` when `i = 1` and
/// it is present; the following steps apply `cycle[0]`, `cycle[1]`, ... in turn.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StepRule {
    first_step: Option<IntMatrix>,
    cycle: Vec<IntMatrix>,
}

impl StepRule {
    /// The same matrix at every step.
    pub fn single(matrix: IntMatrix) -> StepRule {
        StepRule {
            first_step: None,
            cycle: vec![matrix],
        }
    }

    /// A first step, then a cycle of matrices (one or more).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidSpec`] when `cycle` is empty or the matrices differ in size.
    pub fn try_new(first_step: Option<IntMatrix>, cycle: Vec<IntMatrix>) -> Result<StepRule> {
        let invalid = |reason: String| Error::InvalidSpec {
            scheme: String::new(),
            reason,
        };
        let Some(dim) = cycle.first().map(IntMatrix::dim) else {
            return Err(invalid("the cycle has no matrix".into()));
        };
        for m in cycle.iter().chain(first_step.iter()) {
            if m.dim() != dim {
                return Err(invalid(format!(
                    "the step matrices differ in size ({dim}x{dim} and {0}x{0})",
                    m.dim()
                )));
            }
        }
        Ok(StepRule { first_step, cycle })
    }

    /// The matrix of step 1, when it differs from the cycle.
    pub fn first_step(&self) -> Option<&IntMatrix> {
        self.first_step.as_ref()
    }

    /// The matrices applied in turn (after the first step, if any).
    pub fn cycle(&self) -> &[IntMatrix] {
        &self.cycle
    }

    /// The number of matrices in the cycle.
    pub fn period(&self) -> u64 {
        self.cycle.len() as u64
    }

    /// The number of state components.
    pub fn dim(&self) -> usize {
        self.cycle[0].dim()
    }

    /// The level at which the cycle starts: 1 with a first step, else 0.
    pub fn cycle_start(&self) -> u64 {
        u64::from(self.first_step.is_some())
    }

    /// The matrix applied at step `i` (from level `i - 1` to level `i`).
    ///
    /// # Panics
    ///
    /// Panics if `i` is zero.
    pub fn matrix_of_step(&self, i: u64) -> &IntMatrix {
        assert!(i >= 1, "steps are numbered from 1");
        if i == 1 {
            if let Some(f) = &self.first_step {
                return f;
            }
        }
        let k = (i - 1 - self.cycle_start()) % self.period();
        &self.cycle[k as usize]
    }

    /// The product of the cycle from position `r` on, wrapping around: the matrix that takes
    /// level `cycle_start + r + p t` to `cycle_start + r + p (t + 1)`. `None` on `i64` overflow.
    pub(crate) fn rotated_product(&self, r: usize) -> Option<IntMatrix> {
        let p = self.cycle.len();
        let mut acc = self.cycle[r % p].clone();
        for k in 1..p {
            acc = self.cycle[(r + k) % p].checked_mul(&acc)?;
        }
        Some(acc)
    }
}

/// V, E or F as a rational linear combination of the state: `sum c_i x_i / divisor`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Derivation {
    coefficients: Vec<i64>,
    divisor: u64,
}

impl Derivation {
    /// `sum coefficients[i] * x_i / divisor`, reduced to lowest terms.
    ///
    /// # Panics
    ///
    /// Panics if `divisor` is zero.
    pub fn new(coefficients: Vec<i64>, divisor: u64) -> Derivation {
        assert!(divisor > 0, "a derivation needs a positive divisor");
        let g = coefficients
            .iter()
            .fold(divisor, |g, &c| g.gcd(&c.unsigned_abs()));
        let g = g.max(1);
        Derivation {
            // `g` divides every nonzero `c`, so `|c / g| <= |c|` fits in `i64`; in `i128`
            // because `g` may be 2^63 (`g as i64` turned `i64::MIN / 2^63` into `+1`).
            coefficients: coefficients
                .iter()
                .map(|&c| {
                    i64::try_from(i128::from(c) / i128::from(g)).expect("|c / g| is at most |c|")
                })
                .collect(),
            divisor: divisor / g,
        }
    }

    /// The integer coefficient of each state component.
    pub fn coefficients(&self) -> &[i64] {
        &self.coefficients
    }

    /// The common divisor (1 for an integer combination).
    pub fn divisor(&self) -> u64 {
        self.divisor
    }

    fn numerator(&self, x: &[BigInt]) -> BigInt {
        self.coefficients
            .iter()
            .zip(x)
            .filter(|(c, _)| **c != 0)
            .map(|(c, v)| BigInt::from(*c) * v)
            .sum()
    }

    /// The text `(2IE + BE)/3` over the given names.
    pub fn to_text(&self, names: &[String]) -> String {
        let terms: Vec<(BigRational, String)> = self
            .coefficients
            .iter()
            .zip(names)
            .filter(|(c, _)| **c != 0)
            .map(|(c, n)| (BigRational::from_integer(BigInt::from(*c)), n.clone()))
            .collect();
        let body = linear_text(&terms);
        if self.divisor == 1 {
            body
        } else if terms.len() == 1 {
            format!("{body}/{}", self.divisor)
        } else {
            format!("({body})/{}", self.divisor)
        }
    }
}

/// Where V, E or F of a scheme comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Source {
    State(usize),
    Derived(Derivation),
    Unknown,
}

/// Everything needed to build a [`Scheme`]; validated by [`Scheme::try_from_spec`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SchemeSpec {
    /// The name.
    pub name: String,
    /// A one-paragraph description.
    pub description: String,
    /// The state components in order.
    pub state: Vec<Component>,
    /// The step rule.
    pub rule: StepRule,
    /// The meshes it applies to.
    pub requires: MeshClass,
    /// The faces of its output mesh after one or more steps, when fixed.
    pub produces: Option<FaceKind>,
    /// V, E or F (those not in the state) as combinations of the state.
    pub derive: Vec<(Stat, Derivation)>,
}

/// A subdivision rule as integer matrices over a named state.
///
/// Built-ins come from [`builtin`](crate::builtin) and [`builtins`](crate::builtins), custom
/// schemes from [`Scheme::from_toml`] or [`Scheme::try_from_spec`].
///
/// # Example: the icosahedron under Loop
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::{builtin, CountsInput};
///
/// let icosphere = builtin("icosphere")?;
/// assert_eq!(icosphere.name(), "icosphere");
/// assert_eq!(icosphere.canonical_name(), "loop");
/// assert_eq!(icosphere.state_names(), ["V", "E"]);
/// let x0 = icosphere.state_from_input(&"V=12,E=30,F=20".parse::<CountsInput>()?)?;
/// let x3 = icosphere.state_at(&x0, 3)?;
/// assert_eq!(icosphere.vef(&x3)?, [642, 1920, 1280].map(BigInt::from));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Scheme {
    name: String,
    canonical: String,
    description: String,
    components: Vec<Component>,
    names: Vec<String>,
    rule: StepRule,
    period_matrix: IntMatrix,
    recurrence: Recurrence,
    class: MeshClass,
    produces: Option<FaceKind>,
    vef: [Source; 3],
    pub(crate) hints: Hints,
    /// The real subdivision this scheme counts, when it has one.
    geometry: Option<Rule>,
    /// A built-in 4:1 name (`loop` and its aliases) that counts as `loop-boundary` on a mesh
    /// with boundary ([`Scheme::for_mesh`]).
    pub(crate) boundary_variant: bool,
}

/// The counts at one level.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LevelCounts {
    /// The level `s`.
    pub level: u64,
    /// The state at level `s`, in the order of [`Scheme::state_names`].
    pub state: Vec<BigInt>,
    /// `V` at level `s`.
    pub vertices: BigInt,
    /// `E` at level `s`.
    pub edges: BigInt,
    /// `F` at level `s`.
    pub faces: BigInt,
}

/// Defines `NAME_u64` and `NAME_usize` for the counts of [`LevelCounts`].
macro_rules! fitting_accessors {
    ($($field:ident: $u64:ident, $usize:ident;)*) => {$(
        #[doc = concat!("`", stringify!($field), "` as a `u64`.")]
        ///
        /// # Errors
        ///
        /// [`Error::CountDoesNotFit`] when the count does not fit.
        pub fn $u64(&self) -> Result<u64> {
            self.fitting(stringify!($field), &self.$field, "u64")
        }

        #[doc = concat!("`", stringify!($field), "` as a `usize`: an array length.")]
        ///
        /// # Errors
        ///
        /// [`Error::CountDoesNotFit`] when the count does not fit.
        pub fn $usize(&self) -> Result<usize> {
            self.fitting(stringify!($field), &self.$field, "usize")
        }
    )*};
}

/// Checked conversions of the exact counts into machine integers, for sizing buffers.
///
/// ```
/// let lp = schemes::builtin("loop")?;
/// let ico: schemes::CountsInput = "V=12,E=30,F=20".parse()?;
/// let x0 = lp.state_from_input(&ico)?;
/// assert_eq!(lp.level_counts(&x0, 3)?.faces_usize()?, 1280);
/// let huge = lp.level_counts(&x0, 40)?;
/// assert_eq!(
///     huge.faces_u64().unwrap_err().to_string(),
///     "level 40 has 24178516392292583494123520 faces: more than u64 can hold"
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
impl LevelCounts {
    fitting_accessors! {
        vertices: vertices_u64, vertices_usize;
        edges: edges_u64, edges_usize;
        faces: faces_u64, faces_usize;
    }

    fn fitting<T: TryFrom<BigInt>>(
        &self,
        what: &'static str,
        count: &BigInt,
        target: &'static str,
    ) -> Result<T> {
        T::try_from(count.clone()).map_err(|_| Error::CountDoesNotFit {
            what,
            level: self.level,
            count: count.clone(),
            target,
        })
    }
}

/// One phase of a periodic or composed scheme, for closed forms.
///
/// For `s = first_level + period * t` (`t >= 0`, and `s <= last_level` when bounded), the
/// state at level `s` is `recurrence.state_at(x, t)` where `x` is the state at `first_level`
/// in the names of `recurrence` (for a [`Plan`](crate::Plan), see
/// [`Plan::phase_initial`](crate::Plan::phase_initial)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Phase {
    /// E.g. `s = 2t + 1`.
    pub description: String,
    /// The matrix over one period, with the state names of the active scheme.
    pub recurrence: Recurrence,
    /// The first level of the phase.
    pub first_level: u64,
    /// Levels advanced per application of the matrix.
    pub period: u64,
    /// The last level of the phase, when bounded (a stage of a plan).
    pub last_level: Option<u64>,
    /// Index of the plan stage (0 for a single scheme).
    pub stage: usize,
}

impl Phase {
    /// The exact closed form of this phase's recurrence, in the phase variable `t`
    /// (`s = first_level + period * t`), with the state at `first_level` as initial values.
    pub fn closed_form(&self) -> ClosedForm {
        self.recurrence.closed_form()
    }
}

pub(crate) fn apply(m: &IntMatrix, x: &[BigInt]) -> Vec<BigInt> {
    m.rows()
        .map(|row| {
            row.iter()
                .zip(x)
                .filter(|(c, _)| **c != 0)
                .map(|(c, v)| BigInt::from(*c) * v)
                .sum()
        })
        .collect()
}

impl Scheme {
    /// Validates a specification and builds the scheme.
    ///
    /// # Errors
    ///
    /// [`Error::Recurrence`] for unusable names (invalid, duplicate, wrong count),
    /// [`Error::InvalidSpec`] when a derivation has the wrong length, derives something other
    /// than V, E, F or a quantity that is already in the state, and [`Error::PeriodOverflow`]
    /// when a product over one period overflows `i64`.
    pub fn try_from_spec(spec: SchemeSpec) -> Result<Scheme> {
        let names: Vec<String> = spec.state.iter().map(|c| c.name.clone()).collect();
        if spec.rule.dim() != names.len() {
            return Err(Error::InvalidSpec {
                scheme: spec.name.clone(),
                reason: format!(
                    "{} state components for {1}x{1} matrices",
                    names.len(),
                    spec.rule.dim()
                ),
            });
        }
        let period_matrix = spec.rule.rotated_product(0).ok_or(Error::PeriodOverflow {
            scheme: spec.name.clone(),
        })?;
        for r in 1..spec.rule.cycle.len() {
            spec.rule.rotated_product(r).ok_or(Error::PeriodOverflow {
                scheme: spec.name.clone(),
            })?;
        }
        let recurrence = Recurrence::with_names(period_matrix.clone(), names.clone())?;
        let mut vef = [Source::Unknown, Source::Unknown, Source::Unknown];
        for (k, stat) in [Stat::V, Stat::E, Stat::F].into_iter().enumerate() {
            if let Some(i) = names.iter().position(|n| n == stat.short_name()) {
                vef[k] = Source::State(i);
            }
        }
        for (stat, d) in spec.derive {
            let k = match stat {
                Stat::V => 0,
                Stat::E => 1,
                Stat::F => 2,
                other => {
                    return Err(Error::InvalidSpec {
                        scheme: spec.name.clone(),
                        reason: format!("{other} cannot be derived; only V, E and F"),
                    })
                }
            };
            if d.coefficients.len() != names.len() {
                return Err(Error::InvalidSpec {
                    scheme: spec.name.clone(),
                    reason: format!(
                        "the derivation of {stat} has {} coefficients for {} state components",
                        d.coefficients.len(),
                        names.len()
                    ),
                });
            }
            if matches!(vef[k], Source::State(_)) {
                return Err(Error::InvalidSpec {
                    scheme: spec.name.clone(),
                    reason: format!("{stat} is a state component and cannot also be derived"),
                });
            }
            vef[k] = Source::Derived(d);
        }
        Ok(Scheme {
            canonical: spec.name.clone(),
            name: spec.name,
            description: spec.description,
            components: spec.state,
            names,
            rule: spec.rule,
            period_matrix,
            recurrence,
            class: spec.requires,
            produces: spec.produces,
            vef,
            hints: Hints::default(),
            geometry: None,
            boundary_variant: false,
        })
    }

    /// This scheme with the real subdivision it counts: what `halfedge` runs for it
    /// (`subdivide`) and checks its counts against (`verify`). Built-in schemes have theirs; a
    /// scheme file sets it with `topology = "NAME"`.
    ///
    /// ```
    /// use schemes::{Rule, Scheme};
    ///
    /// let text = "name = \"tri\"\nstate = [\"F\"]\nmatrix = [[4]]\n";
    /// let tri = Scheme::from_toml(text)?.with_subdivision_rule(Rule::Midpoint);
    /// assert_eq!(tri.subdivision_rule(), Some(Rule::Midpoint));
    /// # Ok::<(), schemes::Error>(())
    /// ```
    pub fn with_subdivision_rule(mut self, rule: Rule) -> Scheme {
        self.geometry = Some(rule);
        self
    }

    /// The real subdivision this scheme counts (see
    /// [`with_subdivision_rule`](Self::with_subdivision_rule)); `None` for a matrix without one.
    pub fn subdivision_rule(&self) -> Option<Rule> {
        self.geometry
    }

    pub(crate) fn with_hints(mut self, hints: Hints) -> Scheme {
        self.hints = hints;
        self
    }

    pub(crate) fn renamed(mut self, name: &str) -> Scheme {
        self.name = name.to_string();
        self
    }

    /// The name this scheme was asked for (an alias such as `icosphere` stays visible).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The canonical name of the topology rule, e.g. `loop` for `midpoint`, `butterfly` and
    /// `icosphere` (`loop-boundary` for them on a mesh with boundary, see
    /// [`for_mesh`](Self::for_mesh)); equal to [`name`](Self::name) when no alias was used.
    pub fn canonical_name(&self) -> &str {
        &self.canonical
    }

    /// Same as [`canonical_name`](Self::canonical_name): the rule that decides the counts.
    pub fn topology(&self) -> &str {
        &self.canonical
    }

    /// A short description.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The state components with their meaning, in order.
    pub fn components(&self) -> &[Component] {
        &self.components
    }

    /// The state component names, in order.
    pub fn state_names(&self) -> &[String] {
        &self.names
    }

    /// The number of state components.
    pub fn dim(&self) -> usize {
        self.names.len()
    }

    /// The step rule (first step and cycle).
    pub fn rule(&self) -> &StepRule {
        &self.rule
    }

    /// The steady matrix: for a periodic scheme the product over one period, which takes the
    /// state at level `s` to level `s + period` for `s >=` [`StepRule::cycle_start`].
    pub fn matrix(&self) -> &IntMatrix {
        &self.period_matrix
    }

    /// The first-step matrix, when the scheme has one.
    pub fn first_step(&self) -> Option<&IntMatrix> {
        self.rule.first_step()
    }

    /// The matrices applied in turn.
    pub fn cycle(&self) -> &[IntMatrix] {
        self.rule.cycle()
    }

    /// Number of matrices in the cycle (1 unless periodic).
    pub fn period(&self) -> u64 {
        self.rule.period()
    }

    /// The recurrence of [`matrix`](Self::matrix) with the state names.
    pub fn recurrence(&self) -> &Recurrence {
        &self.recurrence
    }

    /// The exact closed form of [`recurrence`](Self::recurrence): the state at level
    /// `s = cycle_start + period * t` as a function of `t` and the state at `cycle_start`
    /// (for a scheme without first step or cycle: `s = t` and the initial state). Periodic
    /// schemes have one form per residue class: see [`phases`](Self::phases) and
    /// [`Phase::closed_form`].
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// let form = schemes::builtin("loop")?.closed_form();
    /// let x0 = [12, 30].map(BigInt::from);
    /// assert_eq!(form.evaluate(&x0, 5)?, [10242, 30720].map(BigInt::from));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn closed_form(&self) -> ClosedForm {
        self.recurrence.closed_form()
    }

    /// The meshes this scheme applies to.
    pub fn mesh_class(&self) -> &MeshClass {
        &self.class
    }

    /// The kind of faces after one or more steps, when fixed.
    pub fn produces(&self) -> Option<FaceKind> {
        self.produces
    }

    /// Whether V, E and F can all be computed from the state.
    pub fn has_mesh_counts(&self) -> bool {
        !self.vef.iter().any(|s| matches!(s, Source::Unknown))
    }

    /// Those of `V`, `E`, `F` that are not state components but derived from the state, with
    /// their formula, e.g. `[("F", "2E/3")]` for `loop`.
    pub fn derived(&self) -> Vec<(&'static str, String)> {
        ["V", "E", "F"]
            .into_iter()
            .zip(&self.vef)
            .filter_map(|(n, s)| match s {
                Source::Derived(d) => Some((n, d.to_text(&self.names))),
                _ => None,
            })
            .collect()
    }

    /// The derivations of those of V, E, F that are outside the state.
    pub fn derivations(&self) -> Vec<(Stat, &Derivation)> {
        [Stat::V, Stat::E, Stat::F]
            .into_iter()
            .zip(&self.vef)
            .filter_map(|(s, src)| match src {
                Source::Derived(d) => Some((s, d)),
                _ => None,
            })
            .collect()
    }

    /// A JSON description: `name`, `canonical_name`, `description`, `state` (objects with
    /// `name` and `meaning`), `mesh_class` (text), `requires` (keywords), `produces`,
    /// `matrix` (the steady matrix), `first_step` and `cycle` (`null` / omitted when not
    /// used), `period`, and `derive` (formulas of V, E, F outside the state).
    ///
    /// ```
    /// let j = schemes::builtin("loop")?.to_json();
    /// assert_eq!(j["matrix"], serde_json::json!([[1, 1], [0, 4]]));
    /// assert_eq!(j["derive"]["F"], "2E/3");
    /// assert_eq!(j["requires"], serde_json::json!(["triangles", "closed"]));
    /// # Ok::<(), schemes::Error>(())
    /// ```
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::json;
        let derive: serde_json::Map<String, serde_json::Value> = self
            .derived()
            .into_iter()
            .map(|(k, f)| (k.to_string(), json!(f)))
            .collect();
        json!({
            "name": self.name,
            "canonical_name": self.canonical,
            "description": self.description,
            "state": self.components.iter().map(|c| json!({"name": c.name, "meaning": c.meaning})).collect::<Vec<_>>(),
            "mesh_class": self.class.to_string(),
            "requires": self.class.keywords(),
            "produces": self.produces.map(FaceKind::keyword),
            "matrix": self.period_matrix.to_rows(),
            "first_step": self.rule.first_step().map(IntMatrix::to_rows),
            "cycle": (self.period() > 1).then(|| self.rule.cycle().iter().map(IntMatrix::to_rows).collect::<Vec<_>>()),
            "period": self.period(),
            "derive": derive,
        })
    }

    /// Checks that `x0` has one value per state component.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] naming the components.
    pub fn check_state(&self, x0: &[BigInt]) -> Result {
        if x0.len() == self.dim() {
            Ok(())
        } else {
            Err(Error::InitialLength {
                scheme: self.name.clone(),
                got: x0.len(),
                expected: self.dim(),
                names: self.names.join(", "),
            })
        }
    }

    /// The initial state of a mesh, after checking that the scheme applies to it.
    ///
    /// # Errors
    ///
    /// [`Error::NotApplicable`] saying why and what to use instead (Loop on quads ->
    /// catmull-clark, a closed-mesh scheme on a mesh with boundary -> the boundary-aware one,
    /// non-manifold edges -> the `-general` one); [`Error::MissingComponents`] when a state
    /// component is not a mesh statistic (custom schemes).
    ///
    /// ```
    /// use schemes::{builtin, MeshCounts};
    /// let cube = MeshCounts::from_polygons(&[
    ///     [0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0],
    /// ])?;
    /// let err = builtin("loop")?.initial_state(&cube).unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "loop needs a triangle mesh, but this mesh has 6 faces of degree 4; use catmull-clark"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn initial_state(&self, counts: &MeshCounts) -> Result<Vec<BigInt>> {
        check_counts(&self.name, &self.class, &self.hints, counts)?;
        let mut out = Vec::with_capacity(self.dim());
        let mut missing = Vec::new();
        for name in &self.names {
            match Stat::from_short_name(name) {
                Some(s) => out.push(BigInt::from(counts.get(s))),
                None => missing.push(name.clone()),
            }
        }
        if !missing.is_empty() {
            return Err(Error::MissingComponents {
                scheme: self.name.clone(),
                missing,
                hint: Some(
                    "they are not mesh statistics (V, E, IE, BE, NME, F, H); give the initial state by name or in order".into(),
                ),
            });
        }
        self.check_derived(&out)?;
        Ok(out)
    }

    /// The initial state from typed counts: state components by name, the rest filled in by
    /// the identities of the scheme's mesh class (see the [`input`](crate::input) module).
    ///
    /// # Errors
    ///
    /// [`Error::UnknownKey`], [`Error::NotApplicable`] (e.g. `BE=3` for a closed-mesh scheme),
    /// [`Error::Contradiction`] naming both values, [`Error::ImpossibleDerived`], and
    /// [`Error::MissingComponents`] listing what is still needed.
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use schemes::{builtin, CountsInput};
    /// let lb = builtin("loop-boundary")?;
    /// // One triangle: E = 3, F = 1 -> IE = 3F - E = 0, BE = 2E - 3F = 3.
    /// let x0 = lb.state_from_input(&"F=1,V=3,E=3".parse::<CountsInput>()?)?;
    /// assert_eq!(x0, [3, 0, 3].map(BigInt::from));
    /// let err = lb.state_from_input(&"E=3,F=1".parse::<CountsInput>()?).unwrap_err();
    /// assert!(err.to_string().starts_with("loop-boundary needs V in its initial state"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn state_from_input(&self, input: &CountsInput) -> Result<Vec<BigInt>> {
        let facts = Facts::of_class(&self.class);
        self.state_from_known(input, &facts, &self.name)
    }

    pub(crate) fn state_from_known(
        &self,
        input: &CountsInput,
        facts: &Facts,
        who: &str,
    ) -> Result<Vec<BigInt>> {
        let mut given: [Option<BigInt>; 7] = Default::default();
        for (key, value) in input.iter() {
            if let Some(s) = Stat::from_short_name(key) {
                given[s.index()] = Some(value.clone());
            } else if !self.names.iter().any(|n| n == key) {
                let mut known: Vec<String> = Stat::ALL
                    .iter()
                    .map(|s| s.short_name().to_string())
                    .collect();
                known.extend(
                    self.names
                        .iter()
                        .filter(|n| Stat::from_short_name(n).is_none())
                        .cloned(),
                );
                return Err(Error::UnknownKey {
                    key: key.to_string(),
                    scheme: who.to_string(),
                    known: known.join(", "),
                });
            }
        }
        let refuse = |needs: &str, found: String, hint: &Option<String>| Error::NotApplicable {
            scheme: who.to_string(),
            needs: needs.to_string(),
            found,
            hint: hint.as_ref().map(|h| format!("use {h}")),
        };
        let required = [
            (
                facts.manifold,
                Stat::NME,
                "every edge to have one or two faces",
                &self.hints.nonmanifold,
            ),
            (
                facts.closed,
                Stat::BE,
                "a closed mesh",
                &self.hints.boundary,
            ),
        ];
        for (applies, stat, needs, hint) in required {
            let given = given[stat.index()].as_ref().filter(|v| !v.is_zero());
            if let Some(v) = given.filter(|_| applies) {
                return Err(refuse(needs, format!("{}={v}", stat.short_name()), hint));
            }
        }
        let solved = solve(&given, facts)?;
        let mut out = Vec::with_capacity(self.dim());
        let mut missing = Vec::new();
        for name in &self.names {
            let value = match Stat::from_short_name(name) {
                Some(s) => solved[s.index()].clone(),
                None => input.get(name).cloned(),
            };
            match value {
                Some(v) => out.push(v),
                None => missing.push(name.clone()),
            }
        }
        if !missing.is_empty() {
            return Err(Error::MissingComponents {
                scheme: who.to_string(),
                missing: missing.clone(),
                hint: Some(format!(
                    "give {} as well (e.g. {}), or the whole initial state in order",
                    missing.join(", "),
                    missing
                        .iter()
                        .map(|m| format!("{m}=..."))
                        .collect::<Vec<_>>()
                        .join(",")
                )),
            });
        }
        self.check_derived(&out)?;
        Ok(out)
    }

    /// Derived V, E, F must be integers for an initial state that describes a mesh.
    fn check_derived(&self, state: &[BigInt]) -> Result {
        if self.vef.iter().any(|s| matches!(s, Source::Derived(_))) && self.has_mesh_counts() {
            self.vef(state)?;
        }
        Ok(())
    }

    /// The exact state at `level`, applying the first step and the cycle in order.
    ///
    /// Costs `O(n^3 log level)` big-integer operations (powering of the period matrix).
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] when `x0` has the wrong length.
    pub fn state_at(&self, x0: &[BigInt], level: u64) -> Result<Vec<BigInt>> {
        self.check_state(x0)?;
        if level == 0 {
            return Ok(x0.to_vec());
        }
        let (x, start) = match self.rule.first_step() {
            Some(f) => (apply(f, x0), 1),
            None => (x0.to_vec(), 0),
        };
        let n = level - start;
        let p = self.period();
        let mut x = self.recurrence.state_at(&x, n / p)?;
        for m in &self.rule.cycle()[..(n % p) as usize] {
            x = apply(m, &x);
        }
        Ok(x)
    }

    /// The states at levels `0..=last`, one matrix-vector product per level.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] when `x0` has the wrong length.
    pub fn states_up_to(&self, x0: &[BigInt], last: u64) -> Result<Vec<Vec<BigInt>>> {
        self.check_state(x0)?;
        let mut out = vec![x0.to_vec()];
        for i in 1..=last {
            let next = apply(self.rule.matrix_of_step(i), &out[out.len() - 1]);
            out.push(next);
        }
        Ok(out)
    }

    /// `[V, E, F]` of a state, exactly.
    ///
    /// # Errors
    ///
    /// [`Error::NoMeshCounts`] when the scheme cannot count one of them (a custom scheme
    /// without `derive`), [`Error::NotIntegral`] when a derived count is a fraction (a state
    /// that no mesh of the scheme's class has), [`Error::InitialLength`].
    pub fn vef(&self, state: &[BigInt]) -> Result<[BigInt; 3]> {
        self.check_state(state)?;
        let mut out: [BigInt; 3] = Default::default();
        for (k, (what, src)) in ["V", "E", "F"].into_iter().zip(&self.vef).enumerate() {
            out[k] = match src {
                Source::State(i) => state[*i].clone(),
                Source::Derived(d) => {
                    let num = d.numerator(state);
                    let (q, r) = num.div_rem(&BigInt::from(d.divisor));
                    if !r.is_zero() {
                        return Err(Error::NotIntegral {
                            scheme: self.name.clone(),
                            what: what.into(),
                            formula: d.to_text(&self.names),
                            value: BigRational::new(num, BigInt::from(d.divisor)).to_string(),
                        });
                    }
                    q
                }
                Source::Unknown => {
                    return Err(Error::NoMeshCounts {
                        scheme: self.name.clone(),
                        what: what.into(),
                    })
                }
            };
        }
        Ok(out)
    }

    /// The state and `V`, `E`, `F` at `level` from an initial state.
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at) and [`vef`](Self::vef).
    pub fn level_counts(&self, x0: &[BigInt], level: u64) -> Result<LevelCounts> {
        crate::Plan::single(self.clone()).level_counts(x0, level)
    }

    /// The counts of `mesh` after `level` steps: what the `halfedge` crate preallocates.
    ///
    /// # Errors
    ///
    /// As [`initial_state`](Self::initial_state) and [`vef`](Self::vef).
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use schemes::{builtin, MeshCounts};
    /// let quad = MeshCounts::from_polygons(&[[0, 1, 2, 3]])?;
    /// let c = builtin("catmull-clark")?.counts_at(&quad, 2)?;
    /// // A 5 x 5 grid of vertices: 25 V, 40 E, 16 F.
    /// assert_eq!((c.vertices, c.edges, c.faces), (25.into(), 40.into(), 16.into()));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn counts_at(&self, mesh: &MeshCounts, level: u64) -> Result<LevelCounts> {
        crate::Plan::single(self.clone()).counts_at(mesh, level)
    }

    /// The phases for closed forms: one per residue class of the cycle (one phase when the
    /// scheme is not periodic), after the first step if any.
    ///
    /// ```
    /// let s = schemes::builtin("sqrt3-boundary")?;
    /// let p = s.phases();
    /// assert_eq!(p.len(), 2);
    /// assert_eq!(p[0].description, "s = 2t");
    /// assert_eq!(p[1].description, "s = 2t + 1");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn phases(&self) -> Vec<Phase> {
        self.phases_from(0, None, 0)
    }

    pub(crate) fn phases_from(&self, offset: u64, last: Option<u64>, stage: usize) -> Vec<Phase> {
        let p = self.period();
        let start = offset + self.rule.cycle_start();
        (0..p)
            .filter_map(|r| {
                let first_level = start + r;
                if last.is_some_and(|l| first_level > l) {
                    return None;
                }
                let m = self.rule.rotated_product(r as usize)?;
                let recurrence = Recurrence::with_names(m, self.names.clone()).ok()?;
                let mut description = phase_text(p, first_level);
                if let Some(l) = last {
                    description.push_str(&format!(", s <= {l}"));
                }
                Some(Phase {
                    description,
                    recurrence,
                    first_level,
                    period: p,
                    last_level: last,
                    stage,
                })
            })
            .collect()
    }
}

pub(crate) fn phase_text(p: u64, first: u64) -> String {
    let t = if p == 1 {
        "t".to_string()
    } else {
        format!("{p}t")
    };
    if first == 0 {
        format!("s = {t}")
    } else {
        format!("s = {t} + {first}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reduction to lowest terms is exact at the ends of `i64` and `u64`: `i64::MIN x / 2^63`
    /// is `-x` (the cast `2^63 as i64` made it `+x`).
    #[test]
    fn derivations_reduce_exactly_at_the_ends_of_the_integers() {
        let d = Derivation::new(vec![i64::MIN, 0], 1 << 63);
        assert_eq!((d.coefficients(), d.divisor()), (&[-1, 0][..], 1));
        let d = Derivation::new(vec![i64::MIN, 1 << 62], 1 << 63);
        assert_eq!((d.coefficients(), d.divisor()), (&[-2, 1][..], 2));
        let d = Derivation::new(vec![0, 0], u64::MAX);
        assert_eq!((d.coefficients(), d.divisor()), (&[0, 0][..], 1));
        let d = Derivation::new(vec![i64::MAX, -i64::MAX], u64::MAX);
        assert_eq!(d.coefficients(), [i64::MAX, -i64::MAX]);
        assert_eq!(d.divisor(), u64::MAX);
    }
}
