//! Mesh statistics ([`schemes::MeshCounts`]) of face lists and half-edge meshes.
//!
//! [`face_list_counts`] (any face list, including the non-manifold meshes that
//! [`HalfEdgeMesh`] refuses) counts through [`MeshCounts::from_face_list`], the one
//! definition, which `schemes` owns and documents; [`HalfEdgeMesh::counts`] (a valid mesh)
//! gives the same numbers, counted by the build as it links the half-edges. This module adds the defect counts
//! ([`face_list_problems`]) and the genus.
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
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `stats.rs`: `face_list_counts` (works on any face list, through
//! `schemes::MeshCounts::from_face_list`, the one owner of the statistics) and
//! `HalfEdgeMesh::counts` (the same numbers: counted by the build of a mesh built from a face
//! list, else read off the half-edges; the tests compare both with the face list's);
//! `face_list_problems` counts every defect at once, and its duplicate-face search (hash, then
//! a sort of equal-hash faces: `n log n` on a file of identical faces) is the one validation
//! uses too.

use schemes::uv::UvCounts;
use schemes::{DisjointSets, MeshCounts};

use crate::mesh::{HalfEdgeMesh, INVALID};

mod duplicates;
mod scan;

use crate::polygon::PolygonMesh;
pub(crate) use duplicates::duplicate_faces;
use duplicates::face_hash;

/// The statistics of a raw face list, counted as it is by [`MeshCounts::from_face_list`]
/// (the one implementation, whose documentation gives the rules): non-manifold edges and
/// vertices, repeated vertices, flipped faces, even indices without a position are counted,
/// never refused; positions no face uses are `unreferenced_vertices`.
///
/// Runs in `O(H log d)` for `H` corners and vertex degrees `d`.
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
    match scan::scan(
        mesh.face_offsets(),
        mesh.face_indices(),
        mesh.n_vertices(),
        false,
        |_| true,
    ) {
        Some(scanned) => scanned.counts,
        None => MeshCounts::from_face_list(mesh.faces(), mesh.n_vertices()),
    }
}

/// The statistics of the mesh's UV layout ([`schemes::uv::UvCounts`]: values, layout edges
/// and boundary edges, seam edges, boundary loops, charts, unused `vt`), counted by
/// [`UvCounts::from_layout`] on [`PolygonMesh::uv_layout`]; `None` when the mesh has no
/// texture coordinates (or they no longer have one `vt` per face corner).
///
/// # Example
///
/// ```
/// use glam::{DVec2, DVec3};
/// use halfedge::uv::Uvs;
/// use halfedge::{stats, PolygonMesh};
///
/// // Two triangles sharing the edge 0-2; the second has its own vt at vertex 2: a seam.
/// let mut mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 4], [[0, 1, 2], [0, 2, 3]]);
/// assert_eq!(stats::uv_counts(&mesh), None);
/// let coords = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y, DVec2::splat(0.5), DVec2::NEG_X];
/// mesh.set_uvs(Some(Uvs::new(coords, vec![0, 1, 2, 0, 4, 3])?))?;
/// let uv = stats::uv_counts(&mesh).expect("a layout");
/// assert_eq!((uv.values, uv.edges, uv.boundary_edges, uv.seam_edges), (5, 6, 6, 1));
/// assert_eq!((uv.boundary_loops, uv.charts, uv.unreferenced), (1, 1, 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn uv_counts(mesh: &PolygonMesh) -> Option<UvCounts> {
    uv_counts_of_faces(mesh, |_| true)
}

/// The statistics of the UV layout as a mesh of its own: the mesh's faces with the layout's
/// values ([`PolygonMesh::uv_layout`]) as corners, counted by [`MeshCounts::from_face_list`]
/// (its `V`, `E`, `BE` are [`uv_counts`]' `values`, `edges`, `boundary_edges`). What the
/// face-varying channel refines, all faces included (holes are refined too), and what
/// [`memory::predicted_uv_bytes`](crate::memory::predicted_uv_bytes) sizes. `None` as for
/// [`uv_counts`].
///
/// ```
/// use glam::{DVec2, DVec3};
/// use halfedge::uv::Uvs;
/// use halfedge::{stats, PolygonMesh};
///
/// // Two triangles with a seam along their shared edge: two separate triangles in UV.
/// let mut mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 4], [[0, 1, 2], [0, 2, 3]]);
/// let coords = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y, DVec2::splat(0.5), DVec2::NEG_X];
/// mesh.set_uvs(Some(Uvs::new(coords, vec![0, 1, 2, 4, 5, 3])?))?;
/// let layout = stats::uv_layout_counts(&mesh).expect("a layout");
/// assert_eq!((layout.vertices, layout.edges, layout.boundary_edges, layout.faces), (6, 6, 6, 2));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn uv_layout_counts(mesh: &PolygonMesh) -> Option<MeshCounts> {
    let uvs = mesh.uvs()?;
    if uvs.corners().len() != mesh.n_corners() {
        return None;
    }
    let layout = mesh.uv_layout()?;
    let offsets = mesh.face_offsets();
    let faces = offsets.windows(2).map(|w| &layout.corners()[w[0]..w[1]]);
    Some(MeshCounts::from_face_list(faces, layout.n_values()))
}

/// [`uv_counts`] of the faces `f` with `keep(f)` (the written faces of a mesh with holes):
/// their layout, with the `vt` entries they do not use as unreferenced.
pub(crate) fn uv_counts_of_faces(
    mesh: &PolygonMesh,
    keep: impl Fn(usize) -> bool,
) -> Option<UvCounts> {
    let uvs = mesh.uvs()?;
    if uvs.corners().len() != mesh.n_corners() {
        return None;
    }
    let layout = mesh.uv_layout()?;
    let offsets = mesh.face_offsets();
    let value_vts: Vec<u32> = (0..layout.n_values() as u32)
        .map(|v| layout.value_vt(v))
        .collect();
    let mut used = vec![false; uvs.coords().len()];
    let mut kept_offsets = vec![0usize];
    let (mut vertex_corners, mut value_corners) = (Vec::new(), Vec::new());
    for f in (0..mesh.n_faces()).filter(|&f| keep(f)) {
        let corners = offsets[f]..offsets[f + 1];
        vertex_corners.extend_from_slice(&mesh.face_indices()[corners.clone()]);
        value_corners.extend_from_slice(&layout.corners()[corners.clone()]);
        for &t in &uvs.corners()[corners] {
            used[t as usize] = true;
        }
        kept_offsets.push(vertex_corners.len());
    }
    let unreferenced = used.iter().filter(|&&u| !u).count() as u64;
    // A layout built by `UvLayout::new` is consistent, so `from_layout` accepts it.
    let mut counts = UvCounts::from_layout(
        &kept_offsets,
        &vertex_corners,
        &value_corners,
        &value_vts,
        unreferenced,
    )
    .ok()?;
    if kept_offsets.len() <= mesh.n_faces() {
        // Some faces are left out: a vertex's sibling values are those of all its faces.
        counts.split_values = UvCounts::kept_split_values(
            offsets,
            mesh.face_indices(),
            layout.corners(),
            layout.n_values(),
            keep,
        )
        .ok()?;
    }
    Some(counts)
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
    face_list_report(mesh).problems
}

/// [`face_list_counts`] and [`face_list_problems`] in one scan of the faces, and whether
/// [`HalfEdgeMesh::try_from_polygon_mesh`] accepts the mesh: what `subcount stats` reports.
///
/// # Example
///
/// ```
/// use halfedge::{shapes, stats};
///
/// let report = stats::face_list_report(&shapes::grid(3, 2)?);
/// assert_eq!((report.counts.faces, report.counts.boundary_loops), (12, 1));
/// assert!(report.problems.is_empty() && report.is_valid());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn face_list_report(mesh: &PolygonMesh) -> FaceListReport {
    let positions = &mesh.positions;
    let scanned = scan::scan(
        mesh.face_offsets(),
        mesh.face_indices(),
        mesh.n_vertices(),
        true,
        |v| positions[v].is_finite(),
    );
    let Some(scan::Scanned {
        counts,
        problems: Some(mut problems),
        finite,
    }) = scanned
    else {
        // Indices without positions, or sizes beyond the scan's: the reference counts.
        return FaceListReport {
            counts: MeshCounts::from_face_list(mesh.faces(), mesh.n_vertices()),
            problems: reference_problems(mesh),
            valid: HalfEdgeMesh::try_from_polygon_mesh(mesh).is_ok(),
        };
    };
    if problems.faces_with_repeated_vertex > 0 {
        // Faces of different degrees can then share a vertex set: the reference search.
        let (indices, offsets) = (mesh.face_indices(), mesh.face_offsets());
        let face = |f: usize| &indices[offsets[f]..offsets[f + 1]];
        problems.duplicate_faces = duplicate_faces(mesh.n_faces(), &face).count;
    }
    // What `build` checks, in terms of the scan: sizes, faces of three corners or more,
    // finite used positions and no defect (a non-orientable surface has a flipped edge in
    // any orientation).
    let limit = u64::from(crate::mesh::INVALID);
    let valid = problems.is_empty()
        && finite
        && counts.faces_by_degree.range(..3).next().is_none()
        && (mesh.n_faces() as u64) < limit
        && (mesh.n_vertices() as u64) < limit
        && 2 * counts.corners < limit;
    FaceListReport {
        counts,
        problems,
        valid,
    }
}

/// The statistics and the defects of a face list ([`face_list_report`]).
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct FaceListReport {
    /// [`face_list_counts`].
    pub counts: MeshCounts,
    /// [`face_list_problems`].
    pub problems: MeshProblems,
    valid: bool,
}

impl FaceListReport {
    /// Whether [`HalfEdgeMesh::try_from_polygon_mesh`] accepts the mesh (so a caller that
    /// only needs its verdict builds nothing; one that needs the error builds it).
    pub fn is_valid(&self) -> bool {
        self.valid
    }
}

/// The defect counts by the reference algorithm (a sort of every side and of every link
/// node): where the scan does not apply, and the tests' oracle.
fn reference_problems(mesh: &PolygonMesh) -> MeshProblems {
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

    // Faces with a repeated vertex.
    let mut repeated = 0u64;
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
    }
    let duplicates = duplicate_faces(n_faces, &face).count;

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
    /// The statistics of this mesh ([`schemes::MeshCounts`]): counted by the build of a
    /// mesh built from a face list, else read off its half-edges in linear time. They equal
    /// [`MeshCounts::from_face_list`] of its faces (the rules' one definition; the tests
    /// check it), and [`face_list_counts`] of the face list the mesh was built from, whose
    /// unused vertices the mesh dropped and reports in `unreferenced_vertices`.
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
        match &self.counts {
            Some(counts) => MeshCounts::clone(counts),
            None => self.structure_counts(),
        }
    }

    /// [`HalfEdgeMesh::counts`] read off the half-edge arrays (what a mesh built from a face
    /// list keeps from its build).
    pub(crate) fn structure_counts(&self) -> MeshCounts {
        // Read off the structure in one pass per array (no sort): a valid mesh has no
        // non-manifold edge, each edge is two half-edges, a boundary half-edge has no face.
        let (nh, nv) = (self.n_halfedges(), self.n_vertices());
        let boundary: Vec<u32> = (0..nh as u32)
            .filter(|&h| self.halfedge_face[h as usize] == INVALID)
            .collect();
        let mut faces_by_degree = std::collections::BTreeMap::new();
        for f in 0..self.n_faces() {
            let start = self.face_halfedge[f];
            let (mut h, mut degree) = (self.halfedge_next[start as usize], 1u32);
            while h != start {
                h = self.halfedge_next[h as usize];
                degree += 1;
            }
            *faces_by_degree.entry(degree).or_insert(0) += 1;
        }
        // Boundary loops: the cycles of `next` through the boundary half-edges.
        let mut seen = vec![false; nh];
        let mut boundary_loops = 0;
        for &start in &boundary {
            if !seen[start as usize] {
                boundary_loops += 1;
                let mut h = start;
                while !seen[h as usize] {
                    seen[h as usize] = true;
                    h = self.halfedge_next[h as usize];
                }
            }
        }
        drop(seen);
        let mut sets = DisjointSets::new(nv);
        for e in 0..nh / 2 {
            sets.union(self.halfedge_vertex[2 * e], self.halfedge_vertex[2 * e + 1]);
        }
        let used = |v: usize| self.vertex_halfedge[v] != INVALID;
        let vertices = (0..nv).filter(|&v| used(v)).count() as u64;
        let components = (0..nv)
            .filter(|&v| used(v) && sets.find(v as u32) == v as u32)
            .count() as u64;
        let (edges, boundary_edges) = ((nh / 2) as u64, boundary.len() as u64);
        let faces = self.n_faces() as u64;
        let chi = i128::from(vertices) - i128::from(edges) + i128::from(faces);
        MeshCounts {
            vertices,
            edges,
            interior_edges: edges - boundary_edges,
            boundary_edges,
            nonmanifold_edges: 0,
            faces,
            corners: nh as u64 - boundary_edges,
            faces_by_degree,
            boundary_loops,
            components,
            euler_characteristic: i64::try_from(chi).unwrap_or(i64::MAX),
            // The mesh keeps only the vertices its faces use, and how many it dropped.
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

    #[test]
    fn identical_faces_and_one_huge_face_take_no_quadratic_pass() {
        // Sizes that take minutes in a quadratic pass (pairs of equal faces, corners of one
        // face compared with each other): 200,000 copies of one triangle, one face of 10^6
        // corners.
        let n = 1_000_000u32;
        let positions: Vec<DVec3> = (0..n + 3)
            .map(|i| DVec3::new(f64::from(i), 0.0, 0.0))
            .collect();
        let mut copies = PolygonMesh::with_positions(positions.clone());
        for _ in 0..200_000 {
            copies.push_face(&[0, 1, 2]);
        }
        let c = face_list_counts(&copies);
        assert_eq!((c.vertices, c.edges, c.nonmanifold_edges), (3, 3, 3));
        assert_eq!((c.faces, c.unreferenced_vertices), (200_000, u64::from(n)));
        let p = face_list_problems(&copies);
        assert_eq!((p.duplicate_faces, p.nonmanifold_edges), (199_999, 3));
        assert_eq!(
            HalfEdgeMesh::try_from(&copies).unwrap_err().to_string(),
            "faces 0 and 1 have the same vertices (0, 1, 2)"
        );

        let mut huge = PolygonMesh::with_positions(positions);
        huge.push_face_from_iter(3..n + 3);
        let c = face_list_counts(&huge);
        assert_eq!(
            (c.vertices, c.edges, c.boundary_edges),
            (u64::from(n), u64::from(n), u64::from(n))
        );
        assert_eq!(
            (c.components, c.boundary_loops, c.unreferenced_vertices),
            (1, 1, 3)
        );
        assert!(face_list_problems(&huge).is_empty());
        let mesh = HalfEdgeMesh::try_from(&huge).expect("a disk");
        assert_eq!(mesh.counts(), c);
        let mut repeated = PolygonMesh::with_positions(vec![DVec3::ZERO; n as usize]);
        repeated.push_face_from_iter((0..n).chain([n / 2]));
        assert_eq!(
            schemes::first_repeated_vertex(repeated.faces()),
            Some((0, n / 2))
        );
        assert_eq!(face_list_problems(&repeated).faces_with_repeated_vertex, 1);
        assert!(matches!(
            HalfEdgeMesh::try_from(&repeated),
            Err(crate::Error::RepeatedVertex { face: 0, vertex, .. }) if vertex == n / 2
        ));
    }
}
