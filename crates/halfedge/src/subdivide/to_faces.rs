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
//! starting at the same corner. With the numbering of `gather`:
//!
//! - 4:1, old face `f` with half-edges `h_0` (its first), `h_1`, `h_2` and edge midpoints
//!   `m_c = V + (h_c >> 1)`: face `4f` is `[m_0, m_1, m_2]` and face `4f + 1 + c` is
//!   `[m_(c+1), m_c, target(h_c)]`.
//! - Catmull-Clark, corner `k` of old face `f` at half-edge `h` (corners numbered face by face
//!   from each face's first half-edge), `p = prev(h)`: face `k` is
//!   `[source(h), V + (h >> 1), V + E + f, V + (p >> 1)]`.

use rayon::prelude::*;

use super::build::{Sizes, StepContext};
use super::catmull_clark::cc_positions;
use super::gather::check;
use super::topo::Topo;
use super::trisplit::{tri_positions, Template, TriRule};
use crate::{HalfEdgeMesh, PolygonMesh, Result};

/// Old faces per parallel task.
const FACES_PER_TASK: usize = 1 << 12;

/// Below this many old faces the corners are written on the calling thread.
const PARALLEL_MIN_FACES: usize = 1 << 12;

/// One 4:1 step whose output is a face list; also returns the number of output edges.
pub(crate) fn four_to_one(
    mesh: &HalfEdgeMesh,
    template: &Template,
    rule: TriRule,
    expected: Sizes,
    parallel: bool,
    ctx: &StepContext<'_>,
) -> Result<(PolygonMesh, usize)> {
    let t = Topo::new(mesh);
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf());
    let built = Sizes {
        vertices: (nv + ne) as usize,
        halfedges: 2 * (2 * ne as usize + 3 * nf),
        faces: 4 * nf,
    };
    check(ctx, expected, built)?;
    let positions = tri_positions(&t, template, rule, Some(expected.vertices), parallel)?;
    let mut corners = super::alloc::filled(0u32, 3 * built.faces, "corners")?;
    let fill = |(chunk, out): (usize, &mut [u32])| {
        let first = chunk * FACES_PER_TASK;
        for (f, tris) in (first as u32..).zip(out.chunks_exact_mut(12)) {
            let h0 = t.face_halfedge(f);
            let h1 = t.next(h0);
            let h2 = t.next(h1);
            let [m0, m1, m2] = [nv + (h0 >> 1), nv + (h1 >> 1), nv + (h2 >> 1)];
            tris.copy_from_slice(&[
                m0,
                m1,
                m2,
                m1,
                m0,
                t.target(h0),
                m2,
                m1,
                t.target(h1),
                m0,
                m2,
                t.target(h2),
            ]);
        }
    };
    let per_task = 12 * FACES_PER_TASK;
    if parallel && nf >= PARALLEL_MIN_FACES {
        corners.par_chunks_mut(per_task).enumerate().for_each(fill);
    } else {
        corners.chunks_mut(per_task).enumerate().for_each(fill);
    }
    let faces = finish(ctx, expected, positions, corners, 3, parallel)?;
    Ok((faces, built.halfedges / 2))
}

/// One Catmull-Clark step whose output is a face list; also returns the number of output
/// edges.
pub(crate) fn catmull_clark(
    mesh: &HalfEdgeMesh,
    expected: Sizes,
    parallel: bool,
    ctx: &StepContext<'_>,
) -> Result<(PolygonMesh, usize)> {
    let t = Topo::new(mesh);
    let (nv, ne, nf) = (t.nv() as u32, t.ne() as u32, t.nf());
    // Every half-edge that is not on the boundary is one face corner.
    let n_corners = 2 * ne as usize - t.boundary_edges();
    let built = Sizes {
        vertices: (nv + ne) as usize + nf,
        halfedges: 2 * (2 * ne as usize + n_corners),
        faces: n_corners,
    };
    check(ctx, expected, built)?;
    let positions = cc_positions(&t, Some(expected.vertices), parallel)?;
    let quad = |f: u32, h: u32| -> [u32; 4] {
        let p = t.prev(h);
        [t.target(p), nv + (h >> 1), nv + ne + f, nv + (p >> 1)]
    };
    let mut corners = super::alloc::filled(0u32, 4 * built.faces, "corners")?;
    if mesh.is_quad_mesh() {
        // Old face f owns output faces 4f..4f + 4: fill in chunks. The face's four half-edges
        // and their targets are loaded once (prev(h_k) = h_(k-1), so `quad` is inlined here
        // without its prev lookup).
        let fill = |(chunk, out): (usize, &mut [u32])| {
            let first = chunk * FACES_PER_TASK;
            for (f, quads) in (first as u32..).zip(out.chunks_exact_mut(16)) {
                let h0 = t.face_halfedge(f);
                let h1 = t.next(h0);
                let h2 = t.next(h1);
                let h3 = t.next(h2);
                let hs = [h0, h1, h2, h3];
                let targets = hs.map(|h| t.target(h));
                let center = nv + ne + f;
                for (k, q) in quads.chunks_exact_mut(4).enumerate() {
                    let p = (k + 3) % 4;
                    q.copy_from_slice(&[targets[p], nv + (hs[k] >> 1), center, nv + (hs[p] >> 1)]);
                }
            }
        };
        let per_task = 16 * FACES_PER_TASK;
        if parallel && nf >= PARALLEL_MIN_FACES {
            corners.par_chunks_mut(per_task).enumerate().for_each(fill);
        } else {
            corners.chunks_mut(per_task).enumerate().for_each(fill);
        }
    } else {
        // Faces of any degree (the first level): corners face by face.
        let mut slots = corners.chunks_exact_mut(4);
        let mut written = 0usize;
        for f in 0..nf as u32 {
            t.for_face(f, |h| {
                if let Some(slot) = slots.next() {
                    slot.copy_from_slice(&quad(f, h));
                    written += 1;
                }
            });
        }
        if written != built.faces {
            return Err(ctx.mismatch("faces", built.faces, written));
        }
    }
    let faces = finish(ctx, expected, positions, corners, 4, parallel)?;
    Ok((faces, built.halfedges / 2))
}

/// Checks the lengths against the prediction (a mismatch is a bug) and assembles the mesh of
/// faces of `degree` corners each.
fn finish(
    ctx: &StepContext<'_>,
    expected: Sizes,
    positions: Vec<glam::DVec3>,
    corners: Vec<u32>,
    degree: usize,
    parallel: bool,
) -> Result<PolygonMesh> {
    for (what, predicted, len, cap) in [
        (
            "vertex positions",
            expected.vertices,
            positions.len(),
            positions.capacity(),
        ),
        (
            "face corners",
            degree * expected.faces,
            corners.len(),
            corners.capacity(),
        ),
    ] {
        if len != predicted || cap != predicted {
            debug_assert!(
                false,
                "{} level {}: predicted {what} {predicted}, built {len} (capacity {cap})",
                ctx.scheme, ctx.level
            );
            return Err(ctx.mismatch(what, predicted, len.max(cap)));
        }
    }
    let mut offsets = super::alloc::with_capacity(expected.faces + 1, "offsets")?;
    super::par::extend(&mut offsets, expected.faces + 1, parallel, |f| degree * f);
    Ok(PolygonMesh::from_raw_parts(positions, offsets, corners))
}
