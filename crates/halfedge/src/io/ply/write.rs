//! Binary little-endian PLY writing.

use std::io::{BufWriter, Write};

use super::super::buffers::{FaceBuffers, MeshBuffers, ObjWriteOptions, UvBuffers};
use crate::polygon::PolygonMesh;
use crate::Scalar;

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
    let vertex_uvs = uvs.and_then(|u| per_vertex_uvs(&u, &list, positions.len()));
    let face_uvs = uvs.filter(|_| vertex_uvs.is_none());
    let byte_colors = mesh.colors.map(|colors| {
        colors
            .iter()
            .flatten()
            .all(|c| (0.0..=1.0).contains(&c.to_f64()))
    });
    let degree = list.iter().map(|f| f.len()).max().unwrap_or(0);
    let wide_texcoord = degree > 127;
    if face_uvs.is_some() && u32::try_from(2 * degree).is_err() {
        let what = format!("a face of {degree} corners has too many texture coordinates for PLY");
        return Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, what));
    }

    let float = if std::mem::size_of::<T>() == 4 {
        "float"
    } else {
        "double"
    };
    let mut w = BufWriter::with_capacity(1 << 16, writer);
    write!(
        w,
        "ply\nformat binary_little_endian 1.0\ncomment subcount\nelement vertex {}\n",
        positions.len()
    )?;
    for name in ["x", "y", "z"] {
        writeln!(w, "property {float} {name}")?;
    }
    if let Some(bytes) = byte_colors {
        let ty = if bytes { "uchar" } else { "float" };
        for name in ["red", "green", "blue"] {
            writeln!(w, "property {ty} {name}")?;
        }
    }
    if normals.is_some() {
        for name in ["nx", "ny", "nz"] {
            writeln!(w, "property {float} {name}")?;
        }
    }
    if vertex_uvs.is_some() {
        writeln!(w, "property {float} s\nproperty {float} t")?;
    }
    writeln!(w, "element face {}", list.len())?;
    let count = if degree > 255 { "uint" } else { "uchar" };
    // Indices beyond `i32::MAX` (more than 2^31 vertices) need `uint`.
    let wide_index = positions.len() > i32::MAX as usize + 1;
    let index = if wide_index { "uint" } else { "int" };
    writeln!(w, "property list {count} {index} vertex_indices")?;
    if face_uvs.is_some() {
        let count = if wide_texcoord { "uint" } else { "uchar" };
        writeln!(w, "property list {count} {float} texcoord")?;
    }
    writeln!(w, "end_header")?;

    for (v, p) in positions.iter().enumerate() {
        for &x in p {
            put(&mut w, x)?;
        }
        match (mesh.colors, byte_colors) {
            (Some(colors), Some(true)) => {
                let rgb = colors[v].map(|c| (c.to_f64().clamp(0.0, 1.0) * 255.0).round() as u8);
                w.write_all(&rgb)?;
            }
            (Some(colors), _) => {
                for &c in &colors[v] {
                    w.write_all(&(c.to_f64() as f32).to_le_bytes())?;
                }
            }
            (None, _) => {}
        }
        if let Some(normals) = &normals {
            for n in normals[v].to_array() {
                put(&mut w, T::from_f64(n))?;
            }
        }
        if let Some(uvs) = &vertex_uvs {
            for &t in &uvs[v] {
                put(&mut w, t)?;
            }
        }
    }
    let mut corner = 0;
    for face in &list {
        let k = face.len();
        if degree > 255 {
            w.write_all(&(k as u32).to_le_bytes())?;
        } else {
            w.write_all(&[k as u8])?;
        }
        for &v in *face {
            match wide_index {
                true => w.write_all(&v.to_le_bytes())?,
                false => w.write_all(&(v as i32).to_le_bytes())?,
            }
        }
        if let Some(uvs) = &face_uvs {
            if wide_texcoord {
                w.write_all(&(2 * k as u32).to_le_bytes())?;
            } else {
                w.write_all(&[2 * k as u8])?;
            }
            for &t in &uvs.corners[corner..corner + k] {
                for &x in &uvs.values[t as usize] {
                    put(&mut w, x)?;
                }
            }
        }
        corner += k;
    }
    w.flush()
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
    let positions: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.to_array()).collect();
    let offsets: Vec<u32> = mesh
        .face_offsets()
        .iter()
        .map(|&o| u32::try_from(o))
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| {
            let what = format!(
                "{} face corners do not fit 32-bit offsets",
                mesh.n_corners()
            );
            std::io::Error::new(std::io::ErrorKind::InvalidInput, what)
        })?;
    let faces = FaceBuffers::Polygons {
        offsets: &offsets,
        indices: mesh.face_indices(),
    };
    let uvs = mesh
        .uvs()
        .filter(|u| options.uvs && u.corners().len() == mesh.n_corners());
    let values: Vec<[f64; 2]> = uvs.map_or(Vec::new(), |u| {
        u.coords().iter().map(|c| c.to_array()).collect()
    });
    let mut buffers = MeshBuffers::new(&positions, faces);
    if let Some(u) = uvs {
        buffers = buffers.with_uvs(UvBuffers {
            values: &values,
            corners: u.corners(),
        });
    }
    if let Some(colors) = mesh.colors() {
        buffers = buffers.with_colors(colors);
    }
    write_mesh_buffers_ply(&buffers, writer, options)
}

/// A UV value per vertex when every vertex's corners agree on theirs (bit for bit), `0, 0`
/// at vertices no face uses; `None` when some vertex has two (a seam).
pub(super) fn per_vertex_uvs<T: Scalar>(
    uvs: &UvBuffers<'_, T>,
    faces: &[&[u32]],
    n_vertices: usize,
) -> Option<Vec<[T; 2]>> {
    const UNUSED: u32 = u32::MAX;
    let bits = |t: u32| uvs.values[t as usize].map(|x| x.to_f64().to_bits());
    let mut value = vec![UNUSED; n_vertices];
    for (&v, &t) in faces.iter().flat_map(|f| f.iter()).zip(uvs.corners) {
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

/// Writes `x` little-endian, as `f32` or `f64` like `T`.
pub(super) fn put<T: Scalar>(w: &mut impl Write, x: T) -> std::io::Result<()> {
    if std::mem::size_of::<T>() == 4 {
        w.write_all(&(x.to_f64() as f32).to_le_bytes())
    } else {
        w.write_all(&x.to_f64().to_le_bytes())
    }
}
