//! The dual-type schemes on polygon meshes: Doo-Sabin and mid-edge (Peters-Reif), closed or
//! with boundary.
//!
//! # Doo-Sabin numbering (input `V`, `E`, `F`)
//!
//! - Vertices: the corner at the source of half-edge `h` inside its face is vertex `h`:
//!   `V' = 2E` on a closed mesh. On a boundary half-edge `h` (no face), vertex `h` is the
//!   Chaikin point of its edge near its source, `(3 source + target) / 4`, and vertex
//!   `2E + r` the one near its target, `r` the rank of `h` among the boundary half-edges
//!   (in increasing order): `V' = 2E + BE`.
//! - Edges: `h` (joining corners `h` and `next(h)`: the side of the shrunken face; on a
//!   boundary half-edge, the outer side of its boundary quad, joining its two Chaikin points)
//!   and `2E + h` (joining vertex `h` to the other vertex at the same old vertex across the old
//!   edge: corner `next(twin(h))`, or the Chaikin point near the source of `h` when `twin(h)`
//!   is a boundary half-edge): `E' = 4E`. With boundary, edge `4E + r` joins the two Chaikin
//!   points at the source of boundary half-edge `r` (the side of that vertex's face on the
//!   new boundary): `E' = 4E + BE`.
//! - Faces: the shrunken old faces `0..F`, one quad per old edge `F + e` (on a boundary edge:
//!   the face's two corners on it and its two Chaikin points), one face per old vertex
//!   `F + E + v` (its degree is the valence inside; `k + 2` on the boundary, `k` the number of
//!   faces at it: a triangle at a corner with one face): `F' = F + E + V`.
//!
//! Geometry: the standard Doo-Sabin weights; the corner at `p_0` of an `n`-gon
//! `p_0, ..., p_{n-1}` is `Σ w_j p_j` with `w_0 = (n + 5) / (4n)` and
//! `w_j = (3 + 2 cos(2πj/n)) / (4n)`, for every face, boundary or not; the boundary points
//! are Chaikin's, so the boundary converges to the quadratic B-spline of the boundary polygon
//! (the rule and its sources: [`schemes::catalog::doo_sabin_boundary`]). A face of more than
//! [`DIRECT_MAX`](super::wide::DIRECT_MAX) sides gets its corners from three face-wide sums instead of a sum
//! over the face per corner (the same weights, `O(n)` rather than `O(n²)` per face), positions
//! and UVs alike.
//!
//! # Mid-edge numbering
//!
//! - Vertices: the midpoint of edge `e` is vertex `e`: `V' = E`. With boundary, vertex `E + r`
//!   is the old source of boundary half-edge `r`, kept and moved by the cubic B-spline rule
//!   `(a + 6v + b) / 8`: `V' = E + BE`.
//! - Edges: a face half-edge `h` gives edge `h`, joining the midpoints of `h` and `next(h)`:
//!   `E' = 2E` on a closed mesh. With boundary, boundary half-edge `h` gives edge `h`, joining
//!   its kept source to its midpoint, and edge `2E + r` joins the midpoint of boundary
//!   half-edge `r` to its kept target: `E' = 2E + BE`.
//! - Faces: the old faces (on the midpoints of their edges) `0..F`, then one face per old vertex
//!   `F + v` on the midpoints of its edges (and, on the boundary, on the kept vertex itself: a
//!   triangle at a corner with one face): `F' = F + V`.
//!
//! The rule and its sources: [`schemes::catalog::mid_edge_boundary`].

use std::f64::consts::PI;

use glam::DVec3;

use super::build::{Builder, StepContext};
use super::corner_step::{seam_ranks, CornerStep};
use super::data::Vector;
use super::par::Sink;
use super::topo::Topo;
use super::trisplit::boundary_vertex;
use super::weights::WeightTable;
use super::wide::{angle, Ring, Wide};
use crate::mesh::INVALID;
use crate::{HalfEdgeMesh, Result};

/// The rank of each boundary half-edge among the boundary half-edges in increasing order
/// (`INVALID` on the others).
fn boundary_ranks(t: &Topo<'_>) -> Result<Vec<u32>> {
    let mut rank = super::alloc::filled(INVALID, 2 * t.ne(), "boundary ranks")?;
    let mut next = 0u32;
    for h in 0..2 * t.ne() as u32 {
        if t.is_boundary(h) {
            rank[h as usize] = next;
            next += 1;
        }
    }
    Ok(rank)
}

/// One Doo-Sabin step on the mesh `t` with boundary (the numbering of the module docs), with
/// the new level's `positions` computed by the caller ([`doo_sabin_points`]).
pub(crate) fn doo_sabin_with_boundary(
    t: &Topo<'_>,
    positions: Vec<DVec3>,
    ctx: &StepContext<'_>,
) -> Result<HalfEdgeMesh> {
    let (t, ne, rank, mut b) = start_with_boundary(t, ctx, |h| (h, 2 * h))?;
    // The Chaikin point near the target of boundary half-edge h.
    let near_target = |h: u32| 2 * ne + rank[h as usize];
    for e in 0..ne {
        let (mut h, mut tw) = (2 * e, 2 * e + 1);
        if t.is_boundary(h) {
            (h, tw) = (tw, h);
        }
        // `h` has a face; `tw` too inside, on the boundary its Chaikin points stand in for
        // the corners `next(tw)` and `tw`.
        let across = if t.is_boundary(tw) {
            near_target(tw)
        } else {
            t.next(tw)
        };
        b.face(&[
            (t.next(h), 2 * h + 1),
            (h, 2 * (2 * ne + h)),
            (across, 2 * tw + 1),
            (tw, 2 * (2 * ne + tw)),
        ]);
    }
    vertex_faces(&t, &mut b, |ring, corners| {
        let (n, first) = (ring.len(), ring[0]);
        if t.is_boundary(first) {
            // ring[0] is the outgoing boundary half-edge, ring[n - 1] the face half-edge whose
            // twin is the incoming one: Chaikin point near v on the incoming edge, the corners
            // at v, the Chaikin point near v on the outgoing edge.
            let last = ring[n - 1];
            corners.push((near_target(last ^ 1), 2 * (2 * ne + last) + 1));
            for k in (0..n - 1).rev() {
                corners.push((ring[k + 1], 2 * (2 * ne + ring[k]) + 1));
            }
            corners.push((first, 2 * (4 * ne + rank[first as usize]) + 1));
        } else {
            for k in (0..n).rev() {
                corners.push((ring[(k + 1) % n], 2 * (2 * ne + ring[k]) + 1));
            }
        }
    });
    b.finish(positions, ctx)
}

/// One mid-edge step on the mesh `t` with boundary (the numbering of the module docs), with
/// the new level's `positions` computed by the caller ([`mid_edge_points`]).
pub(crate) fn mid_edge_with_boundary(
    t: &Topo<'_>,
    positions: Vec<DVec3>,
    ctx: &StepContext<'_>,
) -> Result<HalfEdgeMesh> {
    let (t, ne, rank, mut b) = start_with_boundary(t, ctx, |h| (h >> 1, 2 * h))?;
    vertex_faces(&t, &mut b, |ring, corners| {
        let (n, first) = (ring.len(), ring[0]);
        if t.is_boundary(first) {
            // The midpoint of the outgoing boundary edge, the kept vertex, the midpoint of the
            // incoming boundary edge, then the midpoints of the interior edges.
            let incoming = ring[n - 1] ^ 1;
            corners.push((first >> 1, 2 * first + 1));
            corners.push((
                ne + rank[first as usize],
                2 * (2 * ne + rank[incoming as usize]) + 1,
            ));
            for k in (0..n - 1).rev() {
                corners.push((ring[k + 1] >> 1, 2 * (ring[k] ^ 1) + 1));
            }
        } else {
            for k in (0..n).rev() {
                corners.push((ring[(k + 1) % n] >> 1, 2 * (ring[k] ^ 1) + 1));
            }
        }
    });
    b.finish(positions, ctx)
}

/// The start of a step on a mesh with boundary: the edges, each boundary half-edge's rank
/// ([`boundary_ranks`]) and a builder holding the face of each old face (`corner` as in
/// [`face_faces`]).
fn start_with_boundary<'a>(
    t: &Topo<'a>,
    ctx: &StepContext<'_>,
    corner: impl Fn(u32) -> (u32, u32),
) -> Result<(Topo<'a>, u32, Vec<u32>, Builder)> {
    let t = *t;
    let rank = boundary_ranks(&t)?;
    let mut b = Builder::new(ctx.expected)?;
    face_faces(&t, &mut b, corner);
    Ok((t, t.ne() as u32, rank, b))
}

/// Emits the face of each old face, in order: its corner at old half-edge `h` is the
/// `(vertex, half-edge)` pair `corner(h)`.
fn face_faces(t: &Topo<'_>, b: &mut Builder, corner: impl Fn(u32) -> (u32, u32)) {
    let mut corners: Vec<(u32, u32)> = Vec::new();
    for f in 0..t.nf() as u32 {
        corners.clear();
        t.for_face(f, |h| corners.push(corner(h)));
        b.face(&corners);
    }
}

/// Emits the face of each old vertex, in order: `corners` fills its corners from the vertex's
/// outgoing half-edges (`ring`, in `Topo::for_outgoing`'s order; a boundary vertex's starts
/// with its outgoing boundary half-edge).
fn vertex_faces(
    t: &Topo<'_>,
    b: &mut Builder,
    mut corners: impl FnMut(&[u32], &mut Vec<(u32, u32)>),
) {
    let (mut ring, mut face): (Vec<u32>, Vec<(u32, u32)>) = (Vec::new(), Vec::new());
    for v in 0..t.nv() as u32 {
        ring.clear();
        t.for_outgoing(v, |h| ring.push(h));
        face.clear();
        corners(&ring, &mut face);
        b.face(&face);
    }
}

/// The Doo-Sabin points of a step, appended to `out` (corners and, with boundary, Chaikin
/// points). A face of more than [`DIRECT_MAX`](super::wide::DIRECT_MAX) sides gets its corners from three face-wide
/// sums ([`Wide::sums`]): rewriting the weight `(3 + 2 cos(2π(j - i)/n)) / (4n)` of corner
/// `j` in the point of corner `i` as `3/(4n) + (cos θ_i cos θ_j + sin θ_i sin θ_j) / (2n)`,
/// `θ_j = 2πj/n` from the face's own first corner, the point is
/// `p_i = v_i / 4 + (3/4) mean + (1/2)(cos θ_i C + sin θ_i D)` with
/// `C = (1/n) Σ cos θ_j v_j`, `D = (1/n) Σ sin θ_j v_j`: `O(n)` per face, equal to the direct
/// sum ([`doo_sabin_point`]) up to rounding (the tests hold them to 1e-12 relative).
pub(crate) fn doo_sabin_points<V: Vector>(
    t: &Topo<'_>,
    src: &[V],
    out: &mut impl Sink<V>,
    parallel: bool,
) {
    let wide = Wide::of(t, Ring::Faces);
    let sums: Option<Vec<Vec<V>>> = wide.as_ref().map(|w| {
        (0..w.len())
            .map(|slot| w.sums(t, slot, 1, |h| src[t.source(h) as usize].clone()))
            .collect()
    });
    out.append(2 * t.ne(), parallel, |h| {
        let h = h as u32;
        if t.is_boundary(h) {
            return chaikin(src, t.source(h), t.target(h));
        }
        if let (Some(w), Some(sums)) = (&wide, &sums) {
            if let Some((slot, i)) = w.corner(t, h) {
                let (n, [mean, c, d]) = (w.size(slot), &sums[slot][..]) else {
                    unreachable!("three sums")
                };
                let (sin, cos) = angle(n, i).sin_cos();
                return src[t.source(h) as usize]
                    .clone()
                    .scale(0.25)
                    .add(mean.clone().scale(0.75))
                    .add(c.clone().scale(0.5 * cos))
                    .add(d.clone().scale(0.5 * sin));
            }
        }
        doo_sabin_point(t, src, h)
    });
    if !t.is_closed() {
        let boundary = boundary_halfedges(t);
        out.append(boundary.len(), parallel, |k| {
            let h = boundary[k];
            chaikin(src, t.target(h), t.source(h))
        });
    }
}

/// The boundary half-edges in increasing order.
fn boundary_halfedges(t: &Topo<'_>) -> Vec<u32> {
    (0..2 * t.ne() as u32)
        .filter(|&h| t.is_boundary(h))
        .collect()
}

/// Chaikin's point of the edge `(a, b)` near `a`: `(3a + b) / 4`.
fn chaikin<V: Vector>(src: &[V], a: u32, b: u32) -> V {
    src[a as usize]
        .clone()
        .scale(0.75)
        .add(src[b as usize].clone().scale(0.25))
}

/// The mid-edge points of a step, appended to `out` (midpoints and, with boundary, the kept
/// boundary vertices).
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
    if !t.is_closed() {
        let boundary = boundary_halfedges(t);
        out.append(boundary.len(), parallel, |k| {
            boundary_vertex(t, src, t.source(boundary[k]))
        });
    }
}

/// The Doo-Sabin weight of the corner `j` steps after the corner computed in an `n`-gon:
/// `(n + 5) / (4n)` for `j = 0`, `(3 + 2 cos(2πj/n)) / (4n)` otherwise (they sum to 1).
fn doo_sabin_weight(n: usize, j: usize) -> f64 {
    let nf = n as f64;
    if j == 0 {
        (nf + 5.0) / (4.0 * nf)
    } else {
        (3.0 + 2.0 * (2.0 * PI * j as f64 / nf).cos()) / (4.0 * nf)
    }
}

/// The Doo-Sabin point of the corner at the source of `h` in its face, as a direct sum over
/// the face (faces of at most [`DIRECT_MAX`](super::wide::DIRECT_MAX) sides).
fn doo_sabin_point<V: Vector>(t: &Topo<'_>, src: &[V], h: u32) -> V {
    let n = t.face_degree(t.face(h));
    let mut sum = V::zero();
    let mut g = h;
    for j in 0..n {
        let w = doo_sabin_weight(n, j);
        sum = sum.add(src[t.source(g) as usize].clone().scale(w));
        g = t.next(g);
    }
    sum
}

/// What a dual rule's UV step starts from: the edges and faces, the boundary half-edges
/// ([`n_boundary`]) and the seam edges' ranks ([`seam_ranks`]).
fn uv_step_start(t: &Topo<'_>, cv: &[u32]) -> Result<(u32, u32, usize, Vec<u32>, usize)> {
    let (seams, n_seams) = seam_ranks(t, cv)?;
    Ok((t.ne() as u32, t.nf() as u32, n_boundary(t), seams, n_seams))
}

/// The number of boundary half-edges of `t`.
fn n_boundary(t: &Topo<'_>) -> usize {
    if t.is_closed() {
        0
    } else {
        t.boundary_edges()
    }
}

/// The Doo-Sabin step of the UV corner channel (the rule of the
/// [`face_varying`](crate::refine::face_varying) module docs) from `t` and its corner values
/// `cv` (by half-edge).
///
/// Values: `0..2E` the new vertices' (vertex `h`: the Doo-Sabin point of face corner `h` in
/// its face's chart, or on a boundary half-edge its Chaikin point near the source in the chart
/// of the edge's face), `2E + r` the Chaikin point near the target of boundary half-edge `r`,
/// then two per seam edge `e` (in increasing order): the Chaikin points of `e` near the source
/// and near the target of half-edge `2e`, in the chart of its face. A corner of a face of
/// more than [`DIRECT_MAX`](super::wide::DIRECT_MAX) sides is a row of 4 weights over its own value and the
/// face's three face-wide sums (the step's auxiliary values, [`CornerStep::aux`]), so the
/// table is linear in the corners whatever the faces' degrees.
pub(crate) fn doo_sabin_uv_step<'a>(
    t: &'a Topo<'a>,
    cv: &'a [u32],
    n_values: usize,
) -> Result<CornerStep<'a>> {
    let (ne, nf, nb, seams, n_seams) = uv_step_start(t, cv)?;
    let vertices = 2 * t.ne() + nb;
    let rows = vertices + 2 * n_seams;
    let mut table = WeightTable::with_room(rows, 4 * rows)?;
    let mut row = Vec::new();
    // A wide face's corners are 4-entry rows over its value, then its three face-wide sums,
    // computed first as the step's auxiliary values `n_values + 3 slot + (0, 1, 2)`.
    let wide = Wide::of(t, Ring::Faces);
    let aux = match &wide {
        Some(w) => {
            let n_corners: usize = (0..w.len()).map(|slot| w.size(slot) as usize).sum();
            let mut aux = WeightTable::with_room(3 * w.len(), 3 * n_corners)?;
            for slot in 0..w.len() {
                let n = w.size(slot);
                let each = 1.0 / f64::from(n);
                for k in 0..3 {
                    w.for_corners(t, slot, |j, h| {
                        let (sin, cos) = angle(n, j).sin_cos();
                        let weight = [each, cos * each, sin * each][k];
                        row.push((cv[h as usize], weight));
                    });
                    aux.push_row(&mut row)?;
                }
            }
            Some(aux)
        }
        None => None,
    };
    let aux_value = |slot: usize, k: usize| (n_values + 3 * slot + k) as u32;
    // The Chaikin point near `a` of the side from `a` to `b` of a face (its corners' values).
    let chaikin_row = |row: &mut Vec<(u32, f64)>, a: u32, b: u32| {
        row.push((a, 0.75));
        row.push((b, 0.25));
    };
    for h in 0..2 * ne {
        if t.is_boundary(h) {
            // g = twin: from target(h) to source(h) in its face.
            let g = h ^ 1;
            chaikin_row(&mut row, cv[t.next(g) as usize], cv[g as usize]);
        } else if let Some((slot, i)) = wide.as_ref().and_then(|w| w.corner(t, h)) {
            let n = wide.as_ref().map_or(0, |w| w.size(slot));
            let (sin, cos) = angle(n, i).sin_cos();
            row.push((cv[h as usize], 0.25));
            row.push((aux_value(slot, 0), 0.75));
            row.push((aux_value(slot, 1), 0.5 * cos));
            row.push((aux_value(slot, 2), 0.5 * sin));
        } else {
            let n = t.face_degree(t.face(h));
            let mut g = h;
            for j in 0..n {
                row.push((cv[g as usize], doo_sabin_weight(n, j)));
                g = t.next(g);
            }
        }
        table.push_row(&mut row)?;
    }
    for h in (0..2 * ne).filter(|&h| t.is_boundary(h)) {
        let g = h ^ 1;
        chaikin_row(&mut row, cv[g as usize], cv[t.next(g) as usize]);
        table.push_row(&mut row)?;
    }
    for e in (0..ne).filter(|&e| seams[e as usize] != INVALID) {
        let h = 2 * e;
        let (a, b) = (cv[h as usize], cv[t.next(h) as usize]);
        chaikin_row(&mut row, a, b);
        table.push_row(&mut row)?;
        chaikin_row(&mut row, b, a);
        table.push_row(&mut row)?;
    }
    let corner = move |face: u32, vertex: u32| {
        if face < nf || face >= nf + ne {
            return vertex;
        }
        // The edge face of a seam edge: the corners from the face of 2e + 1 take the
        // Chaikin points in the chart of the face of 2e.
        let e = face - nf;
        let k = seams[e as usize];
        let tw = 2 * e + 1;
        if k == INVALID {
            vertex
        } else if vertex == t.next(tw) {
            vertices as u32 + 2 * k
        } else if vertex == tw {
            vertices as u32 + 2 * k + 1
        } else {
            vertex
        }
    };
    Ok(CornerStep {
        aux,
        values: table,
        corner: Box::new(corner),
    })
}

/// The mid-edge step of the UV corner channel (the rule of the
/// [`face_varying`](crate::refine::face_varying) module docs) from `t` and its corner values
/// `cv` (by half-edge).
///
/// Values: `e` (`0..E`) the midpoint of edge `e` in the chart of the face of half-edge `2e`
/// (of `2e + 1` when `2e` is a boundary half-edge), `E + k` the midpoint of seam edge `k` (in
/// increasing order) in the chart of the face of `2e + 1`, `E + S + r` the kept source of
/// boundary half-edge `r`, its value in the face of the boundary edge leaving it.
pub(crate) fn mid_edge_uv_step<'a>(
    t: &'a Topo<'a>,
    cv: &'a [u32],
    _n_values: usize,
) -> Result<CornerStep<'a>> {
    let (ne, nf, nb, seams, n_seams) = uv_step_start(t, cv)?;
    let rows = t.ne() + n_seams + nb;
    let mut table = WeightTable::with_room(rows, 2 * rows)?;
    let mut row = Vec::new();
    let midpoint = |row: &mut Vec<(u32, f64)>, h: u32| {
        row.push((cv[h as usize], 0.5));
        row.push((cv[t.next(h) as usize], 0.5));
    };
    for e in 0..ne {
        let h = if t.is_boundary(2 * e) {
            2 * e + 1
        } else {
            2 * e
        };
        midpoint(&mut row, h);
        table.push_row(&mut row)?;
    }
    for e in (0..ne).filter(|&e| seams[e as usize] != INVALID) {
        midpoint(&mut row, 2 * e + 1);
        table.push_row(&mut row)?;
    }
    for h in (0..2 * ne).filter(|&h| t.is_boundary(h)) {
        // The face side `h ^ 1` ends at the source of h: its next corner is there.
        row.push((cv[t.next(h ^ 1) as usize], 1.0));
        table.push_row(&mut row)?;
    }
    let side = move |e: u32, face: u32| {
        let k = seams[e as usize];
        if k != INVALID && t.face(2 * e + 1) == face {
            ne + k
        } else {
            e
        }
    };
    let kept = ne + n_seams as u32;
    let corner = move |face: u32, vertex: u32| {
        if face < nf {
            return side(vertex, face);
        }
        if vertex >= ne {
            return kept + (vertex - ne);
        }
        // The face of the half-edge leaving the old vertex along the edge (its twin's on the
        // boundary).
        let v = face - nf;
        let h = if t.source(2 * vertex) == v {
            2 * vertex
        } else {
            2 * vertex + 1
        };
        let g = if t.is_boundary(h) { h ^ 1 } else { h };
        side(vertex, t.face(g))
    };
    Ok(CornerStep {
        aux: None,
        values: table,
        corner: Box::new(corner),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::subdivide::wide::DIRECT_MAX;

    /// Just above the threshold (and further up) the face-wide form equals the direct sum
    /// over the face to 1e-12 of the face's size, for every corner.
    #[test]
    fn the_face_wide_form_agrees_with_the_direct_sum() {
        for n in [DIRECT_MAX + 1, 40, 257] {
            // A wavy n-gon, off-centre, so that no symmetry hides an error.
            let positions: Vec<DVec3> = (0..n)
                .map(|i| {
                    let a = 2.0 * PI * i as f64 / n as f64;
                    let r = 1.0 + 0.3 * (3.0 * a).sin();
                    DVec3::new(5.0 + r * a.cos(), -2.0 + r * a.sin(), 0.1 * (7.0 * a).cos())
                })
                .collect();
            let face: Vec<u32> = (0..n as u32).collect();
            let mesh = HalfEdgeMesh::try_from_polygons(positions.clone(), &[face]).expect("mesh");
            let t = Topo::new(&mesh);
            let src = &mesh.positions;
            let wide = Wide::of(&t, Ring::Faces).expect("one wide face");
            assert_eq!(wide.len(), 1);
            let mut out: Vec<DVec3> = Vec::new();
            doo_sabin_points(&t, src, &mut out, false);
            let mut checked = 0;
            for h in 0..2 * t.ne() as u32 {
                if t.is_boundary(h) {
                    continue;
                }
                assert!(wide.corner(&t, h).is_some());
                let direct = doo_sabin_point(&t, src, h);
                let error = (out[h as usize] - direct).length();
                assert!(error <= 1e-12 * 5.0, "{n}-gon, corner {h}: {error:e}");
                checked += 1;
            }
            assert_eq!(checked, n);
        }
    }

    /// At the threshold the direct sums serve: no wide face.
    #[test]
    fn a_face_at_the_threshold_is_summed_directly() {
        let n = DIRECT_MAX;
        let positions: Vec<DVec3> = (0..n)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / n as f64;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let face: Vec<u32> = (0..n as u32).collect();
        let mesh = HalfEdgeMesh::try_from_polygons(positions, &[face]).expect("mesh");
        assert!(Wide::of(&Topo::new(&mesh), Ring::Faces).is_none());
    }
}
