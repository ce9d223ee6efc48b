//! A real subdivision from a loaded mesh to its last level, in two steps: [`prepare`] picks
//! the path (the raw face list, a half-edge mesh to a face list or a half-edge mesh, or refine
//! once and evaluate into buffers), the UV layout to refine, and guards its memory before
//! anything is built; [`Prepared::run`] subdivides. [`Subdivided::write`] writes the last level
//! as OBJ, atomically.
//!
//! # Design notes (moved from the CLI's `mesh.rs`)
//!
//! Owner of UVs through `subdivide`: the layout refined or why not (no UVs asked, partial `vt`,
//! a rule without UVs: one note each; the raw face-list path writes UVs refined by
//! `subdivide_polygons`), the UV interpolation over the tag ([`uv_interpolation`]), the memory
//! guard's UV share ([`crate::guard::uv_bytes`], when UVs will be refined), the time spent on
//! UVs ([`crate::refined::SurfaceClock`]: the surface's last level reported splits its work
//! from the UVs'); the refinement itself: `halfedge::refine::face_varying`.

use std::path::Path;
use std::time::{Duration, Instant};

use halfedge::holes::HoleSet;
use halfedge::io::ObjWriteOptions;
use halfedge::subdivide::{self as sub, LevelDone, Sharpness, SubdivideOptions};
use halfedge::tags::{FaceVaryingInterpolation, SubdivisionOptions};
use halfedge::uv::{UvLayout, Uvs};
use halfedge::{HalfEdgeMesh, PolygonMesh, Rule};
use num_bigint::BigInt;
use num_traits::ToPrimitive;
use schemes::{MeshCounts, Scheme};

use crate::error::{Error, Result};
use crate::guard::{guard_memory, uv_bytes};
use crate::mesh::LoadedMesh;
use crate::output::MeshFormat;
use crate::refined::{self, Precision, RefineOnce, Refined, SurfaceClock};
use crate::scheme::{choose, on_face_list, Chosen, SchemeChoice};
use crate::Notes;

/// How to subdivide, besides the mesh and the scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct SubdivideJob {
    /// The last level.
    pub levels: u32,
    /// Threads for the geometry passes (0: all cores, 1: the single-thread path).
    pub threads: usize,
    /// Lift the memory guard.
    pub allow_large: bool,
    /// The floating-point type of a refine-once run (`F32` refines once).
    pub precision: Precision,
    /// Refine once, then evaluate this many more times from moved base positions (timed).
    pub frames: u32,
    /// Refine the mesh's UV layout, when it has one (the default).
    pub uvs: bool,
    /// The UV interpolation asked for, over the file's tag.
    pub uv_interpolation: Option<FaceVaryingInterpolation>,
    /// Keep the refinement for evaluations to come ([`Prepared::refinement`]): guarded as a
    /// refine-once run with frames; schemes on the raw face list are refused.
    pub keep_refinement: bool,
    /// Write the limit surface (positions, colors, UVs) instead of the last level's points:
    /// OpenSubdiv's limit masks, Loop and Catmull-Clark (refines once).
    pub limit: bool,
    /// Write the limit surface's normals (from its tangents) as the normals (refines once).
    pub limit_normals: bool,
}

impl SubdivideJob {
    /// Subdivide to `levels`, with every other setting at its default.
    pub fn new(levels: u32) -> SubdivideJob {
        SubdivideJob {
            levels,
            threads: 0,
            allow_large: false,
            precision: Precision::F64,
            frames: 0,
            uvs: true,
            uv_interpolation: None,
            keep_refinement: false,
            limit: false,
            limit_normals: false,
        }
    }

    /// Whether the run refines once and evaluates into buffers.
    fn refine_once(&self) -> bool {
        self.frames > 0
            || self.precision == Precision::F32
            || self.keep_refinement
            || self.wants_limit()
    }

    /// Whether the run computes the limit surface (its positions or its normals).
    fn wants_limit(&self) -> bool {
        self.limit || self.limit_normals
    }
}

/// A subdivision ready to run: its path chosen, its memory guarded, its input validated.
#[derive(Debug)]
pub struct Prepared<'m> {
    pub(crate) loaded: &'m LoadedMesh,
    pub(crate) job: SubdivideJob,
    /// The scheme as it counts what is written.
    pub(crate) chosen: Scheme,
    pub(crate) rule: Rule,
    pub(crate) holes: Option<HoleSet>,
    pub(crate) face_list: bool,
    pub(crate) layout: Option<UvLayout>,
    pub(crate) last_faces: Option<usize>,
    pub(crate) mesh: Option<HalfEdgeMesh>,
    pub(crate) predicted: BigInt,
    pub(crate) final_faces: u64,
    /// Refine once and evaluate into buffers: `--precision f32`, `--frames`, or vertex colors
    /// on a half-edge mesh (refined by the positions' refinement).
    pub(crate) refine_once: bool,
}

/// Chooses how `loaded` is subdivided by `choice` under `job` and guards its memory: the
/// scheme and holes ([`choose`]), the UV layout (none without [`SubdivideJob::uvs`]; `vt` at
/// only some corners is written without UVs, with a note), the path, the predicted peak
/// against half the available memory, then the output (`output`, checked before the work:
/// [`crate::output::check_output`]) and the half-edge mesh.
///
/// # Errors
///
/// [`Error::RepeatedVertex`], [`choose`]'s, [`Error::RefineOnce`], a scheme that does not
/// apply, the memory guard's refusal ([`halfedge::Error::OverMemoryLimit`]), the output's
/// refusals, an invalid mesh ([`Error::InMesh`]).
pub fn prepare<'m>(
    loaded: &'m LoadedMesh,
    choice: &SchemeChoice,
    job: &SubdivideJob,
    output: Option<&Path>,
    notes: Notes<'_>,
) -> Result<Prepared<'m>> {
    let poly = &loaded.poly;
    // A scheme that runs on the half-edge mesh whenever the mesh is valid has it built now and
    // takes the counts its build made (the same numbers as a scan of the face list, at no
    // cost); an invalid mesh is counted by the scan and refused where it always was. A mesh
    // the build accepted has no face with a repeated vertex: the scan for one, which comes
    // first on every path, is left to the others.
    let early = runs_on_half_edges(choice).then(|| loaded.validate());
    if !matches!(early, Some(Ok(_))) {
        loaded.refuse_degenerate_faces()?;
    }
    let counts = match &early {
        Some(Ok(mesh)) => mesh.counts(),
        _ => halfedge::stats::face_list_counts(poly),
    };
    let Chosen {
        scheme: chosen,
        rule,
        holes,
    } = choose(choice, loaded, &counts)?;
    loaded.emit_notes(notes);
    let levels = job.levels;
    let mut face_list = on_face_list(&chosen, rule, &counts, choice.is_custom());
    let layout = if job.uvs {
        if let Some(partial) = poly.partial_uvs() {
            notes(format!(
                "note: {}: {partial}: writing without UVs",
                loaded.label()
            ));
        }
        poly.uv_layout()
    } else {
        None
    };
    if layout.is_some()
        && face_list
        && matches!(rule, Rule::TriSplit(_))
        && HalfEdgeMesh::try_from_polygon_mesh(poly).is_ok()
    {
        // The 1:N² splits (placed on the flat triangles either way) run on the half-edge
        // mesh when the face list is one; the -general schemes and non-manifold input keep
        // the raw face list, whose subdividers refine the UV layout linearly with it.
        face_list = false;
    }
    loaded.carry_notes(output, notes);
    if job.wants_limit() && (face_list || !matches!(rule, Rule::Loop | Rule::CatmullClark)) {
        return Err(Error::LimitNotSupported {
            scheme: chosen.name().to_owned(),
        });
    }
    if job.refine_once() && face_list {
        return Err(match job.keep_refinement {
            true => Error::NoRefinement {
                scheme: chosen.name().to_owned(),
            },
            false => Error::RefineOnce,
        });
    }
    // Colors are refined with the positions' weights: by the refinement that computes the
    // positions (the raw face list places both linearly, in `subdivide_polygons`).
    let refine_once = job.refine_once() || (poly.colors().is_some() && !face_list);
    // The rule's own scheme sizes the output (a custom matrix may be wrong); one that does
    // not apply (a scheme file's `topology = "loop"` on quads) names the mesh, as `verify`.
    let scheme = rule.scheme_for(&counts)?;
    scheme
        .initial_state(&counts)
        .map_err(|e| loaded.not_applicable(e))?;
    // Manifold input: the 4:1 family and Catmull-Clark write the last level
    // straight into a face list (half the peak memory of a half-edge last level).
    let last_faces = (!face_list)
        .then(|| sub::direct_face_degree(rule))
        .flatten();
    let ply = output.is_some_and(|p| crate::output::MeshFormat::of(p) == MeshFormat::Ply);
    let need = predicted_peak(
        loaded,
        (&scheme, rule, &counts),
        (job, refine_once, ply),
        (face_list, last_faces, holes.is_some()),
        layout.is_some(),
    );
    let predicted = guard_memory(need, scheme.name(), levels, job.allow_large)?;
    if let Some(path) = output {
        crate::output::check_output(path)?;
    }
    let mesh = match (face_list, early) {
        (true, _) => None,
        (false, Some(built)) => Some(built?),
        (false, None) => Some(loaded.validate()?),
    };
    let final_faces = scheme
        .counts_at(&counts, u64::from(levels))?
        .faces
        .to_u64()
        .unwrap_or(u64::MAX);
    Ok(Prepared {
        loaded,
        job: *job,
        chosen,
        rule,
        holes,
        face_list,
        layout,
        last_faces,
        mesh,
        predicted,
        final_faces,
        refine_once,
    })
}

/// Whether `choice` subdivides a valid mesh as a half-edge mesh (every scheme file, whose
/// rule runs on the face list only with non-manifold edges, and the built-in schemes that
/// need a manifold).
fn runs_on_half_edges(choice: &SchemeChoice) -> bool {
    match choice {
        SchemeChoice::File { .. } => true,
        SchemeChoice::Builtin(name) => {
            schemes::builtin(name).is_ok_and(|s| s.mesh_class().needs_manifold())
        }
    }
}

/// The peak a run needs, as the memory guard compares it: the surface's path (refine once;
/// the one-shot levels, with crease tables and the face list a half-edge last level becomes;
/// leaving holes out), the UV channel when UVs are refined, and the mesh as read beyond its
/// counts. `path`: on the raw face list, the degree of a last level written as a face list,
/// holes.
fn predicted_peak(
    loaded: &LoadedMesh,
    (scheme, rule, counts): (&Scheme, Rule, &MeshCounts),
    (job, refine_once, ply): (&SubdivideJob, bool, bool),
    (face_list, last_faces, holes): (bool, Option<usize>, bool),
    uvs: bool,
) -> halfedge::Result<BigInt> {
    use halfedge::memory as m;
    let (poly, levels) = (&loaded.poly, job.levels);
    let need = if refine_once {
        let bytes = job.precision.bytes();
        let creases = loaded.has_crease_rules(rule);
        let frames = job.frames > 0 || job.keep_refinement;
        let limit = match job.wants_limit() {
            true => m::predicted_limit_bytes(rule, counts, levels, bytes),
            false => Ok(BigInt::from(0)),
        };
        let peak = m::predicted_refinement_peak_bytes(rule, counts, levels, bytes, frames, creases);
        peak.and_then(|peak| Ok(peak + limit?))
            .and_then(|peak| match holes {
                true => m::refinement_hole_bytes(scheme, counts, levels, bytes)
                    .map(|holes| peak + holes)
                    .map_err(Into::into),
                false => Ok(peak),
            })
    } else {
        let levels_bytes = if loaded.has_crease_rules(rule) && !face_list {
            m::predicted_peak_bytes_with_creases(rule, counts, levels, last_faces)
        } else {
            m::predicted_peak_bytes(scheme, counts, levels, last_faces).map_err(Into::into)
        };
        // A last level built as a half-edge mesh is copied into the face list written.
        let levels_bytes = match last_faces {
            None if !face_list => levels_bytes
                .and_then(|bytes| Ok(bytes + m::face_list_copy_bytes(scheme, counts, levels)?)),
            _ => levels_bytes,
        };
        levels_bytes.and_then(|bytes| match holes {
            true => m::hole_filter_bytes(scheme, counts, levels, last_faces)
                .map(|filter| bytes + filter)
                .map_err(Into::into),
            false => Ok(bytes),
        })
    };
    // With UVs the face-varying channel adds its refinement and buffers (the one-shot path
    // refines them in f64); a rule without a face-varying rule writes without them.
    let need = match uvs {
        true => need.and_then(|need| {
            let scalar = match job.precision {
                Precision::F32 if refine_once => 4,
                _ => 8,
            };
            Ok(need + uv_bytes(poly, rule, levels, scalar, holes)?)
        }),
        false => need,
    };
    // Groups and colors carried, and a PLY writer's copies.
    let how = m::Carrying {
        face_list,
        refinement_scalar: refine_once.then_some(job.precision.bytes()),
        ply,
    };
    let need = need
        .and_then(|need| Ok(need + m::carried_bytes(poly, (scheme, rule), counts, levels, how)?));
    // The face list as read holds its file lines and UVs beyond what its counts predict.
    need.map(|need| need + m::read_extra_bytes(poly))
}

impl Prepared<'_> {
    /// The file's creases and corners and the resolved options, the UV interpolation among
    /// them (the face-list subdividers place points linearly and read neither).
    pub(crate) fn subdivision_inputs(
        &self,
        notes: Notes<'_>,
    ) -> Result<(Option<Sharpness>, SubdivisionOptions)> {
        let (loaded, rule) = (self.loaded, self.rule);
        let (sharpness, mut options) = match &self.mesh {
            Some(mesh) => loaded.crease_inputs(rule, mesh, notes)?,
            None => (None, Default::default()),
        };
        if self.layout.is_some() {
            let asked = self.job.uv_interpolation;
            let mode = uv_interpolation(asked, loaded, rule, self.face_list, notes);
            options = options.with_face_varying(mode);
        }
        Ok((sharpness, options))
    }

    /// The scheme's name as it counts what is written (`loop-boundary` for `loop` on a mesh
    /// with boundary).
    pub fn scheme_name(&self) -> &str {
        self.chosen.name()
    }

    /// The faces of the last level, predicted (`u64::MAX` beyond it).
    pub fn final_faces(&self) -> u64 {
        self.final_faces
    }

    /// The peak the memory guard predicted, in bytes.
    pub fn predicted_peak_bytes(&self) -> &BigInt {
        &self.predicted
    }

    /// Subdivides. `progress` hears of each level of the surface as it is built (a
    /// face-varying channel's levels, which come after, are not reported); `notes` gets the
    /// notes about options a rule does not apply and UVs it cannot refine.
    ///
    /// # Errors
    ///
    /// The geometry's errors (an error about a face of the input names the mesh and line:
    /// [`Error::InMesh`]); a crease the mesh cannot resolve.
    pub fn run(self, progress: &(dyn Fn(u32) + Sync), notes: Notes<'_>) -> Result<Subdivided> {
        let (loaded, job, rule) = (self.loaded, &self.job, self.rule);
        let (poly, levels) = (&loaded.poly, job.levels);
        let refine_once = self.refine_once;
        let groups = poly.groups();
        let holes_as_faces = self.holes.is_some() && !self.face_list && !refine_once;
        let clock = SurfaceClock::new(levels);
        let progress = |done: &LevelDone| {
            if clock.report(done) {
                progress(done.level);
            }
        };
        let (sharpness, options) = self.subdivision_inputs(notes)?;
        let mut opts = SubdivideOptions::default()
            .with_threads(job.threads)
            .with_progress(&progress)
            .with_subdivision(options)
            .with_base_faces(groups.is_some());
        if let Some(sharpness) = &sharpness {
            opts = opts.with_sharpness(sharpness);
        }
        if let Some(holes) = &self.holes {
            opts = opts.with_holes(holes);
        }
        // Level 0 writes the file's UVs as read: the `vt` entries its written corners use,
        // which is what `table` counts at level 0 (the layout's values split a `vt` used at
        // several vertices).
        let as_read = match (&self.layout, poly.uvs()) {
            (Some(_), Some(uvs)) if levels == 0 => {
                Some(uvs.of_written_faces(poly.face_offsets(), |f| {
                    self.holes.as_ref().map_or(true, |h| !h.contains(f as u32))
                }))
            }
            _ => None,
        };
        // The colors of the half-edge mesh's vertices (those some face uses).
        let colors = poly
            .colors()
            .map(|_| poly.colors_of_referenced().unwrap_or_default());
        let t1 = Instant::now();
        let run = |opts: &SubdivideOptions<'_>| match &self.mesh {
            Some(mesh) if refine_once => {
                let run = RefineOnce {
                    mesh,
                    rule,
                    levels,
                    frames: job.frames,
                    opts,
                    clock: &clock,
                    as_read: as_read.as_ref(),
                    colors: colors.as_deref(),
                    groups,
                    limit: job.limit,
                    limit_normals: job.limit_normals,
                };
                refined::run(&run, job.precision).map(Output::Refined)
            }
            // With UVs or groups the last level is a face list carrying them.
            Some(mesh)
                if opts.uvs.is_some()
                    || self.last_faces.is_some()
                    || holes_as_faces
                    || groups.is_some() =>
            {
                sub::subdivide_to_face_list(mesh, rule, levels, opts).map(Output::Faces)
            }
            Some(mesh) => sub::subdivide(mesh, rule, levels, opts).map(Output::Mesh),
            None => sub::subdivide_polygons(poly, rule, levels, opts).map(Output::Polygons),
        };
        let mut result = match &self.layout {
            Some(layout) => match run(&opts.with_uvs(layout)) {
                // Refused before anything is built: the rule has no face-varying rule.
                Err(e @ halfedge::Error::UvsNotSupported { .. }) => {
                    notes(format!(
                        "note: {}: {e}: writing without UVs",
                        loaded.label()
                    ));
                    run(&opts)
                }
                result => result,
            },
            None => run(&opts),
        }
        .map_err(|e| Error::located(e, loaded))?;
        if let Some(as_read) = &as_read {
            set_uvs_as_read(&mut result, as_read)?;
        }
        if let (Output::Faces(level), Some(groups)) = (&mut result, groups) {
            level.carry_groups(groups)?;
        }
        let end = Instant::now();
        let time = match &result {
            Output::Refined(r) => {
                // The UVs' topology is part of refine_topology; their evaluation is not.
                let uv_evaluation = r.uvs.map_or(Duration::ZERO, |u| u.2);
                r.refine_topology + r.first_evaluation + uv_evaluation
            }
            _ => end - t1,
        };
        // The UV values written and the time spent on them (the one-shot path refines them
        // after the surface's last level).
        let since_surface = || clock.since_surface(t1, end);
        let uvs = match &result {
            Output::Refined(r) => r
                .uvs
                .map(|(n, topology, evaluation)| (n, topology + evaluation)),
            Output::Faces(level) => level
                .mesh
                .uvs()
                .map(|u| (u.coords().len(), since_surface())),
            // A level-0 copy keeps the file's UVs (the layout's values), as the other levels do.
            Output::Polygons(p) => p.uvs().map(|u| (u.coords().len(), since_surface())),
            Output::Mesh(_) => None,
        };
        let vef = match &result {
            Output::Mesh(m) => [m.n_vertices(), m.n_edges(), m.n_faces()],
            Output::Faces(level) => [level.mesh.n_vertices(), level.edges, level.mesh.n_faces()],
            Output::Refined(r) => r.vef,
            Output::Polygons(p) => {
                let c = halfedge::stats::face_list_counts(p);
                [c.vertices as usize, c.edges as usize, c.faces as usize]
            }
        };
        Ok(Subdivided {
            output: result,
            vef,
            uvs,
            time,
        })
    }
}

/// At level 0, the file's UVs as read replace the layout's values in a face list written.
fn set_uvs_as_read(result: &mut Output, as_read: &Uvs) -> Result<()> {
    let written = match result {
        Output::Faces(level) => Some(&mut level.mesh),
        Output::Polygons(p) => Some(p),
        Output::Refined(_) | Output::Mesh(_) => None,
    };
    if let Some(m) = written.filter(|m| m.uvs().is_some()) {
        m.set_uvs(Some(as_read.clone()))
            .map_err(|e| halfedge::Error::UvLayoutMismatch {
                reason: e.to_string(),
            })?;
    }
    Ok(())
}

/// The face-varying interpolation of a run with UVs: `flag` (the user's) over the file's
/// `facevaryinginterpolateboundary` tag over `corners-plus1` ([`crate::resolve_options`]
/// resolved the tag; [`LoadedMesh::crease_inputs`] hands it on under Loop and Catmull-Clark).
/// One note when the flag overrides the tag with another value, one when the rule has no such
/// mode (the other rules refine UVs linearly, or not at all).
pub fn uv_interpolation(
    flag: Option<FaceVaryingInterpolation>,
    loaded: &LoadedMesh,
    rule: Rule,
    face_list: bool,
    notes: Notes<'_>,
) -> FaceVaryingInterpolation {
    let resolved = loaded.options.face_varying;
    let Some(flag) = flag else {
        return resolved;
    };
    let label = loaded.label();
    if let Some(tag) = loaded.tags().options.face_varying.filter(|&t| t != flag) {
        notes(format!(
            "note: {label}: --uv-interpolation {flag} overrides the tag facevaryinginterpolateboundary {} ({tag})",
            tag.tag_value()
        ));
    }
    if !matches!(rule, Rule::Loop | Rule::CatmullClark) {
        notes(format!(
            "note: {label}: --uv-interpolation is a mode of loop and catmull-clark, not applied by {rule}"
        ));
    } else if face_list {
        notes(format!(
            "note: {label}: --uv-interpolation is not applied on the raw face list, which refines UVs linearly"
        ));
    }
    flag
}

/// The last level, in the form its path built it.
#[derive(Debug)]
enum Output {
    /// The whole last level as a half-edge mesh.
    Mesh(HalfEdgeMesh),
    /// The last level written straight into a face list.
    Faces(sub::FaceListLevel),
    /// The face-list subdividers' result (non-manifold input).
    Polygons(PolygonMesh),
    /// Refined once, evaluated into buffers.
    Refined(Refined),
}

/// What a run built: the last level, its counts, its UV values and the time spent.
#[derive(Debug)]
pub struct Subdivided {
    output: Output,
    vef: [usize; 3],
    uvs: Option<(usize, Duration)>,
    time: Duration,
}

impl Subdivided {
    /// `[V, E, F]` of the last level.
    pub fn counts(&self) -> [usize; 3] {
        self.vef
    }

    /// The UV values of the last level and the time spent refining them, when UVs were
    /// refined (a level-0 copy keeps the file's).
    pub fn uvs(&self) -> Option<(usize, Duration)> {
        self.uvs
    }

    /// The time the subdivision took (refining once: the topology, the first evaluation and
    /// the UVs' evaluation).
    pub fn time(&self) -> Duration {
        self.time
    }

    /// Refining once: the topology's time and, with frames, the median evaluation's.
    pub fn refine_times(&self) -> Option<(Duration, Option<Duration>)> {
        match &self.output {
            Output::Refined(r) => Some((r.refine_topology, r.evaluate_median)),
            _ => None,
        }
    }

    /// The last level as a face list, as [`Subdivided::write`] writes it (positions, faces,
    /// the UVs refined, colors and groups; a refine-once run's `f32` values widened to `f64`
    /// exactly), for a front end that hands it on in memory.
    ///
    /// ```
    /// use driver::{load, MeshSource, OptionFlags, SchemeChoice};
    /// use driver::subdivide::{prepare, SubdivideJob};
    ///
    /// let mesh = load(&MeshSource::Base("cube".into()), &OptionFlags::default())?;
    /// let scheme = SchemeChoice::Builtin("catmull-clark".into());
    /// let prepared = prepare(&mesh, &scheme, &SubdivideJob::new(1), None, &mut |_| {})?;
    /// let level = prepared.run(&|_| {}, &mut |_| {})?.into_polygon_mesh()?;
    /// assert_eq!((level.n_vertices(), level.n_faces()), (26, 24));
    /// # Ok::<(), driver::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// A refine-once run's buffers that do not fit together ([`halfedge::Error::InvalidOutput`],
    /// a bug).
    pub fn into_polygon_mesh(self) -> Result<PolygonMesh> {
        Ok(match self.output {
            Output::Mesh(m) => m.to_polygon_mesh(),
            Output::Polygons(p) => p,
            Output::Faces(level) => level.mesh,
            Output::Refined(r) => r.into_polygon_mesh()?,
        })
    }

    /// Writes the last level to `path` ([`crate::output::write_atomically`]: `-` is standard
    /// output) as OBJ, or binary PLY for a `.ply` name ([`crate::output::MeshFormat`]), with
    /// UVs when `options` asks and they were refined, normals when it asks, and the colors and
    /// groups the mesh carries.
    ///
    /// # Errors
    ///
    /// The output's errors ([`halfedge::Error::Io`], [`Error::WriteProtected`]).
    pub fn write(&self, path: &Path, options: &ObjWriteOptions) -> Result<()> {
        use crate::output::{write_obj_file, write_polygon_mesh_file, MeshFormat};
        match &self.output {
            Output::Mesh(m) if MeshFormat::of(path) == MeshFormat::Obj => {
                write_obj_file(m, path, options)
            }
            Output::Mesh(m) => write_polygon_mesh_file(&m.to_polygon_mesh(), path, options),
            Output::Polygons(p) => write_polygon_mesh_file(p, path, options),
            Output::Faces(level) => write_polygon_mesh_file(&level.mesh, path, options),
            Output::Refined(r) => r.write(path, options),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{load, load_polygon_mesh, MeshSource, OptionFlags};

    /// Subdivides `loaded` by `scheme` under `job`, and checks that the face list handed out
    /// is what `-o` writes (OBJ read back; `f32` runs compared in `f32`).
    fn in_memory_equals_written(loaded: &LoadedMesh, scheme: &str, job: &SubdivideJob, tag: &str) {
        let choice = SchemeChoice::Builtin(scheme.into());
        let prepared = prepare(loaded, &choice, job, None, &mut |_| {}).unwrap();
        let result = prepared.run(&|_| {}, &mut |_| {}).unwrap();
        let refined = matches!(result.output, Output::Refined(_));
        assert_eq!(refined, tag.starts_with("refined"), "{tag}");
        if tag == "mesh" {
            assert!(matches!(result.output, Output::Mesh(_)));
        }
        let dir = std::env::temp_dir().join(format!("driver-in-memory-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{tag}.obj"));
        let options = ObjWriteOptions::default().with_uvs(result.uvs().is_some());
        result.write(&path, &options).unwrap();
        let written = halfedge::io::read_mesh(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        let counts = result.counts();
        let level = result.into_polygon_mesh().unwrap();
        assert_eq!(level.n_vertices(), counts[0], "{tag}");
        assert_eq!(level.n_faces(), counts[2], "{tag}");
        assert_eq!(level.face_offsets(), written.face_offsets(), "{tag}");
        assert_eq!(level.face_indices(), written.face_indices(), "{tag}");
        let f32_run = job.precision == Precision::F32;
        let same = |a: f64, b: f64| match f32_run {
            true => a as f32 == b as f32,
            false => a.to_bits() == b.to_bits(),
        };
        let pairs = level.positions.iter().zip(&written.positions);
        assert!(
            pairs.clone().all(|(a, b)| (0..3).all(|k| same(a[k], b[k]))),
            "{tag}"
        );
        assert_eq!(
            level.colors().is_some(),
            written.colors().is_some(),
            "{tag}"
        );
        if let (Some(a), Some(b)) = (level.colors(), written.colors()) {
            assert!(
                a.iter()
                    .zip(b)
                    .all(|(a, b)| (0..3).all(|k| same(a[k], b[k]))),
                "{tag}"
            );
        }
        assert_eq!(level.groups(), written.groups(), "{tag}");
    }

    #[test]
    fn the_level_in_memory_is_the_level_written_on_every_path() {
        let flags = OptionFlags::default();
        let ico = load(&MeshSource::Base("icosahedron".into()), &flags).unwrap();
        // A half-edge last level (sqrt3), a face list (loop), the raw face list (-general).
        in_memory_equals_written(&ico, "sqrt3", &SubdivideJob::new(2), "mesh");
        in_memory_equals_written(&ico, "loop", &SubdivideJob::new(2), "faces");
        in_memory_equals_written(&ico, "loop-general", &SubdivideJob::new(2), "polygons");
        // Refined once: in f32, and in f64 for colors.
        let mut f32_job = SubdivideJob::new(2);
        f32_job.precision = Precision::F32;
        in_memory_equals_written(&ico, "loop", &f32_job, "refined-f32");
        let mut cube = halfedge::shapes::cube();
        let colors = (0..8).map(|i| [f64::from(i) / 7.0, 0.5, 1.0]).collect();
        cube.set_colors(Some(colors)).unwrap();
        let mut groups = halfedge::groups::FaceGroups::new(vec!["mtllib a.mtl".into()]);
        for f in 0..6 {
            groups.push_face([None, Some("box"), Some(["red", "blue"][f % 2]), None]);
        }
        cube.set_groups(Some(groups)).unwrap();
        let cube = load_polygon_mesh(cube, "<cube>", &flags).unwrap();
        in_memory_equals_written(&cube, "catmull-clark", &SubdivideJob::new(2), "refined-f64");
    }

    #[test]
    fn an_in_memory_mesh_drops_its_tags_when_they_are_ignored() {
        let mut cube = halfedge::shapes::cube();
        let mut tags = halfedge::tags::Tags::default();
        tags.add_hole(5);
        cube.set_tags(tags).unwrap();
        let kept = load_polygon_mesh(cube.clone(), "<cube>", &OptionFlags::default()).unwrap();
        assert_eq!(kept.tags().hole_faces(), [5]);
        let flags = OptionFlags::new(None, None, None, true);
        let ignored = load_polygon_mesh(cube, "<cube>", &flags).unwrap();
        assert!(ignored.tags().is_empty());
        assert_eq!(ignored.label(), "<cube>");
    }
}
