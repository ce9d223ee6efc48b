//! Flattened per-level tables for the hot rules: a Loop level as index arrays (edge
//! stencils, vertex rings), so an evaluation streams through them with no half-edge walk.
//!
//! The values are combined by the same kernel functions, in the same order, as the half-edge
//! path of `trisplit` (`loop_interior`, `boundary_rule`, `loop_interior_edge`), so both give
//! the same bits.

use crate::mesh::INVALID;
use crate::subdivide::par::{self, Sink};
use crate::subdivide::topo::Topo;
use crate::subdivide::trisplit::{boundary_rule, loop_interior, loop_interior_edge};
use crate::Result;

use super::Vector;

/// Vertices per task when the rings are built in parallel.
const RING_CHUNK: usize = 1 << 14;

/// A Loop level flattened: what the next level's points are computed from.
#[derive(Debug)]
pub(super) struct LoopTables {
    /// Per edge `[a, b, c, d]`: its ends (source and target of half-edge `2e`) and the
    /// opposite vertices of its two faces; `c = INVALID` on a boundary edge.
    edges: Vec<[u32; 4]>,
    /// Start of each vertex's ring in `ring` (`V + 1` entries).
    ring_offsets: Vec<u32>,
    /// Each interior vertex's neighbours in the order of its outgoing half-edges; a boundary
    /// vertex's two neighbours along the boundary: `[right, left]`.
    ring: Vec<u32>,
    /// Whether each vertex is on the boundary.
    boundary: Vec<bool>,
}

impl LoopTables {
    /// The tables of the level `t`.
    pub(super) fn new(t: &Topo<'_>, parallel: bool) -> Result<LoopTables> {
        let t = *t;
        let (nv, ne) = (t.nv(), t.ne());
        let edges = par::collect(Some(ne), ne, parallel, "Loop edge table", |e| {
            let h = 2 * e as u32;
            let (a, b) = (t.source(h), t.target(h));
            if t.is_boundary_edge(e as u32) {
                [a, b, INVALID, INVALID]
            } else {
                [a, b, t.target(t.next(h)), t.target(t.next(h ^ 1))]
            }
        })?;
        let boundary = par::collect(Some(nv), nv, parallel, "Loop boundary flags", |v| {
            t.is_boundary_vertex(v as u32)
        })?;
        // One walk per vertex, in chunks of vertices (in parallel when asked), concatenated.
        let ring_of = |range: std::ops::Range<usize>| {
            let mut ring = Vec::with_capacity(6 * range.len());
            let mut ends = Vec::with_capacity(range.len());
            for v in range {
                let v = v as u32;
                if boundary[v as usize] {
                    let h = t.vertex_halfedge(v);
                    ring.push(t.target(h));
                    ring.push(t.source(t.prev(h)));
                } else {
                    t.for_outgoing(v, |h| ring.push(t.target(h)));
                }
                ends.push(ring.len() as u32);
            }
            (ring, ends)
        };
        let chunks: Vec<(Vec<u32>, Vec<u32>)> = if parallel && nv >= RING_CHUNK {
            use rayon::prelude::*;
            (0..nv.div_ceil(RING_CHUNK))
                .into_par_iter()
                .map(|c| ring_of(c * RING_CHUNK..((c + 1) * RING_CHUNK).min(nv)))
                .collect()
        } else {
            vec![ring_of(0..nv)]
        };
        let total: usize = chunks.iter().map(|(r, _)| r.len()).sum();
        let mut ring = crate::subdivide::alloc::with_capacity(total, "Loop rings")?;
        let mut ring_offsets = crate::subdivide::alloc::with_capacity(nv + 1, "Loop ring offsets")?;
        ring_offsets.push(0u32);
        for (r, ends) in &chunks {
            // Below the half-edge count of the level, which fits u32.
            let start = ring.len() as u32;
            ring.extend_from_slice(r);
            ring_offsets.extend(ends.iter().map(|&e| start + e));
        }
        Ok(LoopTables {
            edges,
            ring_offsets,
            ring,
            boundary,
        })
    }

    /// Bytes held.
    pub(super) fn bytes(&self) -> usize {
        16 * self.edges.len()
            + 4 * (self.ring_offsets.len() + self.ring.len())
            + self.boundary.len()
    }

    /// The points of the next Loop level from `src`, appended to `out`: the moved old
    /// vertices, then the edge points.
    pub(super) fn points<V: Vector>(&self, src: &[V], out: &mut impl Sink<V>, parallel: bool) {
        let nv = self.boundary.len();
        let pos = |v: u32| src[v as usize].clone();
        out.append(nv, parallel, |v| {
            let (a, b) = (
                self.ring_offsets[v] as usize,
                self.ring_offsets[v + 1] as usize,
            );
            let ring = &self.ring[a..b];
            let p = src[v].clone();
            if self.boundary[v] {
                return boundary_rule(p, pos(ring[1]), pos(ring[0]));
            }
            let mut sum = V::zero();
            for &w in ring {
                sum = sum.add(pos(w));
            }
            loop_interior(p, sum, ring.len())
        });
        out.append(self.edges.len(), parallel, |e| {
            let [a, b, c, d] = self.edges[e];
            if c == INVALID {
                pos(a).add(pos(b)).scale(0.5)
            } else {
                loop_interior_edge(pos(a), pos(b), pos(c), pos(d))
            }
        });
    }
}
