//! What the writers take: their options ([`ObjWriteOptions`]) and caller-owned buffers, faces
//! ([`FaceBuffers`]), UV values and indices ([`UvBuffers`]), a whole mesh ([`MeshBuffers`]),
//! checked once for every writer.

use glam::DVec3;

use crate::groups::FaceGroups;
use crate::{normals, Scalar};

/// What the OBJ writers write besides positions and faces.
///
/// With [`uvs`](Self::uvs) (the default), a mesh with texture coordinates
/// ([`PolygonMesh::uvs`](crate::PolygonMesh::uvs), or [`UvBuffers`]) gets its `vt` lines, each value once, and faces
/// `f v/vt`; a mesh without them is written as without this option. With
/// [`normals`](Self::normals) (off by default), the writer computes area-weighted vertex
/// normals of the faces written ([`crate::normals::vertex_normals`]; the limit surface's
/// normals, [`crate::normals::limit_normal`], for a [`MeshBuffers`] with
/// [`tangents`](MeshBuffers::tangents)) and writes one `vn` per
/// vertex, after the `vt` lines, and faces `f v/vt/vn` (or `f v//vn` without texture
/// coordinates), the `vn` index being the vertex's.
///
/// ```
/// use halfedge::io::ObjWriteOptions;
/// let options = ObjWriteOptions::default();
/// assert!(options.uvs && !options.normals);
/// let options = options.with_normals(true).with_uvs(false).with_threads(2);
/// assert!(!options.uvs && options.normals && options.threads == 2);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ObjWriteOptions {
    /// Write the mesh's texture coordinates, when it has some (default `true`).
    pub uvs: bool,
    /// Write vertex normals: area-weighted, or the limit normals of a [`MeshBuffers`] with
    /// tangents (default `false`).
    pub normals: bool,
    /// Threads formatting the text (OBJ) or the records (PLY), in chunks written in order: 1
    /// (the default) the calling thread, 0 rayon's current pool (the one the call runs in,
    /// else the global one), `n >= 2` a pool of `n` threads. The bytes written are the same
    /// for every value.
    pub threads: usize,
}

impl ObjWriteOptions {
    /// Texture coordinates written, no normals, on the calling thread (the default).
    pub const DEFAULT: ObjWriteOptions = ObjWriteOptions {
        uvs: true,
        normals: false,
        threads: 1,
    };

    with_setters! {
        /// These options with [`uvs`](Self::uvs) set to `uvs`.
        with_uvs(uvs: bool);
        /// These options with [`normals`](Self::normals) set to `normals`.
        with_normals(normals: bool);
        /// These options with [`threads`](Self::threads) set to `threads`.
        with_threads(threads: usize);
    }
}

impl Default for ObjWriteOptions {
    fn default() -> Self {
        ObjWriteOptions::DEFAULT
    }
}

/// The faces of caller-owned index buffers (what a
/// [`Refinement`](crate::Refinement) writes): every face with `degree` corners, or polygons
/// given by offsets (`n_faces + 1` of them, starting at 0) into the indices.
#[derive(Clone, Copy, Debug)]
pub enum FaceBuffers<'a> {
    /// `indices.len() / degree` faces of `degree` corners each (triangles: 3, quads: 4).
    Uniform {
        /// Corners per face.
        degree: usize,
        /// The corners, face after face.
        indices: &'a [u32],
    },
    /// Face `f` is `indices[offsets[f]..offsets[f + 1]]`.
    Polygons {
        /// `n_faces + 1` offsets.
        offsets: &'a [u32],
        /// The corners.
        indices: &'a [u32],
    },
}

impl<'a> FaceBuffers<'a> {
    /// The faces, checked to be faces: `None` when the buffers do not describe faces (a
    /// degree of 0 or not dividing the length, offsets that do not start at 0, end at the
    /// last index and increase).
    pub(crate) fn faces(&self) -> Option<FaceList<'a>> {
        match *self {
            FaceBuffers::Uniform { degree, indices } => (degree > 0 && indices.len() % degree == 0)
                .then_some(FaceList::Uniform { degree, indices }),
            FaceBuffers::Polygons { offsets, indices } => (offsets.first() == Some(&0)
                && offsets.last().map(|&l| l as usize) == Some(indices.len())
                && offsets.windows(2).all(|w| w[0] < w[1]))
            .then_some(FaceList::Offsets32 { offsets, indices }),
        }
    }
}

/// Faces whose buffers are known to be faces ([`FaceBuffers::faces`], a
/// [`PolygonMesh`](crate::PolygonMesh)'s): each face's corners by index, without a list of
/// slices.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FaceList<'a> {
    /// `indices.len() / degree` faces of `degree > 0` corners.
    Uniform { degree: usize, indices: &'a [u32] },
    /// Face `f` is `indices[offsets[f]..offsets[f + 1]]`, offsets increasing from 0 to the
    /// length.
    Offsets32 {
        offsets: &'a [u32],
        indices: &'a [u32],
    },
    /// The same with a face list's offsets.
    Offsets {
        offsets: &'a [usize],
        indices: &'a [u32],
    },
}

impl<'a> FaceList<'a> {
    /// A face list's faces.
    pub(crate) fn of_polygon_mesh(mesh: &'a crate::PolygonMesh) -> FaceList<'a> {
        FaceList::Offsets {
            offsets: mesh.face_offsets(),
            indices: mesh.face_indices(),
        }
    }

    /// The number of faces.
    pub(crate) fn len(&self) -> usize {
        match *self {
            FaceList::Uniform { degree, indices } => indices.len() / degree,
            FaceList::Offsets32 { offsets, .. } => offsets.len() - 1,
            FaceList::Offsets { offsets, .. } => offsets.len() - 1,
        }
    }

    /// All the corners, face after face.
    pub(crate) fn indices(&self) -> &'a [u32] {
        match *self {
            FaceList::Uniform { indices, .. }
            | FaceList::Offsets32 { indices, .. }
            | FaceList::Offsets { indices, .. } => indices,
        }
    }

    /// Face `f`'s corners.
    #[inline]
    pub(crate) fn face(&self, f: usize) -> &'a [u32] {
        &self.indices()[self.first_corner(f)..self.first_corner(f + 1)]
    }

    /// The index of face `f`'s first corner among [`indices`](Self::indices) (`f` up to
    /// the number of faces: the end of the last).
    #[inline]
    pub(crate) fn first_corner(&self, f: usize) -> usize {
        match *self {
            FaceList::Uniform { degree, .. } => f * degree,
            FaceList::Offsets32 { offsets, .. } => offsets[f] as usize,
            FaceList::Offsets { offsets, .. } => offsets[f],
        }
    }

    /// The faces in order.
    pub(crate) fn iter(&self) -> impl ExactSizeIterator<Item = &'a [u32]> + 'a {
        let list = *self;
        (0..list.len()).map(move |f| list.face(f))
    }

    /// The most corners of a face (0 without faces).
    pub(crate) fn max_degree(&self) -> usize {
        match *self {
            FaceList::Uniform { degree, indices } if !indices.is_empty() => degree,
            FaceList::Uniform { .. } => 0,
            FaceList::Offsets32 { offsets, .. } => offsets
                .windows(2)
                .map(|w| (w[1] - w[0]) as usize)
                .max()
                .unwrap_or(0),
            FaceList::Offsets { offsets, .. } => {
                offsets.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(0)
            }
        }
    }
}

/// The first of `values` not below `bound`, with its index: a vectorised pass for the usual
/// answer (none), the search only when there is one.
fn first_at_least(values: &[u32], bound: usize) -> Option<(usize, u32)> {
    let max = values.iter().copied().fold(0, u32::max);
    if values.is_empty() || (max as usize) < bound {
        return None;
    }
    values
        .iter()
        .copied()
        .enumerate()
        .find(|&(_, v)| v as usize >= bound)
}

/// Texture coordinates in caller-owned buffers (what a face-varying evaluation writes): the UV
/// values, `f32` or `f64` like the positions, and the value of every face corner, in the
/// order of the [`FaceBuffers`]' corners (0-based).
#[derive(Clone, Copy, Debug)]
pub struct UvBuffers<'a, T> {
    /// The UV values, each written once as a `vt` line.
    pub values: &'a [[T; 2]],
    /// The value of each face corner.
    pub corners: &'a [u32],
}

/// Limit tangents in caller-owned buffers (first, second), one per position
/// ([`MeshBuffers::tangents`]).
pub type TangentBuffers<'a, T> = (&'a [[T; 3]], &'a [[T; 3]]);

/// A mesh in caller-owned buffers, as the writers take it: positions and faces, and
/// optionally texture coordinates, vertex colors and per-face groups.
///
/// ```
/// use halfedge::io::{write_mesh_buffers_obj, FaceBuffers, MeshBuffers, ObjWriteOptions};
/// let positions = [[0.0f64, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let colors = [[1.0f64, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let faces = FaceBuffers::Uniform { degree: 3, indices: &[0, 1, 2] };
/// let mesh = MeshBuffers::new(&positions, faces).with_colors(&colors);
/// let mut out = Vec::new();
/// write_mesh_buffers_obj(&mesh, &mut out, &ObjWriteOptions::default())?;
/// assert!(String::from_utf8(out)?.starts_with("v 0.0 0.0 0.0 1.0 0.0 0.0\n"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub struct MeshBuffers<'a, T> {
    /// The positions.
    pub positions: &'a [[T; 3]],
    /// The faces.
    pub faces: FaceBuffers<'a>,
    /// Texture coordinates: values and a value per face corner.
    pub uvs: Option<UvBuffers<'a, T>>,
    /// A color (`r g b`) per position.
    pub colors: Option<&'a [[T; 3]]>,
    /// The faces' materials, objects, groups and smoothing groups, one face per face.
    pub groups: Option<&'a FaceGroups>,
    /// Limit tangents, two per position: the normals written are then the limit normals
    /// ([`normals::limit_normal`]), not the area-weighted ones.
    pub tangents: Option<TangentBuffers<'a, T>>,
}

impl<'a, T> MeshBuffers<'a, T> {
    /// Positions and faces, nothing else.
    pub fn new(positions: &'a [[T; 3]], faces: FaceBuffers<'a>) -> MeshBuffers<'a, T> {
        MeshBuffers {
            positions,
            faces,
            uvs: None,
            colors: None,
            groups: None,
            tangents: None,
        }
    }

    /// With limit tangents, two per position ([`MeshBuffers::tangents`]).
    pub fn with_tangents(mut self, first: &'a [[T; 3]], second: &'a [[T; 3]]) -> Self {
        self.tangents = Some((first, second));
        self
    }

    /// With texture coordinates.
    pub fn with_uvs(mut self, uvs: UvBuffers<'a, T>) -> Self {
        self.uvs = Some(uvs);
        self
    }

    /// With a color per position.
    pub fn with_colors(mut self, colors: &'a [[T; 3]]) -> Self {
        self.colors = Some(colors);
        self
    }

    /// With groups, one per face.
    pub fn with_groups(mut self, groups: &'a FaceGroups) -> Self {
        self.groups = Some(groups);
        self
    }

    /// What a writer writes under `options`: the faces as slices (checked), the UVs when
    /// asked, the area-weighted vertex normals when asked.
    pub(crate) fn prepare_write(&self, options: &ObjWriteOptions) -> std::io::Result<Written<'a, T>>
    where
        T: Scalar,
    {
        let uvs = self.uvs.filter(|_| options.uvs);
        let list = MeshBuffers { uvs, ..*self }.checked_faces()?;
        let positions = self.positions;
        if let Some((a, b)) = self
            .tangents
            .filter(|(a, b)| a.len() != positions.len() || b.len() != positions.len())
        {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "{} and {} tangents for {} positions",
                    a.len(),
                    b.len(),
                    positions.len()
                ),
            ));
        }
        let normals = options.normals.then(|| {
            let position = |v: u32| DVec3::from_array(positions[v as usize].map(T::to_f64));
            let area = normals::vertex_normals_by(positions.len(), position, list.iter());
            match self.tangents {
                Some((a, b)) => {
                    let d = |x: &[T; 3]| DVec3::from_array(x.map(T::to_f64));
                    (area.iter().zip(a.iter().zip(b)))
                        .map(|(&n, (u, v))| normals::limit_normal(d(u), d(v), n))
                        .collect()
                }
                None => area,
            }
        });
        Ok(Written { list, uvs, normals })
    }

    /// The faces, checked against the positions, the UVs, the colors and the groups
    /// ([`std::io::ErrorKind::InvalidInput`] naming the mismatch).
    pub(crate) fn checked_faces(&self) -> std::io::Result<FaceList<'a>> {
        let faces = self.faces;
        let list = faces.faces().ok_or_else(|| {
            let what = format!("inconsistent face buffers: {faces:?}");
            std::io::Error::new(std::io::ErrorKind::InvalidInput, what)
        })?;
        let uvs = self.uvs.as_ref().map(|u| (u.corners, u.values.len()));
        check_faces(
            list,
            self.positions.len(),
            self.colors.map(<[_]>::len),
            self.groups,
            uvs,
        )?;
        Ok(list)
    }
}

/// Checks faces against `positions` positions, `colors` colors, the groups and the UVs (a
/// value per corner, and the number of values): [`std::io::ErrorKind::InvalidInput`]
/// naming the first mismatch.
pub(crate) fn check_faces(
    list: FaceList<'_>,
    positions: usize,
    colors: Option<usize>,
    groups: Option<&FaceGroups>,
    uvs: Option<(&[u32], usize)>,
) -> std::io::Result<()> {
    let invalid = |what: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, what);
    if let Some((_, v)) = first_at_least(list.indices(), positions) {
        return Err(invalid(format!(
            "a face uses vertex {v}, but there are {positions} positions"
        )));
    }
    if let Some(colors) = colors.filter(|&c| c != positions) {
        return Err(invalid(format!(
            "{colors} colors for {positions} positions"
        )));
    }
    if let Some(groups) = groups.filter(|g| g.n_faces() != list.len()) {
        return Err(invalid(format!(
            "groups of {} faces for {} faces",
            groups.n_faces(),
            list.len()
        )));
    }
    if let Some((uv_corners, values)) = uvs {
        let corners = list.indices().len();
        if uv_corners.len() != corners {
            return Err(invalid(format!(
                "{} texture-coordinate corners for {corners} face corners",
                uv_corners.len()
            )));
        }
        if let Some((corner, t)) = first_at_least(uv_corners, values) {
            return Err(invalid(format!(
                "face corner {corner} uses UV value {t}, but there are {values}"
            )));
        }
    }
    Ok(())
}

/// What the writers write of a [`MeshBuffers`] under their options.
pub(crate) struct Written<'a, T> {
    /// The faces, checked.
    pub(crate) list: FaceList<'a>,
    /// The UVs, when asked for.
    pub(crate) uvs: Option<UvBuffers<'a, T>>,
    /// Area-weighted vertex normals, when asked for.
    pub(crate) normals: Option<Vec<DVec3>>,
}
