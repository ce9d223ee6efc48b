//! Catmull-Clark subdivision on any polygon mesh, with boundary rules.
//!
//! # Numbering (input `V`, `E`, `F`, `H` face corners)
//!
//! - Vertices: old vertices, then one point per edge (`V + e`), then one per face
//!   (`V + E + f`): `V' = V + E + F`.
//! - Edges: old half-edge `h` (parity `s`) is split into the pieces `2h + s` (the half at its
//!   source) and `2 (h ^ 1) + s` (the half at its target), as half-edge ids; face corner `c`
//!   (corners numbered face by face) gets the edge `2E + c` from its edge point to the face
//!   point: `E' = 2E + H`.
//! - Faces: corner `c` of face `f` (the corner at the source of the face's `c`-th half-edge)
//!   becomes the quad `c`: `F' = H`.
//!
//! Geometry: face points are centroids; interior edge points `(a + b + f1 + f2) / 4`; interior
//! vertices `(Q + 2R + (n - 3) S) / n` (Q the average of the adjacent face points, R of the edge
//! midpoints); boundary edges take the midpoint and boundary vertices `3/4 v + 1/8 (l + r)`.

use glam::DVec3;

use super::build::{Builder, StepContext};
use super::par;
use super::topo::Topo;
use super::trisplit::boundary_vertex;
use crate::{HalfEdgeMesh, Result};

/// One Catmull-Clark step.
pub(crate) fn catmull_clark<const GROW: bool>(
    mesh: &HalfEdgeMesh,
    ctx: &StepContext<'_>,
) -> Result<HalfEdgeMesh> {
    let t = Topo::new(mesh);
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf() as u32);
    let offsets = t.corner_offsets();
    let mut b = Builder::<GROW>::new(ctx.expected)?;
    let mut quad = [(0u32, 0u32); 4];
    for f in 0..nf {
        let fp = nv + ne + f;
        let first = t.face_halfedge(f);
        let off = offsets[f as usize];
        let mut prev = t.prev(first);
        let mut h = first;
        let deg = offsets[f as usize + 1] - off;
        for k in 0..deg {
            let kp = if k == 0 { deg - 1 } else { k - 1 };
            let (s, sp) = (h & 1, prev & 1);
            quad[0] = (t.source(h), 2 * h + s);
            quad[1] = (nv + (h >> 1), 2 * (2 * ne + off + k));
            quad[2] = (fp, 2 * (2 * ne + off + kp) + 1);
            quad[3] = (nv + (prev >> 1), 2 * (prev ^ 1) + sp);
            b.face(&quad);
            prev = h;
            h = t.next(h);
        }
    }

    let capacity = (!GROW).then_some(ctx.expected.vertices);
    b.finish(cc_positions(&t, capacity, ctx.parallel)?, ctx)
}

/// The positions of a Catmull-Clark step: moved old vertices, edge points, face points.
/// `capacity`: allocate exactly this many up front (else grow).
///
/// # Errors
///
/// [`crate::Error::AllocationFailed`] when the system refuses the memory.
pub(crate) fn cc_positions(
    t: &Topo<'_>,
    capacity: Option<usize>,
    parallel: bool,
) -> crate::Result<Vec<DVec3>> {
    let t = *t;
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf() as u32);
    let mut positions = super::alloc::with_capacity_or_grow(capacity, "positions")?;
    // Face points first: the vertex and edge rules use them.
    let face_points = par::collect(
        Some(nf as usize),
        nf as usize,
        parallel,
        "face points",
        |f| {
            let mut sum = DVec3::ZERO;
            let mut n = 0u32;
            t.for_face(f as u32, |h| {
                sum += t.pos(t.source(h));
                n += 1;
            });
            sum / f64::from(n)
        },
    )?;
    let face_point = |f: u32| face_points[f as usize];
    par::extend(&mut positions, nv as usize, parallel, |v| {
        let v = v as u32;
        let p = t.pos(v);
        if t.is_boundary_vertex(v) {
            return boundary_vertex(&t, v);
        }
        let (mut q, mut r, mut n) = (DVec3::ZERO, DVec3::ZERO, 0u32);
        t.for_outgoing(v, |h| {
            q += face_point(t.face(h));
            r += (p + t.pos(t.target(h))) * 0.5;
            n += 1;
        });
        let nf = n as f64;
        (q / nf + r * (2.0 / nf) + p * (nf - 3.0)) / nf
    });
    par::extend(&mut positions, ne as usize, parallel, |e| {
        let h = 2 * e as u32;
        let mid = t.pos(t.source(h)) + t.pos(t.target(h));
        if t.is_boundary(h) || t.is_boundary(h ^ 1) {
            mid * 0.5
        } else {
            (mid + face_point(t.face(h)) + face_point(t.face(h ^ 1))) * 0.25
        }
    });
    positions.extend_from_slice(&face_points);
    Ok(positions)
}
