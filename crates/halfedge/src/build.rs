//! Validating construction of a [`HalfEdgeMesh`] from a face list.
//!
//! Edges are matched by sorting the face corners by their undirected vertex pair (one
//! `sort_unstable` over `(u64, u32)` pairs), which is fast, uses no hashing and makes every
//! numbering and every reported error deterministic. Checks run in a fixed order and the first
//! problem found is reported: face sizes, indices and repeated vertices (face by face),
//! non-finite coordinates, faces on the same vertex set, non-manifold edges, orientation
//! (a flipped face or a non-orientable surface), non-manifold vertices.

use glam::DVec3;
use schemes::DisjointSets;

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

    // 1. Face by face: size, range, repeated vertices. `mark[v]` = last face using v.
    let mut mark = vec![INVALID; nv];
    for f in 0..n_faces {
        let vertices = face(f);
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
        for &v in vertices {
            if mark[v as usize] == f as u32 {
                return Err(Error::RepeatedVertex {
                    face: f as u32,
                    vertices: describe(),
                    vertex: v,
                });
            }
            mark[v as usize] = f as u32;
        }
    }

    // 2. Referenced vertices, renumbered in order; non-finite coordinates.
    let mut remap = vec![INVALID; nv];
    let mut old_of_new: Vec<u32> = Vec::with_capacity(nv);
    let mut new_positions = Vec::with_capacity(nv);
    for (v, (&m, &p)) in mark.iter().zip(positions).enumerate() {
        if m == INVALID {
            continue;
        }
        if !p.is_finite() {
            return Err(Error::NonFiniteCoordinate {
                vertex: v as u32,
                x: p.x,
                y: p.y,
                z: p.z,
            });
        }
        remap[v] = old_of_new.len() as u32;
        old_of_new.push(v as u32);
        new_positions.push(p);
    }
    drop(mark);
    let unreferenced = (nv - old_of_new.len()) as u64;

    // 3. The corners' sides in the order of their undirected vertex pair, then tag
    // ([`Sides`]). The tag is `2 * corner + dir`, with dir = 1 when the corner's edge runs
    // from the larger vertex to the smaller.
    let sides = Sides::new(nv, offsets, indices);

    // 4. One pass over the edges, numbered in sorted order: half-edge 2e runs from the
    // smaller vertex to the larger one, 2e + 1 back, and each corner takes the one of its
    // direction. The pass also notes the first of each problem, reported in the documented
    // order after it: faces on one vertex set (compared across the edges they share, or
    // searched by their sets), a non-manifold edge, a flipped one.
    let mut found = EdgeProblems::new(offsets);
    let mut halfedge_vertex: Vec<u32> = Vec::with_capacity(2 * n_corners);
    let mut corner_halfedge = vec![0u32; n_corners];
    let mut at = 0;
    for (key, run) in sides.edges() {
        let e = (halfedge_vertex.len() / 2) as u32;
        halfedge_vertex.push(remap[(key as u32) as usize]);
        halfedge_vertex.push(remap[(key >> 32) as usize]);
        for &(_, tag) in run {
            corner_halfedge[(tag >> 1) as usize] = 2 * e + (tag & 1);
        }
        if run.len() > 1 {
            found.edge(key, run, at, indices);
        }
        at += run.len();
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
    drop(sides);
    halfedge_vertex.shrink_to_fit();
    let nh = halfedge_vertex.len();
    let mut halfedge_face = vec![INVALID; nh];
    let mut halfedge_next = vec![INVALID; nh];
    let mut halfedge_prev = vec![INVALID; nh];
    let mut vertex_halfedge = vec![INVALID; old_of_new.len()];
    let mut face_halfedge = Vec::with_capacity(n_faces);
    for f in 0..n_faces {
        let (start, end) = (offsets[f], offsets[f + 1]);
        face_halfedge.push(corner_halfedge[start]);
        for c in start..end {
            let h = corner_halfedge[c] as usize;
            let n = corner_halfedge[if c + 1 == end { start } else { c + 1 }];
            halfedge_face[h] = f as u32;
            halfedge_next[h] = n;
            halfedge_prev[n as usize] = h as u32;
            vertex_halfedge[remap[indices[c] as usize] as usize] = h as u32;
        }
    }
    drop(corner_halfedge);

    // 6. Boundary loops: link each boundary half-edge to the boundary half-edge leaving its
    // target. A vertex with two outgoing boundary half-edges has two fans.
    let mut out_boundary = vec![INVALID; old_of_new.len()];
    let mut pinched: Option<u32> = None;
    for h in 0..nh {
        if halfedge_face[h] != INVALID {
            continue;
        }
        let from = halfedge_vertex[h ^ 1] as usize;
        if out_boundary[from] != INVALID {
            let old = old_of_new[from];
            pinched = Some(pinched.map_or(old, |p| p.min(old)));
        } else {
            out_boundary[from] = h as u32;
        }
    }
    if let Some(vertex) = pinched {
        return Err(non_manifold_vertex(vertex, n_faces, &face));
    }
    for h in 0..nh {
        if halfedge_face[h] != INVALID {
            continue;
        }
        let n = out_boundary[halfedge_vertex[h] as usize];
        if n == INVALID {
            return Err(Error::BrokenInvariant {
                what: format!("boundary half-edge {h} has no successor"),
            });
        }
        halfedge_next[h] = n;
        halfedge_prev[n as usize] = h as u32;
    }
    for (vh, &b) in vertex_halfedge.iter_mut().zip(&out_boundary) {
        if b != INVALID {
            *vh = b;
        }
    }
    drop(out_boundary);

    // 7. One fan per vertex: the rotation around each vertex must reach all its half-edges.
    let mut out_degree = vec![0u32; old_of_new.len()];
    for h in 0..nh {
        out_degree[halfedge_vertex[h ^ 1] as usize] += 1;
    }
    for (v, (&start, &degree)) in vertex_halfedge.iter().zip(&out_degree).enumerate() {
        let mut h = start;
        let mut count = 0u32;
        loop {
            count += 1;
            let p = halfedge_prev[h as usize];
            if p == INVALID || count > degree {
                return Err(Error::BrokenInvariant {
                    what: format!("rotation around vertex {v} does not close"),
                });
            }
            h = p ^ 1;
            if h == start {
                break;
            }
        }
        if count < degree {
            return Err(non_manifold_vertex(old_of_new[v], n_faces, &face));
        }
    }

    let halfedges = [halfedge_vertex, halfedge_face, halfedge_next, halfedge_prev];
    let mut mesh =
        HalfEdgeMesh::from_raw_parts(new_positions, vertex_halfedge, halfedges, face_halfedge);
    mesh.unreferenced_vertices = unreferenced;
    Ok(mesh)
}

/// Every corner's side, bucketed by its smaller vertex and sorted within the bucket by
/// (larger vertex, tag): the order of one sort of `(undirected pair, tag)` over all sides,
/// in linear time and 8 bytes per side (a bucket holds a vertex's few edges).
struct Sides {
    /// Where each vertex's bucket starts in `ends`.
    start: Vec<u32>,
    /// `(larger vertex, tag)`.
    ends: Vec<(u32, u32)>,
}

impl Sides {
    /// `offsets`/`indices` index `nv` vertices with fewer than `2^31` corners (checked).
    fn new(nv: usize, offsets: &[usize], indices: &[u32]) -> Sides {
        let n_faces = offsets.len().saturating_sub(1);
        let side = |f: usize, c: usize| {
            let (start, end) = (offsets[f], offsets[f + 1]);
            let (a, b) = (
                indices[c],
                indices[if c + 1 == end { start } else { c + 1 }],
            );
            (a.min(b), a.max(b), (c as u32) << 1 | u32::from(a > b))
        };
        let mut start = vec![0u32; nv + 1];
        for f in 0..n_faces {
            for c in offsets[f]..offsets[f + 1] {
                start[side(f, c).0 as usize + 1] += 1;
            }
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut ends = vec![(0u32, 0u32); indices.len()];
        for f in 0..n_faces {
            for c in offsets[f]..offsets[f + 1] {
                let (small, large, tag) = side(f, c);
                let slot = &mut fill[small as usize];
                ends[*slot as usize] = (large, tag);
                *slot += 1;
            }
        }
        drop(fill);
        for v in 0..nv {
            ends[start[v] as usize..start[v + 1] as usize].sort_unstable();
        }
        Sides { start, ends }
    }

    /// Each edge's key `(smaller << 32) | larger` and sides, in sorted order.
    fn edges(&self) -> impl Iterator<Item = (u64, &[(u32, u32)])> {
        self.start.windows(2).enumerate().flat_map(|(a, w)| {
            self.ends[w[0] as usize..w[1] as usize]
                .chunk_by(|x, y| x.0 == y.0)
                .map(move |run| (((a as u64) << 32) | u64::from(run[0].0), run))
        })
    }

    /// The sides as `(key, tag)` in order (for the orientation error).
    fn entries(&self) -> Vec<(u64, u32)> {
        self.edges()
            .flat_map(|(key, run)| run.iter().map(move |&(_, tag)| (key, tag)))
            .collect()
    }
}

/// The first problems of the edges, in the order [`build`] reports them.
///
/// Duplicates are found across edges in a mesh of only triangles or only quads (without
/// repeated vertices): two faces on one vertex set share an edge there (any two of a
/// triangle's vertices make an edge; two 4-cycles through the same 4 vertices share two
/// edges), so only faces across an edge are compared, and the smallest such pair is the
/// smallest pair of the search by sets. Mixed or larger faces, or an edge of more than 8
/// sides (a pile of copies), leave it to that search (`by_sets`).
struct EdgeProblems {
    /// The faces' common degree, 3 or 4.
    degree: usize,
    by_sets: bool,
    duplicate: Option<(u32, u32)>,
    /// The first non-manifold edge: its key and its sides' tags.
    nonmanifold: Option<(u64, Vec<u32>)>,
    /// Where the first flipped edge's sides start, in the sorted order.
    flipped: Option<usize>,
}

impl EdgeProblems {
    fn new(offsets: &[usize]) -> EdgeProblems {
        let degree = offsets.get(1).copied().unwrap_or(0);
        let uniform = offsets.windows(2).all(|w| w[1] - w[0] == degree);
        EdgeProblems {
            degree,
            by_sets: !(uniform && (degree == 3 || degree == 4)),
            duplicate: None,
            nonmanifold: None,
            flipped: None,
        }
    }

    /// An edge of `run.len() >= 2` sides whose sides start at `at`.
    fn edge(&mut self, key: u64, run: &[(u32, u32)], at: usize, indices: &[u32]) {
        if run.len() == 2 {
            if run[0].1 & 1 == run[1].1 & 1 && self.flipped.is_none() {
                self.flipped = Some(at);
            }
        } else if self.nonmanifold.is_none() {
            self.nonmanifold = Some((key, run.iter().map(|&(_, tag)| tag).collect()));
        }
        if self.by_sets {
            return;
        }
        if run.len() > 8 {
            self.by_sets = true;
            return;
        }
        let k = self.degree;
        let corners = |f: usize| &indices[k * f..k * f + k];
        let sum = |f: usize| corners(f).iter().map(|&v| u64::from(v)).sum::<u64>();
        let set = |f: usize| {
            let mut s = [0u32; 4];
            s[..k].copy_from_slice(corners(f));
            s[..k].sort_unstable();
            s
        };
        for (i, a) in run.iter().enumerate() {
            for b in &run[i + 1..] {
                let (f, g) = ((a.1 >> 1) as usize / k, (b.1 >> 1) as usize / k);
                if f != g && sum(f) == sum(g) && set(f) == set(g) {
                    let pair = (f.min(g) as u32, f.max(g) as u32);
                    self.duplicate = Some(self.duplicate.map_or(pair, |p| p.min(pair)));
                }
            }
        }
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
