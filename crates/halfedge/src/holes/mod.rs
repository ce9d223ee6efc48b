//! Holes in a face list: which faces are holes (tagged, or made so by
//! [`BoundaryInterpolation::None`]), the statistics of what is written, and which faces of a
//! subdivided level descend from holes.
//!
//! A hole is not a deleted face: the subdivided surface around it is what it would be with
//! the face there (OpenSubdiv's holes), but the face, its descendants and the vertices only
//! they use are not written. Counting follows [`schemes::holes`]: what is written at level
//! `s` is level `s` of the written faces alone.
//!
//! ```
//! use halfedge::holes::{boundary_faces, HoleSet};
//! use halfedge::shapes;
//!
//! // OpenSubdiv's VTX_BOUNDARY_NONE makes every face with a boundary vertex a hole: on a
//! // 3x3 grid only the centre face stays.
//! let grid = shapes::quad_grid(3, 3)?;
//! assert_eq!(boundary_faces(&grid), [0, 1, 2, 3, 5, 6, 7, 8]);
//!
//! let holes = HoleSet::new(grid.n_faces(), [4, 4, 0])?;
//! assert_eq!(holes.faces(), [0, 4]);
//! let written = holes.written_counts(&grid);
//! assert_eq!((written.vertices, written.faces), (16 - 1, 7));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! [`BoundaryInterpolation::None`]: crate::tags::BoundaryInterpolation::None
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Holes (`SubdivideOptions::holes`, the rules whose faces nest): the whole mesh is refined, so
//! the surface around a hole is unchanged, and only the output is filtered.
//! `subdivide_to_face_list`, `subdivide_polygons` and `Refinement::new` predict what is written
//! (the rule's scheme on the written faces' statistics, `HoleSet::written_level`) and check it
//! fits before building; the last level's faces descending from holes (`HoleSet::written_at`:
//! children contiguous per parent) are then dropped and the vertices renumbered in place
//! (`holes::compact_faces`, no second copy), and the written vertices and faces are checked
//! against the prediction (`Error::PredictionMismatch`). A refinement with holes keeps the written
//! face list and the index of each written vertex, evaluates the whole last level and gathers;
//! `n_vertices`, `n_faces`, `n_edges`, `n_corners` of the last level are the written counts.
//! `verify` counts the written faces of every level. The library's `subdivide` builds a half-edge
//! mesh of the written faces (refused when they meet at a vertex between holes); the CLI always
//! writes holes through the face list, which takes such a vertex.
//!
//! Owner of holes: which faces are holes (`boundary_faces_with` under `VTX_BOUNDARY_NONE`: faces
//! at a vertex with a boundary edge that is not infinitely sharp), the written faces' statistics,
//! which faces of a level descend from holes, leaving them (and the vertices only they use) out of
//! an output, in place: `halfedge::holes` (`holes.rs`: `HoleSet`, `written_at`, `written_level`,
//! `compact_faces`); subdivisions take them through `SubdivideOptions::holes`; the recurrence of
//! what holes remove (`HV, HE, HF, HH`) and `nests_faces`: `schemes::holes`.

pub(crate) mod set;

use schemes::holes::{nests_faces, HoleCounts};
use schemes::{LevelCounts, MeshCounts, Rule};

pub use self::set::HoleSet;
use crate::mesh::FaceId;
use crate::tags::BoundaryInterpolation;
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result};

/// The faces of `mesh` that have a vertex on a boundary edge (an edge of exactly one face), in
/// order: the faces OpenSubdiv makes holes under `VTX_BOUNDARY_NONE` (Loop and Catmull-Clark)
/// on a mesh without creases. [`boundary_faces_with`] follows the file's creases.
pub fn boundary_faces(mesh: &PolygonMesh) -> Vec<u32> {
    boundary_faces_with(mesh, &crate::tags::Tags::default())
}

/// The faces OpenSubdiv makes holes under `VTX_BOUNDARY_NONE` (Loop and Catmull-Clark), in
/// order: every face at a vertex with an incident boundary edge (an edge of exactly one
/// face) that `tags` does not make infinitely sharp (sharpness 10 or more: OpenSubdiv's
/// `Sdc::Crease::IsInfinite`), as `Far::TopologyRefinerFactory` tags them before it sharpens
/// the boundary. A vertex whose boundary edges are all infinitely sharp keeps its faces;
/// non-manifold vertices follow the same rule.
///
/// ```
/// use halfedge::holes::boundary_faces_with;
/// use halfedge::shapes;
/// use halfedge::tags::Tags;
///
/// // A 2x1 strip of quads (vertices 0 1 2 / 3 4 5): with the whole boundary infinitely
/// // sharp no face is a hole; with one boundary edge left smooth, the faces at its ends are.
/// let strip = shapes::quad_grid(2, 1)?;
/// let mut tags = Tags::default();
/// for (a, b) in [(0, 1), (1, 2), (2, 5), (5, 4), (4, 3), (3, 0)] {
///     tags.add_crease(a, b, 10.0)?;
/// }
/// assert!(boundary_faces_with(&strip, &tags).is_empty());
/// tags.add_crease(0, 3, 2.0)?;
/// assert_eq!(boundary_faces_with(&strip, &tags), [0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn boundary_faces_with(mesh: &PolygonMesh, tags: &crate::tags::Tags) -> Vec<u32> {
    let n = mesh.positions.len().max(
        (0..mesh.n_faces())
            .flat_map(|f| mesh.face(f).iter().map(|&v| v as usize + 1))
            .max()
            .unwrap_or(0),
    );
    // Each undirected side, as (smaller, larger); an edge of one face appears once.
    let mut sides: Vec<(u32, u32)> = Vec::new();
    for f in 0..mesh.n_faces() {
        let face = mesh.face(f);
        for (i, &a) in face.iter().enumerate() {
            let b = face[(i + 1) % face.len()];
            if a != b {
                sides.push((a.min(b), a.max(b)));
            }
        }
    }
    sides.sort_unstable();
    // The infinitely sharp edges, sorted as the sides are (the last sharpness given wins).
    let infinite: Vec<(u32, u32)> = tags
        .sharp_edges()
        .into_iter()
        .filter(|c| crate::subdivide::sdc::is_infinite(c.sharpness))
        .map(|c| (c.a, c.b))
        .collect();
    let mut on_boundary = vec![false; n];
    let mut i = 0;
    while i < sides.len() {
        let mut j = i + 1;
        while j < sides.len() && sides[j] == sides[i] {
            j += 1;
        }
        if j - i == 1 && infinite.binary_search(&sides[i]).is_err() {
            on_boundary[sides[i].0 as usize] = true;
            on_boundary[sides[i].1 as usize] = true;
        }
        i = j;
    }
    (0..mesh.n_faces())
        .filter(|&f| mesh.face(f).iter().any(|&v| on_boundary[v as usize]))
        .map(|f| f as u32)
        .collect()
}

/// The faces of `mesh` that are holes under its `tags` with the boundary mode `boundary`: the
/// faces tagged `hole` and, under [`BoundaryInterpolation::None`], the faces at the boundary
/// ([`boundary_faces_with`]; none on a closed mesh), in that order, repeats allowed (what
/// [`HoleSet::new`] takes). The one definition `HalfEdgeMesh::try_from`'s
/// [`Descriptor`](crate::Descriptor) and the `driver` crate share.
///
/// ```
/// use halfedge::holes::holes_of;
/// use halfedge::shapes;
/// use halfedge::tags::{BoundaryInterpolation, Tags};
///
/// let grid = shapes::quad_grid(3, 3)?;
/// let mut tags = Tags::default();
/// tags.add_hole(4);
/// assert_eq!(holes_of(&grid, &tags, BoundaryInterpolation::Edge), [4]);
/// assert_eq!(holes_of(&grid, &tags, BoundaryInterpolation::None), [4, 0, 1, 2, 3, 5, 6, 7, 8]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn holes_of(
    mesh: &PolygonMesh,
    tags: &crate::tags::Tags,
    boundary: BoundaryInterpolation,
) -> Vec<u32> {
    let mut faces = tags.hole_faces();
    if boundary == BoundaryInterpolation::None {
        faces.extend(boundary_faces_with(mesh, tags));
    }
    faces
}

impl HoleSet {
    /// The statistics of the written faces of `mesh` (every face that is not a hole), counted
    /// as [`MeshCounts::from_face_list`] counts a file: vertices only holes use are
    /// unreferenced.
    pub fn written_counts(&self, mesh: &PolygonMesh) -> MeshCounts {
        let written = (0..mesh.n_faces())
            .filter(|&f| !self.contains(f as u32))
            .map(|f| mesh.face(f));
        MeshCounts::from_face_list(written, mesh.positions.len())
    }

    /// The UV layout statistics of the written faces of `mesh`
    /// ([`stats::uv_counts`](crate::stats::uv_counts) of the faces that are not holes; `vt`
    /// entries only holes use are unreferenced): what [`schemes::uv::UvScheme`] counts the
    /// written UV values from, as [`HoleSet::written_counts`] for `V`, `E`, `F`. `None`
    /// without texture coordinates.
    pub fn written_uv_counts(&self, mesh: &PolygonMesh) -> Option<schemes::uv::UvCounts> {
        crate::stats::uv_counts_of_faces(mesh, |f| !self.contains(f as u32))
    }

    /// [`HoleSet::written_counts`] of a half-edge mesh (its faces are the faces of the face
    /// list it was built from, in order).
    pub fn written_mesh_counts(&self, mesh: &HalfEdgeMesh) -> MeshCounts {
        let faces = (0..mesh.n_faces() as u32)
            .filter(|&f| !self.contains(f))
            .map(|f| mesh.face_vertices(FaceId(f)).map(|v| v.0));
        MeshCounts::from_face_list(faces, mesh.n_vertices())
    }

    /// What `rule` writes at `level` of a mesh whose written faces have the statistics
    /// `written` ([`HoleSet::written_counts`]): the rule's scheme for those faces
    /// ([`Rule::scheme_for`]: a closed mesh with holes has boundary and counts with the
    /// boundary-aware state) at `level`.
    ///
    /// ```
    /// use halfedge::holes::HoleSet;
    /// use halfedge::{shapes, Rule};
    ///
    /// let cube = shapes::cube();
    /// let holes = HoleSet::new(cube.n_faces(), [0])?;
    /// let at2 = HoleSet::written_level(Rule::CatmullClark, &holes.written_counts(&cube), 2)?;
    /// assert_eq!(at2.faces, (5 * 16).into());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::HolesNeedNestedFaces`] for a rule whose faces do not nest; [`Error::Scheme`]
    /// when the rule's scheme refuses the written faces.
    pub fn written_level(rule: Rule, written: &MeshCounts, level: u32) -> Result<LevelCounts> {
        if !nests_faces(rule) {
            return Err(Error::HolesNeedNestedFaces { rule });
        }
        let scheme = rule.scheme_for(written)?;
        Ok(scheme.counts_at(written, u64::from(level))?)
    }

    /// What the holes remove from `mesh` ([`schemes::holes::HoleCounts`]).
    pub fn hole_counts(&self, mesh: &PolygonMesh) -> HoleCounts {
        let full = crate::stats::face_list_counts(mesh);
        HoleCounts::between(&full, &self.written_counts(mesh))
    }

    /// Which faces of level `level` of `rule` are written (`true`) or descend from a hole,
    /// for a level numbered as [`crate::subdivide`] numbers it: the children of a face are
    /// contiguous and in the order of their parents (1:N² splits: `N²` per face; Catmull-Clark:
    /// one per corner). `degrees` are the base faces' degrees.
    ///
    /// # Errors
    ///
    /// [`Error::HolesNeedNestedFaces`] for a rule whose faces do not nest (√3, Doo-Sabin,
    /// mid-edge); [`Error::TooLarge`] when the level's faces do not fit `usize`.
    pub fn written_at(&self, rule: Rule, degrees: &[usize], level: u32) -> Result<Vec<bool>> {
        if !nests_faces(rule) {
            return Err(Error::HolesNeedNestedFaces { rule });
        }
        let mut written: Vec<bool> = (0..degrees.len())
            .map(|f| !self.contains(f as u32))
            .collect();
        let split = match rule {
            Rule::TriSplit(n) => n as usize * n as usize,
            _ => 4,
        };
        for s in 1..=level {
            let first = s == 1 && rule == Rule::CatmullClark;
            let total = if first {
                Some(degrees.iter().sum::<usize>())
            } else {
                written.len().checked_mul(split)
            };
            let Some(total) = total else {
                return Err(Error::TooLarge {
                    what: "faces",
                    scheme: rule.to_string(),
                    level: s,
                    count: num_bigint::BigInt::from(written.len()) * split,
                });
            };
            let mut next = Vec::with_capacity(total);
            for (f, &w) in written.iter().enumerate() {
                let children = if first { degrees[f] } else { split };
                next.extend(std::iter::repeat(w).take(children));
            }
            written = next;
        }
        Ok(written)
    }
}

/// The offsets of a face list (`usize` in a [`PolygonMesh`], `u32` in a refinement's buffers).
pub(crate) trait Offset: Copy {
    fn get(self) -> usize;
    /// Only called with values up to an existing offset.
    fn make(n: usize) -> Self;
}

impl Offset for usize {
    fn get(self) -> usize {
        self
    }
    fn make(n: usize) -> usize {
        n
    }
}

impl Offset for u32 {
    fn get(self) -> usize {
        self as usize
    }
    fn make(n: usize) -> u32 {
        n as u32
    }
}

/// Keeps, in place, the faces of `offsets` / `indices` whose `written` entry is `true` (in
/// order) and renumbers their vertices: the vertices they use, in the order of their old
/// index. Returns the old index of each kept vertex (ascending). `written` has one entry per
/// face; `n_vertices` bounds the indices.
pub(crate) fn compact_faces<O: Offset>(
    offsets: &mut Vec<O>,
    indices: &mut Vec<u32>,
    n_vertices: usize,
    written: &[bool],
) -> Result<Vec<u32>> {
    const UNUSED: u32 = u32::MAX;
    let nf = offsets.len().saturating_sub(1);
    let mut map = crate::subdivide::alloc::filled(UNUSED, n_vertices, "the written vertices")?;
    for f in 0..nf {
        if written.get(f) == Some(&true) {
            for &v in &indices[offsets[f].get()..offsets[f + 1].get()] {
                if let Some(slot) = map.get_mut(v as usize) {
                    *slot = 0;
                }
            }
        }
    }
    let used = map.iter().filter(|&&m| m != UNUSED).count();
    let mut kept = crate::subdivide::alloc::with_capacity(used, "the written vertices")?;
    for (v, slot) in map.iter_mut().enumerate() {
        if *slot != UNUSED {
            *slot = kept.len() as u32;
            kept.push(v as u32);
        }
    }
    let (mut start, mut faces, mut corners) = (offsets.first().map_or(0, |o| o.get()), 0, 0);
    for f in 0..nf {
        let end = offsets[f + 1].get();
        if written.get(f) == Some(&true) {
            for i in start..end {
                indices[corners] = map.get(indices[i] as usize).copied().unwrap_or(UNUSED);
                corners += 1;
            }
            faces += 1;
            offsets[faces] = O::make(corners);
        }
        start = end;
    }
    offsets.truncate(faces + 1);
    indices.truncate(corners);
    Ok(kept)
}

/// Moves the entries of `kept` (ascending old indices) to the front of `values`, in order,
/// and drops the rest.
pub(crate) fn compact_values<T: Clone>(values: &mut Vec<T>, kept: &[u32]) {
    for (new, &old) in kept.iter().enumerate() {
        if new != old as usize {
            values[new] = values[old as usize].clone();
        }
    }
    values.truncate(kept.len());
}

/// The written part of a subdivided level: the faces whose `written` entry is `true` and the
/// vertices they use, renumbered in order (compacted in place, no second copy).
pub(crate) fn written_part(mesh: PolygonMesh, written: &[bool]) -> Result<PolygonMesh> {
    let (mut positions, mut offsets, mut indices) = mesh.into_parts();
    let kept = compact_faces(&mut offsets, &mut indices, positions.len(), written)?;
    compact_values(&mut positions, &kept);
    positions.shrink_to_fit();
    Ok(PolygonMesh::from_raw_parts(positions, offsets, indices))
}

/// The holes of a subdivision run (`opts.holes`), `None` when there are none; refused for a
/// rule whose faces do not nest and checked against the base mesh's `n_faces`.
pub(crate) fn active(
    holes: Option<&HoleSet>,
    rule: Rule,
    n_faces: usize,
) -> Result<Option<&HoleSet>> {
    let Some(holes) = holes.filter(|h| !h.is_empty()) else {
        return Ok(None);
    };
    if !nests_faces(rule) {
        return Err(Error::HolesNeedNestedFaces { rule });
    }
    holes.check(n_faces)?;
    Ok(Some(holes))
}

/// The face degrees of a half-edge mesh, for [`HoleSet::written_at`].
pub(crate) fn degrees_of(mesh: &HalfEdgeMesh) -> Vec<usize> {
    (0..mesh.n_faces() as u32)
        .map(|f| mesh.face_degree(FaceId(f)))
        .collect()
}

/// Checks a written level against its prediction (a mismatch is a bug).
pub(crate) fn check_written(
    name: &str,
    level: u32,
    predicted: &LevelCounts,
    vertices: usize,
    faces: usize,
) -> Result<()> {
    for (what, predicted, actual) in [
        ("written vertices", &predicted.vertices, vertices),
        ("written faces", &predicted.faces, faces),
    ] {
        if *predicted != num_bigint::BigInt::from(actual) {
            return Err(Error::PredictionMismatch {
                scheme: name.to_owned(),
                level,
                what,
                predicted: predicted.clone(),
                actual: actual as u64,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn boundary_faces_of_closed_meshes_are_none() {
        assert!(boundary_faces(&shapes::cube()).is_empty());
        let grid = shapes::grid(2, 2).unwrap();
        assert_eq!(boundary_faces(&grid).len(), grid.n_faces());
    }

    #[test]
    fn out_of_range_holes_are_refused_naming_the_face() {
        let err = HoleSet::new(6, [2, 6]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "hole face 6 is out of range (the mesh has 6 faces)"
        );
    }

    #[test]
    fn descendants_of_holes_follow_their_parents() {
        let cube = shapes::cube();
        let holes = HoleSet::new(6, [1]).unwrap();
        let degrees = vec![4; 6];
        let l1 = holes.written_at(Rule::CatmullClark, &degrees, 1).unwrap();
        assert_eq!(l1.len(), 24);
        assert_eq!(l1.iter().filter(|w| !**w).count(), 4);
        assert!(!l1[4] && !l1[7] && l1[3] && l1[8]);
        let l2 = holes.written_at(Rule::CatmullClark, &degrees, 2).unwrap();
        assert_eq!(l2.iter().filter(|w| !**w).count(), 16);
        let tri = HoleSet::new(8, [0, 7]).unwrap();
        let l2 = tri.written_at(Rule::TriSplit(3), &[3; 8], 2).unwrap();
        assert_eq!(
            (l2.len(), l2.iter().filter(|w| !**w).count()),
            (8 * 81, 2 * 81)
        );
        assert!(matches!(
            tri.written_at(Rule::Sqrt3, &[3; 8], 1),
            Err(Error::HolesNeedNestedFaces { .. })
        ));
        let _ = cube;
    }

    #[test]
    fn written_counts_drop_what_only_holes_use() {
        // A 2x2 quad grid with its corner face 0 a hole: vertex 0 is used by no other face.
        let grid = shapes::quad_grid(2, 2).unwrap();
        let holes = HoleSet::new(4, [0]).unwrap();
        let w = holes.written_counts(&grid);
        assert_eq!(
            (w.vertices, w.edges, w.faces, w.unreferenced_vertices),
            (8, 10, 3, 1)
        );
        let h = holes.hole_counts(&grid);
        assert_eq!((h.vertices, h.edges, h.faces, h.corners), (1, 2, 1, 4));
    }
}
