//! [`MeshCounts`]: the statistics of a mesh that subdivision counting needs.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Subdivision schemes as matrices. `MeshCounts` is the plain-number statistics of a mesh (V, E,
//! IE, BE, NME, F, H, faces by degree, boundary loops, components, Euler characteristic,
//! unreferenced vertices); `Stat` names its short keys. `counts.rs` is the one owner of mesh
//! statistics: `MeshCounts::from_face_list` (faces as slices or iterators of indices, plus the
//! number of positions) is the only code that computes them, for `halfedge`'s face lists and
//! half-edge meshes alike, in `O(H log d)`; it also holds the workspace's one disjoint-set
//! structure (`DisjointSets`) and `first_repeated_vertex`. One semantics, documented on
//! `MeshCounts`: a face list is counted as it is, never refused (a repeated vertex is a corner
//! each time, a side from a vertex to itself is no edge, a face running along an edge twice counts
//! twice); `V` is the vertices faces use and positions no face uses are `unreferenced_vertices`,
//! outside every other count. `MeshCounts::from_polygons` validates first (at least three corners,
//! no repeated vertex) because a prediction from such a face is meaningless.
//!
//! Owner of mesh statistics (`MeshCounts` from any face list; one disjoint-set structure):
//! `schemes::MeshCounts::from_face_list` (`counts.rs`); `halfedge::stats` only calls it.

use std::borrow::Borrow;
use std::collections::BTreeMap;
use std::fmt;

use crate::{Error, Result};

/// The statistics of a polygon mesh, as plain numbers.
///
/// Computed from faces in exactly one place, [`MeshCounts::from_face_list`], whose
/// documentation gives the rules (the `halfedge` crate's `stats::face_list_counts` and
/// `HalfEdgeMesh::counts` call it; [`MeshCounts::from_polygons`] validates and then calls it),
/// or typed in by hand. Every field is a plain count; nothing is checked for consistency until
/// [`MeshCounts::check_identities`] is called.
///
/// In short: a face list is counted as it is, never refused. A vertex repeated in a face
/// counts as a corner (`H`) each time, a side from a vertex to itself is no edge, and a face
/// that runs along an edge twice counts twice towards that edge. `V` counts the vertices faces
/// use; positions no face uses are `unreferenced_vertices`, outside `V` and every other count
/// (a half-edge mesh drops them and remembers how many).
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
    /// `E`: distinct undirected edges (unordered pairs of different vertices at consecutive
    /// face corners, the last corner and the first included).
    pub edges: u64,
    /// `IE`: edges with exactly two incident faces.
    pub interior_edges: u64,
    /// `BE`: edges with exactly one incident face.
    pub boundary_edges: u64,
    /// `NME`: edges with three or more incident faces (non-manifold edges).
    pub nonmanifold_edges: u64,
    /// `F`: faces.
    pub faces: u64,
    /// `H`: the sum of face degrees (the number of face corners, repeated vertices included;
    /// the half-edges of a half-edge mesh's faces).
    pub corners: u64,
    /// Number of faces of each degree (3 for triangles, 4 for quads, ...).
    pub faces_by_degree: BTreeMap<u32, u64>,
    /// Connected components of the boundary-edge graph (holes of a manifold mesh).
    pub boundary_loops: u64,
    /// Connected components of the mesh (vertices joined through the sides of faces, so faces
    /// sharing a vertex are one component).
    pub components: u64,
    /// `V - E + F` over referenced vertices.
    pub euler_characteristic: i64,
    /// Positions of the vertex list that no face references (not counted in `V`); 0 when
    /// there is no separate vertex list ([`MeshCounts::from_polygons`]).
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

    /// What the statistic counts, in two words (a chart's legend).
    pub fn brief(self) -> &'static str {
        match self {
            Stat::V => "vertices",
            Stat::E => "edges",
            Stat::IE => "interior edges",
            Stat::BE => "boundary edges",
            Stat::NME => "non-manifold edges",
            Stat::F => "faces",
            Stat::H => "face corners",
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

    /// The statistics of a face list meant for predictions: every face has at least three
    /// corners and no repeated vertex, and there is no separate vertex list (so
    /// `unreferenced_vertices` is 0).
    ///
    /// `V` counts the distinct indices used; indices need not be contiguous. The counts are
    /// those of [`MeshCounts::from_face_list`] (the one implementation, whose documentation
    /// gives the rules); this constructor only refuses the faces that make a subdivision
    /// prediction meaningless. Useful for small meshes in tests and for counts typed in as
    /// faces. Runs in `O(H log H)`.
    ///
    /// # Errors
    ///
    /// [`Error::BadFace`] for the first face with fewer than three corners or a repeated
    /// vertex.
    pub fn from_polygons<P: AsRef<[u32]>>(faces: &[P]) -> Result<MeshCounts> {
        if let Some((face, p)) = faces.iter().enumerate().find(|(_, p)| p.as_ref().len() < 3) {
            return Err(Error::BadFace {
                face,
                reason: format!("has {} corners, a face needs at least 3", p.as_ref().len()),
            });
        }
        if let Some((face, v)) = first_repeated_vertex(faces.iter().map(AsRef::as_ref)) {
            return Err(Error::BadFace {
                face,
                reason: format!("repeats vertex {v}"),
            });
        }
        Ok(MeshCounts::from_face_list(
            faces.iter().map(AsRef::as_ref),
            0,
        ))
    }

    /// The statistics of any face list, counted as it is: the one place where `MeshCounts`
    /// are computed from faces (the `halfedge` crate's face-list and half-edge statistics
    /// call it).
    ///
    /// `faces` yields each face as its vertex indices in order (slices, arrays, vectors or
    /// any iterator of `u32` or `&u32`); it is walked three times, so it must be `Clone`.
    /// `positions` is the length of the mesh's vertex list (0 when there is none).
    ///
    /// Nothing is refused: a raw file may have faces of any degree, repeated vertices,
    /// edges of many faces and unused positions, and these are the rules that count them:
    ///
    /// - `V`: distinct vertex indices that some face uses (an index without a position
    ///   counts too); `unreferenced_vertices`: indices in `0..positions` that no face uses,
    ///   which are not in `V`.
    /// - Each face has one side per corner, from the corner to the next (the last to the
    ///   first). `E`: distinct unordered pairs `{a, b}` with `a != b` of the two ends of a
    ///   side; a side from a vertex to itself (a vertex repeated in consecutive corners) is
    ///   no edge. `IE`, `BE`, `NME`: edges with exactly 2, exactly 1, 3 or more sides (a
    ///   face that runs along an edge twice, as in `0 1 0 2`, counts twice).
    /// - `F`: faces; `H`: corners, repeated vertices included; `faces_by_degree` by corner
    ///   count.
    /// - `boundary_loops`: connected components of the graph of boundary edges;
    ///   `components`: vertices joined through the sides of faces; `euler_characteristic`:
    ///   `V - E + F`.
    ///
    /// Whether such a mesh can be subdivided is another question: [`MeshCounts::from_polygons`]
    /// and the `subcount` commands that predict or subdivide refuse a face with a repeated
    /// vertex, and `subcount stats` reports it among the problems.
    ///
    /// Runs in `O(H log d)` for `H` corners and vertex degrees `d` (a bucket per vertex, then
    /// a sort per bucket), with memory linear in `H`.
    ///
    /// # Example
    ///
    /// ```
    /// use schemes::MeshCounts;
    ///
    /// // Six positions; the quad runs along {0, 1} twice; position 5 is unused.
    /// let faces: [&[u32]; 2] = [&[0, 1, 0, 2], &[2, 3, 4]];
    /// let c = MeshCounts::from_face_list(faces, 6);
    /// assert_eq!((c.vertices, c.unreferenced_vertices, c.corners), (5, 1, 7));
    /// assert_eq!((c.edges, c.interior_edges, c.boundary_edges), (5, 2, 3));
    /// assert_eq!((c.components, c.boundary_loops), (1, 1));
    /// ```
    pub fn from_face_list<F>(faces: F, positions: usize) -> MeshCounts
    where
        F: IntoIterator + Clone,
        F::Item: IntoIterator,
        <F::Item as IntoIterator>::Item: Borrow<u32>,
    {
        // Pass 1: the largest index, to choose how vertices get compact ids.
        let mut max_index: Option<u32> = None;
        for face in faces.clone() {
            for v in face {
                let v = *v.borrow();
                max_index = Some(max_index.map_or(v, |m| m.max(v)));
            }
        }
        let ids = VertexIds::new(faces.clone(), max_index, positions);
        let n = ids.len();

        // Pass 2: faces, corners, components; how many sides start at each smaller end.
        let mut counts = MeshCounts::default();
        let mut components = DisjointSets::new(n);
        let mut bucket_start = vec![0usize; n + 1];
        for_each_side(faces.clone(), &ids, |side| match side {
            Side::Face { degree } => {
                let degree = u32::try_from(degree).unwrap_or(u32::MAX);
                *counts.faces_by_degree.entry(degree).or_insert(0) += 1;
                counts.faces += 1;
            }
            Side::Edge(a, b) => {
                counts.corners += 1;
                components.union(a, b);
                if a != b {
                    bucket_start[a.min(b) as usize + 1] += 1;
                }
            }
        });
        for v in 0..n {
            bucket_start[v + 1] += bucket_start[v];
        }

        // Pass 3: the larger end of each side, in the bucket of the smaller end.
        let mut larger = vec![0u32; bucket_start[n]];
        let mut fill = bucket_start.clone();
        for_each_side(faces, &ids, |side| {
            if let Side::Edge(a, b) = side {
                if a != b {
                    let slot = &mut fill[a.min(b) as usize];
                    larger[*slot] = a.max(b);
                    *slot += 1;
                }
            }
        });
        drop(fill);

        // Edges: equal larger ends within a bucket are the sides of one edge.
        let mut loops = DisjointSets::new(n);
        let mut on_boundary = vec![false; n];
        for a in 0..n {
            let bucket = &mut larger[bucket_start[a]..bucket_start[a + 1]];
            bucket.sort_unstable();
            let mut i = 0;
            while i < bucket.len() {
                let b = bucket[i];
                let mut j = i + 1;
                while j < bucket.len() && bucket[j] == b {
                    j += 1;
                }
                counts.edges += 1;
                match j - i {
                    1 => {
                        counts.boundary_edges += 1;
                        loops.union(a as u32, b);
                        on_boundary[a] = true;
                        on_boundary[b as usize] = true;
                    }
                    2 => counts.interior_edges += 1,
                    _ => counts.nonmanifold_edges += 1,
                }
                i = j;
            }
        }
        counts.vertices = n as u64;
        counts.unreferenced_vertices = (positions - ids.with_position()) as u64;
        counts.boundary_loops = (0..n)
            .filter(|&v| on_boundary[v] && loops.find(v as u32) == v as u32)
            .count() as u64;
        counts.components = (0..n)
            .filter(|&v| components.find(v as u32) == v as u32)
            .count() as u64;
        let chi = i128::from(counts.vertices) - i128::from(counts.edges) + i128::from(counts.faces);
        counts.euler_characteristic = i64::try_from(chi).unwrap_or(i64::MAX);
        counts
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

/// The first face that uses a vertex twice, as `(face, vertex)`: the face with the smallest
/// index that has one, and in it the first corner whose vertex an earlier corner of the face
/// already used. Runs in `O(H log d)` for `H` corners and face degrees `d`.
///
/// # Example
///
/// ```
/// let faces: [&[u32]; 3] = [&[0, 1, 2], &[3, 4, 5, 4, 3], &[6, 6, 7]];
/// assert_eq!(schemes::first_repeated_vertex(faces), Some((1, 4)));
/// assert_eq!(schemes::first_repeated_vertex([[0u32, 1, 2]]), None);
/// ```
pub fn first_repeated_vertex<F>(faces: F) -> Option<(usize, u32)>
where
    F: IntoIterator,
    F::Item: IntoIterator,
    <F::Item as IntoIterator>::Item: Borrow<u32>,
{
    // Short faces are checked pairwise (at most 28 comparisons); longer ones by sorting
    // (vertex, position) pairs: the first repeating corner is the smallest position that
    // is not the first of its vertex.
    const PAIRWISE: usize = 8;
    let mut corners: Vec<u32> = Vec::new();
    let mut sorted: Vec<(u32, usize)> = Vec::new();
    for (f, face) in faces.into_iter().enumerate() {
        corners.clear();
        corners.extend(face.into_iter().map(|v| *v.borrow()));
        if corners.len() <= PAIRWISE {
            if let Some(i) = (1..corners.len()).find(|&i| corners[..i].contains(&corners[i])) {
                return Some((f, corners[i]));
            }
            continue;
        }
        sorted.clear();
        sorted.extend(corners.iter().enumerate().map(|(i, &v)| (v, i)));
        sorted.sort_unstable();
        let first = sorted
            .windows(2)
            .filter(|w| w[0].0 == w[1].0)
            .map(|w| w[1].1)
            .min();
        if let Some(i) = first {
            return Some((f, corners[i]));
        }
    }
    None
}

/// Compact ids `0..len()` for the distinct vertex indices of a face list, numbered in
/// increasing index order.
enum VertexIds {
    /// `ids[v]` for every index `v` up to the largest (`u32::MAX` where unused), when that
    /// array is no larger than the positions (or a million entries).
    Dense {
        ids: Vec<u32>,
        len: usize,
        with_position: usize,
    },
    /// The distinct indices, sorted (for indices far beyond the positions).
    Sorted {
        indices: Vec<u32>,
        with_position: usize,
    },
}

impl VertexIds {
    fn new<F>(faces: F, max_index: Option<u32>, positions: usize) -> VertexIds
    where
        F: IntoIterator,
        F::Item: IntoIterator,
        <F::Item as IntoIterator>::Item: Borrow<u32>,
    {
        let Some(max) = max_index else {
            return VertexIds::Sorted {
                indices: Vec::new(),
                with_position: 0,
            };
        };
        let span = max as usize + 1;
        if max < u32::MAX && span <= positions.max(1 << 20) {
            let mut ids = vec![u32::MAX; span];
            for face in faces {
                for v in face {
                    ids[*v.borrow() as usize] = 0;
                }
            }
            let (mut len, mut with_position) = (0usize, 0usize);
            for (v, id) in ids.iter_mut().enumerate() {
                if *id == 0 {
                    *id = len as u32;
                    len += 1;
                    if v < positions {
                        with_position += 1;
                    }
                }
            }
            return VertexIds::Dense {
                ids,
                len,
                with_position,
            };
        }
        let mut indices: Vec<u32> = faces
            .into_iter()
            .flat_map(|face| face.into_iter().map(|v| *v.borrow()))
            .collect();
        indices.sort_unstable();
        indices.dedup();
        let with_position = indices.partition_point(|&v| (v as usize) < positions);
        VertexIds::Sorted {
            indices,
            with_position,
        }
    }

    /// The number of distinct indices.
    fn len(&self) -> usize {
        match self {
            VertexIds::Dense { len, .. } => *len,
            VertexIds::Sorted { indices, .. } => indices.len(),
        }
    }

    /// The number of distinct indices below the number of positions.
    fn with_position(&self) -> usize {
        match self {
            VertexIds::Dense { with_position, .. } | VertexIds::Sorted { with_position, .. } => {
                *with_position
            }
        }
    }

    /// The id of an index of the face list.
    #[inline]
    fn id(&self, v: u32) -> u32 {
        match self {
            VertexIds::Dense { ids, .. } => ids[v as usize],
            VertexIds::Sorted { indices, .. } => indices.partition_point(|&x| x < v) as u32,
        }
    }
}

/// What [`for_each_side`] reports: a face (before its sides) or one side, as compact ids.
enum Side {
    Face { degree: usize },
    Edge(u32, u32),
}

/// Walks the faces: for each, `Side::Face` and then its sides from each corner to the next
/// (the last corner to the first), in compact ids.
#[inline]
fn for_each_side<F>(faces: F, ids: &VertexIds, mut visit: impl FnMut(Side))
where
    F: IntoIterator,
    F::Item: IntoIterator,
    <F::Item as IntoIterator>::Item: Borrow<u32>,
{
    let mut corners: Vec<u32> = Vec::new();
    for face in faces {
        corners.clear();
        corners.extend(face.into_iter().map(|v| ids.id(*v.borrow())));
        visit(Side::Face {
            degree: corners.len(),
        });
        for (i, &a) in corners.iter().enumerate() {
            let b = corners[if i + 1 == corners.len() { 0 } else { i + 1 }];
            visit(Side::Edge(a, b));
        }
    }
}

/// Union-find over `0..n` with path halving: the one disjoint-set structure of the
/// workspace (mesh components and boundary loops here, vertex fans in `halfedge`'s
/// validation and defect counts).
///
/// # Example
///
/// ```
/// let mut sets = schemes::DisjointSets::new(4);
/// sets.union(0, 2);
/// assert_eq!(sets.find(0), sets.find(2));
/// assert_ne!(sets.find(1), sets.find(2));
/// ```
#[derive(Clone, Debug)]
pub struct DisjointSets {
    parent: Vec<u32>,
}

impl DisjointSets {
    /// `n` singleton sets `{0}, ..., {n - 1}`.
    ///
    /// # Panics
    ///
    /// When `n` exceeds `u32::MAX + 1` (elements are `u32`).
    pub fn new(n: usize) -> DisjointSets {
        assert!(n as u64 <= 1 << 32, "DisjointSets over {n} elements");
        DisjointSets {
            parent: (0..n).map(|x| x as u32).collect(),
        }
    }

    /// The representative of the set holding `x`.
    ///
    /// # Panics
    ///
    /// When `x` is not below `n`.
    #[inline]
    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let grand = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = grand;
            x = grand;
        }
        x
    }

    /// Joins the sets holding `a` and `b`.
    ///
    /// # Panics
    ///
    /// When `a` or `b` is not below `n`.
    #[inline]
    pub fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra as usize] = rb;
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

    /// The rules of [`MeshCounts::from_face_list`] written out the slow, obvious way: maps of
    /// edges to side counts and a graph search for components.
    fn naive_counts(faces: &[Vec<u32>], positions: usize) -> MeshCounts {
        use std::collections::{BTreeSet, HashMap};
        let used: BTreeSet<u32> = faces.iter().flatten().copied().collect();
        let mut sides: BTreeMap<(u32, u32), u64> = BTreeMap::new();
        let mut neighbours: HashMap<u32, Vec<u32>> = HashMap::new();
        let mut c = MeshCounts::default();
        for face in faces {
            c.faces += 1;
            c.corners += face.len() as u64;
            *c.faces_by_degree.entry(face.len() as u32).or_insert(0) += 1;
            for (i, &a) in face.iter().enumerate() {
                let b = face[(i + 1) % face.len()];
                neighbours.entry(a).or_default().push(b);
                neighbours.entry(b).or_default().push(a);
                if a != b {
                    *sides.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
        }
        let search = |start: u32, seen: &mut BTreeSet<u32>, graph: &HashMap<u32, Vec<u32>>| {
            let mut stack = vec![start];
            while let Some(v) = stack.pop() {
                if seen.insert(v) {
                    stack.extend(graph.get(&v).into_iter().flatten());
                }
            }
        };
        let mut seen = BTreeSet::new();
        for &v in &used {
            if !seen.contains(&v) {
                c.components += 1;
                search(v, &mut seen, &neighbours);
            }
        }
        let mut boundary: HashMap<u32, Vec<u32>> = HashMap::new();
        for (&(a, b), &n) in &sides {
            c.edges += 1;
            match n {
                1 => {
                    c.boundary_edges += 1;
                    boundary.entry(a).or_default().push(b);
                    boundary.entry(b).or_default().push(a);
                }
                2 => c.interior_edges += 1,
                _ => c.nonmanifold_edges += 1,
            }
        }
        let mut seen = BTreeSet::new();
        for &v in boundary.keys() {
            if !seen.contains(&v) {
                c.boundary_loops += 1;
                search(v, &mut seen, &boundary);
            }
        }
        c.vertices = used.len() as u64;
        c.unreferenced_vertices = (0..positions)
            .filter(|&v| !used.contains(&(v as u32)))
            .count() as u64;
        c.euler_characteristic = c.vertices as i64 - c.edges as i64 + c.faces as i64;
        c
    }

    /// Any face list: degrees 0 to 9, indices from a small range (repeats and shared edges
    /// are frequent) or, sometimes, far beyond the positions (the sorted-id path).
    fn face_list() -> impl Strategy<Value = (Vec<Vec<u32>>, usize)> {
        let index = prop_oneof![8 => 0u32..10, 1 => (u32::MAX - 3)..=u32::MAX];
        (
            prop::collection::vec(prop::collection::vec(index, 0..10), 0..12),
            0usize..14,
        )
    }

    use proptest::prelude::*;

    proptest! {
        #[test]
        fn from_face_list_follows_the_documented_rules((faces, positions) in face_list()) {
            let counts = MeshCounts::from_face_list(&faces, positions);
            prop_assert_eq!(&counts, &naive_counts(&faces, positions));
            prop_assert!(counts.faces_by_degree.values().sum::<u64>() == counts.faces);
        }

        #[test]
        fn first_repeated_vertex_is_the_first_repeating_corner(
            faces in prop::collection::vec(prop::collection::vec(0u32..40, 0..30), 0..6),
        ) {
            let naive = faces.iter().enumerate().find_map(|(f, face)| {
                (1..face.len())
                    .find(|&i| face[..i].contains(&face[i]))
                    .map(|i| (f, face[i]))
            });
            prop_assert_eq!(first_repeated_vertex(&faces), naive);
        }

        #[test]
        fn from_polygons_counts_valid_faces_like_from_face_list(
            (faces, _) in face_list(),
        ) {
            let valid: Vec<Vec<u32>> = faces
                .into_iter()
                .filter(|f| f.len() >= 3 && first_repeated_vertex([f]).is_none())
                .collect();
            prop_assert_eq!(
                MeshCounts::from_polygons(&valid).expect("valid faces"),
                MeshCounts::from_face_list(&valid, 0)
            );
        }
    }

    #[test]
    fn repeated_and_unreferenced_vertices_follow_one_rule() {
        // Quad 0 1 0 2 runs along {0, 1} and {0, 2} twice each: two interior edges, no loop
        // edge; vertex 3 has a position but no face.
        let c = MeshCounts::from_face_list([[0u32, 1, 0, 2]], 4);
        assert_eq!(
            (c.vertices, c.edges, c.interior_edges, c.boundary_edges),
            (3, 2, 2, 0)
        );
        assert_eq!((c.corners, c.unreferenced_vertices), (4, 1));
        // A degenerate triangle 0 0 1: one edge used twice, the side 0 -> 0 is no edge.
        let c = MeshCounts::from_face_list([[0u32, 0, 1]], 2);
        assert_eq!(
            (c.vertices, c.edges, c.interior_edges, c.corners),
            (2, 1, 1, 3)
        );
        // An index without a position is still a vertex; it is not an unreferenced one.
        let c = MeshCounts::from_face_list([[0u32, 1, 4_000_000_000]], 2);
        assert_eq!((c.vertices, c.edges, c.unreferenced_vertices), (3, 3, 0));
        // from_polygons refuses what from_face_list counts.
        assert_eq!(
            MeshCounts::from_polygons(&[[0, 1, 0, 2]])
                .unwrap_err()
                .to_string(),
            "face 0: repeats vertex 0"
        );
    }

    #[test]
    fn identical_faces_and_one_huge_face_are_counted_quickly() {
        // Sizes that take minutes in a quadratic pass: 200,000 copies of one triangle, and
        // one face of 300,001 corners that repeats a vertex at its end.
        let mut faces: Vec<Vec<u32>> = vec![vec![0, 1, 2]; 200_000];
        let mut huge: Vec<u32> = (3..300_003).collect();
        huge.push(150_000);
        faces.push(huge);
        let c = MeshCounts::from_face_list(&faces, 300_003);
        assert_eq!(
            (c.vertices, c.edges, c.nonmanifold_edges),
            (300_003, 300_004, 3)
        );
        assert_eq!((c.faces, c.corners, c.components), (200_001, 900_001, 2));
        assert_eq!(c.boundary_edges, 300_001);
        assert_eq!(first_repeated_vertex(&faces), Some((200_000, 150_000)));
        assert_eq!(
            MeshCounts::from_polygons(&faces).unwrap_err().to_string(),
            "face 200000: repeats vertex 150000"
        );
    }
}
