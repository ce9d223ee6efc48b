//! One level of Loop or Catmull-Clark with creases, as OpenSubdiv's `Sdc::Scheme` computes
//! it (`ComputeEdgeVertexMask`, `ComputeVertexVertexMask`, the schemes' smooth, crease and
//! corner masks, Catmark's smooth-triangle edge weights), flattened into a sparse table:
//! child vertices as weights of the parent's vertices. Face points inside the masks of
//! Catmull-Clark are expanded into their corners, so a row reads the parent level only.
//!
//! The table holds every child vertex (dense), or only those whose mask is not what the
//! level's [`Base`] computes (the rows written over its values: the rule's own kernels, which
//! give the smooth and dart masks inside and the crease rule along a boundary whose edges are
//! the only sharp ones, or linear interpolation). A vertex with no sharp edge and no
//! sharpness is smooth at every later level too (its children's edges are smooth), so only
//! the vertices on sharp edges (and sharp or boundary ones) are looked at.
//!
//! The child vertices are numbered as the half-edge builders number them: the children of
//! the parent's vertices (same index), then those of its edges (`nv + e`), then, under
//! Catmull-Clark, those of its faces (`nv + ne + f`).
//!
//! Rules, as Vtr tags them: a parent vertex's rule comes from its sharpness and the sharp
//! edges around it; its child's from the decayed values. An edge's child takes the crease
//! rule when both child edges of the edge are sharp, else the smooth or dart rule; a face's
//! child is smooth. When the two rules of a vertex differ, the masks are blended by the
//! fractional weight of [`fractional_weight`]; an edge whose children are not both sharp
//! blends its crease mask (weight: its sharpness, as OpenSubdiv, even above 1 under Chaikin)
//! with its smooth one.

use crate::mesh::INVALID;
use crate::subdivide::par;
use crate::subdivide::sdc::crease::{
    child_edge_sharpness, decrement, fractional_weight, is_sharp, vertex_rule_of,
};
use crate::subdivide::sdc::masks::{edge_mask, Mask, Scheme};
use crate::subdivide::topo::Topo;
use crate::subdivide::weights::{merge_row, Base, WeightTable};
use crate::tags::{CreaseMethod, SubdivisionOptions, TriangleRule};
use crate::{Error, Result};

use super::{Linear, DENSE_MAX_DEGREE};

/// The sharpness of one level: per edge and per vertex, and the order in which OpenSubdiv
/// lists each vertex's edges (its sums of `f32` values run in that order).
#[derive(Clone, Debug)]
pub(crate) struct LevelSharpness {
    /// Per edge (`h >> 1`).
    pub(crate) edges: Vec<f32>,
    /// Per vertex.
    pub(crate) vertices: Vec<f32>,
    /// Per vertex: the outgoing half-edge OpenSubdiv lists first (its leading edge).
    pub(crate) first: Vec<u32>,
}

/// The outgoing half-edges of `v` counter-clockwise from `first` (OpenSubdiv's order of a
/// vertex's edges; face `i`, where there is one, lies between edges `i` and `i + 1`), into
/// `ring`.
pub(crate) fn ccw_ring(t: &Topo<'_>, v: u32, first: u32, ring: &mut Vec<u32>) {
    ring.clear();
    let mut h = first;
    loop {
        ring.push(h);
        if t.is_boundary(h) {
            break;
        }
        h = t.prev(h) ^ 1;
        if h == first || ring.len() > t.ne() * 2 {
            break;
        }
    }
    debug_assert!(ring.iter().all(|&h| t.source(h) == v));
}

/// The leading outgoing half-edge of a boundary vertex (the one whose face follows the
/// boundary counter-clockwise), or `None` for an interior vertex.
pub(crate) fn boundary_first(t: &Topo<'_>, v: u32) -> Option<u32> {
    let h = t.vertex_halfedge(v);
    t.is_boundary(h).then(|| t.prev(h) ^ 1)
}

impl LevelSharpness {
    /// The sharpness of the base level: the given values with boundary edges infinitely sharp
    /// (as OpenSubdiv does under every boundary mode) and, under `edge-and-corner`, boundary
    /// vertices of one face infinitely sharp. Interior vertices list their edges from the
    /// lowest-numbered face around them, as OpenSubdiv's base level does.
    pub(crate) fn base(
        t: &Topo<'_>,
        edges: &[f32],
        vertices: &[f32],
        options: &SubdivisionOptions,
    ) -> LevelSharpness {
        use crate::tags::{BoundaryInterpolation, INFINITELY_SHARP};
        let mut e: Vec<f32> = edges.to_vec();
        for (i, s) in e.iter_mut().enumerate() {
            if t.is_boundary_edge(i as u32) {
                *s = INFINITELY_SHARP;
            }
        }
        let mut vs: Vec<f32> = vertices.to_vec();
        let mut first = Vec::with_capacity(t.nv());
        for v in 0..t.nv() as u32 {
            match boundary_first(t, v) {
                Some(h) => {
                    if options.boundary == BoundaryInterpolation::EdgeAndCorner && t.valence(v) == 2
                    {
                        vs[v as usize] = INFINITELY_SHARP;
                    }
                    first.push(h);
                }
                None => {
                    let mut best = t.vertex_halfedge(v);
                    t.for_outgoing(v, |h| {
                        if t.face(h) < t.face(best) {
                            best = h;
                        }
                    });
                    first.push(best);
                }
            }
        }
        LevelSharpness {
            edges: e,
            vertices: vs,
            first,
        }
    }
}

/// Buffers reused from one vertex row to the next.
#[derive(Default)]
struct Scratch {
    ring: Vec<u32>,
    faces: Vec<u32>,
    parent: Vec<f32>,
    child: Vec<f32>,
    mask: Mask,
    child_mask: Mask,
    row: Vec<(u32, f64)>,
}

/// Rows per task when a weight table is built in parallel.
const ROW_CHUNK: usize = 1 << 13;

/// One crease-aware level built from its parent `t` and the parent's sharpness: the weight
/// table of the child vertices and, when asked, the child level's sharpness.
pub(crate) struct LevelBuilder<'a> {
    t: Topo<'a>,
    sharp: &'a LevelSharpness,
    scheme: Scheme,
    method: CreaseMethod,
    smooth_triangles: bool,
    /// Per half-edge `h`: the sharpness of the child of edge `h >> 1` at `source(h)`.
    child_at: Vec<f32>,
    /// Per vertex: whether its child's crease mask differs from the rule's kernel.
    differs: Vec<bool>,
    /// A face-varying channel's linear interpolation.
    linear: Linear,
}

impl<'a> LevelBuilder<'a> {
    pub(crate) fn new(
        t: Topo<'a>,
        sharp: &'a LevelSharpness,
        scheme: Scheme,
        options: &SubdivisionOptions,
        linear: Linear,
    ) -> LevelBuilder<'a> {
        let method = options.crease_method;
        let (nv, ne) = (t.nv(), t.ne());
        // A vertex with a sharp edge or a sharpness of its own (or on the boundary, whose
        // edges are infinitely sharp); the others are smooth, and so are their edges' children
        // at them, at this level and every later one.
        // Boundary vertices are touched through their boundary edges, infinitely sharp at
        // every level.
        let mut touched: Vec<bool> = sharp.vertices.iter().map(|&s| is_sharp(s)).collect();
        // Per vertex: its sharp edges (saturated).
        let mut sharp_edges = vec![0u8; nv];
        for (e, &s) in sharp.edges.iter().enumerate() {
            if is_sharp(s) {
                let h = 2 * e as u32;
                for v in [t.source(h), t.target(h)] {
                    touched[v as usize] = true;
                    sharp_edges[v as usize] = sharp_edges[v as usize].saturating_add(1);
                }
            }
        }
        debug_assert!((0..nv as u32).all(|v| touched[v as usize] || !t.is_boundary_vertex(v)));
        // The touched vertices whose mask is the rule's kernel all the same: a boundary vertex
        // whose only sharp edges are its two boundary edges (the crease rule along them at
        // both ends of the level, as the kernels' boundary rule), an interior vertex of one
        // sharp edge (a dart at both ends: the smooth mask); neither sharp itself nor linear.
        let boundaries = linear == Linear::Boundaries;
        let mut differs = touched.clone();
        for (v, d) in differs.iter_mut().enumerate() {
            if *d && !is_sharp(sharp.vertices[v]) {
                let boundary = t.is_boundary_vertex(v as u32);
                let plain = if boundary {
                    !boundaries && sharp_edges[v] == 2
                } else {
                    sharp_edges[v] == 1
                };
                *d = !plain;
            }
        }
        let mut child_at = vec![0.0f32; 2 * ne];
        let mut ring = Vec::new();
        let mut edge_sharpness = Vec::new();
        for v in (0..nv as u32).filter(|&v| touched[v as usize]) {
            ccw_ring(&t, v, sharp.first[v as usize], &mut ring);
            edge_sharpness.clear();
            edge_sharpness.extend(ring.iter().map(|&h| sharp.edges[(h >> 1) as usize]));
            for (i, &h) in ring.iter().enumerate() {
                child_at[h as usize] = child_edge_sharpness(method, &edge_sharpness, i);
            }
        }
        LevelBuilder {
            t,
            sharp,
            scheme,
            method,
            smooth_triangles: scheme == Scheme::CatmullClark
                && options.triangle_rule == TriangleRule::Smooth,
            child_at,
            differs,
            linear,
        }
    }

    /// The number of child vertices.
    pub(crate) fn n_rows(&self) -> usize {
        let t = &self.t;
        match self.scheme {
            Scheme::Loop => t.nv() + t.ne(),
            Scheme::CatmullClark => t.nv() + t.ne() + t.nf(),
        }
    }

    /// The weight table of every child vertex, built in chunks of rows (in parallel when
    /// `parallel`).
    pub(crate) fn weights(&self, parallel: bool) -> Result<WeightTable> {
        self.build(None, parallel)
    }

    /// What computes the child vertices other than those of [`LevelBuilder::overrides`].
    pub(crate) fn base(&self) -> Base {
        if self.linear == Linear::All {
            Base::Linear
        } else {
            Base::Rule
        }
    }

    /// The child vertices whose crease mask is not the [`LevelBuilder::base`] one, ascending:
    /// under the rule's kernels, the children of the sharp vertices, of the vertices on sharp
    /// edges (but boundary vertices on their two boundary edges alone and darts), of every
    /// boundary vertex under linear boundaries, of the interior edges with a sharpness and,
    /// under Catmark's smooth-triangle rule, of the interior edges of a triangle; none under
    /// linear interpolation (every vertex, edge and face point of `all` is linear).
    pub(crate) fn override_rows(&self) -> Vec<u32> {
        if self.base() == Base::Linear {
            return Vec::new();
        }
        let t = &self.t;
        let nv = t.nv();
        let tri = |f: u32| f != INVALID && t.face_degree(f) == 3;
        let vertices = (0..nv as u32).filter(|&v| self.differs[v as usize]);
        let edges = (0..t.ne() as u32).filter(|&e| {
            let h = 2 * e;
            if t.is_boundary(h) || t.is_boundary(h ^ 1) {
                return false;
            }
            is_sharp(self.sharp.edges[e as usize])
                || (self.smooth_triangles && (tri(t.face(h)) || tri(t.face(h ^ 1))))
        });
        // Below the child count, which fits u32.
        vertices.chain(edges.map(|e| nv as u32 + e)).collect()
    }

    /// The weight table of the child vertices `rows` only ([`LevelBuilder::override_rows`]).
    pub(crate) fn overrides(&self, rows: Vec<u32>, parallel: bool) -> Result<WeightTable> {
        self.build(Some(rows), parallel)
    }

    /// The weight table of the child vertices `rows` (all of them when `None`), built in
    /// chunks of rows (in parallel when `parallel`).
    fn build(&self, rows: Option<Vec<u32>>, parallel: bool) -> Result<WeightTable> {
        let t = &self.t;
        let (nv, ne) = (t.nv(), t.ne());
        let n = rows.as_ref().map_or_else(|| self.n_rows(), Vec::len);
        let child = |k: usize| rows.as_ref().map_or(k, |r| r[k] as usize);
        // Overriding rows name a wide face by its child point (computed by the base rule
        // first): linear in the face's degree.
        let refs = rows.is_some();
        let part = |range: std::ops::Range<usize>| {
            let mut scratch = Scratch::default();
            let mut index = Vec::with_capacity(8 * range.len());
            let mut weight = Vec::with_capacity(8 * range.len());
            let mut ends = Vec::with_capacity(range.len());
            for k in range {
                let r = child(k);
                let mut row = std::mem::take(&mut scratch.row);
                if r < nv {
                    self.vertex_row(r as u32, refs, &mut scratch, &mut row);
                } else if r < nv + ne {
                    self.edge_row((r - nv) as u32, refs, &mut row);
                } else {
                    self.face_centre((r - nv - ne) as u32, 1.0, false, &mut row);
                }
                merge_row(&mut row, &mut index, &mut weight);
                ends.push(index.len());
                scratch.row = row;
            }
            (index, weight, ends)
        };
        let chunks = par::map_ranges(n, ROW_CHUNK, parallel, 2 * ROW_CHUNK, part);
        let total: usize = chunks.iter().map(|(i, _, _)| i.len()).sum();
        u32::try_from(total).map_err(|_| Error::IndexOverflow {
            what: "crease weight table entries",
            count: total as u128,
        })?;
        let what = "a crease weight table";
        let mut table = WeightTable {
            rows: None,
            offsets: crate::subdivide::alloc::with_capacity(n + 1, what)?,
            index: crate::subdivide::alloc::with_capacity(total, what)?,
            weight: crate::subdivide::alloc::with_capacity(total, what)?,
        };
        table.offsets.push(0);
        for (index, weight, ends) in chunks {
            // At most `total`, which fits u32.
            let start = table.index.len();
            table
                .offsets
                .extend(ends.iter().map(|&e| (start + e) as u32));
            table.index.extend_from_slice(&index);
            table.weight.extend_from_slice(&weight);
        }
        table.rows = rows;
        Ok(table)
    }

    /// Adds `w` times the centre of face `f`: its corners, `w / degree` each, or with `refs`
    /// for a face of more than [`DENSE_MAX_DEGREE`] sides its child point (index
    /// `nv + ne + f`, past the parent's vertices), nothing when `w` is 0 (a term `0 * p`
    /// changes no sum), so that a row is linear in the face's degree.
    fn face_centre(&self, f: u32, w: f64, refs: bool, row: &mut Vec<(u32, f64)>) {
        let t = &self.t;
        let degree = t.face_degree(f);
        if refs && degree > DENSE_MAX_DEGREE {
            if w != 0.0 {
                // Below the child count, which fits u32.
                row.push(((t.nv() + t.ne()) as u32 + f, w));
            }
            return;
        }
        let each = 1.0 / degree as f64;
        t.for_face(f, |h| row.push((t.source(h), w * each)));
    }

    fn vertex_row(&self, v: u32, refs: bool, scratch: &mut Scratch, row: &mut Vec<(u32, f64)>) {
        let t = &self.t;
        if self.linear == Linear::All
            || (self.linear == Linear::Boundaries && t.is_boundary_vertex(v))
        {
            row.push((v, 1.0));
            return;
        }
        let Scratch {
            ring,
            faces,
            parent,
            child,
            mask,
            child_mask,
            ..
        } = scratch;
        ccw_ring(t, v, self.sharp.first[v as usize], ring);
        faces.clear();
        faces.extend(
            ring.iter()
                .filter(|&&h| !t.is_boundary(h))
                .map(|&h| t.face(h)),
        );
        parent.clear();
        parent.extend(ring.iter().map(|&h| self.sharp.edges[(h >> 1) as usize]));
        child.clear();
        child.extend(ring.iter().map(|&h| self.child_at[h as usize]));
        let pv = self.sharp.vertices[v as usize];
        let cv = decrement(pv);
        let p_rule = vertex_rule_of(pv, parent);
        let c_rule = vertex_rule_of(cv, child);
        let nfaces = faces.len();
        mask.set(p_rule, self.scheme, parent, nfaces);
        if !p_rule.is_smooth() && c_rule != p_rule {
            child_mask.set(c_rule, self.scheme, child, nfaces);
            let p = f64::from(fractional_weight(self.method, pv, cv, parent, child));
            mask.blend(child_mask, p);
        }
        row.push((v, mask.vertex));
        for (&h, &w) in ring.iter().zip(&mask.edges) {
            row.push((t.target(h), w));
        }
        if self.scheme == Scheme::CatmullClark {
            for (&f, &w) in faces.iter().zip(&mask.faces) {
                self.face_centre(f, w, refs, row);
            }
        }
    }

    fn edge_row(&self, e: u32, refs: bool, row: &mut Vec<(u32, f64)>) {
        let t = &self.t;
        let h = 2 * e;
        let (a, b) = (t.source(h), t.target(h));
        let s = self.sharp.edges[e as usize];
        let crease_children =
            is_sharp(self.child_at[h as usize]) && is_sharp(self.child_at[(h ^ 1) as usize]);
        if (is_sharp(s) && crease_children) || self.linear == Linear::All {
            row.push((a, 0.5));
            row.push((b, 0.5));
            return;
        }
        // The smooth mask, blended with the crease mask by the edge's sharpness (an edge with a
        // sharp parent and a boundary is never here: boundary edges are infinitely sharp, and
        // so are their children).
        let faces = [t.face(h), t.face(h ^ 1)];
        let tri = |f: u32| self.smooth_triangles && f != INVALID && t.face_degree(f) == 3;
        let (vw, fw) = edge_mask(self.scheme, s, faces.map(tri));
        row.push((a, vw));
        row.push((b, vw));
        match self.scheme {
            Scheme::Loop => {
                row.push((t.target(t.next(h)), fw[0]));
                row.push((t.target(t.next(h ^ 1)), fw[1]));
            }
            Scheme::CatmullClark => {
                for (f, w) in faces.into_iter().zip(fw) {
                    if f != INVALID {
                        self.face_centre(f, w, refs, row);
                    }
                }
            }
        }
    }

    /// The sharpness of the child level `child` (numbered as the module docs say).
    pub(crate) fn child_sharpness(&self, child: &Topo<'_>) -> LevelSharpness {
        let t = &self.t;
        let (nv, ne) = (t.nv() as u32, t.ne() as u32);
        let mut edges = vec![0.0f32; child.ne()];
        for (e, s) in edges.iter_mut().enumerate() {
            let h = 2 * e as u32;
            let (x, y) = (child.source(h), child.target(h));
            let (vertex, mid) = if x < nv { (x, y) } else { (y, x) };
            if vertex < nv && (nv..nv + ne).contains(&mid) {
                let pe = mid - nv;
                let ph = if t.source(2 * pe) == vertex {
                    2 * pe
                } else {
                    2 * pe + 1
                };
                *s = self.child_at[ph as usize];
            }
        }
        let mut vertices = vec![0.0f32; child.nv()];
        for (v, s) in vertices.iter_mut().enumerate().take(nv as usize) {
            *s = decrement(self.sharp.vertices[v]);
        }
        let first = (0..child.nv() as u32)
            .map(|v| {
                if v < nv {
                    // The child of the parent's leading edge leads here too.
                    let target = nv + (self.sharp.first[v as usize] >> 1);
                    let mut found = child.vertex_halfedge(v);
                    child.for_outgoing(v, |h| {
                        if child.target(h) == target {
                            found = h;
                        }
                    });
                    found
                } else {
                    boundary_first(child, v).unwrap_or_else(|| child.vertex_halfedge(v))
                }
            })
            .collect();
        LevelSharpness {
            edges,
            vertices,
            first,
        }
    }
}
