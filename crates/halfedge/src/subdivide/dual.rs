//! The dual-type schemes on closed polygon meshes: Doo-Sabin and mid-edge (Peters-Reif).
//!
//! # Doo-Sabin numbering (input `V`, `E`, `F`; closed, so every half-edge has a face)
//!
//! - Vertices: the corner at the source of half-edge `h` inside its face is vertex `h`:
//!   `V' = 2E`.
//! - Edges: `h` (joining corners `h` and `next(h)`: the side of the shrunken face) and `2E + h`
//!   (joining corner `h` and corner `next(twin(h))`, the other corner at the same old vertex
//!   across the old edge): `E' = 4E`.
//! - Faces: the shrunken old faces `0..F`, one quad per old edge `F + e`, one face per old
//!   vertex `F + E + v` (its degree is the valence): `F' = F + E + V`.
//!
//! Geometry: the standard Doo-Sabin weights; the corner at `p_0` of an `n`-gon
//! `p_0, ..., p_{n-1}` is `Σ w_j p_j` with `w_0 = (n + 5) / (4n)` and
//! `w_j = (3 + 2 cos(2πj/n)) / (4n)`.
//!
//! # Mid-edge numbering
//!
//! - Vertices: the midpoint of edge `e` is vertex `e`: `V' = E`.
//! - Edges: half-edge `h` gives edge `h`, joining the midpoints of `h` and `next(h)`: `E' = 2E`.
//! - Faces: the old faces (on the midpoints of their edges) `0..F`, then one face per old vertex
//!   `F + v` on the midpoints of its edges: `F' = F + V`.

use std::f64::consts::PI;

use super::build::{Builder, StepContext};
use super::par::Sink;
use super::refine::Vector;
use super::topo::Topo;
use crate::{HalfEdgeMesh, Result};

/// One Doo-Sabin step on `t` (closed, every valence >= 3: checked by the caller), face by
/// face, with the new level's `positions` computed by the caller ([`doo_sabin_points`]).
pub(crate) fn doo_sabin_step<const GROW: bool>(
    t: &Topo<'_>,
    positions: Vec<glam::DVec3>,
    ctx: &StepContext<'_>,
) -> Result<HalfEdgeMesh> {
    let t = *t;
    let ne = t.ne() as u32;
    let mut b = Builder::<GROW>::new(ctx.expected)?;
    face_faces(&t, &mut b, |h| (h, 2 * h));
    for e in 0..ne {
        let (h, tw) = (2 * e, 2 * e + 1);
        b.face(&[
            (t.next(h), 2 * h + 1),
            (h, 2 * (2 * ne + h)),
            (t.next(tw), 2 * tw + 1),
            (tw, 2 * (2 * ne + tw)),
        ]);
    }
    vertex_faces(&t, &mut b, |h, next| (next, 2 * (2 * ne + h) + 1));
    b.finish(positions, ctx)
}

/// One mid-edge step on `t` (closed, every valence >= 3: checked by the caller), face by
/// face, with the new level's `positions` computed by the caller ([`mid_edge_points`]).
pub(crate) fn mid_edge_step<const GROW: bool>(
    t: &Topo<'_>,
    positions: Vec<glam::DVec3>,
    ctx: &StepContext<'_>,
) -> Result<HalfEdgeMesh> {
    let t = *t;
    let mut b = Builder::<GROW>::new(ctx.expected)?;
    face_faces(&t, &mut b, |h| (h >> 1, 2 * h));
    vertex_faces(&t, &mut b, |h, next| (next >> 1, 2 * (h ^ 1) + 1));
    b.finish(positions, ctx)
}

/// Emits the face of each old face, in order: its corner at old half-edge `h` is the
/// `(vertex, half-edge)` pair `corner(h)`.
fn face_faces<const GROW: bool>(
    t: &Topo<'_>,
    b: &mut Builder<GROW>,
    corner: impl Fn(u32) -> (u32, u32),
) {
    let mut corners: Vec<(u32, u32)> = Vec::new();
    for f in 0..t.nf() as u32 {
        corners.clear();
        t.for_face(f, |h| corners.push(corner(h)));
        b.face(&corners);
    }
}

/// Emits the face of each old vertex, in order, its corners running against the outgoing
/// half-edges: `corner(h, next)` for each outgoing `h` and the outgoing `next` after it.
fn vertex_faces<const GROW: bool>(
    t: &Topo<'_>,
    b: &mut Builder<GROW>,
    corner: impl Fn(u32, u32) -> (u32, u32),
) {
    let (mut ring, mut corners): (Vec<u32>, Vec<(u32, u32)>) = (Vec::new(), Vec::new());
    for v in 0..t.nv() as u32 {
        ring.clear();
        t.for_outgoing(v, |h| ring.push(h));
        corners.clear();
        let n = ring.len();
        for k in (0..n).rev() {
            corners.push(corner(ring[k], ring[(k + 1) % n]));
        }
        b.face(&corners);
    }
}

/// The Doo-Sabin points of a step, appended to `out`.
pub(crate) fn doo_sabin_points<V: Vector>(
    t: &Topo<'_>,
    src: &[V],
    out: &mut impl Sink<V>,
    parallel: bool,
) {
    out.append(2 * t.ne(), parallel, |h| doo_sabin_point(t, src, h as u32));
}

/// The mid-edge points of a step, appended to `out`.
pub(crate) fn mid_edge_points<V: Vector>(
    t: &Topo<'_>,
    src: &[V],
    out: &mut impl Sink<V>,
    parallel: bool,
) {
    out.append(t.ne(), parallel, |e| {
        let h = 2 * e as u32;
        src[t.source(h) as usize]
            .clone()
            .add(src[t.target(h) as usize].clone())
            .scale(0.5)
    });
}

/// The Doo-Sabin point of the corner at the source of `h` in its face.
fn doo_sabin_point<V: Vector>(t: &Topo<'_>, src: &[V], h: u32) -> V {
    let n = t.face_degree(t.face(h));
    let nf = n as f64;
    let mut sum = V::zero();
    let mut g = h;
    for j in 0..n {
        let w = if j == 0 {
            (nf + 5.0) / (4.0 * nf)
        } else {
            (3.0 + 2.0 * (2.0 * PI * j as f64 / nf).cos()) / (4.0 * nf)
        };
        sum = sum.add(src[t.source(g) as usize].clone().scale(w));
        g = t.next(g);
    }
    sum
}
