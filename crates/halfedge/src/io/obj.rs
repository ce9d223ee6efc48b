//! OBJ reading: `v` (with colors), `vt`, `f`, OpenSubdiv's `t` statements and the grouping
//! statements (`mtllib`, `usemtl`, `o`, `g`, `s`); every other kind of line counted as not
//! carried.

use std::io::{BufRead, Read};
use std::path::Path;

use glam::{DVec2, DVec3};

use super::lines::{LineSource, Place, Words, CHUNK};
use super::obj_extras::{
    index_prefix, parse_index, parse_tex_coordinate, push_element, Extras, UvReader,
};
use super::obj_tags::{TagFailure, TagReader};
use super::{grow, parse_coordinate, Budget, ReadOptions};
use crate::error::{Error, ParseError, Result};
use crate::groups::Statement;
use crate::polygon::PolygonMesh;

mod plain;

/// Reads an OBJ file as a face list, keeping polygons (no triangulation) and every `v` line
/// (used or not) in file order.
///
/// # Errors
///
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] naming the file and line of
/// the first malformed statement, [`Error::NoFaces`] for a file without faces,
/// With [`ReadOptions::available_bytes`] (the `_with` readers): [`Error::FileTooLarge`] for a
/// file larger than those bytes (refused before reading), [`Error::MeshTooLarge`] once the
/// mesh read so far needs more than half of them.
///
/// # Example
///
/// ```no_run
/// let mesh = halfedge::io::read_obj("spot_control_mesh.obj")?;
/// assert_eq!(mesh.n_faces(), 180);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_obj(path: impl AsRef<Path>) -> Result<PolygonMesh> {
    read_obj_with(path, &ReadOptions::default())
}

/// [`read_obj`] with options (e.g. [`ReadOptions::without_tags`]: `t` lines skipped unread).
///
/// # Errors
///
/// As [`read_obj`].
pub fn read_obj_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<PolygonMesh> {
    let within = |file, name: &str, budget| read_obj_within(file, name, budget, options);
    super::read_file(path.as_ref(), options, within)
}

/// Reads OBJ text from any buffered reader; `name` is the file name used in error messages.
///
/// Reads `v x y z` (a fourth value `w` is ignored; six values are a position and a color
/// `r g b`: [`PolygonMesh::colors`] when every `v` line has one, else
/// [`PolygonMesh::partial_colors`] says how many do), `vt u v` (a `w` is ignored) and `f` with corners `v`, `v/vt`, `v/vt/vn` or `v//vn`, where `v` and `vt` are
/// 1-based or negative (relative to the vertices, or texture coordinates, read so far).
/// Positive indices may refer to vertices or texture coordinates defined later in the file.
/// The `vn` field is not read (normals are not carried). When every face corner names a `vt`,
/// the mesh has [`uvs`](PolygonMesh::uvs); when only some do, it has none and
/// [`partial_uvs`](PolygonMesh::partial_uvs) says how many do; `vt` lines no corner uses are
/// kept (counted by [`Uvs::unreferenced`](crate::uv::Uvs::unreferenced)). `mtllib`, `usemtl`, `o`, `g` and `s` become the
/// mesh's [`groups`](PolygonMesh::groups) ([`crate::groups`]). Comments (`#`), blank lines
/// and backslash line continuations are skipped; OpenSubdiv's tags
/// (`t NAME nInts/nFloats/nStrings ints floats strings`) become the mesh's
/// [`tags`](PolygonMesh::tags) as the [`crate::io`] docs describe; every other statement
/// (`vn`, `l`, `p`, ...) is skipped and counted by kind ([`PolygonMesh::uncarried`]).
///
/// # Errors
///
/// As [`read_obj`]: a bad or non-finite coordinate, a vertex with fewer than three
/// coordinates, a `vt` with fewer than two, a face index that is 0, not a number, too large or
/// out of range, a texture-coordinate index that is not valid, too large or out of range
/// (naming the corner: [`ParseError::InvalidTexCoordIndex`],
/// [`ParseError::TexCoordIndexTooLarge`], [`ParseError::TexCoordIndexOutOfRange`]), a
/// face with fewer than three corners, a malformed tag line or a tag on a vertex, face or
/// edge the file does not have, binary data, no faces at all, a mesh beyond the memory budget.
///
/// # Example
///
/// ```
/// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
///             g a\nf 1/1 2/2 3/3\ng b\nf -3/-3/1 -1/-1/1 -2/-2/1\n";
/// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "two.obj")?;
/// assert_eq!(mesh.n_faces(), 2);
/// assert_eq!(mesh.face(1), &[0, 2, 1]);
/// assert_eq!(mesh.uvs().expect("a vt at every corner").corners(), [0, 1, 2, 0, 2, 1]);
///
/// let err = halfedge::io::read_obj_from("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n".as_bytes(), "bad.obj")
///     .unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "bad.obj: line 5: corner 3: texture coordinate index 2 is out of range (the file has 1 texture coordinates)"
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_obj_from(reader: impl BufRead, name: &str) -> Result<PolygonMesh> {
    read_obj_within(
        reader,
        name,
        Budget::of(&ReadOptions::DEFAULT),
        &ReadOptions::DEFAULT,
    )
}

/// [`read_obj_from`] with options.
///
/// # Errors
///
/// As [`read_obj_from`].
///
/// # Example
///
/// ```
/// use halfedge::io::{read_obj_from_with, ReadOptions};
/// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nt crease 2/1/0 0 7 10\n";
/// let err = read_obj_from_with(text.as_bytes(), "t.obj", &ReadOptions::default()).unwrap_err();
/// assert_eq!(err.to_string(), "t.obj: line 5: tag `crease`: vertex 7 is out of range (the mesh has 3 vertices; tag indices are 0-based)");
/// let mesh = read_obj_from_with(text.as_bytes(), "t.obj", &ReadOptions::without_tags())?;
/// assert!(!mesh.has_tags());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_obj_from_with(
    reader: impl BufRead,
    name: &str,
    options: &ReadOptions,
) -> Result<PolygonMesh> {
    read_obj_within(reader, name, Budget::of(options), options)
}

/// [`read_obj_from_with`] with the mesh's memory limited to `budget`.
pub(crate) fn read_obj_within(
    reader: impl BufRead,
    name: &str,
    budget: Budget,
    options: &ReadOptions,
) -> Result<PolygonMesh> {
    read_obj_in_chunks(reader, name, budget, options, CHUNK)
}

/// [`read_obj_within`] reading `chunk` bytes at a time.
pub(super) fn read_obj_in_chunks(
    reader: impl Read,
    name: &str,
    budget: Budget,
    options: &ReadOptions,
    chunk: usize,
) -> Result<PolygonMesh> {
    let mut source = LineSource::with_chunk(reader, chunk);
    let mut at = Place::new(name);
    let mut obj = ObjReader::new(budget, *options);
    loop {
        if let Some((text, pos)) = source.in_place() {
            obj.plain_lines(text, pos, &mut at)?;
        }
        let Some(line) = source.next_line(&mut at)? else {
            break;
        };
        obj.statement(line, &at)?;
    }
    obj.finish(&at)
}

/// The OBJ reader's state: the mesh and every list read so far.
struct ObjReader {
    budget: Budget,
    options: ReadOptions,
    mesh: PolygonMesh,
    tags: TagReader,
    /// The corners of the face line being read.
    corners: Vec<u32>,
    uv: UvReader,
    /// The `vt` of the corners of one face line that have one.
    face_vts: Vec<u32>,
    /// Positive indices beyond the vertices read so far (line, index), each larger than every
    /// earlier one: the first of them beyond the file's count is the file's first bad forward
    /// reference (an earlier, smaller one is within it). A file of faces before their vertices
    /// keeps a few entries, not one per corner.
    forward: Vec<(u64, i64)>,
    extras: Extras,
}

impl ObjReader {
    fn new(budget: Budget, options: ReadOptions) -> ObjReader {
        ObjReader {
            budget,
            options,
            mesh: PolygonMesh::default(),
            tags: TagReader::default(),
            corners: Vec::new(),
            uv: UvReader::default(),
            face_vts: Vec::new(),
            forward: Vec::new(),
            extras: Extras::default(),
        }
    }

    /// Every list the reader grows besides the mesh, which counts against the budget; the
    /// per-line lists (bounded by the line's length) count as what they hold.
    fn extra(&self) -> usize {
        self.tags.heap_bytes()
            + self.uv.heap_bytes()
            + std::mem::size_of_val(self.forward.as_slice())
            + 4 * (self.corners.capacity() + self.face_vts.capacity())
            + self.extras.heap_bytes()
    }

    fn check(&self, at: &Place) -> Result<()> {
        self.budget.check(&self.mesh, self.extra(), at)
    }

    /// Reads one line (comment removed, continuations joined), line `at.line`.
    fn statement(&mut self, line: &str, at: &Place) -> Result<()> {
        let mut words = Words::new(line);
        let Some(keyword) = words.next() else {
            return Ok(());
        };
        match keyword {
            "v" => {
                let missing = |found| ParseError::MissingCoordinates { found };
                let xyz = words.values::<3>(at, parse_coordinate, missing)?;
                let position = DVec3::from_array(xyz);
                push_element(&mut self.mesh.positions, position, "vertices", at)?;
                self.extras.vertex(words, at)?;
                self.check(at)
            }
            "f" => self.face(words, at),
            "vt" => {
                let missing = |found| ParseError::MissingTexCoords { found };
                let st = words.values::<2>(at, parse_tex_coordinate, missing)?;
                let coords = &mut self.uv.coords;
                push_element(coords, DVec2::from_array(st), "texture coordinates", at)?;
                self.check(at)
            }
            "t" if self.options.tags => {
                let room = self.budget.room(&self.mesh, self.extra());
                let tokens = words.rest().split_ascii_whitespace();
                self.tags
                    .read(tokens, at.line, room)
                    .map_err(|failure| match failure {
                        TagFailure::Parse(kind) => at.error(kind),
                        TagFailure::OverBudget => self.budget.refused(at),
                        TagFailure::Allocation { bytes, error } => {
                            at.allocation_failed(bytes, error)
                        }
                    })?;
                self.check(at)
            }
            "t" => Ok(()),
            "mtllib" => {
                let room = self.budget.room(&self.mesh, self.extra());
                if room < (line.len() + 64) as u128 {
                    return Err(self.budget.refused(at));
                }
                self.extras
                    .mtllib(line.trim())
                    .map_err(|e| at.allocation_failed(line.len() as u128, e))
            }
            other => {
                match Statement::of_keyword(other) {
                    Some(statement) => self.extras.statement(statement, words),
                    None => self.extras.uncarried(other),
                }
                self.check(at)
            }
        }
    }

    /// Reads an `f` line's corners (the words after `f`).
    fn face(&mut self, mut words: Words<'_>, at: &Place) -> Result<()> {
        self.corners.clear();
        self.face_vts.clear();
        let count = self.mesh.positions.len() as u64;
        let slash = |t: &str| t.bytes().position(|b| b == b'/');
        let mut corner = 0;
        loop {
            let ahead = words.ahead();
            if ahead.is_empty() {
                break;
            }
            corner += 1;
            // The fields `v`, `v/vt`, `v/vt/vn`, `v//vn`: a plain vertex index is read in
            // place, the rest of the word only when there is one.
            let (index, vt) = match index_prefix(ahead) {
                Some((index, n)) if words.take_word(n) => (index, None),
                Some((index, n)) if ahead[n] == b'/' => {
                    let word = words.next().unwrap_or_default();
                    let rest = &word[n + 1..];
                    (index, Some(&rest[..slash(rest).unwrap_or(rest.len())]))
                }
                _ => {
                    let word = words.next().unwrap_or_default();
                    let (field, vt) = match slash(word) {
                        None => (word, None),
                        Some(i) => {
                            let rest = &word[i + 1..];
                            (&word[..i], Some(&rest[..slash(rest).unwrap_or(rest.len())]))
                        }
                    };
                    (parse_index(field).map_err(|kind| at.error(kind))?, vt)
                }
            };
            self.corner(index, count, at)?;
            match vt {
                Some(vt) if !vt.is_empty() => {
                    let t = self.uv.resolve(vt, corner, at)?;
                    grow(&mut self.face_vts, 1, at)?;
                    self.face_vts.push(t);
                }
                _ => {}
            }
        }
        self.end_face(at)
    }

    /// Adds a face's corner of vertex index `index` (1-based, or negative counting back from
    /// the `count` vertices read so far).
    #[inline(always)]
    fn corner(&mut self, index: i64, count: u64, at: &Place) -> Result<()> {
        let resolved = if index < 0 {
            let back = index.unsigned_abs();
            if back > count {
                let kind = ParseError::IndexOutOfRange {
                    index,
                    vertices: count,
                };
                return Err(at.error(kind));
            }
            count - back
        } else {
            if index as u64 > count && self.forward.last().map_or(true, |&(_, i)| index > i) {
                grow(&mut self.forward, 1, at)?;
                self.forward.push((at.line, index));
            }
            index as u64 - 1
        };
        grow(&mut self.corners, 1, at)?;
        self.corners.push(resolved as u32);
        Ok(())
    }

    /// Adds the face whose corners (and their `vt`) were read.
    fn end_face(&mut self, at: &Place) -> Result<()> {
        if self.corners.len() < 3 {
            let kind = ParseError::FaceTooSmall {
                corners: self.corners.len(),
            };
            return Err(at.error(kind));
        }
        // The face's corners, offset and line, and its corners' vt.
        let adding =
            (self.corners.len() + self.face_vts.len()) * 4 + std::mem::size_of::<usize>() + 8;
        if self.budget.room(&self.mesh, self.extra()) < adding as u128 {
            return Err(self.budget.refused(at));
        }
        self.mesh
            .try_push_face_from_line(&self.corners, at.line)
            .map_err(|e| at.allocation_failed(adding as u128, e))?;
        self.extras.face().map_err(|e| at.allocation_failed(4, e))?;
        self.uv.push_face(&self.face_vts, self.corners.len(), at)?;
        if !self.extras.grouped() {
            // Nothing grew by more than `adding`, which the budget had room for: the mesh by
            // the corners, the offset and the line (16 bytes), the texture coordinates by
            // the face's `vt` at most; the groups (which grow by their capacity) not at all.
            return Ok(());
        }
        self.check(at)
    }

    /// The mesh, once the file is read: the first bad forward reference, no faces and the
    /// tags' problems are errors.
    fn finish(self, at: &Place) -> Result<PolygonMesh> {
        let ObjReader {
            mut mesh,
            tags,
            uv,
            forward,
            extras,
            ..
        } = self;
        let count = mesh.positions.len() as u64;
        let vertex_error = forward
            .iter()
            .find(|&&(_, index)| index as u64 > count)
            .map(|&(line, index)| {
                let kind = ParseError::IndexOutOfRange {
                    index,
                    vertices: count,
                };
                (line, kind)
            });
        // The first bad forward reference in the file, a vertex's before a vt's on one line.
        let error = match (vertex_error, uv.forward_error()) {
            (Some(v), Some(t)) => Some(if t.0 < v.0 { t } else { v }),
            (v, t) => v.or(t),
        };
        let parse_error = |(line, kind)| Error::Parse {
            file: at.name.clone(),
            line,
            kind,
        };
        if let Some(error) = error {
            return Err(parse_error(error));
        }
        if mesh.n_faces() == 0 {
            return Err(Error::NoFaces {
                file: at.name.clone(),
            });
        }
        tags.finish(&mut mesh).map_err(parse_error)?;
        let (uvs, partial) = uv.finish();
        mesh.set_read_uvs(uvs, partial);
        let vertices = mesh.n_vertices();
        let (colors, groups, uncarried) = extras.finish(vertices);
        mesh.set_read_extras(colors, groups, uncarried);
        Ok(mesh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::lines::testing::{outcome, Rng, Trickle};
    use crate::uv::Uvs;
    use glam::DVec3;

    #[test]
    fn corner_forms_groups_and_ignored_statements() {
        let text = "mtllib x.mtl\no one\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0 0.5 0.5 0.5\n\
                    vt 0 0\nvn 0 0 1\nvp 0.5\ns off\ng a b\nusemtl m\n\
                    f 1/1 2/1/1 3//1\nt crease 2/1/0 0 1 2\nl 1 2\ng c\nf -4 -2 \\\n -1 # tail\n\
                    f 1 3 4\n";
        let mesh = read_obj_from(text.as_bytes(), "x.obj").expect("valid");
        assert_eq!(mesh.n_vertices(), 4);
        assert_eq!(mesh.positions[3], DVec3::new(0.0, 1.0, 0.0));
        let faces: Vec<&[u32]> = mesh.faces().collect();
        assert_eq!(faces, [&[0, 1, 2][..], &[0, 2, 3], &[0, 2, 3]]);
    }

    /// Issue 27 review: `mtllib` lines grew outside the budget (an endless stream aborted the
    /// process); now they count and are refused where they outgrow it.
    #[test]
    fn mtllib_lines_count_against_the_budget() {
        use std::io::Read;
        let endless = std::io::repeat(b'x').take(1 << 30);
        let lines = b"mtllib a.mtl\n".repeat(100_000);
        let data = std::io::Cursor::new(lines).chain(endless);
        let budget = Budget { bytes: 100_000 };
        let options = ReadOptions::default();
        let reader = std::io::BufReader::new(data);
        let err = read_obj_within(reader, "m.obj", budget, &options).unwrap_err();
        assert!(matches!(err, Error::MeshTooLarge { .. }), "{err}");
    }

    #[test]
    fn colors_groups_and_uncarried_lines() {
        let text = "mtllib a.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n\
                    o x\ng a b\nusemtl m\ns 1\nf 1 3 2\nl 1 2\nvn 0 0 1\nvn 0 0 1\n";
        let mesh = read_obj_from(text.as_bytes(), "x.obj").expect("valid");
        assert_eq!(mesh.colors().expect("colors")[2], [0.0, 0.0, 1.0]);
        let groups = mesh.groups().expect("groups");
        assert_eq!(groups.mtllib(), ["mtllib a.mtl"]);
        assert_eq!(groups.value(0, Statement::Group), None);
        assert_eq!(groups.value(1, Statement::Group), Some("a b"));
        assert_eq!(groups.value(1, Statement::Smoothing), Some("1"));
        let kinds: Vec<String> = mesh.uncarried().iter().map(ToString::to_string).collect();
        assert_eq!(kinds, ["1 l lines", "2 vn lines"]);
        // Mixed counts: no channel, the record says how many.
        let mixed = "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 1 1 1 1\nf 1 2 3\n";
        let mesh = read_obj_from(mixed.as_bytes(), "m.obj").expect("valid");
        assert_eq!(mesh.colors(), None);
        let partial = mesh.partial_colors().expect("partial");
        assert_eq!(
            partial.to_string(),
            "1 of 3 vertices have colors: no color channel"
        );
        let err = read_obj_from(
            "v 0 0 0 r 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".as_bytes(),
            "c.obj",
        );
        assert_eq!(
            err.unwrap_err().to_string(),
            "c.obj: line 1: `r` is not a valid vertex color"
        );
    }

    #[test]
    fn crlf_and_plus_signs() {
        let text = "v +1 -2.5e1 .5\r\nv 0 0 0\r\nv 0 1 0\r\nf +1 2 3\r\n";
        let mesh = read_obj_from(text.as_bytes(), "x.obj").expect("valid");
        assert_eq!(mesh.positions[0], DVec3::new(1.0, -25.0, 0.5));
        assert_eq!(mesh.face(0), &[0, 1, 2]);
    }

    fn read(text: &str) -> Result<PolygonMesh> {
        read_obj_from(text.as_bytes(), "t.obj")
    }

    /// Four vertices and four texture coordinates; then `faces`.
    fn textured(faces: &str) -> String {
        format!("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1 0.5\nvt 0 1\n{faces}")
    }

    fn vts(mesh: &PolygonMesh) -> Vec<u32> {
        mesh.uvs().expect("uvs").corners().to_vec()
    }

    #[test]
    fn every_corner_form_with_a_vt_gives_uvs() {
        for faces in [
            "f 1/1 2/2 3/3 4/4\n",
            "f 1/1/1 2/2/1 3/3/1 4/4/1\n",
            "f 1/1 2/2/1 3/3/7 4/4\n",
            "f -4/-4 -3/-3/1 -2/-2 -1/-1//\n",
            "f 1/-4 2/2 3/-2 4/4/\n",
        ] {
            let mesh = read(&textured(faces)).expect(faces);
            assert_eq!(vts(&mesh), [0, 1, 2, 3], "{faces}");
            assert_eq!(mesh.face(0), &[0, 1, 2, 3], "{faces}");
            assert_eq!(mesh.partial_uvs(), None);
        }
        let mesh = read(&textured("f 1/1 2/2 3/3 4/4\n")).expect("valid");
        let uvs = mesh.uvs().expect("uvs");
        // `w` is ignored; u and v are kept as f64.
        assert_eq!(uvs.coords()[2], DVec2::new(1.0, 1.0));
        assert_eq!(uvs.unreferenced(), 0);
        // Vertices and texture coordinates are counted apart: -1 is the last vt read so far.
        let text = "v 0 0 0\nvt 0 0\nvt 0.5 0.5\nv 1 0 0\nv 0 1 0\nf -3/-1 -2/-2 -1/-1\nvt 1 1\nf 1/-1 2/-1 3/3\n";
        let mesh = read(text).expect("valid");
        assert_eq!(vts(&mesh), [1, 0, 1, 2, 2, 2]);
        // A positive index may name a vt defined later in the file.
        let mesh = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/3 2/2 3/1\nvt 0 0\nvt 1 0\nvt 0 1\n")
            .expect("valid");
        assert_eq!(vts(&mesh), [2, 1, 0]);
    }

    #[test]
    fn without_vt_at_some_corners_there_are_no_uvs_and_the_mesh_says_why() {
        for (faces, with_vt, corners) in [
            ("f 1/1 2/2 3/3 4/4\nf 1 2 3\n", 4, 7),
            ("f 1 2 3\nf 1/1 2/2 3/3 4/4\n", 4, 7),
            ("f 1/1 2//1 3/3 4/4\n", 3, 4),
            ("f 1//1 2//1 3/3//\n", 1, 3),
        ] {
            let mesh = read(&textured(faces)).expect(faces);
            assert_eq!(mesh.uvs(), None, "{faces}");
            let partial = mesh.partial_uvs().expect(faces);
            assert_eq!((partial.with_vt, partial.corners), (with_vt, corners));
            assert_eq!(
                partial.to_string(),
                format!(
                    "{with_vt} of {corners} face corners have texture coordinates: no UV layout"
                )
            );
        }
        // vt lines that no corner uses: no uvs, and nothing partial either.
        for faces in ["f 1 2 3 4\n", "f 1//1 2//1 3//1\n"] {
            let mesh = read(&textured(faces)).expect(faces);
            assert_eq!((mesh.uvs(), mesh.partial_uvs()), (None, None), "{faces}");
        }
        // Unused vt entries are kept and counted.
        let mesh = read(&textured("f 1/4 2/2 3/4\n")).expect("valid");
        let uvs = mesh.uvs().expect("uvs");
        assert_eq!((uvs.coords().len(), uvs.unreferenced()), (4, 2));
        // set_uvs replaces what the reader recorded.
        let mut mesh = read(&textured("f 1/1 2 3\n")).expect("valid");
        assert!(mesh.partial_uvs().is_some());
        mesh.set_uvs(Some(
            Uvs::new(vec![DVec2::ZERO], vec![0; 3]).expect("in range"),
        ))
        .expect("one per corner");
        assert_eq!(mesh.partial_uvs(), None);
    }

    #[test]
    fn every_texture_coordinate_error_names_the_file_line_and_corner() {
        let cases: &[(&str, &str)] = &[
            ("f 1/1 2/2 3/5\n", "t.obj: line 9: corner 3: texture coordinate index 5 is out of range (the file has 4 texture coordinates)"),
            ("f 1/-5 2/2 3/3\n", "t.obj: line 9: corner 1: texture coordinate index -5 is out of range (the file has 4 texture coordinates)"),
            ("f 1/1 2/0 3/3\n", "t.obj: line 9: corner 2: `0` is not a valid texture coordinate index (expected a non-zero integer; negative ones count back)"),
            ("f 1/1 2/x/1 3/3\n", "t.obj: line 9: corner 2: `x` is not a valid texture coordinate index (expected a non-zero integer; negative ones count back)"),
            ("f 1/1 2/1.5 3/3\n", "t.obj: line 9: corner 2: `1.5` is not a valid texture coordinate index (expected a non-zero integer; negative ones count back)"),
            ("f 1/1 2/2 3/4294967295\n", "t.obj: line 9: corner 3: texture coordinate index `4294967295` is too large"),
            ("f 1/1 2/-4294967295 3/3\n", "t.obj: line 9: corner 2: texture coordinate index `-4294967295` is too large"),
            ("f 1/1 2/2 3/99999999999999999999999\n", "t.obj: line 9: corner 3: texture coordinate index `99999999999999999999999` is too large"),
            ("f 1 2 3 4\nf 1/1 2/2 4/9\n", "t.obj: line 10: corner 3: texture coordinate index 9 is out of range (the file has 4 texture coordinates)"),
            ("vt 1\nf 1/1 2/2 3/3\n", "t.obj: line 9: texture coordinate has 1 values, expected u v (and an optional w)"),
            ("vt\nf 1/1 2/2 3/3\n", "t.obj: line 9: texture coordinate has 0 values, expected u v (and an optional w)"),
            ("vt 0 u\n", "t.obj: line 9: `u` is not a valid texture coordinate"),
            ("vt nan 0\n", "t.obj: line 9: coordinate `nan` is not finite"),
            ("vt 0 1e999\n", "t.obj: line 9: coordinate `1e999` is not finite"),
        ];
        for (faces, message) in cases {
            let err = read(&textured(faces)).unwrap_err();
            assert!(matches!(err, Error::Parse { .. }), "{faces}: {err}");
            assert_eq!(err.to_string(), *message, "{faces}");
        }
        let err = read(&textured("f 1/1 2/2 3/6\n")).unwrap_err();
        assert!(matches!(
            err,
            Error::Parse {
                line: 9,
                kind: ParseError::TexCoordIndexOutOfRange {
                    corner: 3,
                    index: 6,
                    count: 4
                },
                ..
            }
        ));
        // A forward reference beyond the file's vt: the first such corner in the file, even
        // when a larger one follows; a bad vertex on an earlier line comes first.
        let text =
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2 2/7 3/3\nf 1/9 2/2 3/1\nvt 0 0\nvt 1 0\nvt 0 1\n";
        assert_eq!(
            read(text).unwrap_err().to_string(),
            "t.obj: line 4: corner 2: texture coordinate index 7 is out of range (the file has 3 texture coordinates)"
        );
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\nf 1/9 2/2 3/1\nvt 0 0\n";
        assert_eq!(
            read(text).unwrap_err().to_string(),
            "t.obj: line 4: face index 9 is out of range (the file has 3 vertices)"
        );
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/9 2/2 3/1\nf 1 2 9\nvt 0 0\n";
        assert_eq!(
            read(text).unwrap_err().to_string(),
            "t.obj: line 4: corner 1: texture coordinate index 9 is out of range (the file has 1 texture coordinates)"
        );
        // The vertex field is checked before the vt field of the same corner.
        let err = read(&textured("f 1/1 2/2 0/9\n")).unwrap_err();
        assert_eq!(
            err.to_string(),
            "t.obj: line 9: face index 0 is not valid (OBJ indices start at 1)"
        );
    }

    /// An OBJ file from random statements, valid or not.
    fn random_obj(rng: &mut Rng) -> Vec<u8> {
        const LINES: &[&str] = &[
            "v 0 0 0\n",
            "v 1 0 0\n",
            "v 0 1 0\n",
            "v 0.35165546140493487 -2.5 1e3\n",
            "v 1 2 3 0.5 0.5 0.5\n",
            "v 1 2\n",
            "v 1 2 x\n",
            "v\t1\t2\t3\t\n",
            "v 1 2 3\r\n",
            "f 1 2 3\n",
            "f -1 -2 -3\n",
            "f 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17\n",
            "f 1/1 2/2 3/3\n",
            "f 1//1 2//1 3//1\n",
            "f 1 2\n",
            "f 1 2 0\n",
            "f 9 8 7\n",
            "f 1 2 \\\n3\n",
            "vt 0 0\n",
            "vt 0.5\n",
            "g a\n",
            "usemtl m\n",
            "s 1\n",
            "vn 0 0 1\n",
            "t crease 2/1/0 0 1 10\n",
            "# comment\n",
            "\n",
            "  v 1 1 1\n",
            "f 1 2 3 # c\n",
            "f +1 02 3\n",
            "f 1 2 99999999999999999999\n",
            "v 1 2 3\x0b\n",
            "f 1 2 3\x0c\n",
            "f 1\x0b2 3\n",
            "v 1 2 3",
            "\0\n",
            "\u{a0}\n",
        ];
        let mut text = Vec::new();
        for _ in 0..rng.below(30) {
            text.extend_from_slice(LINES[rng.below(LINES.len())].as_bytes());
        }
        text
    }

    #[test]
    fn every_chunk_size_reads_the_same_obj() {
        let mut rng = Rng(0x5eed_0f0b_1234_9876);
        for _ in 0..3000 {
            let text = random_obj(&mut rng);
            for budget in [Budget { bytes: u64::MAX }, Budget { bytes: 300 }] {
                let options = ReadOptions::default();
                let whole = outcome(read_obj_within(text.as_slice(), "t.obj", budget, &options));
                for chunk in [1, 3, 16, 100] {
                    let read =
                        read_obj_in_chunks(text.as_slice(), "t.obj", budget, &options, chunk);
                    assert_eq!(
                        outcome(read),
                        whole,
                        "{:?} {chunk}",
                        String::from_utf8_lossy(&text)
                    );
                }
                let trickle = Trickle::new(&text, 7, None);
                let read = read_obj_in_chunks(trickle, "t.obj", budget, &options, 5);
                assert_eq!(outcome(read), whole);
            }
        }
    }
}
