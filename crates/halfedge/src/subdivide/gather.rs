//! The topology of every split (1:N² and 4:1, Catmull-Clark's quads, √3, Doo-Sabin,
//! mid-edge; √3, Doo-Sabin and mid-edge on a boundary apart): every entry of every output
//! array is a pure function of its index, so the arrays are allocated once at their predicted
//! lengths and written front to back (in parallel chunks with rayon).
//!
//! The numbering is the one documented in `trisplit` and `catmull_clark`, with these details:
//!
//! - 1:N²: the half-edges are placed by the split's template (`trisplit::Template`), the one
//!   description of the split's points and triangles that also writes the face lists. For
//!   `N = 2`: output edge `j < 2E` is the piece of old edge `j >> 1` at the source of old
//!   half-edge `j`; its half-edge `2j + (j & 1)` runs from that source to the midpoint;
//!   inner edge `2E + 3f + c` joins the midpoints of the face's half-edges `c` and `c + 1`;
//!   face `4f` is the inner triangle and face `4f + 1 + c` the corner triangle at the target
//!   of half-edge `c`.
//! - Catmull-Clark: output edge `j < 2E` as for 4:1 (the "source piece" of old half-edge `j`
//!   and the "target piece" of `j ^ 1`); edge `2E + k` joins the midpoint of the half-edge of
//!   corner `k` to the face point; face `k` is the quad at the source of the half-edge of
//!   corner `k`.
//! - √3 on closed meshes, Doo-Sabin and mid-edge: the numbering documented in `sqrt3` and
//!   `dual`.
//!
//! Before writing anything, the counts these formulas produce are compared with the scheme's
//! prediction ([`Error::PredictionMismatch`](crate::Error::PredictionMismatch) on a
//! difference: a bug); the arrays then have exactly the predicted lengths by construction.

use super::build::{Sizes, StepContext};
use super::par;
use super::topo::{Connectivity, Topo};
use super::trisplit::{side_of, Around, Template};
use crate::mesh::INVALID;
use crate::Result;

/// Checks the structural counts of a step against the prediction.
pub(super) fn check(ctx: &StepContext<'_>, built: Sizes) -> Result<()> {
    let expected = ctx.expected;
    ctx.expect("vertices", expected.vertices, built.vertices)?;
    ctx.expect("edges", expected.halfedges / 2, built.halfedges / 2)?;
    ctx.expect("faces", expected.faces, built.faces)
}

/// The sizes of a 1:N² step on `t`: `V + (N - 1) E + (N - 1)(N - 2)/2 F` vertices,
/// `N E + 3 N (N - 1)/2 F` edges, `N² F` faces (for `N = 2`: `V + E`, `2E + 3F`, `4F`).
pub(super) fn tri_split_sizes(t: &Topo<'_>, n: u32) -> Sizes {
    let (nv, ne, nf) = (t.nv(), t.ne(), t.nf());
    let n = n as usize;
    Sizes {
        vertices: nv + (n - 1) * ne + (n - 1) * (n - 2) / 2 * nf,
        halfedges: 2 * (n * ne + 3 * n * (n - 1) / 2 * nf),
        faces: n * n * nf,
    }
}

/// The sizes of a Catmull-Clark step on `t`: `V + E + F` vertices, `2E + H` edges and `H`
/// faces, `H` the face corners (the half-edges that are not on the boundary).
pub(super) fn catmull_clark_sizes(t: &Topo<'_>) -> Sizes {
    let (nv, ne, nf) = (t.nv(), t.ne(), t.nf());
    let n_corners = 2 * ne - t.boundary_edges();
    Sizes {
        vertices: nv + ne + nf,
        halfedges: 2 * (2 * ne + n_corners),
        faces: n_corners,
    }
}

/// The source piece of old half-edge `h`: from its source to its midpoint.
#[inline]
fn source_piece(h: u32) -> u32 {
    2 * h + (h & 1)
}

/// The target piece of old half-edge `h`: from its midpoint to its target.
#[inline]
fn target_piece(h: u32) -> u32 {
    2 * (h ^ 1) + (h & 1)
}

/// Decodes an output half-edge `q < 4E` into (old half-edge, is the source piece).
#[inline]
fn piece(q: u32) -> (u32, bool) {
    let j = q >> 1;
    if q & 1 == j & 1 {
        (j, true)
    } else {
        (j ^ 1, false)
    }
}

/// `[vertex, face, next, prev]` of a piece of a boundary old half-edge (the boundary loops
/// of the output follow the old ones).
#[inline]
fn boundary_piece(t: &Topo<'_>, nv: u32, h: u32, source: bool) -> [u32; 4] {
    if source {
        [
            nv + (h >> 1),
            INVALID,
            target_piece(h),
            target_piece(t.prev(h)),
        ]
    } else {
        [
            t.target(h),
            INVALID,
            source_piece(t.next(h)),
            source_piece(h),
        ]
    }
}

/// The outgoing half-edge of the midpoint of old edge `e` (the boundary one on the boundary).
#[inline]
fn midpoint_halfedge(t: &Topo<'_>, e: u32) -> u32 {
    let h = 2 * e;
    if t.is_boundary(h) {
        target_piece(h)
    } else if t.is_boundary(h ^ 1) {
        target_piece(h ^ 1)
    } else {
        target_piece(h)
    }
}

/// The connectivity of one 1:N² step (4:1 for `N = 2`) on the triangle mesh `t`, every
/// output half-edge placed by the split's template (`trisplit::Template`: the numbering of
/// the `trisplit` module docs): edge pieces first, each in the triangle of the face it runs
/// along (or on the boundary loop), then each face's interior edges.
pub(crate) fn tri_split_topology(
    t: &Topo<'_>,
    template: &Template,
    ctx: &StepContext<'_>,
) -> Result<Connectivity> {
    if template.n == 2 {
        four_to_one_topology(t, ctx)
    } else {
        by_template(t, template, ctx)
    }
}

/// [`tri_split_topology`] read from the template, for any `N`.
fn by_template(t: &Topo<'_>, template: &Template, ctx: &StepContext<'_>) -> Result<Connectivity> {
    let t = *t;
    let n = template.n;
    check(ctx, tri_split_sizes(&t, n))?;
    let (nv, ne) = (t.nv() as u32, t.ne() as u32);
    let pieces = 2 * n * ne;
    let per_face = template.interior_edges();
    // Piece `j` (from the source) of old half-edge `h`, as an output half-edge.
    let piece_of = |h: u32, j: u32| template.piece_along(side_of(h), j);
    // The point at `j` (`1..N`) along old half-edge `h`.
    let point_of = |h: u32, j: u32| template.point_along(side_of(h), j, nv);
    let around = |f: u32| {
        let h0 = t.face_halfedge(f);
        Around {
            t,
            sides: [h0, t.next(h0), t.prev(h0)],
            face: f,
        }
    };
    let halfedge = |q: u32| {
        if q < pieces {
            let (p, d) = (q >> 1, q & 1);
            let (e, k) = (p / n, p % n);
            let h = 2 * e + d;
            let j = if d == 0 { k } else { n - 1 - k };
            let f = t.face(h);
            if f == INVALID {
                // On the boundary loop, which follows the old one.
                let target = if j + 1 == n {
                    t.target(h)
                } else {
                    point_of(h, j + 1)
                };
                let next = if j + 1 == n {
                    piece_of(t.next(h), 0)
                } else {
                    piece_of(h, j + 1)
                };
                let prev = if j == 0 {
                    piece_of(t.prev(h), n - 1)
                } else {
                    piece_of(h, j - 1)
                };
                return [target, INVALID, next, prev];
            }
            // The side of h in its face from its neighbours, next to h in memory (no second
            // random load through the face's first half-edge).
            let h0 = t.face_halfedge(f);
            let (next, prev) = (t.next(h), t.prev(h));
            let (s, sides) = if h == h0 {
                (0, [h, next, prev])
            } else if prev == h0 {
                (1, [prev, h, next])
            } else {
                (2, [next, prev, h])
            };
            let (tri, c) = template.piece_corner(s, j);
            template.halfedge(tri, c, &Around { t, sides, face: f }, nv, ne)
        } else {
            let r = q - pieces;
            let (p, half) = (r >> 1, r & 1);
            let (f, edge) = (p / per_face, p % per_face);
            let (tri, c) = template.interior_corner(edge, half);
            template.halfedge(tri, c, &around(f), nv, ne)
        }
    };
    let n_points = template.interior_points.len() as u32;
    let vertex = |v: u32| {
        if v < nv {
            // The first piece of the vertex's half-edge (the boundary one on the boundary).
            piece_of(t.vertex_halfedge(v), 0)
        } else if v < nv + (n - 1) * ne {
            // Point `k + 1` of edge `e`: along half-edge 2e, or along 2e + 1 when that one
            // is on the boundary.
            let (e, k) = ((v - nv) / (n - 1), (v - nv) % (n - 1));
            if t.is_boundary(2 * e + 1) && !t.is_boundary(2 * e) {
                piece_of(2 * e + 1, n - 1 - k)
            } else {
                piece_of(2 * e, k + 1)
            }
        } else {
            let i = v - nv - (n - 1) * ne;
            let (f, point) = (i / n_points, i % n_points);
            let (tri, c) = template.interior_point_corner(point);
            template.side(tri, c, &around(f), ne)
        }
    };
    let face = |g: u32| {
        let (f, tri) = (g / (n * n), g % (n * n));
        template.side(tri as usize, 0, &around(f), ne)
    };
    assemble(ctx, halfedge, vertex, face)
}

/// The connectivity of one 4:1 step on the triangle mesh `t`: the template's formulas
/// ([`tri_split_topology`]) for `N = 2` written out, for the hottest step of the library (Loop
/// on millions of faces; the template-driven formulas take 2.4x its time there). A test
/// checks that both give the same arrays, closed and with boundary.
fn four_to_one_topology(t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
    let t = *t;
    check(ctx, tri_split_sizes(&t, 2))?;
    let (nv, ne) = (t.nv() as u32, t.ne() as u32);
    let inner = 4 * ne; // first inner half-edge
    let halfedge = |q| {
        if q < inner {
            let (h, source) = piece(q);
            let f = t.face(h);
            if f == INVALID {
                return boundary_piece(&t, nv, h, source);
            }
            // The position `i` of h in its face comes from the neighbour the piece needs
            // anyway (prev for a source piece, next for a target piece), which sits next to
            // h in memory: no second random load through the face's first half-edge.
            let h0 = t.face_halfedge(f);
            if source {
                let p = t.prev(h);
                let i = if h == h0 {
                    0
                } else if p == h0 {
                    1
                } else {
                    2
                };
                // Corner triangle c = i - 1 (at the source of h).
                let c = (i + 2) % 3;
                [
                    nv + (h >> 1),
                    4 * f + 1 + c,
                    inner + 2 * (3 * f + c) + 1,
                    target_piece(p),
                ]
            } else {
                let n = t.next(h);
                let i = if h == h0 {
                    0
                } else if n == h0 {
                    2
                } else {
                    1
                };
                [
                    t.target(h),
                    4 * f + 1 + i,
                    source_piece(n),
                    inner + 2 * (3 * f + i) + 1,
                ]
            }
        } else {
            let r = q - inner;
            let k = r >> 1;
            let (f, c) = (k / 3, k % 3);
            let h0 = t.face_halfedge(f);
            let hs = [h0, t.next(h0), t.prev(h0)];
            let (hc, hc1) = (hs[c as usize], hs[((c + 1) % 3) as usize]);
            if r & 1 == 0 {
                // Inner triangle: m_c -> m_{c+1}.
                [
                    nv + (hc1 >> 1),
                    4 * f,
                    inner + 2 * (3 * f + (c + 1) % 3),
                    inner + 2 * (3 * f + (c + 2) % 3),
                ]
            } else {
                // Corner triangle c: m_{c+1} -> m_c.
                [
                    nv + (hc >> 1),
                    4 * f + 1 + c,
                    target_piece(hc),
                    source_piece(hc1),
                ]
            }
        }
    };
    let vertex = |v| {
        if v < nv {
            source_piece(t.vertex_halfedge(v))
        } else {
            midpoint_halfedge(&t, v - nv)
        }
    };
    let face = |g| {
        let (f, k) = (g / 4, g % 4);
        if k == 0 {
            inner + 2 * (3 * f)
        } else {
            inner + 2 * (3 * f + k - 1) + 1
        }
    };
    assemble(ctx, halfedge, vertex, face)
}

/// The connectivity of one Catmull-Clark step on `t`.
pub(crate) fn catmull_clark_topology(t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
    let t = *t;
    let built = catmull_clark_sizes(&t);
    check(ctx, built)?;
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf() as u32);
    let n_corners = built.faces;
    // Corners numbered face by face: corner_of[h] for face half-edges, and the inverse. On a
    // quad mesh (every level after the first) corner k is the (k % 4)-th half-edge of face
    // k / 4, so the inverse table is skipped (one u32 per corner less at the peak).
    let quads = t.is_quad_mesh();
    let mut corner_of = super::alloc::filled(INVALID, 2 * ne as usize, "corner of")?;
    let mut corner_halfedge =
        super::alloc::with_capacity(if quads { 0 } else { n_corners }, "corner halfedge")?;
    let mut corners = 0u32;
    for f in 0..nf {
        t.for_face(f, |h| {
            corner_of[h as usize] = corners;
            if !quads {
                corner_halfedge.push(h);
            }
            corners += 1;
        });
    }
    ctx.expect("faces", n_corners, corners as usize)?;
    let corner_h = |k: u32| -> u32 {
        if quads {
            let mut h = t.face_halfedge(k / 4);
            for _ in 0..k % 4 {
                h = t.next(h);
            }
            h
        } else {
            corner_halfedge[k as usize]
        }
    };
    let inner = 4 * ne;
    let corner = |h: u32| corner_of[h as usize];
    let halfedge = |q| {
        if q < inner {
            let (h, source) = piece(q);
            if t.is_boundary(h) {
                return boundary_piece(&t, nv, h, source);
            }
            if source {
                [
                    nv + (h >> 1),
                    corner(h),
                    inner + 2 * corner(h),
                    target_piece(t.prev(h)),
                ]
            } else {
                [
                    t.target(h),
                    corner(t.next(h)),
                    source_piece(t.next(h)),
                    inner + 2 * corner(h) + 1,
                ]
            }
        } else {
            let r = q - inner;
            let k = r >> 1;
            let h = corner_h(k);
            if r & 1 == 0 {
                // Midpoint of h -> face point, in quad k.
                [
                    nv + ne + t.face(h),
                    k,
                    inner + 2 * corner(t.prev(h)) + 1,
                    source_piece(h),
                ]
            } else {
                // Face point -> midpoint of h, in the quad of next(h).
                let n = t.next(h);
                [
                    nv + (h >> 1),
                    corner(n),
                    target_piece(h),
                    inner + 2 * corner(n),
                ]
            }
        }
    };
    let vertex = |v| {
        if v < nv {
            source_piece(t.vertex_halfedge(v))
        } else if v < nv + ne {
            midpoint_halfedge(&t, v - nv)
        } else {
            // The first corner of the face is the one of its first half-edge.
            inner + 2 * corner(t.face_halfedge(v - nv - ne)) + 1
        }
    };
    let face = |k| source_piece(corner_h(k));
    assemble(ctx, halfedge, vertex, face)
}

/// The connectivity of one √3 step on the closed triangle mesh `t`.
pub(crate) fn sqrt3_closed_topology(t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
    let t = *t;
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf() as u32);
    let built = Sizes {
        vertices: (nv + nf) as usize,
        halfedges: 2 * (ne as usize + 3 * nf as usize),
        faces: 3 * nf as usize,
    };
    check(ctx, built)?;
    // The position of g in its face from prev(g), next to g in memory (no second random load
    // through the face's first half-edge).
    let corner = |g: u32| {
        let f = t.face(g);
        let h0 = t.face_halfedge(f);
        3 * f
            + if g == h0 {
                0
            } else if t.prev(g) == h0 {
                1
            } else {
                2
            }
    };
    let spoke = |g: u32| 2 * (ne + corner(g));
    let first_spoke = 2 * ne;
    let halfedge = |q| {
        if q < first_spoke {
            // The flipped edge: centroid of face(g) -> centroid of face(g ^ 1), in T(g).
            let g = q;
            [
                nv + t.face(g ^ 1),
                corner(g),
                spoke(g ^ 1) + 1,
                spoke(t.next(g)),
            ]
        } else {
            let c = (q - first_spoke) >> 1;
            let f = c / 3;
            let g = t.triangle_side(f, c % 3);
            if q & 1 == 0 {
                // Corner -> centroid, in T(prev g).
                let p = t.prev(g);
                [nv + f, corner(p), p, spoke(p ^ 1) + 1]
            } else {
                // Centroid -> corner, in T(g ^ 1).
                [t.source(g), corner(g ^ 1), spoke(t.next(g ^ 1)), g ^ 1]
            }
        }
    };
    let vertex = |v| {
        if v < nv {
            spoke(t.vertex_halfedge(v))
        } else {
            spoke(t.face_halfedge(v - nv)) + 1
        }
    };
    let face = |c| t.triangle_side(c / 3, c % 3);
    assemble(ctx, halfedge, vertex, face)
}

/// Zero positions for a face-by-face step that builds only the topology.
fn zeros(ctx: &StepContext<'_>) -> Result<Vec<glam::DVec3>> {
    super::alloc::filled(glam::DVec3::ZERO, ctx.expected.vertices, "positions")
}

/// A dual step's builder on a mesh with boundary (positions written later: zeros here).
type BoundaryDual =
    fn(&Topo<'_>, Vec<glam::DVec3>, &StepContext<'_>) -> Result<crate::HalfEdgeMesh>;

/// The connectivity of a dual step on `t` with boundary, built face by face by `build`.
fn with_boundary(t: &Topo<'_>, ctx: &StepContext<'_>, build: BoundaryDual) -> Result<Connectivity> {
    build(t, zeros(ctx)?, ctx).map(Connectivity::from_mesh)
}

/// `[V, E, F]` of `t` as `u32`.
fn counts_of(t: &Topo<'_>) -> [u32; 3] {
    [t.nv() as u32, t.ne() as u32, t.nf() as u32]
}

/// The output sizes of index formulas' counts (`u32`, as the handles).
fn sizes([vertices, halfedges, faces]: [u32; 3]) -> Sizes {
    let [vertices, halfedges, faces] = [vertices, halfedges, faces].map(|n| n as usize);
    Sizes {
        vertices,
        halfedges,
        faces,
    }
}

/// The connectivity of one Doo-Sabin step on `t` (with boundary: built face by face).
pub(crate) fn doo_sabin_topology(t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
    if !t.is_closed() {
        return with_boundary(t, ctx, super::dual::doo_sabin_with_boundary);
    }
    let ([nv, ne, nf], t) = (counts_of(t), *t);
    check(ctx, sizes([2 * ne, 8 * ne, nf + ne + nv]))?;
    let b0 = 4 * ne;
    let halfedge = |q| {
        if q < b0 {
            let g = q >> 1;
            if q & 1 == 0 {
                // Side of the shrunken face: corner g -> corner next(g).
                [t.next(g), t.face(g), 2 * t.next(g), 2 * t.prev(g)]
            } else {
                // The same side in the edge quad: corner next(g) -> corner g.
                [g, nf + (g >> 1), b0 + 2 * g, b0 + 2 * (g ^ 1)]
            }
        } else {
            let g = (q - b0) >> 1;
            let across = t.next(g ^ 1);
            if q & 1 == 0 {
                // In the edge quad: corner g -> corner next(twin g).
                [across, nf + (g >> 1), 2 * (g ^ 1) + 1, 2 * g + 1]
            } else {
                // In the vertex face of source(g): corner next(twin g) -> corner g.
                [
                    g,
                    nf + ne + t.source(g),
                    b0 + 2 * (t.prev(g) ^ 1) + 1,
                    b0 + 2 * across + 1,
                ]
            }
        }
    };
    let face = |f| {
        if f < nf {
            2 * t.face_halfedge(f)
        } else if f < nf + ne {
            2 * (2 * (f - nf)) + 1
        } else {
            b0 + 2 * t.vertex_halfedge(f - nf - ne) + 1
        }
    };
    assemble(ctx, halfedge, |h| 2 * h, face)
}

/// The connectivity of one mid-edge step on `t` (with boundary: built face by face).
pub(crate) fn mid_edge_topology(t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
    if !t.is_closed() {
        return with_boundary(t, ctx, super::dual::mid_edge_with_boundary);
    }
    let ([nv, ne, nf], t) = (counts_of(t), *t);
    check(ctx, sizes([ne, 4 * ne, nf + nv]))?;
    let halfedge = |q: u32| {
        let h = q >> 1;
        if q & 1 == 0 {
            [t.next(h) >> 1, t.face(h), 2 * t.next(h), 2 * t.prev(h)]
        } else {
            [
                h >> 1,
                nf + t.target(h),
                2 * t.prev(h ^ 1) + 1,
                2 * (t.next(h) ^ 1) + 1,
            ]
        }
    };
    let face = |f| {
        if f < nf {
            2 * t.face_halfedge(f)
        } else {
            2 * (t.vertex_halfedge(f - nf) ^ 1) + 1
        }
    };
    assemble(ctx, halfedge, |e| 4 * e, face)
}

/// The connectivity of a step whose counts [`check`] accepted, every array written front to
/// back from its index formula (in parallel chunks when the step is parallel):
/// `halfedge(q)` is `[vertex, face, next, prev]` of output half-edge `q`, `vertex(v)` the
/// half-edge of output vertex `v`, `face(f)` the half-edge of output face `f`; every length
/// and capacity is checked against the prediction.
fn assemble(
    ctx: &StepContext<'_>,
    halfedge: impl Fn(u32) -> [u32; 4] + Sync + Send,
    vertex: impl Fn(u32) -> u32 + Sync + Send,
    face: impl Fn(u32) -> u32 + Sync + Send,
) -> Result<Connectivity> {
    let (e, parallel) = (ctx.expected, ctx.parallel);
    let halfedges = par::halfedge_arrays(e.halfedges, parallel, halfedge)?;
    let vertex_halfedge = par::collect(e.vertices, parallel, "vertex halfedge", |v| {
        vertex(v as u32)
    })?;
    let face_halfedge = par::collect(e.faces, parallel, "face halfedge", |f| face(f as u32))?;
    for (what, predicted, len, capacity) in [
        (
            "vertices",
            e.vertices,
            vertex_halfedge.len(),
            vertex_halfedge.capacity(),
        ),
        (
            "half-edges",
            e.halfedges,
            halfedges[0].len(),
            halfedges[0].capacity(),
        ),
        (
            "faces",
            e.faces,
            face_halfedge.len(),
            face_halfedge.capacity(),
        ),
    ] {
        ctx.expect_exact(what, predicted, len, capacity)?;
    }
    Ok(Connectivity::from_parts(
        vertex_halfedge,
        halfedges,
        face_halfedge,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::HalfEdgeMesh;

    /// The 4:1 formulas written out are the template's for `N = 2`, on a closed mesh, one
    /// with boundary and one with holes, at two levels.
    #[test]
    fn the_four_to_one_formulas_are_the_templates() {
        let meshes = [
            crate::shapes::icosahedron(),
            crate::shapes::grid(3, 2).expect("a grid"),
            crate::shapes::icosahedron_holes(3).expect("icosahedron with holes"),
        ];
        let template = Template::new(2);
        for (k, polygons) in meshes.iter().enumerate() {
            let mut mesh = HalfEdgeMesh::try_from_polygon_mesh(polygons).expect("a manifold");
            for level in 1..=2 {
                let t = Topo::new(&mesh);
                for parallel in [false, true] {
                    let ctx = StepContext {
                        scheme: "4:1",
                        level,
                        expected: tri_split_sizes(&t, 2),
                        parallel,
                    };
                    let fast = four_to_one_topology(&t, &ctx).expect("4:1");
                    let general = by_template(&t, &template, &ctx).expect("template");
                    assert_eq!(fast.vertex_halfedge, general.vertex_halfedge, "mesh {k}");
                    assert_eq!(fast.halfedge_vertex, general.halfedge_vertex, "mesh {k}");
                    assert_eq!(fast.halfedge_face, general.halfedge_face, "mesh {k}");
                    assert_eq!(fast.halfedge_next, general.halfedge_next, "mesh {k}");
                    assert_eq!(fast.halfedge_prev, general.halfedge_prev, "mesh {k}");
                    assert_eq!(fast.face_halfedge, general.face_halfedge, "mesh {k}");
                }
                let ctx = StepContext {
                    scheme: "4:1",
                    level,
                    expected: tri_split_sizes(&t, 2),
                    parallel: false,
                };
                let next = four_to_one_topology(&t, &ctx).expect("4:1");
                let n = next.vertex_halfedge.len();
                mesh = next.with_positions(vec![glam::DVec3::ZERO; n]);
            }
        }
    }
}
