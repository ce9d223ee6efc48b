//! Flattened per-level tables for the hot rules: a Loop or Catmull-Clark level as index
//! arrays (edge stencils, vertex rings, face corners), so an evaluation streams through them
//! with no half-edge walk.
//!
//! The values are combined by the same kernel functions, in the same order, as the half-edge
//! paths of `trisplit` (`loop_interior`, `boundary_rule`, `loop_interior_edge`) and
//! `catmull_clark` (`cc_interior`, and the face and edge sums written out in its order), so
//! both give the same bits.

use crate::mesh::INVALID;
use crate::subdivide::catmull_clark::{cc_interior, cc_interior_edge};
use crate::subdivide::par::{self, Sink, Slots};
use crate::subdivide::topo::Topo;
use crate::subdivide::trisplit::{boundary_rule, loop_interior, loop_interior_edge};
use crate::Result;

use super::*;

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
        let ne = t.ne();
        let edges = par::collect(ne, parallel, "Loop edge table", |e| {
            let h = 2 * e as u32;
            let (a, b) = (t.source(h), t.target(h));
            if t.is_boundary_edge(e as u32) {
                [a, b, INVALID, INVALID]
            } else {
                [a, b, t.target(t.next(h)), t.target(t.next(h ^ 1))]
            }
        })?;
        let boundary = boundary_flags(&t, parallel)?;
        let (ring, ring_offsets) =
            rings(&t, &boundary, 6, parallel, "Loop rings", |h| t.target(h))?;
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

    /// The bytes of the tables of `t`, before they are built.
    pub(super) fn bytes_of(t: &Topo<'_>) -> usize {
        16 * t.ne() + 4 * (t.nv() + 1 + ring_entries(t)) + t.nv()
    }

    /// The points of the next Loop level from `src`, appended to `out`: the moved old
    /// vertices, then the edge points.
    pub(super) fn points<V: Vector>(&self, src: &[V], out: &mut impl Sink<V>, parallel: bool) {
        let nv = self.boundary.len();
        let pos = |v: u32| src[v as usize].clone();
        out.append(nv, parallel, |v| {
            let ring = entries_of(&self.ring_offsets, &self.ring, v);
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

/// A Catmull-Clark level flattened: what the next level's points are computed from.
#[derive(Debug)]
pub(super) struct CcTables {
    /// Per edge `[a, b, f1, f2]`: its ends (source and target of half-edge `2e`) and the faces
    /// of its half-edges; `f1 = INVALID` on a boundary edge.
    edges: Vec<[u32; 4]>,
    /// Start of each vertex's ring in `ring` (`V + 1` entries).
    ring_offsets: Vec<u32>,
    /// Each interior vertex's `(neighbour, face)` pairs in the order of its outgoing
    /// half-edges; a boundary vertex's two neighbours along the boundary, `right` then `left`
    /// (faces `INVALID`).
    ring: Vec<[u32; 2]>,
    /// Whether each vertex is on the boundary.
    boundary: Vec<bool>,
    /// Start of each face's corners in `corners` (`F + 1` entries).
    face_offsets: Vec<u32>,
    /// The vertices of each face, from its half-edge's source.
    corners: Vec<u32>,
}

impl CcTables {
    /// The tables of the level `t`.
    pub(super) fn new(t: &Topo<'_>, parallel: bool) -> Result<CcTables> {
        let t = *t;
        let (ne, nf) = (t.ne(), t.nf());
        let edges = par::collect(ne, parallel, "Catmull-Clark edge table", |e| {
            let h = 2 * e as u32;
            let (a, b) = (t.source(h), t.target(h));
            if t.is_boundary(h) || t.is_boundary(h ^ 1) {
                [a, b, INVALID, INVALID]
            } else {
                [a, b, t.face(h), t.face(h ^ 1)]
            }
        })?;
        let boundary = boundary_flags(&t, parallel)?;
        let what = "Catmull-Clark rings";
        let (ring, ring_offsets) = rings(&t, &boundary, 4, parallel, what, |h| {
            [t.target(h), t.face(h)]
        })?;
        let face_of = |range: std::ops::Range<usize>| {
            let mut corners = Vec::with_capacity(4 * range.len());
            let mut ends = Vec::with_capacity(range.len());
            for f in range {
                t.for_face(f as u32, |h| corners.push(t.source(h)));
                ends.push(corners.len() as u32);
            }
            (corners, ends)
        };
        let (corners, face_offsets) = concat(nf, parallel, face_of, "face corners")?;
        Ok(CcTables {
            edges,
            ring_offsets,
            ring,
            boundary,
            face_offsets,
            corners,
        })
    }

    /// Bytes held.
    pub(super) fn bytes(&self) -> usize {
        16 * self.edges.len()
            + 4 * (self.ring_offsets.len() + self.face_offsets.len() + self.corners.len())
            + 8 * self.ring.len()
            + self.boundary.len()
    }

    /// The bytes of the tables of `t`, before they are built.
    pub(super) fn bytes_of(t: &Topo<'_>) -> usize {
        16 * t.ne()
            + 4 * (t.nv() + 1 + t.nf() + 1 + super::corners_of(t))
            + 8 * ring_entries(t)
            + t.nv()
    }

    /// The points of the next Catmull-Clark level from `src` into `dst` (exactly
    /// `V + E + F` values): the face points first, at the end, then the moved vertices and
    /// the edge points, as `catmull_clark::cc_fill`.
    pub(super) fn fill<V: Vector>(&self, src: &[V], dst: &mut [V], parallel: bool) {
        let (nv, ne) = (self.boundary.len(), self.edges.len());
        let pos = |v: u32| src[v as usize].clone();
        let (head, face_points) = dst.split_at_mut((nv + ne).min(dst.len()));
        let mut out = Slots::new(face_points);
        out.append(self.face_offsets.len() - 1, parallel, |f| {
            let (a, b) = (
                self.face_offsets[f] as usize,
                self.face_offsets[f + 1] as usize,
            );
            let mut sum = V::zero();
            for &v in &self.corners[a..b] {
                sum = sum.add(pos(v));
            }
            sum.div(f64::from((b - a) as u32))
        });
        let fp: &[V] = face_points;
        let mut out = Slots::new(head);
        out.append(nv, parallel, |v| {
            let ring = entries_of(&self.ring_offsets, &self.ring, v);
            let p = src[v].clone();
            if self.boundary[v] {
                return boundary_rule(p, pos(ring[1][0]), pos(ring[0][0]));
            }
            let (mut faces, mut ends) = (V::zero(), V::zero());
            for &[w, f] in ring {
                faces = faces.add(fp[f as usize].clone());
                ends = ends.add(pos(w));
            }
            cc_interior(p, faces, ends, ring.len())
        });
        out.append(ne, parallel, |e| {
            let [a, b, f1, f2] = self.edges[e];
            let mid = pos(a).add(pos(b));
            if f1 == INVALID {
                mid.scale(0.5)
            } else {
                cc_interior_edge(mid, fp[f1 as usize].clone(), fp[f2 as usize].clone())
            }
        });
    }
}

/// A level refined linearly (a face-varying channel under `all`): vertices stay, edge points
/// are midpoints and, for Catmull-Clark, face points the centroids of their corners.
#[derive(Debug)]
pub(super) struct LinearTables {
    /// The number of vertices.
    vertices: usize,
    /// Per edge: its ends.
    edges: Vec<[u32; 2]>,
    /// Start of each face's corners in `corners` (`F + 1` entries; empty without face points).
    face_offsets: Vec<u32>,
    /// The vertices of each face, ascending (the order of a crease weight table's row).
    corners: Vec<u32>,
}

impl LinearTables {
    /// The tables of the level `t`, with face points when `faces` (Catmull-Clark).
    pub(super) fn new(t: &Topo<'_>, faces: bool, parallel: bool) -> Result<LinearTables> {
        let t = *t;
        let (nv, ne, nf) = (t.nv(), t.ne(), t.nf());
        let edges = par::collect(ne, parallel, "linear edge table", |e| {
            let h = 2 * e as u32;
            [t.source(h), t.target(h)]
        })?;
        let (corners, face_offsets) = if faces {
            let face_of = |range: std::ops::Range<usize>| {
                let mut corners = Vec::with_capacity(4 * range.len());
                let mut ends = Vec::with_capacity(range.len());
                for f in range {
                    let start = corners.len();
                    t.for_face(f as u32, |h| corners.push(t.source(h)));
                    corners[start..].sort_unstable();
                    ends.push(corners.len() as u32);
                }
                (corners, ends)
            };
            concat(nf, parallel, face_of, "face corners")?
        } else {
            (Vec::new(), Vec::new())
        };
        Ok(LinearTables {
            vertices: nv,
            edges,
            face_offsets,
            corners,
        })
    }

    /// Bytes held.
    pub(super) fn bytes(&self) -> usize {
        8 * self.edges.len() + 4 * (self.face_offsets.len() + self.corners.len())
    }

    /// The bytes of the tables of `t` (with face points when `faces`), before they are built.
    pub(super) fn bytes_of(t: &Topo<'_>, faces: bool) -> usize {
        8 * t.ne()
            + if faces {
                4 * (t.nf() + 1 + super::corners_of(t))
            } else {
                0
            }
    }

    /// The points of the next level from `src`, appended to `out`: the vertices, the edge
    /// points, then the face points; each summed as a crease weight table sums its row.
    pub(super) fn points<V: Vector>(&self, src: &[V], out: &mut impl Sink<V>, parallel: bool) {
        let pos = |v: u32| src[v as usize].clone();
        out.append(self.vertices, parallel, |v| src[v].clone());
        out.append(self.edges.len(), parallel, |e| {
            let [a, b] = self.edges[e];
            pos(a).scale(0.5).add(pos(b).scale(0.5))
        });
        let faces = self.face_offsets.len().saturating_sub(1);
        out.append(faces, parallel, |f| {
            let (a, b) = (
                self.face_offsets[f] as usize,
                self.face_offsets[f + 1] as usize,
            );
            let each = 1.0 / (b - a) as f64;
            let mut sum = V::zero();
            for &v in &self.corners[a..b] {
                sum = sum.add(pos(v).scale(each));
            }
            sum
        });
    }
}

/// The entries of the vertex rings of `t`: a boundary vertex's two neighbours, an interior
/// vertex's valence.
fn ring_entries(t: &Topo<'_>) -> usize {
    let mut entries = 2 * t.ne();
    for v in 0..t.nv() as u32 {
        if t.is_boundary_vertex(v) {
            entries = entries + 2 - t.valence(v);
        }
    }
    entries
}

/// The entries of element `i` in `entries` with `offsets`.
#[inline(always)]
fn entries_of<'a, T>(offsets: &[u32], entries: &'a [T], i: usize) -> &'a [T] {
    &entries[offsets[i] as usize..offsets[i + 1] as usize]
}

/// Whether each vertex of `t` is on the boundary.
fn boundary_flags(t: &Topo<'_>, parallel: bool) -> Result<Vec<bool>> {
    par::collect(t.nv(), parallel, "boundary flags", |v| {
        t.is_boundary_vertex(v as u32)
    })
}

/// Every vertex's ring as the vertex rules read it, concatenated with offsets: `entry(h)` of
/// every outgoing half-edge `h` of an interior vertex, in order; for a boundary vertex
/// (`boundary`) its two neighbours along the boundary, `entry` of its boundary half-edge and
/// of the one arriving (`INVALID` in their other fields). One walk per vertex, in chunks of
/// about `valence` entries per vertex (in parallel when asked).
fn rings<T: Ring>(
    t: &Topo<'_>,
    boundary: &[bool],
    valence: usize,
    parallel: bool,
    what: &str,
    entry: impl Fn(u32) -> T + Sync + Send,
) -> Result<(Vec<T>, Vec<u32>)> {
    let ring_of = |range: std::ops::Range<usize>| {
        let mut ring = Vec::with_capacity(valence * range.len());
        let mut ends = Vec::with_capacity(range.len());
        for v in range {
            let v = v as u32;
            if boundary[v as usize] {
                let h = t.vertex_halfedge(v);
                ring.push(T::along_boundary(t.target(h)));
                ring.push(T::along_boundary(t.source(t.prev(h))));
            } else {
                t.for_outgoing(v, |h| ring.push(entry(h)));
            }
            ends.push(ring.len() as u32);
        }
        (ring, ends)
    };
    concat(t.nv(), parallel, ring_of, what)
}

/// An entry of a vertex ring: a neighbour, or a neighbour with the face between.
trait Ring: Copy + Send {
    /// The entry of a neighbour along the boundary.
    fn along_boundary(v: u32) -> Self;
}

impl Ring for u32 {
    fn along_boundary(v: u32) -> u32 {
        v
    }
}

impl Ring for [u32; 2] {
    fn along_boundary(v: u32) -> [u32; 2] {
        [v, INVALID]
    }
}

/// The lists `part(range)` of `n` elements (each with the running end of every element's
/// entries) concatenated, in chunks in parallel when asked: the entries and the `n + 1`
/// offsets.
fn concat<T: Copy + Send>(
    n: usize,
    parallel: bool,
    part: impl Fn(std::ops::Range<usize>) -> (Vec<T>, Vec<u32>) + Sync + Send,
    what: &str,
) -> Result<(Vec<T>, Vec<u32>)> {
    let chunks = par::map_ranges(n, RING_CHUNK, parallel, RING_CHUNK, part);
    let total: usize = chunks.iter().map(|(r, _)| r.len()).sum();
    let mut entries = crate::subdivide::alloc::with_capacity(total, what)?;
    let mut offsets = crate::subdivide::alloc::with_capacity(n + 1, what)?;
    offsets.push(0u32);
    for (r, ends) in &chunks {
        // Below the half-edge count of the level, which fits u32.
        let start = entries.len() as u32;
        entries.extend_from_slice(r);
        offsets.extend(ends.iter().map(|&e| start + e));
    }
    Ok((entries, offsets))
}

/// A level flattened for its rule.
#[derive(Debug)]
pub(super) enum Fast {
    Loop(LoopTables),
    CatmullClark(CcTables),
    /// A face-varying channel's level under linear interpolation (`all`).
    Linear(LinearTables),
    /// A Loop or Catmull-Clark level under crease rules: sparse weights per child vertex,
    /// of every child vertex (a dense table, `base` unused) or of the child vertices where the
    /// crease rules differ from `base` (the rule's tables, or its half-edge kernels on the
    /// level's topology when `None`), written over its values.
    Creased {
        base: Option<Box<Fast>>,
        weights: WeightTable,
    },
}

impl Fast {
    pub(super) fn bytes(&self) -> usize {
        match self {
            Fast::Loop(t) => t.bytes(),
            Fast::CatmullClark(t) => t.bytes(),
            Fast::Linear(t) => t.bytes(),
            Fast::Creased { base, weights } => {
                base.as_ref().map_or(0, |b| b.bytes()) + weights.bytes()
            }
        }
    }

    /// The flattened tables of `t` for `split` (Loop or Catmull-Clark).
    pub(super) fn tables(split: Split, t: &Topo<'_>, parallel: bool) -> Result<Fast> {
        Ok(match split {
            Split::Quad => Fast::CatmullClark(CcTables::new(t, parallel)?),
            _ => Fast::Loop(LoopTables::new(t, parallel)?),
        })
    }

    /// The tables computing the child vertices of `t` outside a crease table's rows: the
    /// rule's (`None` with `tables` false: the half-edge kernels), or the linear ones.
    pub(super) fn base(
        base: Base,
        split: Split,
        t: &Topo<'_>,
        tables: bool,
        parallel: bool,
    ) -> Result<Option<Box<Fast>>> {
        let cc = split == Split::Quad;
        Ok(match base {
            Base::Linear => Some(Box::new(Fast::Linear(LinearTables::new(t, cc, parallel)?))),
            Base::Rule if tables => Some(Box::new(Fast::tables(split, t, parallel)?)),
            Base::Rule => None,
        })
    }

    /// The bytes of the tables a [`Refinement`] keeps under the rows of a sparse crease table
    /// of `t` ([`Fast::base`] with tables).
    pub(super) fn base_bytes(base: Base, split: Split, t: &Topo<'_>) -> usize {
        let cc = split == Split::Quad;
        match base {
            Base::Linear => LinearTables::bytes_of(t, cc),
            Base::Rule if cc => CcTables::bytes_of(t),
            Base::Rule => LoopTables::bytes_of(t),
        }
    }

    /// What refines level `level` (`t`) under `creases`: the rows where the crease rules differ
    /// from the level's base over its tables (`tables`, a refinement's) or its half-edge kernels
    /// (the one-shot subdivision's), when they are at most half the child vertices and hold,
    /// with the tables a refinement keeps, no more than the level's budget (the bound of the
    /// dense table); else the dense table. The level's sharpness is kept.
    pub(super) fn creased(
        creases: &Creases,
        level: usize,
        t: &Topo<'_>,
        split: Split,
        tables: bool,
        parallel: bool,
    ) -> Result<Option<Fast>> {
        // A dense table of a level with a wide face would be quadratic in its degree.
        let wide = crate::subdivide::refine::creases::has_wide_face(t);
        let sparse = |rows: usize, children: usize| wide || 2 * rows <= children;
        let dense = |weights| Fast::Creased {
            base: None,
            weights,
        };
        Ok(match creases.level_table(level, t, parallel, sparse)? {
            None => None,
            Some(LevelTable::Dense(weights)) => Some(dense(weights)),
            Some(LevelTable::Overrides(base, weights)) => {
                // A refinement's tables are built and measured, the one-shot subdivision's
                // (which keeps none) counted.
                let tables = if tables {
                    Some(Fast::base(base, split, t, true, parallel)?)
                } else {
                    None
                };
                let base_bytes = match &tables {
                    Some(b) => b.as_ref().map_or(0, |b| b.bytes()),
                    None => Fast::base_bytes(base, split, t),
                };
                debug_assert_eq!(base_bytes, Fast::base_bytes(base, split, t));
                if wide || base_bytes + weights.bytes() <= creases.budget(level) {
                    let base = match tables {
                        Some(b) => b,
                        None => Fast::base(base, split, t, false, parallel)?,
                    };
                    Some(Fast::Creased { base, weights })
                } else {
                    drop(tables);
                    drop(weights);
                    match creases.level_table(level, t, parallel, |_, _| false)? {
                        Some(LevelTable::Dense(weights) | LevelTable::Overrides(_, weights)) => {
                            Some(dense(weights))
                        }
                        None => None,
                    }
                }
            }
        })
    }
}

/// The budget of each level's tables under crease rules (`levels` of `plan` on a mesh with
/// `counts`): the bound of its dense weight table, what
/// [`Refinement::predicted_bytes_with_creases`] counts for it.
pub(super) fn crease_budgets(plan: &Plan, counts: &MeshCounts, levels: u32) -> Result<Vec<usize>> {
    let mut budgets = Vec::with_capacity(levels.min(64) as usize);
    for s in 0..levels {
        let bound = crease_table_bytes(plan, counts, s)?.unwrap_or_default();
        budgets.push(usize::try_from(bound).unwrap_or(usize::MAX));
    }
    Ok(budgets)
}
