//! The limit surface at a refinement's last level, as OpenSubdiv's `PrimvarRefiner::Limit`:
//! each vertex's limit position and two limit tangents as weights of the level's vertices
//! (a [`LimitTable`]), by the limit masks of [`sdc`](crate::subdivide::sdc)'s `limit.rs`
//! under the vertex's rule at that level.
//!
//! The masks' weights are listed from a vertex's leading edge, and OpenSubdiv's leading edge
//! comes from its numbering of every level (`Vtr`), which is not `halfedge`'s. A
//! [`LimitWalk`] follows the refinement level by level and keeps, in `halfedge`'s half-edges,
//! what decides it in OpenSubdiv ([`Order`]): each vertex's leading edge, each edge's first
//! face and each face's first corner. At level 0 they are those of the face list (a vertex's
//! first face is its lowest-numbered one, a boundary vertex leads with the boundary edge its
//! face follows, an edge's first face is its lowest-numbered); each later level takes them
//! from its parent by `Vtr`'s rules for the children of vertices, edges and faces (the
//! refinements `QuadRefinement` and `TriRefinement`):
//!
//! - the child of a vertex leads with the child of the parent's leading edge;
//! - the child of an edge leads towards the end the edge runs to in its first face;
//! - the child of a face (Catmull-Clark) leads towards the midpoint of the face's last side;
//! - the two halves of an edge have for first face the child of the edge's first face next to
//!   them; an edge inside a parent face the child face at the corner it leaves from;
//! - a child face starts at the child of its corner's vertex, except the children of quads
//!   (rotated so that child `j` starts `j` corners on) and Loop's other three.
//!
//! So the tangents are OpenSubdiv's, direction and length, at every level
//! (`tests/opensubdiv.rs`).
//!
//! # Evaluating it
//!
//! With [`SubdivideOptions::limit`](crate::subdivide::SubdivideOptions::limit) (Loop and Catmull-Clark) the refinement also keeps the
//! limit masks of its last level (OpenSubdiv's `PrimvarRefiner::Limit`):
//! [`Refinement::evaluate_limit`](super::Refinement::evaluate_limit) gives every vertex's limit position and two limit tangents
//! (any per-vertex data: colors too), [`Refinement::evaluate_limit_uvs`](super::Refinement::evaluate_limit_uvs) the limit of the UVs
//! (`LimitFaceVarying`), [`Refinement::limit_stencils`](super::Refinement::limit_stencils) the same as stencils over the base
//! vertices (`LimitStencilTable`); [`normals::limit_normal`](crate::normals::limit_normal)
//! turns the tangents into the surface's normals.
//!
//!

use crate::subdivide::sdc::crease::{vertex_rule_of, VertexRule};
use crate::subdivide::sdc::limit::LimitMasks;
use crate::subdivide::sdc::masks::Scheme;
use crate::subdivide::topo::Topo;
use crate::tags::INFINITELY_SHARP;
use crate::{Error, Result};

use super::creases::{boundary_first, ccw_ring, Creases, LevelSharpness, Linear};
use super::Scalar;
use crate::mesh::INVALID;

/// OpenSubdiv's order of one level, in `halfedge`'s half-edges.
#[derive(Clone, Debug, Default)]
struct Order {
    /// Per vertex: its leading outgoing half-edge (`INVALID` for a vertex in no edge).
    first: Vec<u32>,
    /// Per edge: its half-edge in the edge's first face.
    edge_first: Vec<u32>,
    /// Per face: its half-edge from its first corner.
    face_first: Vec<u32>,
    /// Per edge, for a face-varying channel: whether it lies along a seam.
    seams: Option<Vec<bool>>,
}

impl Order {
    /// The order of a base level.
    fn base(t: &Topo<'_>) -> Order {
        let first = (0..t.nv() as u32)
            .map(|v| {
                if t.vertex_halfedge(v) == INVALID {
                    return INVALID;
                }
                boundary_first(t, v).unwrap_or_else(|| {
                    let mut best = t.vertex_halfedge(v);
                    t.for_outgoing(v, |h| {
                        if t.face(h) < t.face(best) {
                            best = h;
                        }
                    });
                    best
                })
            })
            .collect();
        let edge_first = (0..t.ne() as u32)
            .map(|e| {
                let (h, g) = (2 * e, 2 * e + 1);
                // INVALID (no face) is the largest u32: a face wins.
                if t.face(h) <= t.face(g) {
                    h
                } else {
                    g
                }
            })
            .collect();
        let face_first = (0..t.nf() as u32).map(|f| t.face_halfedge(f)).collect();
        Order {
            first,
            edge_first,
            face_first,
            seams: None,
        }
    }

    /// The order of `child`, refined from `t` (this order) by `scheme`: child vertices
    /// numbered as the builders number them (vertex `v`, edge `nv + e`, face `nv + ne + f`).
    fn child(&self, t: &Topo<'_>, child: &Topo<'_>, scheme: Scheme, level: u32) -> Result<Order> {
        let (nv, ne) = (t.nv() as u32, t.ne() as u32);
        let mid = |h: u32| nv + (h >> 1);
        let centre = |f: u32| nv + ne + f;
        let find = |from: u32, to: u32| -> Result<u32> {
            let mut found = INVALID;
            child.for_outgoing(from, |h| {
                if child.target(h) == to {
                    found = h;
                }
            });
            if found == INVALID {
                return Err(Error::InvalidOutput {
                    scheme: scheme.name().into(),
                    level,
                    what: format!("the limit's walk: no edge from vertex {from} to vertex {to}"),
                });
            }
            Ok(found)
        };
        let mut order = Order {
            first: vec![INVALID; child.nv()],
            edge_first: vec![INVALID; child.ne()],
            face_first: vec![INVALID; child.nf()],
            seams: self.seams.as_ref().map(|_| vec![false; child.ne()]),
        };
        for v in 0..nv {
            let h = self.first[v as usize];
            if h != INVALID {
                order.first[v as usize] = find(v, mid(h))?;
            }
        }
        for e in 0..ne {
            // Edge `e` runs a -> b in its first face.
            let h = self.edge_first[e as usize];
            let (a, b, m) = (t.source(h), t.target(h), mid(h));
            order.first[m as usize] = find(m, b)?;
            let seam = self.seams.as_ref().is_some_and(|s| s[e as usize]);
            for (x, y) in [(a, m), (m, b)] {
                let g = find(x, y)?;
                order.edge_first[(g >> 1) as usize] = g;
                if let (true, Some(seams)) = (seam, order.seams.as_mut()) {
                    // The halves of a seam lie along it.
                    seams[(g >> 1) as usize] = true;
                }
            }
        }
        let mut corners = Vec::new();
        for f in 0..t.nf() as u32 {
            corners.clear();
            let mut h = self.face_first[f as usize];
            loop {
                corners.push(h);
                h = t.next(h);
                if h == self.face_first[f as usize] {
                    break;
                }
            }
            let n = corners.len();
            let mut starts = [(0, 0); 4];
            match scheme {
                Scheme::CatmullClark => {
                    let c = centre(f);
                    let last = corners[n - 1];
                    order.first[c as usize] = find(c, mid(last))?;
                    for (j, &h) in corners.iter().enumerate() {
                        // The edge from the side's midpoint to the centre: first in child j.
                        let g = find(mid(h), c)?;
                        order.edge_first[(g >> 1) as usize] = g;
                        let (v, next, prev) = (t.source(h), mid(h), mid(corners[(j + n - 1) % n]));
                        let start = match (n, j) {
                            (4, 1) => (prev, v),
                            (4, 2) => (c, prev),
                            (4, 3) => (next, c),
                            _ => (v, next),
                        };
                        let g = find(start.0, start.1)?;
                        order.face_first[child.face(g) as usize] = g;
                    }
                }
                Scheme::Loop => {
                    let e = [mid(corners[0]), mid(corners[1]), mid(corners[2])];
                    for (j, &h) in corners.iter().enumerate() {
                        let g = find(mid(h), mid(corners[(j + 2) % 3]))?;
                        order.edge_first[(g >> 1) as usize] = g;
                    }
                    starts[0] = (t.source(corners[0]), e[0]);
                    starts[1] = (e[0], t.source(corners[1]));
                    starts[2] = (e[2], e[1]);
                    starts[3] = (e[1], e[2]);
                    for &(x, y) in &starts {
                        let g = find(x, y)?;
                        order.face_first[child.face(g) as usize] = g;
                    }
                }
            }
        }
        Ok(order)
    }
}

/// Every vertex of a level as its limit position and two limit tangents: row `i` is
/// `Σ w[k][m] * level[indices[k]]` for `k` in `offsets[i]..offsets[i + 1]`, `m` 0 for the
/// position, 1 and 2 for the tangents (OpenSubdiv's order: face weights, edge weights, the
/// vertex's own last), `w` the row's mask: `weights[masks[i]..]`, as long as the row. Rows
/// share their masks (a smooth vertex's depends on its valence alone), so an evaluation
/// streams the indices, not a weight per entry.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct LimitTable {
    offsets: Vec<u32>,
    indices: Vec<u32>,
    masks: Vec<u32>,
    weights: Vec<[f64; 3]>,
    /// The bits of the row being pushed (a buffer reused while the table is built).
    key: Vec<u64>,
}

/// The caller's buffers of the two limit tangents (first, second), one entry per vertex, as
/// [`Refinement::evaluate_limit`](super::Refinement::evaluate_limit) writes them.
pub type TangentBuffersMut<'a, T, const N: usize> = (&'a mut [[T; N]], &'a mut [[T; N]]);

/// Rows per task of a parallel evaluation.
const ROWS_PER_TASK: usize = 1 << 12;

impl LimitTable {
    /// The number of rows (the level's vertices).
    pub(crate) fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The bytes of the table's arrays.
    pub(crate) fn heap_bytes(&self) -> usize {
        4 * (self.offsets.capacity() + self.indices.capacity() + self.masks.capacity())
            + 24 * self.weights.capacity()
    }

    /// Row `i`: its indices and their (position, tangent, tangent) weights.
    pub(crate) fn row(&self, i: usize) -> (&[u32], &[[f64; 3]]) {
        let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
        let m = self.masks[i] as usize;
        (&self.indices[a..b], &self.weights[m..m + (b - a)])
    }

    /// The limit of `level` (one entry per row's vertex) at the rows `rows` (all when
    /// `None`) into `position` and, when given, the tangents, one entry per row written; in
    /// parallel chunks of rows when `parallel` (the same values).
    pub(crate) fn apply<T: Scalar, const N: usize>(
        &self,
        level: &[[T; N]],
        rows: Option<&[u32]>,
        position: &mut [[T; N]],
        tangents: Option<TangentBuffersMut<'_, T, N>>,
        parallel: bool,
    ) {
        use rayon::prelude::*;
        let row_of = |k: usize| rows.map_or(k, |r| r[k] as usize);
        // Rows `from..` into the chunks `p` (and `t`).
        let fill = |from: usize, p: &mut [[T; N]], t: Option<TangentBuffersMut<'_, T, N>>| match t {
            None => {
                for (k, out) in p.iter_mut().enumerate() {
                    let (indices, weights) = self.row(row_of(from + k));
                    let mut acc = [T::ZERO; N];
                    for (&j, w) in indices.iter().zip(weights) {
                        let (x, w) = (&level[j as usize], T::from_f64(w[0]));
                        for c in 0..N {
                            acc[c] = acc[c] + w * x[c];
                        }
                    }
                    *out = acc;
                }
            }
            Some((t1, t2)) => {
                for (k, ((out, u), v)) in p.iter_mut().zip(t1).zip(t2).enumerate() {
                    let (indices, weights) = self.row(row_of(from + k));
                    let mut acc = [[T::ZERO; N]; 3];
                    for (&j, w) in indices.iter().zip(weights) {
                        let x = &level[j as usize];
                        for (m, sum) in acc.iter_mut().enumerate() {
                            let w = T::from_f64(w[m]);
                            for c in 0..N {
                                sum[c] = sum[c] + w * x[c];
                            }
                        }
                    }
                    [*out, *u, *v] = acc;
                }
            }
        };
        if !parallel || position.len() < 4 * ROWS_PER_TASK {
            fill(0, position, tangents);
            return;
        }
        let chunks = position.par_chunks_mut(ROWS_PER_TASK).enumerate();
        match tangents {
            None => chunks.for_each(|(i, p)| fill(i * ROWS_PER_TASK, p, None)),
            Some((t1, t2)) => chunks
                .zip(t1.par_chunks_mut(ROWS_PER_TASK))
                .zip(t2.par_chunks_mut(ROWS_PER_TASK))
                .for_each(|(((i, p), u), v)| fill(i * ROWS_PER_TASK, p, Some((u, v)))),
        }
    }

    /// The limit masks of every vertex of level `t` in `order`, its sharpness `sharp` (`None`:
    /// boundary edges infinitely sharp, nothing else).
    fn build(
        t: &Topo<'_>,
        order: &Order,
        sharp: Option<&LevelSharpness>,
        linear: Linear,
        scheme: Scheme,
    ) -> Result<LimitTable> {
        let nv = t.nv();
        let mut table = LimitTable {
            offsets: Vec::with_capacity(nv + 1),
            indices: Vec::new(),
            masks: Vec::with_capacity(nv),
            weights: Vec::new(),
            key: Vec::new(),
        };
        table.offsets.push(0);
        // Each distinct mask once, found by its weights' bits.
        let mut known: std::collections::HashMap<Vec<u64>, u32> = Default::default();
        let mut row: Vec<[f64; 3]> = Vec::new();
        let (mut ring, mut edges) = (Vec::new(), Vec::new());
        let mut masks = LimitMasks::default();
        for v in 0..nv as u32 {
            let first = order.first[v as usize];
            // A face-varying channel interpolated linearly keeps its values (everywhere, or on
            // its boundary), as OpenSubdiv's linear channels and corner values do.
            let linear = match linear {
                Linear::All => true,
                Linear::Boundaries => t.is_boundary_vertex(v),
                Linear::Nothing => false,
            };
            row.clear();
            if first == INVALID || linear {
                table.indices.push(v);
                row.push([1.0, 0.0, 0.0]);
                table.push_row(&row, &mut known)?;
                continue;
            }
            ccw_ring(t, v, first, &mut ring);
            edges.clear();
            edges.extend(ring.iter().map(|&h| match sharp {
                Some(s) => s.edges[(h >> 1) as usize],
                None if t.is_boundary_edge(h >> 1) => INFINITELY_SHARP,
                None => 0.0,
            }));
            let faces = ring.iter().filter(|&&h| !t.is_boundary(h)).count();
            let vertex = sharp.map_or(0.0, |s| s.vertices[v as usize]);
            let rule = vertex_rule_of(vertex, &edges);
            masks.set(scheme, rule, &edges, faces);
            let on_seam = order
                .seams
                .as_ref()
                .is_some_and(|s| ring.iter().any(|&h| s[(h >> 1) as usize]));
            if on_seam && rule == VertexRule::Crease {
                // A value along a seam (mismatched in OpenSubdiv's face-varying channel): its
                // crease mask in OpenSubdiv's `f32` constants (`LimitFaceVarying`).
                let p = &mut masks.position;
                p.vertex = f64::from(2.0f32 / 3.0f32);
                for w in p.edges.iter_mut().filter(|w| **w != 0.0) {
                    *w = f64::from(1.0f32 / 6.0f32);
                }
            }
            let [p, t1, t2] = [&masks.position, &masks.tangent1, &masks.tangent2];
            let n_faces = p.faces.len().max(t1.faces.len());
            for (i, &h) in ring.iter().take(n_faces).enumerate() {
                let f = t.face(h);
                if t.face_degree(f) != 4 {
                    return Err(Error::LimitNeedsQuads {
                        face: f,
                        sides: t.face_degree(f),
                    });
                }
                let at =
                    |m: &crate::subdivide::sdc::masks::Mask| m.faces.get(i).copied().unwrap_or(0.0);
                table.indices.push(t.target(t.next(h)));
                row.push([at(p), at(t1), at(t2)]);
            }
            for (i, &h) in ring.iter().enumerate() {
                let at =
                    |m: &crate::subdivide::sdc::masks::Mask| m.edges.get(i).copied().unwrap_or(0.0);
                table.indices.push(t.target(h));
                row.push([at(p), at(t1), at(t2)]);
            }
            table.indices.push(v);
            row.push([p.vertex, t1.vertex, t2.vertex]);
            table.push_row(&row, &mut known)?;
        }
        table.key = Vec::new();
        Ok(table)
    }

    /// Ends the row whose indices were pushed, its mask `row` (shared with an earlier row of
    /// the same weights, bit for bit).
    fn push_row(
        &mut self,
        row: &[[f64; 3]],
        known: &mut std::collections::HashMap<Vec<u64>, u32>,
    ) -> Result<()> {
        let overflow = |count: usize| Error::IndexOverflow {
            what: "limit entries",
            count: count as u128,
        };
        let mut key = std::mem::take(&mut self.key);
        key.clear();
        key.extend(row.iter().flatten().map(|w| w.to_bits()));
        let found = known.get(key.as_slice()).copied();
        let start = match found {
            Some(start) => start,
            None => {
                let start =
                    u32::try_from(self.weights.len()).map_err(|_| overflow(self.weights.len()))?;
                self.weights.extend_from_slice(row);
                known.insert(key.clone(), start);
                start
            }
        };
        self.key = key;
        self.masks.push(start);
        let end = u32::try_from(self.indices.len()).map_err(|_| overflow(self.indices.len()))?;
        self.offsets.push(end);
        Ok(())
    }
}

/// Follows a refinement level by level (`Refinement::refine_levels` calls
/// [`LimitWalk::push`] with each level and its parent, then [`LimitWalk::finish`] with the
/// last level and its sharpness, which the refinement's `Creases` computed) and builds the
/// [`LimitTable`] of the last one.
#[derive(Debug)]
pub(crate) struct LimitWalk {
    scheme: Scheme,
    /// A face-varying channel's linear interpolation.
    linear: Linear,
    order: Order,
    /// The level the order is of (for messages).
    level: u32,
    table: Option<LimitTable>,
}

impl LimitWalk {
    /// A walk from the base level `t` under `scheme` and the crease rules `creases`, the
    /// table built at once when `levels` is 0; `seams` marks the edges of a face-varying
    /// channel along its seams (their values take `LimitFaceVarying`'s crease mask).
    pub(crate) fn new(
        t: &Topo<'_>,
        scheme: Scheme,
        creases: Option<&Creases>,
        levels: u32,
        seams: Option<Vec<bool>>,
    ) -> Result<LimitWalk> {
        let mut order = Order::base(t);
        order.seams = seams;
        let mut walk = LimitWalk {
            scheme,
            linear: creases.map_or(Linear::Nothing, Creases::linear),
            order,
            level: 0,
            table: None,
        };
        if levels == 0 {
            walk.finish(t, creases.and_then(|c| c.level(0)))?;
        }
        Ok(walk)
    }

    /// Level `child` refined from `parent` (the walk's current level).
    pub(crate) fn push(&mut self, parent: &Topo<'_>, child: &Topo<'_>) -> Result<()> {
        self.level += 1;
        self.order = self.order.child(parent, child, self.scheme, self.level)?;
        Ok(())
    }

    /// Builds the table of the walk's current level `t`, of sharpness `sharp` (`None`: no
    /// crease rules, boundary edges infinitely sharp).
    pub(crate) fn finish(&mut self, t: &Topo<'_>, sharp: Option<&LevelSharpness>) -> Result<()> {
        let table = LimitTable::build(t, &self.order, sharp, self.linear, self.scheme);
        self.table = Some(table?);
        Ok(())
    }

    /// The table of the last level, once built.
    pub(crate) fn into_table(self) -> Option<LimitTable> {
        self.table
    }
}

/// The crease-aware scheme of `rule`, the one the limit masks are written for.
pub(crate) fn scheme_of(rule: crate::Rule) -> Result<Scheme> {
    Scheme::of(rule).ok_or_else(|| Error::LimitNotSupported {
        rule: rule.to_string(),
    })
}

impl super::Refinement {
    /// Whether the refinement keeps the limit surface ([`SubdivideOptions::limit`]).
    ///
    /// [`SubdivideOptions::limit`]: crate::subdivide::SubdivideOptions::limit
    pub fn has_limit(&self) -> bool {
        self.limit.is_some()
    }

    /// The limit surface of `base` at the last level's vertices (its written ones, with
    /// holes): refines `base` to the last level, then applies OpenSubdiv's limit masks
    /// (`PrimvarRefiner::Limit`) into `position` and, when given, the two tangents, each with
    /// `n_vertices(levels)` entries. Any per-vertex data works (colors: the same masks).
    ///
    /// # Errors
    ///
    /// [`Error::NoLimit`] for a refinement built without [`SubdivideOptions::limit`];
    /// [`Error::BufferSize`]; [`Error::AllocationFailed`].
    ///
    /// ```
    /// use halfedge::refine::Refinement;
    /// use halfedge::subdivide::SubdivideOptions;
    /// use halfedge::{shapes, HalfEdgeMesh, Rule};
    ///
    /// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
    /// let base: Vec<[f64; 3]> = cube.positions().iter().map(|p| p.to_array()).collect();
    /// let opts = SubdivideOptions::default().with_limit(true);
    /// let r = Refinement::new(&cube, Rule::CatmullClark, 2, &opts)?;
    /// let n = r.n_vertices(2);
    /// let (mut limit, mut t1, mut t2) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
    /// r.evaluate_limit(&base, &mut limit, Some((&mut t1, &mut t2)))?;
    /// // Vertex 0 (a corner of the cube) at level 2 and its limit: where level 8 has it by now.
    /// let deep = Refinement::new(&cube, Rule::CatmullClark, 8, &SubdivideOptions::default())?;
    /// let mut far = vec![[0.0; 3]; deep.n_vertices(8)];
    /// deep.evaluate(&base, &mut far)?;
    /// let gap = |a: [f64; 3], b: [f64; 3]| (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max);
    /// assert!(gap(limit[0], far[0]) < 1e-4);
    /// // Without the option there is no limit to evaluate.
    /// let plain = Refinement::new(&cube, Rule::CatmullClark, 2, &SubdivideOptions::default())?;
    /// assert!(plain.evaluate_limit(&base, &mut limit, None).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// [`SubdivideOptions::limit`]: crate::subdivide::SubdivideOptions::limit
    pub fn evaluate_limit<T: Scalar, const N: usize>(
        &self,
        base: &[[T; N]],
        position: &mut [[T; N]],
        tangents: Option<TangentBuffersMut<'_, T, N>>,
    ) -> Result<()> {
        self.evaluator().evaluate_limit(base, position, tangents)
    }

    /// The limit table, or [`Error::NoLimit`].
    pub(super) fn limit_table(&self) -> Result<&LimitTable> {
        self.limit.as_ref().ok_or(Error::NoLimit)
    }

    /// The rows of the limit table that are written (with holes), else `None` (all).
    pub(super) fn limit_rows(&self) -> Option<&[u32]> {
        self.written.as_ref().map(|w| w.kept.as_slice())
    }
}

impl super::Refinement {
    /// The limit of the UV values `base` (one per value of the layout) at the last level, into
    /// `out` (`n_uvs(levels)` entries, numbered as [`Refinement::evaluate_uvs`] numbers them):
    /// OpenSubdiv's `LimitFaceVarying`, the layout's own limit masks (a value inside its
    /// layout takes its vertex's masks, a value along a seam or the boundary the crease mask
    /// along it or stays, a corner stays; under `all` every value stays, under `boundaries`
    /// every boundary value).
    ///
    /// # Errors
    ///
    /// [`Error::NoUvs`] without a layout; [`Error::NoLimit`] for a refinement built without
    /// [`SubdivideOptions::limit`](crate::subdivide::SubdivideOptions::limit);
    /// [`Error::BufferSize`] (`uv base`, `uv out`); [`Error::AllocationFailed`].
    ///
    /// [`Refinement::evaluate_uvs`]: super::Refinement::evaluate_uvs
    pub fn evaluate_limit_uvs<T: Scalar>(&self, base: &[[T; 2]], out: &mut [[T; 2]]) -> Result<()> {
        let uvs = self.uvs.as_ref().ok_or(Error::NoUvs)?;
        self.limit_table()?;
        self.run(|| uvs.evaluate_limit(base, out))
    }
}

/// The limit surface as stencils over the base vertices (OpenSubdiv's `LimitStencilTable`):
/// one [`StencilTable`](super::StencilTable) for the limit positions and one for each limit
/// tangent, a row per vertex of the last level (the written ones, with holes), in the order
/// of [`Refinement::evaluate_limit`](super::Refinement::evaluate_limit)'s output. For GPU-style
/// evaluation: `position.apply(base, out)` gives the limit positions, and so on.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LimitStencils {
    /// The limit positions.
    pub position: super::StencilTable,
    /// The first limit tangents.
    pub tangent1: super::StencilTable,
    /// The second limit tangents.
    pub tangent2: super::StencilTable,
}

impl super::Refinement {
    /// The limit surface as stencils over the base vertices ([`LimitStencils`]): the
    /// refinement's stencils of the whole last level ([`Refinement::stencils`]) combined by
    /// the limit masks; applied to the base positions they give
    /// [`Refinement::evaluate_limit`]'s results up to rounding (the sums run in another order).
    ///
    /// # Errors
    ///
    /// [`Error::NoLimit`] for a refinement built without
    /// [`SubdivideOptions::limit`](crate::subdivide::SubdivideOptions::limit);
    /// [`Error::IndexOverflow`] beyond `u32` entries; [`Error::AllocationFailed`].
    ///
    /// [`Refinement::stencils`]: super::Refinement::stencils
    /// [`Refinement::evaluate_limit`]: super::Refinement::evaluate_limit
    pub fn limit_stencils(&self) -> Result<LimitStencils> {
        use super::Sparse;
        let table = self.limit_table()?;
        let whole = self.last_level_sums(Sparse::unit, true)?;
        let rows = self.limit_rows();
        let n = rows.map_or(table.len(), <[u32]>::len);
        let mut sums: [Vec<Sparse>; 3] = Default::default();
        let mut terms: Vec<(u32, f64)> = Vec::new();
        for k in 0..n {
            let i = rows.map_or(k, |r| r[k] as usize);
            let (indices, weights) = table.row(i);
            for (m, out) in sums.iter_mut().enumerate() {
                terms.clear();
                for (&j, w) in indices.iter().zip(weights) {
                    if w[m] != 0.0 {
                        terms.extend(whole[j as usize].0.iter().map(|&(v, x)| (v, w[m] * x)));
                    }
                }
                terms.sort_unstable_by_key(|t| t.0);
                let mut row: Vec<(u32, f64)> = Vec::with_capacity(terms.len());
                for &(v, x) in &terms {
                    match row.last_mut() {
                        Some(last) if last.0 == v => last.1 += x,
                        _ => row.push((v, x)),
                    }
                }
                row.retain(|t| t.1 != 0.0);
                out.push(Sparse(row));
            }
        }
        let n0 = self.base_vertices();
        let [p, t1, t2] = sums.map(|rows| {
            let sizes = super::StencilSizes {
                rows: rows.len(),
                entries: rows.iter().map(|r| r.0.len()).sum(),
            };
            super::StencilTable::from_sums(&rows, n0, sizes, &self.name, self.levels)
        });
        Ok(LimitStencils {
            position: p?,
            tangent1: t1?,
            tangent2: t2?,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::holes::HoleSet;
    use crate::subdivide::SubdivideOptions;
    use crate::{shapes, HalfEdgeMesh, Refinement, Rule};

    /// One refinement of the levels gives the last level's points and the limit, each to the
    /// bit of its own evaluation, with holes too.
    #[test]
    fn points_and_limit_together_equal_each_alone() {
        let cube = HalfEdgeMesh::try_from(&shapes::cube()).expect("a cube");
        let base: Vec<[f64; 3]> = cube.positions().iter().map(|p| p.to_array()).collect();
        let holes = HoleSet::new(cube.n_faces(), [2]).expect("a hole");
        for holed in [false, true] {
            for levels in 0..=2 {
                let mut opts = SubdivideOptions::default().with_limit(true);
                if holed {
                    opts = opts.with_holes(&holes);
                }
                let r = Refinement::new(&cube, Rule::CatmullClark, levels, &opts).expect("built");
                let n = r.n_vertices(levels);
                let zero = || vec![[0.0; 3]; n];
                let (mut points, mut limit, mut t1, mut t2) = (zero(), zero(), zero(), zero());
                r.evaluator()
                    .evaluate_with_limit(&base, &mut points, &mut limit, Some((&mut t1, &mut t2)))
                    .expect("evaluated");
                let (mut p, mut l, mut u, mut v) = (zero(), zero(), zero(), zero());
                r.evaluate(&base, &mut p).expect("points");
                r.evaluate_limit(&base, &mut l, Some((&mut u, &mut v)))
                    .expect("limit");
                assert_eq!(
                    (points, limit, t1, t2),
                    (p, l, u, v),
                    "holes {holed}, level {levels}"
                );
            }
        }
    }
}
