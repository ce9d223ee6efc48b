//! OBJ writing, and the one writer of output files ([`write_atomically`]).

use std::fs::{self, File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};

use glam::DVec3;

use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;
use crate::normals;
use crate::polygon::PolygonMesh;
use crate::Scalar;

/// What the OBJ writers write besides positions and faces.
///
/// With [`uvs`](Self::uvs) (the default), a mesh with texture coordinates
/// ([`PolygonMesh::uvs`], or [`UvBuffers`]) gets its `vt` lines, each value once, and faces
/// `f v/vt`; a mesh without them is written as without this option. With
/// [`normals`](Self::normals) (off by default), the writer computes area-weighted vertex
/// normals of the faces written ([`crate::normals::vertex_normals`]) and writes one `vn` per
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
    /// Write area-weighted vertex normals (default `false`).
    pub normals: bool,
}

impl ObjWriteOptions {
    /// Texture coordinates written, no normals (the default).
    pub const DEFAULT: ObjWriteOptions = ObjWriteOptions {
        uvs: true,
        normals: false,
    };

    /// These options with [`uvs`](Self::uvs) set to `uvs`.
    pub fn with_uvs(mut self, uvs: bool) -> ObjWriteOptions {
        self.uvs = uvs;
        self
    }

    /// These options with [`normals`](Self::normals) set to `normals`.
    pub fn with_normals(mut self, normals: bool) -> ObjWriteOptions {
        self.normals = normals;
        self
    }
}

impl Default for ObjWriteOptions {
    fn default() -> Self {
        ObjWriteOptions::DEFAULT
    }
}

/// Writes a mesh as OBJ text: one `v x y z` line per vertex, then one `f` line per face
/// (1-based indices, n-gons kept), nothing else.
///
/// Coordinates are written with Rust's shortest round-trip formatting, so reading the file
/// back gives the same `f64` values. The writer is wrapped in a `BufWriter` by this function.
///
/// # Errors
///
/// Any error of the writer.
///
/// # Example
///
/// ```
/// let mesh = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::tetrahedron())?;
/// let mut out = Vec::new();
/// halfedge::io::write_obj(&mesh, &mut out)?;
/// let text = String::from_utf8(out)?;
/// assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_obj(mesh: &HalfEdgeMesh, writer: impl Write) -> std::io::Result<()> {
    write_obj_with(mesh, writer, &ObjWriteOptions::DEFAULT)
}

/// [`write_obj`] with options: a half-edge mesh has no texture coordinates, so only
/// [`ObjWriteOptions::normals`] changes the text.
///
/// # Errors
///
/// Any error of the writer.
///
/// ```
/// use halfedge::io::{write_obj_with, ObjWriteOptions};
/// let mesh = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::tetrahedron())?;
/// let mut out = Vec::new();
/// write_obj_with(&mesh, &mut out, &ObjWriteOptions::default().with_normals(true))?;
/// let text = String::from_utf8(out)?;
/// assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), 4);
/// assert!(text.contains("\nf 1//1 "));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_obj_with(
    mesh: &HalfEdgeMesh,
    writer: impl Write,
    options: &ObjWriteOptions,
) -> std::io::Result<()> {
    let faces = || mesh.faces().map(|f| mesh.face_vertices(f).map(|v| v.0));
    let normals = options.normals.then(|| {
        let lists = faces().map(|f| f.collect::<Vec<u32>>());
        normals::vertex_normals(mesh.positions(), lists)
    });
    write_coordinates(
        mesh.positions().iter().map(|p| [&p.x, &p.y, &p.z]),
        None::<TexCoords<'_, f64, std::iter::Empty<[&f64; 2]>>>,
        normals.as_deref(),
        faces(),
        writer,
    )
}

/// Writes a face list as OBJ text, like [`write_obj`] (every position is written, used or
/// not, so indices are kept), with its texture coordinates when it has some
/// ([`PolygonMesh::uvs`]: every `vt`, used or not, so indices are kept, and `f v/vt`); a
/// mesh without them is written exactly as [`write_obj`] writes it.
///
/// # Errors
///
/// Any error of the writer.
///
/// ```
/// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
/// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "uv.obj")?;
/// let mut out = Vec::new();
/// halfedge::io::write_polygon_obj(&mesh, &mut out)?;
/// assert_eq!(
///     String::from_utf8(out)?,
///     "v 0.0 0.0 0.0\nv 1.0 0.0 0.0\nv 0.0 1.0 0.0\nvt 0.0 0.0\nvt 1.0 0.0\nvt 0.0 1.0\nf 1/1 2/2 3/3\n"
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_polygon_obj(mesh: &PolygonMesh, writer: impl Write) -> std::io::Result<()> {
    write_polygon_obj_with(mesh, writer, &ObjWriteOptions::DEFAULT)
}

/// [`write_polygon_obj`] with options: texture coordinates left out, or normals written
/// ([`ObjWriteOptions`]).
///
/// # Errors
///
/// Any error of the writer.
///
/// ```
/// use halfedge::io::{read_obj_from, write_polygon_obj_with, ObjWriteOptions};
/// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
/// let mesh = read_obj_from(text.as_bytes(), "uv.obj")?;
/// let mut out = Vec::new();
/// write_polygon_obj_with(&mesh, &mut out, &ObjWriteOptions::default().with_normals(true))?;
/// let written = String::from_utf8(out)?;
/// assert!(written.ends_with("vn 0.0 0.0 1.0\nvn 0.0 0.0 1.0\nvn 0.0 0.0 1.0\nf 1/1/1 2/2/2 3/3/3\n"));
/// let mut out = Vec::new();
/// write_polygon_obj_with(&mesh, &mut out, &ObjWriteOptions::default().with_uvs(false))?;
/// assert!(String::from_utf8(out)?.ends_with("v 0.0 1.0 0.0\nf 1 2 3\n"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_polygon_obj_with(
    mesh: &PolygonMesh,
    writer: impl Write,
    options: &ObjWriteOptions,
) -> std::io::Result<()> {
    let uvs = mesh
        .uvs()
        .filter(|u| options.uvs && u.corners().len() == mesh.n_corners());
    let texcoords = uvs.map(|u| TexCoords {
        values: u.coords().iter().map(|c| [&c.x, &c.y]),
        corners: u.corners(),
    });
    let normals = options
        .normals
        .then(|| normals::vertex_normals(&mesh.positions, mesh.faces()));
    write_coordinates(
        mesh.positions.iter().map(|p| [&p.x, &p.y, &p.z]),
        texcoords,
        normals.as_deref(),
        mesh.faces().map(|f| f.iter().copied()),
        writer,
    )
}

/// Writes a mesh to an OBJ file with [`write_atomically`]: the text goes to a temporary file
/// in the target's folder, which is renamed over the target only once it is complete and
/// synced; on any error the temporary file is removed and the target is untouched. See
/// [`write_atomically`] for `-`, symbolic links, special files and write-protected targets.
///
/// # Errors
///
/// [`Error::Io`] naming the file, [`Error::WriteProtected`] for a target the user may not
/// write.
pub fn write_obj_file(mesh: &HalfEdgeMesh, path: impl AsRef<Path>) -> Result<()> {
    write_atomically(path.as_ref(), |file| write_obj(mesh, file))
}

/// Writes a face list to an OBJ file atomically, like [`write_obj_file`].
///
/// # Errors
///
/// As [`write_obj_file`].
pub fn write_polygon_obj_file(mesh: &PolygonMesh, path: impl AsRef<Path>) -> Result<()> {
    write_atomically(path.as_ref(), |file| write_polygon_obj(mesh, file))
}

/// [`write_obj_file`] with options ([`write_obj_with`]).
///
/// # Errors
///
/// As [`write_obj_file`].
pub fn write_obj_file_with(
    mesh: &HalfEdgeMesh,
    path: impl AsRef<Path>,
    options: &ObjWriteOptions,
) -> Result<()> {
    write_atomically(path.as_ref(), |file| write_obj_with(mesh, file, options))
}

/// [`write_polygon_obj_file`] with options ([`write_polygon_obj_with`]).
///
/// # Errors
///
/// As [`write_obj_file`].
pub fn write_polygon_obj_file_with(
    mesh: &PolygonMesh,
    path: impl AsRef<Path>,
    options: &ObjWriteOptions,
) -> Result<()> {
    write_atomically(path.as_ref(), |file| {
        write_polygon_obj_with(mesh, file, options)
    })
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

impl FaceBuffers<'_> {
    /// The faces as slices; `None` when the buffers do not describe faces (a degree of 0 or
    /// not dividing the length, offsets that decrease or leave the indices).
    fn faces(&self) -> Option<Vec<&[u32]>> {
        match *self {
            FaceBuffers::Uniform { degree, indices } => (degree > 0 && indices.len() % degree == 0)
                .then(|| indices.chunks_exact(degree).collect()),
            FaceBuffers::Polygons { offsets, indices } => {
                let whole = offsets.first() == Some(&0)
                    && offsets.last().map(|&l| l as usize) == Some(indices.len());
                let faces: Option<Vec<&[u32]>> = offsets
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

/// Writes positions and faces from caller-owned buffers as OBJ text, like
/// [`write_polygon_obj`]: coordinates in `f32` or `f64` are written with the shortest text
/// that reads back as the same value of that type.
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] when the face buffers are inconsistent (offsets that
/// do not start at 0, end at the last index, or give an empty face) or a corner
/// names a vertex beyond `positions`; any error of the writer.
///
/// ```
/// use halfedge::io::{write_buffers_obj, FaceBuffers};
/// let positions: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.1, 1.0, 0.0]];
/// let faces = FaceBuffers::Uniform { degree: 3, indices: &[0, 1, 2] };
/// let mut out = Vec::new();
/// write_buffers_obj(&positions, faces, &mut out)?;
/// assert_eq!(String::from_utf8(out)?, "v 0.0 0.0 0.0\nv 1.0 0.0 0.0\nv 0.1 1.0 0.0\nf 1 2 3\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_buffers_obj<T: Scalar>(
    positions: &[[T; 3]],
    faces: FaceBuffers<'_>,
    writer: impl Write,
) -> std::io::Result<()> {
    write_buffers_obj_with(positions, faces, None, writer, &ObjWriteOptions::DEFAULT)
}

/// [`write_buffers_obj`] with texture coordinates and options: with `uvs` (and
/// [`ObjWriteOptions::uvs`]) the values are written as `vt` lines, in `T`'s shortest text
/// like the positions, and the faces as `f v/vt`; with [`ObjWriteOptions::normals`], the
/// area-weighted vertex normals of the faces ([`crate::normals::vertex_normals_by`], in
/// `f64`, written in `T`) as `vn` lines and `f v/vt/vn` or `f v//vn`. Without either, the
/// text is [`write_buffers_obj`]'s.
///
/// # Errors
///
/// As [`write_buffers_obj`], and [`std::io::ErrorKind::InvalidInput`] when `uvs` has not one
/// corner per face corner or a corner names a value beyond its values; nothing is written
/// then.
///
/// ```
/// use halfedge::io::{write_buffers_obj_with, FaceBuffers, ObjWriteOptions, UvBuffers};
/// let positions: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let faces = FaceBuffers::Uniform { degree: 3, indices: &[0, 1, 2, 0, 2, 3] };
/// let uvs = UvBuffers { values: &[[0.0f32, 0.0], [1.0, 0.5], [0.25, 1.0]], corners: &[0, 1, 2, 0, 2, 1] };
/// let mut out = Vec::new();
/// write_buffers_obj_with(&positions, faces, Some(uvs), &mut out, &ObjWriteOptions::default())?;
/// let text = String::from_utf8(out)?;
/// assert!(text.ends_with("vt 0.0 0.0\nvt 1.0 0.5\nvt 0.25 1.0\nf 1/1 2/2 3/3\nf 1/1 3/3 4/2\n"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_buffers_obj_with<T: Scalar>(
    positions: &[[T; 3]],
    faces: FaceBuffers<'_>,
    uvs: Option<UvBuffers<'_, T>>,
    writer: impl Write,
    options: &ObjWriteOptions,
) -> std::io::Result<()> {
    let invalid = |what: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, what);
    let list = faces
        .faces()
        .ok_or_else(|| invalid(format!("inconsistent face buffers: {faces:?}")))?;
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
    let uvs = uvs.filter(|_| options.uvs);
    if let Some(uv) = &uvs {
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
    let normals = options.normals.then(|| {
        let position = |v: u32| {
            let [x, y, z] = positions[v as usize];
            DVec3::new(x.to_f64(), y.to_f64(), z.to_f64())
        };
        normals::vertex_normals_by(positions.len(), position, &list)
    });
    let texcoords = uvs.map(|u| TexCoords {
        values: u.values.iter().map(|[s, t]| [s, t]),
        corners: u.corners,
    });
    write_coordinates(
        positions.iter().map(|[x, y, z]| [x, y, z]),
        texcoords,
        normals.as_deref(),
        list.iter().map(|f| f.iter().copied()),
        writer,
    )
}

/// [`write_buffers_obj`] into a file, atomically ([`write_atomically`]).
///
/// # Errors
///
/// As [`write_obj_file`], and [`Error::Io`] for inconsistent buffers.
pub fn write_buffers_obj_file<T: Scalar>(
    positions: &[[T; 3]],
    faces: FaceBuffers<'_>,
    path: impl AsRef<Path>,
) -> Result<()> {
    write_atomically(path.as_ref(), |file| {
        write_buffers_obj(positions, faces, file)
    })
}

/// [`write_buffers_obj_with`] into a file, atomically ([`write_atomically`]).
///
/// # Errors
///
/// As [`write_buffers_obj_file`].
pub fn write_buffers_obj_file_with<T: Scalar>(
    positions: &[[T; 3]],
    faces: FaceBuffers<'_>,
    uvs: Option<UvBuffers<'_, T>>,
    path: impl AsRef<Path>,
    options: &ObjWriteOptions,
) -> Result<()> {
    write_atomically(path.as_ref(), |file| {
        write_buffers_obj_with(positions, faces, uvs, file, options)
    })
}

/// The texture coordinates [`write_coordinates`] writes: the values, and the value of each
/// face corner (checked by the caller).
struct TexCoords<'a, T: 'a, U: Iterator<Item = [&'a T; 2]>> {
    values: U,
    corners: &'a [u32],
}

/// The one OBJ text writer: `v` lines with each coordinate's shortest round-trip text
/// (`Debug` of `f32`/`f64`), the `vt` lines of `texcoords`, the `vn` lines of `normals` (in
/// `T`), then 1-based `f` lines: `f v`, `f v/vt`, `f v//vn` or `f v/vt/vn`.
fn write_coordinates<'p, T, P, U, F, I>(
    positions: P,
    texcoords: Option<TexCoords<'p, T, U>>,
    normals: Option<&[DVec3]>,
    faces: F,
    writer: impl Write,
) -> std::io::Result<()>
where
    T: Scalar + 'p,
    P: Iterator<Item = [&'p T; 3]>,
    U: Iterator<Item = [&'p T; 2]>,
    F: Iterator<Item = I>,
    I: Iterator<Item = u32>,
{
    let mut w = BufWriter::with_capacity(1 << 16, writer);
    for [x, y, z] in positions {
        writeln!(w, "v {x:?} {y:?} {z:?}")?;
    }
    let mut vts: &[u32] = &[];
    if let Some(TexCoords { values, corners }) = texcoords {
        for [s, t] in values {
            writeln!(w, "vt {s:?} {t:?}")?;
        }
        vts = corners;
    }
    if let Some(normals) = normals {
        for n in normals {
            let [x, y, z] = n.to_array().map(T::from_f64);
            writeln!(w, "vn {x:?} {y:?} {z:?}")?;
        }
    }
    let with_normals = normals.is_some();
    let mut vts = vts.iter();
    for face in faces {
        w.write_all(b"f")?;
        for v in face {
            let v = u64::from(v) + 1;
            match (vts.next(), with_normals) {
                (None, false) => write!(w, " {v}")?,
                (None, true) => write!(w, " {v}//{v}")?,
                (Some(t), false) => write!(w, " {v}/{}", u64::from(*t) + 1)?,
                (Some(t), true) => write!(w, " {v}/{}/{v}", u64::from(*t) + 1)?,
            }
        }
        w.write_all(b"\n")?;
    }
    w.flush()
}

/// Writes an output file so that what it replaces is never damaged: `body` writes the
/// contents into a [`File`], and where that file goes depends on `path`:
///
/// - `-` is standard output (a duplicate of its descriptor; nothing is renamed).
/// - A regular file, or a path that does not exist yet: `body` writes a temporary file in the
///   target's folder (a short name, `.<at most 24 bytes of the name>.<pid>.<n>.tmp`, so any
///   target name the file system accepts still works), which is synced and renamed over the
///   target only when complete; on any error it is removed and the target is untouched. The
///   new file keeps the permission bits of the file it replaces.
/// - A symbolic link is written through: the file it points to (following every link) is
///   replaced, and the link stays. A dangling link creates the file it names.
/// - A special file (`/dev/stdout` on a pipe or terminal, a FIFO, a character device such as
///   `/dev/null`) is opened and written directly, never renamed over.
///
/// An existing target the user may not write is refused and left intact
/// ([`Error::WriteProtected`]): one without any write permission bit (mode 444), even for
/// root, whom the kernel would let write it (the mode is the owner's statement that the file
/// is not to be changed, as `rm` and `cp -i` treat it), and one for which `access(W_OK)`
/// fails (the mode bits of the user's class, ACLs, a read-only file system). Renaming over a
/// file needs only the folder's permission, so without this check a read-only file would be
/// replaced.
///
/// While a temporary file exists, `SIGINT`, `SIGTERM` and `SIGHUP` remove it before the
/// process ends: the first call installs (with `signal-hook`) a thread that deletes every
/// live temporary file on those signals and then ends the process as the signal's default
/// action would (a shell reports exit status 130 for `SIGINT`, 143 for `SIGTERM`). A signal
/// the process ignores (as `nohup` arranges) stays ignored.
///
/// # Errors
///
/// [`Error::Io`] naming `path` for any failure to open, write, sync or rename (the target is
/// then untouched, except for a special file, which is written as it goes), and
/// [`Error::WriteProtected`].
///
/// # Example
///
/// ```
/// use std::io::Write;
/// let dir = std::env::temp_dir().join(format!("write-atomically-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let target = dir.join("out.txt");
/// halfedge::io::write_atomically(&target, |file| file.write_all(b"hello\n"))?;
/// assert_eq!(std::fs::read_to_string(&target)?, "hello\n");
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_atomically(
    path: &Path,
    body: impl FnOnce(&mut File) -> std::io::Result<()>,
) -> Result<()> {
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    if path.as_os_str() == "-" {
        return write_stdout(body).map_err(io_error);
    }
    match resolve_target(path).map_err(io_error)? {
        Target::Special => {
            let result = OpenOptions::new()
                .write(true)
                .open(path)
                .and_then(|mut file| body(&mut file).and_then(|()| file.flush()));
            result.map_err(io_error)
        }
        Target::Regular { resolved, existing } => {
            if let Some(metadata) = &existing {
                refuse_write_protected(path, &resolved, metadata)?;
            }
            let permissions = existing.map(|m| m.permissions());
            write_through_temporary(&resolved, permissions, body).map_err(io_error)
        }
    }
}

/// The mesh formats an output name's extension may name that the writers do not write
/// (they write OBJ): a file named `out.ply` holding OBJ text would mislead every program that
/// opens it.
pub const UNWRITTEN_MESH_FORMATS: &[&str] = &[
    "ply", "stl", "off", "glb", "gltf", "fbx", "usd", "usda", "usdc", "3ds", "dae",
];

/// The extension of `path` (lowercase) when it names a mesh format the writers do not write
/// ([`UNWRITTEN_MESH_FORMATS`]); `None` for `.obj` and every other name, written as OBJ.
///
/// ```
/// use halfedge::io::unwritten_mesh_format;
/// use std::path::Path;
/// assert_eq!(unwritten_mesh_format(Path::new("out.PLY")).as_deref(), Some("ply"));
/// assert_eq!(unwritten_mesh_format(Path::new("out.obj")), None);
/// assert_eq!(unwritten_mesh_format(Path::new("out.txt")), None);
/// ```
pub fn unwritten_mesh_format(path: &Path) -> Option<String> {
    let extension = path.extension()?.to_str()?.to_ascii_lowercase();
    UNWRITTEN_MESH_FORMATS
        .contains(&extension.as_str())
        .then_some(extension)
}

/// Checks up front what [`write_atomically`] would refuse without writing anything: a
/// write-protected target or a folder, so that a long computation is not wasted on an output
/// that cannot be written. Everything else (`-`, a new file, a special file) passes.
///
/// # Errors
///
/// As [`write_atomically`]'s refusals: [`Error::WriteProtected`], [`Error::Io`].
pub fn check_output(path: &Path) -> Result<()> {
    if path.as_os_str() == "-" {
        return Ok(());
    }
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    match resolve_target(path).map_err(io_error)? {
        Target::Regular {
            resolved,
            existing: Some(metadata),
        } => refuse_write_protected(path, &resolved, &metadata),
        _ => Ok(()),
    }
}

/// Where [`write_atomically`] puts the bytes.
enum Target {
    /// Not a regular file: written directly.
    Special,
    /// A regular file (`existing` is its metadata) or a path to create, with every symbolic
    /// link resolved.
    Regular {
        resolved: PathBuf,
        existing: Option<fs::Metadata>,
    },
}

fn resolve_target(path: &Path) -> std::io::Result<Target> {
    match fs::metadata(path) {
        Ok(metadata) if metadata.is_dir() => Err(std::io::Error::other("is a directory")),
        Ok(metadata) if !metadata.is_file() => Ok(Target::Special),
        Ok(metadata) => {
            let resolved = follow_links(path)?;
            // A link that does not lead to a path naming the same file (a /proc/self/fd link
            // to a deleted file, another mount namespace): the path cannot be renamed over,
            // so the file is written directly.
            let same = fs::metadata(&resolved).is_ok_and(|m| same_file(&m, &metadata));
            if same {
                Ok(Target::Regular {
                    resolved,
                    existing: Some(metadata),
                })
            } else {
                Ok(Target::Special)
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Target::Regular {
            // A dangling link creates the file it points to.
            resolved: follow_links(path)?,
            existing: None,
        }),
        Err(e) => Err(e),
    }
}

#[cfg(unix)]
fn same_file(a: &fs::Metadata, b: &fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    (a.dev(), a.ino()) == (b.dev(), b.ino())
}

#[cfg(not(unix))]
fn same_file(_: &fs::Metadata, _: &fs::Metadata) -> bool {
    true
}

/// Follows symbolic links from `path` (at most 40, as Linux does) to the first path that is
/// not a link (or does not exist).
fn follow_links(path: &Path) -> std::io::Result<PathBuf> {
    let mut current = path.to_path_buf();
    for _ in 0..40 {
        match fs::symlink_metadata(&current) {
            Ok(m) if m.file_type().is_symlink() => {
                let target = fs::read_link(&current)?;
                current = match current.parent() {
                    Some(parent) if target.is_relative() => parent.join(target),
                    _ => target,
                };
            }
            Ok(_) => return Ok(current),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(current),
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// Refuses an existing regular file the user may not write (see [`write_atomically`]).
fn refuse_write_protected(path: &Path, resolved: &Path, metadata: &fs::Metadata) -> Result<()> {
    let refuse = |reason: String| Error::WriteProtected {
        path: path.to_path_buf(),
        reason,
    };
    if metadata.permissions().readonly() {
        return Err(refuse(mode_text(metadata)));
    }
    #[cfg(unix)]
    if let Err(e) = rustix::fs::access(resolved, rustix::fs::Access::WRITE_OK) {
        return Err(refuse(std::io::Error::from(e).to_string()));
    }
    let _ = resolved;
    Ok(())
}

#[cfg(unix)]
fn mode_text(metadata: &fs::Metadata) -> String {
    use std::os::unix::fs::PermissionsExt;
    format!(
        "it is read-only (mode {:o})",
        metadata.permissions().mode() & 0o7777
    )
}

#[cfg(not(unix))]
fn mode_text(_: &fs::Metadata) -> String {
    "it is read-only".to_string()
}

/// Writes to standard output through a duplicate of its descriptor (so `body` gets a
/// [`File`], and the shell's redirection, `>>` included, is kept).
#[cfg(unix)]
fn write_stdout(body: impl FnOnce(&mut File) -> std::io::Result<()>) -> std::io::Result<()> {
    use std::os::fd::AsFd;
    let stdout = std::io::stdout();
    // Whatever Rust buffered for stdout goes first.
    stdout.lock().flush()?;
    let mut file = File::from(stdout.as_fd().try_clone_to_owned()?);
    body(&mut file)?;
    file.flush()
}

#[cfg(not(unix))]
fn write_stdout(_: impl FnOnce(&mut File) -> std::io::Result<()>) -> std::io::Result<()> {
    Err(std::io::Error::other(
        "writing to standard output is supported on Unix only",
    ))
}

fn write_through_temporary(
    target: &Path,
    permissions: Option<fs::Permissions>,
    body: impl FnOnce(&mut File) -> std::io::Result<()>,
) -> std::io::Result<()> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let dir = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file_name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"))?;
    let prefix = short_prefix(&file_name, 24);
    install_signal_cleanup();
    let (temp_path, mut file) = loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let candidate = dir.join(format!(".{prefix}.{}.{n}.tmp", std::process::id()));
        // Registered before it exists, so a signal between creating and registering cannot
        // leave it behind.
        register_temporary(&candidate);
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&candidate)
        {
            Ok(file) => break (candidate, file),
            Err(e) => {
                unregister_temporary(&candidate);
                if e.kind() == std::io::ErrorKind::AlreadyExists {
                    continue;
                }
                return Err(e);
            }
        }
    };
    let result = permissions
        .map_or(Ok(()), |p| file.set_permissions(p))
        .and_then(|()| body(&mut file))
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            drop(file);
            fs::rename(&temp_path, target)
        });
    if result.is_err() {
        // Best effort: the temporary file may already be gone.
        let _ = fs::remove_file(&temp_path);
    }
    unregister_temporary(&temp_path);
    result
}

/// At most `max` bytes of `name`, cut at a character boundary.
fn short_prefix(name: &str, max: usize) -> &str {
    let mut end = name.len().min(max);
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    &name[..end]
}

/// The temporary files being written now, which a signal removes.
fn live_temporaries() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
    LIVE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn register_temporary(path: &Path) {
    live_temporaries().push(path.to_path_buf());
}

fn unregister_temporary(path: &Path) {
    let mut live = live_temporaries();
    if let Some(i) = live.iter().position(|p| p == path) {
        live.swap_remove(i);
    }
}

/// Installs, once, the thread that removes live temporary files on `SIGINT`, `SIGTERM` and
/// `SIGHUP` and then ends the process as the signal would have (signals the process ignores
/// are left alone). Without Unix signals, or when the handler cannot be installed, nothing
/// happens: writing still works, only the cleanup on a signal is missing.
fn install_signal_cleanup() {
    static INSTALLED: OnceLock<()> = OnceLock::new();
    INSTALLED.get_or_init(|| {
        #[cfg(unix)]
        {
            use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
            let ignored = ignored_signals();
            let wanted: Vec<i32> = [SIGINT, SIGTERM, SIGHUP]
                .into_iter()
                .filter(|&s| ignored & (1u64 << (s - 1)) == 0)
                .collect();
            let Ok(mut signals) = signal_hook::iterator::Signals::new(&wanted) else {
                return;
            };
            let spawned = std::thread::Builder::new()
                .name("temporary-file-cleanup".into())
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        for path in live_temporaries().drain(..) {
                            let _ = fs::remove_file(path);
                        }
                        // Ends the process as the signal's default action does; should
                        // that fail, the exit status a shell would show.
                        let _ = signal_hook::low_level::emulate_default_handler(signal);
                        std::process::exit(128 + signal);
                    }
                });
            drop(spawned);
        }
    });
}

/// The mask of signals this process ignores (`SigIgn` of `/proc/self/status`; bit `s - 1`
/// for signal `s`), 0 when it cannot be read.
#[cfg(unix)]
fn ignored_signals() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|status| {
            let hex = status.lines().find_map(|l| l.strip_prefix("SigIgn:"))?;
            u64::from_str_radix(hex.trim(), 16).ok()
        })
        .unwrap_or(0)
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("halfedge-write-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("a temporary folder");
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .expect("listed")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_write_protected_file_is_refused_and_left_intact() {
        use std::os::unix::fs::PermissionsExt;
        let dir = temp_dir("ro");
        let target = dir.join("ro.obj");
        fs::write(&target, "keep\n").expect("written");
        fs::set_permissions(&target, fs::Permissions::from_mode(0o444)).expect("chmod");
        let err = write_atomically(&target, |f| f.write_all(b"new\n")).unwrap_err();
        assert!(matches!(err, Error::WriteProtected { .. }), "{err:?}");
        assert_eq!(
            err.to_string(),
            format!(
                "{}: refusing to write over it: it is read-only (mode 444)",
                target.display()
            )
        );
        assert_eq!(fs::read_to_string(&target).expect("read"), "keep\n");
        assert_eq!(names(&dir), ["ro.obj"]);
        // The same refusal up front, before any work.
        let early = check_output(&target).unwrap_err();
        assert_eq!(early.to_string(), err.to_string());
        check_output(&dir.join("new.obj")).expect("a new file may be written");
        check_output(Path::new("-")).expect("stdout may be written");
        check_output(Path::new("/dev/null")).expect("a device may be written");
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn a_symlink_is_written_through_and_the_mode_is_kept() {
        use std::os::unix::fs::PermissionsExt;
        let dir = temp_dir("link");
        fs::create_dir_all(dir.join("real")).expect("dir");
        let real = dir.join("real").join("mesh.obj");
        fs::write(&real, "old\n").expect("written");
        fs::set_permissions(&real, fs::Permissions::from_mode(0o640)).expect("chmod");
        let link = dir.join("link.obj");
        std::os::unix::fs::symlink("real/mesh.obj", &link).expect("link");
        // A chain of two links.
        let link2 = dir.join("link2.obj");
        std::os::unix::fs::symlink(&link, &link2).expect("link");
        write_atomically(&link2, |f| f.write_all(b"new\n")).expect("written");
        assert!(fs::symlink_metadata(&link)
            .expect("stat")
            .file_type()
            .is_symlink());
        assert!(fs::symlink_metadata(&link2)
            .expect("stat")
            .file_type()
            .is_symlink());
        assert_eq!(fs::read_to_string(&real).expect("read"), "new\n");
        let mode = fs::metadata(&real).expect("stat").permissions().mode() & 0o777;
        assert_eq!(mode, 0o640);
        assert_eq!(names(&dir.join("real")), ["mesh.obj"]);
        // A dangling link creates the file it names.
        let dangling = dir.join("dangling.obj");
        std::os::unix::fs::symlink("real/new.obj", &dangling).expect("link");
        write_atomically(&dangling, |f| f.write_all(b"made\n")).expect("written");
        assert_eq!(
            fs::read_to_string(dir.join("real/new.obj")).expect("read"),
            "made\n"
        );
        assert!(fs::symlink_metadata(&dangling)
            .expect("stat")
            .file_type()
            .is_symlink());
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn special_files_are_written_directly() {
        // /dev/null is a character device: renaming over it would replace it.
        write_atomically(Path::new("/dev/null"), |f| f.write_all(b"gone\n")).expect("written");
        let meta = fs::symlink_metadata("/dev/null").expect("stat");
        assert!(!meta.is_file(), "/dev/null was replaced by a regular file");
        // A FIFO: a reader on the other end gets the bytes; the FIFO stays.
        let dir = temp_dir("fifo");
        let fifo = dir.join("pipe.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let reader = {
                let fifo = fifo.clone();
                std::thread::spawn(move || fs::read_to_string(fifo).expect("read"))
            };
            write_atomically(&fifo, |f| f.write_all(b"through\n")).expect("written");
            assert_eq!(reader.join().expect("joined"), "through\n");
            assert!(!fs::symlink_metadata(&fifo).expect("stat").is_file());
        }
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn a_name_of_255_bytes_still_gets_a_temporary_file() {
        let dir = temp_dir("long");
        let name = format!("{}.obj", "é".repeat(125));
        assert_eq!(name.len(), 254);
        let target = dir.join(&name);
        write_atomically(&target, |f| f.write_all(b"ok\n")).expect("written");
        assert_eq!(fs::read_to_string(&target).expect("read"), "ok\n");
        assert_eq!(names(&dir), [name]);
        assert_eq!(short_prefix("éé", 3), "é");
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn a_directory_is_refused() {
        let dir = temp_dir("dir");
        let err = write_atomically(&dir, |f| f.write_all(b"x")).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("{}: is a directory", dir.display())
        );
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    /// A mesh without texture coordinates is written as before whatever the UV option; one
    /// with them gets `vt` and `f v/vt` unless the option is off; normals add `vn` and
    /// `f v/vt/vn` or `f v//vn`.
    #[test]
    fn texture_coordinates_and_normals_in_every_face_form() {
        use crate::uv::Uvs;
        use glam::DVec2;
        let plain = crate::PolygonMesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            [[0u32, 1, 2, 3]],
        );
        let text = |mesh: &crate::PolygonMesh, options: ObjWriteOptions| {
            let mut out = Vec::new();
            write_polygon_obj_with(mesh, &mut out, &options).expect("written");
            String::from_utf8(out).expect("text")
        };
        let positions = "v 0.0 0.0 0.0\nv 1.0 0.0 0.0\nv 1.0 1.0 0.0\nv 0.0 1.0 0.0\n";
        let on = ObjWriteOptions::default();
        for options in [on, on.with_uvs(false)] {
            assert_eq!(text(&plain, options), format!("{positions}f 1 2 3 4\n"));
        }
        let normals = "vn 0.0 0.0 1.0\n".repeat(4);
        assert_eq!(
            text(&plain, on.with_normals(true)),
            format!("{positions}{normals}f 1//1 2//2 3//3 4//4\n")
        );
        let mut textured = plain.clone();
        let coords = vec![
            DVec2::new(0.5, 0.25),
            DVec2::ZERO,
            DVec2::X,
            DVec2::new(0.1, 0.7),
        ];
        textured
            .set_uvs(Some(Uvs::new(coords, vec![1, 2, 0, 2]).expect("in range")))
            .expect("a vt per corner");
        let vt = "vt 0.5 0.25\nvt 0.0 0.0\nvt 1.0 0.0\nvt 0.1 0.7\n";
        assert_eq!(
            text(&textured, on),
            format!("{positions}{vt}f 1/2 2/3 3/1 4/3\n")
        );
        assert_eq!(
            text(&textured, on.with_normals(true)),
            format!("{positions}{vt}{normals}f 1/2/1 2/3/2 3/1/3 4/3/4\n")
        );
        assert_eq!(text(&textured, on.with_uvs(false)), text(&plain, on));
        let mut out = Vec::new();
        write_polygon_obj(&textured, &mut out).expect("written");
        assert_eq!(String::from_utf8(out).expect("text"), text(&textured, on));
        // The half-edge writer: normals only.
        let mesh = HalfEdgeMesh::try_from(&textured).expect("a quad");
        let mut out = Vec::new();
        write_obj_with(&mesh, &mut out, &on.with_normals(true)).expect("written");
        assert_eq!(
            String::from_utf8(out).expect("text"),
            text(&plain, on.with_normals(true))
        );
    }

    /// Buffers with UVs: `f32` values written as `f32`, normals in `f32`, bad UV buffers
    /// refused before anything is written.
    #[test]
    fn uv_buffers_are_written_and_checked() {
        let positions: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [0.0, 0.0, 3.0], [0.0, 0.1, 0.0]];
        let faces = FaceBuffers::Uniform {
            degree: 3,
            indices: &[0, 1, 2],
        };
        let values = [[0.1f32, 0.2], [0.3, 0.4]];
        let uvs = UvBuffers {
            values: &values,
            corners: &[1, 0, 1],
        };
        let on = ObjWriteOptions::default();
        let write = |uvs, options: ObjWriteOptions| {
            let mut out = Vec::new();
            write_buffers_obj_with(&positions, faces, uvs, &mut out, &options)
                .map(|()| String::from_utf8(out).expect("text"))
        };
        let v = "v 0.0 0.0 0.0\nv 0.0 0.0 3.0\nv 0.0 0.1 0.0\n";
        assert_eq!(
            write(Some(uvs), on).expect("written"),
            format!("{v}vt 0.1 0.2\nvt 0.3 0.4\nf 1/2 2/1 3/2\n")
        );
        assert_eq!(
            write(Some(uvs), on.with_normals(true)).expect("written"),
            format!(
                "{v}vt 0.1 0.2\nvt 0.3 0.4\n{}f 1/2/1 2/1/2 3/2/3\n",
                "vn -1.0 0.0 0.0\n".repeat(3)
            )
        );
        let mut plain = Vec::new();
        write_buffers_obj(&positions, faces, &mut plain).expect("written");
        let plain = String::from_utf8(plain).expect("text");
        assert_eq!(
            write(Some(uvs), on.with_uvs(false)).expect("written"),
            plain
        );
        assert_eq!(write(None, on).expect("written"), plain);
        for (bad, message) in [
            (
                UvBuffers {
                    values: &values,
                    corners: &[0, 1],
                },
                "2 texture-coordinate corners for 3 face corners",
            ),
            (
                UvBuffers {
                    values: &values,
                    corners: &[0, 1, 2],
                },
                "face corner 2 uses UV value 2, but there are 2",
            ),
        ] {
            let err = write(Some(bad), on).unwrap_err();
            assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
            assert_eq!(err.to_string(), message);
        }
    }

    /// `f32` coordinates come back as the same `f32` from the text, and inconsistent buffers
    /// are refused before anything is written.
    #[test]
    fn buffers_round_trip_in_f32_and_bad_buffers_are_refused() {
        let mut x = 0x2545_f491_u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            f32::from_bits(x & 0x7f7f_ffff) * if x & 1 == 0 { 1.0 } else { -1.0 }
        };
        let positions: Vec<[f32; 3]> = (0..300).map(|_| [next(), next(), next()]).collect();
        let indices: Vec<u32> = (0..300).collect();
        let mut out = Vec::new();
        let faces = FaceBuffers::Uniform {
            degree: 3,
            indices: &indices,
        };
        write_buffers_obj(&positions, faces, &mut out).expect("written");
        let text = String::from_utf8(out).expect("text");
        let read: Vec<[f32; 3]> = text
            .lines()
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let c: Vec<f32> = l.split(' ').map(|t| t.parse().expect("f32")).collect();
                [c[0], c[1], c[2]]
            })
            .collect();
        assert_eq!(read, positions);
        assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 100);
        let polygons = FaceBuffers::Polygons {
            offsets: &[0, 3, 7],
            indices: &indices[..7],
        };
        let mut out = Vec::new();
        write_buffers_obj(&positions, polygons, &mut out).expect("written");
        assert!(String::from_utf8(out)
            .expect("text")
            .ends_with("f 1 2 3\nf 4 5 6 7\n"));
        for bad in [
            FaceBuffers::Uniform {
                degree: 4,
                indices: &indices[..6],
            },
            FaceBuffers::Uniform {
                degree: 0,
                indices: &[],
            },
            FaceBuffers::Polygons {
                offsets: &[0, 5, 3],
                indices: &indices[..6],
            },
            FaceBuffers::Uniform {
                degree: 3,
                indices: &[0, 1, 300],
            },
        ] {
            let mut out = Vec::new();
            let err = write_buffers_obj(&positions, bad, &mut out).unwrap_err();
            assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput, "{bad:?}");
            assert!(out.is_empty());
        }
    }
}
