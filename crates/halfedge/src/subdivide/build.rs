//! The output side of one subdivision step: half-edge arrays written by index.
//!
//! Every scheme computes the id of each new vertex, half-edge and face by arithmetic on the ids
//! of the old mesh (see the module docs of each scheme), so the output needs no hash map: a face
//! is emitted as its corners `(start vertex, half-edge id)` and the builder writes `vertex`,
//! `face`, `next` and `prev` of each half-edge directly. Faces are numbered in emission order.
//! Boundary half-edges (the twins nobody emitted) are linked into loops at the end.
//!
//! The arrays are allocated once with exactly the predicted lengths and a write past them is
//! recorded (not performed) and reported as a
//! [`Error::PredictionMismatch`](crate::Error::PredictionMismatch).

use glam::DVec3;

use crate::mesh::{HalfEdgeMesh, INVALID};
use crate::{Error, Result};

/// The sizes of a mesh (or a predicted mesh) as array lengths.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Sizes {
    pub(crate) vertices: usize,
    pub(crate) halfedges: usize,
    pub(crate) faces: usize,
}

/// One subdivision step: where it is (for error messages), the sizes the scheme predicts for
/// its output, and whether its passes may run in parallel.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepContext<'a> {
    pub(crate) scheme: &'a str,
    pub(crate) level: u32,
    /// The output's predicted sizes.
    pub(crate) expected: Sizes,
    /// Whether the passes may run in parallel (rayon).
    pub(crate) parallel: bool,
}

impl StepContext<'_> {
    /// `Ok` when the count `actual` of `what` is the predicted `predicted`; else
    /// [`Error::PredictionMismatch`] (a bug, and a debug assertion).
    pub(crate) fn expect(&self, what: &'static str, predicted: usize, actual: usize) -> Result<()> {
        if predicted == actual {
            return Ok(());
        }
        debug_assert!(
            false,
            "{} level {}: predicted {what} {predicted}, built {actual}",
            self.scheme, self.level
        );
        Err(self.mismatch(what, predicted, actual))
    }

    /// `Ok` when an array of length `len` and capacity `capacity` has exactly the predicted
    /// length and never grew; else as [`StepContext::expect`].
    pub(crate) fn expect_exact(
        &self,
        what: &'static str,
        predicted: usize,
        len: usize,
        capacity: usize,
    ) -> Result<()> {
        if len == predicted && capacity == predicted {
            return Ok(());
        }
        debug_assert!(
            false,
            "{} level {}: predicted {what} {predicted}, built {len} (capacity {capacity})",
            self.scheme, self.level
        );
        Err(self.mismatch(what, predicted, len.max(capacity)))
    }

    pub(crate) fn mismatch(&self, what: &'static str, predicted: usize, actual: usize) -> Error {
        Error::PredictionMismatch {
            scheme: self.scheme.to_owned(),
            level: self.level,
            what,
            predicted: predicted.into(),
            actual: actual as u64,
        }
    }

    pub(crate) fn invalid(&self, what: String) -> Error {
        Error::InvalidOutput {
            scheme: self.scheme.to_owned(),
            level: self.level,
            what,
        }
    }
}

/// Half-edge arrays under construction.
pub(crate) struct Builder {
    expected: Sizes,
    vertex_halfedge: Vec<u32>,
    halfedge_vertex: Vec<u32>,
    halfedge_face: Vec<u32>,
    halfedge_next: Vec<u32>,
    halfedge_prev: Vec<u32>,
    face_halfedge: Vec<u32>,
    /// One past the largest vertex id written (to report a mismatch).
    max_vertex: usize,
    /// One past the largest half-edge id written (to report a mismatch).
    max_halfedge: usize,
}

impl Builder {
    /// Allocates the arrays: exactly `expected`.
    ///
    /// # Errors
    ///
    /// [`Error::AllocationFailed`] when the system refuses the memory.
    pub(crate) fn new(expected: Sizes) -> Result<Self> {
        let (nv, nh, nf) = (expected.vertices, expected.halfedges, expected.faces);
        use super::alloc::{filled, with_capacity};
        Ok(Builder {
            expected,
            vertex_halfedge: filled(INVALID, nv, "vertex half-edges")?,
            halfedge_vertex: filled(INVALID, nh, "half-edge targets")?,
            halfedge_face: filled(INVALID, nh, "half-edge faces")?,
            halfedge_next: filled(INVALID, nh, "next half-edges")?,
            halfedge_prev: filled(INVALID, nh, "previous half-edges")?,
            face_halfedge: with_capacity(nf, "face half-edges")?,
            max_vertex: 0,
            max_halfedge: 0,
        })
    }

    /// Emits the next face. `corners[i] = (v, h)`: half-edge `h` runs from vertex `v` to the
    /// vertex of `corners[i + 1]`.
    #[inline]
    pub(crate) fn face(&mut self, corners: &[(u32, u32)]) {
        let f = self.face_halfedge.len() as u32;
        let n = corners.len();
        self.face_halfedge.push(corners[0].1);
        for i in 0..n {
            let (v, h) = corners[i];
            let (w, hn) = corners[if i + 1 == n { 0 } else { i + 1 }];
            let (vi, hi, hni) = (v as usize, h as usize, hn as usize);
            self.max_vertex = self.max_vertex.max(vi + 1);
            self.max_halfedge = self.max_halfedge.max((hi | 1) + 1);
            // Out-of-range ids are a prediction mismatch, reported by `finish`.
            if let (Some(vh), true) = (
                self.vertex_halfedge.get_mut(vi),
                (hi | 1) < self.halfedge_vertex.len() && hni < self.halfedge_vertex.len(),
            ) {
                *vh = h;
                self.halfedge_vertex[hi] = w;
                self.halfedge_vertex[hi ^ 1] = v;
                self.halfedge_face[hi] = f;
                self.halfedge_next[hi] = hn;
                self.halfedge_prev[hni] = h;
            }
        }
    }

    /// Links the boundary loops, checks the sizes against the prediction and assembles the mesh.
    pub(crate) fn finish(
        mut self,
        positions: Vec<DVec3>,
        ctx: &StepContext<'_>,
    ) -> Result<HalfEdgeMesh> {
        let e = self.expected;
        let check = |what, predicted, actual| ctx.expect(what, predicted, actual);
        check(
            "vertices",
            e.vertices,
            self.max_vertex.max(self.vertex_halfedge.len()),
        )?;
        check("vertex positions", e.vertices, positions.len())?;
        check(
            "edges",
            e.halfedges / 2,
            self.max_halfedge.max(self.halfedge_vertex.len()) / 2,
        )?;
        check("faces", e.faces, self.face_halfedge.len())?;
        check("face capacity", e.faces, self.face_halfedge.capacity())?;
        check("position capacity", e.vertices, positions.capacity())?;
        if let Some(v) = self.vertex_halfedge.iter().position(|&h| h == INVALID) {
            // Fewer vertices were used than predicted.
            let used = self
                .vertex_halfedge
                .iter()
                .filter(|&&h| h != INVALID)
                .count();
            let _ = v;
            return Err(ctx.mismatch("vertices", e.vertices, used));
        }
        // Boundary half-edges: the ones no face claimed. First make each boundary vertex point
        // at its outgoing boundary half-edge, then link each boundary half-edge to the one
        // leaving its target.
        let nh = self.halfedge_vertex.len();
        for h in 0..nh {
            if self.halfedge_face[h] == INVALID {
                if self.halfedge_vertex[h] == INVALID {
                    let used = self
                        .halfedge_vertex
                        .iter()
                        .filter(|&&v| v != INVALID)
                        .count();
                    return Err(ctx.mismatch("edges", e.halfedges / 2, used / 2));
                }
                let source = self.halfedge_vertex[h ^ 1] as usize;
                self.vertex_halfedge[source] = h as u32;
            }
        }
        for h in 0..nh {
            if self.halfedge_face[h] == INVALID {
                let target = self.halfedge_vertex[h] as usize;
                let n = self.vertex_halfedge[target];
                if self.halfedge_face[n as usize] != INVALID {
                    return Err(ctx.invalid(format!(
                        "boundary half-edge {h} ends at vertex {target}, which has no outgoing boundary half-edge"
                    )));
                }
                self.halfedge_next[h] = n;
                self.halfedge_prev[n as usize] = h as u32;
            }
        }
        let halfedges = [
            self.halfedge_vertex,
            self.halfedge_face,
            self.halfedge_next,
            self.halfedge_prev,
        ];
        Ok(HalfEdgeMesh::from_raw_parts(
            positions,
            self.vertex_halfedge,
            halfedges,
            self.face_halfedge,
        ))
    }
}
