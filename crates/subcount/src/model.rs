//! What a command counts: a recurrence (from `--matrix`) or a scheme plan (from `--scheme`,
//! `--scheme-file`), and its initial state (from `--init`, `--counts`, `--mesh` or `--base`).

use std::cell::RefCell;
use std::ops::RangeInclusive;
use std::path::PathBuf;

use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};
use schemes::{CountsInput, MeshCounts, Plan, Scheme};

use crate::args::{MeshSource, Source};
use crate::failure::{input, usage, Failure, Kind};
use crate::output::Row;

/// The default scheme and counts: the icosahedron under 4:1 (Loop) subdivision.
pub(crate) const DEFAULT_SCHEME: &str = "loop";
/// The icosahedron's counts.
pub(crate) const DEFAULT_COUNTS: &str = "V=12,E=30,F=20";

/// The rule that advances the state one level.
pub(crate) enum Dynamics {
    /// A bare matrix from `--matrix`.
    Matrix(Recurrence),
    /// A scheme, a custom scheme or a composition.
    Plan(Plan),
}

/// Maps a `schemes` error to an exit code: problems with the typed command line are usage
/// errors (2); a scheme that does not apply or a bad scheme file is exit 3.
pub(crate) fn scheme_failure(e: schemes::Error) -> Failure {
    use schemes::Error as E;
    let kind = match &e {
        E::NotApplicable { .. }
        | E::SchemeFile { .. }
        | E::NoMeshCounts { .. }
        | E::BadFace { .. } => Kind::Input,
        E::NothingFits { .. } => Kind::Input,
        E::SearchTooLarge { .. } => Kind::Guard,
        _ => Kind::Usage,
    };
    Failure::new(kind, e)
}

/// Reads the mesh named by `--mesh` or `--base`, if any.
pub(crate) fn load_mesh(mesh: &MeshSource) -> Result<Option<halfedge::PolygonMesh>, Failure> {
    match (&mesh.mesh, &mesh.base) {
        (Some(_), Some(_)) => Err(usage!("--mesh and --base cannot be used together")),
        (Some(path), None) => halfedge::io::read_mesh(path).map(Some).map_err(|e| {
            let kind = if e.is_resource_limit() {
                Kind::Guard
            } else {
                Kind::Input
            };
            Failure::new(kind, e)
        }),
        (None, Some(name)) => halfedge::shapes::from_name(name).map(Some).map_err(|e| {
            let kind = if e.is_resource_limit() {
                Kind::Guard
            } else {
                Kind::Usage
            };
            Failure::new(kind, e)
        }),
        (None, None) => Ok(None),
    }
}

/// How errors name the mesh: its path, or `base mesh NAME`.
pub(crate) fn mesh_label(mesh: &MeshSource) -> String {
    match (&mesh.mesh, &mesh.base) {
        (Some(path), _) => path.display().to_string(),
        (None, Some(name)) => format!("base mesh {name}"),
        (None, None) => "the mesh".to_string(),
    }
}

/// Builds the validated half-edge mesh, naming the file and the line of the offending face.
pub(crate) fn validate(
    poly: &halfedge::PolygonMesh,
    mesh: &MeshSource,
) -> Result<halfedge::HalfEdgeMesh, Failure> {
    halfedge::HalfEdgeMesh::try_from(poly).map_err(|e| {
        let label = mesh_label(mesh);
        let line = e.face().and_then(|f| poly.face_line(f as usize));
        match line {
            Some(line) => input!("{label}: line {line}: {e}"),
            None => input!("{label}: {e}"),
        }
    })
}

/// Refuses a face that uses a vertex twice (on every path, before any counting: such a face
/// makes the counts meaningless), naming the file, the line and the face.
pub(crate) fn refuse_degenerate_faces(
    poly: &halfedge::PolygonMesh,
    mesh: &MeshSource,
) -> Result<(), Failure> {
    for (f, face) in poly.faces().enumerate() {
        for (i, v) in face.iter().enumerate() {
            if face[..i].contains(v) {
                let vertices: Vec<String> = face.iter().map(ToString::to_string).collect();
                let label = mesh_label(mesh);
                let place = poly
                    .face_line(f)
                    .map(|l| format!("line {l}: "))
                    .unwrap_or_default();
                return Err(input!(
                    "{label}: {place}face {f} (vertices {}) repeats vertex {v}",
                    vertices.join(", ")
                ));
            }
        }
    }
    Ok(())
}

/// A scheme that does not apply to the mesh: exit 3, naming the mesh.
pub(crate) fn not_applicable(mesh: &MeshSource, e: schemes::Error) -> Failure {
    input!("{}: {e}", mesh_label(mesh))
}

thread_local! {
    /// The mesh source last counted by [`mesh_counts`] and its statistics: resolving a
    /// scheme against the mesh ([`Dynamics::from_source`]) and mapping the mesh to the
    /// initial state ([`Dynamics::initial_state`]) read the file once.
    static COUNTED: RefCell<Option<(MeshKey, MeshCounts)>> = const { RefCell::new(None) };
}

/// What identifies a mesh source: the file and the base mesh name.
type MeshKey = (Option<PathBuf>, Option<String>);

/// The statistics of the mesh named by `--mesh` or `--base`, if any.
pub(crate) fn mesh_counts(mesh: &MeshSource) -> Result<Option<MeshCounts>, Failure> {
    let key: MeshKey = (mesh.mesh.clone(), mesh.base.clone());
    if let Some(counts) = COUNTED.with_borrow(|c| {
        c.as_ref()
            .filter(|(k, _)| *k == key)
            .map(|(_, counts)| counts.clone())
    }) {
        return Ok(Some(counts));
    }
    match load_mesh(mesh)? {
        Some(poly) => {
            refuse_degenerate_faces(&poly, mesh)?;
            let counts = halfedge::stats::face_list_counts(&poly);
            COUNTED.set(Some((key, counts.clone())));
            Ok(Some(counts))
        }
        None => Ok(None),
    }
}

/// The plan that counts `plan` on the initial state the flags name: the 4:1 aliases
/// (`midpoint`, `butterfly`, `icosphere`) count as `loop-boundary` on a mesh with boundary,
/// exactly as `subdivide` and `verify` count them ([`Plan::for_mesh`], [`Plan::for_counts`]).
/// `loop` itself is unchanged (it refuses a boundary). With no mesh or counts, or with more
/// than one initial state (a usage error [`Dynamics::initial_state`] reports), or counts
/// that do not parse (reported there too), the plan is unchanged.
fn for_initial_state(plan: Plan, source: &Source) -> Result<Plan, Failure> {
    if !plan.has_boundary_variant() {
        return Ok(plan);
    }
    let mesh_given = source.mesh.mesh.is_some() || source.mesh.base.is_some();
    match (&source.init, &source.counts, mesh_given) {
        (None, Some(text), false) => Ok(match CountsInput::parse(text) {
            Ok(input) => plan.for_counts(&input),
            Err(_) => plan,
        }),
        (None, None, true) => Ok(match mesh_counts(&source.mesh)? {
            Some(counts) => plan.for_mesh(&counts),
            None => plan,
        }),
        _ => Ok(plan),
    }
}

impl Dynamics {
    /// Builds the rule named by the flags, or the default (`loop`), counted for the initial
    /// state the flags name (a 4:1 alias on a mesh with boundary counts as `loop-boundary`).
    pub(crate) fn from_source(source: &Source) -> Result<Dynamics, Failure> {
        if let Some(text) = source.matrix.as_deref() {
            if source.scheme.is_some() || source.scheme_file.is_some() {
                return Err(usage!(
                    "--matrix cannot be combined with --scheme or --scheme-file"
                ));
            }
            let matrix: IntMatrix = text.parse().map_err(|e| usage!("invalid --matrix: {e}"))?;
            let recurrence = match &source.names {
                Some(names) => Recurrence::with_names(matrix, names.iter().map(|n| n.trim()))
                    .map_err(|e| usage!("invalid --names: {e}"))?,
                None => Recurrence::new(matrix),
            };
            return Ok(Dynamics::Matrix(recurrence));
        }
        if source.names.is_some() {
            return Err(usage!(
                "--names needs --matrix (a scheme names its own state)"
            ));
        }
        let custom = match &source.scheme_file {
            Some(path) => Some(load_scheme_file(path)?),
            None => None,
        };
        let plan = match (&source.scheme, custom) {
            (Some(text), custom) => Plan::parse_with(text, |name| match &custom {
                Some(c) if c.name() == name => Ok(c.clone()),
                _ => schemes::builtin(name),
            })
            .map_err(scheme_failure)?,
            (None, Some(custom)) => Plan::single(custom),
            (None, None) => Plan::parse(DEFAULT_SCHEME).map_err(scheme_failure)?,
        };
        Ok(Dynamics::Plan(for_initial_state(plan, source)?))
    }

    /// Whether neither a matrix nor a scheme was named (the built-in default).
    pub(crate) fn is_default(source: &Source) -> bool {
        source.matrix.is_none() && source.scheme.is_none() && source.scheme_file.is_none()
    }

    /// The output columns after `level`: the state in order, then whichever of V, E, F the
    /// state lacks (for a composition, every stage's state in order of appearance).
    pub(crate) fn columns(&self) -> Vec<String> {
        match self {
            Dynamics::Matrix(r) => r.names().to_vec(),
            Dynamics::Plan(plan) => {
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
        }
    }

    /// The number of state components at level 0.
    fn dim(&self) -> usize {
        match self {
            Dynamics::Matrix(r) => r.dim(),
            Dynamics::Plan(plan) => plan.state_names().len(),
        }
    }

    fn state_names(&self) -> Vec<String> {
        match self {
            Dynamics::Matrix(r) => r.names().to_vec(),
            Dynamics::Plan(plan) => plan.state_names().to_vec(),
        }
    }

    /// The initial state named by the flags (for the default, the icosahedron).
    pub(crate) fn initial_state(&self, source: &Source) -> Result<Vec<BigInt>, Failure> {
        let given = [
            source.init.is_some(),
            source.counts.is_some(),
            source.mesh.mesh.is_some() || source.mesh.base.is_some(),
        ]
        .iter()
        .filter(|&&b| b)
        .count();
        if given > 1 {
            return Err(usage!(
                "give the initial state once: --init, --counts, or --mesh/--base"
            ));
        }
        let x0 = if let Some(text) = &source.init {
            let values = parse_init(text)?;
            if values.len() != self.dim() {
                return Err(usage!(
                    "--init has {} values but the state has {} components ({})",
                    values.len(),
                    self.dim(),
                    self.state_names().join(", ")
                ));
            }
            if let Dynamics::Plan(plan) = self {
                plan.first().check_state(&values).map_err(scheme_failure)?;
            }
            values
        } else {
            match self {
                Dynamics::Matrix(_) => {
                    return Err(usage!("--matrix needs --init with one value per component"));
                }
                Dynamics::Plan(plan) => {
                    if let Some(counts) = mesh_counts(&source.mesh)? {
                        plan.initial_state(&counts)
                            .map_err(|e| not_applicable(&source.mesh, e))?
                    } else {
                        let text = match (&source.counts, Dynamics::is_default(source)) {
                            (Some(text), _) => text.as_str(),
                            (None, true) => DEFAULT_COUNTS,
                            (None, false) => {
                                return Err(usage!(
                                    "{} needs an initial state: --counts (e.g. {DEFAULT_COUNTS}), --init, --mesh or --base",
                                    plan.name()
                                ))
                            }
                        };
                        let input = CountsInput::parse(text).map_err(scheme_failure)?;
                        plan.state_from_input(&input).map_err(scheme_failure)?
                    }
                }
            }
        };
        Ok(x0)
    }

    /// The closed form that gives the state at every level directly, when there is one: a
    /// bare matrix, or a single scheme without a first step or a cycle; and when its
    /// [`closed_form_cost`](Recurrence::closed_form_cost) is within [`CLOSED_FORM_LIMIT`]
    /// (callers then power the matrix, which is exact too).
    pub(crate) fn direct_form(&self) -> Option<recurrence::ClosedForm> {
        self.direct_form_within(false)
    }

    /// [`direct_form`](Self::direct_form), with no cost limit when `allow_large` is set.
    pub(crate) fn direct_form_within(&self, allow_large: bool) -> Option<recurrence::ClosedForm> {
        let limit = if allow_large {
            u64::MAX
        } else {
            CLOSED_FORM_LIMIT
        };
        match self {
            Dynamics::Matrix(r) => r.closed_form_within(limit).ok(),
            Dynamics::Plan(plan) => {
                let phases = plan.phases();
                match phases.as_slice() {
                    [only]
                        if only.first_level == 0
                            && only.period == 1
                            && only.last_level.is_none() =>
                    {
                        only.recurrence.closed_form_within(limit).ok()
                    }
                    _ => None,
                }
            }
        }
    }

    /// The state at level `s`, by the fastest exact path: the closed form when it is exact
    /// (powers of two become shifts), matrix powering otherwise.
    pub(crate) fn state_at(&self, x0: &[BigInt], s: u64) -> Result<Vec<BigInt>, Failure> {
        if s > 64 {
            if let Some(form) = self.direct_form().filter(|f| f.is_exact()) {
                if let Ok(state) = form.evaluate(x0, s) {
                    return Ok(state);
                }
            }
        }
        match self {
            Dynamics::Matrix(r) => r.state_at(x0, s).map_err(|e| usage!("{e}")),
            Dynamics::Plan(plan) => plan.state_at(x0, s).map_err(scheme_failure),
        }
    }

    /// The row of `columns()` at level `s` given the state there.
    pub(crate) fn row_from_state(&self, level: u64, state: Vec<BigInt>) -> Result<Row, Failure> {
        match self {
            Dynamics::Matrix(_) => Ok(Row {
                level,
                values: state.into_iter().map(Some).collect(),
            }),
            Dynamics::Plan(plan) => {
                let names = plan.state_names_at(level).map_err(scheme_failure)?;
                let vef = if plan.has_mesh_counts() {
                    Some(plan.vef(level, &state).map_err(scheme_failure)?)
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
        }
    }

    /// The row at one level.
    pub(crate) fn row_at(&self, x0: &[BigInt], s: u64) -> Result<Row, Failure> {
        let state = self.state_at(x0, s)?;
        self.row_from_state(s, state)
    }

    /// The rows for a range of levels.
    pub(crate) fn rows(
        &self,
        x0: &[BigInt],
        levels: RangeInclusive<u64>,
    ) -> Result<Vec<Row>, Failure> {
        let (start, end) = (*levels.start(), *levels.end());
        let states: Vec<(u64, Vec<BigInt>)> = match self {
            Dynamics::Matrix(r) => {
                let first = r.state_at(x0, start).map_err(|e| usage!("{e}"))?;
                let states = r
                    .states_up_to(&first, end - start)
                    .map_err(|e| usage!("{e}"))?;
                (start..=end).zip(states).collect()
            }
            Dynamics::Plan(plan) if start <= 64 => {
                let states = plan.states_up_to(x0, end).map_err(scheme_failure)?;
                (0..=end).zip(states).skip(start as usize).collect()
            }
            Dynamics::Plan(plan) => (start..=end)
                .map(|s| plan.state_at(x0, s).map(|x| (s, x)).map_err(scheme_failure))
                .collect::<Result<_, _>>()?,
        };
        states
            .into_iter()
            .map(|(s, x)| self.row_from_state(s, x))
            .collect()
    }

    /// An estimate of log10 of the largest count at level `s`, for resource guards.
    pub(crate) fn estimate_log10_max(&self, x0: &[BigInt], s: u64) -> Result<f64, Failure> {
        match self {
            Dynamics::Matrix(r) => Ok(estimate_log10(r, x0, s).into_iter().fold(0.0, f64::max)),
            Dynamics::Plan(plan) => {
                // Exact up to a small level past every stage boundary, then the last stage's
                // steady matrix bounds the growth.
                let last = plan.stages().last().expect("a plan has a stage");
                let base_level = plan.last_level().unwrap_or(0) + last.scheme().period() + 1;
                if s <= base_level + 64 {
                    let state = plan.state_at(x0, s).map_err(scheme_failure)?;
                    return Ok(state.iter().map(log10_big).fold(0.0, f64::max));
                }
                let state = plan.state_at(x0, base_level).map_err(scheme_failure)?;
                let period = last.scheme().period().max(1);
                let steps = (s - base_level).div_ceil(period);
                let cycle = cycle_recurrence(last.scheme());
                Ok(estimate_log10(&cycle, &state, steps)
                    .into_iter()
                    .fold(0.0, f64::max))
            }
        }
    }
}

/// The largest [`Recurrence::closed_form_cost`] computed without `--allow-large` (about
/// 20 components with entries up to 10^4, a second or two in a debug build). Above it,
/// `formula` refuses (exit 4) and `at`, `table` and `plot` power the matrix instead.
pub(crate) const CLOSED_FORM_LIMIT: u64 = 1 << 22;

/// Refuses, with exit 4, closed forms whose cost estimate exceeds [`CLOSED_FORM_LIMIT`]
/// (every phase of a plan), unless `allow_large`.
pub(crate) fn guard_closed_forms(dynamics: &Dynamics, allow_large: bool) -> Result<(), Failure> {
    if allow_large {
        return Ok(());
    }
    let recurrences: Vec<(String, Recurrence)> = match dynamics {
        Dynamics::Matrix(r) => vec![("--matrix".to_string(), r.clone())],
        Dynamics::Plan(plan) => {
            let phases = plan.phases();
            let single = phases.len() == 1;
            phases
                .into_iter()
                .map(|p| {
                    let what = if single {
                        format!("scheme `{}`", plan.name())
                    } else {
                        format!("scheme `{}`, {}", plan.name(), p.description)
                    };
                    (what, p.recurrence)
                })
                .collect()
        }
    };
    for (what, r) in recurrences {
        let cost = r.closed_form_cost();
        if cost > CLOSED_FORM_LIMIT {
            return Err(Failure::new(
                Kind::Guard,
                anyhow::anyhow!(
                    "{what}: the closed form of a {n}x{n} matrix would cost about {cost:.2e} work units (estimated from its size and entries), more than the limit of {CLOSED_FORM_LIMIT} (about 20 components): use `at` or `table` for exact counts (they power the matrix), or --allow-large to compute it anyway",
                    n = r.dim(),
                    cost = cost as f64,
                ),
            ));
        }
    }
    Ok(())
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

/// The largest scheme file read, in bytes (a 32-component matrix of 20-digit entries is
/// about 25 KB).
pub(crate) const SCHEME_FILE_MAX_BYTES: u64 = 1 << 20;

/// Reads and validates a custom scheme file.
pub(crate) fn load_scheme_file(path: &std::path::Path) -> Result<Scheme, Failure> {
    let text = halfedge::io::read_text_capped(path, SCHEME_FILE_MAX_BYTES)
        .map_err(|e| input!("cannot read {}: {e}", path.display()))?;
    Scheme::from_toml(&text).map_err(|e| input!("{}: {e}", path.display()))
}

/// Parses `12,30,20` (negative values allowed: a recurrence is any integer sequence).
fn parse_init(text: &str) -> Result<Vec<BigInt>, Failure> {
    text.split(',')
        .map(|t| {
            let t = t.trim();
            t.parse::<BigInt>()
                .map_err(|_| usage!("invalid --init: `{t}` is not an integer"))
        })
        .collect()
}

/// An upper estimate of log10 |x_s| for each component, in floating point: powering of the
/// entrywise absolute matrix with renormalization, so that no level overflows `f64`. Used only
/// by resource guards.
pub(crate) fn estimate_log10(recurrence: &Recurrence, x0: &[BigInt], s: u64) -> Vec<f64> {
    let n = recurrence.dim();
    let m = recurrence.matrix();
    // |M| entrywise bounds |M^s| entrywise, so this is an upper bound up to rounding.
    let abs: Vec<f64> = m.rows().flatten().map(|&x| (x as f64).abs()).collect();
    let x: Vec<f64> = x0.iter().map(log10_big).collect();
    let max_x = x.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let mut vec: Vec<f64> = x
        .iter()
        .map(|&l| {
            if l.is_finite() && max_x.is_finite() {
                10f64.powf(l - max_x)
            } else {
                0.0
            }
        })
        .collect();
    let mut log_scale = if max_x.is_finite() { max_x } else { 0.0 };
    let mut base = abs;
    let mut base_log = 0.0f64;
    let mut s = s;
    let mul = |a: &[f64], b: &[f64]| -> Vec<f64> {
        let mut c = vec![0.0; n * n];
        for i in 0..n {
            for k in 0..n {
                let aik = a[i * n + k];
                if aik == 0.0 {
                    continue;
                }
                for j in 0..n {
                    c[i * n + j] += aik * b[k * n + j];
                }
            }
        }
        c
    };
    let normalize = |v: &mut [f64]| -> f64 {
        let max = v.iter().cloned().fold(0.0, f64::max);
        if max > 0.0 {
            v.iter_mut().for_each(|x| *x /= max);
            max.log10()
        } else {
            0.0
        }
    };
    while s > 0 {
        if s & 1 == 1 {
            let mut next = vec![0.0; n];
            for i in 0..n {
                for j in 0..n {
                    next[i] += base[i * n + j] * vec[j];
                }
            }
            vec = next;
            log_scale += base_log + normalize(&mut vec);
        }
        s >>= 1;
        if s > 0 {
            base = mul(&base, &base);
            base_log = 2.0 * base_log + normalize(&mut base);
        }
    }
    vec.iter()
        .map(|&v| {
            if v > 0.0 {
                v.log10() + log_scale
            } else {
                f64::NEG_INFINITY
            }
        })
        .collect()
}

/// log10 |v| (negative infinity for zero), from the top 60 bits.
pub(crate) fn log10_big(v: &BigInt) -> f64 {
    let bits = v.bits();
    if bits == 0 {
        return f64::NEG_INFINITY;
    }
    let shift = bits.saturating_sub(60);
    let top = (v.magnitude() >> shift)
        .to_string()
        .parse::<f64>()
        .unwrap_or(1.0);
    top.log10() + shift as f64 * std::f64::consts::LOG10_2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed-form guard never refuses a built-in scheme (their costs are a few thousand
    /// units, far below the limit), and refuses exactly from 21 components for 3-digit
    /// entries: `n^5 + n^3 w^2` with `w = ceil(n (10 + bits(n)) / 64)`.
    #[test]
    fn closed_form_guard_spares_builtins_and_stops_near_20_components() {
        for scheme in schemes::builtins() {
            let plan = Plan::single(scheme.clone());
            for phase in plan.phases() {
                let cost = phase.recurrence.closed_form_cost();
                assert!(cost < 100_000, "{}: {cost}", scheme.name());
            }
            assert!(guard_closed_forms(&Dynamics::Plan(plan), false).is_ok());
        }
        let dense =
            |n: usize| Recurrence::new(IntMatrix::try_from_rows(vec![vec![999; n]; n]).unwrap());
        assert_eq!(dense(20).closed_form_cost(), 3_200_000 + 8000 * 25);
        assert!(guard_closed_forms(&Dynamics::Matrix(dense(20)), false).is_ok());
        assert_eq!(dense(21).closed_form_cost(), 4_084_101 + 9261 * 25);
        let refused = guard_closed_forms(&Dynamics::Matrix(dense(21)), false).unwrap_err();
        assert_eq!(refused.kind.exit_code(), 4);
        assert!(guard_closed_forms(&Dynamics::Matrix(dense(21)), true).is_ok());
    }

    #[test]
    fn estimate_tracks_exact_digits() {
        let r = Recurrence::with_names("[[1,1],[0,4]]".parse().unwrap(), ["V", "E"]).unwrap();
        let x0 = [BigInt::from(12), BigInt::from(30)];
        for s in [0u64, 1, 5, 100, 1000] {
            let exact = r.state_at(&x0, s).unwrap();
            let est = estimate_log10(&r, &x0, s);
            for (e, x) in est.iter().zip(&exact) {
                let digits = x.to_string().len() as f64;
                assert!(
                    *e + 1.0 >= digits - 1e-9,
                    "s={s}: estimate {e} below {digits} digits"
                );
                assert!(
                    *e <= digits + 1.0,
                    "s={s}: estimate {e} far above {digits} digits"
                );
            }
        }
        let big = estimate_log10(&r, &x0, 1_000_000_000_000);
        assert!((big[0] - 1e12 * 4f64.log10()).abs() < 1e3);
    }
}
