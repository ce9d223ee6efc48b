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
//! # Same results as the one-shot subdivision
//!
//! The one-shot subdivision is a refinement: [`subdivide`](super::subdivide),
//! [`subdivide_to_face_list`](super::subdivide_to_face_list) and
//! [`verify`](super::verify) run a private streaming mode of [`Refinement`] that checks the
//! same sizes, builds each level by the same topology step, computes its positions by the
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
//! the positions the refinement computed); the last level's index buffers are written from level
//! `L - 1` for the 4:1 family and Catmull-Clark (bounded by `u32` vertex indices, not half-edge
//! handles), from a kept face list for the other rules. Loop and Catmull-Clark levels are
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

pub(crate) mod corners;
pub mod face_varying;
mod oneshot;
mod stencil;
mod tables;

use std::sync::Arc;

use schemes::MeshCounts;

pub(crate) use self::oneshot::{one_shot, OneShot};
pub use self::stencil::{StencilSizes, StencilTable};
pub use super::data::Scalar;
pub(crate) use super::data::{Sparse, Support, Vector};

use self::tables::{CcTables, LinearTables, LoopTables};
use super::build::{Sizes, StepContext};
use super::par::Slots;
use super::sdc::{Base, Creases, LevelTable, WeightTable};
use super::sqrt3::StepB;
use super::topo::{Connectivity, Topo};
use super::trisplit::{Template, TriRule};
use super::{Algorithm, LevelDone, Plan, Rule, SubdivideOptions};
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

/// A level flattened for its rule.
#[derive(Debug)]
enum Fast {
    Loop(LoopTables),
    CatmullClark(CcTables),
    /// A face-varying channel's level under linear interpolation (`all`).
    Linear(LinearTables),
    /// A Loop or Catmull-Clark level under crease rules: sparse weights per child vertex,
    /// of every child vertex (a dense table, `base` unused) or of the child vertices where the
    /// crease rules differ from `base` (the rule's tables, or its half-edge kernels on the
    /// level's topology when `None`), written over its values.
    Creased {
        base: Option<Box<Fast>>,
        weights: WeightTable,
    },
}

impl Fast {
    fn bytes(&self) -> usize {
        match self {
            Fast::Loop(t) => t.bytes(),
            Fast::CatmullClark(t) => t.bytes(),
            Fast::Linear(t) => t.bytes(),
            Fast::Creased { base, weights } => {
                base.as_ref().map_or(0, |b| b.bytes()) + weights.bytes()
            }
        }
    }

    /// The flattened tables of `t` for `algorithm` (Loop or Catmull-Clark).
    fn tables(algorithm: Algorithm, t: &Topo<'_>, parallel: bool) -> Result<Fast> {
        Ok(match algorithm {
            Algorithm::CatmullClark => Fast::CatmullClark(CcTables::new(t, parallel)?),
            _ => Fast::Loop(LoopTables::new(t, parallel)?),
        })
    }

    /// The tables computing the child vertices of `t` outside a crease table's rows: the
    /// rule's (`None` with `tables` false: the half-edge kernels), or the linear ones.
    fn base(
        base: Base,
        algorithm: Algorithm,
        t: &Topo<'_>,
        tables: bool,
        parallel: bool,
    ) -> Result<Option<Box<Fast>>> {
        let cc = algorithm == Algorithm::CatmullClark;
        Ok(match base {
            Base::Linear => Some(Box::new(Fast::Linear(LinearTables::new(t, cc, parallel)?))),
            Base::Rule if tables => Some(Box::new(Fast::tables(algorithm, t, parallel)?)),
            Base::Rule => None,
        })
    }

    /// The bytes of the tables a [`Refinement`] keeps under the rows of a sparse crease table
    /// of `t` ([`Fast::base`] with tables).
    fn base_bytes(base: Base, algorithm: Algorithm, t: &Topo<'_>) -> usize {
        let cc = algorithm == Algorithm::CatmullClark;
        match base {
            Base::Linear => LinearTables::bytes_of(t, cc),
            Base::Rule if cc => CcTables::bytes_of(t),
            Base::Rule => LoopTables::bytes_of(t),
        }
    }

    /// What refines level `level` (`t`) under `creases`: the rows where the crease rules differ
    /// from the level's base over its tables (`tables`, a refinement's) or its half-edge kernels
    /// (the one-shot subdivision's), when they are at most half the child vertices and hold,
    /// with the tables a refinement keeps, no more than the level's budget (the bound of the
    /// dense table); else the dense table. The level's sharpness is kept.
    fn creased(
        creases: &Creases,
        level: usize,
        t: &Topo<'_>,
        algorithm: Algorithm,
        tables: bool,
        parallel: bool,
    ) -> Result<Option<Fast>> {
        // A dense table of a level with a wide face would be quadratic in its degree.
        let wide = super::sdc::has_wide_face(t);
        let sparse = |rows: usize, children: usize| wide || 2 * rows <= children;
        let dense = |weights| Fast::Creased {
            base: None,
            weights,
        };
        Ok(match creases.level_table(level, t, parallel, sparse)? {
            None => None,
            Some(LevelTable::Dense(weights)) => Some(dense(weights)),
            Some(LevelTable::Overrides(base, weights)) => {
                // A refinement's tables are built and measured, the one-shot subdivision's
                // (which keeps none) counted.
                let tables = if tables {
                    Some(Fast::base(base, algorithm, t, true, parallel)?)
                } else {
                    None
                };
                let base_bytes = match &tables {
                    Some(b) => b.as_ref().map_or(0, |b| b.bytes()),
                    None => Fast::base_bytes(base, algorithm, t),
                };
                debug_assert_eq!(base_bytes, Fast::base_bytes(base, algorithm, t));
                if wide || base_bytes + weights.bytes() <= creases.budget(level) {
                    let base = match tables {
                        Some(b) => b,
                        None => Fast::base(base, algorithm, t, false, parallel)?,
                    };
                    Some(Fast::Creased { base, weights })
                } else {
                    drop(tables);
                    drop(weights);
                    match creases.level_table(level, t, parallel, |_, _| false)? {
                        Some(LevelTable::Dense(weights) | LevelTable::Overrides(_, weights)) => {
                            Some(dense(weights))
                        }
                        None => None,
                    }
                }
            }
        })
    }
}

/// The budget of each level's tables under crease rules (`levels` of `plan` on a mesh with
/// `counts`): the bound of its dense weight table, what
/// [`Refinement::predicted_bytes_with_creases`] counts for it.
fn crease_budgets(plan: &Plan, counts: &MeshCounts, levels: u32) -> Result<Vec<usize>> {
    let mut budgets = Vec::with_capacity(levels.min(64) as usize);
    for s in 0..levels {
        let bound = crease_table_bytes(plan, counts, s)?.unwrap_or_default();
        budgets.push(usize::try_from(bound).unwrap_or(usize::MAX));
    }
    Ok(budgets)
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
/// pairs), 4 per face corner and per face, 5 per vertex. Level `levels - 1` keeps its
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
    algorithm: Algorithm,
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

/// Whether the last level of `algorithm` is written from the level before (no half-edge mesh).
fn direct(algorithm: Algorithm) -> bool {
    matches!(algorithm, Algorithm::Tri(_, 2) | Algorithm::CatmullClark)
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
    let scheme = match plan.algorithm {
        Algorithm::Tri(TriRule::Loop, 2) => super::sdc::TableScheme::Loop,
        Algorithm::CatmullClark => super::sdc::TableScheme::CatmullClark,
        _ => return Ok(None),
    };
    let c = plan.scheme.counts_at(counts, u64::from(level))?;
    Ok(Some(super::sdc::table_bytes_bound(
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
    /// also keeps 4 bytes per written vertex; [`Refinement::predicted_bytes`] does not count
    /// them.
    pub fn new(
        mesh: &HalfEdgeMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
    ) -> Result<Refinement> {
        // Refused before any topology is built.
        if opts.uvs.is_some() {
            face_varying::channel_kind(rule)?;
        }
        let creases = || Creases::new(mesh, rule, opts.sharpness, &opts.subdivision);
        let mut refinement = Refinement::with_creases(mesh, rule, levels, opts, creases)?;
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
    /// no UVs.
    fn with_creases(
        mesh: &HalfEdgeMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
        creases: impl FnOnce() -> Result<Option<Creases>>,
    ) -> Result<Refinement> {
        let counts = mesh.counts();
        let plan = super::plan(rule, &counts)?;
        plan.scheme.initial_state(&counts)?;
        super::check_mesh(&plan, mesh)?;
        let mut creases = creases()?;
        if let Some(creases) = creases.as_mut() {
            creases.set_budgets(crease_budgets(&plan, &counts, levels)?);
        }
        let planned = plan_sizes(&plan, &counts, levels, !direct(plan.algorithm))?;
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
        let template = match plan.algorithm {
            Algorithm::Tri(_, n) => Some(Template::new(n)),
            _ => None,
        };
        let mut refinement = Refinement {
            rule,
            name: plan.name.clone(),
            algorithm: plan.algorithm,
            levels,
            threads: opts.threads,
            pool,
            template,
            topology: Vec::with_capacity(levels.clamp(1, 64) as usize),
            sizes: Vec::with_capacity(levels as usize + 1),
            polygons: None,
            face_degree: None,
            creases,
            written: None,
            uvs: None,
        };
        let base = Topo::new(mesh);
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
        refinement.install(|r| r.build(&planned, opts))?;
        if let (Some(holes), Some(predicted)) = (holes, written) {
            refinement.keep_written(mesh, holes, &predicted)?;
        }
        Ok(refinement)
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
        self.written = Some(Written { kept, full });
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

    /// Builds levels `1..=levels` (the topology `new` keeps).
    fn build(
        &mut self,
        planned: &[(Option<Sizes>, [usize; 3])],
        opts: &SubdivideOptions<'_>,
    ) -> Result<()> {
        let levels = self.levels;
        let parallel = self.threads != 1;
        let report = |level: u32, size: &LevelSize| {
            if let Some(progress) = opts.progress {
                progress(&LevelDone {
                    level,
                    levels,
                    vertices: size.vertices,
                    edges: size.edges,
                    faces: size.faces,
                });
            }
        };
        for (s, &(sizes, [vertices, edges, faces])) in (1..=levels).zip(planned) {
            let before = self.topology.last().and_then(|l| l.topology.as_ref());
            let Some(before) = before else {
                return Err(Error::InvalidOutput {
                    scheme: self.name.clone(),
                    level: s,
                    what: "no level to refine".into(),
                });
            };
            let t = before.topo();
            let step_b = self.step_b(&t, s, sizes, parallel)?;
            let Some(expected) = sizes else {
                // The last level of a direct rule: its faces are written from level s - 1.
                let corners = match self.algorithm {
                    Algorithm::CatmullClark => 4 * faces,
                    _ => 3 * faces,
                };
                let size = LevelSize {
                    vertices,
                    edges,
                    faces,
                    corners,
                };
                self.face_degree = Some(corners / faces.max(1));
                if let Some(last) = self.topology.last_mut() {
                    last.step_b = step_b;
                }
                report(s, &size);
                self.sizes.push(size);
                break;
            };
            let ctx = self.context(s, expected, parallel);
            let next = self.step(&t, &ctx)?;
            let nt = next.topo();
            if let (Some(creases), true) = (self.creases.as_mut(), s < levels) {
                creases.push_child(s as usize - 1, &t, &nt);
            }
            let size = LevelSize {
                vertices: nt.nv(),
                edges: nt.ne(),
                faces: nt.nf(),
                corners: corners_of(&nt),
            };
            if let Some(last) = self.topology.last_mut() {
                last.step_b = step_b;
            }
            report(s, &size);
            self.sizes.push(size);
            if s == levels {
                let polygons = polygons_of(&nt)?;
                self.face_degree = common_degree(&polygons);
                self.polygons = Some(polygons);
            } else {
                self.topology.push(Level {
                    topology: Some(next),
                    step_b: None,
                    fast: None,
                });
                // Level s - 1 is not needed as connectivity any more (a lower peak).
                self.flatten(s as usize - 1, false, parallel)?;
            }
        }
        if levels == 0 {
            if let Some(base) = &self.topology[0].topology {
                let polygons = polygons_of(&base.topo())?;
                self.face_degree = common_degree(&polygons);
                self.polygons = Some(polygons);
            }
        }
        // Flatten the levels still holding their connectivity (level `levels - 1` keeps it for
        // the index buffers; the others were flattened as soon as the next level was built).
        for i in 0..self.topology.len() {
            self.flatten(i, true, parallel)?;
        }
        Ok(())
    }

    /// Flattens level `i` for the Loop and Catmull-Clark rules (a no-op for the others and
    /// for a level already flattened), dropping its connectivity unless `keep`.
    fn flatten(&mut self, i: usize, keep: bool, parallel: bool) -> Result<()> {
        let algorithm = self.algorithm;
        if self.levels == 0
            || !matches!(
                algorithm,
                Algorithm::Tri(TriRule::Loop, 2) | Algorithm::CatmullClark
            )
        {
            return Ok(());
        }
        let Some(level) = self.topology.get_mut(i) else {
            return Ok(());
        };
        if level.fast.is_none() {
            if let (Some(c), Some(creases)) = (&level.topology, self.creases.as_mut()) {
                let fast = Fast::creased(creases, i, &c.topo(), algorithm, true, parallel)?;
                let fast = fast.ok_or_else(|| Error::InvalidOutput {
                    scheme: self.name.clone(),
                    level: i as u32 + 1,
                    what: "no sharpness for the level refined".into(),
                })?;
                creases.release(i);
                level.fast = Some(fast);
            }
        }
        if level.fast.is_none() {
            if let Some(c) = &level.topology {
                level.fast = Some(Fast::tables(algorithm, &c.topo(), parallel)?);
            }
        }
        if !keep {
            level.topology = None;
        }
        Ok(())
    }

    /// The boundary tables of a √3 step B refining `t` into level `level` (built as a half-edge
    /// mesh with `sizes`), `None` for the other steps.
    fn step_b(
        &self,
        t: &Topo<'_>,
        level: u32,
        sizes: Option<Sizes>,
        parallel: bool,
    ) -> Result<Option<StepB>> {
        match (self.algorithm, sizes) {
            (Algorithm::Sqrt3 { boundary: true }, Some(expected)) if level % 2 == 0 => {
                let ctx = self.context(level, expected, parallel);
                Ok(Some(StepB::new(t, &ctx)?))
            }
            _ => Ok(None),
        }
    }

    fn context(&self, level: u32, expected: Sizes, parallel: bool) -> StepContext<'_> {
        StepContext {
            scheme: &self.name,
            level,
            expected,
            parallel,
        }
    }

    /// The connectivity of the level after `t` (`ctx.level`).
    fn step(&self, t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
        Ok(match self.next_level(t, ctx, false, None)? {
            Next::Topology(c, _) => c,
            Next::Mesh(m) => Connectivity::from_mesh(m),
        })
    }

    /// The level after `t` (`ctx.level`): the topology of every refinement and of the one-shot
    /// subdivision. By index formulas into arrays of the predicted lengths (the 4:1 family,
    /// Catmull-Clark, √3 on closed meshes, Doo-Sabin, mid-edge), else face by face into
    /// index-addressed arrays; with `grow`, always face by face into arrays that grow on
    /// demand. `positions`, the new level's (from [`Refinement::values_after`]), are handed back
    /// with a connectivity or become the mesh's; the face-by-face steps fill zeros without
    /// them.
    fn next_level(
        &self,
        t: &Topo<'_>,
        ctx: &StepContext<'_>,
        grow: bool,
        positions: Option<Vec<glam::DVec3>>,
    ) -> Result<Next> {
        use super::{catmull_clark, dual, gather, sqrt3, trisplit};
        let zeros = |p: Option<Vec<glam::DVec3>>| match p {
            Some(p) => Ok(p),
            None => super::alloc::filled(glam::DVec3::ZERO, ctx.expected.vertices, "positions"),
        };
        if grow {
            let mesh = match (self.algorithm, &self.template) {
                (Algorithm::Tri(_, _), Some(template)) => {
                    trisplit::tri_split_step::<true>(t, positions, template, ctx)?
                }
                (Algorithm::Tri(..), None) => return Err(ctx.invalid("no split template".into())),
                (Algorithm::CatmullClark, _) => {
                    catmull_clark::catmull_clark_step::<true>(t, zeros(positions)?, ctx)?
                }
                (Algorithm::Sqrt3 { boundary }, _) => {
                    let step_b = boundary && ctx.level % 2 == 0;
                    sqrt3::sqrt3_step::<true>(t, positions, step_b, ctx)?
                }
                (Algorithm::DooSabin, _) => {
                    dual::doo_sabin_step::<true>(t, zeros(positions)?, ctx)?
                }
                (Algorithm::MidEdge, _) => dual::mid_edge_step::<true>(t, zeros(positions)?, ctx)?,
            };
            return Ok(Next::Mesh(mesh));
        }
        let topology = match (self.algorithm, &self.template) {
            (Algorithm::Tri(_, 2), _) => gather::four_to_one_topology(t, ctx)?,
            (Algorithm::Tri(_, _), Some(template)) => {
                let mesh = trisplit::tri_split_step::<false>(t, positions, template, ctx)?;
                return Ok(Next::Mesh(mesh));
            }
            (Algorithm::Tri(..), None) => return Err(ctx.invalid("no split template".into())),
            (Algorithm::CatmullClark, _) => gather::catmull_clark_topology(t, ctx)?,
            (Algorithm::Sqrt3 { .. }, _) if t.is_closed() => gather::sqrt3_closed_topology(t, ctx)?,
            (Algorithm::Sqrt3 { boundary }, _) => {
                let step_b = boundary && ctx.level % 2 == 0;
                let mesh = sqrt3::sqrt3_step::<false>(t, positions, step_b, ctx)?;
                return Ok(Next::Mesh(mesh));
            }
            (Algorithm::DooSabin, _) => gather::doo_sabin_topology(t, ctx)?,
            (Algorithm::MidEdge, _) => gather::mid_edge_topology(t, ctx)?,
        };
        Ok(Next::Topology(topology, positions))
    }

    /// Runs `f` in the refinement's pool (or on the calling thread / the global pool).
    fn install<R: Send>(&mut self, f: impl FnOnce(&mut Self) -> Result<R> + Send) -> Result<R> {
        match self.pool.clone() {
            Some(pool) => pool.install(|| f(self)),
            None => f(self),
        }
    }

    /// Runs `f` in the refinement's pool (shared access).
    fn run<R: Send>(&self, f: impl FnOnce() -> R + Send) -> R {
        match &self.pool {
            Some(pool) => pool.install(f),
            None => f(),
        }
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

    /// Whether the refinement refines UVs ([`SubdivideOptions::uvs`]; [`face_varying`]).
    pub fn has_uvs(&self) -> bool {
        self.uvs.is_some()
    }

    /// The UV values of level `level` (`0..=levels`; 0 beyond the last level, and without
    /// UVs): level 0 is the layout's values, the last level's are the values its written
    /// faces use (with holes, fewer than the level has). Known when the refinement is built.
    pub fn n_uvs(&self, level: u32) -> usize {
        self.uvs.as_ref().map_or(0, |u| u.n_uvs(level))
    }

    /// Refines the UV values `base` (one per value of the layout,
    /// [`UvLayout::values`](crate::uv::UvLayout::values)) to the last level, into `out`
    /// (`n_uvs(levels)` entries), by the face-varying rules of [`face_varying`].
    ///
    /// # Errors
    ///
    /// [`Error::NoUvs`] without a layout; [`Error::BufferSize`] (`uv base`, `uv out`);
    /// [`Error::AllocationFailed`].
    pub fn evaluate_uvs<T: Scalar>(&self, base: &[[T; 2]], out: &mut [[T; 2]]) -> Result<()> {
        let uvs = self.uvs.as_ref().ok_or(Error::NoUvs)?;
        self.run(|| uvs.evaluate(base, out))
    }

    /// Writes the UV value of every face corner of the last level (`n_corners(levels)`
    /// entries), face after face in the order of [`Refinement::write_triangles`],
    /// [`write_quads`](Refinement::write_quads) and [`write_polygons`](Refinement::write_polygons)
    /// (with holes, the written faces only): index `i` names entry `i` of
    /// [`Refinement::evaluate_uvs`]' output.
    ///
    /// # Errors
    ///
    /// [`Error::NoUvs`] without a layout; [`Error::BufferSize`] (`uv indices`).
    pub fn write_uv_indices(&self, out: &mut [u32]) -> Result<()> {
        let uvs = self.uvs.as_ref().ok_or(Error::NoUvs)?;
        uvs.write_indices(out, self.n_corners(self.levels))
    }

    /// The bytes the refinement keeps on the heap (see [Memory](Refinement#memory)).
    pub fn heap_bytes(&self) -> usize {
        let levels: usize = self
            .topology
            .iter()
            .map(|l| {
                l.topology.as_ref().map_or(0, Connectivity::bytes)
                    + l.step_b.as_ref().map_or(0, StepB::bytes)
                    + l.fast.as_ref().map_or(0, Fast::bytes)
            })
            .sum();
        let polygons = self
            .polygons
            .as_ref()
            .map_or(0, |p| 4 * (p.offsets.len() + p.indices.len()));
        let written = self.written.as_ref().map_or(0, |w| 4 * w.kept.len());
        let uvs = self.uvs.as_ref().map_or(0, |u| u.heap_bytes());
        levels + polygons + written + uvs
    }

    /// The bytes [`Refinement::new`] would keep for `rule` at `levels` on a mesh with
    /// `counts`, before building anything: exact on closed meshes, an upper bound (within a
    /// few percent) with a boundary, where a boundary vertex's ring holds 2 entries instead of
    /// its valence and boundary half-edges have no face corner.
    ///
    /// ```
    /// use halfedge::refine::Refinement;
    /// use halfedge::subdivide::SubdivideOptions;
    /// use halfedge::{shapes, HalfEdgeMesh, Rule};
    ///
    /// let ico = HalfEdgeMesh::try_from(&shapes::icosahedron())?;
    /// let predicted = Refinement::predicted_bytes(Rule::Loop, &ico.counts(), 4)?;
    /// let r = Refinement::new(&ico, Rule::Loop, 4, &SubdivideOptions::default())?;
    /// assert_eq!(predicted, r.heap_bytes().into());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As the scheme lookup of [`Refinement::new`] ([`Error::Scheme`]).
    pub fn predicted_bytes(
        rule: Rule,
        counts: &MeshCounts,
        levels: u32,
    ) -> Result<num_bigint::BigInt> {
        use num_bigint::BigInt;
        let plan = super::plan(rule, counts)?;
        let mut level = Vec::with_capacity(levels as usize + 1);
        for s in 0..=levels {
            let c = plan.scheme.counts_at(counts, u64::from(s))?;
            let corners = match plan.algorithm {
                _ if s == 0 => BigInt::from(counts.corners),
                Algorithm::Tri(..) | Algorithm::Sqrt3 { .. } => &c.faces * 3u32,
                Algorithm::CatmullClark => &c.faces * 4u32,
                _ => &c.edges * 2u32,
            };
            level.push((c.vertices, c.edges, c.faces, corners));
        }
        let connectivity =
            |(v, e, f, _): &(BigInt, BigInt, BigInt, BigInt)| v * 4u32 + e * 32u32 + f * 4u32;
        let kept = &level[..levels.max(1) as usize];
        let mut bytes = BigInt::from(0u32);
        match plan.algorithm {
            Algorithm::Tri(TriRule::Loop, 2) if levels > 0 => {
                for (v, e, _, _) in kept {
                    bytes += e * 24u32 + v * 5u32 + 4u32;
                }
                bytes += connectivity(&level[levels as usize - 1]);
            }
            Algorithm::CatmullClark if levels > 0 => {
                for (v, e, f, h) in kept {
                    bytes += e * 32u32 + v * 5u32 + f * 4u32 + h * 4u32 + 8u32;
                }
                bytes += connectivity(&level[levels as usize - 1]);
            }
            algorithm => {
                for l in kept {
                    bytes += connectivity(l);
                }
                if levels == 0 || !direct(algorithm) {
                    let (_, _, f, h) = &level[levels as usize];
                    bytes += f * 4u32 + h * 4u32 + 4u32;
                }
                if algorithm == (Algorithm::Sqrt3 { boundary: true }) {
                    for (s, (_, _, f, _)) in kept.iter().enumerate() {
                        // Level s is refined by step B when s + 1 is even.
                        if (s + 1) % 2 == 0 {
                            bytes += f * 12u32;
                        }
                    }
                }
            }
        }
        Ok(bytes)
    }

    /// An upper bound of the bytes [`Refinement::new`] keeps for `rule` (Loop or
    /// Catmull-Clark) at `levels` under crease rules ([`sdc`](super::sdc)): as
    /// [`Refinement::predicted_bytes`], with each level's tables bounded by a dense weight
    /// table of full smooth rows (a vertex's distinct neighbours through its faces, an edge's
    /// two faces' corners; a face of more than 32 sides, which an overriding row names by its
    /// child point, counting 4 entries per side rather than its degree: linear in it); within about 15 % of a level whose every row is semi-sharp and
    /// blended with its smooth mask, on quad and triangle meshes. A level whose rows mostly
    /// keep the rule's masks (a few creases, a UV channel's seams) keeps the flattened tables
    /// and its sharp rows ([Memory](Refinement#memory)), far below: about
    /// [`Refinement::predicted_bytes`]. Other rules: as [`Refinement::predicted_bytes`].
    ///
    /// ```
    /// use halfedge::refine::Refinement;
    /// use halfedge::subdivide::{Sharpness, SubdivideOptions};
    /// use halfedge::tags::Tags;
    /// use halfedge::{shapes, HalfEdgeMesh, Rule};
    ///
    /// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
    /// let mut tags = Tags::default();
    /// tags.add_crease(0, 1, 2.5)?;
    /// let sharpness = Sharpness::from_tags(&cube, &tags)?;
    /// let opts = SubdivideOptions::default().with_sharpness(&sharpness);
    /// let r = Refinement::new(&cube, Rule::CatmullClark, 3, &opts)?;
    /// let bound = Refinement::predicted_bytes_with_creases(Rule::CatmullClark, &cube.counts(), 3)?;
    /// assert!(bound >= r.heap_bytes().into());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`Refinement::predicted_bytes`].
    pub fn predicted_bytes_with_creases(
        rule: Rule,
        counts: &MeshCounts,
        levels: u32,
    ) -> Result<num_bigint::BigInt> {
        Refinement::tables_bound(rule, counts, levels, false)
    }

    /// [`Refinement::predicted_bytes_with_creases`] for a face-varying channel whose surface
    /// has no crease rules (its sharpness is its corners, seams and boundary, infinitely
    /// sharp: override rows of at most 3 entries): a level with a face of more than 32 sides
    /// never gets a dense table, so each face counts at most 32 entries per side.
    pub(crate) fn predicted_channel_bytes(
        rule: Rule,
        counts: &MeshCounts,
        levels: u32,
    ) -> Result<num_bigint::BigInt> {
        Refinement::tables_bound(rule, counts, levels, true)
    }

    fn tables_bound(
        rule: Rule,
        counts: &MeshCounts,
        levels: u32,
        dense_only_narrow: bool,
    ) -> Result<num_bigint::BigInt> {
        use num_bigint::BigInt;
        let plan = super::plan(rule, counts)?;
        if levels == 0 || crease_table_bytes(&plan, counts, 0)?.is_none() {
            return Refinement::predicted_bytes(rule, counts, levels);
        }
        let mut bytes = BigInt::from(0u32);
        for s in 0..levels {
            bytes += table_bytes(&plan, counts, s, dense_only_narrow)?.unwrap_or_default();
        }
        // The last parent level keeps its connectivity for the index buffers.
        let c = plan.scheme.counts_at(counts, u64::from(levels - 1))?;
        bytes += &c.vertices * 4u32 + &c.edges * 32u32 + &c.faces * 4u32;
        Ok(bytes)
    }

    /// An upper bound of what the one-shot subdivision
    /// ([`subdivide`](super::subdivide), [`subdivide_to_face_list`](super::subdivide_to_face_list))
    /// holds under crease rules, next to the input and level `levels - 1`, while it builds the
    /// weight table of level `levels - 1` (the largest), for `rule` (Loop or Catmull-Clark; 0
    /// for the others, which have no crease rules) at `levels` on a mesh with `counts`: the
    /// table twice (its rows are built in chunks, then copied into the table; bounded as in
    /// [`Refinement::predicted_bytes_with_creases`]), 8 bytes per row (the chunks' row ends)
    /// and the level's sharpness (4 bytes per edge, 8 per vertex). What
    /// [`memory::predicted_peak_bytes_with_creases`](crate::memory::predicted_peak_bytes_with_creases)
    /// weighs against the last level.
    ///
    /// # Errors
    ///
    /// As [`Refinement::predicted_bytes`].
    pub fn one_shot_crease_bytes(
        rule: Rule,
        counts: &MeshCounts,
        levels: u32,
    ) -> Result<num_bigint::BigInt> {
        let plan = super::plan(rule, counts)?;
        let Some(last) = levels.checked_sub(1) else {
            return Ok(0u32.into());
        };
        let Some(table) = crease_table_bytes(&plan, counts, last)? else {
            return Ok(0u32.into());
        };
        let c = plan.scheme.counts_at(counts, u64::from(last))?;
        // One row per vertex of the next level.
        let rows = plan.scheme.counts_at(counts, u64::from(levels))?.vertices;
        Ok(table * 2u32 + rows * 8u32 + &c.edges * 4u32 + &c.vertices * 8u32)
    }

    /// Refines `base` (one entry per vertex of level 0) straight to the last level, into
    /// `out` (one entry per vertex of the last level), in the refinement's threads. The
    /// intermediate levels are allocated for the call; an [`Evaluator`] keeps them.
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`] when `base` or `out` has the wrong length (nothing is written);
    /// [`Error::AllocationFailed`] for the intermediate levels.
    pub fn evaluate<T: Scalar, const N: usize>(
        &self,
        base: &[[T; N]],
        out: &mut [[T; N]],
    ) -> Result<()> {
        self.evaluator().evaluate(base, out)
    }

    /// An evaluator of `[T; N]` data that keeps its intermediate levels between calls.
    pub fn evaluator<T: Scalar, const N: usize>(&self) -> Evaluator<'_, T, N> {
        Evaluator {
            refinement: self,
            scratch: [Vec::new(), Vec::new()],
            full: Vec::new(),
        }
    }

    /// Refines one level: `src` has `n_vertices(level - 1)` entries, `dst` `n_vertices(level)`.
    ///
    /// # Errors
    ///
    /// [`Error::LevelOutOfRange`] unless `1 <= level <= levels`; [`Error::BufferSize`].
    pub fn evaluate_level<T: Scalar, const N: usize>(
        &self,
        level: u32,
        src: &[[T; N]],
        dst: &mut [[T; N]],
    ) -> Result<()> {
        self.check_level(level)?;
        check_len("src", self.n_vertices(level - 1), src.len())?;
        check_len("dst", self.n_vertices(level), dst.len())?;
        if self.written.is_some() && level == self.levels {
            let n = self.computed_vertices(level);
            let mut full = super::alloc::filled([T::ZERO; N], n, "the whole last level")?;
            self.run(|| self.fill_level(level, src, &mut full));
            self.gather(&full, dst);
            return Ok(());
        }
        self.run(|| self.fill_level(level, src, dst));
        Ok(())
    }

    fn check_level(&self, level: u32) -> Result<()> {
        if level == 0 || level > self.levels {
            return Err(Error::LevelOutOfRange {
                level,
                first: 1,
                levels: self.levels,
            });
        }
        Ok(())
    }

    /// Refines flat data, `stride` entries per vertex (`base`: `stride * n_vertices(0)`,
    /// `out`: `stride * n_vertices(levels)`). Strides 1 to 16 run as `[T; stride]`; wider data
    /// of the linear rules runs component by component (the same values: the rules act on
    /// each component alike).
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`]; [`Error::UnsupportedStride`] for a stride of 0, or above 16
    /// under the icosphere rule (its projection couples the components).
    pub fn evaluate_strided<T: Scalar>(
        &self,
        base: &[T],
        stride: usize,
        out: &mut [T],
    ) -> Result<()> {
        if stride == 0 {
            return Err(Error::UnsupportedStride {
                rule: self.name.clone(),
                stride,
                reason: "a vertex needs at least one entry",
            });
        }
        let n0 = self.base_vertices();
        let nl = self.n_vertices(self.levels);
        let entries = |n: usize| stride.saturating_mul(n);
        check_len("base", entries(n0), base.len())?;
        check_len("out", entries(nl), out.len())?;
        macro_rules! widths {
            ($($n:literal)*) => {
                match stride {
                    $($n => return self.strided::<T, $n>(base, out),)*
                    _ => {}
                }
            };
        }
        widths!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16);
        if !self.rule.is_linear() {
            return Err(Error::UnsupportedStride {
                rule: self.name.clone(),
                stride,
                reason: "the sphere projection needs the whole vector, at most 16 entries",
            });
        }
        let mut evaluator = self.evaluator::<T, 1>();
        let mut column = super::alloc::filled([T::ZERO], n0, "a column of the base")?;
        let mut result = super::alloc::filled([T::ZERO], nl, "a column of the result")?;
        for c in 0..stride {
            for (x, chunk) in column.iter_mut().zip(base.chunks_exact(stride)) {
                *x = [chunk[c]];
            }
            evaluator.evaluate(&column, &mut result)?;
            for (chunk, x) in out.chunks_exact_mut(stride).zip(&result) {
                chunk[c] = x[0];
            }
        }
        Ok(())
    }

    fn strided<T: Scalar, const N: usize>(&self, base: &[T], out: &mut [T]) -> Result<()> {
        let n0 = self.base_vertices();
        let nl = self.n_vertices(self.levels);
        let mut packed = super::alloc::with_capacity(n0, "the packed base")?;
        packed.extend(
            base.chunks_exact(N)
                .map(|c| std::array::from_fn::<T, N, _>(|i| c[i])),
        );
        let mut result = super::alloc::filled([T::ZERO; N], nl, "the packed result")?;
        self.evaluate(&packed, &mut result)?;
        for (chunk, x) in out.chunks_exact_mut(N).zip(&result) {
            chunk.copy_from_slice(x);
        }
        Ok(())
    }

    /// The level before `level` (1-based), as the evaluation reads it.
    fn before(&self, level: u32) -> Option<LevelRef<'_>> {
        let before = self.topology.get(level as usize - 1)?;
        Some(LevelRef {
            topology: before.topology.as_ref().map(Connectivity::topo),
            step_b: before.step_b.as_ref(),
            fast: before.fast.as_ref(),
        })
    }

    /// Level `level` from `src` (the level before) into `dst`; lengths checked by the caller.
    fn fill_level<V: Vector>(&self, level: u32, src: &[V], dst: &mut [V]) {
        if let Some(before) = self.before(level) {
            self.fill_from(&before, src, dst);
        }
    }

    /// The level after `before` from its values `src` into `dst` (exactly its vertices).
    fn fill_from<V: Vector>(&self, before: &LevelRef<'_>, src: &[V], dst: &mut [V]) {
        use super::{catmull_clark, dual, sqrt3, trisplit};
        let parallel = self.threads != 1;
        match before.fast {
            Some(Fast::Loop(fast)) => return fast.points(src, &mut Slots::new(dst), parallel),
            Some(Fast::CatmullClark(fast)) => return fast.fill(src, dst, parallel),
            Some(Fast::Linear(fast)) => return fast.points(src, &mut Slots::new(dst), parallel),
            Some(Fast::Creased { weights, .. }) if weights.is_dense() => {
                return weights.points(src, &mut Slots::new(dst), parallel)
            }
            Some(Fast::Creased { base, weights }) => {
                let base = LevelRef {
                    fast: base.as_deref(),
                    ..*before
                };
                self.fill_from(&base, src, dst);
                weights.apply(src, dst, parallel);
                return;
            }
            None => {}
        }
        let Some(t) = before.topology else {
            return;
        };
        if self.algorithm == Algorithm::CatmullClark {
            catmull_clark::cc_fill(&t, src, dst, parallel);
            return;
        }
        let mut out = Slots::new(dst);
        match (self.algorithm, &self.template) {
            (Algorithm::Tri(rule, _), Some(template)) => {
                trisplit::tri_points(&t, src, template, rule, &mut out, parallel);
            }
            (Algorithm::Tri(..), None) => {}
            (Algorithm::CatmullClark, _) => {}
            (Algorithm::Sqrt3 { .. }, _) => {
                sqrt3::sqrt3_points(&t, src, before.step_b, &mut out, parallel);
            }
            (Algorithm::DooSabin, _) => dual::doo_sabin_points(&t, src, &mut out, parallel),
            (Algorithm::MidEdge, _) => dual::mid_edge_points(&t, src, &mut out, parallel),
        }
    }

    /// Level `level` from `src` into a new vector (the stencils' sparse sums).
    fn collect_level<V: Vector>(&self, level: u32, src: &[V]) -> Result<Vec<V>> {
        match self.before(level) {
            Some(before) => {
                let n = self.computed_vertices(level);
                let full = self.values_after(&before, src, n, false, "stencils")?;
                Ok(if level == self.levels {
                    self.written_of(full)
                } else {
                    full
                })
            }
            None => Ok(Vec::new()),
        }
    }

    /// The `n` values of the level after `before` from its values `src`, in a new vector:
    /// allocated exactly, or growing on demand with `grow` (the one-shot baseline). The
    /// geometry of the stencils and of the one-shot subdivision; `what` names the vector in an
    /// allocation failure.
    fn values_after<V: Vector>(
        &self,
        before: &LevelRef<'_>,
        src: &[V],
        n: usize,
        grow: bool,
        what: &str,
    ) -> Result<Vec<V>> {
        use super::{catmull_clark, dual, sqrt3, trisplit};
        let parallel = self.threads != 1;
        let capacity = (!grow).then_some(n);
        let out = || super::alloc::with_capacity_or_grow(capacity, what);
        match before.fast {
            Some(Fast::Loop(fast)) => {
                let mut out = out()?;
                fast.points(src, &mut out, parallel);
                return Ok(out);
            }
            Some(Fast::CatmullClark(fast)) => {
                let mut out = out()?;
                out.resize(n, V::zero());
                fast.fill(src, &mut out, parallel);
                return Ok(out);
            }
            Some(Fast::Linear(fast)) => {
                let mut out = out()?;
                fast.points(src, &mut out, parallel);
                return Ok(out);
            }
            Some(Fast::Creased { weights, .. }) if weights.is_dense() => {
                let mut out = out()?;
                weights.points(src, &mut out, parallel);
                return Ok(out);
            }
            Some(Fast::Creased { base, weights }) => {
                let base = LevelRef {
                    fast: base.as_deref(),
                    ..*before
                };
                let mut out = self.values_after(&base, src, n, grow, what)?;
                weights.apply(src, &mut out, parallel);
                return Ok(out);
            }
            None => {}
        }
        let Some(t) = before.topology else {
            return out();
        };
        if let Algorithm::CatmullClark = self.algorithm {
            return catmull_clark::cc_positions(&t, src, capacity, parallel);
        }
        let mut out = out()?;
        match (self.algorithm, &self.template) {
            (Algorithm::Tri(rule, _), Some(template)) => {
                trisplit::tri_points(&t, src, template, rule, &mut out, parallel);
            }
            (Algorithm::Tri(..), None) | (Algorithm::CatmullClark, _) => {}
            (Algorithm::Sqrt3 { .. }, _) => {
                sqrt3::sqrt3_points(&t, src, before.step_b, &mut out, parallel);
            }
            (Algorithm::DooSabin, _) => dual::doo_sabin_points(&t, src, &mut out, parallel),
            (Algorithm::MidEdge, _) => dual::mid_edge_points(&t, src, &mut out, parallel),
        }
        Ok(out)
    }

    /// Writes the last level's triangles, 3 vertex indices per face (`3 * n_faces(levels)`
    /// entries), numbered as [`subdivide_to_face_list`](super::subdivide_to_face_list) numbers
    /// them.
    ///
    /// # Errors
    ///
    /// [`Error::FaceDegreeMismatch`] when a face of the last level is not a triangle;
    /// [`Error::BufferSize`].
    pub fn write_triangles(&self, out: &mut [u32]) -> Result<()> {
        self.write_uniform(out, 3, "triangles")
    }

    /// Writes the last level's quads, 4 vertex indices per face (`4 * n_faces(levels)`
    /// entries).
    ///
    /// # Errors
    ///
    /// [`Error::FaceDegreeMismatch`] when a face of the last level is not a quad;
    /// [`Error::BufferSize`].
    pub fn write_quads(&self, out: &mut [u32]) -> Result<()> {
        self.write_uniform(out, 4, "quads")
    }

    fn write_uniform(&self, out: &mut [u32], degree: usize, what: &'static str) -> Result<()> {
        if self.face_degree != Some(degree) {
            let (face, found) = self.first_face_not_of(degree);
            return Err(Error::FaceDegreeMismatch {
                what,
                wanted: degree,
                face,
                degree: found,
            });
        }
        let nf = self.n_faces(self.levels);
        let what = if degree == 3 {
            "triangle indices"
        } else {
            "quad indices"
        };
        check_len(what, degree * nf, out.len())?;
        self.write_corners(out)
    }

    /// The first face of the last level whose degree is not `degree`, with its degree.
    fn first_face_not_of(&self, degree: usize) -> (usize, usize) {
        if let Some(p) = &self.polygons {
            let found = p
                .offsets
                .windows(2)
                .map(|w| (w[1] - w[0]) as usize)
                .enumerate()
                .find(|&(_, d)| d != degree);
            return found.unwrap_or((0, degree));
        }
        // A direct rule: every face has the rule's degree.
        (0, self.face_degree.unwrap_or(0))
    }

    /// The face corners of the last level into `out` (exactly `n_corners(levels)` entries).
    fn write_corners(&self, out: &mut [u32]) -> Result<()> {
        if let Some(p) = &self.polygons {
            out.copy_from_slice(&p.indices);
            return Ok(());
        }
        let parallel = self.threads != 1;
        let Some(t) = self
            .topology
            .last()
            .and_then(|l| l.topology.as_ref())
            .map(Connectivity::topo)
        else {
            return Ok(());
        };
        let expected = self.n_faces(self.levels);
        let written = self.run(|| match self.algorithm {
            Algorithm::CatmullClark => super::to_faces::catmull_clark_corners(&t, out, parallel),
            _ => {
                super::to_faces::four_to_one_corners(&t, out, parallel);
                4 * t.nf()
            }
        });
        if written != expected {
            return Err(Error::PredictionMismatch {
                scheme: self.name.clone(),
                level: self.levels,
                what: "faces",
                predicted: expected.into(),
                actual: written as u64,
            });
        }
        Ok(())
    }

    /// Writes the last level's faces as polygons: `offsets` (`n_faces + 1` entries, face `f`
    /// is `indices[offsets[f]..offsets[f + 1]]`) and `indices` (`n_corners` entries).
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`]; [`Error::IndexOverflow`] when the corners do not fit `u32`
    /// offsets.
    pub fn write_polygons(&self, offsets: &mut [u32], indices: &mut [u32]) -> Result<()> {
        let nf = self.n_faces(self.levels);
        let nc = self.n_corners(self.levels);
        check_len("face offsets", nf + 1, offsets.len())?;
        check_len("face indices", nc, indices.len())?;
        if u32::try_from(nc).is_err() {
            return Err(Error::IndexOverflow {
                what: "face corners",
                count: nc as u128,
            });
        }
        match (&self.polygons, self.face_degree) {
            (Some(p), _) => offsets.copy_from_slice(&p.offsets),
            (None, Some(d)) => {
                for (f, o) in offsets.iter_mut().enumerate() {
                    // At most nc, which fits u32.
                    *o = (d * f) as u32;
                }
            }
            (None, None) => {}
        }
        self.write_corners(indices)
    }

    /// The last level's vertices as weighted sums of the base vertices, for the linear rules
    /// (every rule but [`Rule::Icosphere`]): the form GPU evaluators consume (OpenSubdiv's
    /// `Far::StencilTable`). Computed by running the rules' kernels level by level on sparse
    /// sums, after the table's sizes are counted ([`Refinement::stencil_sizes`]); its arrays
    /// are allocated once, exactly, and filled.
    ///
    /// # Errors
    ///
    /// [`Error::NotLinear`] for [`Rule::Icosphere`]; [`Error::IndexOverflow`] beyond `u32`
    /// entries; [`Error::AllocationFailed`].
    pub fn stencils(&self) -> Result<StencilTable> {
        let sizes = self.stencil_sizes()?;
        let n0 = self.base_vertices() as u32;
        let mut current: Vec<Sparse> = (0..n0).map(Sparse::unit).collect();
        for s in 1..=self.levels {
            current = self.run(|| self.collect_level(s, &current))?;
        }
        if self.levels == 0 {
            current = self.written_of(current);
        }
        StencilTable::from_sums(&current, n0 as usize, sizes, &self.name, self.levels)
    }

    /// The sizes of [`Refinement::stencils`]' table before anything of it is allocated: its
    /// rows (the last level's vertices) and its entries, counted by running the rules' kernels
    /// level by level on the supports of the sums (their base vertices, without weights).
    ///
    /// ```
    /// use halfedge::refine::Refinement;
    /// use halfedge::subdivide::SubdivideOptions;
    /// use halfedge::{shapes, HalfEdgeMesh, Rule};
    ///
    /// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
    /// let r = Refinement::new(&cube, Rule::CatmullClark, 2, &SubdivideOptions::default())?;
    /// let sizes = r.stencil_sizes()?;
    /// assert_eq!(sizes.rows, r.n_vertices(2));
    /// assert_eq!(sizes, r.stencils()?.sizes());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::NotLinear`] for [`Rule::Icosphere`]; [`Error::AllocationFailed`].
    pub fn stencil_sizes(&self) -> Result<StencilSizes> {
        if !self.rule.is_linear() {
            return Err(Error::NotLinear {
                rule: self.name.clone(),
                reason: "the sphere projection",
            });
        }
        let n0 = self.base_vertices() as u32;
        let mut current: Vec<Support> = (0..n0).map(Support::unit).collect();
        for s in 1..=self.levels {
            current = self.run(|| self.collect_level(s, &current))?;
        }
        if self.levels == 0 {
            current = self.written_of(current);
        }
        Ok(StencilSizes {
            rows: current.len(),
            entries: current.iter().map(|r| r.0.len()).sum(),
        })
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

/// Evaluates `[T; N]` data on a [`Refinement`], keeping the intermediate levels' buffers
/// between calls (no allocation after the first call).
#[derive(Debug)]
pub struct Evaluator<'r, T: Scalar, const N: usize> {
    refinement: &'r Refinement,
    scratch: [Vec<[T; N]>; 2],
    /// The whole last level, when holes leave only part of it written.
    full: Vec<[T; N]>,
}

impl<T: Scalar, const N: usize> Evaluator<'_, T, N> {
    /// As [`Refinement::evaluate`].
    ///
    /// # Errors
    ///
    /// As [`Refinement::evaluate`].
    pub fn evaluate(&mut self, base: &[[T; N]], out: &mut [[T; N]]) -> Result<()> {
        let r = self.refinement;
        let levels = r.levels;
        check_len("base", r.base_vertices(), base.len())?;
        check_len("out", r.n_vertices(levels), out.len())?;
        if levels == 0 {
            match r.written {
                Some(_) => r.gather(base, out),
                None => out.copy_from_slice(base),
            }
            return Ok(());
        }
        let need = |parity: u32| {
            (1..levels)
                .filter(|s| s % 2 == parity)
                .map(|s| r.n_vertices(s))
                .max()
                .unwrap_or(0)
        };
        let [a, b] = &mut self.scratch;
        reserve(a, need(1))?;
        reserve(b, need(0))?;
        let (a, b): (&mut [[T; N]], &mut [[T; N]]) = (a, b);
        let whole = r.computed_vertices(levels);
        if r.written.is_some() {
            reserve(&mut self.full, whole)?;
        }
        let full = &mut self.full;
        r.run(|| {
            // Odd levels go to `a`, even ones to `b`.
            for s in 1..levels {
                let (n, m) = (r.n_vertices(s), r.n_vertices(s - 1));
                if s % 2 == 1 {
                    let input = if s == 1 { base } else { &b[..m] };
                    r.fill_level(s, input, &mut a[..n]);
                } else {
                    r.fill_level(s, &a[..m], &mut b[..n]);
                }
            }
            let m = r.n_vertices(levels - 1);
            let input = match levels {
                1 => base,
                l if (l - 1) % 2 == 1 => &a[..m],
                _ => &b[..m],
            };
            if r.written.is_some() {
                r.fill_level(levels, input, &mut full[..whole]);
                r.gather(&full[..whole], out);
            } else {
                r.fill_level(levels, input, out);
            }
        });
        Ok(())
    }
}

/// Grows `buffer` to at least `n` entries (fallibly).
fn reserve<T: Scalar, const N: usize>(buffer: &mut Vec<[T; N]>, n: usize) -> Result<()> {
    if buffer.len() < n {
        buffer
            .try_reserve_exact(n - buffer.len())
            .map_err(|e| Error::AllocationFailed {
                what: "intermediate level data".into(),
                bytes: n as u128 * std::mem::size_of::<[T; N]>() as u128,
                reason: e.to_string(),
            })?;
        buffer.resize(n, [T::ZERO; N]);
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
