//! [`MeshCounts`]: the statistics of a mesh that subdivision counting needs.

use std::collections::{BTreeMap, HashMap};
use std::fmt;

use crate::{Error, Result};

/// The statistics of a polygon mesh, as plain numbers.
///
/// Computed by the `halfedge` crate from a real mesh, built from a face list with
/// [`MeshCounts::from_polygons`], or typed in by hand. Every field is a plain count; nothing is
/// checked for consistency until [`MeshCounts::check_identities`] is called.
///
/// Field names follow the short names used on the command line and in JSON:
/// `V`, `E`, `IE`, `BE`, `NME`, `F`, `H` (see [`Stat`]).
///
/// # Example
///
/// ```
/// use schemes::{MeshCounts, Stat};
///
/// // A square pyramid: one quad and four triangles.
/// let m = MeshCounts::from_polygons(&[
///     vec![0, 1, 2, 3], vec![0, 4, 1], vec![1, 4, 2], vec![2, 4, 3], vec![3, 4, 0],
/// ])?;
/// assert_eq!((m.vertices, m.edges, m.faces, m.corners), (5, 8, 5, 16));
/// assert_eq!(m.get(Stat::BE), 0);
/// assert_eq!(m.euler_characteristic, 2);
/// m.check_identities()?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshCounts {
    /// `V`: vertices referenced by at least one face.
    pub vertices: u64,
    /// `E`: distinct undirected edges (unordered pairs of consecutive face corners).
    pub edges: u64,
    /// `IE`: edges with exactly two incident faces.
    pub interior_edges: u64,
    /// `BE`: edges with exactly one incident face.
    pub boundary_edges: u64,
    /// `NME`: edges with three or more incident faces (non-manifold edges).
    pub nonmanifold_edges: u64,
    /// `F`: faces.
    pub faces: u64,
    /// `H`: the sum of face degrees (the number of face corners, or half-edges).
    pub corners: u64,
    /// Number of faces of each degree (3 for triangles, 4 for quads, ...).
    pub faces_by_degree: BTreeMap<u32, u64>,
    /// Connected components of the boundary-edge graph (holes of a manifold mesh).
    pub boundary_loops: u64,
    /// Connected components of the mesh (faces joined through shared vertices).
    pub components: u64,
    /// `V - E + F` over referenced vertices.
    pub euler_characteristic: i64,
    /// Vertices in the file that no face references (not counted in `V`).
    pub unreferenced_vertices: u64,
}

/// One of the linear mesh statistics that a scheme state can bind to, by its short name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum Stat {
    /// Vertices referenced by faces.
    V,
    /// Edges.
    E,
    /// Interior edges (two faces).
    IE,
    /// Boundary edges (one face).
    BE,
    /// Non-manifold edges (three or more faces).
    NME,
    /// Faces.
    F,
    /// Sum of face degrees (corners, half-edges).
    H,
}

impl Stat {
    /// All statistics, in the order `V, E, IE, BE, NME, F, H`.
    pub const ALL: [Stat; 7] = [
        Stat::V,
        Stat::E,
        Stat::IE,
        Stat::BE,
        Stat::NME,
        Stat::F,
        Stat::H,
    ];

    /// The short name, e.g. `"IE"`.
    pub fn short_name(self) -> &'static str {
        match self {
            Stat::V => "V",
            Stat::E => "E",
            Stat::IE => "IE",
            Stat::BE => "BE",
            Stat::NME => "NME",
            Stat::F => "F",
            Stat::H => "H",
        }
    }

    /// What the statistic counts, in words.
    pub fn meaning(self) -> &'static str {
        match self {
            Stat::V => "vertices",
            Stat::E => "edges",
            Stat::IE => "interior edges (two faces)",
            Stat::BE => "boundary edges (one face)",
            Stat::NME => "non-manifold edges (three or more faces)",
            Stat::F => "faces",
            Stat::H => "sum of face degrees (corners)",
        }
    }

    /// The statistic with this short name (exact, case-sensitive).
    pub fn from_short_name(name: &str) -> Option<Stat> {
        Stat::ALL.into_iter().find(|s| s.short_name() == name)
    }

    pub(crate) fn index(self) -> usize {
        Stat::ALL.iter().position(|s| *s == self).unwrap_or(0)
    }
}

impl fmt::Display for Stat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.short_name())
    }
}

impl MeshCounts {
    /// The value of one linear statistic.
    pub fn get(&self, stat: Stat) -> u64 {
        match stat {
            Stat::V => self.vertices,
            Stat::E => self.edges,
            Stat::IE => self.interior_edges,
            Stat::BE => self.boundary_edges,
            Stat::NME => self.nonmanifold_edges,
            Stat::F => self.faces,
            Stat::H => self.corners,
        }
    }

    /// Whether the mesh has neither boundary nor non-manifold edges (`BE = 0` and `NME = 0`).
    pub fn is_closed(&self) -> bool {
        self.boundary_edges == 0 && self.nonmanifold_edges == 0
    }

    /// The statistics of a polygon mesh given as a face list (vertex indices per face).
    ///
    /// `V` counts the distinct indices used; indices need not be contiguous. Useful for small
    /// meshes in tests and for counts typed in as faces.
    ///
    /// # Errors
    ///
    /// [`Error::BadFace`] for a face with fewer than three corners or a repeated vertex.
    pub fn from_polygons<P: AsRef<[u32]>>(faces: &[P]) -> Result<MeshCounts> {
        let mut edge_faces: HashMap<(u32, u32), u64> = HashMap::new();
        let mut vertex_ids: BTreeMap<u32, usize> = BTreeMap::new();
        let mut counts = MeshCounts::default();
        for (i, face) in faces.iter().enumerate() {
            let face = face.as_ref();
            if face.len() < 3 {
                return Err(Error::BadFace {
                    face: i,
                    reason: format!("has {} corners, a face needs at least 3", face.len()),
                });
            }
            for (j, v) in face.iter().enumerate() {
                if face[..j].contains(v) {
                    return Err(Error::BadFace {
                        face: i,
                        reason: format!("repeats vertex {v}"),
                    });
                }
                let next = vertex_ids.len();
                vertex_ids.entry(*v).or_insert(next);
            }
            let degree = u32::try_from(face.len()).unwrap_or(u32::MAX);
            *counts.faces_by_degree.entry(degree).or_insert(0) += 1;
            counts.faces += 1;
            counts.corners += face.len() as u64;
            for j in 0..face.len() {
                let (a, b) = (face[j], face[(j + 1) % face.len()]);
                *edge_faces.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        counts.vertices = vertex_ids.len() as u64;
        counts.edges = edge_faces.len() as u64;
        let mut boundary = UnionFind::new(vertex_ids.len());
        let mut boundary_vertices = vec![false; vertex_ids.len()];
        for (&(a, b), &n) in &edge_faces {
            match n {
                1 => {
                    counts.boundary_edges += 1;
                    let (a, b) = (vertex_ids[&a], vertex_ids[&b]);
                    boundary.union(a, b);
                    boundary_vertices[a] = true;
                    boundary_vertices[b] = true;
                }
                2 => counts.interior_edges += 1,
                _ => counts.nonmanifold_edges += 1,
            }
        }
        counts.boundary_loops = boundary_vertices
            .iter()
            .enumerate()
            .filter(|&(v, &on)| on && boundary.find(v) == v)
            .count() as u64;
        let mut mesh = UnionFind::new(vertex_ids.len());
        for face in faces {
            let face = face.as_ref();
            for w in face.windows(2) {
                mesh.union(vertex_ids[&w[0]], vertex_ids[&w[1]]);
            }
        }
        counts.components = (0..vertex_ids.len()).filter(|&v| mesh.find(v) == v).count() as u64;
        counts.euler_characteristic =
            counts.vertices as i64 - counts.edges as i64 + counts.faces as i64;
        Ok(counts)
    }

    /// Checks the identities every mesh satisfies:
    /// `E = IE + BE + NME`, `H >= 2 IE + BE + 3 NME`, `F` and `H` equal to the sums over
    /// `faces_by_degree` (when it is filled in), `V - E + F = euler_characteristic`, and
    /// `BE = 0` exactly when there are no boundary loops.
    ///
    /// # Errors
    ///
    /// [`Error::InconsistentCounts`] naming the first identity that fails, with its values.
    pub fn check_identities(&self) -> Result {
        let fail = |detail: String| Err(Error::InconsistentCounts { detail });
        let sum = u128::from(self.interior_edges)
            + u128::from(self.boundary_edges)
            + u128::from(self.nonmanifold_edges);
        if u128::from(self.edges) != sum {
            return fail(format!(
                "E={} but IE + BE + NME = {sum} (IE={}, BE={}, NME={})",
                self.edges, self.interior_edges, self.boundary_edges, self.nonmanifold_edges
            ));
        }
        let least = 2 * u128::from(self.interior_edges)
            + u128::from(self.boundary_edges)
            + 3 * u128::from(self.nonmanifold_edges);
        if u128::from(self.corners) < least {
            return fail(format!(
                "H={} but 2 IE + BE + 3 NME = {least} (every edge side is a corner)",
                self.corners
            ));
        }
        if self.nonmanifold_edges == 0 && u128::from(self.corners) != least {
            return fail(format!(
                "H={} but 2 IE + BE = {least} on a mesh without non-manifold edges",
                self.corners
            ));
        }
        if !self.faces_by_degree.is_empty() || self.faces == 0 {
            let f: u128 = self.faces_by_degree.values().map(|&n| u128::from(n)).sum();
            let h: u128 = self
                .faces_by_degree
                .iter()
                .map(|(&d, &n)| u128::from(d) * u128::from(n))
                .sum();
            if f != u128::from(self.faces) {
                return fail(format!("F={} but faces_by_degree sums to {f}", self.faces));
            }
            if h != u128::from(self.corners) {
                return fail(format!(
                    "H={} but faces_by_degree gives {h} corners",
                    self.corners
                ));
            }
        }
        let chi = i128::from(self.vertices) - i128::from(self.edges) + i128::from(self.faces);
        if chi != i128::from(self.euler_characteristic) {
            return fail(format!(
                "euler_characteristic={} but V - E + F = {chi}",
                self.euler_characteristic
            ));
        }
        if (self.boundary_edges == 0) != (self.boundary_loops == 0) {
            return fail(format!(
                "BE={} but boundary_loops={}",
                self.boundary_edges, self.boundary_loops
            ));
        }
        Ok(())
    }

    /// Faces whose degree is not `degree`, as `(degree, count)` pairs, when known.
    ///
    /// Uses `faces_by_degree` when it is filled in; otherwise only answers for triangles
    /// (`H = 3F` exactly when every face is a triangle) and returns `None` when it cannot tell.
    pub(crate) fn faces_not_of_degree(&self, degree: u32) -> Option<Vec<(u32, u64)>> {
        if !self.faces_by_degree.is_empty() || self.faces == 0 {
            return Some(
                self.faces_by_degree
                    .iter()
                    .filter(|&(&d, &n)| d != degree && n > 0)
                    .map(|(&d, &n)| (d, n))
                    .collect(),
            );
        }
        if degree == 3 {
            if u128::from(self.corners) == 3 * u128::from(self.faces) {
                return Some(Vec::new());
            }
            return None;
        }
        None
    }
}

struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    fn find(&mut self, mut v: usize) -> usize {
        while self.parent[v] != v {
            self.parent[v] = self.parent[self.parent[v]];
            v = self.parent[v];
        }
        v
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.parent[a] = b;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_counts() {
        // Cube: 8 vertices, 12 edges (all interior), 6 quads, 24 corners, chi = 2.
        let cube = MeshCounts::from_polygons(&[
            [0, 1, 2, 3],
            [4, 7, 6, 5],
            [0, 4, 5, 1],
            [1, 5, 6, 2],
            [2, 6, 7, 3],
            [3, 7, 4, 0],
        ])
        .unwrap();
        assert_eq!(cube.vertices, 8);
        assert_eq!(cube.edges, 12);
        assert_eq!(cube.interior_edges, 12);
        assert_eq!(cube.boundary_edges, 0);
        assert_eq!(cube.faces, 6);
        assert_eq!(cube.corners, 24);
        assert_eq!(cube.faces_by_degree, BTreeMap::from([(4, 6)]));
        assert_eq!(cube.components, 1);
        assert_eq!(cube.boundary_loops, 0);
        assert_eq!(cube.euler_characteristic, 2);
        cube.check_identities().unwrap();
    }

    #[test]
    fn open_strip_and_book() {
        // Two separate triangles: 2 components, 2 boundary loops, 6 boundary edges.
        let two = MeshCounts::from_polygons(&[[0, 1, 2], [3, 4, 5]]).unwrap();
        assert_eq!(
            (two.components, two.boundary_loops, two.boundary_edges),
            (2, 2, 6)
        );
        // Three triangles on one edge (0,1): one non-manifold edge.
        let book = MeshCounts::from_polygons(&[[0, 1, 2], [1, 0, 3], [0, 1, 4]]).unwrap();
        assert_eq!(
            (book.vertices, book.edges, book.nonmanifold_edges),
            (5, 7, 1)
        );
        assert_eq!(
            (book.boundary_edges, book.interior_edges, book.corners),
            (6, 0, 9)
        );
        book.check_identities().unwrap();
    }

    #[test]
    fn bad_faces_and_identities() {
        let err = MeshCounts::from_polygons(&[vec![0, 1, 0]]).unwrap_err();
        assert_eq!(err.to_string(), "face 0: repeats vertex 0");
        let err = MeshCounts::from_polygons(&[vec![0, 1]]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "face 0: has 2 corners, a face needs at least 3"
        );
        let bad = MeshCounts {
            vertices: 12,
            edges: 31,
            interior_edges: 30,
            faces: 20,
            corners: 60,
            ..MeshCounts::default()
        };
        assert_eq!(
            bad.check_identities().unwrap_err().to_string(),
            "inconsistent mesh counts: E=31 but IE + BE + NME = 30 (IE=30, BE=0, NME=0)"
        );
    }
}
