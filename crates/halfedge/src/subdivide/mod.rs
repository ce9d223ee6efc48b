//! Real subdivision for every built-in scheme, with output buffers allocated once from the
//! scheme's predicted counts.
//!
//! [`subdivide`] runs any built-in scheme of the `schemes` crate (aliases and `tri-split-N`
//! included) on a [`HalfEdgeMesh`]: it checks that the scheme applies, asks the scheme for the
//! counts of each level ([`schemes::Scheme::counts_at`]), allocates the output arrays once with
//! exactly those lengths, builds the new topology by index arithmetic (each scheme module
//! documents its numbering) and the standard geometry, and checks that every array came out
//! exactly as long as predicted without growing: a mismatch is a bug, reported as
//! [`Error::PredictionMismatch`] (and a debug assertion). Multi-level subdivision keeps only
//! levels `s - 1` and `s` alive.
//!
//! [`subdivide_polygons`] does the same on raw face lists ([`PolygonMesh`]), including
//! non-manifold ones, for the schemes whose topology is a per-face refinement (4:1, 1:N²,
//! Catmull-Clark); [`verify`] and [`verify_polygons`] compare, level by level, every state
//! component the scheme predicts with the real mesh.
//!
//! | scheme | topology | geometry |
//! |---|---|---|
//! | `loop`, `loop-boundary`, `loop-general` | 4:1 | Loop's weights, cubic B-spline boundary |
//! | `midpoint` | 4:1 | midpoints, old vertices kept |
//! | `icosphere` | 4:1 | midpoints projected on the unit sphere |
//! | `butterfly` | 4:1 | modified butterfly (interpolating) |
//! | `tri-split-N`, `ternary` | 1:N² | linear (points on the flat triangles) |
//! | `catmull-clark`, `catmull-clark-quad`, `catmull-clark-general` | quads | Catmull-Clark, boundary rules |
//! | `sqrt3`, `sqrt3-boundary` | √3 | Kobbelt's, with his boundary rule |
//! | `doo-sabin` | dual | Doo-Sabin weights |
//! | `mid-edge` | dual | edge midpoints (Peters-Reif) |
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
//! - `midpoint`, `icosphere` and `butterfly` are `loop` (closed meshes) in the `schemes`
//!   crate; their geometry also handles boundaries, so on a mesh with boundary edges they are
//!   counted (and checked) as `loop-boundary`, the same 4:1 topology.
//! - `sqrt3-boundary` alternates Kobbelt's steps as the `schemes` crate defines them: step A
//!   at odd step numbers (boundary edges kept, boundary vertices fixed), step B at even ones
//!   (boundary edges trisected with the ternary cubic B-spline rule `1, 16, 10 / 27` and
//!   `4, 19, 4 / 27`; the boundary triangle is split from its opposite vertex).
//! - Catmull-Clark: boundary edges take the midpoint, boundary vertices `3/4, 1/8, 1/8`.
//! - Doo-Sabin and mid-edge need closed meshes whose vertices all have valence >= 3.
//!
//! The 4:1 family, Catmull-Clark, √3 on closed meshes, Doo-Sabin and mid-edge write every
//! output array front to back from index formulas (in parallel chunks when `threads != 1`);
//! the other steps (1:N² for N >= 3, √3 on a boundary) and every scheme with
//! [`SubdivideOptions::preallocate`] off emit faces one by one into index-addressed arrays. Both paths check every length against the prediction.
//!
//! # Example
//!
//! ```
//! use halfedge::subdivide::{subdivide, verify, SubdivideOptions};
//! use halfedge::{shapes, HalfEdgeMesh};
//!
//! let ico = HalfEdgeMesh::try_from(&shapes::icosahedron())?;
//! let sphere = subdivide(&ico, "icosphere", 2, &SubdivideOptions::default())?;
//! assert_eq!((sphere.n_vertices(), sphere.n_edges(), sphere.n_faces()), (162, 480, 320));
//! assert!(sphere.positions().iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
//!
//! for report in verify(&ico, "loop", 3, &SubdivideOptions::default())? {
//!     assert!(report.is_match(), "{report:?}");
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod alloc;
mod build;
mod catmull_clark;
mod dual;
mod faces;
mod finite;
mod gather;
mod par;
mod sqrt3;
mod to_faces;
mod topo;
mod trisplit;

use glam::DVec3;
use num_bigint::BigInt;
use schemes::{LevelCounts, MeshCounts, Scheme, Stat};

use self::build::{Sizes, StepContext};
use self::topo::Topo;
use self::trisplit::{Template, TriRule};
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result};

/// Options of [`subdivide`] and friends.
///
/// ```
/// use halfedge::subdivide::SubdivideOptions;
/// let opts = SubdivideOptions::default().with_threads(1).with_preallocate(false);
/// assert_eq!((opts.threads, opts.preallocate), (1, false));
/// ```
#[derive(Clone, Copy)]
#[non_exhaustive]
pub struct SubdivideOptions<'a> {
    /// Threads for the geometry passes: 1 runs everything on the calling thread, 0 uses
    /// rayon's global pool, `n >= 2` a pool of `n` threads. Topology is built on one thread.
    pub threads: usize,
    /// Allocate every output array once from the predicted counts (the default); `false`
    /// starts from empty arrays that grow on demand (the baseline for benchmarks). Both paths
    /// check the final sizes against the prediction.
    pub preallocate: bool,
    /// Called after each level is built.
    pub progress: Option<&'a (dyn Fn(&LevelDone) + Sync)>,
}

impl Default for SubdivideOptions<'_> {
    fn default() -> Self {
        SubdivideOptions {
            threads: 1,
            preallocate: true,
            progress: None,
        }
    }
}

impl<'a> SubdivideOptions<'a> {
    /// Sets [`SubdivideOptions::threads`].
    pub fn with_threads(mut self, threads: usize) -> Self {
        self.threads = threads;
        self
    }

    /// Sets [`SubdivideOptions::preallocate`].
    pub fn with_preallocate(mut self, preallocate: bool) -> Self {
        self.preallocate = preallocate;
        self
    }

    /// Sets [`SubdivideOptions::progress`].
    pub fn with_progress(mut self, progress: &'a (dyn Fn(&LevelDone) + Sync)) -> Self {
        self.progress = Some(progress);
        self
    }
}

impl std::fmt::Debug for SubdivideOptions<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SubdivideOptions")
            .field("threads", &self.threads)
            .field("preallocate", &self.preallocate)
            .field("progress", &self.progress.map(|_| "callback"))
            .finish()
    }
}

/// Passed to the progress callback after each level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct LevelDone {
    /// The level just built (1-based).
    pub level: u32,
    /// The final level.
    pub levels: u32,
    /// Vertices of the level.
    pub vertices: usize,
    /// Edges of the level.
    pub edges: usize,
    /// Faces of the level.
    pub faces: usize,
}

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

/// The rule a scheme name stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rule {
    /// 1:N² triangle split (N = 2 for the 4:1 family).
    Tri(TriRule, u32),
    CatmullClark,
    /// `boundary`: alternate steps A and B (`sqrt3-boundary`).
    Sqrt3 {
        boundary: bool,
    },
    DooSabin,
    MidEdge,
}

struct Plan {
    /// The name as given (for messages).
    name: String,
    /// The scheme whose counts are predicted and checked.
    scheme: Scheme,
    rule: Rule,
}

impl Plan {
    /// The face degree when the last level can be written straight into a face list.
    fn direct_face_degree(&self) -> Option<usize> {
        match self.rule {
            Rule::Tri(_, 2) => Some(3),
            Rule::CatmullClark => Some(4),
            _ => None,
        }
    }

    /// The scheme that counts this plan on a mesh with `counts` ([`Scheme::for_mesh`]): the
    /// 4:1 aliases `midpoint`, `icosphere` and `butterfly` count as `loop`, which needs a
    /// closed mesh; their geometry handles boundaries, so on a mesh with boundary they are
    /// counted as `loop-boundary` (the same 4:1 topology), under their own name.
    fn for_mesh(mut self, counts: &MeshCounts) -> Plan {
        self.scheme = self.scheme.for_mesh(counts);
        self
    }
}

/// The names [`supports`] accepts, for messages.
const SUPPORTED: &str = "loop, loop-boundary, loop-general, midpoint, icosphere, butterfly, \
tri-split-N, ternary, catmull-clark, catmull-clark-quad, catmull-clark-general, sqrt3, \
sqrt3-boundary, doo-sabin, mid-edge";

fn plan(name: &str) -> Result<Plan> {
    let scheme = schemes::builtin(name)?;
    let rule = match (scheme.name(), scheme.canonical_name()) {
        ("midpoint", _) => Rule::Tri(TriRule::Midpoint, 2),
        ("icosphere", _) => Rule::Tri(TriRule::Icosphere, 2),
        ("butterfly", _) => Rule::Tri(TriRule::Butterfly, 2),
        (_, "loop" | "loop-boundary" | "loop-general") => Rule::Tri(TriRule::Loop, 2),
        (_, "catmull-clark" | "catmull-clark-quad" | "catmull-clark-general") => Rule::CatmullClark,
        (_, "sqrt3") => Rule::Sqrt3 { boundary: false },
        (_, "sqrt3-boundary") => Rule::Sqrt3 { boundary: true },
        (_, "doo-sabin") => Rule::DooSabin,
        (_, "mid-edge") => Rule::MidEdge,
        (_, canonical) => match canonical
            .strip_prefix("tri-split-")
            .and_then(|n| n.parse::<u32>().ok())
        {
            Some(n) if n >= 2 => Rule::Tri(TriRule::Linear, n),
            _ => {
                return Err(Error::UnsupportedScheme {
                    name: name.to_owned(),
                    supported: SUPPORTED.to_owned(),
                })
            }
        },
    };
    Ok(Plan {
        name: name.to_owned(),
        scheme,
        rule,
    })
}

/// Whether [`subdivide`] can run the scheme `name` (a built-in name, alias or `tri-split-N`).
///
/// ```
/// use halfedge::subdivide::supports;
/// assert!(supports("loop") && supports("ternary") && supports("tri-split-7"));
/// assert!(!supports("tri-split-1") && !supports("no-such-scheme"));
/// ```
pub fn supports(name: &str) -> bool {
    plan(name).is_ok()
}

/// Whether [`subdivide_polygons`] can run the scheme `name` on raw face lists: the schemes
/// with 4:1, 1:N² or Catmull-Clark topology.
///
/// ```
/// use halfedge::subdivide::supports_polygons;
/// assert!(supports_polygons("loop-general") && supports_polygons("catmull-clark-general"));
/// assert!(supports_polygons("tri-split-4") && !supports_polygons("sqrt3"));
/// ```
pub fn supports_polygons(name: &str) -> bool {
    plan(name).is_ok_and(|p| matches!(p.rule, Rule::Tri(..) | Rule::CatmullClark))
}

/// Checks what the scheme's class cannot see: structural needs of the algorithm.
fn check_mesh(plan: &Plan, mesh: &HalfEdgeMesh) -> Result<()> {
    let t = Topo::new(mesh);
    let name = &plan.name;
    let refuse = |reason: String| {
        Err(Error::SchemeNotApplicable {
            scheme: name.to_owned(),
            reason,
        })
    };
    match plan.rule {
        Rule::Tri(..) | Rule::Sqrt3 { .. } => {
            if let Some((f, d)) = t.first_non_triangle() {
                return refuse(format!(
                    "face {f} has {d} vertices, the scheme needs triangles"
                ));
            }
            if plan.rule == (Rule::Sqrt3 { boundary: false }) && t.boundary_edges() > 0 {
                return refuse("the mesh has a boundary; use sqrt3-boundary".into());
            }
        }
        Rule::DooSabin | Rule::MidEdge => {
            if t.boundary_edges() > 0 {
                return refuse("the mesh has a boundary, the scheme needs a closed mesh".into());
            }
            if let Some(v) = (0..t.nv() as u32).find(|&v| t.valence(v) < 3) {
                return refuse(format!(
                    "vertex {v} has valence {}, the scheme needs at least 3 (its vertex face would have fewer than 3 sides)",
                    t.valence(v)
                ));
            }
        }
        Rule::CatmullClark => {}
    }
    Ok(())
}

/// Array sizes of a predicted level, refused when they do not fit 32-bit handles.
fn sizes(c: &LevelCounts, scheme: &str, level: u32) -> Result<Sizes> {
    let limit = BigInt::from(u32::MAX);
    let fits = |what: &'static str, count: &BigInt, factor: u32| -> Result<usize> {
        let scaled = count * factor;
        if scaled.sign() == num_bigint::Sign::Minus || scaled >= limit {
            return Err(Error::TooLarge {
                scheme: scheme.to_owned(),
                level,
                what,
                count: count.clone(),
            });
        }
        // Below u32::MAX, so it fits usize.
        Ok(u32::try_from(&scaled).map_or(0, |v| v as usize))
    };
    Ok(Sizes {
        vertices: fits("vertices", &c.vertices, 1)?,
        halfedges: fits("edges", &c.edges, 2)?,
        faces: fits("faces", &c.faces, 1)?,
    })
}

/// One level: `level` is the level being built (1-based).
fn step(
    plan: &Plan,
    template: Option<&Template>,
    mesh: &HalfEdgeMesh,
    level: u32,
    expected: Sizes,
    opts: &SubdivideOptions<'_>,
) -> Result<HalfEdgeMesh> {
    let ctx = StepContext {
        scheme: &plan.name,
        level,
        expected,
        parallel: opts.threads != 1,
    };
    if !opts.preallocate {
        return built_by_faces::<true>(plan, template, mesh, &ctx);
    }
    match (plan.rule, template) {
        (Rule::Tri(rule, 2), Some(t)) => gather::four_to_one(mesh, t, rule, &ctx),
        (Rule::CatmullClark, _) => gather::catmull_clark(mesh, &ctx),
        (Rule::Sqrt3 { .. }, _) if mesh.is_closed() => gather::sqrt3_closed(mesh, &ctx),
        (Rule::DooSabin, _) => gather::doo_sabin(mesh, &ctx),
        (Rule::MidEdge, _) => gather::mid_edge(mesh, &ctx),
        _ => built_by_faces::<false>(plan, template, mesh, &ctx),
    }
}

/// One level built face by face ([`build::Builder`]): into arrays of the predicted lengths,
/// or growing ones with `GROW`.
fn built_by_faces<const GROW: bool>(
    plan: &Plan,
    template: Option<&Template>,
    mesh: &HalfEdgeMesh,
    ctx: &StepContext<'_>,
) -> Result<HalfEdgeMesh> {
    match (plan.rule, template) {
        (Rule::Tri(rule, _), Some(t)) => trisplit::tri_split::<GROW>(mesh, t, rule, ctx),
        (Rule::Tri(..), None) => Err(ctx.invalid("no split template".into())),
        (Rule::CatmullClark, _) => catmull_clark::catmull_clark::<GROW>(mesh, ctx),
        (Rule::Sqrt3 { boundary }, _) => {
            sqrt3::sqrt3::<GROW>(mesh, boundary && ctx.level % 2 == 0, ctx)
        }
        (Rule::DooSabin, _) => dual::doo_sabin::<GROW>(mesh, ctx),
        (Rule::MidEdge, _) => dual::mid_edge::<GROW>(mesh, ctx),
    }
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

/// Subdivides `mesh` `levels` times with the built-in scheme `scheme` (a canonical name, an
/// alias such as `midpoint` or `ternary`, or `tri-split-N`).
///
/// Each level's arrays are allocated once with the lengths the scheme predicts
/// ([`schemes::Scheme::counts_at`]) and checked afterwards; only levels `s - 1` and `s` are
/// alive at a time. `levels = 0` returns a copy of the input.
///
/// # Errors
///
/// - [`Error::Scheme`] for an unknown name or a mesh outside the scheme's class (e.g. a quad
///   under `loop`, a boundary under `sqrt3`), with the scheme crate's suggestion;
/// - [`Error::UnsupportedScheme`] for a scheme without real subdivision;
/// - [`Error::SchemeNotApplicable`] when the algorithm cannot run (a vertex of valence 2 under
///   a dual scheme);
/// - [`Error::TooLarge`] when a level would not fit 32-bit handles;
/// - [`Error::ThreadPool`] when the requested threads cannot be started;
/// - [`Error::PredictionMismatch`] / [`Error::InvalidOutput`]: bugs.
///
/// ```
/// use halfedge::subdivide::{subdivide, SubdivideOptions};
/// use halfedge::{shapes, HalfEdgeMesh};
///
/// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
/// let smooth = subdivide(&cube, "catmull-clark", 2, &SubdivideOptions::default())?;
/// assert_eq!((smooth.n_vertices(), smooth.n_edges(), smooth.n_faces()), (98, 192, 96));
/// let err = subdivide(&cube, "loop", 1, &SubdivideOptions::default()).unwrap_err();
/// assert!(err.to_string().contains("triangle"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn subdivide(
    mesh: &HalfEdgeMesh,
    scheme: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<HalfEdgeMesh> {
    let counts = mesh.counts();
    let plan = plan(scheme)?.for_mesh(&counts);
    run_levels(&plan, mesh, &counts, levels, opts, |_, _| Ok(()))
}

/// The last level of [`subdivide_to_face_list`]: the subdivided mesh as a face list.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct FaceListLevel {
    /// Positions and faces, numbered exactly as [`HalfEdgeMesh::to_polygon_mesh`] numbers the
    /// mesh [`subdivide`] returns (same vertices, faces in the same order, each face from the
    /// same corner).
    pub mesh: PolygonMesh,
    /// The number of edges of the level: counted by the construction from the half-edge mesh
    /// of the level before (4:1: `2E + 3F`; Catmull-Clark: `2E` plus one per face corner), or
    /// read off the half-edge mesh for the schemes built that way.
    pub edges: usize,
}

/// `Some(d)` when [`subdivide_to_face_list`] writes the last level of `name` straight into a
/// face list, every face with `d` corners (the 4:1 family: 3; Catmull-Clark: 4); `None` for
/// the schemes whose last level is built as a half-edge mesh and converted (and for unknown
/// names).
///
/// ```
/// use halfedge::subdivide::direct_face_degree;
/// assert_eq!(direct_face_degree("loop"), Some(3));
/// assert_eq!(direct_face_degree("butterfly"), Some(3));
/// assert_eq!(direct_face_degree("catmull-clark-quad"), Some(4));
/// assert_eq!(direct_face_degree("sqrt3"), None);
/// assert_eq!(direct_face_degree("tri-split-3"), None);
/// assert_eq!(direct_face_degree("no-such-scheme"), None);
/// ```
pub fn direct_face_degree(name: &str) -> Option<usize> {
    plan(name).ok().and_then(|p| p.direct_face_degree())
}

/// Subdivides like [`subdivide`], with the last level written as a face list
/// ([`PolygonMesh`]) instead of a half-edge mesh.
///
/// For the schemes of [`direct_face_degree`] (with [`SubdivideOptions::preallocate`] on) the
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
/// use halfedge::subdivide::{subdivide, subdivide_to_face_list, SubdivideOptions};
/// use halfedge::{shapes, HalfEdgeMesh};
///
/// let ico = HalfEdgeMesh::try_from(&shapes::icosahedron())?;
/// let opts = SubdivideOptions::default();
/// let level = subdivide_to_face_list(&ico, "loop", 2, &opts)?;
/// assert_eq!((level.mesh.n_vertices(), level.edges, level.mesh.n_faces()), (162, 480, 320));
/// assert_eq!(level.mesh, subdivide(&ico, "loop", 2, &opts)?.to_polygon_mesh());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn subdivide_to_face_list(
    mesh: &HalfEdgeMesh,
    scheme: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<FaceListLevel> {
    let counts = mesh.counts();
    let plan = plan(scheme)?.for_mesh(&counts);
    let convert = |m: &HalfEdgeMesh| FaceListLevel {
        mesh: m.to_polygon_mesh(),
        edges: m.n_edges(),
    };
    drive(
        &plan,
        mesh,
        &counts,
        levels,
        opts,
        |_, _| Ok(()),
        |input, s, sizes, template| {
            let ctx = StepContext {
                scheme: &plan.name,
                level: s,
                expected: sizes,
                parallel: opts.threads != 1,
            };
            let direct = match (plan.rule, template) {
                _ if !opts.preallocate => None,
                (Rule::Tri(rule, 2), Some(t)) => Some(to_faces::four_to_one(input, t, rule, &ctx)?),
                (Rule::CatmullClark, _) => Some(to_faces::catmull_clark(input, &ctx)?),
                _ => None,
            };
            match direct {
                Some((mesh, edges)) => Ok(FaceListLevel { mesh, edges }),
                None => Ok(convert(&step(&plan, template, input, s, sizes, opts)?)),
            }
        },
        convert,
    )
}

/// Defines the public shorthands for [`subdivide`] with one scheme: `name => "scheme"`, or
/// `name => "closed" or "open"` for a scheme on closed meshes and its variant for meshes with a
/// boundary; the string before the name completes the "As [`subdivide`]" of the errors.
/// (A macro: functions cannot define functions.)
macro_rules! shorthands {
    ($($(#[doc = $doc:literal])* $errors:literal $fn:ident => $closed:literal $(or $open:literal)?;)*) => {$(
        $(#[doc = $doc])*
        ///
        /// # Errors
        ///
        #[doc = concat!("As [`subdivide`]", $errors, ".")]
        pub fn $fn(
            mesh: &HalfEdgeMesh,
            levels: u32,
            opts: &SubdivideOptions<'_>,
        ) -> Result<HalfEdgeMesh> {
            let name = $closed;
            $(let name = if mesh.is_closed() { name } else { $open };)?
            subdivide(mesh, name, levels, opts)
        }
    )*};
}

shorthands! {
    /// Loop subdivision (`loop`, or `loop-boundary` when the mesh has a boundary): Loop's
    /// weights, boundary curves as cubic B-splines.
    ///
    /// ```
    /// use halfedge::subdivide::{loop_subdivide, SubdivideOptions};
    /// let grid = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::grid(2, 2)?)?;
    /// let out = loop_subdivide(&grid, 2, &SubdivideOptions::default())?;
    /// assert_eq!(out.n_faces(), 8 * 16);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    " (e.g. a face that is not a triangle)" loop_subdivide => "loop" or "loop-boundary";

    /// Plain 4:1 split with edge midpoints (`midpoint`), old vertices kept.
    "" midpoint_subdivide => "midpoint";

    /// 4:1 split with the edge midpoints projected onto the unit sphere (`icosphere`).
    "" icosphere_subdivide => "icosphere";

    /// The modified butterfly scheme (`butterfly`, interpolating; boundary rules in the module
    /// docs of the implementation).
    "" butterfly_subdivide => "butterfly";

    /// Catmull-Clark subdivision on any polygon mesh, with boundary rules (`catmull-clark`).
    ///
    /// ```
    /// use halfedge::subdivide::{catmull_clark_subdivide, SubdivideOptions};
    /// let mixed = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::mixed())?;
    /// let out = catmull_clark_subdivide(&mixed, 1, &SubdivideOptions::default())?;
    /// assert!(out.is_quad_mesh());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    "" catmull_clark_subdivide => "catmull-clark";

    /// Kobbelt's √3 subdivision (`sqrt3`, or `sqrt3-boundary` with Kobbelt's boundary rule when
    /// the mesh has a boundary).
    "" sqrt3_subdivide => "sqrt3" or "sqrt3-boundary";

    /// Doo-Sabin subdivision on closed polygon meshes (`doo-sabin`).
    " (a boundary, or a vertex of valence below 3)" doo_sabin_subdivide => "doo-sabin";

    /// Peters-Reif mid-edge subdivision on closed polygon meshes (`mid-edge`).
    " (a boundary, or a vertex of valence below 3)" mid_edge_subdivide => "mid-edge";
}

/// The 1:N² triangle split (`tri-split-N`) with points on the flat triangles.
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
    subdivide(mesh, &format!("tri-split-{n}"), levels, opts)
}

/// The level loop shared by [`subdivide`] and [`verify`]; `visit(level, mesh)` sees every
/// level built.
fn run_levels(
    plan: &Plan,
    mesh: &HalfEdgeMesh,
    counts: &MeshCounts,
    levels: u32,
    opts: &SubdivideOptions<'_>,
    visit: impl FnMut(u32, &HalfEdgeMesh) -> Result<()> + Send,
) -> Result<HalfEdgeMesh> {
    drive(
        plan,
        mesh,
        counts,
        levels,
        opts,
        visit,
        |input, s, sizes, template| step(plan, template, input, s, sizes, opts),
        HalfEdgeMesh::clone,
    )
}

/// What the last level of [`drive`] is built as.
trait LastLevel: Send {
    /// Vertices, edges and faces.
    fn vef(&self) -> [usize; 3];
    /// The vertex positions.
    fn positions(&self) -> &[DVec3];
    /// The half-edge mesh, when the level is one (for the level visitor).
    fn as_halfedge(&self) -> Option<&HalfEdgeMesh>;
}

impl LastLevel for HalfEdgeMesh {
    fn vef(&self) -> [usize; 3] {
        [self.n_vertices(), self.n_edges(), self.n_faces()]
    }
    fn positions(&self) -> &[DVec3] {
        HalfEdgeMesh::positions(self)
    }
    fn as_halfedge(&self) -> Option<&HalfEdgeMesh> {
        Some(self)
    }
}

impl LastLevel for FaceListLevel {
    fn vef(&self) -> [usize; 3] {
        [self.mesh.n_vertices(), self.edges, self.mesh.n_faces()]
    }
    fn positions(&self) -> &[DVec3] {
        &self.mesh.positions
    }
    fn as_halfedge(&self) -> Option<&HalfEdgeMesh> {
        None
    }
}

/// Checks the scheme and every level's size, builds levels `1..levels` as half-edge meshes
/// (only two alive at a time) and the last one with `last`; `level0` answers `levels = 0`.
/// `visit` sees every half-edge level, the progress callback every level.
#[allow(clippy::too_many_arguments)]
fn drive<T: LastLevel>(
    plan: &Plan,
    mesh: &HalfEdgeMesh,
    counts: &MeshCounts,
    levels: u32,
    opts: &SubdivideOptions<'_>,
    mut visit: impl FnMut(u32, &HalfEdgeMesh) -> Result<()> + Send,
    last: impl FnOnce(&HalfEdgeMesh, u32, Sizes, Option<&Template>) -> Result<T> + Send,
    level0: impl FnOnce(&HalfEdgeMesh) -> T + Send,
) -> Result<T> {
    plan.scheme.initial_state(counts)?;
    check_mesh(plan, mesh)?;
    let name = &plan.name;
    // Check every level's size before building anything.
    let mut expected = Vec::with_capacity(levels as usize);
    for s in 1..=levels {
        let c = plan.scheme.counts_at(counts, u64::from(s))?;
        expected.push(sizes(&c, name, s)?);
    }
    let Some(&last_sizes) = expected.last() else {
        return Ok(level0(mesh));
    };
    let template = match plan.rule {
        Rule::Tri(_, n) => Some(Template::new(n)),
        _ => None,
    };
    let report = |level: u32, [vertices, edges, faces]: [usize; 3]| {
        if let Some(progress) = opts.progress {
            progress(&LevelDone {
                level,
                levels,
                vertices,
                edges,
                faces,
            });
        }
    };
    with_threads(opts.threads, || {
        let mut current: Option<HalfEdgeMesh> = None;
        for (s, &sizes) in (1..levels).zip(&expected) {
            let input = current.as_ref().unwrap_or(mesh);
            let next = step(plan, template.as_ref(), input, s, sizes, opts)?;
            let before = finite::Before::Mesh(input);
            finite::check_positions(name, plan.rule, s, &before, next.positions())?;
            visit(s, &next)?;
            report(s, next.vef());
            // Level s - 1 is dropped here.
            current = Some(next);
        }
        let input = current.as_ref().unwrap_or(mesh);
        let out = last(input, levels, last_sizes, template.as_ref())?;
        let before = finite::Before::Mesh(input);
        finite::check_positions(name, plan.rule, levels, &before, out.positions())?;
        drop(current);
        if let Some(m) = out.as_halfedge() {
            visit(levels, m)?;
        }
        report(levels, out.vef());
        Ok(out)
    })
}

/// The components a report lists: the state, then `V`, `E`, `F` when not in the state.
fn report_names(scheme: &Scheme) -> Vec<String> {
    let mut names: Vec<String> = scheme.state_names().to_vec();
    for extra in ["V", "E", "F"] {
        if !names.iter().any(|n| n == extra) {
            names.push(extra.to_owned());
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
    let c = scheme.counts_at(counts0, u64::from(level))?;
    let names = report_names(scheme);
    let predicted_value = |name: &str| -> BigInt {
        match scheme.state_names().iter().position(|n| n == name) {
            Some(i) => c.state[i].clone(),
            None => match name {
                "V" => c.vertices.clone(),
                "E" => c.edges.clone(),
                _ => c.faces.clone(),
            },
        }
    };
    let predicted = names
        .iter()
        .map(|n| (n.clone(), predicted_value(n)))
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

/// Really subdivides `mesh` level by level up to `levels` and reports, for level 0 (the input)
/// to `levels`, every state component of the scheme (and `V`, `E`, `F`) as predicted and as
/// counted on the mesh.
///
/// # Errors
///
/// As [`subdivide`].
///
/// ```
/// use halfedge::subdivide::{verify, SubdivideOptions};
/// use halfedge::{shapes, HalfEdgeMesh};
///
/// let grid = HalfEdgeMesh::try_from(&shapes::grid(3, 2)?)?;
/// let reports = verify(&grid, "loop-boundary", 2, &SubdivideOptions::default())?;
/// assert_eq!(reports.len(), 3);
/// assert!(reports.iter().all(|r| r.is_match()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn verify(
    mesh: &HalfEdgeMesh,
    scheme: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<Vec<LevelReport>> {
    let counts = mesh.counts();
    let plan = plan(scheme)?.for_mesh(&counts);
    let mut reports = vec![report(&plan.scheme, &counts, 0, &counts)?];
    run_levels(&plan, mesh, &counts, levels, opts, |s, m| {
        reports.push(report(&plan.scheme, &counts, s, &m.counts())?);
        Ok(())
    })?;
    Ok(reports)
}

/// Subdivides a raw face list (non-manifold allowed) `levels` times with a scheme whose
/// topology is a per-face refinement: 4:1 (`loop-general` and the other Loop names), 1:N²
/// (`tri-split-N`, `ternary`) or Catmull-Clark (`catmull-clark-general`, ...). Topology only:
/// new points are placed linearly (edge points at the midpoint or on the edge, face points at
/// the centroid or on the flat triangle), old vertices stay.
///
/// From level 1 on, vertices no face uses are dropped (level 0 is a copy of the input).
///
/// # Errors
///
/// As [`subdivide`] ([`Error::Scheme`] when the face list is outside the scheme's class, e.g.
/// non-manifold edges under `loop`), and [`Error::UnsupportedScheme`] for the other schemes.
///
/// ```
/// use glam::DVec3;
/// use halfedge::subdivide::{subdivide_polygons, SubdivideOptions};
/// use halfedge::PolygonMesh;
///
/// // Three triangles on one edge: a non-manifold "book".
/// let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y];
/// let book = PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
/// let out = subdivide_polygons(&book, "loop-general", 1, &SubdivideOptions::default())?;
/// assert_eq!((out.n_vertices(), out.n_faces()), (5 + 7, 12));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn subdivide_polygons(
    mesh: &PolygonMesh,
    scheme: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<PolygonMesh> {
    let plan = plan(scheme)?.for_mesh(&crate::stats::face_list_counts(mesh));
    faces::run_levels(&plan, mesh, levels, opts, |_, _| Ok(()))
}

/// [`verify`] for raw face lists: really subdivides with [`subdivide_polygons`] and compares
/// every predicted component with the face-list statistics of each level.
///
/// # Errors
///
/// As [`subdivide_polygons`].
///
/// ```
/// use glam::DVec3;
/// use halfedge::subdivide::{verify_polygons, SubdivideOptions};
/// use halfedge::PolygonMesh;
///
/// let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y];
/// let book = PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
/// let reports = verify_polygons(&book, "tri-split-3", 2, &SubdivideOptions::default())?;
/// assert!(reports.iter().all(|r| r.is_match()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn verify_polygons(
    mesh: &PolygonMesh,
    scheme: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<Vec<LevelReport>> {
    let counts = crate::stats::face_list_counts(mesh);
    let plan = plan(scheme)?.for_mesh(&counts);
    let mut reports = vec![report(&plan.scheme, &counts, 0, &counts)?];
    faces::run_levels(&plan, mesh, levels, opts, |s, m| {
        let measured = crate::stats::face_list_counts(m);
        reports.push(report(&plan.scheme, &counts, s, &measured)?);
        Ok(())
    })?;
    Ok(reports)
}
