//! OBJ writing into any [`Write`]: half-edge meshes, face lists and caller-owned buffers.
//! Files (atomic replacement, `-`, signals) are the front ends' (`driver::output`).
//!
//! The text is formatted in chunks of lines ([`chunks`]), in parallel with
//! [`ObjWriteOptions::threads`], each coordinate by [`float_text`] (std's `{:?}` text, byte
//! for byte, faster): the same bytes for every thread count.

pub(crate) mod chunks;
pub(crate) mod float_text;

use std::io::Write;
use std::ops::Range;

use glam::DVec3;

use self::chunks::ChunkWriter;
use self::float_text::{push, push_u64};
use super::buffers::{FaceBuffers, FaceList, MeshBuffers, ObjWriteOptions, UvBuffers, Written};
use crate::groups::{FaceGroups, Statement};
use crate::mesh::{FaceId, HalfEdgeMesh};
use crate::normals;
use crate::polygon::PolygonMesh;
use crate::Scalar;

/// `v` and `vt` lines per chunk (about half a megabyte of `f64` text).
const VERTEX_CHUNK: usize = 1 << 13;

/// `f` lines per chunk.
const FACE_CHUNK: usize = 1 << 14;

/// Writes a mesh as OBJ text: one `v x y z` line per vertex, then one `f` line per face
/// (1-based indices, n-gons kept), nothing else.
///
/// Coordinates are written with Rust's shortest round-trip formatting, so reading the file
/// back gives the same `f64` values. The text goes to the writer in chunks of about half a
/// megabyte: it needs no `BufWriter`.
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
    let normals = options.normals.then(|| {
        let lists = mesh
            .faces()
            .map(|f| mesh.face_vertices(f).map(|v| v.0).collect::<Vec<_>>());
        normals::vertex_normals(mesh.positions(), lists)
    });
    let positions = mesh.positions();
    let text = ObjText {
        positions: (positions.len(), |i: usize| positions[i].to_array()),
        colors: None,
        texcoords: None::<TexCoords<'_, NoUv, fn(usize) -> usize>>,
        normals: normals.as_deref(),
        faces: HalfEdgeFaces(mesh),
        groups: None,
    };
    text.write(writer, options.threads)
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
/// Any error of the writer; [`std::io::ErrorKind::InvalidInput`] when the mesh's colors are
/// not one per position or its groups not one per face (its public `positions` changed
/// after they were set); nothing is written then.
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
    let offsets = mesh.face_offsets();
    let texcoords = uvs.map(|u| {
        let coords = u.coords();
        TexCoords {
            values: (coords.len(), move |i: usize| coords[i].to_array()),
            corners: u.corners(),
            first_corner: move |f: usize| offsets[f],
        }
    });
    let normals = options
        .normals
        .then(|| normals::vertex_normals(&mesh.positions, mesh.faces()));
    // `positions` is a public field: colors or groups that no longer fit are refused, not
    // written short.
    let invalid = |what: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, what);
    if let Some(colors) = mesh.colors().filter(|c| c.len() != mesh.n_vertices()) {
        let n = mesh.n_vertices();
        return Err(invalid(format!(
            "{} colors for {n} positions",
            colors.len()
        )));
    }
    if let Some(groups) = mesh.groups().filter(|g| g.n_faces() != mesh.n_faces()) {
        let n = mesh.n_faces();
        return Err(invalid(format!(
            "groups of {} faces for {n} faces",
            groups.n_faces()
        )));
    }
    let positions = &mesh.positions;
    let text = ObjText {
        positions: (positions.len(), |i: usize| positions[i].to_array()),
        colors: mesh.colors(),
        texcoords,
        normals: normals.as_deref(),
        faces: FaceList::of_polygon_mesh(mesh),
        groups: mesh.groups(),
    };
    text.write(writer, options.threads)
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
/// `f64`, written in `T`; the limit normals with [`MeshBuffers::tangents`]) as `vn` lines and
/// `f v/vt/vn` or `f v//vn`. Without either, the
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
    let mut mesh = MeshBuffers::new(positions, faces);
    mesh.uvs = uvs;
    write_mesh_buffers_obj(&mesh, writer, options)
}

/// Writes a mesh from caller-owned buffers as OBJ text ([`write_buffers_obj_with`], with
/// its colors on the `v` lines and its groups before the faces they change at).
///
/// # Errors
///
/// As [`write_buffers_obj_with`], and [`std::io::ErrorKind::InvalidInput`] when the colors
/// are not one per position or the groups not one per face; nothing is written then.
pub fn write_mesh_buffers_obj<T: Scalar>(
    mesh: &MeshBuffers<'_, T>,
    writer: impl Write,
    options: &ObjWriteOptions,
) -> std::io::Result<()> {
    let Written { list, uvs, normals } = mesh.prepare_write(options)?;
    let positions = mesh.positions;
    let texcoords = uvs.map(|u| TexCoords {
        values: (u.values.len(), move |i: usize| u.values[i]),
        corners: u.corners,
        first_corner: move |f: usize| list.first_corner(f),
    });
    let text = ObjText {
        positions: (positions.len(), |i: usize| positions[i]),
        colors: mesh.colors,
        texcoords,
        normals: normals.as_deref(),
        faces: list,
        groups: mesh.groups,
    };
    text.write(writer, options.threads)
}

/// The faces [`ObjText`] writes, by index.
trait Faces: Sync {
    /// The number of faces.
    fn len(&self) -> usize;
    /// Face `f`'s vertices (0-based).
    fn corners(&self, f: usize) -> impl Iterator<Item = u32> + '_;
}

impl Faces for FaceList<'_> {
    fn len(&self) -> usize {
        FaceList::len(self)
    }

    #[inline]
    fn corners(&self, f: usize) -> impl Iterator<Item = u32> + '_ {
        self.face(f).iter().copied()
    }
}

/// A half-edge mesh's faces, each from its half-edge cycle.
struct HalfEdgeFaces<'a>(&'a HalfEdgeMesh);

impl Faces for HalfEdgeFaces<'_> {
    fn len(&self) -> usize {
        self.0.n_faces()
    }

    #[inline]
    fn corners(&self, f: usize) -> impl Iterator<Item = u32> + '_ {
        self.0.face_vertices(FaceId(f as u32)).map(|v| v.0)
    }
}

/// The texture coordinates [`ObjText`] writes: the number of values and value `i`, the value
/// of each face corner (checked by the caller), and where face `f`'s corners start among
/// them.
struct TexCoords<'a, V, C> {
    values: (usize, V),
    corners: &'a [u32],
    first_corner: C,
}

/// The type of absent texture coordinates.
type NoUv = fn(usize) -> [f64; 2];

/// A mesh as the one OBJ text writer takes it: the number of positions and position `i`,
/// a color per vertex (written on its `v` line), texture coordinates, normals (written in
/// `T`), the faces, and their groups (a statement line before each face whose value
/// differs from the face written before, the `mtllib` lines before the first `v`).
struct ObjText<'a, T, P, V, C, F> {
    positions: (usize, P),
    colors: Option<&'a [[T; 3]]>,
    texcoords: Option<TexCoords<'a, V, C>>,
    normals: Option<&'a [DVec3]>,
    faces: F,
    groups: Option<&'a FaceGroups>,
}

/// Appends `v` and then ` x y z` (each coordinate's shortest round-trip text, std's `{:?}`).
#[inline]
fn push_values<T: Scalar>(out: &mut Vec<u8>, values: &[T]) {
    for &x in values {
        out.push(b' ');
        push(out, x);
    }
}

impl<T, P, V, C, F> ObjText<'_, T, P, V, C, F>
where
    T: Scalar,
    P: Fn(usize) -> [T; 3] + Sync,
    V: Fn(usize) -> [T; 2] + Sync,
    C: Fn(usize) -> usize + Sync,
    F: Faces,
{
    /// Writes the text: the `mtllib` lines, `v` lines, the `vt` lines of the texture
    /// coordinates, the `vn` lines of the normals (in `T`), then 1-based `f` lines: `f v`,
    /// `f v/vt`, `f v//vn` or `f v/vt/vn`, each section in chunks on `threads`
    /// ([`ObjWriteOptions::threads`]).
    fn write(&self, writer: impl Write, threads: usize) -> std::io::Result<()> {
        let (n, position) = &self.positions;
        let n_uvs = self.texcoords.as_ref().map_or(0, |t| t.values.0);
        let n_normals = self.normals.map_or(0, <[DVec3]>::len);
        let items = n + n_uvs + n_normals + self.faces.len();
        let mut w = ChunkWriter::new(writer, threads, items)?;
        if let Some(groups) = self.groups {
            let mut head = Vec::new();
            for line in groups.mtllib() {
                head.extend_from_slice(line.as_bytes());
                head.push(b'\n');
            }
            w.write_all(&head)?;
        }
        w.section(*n, VERTEX_CHUNK, |range, out| {
            for i in range {
                out.push(b'v');
                push_values(out, &position(i));
                if let Some(colors) = self.colors {
                    push_values(out, &colors[i]);
                }
                out.push(b'\n');
            }
        })?;
        if let Some(TexCoords { values, .. }) = &self.texcoords {
            w.section(values.0, VERTEX_CHUNK, |range, out| {
                for i in range {
                    out.extend_from_slice(b"vt");
                    push_values(out, &(values.1)(i));
                    out.push(b'\n');
                }
            })?;
        }
        if let Some(normals) = self.normals {
            w.section(normals.len(), VERTEX_CHUNK, |range, out| {
                for n in &normals[range] {
                    out.extend_from_slice(b"vn");
                    push_values(out, &n.to_array().map(T::from_f64));
                    out.push(b'\n');
                }
            })?;
        }
        w.section(self.faces.len(), FACE_CHUNK, |range, out| {
            self.face_lines(range, out);
        })?;
        w.flush()
    }

    /// The `f` lines of faces `range`, with the statement lines before them.
    fn face_lines(&self, range: Range<usize>, out: &mut Vec<u8>) {
        let with_normals = self.normals.is_some();
        let mut vts = self
            .texcoords
            .as_ref()
            .map(|t| t.corners[(t.first_corner)(range.start)..].iter());
        // The class of the face written before.
        let mut class = range
            .start
            .checked_sub(1)
            .and_then(|f| self.groups?.class(f));
        for f in range {
            if let Some(groups) = self.groups {
                push_statements(out, groups, &mut class, f);
            }
            out.push(b'f');
            for v in self.faces.corners(f) {
                let v = u64::from(v) + 1;
                out.push(b' ');
                push_u64(out, v);
                match (vts.as_mut().and_then(Iterator::next), with_normals) {
                    (None, false) => {}
                    (None, true) => {
                        out.extend_from_slice(b"//");
                        push_u64(out, v);
                    }
                    (Some(&t), normal) => {
                        out.push(b'/');
                        push_u64(out, u64::from(t) + 1);
                        if normal {
                            out.push(b'/');
                            push_u64(out, v);
                        }
                    }
                }
            }
            out.push(b'\n');
        }
    }
}

/// The statement lines before face `f`: those whose value differs from the face written
/// before (`class`, updated).
fn push_statements(out: &mut Vec<u8>, groups: &FaceGroups, class: &mut Option<u32>, f: usize) {
    let Some(now) = groups.class(f) else {
        return;
    };
    if *class == Some(now) {
        return;
    }
    for statement in Statement::ALL {
        if let Some(value) = groups.change(*class, now, statement) {
            let value = value.unwrap_or(statement.unset());
            out.extend_from_slice(statement.keyword().as_bytes());
            if !value.is_empty() {
                out.push(b' ');
                out.extend_from_slice(value.as_bytes());
            }
            out.push(b'\n');
        }
    }
    *class = Some(now);
}

#[cfg(test)]
mod tests {
    use super::*;

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
