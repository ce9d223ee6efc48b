//! Mesh statistics ([`schemes::MeshCounts`]) of face lists and half-edge meshes.
//!
//! [`face_list_counts`] works on any face list, including the non-manifold meshes that
//! [`HalfEdgeMesh`] refuses; [`HalfEdgeMesh::counts`] gives the same numbers for a valid mesh
//! in time linear in its size.
//!
//! # Example
//!
//! ```
//! use halfedge::{shapes, stats, HalfEdgeMesh};
//!
//! let cube = shapes::cube();
//! let counts = stats::face_list_counts(&cube);
//! assert_eq!((counts.vertices, counts.edges, counts.faces), (8, 12, 6));
//! assert_eq!(counts.euler_characteristic, 2);
//! assert_eq!(stats::genus(&counts), Some(0));
//! assert_eq!(HalfEdgeMesh::try_from(&cube)?.counts(), counts);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::collections::BTreeMap;

use schemes::MeshCounts;

use crate::mesh::{HalfEdgeMesh, INVALID};
use crate::polygon::PolygonMesh;

/// Union-find over `0..n` with path halving.
struct DisjointSets {
    parent: Vec<u32>,
}

impl DisjointSets {
    fn new(n: usize) -> Self {
        DisjointSets {
            parent: (0..n as u32).collect(),
        }
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let grand = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = grand;
            x = grand;
        }
        x
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra as usize] = rb;
        }
    }
}

/// The statistics of a raw face list (any faces: non-manifold edges and vertices, repeated
/// vertices, flipped faces, even indices without a position are counted as they are).
///
/// - `V`: distinct vertex indices used by faces; `unreferenced_vertices`: positions no face
///   uses.
/// - `E`: distinct unordered pairs `{a, b}` of consecutive corners (the closing pair included)
///   with `a != b`; `IE`, `BE`, `NME`: edges used by exactly 2, exactly 1, 3 or more face
///   sides (a face that runs along an edge twice counts twice).
/// - `F`, `H` (corners), faces by degree; `boundary_loops`: connected components of the graph
///   of boundary edges; `components`: faces joined through shared vertices;
///   `euler_characteristic` = `V - E + F`.
///
/// Runs in `O(H log H)` (one sort of the corners).
///
/// # Example
///
/// ```
/// use glam::DVec3;
/// use halfedge::{stats, PolygonMesh};
///
/// // Three triangles on one edge (non-manifold): the half-edge mesh refuses it,
/// // the face-list statistics do not.
/// let p = vec![DVec3::ZERO; 5];
/// let mesh = PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
/// let c = stats::face_list_counts(&mesh);
/// assert_eq!((c.vertices, c.edges, c.nonmanifold_edges, c.boundary_edges), (5, 7, 1, 6));
/// assert_eq!((c.components, c.boundary_loops, c.euler_characteristic), (1, 1, 1));
/// ```
pub fn face_list_counts(mesh: &PolygonMesh) -> MeshCounts {
    let indices = mesh.face_indices();
    let offsets = mesh.face_offsets();
    let n_faces = mesh.n_faces();

    // Compact vertex ids: a dense array when all indices have a position, else a sorted list.
    let max_index = indices.iter().copied().max().map_or(0, |m| m as usize + 1);
    let (compact, n_used): (Vec<u32>, usize) = if max_index <= mesh.positions.len().max(1 << 20) {
        let mut id = vec![INVALID; max_index];
        let mut next = 0u32;
        let compact = indices
            .iter()
            .map(|&v| {
                let slot = &mut id[v as usize];
                if *slot == INVALID {
                    *slot = next;
                    next += 1;
                }
                *slot
            })
            .collect();
        (compact, next as usize)
    } else {
        let mut sorted = indices.to_vec();
        sorted.sort_unstable();
        sorted.dedup();
        let compact = indices
            .iter()
            .map(|v| sorted.partition_point(|x| x < v) as u32)
            .collect();
        (compact, sorted.len())
    };
    let used_with_position = {
        let mut seen = vec![false; mesh.positions.len()];
        let mut count = 0usize;
        for &v in indices {
            if let Some(s) = seen.get_mut(v as usize) {
                if !*s {
                    *s = true;
                    count += 1;
                }
            }
        }
        count
    };

    // Edges: sort the undirected corner pairs (compact ids).
    let mut keys: Vec<u64> = Vec::with_capacity(indices.len());
    let mut faces_by_degree = BTreeMap::new();
    let mut components = DisjointSets::new(n_used);
    for f in 0..n_faces {
        let (start, end) = (offsets[f], offsets[f + 1]);
        *faces_by_degree.entry((end - start) as u32).or_insert(0u64) += 1;
        for c in start..end {
            let a = compact[c];
            let b = compact[if c + 1 == end { start } else { c + 1 }];
            components.union(a, b);
            if a != b {
                keys.push((u64::from(a.min(b)) << 32) | u64::from(a.max(b)));
            }
        }
    }
    keys.sort_unstable();
    let (mut edges, mut interior, mut boundary, mut nonmanifold) = (0u64, 0u64, 0u64, 0u64);
    let mut loops = DisjointSets::new(n_used);
    let mut on_boundary = vec![false; n_used];
    let mut i = 0;
    while i < keys.len() {
        let mut j = i + 1;
        while j < keys.len() && keys[j] == keys[i] {
            j += 1;
        }
        edges += 1;
        match j - i {
            1 => {
                boundary += 1;
                let (a, b) = ((keys[i] >> 32) as u32, keys[i] as u32);
                loops.union(a, b);
                on_boundary[a as usize] = true;
                on_boundary[b as usize] = true;
            }
            2 => interior += 1,
            _ => nonmanifold += 1,
        }
        i = j;
    }
    let boundary_loops = (0..n_used as u32)
        .filter(|&v| on_boundary[v as usize] && loops.find(v) == v)
        .count() as u64;
    let n_components = (0..n_used as u32)
        .filter(|&v| components.find(v) == v)
        .count() as u64;
    MeshCounts {
        vertices: n_used as u64,
        edges,
        interior_edges: interior,
        boundary_edges: boundary,
        nonmanifold_edges: nonmanifold,
        faces: n_faces as u64,
        corners: indices.len() as u64,
        faces_by_degree,
        boundary_loops,
        components: n_components,
        euler_characteristic: n_used as i64 - edges as i64 + n_faces as i64,
        unreferenced_vertices: (mesh.positions.len() - used_with_position) as u64,
    }
}

/// The defects of a face list that make [`HalfEdgeMesh`] refuse it (or would, for some of
/// them), counted — the "collect every problem" view of validation; see
/// [`face_list_problems`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct MeshProblems {
    /// Faces that use some vertex more than once (degenerate faces).
    pub faces_with_repeated_vertex: u64,
    /// Faces whose vertex set equals that of an earlier face (duplicate or back-to-back).
    pub duplicate_faces: u64,
    /// Edges with three or more face sides.
    pub nonmanifold_edges: u64,
    /// Vertices whose link (the graph of the edges opposite them in their faces) is not
    /// connected: their faces form several fans (pinched or bow-tie vertices).
    pub nonmanifold_vertices: u64,
    /// Edges with exactly two face sides that run in the same direction (a flipped face).
    pub inconsistently_oriented_edges: u64,
}

impl MeshProblems {
    /// No non-manifold edge or vertex and no face with a repeated vertex (duplicate faces and
    /// orientation are not part of manifoldness).
    pub fn is_manifold(&self) -> bool {
        self.nonmanifold_edges == 0
            && self.nonmanifold_vertices == 0
            && self.faces_with_repeated_vertex == 0
    }

    /// No problem at all (a manifold, consistently oriented face list without duplicates).
    pub fn is_empty(&self) -> bool {
        *self == MeshProblems::default()
    }
}

/// Counts every defect of a face list at once (where [`HalfEdgeMesh::try_from_polygons`]
/// stops at the first): faces with a repeated vertex, duplicate faces, non-manifold edges and
/// vertices, inconsistently oriented edges. Works on any face list, in `O(H log H)`.
///
/// # Example
///
/// ```
/// use glam::DVec3;
/// use halfedge::{stats, PolygonMesh};
///
/// // Two triangles touching at vertex 0 (a bow-tie) and a flipped neighbour of the first.
/// let p = vec![DVec3::ZERO; 6];
/// let mesh = PolygonMesh::from_faces(p, [[0, 1, 2], [0, 3, 4], [1, 2, 5]]);
/// let problems = stats::face_list_problems(&mesh);
/// assert_eq!(problems.nonmanifold_vertices, 1);
/// assert_eq!(problems.inconsistently_oriented_edges, 1);
/// assert!(!problems.is_manifold());
/// ```
pub fn face_list_problems(mesh: &PolygonMesh) -> MeshProblems {
    let indices = mesh.face_indices();
    let offsets = mesh.face_offsets();
    let n_faces = mesh.n_faces();
    let face = |f: usize| &indices[offsets[f]..offsets[f + 1]];
    let next_corner = |f: usize, c: usize| {
        if c + 1 == offsets[f + 1] {
            offsets[f]
        } else {
            c + 1
        }
    };
    let prev_corner = |f: usize, c: usize| {
        if c == offsets[f] {
            offsets[f + 1] - 1
        } else {
            c - 1
        }
    };

    // Faces with a repeated vertex, and duplicate vertex sets (a set hash, then exact).
    let mut repeated = 0u64;
    let mut sets: Vec<(u64, u32)> = Vec::with_capacity(n_faces);
    let mut scratch: Vec<u32> = Vec::new();
    for f in 0..n_faces {
        scratch.clear();
        scratch.extend_from_slice(face(f));
        scratch.sort_unstable();
        let len = scratch.len();
        scratch.dedup();
        if scratch.len() < len {
            repeated += 1;
        }
        let hash = scratch.iter().fold(scratch.len() as u64, |h, &v| {
            h.wrapping_mul(0x100_0000_01b3)
                .wrapping_add(crate::build::mix(v))
        });
        sets.push((hash, f as u32));
    }
    sets.sort_unstable();
    let mut duplicates = 0u64;
    let distinct_set = |f: u32| {
        let mut s = face(f as usize).to_vec();
        s.sort_unstable();
        s.dedup();
        s
    };
    let mut i = 0;
    while i < sets.len() {
        let mut j = i + 1;
        while j < sets.len() && sets[j].0 == sets[i].0 {
            j += 1;
        }
        if j - i > 1 {
            let mut group: Vec<Vec<u32>> =
                sets[i..j].iter().map(|&(_, f)| distinct_set(f)).collect();
            group.sort_unstable();
            group.dedup();
            duplicates += (j - i - group.len()) as u64;
        }
        i = j;
    }

    // Edges: undirected key with direction bit.
    let mut edges: Vec<(u64, bool)> = Vec::with_capacity(indices.len());
    for f in 0..n_faces {
        for c in offsets[f]..offsets[f + 1] {
            let (a, b) = (indices[c], indices[next_corner(f, c)]);
            if a != b {
                edges.push(((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), a < b));
            }
        }
    }
    edges.sort_unstable();
    let (mut nonmanifold, mut inconsistent) = (0u64, 0u64);
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j].0 == edges[i].0 {
            j += 1;
        }
        match j - i {
            2 if edges[i].1 == edges[i + 1].1 => inconsistent += 1,
            n if n > 2 => nonmanifold += 1,
            _ => {}
        }
        i = j;
    }
    drop(edges);

    // Vertex links: nodes are (vertex, neighbour) pairs, each corner joins (v, prev) and
    // (v, next); a vertex is non-manifold when its nodes form several components.
    let key = |v: u32, w: u32| (u64::from(v) << 32) | u64::from(w);
    let mut nodes: Vec<u64> = Vec::with_capacity(2 * indices.len());
    for f in 0..n_faces {
        for c in offsets[f]..offsets[f + 1] {
            let v = indices[c];
            nodes.push(key(v, indices[prev_corner(f, c)]));
            nodes.push(key(v, indices[next_corner(f, c)]));
        }
    }
    nodes.sort_unstable();
    nodes.dedup();
    let id = |k: u64| nodes.partition_point(|&x| x < k) as u32;
    let mut sets = DisjointSets::new(nodes.len());
    for f in 0..n_faces {
        for c in offsets[f]..offsets[f + 1] {
            let v = indices[c];
            let p = id(key(v, indices[prev_corner(f, c)]));
            let n = id(key(v, indices[next_corner(f, c)]));
            sets.union(p, n);
        }
    }
    let mut nonmanifold_vertices = 0u64;
    let mut roots: Vec<u32> = Vec::new();
    let mut i = 0;
    while i < nodes.len() {
        let v = nodes[i] >> 32;
        let mut j = i;
        roots.clear();
        while j < nodes.len() && nodes[j] >> 32 == v {
            roots.push(sets.find(j as u32));
            j += 1;
        }
        roots.sort_unstable();
        roots.dedup();
        if roots.len() > 1 {
            nonmanifold_vertices += 1;
        }
        i = j;
    }
    MeshProblems {
        faces_with_repeated_vertex: repeated,
        duplicate_faces: duplicates,
        nonmanifold_edges: nonmanifold,
        nonmanifold_vertices,
        inconsistently_oriented_edges: inconsistent,
    }
}

/// The genus of a manifold, orientable surface with these counts: `(2C - chi - b) / 2` (the
/// sum over components), with `C` components, `chi` the Euler characteristic over used
/// vertices and `b` boundary loops.
///
/// Returns `None` where the formula does not apply: non-manifold edges, or a value that is
/// not a non-negative integer. The counts alone cannot show a non-manifold vertex; for a
/// [`HalfEdgeMesh`] (always manifold and oriented) use [`HalfEdgeMesh::genus`].
///
/// # Example
///
/// ```
/// let torus = halfedge::shapes::torus(2)?;
/// let counts = halfedge::stats::face_list_counts(&torus);
/// assert_eq!(halfedge::stats::genus(&counts), Some(2));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn genus(counts: &MeshCounts) -> Option<u64> {
    if counts.nonmanifold_edges > 0 {
        return None;
    }
    let twice = 2 * i128::from(counts.components)
        - i128::from(counts.euler_characteristic)
        - i128::from(counts.boundary_loops);
    (twice >= 0 && twice % 2 == 0).then_some((twice / 2) as u64)
}

impl HalfEdgeMesh {
    /// The statistics of this mesh ([`schemes::MeshCounts`]), in linear time. They equal
    /// [`face_list_counts`] of the face list the mesh was built from (whose unused vertices
    /// are reported in `unreferenced_vertices`).
    ///
    /// # Example
    ///
    /// ```
    /// let mesh = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::icosahedron())?;
    /// let counts = mesh.counts();
    /// assert_eq!((counts.vertices, counts.edges, counts.faces), (12, 30, 20));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn counts(&self) -> MeshCounts {
        let nv = self.n_vertices();
        let mut faces_by_degree = BTreeMap::new();
        for f in self.faces() {
            *faces_by_degree
                .entry(self.face_degree(f) as u32)
                .or_insert(0u64) += 1;
        }
        let boundary_halfedges =
            self.halfedge_face.iter().filter(|&&f| f == INVALID).count() as u64;
        // Boundary loops: cycles of boundary half-edges.
        let mut seen = vec![false; self.n_halfedges()];
        let mut boundary_loops = 0u64;
        for h in 0..self.n_halfedges() {
            if self.halfedge_face[h] != INVALID || seen[h] {
                continue;
            }
            boundary_loops += 1;
            let mut g = h;
            while !seen[g] {
                seen[g] = true;
                g = self.halfedge_next[g] as usize;
            }
        }
        let mut sets = DisjointSets::new(nv);
        for h in (0..self.n_halfedges()).step_by(2) {
            sets.union(self.halfedge_vertex[h], self.halfedge_vertex[h + 1]);
        }
        let components = (0..nv as u32).filter(|&v| sets.find(v) == v).count() as u64;
        let (v, e, f) = (nv as u64, self.n_edges() as u64, self.n_faces() as u64);
        MeshCounts {
            vertices: v,
            edges: e,
            interior_edges: e - boundary_halfedges,
            boundary_edges: boundary_halfedges,
            nonmanifold_edges: 0,
            faces: f,
            corners: self.n_halfedges() as u64 - boundary_halfedges,
            faces_by_degree,
            boundary_loops,
            components,
            euler_characteristic: v as i64 - e as i64 + f as i64,
            unreferenced_vertices: self.unreferenced_vertices,
        }
    }

    /// The genus of the surface, summed over its components: `(2C - chi - b) / 2`.
    ///
    /// # Example
    ///
    /// ```
    /// let mesh = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::torus(3)?)?;
    /// assert_eq!(mesh.genus(), 3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn genus(&self) -> u64 {
        // A valid half-edge mesh is a manifold orientable surface, so the formula applies.
        genus(&self.counts()).unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;
    use glam::DVec3;

    #[test]
    fn faces_with_repeated_vertices_do_not_make_loop_edges() {
        // Quad 0 1 0 2 runs along {0, 1} and {0, 2} twice each; the pair (1, 0)... no loops.
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 3], [[0, 1, 0, 2]]);
        let c = face_list_counts(&mesh);
        assert_eq!(
            (c.vertices, c.edges, c.interior_edges, c.boundary_edges),
            (3, 2, 2, 0)
        );
        assert_eq!(
            (
                c.corners,
                c.components,
                c.boundary_loops,
                c.euler_characteristic
            ),
            (4, 1, 0, 2)
        );
        // A degenerate triangle 0 0 1 has one edge, used twice.
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 2], [[0, 0, 1]]);
        let c = face_list_counts(&mesh);
        assert_eq!((c.vertices, c.edges, c.interior_edges), (2, 1, 1));
    }

    #[test]
    fn components_loops_and_unreferenced_vertices() {
        // Two separate triangles and a bow-tie pair sharing vertex 6; vertex 9 unused.
        let faces = [[0u32, 1, 2], [3, 4, 5], [6, 7, 8], [6, 10, 11]];
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 12], faces);
        let c = face_list_counts(&mesh);
        assert_eq!((c.vertices, c.unreferenced_vertices), (11, 1));
        assert_eq!(
            (c.components, c.boundary_loops, c.boundary_edges),
            (3, 3, 12)
        );
        assert_eq!(c.euler_characteristic, 11 - 12 + 4);
        // The formula gives (2*3 - 3 - 3)/2 = 0: counts cannot see the pinched vertex.
        assert_eq!(genus(&c), Some(0));
    }

    #[test]
    fn indices_without_positions_are_still_counted() {
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 2], [[0, 1, 4_000_000_000]]);
        let c = face_list_counts(&mesh);
        assert_eq!((c.vertices, c.edges, c.unreferenced_vertices), (3, 3, 0));
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 2], [[0, 1, 7]]);
        assert_eq!(face_list_counts(&mesh).vertices, 3);
    }

    #[test]
    fn genus_is_none_where_the_formula_does_not_apply() {
        let c = face_list_counts(&shapes::torus(4).expect("torus"));
        assert_eq!(genus(&c), Some(4));
        let mut odd = c.clone();
        odd.euler_characteristic += 1;
        assert_eq!(genus(&odd), None);
        let mut nonmanifold = c;
        nonmanifold.nonmanifold_edges = 1;
        assert_eq!(genus(&nonmanifold), None);
    }

    #[test]
    fn half_edge_counts_equal_face_list_counts() {
        for name in [
            "icosahedron-holes:3",
            "grid:5x2",
            "mixed",
            "torus:3",
            "cube",
        ] {
            let polygons = shapes::from_name(name).expect("shape");
            let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
            assert_eq!(mesh.counts(), face_list_counts(&polygons), "{name}");
        }
    }
}
