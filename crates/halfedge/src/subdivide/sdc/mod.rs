//! Creases and corners under Loop and Catmull-Clark, by OpenSubdiv 3.5's `Sdc` rules: the
//! smooth, dart, crease and corner vertex rules, semi-sharp edges and vertices whose
//! sharpness decays level by level (uniformly or by Chaikin's rule), the fractional blending
//! of two rules where a sharpness decays to zero, Catmark's smooth-triangle rule and the
//! vertex boundary interpolation modes.
//!
//! A [`Sharpness`] is a mesh's tags ([`Tags`]) resolved on its edges and vertices; it goes to
//! [`Refinement::new`](crate::Refinement::new) through
//! [`SubdivideOptions::with_sharpness`](super::SubdivideOptions::with_sharpness), with the
//! options in [`SubdivideOptions::subdivision`](super::SubdivideOptions::subdivision).
//!
//! ```
//! use halfedge::refine::Refinement;
//! use halfedge::subdivide::{Sharpness, SubdivideOptions};
//! use halfedge::tags::{CreaseMethod, SubdivisionOptions, Tags, INFINITELY_SHARP};
//! use halfedge::{shapes, HalfEdgeMesh, Rule};
//!
//! let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
//! let mut tags = Tags::default();
//! tags.add_crease(0, 1, INFINITELY_SHARP)?; // a hard edge
//! tags.add_crease(1, 3, 1.5)?; // a semi-sharp one
//! tags.add_corner(7, 2.0)?;
//! let sharpness = Sharpness::from_tags(&cube, &tags)?;
//! assert_eq!(sharpness.n_sharp_edges(), 2);
//!
//! let options = SubdivideOptions::default()
//!     .with_sharpness(&sharpness)
//!     .with_subdivision(SubdivisionOptions::default().with_crease_method(CreaseMethod::Chaikin));
//! let refinement = Refinement::new(&cube, Rule::CatmullClark, 2, &options)?;
//! let base: Vec<[f64; 3]> = cube.positions().iter().map(|p| p.to_array()).collect();
//! let mut out = vec![[0.0; 3]; refinement.n_vertices(2)];
//! refinement.evaluate(&base, &mut out)?;
//! // A sharp corner vertex of sharpness 2 stays where it is for two levels.
//! assert_eq!(out[7], base[7]);
//!
//! // A crease that is not an edge is refused, naming it.
//! let mut bad = Tags::default();
//! bad.add_crease(0, 6, 1.0)?;
//! let err = Sharpness::from_tags(&cube, &bad).unwrap_err();
//! assert_eq!(err.to_string(), "crease (0, 6) is not an edge of the mesh");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # What OpenSubdiv does, and so this module
//!
//! - Boundary edges are infinitely sharp under every boundary mode (`Sdc::Crease::
//!   SharpenBoundaryEdge`). `edge` (`VTX_BOUNDARY_EDGE_ONLY`) stops there;
//!   `edge-and-corner` also makes every boundary vertex of one face an infinitely sharp
//!   corner; `none` computes the same positions as `edge` (OpenSubdiv only tags the faces
//!   around boundary vertices as holes, which changes what is output, not where the vertices
//!   go; holes are not handled here).
//! - Sharpness values are `f32`; each level subtracts 1 from semi-sharp values (the vertex
//!   sharpness always, edges under [`CreaseMethod::Uniform`]) or, for edges under
//!   [`CreaseMethod::Chaikin`], takes 3/4 of the edge's value plus 1/4 of the average of the
//!   other semi-sharp edges at the child's end vertex, less 1. Values of 10 and above are
//!   infinite and stay.
//! - A vertex's rule: corner when the vertex is sharp or has more than two sharp edges, crease
//!   with two, dart with one, smooth with none. The crease mask is `3/4, 1/8, 1/8` along the
//!   two sharp edges, the corner mask keeps the vertex, dart and smooth vertices take the
//!   scheme's smooth mask. When the child's rule differs, the two masks are blended by the
//!   average of the sharpness values that decay to zero (clamped to 1).
//! - An edge's point is the midpoint while both its children are sharp, the smooth point
//!   where the edge is smooth, and a blend of the two weighted by the edge's sharpness
//!   otherwise.
//! - [`TriangleRule::Smooth`] (Catmull-Clark only) weights the face points of an edge next to
//!   a triangle by 0.47 instead of 0.25.
//!
//! The weights are computed in `f64` from the `f32` sharpness values and fractional weights,
//! as OpenSubdiv's `PrimvarRefinerReal<double>` does; positions agree with it to about 1e-15
//! of the bounding box (`tests/opensubdiv.rs`).
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `subdivide/sdc/` (`halfedge::subdivide::sdc`): creases and corners for Loop and Catmull-Clark
//! by OpenSubdiv 3.5's `Sdc` rules. `Refinement::new` takes a `Sharpness` and `SubdivisionOptions`
//! from `SubdivideOptions`; when they change something on the mesh (`Creases::new` decides), each
//! level keeps its flattened tables (or, for a face-varying channel under `all`, linear ones:
//! `tables.rs`' `LinearTables`) and a sparse `WeightTable` of the child vertices whose crease mask
//! differs from the rule's, written over the tables' values (`Creases::level_table`,
//! `LevelTable::Overrides`); a level where they are more than half the rows, or the two together
//! exceed the bound of `predicted_bytes_with_creases`, is one dense `WeightTable` instead (every
//! child vertex as sparse weights of the parent's vertices, Catmull-Clark's face points expanded),
//! except on a level with a face of more than 32 sides (`sdc::DENSE_MAX_DEGREE`), where expanding
//! its face point would be quadratic in its degree: that level keeps the overrides, and an
//! overriding row names such a face by its child point (one entry, read from the child level the
//! base rule has just computed; a zero weight names nothing), so that its rows and the guard's
//! bound (4 entries per side of a wide face instead of `d`) are linear in the degree. The rows are
//! built from the parent's connectivity and its `LevelSharpness` (per edge and vertex, and the
//! edge order OpenSubdiv sums `f32` sharpness in); the next level's sharpness is read off the
//! child's edges by their end vertices (vertex child and edge child). Otherwise the fast path
//! above runs unchanged. The differential tests hold it to OpenSubdiv on the tagged shared meshes
//! and generated grids (`tests/opensubdiv.rs`); `tests/integration/creases.rs` keeps values
//! recorded from OpenSubdiv for `cargo test` alone.
//!
//! Owner of crease rules: sharpness resolved on a mesh, OpenSubdiv's vertex rules, sharpness decay
//! (uniform, Chaikin), fractional blending, boundary modes, smooth triangles:
//! `halfedge::subdivide::sdc` (`crates/halfedge/src/subdivide/sdc/`: `Sharpness`, `crease.rs` the
//! `f32` arithmetic, `masks.rs` the per-level weight tables); `halfedge::tags` describes creases
//! and options.

mod crease;
mod masks;
pub(crate) mod sharpness;

use crate::mesh::{EdgeId, VertexId};
use crate::subdivide::topo::Topo;
use crate::tags::{BoundaryInterpolation, SubdivisionOptions, Tags, TriangleRule};
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result, Rule};

pub(crate) use self::crease::is_infinite;
pub(crate) use self::masks::{boundary_first, ccw_ring, Base, WeightTable};
use self::masks::{LevelBuilder, LevelSharpness, Scheme};
pub use self::sharpness::Sharpness;

#[cfg(doc)]
use crate::tags::CreaseMethod;

/// `v` when a mesh of `vertices` vertices has it, else [`Error::TagVertexOutOfRange`] for the
/// tag kind `what`.
fn tag_vertex(what: &'static str, v: u32, vertices: usize) -> Result<u32> {
    if (v as usize) < vertices {
        Ok(v)
    } else {
        Err(Error::TagVertexOutOfRange {
            what,
            vertex: v,
            vertices,
        })
    }
}

impl Sharpness {
    /// No sharpness on `mesh`: every edge and vertex smooth.
    pub fn smooth(mesh: &HalfEdgeMesh) -> Sharpness {
        Sharpness {
            edges: vec![0.0; mesh.n_edges()],
            vertices: vec![0.0; mesh.n_vertices()],
        }
    }

    /// The creases and corners of `tags` on `mesh`, whose vertex indices are the mesh's (the
    /// file's, when no vertex of the file was dropped for being in no face; else see
    /// [`Sharpness::from_tags_of`]). A later value for the same edge or vertex replaces an
    /// earlier one. Holes and options are not read.
    ///
    /// # Errors
    ///
    /// [`Error::TagVertexOutOfRange`] for a vertex the mesh does not have;
    /// [`Error::CreaseNotAnEdge`] for a crease whose two vertices no edge joins.
    pub fn from_tags(mesh: &HalfEdgeMesh, tags: &Tags) -> Result<Sharpness> {
        Sharpness::resolve(mesh, tags, Some)
    }

    /// As [`Sharpness::from_tags`], for tags numbering the vertices of `source`, the face
    /// list `mesh` was built from (which drops the vertices no face uses, renumbering the
    /// others in order). A corner on a vertex in no face has no effect and is skipped.
    ///
    /// # Errors
    ///
    /// As [`Sharpness::from_tags`] (vertices counted in `source`, a crease on a vertex in no
    /// face is not an edge); [`Error::SharpnessMismatch`] when `mesh` was not built from
    /// `source`.
    pub fn from_tags_of(
        source: &PolygonMesh,
        mesh: &HalfEdgeMesh,
        tags: &Tags,
    ) -> Result<Sharpness> {
        let mut used = vec![false; source.n_vertices()];
        for &v in source.face_indices() {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
        let mut new_of_old = Vec::with_capacity(used.len());
        let mut next = 0u32;
        for &u in &used {
            new_of_old.push(u.then_some(next));
            next += u32::from(u);
        }
        if next as usize != mesh.n_vertices() {
            return Err(Error::SharpnessMismatch {
                edges: mesh.n_edges(),
                vertices: next as usize,
                mesh_edges: mesh.n_edges(),
                mesh_vertices: mesh.n_vertices(),
            });
        }
        let n = source.n_vertices();
        let check = |what: &'static str, v: u32| tag_vertex(what, v, n);
        for c in tags.creases() {
            check("crease", c.a)?;
            check("crease", c.b)?;
            if new_of_old[c.a as usize].is_none() || new_of_old[c.b as usize].is_none() {
                return Err(Error::CreaseNotAnEdge { a: c.a, b: c.b });
            }
        }
        for c in tags.corners() {
            check("corner", c.vertex)?;
        }
        Sharpness::resolve(mesh, tags, |v| new_of_old[v as usize])
    }

    fn resolve(
        mesh: &HalfEdgeMesh,
        tags: &Tags,
        to_mesh: impl Fn(u32) -> Option<u32>,
    ) -> Result<Sharpness> {
        let t = Topo::new(mesh);
        let nv = mesh.n_vertices();
        let mut sharpness = Sharpness::smooth(mesh);
        let in_range = |what: &'static str, v: u32| tag_vertex(what, v, nv);
        for c in tags.creases() {
            let not_an_edge = Error::CreaseNotAnEdge { a: c.a, b: c.b };
            let (Some(a), Some(b)) = (to_mesh(c.a), to_mesh(c.b)) else {
                return Err(not_an_edge);
            };
            let (a, b) = (in_range("crease", a)?, in_range("crease", b)?);
            let mut edge = None;
            t.for_outgoing(a, |h| {
                if t.target(h) == b {
                    edge = Some(h >> 1);
                }
            });
            let Some(e) = edge else {
                return Err(not_an_edge);
            };
            sharpness.edges[e as usize] = c.sharpness;
        }
        for c in tags.corners() {
            if let Some(v) = to_mesh(c.vertex) {
                let v = in_range("corner", v)?;
                sharpness.vertices[v as usize] = c.sharpness;
            }
        }
        Ok(sharpness)
    }

    /// The sharpness of every edge, indexed by [`EdgeId`].
    pub fn edges(&self) -> &[f32] {
        &self.edges
    }

    /// The sharpness of every vertex, indexed by [`VertexId`].
    pub fn vertices(&self) -> &[f32] {
        &self.vertices
    }

    /// The sharpness of edge `e` (0 beyond the mesh).
    pub fn edge(&self, e: EdgeId) -> f32 {
        self.edges.get(e.idx()).copied().unwrap_or(0.0)
    }

    /// The sharpness of vertex `v` (0 beyond the mesh).
    pub fn vertex(&self, v: VertexId) -> f32 {
        self.vertices.get(v.idx()).copied().unwrap_or(0.0)
    }
}

/// The largest face degree of a level that may be refined by a dense weight table: its
/// Catmull-Clark rows expand the face points, so a face of degree `d` puts `d` entries in each
/// of its `d` edge rows and `d` vertex rows, `d²` in all. A level with a wider face keeps the
/// rule's tables and overrides the rows that differ, whatever their number (linear in the
/// degree for the infinitely sharp and crease rows of a face-varying channel).
pub(crate) const DENSE_MAX_DEGREE: usize = 32;

/// The entries a face of more than [`DENSE_MAX_DEGREE`] sides counts per side in
/// [`table_bytes_bound`] (in place of its degree): an overriding row names it by its child
/// point, one entry, next to the row's own vertices.
const WIDE_FACE_ENTRIES: u32 = 4;

/// Whether level `t` has a face of more than [`DENSE_MAX_DEGREE`] sides.
pub(crate) fn has_wide_face(t: &Topo<'_>) -> bool {
    (0..t.nf() as u32).any(|f| t.face_degree(f) > DENSE_MAX_DEGREE)
}

/// The scheme of a weight table, for [`table_bytes_bound`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TableScheme {
    Loop,
    CatmullClark,
}

/// An upper bound of the bytes of the weight table refining level `level` (counts `c`) of a
/// mesh with base counts `base`: every row at most its smooth size. Loop: a vertex row holds
/// the vertex and its neighbours (`V + 2E` entries in all), an edge row 4 (2 on the boundary).
/// Catmull-Clark: a vertex row the vertex and the distinct vertices of its faces (at most
/// `sum over its faces of (degree - 1) - valence + 2`), an edge row the corners of its two
/// faces (`deg f1 + deg f2 - 2`, 2 on the boundary), a face row its corners. The sums of
/// squared face degrees come from the base's faces by degree at level 0 and are `16 F` (quads)
/// after. 12 bytes per entry, 4 per row and one.
///
/// A level with a face of more than [`DENSE_MAX_DEGREE`] sides never gets the dense table, and
/// its overriding rows name such a face by its child point, one entry, rather than by its
/// corners: a wide face of degree `d` counts `d WIDE_FACE_ENTRIES` instead of `d²` (linear in
/// the degree: per corner, the face's entry in the vertex row, and per side its entry in the
/// edge row with the two ends the sums above count once). With `dense_only_narrow` (a
/// face-varying channel) it counts `d min(d, DENSE_MAX_DEGREE)`, as before.
pub(crate) fn table_bytes_bound(
    scheme: TableScheme,
    base: &schemes::MeshCounts,
    level: u32,
    c: &schemes::LevelCounts,
    dense_only_narrow: bool,
) -> num_bigint::BigInt {
    use num_bigint::BigInt;
    let (v, e, f) = (&c.vertices, &c.edges, &c.faces);
    // Boundary edges double at each level under both schemes.
    let boundary = BigInt::from(base.boundary_edges) << level;
    let interior = e - &boundary;
    let (entries, rows) = match scheme {
        TableScheme::Loop => (v + e * 2u32 + &interior * 4u32 + &boundary * 2u32, v + e),
        TableScheme::CatmullClark => {
            let (squares, corners) = if level == 0 {
                let squares: BigInt = base
                    .faces_by_degree
                    .iter()
                    .map(|(&d, &n)| {
                        let cap = if dense_only_narrow {
                            d.min(DENSE_MAX_DEGREE as u32)
                        } else if d > DENSE_MAX_DEGREE as u32 {
                            WIDE_FACE_ENTRIES
                        } else {
                            d
                        };
                        BigInt::from(d) * cap * n
                    })
                    .sum();
                (squares, BigInt::from(base.corners))
            } else {
                (f * 16u32, f * 4u32)
            };
            let vertex_rows = v * 3u32 + &squares - &corners - e * 2u32;
            let edge_rows = &squares - &interior * 2u32 + &boundary * 2u32;
            (vertex_rows + edge_rows + &corners, v + e + f)
        }
    };
    entries * 12u32 + (rows + 1u32) * 4u32
}

/// What a face-varying channel interpolates linearly at every level
/// (`FVarLinearInterpolation`'s `boundaries` and `all`), on top of its sharpness.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum Linear {
    /// Nothing beyond the sharpness (the surface, and the channels of the other modes).
    #[default]
    Nothing,
    /// Every boundary vertex of the channel is a corner, at every level.
    Boundaries,
    /// Every vertex is a corner and every edge point a midpoint (bilinear).
    All,
}

/// How a level under crease rules is refined.
#[derive(Debug)]
pub(crate) enum LevelTable {
    /// Every child vertex as weights of the parent's vertices.
    Dense(WeightTable),
    /// The base rule, then the rows of the table (the child vertices where the crease rules
    /// differ from it) written over its values.
    Overrides(Base, WeightTable),
}

/// The crease rules of a refinement: the sharpness of the levels still to be flattened.
#[derive(Debug)]
pub(crate) struct Creases {
    scheme: Scheme,
    options: SubdivisionOptions,
    linear: Linear,
    /// Per level: its sharpness, until its weight table is built.
    levels: Vec<Option<LevelSharpness>>,
    /// Per level: the bytes a refinement may keep for it ([`Creases::set_budgets`]).
    budgets: Vec<usize>,
}

/// Whether Catmull-Clark's smooth triangle rule changes anything on `t` under `rule`: the rule
/// is Catmull-Clark, `options` ask for it and `t` has a triangle.
fn smooth_triangles(t: &Topo<'_>, rule: Rule, options: &SubdivisionOptions) -> bool {
    rule == Rule::CatmullClark
        && options.triangle_rule == TriangleRule::Smooth
        && (0..t.nf() as u32).any(|f| t.face_degree(f) == 3)
}

impl Creases {
    /// The crease rules of `rule` on `mesh`, or `None` when they give what the rule's own
    /// kernels give (no sharpness, no corner to sharpen, no triangle to smooth): the fast path.
    ///
    /// # Errors
    ///
    /// [`Error::CreasesNotSupported`] for a rule other than Loop and Catmull-Clark when they
    /// would apply; [`Error::SharpnessMismatch`] for a sharpness of another mesh.
    pub(crate) fn new(
        mesh: &HalfEdgeMesh,
        rule: Rule,
        sharpness: Option<&Sharpness>,
        options: &SubdivisionOptions,
    ) -> Result<Option<Creases>> {
        let t = Topo::new(mesh);
        if let Some(s) = sharpness {
            if s.edges.len() != mesh.n_edges() || s.vertices.len() != mesh.n_vertices() {
                return Err(Error::SharpnessMismatch {
                    edges: s.edges.len(),
                    vertices: s.vertices.len(),
                    mesh_edges: mesh.n_edges(),
                    mesh_vertices: mesh.n_vertices(),
                });
            }
        }
        let sharp = sharpness.is_some_and(|s| !s.is_smooth());
        let corners = options.boundary == BoundaryInterpolation::EdgeAndCorner
            && (0..t.nv() as u32).any(|v| t.is_boundary_vertex(v) && t.valence(v) == 2);
        let triangles = smooth_triangles(&t, rule, options);
        if !(sharp || corners || triangles) {
            return Ok(None);
        }
        let Some(scheme) = Scheme::of(rule) else {
            return Err(Error::CreasesNotSupported {
                rule: rule.to_string(),
                what: if sharp {
                    "creases and corners"
                } else if corners {
                    "the edge-and-corner boundary"
                } else {
                    "the smooth triangle rule"
                },
            });
        };
        let smooth;
        let given = match sharpness {
            Some(s) => s,
            None => {
                smooth = Sharpness::smooth(mesh);
                &smooth
            }
        };
        let base = LevelSharpness::base(&t, &given.edges, &given.vertices, options);
        Ok(Some(Creases::from_base(
            scheme,
            *options,
            Linear::Nothing,
            base,
        )))
    }

    /// The crease rules of a face-varying channel ([`refine::face_varying`](crate::refine::face_varying)):
    /// `mesh` is the channel's own topology (the UV layout, its boundary the surface's
    /// boundary and the seams), `edges` and `vertices` its sharpness (boundary edges are made
    /// infinitely sharp here), under `options` (whose boundary mode is ignored: the channel's
    /// corners come in `vertices`) and `linear`. `None` when the rule's own kernels give the
    /// same values.
    pub(crate) fn for_channel(
        mesh: &HalfEdgeMesh,
        rule: Rule,
        edges: &[f32],
        vertices: &[f32],
        options: &SubdivisionOptions,
        linear: Linear,
    ) -> Result<Option<Creases>> {
        let t = Topo::new(mesh);
        let options = SubdivisionOptions {
            boundary: BoundaryInterpolation::Edge,
            ..*options
        };
        let sharp = edges.iter().chain(vertices).any(|&s| s > 0.0);
        let triangles = smooth_triangles(&t, rule, &options);
        if !(sharp || triangles || linear != Linear::Nothing) {
            return Ok(None);
        }
        let Some(scheme) = Scheme::of(rule) else {
            return Err(Error::UvsNotSupported {
                rule: rule.to_string(),
            });
        };
        let base = LevelSharpness::base(&t, edges, vertices, &options);
        Ok(Some(Creases::from_base(scheme, options, linear, base)))
    }

    /// The crease rules from the sharpness `base` of the first level.
    fn from_base(
        scheme: Scheme,
        options: SubdivisionOptions,
        linear: Linear,
        base: LevelSharpness,
    ) -> Creases {
        Creases {
            scheme,
            options,
            linear,
            levels: vec![Some(base)],
            budgets: Vec::new(),
        }
    }

    /// Records the sharpness of level `level + 1`, built as `child` from level `level`
    /// (`parent`).
    pub(crate) fn push_child(&mut self, level: usize, parent: &Topo<'_>, child: &Topo<'_>) {
        let next = match self.levels.get(level) {
            Some(Some(sharp)) => {
                LevelBuilder::new(*parent, sharp, self.scheme, &self.options, self.linear)
                    .child_sharpness(child)
            }
            _ => return,
        };
        if self.levels.len() <= level + 1 {
            self.levels.resize_with(level + 2, || None);
        }
        self.levels[level + 1] = Some(next);
    }

    /// Sets the bytes a refinement may keep for each level's tables (entry `s`: level `s`,
    /// the bound of [`table_bytes_bound`]); a level without one has no limit.
    pub(crate) fn set_budgets(&mut self, budgets: Vec<usize>) {
        self.budgets = budgets;
    }

    /// The bytes a refinement may keep for level `level`'s tables.
    pub(crate) fn budget(&self, level: usize) -> usize {
        self.budgets.get(level).copied().unwrap_or(usize::MAX)
    }

    /// What refines level `level` (`t`) into the next one, the level's sharpness kept: the rows
    /// where the crease rules do not give what the level's [`Base`] gives, when
    /// `sparse(rows, children)` accepts their number, else every child vertex's row; `None`
    /// for a level without sharpness.
    pub(crate) fn level_table(
        &self,
        level: usize,
        t: &Topo<'_>,
        parallel: bool,
        sparse: impl FnOnce(usize, usize) -> bool,
    ) -> Result<Option<LevelTable>> {
        let Some(Some(sharp)) = self.levels.get(level) else {
            return Ok(None);
        };
        let builder = LevelBuilder::new(*t, sharp, self.scheme, &self.options, self.linear);
        let rows = builder.override_rows();
        Ok(Some(if sparse(rows.len(), builder.n_rows()) {
            LevelTable::Overrides(builder.base(), builder.overrides(rows, parallel)?)
        } else {
            LevelTable::Dense(builder.weights(parallel)?)
        }))
    }

    /// Drops the sharpness of level `level` (its table is built, its child's recorded).
    pub(crate) fn release(&mut self, level: usize) {
        if let Some(sharp) = self.levels.get_mut(level) {
            *sharp = None;
        }
    }
}
