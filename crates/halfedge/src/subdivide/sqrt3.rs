//! Kobbelt's √3 subdivision, with his boundary rule (the variant of the `schemes` crate's
//! `sqrt3-boundary`: steps A and B alternate, step B at even step numbers).
//!
//! A plain step (`sqrt3`, and step A of `sqrt3-boundary`) inserts the centroid of every
//! triangle, connects it to the three corners and flips every old interior edge (it then joins
//! the centroids of its two old faces); boundary edges stay. Step B trisects every boundary edge
//! `a -> b` of a boundary triangle `(a, b, c)` (after step A every face has at most one
//! boundary edge), joins `c` to the two new points `p1`, `p2` instead of inserting a centroid,
//! and flips the old interior edges as well: edge `c a` then joins `p1` to the centroid across
//! it, edge `b c` joins `p2` to the centroid across it.
//!
//! Each old face half-edge `g` gives exactly one new triangle: for an interior edge the
//! triangle (target of `g`, `rep(g)`, `rep(twin g)`), where `rep(g)` is the centroid of the
//! face of `g` (or `p1`/`p2` on a step-B boundary face, the point the flipped edge reaches);
//! for a boundary edge the old edge with the centroid (step A) or the middle triangle
//! `(p1, p2, c)` (step B).
//!
//! # Numbering (input `V`, `E`, `F` triangles, `IE`/`BE` interior/boundary edges)
//!
//! - Vertices: old vertices; then `V + f`: the centroid of face `f`, or `p1` of a step-B
//!   boundary face; then `V + F + i`: `p2` of the `i`-th step-B boundary face (in face order).
//! - Edges: old interior edge `e` keeps its id (flipped); the spoke from corner `c = 3f + k`
//!   (the source of the `k`-th half-edge of face `f`) to the centroid of `f` is `E + c`; on a
//!   step-B boundary face `(a, b, c)` (boundary half-edge `g: a -> b`) the ids of `g`'s edge and
//!   of its three corners, plus `E + 3F + i`, give `p1 p2`, `a p1`, `p2 b`, `c p1` and `c p2`.
//! - Faces: the triangle of face half-edge `g` at corner `c` is face `c`.
//!
//! So step A (and `sqrt3`) gives `V' = V + F`, `E' = E + 3F`, `F' = 3F`, `BE' = BE`, and
//! step B gives `V' = V + F + BE`, `E' = E + 3F + BE`, `F' = 3F`, `BE' = 3 BE`.
//!
//! Geometry: centroids; interior vertices `(1 - α) v + α/n Σ neighbours` with
//! `α = (4 - 2 cos(2π/n)) / 9`; boundary vertices stay in step A, and in step B the boundary
//! polygon is refined by Kobbelt's ternary cubic B-spline rule: old vertices
//! `(4 l + 19 v + 4 r) / 27`, new points `(l + 16 a + 10 b) / 27` and `(10 a + 16 b + r) / 27`.
//!
//! UVs: [`sqrt3_uv_step`], the corner channel's step of the linear UV rule of the
//! [`face_varying`](crate::refine::face_varying) module docs, on the same numbering.

use std::f64::consts::PI;

use glam::DVec3;

use super::build::{Builder, StepContext};
use super::corner_step::{seam_ranks, CornerStep};
use super::data::Vector;
use super::par::Sink;
use super::topo::Topo;
use super::weights::WeightTable;
use crate::mesh::INVALID;
use crate::{HalfEdgeMesh, Result};

/// One √3 step on the triangle mesh `t`, face by face; `step_b` selects Kobbelt's boundary
/// trisection. The new level's `positions` computed by the caller (the refinement's
/// evaluation, [`sqrt3_points`]), zeros without (a refinement keeps only the topology).
pub(crate) fn sqrt3_step(
    t: &Topo<'_>,
    positions: Option<Vec<DVec3>>,
    step_b: bool,
    ctx: &StepContext<'_>,
) -> Result<HalfEdgeMesh> {
    let t = *t;
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf() as u32);
    // corner[g] = 3f + k for face half-edges.
    let mut corner = super::alloc::filled(INVALID, 2 * ne as usize, "corner")?;
    for f in 0..nf {
        let mut k = 0;
        t.for_face(f, |g| {
            corner[g as usize] = 3 * f + k;
            k += 1;
        });
    }
    let tables = if step_b {
        StepB::new(&t, ctx)?
    } else {
        StepB::default()
    };
    let number_of = &tables.number_of;
    let spoke = |k: u32| ne + corner[k as usize];
    // Empty tables (not a step B): no face is a step-B boundary face.
    let role = |g: u32| tables.role(&t, g);
    let p2_of = |gb: u32| nv + nf + number_of[t.face(gb) as usize];
    let c2_of = |gb: u32| ne + 3 * nf + number_of[t.face(gb) as usize];
    // The point the new edge through old edge g reaches on g's side.
    let rep = |g: u32| match role(g) {
        Some((1, gb)) => p2_of(gb),
        _ => nv + t.face(g),
    };
    // Half-edge from target(g) to rep(g) inside face(g).
    let out = |g: u32| match role(g) {
        Some((1, gb)) => 2 * c2_of(gb), // c -> p2
        Some((2, gb)) => 2 * spoke(gb), // a -> p1
        _ => 2 * spoke(t.next(g)),
    };
    // Half-edge from rep(k) to source(k) inside face(k).
    let into = |k: u32| match role(k) {
        Some((1, _)) => 2 * spoke(k),     // p2 -> b
        Some((2, _)) => 2 * spoke(k) + 1, // p1 -> c
        _ => 2 * spoke(k) + 1,
    };

    let mut b = Builder::new(ctx.expected)?;
    for f in 0..nf {
        let g0 = t.face_halfedge(f);
        for g in [g0, t.next(g0), t.prev(g0)] {
            if !t.is_boundary(g ^ 1) {
                b.face(&[
                    (t.target(g), out(g)),
                    (rep(g), g),
                    (rep(g ^ 1), into(g ^ 1)),
                ]);
            } else if !step_b {
                b.face(&[
                    (t.source(g), g),
                    (t.target(g), 2 * spoke(t.next(g))),
                    (nv + f, 2 * spoke(g) + 1),
                ]);
            } else {
                // Middle triangle (p1, p2, c): p1 p2 is g's edge, c p1 is the spoke slot of
                // prev(g), c p2 the extra edge.
                let c = t.target(t.next(g));
                b.face(&[
                    (nv + f, g),
                    (p2_of(g), 2 * c2_of(g) + 1),
                    (c, 2 * spoke(t.prev(g))),
                ]);
            }
        }
    }

    let positions = match positions {
        Some(positions) => positions,
        None => super::alloc::filled(DVec3::ZERO, ctx.expected.vertices, "positions")?,
    };
    b.finish(positions, ctx)
}

/// The faces of a step-B √3 step that have a boundary edge: per face its boundary half-edge
/// (`INVALID` for the others) and its number among them, and the list of those half-edges.
#[derive(Clone, Debug, Default)]
pub(crate) struct StepB {
    boundary_of: Vec<u32>,
    number_of: Vec<u32>,
    boundary_faces: Vec<u32>,
}

impl StepB {
    /// The tables of `t` (after step A every face has at most one boundary edge: more is an
    /// [`crate::Error::InvalidOutput`]).
    pub(crate) fn new(t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<StepB> {
        StepB::build(t, |what| ctx.invalid(what))
    }

    /// [`StepB::new`] with `invalid` making the error of a face with two or three boundary
    /// edges.
    fn build(t: &Topo<'_>, invalid: impl Fn(String) -> crate::Error) -> Result<StepB> {
        let nf = t.nf() as u32;
        let mut boundary_of = super::alloc::filled(INVALID, nf as usize, "boundary faces")?;
        let mut number_of = super::alloc::filled(INVALID, nf as usize, "boundary face numbers")?;
        let mut boundary_faces = Vec::new();
        for f in 0..nf {
            let mut found = INVALID;
            let mut count = 0;
            t.for_face(f, |g| {
                if t.is_boundary(g ^ 1) {
                    found = g;
                    count += 1;
                }
            });
            if count > 1 {
                return Err(invalid(format!(
                    "face {f} has {count} boundary edges in a trisecting step (step A leaves at most one)"
                )));
            }
            if count == 1 {
                boundary_of[f as usize] = found;
                number_of[f as usize] = boundary_faces.len() as u32;
                boundary_faces.push(found);
            }
        }
        Ok(StepB {
            boundary_of,
            number_of,
            boundary_faces,
        })
    }

    /// Bytes held by the tables.
    pub(crate) fn bytes(&self) -> usize {
        4 * (self.boundary_of.len() + self.number_of.len() + self.boundary_faces.len())
    }

    /// The role of half-edge `g` in its face when that face is a step-B boundary face, with
    /// the face's boundary half-edge `gb`: `(0, gb)` for the boundary half-edge, `(1, gb)` for
    /// next of it (b -> c), `(2, gb)` for prev of it (c -> a); `None` on an ordinary face and
    /// with empty tables (not a step B).
    fn role(&self, t: &Topo<'_>, g: u32) -> Option<(u32, u32)> {
        let gb = *self.boundary_of.get(t.face(g) as usize)?;
        if gb == INVALID {
            None
        } else if g == gb {
            Some((0, gb))
        } else if g == t.next(gb) {
            Some((1, gb))
        } else {
            Some((2, gb))
        }
    }
}

/// The points of a √3 step from the values `src` of the level before, appended to `out`:
/// old vertices, then one per face (centroid, or `p1` of a step-B boundary face), then the
/// `p2` of the step-B boundary faces. `step_b`: the tables of a step B.
pub(crate) fn sqrt3_points<V: Vector>(
    t: &Topo<'_>,
    src: &[V],
    step_b: Option<&StepB>,
    out: &mut impl Sink<V>,
    parallel: bool,
) {
    let t = *t;
    let (nv, nf) = (t.nv(), t.nf());
    let pos = |v: u32| src[v as usize].clone();
    out.append(nv, parallel, |v| {
        let v = v as u32;
        if t.is_boundary_vertex(v) {
            let p = pos(v);
            if step_b.is_none() {
                return p;
            }
            let h = t.vertex_halfedge(v);
            let right = pos(t.target(h));
            let left = pos(t.source(t.prev(h)));
            return left
                .scale(4.0)
                .add(p.scale(19.0))
                .add(right.scale(4.0))
                .div(27.0);
        }
        interior_vertex(&t, src, v)
    });
    // Boundary points: g runs a -> b inside the mesh, its twin b -> a on the boundary.
    let p1 = |g: u32| {
        let before = pos(t.target(t.next(g ^ 1)));
        before
            .add(pos(t.source(g)).scale(16.0))
            .add(pos(t.target(g)).scale(10.0))
            .div(27.0)
    };
    let p2 = |g: u32| {
        let after = pos(t.source(t.prev(g ^ 1)));
        pos(t.source(g))
            .scale(10.0)
            .add(pos(t.target(g)).scale(16.0))
            .add(after)
            .div(27.0)
    };
    out.append(nf, parallel, |f| match step_b {
        Some(b) if b.boundary_of[f] != INVALID => p1(b.boundary_of[f]),
        _ => centroid(&t, src, f as u32),
    });
    if let Some(b) = step_b {
        out.append(
            b.boundary_faces.len(),
            parallel,
            |i| p2(b.boundary_faces[i]),
        );
    }
}

/// Kobbelt's smoothing of an interior vertex: `(1 - α) v + α/n Σ neighbours`,
/// `α = (4 - 2 cos(2π/n)) / 9`.
pub(crate) fn interior_vertex<V: Vector>(t: &Topo<'_>, src: &[V], v: u32) -> V {
    let p = src[v as usize].clone();
    let mut sum = V::zero();
    let mut n = 0u32;
    t.for_outgoing(v, |h| {
        sum = sum.clone().add(src[t.target(h) as usize].clone());
        n += 1;
    });
    let nf = f64::from(n);
    let alpha = (4.0 - 2.0 * (2.0 * PI / nf).cos()) / 9.0;
    p.scale(1.0 - alpha).add(sum.scale(alpha / nf))
}

/// The centroid of triangle `f`.
pub(crate) fn centroid<V: Vector>(t: &Topo<'_>, src: &[V], f: u32) -> V {
    let g = t.face_halfedge(f);
    src[t.source(g) as usize]
        .clone()
        .add(src[t.target(g) as usize].clone())
        .add(src[t.target(t.next(g)) as usize].clone())
        .div(3.0)
}

/// The √3 step of the UV corner channel (the rule of the
/// [`face_varying`](crate::refine::face_varying) module docs, "√3") from `t` and its corner
/// values `cv` (by half-edge; `n_values` values); `step_b`: Kobbelt's trisecting step.
///
/// Values: `0..n` the old values, kept; `n + f` the centroid of face `f` in its chart, or on a
/// step-B boundary face `(a, b, c)` (boundary half-edge `a -> b`) `p1 = (2a + b) / 3`;
/// `n + F + i` the `p2 = (a + 2b) / 3` of the `i`-th step-B boundary face; then two per seam
/// edge `e` (in increasing order): its midpoint in the chart of the face of `2e`, then of
/// `2e + 1`. Child faces and vertices are [`sqrt3_step`]'s: the triangle of half-edge `g`
/// (corner `c = 3f + k`) is face `c`.
pub(crate) fn sqrt3_uv_step<'a>(
    t: &'a Topo<'a>,
    cv: &'a [u32],
    n_values: usize,
    step_b: bool,
    child: u32,
) -> Result<CornerStep<'a>> {
    let t = *t;
    let (nv, nf) = (t.nv() as u32, t.nf() as u32);
    let tables = if step_b {
        StepB::build(&t, |what| crate::Error::InvalidOutput {
            scheme: "sqrt3-boundary".into(),
            level: child,
            what,
        })?
    } else {
        StepB::default()
    };
    let nb = tables.boundary_faces.len();
    let (seams, n_seams) = seam_ranks(&t, cv)?;
    let n = u32::try_from(n_values).map_err(|_| crate::Error::IndexOverflow {
        what: "uv values",
        count: n_values as u128,
    })?;
    let rows = n_values + nf as usize + nb + 2 * n_seams;
    let mut table = WeightTable::with_room(rows, n_values + 3 * nf as usize + 4 * n_seams)?;
    let mut row = Vec::new();
    for v in 0..n {
        row.push((v, 1.0));
        table.push_row(&mut row)?;
    }
    let value = |h: u32| cv[h as usize];
    for f in 0..nf {
        match tables.boundary_of.get(f as usize) {
            Some(&gb) if gb != INVALID => {
                row.push((value(gb), 2.0 / 3.0));
                row.push((value(t.next(gb)), 1.0 / 3.0));
            }
            _ => t.for_face(f, |g| row.push((value(g), 1.0 / 3.0))),
        }
        table.push_row(&mut row)?;
    }
    for &gb in &tables.boundary_faces {
        row.push((value(gb), 1.0 / 3.0));
        row.push((value(t.next(gb)), 2.0 / 3.0));
        table.push_row(&mut row)?;
    }
    for e in (0..t.ne() as u32).filter(|&e| seams[e as usize] != INVALID) {
        for h in [2 * e, 2 * e + 1] {
            row.push((value(h), 0.5));
            row.push((value(t.next(h)), 0.5));
            table.push_row(&mut row)?;
        }
    }
    let first_mid = n + nf + nb as u32;
    let corner = move |face: u32, vertex: u32| -> u32 {
        let f = face / 3;
        let g = t.triangle_side(f, face % 3);
        let role = |h: u32| tables.role(&t, h);
        let number = |gb: u32| tables.number_of[t.face(gb) as usize];
        // The vertex rep(h) and its value in the chart of h's face.
        let rep = |h: u32| match role(h) {
            Some((1, gb)) => (nv + nf + number(gb), n + nf + number(gb)),
            _ => (nv + t.face(h), n + t.face(h)),
        };
        let mid = |h: u32| first_mid + 2 * seams[(h >> 1) as usize] + (h & 1);
        let tw = g ^ 1;
        if !t.is_boundary(tw) {
            let seam = seams[(g >> 1) as usize] != INVALID;
            // The chart: g's face in a plain step or step A, the face across g in step B.
            let (home, other) = if step_b { (tw, g) } else { (g, tw) };
            let (own_vertex, own_value) = rep(home);
            if vertex == t.target(g) {
                // The corner at target(g): source of tw in its face, of next(g) in g's.
                if step_b {
                    value(tw)
                } else {
                    value(t.next(g))
                }
            } else if vertex == own_vertex {
                own_value
            } else if seam {
                mid(home)
            } else {
                rep(other).1
            }
        } else if !step_b {
            // The old boundary edge with the centroid.
            if vertex == t.source(g) {
                value(g)
            } else if vertex == t.target(g) {
                value(t.next(g))
            } else {
                n + f
            }
        } else if vertex == nv + f {
            n + f
        } else if vertex == nv + nf + number(g) {
            n + nf + number(g)
        } else {
            // The opposite corner c: the source of prev(g).
            value(t.prev(g))
        }
    };
    Ok(CornerStep {
        aux: None,
        values: table,
        corner: Box::new(corner),
    })
}
