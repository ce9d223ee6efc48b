//! The fast path (the 4:1 family, Catmull-Clark, √3 on closed meshes, Doo-Sabin, mid-edge): every entry of
//! every output array is a pure function of its index, so the arrays are allocated once at
//! their predicted lengths and written front to back (in parallel chunks with rayon).
//!
//! The numbering is the one documented in `trisplit` (for `N = 2`) and `catmull_clark`, with
//! these details:
//!
//! - Output edge `j < 2E` is the piece of old edge `j >> 1` at the source of old half-edge `j`;
//!   its half-edge `2j + (j & 1)` runs from that source to the midpoint (the "source piece" of
//!   old half-edge `j`), the other half is the "target piece" of old half-edge `j ^ 1`.
//! - 4:1: inner edge `2E + 3f + c` joins the midpoints of the face's half-edges `c` and
//!   `c + 1`; face `4f` is the inner triangle and face `4f + 1 + c` the corner triangle at the
//!   target of half-edge `c`.
//! - Catmull-Clark: edge `2E + k` joins the midpoint of the half-edge of corner `k` to the face
//!   point; face `k` is the quad at the source of the half-edge of corner `k`.
//! - √3 on closed meshes, Doo-Sabin and mid-edge: the numbering documented in `sqrt3` and
//!   `dual`.
//!
//! Before writing anything, the counts these formulas produce are compared with the scheme's
//! prediction ([`Error::PredictionMismatch`](crate::Error::PredictionMismatch) on a
//! difference: a bug); the arrays then have exactly the predicted lengths by construction.

use super::build::{Sizes, StepContext};
use super::par;
use super::topo::{Connectivity, Topo};
use crate::mesh::INVALID;
use crate::Result;

/// Checks the structural counts of a step against the prediction.
pub(super) fn check(ctx: &StepContext<'_>, built: Sizes) -> Result<()> {
    let expected = ctx.expected;
    ctx.expect("vertices", expected.vertices, built.vertices)?;
    ctx.expect("edges", expected.halfedges / 2, built.halfedges / 2)?;
    ctx.expect("faces", expected.faces, built.faces)
}

/// The sizes of a 4:1 step on `t`: `V + E` vertices, `2E + 3F` edges, `4F` faces.
pub(super) fn four_to_one_sizes(t: &Topo<'_>) -> Sizes {
    let (nv, ne, nf) = (t.nv(), t.ne(), t.nf());
    Sizes {
        vertices: nv + ne,
        halfedges: 2 * (2 * ne + 3 * nf),
        faces: 4 * nf,
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

/// The connectivity of one 4:1 step on the triangle mesh `t`.
pub(crate) fn four_to_one_topology(t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
    let t = *t;
    check(ctx, four_to_one_sizes(&t))?;
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
