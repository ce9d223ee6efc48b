//! The crease rules of a refinement ([`Creases`]): the sharpness of each level still to be
//! flattened, what refines a level under them ([`LevelTable`]: a dense weight table or the
//! rows overriding the rule's kernels) and the bound of those tables' bytes. The rules
//! themselves (masks, decay, vertex rules) are [`sdc`](crate::subdivide::sdc)'s;
//! `level.rs` walks a level's topology and applies them.

mod level;

use self::level::LevelBuilder;
pub(crate) use self::level::{boundary_first, ccw_ring, LevelSharpness};
use crate::subdivide::sdc::masks::Scheme;
use crate::subdivide::sdc::sharpness::Sharpness;
use crate::subdivide::topo::Topo;
use crate::subdivide::weights::{Base, WeightTable};
use crate::tags::{BoundaryInterpolation, SubdivisionOptions, TriangleRule};
use crate::{Error, HalfEdgeMesh, Result, Rule};

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
    scheme: Scheme,
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
        Scheme::Loop => (v + e * 2u32 + &interior * 4u32 + &boundary * 2u32, v + e),
        Scheme::CatmullClark => {
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

    /// The sharpness of level `level`, while it is kept (the limit's walk reads the last
    /// level's: `refine/limit.rs`).
    pub(crate) fn level(&self, level: usize) -> Option<&LevelSharpness> {
        self.levels.get(level)?.as_ref()
    }

    /// What the rules interpolate linearly.
    pub(crate) fn linear(&self) -> Linear {
        self.linear
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
