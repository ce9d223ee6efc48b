//! Reading and writing meshes (OBJ, OFF, PLY), keeping polygons as they are.
//!
//! # Why OBJ is parsed here and not with tobj
//!
//! The project's owner named `tobj` as the OBJ loader, and it is a good loader for rendering,
//! but it loses exactly what this crate needs: it splits the file into one model per
//! `o`/`g` group and renumbers the vertices of each model (groups that share vertices come
//! back as separate meshes), it drops vertices no face references (we must report them), and
//! its `LoadError` carries no line number (we must name the line). Pre-scanning the file to
//! recover all that would mean parsing it twice. So this module reads the part of OBJ that
//! matters for topology and texturing itself — `v` and `vt` lines and the first two fields
//! of each `f` corner (`v`, `v/vt`, `v/vt/vn`, `v//vn`, negative indices) — in one streaming
//! pass over a `BufRead` (no whole-file string), with an error naming the file and line (and,
//! for a texture-coordinate index, the corner) for every bad token; it keeps vertex colors
//! (`v x y z r g b`), OpenSubdiv's tags (below) and the grouping statements (`mtllib`,
//! `usemtl`, `o`, `g`, `s`: [`crate::groups`]), and counts every other kind of line (`vn`,
//! `vp`, `l`, `p`, ...) in [`PolygonMesh::uncarried`]. tobj is kept as an independent cross-check: the test suite
//! loads every mesh of the shared folder with both and compares positions, faces and each
//! corner's texture coordinate.
//!
//! # Texture coordinates (OBJ)
//!
//! `vt u v [w]` lines are read as `f64` `(u, v)` (`w` is ignored), and each corner's `vt`
//! field becomes its texture coordinate ([`crate::uv`]): when **every** face corner of the
//! file names one, the mesh has [`uvs`](PolygonMesh::uvs) (unused `vt` lines are kept and
//! counted by [`crate::uv::Uvs::unreferenced`]). A file where only some corners name one is
//! read without UVs, not refused: [`PolygonMesh::partial_uvs`] says how many do ("N of M face
//! corners have texture coordinates: no UV layout"). A file with `vt` lines that no corner
//! uses has no UVs and nothing partial. A `vt` index is 1-based, or negative counting back
//! from the `vt` lines read so far, and may name a later line; one that is not a valid index
//! or names no `vt` of the file is an error naming the file, line and corner
//! ([`ParseError::InvalidTexCoordIndex`], [`ParseError::TexCoordIndexTooLarge`],
//! [`ParseError::TexCoordIndexOutOfRange`]), and a
//! `vt` line with fewer than two values is [`ParseError::MissingTexCoords`]. Normals (`vn`,
//! the third corner field) are not read: a subdivided surface needs new ones. OFF files have
//! no texture coordinates.
//!
//! OFF (`OFF`, `COFF`, `NOFF`, `CNOFF` with ASCII data) is read the same way. OFF has no tags:
//! an OFF mesh's [`PolygonMesh::tags`] are always empty.
//!
//! # Tags (OBJ)
//!
//! OpenSubdiv's shapes carry creases, corners, holes and subdivision options as tag lines,
//! `t NAME nInts/nFloats/nStrings ints floats strings`, read by default into the mesh's
//! [`tags`](PolygonMesh::tags) ([`crate::tags::Tags`]) as OpenSubdiv's shape loader
//! interprets them. Indices in tags are **0-based** (unlike `f` lines).
//!
//! | tag | values | meaning |
//! |---|---|---|
//! | `crease` | `2k/1/0` or `2k/k/0` | vertex pairs `a b c d ...` are the edges (a,b), (c,d), ...; one sharpness for all pairs or one per pair |
//! | `corner` | `k/1/0` or `k/k/0` | vertex sharpness, one for all vertices or one per vertex |
//! | `hole` | `k/0/0` | face indices |
//! | `interpolateboundary` | `1/0/0` | 0 none, 1 edge-and-corner, 2 edge-only ([`crate::tags::BoundaryInterpolation`]) |
//! | `facevaryinginterpolateboundary` | `1/0/0` | 0-5: none, corners-only, corners-plus1, corners-plus2, boundaries, all |
//! | `creasemethod` | `0/0/1` | `normal` (uniform) or `chaikin` |
//! | `smoothtriangles` | `0/0/1` | `catmark` or `smooth` |
//!
//! A later crease or corner on the same edge or vertex replaces the earlier one, a later
//! option tag the earlier one. Any other tag name (`vertexedit`, `facevaryingpropagatecorners`,
//! ...) is not interpreted: the reader returns each such name with its number of lines
//! ([`PolygonMesh::ignored_tags`]) and prints nothing. The reader is deliberately stricter
//! than OpenSubdiv's (which skips or aborts): every tag line must follow the grammar (the
//! counts must match the values on the line), a known tag must have the form the table gives
//! with valid values (integers, sharpness a finite `f64` `>= 0`, clamped to
//! [`crate::tags::INFINITELY_SHARP`] as OpenSubdiv clamps, an option value in range), and its
//! vertices, faces and edges must exist in the file (a crease's two vertices must be the ends
//! of a side of some face); otherwise the read fails with [`Error::Parse`] naming the file and
//! the tag's line ([`ParseError::TagIncomplete`], [`ParseError::TagCounts`], [`ParseError::TagValueCount`],
//! [`ParseError::TagForm`], [`ParseError::TagOption`], [`ParseError::TagSharpness`],
//! [`ParseError::Tag`], ...). [`ReadOptions::without_tags`] skips `t` lines unread, as this
//! crate did before it read tags. Text from the file echoed in a message (a token, a tag's
//! name, an ignored tag's name) has its control characters escaped ([`escape_controls`]).
//!
//! # PLY
//!
//! [`read_ply`] (and [`read_mesh`] for `.ply`, any case) reads `ascii 1.0`,
//! `binary_little_endian 1.0` and `binary_big_endian 1.0` in one streaming pass (types `char`
//! to `double` and `int8` to `float64`). Of the `vertex` element, `x y z` (any numeric type,
//! in `f64`) are the positions, in file order, used or not; `red green blue`, when all three
//! are there, the [`PolygonMesh::colors`] (`uchar` scaled to 0-1 as `c / 255`, other types
//! kept as read); `s t`, `u v` or `texture_u texture_v` a UV value per vertex
//! ([`PolygonMesh::uvs`]). Of the `face` element, the list `vertex_indices` (or
//! `vertex_index`) gives the corners in file order, and a list `texcoord` (`u v` per corner,
//! as MeshLab writes it) a UV value per corner, equal `(u, v)` at one vertex shared (the UV
//! layout's values); these win over
//! per-vertex ones. Every other element and property (normals among them) is skipped and
//! listed in [`PolygonMesh::uncarried`] (`` 12 `edge` elements ``, `` 500 values of `vertex`
//! property `nx` ``). A problem in the header is [`Error::Parse`] naming its line; one in the
//! data is [`Error::PlyData`] naming the element, its 0-based index and, for a value, the
//! property (`bunny.ply: face 12: vertex index 900 is out of range (the file has 500
//! vertices)`). The memory guards are OBJ's (below): a header's counts preallocate at most
//! 65,536 elements, a list holds at most 16 Mi items, and everything kept counts against the
//! budget ([`Error::MeshTooLarge`] names the data's line in ASCII, in binary data the line
//! after `end_header`, where the data starts). [`write_polygon_ply`] and
//! [`write_mesh_buffers_ply`] write binary little-endian PLY: positions, colors (`uchar` when
//! every component is in 0-1, else `float`), normals and texture coordinates on request
//! ([`ObjWriteOptions`]: `s t` per vertex without seams, else a `texcoord` list per face),
//! faces as `vertex_indices`; groups are not written.
//!
//! # Memory
//!
//! Everything a reader keeps grows inside its budget (half of
//! [`ReadOptions::available_bytes`], the memory the caller says the process may still
//! allocate; no budget without it): the mesh, the texture coordinates, the tags (a tag line's entries are checked
//! before they are added) and the forward references of `f` lines (only those larger than
//! every earlier one are kept: the first beyond the file's vertices is the first bad one).
//! Past it the read is [`Error::MeshTooLarge`]; every list grows by a fallible reservation,
//! so an allocation refused below the budget is [`Error::AllocationFailed`], never an abort.
//!
//! Writing produces plain OBJ (`v` and `f` lines, n-gons kept) that Blender and MeshLab
//! open; a mesh with texture coordinates also gets its `vt` lines and `f v/vt` corners, so it
//! opens textured, and [`ObjWriteOptions`] leaves them out or adds area-weighted vertex
//! normals ([`crate::normals`]) as `vn` lines with `f v/vt/vn` or `f v//vn` corners (the
//! `vn` index is the vertex's); a mesh without texture coordinates and without normals is
//! written exactly as before they existed. A mesh with vertex colors gets `v x y z r g b`
//! lines, and one with groups its `mtllib` lines before the first `v` and a `usemtl` / `o` /
//! `g` / `s` line before each face whose value changes ([`crate::groups`]).
//! [`write_mesh_buffers_obj`] writes all of it from caller buffers ([`MeshBuffers`]);
//! [`write_buffers_obj_with`] writes caller-owned
//! buffers, UV values and a value per corner ([`UvBuffers`]) included. The writers take any
//! [`std::io::Write`]; putting the text in a file (atomically, `-` for standard output, signals)
//! is the front ends' (`driver::output`).
//!
//! # Example
//!
//! ```
//! use halfedge::{io, HalfEdgeMesh};
//!
//! let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
//! let polygons = io::read_obj_from(text.as_bytes(), "square.obj")?;
//! let mesh = HalfEdgeMesh::try_from(&polygons)?;
//! assert_eq!((mesh.n_vertices(), mesh.n_edges(), mesh.n_faces()), (4, 4, 1));
//!
//! let mut out = Vec::new();
//! io::write_obj(&mesh, &mut out)?;
//! assert_eq!(String::from_utf8(out)?, "v 0.0 0.0 0.0\nv 1.0 0.0 0.0\nv 1.0 1.0 0.0\nv 0.0 1.0 0.0\nf 1 2 3 4\n");
//!
//! let err = io::read_obj_from("v 0 0 0\nf 1 2 3\n".as_bytes(), "bad.obj").unwrap_err();
//! assert_eq!(err.to_string(), "bad.obj: line 2: face index 2 is out of range (the file has 1 vertices)");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `io/`: OBJ and OFF read in one streaming pass into a `PolygonMesh` (the raw face list, which
//! may be non-manifold), with errors naming file and line. OBJ's OpenSubdiv tags (`t crease 2/1/0
//! 0 1 10`, ...) are read by default into `PolygonMesh::tags` (a `halfedge::tags::Tags`), strictly
//! (a malformed tag, an index out of range or a crease off the faces' edges is a `ParseError` with
//! the tag's line); unknown tags are returned (`PolygonMesh::ignored_tags`), never printed;
//! `ReadOptions::without_tags` skips them. OFF has no tags. OBJ `vt` become `PolygonMesh::uvs`
//! when every corner has one (else `PolygonMesh::partial_uvs` records how many do; a bad `vt`
//! index names the file, line and corner); `vn` are not read. Sharpness is read in `f64` and
//! clamped to 10 (`INFINITELY_SHARP`). Text from a file echoed in a message goes through
//! `io::escape_controls` (the one escape of control characters; the CLI's error line too). The OBJ
//! writers write `vt` and `f v/vt` for a mesh with UVs (`ObjWriteOptions::uvs`, default on;
//! `UvBuffers` for caller-owned UV values) and, with `ObjWriteOptions::normals`, `vn` from
//! `normals.rs`'s area-weighted vertex normals. OBJ is parsed here rather than with tobj, because
//! tobj renumbers vertices per `o`/`g` group, drops unreferenced vertices and reports no line
//! numbers; the tests compare both readers on every shared mesh. Given the available memory
//! (`ReadOptions::available_bytes`, which the front ends measure), readers refuse a larger file
//! and stop once the mesh outgrows half of it. Everything a reader keeps
//! (mesh, `vt`, tags, the rising forward references) counts against that half and grows by
//! fallible reservations (`Error::AllocationFailed`, never an abort).
//!
//! Owner of reading OpenSubdiv's OBJ tags (`t` lines: grammar, forms, range and edge checks,
//! ignored tags): `halfedge::io`'s `obj_tags.rs` (`TagReader`), checking through `Tags::check_against`.
//!
//! Owner of reading OBJ texture coordinates (`vt`, the corner forms `v/vt`, `v/vt/vn`, `v//vn`,
//! negative and forward `vt` indices, the errors naming file, line and corner): `halfedge::io`'s
//! `obj.rs` (`UvReader`).
//!
//! Owner of OBJ text (every writer: half-edge meshes, face lists, caller-owned `f32`/`f64`
//! buffers; `vt` and `f v/vt` for texture coordinates, `vn` on request: `ObjWriteOptions`,
//! `UvBuffers`): `halfedge::io`'s `write.rs` (`write_coordinates`).
//!
//! Owner of writing an output file (`-o`): `driver::output::write_atomically` (OBJ, PLY and
//! plot output alike; `driver::output::MeshFormat` by the name); mesh formats not written
//! (`-o out.stl` is a usage error): `driver::output::unwritten_mesh_format`.

mod buffers;
mod float;
mod lines;
mod obj;
mod obj_extras;
mod obj_tags;
mod off;
mod ply;
mod write;

pub use self::buffers::{FaceBuffers, MeshBuffers, ObjWriteOptions, TangentBuffers, UvBuffers};
pub use self::obj::{read_obj, read_obj_from, read_obj_from_with, read_obj_with};
pub use self::off::{read_off, read_off_from};
pub use self::ply::{
    read_ply, read_ply_from, read_ply_with, write_mesh_buffers_ply, write_polygon_ply,
};
pub use self::write::{
    write_buffers_obj, write_buffers_obj_with, write_mesh_buffers_obj, write_obj, write_obj_with,
    write_polygon_obj, write_polygon_obj_with,
};
pub use crate::text::escape_controls;

use std::io::Read;
use std::path::Path;

use self::lines::Place;

use crate::error::{Error, ParseError, Result};
use crate::polygon::PolygonMesh;

/// Reads a mesh file, choosing the format by its extension (`.obj`, `.off` or `.ply`, any case).
///
/// # Errors
///
/// [`Error::UnknownFormat`] for another extension, otherwise as [`read_obj`] / [`read_off`].
///
/// # Example
///
/// ```no_run
/// let mesh = halfedge::io::read_mesh("bunny.obj")?;
/// println!("{} faces", mesh.n_faces());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_mesh(path: impl AsRef<Path>) -> Result<PolygonMesh> {
    read_mesh_with(path, &ReadOptions::default())
}

/// [`read_mesh`] with options (OFF has no tags, so [`ReadOptions::tags`] changes nothing
/// there).
///
/// # Errors
///
/// As [`read_mesh`].
///
/// # Example
///
/// ```no_run
/// use halfedge::io::{read_mesh_with, ReadOptions};
/// let pawn = read_mesh_with("osd_catmark_pawn.obj", &ReadOptions::default())?;
/// assert_eq!(pawn.tags().sharp_edges().len(), 120);
/// let untagged = read_mesh_with("osd_catmark_pawn.obj", &ReadOptions::without_tags())?;
/// assert!(untagged.tags().is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_mesh_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<PolygonMesh> {
    let path = path.as_ref();
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => read_obj_with(path, options),
        Some("off") => off::read_off_with(path, options),
        Some("ply") => read_ply_with(path, options),
        _ => Err(Error::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// How the readers read a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadOptions {
    /// Read OpenSubdiv's `t` lines into [`PolygonMesh::tags`] (the default); when `false`
    /// they are skipped unread, malformed or not.
    pub tags: bool,
    /// The bytes the process may still allocate, as its caller measured them (the front ends
    /// ask the system: `driver::system::available_bytes`): a regular file larger than this is
    /// refused before it is read ([`Error::FileTooLarge`]), and reading stops once the mesh
    /// and the reader's lists outgrow half of it ([`Error::MeshTooLarge`]). `None` (the
    /// default): no limit, as the kernel reads no system state.
    pub available_bytes: Option<u64>,
}

impl ReadOptions {
    /// Tags read, no memory limit (the default).
    pub const DEFAULT: ReadOptions = ReadOptions {
        tags: true,
        available_bytes: None,
    };

    /// Tags skipped unread.
    pub fn without_tags() -> ReadOptions {
        ReadOptions {
            tags: false,
            ..ReadOptions::DEFAULT
        }
    }

    /// These options with the memory limit of [`ReadOptions::available_bytes`].
    ///
    /// ```
    /// use halfedge::io::{read_obj_from_with, ReadOptions};
    /// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".repeat(100);
    /// let options = ReadOptions::default().with_available_bytes(Some(4096));
    /// let err = read_obj_from_with(text.as_bytes(), "big.obj", &options).unwrap_err();
    /// assert!(err.is_resource_limit(), "{err}");
    /// ```
    pub fn with_available_bytes(mut self, available_bytes: Option<u64>) -> ReadOptions {
        self.available_bytes = available_bytes;
        self
    }
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions::DEFAULT
    }
}

/// The longest line (after joining backslash continuations) the readers accept, in bytes.
///
/// Lines are read with a bounded buffer, so a file with a longer line (a 200 MB single-line
/// file, binary data without newlines) is refused with [`ParseError::LineTooLong`] after
/// reading at most this many bytes of it. 16 MiB holds an OBJ polygon of about 500 000
/// corners written as `v/vt/vn`.
pub const MAX_LINE_BYTES: usize = 16 << 20;

/// Reads the file at `path` with a reader's body `within` (given the buffered file, its name
/// for messages and the budget of `options`), after [`open`]'s size check.
fn read_file(
    path: &Path,
    options: &ReadOptions,
    within: impl FnOnce(std::io::BufReader<std::fs::File>, &str, Budget) -> Result<PolygonMesh>,
) -> Result<PolygonMesh> {
    let file = open(path, options.available_bytes)?;
    within(file, &path.display().to_string(), Budget::of(options))
}

/// Opens a mesh file for buffered reading, with the path in the error; a regular file larger
/// than `available` bytes ([`ReadOptions::available_bytes`]) is refused before it is read
/// ([`Error::FileTooLarge`]).
fn open(path: &Path, available: Option<u64>) -> Result<std::io::BufReader<std::fs::File>> {
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io_error)?;
    let metadata = file.metadata().map_err(io_error)?;
    if let Some(limit) = available {
        if metadata.is_file() && metadata.len() > limit {
            return Err(Error::FileTooLarge {
                path: path.to_path_buf(),
                size: metadata.len(),
                limit,
            });
        }
    }
    Ok(std::io::BufReader::with_capacity(1 << 16, file))
}

/// Reads a whole text file of at most `max_bytes` bytes (a scheme file, a configuration),
/// checking the size before reading it all: a regular file by its length, anything else
/// (`/dev/zero`, a FIFO) by reading at most one byte past the limit.
///
/// # Errors
///
/// The error of opening or reading the file; [`std::io::ErrorKind::InvalidData`] for a file
/// longer than `max_bytes` ("the file is larger than the limit of N bytes") or not UTF-8.
///
/// # Example
///
/// ```
/// let err = halfedge::io::read_text_capped(std::path::Path::new("/dev/zero"), 1024).unwrap_err();
/// assert_eq!(err.to_string(), "the file is larger than the limit of 1024 bytes");
/// ```
pub fn read_text_capped(path: &Path, max_bytes: u64) -> std::io::Result<String> {
    let too_large = || {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("the file is larger than the limit of {max_bytes} bytes"),
        )
    };
    let file = std::fs::File::open(path)?;
    let metadata = file.metadata()?;
    if metadata.is_file() && metadata.len() > max_bytes {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large());
    }
    String::from_utf8(bytes).map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e))
}

/// The memory a reader may fill with the mesh it reads: half of what the process may still
/// allocate ([`ReadOptions::available_bytes`]), leaving room for a vector's growth.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Budget {
    bytes: u64,
}

impl Budget {
    /// Half of [`ReadOptions::available_bytes`] (no limit without it).
    pub(crate) fn of(options: &ReadOptions) -> Budget {
        Budget {
            bytes: options.available_bytes.map_or(u64::MAX, |b| b / 2),
        }
    }

    /// Refuses once `mesh` and `extra` bytes (the reader's other lists: tags, texture
    /// coordinates, forward references) occupy more than the budget.
    fn check(self, mesh: &PolygonMesh, extra: usize, lines: &Place) -> Result<()> {
        if mesh.heap_bytes() as u128 + extra as u128 > u128::from(self.bytes) {
            return Err(self.refused(lines));
        }
        Ok(())
    }

    /// The bytes the budget still has room for once `mesh` and `extra` bytes occupy it.
    fn room(self, mesh: &PolygonMesh, extra: usize) -> u128 {
        u128::from(self.bytes).saturating_sub(mesh.heap_bytes() as u128 + extra as u128)
    }

    /// The refusal of the mesh read so far, where the reader got to.
    fn refused(self, lines: &Place) -> Error {
        Error::MeshTooLarge {
            file: lines.name.clone(),
            line: lines.line,
            limit: self.bytes,
        }
    }
}

/// Room for `additional` more elements in a reader's growing list: a refused allocation (an
/// address-space limit tighter than the budget saw) is [`Error::AllocationFailed`] naming the
/// file and line, never an abort.
fn grow<T>(list: &mut Vec<T>, additional: usize, lines: &Place) -> Result<()> {
    list.try_reserve(additional).map_err(|e| {
        lines.allocation_failed(additional as u128 * std::mem::size_of::<T>() as u128, e)
    })
}

/// Shortens a token for an error message, its control characters escaped.
fn shorten(token: &str) -> String {
    const MAX: usize = 40;
    if token.chars().count() <= MAX {
        escape_controls(token).into_owned()
    } else {
        let head: String = token.chars().take(MAX).collect();
        format!("{}...", escape_controls(&head))
    }
}

/// The next `N` tokens of a line, each read by `parse`; a line with fewer is the error
/// `missing(found)`.
fn parse_values<'a, const N: usize>(
    tokens: &mut impl Iterator<Item = &'a str>,
    lines: &Place,
    parse: fn(&str) -> std::result::Result<f64, ParseError>,
    missing: fn(usize) -> ParseError,
) -> Result<[f64; N]> {
    values_from(|| tokens.next().map(parse), lines, missing)
}

/// The next `N` values of a line, each from `next` (`None` at the line's end); a line with
/// fewer is the error `missing(found)`.
#[inline]
fn values_from<const N: usize>(
    mut next: impl FnMut() -> Option<std::result::Result<f64, ParseError>>,
    lines: &Place,
    missing: fn(usize) -> ParseError,
) -> Result<[f64; N]> {
    let mut values = [0.0f64; N];
    for (i, slot) in values.iter_mut().enumerate() {
        match next() {
            None => return Err(lines.error(missing(i))),
            Some(value) => *slot = value.map_err(|kind| lines.error(kind))?,
        }
    }
    Ok(values)
}

/// A vertex position: the next three tokens of a line, finite coordinates.
fn parse_position<'a>(
    tokens: &mut impl Iterator<Item = &'a str>,
    lines: &Place,
) -> Result<glam::DVec3> {
    let missing = |found| ParseError::MissingCoordinates { found };
    parse_values(tokens, lines, parse_coordinate, missing).map(glam::DVec3::from_array)
}

/// Parses a finite coordinate.
fn parse_coordinate(token: &str) -> std::result::Result<f64, ParseError> {
    parse_finite(token, "coordinate")
}

/// Parses a finite number, `expected` naming what it is in the error of a token that is no
/// number.
fn parse_finite(token: &str, expected: &'static str) -> std::result::Result<f64, ParseError> {
    match float::parse_f64(token) {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(ParseError::NonFiniteCoordinate {
            token: shorten(token),
        }),
        Err(_) => Err(ParseError::InvalidNumber {
            token: shorten(token),
            expected,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::BufReader;

    #[test]
    fn a_mesh_beyond_the_budget_is_refused_where_the_reader_got_to() {
        // An endless stream of vertices (a FIFO, a generated file): refused once the mesh
        // read so far exceeds the budget, instead of filling memory.
        let endless = BufReader::new(std::io::repeat(b'v').take(1 << 30));
        let vertices = b"v 0 0 0\n".repeat(1000);
        let data = std::io::Cursor::new(vertices).chain(endless);
        let budget = Budget { bytes: 24 * 500 };
        let err = obj::read_obj_within(
            BufReader::new(data),
            "endless.obj",
            budget,
            &ReadOptions::default(),
        )
        .unwrap_err();
        assert_eq!(
            err.to_string(),
            "endless.obj: line 500: the mesh read so far needs more than 12000 bytes of memory, half of what is available to this process"
        );
        assert!(err.is_resource_limit());
        let off = format!("OFF\n1000 1 0\n{}3 0 1 2\n", "0 0 0\n".repeat(1000));
        let err = off::read_off_within(off.as_bytes(), "m.off", budget).unwrap_err();
        assert!(
            matches!(err, Error::MeshTooLarge { line: 502, .. }),
            "{err}"
        );
    }

    /// Issue 24: the reader's list of forward references (16 bytes a corner) was outside its
    /// budget and grew infallibly: 2 M faces before their vertices aborted the process. Only
    /// increasing references are kept now, and what is kept counts against the budget, as do
    /// a tag line's entries before they are added.
    #[test]
    fn forward_references_and_tag_entries_count_against_the_budget() {
        let budget = Budget { bytes: 1_000_000 };
        let read = |text: &str| {
            obj::read_obj_within(text.as_bytes(), "f.obj", budget, &ReadOptions::default())
        };
        // 20,000 faces of the same three forward references (28 bytes a face): read within
        // the budget.
        let same = format!("{}v 0 0 0\nv 1 0 0\nv 0 1 0\n", "f 1 2 3\n".repeat(20_000));
        assert_eq!(read(&same).expect("within the budget").n_faces(), 20_000);
        // Ever larger forward references: the list counts, refused where it outgrows it.
        let rising: String = (1..=30_000u32)
            .map(|k| format!("f {} {} {}\n", 3 * k - 2, 3 * k - 1, 3 * k))
            .collect();
        let err = read(&rising).unwrap_err();
        assert!(matches!(err, Error::MeshTooLarge { .. }), "{err}");
        assert!(err.is_resource_limit());
        // The faces alone would fit (30,000 * 28 = 840,000 bytes); the list adds three
        // entries of 16 bytes a face: 76 bytes a face in all.
        let Error::MeshTooLarge { line, .. } = err else {
            unreachable!()
        };
        assert_eq!(line, 1_000_000 / 76 + 1, "refused at line {line}");
        // A tag line whose entries would not fit is refused before they are added.
        let mesh = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let pairs = 60_000;
        let tag = format!("t crease {}/1/0 {}10\n", 2 * pairs, "0 1 ".repeat(pairs));
        let err = read(&format!("{mesh}{tag}")).unwrap_err();
        assert!(matches!(err, Error::MeshTooLarge { line: 5, .. }), "{err}");
        let hole = format!("t hole {}/0/0 {}\n", 2 * pairs, "0 ".repeat(2 * pairs));
        let err = read(&format!("{mesh}{hole}")).unwrap_err();
        assert!(matches!(err, Error::MeshTooLarge { line: 5, .. }), "{err}");
    }

    #[test]
    fn capped_text_files() {
        let dir = std::env::temp_dir().join(format!("halfedge-capped-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("s.toml");
        std::fs::write(&path, "name = \"x\"\n").expect("written");
        assert_eq!(read_text_capped(&path, 11).expect("read"), "name = \"x\"\n");
        let err = read_text_capped(&path, 10).unwrap_err();
        assert_eq!(
            err.to_string(),
            "the file is larger than the limit of 10 bytes"
        );
        std::fs::remove_dir_all(&dir).expect("cleanup");
        let err = read_text_capped(Path::new("/dev/zero"), 1 << 20).unwrap_err();
        assert_eq!(
            err.to_string(),
            "the file is larger than the limit of 1048576 bytes"
        );
    }

    #[test]
    fn an_overlong_line_is_refused_after_a_bounded_read() {
        // An endless line: the reader must stop at the limit instead of buffering it all.
        let endless = BufReader::new(std::io::repeat(b'1'));
        let data = b"v 0 0 0\nf 1 ".chain(endless);
        let err = read_obj_from(BufReader::new(data), "long.obj").unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("long.obj: line 2: line is longer than {MAX_LINE_BYTES} bytes")
        );
    }

    #[test]
    fn a_byte_order_mark_before_the_first_line_is_not_part_of_it() {
        let obj = "\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let mesh = read_obj_from(obj.as_bytes(), "bom.obj").expect("valid");
        assert_eq!((mesh.n_vertices(), mesh.n_faces()), (3, 1));
        let off = "\u{feff}OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let mesh = read_off_from(off.as_bytes(), "bom.off").expect("valid");
        assert_eq!((mesh.n_vertices(), mesh.n_faces()), (3, 1));
        // Only a mark before the first line is skipped; elsewhere it is an unknown token.
        let later = "v 0 0 0\n\u{feff}v 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let err = read_obj_from(later.as_bytes(), "later.obj").unwrap_err();
        assert_eq!(
            err.to_string(),
            "later.obj: line 4: face index 3 is out of range (the file has 2 vertices)"
        );
    }

    #[test]
    fn continuations_count_towards_the_line_limit() {
        let piece = format!("{}\\\n", "1 ".repeat(1 << 19));
        let reader =
            std::io::Cursor::new(format!("f {}", piece.repeat(20))).chain(b"1 2 3\n".as_slice());
        let err = read_obj_from(BufReader::new(reader), "cont.obj").unwrap_err();
        assert!(matches!(
            err,
            Error::Parse {
                line: 1,
                kind: ParseError::LineTooLong { .. },
                ..
            }
        ));
    }
}
