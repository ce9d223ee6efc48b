//! Refine once, evaluate many: a [`Refinement`] holds the topology of every level of a
//! subdivision, built once; any per-vertex data (positions in `f32` or `f64`, colours,
//! weights, rest positions) is then refined into the caller's slices as often as needed, and
//! the last level's index buffers are written into the caller's `&mut [u32]`. OpenSubdiv's
//! split, `Far::TopologyRefiner` once and `PrimvarRefiner` / `StencilTable` per frame.
//!
//! # A graphics programmer's five minutes
//!
//! ```
//! use halfedge::refine::Refinement;
//! use halfedge::subdivide::SubdivideOptions;
//! use halfedge::{shapes, HalfEdgeMesh, Rule};
//!
//! let ico = HalfEdgeMesh::try_from(&shapes::icosahedron())?;
//! // Topology of 3 Loop levels, built once; every size is known up front.
//! let refinement = Refinement::new(&ico, Rule::Loop, 3, &SubdivideOptions::default())?;
//! assert_eq!(refinement.n_vertices(3), 642);
//! assert_eq!(refinement.face_degree(), Some(3));
//!
//! // The caller's buffers (a GPU staging buffer, say), sized from the refinement.
//! let mut positions = vec![[0f32; 3]; refinement.n_vertices(3)];
//! let mut indices = vec![0u32; 3 * refinement.n_faces(3)];
//! refinement.write_triangles(&mut indices)?;
//!
//! // Per frame: move the base, evaluate again (no topology work, no allocation).
//! let mut base: Vec<[f32; 3]> = ico.positions().iter().map(|p| p.as_vec3().to_array()).collect();
//! let mut evaluator = refinement.evaluator::<f32, 3>();
//! for frame in 0..3 {
//!     base[0][2] += 0.01 * frame as f32;
//!     evaluator.evaluate(&base, &mut positions)?;
//! }
//! assert!(positions.iter().all(|p| p.iter().all(|x| x.is_finite())));
//!
//! // A buffer of the wrong length is refused, naming it.
//! let err = refinement.evaluate(&base[..5], &mut positions).unwrap_err();
//! assert_eq!(err.to_string(), "base buffer has 5 entries, expected 12");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # The limit surface
//!
//! With [`SubdivideOptions::limit`] the refinement keeps its last level's limit masks:
//! [`Refinement::evaluate_limit`], [`Refinement::evaluate_limit_uvs`],
//! [`Refinement::limit_stencils`] (an example at the first; `refine/limit.rs` has the design).
//!
//! # Same results as the one-shot subdivision
//!
//! The one-shot subdivision is a refinement: [`subdivide`](super::subdivide),
//! [`subdivide_to_face_list`](super::subdivide_to_face_list) and
//! [`verify`](super::verify) run the refinement's one level loop with the retention
//! `Retain::LastTwo` (`levels.rs`, `oneshot.rs`): it checks the same sizes, builds each level by the same topology step, computes its positions by the
//! same evaluation dispatch as [`Refinement::stencils`] and writes the last level's faces
//! with the same index buffers as [`Refinement::write_triangles`], keeping only two levels
//! alive and no flattened tables (it evaluates once), except, under crease rules, the weight
//! table of the level it refines: the table [`Refinement::new`] keeps for that level.
//!
//! The geometry is one implementation: every rule's kernels are generic over the data they
//! combine (`DVec3` for [`subdivide`](super::subdivide), `[T; N]` here, a sparse weighted sum
//! for [`Refinement::stencils`]) and run the same operations in the same order, so in `f64`
//! [`Refinement::evaluate`] on the base positions gives exactly the positions of
//! [`subdivide`](super::subdivide) and [`subdivide_to_face_list`](super::subdivide_to_face_list),
//! to the bit, for every thread count. The index buffers number vertices and faces exactly
//! as [`subdivide_to_face_list`](super::subdivide_to_face_list) (and
//! [`HalfEdgeMesh::to_polygon_mesh`]) do. The kernels' weights are computed in `f64` and
//! rounded to `T`; the sums run in `T`.
//!
//! Evaluation does not check that the results are finite (the one-shot subdivision does):
//! data near the overflow limit of `T` can give infinities.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `subdivide/refine/` (`halfedge::refine`, also `halfedge::{Refinement, StencilTable, Scalar}`):
//! refine once, evaluate many (OpenSubdiv's `TopologyRefiner` + `PrimvarRefiner` / `StencilTable`
//! split). `Refinement::new` checks every level's size from the counts, then builds the
//! connectivity of levels `0..L` only (`topo.rs`'s positionless `Connectivity`, from the
//! index-arithmetic builders of `gather.rs` or, face by face, `build.rs`'s `Builder`, which take
//! the positions the refinement computed: √3, Doo-Sabin and mid-edge on a boundary); the last
//! level's index buffers are written from level `L - 1` for the 4:1 family and Catmull-Clark
//! (bounded by `u32` vertex indices, not half-edge handles), from a kept face list for the
//! other rules. Loop and Catmull-Clark levels are
//! flattened instead (`tables.rs`: edge stencils, vertex rings, face corners), so an evaluation is
//! streaming gathers with no half-edge walk; `Refinement::predicted_bytes` gives what a refinement
//! keeps before it is built. `evaluate` / `evaluate_level` / `evaluate_strided` / `Evaluator`
//! refine `[T; N]` (`T: Scalar`, `f32` or `f64`) into the caller's slices; `stencils` runs the
//! same kernels on sparse sums (`data.rs`'s `Sparse`) and is refused for the icosphere rule;
//! `stencil_sizes` counts the table's rows and entries first (the same kernels on `data.rs`'s
//! `Support`, the sums' vertex sets), so the table is allocated once, exactly. **Architecture
//! Invariant:** one implementation of each rule's geometry. The kernels in `trisplit.rs`,
//! `catmull_clark.rs`, `sqrt3.rs`, `dual.rs` are generic over `data::Vector` (`DVec3` for the
//! one-shot subdivision, `[T; N]`, `Sparse`) and write through `par::Sink` (a growing `Vec` or the
//! caller's slice), every operation componentwise and in one order, so in `f64` a refinement's
//! evaluation equals `subdivide`'s positions to the bit for every rule and thread count
//! (`tests/refine.rs`); the flattened tables call the same kernel functions in the same order.

mod buffers;
mod bytes;
pub(crate) mod corners;
pub(crate) mod creases;
mod evaluate;
pub mod face_varying;
mod levels;
pub(crate) mod limit;
pub(crate) mod oneshot;
mod stencil;
mod tables;
mod varying;

use std::sync::Arc;

use schemes::MeshCounts;

pub use self::evaluate::{Evaluator, Scratch};
pub use self::limit::{LimitStencils, TangentBuffersMut};
pub(crate) use self::oneshot::{one_shot, OneShot};
pub use self::stencil::{StencilSizes, StencilTable};
pub use super::data::Scalar;
pub(crate) use super::data::{Sparse, Support, Vector};

use self::creases::{Creases, LevelTable};
use self::levels::Retain;
use self::tables::{crease_budgets, Fast};
use super::build::{Sizes, StepContext};
use super::par::Slots;
use super::sqrt3::StepB;
use super::topo::{Connectivity, Topo};
use super::trisplit::Template;
use super::weights::{Base, WeightTable};
use super::{LevelDone, Plan, Rule, Split, SubdivideOptions};
use crate::{Error, HalfEdgeMesh, Result};

/// The sizes of one level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct LevelSize {
    vertices: usize,
    edges: usize,
    faces: usize,
    /// The sum of face degrees.
    corners: usize,
}

/// A level whose topology the refinement keeps: what the next level is evaluated from.
#[derive(Debug)]
struct Level {
    /// The connectivity (dropped for the levels before the last kept one when `fast` has
    /// all an evaluation needs).
    topology: Option<Connectivity>,
    /// The boundary tables of a √3 step B built from this level.
    step_b: Option<StepB>,
    /// The flattened tables of a Loop or Catmull-Clark level.
    fast: Option<Fast>,
}

/// A level as the evaluation reads it: borrowed from a [`Level`] the refinement keeps, or
/// from the half-edge mesh of the level the one-shot subdivision holds.
#[derive(Clone, Copy)]
struct LevelRef<'a> {
    topology: Option<Topo<'a>>,
    step_b: Option<&'a StepB>,
    fast: Option<&'a Fast>,
}

/// The level [`Refinement::next_level`] built.
enum Next {
    /// Its connectivity, and the positions it was given back.
    Topology(Connectivity, Option<Vec<glam::DVec3>>),
    /// Built face by face with its positions.
    Mesh(HalfEdgeMesh),
}

/// The faces of the last level, when they are kept as a list (rules whose last level is
/// built as a half-edge mesh, and `levels = 0`).
#[derive(Debug)]
struct Polygons {
    offsets: Vec<u32>,
    indices: Vec<u32>,
}

/// The topology of a subdivision, refined once, that refines any per-vertex data into the
/// caller's buffers ([module docs](self)).
///
/// # Memory
///
/// A refinement keeps, for each level `0..levels` (each level is evaluated from the one
/// before), either its connectivity (4 bytes per vertex, 32 per edge: two half-edges of
/// target, face, next and prev, and 4 per face) or, for Loop and Catmull-Clark, its flattened
/// tables: Loop 24 bytes per edge (an edge stencil of 16 and the vertex rings, 8 per edge)
/// and 5 per vertex; Catmull-Clark 32 per edge (edge stencils and rings of (neighbour, face)
/// pairs), 4 per face corner and per face, 5 per vertex, and 4 per base face (its degree, for
/// [`Refinement::base_faces`]). Level `levels - 1` keeps its
/// connectivity too: the last level, the largest, is not built as a half-edge mesh for the
/// 4:1 rules and Catmull-Clark, its index buffers are written from level `levels - 1`. For
/// the other rules (1:N² with `N >= 3`, √3, Doo-Sabin, mid-edge) the last level is built
/// and its face list kept (4 bytes per face corner and per face). A √3 refinement on a mesh
/// with boundary keeps 8 bytes per face of its trisecting levels. [`Refinement::heap_bytes`]
/// is the total. [`Refinement::evaluate`] allocates the intermediate levels' data
/// (`n_vertices(s)` entries for `s < levels`, two buffers in all) on every call; an
/// [`Evaluator`] keeps them between calls.
///
/// Under crease rules ([`sdc`](super::sdc)) each Loop or Catmull-Clark level keeps its
/// flattened tables and a sparse weight table of the child vertices whose crease mask is not
/// the rule's (the children of sharp vertices, of vertices on sharp edges other than plain
/// boundary and dart vertices, of interior sharp edges, of the edges of triangles under
/// Catmark's smooth-triangle rule): 12 bytes per weight and 8 per row; a level refined
/// linearly (a face-varying channel under `all`) keeps only its edges' ends (8 bytes per
/// edge) and, for Catmull-Clark, its face corners. A level where those rows are more than half
/// the child vertices, or would exceed the bound below, keeps instead one dense weight table
/// of every child vertex (12 bytes per weight, Loop about 5 per child vertex, Catmull-Clark
/// about 6 on quads, its face points expanded into their corners, and 4 per child vertex).
/// [`Refinement::predicted_bytes`] does not count the weight tables,
/// [`Refinement::predicted_bytes_with_creases`] bounds every case by the dense tables.
///
/// With UVs ([`SubdivideOptions::uvs`]) the refinement also keeps the UV layout's own
/// refinement ([`face_varying`]): the bytes above for a mesh whose vertices are the layout's
/// values (the surface's vertices plus one per extra value along seams), and 8 bytes per
/// extra run of a value, 4 per vertex of the last level when runs are merged, 4 per written
/// corner with holes; under Doo-Sabin and mid-edge instead the corner channel's weight table
/// per level (4 bytes per value, 12 per weight) and 4 bytes per corner of the last level.
/// [`Refinement::heap_bytes`] counts them, [`Refinement::predicted_bytes`] does not.
///
/// For Loop at 3 levels on the 81,920-face icosphere the refinement holds 137 MB (a
/// half-edge mesh of the 5.2 M output triangles alone would take 250 MB), for Catmull-Clark
/// 185 MB.
pub struct Refinement {
    rule: Rule,
    name: String,
    split: Split,
    levels: u32,
    threads: usize,
    pool: Option<Arc<rayon::ThreadPool>>,
    template: Option<Template>,
    /// Levels `0..levels` (level 0 alone when `levels = 0`).
    topology: Vec<Level>,
    /// Sizes of levels `0..=levels`.
    sizes: Vec<LevelSize>,
    /// The last level's face list, when it is kept.
    polygons: Option<Polygons>,
    face_degree: Option<usize>,
    /// The crease rules, when sharpness or options call for them (`None`: the rules' kernels).
    creases: Option<Creases>,
    /// With holes ([`SubdivideOptions::holes`]): the written part of the last level.
    written: Option<Written>,
    /// With a UV layout ([`SubdivideOptions::uvs`]): its face-varying channel.
    uvs: Option<Box<face_varying::UvChannel>>,
    /// The base faces' degrees under Catmull-Clark (the children of the first level), for
    /// [`Refinement::base_faces`]; empty under the other rules.
    base_degrees: Vec<u32>,
    /// With [`SubdivideOptions::limit`]: the last level's limit masks, and the walk that
    /// builds them while the levels are refined.
    limit: Option<limit::LimitTable>,
    limit_walk: Option<limit::LimitWalk>,
}

/// The written part of the last level of a refinement with holes: its face list is
/// [`Refinement::polygons`] and its sizes the last of [`Refinement::sizes`]; the whole level
/// is evaluated and its written vertices gathered.
#[derive(Debug)]
struct Written {
    /// The index in the whole last level of each written vertex (ascending).
    kept: Vec<u32>,
    /// The sizes of the whole last level.
    full: LevelSize,
    /// Whether each base face is a hole.
    holes: Vec<bool>,
}

impl std::fmt::Debug for Refinement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Refinement")
            .field("rule", &self.rule)
            .field("levels", &self.levels)
            .field("threads", &self.threads)
            .field("sizes", &self.sizes)
            .field("face_degree", &self.face_degree)
            .finish_non_exhaustive()
    }
}

/// Whether the last level of `split` is written from the level before (no half-edge mesh).
fn direct(split: Split) -> bool {
    matches!(split, Split::Tri(2) | Split::Quad)
}

/// The half-edge sizes of levels `1..levels` (and of the last level when it is built as a
/// half-edge mesh), and the index sizes of the last level otherwise: what
/// [`Refinement::new`] checks before it allocates. Entry `s - 1` is level `s`; the last one
/// is `None` when the last level is written from the one before (`last_built` false: for
/// [`Refinement::new`] the rules of [`direct`], for the one-shot face list too).
fn plan_sizes(
    plan: &Plan,
    counts: &MeshCounts,
    levels: u32,
    last_built: bool,
) -> Result<Vec<(Option<Sizes>, [usize; 3])>> {
    // Capped: a level count beyond 64 is refused by the size check long before.
    let mut out = Vec::with_capacity(levels.min(64) as usize);
    for s in 1..=levels {
        let c = plan.scheme.counts_at(counts, u64::from(s))?;
        let built = s < levels || last_built;
        let sizes = super::sizes(&c, &plan.name, s, built)?;
        let vef = [sizes.vertices, sizes.halfedges / 2, sizes.faces];
        out.push((built.then_some(sizes), vef));
    }
    Ok(out)
}

/// An upper bound of the bytes of the crease weight table that refines level `level` of
/// `plan` on a mesh with `counts` ([`sdc::table_bytes_bound`](super::sdc)), `None` for the
/// rules without crease rules: each term of [`Refinement::predicted_bytes_with_creases`] and
/// of [`Refinement::one_shot_crease_bytes`].
fn crease_table_bytes(
    plan: &Plan,
    counts: &MeshCounts,
    level: u32,
) -> Result<Option<num_bigint::BigInt>> {
    table_bytes(plan, counts, level, false)
}

/// [`crease_table_bytes`], with `dense_only_narrow` as [`super::sdc::table_bytes_bound`]'s.
fn table_bytes(
    plan: &Plan,
    counts: &MeshCounts,
    level: u32,
    dense_only_narrow: bool,
) -> Result<Option<num_bigint::BigInt>> {
    let Some(scheme) = super::sdc::masks::Scheme::of(plan.rule) else {
        return Ok(None);
    };
    let c = plan.scheme.counts_at(counts, u64::from(level))?;
    Ok(Some(self::creases::table_bytes_bound(
        scheme,
        counts,
        level,
        &c,
        dense_only_narrow,
    )))
}

/// The number of face corners of `t` (the half-edges with a face).
fn corners_of(t: &Topo<'_>) -> usize {
    2 * t.ne() - t.boundary_edges()
}

/// The face list of `t` as `to_polygon_mesh` numbers it (each face from its half-edge's
/// source).
fn polygons_of(t: &Topo<'_>) -> Result<Polygons> {
    let nf = t.nf();
    let mut offsets = super::alloc::with_capacity(nf + 1, "face offsets")?;
    let mut indices = super::alloc::with_capacity(corners_of(t), "face corners")?;
    offsets.push(0u32);
    for f in 0..nf as u32 {
        t.for_face(f, |h| indices.push(t.source(h)));
        let n = u32::try_from(indices.len()).map_err(|_| Error::IndexOverflow {
            what: "face corners",
            count: indices.len() as u128,
        })?;
        offsets.push(n);
    }
    Ok(Polygons { offsets, indices })
}

/// The common degree of the faces, if any.
fn common_degree(p: &Polygons) -> Option<usize> {
    let mut degrees = p.offsets.windows(2).map(|w| (w[1] - w[0]) as usize);
    let first = degrees.next()?;
    degrees.all(|d| d == first).then_some(first)
}

impl Refinement {
    /// Refines the topology of `mesh` `levels` times by `rule`: every level's size is known
    /// from the exact counts of the rule's scheme ([`Rule::scheme_for`]) and checked before
    /// anything is allocated; then levels `1..levels` are built (connectivity only, no
    /// positions), and the last one as a face list for the rules that need it. `opts.threads`
    /// sets the threads of the building and of every later evaluation (1: the calling thread,
    /// 0: rayon's global pool, `n`: a pool of `n` threads kept by the refinement);
    /// `opts.progress` is called after each level; `opts.preallocate` is ignored (always on).
    ///
    /// The last level is bounded by its indices, not by half-edge handles: for the 4:1 rules
    /// and Catmull-Clark it may have up to `u32::MAX - 1` vertices however many edges, faces
    /// and corners it has (3holes.obj at Loop level 9 has 2,831,155,200 edges). Levels built
    /// as half-edge meshes must fit 32-bit half-edge handles.
    ///
    /// # Errors
    ///
    /// As [`subdivide`](super::subdivide): [`Error::Scheme`] for a mesh outside the rule's
    /// class, [`Error::SchemeNotApplicable`], [`Error::TooLarge`] for a level that does not fit
    /// (its half-edge handles, or the last level's vertex indices), [`Error::ThreadPool`],
    /// [`Error::AllocationFailed`], [`Error::PredictionMismatch`] (a bug);
    /// [`Error::CreasesNotSupported`] when `opts.sharpness` or `opts.subdivision` call for
    /// crease rules under a rule other than Loop and Catmull-Clark,
    /// [`Error::SharpnessMismatch`] for a sharpness resolved on another mesh.
    ///
    /// With creases ([`SubdivideOptions::sharpness`], [`SubdivideOptions::subdivision`]:
    /// [`sdc`](super::sdc)) Loop and Catmull-Clark levels follow OpenSubdiv's crease rules.
    ///
    /// With holes ([`SubdivideOptions::holes`], rules whose faces nest, else
    /// [`Error::HolesNeedNestedFaces`]) every level is refined whole, but the last level's
    /// buffers hold only what is written: its faces not descending from holes and the
    /// vertices they use, in order; their sizes are predicted (and checked to fit) before
    /// anything is built, the written vertices and faces checked afterwards. The refinement
    /// also keeps 4 bytes per written vertex and 1 per base face; [`Refinement::predicted_bytes`]
    /// does not count them.
    pub fn new(
        mesh: &HalfEdgeMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
    ) -> Result<Refinement> {
        let opts = &opts.over_descriptor(mesh, Some(rule))?;
        // Refused before any topology is built.
        if opts.uvs.is_some() {
            face_varying::channel_kind(rule)?;
        }
        let creases = || Creases::new(mesh, rule, opts.sharpness, &opts.subdivision);
        let mut refinement = Refinement::with_creases(mesh, rule, levels, opts, creases, None)?;
        if let Some(layout) = opts.uvs {
            refinement.uvs = Some(Box::new(face_varying::UvChannel::new(
                mesh,
                layout,
                rule,
                levels,
                opts,
                &refinement,
            )?));
        }
        Ok(refinement)
    }

    /// [`Refinement::new`] with the crease rules given (a face-varying channel's own), and
    /// no UVs; `seams` marks the edges of a face-varying channel along its seams, for its
    /// limit (`limit::LimitWalk::new`).
    fn with_creases(
        mesh: &HalfEdgeMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
        creases: impl FnOnce() -> Result<Option<Creases>>,
        seams: Option<Vec<bool>>,
    ) -> Result<Refinement> {
        let counts = mesh.counts();
        let plan = super::plan(rule, &counts)?;
        plan.scheme.initial_state(&counts)?;
        super::check_mesh(&plan, mesh)?;
        let creases = creases()?;
        // The limit needs the last level's topology: built even where its faces could be
        // written from the level before.
        let limit = opts.limit.then(|| limit::scheme_of(rule)).transpose()?;
        let planned = plan_sizes(
            &plan,
            &counts,
            levels,
            !direct(plan.split) || limit.is_some(),
        )?;
        // With holes, what is written is known (and checked to fit) before anything is built.
        let holes = crate::holes::active(opts.holes, rule, mesh.n_faces())?;
        let written = match holes {
            Some(holes) => Some(super::written_prediction(
                &plan,
                &holes.written_mesh_counts(mesh),
                levels,
            )?),
            None => None,
        };
        let pool = match opts.threads {
            0 | 1 => None,
            n => Some(Arc::new(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .map_err(|e| Error::ThreadPool {
                        threads: n,
                        reason: e.to_string(),
                    })?,
            )),
        };
        let mut refinement =
            Refinement::empty(&plan, &counts, levels, opts.threads, pool, creases)?;
        let base = Topo::new(mesh);
        if plan.split == Split::Quad && levels > 0 {
            // At most the mesh's face corners, which fit u32.
            refinement.base_degrees = (0..base.nf() as u32)
                .map(|f| base.face_degree(f) as u32)
                .collect();
        }
        refinement.sizes.push(LevelSize {
            vertices: base.nv(),
            edges: base.ne(),
            faces: base.nf(),
            corners: corners_of(&base),
        });
        refinement.topology.push(Level {
            topology: Some(Connectivity::of_mesh(mesh)),
            step_b: None,
            fast: None,
        });
        if let Some(scheme) = limit {
            let creases = refinement.creases.as_ref();
            let walk = limit::LimitWalk::new(&base, scheme, creases, levels, seams)?;
            refinement.limit_walk = Some(walk);
        }
        let run = |r: &mut Refinement| {
            r.refine_levels(mesh, &planned, opts, Retain::All, &mut |_, _| Ok(()))
        };
        refinement.install(run)?;
        refinement.limit = refinement
            .limit_walk
            .take()
            .and_then(limit::LimitWalk::into_table);
        if let (Some(holes), Some(predicted)) = (holes, written) {
            refinement.keep_written(mesh, holes, &predicted)?;
        }
        Ok(refinement)
    }

    /// A refinement of `plan` to `levels` on a mesh with `counts` that holds no level yet,
    /// under `creases` (their per-level table budgets set): what [`Refinement::refine_levels`]
    /// fills.
    fn empty(
        plan: &Plan,
        counts: &MeshCounts,
        levels: u32,
        threads: usize,
        pool: Option<Arc<rayon::ThreadPool>>,
        mut creases: Option<Creases>,
    ) -> Result<Refinement> {
        if let Some(creases) = creases.as_mut() {
            // Each level's tables are bounded (the same choices for every retention).
            creases.set_budgets(crease_budgets(plan, counts, levels)?);
        }
        let template = match plan.split {
            Split::Tri(n) => Some(Template::new(n)),
            _ => None,
        };
        Ok(Refinement {
            rule: plan.rule,
            name: plan.name.clone(),
            split: plan.split,
            levels,
            threads,
            pool,
            template,
            topology: Vec::with_capacity(levels.clamp(1, 64) as usize),
            sizes: Vec::with_capacity(levels.min(64) as usize + 1),
            polygons: None,
            face_degree: None,
            creases,
            written: None,
            uvs: None,
            base_degrees: Vec::new(),
            limit: None,
            limit_walk: None,
        })
    }

    /// Replaces the last level's face list and sizes by its written part (holes and their
    /// descendants dropped, with the vertices only they use; the others renumbered in order),
    /// checked against the prediction.
    fn keep_written(
        &mut self,
        mesh: &HalfEdgeMesh,
        holes: &crate::holes::HoleSet,
        predicted: &schemes::LevelCounts,
    ) -> Result<()> {
        let levels = self.levels;
        let Some(&full) = self.sizes.last() else {
            return Ok(());
        };
        let mask = holes.written_at(self.rule, &crate::holes::degrees_of(mesh), levels)?;
        if mask.len() != full.faces {
            return Err(Error::InvalidOutput {
                scheme: self.name.clone(),
                level: levels,
                what: format!(
                    "{} faces where the holes' descendants were counted on {}",
                    full.faces,
                    mask.len()
                ),
            });
        }
        let mut polygons = match self.polygons.take() {
            Some(p) => p,
            None => {
                // A direct rule: the whole level's corners, written from level `levels - 1`.
                if u32::try_from(full.corners).is_err() {
                    return Err(Error::IndexOverflow {
                        what: "face corners",
                        count: full.corners as u128,
                    });
                }
                let degree = self.face_degree.unwrap_or(0);
                let mut indices = super::alloc::filled(0u32, full.corners, "face corners")?;
                self.write_corners(&mut indices)?;
                let mut offsets = super::alloc::with_capacity(full.faces + 1, "face offsets")?;
                // At most `full.corners`, which fits u32.
                offsets.extend((0..=full.faces).map(|f| (degree * f) as u32));
                Polygons { offsets, indices }
            }
        };
        let kept = crate::holes::compact_faces(
            &mut polygons.offsets,
            &mut polygons.indices,
            full.vertices,
            &mask,
        )?;
        polygons.offsets.shrink_to_fit();
        polygons.indices.shrink_to_fit();
        let faces = polygons.offsets.len() - 1;
        crate::holes::check_written(&self.name, levels, predicted, kept.len(), faces)?;
        let edges = usize::try_from(&predicted.edges).map_err(|_| Error::TooLarge {
            scheme: self.name.clone(),
            level: levels,
            what: "edges",
            count: predicted.edges.clone(),
        })?;
        if let Some(last) = self.sizes.last_mut() {
            *last = LevelSize {
                vertices: kept.len(),
                edges,
                faces,
                corners: polygons.indices.len(),
            };
        }
        self.face_degree = common_degree(&polygons).or(self.face_degree.filter(|_| faces == 0));
        self.polygons = Some(polygons);
        let holes = (0..mesh.n_faces() as u32)
            .map(|f| holes.contains(f))
            .collect();
        self.written = Some(Written { kept, full, holes });
        Ok(())
    }

    /// The vertices of the base level (with holes at `levels = 0`, more than the written
    /// [`Refinement::n_vertices`]`(0)`).
    fn base_vertices(&self) -> usize {
        match &self.written {
            Some(w) if self.levels == 0 => w.full.vertices,
            _ => self.n_vertices(0),
        }
    }

    /// The vertices the evaluation of `level` computes: the whole last level with holes.
    fn computed_vertices(&self, level: u32) -> usize {
        match &self.written {
            Some(w) if level == self.levels => w.full.vertices,
            _ => self.n_vertices(level),
        }
    }

    /// `dst[i] = full[kept[i]]`: the written vertices of the last level, when there are
    /// holes (`dst` is then `n_vertices(levels)` long).
    fn gather<V: Clone>(&self, full: &[V], dst: &mut [V]) {
        if let Some(w) = &self.written {
            for (d, &old) in dst.iter_mut().zip(&w.kept) {
                *d = full[old as usize].clone();
            }
        }
    }

    /// The written entries of the last level's `full` values (all of them without holes).
    fn written_of<V: Clone>(&self, mut full: Vec<V>) -> Vec<V> {
        if let Some(w) = &self.written {
            crate::holes::compact_values(&mut full, &w.kept);
        }
        full
    }

    /// The rule.
    pub fn rule(&self) -> Rule {
        self.rule
    }

    /// The number of levels.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    fn size(&self, level: u32) -> Option<&LevelSize> {
        self.sizes.get(level as usize)
    }

    /// The vertices of level `level` (`0..=levels`; 0 beyond the last level). With holes
    /// ([`SubdivideOptions::holes`]) the last level's are the written ones (what
    /// [`Refinement::evaluate`] fills), known before the refinement was built.
    pub fn n_vertices(&self, level: u32) -> usize {
        self.size(level).map_or(0, |s| s.vertices)
    }

    /// The faces of level `level` (`0..=levels`; 0 beyond the last level); with holes, the
    /// last level's written faces (what the index buffers hold).
    pub fn n_faces(&self, level: u32) -> usize {
        self.size(level).map_or(0, |s| s.faces)
    }

    /// The edges of level `level` (`0..=levels`; 0 beyond the last level); with holes, the
    /// last level's written edges as predicted (its vertices and faces are checked).
    pub fn n_edges(&self, level: u32) -> usize {
        self.size(level).map_or(0, |s| s.edges)
    }

    /// The face corners of level `level` (the sum of its face degrees; `0..=levels`, 0 beyond
    /// the last level).
    pub fn n_corners(&self, level: u32) -> usize {
        self.size(level).map_or(0, |s| s.corners)
    }

    /// `Some(d)` when every face of the last level has `d` vertices (3 for the triangle
    /// rules, 4 for Catmull-Clark from level 1 on).
    pub fn face_degree(&self) -> Option<usize> {
        self.face_degree
    }
}

/// `Ok` when a buffer has the length it must have.
fn check_len(what: &'static str, expected: usize, given: usize) -> Result<()> {
    if expected != given {
        return Err(Error::BufferSize {
            what,
            expected,
            given,
        });
    }
    Ok(())
}

// A refinement is shared between threads (evaluations of several data in parallel).
const _: () = {
    const fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<Refinement>();
};

#[cfg(test)]
mod tests {
    use super::*;

    /// A 60 x 60 torus of triangles: the counts of 3holes.obj under Loop (7,200 faces, 10,800
    /// edges; the genus does not change E or F).
    fn torus_counts() -> MeshCounts {
        let n = 60u32;
        let id = |i: u32, j: u32| (i % n) * n + (j % n);
        let mut faces = Vec::new();
        for i in 0..n {
            for j in 0..n {
                faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        MeshCounts::from_polygons(&faces).expect("a valid torus")
    }

    #[test]
    fn the_last_level_is_bounded_by_its_indices_not_by_half_edges() {
        let counts = torus_counts();
        assert_eq!((counts.faces, counts.edges), (7200, 10800));
        let plan = super::super::plan(Rule::Loop, &counts).expect("plan");
        // Level 9: 2,831,155,200 edges (5.7e9 half-edges) but 943,718,400 vertices.
        let sizes = plan_sizes(&plan, &counts, 9, false).expect("level 9 fits u32 indices");
        let (last, [vertices, edges, faces]) = sizes[8];
        assert!(last.is_none());
        assert_eq!(
            (vertices, edges, faces),
            (943_718_400, 2_831_155_200, 1_887_436_800)
        );
        assert!(sizes[7].0.is_some(), "level 8 is built as a half-edge mesh");
        // Level 10 builds level 9 as a half-edge mesh: refused, naming its edges.
        let err = plan_sizes(&plan, &counts, 10, false).unwrap_err();
        assert!(
            matches!(
                err,
                Error::TooLarge {
                    level: 9,
                    what: "edges",
                    ..
                }
            ),
            "{err}"
        );
        // A rule whose last level is a half-edge mesh is bounded by its handles.
        let plan = super::super::plan(Rule::Sqrt3, &counts).expect("plan");
        assert!(plan_sizes(&plan, &counts, 11, true).is_ok());
        assert!(plan_sizes(&plan, &counts, 12, true).is_err());
    }
}
