//! [`PolygonMesh`]: a raw face list, as read from a file, before any validation.

mod parts;

use std::collections::HashMap;

use glam::DVec3;

pub use self::parts::{PartsError, PolygonParts};

use crate::groups::{FaceGroups, GroupsError};
use crate::tags::{IgnoredTag, TagError, Tags};
use crate::uv::{PartialUvs, UvError, UvLayout, Uvs};

/// A polygon mesh as a plain face list: vertex positions and, per face, its vertex indices
/// (0-based) in order.
///
/// Nothing is validated: faces may repeat vertices, share edges between any number of faces,
/// refer to missing vertices or leave vertices unused. A mesh may carry
/// [`tags`](PolygonMesh::tags) (creases, corners, holes, subdivision options): the OBJ
/// reader fills them from OpenSubdiv's `t` lines, and [`PolygonMesh::set_tags`] sets them
/// (checked against the faces); [`PolygonMesh::into_parts`] and the writers leave them out. Statistics
/// ([`crate::stats::face_list_counts`]) work on any face list; [`crate::HalfEdgeMesh`] is built
/// from it with `HalfEdgeMesh::try_from(&polygon_mesh)`, which validates.
///
/// # Example
///
/// ```
/// use glam::DVec3;
/// use halfedge::{HalfEdgeMesh, PolygonMesh};
///
/// let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
/// let mesh = PolygonMesh::from_faces(positions, [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]);
/// assert_eq!(mesh.n_faces(), 4);
/// assert_eq!(mesh.face(1), &[0, 1, 3]);
/// let tetrahedron = HalfEdgeMesh::try_from(&mesh)?;
/// assert_eq!(tetrahedron.n_edges(), 6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct PolygonMesh {
    /// Vertex positions; face indices refer to this list.
    pub positions: Vec<DVec3>,
    /// `face_offsets[f]..face_offsets[f + 1]` is the range of face `f` in `face_indices`.
    face_offsets: Vec<usize>,
    face_indices: Vec<u32>,
    /// The file line of each face, for meshes read from a file (else empty).
    face_lines: Vec<u64>,
    /// Creases, corners, holes and options (OpenSubdiv's OBJ tags, or set in code).
    tags: Tags,
    /// The tags of the file that were not interpreted.
    ignored_tags: Vec<IgnoredTag>,
    /// Texture coordinates, when every face corner has one.
    uvs: Option<Uvs>,
    /// For a file where only some corners name a `vt`: how many.
    partial_uvs: Option<PartialUvs>,
    /// The file's materials, objects, groups and smoothing groups, per face.
    groups: Option<FaceGroups>,
    /// Vertex colors (`r g b`), one per vertex.
    colors: Option<Vec<[f64; 3]>>,
    /// For a file where only some vertices have a color: how many.
    partial_colors: Option<PartialColors>,
    /// The kinds of lines of the file no output carries, with their counts.
    uncarried: Vec<Uncarried>,
}

/// What a reader found about vertex colors: one per vertex, or how many vertices had one.
pub(crate) type ReadColors = (Option<Vec<[f64; 3]>>, Option<PartialColors>);

/// What of a file no output carries, by kind: OBJ's `vn`, `l`, `p` and other statements
/// (`what` is `l lines`), PLY's other elements and properties. Displayed as `12 l lines`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Uncarried {
    /// The kind, plural (`l lines`, `` `edge` elements ``; control characters escaped).
    pub what: String,
    /// How many.
    pub count: u64,
}

impl std::fmt::Display for Uncarried {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {}", self.count, self.what)
    }
}

/// Why a mesh read from a file has no vertex colors although some of its vertices have one:
/// how many do (a `v` line with 6 values, the others with 3 or 4; or other counts).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PartialColors {
    /// The vertices with a color.
    pub with_colors: usize,
    /// All vertices.
    pub vertices: usize,
}

impl std::fmt::Display for PartialColors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} of {} vertices have colors: no color channel",
            self.with_colors, self.vertices
        )
    }
}

/// Vertex colors that do not fit their mesh.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ColorError {
    /// Not one color per vertex.
    #[error("{given} vertex colors for a mesh with {expected} vertices")]
    Count {
        /// Colors given.
        given: usize,
        /// Vertices of the mesh.
        expected: usize,
    },
}

impl Default for PolygonMesh {
    fn default() -> Self {
        PolygonMesh {
            positions: Vec::new(),
            face_offsets: vec![0],
            face_indices: Vec::new(),
            face_lines: Vec::new(),
            tags: Tags::default(),
            ignored_tags: Vec::new(),
            uvs: None,
            partial_uvs: None,
            groups: None,
            colors: None,
            partial_colors: None,
            uncarried: Vec::new(),
        }
    }
}

/// Equal positions, faces, [`tags`](PolygonMesh::tags) (creases, corners, holes and
/// options change the surface), [`uvs`](PolygonMesh::uvs), [`groups`](PolygonMesh::groups)
/// and [`colors`](PolygonMesh::colors). Where the faces were read
/// from, which tags the reader ignored ([`PolygonMesh::ignored_tags`]) and why a file gave no
/// UVs ([`PolygonMesh::partial_uvs`]) do not matter.
impl PartialEq for PolygonMesh {
    fn eq(&self, other: &PolygonMesh) -> bool {
        self.positions == other.positions
            && self.face_offsets == other.face_offsets
            && self.face_indices == other.face_indices
            && self.tags == other.tags
            && self.uvs == other.uvs
            && self.groups == other.groups
            && self.colors == other.colors
    }
}

impl PolygonMesh {
    /// A mesh with the given positions and no faces.
    pub fn with_positions(positions: Vec<DVec3>) -> PolygonMesh {
        PolygonMesh {
            positions,
            ..PolygonMesh::default()
        }
    }

    /// A mesh from positions and faces (each face a list of 0-based vertex indices).
    pub fn from_faces<I, F>(positions: Vec<DVec3>, faces: I) -> PolygonMesh
    where
        I: IntoIterator<Item = F>,
        F: AsRef<[u32]>,
    {
        let mut mesh = PolygonMesh::with_positions(positions);
        for face in faces {
            mesh.push_face(face.as_ref());
        }
        mesh
    }

    /// A mesh from its arrays as [`face_offsets`](Self::face_offsets) and
    /// [`face_indices`](Self::face_indices) return them (the caller guarantees that the
    /// offsets start at 0, never decrease and end at `face_indices.len()`).
    pub(crate) fn from_raw_parts(
        positions: Vec<DVec3>,
        face_offsets: Vec<usize>,
        face_indices: Vec<u32>,
    ) -> PolygonMesh {
        debug_assert!(face_offsets.first() == Some(&0));
        debug_assert!(face_offsets.last() == Some(&face_indices.len()));
        PolygonMesh {
            positions,
            face_offsets,
            face_indices,
            ..PolygonMesh::default()
        }
    }

    /// The number of recorded file lines (0 for meshes not read from a file).
    pub(crate) fn face_lines_len(&self) -> usize {
        self.face_lines.len()
    }

    /// Reserves room for `faces` more faces with `corners` more corners in total.
    pub fn reserve_faces(&mut self, faces: usize, corners: usize) {
        self.face_offsets.reserve(faces);
        self.face_indices.reserve(corners);
    }

    /// As [`reserve_faces`](Self::reserve_faces), reporting a refused allocation instead of
    /// aborting (for the subdividers' large outputs).
    pub(crate) fn try_reserve_faces(
        &mut self,
        faces: usize,
        corners: usize,
    ) -> std::result::Result<(), std::collections::TryReserveError> {
        self.face_offsets.try_reserve_exact(faces)?;
        self.face_indices.try_reserve_exact(corners)
    }

    /// Appends a face (its vertex indices in order; not validated).
    ///
    /// The new face's corners have no texture coordinates, so a mesh with
    /// [`uvs`](Self::uvs) loses them (they become `None`): set them again for every corner
    /// with [`set_uvs`](Self::set_uvs) after the last face. The same holds for
    /// [`groups`](Self::groups) ([`set_groups`](Self::set_groups)).
    ///
    /// ```
    /// use halfedge::glam::{DVec2, DVec3};
    /// use halfedge::uv::Uvs;
    /// use halfedge::PolygonMesh;
    ///
    /// let mut mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 4], [vec![0, 1, 2]]);
    /// mesh.set_uvs(Some(Uvs::new(vec![DVec2::ZERO; 3], vec![0, 1, 2])?))?;
    /// mesh.push_face(&[0, 2, 3]);
    /// assert!(mesh.uvs().is_none());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn push_face(&mut self, vertices: &[u32]) {
        self.uvs = None;
        self.groups = None;
        self.face_indices.extend_from_slice(vertices);
        self.face_offsets.push(self.face_indices.len());
    }

    /// Appends a face from an iterator of vertex indices (not validated). As
    /// [`push_face`](Self::push_face), a mesh with [`uvs`](Self::uvs) loses them.
    pub fn push_face_from_iter(&mut self, vertices: impl IntoIterator<Item = u32>) {
        self.uvs = None;
        self.groups = None;
        self.face_indices.extend(vertices);
        self.face_offsets.push(self.face_indices.len());
    }

    /// Appends a face read from line `line` of a file (see [`PolygonMesh::face_line`]),
    /// reporting a refused allocation instead of aborting (the readers' lists grow with the
    /// file).
    pub(crate) fn try_push_face_from_line(
        &mut self,
        vertices: &[u32],
        line: u64,
    ) -> std::result::Result<(), std::collections::TryReserveError> {
        let faces = self.n_faces();
        self.face_lines
            .try_reserve((faces + 1).saturating_sub(self.face_lines.len()))?;
        self.face_offsets.try_reserve(1)?;
        self.face_indices.try_reserve(vertices.len())?;
        self.face_lines.resize(faces, 0);
        self.face_lines.push(line);
        self.push_face(vertices);
        Ok(())
    }

    /// The 1-based line of the file face `f` was read from, for meshes read by [`crate::io`]
    /// (`None` otherwise). Validation errors name faces by index (see [`crate::Error::face`]);
    /// this maps them back to the file.
    ///
    /// # Example
    ///
    /// ```
    /// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n# a comment\nf 1 2 3\nf 1 3 2\n";
    /// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "twice.obj")?;
    /// let err = halfedge::HalfEdgeMesh::try_from(&mesh).unwrap_err();
    /// assert_eq!(err.face(), Some(1));
    /// assert_eq!(mesh.face_line(1), Some(6));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn face_line(&self, f: usize) -> Option<u64> {
        self.face_lines.get(f).copied().filter(|&line| line > 0)
    }

    /// The creases, corners, holes and options of the mesh: what an OBJ file's `t` lines say
    /// (see [`crate::io`]), or what [`set_tags`](Self::set_tags) set; empty otherwise.
    ///
    /// ```
    /// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nt crease 2/1/0 0 1 10\nt vertexedit 0/0/1 x\n";
    /// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "tagged.obj")?;
    /// assert_eq!(mesh.tags().sharp_edges().len(), 1);
    /// assert_eq!(mesh.ignored_tags()[0].name, "vertexedit");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn tags(&self) -> &Tags {
        &self.tags
    }

    /// Sets the tags, checked against the faces the mesh has now ([`Tags::check_against`]).
    ///
    /// # Errors
    ///
    /// The first crease, corner or hole that names a vertex, face or edge the mesh does not
    /// have; the tags are then left as they were.
    ///
    /// ```
    /// use halfedge::{shapes, tags::Tags};
    /// let mut cube = shapes::cube();
    /// let mut tags = Tags::default();
    /// tags.add_hole(5);
    /// cube.set_tags(tags)?;
    /// assert_eq!(cube.tags().hole_faces(), [5]);
    /// let mut beyond = Tags::default();
    /// beyond.add_hole(6);
    /// assert!(cube.set_tags(beyond).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_tags(&mut self, tags: Tags) -> Result<(), TagError> {
        tags.check_against(self)?;
        self.tags = tags;
        Ok(())
    }

    /// Sets tags the reader has checked, and the tags it ignored.
    pub(crate) fn set_read_tags(&mut self, tags: Tags, ignored: Vec<IgnoredTag>) {
        self.tags = tags;
        self.ignored_tags = ignored;
    }

    /// The tags of the file that the reader did not interpret (`vertexedit`, ...), each
    /// name once with its number of lines, sorted by name; empty for meshes not read from a
    /// file or read without tags.
    pub fn ignored_tags(&self) -> &[IgnoredTag] {
        &self.ignored_tags
    }

    /// Whether the mesh has tags: interpreted ([`tags`](Self::tags) not empty) or ignored.
    pub fn has_tags(&self) -> bool {
        !self.tags.is_empty() || !self.ignored_tags.is_empty()
    }

    /// The texture coordinates ([`crate::uv`]): a `vt` per face corner, when the file gave one
    /// to every corner or [`set_uvs`](Self::set_uvs) set them; `None` otherwise (see
    /// [`partial_uvs`](Self::partial_uvs) for a file where only some corners have one).
    ///
    /// ```
    /// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 9 9\nf 1/1 2/2 3/-2\n";
    /// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "uv.obj")?;
    /// let uvs = mesh.uvs().expect("every corner has a vt");
    /// assert_eq!(uvs.corners(), [0, 1, 2]);
    /// assert_eq!((uvs.coords().len(), uvs.unreferenced()), (4, 1));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn uvs(&self) -> Option<&Uvs> {
        self.uvs.as_ref()
    }

    /// Why the mesh has no [`uvs`](Self::uvs) although its file names texture coordinates:
    /// `Some` when only some of its face corners have a `vt` ([`PartialUvs`]: how many of
    /// how many); `None` when every corner has one (the mesh has UVs), when none has one, and
    /// for meshes not read from an OBJ file or whose UVs were [set](Self::set_uvs).
    pub fn partial_uvs(&self) -> Option<PartialUvs> {
        self.partial_uvs
    }

    /// The reader's texture coordinates (one `vt` per corner, checked by the reader) or the
    /// record of a file where only some corners have one.
    pub(crate) fn set_read_uvs(&mut self, uvs: Option<Uvs>, partial: Option<PartialUvs>) {
        debug_assert!(uvs
            .as_ref()
            .map_or(true, |u| u.corners().len() == self.n_corners()));
        debug_assert!(uvs.is_none() || partial.is_none());
        self.uvs = uvs;
        self.partial_uvs = partial;
    }

    /// Sets (or, with `None`, removes) the texture coordinates, checked against the faces the
    /// mesh has now: one `vt` per face corner. On success the reader's record of partial
    /// texture coordinates ([`partial_uvs`](Self::partial_uvs)) is cleared.
    ///
    /// # Errors
    ///
    /// [`UvError::CornerCount`] when the corners differ in number from the mesh's; the
    /// texture coordinates are then left as they were.
    pub fn set_uvs(&mut self, uvs: Option<Uvs>) -> Result<(), UvError> {
        if let Some(u) = &uvs {
            if u.corners().len() != self.n_corners() {
                return Err(UvError::CornerCount {
                    given: u.corners().len(),
                    expected: self.n_corners(),
                });
            }
        }
        self.uvs = uvs;
        self.partial_uvs = None;
        Ok(())
    }

    /// The file's materials, objects, groups and smoothing groups per face
    /// ([`crate::groups`]), `None` when it has none (or for a mesh not read from OBJ).
    pub fn groups(&self) -> Option<&FaceGroups> {
        self.groups.as_ref()
    }

    /// Sets (or, with `None`, removes) the per-face groups.
    ///
    /// # Errors
    ///
    /// [`GroupsError::FaceCount`] when the groups have another number of faces.
    pub fn set_groups(&mut self, groups: Option<FaceGroups>) -> Result<(), GroupsError> {
        let expected = self.n_faces();
        match groups.as_ref().map(FaceGroups::n_faces) {
            Some(given) if given != expected => Err(GroupsError::FaceCount { given, expected }),
            _ => {
                self.groups = groups;
                Ok(())
            }
        }
    }

    /// The vertex colors (`r g b` per vertex, as the file writes them: no scaling, never
    /// clamped), when every vertex has one; `None` otherwise (see
    /// [`partial_colors`](Self::partial_colors)).
    ///
    /// ```
    /// let text = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
    /// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "rgb.obj")?;
    /// assert_eq!(mesh.colors().expect("every v has r g b")[1], [0.0, 1.0, 0.0]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn colors(&self) -> Option<&[[f64; 3]]> {
        self.colors.as_deref()
    }

    /// The colors of the vertices some face uses, in order: one per vertex of the half-edge
    /// mesh built from this one (which drops the others); `None` without colors.
    pub fn colors_of_referenced(&self) -> Option<Vec<[f64; 3]>> {
        let colors = self.colors()?;
        let kept = self.referenced_vertices().into_iter();
        Some(kept.map(|v| colors[v as usize]).collect())
    }

    /// The vertices some face uses, in order: vertex `i` of the half-edge mesh built from
    /// this one (which drops the others) is vertex `referenced_vertices()[i]` of this one.
    pub fn referenced_vertices(&self) -> Vec<u32> {
        let mut used = vec![false; self.n_vertices()];
        for &v in &self.face_indices {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
        (0..used.len() as u32)
            .filter(|&v| used[v as usize])
            .collect()
    }

    /// Why the mesh has no [`colors`](Self::colors) although some vertices of its file have
    /// one: how many do ([`PartialColors`]).
    pub fn partial_colors(&self) -> Option<PartialColors> {
        self.partial_colors
    }

    /// Sets (or, with `None`, removes) the vertex colors, one per vertex; clears the
    /// reader's [`partial_colors`](Self::partial_colors).
    ///
    /// # Errors
    ///
    /// [`ColorError::Count`] when the colors are not one per vertex.
    pub fn set_colors(&mut self, colors: Option<Vec<[f64; 3]>>) -> Result<(), ColorError> {
        if let Some(c) = &colors {
            if c.len() != self.n_vertices() {
                return Err(ColorError::Count {
                    given: c.len(),
                    expected: self.n_vertices(),
                });
            }
        }
        self.colors = colors;
        self.partial_colors = None;
        Ok(())
    }

    /// Sets what a reader found: colors (one per vertex) or the record of partial ones,
    /// groups (one class per face) and the lines it did not carry.
    pub(crate) fn set_read_extras(
        &mut self,
        colors: ReadColors,
        groups: Option<FaceGroups>,
        uncarried: Vec<Uncarried>,
    ) {
        debug_assert!(colors
            .0
            .as_ref()
            .map_or(true, |c| c.len() == self.n_vertices()));
        debug_assert!(groups
            .as_ref()
            .map_or(true, |g| g.n_faces() == self.n_faces()));
        (self.colors, self.partial_colors) = colors;
        self.groups = groups;
        self.uncarried = uncarried;
    }

    /// What of the file no output carries (OBJ's `vn`, `l`, `p` and statements it does not
    /// read; PLY's other elements and properties), each kind with its count, sorted.
    pub fn uncarried(&self) -> &[Uncarried] {
        &self.uncarried
    }

    /// The UV layout of the mesh ([`UvLayout`]), when it has texture coordinates.
    pub fn uv_layout(&self) -> Option<UvLayout> {
        self.uvs
            .as_ref()
            .map(|u| UvLayout::new(&self.face_indices, u))
    }

    /// Number of vertex positions (used or not).
    pub fn n_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.face_offsets.len() - 1
    }

    /// Number of face corners (the sum of the face degrees).
    pub fn n_corners(&self) -> usize {
        self.face_indices.len()
    }

    /// The vertex indices of face `f`.
    ///
    /// # Panics
    ///
    /// When `f >= self.n_faces()`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_indices[self.face_offsets[f]..self.face_offsets[f + 1]]
    }

    /// Iterator over the faces, each as its vertex indices.
    pub fn faces(&self) -> PolygonFaces<'_> {
        PolygonFaces {
            mesh: self,
            next: 0,
        }
    }

    /// All face corners, face after face (see [`PolygonMesh::face_offsets`]).
    pub fn face_indices(&self) -> &[u32] {
        &self.face_indices
    }

    /// Face boundaries in [`PolygonMesh::face_indices`]: face `f` is
    /// `face_offsets()[f]..face_offsets()[f + 1]`; the slice has `n_faces() + 1` entries and
    /// starts with 0.
    pub fn face_offsets(&self) -> &[usize] {
        &self.face_offsets
    }

    /// The mesh's arrays, without a copy: `(positions, face_offsets, face_indices)` as
    /// [`PolygonMesh::face_offsets`] and [`PolygonMesh::face_indices`] describe them (e.g. to
    /// hand a subdivided level to a renderer).
    ///
    /// ```
    /// use halfedge::{shapes, PolygonMesh};
    /// let (positions, offsets, indices) = shapes::cube().into_parts();
    /// assert_eq!((positions.len(), offsets.len(), indices.len()), (8, 7, 24));
    /// ```
    pub fn into_parts(self) -> (Vec<DVec3>, Vec<usize>, Vec<u32>) {
        (self.positions, self.face_offsets, self.face_indices)
    }
}

/// Iterator over the faces of a [`PolygonMesh`]; see [`PolygonMesh::faces`].
#[derive(Clone, Debug)]
pub struct PolygonFaces<'a> {
    mesh: &'a PolygonMesh,
    next: usize,
}

impl<'a> Iterator for PolygonFaces<'a> {
    type Item = &'a [u32];

    fn next(&mut self) -> Option<&'a [u32]> {
        if self.next >= self.mesh.n_faces() {
            return None;
        }
        let face = self.mesh.face(self.next);
        self.next += 1;
        Some(face)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.mesh.n_faces() - self.next;
        (left, Some(left))
    }
}

impl ExactSizeIterator for PolygonFaces<'_> {}

// In this module rather than `tags.rs`, so that `tags` does not import `polygon` (which holds
// a mesh's `Tags`): the tags are checked against the face list they describe.
impl Tags {
    /// Checks the tags against a mesh: every crease and corner vertex exists, every hole
    /// face exists, and every crease joins the two ends of a side of some face (in either
    /// direction; a side from a vertex to itself, as in a face that repeats a vertex, joins
    /// nothing).
    ///
    /// # Errors
    ///
    /// The first problem as a [`TagError`] naming the entry (its position in
    /// [`creases`](Self::creases), [`corners`](Self::corners) or [`holes`](Self::holes)):
    /// creases are checked first, then corners, then holes.
    ///
    /// ```
    /// use halfedge::{shapes, tags::{TagError, Tags}};
    ///
    /// let cube = shapes::cube();
    /// let mut tags = Tags::default();
    /// tags.add_crease(0, 1, 10.0)?;
    /// assert_eq!(tags.check_against(&cube), Ok(()));
    /// tags.add_crease(0, 6, 1.0)?; // a diagonal: no face has the side (0, 6)
    /// assert_eq!(tags.check_against(&cube), Err(TagError::NotAnEdge { entry: 1, a: 0, b: 6 }));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn check_against(&self, mesh: &PolygonMesh) -> Result<(), TagError> {
        let vertices = mesh.n_vertices();
        let in_range = |v: u32| (v as usize) < vertices;
        for (entry, c) in self.creases().iter().enumerate() {
            if let Some(vertex) = [c.a, c.b].into_iter().find(|&v| !in_range(v)) {
                return Err(TagError::VertexOutOfRange {
                    tag: "crease",
                    entry,
                    vertex,
                    vertices,
                });
            }
        }
        if !self.creases().is_empty() {
            // Each wanted edge once, with its first entry; the sides of the faces mark them.
            // A side from a vertex to itself (a face repeating a vertex, `f 1 2 2`) is no
            // edge: a crease `v v` is refused even on such a face.
            let mut wanted: HashMap<(u32, u32), (usize, bool)> = HashMap::new();
            for (entry, c) in self.creases().iter().enumerate() {
                wanted
                    .entry((c.a.min(c.b), c.a.max(c.b)))
                    .or_insert((entry, false));
            }
            for face in mesh.faces() {
                for (i, &a) in face.iter().enumerate() {
                    let b = face[(i + 1) % face.len()];
                    if a == b {
                        continue;
                    }
                    if let Some(found) = wanted.get_mut(&(a.min(b), a.max(b))) {
                        found.1 = true;
                    }
                }
            }
            if let Some(&entry) = wanted
                .values()
                .filter(|(_, found)| !found)
                .map(|(entry, _)| entry)
                .min()
            {
                let c = self.creases()[entry];
                return Err(TagError::NotAnEdge {
                    entry,
                    a: c.a,
                    b: c.b,
                });
            }
        }
        for (entry, c) in self.corners().iter().enumerate() {
            if !in_range(c.vertex) {
                return Err(TagError::VertexOutOfRange {
                    tag: "corner",
                    entry,
                    vertex: c.vertex,
                    vertices,
                });
            }
        }
        let faces = mesh.n_faces();
        for (entry, &face) in self.holes().iter().enumerate() {
            if face as usize >= faces {
                return Err(TagError::FaceOutOfRange { entry, face, faces });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pushing_a_face_clears_the_texture_coordinates() {
        use glam::DVec2;
        let mut mesh = PolygonMesh::from_faces(vec![DVec3::ZERO; 4], [vec![0, 1, 2]]);
        let uvs = Uvs::new(vec![DVec2::ZERO; 3], vec![0, 1, 2]).unwrap();
        mesh.set_uvs(Some(uvs)).unwrap();
        mesh.push_face(&[0, 2, 3]);
        assert_eq!(mesh.uvs(), None);
        assert!(mesh.uv_layout().is_none());
        // Set again for every corner, then a face pushed from an iterator.
        let six = Uvs::new(vec![DVec2::ZERO; 3], vec![0, 1, 2, 0, 2, 1]).unwrap();
        mesh.set_uvs(Some(six)).unwrap();
        assert!(mesh.uvs().is_some());
        mesh.push_face_from_iter([1, 2, 3]);
        assert_eq!(mesh.uvs(), None);
        // The OBJ writer writes no `vt` rather than a file short of corners.
        let mut out = Vec::new();
        crate::io::write_polygon_obj(&mesh, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(!text.contains("vt"), "{text}");
        assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 3);
    }
}
