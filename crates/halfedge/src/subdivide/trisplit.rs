//! Triangle splits: the 4:1 family (Loop, midpoint, icosphere, modified butterfly) and the
//! general 1:N² split (`tri-split-N`, `ternary`).
//!
//! # Numbering (input `V`, `E`, `F`; split factor `N`)
//!
//! - Vertices: the old vertices keep their ids; edge `e` gets the `N - 1` points
//!   `V + e (N - 1) + k`, `k = 0..N-1`, ordered from the source of half-edge `2e`; face `f`
//!   gets its `(N - 1)(N - 2) / 2` interior grid points after all edge points.
//! - Edges: edge `e` is cut into the `N` pieces `N e + k` (ordered the same way; half-edge
//!   `2 (N e + k)` runs in the direction of `2e`); face `f` gets its `3 N (N - 1) / 2` interior
//!   edges after all pieces.
//! - Faces: face `f` becomes the faces `N² f + t`, `t` in the order of the split template
//!   ([`Template`]: for `N = 2` the 4:1 order of `gather`, the middle triangle first; for
//!   `N >= 3` row by row from corner 0). The template writes the corners of every level the
//!   split builds: the half-edge step, the last level as a face list (`to_faces`) and raw
//!   face lists (`faces`).
//!
//! So `V' = V + (N-1) E + F (N-1)(N-2)/2`, `E' = N E + 3 N (N-1)/2 F`, `F' = N² F`: for
//! `N = 2`, `V + E`, `2E + 3F`, `4F`.

use std::collections::HashMap;
use std::f64::consts::PI;

use super::data::Vector;
use super::par::Sink;
use super::sdc::masks::{loop_smooth, CREASE_VERTEX, LOOP_EDGE};
use super::topo::Topo;
use super::wide::{angle, Ring, Wide};
use crate::Rule;

/// A point of the split template of one triangle.
#[derive(Clone, Copy, Debug)]
pub(crate) enum PointRef {
    /// Corner `k` (the source of the face's half-edge `k`).
    Corner(u8),
    /// Point `j` (`1..N`) along side `s`, counted from the side's source corner.
    Side(u8, u32),
    /// Interior point number `i` of the face.
    Interior(u32),
}

/// A directed side of a template triangle.
#[derive(Clone, Copy, Debug)]
enum SideRef {
    /// Piece `j` of side `s`, from point `j` to `j + 1` (the triangles of a face run
    /// along its sides).
    Piece { side: u8, j: u32 },
    /// Interior edge `edge` of the face, half `half`.
    Interior { edge: u32, half: u32 },
}

/// A point `(a, b)` of the barycentric grid of the split.
type GridPoint = (u32, u32);

/// The split of one triangle into `N²`, as references to be mapped per face.
pub(crate) struct Template {
    pub(crate) n: u32,
    /// Barycentric grid coordinates `(a, b)` of each interior point (for the linear geometry).
    pub(crate) interior_points: Vec<(u32, u32)>,
    interior_edges: u32,
    triangles: Vec<[(PointRef, SideRef); 3]>,
    /// The template's points, each once: the corners, the points of sides 0, 1, 2, the
    /// interior points.
    points: Vec<PointRef>,
    /// Per corner of every triangle, in order, its point's index in `points`.
    slots: Vec<u32>,
    /// `(triangle, corner)` whose side is piece `j` of side `s`, at `s N + j`.
    piece_at: Vec<(u32, u8)>,
    /// `(triangle, corner)` whose side is half `h` of interior edge `e`, at `2 e + h`.
    interior_at: Vec<(u32, u8)>,
    /// The first `(triangle, corner)` at each interior point.
    interior_from: Vec<(u32, u8)>,
}

/// The corners of [`Template::new(2)`](Template::new)'s four triangles as indices into its
/// six points `[corner 0, corner 1, corner 2, midpoint of side 0, of side 1, of side 2]`: the
/// template written out for the last level of every 4:1 subdivision (millions of faces,
/// `to_faces`), checked equal to the template by a test.
pub(crate) const FOUR_TO_ONE_SLOTS: [usize; 12] = [3, 4, 5, 4, 3, 1, 5, 4, 2, 3, 5, 0];

/// A triangle of the level refined as the split numbers its points: its corners (the
/// sources of its sides `0, 1, 2`), each side's edge and whether the side runs along that edge
/// (from the end the edge's points are counted from), and the triangle's face.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub(crate) corners: [u32; 3],
    pub(crate) sides: [(u32, bool); 3],
    pub(crate) face: u32,
}

impl Frame {
    /// The frame of triangle `f` of the half-edge level `t` (an edge's points counted from the
    /// source of its even half-edge).
    #[inline(always)]
    pub(crate) fn of(t: &Topo<'_>, f: u32) -> Frame {
        let h0 = t.face_halfedge(f);
        let h1 = t.next(h0);
        let h2 = t.next(h1);
        Frame {
            corners: [t.target(h2), t.target(h0), t.target(h1)],
            sides: [side_of(h0), side_of(h1), side_of(h2)],
            face: f,
        }
    }
}

/// A side's edge and whether the side runs along it: half-edge `h` runs along edge `h >> 1`
/// when it is the even one (an edge's points are counted from the source of its even
/// half-edge).
#[inline(always)]
pub(crate) fn side_of(h: u32) -> (u32, bool) {
    (h >> 1, h & 1 == 0)
}

/// What the split's numbering reads of a triangle of the level refined: its corners, its
/// sides' edges and directions, its face. A [`Frame`] holds them; the half-edge step reads
/// them from the level on demand ([`Around`]), loading only what an index needs.
pub(crate) trait Triangle {
    /// Corner `k`: the source of side `k`.
    fn corner(&self, k: usize) -> u32;
    /// Side `s`'s edge and whether the side runs along it.
    fn side(&self, s: usize) -> (u32, bool);
    /// The triangle's face.
    fn face(&self) -> u32;
}

impl Triangle for Frame {
    #[inline(always)]
    fn corner(&self, k: usize) -> u32 {
        self.corners[k]
    }
    #[inline(always)]
    fn side(&self, s: usize) -> (u32, bool) {
        self.sides[s]
    }
    #[inline(always)]
    fn face(&self) -> u32 {
        self.face
    }
}

/// Triangle `face` of a half-edge level by its sides' half-edges `sides` (side `s` runs from
/// corner `s` to corner `s + 1`); a corner is loaded only when asked for.
#[derive(Clone, Copy)]
pub(crate) struct Around<'t> {
    pub(crate) t: Topo<'t>,
    pub(crate) sides: [u32; 3],
    pub(crate) face: u32,
}

impl Triangle for Around<'_> {
    #[inline(always)]
    fn corner(&self, k: usize) -> u32 {
        self.t.source(self.sides[k])
    }
    #[inline(always)]
    fn side(&self, s: usize) -> (u32, bool) {
        side_of(self.sides[s])
    }
    #[inline(always)]
    fn face(&self) -> u32 {
        self.face
    }
}

impl Template {
    /// The vertex of point `p` of the triangle `frame` on a level of `nv` vertices and `ne`
    /// edges: the numbering of the module docs, shared by every level the split builds (the
    /// half-edge step, the last level as a face list, raw face lists).
    #[inline(always)]
    pub(crate) fn vertex(&self, p: PointRef, frame: &impl Triangle, nv: u32, ne: u32) -> u32 {
        let n = self.n;
        match p {
            PointRef::Corner(k) => frame.corner(k as usize),
            PointRef::Side(s, j) => self.point_along(frame.side(s as usize), j, nv),
            PointRef::Interior(i) => {
                let per_face = self.interior_points.len() as u32;
                nv + (n - 1) * ne + frame.face() * per_face + i
            }
        }
    }

    /// The vertex of the point `j` (`1..N`) along a side that is `(edge, along)`
    /// ([`Triangle::side`]), counted from the side's source, on a level of `nv` vertices.
    #[inline(always)]
    pub(crate) fn point_along(&self, (e, along): (u32, bool), j: u32, nv: u32) -> u32 {
        let n = self.n;
        nv + e * (n - 1) + if along { j - 1 } else { n - 1 - j }
    }

    /// The half-edge of piece `j` (`0..N`, from point `j` to `j + 1`) along a side that is
    /// `(edge, along)`, running along the side.
    #[inline(always)]
    pub(crate) fn piece_along(&self, (e, along): (u32, bool), j: u32) -> u32 {
        let n = self.n;
        let k = if along { j } else { n - 1 - j };
        2 * (n * e + k) + u32::from(!along)
    }

    /// The half-edge of side `s` of a template triangle in the triangle `frame` of a level of
    /// `ne` edges: edge `e`'s piece `k` (counted from the source of `2e`) is the edge
    /// `N e + k`, its half-edge `2 (N e + k)` running along `2e`; the face's interior edges
    /// follow every piece (the module docs).
    #[inline(always)]
    fn side_halfedge(&self, s: SideRef, frame: &impl Triangle, ne: u32) -> u32 {
        let n = self.n;
        match s {
            SideRef::Piece { side, j } => self.piece_along(frame.side(side as usize), j),
            SideRef::Interior { edge, half } => {
                2 * (n * ne + frame.face() * self.interior_edges + edge) + half
            }
        }
    }

    /// `[target, face, next, prev]` of the half-edge of corner `c` of template triangle
    /// `tri` (its side from corner `c` to corner `c + 1`) in the triangle `frame` of a level
    /// of `nv` vertices and `ne` edges.
    #[inline(always)]
    pub(crate) fn halfedge(
        &self,
        tri: usize,
        c: usize,
        frame: &impl Triangle,
        nv: u32,
        ne: u32,
    ) -> [u32; 4] {
        let triangle = &self.triangles[tri];
        let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
        [
            self.vertex(triangle[c1].0, frame, nv, ne),
            self.n * self.n * frame.face() + tri as u32,
            self.side_halfedge(triangle[c1].1, frame, ne),
            self.side_halfedge(triangle[c2].1, frame, ne),
        ]
    }

    /// The half-edge leaving a template point of a triangle: `(triangle, corner)` of the
    /// template piece `j` of side `s` (running along the side), of half `half` of interior
    /// edge `edge`, of the first corner at interior point `i`.
    #[inline(always)]
    pub(crate) fn piece_corner(&self, s: u32, j: u32) -> (usize, usize) {
        let (tri, c) = self.piece_at[(s * self.n + j) as usize];
        (tri as usize, c as usize)
    }

    /// See [`Template::piece_corner`].
    #[inline(always)]
    pub(crate) fn interior_corner(&self, edge: u32, half: u32) -> (usize, usize) {
        let (tri, c) = self.interior_at[(2 * edge + half) as usize];
        (tri as usize, c as usize)
    }

    /// See [`Template::piece_corner`].
    #[inline(always)]
    pub(crate) fn interior_point_corner(&self, i: u32) -> (usize, usize) {
        let (tri, c) = self.interior_from[i as usize];
        (tri as usize, c as usize)
    }

    /// The number of interior edges of a face, `3 N (N - 1) / 2`.
    pub(crate) fn interior_edges(&self) -> u32 {
        self.interior_edges
    }

    /// The half-edge of the side of corner `c` of template triangle `tri` (leaving the
    /// corner's point) in the triangle `frame` of a level of `ne` edges.
    #[inline(always)]
    pub(crate) fn side(&self, tri: usize, c: usize, frame: &impl Triangle, ne: u32) -> u32 {
        self.side_halfedge(self.triangles[tri][c].1, frame, ne)
    }

    /// The corners of the `N²` triangles of `frame`, in order, into `out` (`3 N²` entries):
    /// each point's vertex computed once, then copied to its corners.
    #[inline]
    pub(crate) fn write_corners(&self, frame: &impl Triangle, nv: u32, ne: u32, out: &mut [u32]) {
        match self.points.len() {
            // N = 2 and N = 3: the points on the stack, their number known to the compiler.
            6 => self.write_through::<6>(frame, nv, ne, out),
            10 => self.write_through::<10>(frame, nv, ne, out),
            _ => {
                for (o, &s) in out.iter_mut().zip(&self.slots) {
                    *o = self.vertex(self.points[s as usize], frame, nv, ne);
                }
            }
        }
    }

    /// [`Template::write_corners`] for a template of `P` points.
    #[inline(always)]
    fn write_through<const P: usize>(
        &self,
        frame: &impl Triangle,
        nv: u32,
        ne: u32,
        out: &mut [u32],
    ) {
        let mut ids = [0u32; P];
        for (id, &p) in ids.iter_mut().zip(&self.points) {
            *id = self.vertex(p, frame, nv, ne);
        }
        for (o, &s) in out.iter_mut().zip(&self.slots) {
            *o = ids[s as usize];
        }
    }

    /// Point `k` (`1..N`) of the edge from `a` to `b` under the linear rule.
    #[inline]
    pub(crate) fn edge_point<V: Vector>(&self, a: V, b: V, k: u32) -> V {
        a.clone()
            .add(b.sub(a).scale(f64::from(k) / f64::from(self.n)))
    }

    /// Interior point `i` of the triangle on the corners `p` under the linear rule.
    #[inline]
    pub(crate) fn interior_point<V: Vector>(&self, [p0, p1, p2]: [V; 3], i: usize) -> V {
        let (a, b) = self.interior_points[i];
        let n = f64::from(self.n);
        p0.clone()
            .add(p1.sub(p0.clone()).scale(f64::from(a) / n))
            .add(p2.sub(p0).scale(f64::from(b) / n))
    }

    /// The number of triangles, `N²`.
    pub(crate) fn n_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// Builds the template of the 1:N² split.
    ///
    /// # Panics
    ///
    /// If `n < 2` (the callers check).
    pub(crate) fn new(n: u32) -> Template {
        assert!(n >= 2, "split factor must be at least 2");
        // Grid point (a, b) = v0 + a/N (v1 - v0) + b/N (v2 - v0), a + b <= N.
        let mut interior_index = HashMap::new();
        let mut interior_points = Vec::new();
        for b in 1..n {
            for a in 1..n - b {
                interior_index.insert((a, b), interior_points.len() as u32);
                interior_points.push((a, b));
            }
        }
        let classify = |a: u32, b: u32| -> PointRef {
            match (a, b) {
                (0, 0) => PointRef::Corner(0),
                _ if a == n && b == 0 => PointRef::Corner(1),
                _ if a == 0 && b == n => PointRef::Corner(2),
                _ if b == 0 => PointRef::Side(0, a),
                _ if a + b == n => PointRef::Side(1, b),
                _ if a == 0 => PointRef::Side(2, n - b),
                _ => PointRef::Interior(interior_index[&(a, b)]),
            }
        };
        // Position of a grid point along side s (None when not on that side).
        let on_side = |s: u8, a: u32, b: u32| -> Option<u32> {
            match s {
                0 => (b == 0).then_some(a),
                1 => (a + b == n).then_some(b),
                _ => (a == 0).then_some(n - b),
            }
        };
        let mut interior_edges: HashMap<(GridPoint, GridPoint), u32> = HashMap::new();
        let mut side_ref = |p: (u32, u32), q: (u32, u32)| -> SideRef {
            for s in 0..3u8 {
                if let (Some(jp), Some(jq)) = (on_side(s, p.0, p.1), on_side(s, q.0, q.1)) {
                    if jp.abs_diff(jq) == 1 {
                        // The triangles run along the face's sides (ccw): the numbering of
                        // the pieces relies on it.
                        assert!(jq > jp, "a template triangle runs along its sides");
                        return SideRef::Piece { side: s, j: jp };
                    }
                }
            }
            if let Some(&edge) = interior_edges.get(&(q, p)) {
                return SideRef::Interior { edge, half: 1 };
            }
            let edge = interior_edges.len() as u32;
            interior_edges.insert((p, q), edge);
            SideRef::Interior { edge, half: 0 }
        };
        let mut triangles = Vec::with_capacity((n * n) as usize);
        let mut push = |pts: [(u32, u32); 3]| {
            let mut tri = [(PointRef::Corner(0), SideRef::Interior { edge: 0, half: 0 }); 3];
            for i in 0..3 {
                let (p, q) = (pts[i], pts[(i + 1) % 3]);
                tri[i] = (classify(p.0, p.1), side_ref(p, q));
            }
            triangles.push(tri);
        };
        if n == 2 {
            // The 4:1 order (`gather`'s half-edge numbering): the middle triangle on the
            // midpoints `m_c` of sides 0, 1, 2, then at each corner `c + 1` (the target of side
            // `c`) the triangle `[m_(c+1), m_c, corner]`.
            let m = [(1, 0), (1, 1), (0, 1)];
            let corner = [(0, 0), (2, 0), (0, 2)];
            push(m);
            for c in 0..3 {
                push([m[(c + 1) % 3], m[c], corner[(c + 1) % 3]]);
            }
        } else {
            for b in 0..n {
                for a in 0..n - b {
                    push([(a, b), (a + 1, b), (a, b + 1)]);
                    if a + b + 2 <= n {
                        push([(a + 1, b), (a + 1, b + 1), (a, b + 1)]);
                    }
                }
            }
        }
        let interior_edges = interior_edges.len() as u32;
        debug_assert_eq!(interior_edges, 3 * n * (n - 1) / 2);
        debug_assert_eq!(triangles.len() as u32, n * n);
        let sides = (0..3u8).flat_map(|s| (1..n).map(move |j| PointRef::Side(s, j)));
        let points: Vec<PointRef> = (0..3u8)
            .map(PointRef::Corner)
            .chain(sides)
            .chain((0..interior_points.len() as u32).map(PointRef::Interior))
            .collect();
        let slot = |p: PointRef| match p {
            PointRef::Corner(k) => u32::from(k),
            PointRef::Side(s, j) => 3 + u32::from(s) * (n - 1) + j - 1,
            PointRef::Interior(i) => 3 + 3 * (n - 1) + i,
        };
        let slots = triangles.iter().flatten().map(|c| slot(c.0)).collect();
        let unset = (u32::MAX, 0);
        let mut piece_at = vec![unset; 3 * n as usize];
        let mut interior_at = vec![unset; 2 * interior_edges as usize];
        let mut interior_from = vec![unset; interior_points.len()];
        for (tri, corners) in triangles.iter().enumerate() {
            for (c, &(p, side)) in corners.iter().enumerate() {
                let at = (tri as u32, c as u8);
                match side {
                    SideRef::Piece { side, j } => piece_at[(u32::from(side) * n + j) as usize] = at,
                    SideRef::Interior { edge, half } => {
                        interior_at[(2 * edge + half) as usize] = at;
                    }
                }
                if let PointRef::Interior(i) = p {
                    if interior_from[i as usize] == unset {
                        interior_from[i as usize] = at;
                    }
                }
            }
        }
        debug_assert!(piece_at.iter().chain(&interior_at).all(|&a| a != unset));
        Template {
            n,
            interior_points,
            interior_edges,
            triangles,
            points,
            slots,
            piece_at,
            interior_at,
            interior_from,
        }
    }
}

/// The points of a 1:N² step from the values `src` of the level before, appended to `out`:
/// old vertices (moved by Loop's rule or kept), edge points, interior face points.
pub(crate) fn tri_points<V: Vector>(
    t: &Topo<'_>,
    src: &[V],
    template: &Template,
    rule: Rule,
    out: &mut impl Sink<V>,
    parallel: bool,
) {
    let n = template.n;
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf() as u32);
    let points_per_face = template.interior_points.len() as u32;
    let t = *t;
    let pos = |v: u32| src[v as usize].clone();
    // Old vertices.
    if rule == Rule::Loop {
        out.append(nv as usize, parallel, |v| loop_vertex(&t, src, v as u32));
    } else {
        out.append(nv as usize, parallel, |v| pos(v as u32));
    }
    // Edge points (the butterfly's wide vertex rings summed once, not once per edge).
    let rings = (rule == Rule::Butterfly)
        .then(|| WideRings::of(&t, src))
        .flatten();
    let per_edge = (n - 1) as usize;
    out.append(ne as usize * per_edge, parallel, |i| {
        let e = (i / per_edge) as u32;
        match rule {
            Rule::Loop => loop_edge(&t, src, e),
            Rule::Midpoint => midpoint(&t, src, e),
            Rule::Icosphere => midpoint(&t, src, e).project_to_sphere(),
            Rule::Butterfly => butterfly_edge(&t, src, rings.as_ref(), e),
            // The linear 1:N² split (`tri-split-N`; no other rule runs a triangle split).
            _ => {
                let k = (i % per_edge) as u32 + 1;
                template.edge_point(pos(t.source(2 * e)), pos(t.target(2 * e)), k)
            }
        }
    });
    // Interior face points (only for N >= 3: linear).
    let ppf = points_per_face as usize;
    if ppf > 0 {
        out.append(nf as usize * ppf, parallel, |i| {
            let f = (i / ppf) as u32;
            let h0 = t.face_halfedge(f);
            let h1 = t.next(h0);
            let p = [t.source(h0), t.target(h0), t.target(h1)].map(pos);
            template.interior_point(p, i % ppf)
        });
    }
}

fn midpoint<V: Vector>(t: &Topo<'_>, src: &[V], e: u32) -> V {
    let (a, b) = (t.source(2 * e), t.target(2 * e));
    src[a as usize]
        .clone()
        .add(src[b as usize].clone())
        .scale(0.5)
}

/// Loop's vertex rule: `(1 - n β) v + β Σ neighbours` with Loop's original
/// `β = (5/8 - (3/8 + 1/4 cos(2π/n))²) / n`; on the boundary `3/4 v + 1/8 (left + right)`.
#[inline]
pub(crate) fn loop_vertex<V: Vector>(t: &Topo<'_>, src: &[V], v: u32) -> V {
    if t.is_boundary_vertex(v) {
        return boundary_vertex(t, src, v);
    }
    let mut sum = V::zero();
    let mut n = 0usize;
    t.for_outgoing(v, |h| {
        sum = sum.clone().add(src[t.target(h) as usize].clone());
        n += 1;
    });
    loop_interior(src[v as usize].clone(), sum, n)
}

/// Loop's interior vertex rule on the vertex `p` and the sum of its `n` neighbours.
#[inline(always)]
pub(crate) fn loop_interior<V: Vector>(p: V, sum: V, n: usize) -> V {
    let (vertex, neighbour) = loop_smooth(n);
    p.scale(vertex).add(sum.scale(neighbour))
}

/// The cubic B-spline rule of a boundary vertex `v` (Loop and Catmull-Clark):
/// `3/4 v + 1/8 (left + right)`, its neighbours along the boundary.
#[inline]
pub(crate) fn boundary_vertex<V: Vector>(t: &Topo<'_>, src: &[V], v: u32) -> V {
    let h = t.vertex_halfedge(v);
    let right = src[t.target(h) as usize].clone();
    let left = src[t.source(t.prev(h)) as usize].clone();
    boundary_rule(src[v as usize].clone(), left, right)
}

/// `3/4 v + 1/8 (left + right)`.
#[inline(always)]
pub(crate) fn boundary_rule<V: Vector>(v: V, left: V, right: V) -> V {
    let [vertex, neighbour] = CREASE_VERTEX;
    v.scale(vertex).add(left.add(right).scale(neighbour))
}

/// Loop's edge rule: `3/8 (a + b) + 1/8 (c + d)`; boundary edges: midpoints.
#[inline]
pub(crate) fn loop_edge<V: Vector>(t: &Topo<'_>, src: &[V], e: u32) -> V {
    let h = 2 * e;
    let (a, b) = (
        src[t.source(h) as usize].clone(),
        src[t.target(h) as usize].clone(),
    );
    if t.is_boundary_edge(e) {
        return a.add(b).scale(0.5);
    }
    let c = src[t.target(t.next(h)) as usize].clone();
    let d = src[t.target(t.next(h ^ 1)) as usize].clone();
    loop_interior_edge(a, b, c, d)
}

/// `3/8 (a + b) + 1/8 (c + d)`.
#[inline(always)]
pub(crate) fn loop_interior_edge<V: Vector>(a: V, b: V, c: V, d: V) -> V {
    let [end, opposite] = LOOP_EDGE;
    a.add(b).scale(end).add(c.add(d).scale(opposite))
}

/// The modified butterfly edge rule (Zorin, Schröder, Sweldens 1996).
///
/// - Interior edge, both ends interior of valence 6: the 8-point stencil
///   `1/2 (a + b) + 1/8 (c + d) - 1/16 (w1 + w2 + w3 + w4)`.
/// - Interior edge with one interior end of valence `k != 6` (the other regular): Zorin's
///   one-ring stencil of the extraordinary end; both extraordinary: the average of the two.
/// - Boundary edge: the 4-point rule `9/16 (a + b) - 1/16 (a' + b')` along the boundary.
/// - Simplifications (documented): an interior edge with exactly one boundary end uses the
///   one-ring stencil of its interior end (regular or not); an interior edge whose two ends
///   are both on the boundary takes the midpoint.
///
/// `rings`: the wide vertex rings ([`WideRings`]), whose one-ring stencils are read off their
/// ring-wide sums.
pub(crate) fn butterfly_edge<V: Vector>(
    t: &Topo<'_>,
    src: &[V],
    rings: Option<&WideRings<V>>,
    e: u32,
) -> V {
    let pos = |v: u32| src[v as usize].clone();
    let h = 2 * e;
    let (va, vb) = (t.source(h), t.target(h));
    let (a, b) = (pos(va), pos(vb));
    if t.is_boundary_edge(e) {
        // Orient along the boundary loop: g is the boundary half-edge of e.
        let g = if t.is_boundary(h) { h } else { h ^ 1 };
        let before = pos(t.source(t.prev(g)));
        let after = pos(t.target(t.next(g)));
        return a
            .add(b)
            .scale(9.0 / 16.0)
            .sub(before.add(after).scale(1.0 / 16.0));
    }
    let a_in = !t.is_boundary_vertex(va);
    let b_in = !t.is_boundary_vertex(vb);
    match (a_in, b_in) {
        (true, true) => {
            let valence = |v: u32, g: u32| match rings.and_then(|r| r.wide.corner(t, g)) {
                Some((slot, _)) => rings.map_or(0, |r| r.wide.size(slot) as usize),
                None => t.valence(v),
            };
            let ka = valence(va, h);
            let kb = valence(vb, h ^ 1);
            match (ka == 6, kb == 6) {
                (true, true) => {
                    let c = pos(t.target(t.next(h)));
                    let d = pos(t.target(t.next(h ^ 1)));
                    let wing = |g: u32| pos(t.target(t.next(g ^ 1)));
                    let w = wing(t.next(h))
                        .add(wing(t.prev(h)))
                        .add(wing(t.next(h ^ 1)))
                        .add(wing(t.prev(h ^ 1)));
                    a.add(b)
                        .scale(0.5)
                        .add(c.add(d).scale(0.125))
                        .sub(w.scale(1.0 / 16.0))
                }
                (false, true) => one_ring_stencil(t, src, rings, h),
                (true, false) => one_ring_stencil(t, src, rings, h ^ 1),
                (false, false) => one_ring_stencil(t, src, rings, h)
                    .add(one_ring_stencil(t, src, rings, h ^ 1))
                    .scale(0.5),
            }
        }
        (true, false) => one_ring_stencil(t, src, rings, h),
        (false, true) => one_ring_stencil(t, src, rings, h ^ 1),
        (false, false) => a.add(b).scale(0.5),
    }
}

/// The interior vertices of a level whose valence is over [`DIRECT_MAX`](super::wide::DIRECT_MAX) and their
/// ring-wide sums (mean and the first two harmonics of their neighbours' positions), for the
/// butterfly's one-ring stencil in `O(1)` per edge rather than `O(k)`.
pub(crate) struct WideRings<V> {
    wide: Wide,
    sums: Vec<Vec<V>>,
}

impl<V: Vector> WideRings<V> {
    /// `None` when no interior vertex of `t` is wide.
    fn of(t: &Topo<'_>, src: &[V]) -> Option<WideRings<V>> {
        let wide = Wide::of(t, Ring::Vertices)?;
        let sums = (0..wide.len())
            .map(|slot| wide.sums(t, slot, 2, |h| src[t.target(h) as usize].clone()))
            .collect();
        Some(WideRings { wide, sums })
    }
}

/// Zorin's stencil around the (interior) source `x` of `g`, valence `k`: `3/4 x + Σ s_j p_j`,
/// `p_0` the target of `g`; `k = 3`: `5/12, -1/12, -1/12`; `k = 4`: `3/8, 0, -1/8, 0`;
/// `k >= 5`: `s_j = (1/4 + cos(2πj/k) + 1/2 cos(4πj/k)) / k`.
///
/// Around a wide vertex (valence over [`DIRECT_MAX`](super::wide::DIRECT_MAX)) the same stencil from its ring-wide
/// sums, `O(1)`: with `θ_j = 2πj/k` from the ring's own first half-edge and `g` its corner
/// `i`, `Σ s_(j-i) p_j = M/4 + cos θ_i C1 + sin θ_i S1 + (cos 2θ_i C2 + sin 2θ_i S2) / 2`,
/// `M` the ring's mean, `C1, S1, C2, S2` its `(1/k) Σ cos(θ_j) p_j`, ... ([`Wide::sums`]).
fn one_ring_stencil<V: Vector>(t: &Topo<'_>, src: &[V], rings: Option<&WideRings<V>>, g: u32) -> V {
    let x = src[t.source(g) as usize].clone();
    if let Some((r, (slot, i))) = rings.and_then(|r| Some((r, r.wide.corner(t, g)?))) {
        let [m, c1, s1, c2, s2] = &r.sums[slot][..] else {
            unreachable!("five sums")
        };
        let k = r.wide.size(slot);
        let (sin, cos) = angle(k, i).sin_cos();
        let (sin2, cos2) = angle(k, (2 * i) % k).sin_cos();
        return x
            .scale(0.75)
            .add(m.clone().scale(0.25))
            .add(c1.clone().scale(cos))
            .add(s1.clone().scale(sin))
            .add(c2.clone().scale(0.5 * cos2))
            .add(s2.clone().scale(0.5 * sin2));
    }
    let k = t.valence(t.source(g));
    let mut sum = V::zero();
    let mut h = g;
    for j in 0..k {
        let s = match (k, j) {
            (3, 0) => 5.0 / 12.0,
            (3, _) => -1.0 / 12.0,
            (4, 0) => 3.0 / 8.0,
            (4, 2) => -1.0 / 8.0,
            (4, _) => 0.0,
            _ => {
                let kf = k as f64;
                let th = 2.0 * PI * j as f64 / kf;
                (0.25 + th.cos() + 0.5 * (2.0 * th).cos()) / kf
            }
        };
        sum = sum.add(src[t.target(h) as usize].clone().scale(s));
        h = t.next(h ^ 1);
    }
    x.scale(0.75).add(sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::subdivide::wide::DIRECT_MAX;
    use crate::HalfEdgeMesh;
    use glam::DVec3;

    /// A wavy bipyramid: apexes 0 (top) and `k + 1` (bottom) of valence `k`, ring `1..=k`.
    fn bipyramid(k: usize) -> HalfEdgeMesh {
        let mut positions = vec![DVec3::new(0.2, -0.1, 1.0)];
        positions.extend((0..k).map(|i| {
            let a = 2.0 * PI * i as f64 / k as f64;
            let r = 1.0 + 0.3 * (3.0 * a).sin();
            DVec3::new(r * a.cos(), r * a.sin(), 0.1 * (5.0 * a).cos())
        }));
        positions.push(DVec3::new(-0.1, 0.3, -1.2));
        let ring = |i: usize| (1 + i % k) as u32;
        let bottom = (k + 1) as u32;
        let faces: Vec<Vec<u32>> = (0..k)
            .flat_map(|i| {
                [
                    vec![0, ring(i), ring(i + 1)],
                    vec![bottom, ring(i + 1), ring(i)],
                ]
            })
            .collect();
        HalfEdgeMesh::try_from_polygons(positions, &faces).expect("a closed bipyramid")
    }

    #[test]
    fn the_four_to_one_slots_are_the_templates() {
        let t = Template::new(2);
        let slots: Vec<usize> = t.slots.iter().map(|&s| s as usize).collect();
        assert_eq!(slots, FOUR_TO_ONE_SLOTS);
        assert_eq!(t.points.len(), 6);
    }

    /// Around a wide vertex the one-ring stencil from the ring-wide sums equals the direct
    /// sum over the ring to 1e-12, from every half-edge; at the threshold no ring is wide.
    #[test]
    fn the_ring_wide_stencil_agrees_with_the_direct_sum() {
        for k in [DIRECT_MAX + 1, 40, 257] {
            let mesh = bipyramid(k);
            let t = Topo::new(&mesh);
            let src = &mesh.positions;
            let rings = WideRings::of(&t, src).expect("two wide apexes");
            assert_eq!(rings.wide.len(), 2);
            let mut checked = 0;
            for g in 0..2 * t.ne() as u32 {
                let v = t.source(g);
                if v != 0 && v != (k + 1) as u32 {
                    continue;
                }
                let wide = one_ring_stencil(&t, src, Some(&rings), g);
                let direct = one_ring_stencil(&t, src, None, g);
                let error = (wide - direct).length();
                assert!(error <= 1e-12, "valence {k}, half-edge {g}: {error:e}");
                checked += 1;
            }
            assert_eq!(checked, 2 * k);
        }
        let mesh = bipyramid(DIRECT_MAX);
        assert!(WideRings::of(&Topo::new(&mesh), &mesh.positions).is_none());
    }
}
