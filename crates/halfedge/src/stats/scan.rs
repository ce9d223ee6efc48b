//! The statistics and the defects of a flat face list in one scan, in memory bounded by the
//! mesh's own size: what [`super::face_list_counts`], [`super::face_list_problems`] and
//! [`super::face_list_report`] run on a [`PolygonMesh`](crate::PolygonMesh).
//!
//! [`MeshCounts::from_face_list`] defines the statistics (any iterator of faces; a bucket
//! per vertex, sorted) and the reference defect count stays in the tests; this scan computes
//! the same numbers from the flat arrays, checked equal to both by property tests:
//!
//! 1. One pass over the faces: degrees, corners, repeated vertices, the number of corners at
//!    each vertex.
//! 2. Vertex ranges of at most [`CHUNK_CORNERS`] corners: one pass over the faces gathers, for
//!    each corner at a vertex of the range, its previous and next vertex (8 bytes), then each
//!    vertex is settled from its own corners alone:
//!    - each edge `{v, w}`, `w > v`, is a side of exactly the corners at `v` whose next or
//!      previous vertex is `w`: its sides and their directions (interior, boundary,
//!      non-manifold, flipped) are there;
//!    - the vertex's link (previous to next, per corner) tells a single fan from several;
//!    - a triangle on its smallest vertex `v` is that corner's `(prev, v, next)`: duplicate
//!      triangles meet in the bucket of `v`; other faces are compared by a hash of their
//!      vertex set, per range.
//! 3. Components by union-find over the edges; boundary loops over the boundary edges only.
//!
//! A grid of 33.5 M triangles takes the mesh's 1.07 GB plus about 270 MB here (a corner count
//! per vertex, the union-find, one range's corners), where sorting every side took 4 GB.

use std::collections::BTreeMap;

use schemes::{DisjointSets, MeshCounts};

use super::MeshProblems;

/// The most corners whose neighbours one vertex range gathers at once (8 bytes each).
pub(crate) const CHUNK_CORNERS: usize = 1 << 24;

/// Marks a previous vertex whose corner belongs to a triangle (vertex ids stay below `2^31`).
const TRIANGLE: u32 = 1 << 31;

/// What one scan found: the counts, and the defects when asked for.
pub(crate) struct Scanned {
    pub(crate) counts: MeshCounts,
    pub(crate) problems: Option<MeshProblems>,
    /// Every used position is finite (only checked with the defects).
    pub(crate) finite: bool,
}

/// Scans the faces `offsets`/`indices` over `positions` vertices (`finite(v)` tells whether a
/// position is finite). `None` where the scan does not apply and the reference
/// implementations must run: an index without a position, `2^31` or more vertices, `2^32`
/// or more corners.
pub(crate) fn scan(
    offsets: &[usize],
    indices: &[u32],
    positions: usize,
    problems: bool,
    finite: impl Fn(usize) -> bool,
) -> Option<Scanned> {
    scan_in_ranges(offsets, indices, positions, problems, finite, CHUNK_CORNERS)
}

/// [`scan`] with vertex ranges of at most `chunk` corners (small in tests).
fn scan_in_ranges(
    offsets: &[usize],
    indices: &[u32],
    positions: usize,
    problems: bool,
    finite: impl Fn(usize) -> bool,
    chunk: usize,
) -> Option<Scanned> {
    let n = positions;
    if n >= TRIANGLE as usize || indices.len() >= u32::MAX as usize {
        return None;
    }
    let n_faces = offsets.len().saturating_sub(1);

    // 1. Faces: degrees, repeated vertices, corners per vertex (then their start offsets).
    let mut start = vec![0u32; n + 1];
    let mut small_degrees = [0u64; 8];
    let mut degrees: BTreeMap<u32, u64> = BTreeMap::new();
    let mut repeated = 0u64;
    let mut empty = 0u64;
    let mut scratch: Vec<u32> = Vec::new();
    for f in 0..n_faces {
        let face = &indices[offsets[f]..offsets[f + 1]];
        match small_degrees.get_mut(face.len()) {
            Some(slot) => *slot += 1,
            None => {
                *degrees
                    .entry(u32::try_from(face.len()).unwrap_or(u32::MAX))
                    .or_insert(0) += 1
            }
        }
        for &v in face {
            *start.get_mut(v as usize + 1)? += 1;
        }
        if problems && has_repeat(face, &mut scratch) {
            repeated += 1;
        }
        empty += u64::from(face.is_empty());
    }
    for (d, &count) in small_degrees.iter().enumerate() {
        if count > 0 {
            degrees.insert(d as u32, count);
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let used = |v: usize| start[v + 1] > start[v];
    let vertices = (0..n).filter(|&v| used(v)).count() as u64;
    let all_finite = !problems || (0..n).all(|v| !used(v) || finite(v));

    // 2. Vertex ranges: each corner's neighbours, then each vertex on its own.
    let mut acc = Accumulator::new(n, problems, problems && repeated == 0);
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    let mut cursor: Vec<u32> = Vec::new();
    let mut others: Vec<(u64, u32)> = Vec::new();
    let mut lo = 0usize;
    while lo < n {
        let mut hi = lo + 1;
        while hi < n && (start[hi + 1] - start[lo]) as usize <= chunk {
            hi += 1;
        }
        let base = start[lo];
        pairs.clear();
        pairs.resize((start[hi] - base) as usize, (0, 0));
        cursor.clear();
        cursor.extend((lo..hi).map(|v| start[v] - base));
        others.clear();
        let (lo32, hi32) = (lo as u32, hi as u32);
        for f in 0..n_faces {
            let face = &indices[offsets[f]..offsets[f + 1]];
            let k = face.len();
            let mark = if k == 3 { TRIANGLE } else { 0 };
            for (i, &v) in face.iter().enumerate() {
                if v >= lo32 && v < hi32 {
                    let prev = face[if i == 0 { k - 1 } else { i - 1 }];
                    let next = face[if i + 1 == k { 0 } else { i + 1 }];
                    let slot = &mut cursor[(v - lo32) as usize];
                    pairs[*slot as usize] = (prev | mark, next);
                    *slot += 1;
                }
            }
            if acc.dedupe_faces && k != 3 && k > 0 {
                let least = face.iter().copied().min().unwrap_or(0);
                if least >= lo32 && least < hi32 {
                    others.push((super::face_hash(face), f as u32));
                }
            }
        }
        for v in lo..hi {
            let corners = &pairs[(start[v] - base) as usize..(start[v + 1] - base) as usize];
            acc.vertex(v as u32, corners);
        }
        if acc.dedupe_faces {
            acc.duplicates += duplicates_by_hash(&mut others, |f| {
                &indices[offsets[f as usize]..offsets[f as usize + 1]]
            });
        }
        lo = hi;
    }
    drop(pairs);

    // 3. Components and boundary loops.
    let components = (0..n)
        .filter(|&v| used(v) && acc.components.find(v as u32) == v as u32)
        .count() as u64;
    let boundary_loops = loops(&acc.boundary);
    let counts = MeshCounts {
        vertices,
        edges: acc.interior + acc.boundary_edges + acc.nonmanifold,
        interior_edges: acc.interior,
        boundary_edges: acc.boundary_edges,
        nonmanifold_edges: acc.nonmanifold,
        faces: n_faces as u64,
        corners: indices.len() as u64,
        faces_by_degree: degrees,
        boundary_loops,
        components,
        euler_characteristic: {
            let edges = acc.interior + acc.boundary_edges + acc.nonmanifold;
            let chi = i128::from(vertices) - i128::from(edges) + n_faces as i128;
            i64::try_from(chi).unwrap_or(i64::MAX)
        },
        unreferenced_vertices: n as u64 - vertices,
    };
    let problems = problems.then(|| MeshProblems {
        faces_with_repeated_vertex: repeated,
        // With a repeated vertex, faces of different degrees can have one vertex set: the
        // caller counts duplicates by the reference search instead.
        duplicate_faces: acc.duplicates + empty.saturating_sub(1),
        nonmanifold_edges: acc.nonmanifold,
        nonmanifold_vertices: acc.nonmanifold_vertices,
        inconsistently_oriented_edges: acc.inconsistent,
    });
    Some(Scanned {
        counts,
        problems,
        finite: all_finite,
    })
}

/// Whether `face` uses a vertex twice (`scratch` sorts faces of more than eight corners).
fn has_repeat(face: &[u32], scratch: &mut Vec<u32>) -> bool {
    match face {
        [a, b, c] => a == b || b == c || a == c,
        _ if face.len() <= 8 => (1..face.len()).any(|i| face[..i].contains(&face[i])),
        _ => {
            scratch.clear();
            scratch.extend_from_slice(face);
            scratch.sort_unstable();
            scratch.windows(2).any(|w| w[0] == w[1])
        }
    }
}

/// Faces beyond the first on each vertex set among `list` (hash, face), comparing sets
/// only within a hash.
fn duplicates_by_hash<'a>(list: &mut [(u64, u32)], face: impl Fn(u32) -> &'a [u32]) -> u64 {
    list.sort_unstable();
    let mut count = 0;
    for run in list.chunk_by(|x, y| x.0 == y.0).filter(|run| run.len() > 1) {
        let mut sets: Vec<Vec<u32>> = run
            .iter()
            .map(|&(_, f)| {
                let mut s = face(f).to_vec();
                s.sort_unstable();
                s
            })
            .collect();
        sets.sort_unstable();
        count += sets
            .chunk_by(|x, y| x == y)
            .map(|s| s.len() as u64 - 1)
            .sum::<u64>();
    }
    count
}

/// Boundary loops: components of the graph of boundary edges, over their vertices only.
fn loops(edges: &[(u32, u32)]) -> u64 {
    let mut ends: Vec<u32> = edges.iter().flat_map(|&(a, b)| [a, b]).collect();
    ends.sort_unstable();
    ends.dedup();
    let id = |v: u32| ends.partition_point(|&x| x < v) as u32;
    let mut sets = DisjointSets::new(ends.len());
    for &(a, b) in edges {
        sets.union(id(a), id(b));
    }
    (0..ends.len() as u32)
        .filter(|&x| sets.find(x) == x)
        .count() as u64
}

/// The totals of the per-vertex step.
struct Accumulator {
    components: DisjointSets,
    want_problems: bool,
    dedupe_faces: bool,
    interior: u64,
    boundary_edges: u64,
    nonmanifold: u64,
    inconsistent: u64,
    nonmanifold_vertices: u64,
    duplicates: u64,
    /// Boundary edges `(v, w)`, `v < w`.
    boundary: Vec<(u32, u32)>,
    /// Per vertex: the other ends above it, with 1 for a side arriving at the vertex.
    ends: Vec<(u32, u32)>,
    /// Per vertex: triangles on it as their smallest vertex.
    triangles: Vec<(u32, u32)>,
    /// Per vertex: the link's nodes, for the general fan count.
    nodes: Vec<u32>,
}

impl Accumulator {
    fn new(n: usize, want_problems: bool, dedupe_faces: bool) -> Accumulator {
        Accumulator {
            components: DisjointSets::new(n),
            want_problems,
            dedupe_faces,
            interior: 0,
            boundary_edges: 0,
            nonmanifold: 0,
            inconsistent: 0,
            nonmanifold_vertices: 0,
            duplicates: 0,
            boundary: Vec::new(),
            ends: Vec::new(),
            triangles: Vec::new(),
            nodes: Vec::new(),
        }
    }

    /// Settles vertex `v` from its corners `(prev, next)` (a triangle's `prev` marked).
    fn vertex(&mut self, v: u32, corners: &[(u32, u32)]) {
        if corners.is_empty() {
            return;
        }
        // Edges {v, w}, w > v: the corners at v whose next (a side leaving v) or previous
        // vertex (a side arriving) is w.
        self.ends.clear();
        for &(prev, next) in corners {
            let prev = prev & !TRIANGLE;
            if next > v {
                self.ends.push((next, 0));
            }
            if prev > v {
                self.ends.push((prev, 1));
            }
        }
        self.ends.sort_unstable();
        let mut i = 0;
        while i < self.ends.len() {
            let (w, dir) = self.ends[i];
            let mut j = i + 1;
            while j < self.ends.len() && self.ends[j].0 == w {
                j += 1;
            }
            match j - i {
                1 => {
                    self.boundary_edges += 1;
                    self.boundary.push((v, w));
                }
                2 => {
                    self.interior += 1;
                    if dir == self.ends[i + 1].1 {
                        self.inconsistent += 1;
                    }
                }
                _ => self.nonmanifold += 1,
            }
            self.components.union(v, w);
            i = j;
        }
        if !self.want_problems {
            return;
        }
        if !single_fan(corners) {
            self.nonmanifold_vertices += u64::from(!self.single_fan_general(corners));
        }
        if self.dedupe_faces {
            self.triangles.clear();
            for &(prev, next) in corners {
                if prev & TRIANGLE != 0 {
                    let prev = prev & !TRIANGLE;
                    if prev > v && next > v {
                        self.triangles.push((prev.min(next), prev.max(next)));
                    }
                }
            }
            if self.triangles.len() > 1 {
                self.triangles.sort_unstable();
                let before = self.triangles.len();
                self.triangles.dedup();
                self.duplicates += (before - self.triangles.len()) as u64;
            }
        }
    }

    /// Whether the link (nodes: the previous and next vertices; one link edge per corner)
    /// is connected, by union-find over its distinct nodes.
    fn single_fan_general(&mut self, corners: &[(u32, u32)]) -> bool {
        self.nodes.clear();
        self.nodes
            .extend(corners.iter().flat_map(|&(p, n)| [p & !TRIANGLE, n]));
        self.nodes.sort_unstable();
        self.nodes.dedup();
        let id = |x: u32| self.nodes.partition_point(|&y| y < x) as u32;
        let mut sets = DisjointSets::new(self.nodes.len());
        let mut parts = self.nodes.len();
        for &(p, n) in corners {
            let (a, b) = (sets.find(id(p & !TRIANGLE)), sets.find(id(n)));
            if a != b {
                sets.union(a, b);
                parts -= 1;
            }
        }
        parts == 1
    }
}

/// The common case of a manifold vertex, without allocating: at most 16 corners, no node
/// twice as a previous or twice as a next vertex (so the link is paths and cycles), and one
/// walk from a path's start (or anywhere on a cycle) crosses every corner. `false` means
/// "not shown": the general count decides.
fn single_fan(corners: &[(u32, u32)]) -> bool {
    let k = corners.len();
    if k > 16 {
        return false;
    }
    let prev = |i: usize| corners[i].0 & !TRIANGLE;
    for i in 1..k {
        for j in 0..i {
            if prev(i) == prev(j) || corners[i].1 == corners[j].1 {
                return false;
            }
        }
    }
    // A path starts at a node that is no corner's next vertex.
    let begin = (0..k)
        .map(prev)
        .find(|&p| corners.iter().all(|&(_, n)| n != p))
        .unwrap_or_else(|| prev(0));
    let mut at = begin;
    let mut steps = 0;
    while let Some(i) = (0..k).find(|&i| prev(i) == at) {
        at = corners[i].1;
        steps += 1;
        if at == begin || steps > k {
            break;
        }
    }
    steps == k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::PolygonMesh;
    use crate::HalfEdgeMesh;
    use glam::DVec3;
    use proptest::prelude::*;

    /// Face lists with every defect: small vertex pools, faces of 0-6 corners, repeats,
    /// flips, copies, unused and non-finite positions.
    fn face_list() -> impl Strategy<Value = (Vec<Vec<u32>>, usize, Option<usize>)> {
        (3usize..14).prop_flat_map(|n| {
            (
                prop::collection::vec(prop::collection::vec(0..n as u32, 0..7), 0..14),
                Just(n),
                prop::option::weighted(0.2, 0..n),
            )
        })
    }

    /// Valid meshes too (defects are rare above): strips and fans of triangles and quads.
    fn surface() -> impl Strategy<Value = (Vec<Vec<u32>>, usize, Option<usize>)> {
        (2u32..7, 1u32..5, any::<bool>(), prop::option::of(0usize..8)).prop_map(
            |(w, h, quads, flip)| {
                let mesh = if quads {
                    crate::shapes::from_name(&format!("quad-grid:{w}x{h}"))
                } else {
                    crate::shapes::grid(w, h)
                }
                .expect("grid");
                let mut faces: Vec<Vec<u32>> = mesh.faces().map(<[u32]>::to_vec).collect();
                if let Some(f) = flip.filter(|&f| f < faces.len()) {
                    faces[f].reverse();
                }
                (faces, mesh.n_vertices(), None)
            },
        )
    }

    /// Only triangles or only quads, without repeated vertices, over few vertices: many
    /// copies and flips (validation compares them across edges).
    fn uniform() -> impl Strategy<Value = (Vec<Vec<u32>>, usize, Option<usize>)> {
        (3usize..5, 4u32..9).prop_flat_map(|(k, n)| {
            let face = Just((0..n).collect::<Vec<u32>>())
                .prop_shuffle()
                .prop_map(move |v| v[..k].to_vec());
            (
                prop::collection::vec(face, 0..12),
                Just(n as usize),
                Just(None),
            )
        })
    }

    fn check(faces: &[Vec<u32>], n: usize, nan: Option<usize>, chunk: usize) {
        let mut positions = vec![DVec3::ZERO; n];
        if let Some(v) = nan {
            positions[v].x = f64::NAN;
        }
        let mesh = PolygonMesh::from_faces(positions, faces);
        let reference = MeshCounts::from_face_list(mesh.faces(), n);
        let scanned = scan_in_ranges(
            mesh.face_offsets(),
            mesh.face_indices(),
            n,
            true,
            |v| mesh.positions[v].is_finite(),
            chunk,
        )
        .expect("in range");
        assert_eq!(scanned.counts, reference, "{faces:?}");
        let mut problems = scanned.problems.expect("asked for");
        let expected = super::super::reference_problems(&mesh);
        if problems.faces_with_repeated_vertex > 0 {
            // face_list_report replaces the duplicates by the reference search then.
            problems.duplicate_faces = expected.duplicate_faces;
        }
        assert_eq!(problems, expected, "{faces:?}");
        // Duplicates by definition: faces whose set of distinct vertices an earlier face has.
        let set = |f: &Vec<u32>| {
            let mut s = f.clone();
            s.sort_unstable();
            s.dedup();
            s
        };
        let naive = (0..faces.len())
            .filter(|&g| (0..g).any(|f| set(&faces[f]) == set(&faces[g])))
            .count() as u64;
        assert_eq!(expected.duplicate_faces, naive, "{faces:?}");
        let first = (0..faces.len())
            .flat_map(|g| (0..g).map(move |f| (f as u32, g as u32)))
            .filter(|&(f, g)| set(&faces[f as usize]) == set(&faces[g as usize]))
            .min();
        let face = |f: usize| faces[f].as_slice();
        assert_eq!(
            super::super::duplicate_faces(faces.len(), &face).first_pair,
            first
        );
        // Validation names the smallest pair when nothing comes before duplicates.
        let clean = faces
            .iter()
            .all(|f| f.len() >= 3 && set(f).len() == f.len());
        if clean && nan.is_none() {
            let named = match HalfEdgeMesh::try_from_polygon_mesh(&mesh) {
                Err(crate::Error::DuplicateFace { first, second, .. }) => Some((first, second)),
                _ => None,
            };
            assert_eq!(named, first, "{faces:?}");
        }
        let report = super::super::face_list_report(&mesh);
        let built = HalfEdgeMesh::try_from_polygon_mesh(&mesh);
        assert_eq!(report.is_valid(), built.is_ok(), "{faces:?} {nan:?}");
        if let Ok(built) = built {
            // The half-edge mesh reads the same counts off its structure.
            let own_faces = (0..built.n_faces() as u32)
                .map(|f| built.face_vertices(crate::mesh::FaceId(f)).map(|v| v.0));
            let own = MeshCounts {
                unreferenced_vertices: reference.unreferenced_vertices,
                ..MeshCounts::from_face_list(own_faces, built.n_vertices())
            };
            assert_eq!(built.counts(), own, "{faces:?}");
            assert_eq!(built.counts(), reference, "{faces:?}");
        }
        assert_eq!((report.counts, report.problems), (reference, expected));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn the_scan_counts_what_the_reference_counts((faces, n, nan) in face_list(), chunk in 1usize..40) {
            check(&faces, n, nan, chunk);
        }

        #[test]
        fn the_scan_counts_uniform_faces_as_the_reference((faces, n, nan) in uniform(), chunk in 1usize..40) {
            check(&faces, n, nan, chunk);
        }

        #[test]
        fn the_scan_counts_surfaces_as_the_reference((faces, n, nan) in surface(), chunk in 1usize..40) {
            check(&faces, n, nan, chunk);
        }
    }

    #[test]
    fn indices_without_positions_leave_it_to_the_reference() {
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 2], [[0, 1, 7]]);
        let scanned = scan(mesh.face_offsets(), mesh.face_indices(), 2, false, |_| true);
        assert!(scanned.is_none());
        assert_eq!(super::super::face_list_counts(&mesh).vertices, 3);
    }
}
