//! Holes: faces tagged as holes (OpenSubdiv's `holeIndices`, the `t hole` tag) and what they
//! remove from a subdivision's counts.
//!
//! A hole is not a deleted face: the surface around it is computed as if the face were there,
//! but the face and all its descendants are not written, nor are the vertices and edges that
//! only hole faces use. Holes apply to the rules whose faces nest (each child face lies in
//! one parent face): the 4:1 family (Loop, midpoint, butterfly, icosphere), `tri-split-N` and
//! Catmull-Clark ([`nests_faces`]).
//!
//! # Counting what is written
//!
//! Topologically, what is written at level `s` is level `s` of the *written mesh*: the faces
//! that are not holes (and the vertices and edges they use) subdivided `s` times, because the
//! children of a written face are its own and the children of a hole are holes. So a mesh
//! with holes counts exactly by the usual schemes applied to the statistics of its written
//! faces; a closed mesh with holes has boundary there and counts with the boundary-aware
//! state.
//!
//! The same counts follow from the statistics the holes add, [`HoleCounts`]: `HV` vertices
//! all of whose faces are holes, `HE` edges all of whose faces are holes, `HF` hole faces and
//! `HH` their corners. They evolve by their own linear recurrence ([`hole_recurrence`]),
//! derived from where each child element comes from:
//!
//! - a child face is a hole exactly when its parent face is: `HF' = N² HF` (1:N² split) or
//!   `HF' = HH` (Catmull-Clark: one quad per corner), and `HH' = N² HH` / `HH' = 4 HH`;
//! - a child edge inside a parent face has only children of that face around it, and a child
//!   edge on a parent edge only children of that edge's faces: `HE' = N HE + 3N(N-1)/2 HF`
//!   (1:N²), `HE' = 2 HE + HH` (Catmull-Clark);
//! - likewise for child vertices on parent vertices, edges and faces:
//!   `HV' = HV + (N-1) HE + (N-1)(N-2)/2 HF` (1:N²), `HV' = HV + HE + HF` (Catmull-Clark).
//!
//! What is written is the whole mesh's count minus the holes' (`V - HV`, `E - HE`, `F - HF`),
//! which equals the written mesh's count: a test checks both against each other and against
//! real subdivision.
//!
//! ```
//! use schemes::holes::{hole_recurrence, HoleCounts};
//! use schemes::{BigInt, MeshCounts, Rule};
//!
//! // Two triangles of a closed octahedron are holes (they share an edge).
//! let octahedron: [[u32; 3]; 8] = [
//!     [0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1], [5, 2, 1], [5, 3, 2], [5, 4, 3], [5, 1, 4],
//! ];
//! let holes = [0usize, 1];
//! let full = MeshCounts::from_polygons(&octahedron)?;
//! let written: Vec<[u32; 3]> = (0..8).filter(|f| !holes.contains(f)).map(|f| octahedron[f]).collect();
//! let written = MeshCounts::from_polygons(&written)?;
//! let h = HoleCounts::between(&full, &written);
//! assert_eq!((h.vertices, h.edges, h.faces, h.corners), (0, 1, 2, 6));
//!
//! // Level 2 under Loop: 4^2 * 2 = 32 hole faces are not written.
//! let r = hole_recurrence(Rule::Loop).expect("Loop's faces nest");
//! let at2 = r.state_at(&h.state(), 2)?;
//! assert_eq!(at2[2], BigInt::from(32));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};

use crate::counts::MeshCounts;
use crate::rule::Rule;

/// The names of the hole statistics, in the state order of [`hole_recurrence`].
pub const HOLE_STATE: [&str; 4] = ["HV", "HE", "HF", "HH"];

/// What holes remove from a mesh: the elements that only hole faces use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct HoleCounts {
    /// `HV`: vertices all of whose faces are holes.
    pub vertices: u64,
    /// `HE`: edges all of whose faces are holes.
    pub edges: u64,
    /// `HF`: hole faces.
    pub faces: u64,
    /// `HH`: the corners of the hole faces (the sum of their degrees).
    pub corners: u64,
}

impl HoleCounts {
    /// The holes' statistics from the counts of the whole mesh and of its written faces
    /// (the faces that are not holes, counted with
    /// [`MeshCounts::from_face_list`]): each is the difference.
    pub fn between(full: &MeshCounts, written: &MeshCounts) -> HoleCounts {
        HoleCounts {
            vertices: full.vertices.saturating_sub(written.vertices),
            edges: full.edges.saturating_sub(written.edges),
            faces: full.faces.saturating_sub(written.faces),
            corners: full.corners.saturating_sub(written.corners),
        }
    }

    /// `[HV, HE, HF, HH]`, the initial state of [`hole_recurrence`].
    pub fn state(&self) -> [BigInt; 4] {
        [self.vertices, self.edges, self.faces, self.corners].map(BigInt::from)
    }

    /// `true` when there are no hole faces.
    pub fn is_empty(&self) -> bool {
        self.faces == 0
    }
}

/// Whether the faces of `rule` nest, each child face inside one parent face, so that a
/// hole's descendants are defined: the 4:1 family, `tri-split-N` and Catmull-Clark; not √3
/// (its edge flips), Doo-Sabin or mid-edge (their faces sit on vertices and edges too).
pub fn nests_faces(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::Loop
            | Rule::Midpoint
            | Rule::Butterfly
            | Rule::Icosphere
            | Rule::TriSplit(_)
            | Rule::CatmullClark
    )
}

/// The recurrence of the hole statistics `(HV, HE, HF, HH)` under `rule` (module docs), or
/// `None` when the rule's faces do not nest ([`nests_faces`]).
///
/// ```
/// use schemes::holes::hole_recurrence;
/// use schemes::Rule;
///
/// let cc = hole_recurrence(Rule::CatmullClark).unwrap();
/// assert_eq!(cc.names(), ["HV", "HE", "HF", "HH"]);
/// assert!(hole_recurrence(Rule::Sqrt3).is_none());
/// ```
pub fn hole_recurrence(rule: Rule) -> Option<Recurrence> {
    let rows: [[i64; 4]; 4] = match rule {
        Rule::CatmullClark => [[1, 1, 1, 0], [0, 2, 0, 1], [0, 0, 0, 1], [0, 0, 0, 4]],
        Rule::Loop | Rule::Midpoint | Rule::Butterfly | Rule::Icosphere => split_rows(2)?,
        Rule::TriSplit(n) => split_rows(i64::from(n))?,
        Rule::Sqrt3 | Rule::DooSabin | Rule::MidEdge => return None,
    };
    let matrix = IntMatrix::try_from_rows(rows.iter().map(|r| r.to_vec()).collect()).ok()?;
    Recurrence::with_names(matrix, HOLE_STATE).ok()
}

/// The rows of the 1:N² split (module docs); `None` when `N²` overflows.
fn split_rows(n: i64) -> Option<[[i64; 4]; 4]> {
    let n2 = n.checked_mul(n)?;
    let inner_edges = n2.checked_sub(n)?.checked_mul(3)? / 2;
    let inner_vertices = (n - 1).checked_mul(n - 2)? / 2;
    Some([
        [1, n - 1, inner_vertices, 0],
        [0, n, inner_edges, 0],
        [0, 0, n2, 0],
        [0, 0, 0, n2],
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;

    /// A quad grid `w x h` (vertices `(w+1) x (h+1)`, row-major).
    fn grid(w: u32, h: u32) -> Vec<[u32; 4]> {
        let mut faces = Vec::new();
        for j in 0..h {
            for i in 0..w {
                let a = j * (w + 1) + i;
                faces.push([a, a + 1, a + w + 2, a + w + 1]);
            }
        }
        faces
    }

    fn counts_without(faces: &[[u32; 4]], holes: &[usize]) -> (MeshCounts, MeshCounts) {
        let full = MeshCounts::from_polygons(faces).unwrap();
        let written: Vec<[u32; 4]> = (0..faces.len())
            .filter(|f| !holes.contains(f))
            .map(|f| faces[f])
            .collect();
        (full, MeshCounts::from_polygons(&written).unwrap())
    }

    #[test]
    fn whole_minus_holes_equals_the_written_mesh_under_catmull_clark() {
        // A 4x4 grid: one hole, two adjacent holes, holes at the boundary, and a vertex
        // (the grid's vertex 6) surrounded by holes.
        let faces = grid(4, 4);
        let r = hole_recurrence(Rule::CatmullClark).unwrap();
        let cc = builtin("catmull-clark").unwrap();
        for holes in [vec![5], vec![5, 6], vec![0, 3, 12], vec![0, 1, 4, 5]] {
            let (full, written) = counts_without(&faces, &holes);
            let h = HoleCounts::between(&full, &written);
            for s in 0..5u64 {
                let whole = cc.counts_at(&full, s).unwrap();
                let kept = cc.counts_at(&written, s).unwrap();
                let gone = r.state_at(&h.state(), s).unwrap();
                assert_eq!(
                    whole.vertices - &gone[0],
                    kept.vertices,
                    "{holes:?} V at {s}"
                );
                assert_eq!(whole.edges - &gone[1], kept.edges, "{holes:?} E at {s}");
                assert_eq!(whole.faces - &gone[2], kept.faces, "{holes:?} F at {s}");
            }
        }
        let (full, written) = counts_without(&faces, &[0, 1, 4, 5]);
        assert_eq!(HoleCounts::between(&full, &written).vertices, 4);
    }

    #[test]
    fn whole_minus_holes_equals_the_written_mesh_under_splits() {
        // The octahedron (faces 0-3 around apex 0, faces 4-7 around apex 5, the square 1-4
        // between them) with a closed cap of holes around vertex 0 and a single hole.
        let ring = |i: u32| 1 + i % 4;
        let top = (0..4).map(|i| [0, ring(i), ring(i + 1)]);
        let oct: Vec<[u32; 3]> = top
            .chain((0..4).map(|i| [5, ring(i + 1), ring(i)]))
            .collect();
        for (rule, scheme) in [
            (Rule::Loop, "loop-boundary"),
            (Rule::TriSplit(3), "tri-split-3"),
            (Rule::TriSplit(5), "tri-split-5"),
        ] {
            let r = hole_recurrence(rule).unwrap();
            let sch = builtin(scheme).unwrap();
            for holes in [vec![0usize, 1, 2, 3], vec![6], vec![0, 4]] {
                let full = MeshCounts::from_polygons(&oct).unwrap();
                let kept: Vec<[u32; 3]> = (0..8)
                    .filter(|f| !holes.contains(f))
                    .map(|f| oct[f])
                    .collect();
                let written = MeshCounts::from_polygons(&kept).unwrap();
                let h = HoleCounts::between(&full, &written);
                let whole_scheme = if scheme == "loop-boundary" {
                    builtin("loop").unwrap()
                } else {
                    sch.clone()
                };
                for s in 0..4u64 {
                    let whole = whole_scheme.counts_at(&full, s).unwrap();
                    let kept = sch.counts_at(&written, s).unwrap();
                    let gone = r.state_at(&h.state(), s).unwrap();
                    assert_eq!(whole.vertices - &gone[0], kept.vertices, "{rule} {holes:?}");
                    assert_eq!(whole.edges - &gone[1], kept.edges, "{rule} {holes:?}");
                    assert_eq!(whole.faces - &gone[2], kept.faces, "{rule} {holes:?}");
                }
            }
        }
    }

    #[test]
    fn rules_whose_faces_do_not_nest_have_no_hole_recurrence() {
        for rule in Rule::ALL {
            assert_eq!(hole_recurrence(rule).is_some(), nests_faces(rule), "{rule}");
        }
        assert!(split_rows(i64::MAX).is_none());
    }
}
