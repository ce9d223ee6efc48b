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
/// let options = options.with_normals(true).with_uvs(false);
/// assert!(!options.uvs && options.normals);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ObjWriteOptions {
    /// Write the mesh's texture coordinates, when it has some (default `true`).
    pub uvs: bool,
    /// Write vertex normals: area-weighted, or the limit normals of a [`MeshBuffers`] with
    /// tangents (default `false`).
    pub normals: bool,
}

impl ObjWriteOptions {
    /// Texture coordinates written, no normals (the default).
    pub const DEFAULT: ObjWriteOptions = ObjWriteOptions {
        uvs: true,
        normals: false,
    };

    with_setters! {
        /// These options with [`uvs`](Self::uvs) set to `uvs`.
        with_uvs(uvs: bool);
        /// These options with [`normals`](Self::normals) set to `normals`.
        with_normals(normals: bool);
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
    /// The faces as slices; `None` when the buffers do not describe faces (a degree of 0 or
    /// not dividing the length, offsets that decrease or leave the indices).
    pub(crate) fn faces(&self) -> Option<Vec<&'a [u32]>> {
        match *self {
            FaceBuffers::Uniform { degree, indices } => (degree > 0 && indices.len() % degree == 0)
                .then(|| indices.chunks_exact(degree).collect()),
            FaceBuffers::Polygons { offsets, indices } => {
                let whole = offsets.first() == Some(&0)
                    && offsets.last().map(|&l| l as usize) == Some(indices.len());
                let faces: Option<Vec<&'a [u32]>> = offsets
                    .windows(2)
                    .map(|w| indices.get(w[0] as usize..w[1] as usize))
                    .collect();
                faces.filter(|f| whole && f.iter().all(|f| !f.is_empty()))
            }
        }
    }
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
            let area = normals::vertex_normals_by(positions.len(), position, &list);
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

    /// The faces as slices, checked against the positions, the UVs, the colors and the
    /// groups ([`std::io::ErrorKind::InvalidInput`] naming the mismatch).
    pub(crate) fn checked_faces(&self) -> std::io::Result<Vec<&'a [u32]>> {
        let invalid = |what: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, what);
        let faces = self.faces;
        let list = faces
            .faces()
            .ok_or_else(|| invalid(format!("inconsistent face buffers: {faces:?}")))?;
        let positions = self.positions;
        if let Some(&v) = list
            .iter()
            .flat_map(|f| f.iter())
            .find(|&&v| v as usize >= positions.len())
        {
            return Err(invalid(format!(
                "a face uses vertex {v}, but there are {} positions",
                positions.len()
            )));
        }
        if let Some(colors) = self.colors.filter(|c| c.len() != positions.len()) {
            return Err(invalid(format!(
                "{} colors for {} positions",
                colors.len(),
                positions.len()
            )));
        }
        if let Some(groups) = self.groups.filter(|g| g.n_faces() != list.len()) {
            return Err(invalid(format!(
                "groups of {} faces for {} faces",
                groups.n_faces(),
                list.len()
            )));
        }
        if let Some(uv) = &self.uvs {
            let corners: usize = list.iter().map(|f| f.len()).sum();
            if uv.corners.len() != corners {
                return Err(invalid(format!(
                    "{} texture-coordinate corners for {corners} face corners",
                    uv.corners.len()
                )));
            }
            if let Some((corner, &t)) = uv
                .corners
                .iter()
                .enumerate()
                .find(|(_, &t)| t as usize >= uv.values.len())
            {
                return Err(invalid(format!(
                    "face corner {corner} uses UV value {t}, but there are {}",
                    uv.values.len()
                )));
            }
        }
        Ok(list)
    }
}

/// What the writers write of a [`MeshBuffers`] under their options.
pub(crate) struct Written<'a, T> {
    /// The faces, checked.
    pub(crate) list: Vec<&'a [u32]>,
    /// The UVs, when asked for.
    pub(crate) uvs: Option<UvBuffers<'a, T>>,
    /// Area-weighted vertex normals, when asked for.
    pub(crate) normals: Option<Vec<DVec3>>,
}
