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
//! vertices `(n - 2) / n S + 1 / n² (Σ face points + Σ neighbours)` (the smooth mask of
//! `sdc::masks::catmull_clark_smooth`, the classic `(Q + 2R + (n - 3) S) / n` rewritten);
//! boundary edges take the midpoint and boundary vertices `3/4 v + 1/8 (l + r)`.

use super::data::Vector;
use super::par::{Sink, Slots};
use super::sdc::masks::{catmull_clark_smooth, CATMULL_CLARK_EDGE};
use super::topo::Topo;
use super::trisplit::boundary_vertex;

/// The values of a Catmull-Clark step from the values `src` of the level before, into `dst`
/// (exactly `V + E + F` values: moved old vertices, edge points, face points): the face points
/// are written first, at the end of `dst`, and read from there.
pub(crate) fn cc_fill<V: Vector>(t: &Topo<'_>, src: &[V], dst: &mut [V], parallel: bool) {
    let t = *t;
    let (nv, ne) = (t.nv(), t.ne());
    let (head, face_points) = dst.split_at_mut((nv + ne).min(dst.len()));
    let mut out = Slots::new(face_points);
    out.append(t.nf(), parallel, |f| cc_face_point(&t, src, f as u32));
    let face_points: &[V] = face_points;
    let mut out = Slots::new(head);
    out.append(nv, parallel, |v| cc_vertex(&t, src, face_points, v as u32));
    out.append(ne, parallel, |e| cc_edge(&t, src, face_points, e as u32));
}

/// The centroid of face `f`.
#[inline]
pub(crate) fn cc_face_point<V: Vector>(t: &Topo<'_>, src: &[V], f: u32) -> V {
    let mut sum = V::zero();
    let mut n = 0u32;
    t.for_face(f, |h| {
        sum = sum.clone().add(src[t.source(h) as usize].clone());
        n += 1;
    });
    sum.div(f64::from(n))
}

/// The moved old vertex `v`: the smooth mask inside, the boundary rule on the boundary.
#[inline]
pub(crate) fn cc_vertex<V: Vector>(t: &Topo<'_>, src: &[V], face_points: &[V], v: u32) -> V {
    if t.is_boundary_vertex(v) {
        return boundary_vertex(t, src, v);
    }
    let (mut faces, mut ends, mut n) = (V::zero(), V::zero(), 0usize);
    t.for_outgoing(v, |h| {
        faces = faces.clone().add(face_points[t.face(h) as usize].clone());
        ends = ends.clone().add(src[t.target(h) as usize].clone());
        n += 1;
    });
    cc_interior(src[v as usize].clone(), faces, ends, n)
}

/// Catmull-Clark's smooth vertex mask ([`catmull_clark_smooth`]) on the vertex `p`, the sum
/// `faces` of its `n` face points and the sum `ends` of its `n` neighbours: the smaller
/// weights first (OpenSubdiv weighs each term; the sums here are scaled once).
#[inline(always)]
pub(crate) fn cc_interior<V: Vector>(p: V, faces: V, ends: V, n: usize) -> V {
    let (vertex, each) = catmull_clark_smooth(n);
    faces.add(ends).scale(each).add(p.scale(vertex))
}

/// The point of edge `e`: `(a + b + f1 + f2) / 4` inside, the midpoint on the boundary.
#[inline]
pub(crate) fn cc_edge<V: Vector>(t: &Topo<'_>, src: &[V], face_points: &[V], e: u32) -> V {
    let h = 2 * e;
    let mid = src[t.source(h) as usize]
        .clone()
        .add(src[t.target(h) as usize].clone());
    if t.is_boundary(h) || t.is_boundary(h ^ 1) {
        mid.scale(0.5)
    } else {
        let (f1, f2) = (t.face(h) as usize, t.face(h ^ 1) as usize);
        cc_interior_edge(mid, face_points[f1].clone(), face_points[f2].clone())
    }
}

/// Catmull-Clark's smooth edge rule on the sum `ends` of the edge's ends and its two face
/// points: `(a + b + f1 + f2) / 4`.
#[inline(always)]
pub(crate) fn cc_interior_edge<V: Vector>(ends: V, f1: V, f2: V) -> V {
    ends.add(f1).add(f2).scale(CATMULL_CLARK_EDGE)
}

/// The child quad at a corner of face `face` on a level of `nv` vertices and `ne` edges:
/// `[corner, point of edge side, face point, point of edge before]`, the corner's vertex, the
/// edge of the side leaving it and the edge of the side arriving at it (the numbering of the
/// module docs, shared by the last level as a face list and raw face lists).
#[inline(always)]
pub(crate) fn quad_corners(
    nv: u32,
    ne: u32,
    face: u32,
    corner: u32,
    side: u32,
    before: u32,
) -> [u32; 4] {
    [corner, nv + side, nv + ne + face, nv + before]
}
