//! The last level of a subdivision written straight into a face list.
//!
//! A caller that only wants the final mesh (to write it, to draw it, to hand it to another
//! library) does not need the half-edge arrays of the last level: 16 bytes per half-edge, 48
//! per output triangle. For the 4:1 family and Catmull-Clark the faces of level `s` are a pure
//! function of the faces of level `s - 1`, so the last step writes only positions (the same
//! geometry passes as the half-edge step) and the face corners: 12 bytes per triangle plus the
//! face offsets.
//!
//! The numbering is exactly the one of the half-edge step followed by
//! [`HalfEdgeMesh::to_polygon_mesh`]: the same vertices, faces in the same order, each face
//! starting at the same corner. The corners are written by the split's own functions
//! (`trisplit::Template::write_corners`, `catmull_clark::quad_corners`), with the numbering of
//! `gather`:
//!
//! - 4:1, old face `f` with half-edges `h_0` (its first), `h_1`, `h_2` and edge midpoints
//!   `m_c = V + (h_c >> 1)`: face `4f` is `[m_0, m_1, m_2]` and face `4f + 1 + c` is
//!   `[m_(c+1), m_c, target(h_c)]`.
//! - Catmull-Clark, corner `k` of old face `f` at half-edge `h` (corners numbered face by face
//!   from each face's first half-edge), `p = prev(h)`: face `k` is
//!   `[source(h), V + (h >> 1), V + E + f, V + (p >> 1)]`.

use super::build::StepContext;
use super::catmull_clark::quad_corners;
use super::gather::{catmull_clark_sizes, check, tri_split_sizes};
use super::par;
use super::topo::Topo;
use super::trisplit::{Frame, Template, FOUR_TO_ONE_SLOTS};
use crate::{PolygonMesh, Result};

/// Old faces per parallel task.
const FACES_PER_TASK: usize = 1 << 12;

/// Below this many old faces the corners are written on the calling thread.
const PARALLEL_MIN_FACES: usize = 1 << 12;

/// The last level of a 1:N² step (`template`) or a Catmull-Clark step (`None`) on `t` as a
/// face list, with its `positions` computed by the caller (the refinement's evaluation); also
/// returns the number of output edges.
pub(crate) fn faces_after(
    t: &Topo<'_>,
    positions: Vec<glam::DVec3>,
    template: Option<&Template>,
    ctx: &StepContext<'_>,
) -> Result<(PolygonMesh, usize)> {
    let built = match template {
        Some(template) => tri_split_sizes(t, template.n),
        None => catmull_clark_sizes(t),
    };
    check(ctx, built)?;
    let degree = if template.is_some() { 3 } else { 4 };
    let mut corners = super::alloc::filled(0u32, degree * built.faces, "corners")?;
    let written = corners_after(t, template, &mut corners, ctx.parallel);
    if written != built.faces {
        return Err(ctx.mismatch("faces", built.faces, written));
    }
    let faces = finish(ctx, positions, corners, degree)?;
    Ok((faces, built.halfedges / 2))
}

/// The corners of the faces of a 1:N² step (`template`, three per triangle, `3 N² F`
/// entries) or of a Catmull-Clark step (`None`, four per quad, `4 H` entries, `H` the face
/// corners) on `t` into `corners`; returns the number of faces written.
pub(crate) fn corners_after(
    t: &Topo<'_>,
    template: Option<&Template>,
    corners: &mut [u32],
    parallel: bool,
) -> usize {
    let t = *t;
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf());
    let Some(template) = template else {
        return catmull_clark_corners(&t, corners, parallel);
    };
    let per_face = 3 * template.n_triangles();
    if template.n == 2 {
        // The last level of every 4:1 subdivision (millions of faces): the template's six
        // points (the corners, the midpoints of sides 0, 1, 2, as `Template::vertex` numbers
        // them for N = 2) copied by its constant slots.
        // Written out with constant indices: `array::map` here compiled to a call per face
        // (2.3x the time of this loop).
        const S: [usize; 12] = FOUR_TO_ONE_SLOTS;
        for_each_face::<12>(corners, per_face, parallel, |f, out| {
            let frame = Frame::of(&t, f);
            let [a, b, c] = frame.corners;
            let side = |s: usize| nv + frame.sides[s].0;
            let ids = [a, b, c, side(0), side(1), side(2)];
            out.copy_from_slice(&[
                ids[S[0]], ids[S[1]], ids[S[2]], ids[S[3]], ids[S[4]], ids[S[5]], ids[S[6]],
                ids[S[7]], ids[S[8]], ids[S[9]], ids[S[10]], ids[S[11]],
            ]);
        });
    } else {
        for_each_face::<0>(corners, per_face, parallel, |f, out| {
            template.write_corners(&Frame::of(&t, f), nv, ne, out);
        });
    }
    corners.len().min(per_face * nf) / 3
}

/// The corners of the quads of a Catmull-Clark step on `t`, four per quad, into `corners`
/// (`4 H` entries, `H` the face corners of `t`); returns the number of quads written.
fn catmull_clark_corners(t: &Topo<'_>, corners: &mut [u32], parallel: bool) -> usize {
    let t = *t;
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf());
    if t.is_quad_mesh() && corners.len() == 16 * nf {
        // Old face f owns output faces 4f..4f + 4: fill in chunks. The face's four half-edges
        // and their targets are loaded once (prev(h_k) = h_(k-1)).
        for_each_face::<16>(corners, 16, parallel, |f, quads| {
            let h0 = t.face_halfedge(f);
            let h1 = t.next(h0);
            let h2 = t.next(h1);
            let h3 = t.next(h2);
            let hs = [h0, h1, h2, h3];
            let targets = hs.map(|h| t.target(h));
            for (k, q) in quads.chunks_exact_mut(4).enumerate() {
                let p = (k + 3) % 4;
                let quad = quad_corners(nv, ne, f, targets[p], hs[k] >> 1, hs[p] >> 1);
                q.copy_from_slice(&quad);
            }
        });
        return 4 * nf;
    }
    // Faces of any degree (the first level): corners face by face.
    let mut slots = corners.chunks_exact_mut(4);
    let mut written = 0usize;
    for f in 0..nf as u32 {
        t.for_face(f, |h| {
            if let Some(slot) = slots.next() {
                let p = t.prev(h);
                slot.copy_from_slice(&quad_corners(nv, ne, f, t.target(p), h >> 1, p >> 1));
                written += 1;
            }
        });
    }
    written
}

/// Calls `write(f, out)` for every old face `f` in order, `out` the `per_face` corners it
/// owns at `f * per_face` in `corners`; in parallel tasks of [`FACES_PER_TASK`] old faces
/// when `parallel` and there are at least [`PARALLEL_MIN_FACES`]. `K`, when not 0, is
/// `per_face` known to the compiler (the common degrees: a fixed-size copy per face).
#[inline]
fn for_each_face<const K: usize>(
    corners: &mut [u32],
    per_face: usize,
    parallel: bool,
    write: impl Fn(u32, &mut [u32]) + Sync + Send,
) {
    debug_assert!(
        K == 0 || K == per_face,
        "{K} corners per face, not {per_face}"
    );
    let per_face = if K > 0 { K } else { per_face };
    let fill = |(chunk, out): (usize, &mut [u32])| {
        let first = chunk * FACES_PER_TASK;
        for (f, out) in (first as u32..).zip(out.chunks_exact_mut(per_face)) {
            write(f, out);
        }
    };
    let (per_task, min) = (per_face * FACES_PER_TASK, per_face * PARALLEL_MIN_FACES);
    par::for_each_chunk(corners, per_task, parallel, min, fill);
}

/// Checks the lengths against the prediction (a mismatch is a bug) and assembles the mesh of
/// faces of `degree` corners each.
fn finish(
    ctx: &StepContext<'_>,
    positions: Vec<glam::DVec3>,
    corners: Vec<u32>,
    degree: usize,
) -> Result<PolygonMesh> {
    let e = ctx.expected;
    let (n, capacity) = (positions.len(), positions.capacity());
    ctx.expect_exact("vertex positions", e.vertices, n, capacity)?;
    let (n, capacity) = (corners.len(), corners.capacity());
    ctx.expect_exact("face corners", degree * e.faces, n, capacity)?;
    let offsets = par::collect(e.faces + 1, ctx.parallel, "offsets", |f| degree * f)?;
    Ok(PolygonMesh::from_raw_parts(positions, offsets, corners))
}
