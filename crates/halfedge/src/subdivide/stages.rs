//! Compositions (`loop:1,sqrt3`, a [`schemes::Plan`] of several stages): each stage
//! subdivides, by its own rule, the last level of the stage before, and every level is checked
//! against the composition's own prediction from the input's counts.
//!
//! A stage runs on the half-edge path when its scheme needs a manifold mesh, on the raw face
//! list otherwise (as [`subdivide_polygons`] and [`verify_polygons`] do); UVs
//! ([`SubdivideOptions::uvs`]) are carried from stage to stage (each stage refines the layout
//! of what the stage before wrote), and so are groups and vertex colors
//! ([`PolygonMesh::groups`], [`PolygonMesh::colors`]: each face takes its base face's, colors
//! the positions' weights). Creases, corners and holes are not: a stage's sharpness
//! and a hole's descendants are defined within one rule, so a composition with them is
//! refused ([`Error::NotComposable`]).
//!
//! ```
//! use halfedge::subdivide::{subdivide_stages, SubdivideOptions};
//! use halfedge::shapes;
//!
//! let plan = schemes::Plan::parse("loop:1,sqrt3")?;
//! let ico = shapes::icosahedron();
//! let run = subdivide_stages(&ico, &plan, 3, &SubdivideOptions::default(), false, &mut |_| Ok(()))?;
//! // 20 faces, 80 after Loop, then x3 per √3 level.
//! let last = run.mesh.expect("kept without the check");
//! assert_eq!(last.n_faces(), 80 * 9);
//!
//! // Every level counted against the composition's prediction.
//! let run = subdivide_stages(&ico, &plan, 3, &SubdivideOptions::default(), true, &mut |_| Ok(()))?;
//! assert_eq!(run.reports.len(), 4);
//! assert!(run.reports.iter().all(|r| r.is_match()));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of compositions really subdivided (`verify` and `subdivide` of `A:k,B`: each stage on
//! what the one before wrote, every level against the plan's prediction, UVs carried; creases and
//! holes refused): `halfedge::subdivide::subdivide_stages` (`stages.rs`); the CLI's `compose.rs`
//! (its memory guard per stage).

use num_bigint::BigInt;
use schemes::{MeshCounts, Plan, Scheme};

use super::{
    checked_rule, report_names, subdivide_polygons, subdivide_to_face_list, verify,
    verify_polygons, LevelReport, SubdivideOptions,
};
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result, Rule};

/// What [`subdivide_stages`] built.
#[derive(Debug)]
pub struct StagedRun {
    /// The last level, with its UVs when they were carried; `None` with `check` (the levels
    /// are counted, the last one is not kept).
    pub mesh: Option<PolygonMesh>,
    /// With `check`: one report per level `0..=levels`, the composition's prediction (in the
    /// names of the stage that built the level) against the real level; empty otherwise.
    pub reports: Vec<LevelReport>,
}

/// One stage about to run, for the caller's checks (a memory guard): its scheme, rule and
/// levels, and the mesh it starts from with its statistics.
#[derive(Debug)]
pub struct StageStart<'a> {
    /// The stage's place in the plan (0 the first: its mesh is the caller's).
    pub index: usize,
    /// The mesh it starts from (the caller's, or the last level of the stage before, which
    /// the run holds besides the caller's mesh).
    pub mesh: &'a PolygonMesh,
    /// The stage's scheme (as it counts this mesh).
    pub scheme: &'a Scheme,
    /// The rule that subdivides it.
    pub rule: Rule,
    /// The levels it runs.
    pub levels: u32,
    /// The statistics of the mesh it starts from.
    pub counts: &'a MeshCounts,
    /// Whether it runs on the raw face list (else on a half-edge mesh).
    pub face_list: bool,
}

/// Subdivides `mesh` by the composition `plan` to `levels`, each stage in turn on the last
/// level of the one before. `before_stage` is called before each stage runs (an error stops
/// the run). With `check`, every level's statistics are measured and reported against the
/// plan's prediction from `mesh`'s counts ([`StagedRun::reports`]); without it the last level
/// alone is compared with the prediction ([`Error::PredictionMismatch`]).
///
/// # Errors
///
/// [`Error::NotComposable`] for creases, corners or holes in `opts`; the errors of
/// [`checked_rule`], [`subdivide_to_face_list`], [`subdivide_polygons`], [`verify`] and
/// [`verify_polygons`] for each stage; `before_stage`'s.
pub fn subdivide_stages(
    mesh: &PolygonMesh,
    plan: &Plan,
    levels: u32,
    opts: &SubdivideOptions<'_>,
    check: bool,
    before_stage: &mut dyn FnMut(&StageStart<'_>) -> Result<()>,
) -> Result<StagedRun> {
    if opts.sharpness.is_some_and(|s| !s.is_smooth()) {
        return Err(Error::NotComposable {
            scheme: plan.name(),
            what: "creases and corners".into(),
        });
    }
    if opts.holes.is_some_and(|h| !h.is_empty()) {
        return Err(Error::NotComposable {
            scheme: plan.name(),
            what: "holes".into(),
        });
    }
    let counts0 = crate::stats::face_list_counts(mesh);
    let plan = plan.for_mesh(&counts0);
    let x0 = plan.initial_state(&counts0)?;
    let carry_uvs = opts.uvs.is_some();
    // The last level of the stage before; `mesh` until a stage has run.
    let mut last: Option<PolygonMesh> = None;
    let mut reports = Vec::new();
    let mut start = 0u32;
    for (i, stage) in plan.stages().iter().enumerate() {
        let last_stage = i + 1 == plan.stages().len();
        let n = match stage.levels() {
            Some(k) if !last_stage => u32::try_from(k).unwrap_or(u32::MAX).min(levels - start),
            _ => levels - start,
        };
        if n == 0 && !(check && i == 0) {
            continue;
        }
        let current = last.as_ref().unwrap_or(mesh);
        let counts = crate::stats::face_list_counts(current);
        let scheme = stage.scheme().for_mesh(&counts);
        let rule = checked_rule(&scheme, &counts)?;
        // As `subdivide` of one scheme: the raw face list for the schemes that refine each face
        // on its own and accept any face list; a half-edge mesh (built after the guard, its
        // errors the mesh's) for the others.
        let face_list = !scheme.mesh_class().needs_manifold() && rule.refines_faces();
        before_stage(&StageStart {
            index: i,
            mesh: current,
            scheme: &scheme,
            rule,
            levels: n,
            counts: &counts,
            face_list,
        })?;
        let layout = if carry_uvs { current.uv_layout() } else { None };
        let stage_opts = match &layout {
            Some(layout) => opts.with_uvs(layout),
            None => *opts,
        };
        let he = if face_list {
            None
        } else {
            Some(HalfEdgeMesh::try_from_polygon_mesh(current)?)
        };
        if check {
            let stage_reports = match &he {
                Some(he) => verify(he, &scheme, n, &stage_opts)?,
                None => verify_polygons(current, &scheme, n, &stage_opts)?,
            };
            let skip = usize::from(i > 0 || start > 0);
            for r in stage_reports.into_iter().skip(skip) {
                let level = start + r.level;
                reports.push(plan_report(&plan, &x0, level, &scheme, r.measured)?);
            }
        }
        if n > 0 && (!check || !last_stage) {
            let next = match &he {
                Some(he) => stage_face_list((current, he), (rule, n), &stage_opts)?,
                None => subdivide_polygons(current, rule, n, &stage_opts)?,
            };
            drop(he);
            last = Some(next);
        }
        start += n;
    }
    if !check {
        let predicted = plan.counts_at(&counts0, u64::from(levels))?;
        let measured = crate::stats::face_list_counts(last.as_ref().unwrap_or(mesh));
        let pairs = [
            ("vertices", predicted.vertices, measured.vertices),
            ("edges", predicted.edges, measured.edges),
            ("faces", predicted.faces, measured.faces),
        ];
        for (what, predicted, actual) in pairs {
            if predicted != BigInt::from(actual) {
                return Err(Error::PredictionMismatch {
                    scheme: plan.name(),
                    level: levels,
                    what,
                    predicted,
                    actual,
                });
            }
        }
    }
    let mesh = match last {
        _ if check => None,
        Some(last) => Some(last),
        None => {
            let mut level0 = mesh.clone();
            if !carry_uvs {
                level0.set_uvs(None).ok();
            }
            Some(level0)
        }
    };
    Ok(StagedRun { mesh, reports })
}

/// The report of `level`: the plan's prediction from `x0` in the names of `scheme` (the
/// stage's) against `measured`.
/// One stage on the half-edge path: its last level as a face list, carrying what `current`
/// (the stage's input, `he` its half-edge mesh) carries besides UVs: each face's groups from
/// its base face, the vertex colors refined with the positions' weights
/// ([`Refinement::evaluate_attributes`](crate::Refinement::evaluate_attributes)).
fn stage_face_list(
    (current, he): (&PolygonMesh, &HalfEdgeMesh),
    (rule, n): (Rule, u32),
    opts: &SubdivideOptions<'_>,
) -> Result<PolygonMesh> {
    let groups = current.groups();
    let mut level = subdivide_to_face_list(he, rule, n, &opts.with_base_faces(groups.is_some()))?;
    let invalid = |what: String| Error::InvalidOutput {
        scheme: rule.to_string(),
        level: n,
        what,
    };
    if let Some(groups) = groups {
        level.carry_groups(groups)?;
    }
    if let Some(base) = current.colors_of_referenced() {
        let plain = SubdivideOptions {
            uvs: None,
            limit: false,
            ..*opts
        };
        let refinement = crate::Refinement::new(he, rule, n, &plain)?;
        let mut colors = vec![[0.0f64; 3]; refinement.n_vertices(n)];
        refinement.evaluate_attributes(he, &base, &mut colors)?;
        let scheme = rule.to_string();
        super::check_colors((&scheme, n), &colors, "refined with the positions' weights")?;
        level
            .mesh
            .set_colors(Some(colors))
            .map_err(|e| invalid(e.to_string()))?;
    }
    Ok(level.mesh)
}

fn plan_report(
    plan: &Plan,
    x0: &[BigInt],
    level: u32,
    scheme: &Scheme,
    measured: Vec<(String, BigInt)>,
) -> Result<LevelReport> {
    let c = plan.level_counts(x0, u64::from(level))?;
    let names = plan.state_names_at(u64::from(level))?.to_vec();
    let predicted = report_names(scheme)
        .into_iter()
        .filter_map(|n| {
            let v = match names.iter().position(|m| *m == n) {
                Some(i) => c.state[i].clone(),
                None => match n.as_str() {
                    "V" => c.vertices.clone(),
                    "E" => c.edges.clone(),
                    "F" => c.faces.clone(),
                    _ => return None,
                },
            };
            Some((n, v))
        })
        .collect();
    Ok(LevelReport {
        level,
        predicted,
        measured,
    })
}
