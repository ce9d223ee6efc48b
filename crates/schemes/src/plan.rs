//! [`Plan`]: a single scheme or a composition `A:k,B` (A for k levels, then B), counted
//! through one interface.

use num_bigint::BigInt;
use num_traits::Zero;

use crate::input::Facts;
use crate::scheme::Phase;
use crate::{builtin, CountsInput, Error, FaceKind, LevelCounts, MeshCounts, Result, Scheme, Stat};

/// One stage of a [`Plan`]: a scheme and how many levels it runs (`None`: forever; only the
/// last stage).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stage {
    scheme: Scheme,
    levels: Option<u64>,
}

impl Stage {
    /// The scheme of this stage.
    pub fn scheme(&self) -> &Scheme {
        &self.scheme
    }

    /// The number of levels it runs, `None` when unbounded.
    pub fn levels(&self) -> Option<u64> {
        self.levels
    }
}

/// A single scheme, or schemes applied one after another (`A:k,B`: A for `k` levels, then B).
///
/// The state at level `s` is the state of the stage that produced level `s`, in that
/// scheme's names ([`Plan::scheme_at`]); at a stage boundary `k` it is A's state, and B
/// starts from it mapped through the identities of [`input`](crate::input) with what A's
/// output is known to be (A's faces after a step, closed or manifold when A requires it, or
/// when the counts show `BE = 0`, `NME = 0`).
///
/// # Example
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::{MeshCounts, Plan};
///
/// // A triangle: two levels of Catmull-Clark, then quads stay quads under catmull-clark-quad.
/// let plan = Plan::parse("catmull-clark:2,catmull-clark-quad")?;
/// let tri = MeshCounts::from_polygons(&[[0, 1, 2]])?;
/// let c = plan.counts_at(&tri, 3)?;
/// assert_eq!((c.vertices, c.edges, c.faces), (61.into(), 108.into(), 48.into()));
/// assert_eq!(plan.scheme_at(3)?.name(), "catmull-clark-quad");
///
/// // Loop needs triangles, and Catmull-Clark makes quads.
/// let err = Plan::parse("catmull-clark:1,loop").unwrap_err();
/// assert_eq!(err.to_string(), "loop needs a triangle mesh, but catmull-clark produces quads; use catmull-clark");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    stages: Vec<Stage>,
}

impl From<Scheme> for Plan {
    fn from(scheme: Scheme) -> Plan {
        Plan::single(scheme)
    }
}

impl Plan {
    /// A plan of one scheme, unbounded.
    pub fn single(scheme: Scheme) -> Plan {
        Plan {
            stages: vec![Stage {
                scheme,
                levels: None,
            }],
        }
    }

    /// Parses `A`, `A:k,B`, `A:k,B:j,C`, ... with built-in scheme names.
    ///
    /// # Errors
    ///
    /// [`Error::PlanSyntax`] for bad syntax (a missing level count before the last stage, a
    /// count that is not an integer), the errors of [`builtin`], and [`Error::NotApplicable`]
    /// when a scheme's output faces do not suit the next scheme.
    pub fn parse(text: &str) -> Result<Plan> {
        Plan::parse_with(text, builtin)
    }

    /// As [`parse`](Self::parse), resolving names with `resolve` (e.g. built-ins plus custom
    /// schemes loaded by the caller).
    ///
    /// # Errors
    ///
    /// As [`parse`](Self::parse), plus whatever `resolve` returns.
    pub fn parse_with(text: &str, mut resolve: impl FnMut(&str) -> Result<Scheme>) -> Result<Plan> {
        let syntax = |reason: String| Error::PlanSyntax {
            text: text.to_string(),
            reason,
        };
        let parts: Vec<&str> = text.split(',').map(str::trim).collect();
        let mut plan: Option<Plan> = None;
        let mut pending: Option<u64> = None;
        for (i, part) in parts.iter().enumerate() {
            let last = i + 1 == parts.len();
            let (name, levels) = match part.split_once(':') {
                Some((n, k)) => {
                    let k = k.trim();
                    let levels: u64 = k.parse().map_err(|_| {
                        syntax(format!("`{k}` after `{}:` is not a level count", n.trim()))
                    })?;
                    (n.trim(), Some(levels))
                }
                None => (*part, None),
            };
            if name.is_empty() {
                return Err(syntax(format!("scheme {} has no name", i + 1)));
            }
            if levels.is_none() && !last {
                return Err(syntax(format!(
                    "`{name}` is followed by another scheme, so it needs a level count (`{name}:k`)"
                )));
            }
            let scheme = resolve(name)?;
            plan = Some(match (plan, pending) {
                (None, _) => Plan {
                    stages: vec![Stage { scheme, levels }],
                },
                (Some(p), Some(k)) => {
                    let mut p = p.then(k, scheme)?;
                    if let Some(l) = p.stages.last_mut() {
                        l.levels = levels;
                    }
                    p
                }
                (Some(_), None) => unreachable!("every stage but the last has a level count"),
            });
            pending = levels;
        }
        plan.ok_or_else(|| syntax("no scheme given".into()))
    }

    /// Runs the last stage for `levels` levels, then `next` (unbounded).
    ///
    /// # Errors
    ///
    /// [`Error::NotApplicable`] when the last stage's output faces do not suit `next`.
    pub fn then(mut self, levels: u64, next: Scheme) -> Result<Plan> {
        let prev = self.stages.last_mut().map(|s| {
            s.levels = Some(levels);
            s.clone()
        });
        if let Some(prev) = prev {
            let faces = output_faces(&prev);
            if let Some(degree) = next.mesh_class().faces.degree() {
                let ok = faces.and_then(FaceKind::degree) == Some(degree);
                if !ok {
                    return Err(Error::NotApplicable {
                        scheme: next.name().to_string(),
                        needs: format!("a {} mesh", next.mesh_class().faces.keyword().trim_end_matches('s')),
                        found: match faces {
                            Some(k) => format!("{} produces {}", prev.scheme.name(), k.keyword()),
                            None => format!(
                                "the faces {} produces are not known (declare `produces` in its file)",
                                prev.scheme.name()
                            ),
                        },
                        hint: next.hints.faces.as_ref().map(|h| format!("use {h}")),
                    });
                }
            }
        }
        self.stages.push(Stage {
            scheme: next,
            levels: None,
        });
        Ok(self)
    }

    /// Whether a stage is a 4:1 alias that counts as `loop-boundary` on a mesh with boundary,
    /// or `doo-sabin` / `mid-edge` ([`Scheme::has_boundary_variant`]), so that
    /// [`for_mesh`](Self::for_mesh) and [`for_counts`](Self::for_counts) may change the plan.
    pub fn has_boundary_variant(&self) -> bool {
        self.stages.iter().any(|s| s.scheme.has_boundary_variant())
    }

    /// The plan that counts this one on a mesh with `counts`: every stage through
    /// [`Scheme::for_mesh`], so a 4:1 alias (`midpoint`, `butterfly`, `icosphere`) counts as
    /// `loop-boundary` on a mesh with boundary, as `halfedge`'s subdivision does. A later
    /// stage is decided by the same input mesh: the refinement schemes keep a boundary, and
    /// `loop-boundary` also counts a closed mesh exactly.
    ///
    /// ```
    /// use schemes::{MeshCounts, Plan};
    ///
    /// let open_square = MeshCounts::from_polygons(&[[0, 1, 2], [0, 2, 3]])?;
    /// let plan = Plan::parse("midpoint:1,butterfly")?.for_mesh(&open_square);
    /// let canonical: Vec<&str> = plan.stages().iter().map(|s| s.scheme().canonical_name()).collect();
    /// assert_eq!(canonical, ["loop-boundary", "loop-boundary"]);
    /// assert_eq!(plan.name(), "midpoint:1,butterfly");
    /// let c = plan.counts_at(&open_square, 2)?;
    /// assert_eq!((c.vertices, c.edges, c.faces), (25.into(), 56.into(), 32.into()));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn for_mesh(&self, counts: &MeshCounts) -> Plan {
        self.map_schemes(|s| s.for_mesh(counts))
    }

    /// As [`for_mesh`](Self::for_mesh) for counts typed in, through [`Scheme::for_counts`].
    pub fn for_counts(&self, input: &CountsInput) -> Plan {
        self.map_schemes(|s| s.for_counts(input))
    }

    fn map_schemes(&self, f: impl Fn(&Scheme) -> Scheme) -> Plan {
        Plan {
            stages: self
                .stages
                .iter()
                .map(|s| Stage {
                    scheme: f(&s.scheme),
                    levels: s.levels,
                })
                .collect(),
        }
    }

    /// The stages in order.
    pub fn stages(&self) -> &[Stage] {
        &self.stages
    }

    /// The scheme of the first stage: its state is the plan's initial state.
    pub fn first(&self) -> &Scheme {
        &self.stages[0].scheme
    }

    /// `loop` or `catmull-clark:2,loop-general`.
    pub fn name(&self) -> String {
        self.stages
            .iter()
            .map(|s| match s.levels {
                Some(k) if self.stages.len() > 1 => format!("{}:{k}", s.scheme.name()),
                _ => s.scheme.name().to_string(),
            })
            .collect::<Vec<_>>()
            .join(",")
    }

    /// Whether the plan is one scheme.
    pub fn is_single(&self) -> bool {
        self.stages.len() == 1
    }

    /// The names of the initial state (those of the first stage).
    pub fn state_names(&self) -> &[String] {
        self.first().state_names()
    }

    /// The last level when the last stage has a level count.
    pub fn last_level(&self) -> Option<u64> {
        let last = self.stages.last()?;
        last.levels.map(|_| self.stage_end(self.stages.len() - 1))
    }

    fn stage_start(&self, i: usize) -> u64 {
        self.stages[..i]
            .iter()
            .map(|s| s.levels.unwrap_or(0))
            .fold(0u64, u64::saturating_add)
    }

    fn stage_end(&self, i: usize) -> u64 {
        match self.stages[i].levels {
            Some(k) => self.stage_start(i).saturating_add(k),
            None => u64::MAX,
        }
    }

    /// The index of the stage that produced `level` (a boundary level belongs to the earlier
    /// stage).
    ///
    /// # Errors
    ///
    /// [`Error::LevelBeyondPlan`] past the end of a bounded plan.
    pub fn stage_index_at(&self, level: u64) -> Result<usize> {
        for i in 0..self.stages.len() {
            if level <= self.stage_end(i) {
                return Ok(i);
            }
        }
        Err(Error::LevelBeyondPlan {
            level,
            last: self.stage_end(self.stages.len() - 1),
        })
    }

    /// The scheme whose state describes `level`.
    ///
    /// # Errors
    ///
    /// [`Error::LevelBeyondPlan`].
    pub fn scheme_at(&self, level: u64) -> Result<&Scheme> {
        Ok(&self.stages[self.stage_index_at(level)?].scheme)
    }

    /// The state names at `level`.
    ///
    /// # Errors
    ///
    /// [`Error::LevelBeyondPlan`].
    pub fn state_names_at(&self, level: u64) -> Result<&[String]> {
        Ok(self.scheme_at(level)?.state_names())
    }

    /// The initial state of a mesh for the first stage.
    ///
    /// # Errors
    ///
    /// As [`Scheme::initial_state`].
    pub fn initial_state(&self, counts: &MeshCounts) -> Result<Vec<BigInt>> {
        self.first().initial_state(counts)
    }

    /// The initial state from typed counts for the first stage.
    ///
    /// # Errors
    ///
    /// As [`Scheme::state_from_input`].
    pub fn state_from_input(&self, input: &CountsInput) -> Result<Vec<BigInt>> {
        self.first().state_from_input(input)
    }

    /// The state of stage `i` at `level` (`level` within the stage, its start included), in
    /// that stage's names.
    fn stage_state(&self, x0: &[BigInt], i: usize, level: u64) -> Result<Vec<BigInt>> {
        let start = self.stage_start(i);
        if i == 0 {
            return self.stages[0].scheme.state_at(x0, level);
        }
        let prev = self.stage_state(x0, i - 1, start)?;
        let mapped = self.map_state(i - 1, &prev, start)?;
        self.stages[i].scheme.state_at(&mapped, level - start)
    }

    /// Maps the state of stage `i` at its last level to the state of stage `i + 1`.
    fn map_state(&self, i: usize, state: &[BigInt], level: u64) -> Result<Vec<BigInt>> {
        let (a, b) = (&self.stages[i], &self.stages[i + 1]);
        let after = format!(
            "after {} level{} of {}",
            level - self.stage_start(i),
            if level - self.stage_start(i) == 1 {
                ""
            } else {
                "s"
            },
            a.scheme.name()
        );
        let mut known = CountsInput::default();
        for (name, v) in a.scheme.state_names().iter().zip(state) {
            if Stat::from_short_name(name).is_some() {
                known.insert(name, v.clone())?;
            }
        }
        if a.scheme.has_mesh_counts() {
            let vef = a.scheme.vef(state)?;
            for (name, v) in ["V", "E", "F"].into_iter().zip(vef) {
                if known.get(name).is_none() {
                    known.insert(name, v)?;
                }
            }
        }
        let class = a.scheme.mesh_class();
        let mut facts = Facts {
            faces: output_faces(a).filter(|k| *k != FaceKind::Polygons),
            closed: class.closed,
            manifold: class.needs_manifold(),
        };
        let solved = crate::input::solve(&stat_values(&known), &facts)?;
        let value = |s: Stat| solved[s.index()].clone();
        if value(Stat::NME).is_some_and(|v| v.is_zero()) {
            facts.manifold = true;
        }
        if facts.manifold && value(Stat::BE).is_some_and(|v| v.is_zero()) {
            facts.closed = true;
        }
        let need = b.scheme.mesh_class();
        let refuse = |needs: &str, found: String, hint: &Option<String>| Error::NotApplicable {
            scheme: b.scheme.name().to_string(),
            needs: needs.to_string(),
            found,
            hint: hint.as_ref().map(|h| format!("use {h}")),
        };
        if need.needs_manifold() && !facts.manifold {
            let found = match value(Stat::NME) {
                Some(v) => format!("{after} NME = {v}"),
                None => format!("{after} the non-manifold edges are not known"),
            };
            return Err(refuse(
                "every edge to have one or two faces",
                found,
                &b.scheme.hints.nonmanifold,
            ));
        }
        if need.closed && !facts.closed {
            let found = match value(Stat::BE) {
                Some(v) => format!("{after} BE = {v}"),
                None => format!(
                    "{after} the boundary edges are not known ({} does not count them)",
                    a.scheme.name()
                ),
            };
            return Err(refuse("a closed mesh", found, &b.scheme.hints.boundary));
        }
        let mut all = CountsInput::default();
        for s in Stat::ALL {
            if let Some(v) = value(s) {
                all.insert(s.short_name(), v)?;
            }
        }
        b.scheme.state_from_known(&all, &facts, b.scheme.name())
    }

    /// The exact state at `level`, in the names of [`scheme_at(level)`](Self::scheme_at).
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`], [`Error::LevelBeyondPlan`], and [`Error::NotApplicable`]
    /// when the mesh after one stage does not suit the next (e.g. boundary edges before a
    /// closed-mesh scheme).
    pub fn state_at(&self, x0: &[BigInt], level: u64) -> Result<Vec<BigInt>> {
        self.first().check_state(x0)?;
        let i = self.stage_index_at(level)?;
        self.stage_state(x0, i, level)
    }

    /// `[V, E, F]` of `state`, the state at `level`.
    ///
    /// # Errors
    ///
    /// As [`Scheme::vef`] for [`scheme_at(level)`](Self::scheme_at).
    pub fn vef(&self, level: u64, state: &[BigInt]) -> Result<[BigInt; 3]> {
        self.scheme_at(level)?.vef(state)
    }

    /// Whether every stage can count V, E and F.
    pub fn has_mesh_counts(&self) -> bool {
        self.stages.iter().all(|s| s.scheme.has_mesh_counts())
    }

    /// The state and V, E, F at `level`.
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at) and [`vef`](Self::vef).
    pub fn level_counts(&self, x0: &[BigInt], level: u64) -> Result<LevelCounts> {
        let state = self.state_at(x0, level)?;
        let [vertices, edges, faces] = self.vef(level, &state)?;
        Ok(LevelCounts {
            level,
            state,
            vertices,
            edges,
            faces,
        })
    }

    /// The counts of `mesh` at `level`.
    ///
    /// # Errors
    ///
    /// As [`initial_state`](Self::initial_state) and [`level_counts`](Self::level_counts).
    pub fn counts_at(&self, mesh: &MeshCounts, level: u64) -> Result<LevelCounts> {
        let x0 = self.initial_state(mesh)?;
        self.level_counts(&x0, level)
    }

    /// The states at levels `0..=last`, one step at a time (each in the names of its stage).
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at).
    pub fn states_up_to(&self, x0: &[BigInt], last: u64) -> Result<Vec<Vec<BigInt>>> {
        self.first().check_state(x0)?;
        let mut out = vec![x0.to_vec()];
        let mut stage = 0;
        for level in 1..=last {
            let prev = &out[out.len() - 1];
            let i = self.stage_index_at(level)?;
            let (base, start) = if i != stage {
                let mapped = self.map_state(stage, prev, level - 1)?;
                stage = i;
                (mapped, level - 1)
            } else {
                (prev.clone(), self.stage_start(i))
            };
            let step = level - start;
            let m = self.stages[i].scheme.rule().matrix_of_step(step);
            out.push(crate::scheme::apply(m, &base));
        }
        Ok(out)
    }

    /// The phases for closed forms: each stage's phases (one per residue class of its cycle),
    /// with levels counted from the start of the plan.
    ///
    /// ```
    /// let plan = schemes::Plan::parse("loop-boundary:2,sqrt3-boundary")?;
    /// let d: Vec<String> = plan.phases().into_iter().map(|p| p.description).collect();
    /// assert_eq!(d, ["s = t, s <= 2", "s = 2t + 2", "s = 2t + 3"]);
    /// # Ok::<(), schemes::Error>(())
    /// ```
    pub fn phases(&self) -> Vec<Phase> {
        let mut out = Vec::new();
        for i in 0..self.stages.len() {
            let start = self.stage_start(i);
            let last = self.stages[i].levels.map(|_| self.stage_end(i));
            out.extend(self.stages[i].scheme.phases_from(start, last, i));
        }
        out
    }

    /// The state at `phase.first_level` in the names of the phase's recurrence: the initial
    /// value for its closed form.
    ///
    /// # Errors
    ///
    /// As [`state_at`](Self::state_at).
    pub fn phase_initial(&self, phase: &Phase, x0: &[BigInt]) -> Result<Vec<BigInt>> {
        self.first().check_state(x0)?;
        self.stage_state(
            x0,
            phase.stage.min(self.stages.len() - 1),
            phase.first_level,
        )
    }

    /// The state of the last stage at `level` (at or after its start), in its names.
    pub(crate) fn tail_state(&self, x0: &[BigInt], level: u64) -> Result<Vec<BigInt>> {
        self.first().check_state(x0)?;
        self.stage_state(x0, self.stages.len() - 1, level)
    }

    /// The last stage, its first level, and the level from which its cycle runs.
    pub(crate) fn tail(&self) -> (&Scheme, u64, u64) {
        let i = self.stages.len() - 1;
        let start = self.stage_start(i);
        let scheme = &self.stages[i].scheme;
        (
            scheme,
            start,
            start.saturating_add(scheme.rule().cycle_start()),
        )
    }
}

fn output_faces(stage: &Stage) -> Option<FaceKind> {
    if stage.levels == Some(0) {
        match stage.scheme.mesh_class().faces {
            FaceKind::Polygons => None,
            k => Some(k),
        }
    } else {
        stage.scheme.produces()
    }
}

fn stat_values(input: &CountsInput) -> [Option<BigInt>; 7] {
    let mut out: [Option<BigInt>; 7] = Default::default();
    for (k, v) in input.iter() {
        if let Some(s) = Stat::from_short_name(k) {
            out[s.index()] = Some(v.clone());
        }
    }
    out
}
