//! Real subdivision by every built-in rule, with output buffers allocated once from the
//! predicted counts.
//!
//! A [`Rule`] (defined in `schemes`, next to the matrices that count it, and re-exported
//! here) names what to run: [`subdivide`] runs it on a [`HalfEdgeMesh`]. The rule's counting
//! scheme for the mesh ([`Rule::scheme_for`]: Loop on a mesh with boundary is counted by
//! `loop-boundary`) gives the counts of each level ([`schemes::Scheme::counts_at`]); the output
//! arrays are allocated once with exactly those lengths, the new topology is built by index
//! arithmetic (each module documents its numbering) and the geometry by the rule, and every
//! array is checked to come out exactly as long as predicted without growing: a mismatch is a
//! bug, reported as [`Error::PredictionMismatch`] (and a debug assertion). Multi-level
//! subdivision keeps only levels `s - 1` and `s` alive.
//!
//! [`subdivide_polygons`] does the same on raw face lists ([`PolygonMesh`]), including
//! non-manifold ones, for the rules whose topology is a per-face refinement (4:1, 1:N²,
//! Catmull-Clark), carrying UVs ([`SubdivideOptions::uvs`]) refined linearly with the
//! positions; [`verify`] and [`verify_polygons`] take a [`Scheme`] (a built-in, or a
//! custom matrix whose file names its `topology`), really subdivide by its rule and compare,
//! level by level, every state component the scheme predicts with the real mesh.
//! [`checked_rule`] is the bridge from a scheme the user named to the rule to run.
//!
//! | rule | scheme names | topology | geometry |
//! |---|---|---|---|
//! | [`Rule::Loop`] | `loop`, `loop-boundary`, `loop-general` | 4:1 | Loop's weights, cubic B-spline boundary |
//! | [`Rule::Midpoint`] | `midpoint` | 4:1 | midpoints, old vertices kept |
//! | [`Rule::Icosphere`] | `icosphere` | 4:1 | midpoints projected on the unit sphere |
//! | [`Rule::Butterfly`] | `butterfly` | 4:1 | modified butterfly (interpolating) |
//! | [`Rule::TriSplit`] | `tri-split-N`, `ternary` | 1:N² | linear (points on the flat triangles) |
//! | [`Rule::CatmullClark`] | `catmull-clark`, `catmull-clark-quad`, `catmull-clark-general` | quads | Catmull-Clark, boundary rules |
//! | [`Rule::Sqrt3`] | `sqrt3`, `sqrt3-boundary` | √3 | Kobbelt's, with his boundary rule |
//! | [`Rule::DooSabin`] | `doo-sabin`, `doo-sabin-boundary` | dual | Doo-Sabin weights, Chaikin boundary |
//! | [`Rule::MidEdge`] | `mid-edge`, `mid-edge-boundary` | dual | edge midpoints (Peters-Reif), cubic B-spline boundary |
//!
//! # Geometry and scheme notes
//!
//! - Loop: Loop's original `β = (5/8 - (3/8 + 1/4 cos(2π/n))²) / n`; interior edge points
//!   `3/8, 3/8, 1/8, 1/8`; boundary edges take the midpoint and boundary vertices
//!   `3/4, 1/8, 1/8` (the cubic B-spline of the boundary polygon).
//! - Modified butterfly: the 8-point stencil between regular interior vertices, Zorin's
//!   one-ring stencils at extraordinary interior vertices (averaged when both ends are
//!   extraordinary), the 4-point rule `-1/16, 9/16, 9/16, -1/16` on boundary edges.
//!   Simplifications: an interior edge with one boundary end uses the one-ring stencil of its
//!   interior end; an interior edge with both ends on the boundary takes the midpoint.
//! - Loop, midpoint, icosphere and butterfly are counted by `loop` on closed meshes; their
//!   geometry also handles boundaries, so on a mesh with boundary edges they are counted (and
//!   checked) as `loop-boundary`, the same 4:1 topology.
//! - `sqrt3-boundary` alternates Kobbelt's steps as the `schemes` crate defines them: step A
//!   at odd step numbers (boundary edges kept, boundary vertices fixed), step B at even ones
//!   (boundary edges trisected with the ternary cubic B-spline rule `1, 16, 10 / 27` and
//!   `4, 19, 4 / 27`; the boundary triangle is split from its opposite vertex).
//! - Catmull-Clark: boundary edges take the midpoint, boundary vertices `3/4, 1/8, 1/8`.
//! - Doo-Sabin and mid-edge are counted by `doo-sabin` and `mid-edge` on closed meshes and by
//!   `doo-sabin-boundary` and `mid-edge-boundary` on meshes with boundary: Doo-Sabin adds
//!   Chaikin's points `3/4, 1/4` on boundary edges (the boundary becomes the quadratic
//!   B-spline of the boundary polygon), mid-edge keeps the boundary vertices with
//!   `3/4, 1/8, 1/8` (the cubic B-spline); a corner with one face gets a triangle. Interior
//!   vertices need valence >= 3 (a vertex face has at least 3 sides). On a boundary both are
//!   built face by face into the predicted arrays.
//!
//! The 1:N² splits, Catmull-Clark, √3, Doo-Sabin and mid-edge write every output array front
//! to back from index formulas (in parallel chunks when `threads != 1`); on a boundary √3,
//! Doo-Sabin and mid-edge (rules of their own there) emit faces one by one into
//! index-addressed arrays of the predicted sizes; both check every length.
//!
//! # Example
//!
//! ```
//! use halfedge::subdivide::{subdivide, verify, Rule, SubdivideOptions};
//! use halfedge::{shapes, HalfEdgeMesh};
//!
//! let ico = HalfEdgeMesh::try_from(&shapes::icosahedron())?;
//! let sphere = subdivide(&ico, Rule::Icosphere, 2, &SubdivideOptions::default())?;
//! assert_eq!((sphere.n_vertices(), sphere.n_edges(), sphere.n_faces()), (162, 480, 320));
//! assert!(sphere.positions().iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
//!
//! let lp = schemes::builtin("loop")?;
//! for report in verify(&ico, &lp, 3, &SubdivideOptions::default())? {
//!     assert!(report.is_match(), "{report:?}");
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `subdivide/`: real subdivision by every `Rule` (the typed rule of `schemes`, re-exported:
//! `subdivide(&mesh, Rule::Loop, levels, &opts)`; the module has no scheme names). The rule's
//! counting scheme for the mesh (`Rule::scheme_for`: Loop on a mesh with boundary is counted by
//! `loop-boundary`) sizes the arrays; `verify` takes a `Scheme` (built-in or custom with a
//! `topology`), runs its rule and compares the scheme's own predictions with the real mesh, so a
//! wrong custom matrix is a mismatch, not a crash. Each level's arrays are allocated once from
//! `Scheme::counts_at` and checked afterwards (length equals prediction, capacity did not grow); a
//! mismatch is `Error::PredictionMismatch`, a bug. Topology is built by index arithmetic (each
//! module documents its numbering); only levels `s - 1` and `s` are alive. `subdivide`,
//! `subdivide_to_face_list` and `verify` are a thin wrapper over the refinement (below): its
//! one level loop with the retention `LastTwo` (`refine/oneshot.rs`) runs the refinement's own size checks, topology
//! steps (`Refinement::next_level`), geometry (`Refinement::values_after`, the dispatch the
//! stencils use) and index buffers (`to_faces::faces_after`), keeping only the level it refines
//! (as a half-edge mesh with its positions) and the one it builds and flattening nothing into fast
//! tables, so a rule changed in the refinement changes the one-shot subdivision too; its output is
//! hashed to the bit for every rule at levels 1-3 (`tests/integration/oneshot_hashes.rs`). Under crease
//! rules it takes the same `Creases` as `Refinement::new` (`SubdivideOptions::sharpness` and
//! `subdivision`): each level's positions come from the half-edge kernels and the crease rows of
//! the level refined written over them, or its dense weight table, as `Refinement::new` chooses
//! (`Fast::creased`, built just before and dropped before the next level's topology), then the
//! child's sharpness is pushed (`Creases::push_child`) and the parent's released, so only the last
//! two levels' sharpness is alive; in `f64` it equals `Refinement::evaluate` to the bit
//! (`tests/integration/creases.rs`). `verify` still visits every level as a half-edge mesh (it
//! counts the real mesh). Doo-Sabin and mid-edge on a boundary (`dual.rs`) number their boundary
//! points by the rank of each boundary half-edge, so they are built face by face into the
//! predicted arrays. `subdivide_to_face_list`
//! (what `subcount subdivide` runs) writes the last level of the 4:1 family and Catmull-Clark
//! straight into a `PolygonMesh` (`to_faces.rs`: positions and corners only, identical to
//! converting the half-edge result, half the peak memory); that last level needs only its vertex
//! indices to fit `u32`, not half-edge handles. The face-list subdividers serve the non-manifold
//! schemes (`loop-general`, `catmull-clark-general`, `tri-split-N`), and carry UVs by refining the
//! layout as a face list of its own through the same subdivider (`faces.rs`' `refined_uvs`: same
//! faces, same order, checked). Large buffers are reserved fallibly (`alloc.rs`: a refused
//! allocation is `Error::AllocationFailed`), and every level's positions are checked for
//! finiteness (`finite.rs`: `Error::NonFinitePosition` names the vertex and its origin; UVs by
//! `check_uvs`, `Error::NonFiniteUv`, on the one-shot path and by `refined.rs` in `f32`/`f64`).
//!
//! Owner of which schemes apply to a mesh and can run on it:
//! `halfedge::subdivide::applicable_schemes`; a scheme named by a user to the rule to run:
//! `halfedge::subdivide::checked_rule`.

pub(crate) mod alloc;
mod build;
mod catmull_clark;
mod corner_step;
pub(crate) mod data;
pub(crate) mod dual;
mod faces;
mod finite;
mod gather;
mod options;
mod par;
pub mod refine;
pub mod sdc;
mod sharpness;
mod shorthands;
mod sqrt3;
mod stages;
mod to_faces;
mod topo;
mod trisplit;
pub(crate) mod uniform;
mod verify;
pub(crate) mod weights;
pub(crate) mod wide;

use num_bigint::BigInt;
pub use schemes::Rule;

pub use self::finite::{check_colors, check_uvs};
pub use self::options::{LevelDone, SubdivideOptions};
pub use self::refine::oneshot::{direct_face_degree, FaceListLevel};
use self::refine::oneshot::{keep_written, written_prediction};
pub use self::sdc::Sharpness;
pub use self::shorthands::*;
pub use self::stages::{subdivide_stages, StageStart, StagedRun};
use self::verify::report_names;
pub use self::verify::{verify, verify_polygons, LevelReport};
use schemes::{LevelCounts, MeshCounts, Scheme, Stat};

use self::build::Sizes;
use self::topo::Topo;
use self::trisplit::Template;
use crate::holes::HoleSet;
use crate::tags::SubdivisionOptions;
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result};

/// How a level is split, as OpenSubdiv's split type (the scheme decides it): the topology
/// step of a [`Rule`] on a mesh. Rules are named once, by [`Rule`]; the split names the
/// topology family and the plan's rule the geometry (the 4:1 family shares one split).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Split {
    /// 1:N² triangle split (N = 2: the 4:1 split of Loop, midpoint, icosphere, butterfly).
    Tri(u32),
    /// A quad per face corner (Catmull-Clark).
    Quad,
    /// √3: a point per face, the old edges flipped; `boundary`: steps A and B alternate
    /// (`sqrt3-boundary`).
    Sqrt3 { boundary: bool },
    /// The dual split with a point per face corner (Doo-Sabin).
    DualCorners,
    /// The dual split with a point per edge (mid-edge).
    DualEdges,
}

pub(crate) struct Plan {
    /// The rule.
    pub(crate) rule: Rule,
    /// The name for messages: the scheme asked for, or the rule's name.
    pub(crate) name: String,
    /// The scheme whose counts size the output arrays: the rule's own built-in scheme for the
    /// mesh ([`Rule::scheme_for`]).
    pub(crate) scheme: Scheme,
    pub(crate) split: Split,
}

/// The plan of `rule` on a mesh with `counts`: its counting scheme and its split.
pub(crate) fn plan(rule: Rule, counts: &MeshCounts) -> Result<Plan> {
    let scheme = rule.scheme_for(counts)?;
    let split = match rule {
        Rule::Loop | Rule::Midpoint | Rule::Butterfly | Rule::Icosphere => Split::Tri(2),
        Rule::TriSplit(n) => Split::Tri(n),
        Rule::CatmullClark => Split::Quad,
        Rule::Sqrt3 => Split::Sqrt3 {
            boundary: scheme.canonical_name() == "sqrt3-boundary",
        },
        Rule::DooSabin => Split::DualCorners,
        Rule::MidEdge => Split::DualEdges,
    };
    Ok(Plan {
        rule,
        name: rule.to_string(),
        scheme,
        split,
    })
}

/// The rule that really subdivides `scheme` on a mesh with `counts`, once the scheme itself
/// accepts the mesh: what `subcount subdivide --scheme NAME` runs. The scheme decides the
/// class of meshes (`catmull-clark-quad` refuses a triangle, `loop` on a mesh with boundary
/// counts as `loop-boundary`), its [`Scheme::subdivision_rule`] the rule to run.
///
/// # Errors
///
/// [`Error::Scheme`] when the scheme refuses the mesh (with its suggestion);
/// [`Error::NoSubdivision`] for a scheme without a rule (a scheme file without `topology`).
///
/// ```
/// use halfedge::subdivide::{checked_rule, Rule};
/// use schemes::{builtin, MeshCounts, Scheme};
///
/// let open_square = MeshCounts::from_polygons(&[[0, 1, 2], [0, 2, 3]])?;
/// assert_eq!(checked_rule(&builtin("loop")?, &open_square)?, Rule::Loop);
/// assert!(checked_rule(&builtin("catmull-clark-quad")?, &open_square).is_err());
/// let bare = Scheme::from_toml("name = \"m\"\nstate = [\"F\"]\nmatrix = [[4]]\n")?;
/// let err = checked_rule(&bare, &open_square).unwrap_err();
/// assert!(err.to_string().contains("topology = "), "{err}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn checked_rule(scheme: &Scheme, counts: &MeshCounts) -> Result<Rule> {
    let Some(rule) = scheme.subdivision_rule() else {
        return Err(no_rule(scheme));
    };
    scheme.for_mesh(counts).initial_state(counts)?;
    Ok(rule)
}

/// The built-in schemes ([`schemes::builtins`]) whose counts apply to a mesh with `counts`
/// and whose subdivision can run on it: on a `manifold` mesh (a valid [`HalfEdgeMesh`]) every
/// scheme whose class admits it, otherwise the ones that run on raw face lists
/// ([`Rule::refines_faces`] and a class without the manifold requirement). What
/// `subcount stats` lists as `applicable schemes`.
///
/// ```
/// use halfedge::subdivide::applicable_schemes;
/// let cube = halfedge::stats::face_list_counts(&halfedge::shapes::cube());
/// let names: Vec<String> = applicable_schemes(&cube, true).iter().map(|s| s.name().to_owned()).collect();
/// assert!(names.contains(&"catmull-clark".to_owned()) && !names.contains(&"loop".to_owned()));
/// ```
pub fn applicable_schemes(counts: &MeshCounts, manifold: bool) -> Vec<Scheme> {
    schemes::builtins()
        .into_iter()
        .filter(|s| {
            let runs = s.subdivision_rule().is_some_and(|rule| {
                manifold || (rule.refines_faces() && !s.mesh_class().needs_manifold())
            });
            runs && s.initial_state(counts).is_ok()
        })
        .collect()
}

fn no_rule(scheme: &Scheme) -> Error {
    Error::NoSubdivision {
        scheme: scheme.name().to_owned(),
        reason: "its matrix names no rule; add `topology = \"NAME\"` to the scheme file, \
                 NAME the built-in scheme whose subdivision it counts (loop, catmull-clark, \
                 sqrt3, ...)"
            .into(),
    }
}

/// Checks what the scheme's class cannot see: structural needs of the split.
fn check_mesh(plan: &Plan, mesh: &HalfEdgeMesh) -> Result<()> {
    let t = Topo::new(mesh);
    let name = &plan.name;
    let refuse = |reason: String| {
        Err(Error::SchemeNotApplicable {
            scheme: name.to_owned(),
            reason,
        })
    };
    match plan.split {
        Split::Tri(..) | Split::Sqrt3 { .. } => {
            if let Some((f, d)) = t.first_non_triangle() {
                return refuse(format!(
                    "face {f} has {d} vertices, the scheme needs triangles"
                ));
            }
            if plan.split == (Split::Sqrt3 { boundary: false }) && t.boundary_edges() > 0 {
                return refuse("the mesh has a boundary; use sqrt3-boundary".into());
            }
        }
        Split::DualCorners | Split::DualEdges => {
            // A boundary vertex of valence 2 (a corner with one face) gets a triangle.
            if let Some(v) =
                (0..t.nv() as u32).find(|&v| t.valence(v) < 3 && !t.is_boundary_vertex(v))
            {
                return refuse(format!(
                    "vertex {v} has valence {}, the scheme needs at least 3 (its vertex face would have fewer than 3 sides)",
                    t.valence(v)
                ));
            }
        }
        Split::Quad => {}
    }
    Ok(())
}

/// Array sizes of a predicted level, refused when they do not fit 32-bit handles. With
/// `handles` false (a last level written straight into a face list, which has no half-edges)
/// only the vertex indices must fit `u32`: edges and faces are counted in `usize`.
fn sizes(c: &LevelCounts, scheme: &str, level: u32, handles: bool) -> Result<Sizes> {
    let too_large = |what: &'static str, count: &BigInt| Error::TooLarge {
        scheme: scheme.to_owned(),
        level,
        what,
        count: count.clone(),
    };
    let fits = |what: &'static str, count: &BigInt, factor: u32, indexed: bool| {
        let scaled = count * factor;
        if scaled.sign() == num_bigint::Sign::Minus || (indexed && scaled >= BigInt::from(u32::MAX))
        {
            return Err(too_large(what, count));
        }
        usize::try_from(&scaled).map_err(|_| too_large(what, count))
    };
    Ok(Sizes {
        vertices: fits("vertices", &c.vertices, 1, true)?,
        halfedges: fits("edges", &c.edges, 2, handles)?,
        faces: fits("faces", &c.faces, 1, handles)?,
    })
}

/// Runs `f` on the calling thread (`threads` 0 or 1) or inside a pool of `threads` threads.
fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> Result<T> + Send) -> Result<T> {
    if threads <= 1 {
        return f();
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::ThreadPool {
            threads,
            reason: e.to_string(),
        })?;
    pool.install(f)
}

/// Subdivides `mesh` `levels` times by `rule`.
///
/// Each level's arrays are allocated once with the lengths the rule's counting scheme
/// predicts ([`Rule::scheme_for`], [`schemes::Scheme::counts_at`]) and checked afterwards;
/// only levels `s - 1` and `s` are alive at a time. `levels = 0` returns a copy of the input.
/// On a mesh with boundary, Loop and its 4:1 relatives use their boundary rules (counted by
/// `loop-boundary`), √3 alternates Kobbelt's boundary steps (`sqrt3-boundary`), and Doo-Sabin
/// and mid-edge use theirs (`doo-sabin-boundary`, `mid-edge-boundary`).
///
/// # Errors
///
/// - [`Error::Scheme`] for a mesh outside the rule's class (e.g. a quad under Loop), with the
///   scheme crate's suggestion;
/// - [`Error::SchemeNotApplicable`] when the split cannot run (an interior vertex of
///   valence 2 under a dual scheme);
/// - [`Error::TooLarge`] when a level would not fit 32-bit handles;
/// - [`Error::ThreadPool`] when the requested threads cannot be started;
/// - [`Error::PredictionMismatch`] / [`Error::InvalidOutput`]: bugs.
///
/// ```
/// use halfedge::subdivide::{subdivide, Rule, SubdivideOptions};
/// use halfedge::{shapes, HalfEdgeMesh};
///
/// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
/// let smooth = subdivide(&cube, Rule::CatmullClark, 2, &SubdivideOptions::default())?;
/// assert_eq!((smooth.n_vertices(), smooth.n_edges(), smooth.n_faces()), (98, 192, 96));
/// let err = subdivide(&cube, Rule::Loop, 1, &SubdivideOptions::default()).unwrap_err();
/// assert!(err.to_string().contains("triangle"));
///
/// // Loop on a mesh with boundary: Loop's boundary rules.
/// let grid = HalfEdgeMesh::try_from(&shapes::grid(2, 2)?)?;
/// let out = subdivide(&grid, Rule::Loop, 2, &SubdivideOptions::default())?;
/// assert_eq!(out.n_faces(), 8 * 16);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn subdivide(
    mesh: &HalfEdgeMesh,
    rule: Rule,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<HalfEdgeMesh> {
    let opts = &opts.over_descriptor(mesh, Some(rule))?;
    let counts = mesh.counts();
    let plan = plan(rule, &counts)?;
    if crate::holes::active(opts.holes, rule, mesh.n_faces())?.is_some() {
        // The written faces as a half-edge mesh: refused by its validation when they are not
        // one (two written fans meeting at a vertex between holes).
        let level = subdivide_to_face_list(mesh, rule, levels, opts)?;
        return HalfEdgeMesh::try_from_polygon_mesh(&level.mesh);
    }
    run_levels(&plan, mesh, &counts, levels, opts, |_, _| Ok(()))
}

/// The statistics of the faces of `faces` (an iterator of vertex lists) whose `written`
/// entry is `true`.
fn written_face_counts<F, I>(faces: F, written: &[bool], positions: usize) -> MeshCounts
where
    F: Iterator<Item = I> + Clone,
    I: IntoIterator<Item = u32>,
{
    let faces = faces
        .zip(written.iter().copied())
        .filter(|(_, w)| *w)
        .map(|(f, _)| f);
    MeshCounts::from_face_list(faces, positions)
}

/// Subdivides like [`subdivide`], with the last level written as a face list
/// ([`PolygonMesh`]) instead of a half-edge mesh.
///
/// For the schemes of [`direct_face_degree`] the
/// last step writes only positions and face corners: 12 bytes per output triangle (16 per
/// quad) plus 8 per face offset, against 52 (68) for the half-edge arrays, so the peak memory
/// is about half and the last level, the largest, is faster to build. The result is identical
/// to `subdivide(..)?.to_polygon_mesh()` (tested for every scheme); other schemes are built
/// that way.
///
/// # Errors
///
/// As [`subdivide`].
///
/// ```
/// use halfedge::subdivide::{subdivide, subdivide_to_face_list, Rule, SubdivideOptions};
/// use halfedge::{shapes, HalfEdgeMesh};
///
/// let ico = HalfEdgeMesh::try_from(&shapes::icosahedron())?;
/// let opts = SubdivideOptions::default();
/// let level = subdivide_to_face_list(&ico, Rule::Loop, 2, &opts)?;
/// assert_eq!((level.mesh.n_vertices(), level.edges, level.mesh.n_faces()), (162, 480, 320));
/// assert_eq!(level.mesh, subdivide(&ico, Rule::Loop, 2, &opts)?.to_polygon_mesh());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn subdivide_to_face_list(
    mesh: &HalfEdgeMesh,
    rule: Rule,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<FaceListLevel> {
    let opts = &opts.over_descriptor(mesh, Some(rule))?;
    let counts = mesh.counts();
    let plan = plan(rule, &counts)?;
    if opts.uvs.is_some() {
        refine::face_varying::channel_kind(rule)?;
    }
    let holes = crate::holes::active(opts.holes, rule, mesh.n_faces())?;
    let written = match holes {
        Some(holes) => Some(written_prediction(
            &plan,
            &holes.written_mesh_counts(mesh),
            levels,
        )?),
        None => None,
    };
    // The base faces: a closed form for the nesting splits, else chained level by level.
    let degrees = mesh.faces().map(|f| mesh.face_degree(f));
    let nested = match opts.base_faces {
        true => uniform::nested_base_faces(plan.split, degrees, levels)?,
        false => None,
    };
    let mut chained = match (opts.base_faces, &nested) {
        (true, None) if levels > 0 => {
            let identity: Vec<u32> = (0..mesh.n_faces() as u32).collect();
            Some(uniform::child_faces(
                plan.split,
                &Topo::new(mesh),
                &identity,
            )?)
        }
        _ => None,
    };
    let visit = |s: u32, m: &HalfEdgeMesh| {
        if let Some(values) = chained.as_mut().filter(|_| s < levels) {
            *values = uniform::child_faces(plan.split, &Topo::new(m), values)?;
        }
        Ok(())
    };
    let level = match refine::one_shot(&plan, mesh, &counts, levels, true, opts, visit)? {
        refine::OneShot::Mesh(m) => (m.to_polygon_mesh(), m.n_edges()),
        refine::OneShot::Faces(mesh, edges) => (*mesh, edges),
    };
    let base_faces = match (opts.base_faces, nested, chained) {
        (false, ..) => None,
        (true, Some(faces), _) | (true, None, Some(faces)) => Some(faces),
        (true, None, None) => Some((0..mesh.n_faces() as u32).collect()),
    };
    let mut level = match (holes, written) {
        (Some(holes), Some(predicted)) => {
            let degrees = crate::holes::degrees_of(mesh);
            let last = (level.0, base_faces);
            keep_written(last, holes, &degrees, &plan, levels, &predicted)?
        }
        _ => FaceListLevel {
            mesh: level.0,
            edges: level.1,
            base_faces,
        },
    };
    if let Some(layout) = opts.uvs {
        let uvs = refine::face_varying::refined_uvs(mesh, layout, rule, levels, opts)?;
        level
            .mesh
            .set_uvs(Some(uvs))
            .map_err(|e| Error::UvLayoutMismatch {
                reason: e.to_string(),
            })?;
    }
    Ok(level)
}

/// The 1:N² triangle split ([`Rule::TriSplit`]) with points on the flat triangles.
///
/// # Errors
///
/// As [`subdivide`]; `n < 2` is refused by the scheme lookup.
pub fn tri_split_subdivide(
    mesh: &HalfEdgeMesh,
    n: u32,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<HalfEdgeMesh> {
    subdivide(mesh, Rule::TriSplit(n), levels, opts)
}

/// The level loop shared by [`subdivide`] and [`verify`] (the refinement's, keeping two
/// levels: [`refine::one_shot`]); `visit(level, mesh)` sees every level built.
fn run_levels(
    plan: &Plan,
    mesh: &HalfEdgeMesh,
    counts: &MeshCounts,
    levels: u32,
    opts: &SubdivideOptions<'_>,
    visit: impl FnMut(u32, &HalfEdgeMesh) -> Result<()> + Send,
) -> Result<HalfEdgeMesh> {
    match refine::one_shot(plan, mesh, counts, levels, false, opts, visit)? {
        refine::OneShot::Mesh(m) => Ok(m),
        refine::OneShot::Faces(..) => Err(Error::InvalidOutput {
            scheme: plan.name.clone(),
            level: levels,
            what: "a face list where a half-edge mesh was asked for".into(),
        }),
    }
}

/// Subdivides a raw face list (non-manifold allowed) `levels` times by a rule whose topology
/// is a per-face refinement ([`Rule::refines_faces`]): 4:1 (the Loop family, counted by
/// `loop-general` on non-manifold edges), 1:N² ([`Rule::TriSplit`]) or Catmull-Clark.
/// Topology only: new points are placed linearly (edge points at the midpoint or on the edge,
/// face points at the centroid or on the flat triangle), old vertices stay.
///
/// From level 1 on, vertices no face uses are dropped (level 0 is a copy of the input).
///
/// With [`SubdivideOptions::uvs`] (the layout of `mesh`, [`PolygonMesh::uv_layout`]) the
/// layout is refined as a face list of its own (its values as vertices at their UV, its
/// value-index faces) by the same subdivider and levels, so each child value is placed as its
/// child vertex is, within its face: the edge midpoint and the face centroid under the 4:1
/// family and Catmull-Clark, the points `k / N` on the edge and on the flat triangle under
/// 1:N². Faces that disagree at an end of a shared edge (a seam) give it a child value each.
/// The refined layout must have the output's faces in the same order with the same sizes (a
/// mismatch is a bug, [`Error::InvalidOutput`]); the output then carries its corners' values
/// as [`PolygonMesh::uvs`] (with holes, the written faces' values, renumbered in order of
/// first use). The value counts are `schemes::uv`'s from `UV0 = V` (the layout refined as a
/// mesh; OpenSubdiv's sibling values are not split here).
///
/// # Errors
///
/// As [`subdivide`] ([`Error::Scheme`] when the face list is outside the rule's class), and
/// [`Error::NoSubdivision`] for the other rules.
///
/// ```
/// use glam::DVec3;
/// use halfedge::subdivide::{subdivide_polygons, Rule, SubdivideOptions};
/// use halfedge::PolygonMesh;
///
/// // Three triangles on one edge: a non-manifold "book".
/// let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y];
/// let book = PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
/// let out = subdivide_polygons(&book, Rule::Loop, 1, &SubdivideOptions::default())?;
/// assert_eq!((out.n_vertices(), out.n_faces()), (5 + 7, 12));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn subdivide_polygons(
    mesh: &PolygonMesh,
    rule: Rule,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<PolygonMesh> {
    let plan = plan(rule, &crate::stats::face_list_counts(mesh))?;
    let degrees: Vec<usize> = mesh.faces().map(<[u32]>::len).collect();
    let holes = crate::holes::active(opts.holes, rule, mesh.n_faces())?;
    let predicted = match holes {
        Some(holes) => Some(written_prediction(
            &plan,
            &holes.written_counts(mesh),
            levels,
        )?),
        None => None,
    };
    let last = faces::run_levels(&plan, mesh, levels, opts, |_, _| Ok(()))?;
    let mask = match holes {
        Some(holes) => Some(holes.written_at(plan.rule, &degrees, levels)?),
        None => None,
    };
    let uvs = match opts.uvs {
        Some(layout) => Some(faces::refined_uvs(
            &plan,
            mesh,
            layout,
            levels,
            opts,
            &last,
            mask.as_deref(),
        )?),
        None => None,
    };
    // The colors: placed as the positions are (the face-list subdividers are linear).
    let colors = match mesh.colors() {
        Some(colors) => {
            let mut as_points = mesh.clone();
            as_points.positions = colors.iter().map(|&c| glam::DVec3::from_array(c)).collect();
            let points = faces::run_levels(&plan, &as_points, levels, opts, |_, _| Ok(()))
                .map_err(|e| match e {
                    // The colors ran as positions: an overflow is a color's.
                    Error::NonFinitePosition {
                        scheme,
                        level,
                        vertex,
                        origin,
                        x,
                        y,
                        z,
                    } => Error::NonFiniteColor {
                        scheme,
                        level,
                        vertex,
                        origin,
                        r: x,
                        g: y,
                        b: z,
                    },
                    e => e,
                })?;
            Some(points.positions)
        }
        None => None,
    };
    // The groups: each face's base face's (the per-face refinements nest).
    let base_faces = match mesh.groups() {
        Some(_) => uniform::nested_base_faces(plan.split, degrees.iter().copied(), levels)?,
        None => None,
    };
    let (mut written, base_faces, colors) = match (holes, predicted) {
        (Some(holes), Some(predicted)) => {
            let colors = colors.map(|c| {
                let mut p = last.clone();
                p.positions = c;
                p
            });
            let level = keep_written(
                (last, base_faces),
                holes,
                &degrees,
                &plan,
                levels,
                &predicted,
            )?;
            let colors = match colors {
                Some(c) => Some(
                    keep_written((c, None), holes, &degrees, &plan, levels, &predicted)?
                        .mesh
                        .positions,
                ),
                None => None,
            };
            (level.mesh, level.base_faces, colors)
        }
        _ => (last, base_faces, colors),
    };
    let mismatch = |what: String| Error::InvalidOutput {
        scheme: plan.name.clone(),
        level: levels,
        what,
    };
    if let Some(colors) = colors {
        let colors: Vec<[f64; 3]> = colors.iter().map(|p| p.to_array()).collect();
        check_colors((&plan.name, levels), &colors, "placed as its position")?;
        let set = written.set_colors(Some(colors));
        set.map_err(|e| mismatch(e.to_string()))?;
    }
    if let (Some(groups), Some(base)) = (mesh.groups(), base_faces) {
        let groups = groups
            .of_base_faces(base)
            .map_err(|e| mismatch(e.to_string()))?;
        let set = written.set_groups(Some(groups));
        set.map_err(|e| mismatch(e.to_string()))?;
    }
    match uvs {
        Some(uvs) => with_uvs(written, uvs),
        None => Ok(written),
    }
}

/// `mesh` with the refined UVs `uvs` of its corners.
fn with_uvs(mut mesh: PolygonMesh, uvs: crate::uv::Uvs) -> Result<PolygonMesh> {
    mesh.set_uvs(Some(uvs))
        .map_err(|e| Error::UvLayoutMismatch {
            reason: e.to_string(),
        })?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 3holes.obj (7,200 faces, genus 3) under Loop at level 9: 2,831,155,200 edges, more than
    /// 32-bit half-edge handles address, but the vertex indices of a face list fit `u32`.
    #[test]
    fn a_face_list_last_level_needs_only_its_vertex_indices_to_fit_u32() {
        let faces = BigInt::from(7200u64 << 18);
        let edges = &faces * 3 / 2;
        let c = LevelCounts {
            level: 9,
            state: vec![],
            vertices: &edges - &faces - 4,
            edges,
            faces,
        };
        let err = sizes(&c, "loop", 9, true).unwrap_err();
        assert_eq!(
            err.to_string(),
            "loop level 9 would have 2831155200 edges: more than 32-bit handles can address"
        );
        let s = sizes(&c, "loop", 9, false).expect("a face list holds it");
        assert_eq!(
            (s.vertices, s.halfedges, s.faces),
            (943_718_396, 5_662_310_400, 1_887_436_800)
        );
        let too_many_vertices = LevelCounts {
            vertices: BigInt::from(u32::MAX),
            ..c
        };
        assert!(sizes(&too_many_vertices, "loop", 9, false).is_err());
    }
}
