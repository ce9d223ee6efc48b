//! OBJ reading: `v` (with colors), `vt`, `f`, OpenSubdiv's `t` statements and the grouping
//! statements (`mtllib`, `usemtl`, `o`, `g`, `s`); every other kind of line counted as not
//! carried.

use std::io::BufRead;
use std::path::Path;

use glam::DVec2;

use super::{
    grow, parse_coordinate, parse_position, parse_values, shorten, Budget, Lines, ReadOptions,
};
use crate::error::{Error, ParseError, Result};
use crate::groups::{GroupsReader, Statement};
use crate::polygon::{PartialColors, PolygonMesh, ReadColors, Uncarried};
use crate::uv::{PartialUvs, Uvs};

use super::obj_tags::{TagFailure, TagReader};

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
/// kept (counted by [`Uvs::unreferenced`]). `mtllib`, `usemtl`, `o`, `g` and `s` become the
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
    let mut lines = Lines::new(reader, name);
    let mut mesh = PolygonMesh::default();
    let mut tags = TagReader::default();
    let mut corners: Vec<u32> = Vec::new();
    let mut uv = UvReader::default();
    // The `vt` of the corners of one face line that have one.
    let mut face_vts: Vec<u32> = Vec::new();
    // Positive indices beyond the vertices read so far (line, index), each larger than every
    // earlier one: the first of them beyond the file's count is the file's first bad forward
    // reference (an earlier, smaller one is within it). A file of faces before their vertices
    // keeps a few entries, not one per corner.
    let mut forward: Vec<(u64, i64)> = Vec::new();
    let mut extras = Extras::default();
    // Every list the reader grows besides the mesh counts against the budget.
    let extra = |tags: &TagReader, uv: &UvReader, forward: &[(u64, i64)], scratch: usize| {
        tags.heap_bytes() + uv.heap_bytes() + std::mem::size_of_val(forward) + scratch
    };
    let extra = |tags: &TagReader, uv: &UvReader, e: &Extras, f: &[(u64, i64)], s: usize| {
        extra(tags, uv, f, s) + e.heap_bytes()
    };
    loop {
        if !lines.next_line()? {
            break;
        }
        let line = lines.text.as_str();
        let mut tokens = line.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        // The per-line lists (bounded by the line's length) count as what they hold.
        let scratch = 4 * (corners.capacity() + face_vts.capacity());
        match keyword {
            "v" => {
                let position = parse_position(&mut tokens, &lines)?;
                push_element(&mut mesh.positions, position, "vertices", &lines)?;
                extras.vertex(tokens, &lines)?;
                budget.check(&mesh, extra(&tags, &uv, &extras, &forward, scratch), &lines)?;
            }
            "vt" => {
                let missing = |found| ParseError::MissingTexCoords { found };
                let st = parse_values(&mut tokens, &lines, parse_tex_coordinate, missing)?;
                push_element(
                    &mut uv.coords,
                    DVec2::from_array(st),
                    "texture coordinates",
                    &lines,
                )?;
                budget.check(&mesh, extra(&tags, &uv, &extras, &forward, scratch), &lines)?;
            }
            "f" => {
                corners.clear();
                face_vts.clear();
                let count = mesh.positions.len() as u64;
                for (k, token) in tokens.enumerate() {
                    let mut fields = token.split('/');
                    let field = fields.next().unwrap_or("");
                    let index = parse_index(field).map_err(|kind| lines.error(kind))?;
                    let resolved = if index < 0 {
                        let back = index.unsigned_abs();
                        if back > count {
                            let kind = ParseError::IndexOutOfRange {
                                index,
                                vertices: count,
                            };
                            return Err(lines.error(kind));
                        }
                        count - back
                    } else {
                        if index as u64 > count && forward.last().map_or(true, |&(_, i)| index > i)
                        {
                            grow(&mut forward, 1, &lines)?;
                            forward.push((lines.line, index));
                        }
                        index as u64 - 1
                    };
                    grow(&mut corners, 1, &lines)?;
                    corners.push(resolved as u32);
                    match fields.next() {
                        Some(vt) if !vt.is_empty() => {
                            let t = uv.resolve(vt, k + 1, &lines)?;
                            grow(&mut face_vts, 1, &lines)?;
                            face_vts.push(t);
                        }
                        _ => {}
                    }
                }
                if corners.len() < 3 {
                    let kind = ParseError::FaceTooSmall {
                        corners: corners.len(),
                    };
                    return Err(lines.error(kind));
                }
                let scratch = 4 * (corners.capacity() + face_vts.capacity());
                // The face's corners, offset and line, and its corners' vt.
                let adding =
                    (corners.len() + face_vts.len()) * 4 + std::mem::size_of::<usize>() + 8;
                if budget.room(&mesh, extra(&tags, &uv, &extras, &forward, scratch))
                    < adding as u128
                {
                    return Err(budget.refused(&lines));
                }
                mesh.try_push_face_from_line(&corners, lines.line)
                    .map_err(|e| lines.allocation_failed(adding as u128, e))?;
                extras
                    .groups
                    .face()
                    .map_err(|e| lines.allocation_failed(4, e))?;
                uv.push_face(&face_vts, corners.len(), &lines)?;
                budget.check(&mesh, extra(&tags, &uv, &extras, &forward, scratch), &lines)?;
            }
            "t" if options.tags => {
                let room = budget.room(&mesh, extra(&tags, &uv, &extras, &forward, scratch));
                tags.read(tokens, lines.line, room)
                    .map_err(|failure| match failure {
                        TagFailure::Parse(kind) => lines.error(kind),
                        TagFailure::OverBudget => budget.refused(&lines),
                        TagFailure::Allocation { bytes, error } => {
                            lines.allocation_failed(bytes, error)
                        }
                    })?;
                budget.check(&mesh, extra(&tags, &uv, &extras, &forward, scratch), &lines)?;
            }
            "t" => {}
            "mtllib" => {
                let room = budget.room(&mesh, extra(&tags, &uv, &extras, &forward, scratch));
                if room < (line.len() + 64) as u128 {
                    return Err(budget.refused(&lines));
                }
                extras
                    .groups
                    .mtllib(line.trim())
                    .map_err(|e| lines.allocation_failed(line.len() as u128, e))?;
            }
            other => {
                match Statement::of_keyword(other) {
                    Some(statement) => extras.groups.statement(statement, tokens),
                    None => extras.uncarried(other),
                }
                budget.check(&mesh, extra(&tags, &uv, &extras, &forward, scratch), &lines)?;
            }
        }
    }
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
    if let Some((line, kind)) = error {
        return Err(Error::Parse {
            file: lines.name.clone(),
            line,
            kind,
        });
    }
    if mesh.n_faces() == 0 {
        return Err(Error::NoFaces {
            file: lines.name.clone(),
        });
    }
    tags.finish(&mut mesh)
        .map_err(|(line, kind)| Error::Parse {
            file: lines.name.clone(),
            line,
            kind,
        })?;
    let (uvs, partial) = uv.finish();
    mesh.set_read_uvs(uvs, partial);
    let vertices = mesh.n_vertices();
    let (colors, groups, uncarried) = extras.finish(vertices);
    mesh.set_read_extras(colors, groups, uncarried);
    Ok(mesh)
}

/// What the OBJ reader keeps besides positions, faces, texture coordinates and tags: vertex
/// colors, the grouping statements, and the kinds of lines no output carries.
#[derive(Default)]
struct Extras {
    /// The colors of the `v` lines so far, while every one has `r g b` (else empty).
    colors: Vec<[f64; 3]>,
    /// The `v` lines with a color, and whether one had a count of values other than 3, 4 or 6.
    with_colors: usize,
    vertices: usize,
    odd: bool,
    groups: GroupsReader,
    uncarried: std::collections::HashMap<String, u64>,
}

impl Extras {
    fn heap_bytes(&self) -> usize {
        let uncarried: usize = self.uncarried.keys().map(|k| k.capacity() + 48).sum();
        24 * self.colors.capacity() + self.groups.heap_bytes() + uncarried
    }

    /// Reads the values of a `v` line after its position: none, `w`, or `r g b`.
    fn vertex<'a, R>(
        &mut self,
        mut rest: impl Iterator<Item = &'a str> + Clone,
        lines: &Lines<R>,
    ) -> Result<()> {
        // Counted without collecting: this runs once per `v` line.
        let count = rest.clone().take(4).count();
        let all_so_far = self.with_colors == self.vertices;
        self.vertices += 1;
        match count {
            3 => {
                let missing = |found| ParseError::MissingCoordinates { found };
                let rgb = parse_values::<3, R>(&mut rest, lines, parse_color, missing)?;
                self.with_colors += 1;
                if all_so_far {
                    grow(&mut self.colors, 1, lines)?;
                    self.colors.push(rgb);
                }
            }
            n => {
                self.odd |= n > 1;
                self.colors = Vec::new();
            }
        }
        Ok(())
    }

    /// Counts a line no output carries.
    fn uncarried(&mut self, keyword: &str) {
        let keyword = shorten(keyword);
        *self.uncarried.entry(keyword).or_insert(0) += 1;
    }

    fn finish(
        self,
        vertices: usize,
    ) -> (
        ReadColors,
        Option<crate::groups::FaceGroups>,
        Vec<Uncarried>,
    ) {
        let colors = if self.with_colors == vertices && vertices > 0 {
            (Some(self.colors), None)
        } else if self.with_colors > 0 || self.odd {
            let partial = PartialColors {
                with_colors: self.with_colors,
                vertices,
            };
            (None, Some(partial))
        } else {
            (None, None)
        };
        let mut uncarried: Vec<Uncarried> = self
            .uncarried
            .into_iter()
            .map(|(keyword, count)| Uncarried {
                what: format!("{keyword} lines"),
                count,
            })
            .collect();
        uncarried.sort_by(|a, b| a.what.cmp(&b.what));
        (colors, self.groups.finish(), uncarried)
    }
}

/// Parses a finite color value.
pub(super) fn parse_color(token: &str) -> std::result::Result<f64, ParseError> {
    parse_coordinate(token).map_err(|kind| match kind {
        ParseError::InvalidNumber { token, .. } => ParseError::InvalidNumber {
            token,
            expected: "vertex color",
        },
        kind => kind,
    })
}

/// The texture coordinates read so far and the `vt` of the face corners.
#[derive(Default)]
struct UvReader {
    /// The `vt` lines.
    coords: Vec<DVec2>,
    /// The `vt` of every corner so far, while every corner so far has one (else empty).
    vts: Vec<u32>,
    /// The corners read so far, and those of them with a `vt`.
    corners: usize,
    with_vt: usize,
    /// Positive `vt` indices beyond the `vt` lines read so far (line, corner, index), each
    /// larger than every earlier one: the first of them beyond the file's count is the
    /// file's first bad forward reference (an earlier, smaller one is within it).
    forward: Vec<(u64, usize, i64)>,
}

impl UvReader {
    fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(self.coords.as_slice())
            + std::mem::size_of_val(self.vts.as_slice())
            + std::mem::size_of_val(self.forward.as_slice())
    }

    /// The 0-based `vt` of a corner's `vt` field (corner `corner` of the face on the line
    /// `lines` is at).
    fn resolve<R>(&mut self, field: &str, corner: usize, lines: &Lines<R>) -> Result<u32> {
        let index = parse_index(field).map_err(|e| {
            lines.error(match e {
                ParseError::IndexTooLarge { token } => {
                    ParseError::TexCoordIndexTooLarge { corner, token }
                }
                _ => ParseError::InvalidTexCoordIndex {
                    corner,
                    token: shorten(field),
                },
            })
        })?;
        let count = self.coords.len() as u64;
        if index < 0 {
            let back = index.unsigned_abs();
            if back > count {
                return Err(lines.error(ParseError::TexCoordIndexOutOfRange {
                    corner,
                    index,
                    count,
                }));
            }
            return Ok((count - back) as u32);
        }
        if index as u64 > count && self.forward.last().map_or(true, |&(_, _, i)| index > i) {
            grow(&mut self.forward, 1, lines)?;
            self.forward.push((lines.line, corner, index));
        }
        Ok(index as u32 - 1)
    }

    /// Records a face of `corners` corners whose corners with a `vt` have `vts`.
    fn push_face<R>(&mut self, vts: &[u32], corners: usize, lines: &Lines<R>) -> Result<()> {
        let all_so_far = self.with_vt == self.corners;
        self.with_vt += vts.len();
        self.corners += corners;
        if all_so_far && vts.len() == corners {
            grow(&mut self.vts, vts.len(), lines)?;
            self.vts.extend_from_slice(vts);
        } else if !self.vts.is_empty() {
            self.vts = Vec::new();
        }
        Ok(())
    }

    /// The first corner naming a `vt` beyond the file's, with its line.
    fn forward_error(&self) -> Option<(u64, ParseError)> {
        let count = self.coords.len() as u64;
        self.forward
            .iter()
            .find(|&&(_, _, index)| index as u64 > count)
            .map(|&(line, corner, index)| {
                let kind = ParseError::TexCoordIndexOutOfRange {
                    corner,
                    index,
                    count,
                };
                (line, kind)
            })
    }

    /// The mesh's texture coordinates (every corner has a `vt`), or the record of a file
    /// where only some corners have one; neither when no corner has one (`vt` lines or not).
    fn finish(self) -> (Option<Uvs>, Option<PartialUvs>) {
        if self.with_vt == 0 {
            (None, None)
        } else if self.with_vt == self.corners {
            (Some(Uvs::from_read(self.coords, self.vts)), None)
        } else {
            let partial = PartialUvs {
                with_vt: self.with_vt,
                corners: self.corners,
            };
            (None, Some(partial))
        }
    }
}

/// Appends `item` to `list`, the file's `what` (vertices or texture coordinates): at most
/// `u32::MAX - 1` of them, so that an index and `INVALID` fit `u32`.
fn push_element<T, R>(
    list: &mut Vec<T>,
    item: T,
    what: &'static str,
    lines: &Lines<R>,
) -> Result<()> {
    if list.len() >= u32::MAX as usize - 1 {
        return Err(Error::TooManyElements {
            what,
            count: list.len() as u64 + 1,
        });
    }
    grow(list, 1, lines)?;
    list.push(item);
    Ok(())
}

/// Parses a finite texture coordinate.
fn parse_tex_coordinate(token: &str) -> std::result::Result<f64, ParseError> {
    parse_coordinate(token).map_err(|kind| match kind {
        ParseError::InvalidNumber { token, .. } => ParseError::InvalidNumber {
            token,
            expected: "texture coordinate",
        },
        kind => kind,
    })
}

/// Parses an OBJ vertex index: a non-zero integer whose magnitude fits `u32`.
fn parse_index(field: &str) -> std::result::Result<i64, ParseError> {
    let digits = field.strip_prefix(['-', '+']).unwrap_or(field);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(ParseError::InvalidNumber {
            token: shorten(field),
            expected: "vertex index",
        });
    }
    let too_large = || ParseError::IndexTooLarge {
        token: shorten(field),
    };
    let index: i64 = field.parse().map_err(|_| too_large())?;
    if index == 0 {
        return Err(ParseError::IndexZero);
    }
    if index.unsigned_abs() >= u64::from(u32::MAX) {
        return Err(too_large());
    }
    Ok(index)
}

#[cfg(test)]
mod tests {
    use super::*;
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
}
