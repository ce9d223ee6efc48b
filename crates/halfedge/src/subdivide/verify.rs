//! Real subdivision against the prediction, level by level: [`verify`] on a half-edge mesh,
//! [`verify_polygons`] on a raw face list, each level's [`LevelReport`].

use super::*;

/// Predicted and measured counts at one level (see [`verify`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LevelReport {
    /// The level (0 is the input).
    pub level: u32,
    /// The scheme's prediction: every state component, then `V`, `E`, `F` when they are not
    /// state components.
    pub predicted: Vec<(String, BigInt)>,
    /// The same components counted on the real mesh of this level.
    pub measured: Vec<(String, BigInt)>,
}

impl LevelReport {
    /// Whether every measured component equals its prediction.
    pub fn is_match(&self) -> bool {
        self.predicted == self.measured
    }

    /// The components whose measured value differs from the prediction (or was not measured),
    /// by name.
    ///
    /// ```
    /// use halfedge::subdivide::LevelReport;
    /// let r = LevelReport {
    ///     level: 1,
    ///     predicted: vec![("V".into(), 42.into()), ("F".into(), 80.into())],
    ///     measured: vec![("V".into(), 42.into()), ("F".into(), 81.into())],
    /// };
    /// assert_eq!(r.mismatches(), ["F"]);
    /// assert!(!r.is_match());
    /// ```
    pub fn mismatches(&self) -> Vec<&str> {
        self.predicted
            .iter()
            .filter(|(name, value)| !self.measured.iter().any(|(n, v)| n == name && v == value))
            .map(|(name, _)| name.as_str())
            .collect()
    }
}

/// The components a report lists: the state, then `V`, `E`, `F` when not in the state (and
/// the scheme derives them).
pub(super) fn report_names(scheme: &Scheme) -> Vec<String> {
    let mut names: Vec<String> = scheme.state_names().to_vec();
    if scheme.has_mesh_counts() {
        for extra in ["V", "E", "F"] {
            if !names.iter().any(|n| n == extra) {
                names.push(extra.to_owned());
            }
        }
    }
    names
}

fn report(
    scheme: &Scheme,
    counts0: &MeshCounts,
    level: u32,
    measured: &MeshCounts,
) -> Result<LevelReport> {
    let names = report_names(scheme);
    let (state, vef) = if scheme.has_mesh_counts() {
        let c = scheme.counts_at(counts0, u64::from(level))?;
        (c.state, Some([c.vertices, c.edges, c.faces]))
    } else {
        let x0 = scheme.initial_state(counts0)?;
        (scheme.state_at(&x0, u64::from(level))?, None)
    };
    let predicted_value = |name: &str| -> Option<BigInt> {
        match scheme.state_names().iter().position(|n| n == name) {
            Some(i) => Some(state[i].clone()),
            None => {
                let [v, e, f] = vef.as_ref()?;
                Some(match name {
                    "V" => v.clone(),
                    "E" => e.clone(),
                    _ => f.clone(),
                })
            }
        }
    };
    let predicted = names
        .iter()
        .filter_map(|n| predicted_value(n).map(|v| (n.clone(), v)))
        .collect();
    let measured = names
        .iter()
        .filter_map(|n| {
            Stat::from_short_name(n).map(|s| (n.clone(), BigInt::from(measured.get(s))))
        })
        .collect();
    Ok(LevelReport {
        level,
        predicted,
        measured,
    })
}

/// Really subdivides `mesh` level by level up to `levels` by the scheme's rule
/// ([`Scheme::subdivision_rule`]) and reports, for level 0 (the input) to `levels`, every
/// state component of the scheme (and `V`, `E`, `F`) as predicted by its matrix and as
/// counted on the mesh. The output arrays are sized by the rule's own counting scheme, so a
/// custom matrix that predicts wrongly shows up as a mismatch in the reports, not as an error.
///
/// # Errors
///
/// As [`subdivide`], and [`Error::NoSubdivision`] for a scheme without a rule (a scheme file
/// without `topology`).
///
/// ```
/// use halfedge::subdivide::{verify, SubdivideOptions};
/// use halfedge::{shapes, HalfEdgeMesh};
/// use schemes::{builtin, Scheme};
///
/// let grid = HalfEdgeMesh::try_from(&shapes::grid(3, 2)?)?;
/// let reports = verify(&grid, &builtin("loop-boundary")?, 2, &SubdivideOptions::default())?;
/// assert_eq!(reports.len(), 3);
/// assert!(reports.iter().all(|r| r.is_match()));
///
/// // A wrong matrix for Loop's topology (F' = 3F): the real subdivision says otherwise.
/// let wrong = "name = \"wrong\"\nstate = [\"F\"]\nmatrix = [[3]]\ntopology = \"loop\"\n";
/// let reports = verify(&grid, &Scheme::from_toml(wrong)?, 1, &SubdivideOptions::default())?;
/// assert_eq!(reports[1].mismatches(), ["F"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn verify(
    mesh: &HalfEdgeMesh,
    scheme: &Scheme,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<Vec<LevelReport>> {
    let opts = &opts.over_descriptor(mesh, scheme.subdivision_rule())?;
    let counts = mesh.counts();
    let holes = verify_holes(scheme, opts, mesh.n_faces())?.map(|h| {
        (
            h,
            h.written_mesh_counts(mesh),
            crate::holes::degrees_of(mesh),
        )
    });
    level_reports(scheme, &counts, holes, |plan, visit| {
        run_levels(plan, mesh, &counts, levels, opts, visit).map(drop)
    })
}

/// The plan that really subdivides `scheme` (named as the scheme) and the scheme whose
/// predictions are checked, for a mesh with `counts`.
fn verify_plan(scheme: &Scheme, counts: &MeshCounts) -> Result<(Plan, Scheme)> {
    let rule = checked_rule(scheme, counts)?;
    let mut plan = plan(rule, counts)?;
    plan.name = scheme.name().to_owned();
    Ok((plan, scheme.for_mesh(counts)))
}

/// The holes of a [`verify`] run of `scheme` (see [`crate::holes::active`]).
fn verify_holes<'a>(
    scheme: &Scheme,
    opts: &SubdivideOptions<'a>,
    n_faces: usize,
) -> Result<Option<&'a HoleSet>> {
    if opts.holes.map_or(true, HoleSet::is_empty) {
        return Ok(None);
    }
    match scheme.subdivision_rule() {
        Some(rule) => crate::holes::active(opts.holes, rule, n_faces),
        None => Err(no_rule(scheme)),
    }
}

/// [`verify_plan`] with holes: the scheme must accept the written faces (`written`), whose
/// counts it predicts; the subdivision of the whole mesh (`counts`) is sized by the rule's
/// own scheme.
fn verify_plan_with_holes(
    scheme: &Scheme,
    counts: &MeshCounts,
    written: &MeshCounts,
) -> Result<(Plan, Scheme)> {
    let rule = checked_rule(scheme, written)?;
    let mut plan = plan(rule, counts)?;
    plan.name = scheme.name().to_owned();
    Ok((plan, scheme.for_mesh(written)))
}

/// [`verify`] for raw face lists: really subdivides with [`subdivide_polygons`] and compares
/// every component the scheme predicts with the face-list statistics of each level.
///
/// # Errors
///
/// As [`subdivide_polygons`] and [`verify`].
///
/// ```
/// use glam::DVec3;
/// use halfedge::subdivide::{verify_polygons, SubdivideOptions};
/// use halfedge::PolygonMesh;
///
/// let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y];
/// let book = PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
/// let ternary = schemes::builtin("tri-split-3")?;
/// let reports = verify_polygons(&book, &ternary, 2, &SubdivideOptions::default())?;
/// assert!(reports.iter().all(|r| r.is_match()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn verify_polygons(
    mesh: &PolygonMesh,
    scheme: &Scheme,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<Vec<LevelReport>> {
    let counts = crate::stats::face_list_counts(mesh);
    let holes = verify_holes(scheme, opts, mesh.n_faces())?.map(|h| {
        let degrees = mesh.faces().map(<[u32]>::len).collect();
        (h, h.written_counts(mesh), degrees)
    });
    level_reports(scheme, &counts, holes, |plan, visit| {
        faces::run_levels(plan, mesh, levels, opts, visit).map(drop)
    })
}

/// A level [`level_reports`] measures: a half-edge mesh ([`verify`]) or a face list
/// ([`verify_polygons`]).
trait Measured: Sync {
    /// The statistics of all its faces.
    fn all_counts(&self) -> MeshCounts;
    /// The statistics of the faces `written` marks.
    fn written_counts(&self, written: &[bool]) -> MeshCounts;
}

impl Measured for HalfEdgeMesh {
    fn all_counts(&self) -> MeshCounts {
        self.counts()
    }

    fn written_counts(&self, written: &[bool]) -> MeshCounts {
        let faces =
            (0..self.n_faces() as u32).map(|f| self.face_vertices(crate::FaceId(f)).map(|v| v.0));
        written_face_counts(faces, written, self.n_vertices())
    }
}

impl Measured for PolygonMesh {
    fn all_counts(&self) -> MeshCounts {
        crate::stats::face_list_counts(self)
    }

    fn written_counts(&self, written: &[bool]) -> MeshCounts {
        let faces = self.faces().map(|f| f.iter().copied());
        written_face_counts(faces, written, self.n_vertices())
    }
}

/// The reports of every level `run` builds (it subdivides by the plan and hands each level to
/// the visitor), predicted by `scheme` from `counts` (all faces) or, with `holes` (the holes,
/// the written faces' statistics, the degree of every face), from what is written and
/// measured on it: one report loop for both kinds of mesh.
fn level_reports<M: Measured>(
    scheme: &Scheme,
    counts: &MeshCounts,
    holes: Option<(&HoleSet, MeshCounts, Vec<usize>)>,
    run: impl FnOnce(&Plan, &mut (dyn FnMut(u32, &M) -> Result<()> + Send)) -> Result<()>,
) -> Result<Vec<LevelReport>> {
    let (plan, predictor) = match &holes {
        // What is written is predicted from the written faces and counted on them.
        Some((_, written, _)) => verify_plan_with_holes(scheme, counts, written)?,
        None => verify_plan(scheme, counts)?,
    };
    let base = holes.as_ref().map_or(counts, |(_, written, _)| written);
    let mut reports = vec![report(&predictor, base, 0, base)?];
    run(&plan, &mut |s, m: &M| {
        let measured = match &holes {
            Some((holes, _, degrees)) => {
                m.written_counts(&holes.written_at(plan.rule, degrees, s)?)
            }
            None => m.all_counts(),
        };
        reports.push(report(&predictor, base, s, &measured)?);
        Ok(())
    })?;
    Ok(reports)
}
