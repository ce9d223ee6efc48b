//! Compositions (`loop:1,sqrt3`): each stage in turn on what the stage before wrote
//! ([`halfedge::subdivide::subdivide_stages`]), every level checked against the composition's
//! prediction when verifying, a memory guard before each stage.

use std::path::Path;
use std::time::{Duration, Instant};

use halfedge::subdivide::{self as sub, StageStart, SubdivideOptions};
use halfedge::PolygonMesh;
use num_bigint::BigInt;
use schemes::Plan;

use crate::error::{Error, Result};
use crate::guard::uv_bytes;
use crate::mesh::LoadedMesh;
use crate::subdivide::SubdivideJob;
use crate::verify::Verified;
use crate::Notes;

/// What the stages before a stage leave resident in the worker threads' heap arenas.
const STAGE_ARENA_BYTES: u64 = 4 << 20;

/// A composition checked against its mesh.
#[derive(Debug)]
pub struct Composition<'m> {
    loaded: &'m LoadedMesh,
    plan: Plan,
    /// The statistics of the mesh's faces.
    counts: schemes::MeshCounts,
}

/// Checks `plan` on `loaded`: its first stage's boundary variant for the mesh, the plan
/// applies, and the mesh has no creases or corners (which no stage after the first could
/// follow) nor holes; then hands the mesh's notes to `notes`.
///
/// # Errors
///
/// [`Error::RepeatedVertex`], [`Error::NotApplicable`], [`Error::NotComposable`], the
/// refusals of [`LoadedMesh::holes`].
pub fn start<'m>(loaded: &'m LoadedMesh, plan: &Plan, notes: Notes<'_>) -> Result<Composition<'m>> {
    loaded.refuse_degenerate_faces()?;
    let counts = halfedge::stats::face_list_counts(&loaded.poly);
    let plan = plan.for_mesh(&counts);
    plan.initial_state(&counts)
        .map_err(|e| loaded.not_applicable(e))?;
    let tags = loaded.tags();
    let what = if !tags.sharp_edges().is_empty() || !tags.sharp_vertices().is_empty() {
        Some("creases and corners")
    } else if !tags.holes().is_empty() {
        Some("holes")
    } else {
        None
    };
    let refuse = |what: &str| Error::NotComposable {
        mesh: loaded.label().to_owned(),
        error: Box::new(halfedge::Error::NotComposable {
            scheme: plan.name(),
            what: what.into(),
        }),
    };
    if let Some(what) = what {
        return Err(refuse(what));
    }
    if loaded.plan_holes(&counts, &plan)?.is_some() {
        return Err(refuse("the holes of boundary none"));
    }
    loaded.emit_notes(notes);
    Ok(Composition {
        loaded,
        plan,
        counts,
    })
}

/// The last level of a composition, and what its run took.
#[derive(Debug)]
pub struct Composed {
    /// The last level (with its UVs when they were carried).
    pub mesh: PolygonMesh,
    /// The subdivision's time.
    pub time: Duration,
    /// The largest need the stages' memory guards predicted, in bytes.
    pub predicted_peak_bytes: BigInt,
}

impl Composition<'_> {
    /// The plan, its first stage's boundary variant chosen for the mesh.
    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// The plan's initial state on the mesh.
    ///
    /// # Errors
    ///
    /// The plan's refusal (checked by [`start`] already).
    pub fn initial_state(&self) -> Result<Vec<BigInt>> {
        Ok(self.plan.initial_state(&self.counts)?)
    }

    /// Every level to `levels`, really subdivided stage by stage, against the prediction.
    ///
    /// # Errors
    ///
    /// A stage's memory guard's refusal, the geometry's errors.
    pub fn verify(&self, levels: u32, threads: usize, allow_large: bool) -> Result<Verified> {
        let opts = SubdivideOptions::default().with_threads(threads);
        let mut peak = BigInt::from(0);
        let poly = &self.loaded.poly;
        let mut guard = |s: &StageStart<'_>| guard_stage(s, poly, false, allow_large, &mut peak);
        let run = sub::subdivide_stages(poly, &self.plan, levels, &opts, true, &mut guard)?;
        Ok(Verified {
            reports: run.reports,
            scheme: self.plan.name(),
            levels,
        })
    }

    /// The stages in turn to `job.levels`, UVs carried (unless the job has none; `vt` at only
    /// some corners is written without UVs, with a note), the last level kept. `output` is
    /// checked before the work ([`crate::output::check_output`]).
    ///
    /// # Errors
    ///
    /// [`Error::RefineOnceComposition`] for a job in `f32` or with frames, the output's
    /// refusals, a stage's memory guard's refusal, the geometry's errors.
    pub fn subdivide(
        &self,
        job: &SubdivideJob,
        output: Option<&Path>,
        notes: Notes<'_>,
    ) -> Result<Composed> {
        let loaded = self.loaded;
        if let Some(path) = output {
            crate::output::check_output(path)?;
        }
        loaded.carry_notes(output, notes);
        let layout = if job.uvs {
            if let Some(partial) = loaded.poly.partial_uvs() {
                notes(format!(
                    "note: {}: {partial}: writing without UVs",
                    loaded.label()
                ));
            }
            loaded.poly.uv_layout()
        } else {
            None
        };
        let mut options = halfedge::tags::SubdivisionOptions::default();
        options.face_varying = job.uv_interpolation.unwrap_or(loaded.options.face_varying);
        let mut opts = SubdivideOptions::default()
            .with_threads(job.threads)
            .with_subdivision(options);
        if let Some(layout) = &layout {
            opts = opts.with_uvs(layout);
        }
        let t1 = Instant::now();
        let mut peak = BigInt::from(0);
        let uvs = layout.is_some();
        let poly = &loaded.poly;
        let mut guard = |s: &StageStart<'_>| guard_stage(s, poly, uvs, job.allow_large, &mut peak);
        let run = sub::subdivide_stages(poly, &self.plan, job.levels, &opts, false, &mut guard)?;
        let time = t1.elapsed();
        let mesh = run.mesh.ok_or(halfedge::Error::BrokenInvariant {
            what: "a composition's run kept no last level".into(),
        })?;
        Ok(Composed {
            mesh,
            time,
            predicted_peak_bytes: peak,
        })
    }
}

/// The memory guard of one stage, as `subdivide`'s of one scheme: the peak of subdividing
/// its mesh to a face list (the input, its half-edge build, the levels), the UV channel's
/// share when UVs are carried, the mesh as read (its file lines and `vt`), and from the
/// second stage on the mesh as read held beside the stage's own; the largest need of the
/// stages so far in `peak`.
fn guard_stage(
    stage: &StageStart<'_>,
    base: &PolygonMesh,
    uvs: bool,
    allow_large: bool,
    peak: &mut BigInt,
) -> halfedge::Result<()> {
    let sizing = stage.rule.scheme_for(stage.counts)?;
    let last_faces = (!stage.face_list)
        .then(|| sub::direct_face_degree(stage.rule))
        .flatten();
    let mut need =
        halfedge::memory::predicted_peak_bytes(&sizing, stage.counts, stage.levels, last_faces)?;
    if !stage.face_list && last_faces.is_none() {
        need += halfedge::memory::face_list_copy_bytes(&sizing, stage.counts, stage.levels)?;
    }
    if uvs {
        need += uv_bytes(stage.mesh, stage.rule, stage.levels, 8, false)?;
    }
    need += halfedge::memory::read_extra_bytes(base);
    // Groups and colors carried (a refinement of the stage's own evaluates colors).
    let how = halfedge::memory::Carrying {
        face_list: stage.face_list,
        ..Default::default()
    };
    need += halfedge::memory::carried_bytes(
        stage.mesh,
        (&sizing, stage.rule),
        stage.counts,
        stage.levels,
        how,
    )?;
    // The stage's input as a half-edge mesh, alive beside its levels.
    if !stage.face_list {
        let c = stage.counts;
        need += BigInt::from(halfedge::HalfEdgeMesh::bytes_for(
            c.vertices, c.edges, c.faces,
        ));
    }
    if stage.index > 0 {
        // The mesh as read, held beside the stage's own; and what the stages before leave
        // resident in the worker threads' heap arenas (1.9 to 3.1 MB measured on the
        // icosahedron and the charted cube at levels 7-8: a stage after the first peaked that
        // much above the same scheme run alone).
        need += BigInt::from(base.heap_bytes()) + BigInt::from(STAGE_ARENA_BYTES);
    }
    let limit = crate::guard::limit(allow_large);
    let need = halfedge::memory::within_limit(need, sizing.name(), stage.levels, limit)?;
    *peak = need.max(peak.clone());
    Ok(())
}
