//! Binary little-endian PLY writing.

use std::io::Write;

use glam::DVec3;

use super::super::buffers::{check_faces, FaceList, MeshBuffers, ObjWriteOptions, UvBuffers};
use super::super::write::chunks::ChunkWriter;
use crate::polygon::PolygonMesh;
use crate::{normals, Scalar};

/// Vertex records per chunk (at least 12 bytes each).
const VERTEX_CHUNK: usize = 1 << 15;

/// Face records per chunk (at least 13 bytes each).
const FACE_CHUNK: usize = 1 << 16;

/// Writes a mesh from caller-owned buffers as binary little-endian PLY: the vertex element
/// (`x y z` as `double`, or `float` when `T` is `f32`; the colors as `uchar` when every
/// component is in `[0, 1]` (rounded `c * 255`), else as `float`, as MeshLab writes them; with
/// [`ObjWriteOptions::normals`], `nx ny nz`, the area-weighted vertex normals of the faces
/// (the limit normals with [`MeshBuffers::tangents`](crate::io::MeshBuffers::tangents));
/// with [`ObjWriteOptions::uvs`] and texture coordinates without seams (one UV value per
/// vertex across its corners), `s t`, 0 at vertices no face uses) and the face element
/// (`vertex_indices`, an `int` per corner after a `uchar` count, `uint` for a face of more
/// than 255 corners; texture coordinates with seams as `texcoord`, `u v` per corner, after a
/// `uchar` count, `uint` for a face of more than 127 corners). Groups are not written.
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] as [`write_mesh_buffers_obj`](crate::io::write_mesh_buffers_obj)
/// (nothing is written then); any error of the writer.
///
/// # Example
///
/// ```
/// use halfedge::io::{read_ply_from, write_mesh_buffers_ply, FaceBuffers, MeshBuffers, ObjWriteOptions};
/// let positions = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let faces = FaceBuffers::Uniform { degree: 3, indices: &[0, 1, 2] };
/// let mut out = Vec::new();
/// write_mesh_buffers_ply(&MeshBuffers::new(&positions, faces), &mut out, &ObjWriteOptions::default())?;
/// assert!(out.starts_with(b"ply\nformat binary_little_endian 1.0\ncomment subcount\nelement vertex 3\nproperty float x\n"));
/// let mesh = read_ply_from(out.as_slice(), "out.ply")?;
/// assert_eq!(mesh.face(0), &[0, 1, 2]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_mesh_buffers_ply<T: Scalar>(
    mesh: &MeshBuffers<'_, T>,
    writer: impl Write,
    options: &ObjWriteOptions,
) -> std::io::Result<()> {
    let super::super::buffers::Written { list, uvs, normals } = mesh.prepare_write(options)?;
    let positions = mesh.positions;
    let ply = Ply {
        positions: (positions.len(), |v: usize| positions[v]),
        colors: mesh.colors,
        normals,
        uvs,
        list,
    };
    ply.write(writer, options.threads)
}

/// A mesh as the PLY writer takes it, checked: the number of positions and position `v`,
/// colors, normals, UVs (values and a value per corner) and faces.
struct Ply<'a, T, P> {
    positions: (usize, P),
    colors: Option<&'a [[T; 3]]>,
    normals: Option<Vec<DVec3>>,
    uvs: Option<UvBuffers<'a, T>>,
    list: FaceList<'a>,
}

impl<T: Scalar, P: Fn(usize) -> [T; 3] + Sync> Ply<'_, T, P> {
    /// Writes the header and the records ([`write_mesh_buffers_ply`]), in chunks on
    /// `threads` ([`ObjWriteOptions::threads`]).
    fn write(self, writer: impl Write, threads: usize) -> std::io::Result<()> {
        let Ply {
            positions: (n_positions, position),
            colors,
            normals,
            uvs,
            list,
        } = self;
        let vertex_uvs = uvs.and_then(|u| per_vertex_uvs(&u, list, n_positions));
        let face_uvs = uvs.filter(|_| vertex_uvs.is_none());
        let byte_colors = colors.map(|colors| {
            colors
                .iter()
                .flatten()
                .all(|c| (0.0..=1.0).contains(&c.to_f64()))
        });
        let degree = list.max_degree();
        let wide_texcoord = degree > 127;
        if face_uvs.is_some() && u32::try_from(2 * degree).is_err() {
            let what =
                format!("a face of {degree} corners has too many texture coordinates for PLY");
            return Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, what));
        }

        let float = if std::mem::size_of::<T>() == 4 {
            "float"
        } else {
            "double"
        };
        let mut header = b"ply\nformat binary_little_endian 1.0\ncomment subcount\n".to_vec();
        writeln!(header, "element vertex {n_positions}")?;
        for name in ["x", "y", "z"] {
            writeln!(header, "property {float} {name}")?;
        }
        if let Some(bytes) = byte_colors {
            let ty = if bytes { "uchar" } else { "float" };
            for name in ["red", "green", "blue"] {
                writeln!(header, "property {ty} {name}")?;
            }
        }
        if normals.is_some() {
            for name in ["nx", "ny", "nz"] {
                writeln!(header, "property {float} {name}")?;
            }
        }
        if vertex_uvs.is_some() {
            writeln!(header, "property {float} s\nproperty {float} t")?;
        }
        writeln!(header, "element face {}", list.len())?;
        let count = if degree > 255 { "uint" } else { "uchar" };
        // Indices beyond `i32::MAX` (more than 2^31 vertices) need `uint` (the same bytes).
        let wide_index = n_positions > i32::MAX as usize + 1;
        let index = if wide_index { "uint" } else { "int" };
        writeln!(header, "property list {count} {index} vertex_indices")?;
        if face_uvs.is_some() {
            let count = if wide_texcoord { "uint" } else { "uchar" };
            writeln!(header, "property list {count} {float} texcoord")?;
        }
        writeln!(header, "end_header")?;

        let items = n_positions + list.len();
        let mut w = ChunkWriter::new(writer, threads, items)?;
        w.write_all(&header)?;
        w.section(n_positions, VERTEX_CHUNK, |range, out| {
            for v in range {
                for x in position(v) {
                    put(out, x);
                }
                match (colors, byte_colors) {
                    (Some(colors), Some(true)) => {
                        let rgb =
                            colors[v].map(|c| (c.to_f64().clamp(0.0, 1.0) * 255.0).round() as u8);
                        out.extend_from_slice(&rgb);
                    }
                    (Some(colors), _) => {
                        for &c in &colors[v] {
                            out.extend_from_slice(&(c.to_f64() as f32).to_le_bytes());
                        }
                    }
                    (None, _) => {}
                }
                if let Some(normals) = &normals {
                    for n in normals[v].to_array() {
                        put(out, T::from_f64(n));
                    }
                }
                if let Some(uvs) = &vertex_uvs {
                    for &t in &uvs[v] {
                        put(out, t);
                    }
                }
            }
        })?;
        w.section(list.len(), FACE_CHUNK, |range, out| {
            for f in range {
                let face = list.face(f);
                let k = face.len();
                if degree > 255 {
                    out.extend_from_slice(&(k as u32).to_le_bytes());
                } else {
                    out.push(k as u8);
                }
                // An `int` index below 2^31 and a `uint` have the same bytes.
                for &v in face {
                    out.extend_from_slice(&v.to_le_bytes());
                }
                if let Some(uvs) = &face_uvs {
                    if wide_texcoord {
                        out.extend_from_slice(&(2 * k as u32).to_le_bytes());
                    } else {
                        out.push(2 * k as u8);
                    }
                    let corner = list.first_corner(f);
                    for &t in &uvs.corners[corner..corner + k] {
                        for &x in &uvs.values[t as usize] {
                            put(out, x);
                        }
                    }
                }
            }
        })?;
        w.flush()
    }
}

/// Writes a face list as binary PLY, as [`write_mesh_buffers_ply`] writes buffers: every
/// position (used or not), the faces, the colors and (with [`ObjWriteOptions::uvs`]) the
/// texture coordinates of the mesh; its tags and groups are not written.
///
/// # Errors
///
/// Any error of the writer; [`std::io::ErrorKind::InvalidInput`] for a mesh of more than
/// `u32::MAX` face corners.
///
/// # Example
///
/// ```
/// use halfedge::io::{read_ply_from, write_polygon_ply, ObjWriteOptions};
/// let cube = halfedge::shapes::cube();
/// let mut out = Vec::new();
/// write_polygon_ply(&cube, &mut out, &ObjWriteOptions::default())?;
/// assert_eq!(read_ply_from(out.as_slice(), "cube.ply")?, cube);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_polygon_ply(
    mesh: &PolygonMesh,
    writer: impl Write,
    options: &ObjWriteOptions,
) -> std::io::Result<()> {
    if u32::try_from(mesh.n_corners()).is_err() {
        let what = format!(
            "{} face corners do not fit 32-bit offsets",
            mesh.n_corners()
        );
        return Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, what));
    }
    let list = FaceList::of_polygon_mesh(mesh);
    let uvs = mesh
        .uvs()
        .filter(|u| options.uvs && u.corners().len() == mesh.n_corners());
    let values: Vec<[f64; 2]> = uvs.map_or(Vec::new(), |u| {
        u.coords().iter().map(|c| c.to_array()).collect()
    });
    let uvs = uvs.map(|u| UvBuffers {
        values: &values,
        corners: u.corners(),
    });
    let positions = &mesh.positions;
    let colors = mesh.colors();
    let uv_counts = uvs.map(|u| (u.corners, u.values.len()));
    check_faces(
        list,
        positions.len(),
        colors.map(<[_]>::len),
        None,
        uv_counts,
    )?;
    let normals = options
        .normals
        .then(|| normals::vertex_normals(positions, mesh.faces()));
    let ply = Ply {
        positions: (positions.len(), |v: usize| positions[v].to_array()),
        colors,
        normals,
        uvs,
        list,
    };
    ply.write(writer, options.threads)
}

/// A UV value per vertex when every vertex's corners agree on theirs (bit for bit), `0, 0`
/// at vertices no face uses; `None` when some vertex has two (a seam).
pub(super) fn per_vertex_uvs<T: Scalar>(
    uvs: &UvBuffers<'_, T>,
    faces: FaceList<'_>,
    n_vertices: usize,
) -> Option<Vec<[T; 2]>> {
    const UNUSED: u32 = u32::MAX;
    let bits = |t: u32| uvs.values[t as usize].map(|x| x.to_f64().to_bits());
    let mut value = vec![UNUSED; n_vertices];
    for (&v, &t) in faces.indices().iter().zip(uvs.corners) {
        let first = &mut value[v as usize];
        if *first == UNUSED {
            *first = t;
        } else if *first != t && bits(*first) != bits(t) {
            return None;
        }
    }
    Some(
        value
            .into_iter()
            .map(|t| match t {
                UNUSED => [T::ZERO; 2],
                t => uvs.values[t as usize],
            })
            .collect(),
    )
}

/// Appends `x` little-endian, as `f32` or `f64` like `T`.
#[inline]
fn put<T: Scalar>(out: &mut Vec<u8>, x: T) {
    if std::mem::size_of::<T>() == 4 {
        out.extend_from_slice(&(x.to_f64() as f32).to_le_bytes());
    } else {
        out.extend_from_slice(&x.to_f64().to_le_bytes());
    }
}
