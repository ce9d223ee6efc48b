//! Validating construction of a [`HalfEdgeMesh`] from a face list.
//!
//! Edges are matched by bucketing the faces' sides by their smaller vertex (a counting sort)
//! and sorting each bucket, a vertex's few sides, by (larger vertex, corner): linear time, no
//! hashing, and every numbering and every reported error deterministic. Checks run in a fixed
//! order and the first problem found is reported: face sizes, indices and repeated vertices
//! (face by face), non-finite coordinates, faces on the same vertex set, non-manifold edges,
//! orientation (a flipped face or a non-orientable surface), non-manifold vertices.
//!
//! The passes also count what [`HalfEdgeMesh::counts`] reports (faces by degree, boundary
//! edges and loops, components), which the mesh keeps: a mesh read from a file is counted
//! by its build, not walked again.

use std::collections::BTreeMap;

use glam::DVec3;
use schemes::{DisjointSets, MeshCounts};

use crate::descriptor::Descriptor;
use crate::error::{Error, FaceVertices, Result};
use crate::mesh::{HalfEdgeMesh, INVALID};
use crate::polygon::PolygonMesh;

/// Builds and validates. `offsets` has one entry more than there are faces and starts at 0.
pub(crate) fn build(
    positions: &[DVec3],
    offsets: &[usize],
    indices: &[u32],
) -> Result<HalfEdgeMesh> {
    let n_faces = offsets.len().saturating_sub(1);
    let nv = positions.len();
    let n_corners = indices.len();
    if n_faces >= INVALID as usize {
        return Err(Error::TooManyElements {
            what: "faces",
            count: n_faces as u64,
        });
    }
    if nv >= INVALID as usize {
        return Err(Error::TooManyElements {
            what: "vertices",
            count: nv as u64,
        });
    }
    if (n_corners as u64) * 2 >= u64::from(INVALID) {
        return Err(Error::TooManyElements {
            what: "half-edges",
            count: n_corners as u64 * 2,
        });
    }
    let face = |f: usize| &indices[offsets[f]..offsets[f + 1]];

    // 1. Face by face: size, range, repeated vertices. `last[v]` = 1 + the last corner at v
    // (0: no face uses v); the sides are counted by their smaller vertex for step 3.
    let mut last = vec![0u32; nv];
    let mut counted = vec![0u32; nv + 2];
    let mut degrees = Degrees::default();
    for (f, w) in offsets.windows(2).enumerate() {
        let (first, vertices) = (w[0], &indices[w[0]..w[1]]);
        let describe = || FaceVertices(vertices.to_vec());
        if vertices.len() < 3 {
            return Err(Error::FaceTooSmall {
                face: f as u32,
                vertices: describe(),
                degree: vertices.len(),
            });
        }
        if let Some(&v) = vertices.iter().find(|&&v| v as usize >= nv) {
            return Err(Error::VertexOutOfRange {
                face: f as u32,
                vertices: describe(),
                vertex: v,
                n_vertices: nv,
            });
        }
        for (c, &v) in (first..).zip(vertices) {
            if last[v as usize] as usize > first {
                return Err(Error::RepeatedVertex {
                    face: f as u32,
                    vertices: describe(),
                    vertex: v,
                });
            }
            last[v as usize] = c as u32 + 1;
        }
        Sides::count(&mut counted, vertices);
        degrees.add(vertices.len());
    }

    // 2. Referenced vertices, renumbered in order (no table when every vertex is); non-finite
    // coordinates.
    let unreferenced = last.iter().filter(|&&l| l == 0).count();
    let used = |v: usize| unreferenced == 0 || last[v] != 0;
    if let Some(v) = (0..nv).find(|&v| used(v) && !positions[v].is_finite()) {
        let p = positions[v];
        return Err(Error::NonFiniteCoordinate {
            vertex: v as u32,
            x: p.x,
            y: p.y,
            z: p.z,
        });
    }
    let mut remap = Vec::new();
    let new_positions = match unreferenced {
        0 => positions.to_vec(),
        _ => {
            remap = vec![INVALID; nv];
            let mut kept = Vec::with_capacity(nv - unreferenced);
            for (v, &p) in positions.iter().enumerate().filter(|&(v, _)| used(v)) {
                remap[v] = kept.len() as u32;
                kept.push(p);
            }
            kept
        }
    };
    let n_used = new_positions.len();
    let renumber = |v: u32| remap.get(v as usize).copied().unwrap_or(v);
    let old_number = |new: u32| match remap.is_empty() {
        true => new,
        false => remap.iter().position(|&n| n == new).unwrap_or(0) as u32,
    };

    // 3. The corners' sides, bucketed by smaller vertex ([`Sides`]). The tag is
    // `2 * corner + dir`, with dir = 1 when the corner's edge runs from the larger vertex to
    // the smaller.
    let mut sides = Sides::new(counted, offsets, indices);

    // 4. One pass over the edges, numbered in sorted order: half-edge 2e runs from the
    // smaller vertex to the larger one, 2e + 1 back, and each corner takes the one of its
    // direction; `corner_of` holds each half-edge's corner (`INVALID` on the boundary) and
    // the boundary half-edges are listed. The pass also notes the first of each problem,
    // reported in the documented order after it: faces on one vertex set (compared across
    // the edges they share, or searched by their sets), a non-manifold edge, a flipped one.
    let uniform = degrees.uniform();
    let mut found = EdgeProblems::new(uniform, indices);
    let mut halfedge_vertex: Vec<u32> = Vec::with_capacity(2 * n_corners);
    let mut corner_of: Vec<u32> = Vec::with_capacity(2 * n_corners);
    let mut corner_halfedge = vec![0u32; n_corners];
    let mut boundary: Vec<u32> = Vec::new();
    let mut at = 0;
    for small in 0..nv {
        let bucket = sides.bucket(small);
        let a = renumber(small as u32);
        for run in bucket.chunk_by(|x, y| x[0] == y[0]) {
            let e = (halfedge_vertex.len() / 2) as u32;
            let b = renumber(run[0][0]);
            halfedge_vertex.extend([b, a]);
            let (mut from_small, mut from_large) = (INVALID, INVALID);
            for &[_, tag] in run {
                corner_halfedge[(tag >> 1) as usize] = 2 * e + (tag & 1);
                match tag & 1 {
                    0 => from_small = tag >> 1,
                    _ => from_large = tag >> 1,
                }
            }
            corner_of.extend([from_small, from_large]);
            if run.len() == 1 {
                boundary.push(2 * e + 1 - (run[0][1] & 1));
            }
        }
        found.bucket(small as u32, bucket, at);
        at += bucket.len();
    }
    let face_of_corner = |c: u32| offsets.partition_point(|&o| o <= c as usize) - 1;
    let duplicate = match found.by_sets {
        true => crate::stats::duplicate_faces(n_faces, &face).first_pair,
        false => found.duplicate,
    };
    if let Some((first, second)) = duplicate {
        return Err(Error::DuplicateFace {
            first,
            second,
            vertices: FaceVertices(face(first as usize).to_vec()),
        });
    }
    if let Some((key, tags)) = found.nonmanifold {
        return Err(Error::NonManifoldEdge {
            a: (key >> 32) as u32,
            b: key as u32,
            count: tags.len(),
            faces: FaceVertices(
                tags.iter()
                    .map(|&t| face_of_corner(t >> 1) as u32)
                    .collect(),
            ),
        });
    }
    if let Some(first) = found.flipped {
        let entries = sides.entries();
        return Err(orientation_error(&entries, first, n_faces, &face_of_corner));
    }

    // 5. Each half-edge's face, next and previous: in half-edge order when the faces have
    // one degree (the corners around its corner are at known places), else face by face.
    // The sides' buffer, two `u32` a corner, is reused for `next` (`nh` is at most twice the
    // corners), every entry of which is written here or in step 6.
    halfedge_vertex.shrink_to_fit();
    let mut halfedge_face = corner_of;
    halfedge_face.shrink_to_fit();
    let nh = halfedge_vertex.len();
    let Sides { start, ends } = sides;
    let components = Components::count(start, n_used, &halfedge_vertex);
    let mut halfedge_next = ends.into_flattened();
    halfedge_next.truncate(nh);
    halfedge_next.shrink_to_fit();
    let mut halfedge_prev = vec![0u32; nh];
    let links = (&mut halfedge_face, &mut halfedge_next, &mut halfedge_prev);
    match uniform {
        Some(3) => link_uniform::<3>(&corner_halfedge, links),
        Some(4) => link_uniform::<4>(&corner_halfedge, links),
        _ => link_faces(&corner_halfedge, offsets, links),
    }
    // A vertex's half-edge is its last corner's (a boundary vertex's is replaced in step 6), a
    // face's its first corner's: written over `last` and `corner_halfedge` in place (entry
    // `i` is read from `i` or after).
    let mut vertex_halfedge = last;
    let mut w = 0;
    for v in 0..nv {
        if vertex_halfedge[v] != 0 {
            vertex_halfedge[w] = corner_halfedge[vertex_halfedge[v] as usize - 1];
            w += 1;
        }
    }
    vertex_halfedge.truncate(w);
    vertex_halfedge.shrink_to_fit();
    let mut face_halfedge = corner_halfedge;
    for (f, &o) in offsets[..n_faces].iter().enumerate() {
        face_halfedge[f] = face_halfedge[o];
    }
    face_halfedge.truncate(n_faces);
    face_halfedge.shrink_to_fit();

    // 6. Boundary loops: link each boundary half-edge to the boundary half-edge leaving its
    // target. A vertex with two outgoing boundary half-edges has two fans.
    let mut boundary_loops = 0;
    if !boundary.is_empty() {
        let from = |h: u32| halfedge_vertex[h as usize ^ 1] as usize;
        let mut out_boundary = vec![INVALID; n_used];
        let mut pinched: Option<u32> = None;
        for &h in &boundary {
            if out_boundary[from(h)] != INVALID {
                let v = from(h) as u32;
                pinched = Some(pinched.map_or(v, |p| p.min(v)));
            } else {
                out_boundary[from(h)] = h;
            }
        }
        if let Some(vertex) = pinched {
            return Err(non_manifold_vertex(old_number(vertex), n_faces, &face));
        }
        for &h in &boundary {
            let n = out_boundary[halfedge_vertex[h as usize] as usize];
            if n == INVALID {
                return Err(Error::BrokenInvariant {
                    what: format!("boundary half-edge {h} has no successor"),
                });
            }
            halfedge_next[h as usize] = n;
            halfedge_prev[n as usize] = h;
        }
        for (vh, &b) in vertex_halfedge.iter_mut().zip(&out_boundary) {
            if b != INVALID {
                *vh = b;
            }
        }
        // The cycles of `next` through the boundary, each boundary half-edge known by the
        // vertex it leaves.
        let mut seen = vec![false; n_used];
        for &h in &boundary {
            if !seen[from(h)] {
                boundary_loops += 1;
                let mut g = h;
                while !seen[from(g)] {
                    seen[from(g)] = true;
                    g = halfedge_next[g as usize];
                }
            }
        }
    }

    // 7. One fan per vertex: the rotation around each vertex must reach all its half-edges.
    // Every rotation is a cycle of the vertex's outgoing half-edges, so they all do exactly
    // when the rotations' lengths add up to the half-edges; otherwise the vertices are
    // walked again in order against their degrees, and the first one short of its degree
    // (or whose rotation does not close within it) is reported.
    let fan = |v: usize, most: usize| -> Result<usize> {
        let start = vertex_halfedge[v];
        let (mut h, mut count) = (start, 0);
        loop {
            count += 1;
            let p = halfedge_prev[h as usize];
            if p == INVALID || count > most {
                return Err(Error::BrokenInvariant {
                    what: format!("rotation around vertex {v} does not close"),
                });
            }
            h = p ^ 1;
            if h == start {
                return Ok(count);
            }
        }
    };
    let reached = (0..n_used).try_fold(0, |sum, v| fan(v, nh).map(|count| sum + count));
    if reached.ok() != Some(nh) {
        let mut out_degree = vec![0usize; n_used];
        for h in 0..nh {
            out_degree[halfedge_vertex[h ^ 1] as usize] += 1;
        }
        for (v, &degree) in out_degree.iter().enumerate() {
            if fan(v, degree)? < degree {
                return Err(non_manifold_vertex(old_number(v as u32), n_faces, &face));
            }
        }
    }

    let boundary_edges = boundary.len() as u64;
    let edges = (nh / 2) as u64;
    let chi = n_used as i128 - i128::from(edges) + n_faces as i128;
    let counts = MeshCounts {
        vertices: n_used as u64,
        edges,
        interior_edges: edges - boundary_edges,
        boundary_edges,
        nonmanifold_edges: 0,
        faces: n_faces as u64,
        corners: nh as u64 - boundary_edges,
        faces_by_degree: degrees.by_degree,
        boundary_loops,
        components: components as u64,
        euler_characteristic: i64::try_from(chi).unwrap_or(i64::MAX),
        unreferenced_vertices: unreferenced as u64,
    };
    let halfedges = [halfedge_vertex, halfedge_face, halfedge_next, halfedge_prev];
    let mut mesh =
        HalfEdgeMesh::from_raw_parts(new_positions, vertex_halfedge, halfedges, face_halfedge);
    mesh.unreferenced_vertices = unreferenced as u64;
    mesh.set_counts(counts);
    Ok(mesh)
}

/// The faces by degree, counted face by face in runs of one degree.
#[derive(Default)]
struct Degrees {
    by_degree: BTreeMap<u32, u64>,
    /// The degree of the last faces counted and how many there are not yet in `by_degree`.
    run: (u32, u64),
}

impl Degrees {
    fn add(&mut self, degree: usize) {
        let degree = degree as u32;
        if self.run.0 != degree {
            self.flush();
            self.run.0 = degree;
        }
        self.run.1 += 1;
    }

    fn flush(&mut self) {
        if self.run.1 > 0 {
            *self.by_degree.entry(self.run.0).or_insert(0) += self.run.1;
            self.run.1 = 0;
        }
    }

    /// Flushes the last run; the faces' one degree, if they have one.
    fn uniform(&mut self) -> Option<usize> {
        self.flush();
        match self.by_degree.len() {
            1 => self.by_degree.keys().next().map(|&k| k as usize),
            _ => None,
        }
    }
}

/// The components, joined edge by edge (a union-find whose roots are the least vertices
/// of their sets, with path halving).
struct Components {
    parent: Vec<u32>,
    merged: usize,
}

impl Components {
    /// The components of `n` vertices joined by the edges of `halfedge_vertex` (two entries
    /// an edge): the vertices less the joins that merged two. `buffer`'s memory (the sides'
    /// bucket starts, one more than the vertices) is reused for the union-find.
    fn count(mut buffer: Vec<u32>, n: usize, halfedge_vertex: &[u32]) -> usize {
        buffer.clear();
        buffer.extend(0..n as u32);
        let mut sets = Components {
            parent: buffer,
            merged: 0,
        };
        for edge in halfedge_vertex.chunks_exact(2) {
            sets.join(edge[0], edge[1]);
        }
        n - sets.merged
    }

    fn root(&mut self, mut x: u32) -> u32 {
        loop {
            let p = self.parent[x as usize];
            let grand = self.parent[p as usize];
            if grand == p {
                return p;
            }
            self.parent[x as usize] = grand;
            x = grand;
        }
    }

    fn join(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.parent[ra.max(rb) as usize] = ra.min(rb);
            self.merged += 1;
        }
    }
}

/// Buckets of up to this many sides are sorted by insertion.
const SORTED_BY_INSERTION: usize = 32;

/// Every corner's side `[larger vertex, tag]`, bucketed by its smaller vertex; a bucket is
/// sorted (by larger vertex, then tag) when the edge pass takes it. The buckets in order
/// are the order of one sort of `(undirected pair, tag)` over all sides, in linear time and
/// 8 bytes per side (a bucket holds a vertex's few edges).
struct Sides {
    /// Where each vertex's bucket starts in `ends` (and the last one ends).
    start: Vec<u32>,
    /// `[larger vertex, tag]`.
    ends: Vec<[u32; 2]>,
}

impl Sides {
    /// Counts the sides of a face by smaller vertex `v`, in `counted[v + 2]`.
    fn count(counted: &mut [u32], vertices: &[u32]) {
        let mut a = vertices[vertices.len() - 1];
        for &b in vertices {
            counted[a.min(b) as usize + 2] += 1;
            a = b;
        }
    }

    /// The sides of the faces `offsets`/`indices` (fewer than `2^31` corners, checked),
    /// counted by [`Sides::count`] into `counted` (two more entries than vertices).
    fn new(mut counted: Vec<u32>, offsets: &[usize], indices: &[u32]) -> Sides {
        // A counting sort: `counted[v + 1]` becomes where bucket v starts, then, as its
        // sides are placed, where it ends, which is where bucket v + 1 starts.
        for i in 2..counted.len() {
            counted[i] += counted[i - 1];
        }
        let mut ends = vec![[0u32; 2]; indices.len()];
        for w in offsets.windows(2) {
            let (start, end) = (w[0], w[1]);
            for c in start..end {
                let (a, b) = (
                    indices[c],
                    indices[if c + 1 == end { start } else { c + 1 }],
                );
                let slot = &mut counted[a.min(b) as usize + 1];
                ends[*slot as usize] = [a.max(b), (c as u32) << 1 | u32::from(a > b)];
                *slot += 1;
            }
        }
        counted.pop();
        Sides {
            start: counted,
            ends,
        }
    }

    /// The sides of the edges whose smaller vertex is `v`, sorted.
    fn bucket(&mut self, v: usize) -> &[[u32; 2]] {
        let bucket = &mut self.ends[self.start[v] as usize..self.start[v + 1] as usize];
        if bucket.len() > SORTED_BY_INSERTION {
            bucket.sort_unstable();
            return bucket;
        }
        // The tags were placed in increasing order: sorting by the larger vertex, stably,
        // sorts by both.
        for i in 1..bucket.len() {
            let side = bucket[i];
            let mut j = i;
            while j > 0 && bucket[j - 1][0] > side[0] {
                bucket[j] = bucket[j - 1];
                j -= 1;
            }
            bucket[j] = side;
        }
        bucket
    }

    /// The sides as `(key, tag)` in order, key `(smaller << 32) | larger` (for the
    /// orientation error, once every bucket is sorted).
    fn entries(&self) -> Vec<(u64, u32)> {
        let mut entries = Vec::with_capacity(self.ends.len());
        for (small, w) in self.start.windows(2).enumerate() {
            let bucket = &self.ends[w[0] as usize..w[1] as usize];
            let key = |large: u32| ((small as u64) << 32) | u64::from(large);
            entries.extend(bucket.iter().map(|&[large, tag]| (key(large), tag)));
        }
        entries
    }
}

/// Step 5 for faces of `K` corners each, in half-edge order: `face` holds each half-edge's
/// corner (`INVALID` on the boundary), replaced by its face; the corners before and after it
/// are in the same face, so their half-edges are read from one place.
fn link_uniform<const K: usize>(
    corner_halfedge: &[u32],
    (face, next, prev): (&mut Vec<u32>, &mut Vec<u32>, &mut Vec<u32>),
) {
    for ((f, n), p) in face.iter_mut().zip(next.iter_mut()).zip(prev.iter_mut()) {
        if *f == INVALID {
            (*n, *p) = (INVALID, INVALID);
            continue;
        }
        let c = *f as usize;
        let (of, i) = (c / K, c % K);
        *n = corner_halfedge[of * K + (i + 1) % K];
        *p = corner_halfedge[of * K + (i + K - 1) % K];
        *f = of as u32;
    }
}

/// Step 5 face by face (faces of several degrees): `face` and `next` of each face's
/// half-edges, and `prev` of the half-edges after them. The boundary half-edges are left to
/// step 6.
fn link_faces(
    corner_halfedge: &[u32],
    offsets: &[usize],
    (face, next, prev): (&mut Vec<u32>, &mut Vec<u32>, &mut Vec<u32>),
) {
    for (f, w) in offsets.windows(2).enumerate() {
        let (start, end) = (w[0], w[1]);
        for c in start..end {
            let h = corner_halfedge[c] as usize;
            let n = corner_halfedge[if c + 1 == end { start } else { c + 1 }];
            face[h] = f as u32;
            next[h] = n;
            prev[n as usize] = h as u32;
        }
    }
}

/// The larger vertex of the other side at the bucket's vertex of the quad of the side `tag`,
/// when that side is in `bucket` too (the vertex is smaller than both its neighbours in the
/// quad).
fn other_side(bucket: &[[u32; 2]], tag: u32) -> Option<u32> {
    const K: usize = 4;
    let c = (tag >> 1) as usize;
    let (base, i) = (c / K * K, c % K);
    // From the bucket's vertex (dir 0), the other side is the previous corner's, toward
    // it (dir 1); toward it, the next corner's, from it.
    let other = match tag & 1 {
        0 => 2 * (base + (i + K - 1) % K) + 1,
        _ => 2 * (base + (i + 1) % K),
    } as u32;
    bucket.iter().find(|&&[_, t]| t == other).map(|&[z, _]| z)
}

/// The first problems of the edges, in the order [`build`] reports them.
///
/// Duplicates are found across edges in a mesh of only triangles or only quads (without
/// repeated vertices): two faces on one vertex set share an edge at the set's smallest
/// vertex `m`, and each has two sides in `m`'s bucket (any two of a triangle's vertices make
/// an edge; two 4-cycles through the same 4 vertices share an edge at each vertex). So only
/// faces across an edge of a bucket where both have two sides can be duplicates, which the
/// bucket tells without reading the faces: two triangles are when they share two of the
/// bucket's edges; two quads are when `m` is the smallest vertex of both and their vertices
/// across from `m` (`far`, noted before the pass) and their other neighbours of `m` (in the
/// bucket) are the same two. An edge of three to eight sides, or of a bucket of more than
/// [`SCANNED_BUCKET`] sides, has its faces compared. Mixed or larger faces, or an edge of
/// more than 8 sides (a pile of copies), leave it to the search by sets (`by_sets`), which
/// finds the same smallest pair.
struct EdgeProblems<'a> {
    /// The faces' common degree, 3 or 4.
    degree: usize,
    indices: &'a [u32],
    by_sets: bool,
    duplicate: Option<(u32, u32)>,
    /// The first non-manifold edge: its key and its sides' tags.
    nonmanifold: Option<(u64, Vec<u32>)>,
    /// Where the first flipped edge's sides start, in the sorted order.
    flipped: Option<usize>,
    /// For quads, each face's vertex across from its smallest.
    far: Vec<u32>,
    /// The pairs of triangles across an edge of two sides, bucket by bucket, as
    /// `(first << 32) | second` (one 8-byte word: a store the sort's load can take over).
    pairs: Vec<u64>,
}

/// Buckets beyond this many sides have their quads compared across every edge of two sides
/// (rather than looking for their other sides in the bucket).
const SCANNED_BUCKET: usize = 32;

impl<'a> EdgeProblems<'a> {
    fn new(uniform: Option<usize>, indices: &'a [u32]) -> EdgeProblems<'a> {
        let degree = uniform.unwrap_or(0);
        let far = match degree {
            4 => indices
                .chunks_exact(4)
                .map(|q| {
                    let least = (1..4).fold(0, |i, j| if q[j] < q[i] { j } else { i });
                    q[(least + 2) % 4]
                })
                .collect(),
            _ => Vec::new(),
        };
        EdgeProblems {
            degree,
            indices,
            by_sets: !(degree == 3 || degree == 4),
            duplicate: None,
            nonmanifold: None,
            flipped: None,
            far,
            pairs: Vec::new(),
        }
    }

    /// The sides of the edges whose smaller vertex is `small`, sorted, starting at `at` in
    /// the sorted order.
    fn bucket(&mut self, small: u32, bucket: &[[u32; 2]], at: usize) {
        let mut at = at;
        for run in bucket.chunk_by(|x, y| x[0] == y[0]) {
            match run.len() {
                1 => {}
                2 => {
                    if run[0][1] & 1 == run[1][1] & 1 && self.flipped.is_none() {
                        self.flipped = Some(at);
                    }
                    if !self.by_sets {
                        self.across(small, bucket, run);
                    }
                }
                _ => {
                    if self.nonmanifold.is_none() {
                        let key = (u64::from(small) << 32) | u64::from(run[0][0]);
                        self.nonmanifold = Some((key, run.iter().map(|&[_, tag]| tag).collect()));
                    }
                    if run.len() > 8 {
                        self.by_sets = true;
                    }
                    if !self.by_sets {
                        for (i, a) in run.iter().enumerate() {
                            for b in &run[i + 1..] {
                                self.compare(self.face(a[1]), self.face(b[1]));
                            }
                        }
                    }
                }
            }
            at += run.len();
        }
        // Two triangles across two of the bucket's edges are on one vertex set.
        if self.pairs.len() > 1 {
            self.pairs.sort_unstable();
            let twice = self.pairs.windows(2).find(|w| w[0] == w[1]).map(|w| w[0]);
            if let Some(pair) = twice {
                self.found(((pair >> 32) as u32, pair as u32));
            }
        }
        self.pairs.clear();
    }

    /// The faces across an edge of two sides (`run`) of the bucket of vertex `small`.
    fn across(&mut self, small: u32, bucket: &[[u32; 2]], run: &[[u32; 2]]) {
        let (f, g) = (self.face(run[0][1]), self.face(run[1][1]));
        if self.degree == 3 {
            self.pairs
                .push(u64::from(f.min(g)) << 32 | u64::from(f.max(g)));
        } else if bucket.len() > SCANNED_BUCKET {
            self.compare(f, g);
        } else if let (Some(zf), Some(zg)) =
            (other_side(bucket, run[0][1]), other_side(bucket, run[1][1]))
        {
            // Quads through `small`, the edge's vertex and their other neighbours of `small`
            // (`zf`, `zg`): on one set when their vertices across from `small` complete it,
            // `small` being the smallest of both.
            let (of, og) = (self.far[f as usize], self.far[g as usize]);
            if of != small && og != small && ((zf, of) == (zg, og) || (zf, of) == (og, zg)) {
                self.found((f.min(g), f.max(g)));
            }
        }
    }

    fn face(&self, tag: u32) -> u32 {
        (tag >> 1) / self.degree as u32
    }

    /// Compares faces `f` and `g` by their vertex sets.
    fn compare(&mut self, f: u32, g: u32) {
        let k = self.degree;
        let corners = |f: u32| &self.indices[k * f as usize..k * f as usize + k];
        let sum = |f: u32| corners(f).iter().map(|&v| u64::from(v)).sum::<u64>();
        let set = |f: u32| {
            let mut s = [0u32; 4];
            s[..k].copy_from_slice(corners(f));
            s[..k].sort_unstable();
            s
        };
        if f != g && sum(f) == sum(g) && set(f) == set(g) {
            self.found((f.min(g), f.max(g)));
        }
    }

    fn found(&mut self, pair: (u32, u32)) {
        self.duplicate = Some(self.duplicate.map_or(pair, |p| p.min(pair)));
    }
}

/// Refuses faces on one vertex set ([`Error::DuplicateFace`], naming the smallest such pair):
/// the one duplicate-face check, of half-edge meshes and of the face-list subdividers alike.
pub(crate) fn check_duplicate_faces<'a>(
    n_faces: usize,
    face: &impl Fn(usize) -> &'a [u32],
) -> Result<()> {
    match crate::stats::duplicate_faces(n_faces, face).first_pair {
        Some((first, second)) => Err(Error::DuplicateFace {
            first,
            second,
            vertices: FaceVertices(face(first as usize).to_vec()),
        }),
        None => Ok(()),
    }
}

/// Tells a non-orientable surface from merely flipped faces: propagates a flip bit per face
/// over the edges shared by two faces; a contradiction means no choice of flips works.
fn orientation_error(
    entries: &[(u64, u32)],
    first_flipped: usize,
    n_faces: usize,
    face_of_corner: &impl Fn(u32) -> usize,
) -> Error {
    // Adjacency in CSR form: (other face, same direction, edge key).
    let mut pairs: Vec<(u32, u32, bool, u64)> = Vec::new();
    let mut i = 0;
    while i < entries.len() {
        let key = entries[i].0;
        if i + 1 < entries.len() && entries[i + 1].0 == key {
            let (t1, t2) = (entries[i].1, entries[i + 1].1);
            let (f1, f2) = (
                face_of_corner(t1 >> 1) as u32,
                face_of_corner(t2 >> 1) as u32,
            );
            pairs.push((f1, f2, t1 & 1 == t2 & 1, key));
            i += 2;
        } else {
            i += 1;
        }
    }
    let mut start = vec![0usize; n_faces + 1];
    for &(f1, f2, _, _) in &pairs {
        start[f1 as usize + 1] += 1;
        start[f2 as usize + 1] += 1;
    }
    for f in 0..n_faces {
        start[f + 1] += start[f];
    }
    let mut fill = start.clone();
    let mut adjacent = vec![(0u32, false, 0u64); start[n_faces]];
    for &(f1, f2, same, key) in &pairs {
        adjacent[fill[f1 as usize]] = (f2, same, key);
        fill[f1 as usize] += 1;
        adjacent[fill[f2 as usize]] = (f1, same, key);
        fill[f2 as usize] += 1;
    }
    const UNSET: u8 = 2;
    let mut flip = vec![UNSET; n_faces];
    let mut stack = Vec::new();
    for root in 0..n_faces {
        if flip[root] != UNSET {
            continue;
        }
        flip[root] = 0;
        stack.push(root);
        while let Some(f) = stack.pop() {
            for &(g, same, key) in &adjacent[start[f]..start[f + 1]] {
                let wanted = flip[f] ^ u8::from(same);
                if flip[g as usize] == UNSET {
                    flip[g as usize] = wanted;
                    stack.push(g as usize);
                } else if flip[g as usize] != wanted {
                    return Error::NonOrientable {
                        face: root as u32,
                        a: (key >> 32) as u32,
                        b: key as u32,
                    };
                }
            }
        }
    }
    let (key, t1) = entries[first_flipped];
    let t2 = entries[first_flipped + 1].1;
    let (min, max) = ((key >> 32) as u32, key as u32);
    let (a, b) = if t1 & 1 == 0 { (min, max) } else { (max, min) };
    let (f1, f2) = (
        face_of_corner(t1 >> 1) as u32,
        face_of_corner(t2 >> 1) as u32,
    );
    Error::InconsistentOrientation {
        a,
        b,
        first: f1.min(f2),
        second: f1.max(f2),
    }
}

/// The error for a vertex whose faces form several fans, counting the fans: faces around the
/// vertex are joined when they share an edge at it.
fn non_manifold_vertex<'a>(
    vertex: u32,
    n_faces: usize,
    face: &impl Fn(usize) -> &'a [u32],
) -> Error {
    // Corners at the vertex: (previous vertex, next vertex).
    let mut corners: Vec<(u32, u32)> = Vec::new();
    for f in 0..n_faces {
        let vertices = face(f);
        let k = vertices.len();
        for i in 0..k {
            if vertices[i] == vertex {
                corners.push((vertices[(i + k - 1) % k], vertices[(i + 1) % k]));
            }
        }
    }
    let mut fans = DisjointSets::new(corners.len());
    // Join corners through shared neighbour vertices (an edge at the vertex).
    let mut by_neighbour: Vec<(u32, u32)> = Vec::with_capacity(2 * corners.len());
    for (i, &(p, n)) in (0u32..).zip(&corners) {
        by_neighbour.push((p, i));
        by_neighbour.push((n, i));
    }
    by_neighbour.sort_unstable();
    for pair in by_neighbour.windows(2) {
        if pair[0].0 == pair[1].0 {
            fans.union(pair[0].1, pair[1].1);
        }
    }
    let fans = (0..corners.len() as u32)
        .filter(|&i| fans.find(i) == i)
        .count();
    Error::NonManifoldVertex { vertex, fans }
}

impl HalfEdgeMesh {
    /// Builds a mesh from vertex positions and polygons (0-based vertex indices, in
    /// counterclockwise order seen from outside), validating everything.
    ///
    /// Vertices no face uses are dropped (vertex ids are renumbered in order); their number
    /// is kept in [`HalfEdgeMesh::unreferenced_vertices`].
    ///
    /// # Errors
    ///
    /// The first problem found, in this order: [`Error::TooManyElements`], per face in order
    /// [`Error::FaceTooSmall`], [`Error::VertexOutOfRange`], [`Error::RepeatedVertex`]; then
    /// [`Error::NonFiniteCoordinate`] (used vertices only), [`Error::DuplicateFace`],
    /// [`Error::NonManifoldEdge`], [`Error::NonOrientable`] or
    /// [`Error::InconsistentOrientation`], [`Error::NonManifoldVertex`]. Vertex and face
    /// numbers in the errors are the input's indices.
    ///
    /// # Example
    ///
    /// ```
    /// use glam::DVec3;
    /// use halfedge::{Error, HalfEdgeMesh};
    ///
    /// let square = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    /// let mesh = HalfEdgeMesh::try_from_polygons(square.clone(), &[[0, 1, 2, 3]])?;
    /// assert_eq!((mesh.n_vertices(), mesh.n_edges(), mesh.n_faces()), (4, 4, 1));
    ///
    /// let err = HalfEdgeMesh::try_from_polygons(square, &[[0, 1, 2], [0, 2, 1]]).unwrap_err();
    /// assert!(matches!(err, Error::DuplicateFace { first: 0, second: 1, .. }));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn try_from_polygons<F: AsRef<[u32]>>(
        positions: Vec<DVec3>,
        faces: &[F],
    ) -> Result<HalfEdgeMesh> {
        let mut offsets = Vec::with_capacity(faces.len() + 1);
        offsets.push(0);
        let mut indices = Vec::new();
        for f in faces {
            indices.extend_from_slice(f.as_ref());
            offsets.push(indices.len());
        }
        build(&positions, &offsets, &indices)
    }

    /// Builds a mesh from a [`PolygonMesh`]'s positions and faces alone: unlike
    /// `HalfEdgeMesh::try_from(mesh)`, which also keeps the file's tags and UVs
    /// ([`HalfEdgeMesh::descriptor`]), the mesh carries nothing else (a caller that passes
    /// every option itself, as the `driver` crate does).
    ///
    /// # Errors
    ///
    /// As [`HalfEdgeMesh::try_from_polygons`].
    pub fn try_from_polygon_mesh(mesh: &PolygonMesh) -> Result<HalfEdgeMesh> {
        build(&mesh.positions, mesh.face_offsets(), mesh.face_indices())
    }

    /// The mesh as a face list (positions and faces in this mesh's numbering).
    pub fn to_polygon_mesh(&self) -> PolygonMesh {
        let mut out = PolygonMesh::with_positions(self.positions.clone());
        out.reserve_faces(self.n_faces(), self.n_halfedges());
        for f in self.faces() {
            out.push_face_from_iter(self.face_vertices(f).map(|v| v.0));
        }
        out
    }
}

impl Descriptor {
    /// What `source`'s tags and UVs say about `mesh`, the half-edge mesh built from it;
    /// `None` when they say nothing (no tag, no UVs).
    ///
    /// # Errors
    ///
    /// A crease [`crate::subdivide::Sharpness::from_tags_of`] cannot resolve on `mesh` (two vertices that share
    /// no edge: [`Error::CreaseNotAnEdge`]); a hole out of range ([`Error::HoleOutOfRange`]).
    pub fn of(source: &PolygonMesh, mesh: &HalfEdgeMesh) -> Result<Option<Descriptor>> {
        let tags = source.tags();
        let uvs = source.uv_layout();
        if !source.has_tags() && uvs.is_none() {
            return Ok(None);
        }
        let sharpness = if tags.creases().is_empty() && tags.corners().is_empty() {
            None
        } else {
            Some(crate::subdivide::Sharpness::from_tags_of(
                source, mesh, tags,
            )?)
            .filter(|s| !s.is_smooth())
        };
        let subdivision = tags
            .options
            .over(crate::tags::SubdivisionOptions::default());
        let faces = crate::holes::holes_of(source, tags, subdivision.boundary);
        let holes = match faces.is_empty() {
            true => None,
            false => Some(crate::holes::HoleSet::new(mesh.n_faces(), faces)?),
        };
        Ok(Some(Descriptor {
            sharpness,
            subdivision,
            holes,
            uvs,
        }))
    }
}

impl TryFrom<&PolygonMesh> for HalfEdgeMesh {
    type Error = Error;

    /// The mesh of [`HalfEdgeMesh::try_from_polygon_mesh`] carrying what `mesh`'s tags and
    /// UVs say ([`Descriptor::of`]), which its subdivisions honour by default.
    ///
    /// # Errors
    ///
    /// As [`HalfEdgeMesh::try_from_polygon_mesh`] and [`Descriptor::of`].
    fn try_from(mesh: &PolygonMesh) -> Result<HalfEdgeMesh> {
        let mut built = HalfEdgeMesh::try_from_polygon_mesh(mesh)?;
        built.set_descriptor(Descriptor::of(mesh, &built)?);
        Ok(built)
    }
}

impl TryFrom<PolygonMesh> for HalfEdgeMesh {
    type Error = Error;

    fn try_from(mesh: PolygonMesh) -> Result<HalfEdgeMesh> {
        HalfEdgeMesh::try_from(&mesh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(n: usize) -> Vec<DVec3> {
        (0..n)
            .map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0))
            .collect()
    }

    #[test]
    fn unreferenced_vertices_are_dropped_and_counted() {
        // Vertices 0 and 3 are unused; 1, 2, 4 become 0, 1, 2.
        let mesh = HalfEdgeMesh::try_from_polygons(points(6), &[[1, 2, 4]]).expect("valid");
        assert_eq!(mesh.n_vertices(), 3);
        assert_eq!(mesh.unreferenced_vertices(), 3);
        assert_eq!(
            mesh.positions(),
            &[points(6)[1], points(6)[2], points(6)[4]]
        );
        let face: Vec<u32> = mesh.face_vertices(crate::FaceId(0)).map(|v| v.0).collect();
        assert_eq!(face, [0, 1, 2]);
        assert_eq!(mesh.counts().unreferenced_vertices, 3);
    }

    #[test]
    fn the_counts_of_the_build_are_those_of_the_structure() {
        // Closed, with boundary and holes, mixed degrees, quads, unused vertices, two parts.
        let names = [
            "icosahedron",
            "grid:3x2",
            "mixed",
            "torus:2",
            "quad-grid:3x3",
        ];
        let mut meshes: Vec<PolygonMesh> = names
            .iter()
            .chain(&["icosahedron-holes:3", "cube"])
            .map(|name| crate::shapes::from_name(name).expect("shape"))
            .collect();
        let two = [[0u32, 1, 2], [3, 5, 4], [6, 7, 8], [6, 8, 9]];
        meshes.push(PolygonMesh::from_faces(points(11), two));
        for poly in &meshes {
            let mesh = HalfEdgeMesh::try_from(poly).expect("valid");
            assert_eq!(mesh.counts(), mesh.structure_counts(), "{poly:?}");
            assert_eq!(mesh.counts(), crate::stats::face_list_counts(poly));
        }
    }

    #[test]
    fn an_empty_face_list_is_an_empty_mesh() {
        let faces: [[u32; 3]; 0] = [];
        let mesh = HalfEdgeMesh::try_from_polygons(points(2), &faces).expect("valid");
        assert_eq!(
            (
                mesh.n_vertices(),
                mesh.n_faces(),
                mesh.unreferenced_vertices()
            ),
            (0, 0, 2)
        );
    }

    #[test]
    fn two_closed_fans_at_a_vertex_are_refused() {
        // Two tetrahedra sharing vertex 0 only: every edge has two faces, vertex 0 two fans.
        let tet = [[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let mut faces: Vec<[u32; 3]> = tet.to_vec();
        faces.extend(
            tet.iter()
                .map(|f| f.map(|v| if v == 0 { 0 } else { v + 3 })),
        );
        let err = HalfEdgeMesh::try_from_polygons(points(7), &faces).unwrap_err();
        assert_eq!(
            err.to_string(),
            "vertex 0 is non-manifold: its faces form 2 separate fans"
        );
    }

    #[test]
    fn face_errors_come_in_face_order() {
        let err =
            HalfEdgeMesh::try_from_polygons(points(4), &[vec![0, 1, 2], vec![0, 1]]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "face 1 (vertices 0, 1) has 2 vertices, at least 3 are needed"
        );
        let err = HalfEdgeMesh::try_from_polygons(points(4), &[vec![0, 1, 9], vec![0, 0, 1]])
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "face 0 (vertices 0, 1, 9) refers to vertex 9, but the mesh has 4 vertices"
        );
        let long: Vec<u32> = (0..12).chain([3]).collect();
        let err = HalfEdgeMesh::try_from_polygons(points(12), &[long]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "face 0 (vertices 0, 1, 2, 3, 4, 5, 6, 7, ... (13 vertices)) repeats vertex 3"
        );
    }

    #[test]
    fn duplicate_faces_with_other_vertex_orders_are_found() {
        // Pentagons 0 1 2 3 4 and 0 2 4 1 3 share no edge but have the same vertex set.
        let err = HalfEdgeMesh::try_from_polygons(points(5), &[[0, 1, 2, 3, 4], [0, 2, 4, 1, 3]])
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "faces 0 and 1 have the same vertices (0, 1, 2, 3, 4)"
        );
    }

    #[test]
    fn a_flipped_face_in_a_closed_mesh_is_inconsistent_not_non_orientable() {
        let tet = [[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [3, 0, 2]];
        let err = HalfEdgeMesh::try_from_polygons(points(4), &tet).unwrap_err();
        assert!(
            matches!(
                err,
                Error::InconsistentOrientation {
                    first: 0,
                    second: 3,
                    ..
                }
            ),
            "{err}"
        );
    }

    #[test]
    fn round_trip_through_a_polygon_mesh() {
        let faces = [vec![0u32, 1, 2, 3], vec![1, 4, 5, 2], vec![2, 5, 6]];
        let mesh = HalfEdgeMesh::try_from_polygons(points(7), &faces).expect("valid");
        let back = mesh.to_polygon_mesh();
        assert_eq!(back, PolygonMesh::from_faces(points(7), &faces));
        assert_eq!(HalfEdgeMesh::try_from(back).expect("valid").n_edges(), 9);
    }
}
