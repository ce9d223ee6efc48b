//! PLY reading (`ascii`, `binary_little_endian`, `binary_big_endian` 1.0) and writing
//! (`binary_little_endian` 1.0): positions, faces, vertex colors and texture coordinates.

use std::collections::{BTreeMap, HashMap};
use std::io::{BufRead, BufWriter, Read, Write};
use std::path::Path;

use glam::{DVec2, DVec3};

use super::write::{FaceBuffers, MeshBuffers, ObjWriteOptions, UvBuffers};
use super::{escape_controls, open, shorten, Budget, ReadOptions, MAX_LINE_BYTES};
use crate::error::{Error, ParseError, Result};
use crate::polygon::{PolygonMesh, Uncarried};
use crate::uv::Uvs;
use crate::{normals, Scalar};

/// The largest count of a list property the reader accepts (a face of 16 Mi corners).
const MAX_LIST_ITEMS: u64 = 1 << 24;

/// Elements preallocated at most from a header's count (the count is not trusted).
const MAX_PREALLOCATED: u64 = 1 << 16;

/// Reads a PLY file (ASCII or binary, either byte order) as a face list: every vertex in file
/// order (used or not), faces with their corners in file order, vertex colors and texture
/// coordinates (see the [`crate::io`] docs, section PLY).
///
/// # Errors
///
/// [`Error::Io`] when the file cannot be read; [`Error::Parse`] naming the file and the
/// header line for a malformed header; [`Error::PlyData`] naming the file, the element, its
/// index and the property for bad data (a vertex index out of range, a face of fewer than 3
/// corners, a list count that is negative or above 16 Mi, a non-finite coordinate, color or
/// texture coordinate, text that is not a number in ASCII data, data that ends early);
/// [`Error::NoFaces`] for a file without faces.
///
/// # Example
///
/// ```no_run
/// let mesh = halfedge::io::read_ply("bunny.ply")?;
/// println!("{} faces", mesh.n_faces());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_ply(path: impl AsRef<Path>) -> Result<PolygonMesh> {
    read_ply_with(path, &ReadOptions::DEFAULT)
}

/// [`read_ply`] within the memory limit of `options` ([`ReadOptions::available_bytes`]: a
/// larger file is [`Error::FileTooLarge`] before it is read, a mesh outgrowing half of it
/// [`Error::MeshTooLarge`]); PLY has no tags.
///
/// # Errors
///
/// As [`read_ply`], and the memory refusals.
pub fn read_ply_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<PolygonMesh> {
    let path = path.as_ref();
    read_ply_within(
        open(path, options.available_bytes)?,
        &path.display().to_string(),
        Budget::of(options),
    )
}

/// Reads PLY data from any buffered reader; `name` is the file name used in error messages.
///
/// # Errors
///
/// As [`read_ply`].
///
/// # Example
///
/// ```
/// let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
///             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
///             end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
/// let mesh = halfedge::io::read_ply_from(text.as_bytes(), "triangle.ply")?;
/// assert_eq!((mesh.n_vertices(), mesh.face(0)), (3, &[0, 1, 2][..]));
///
/// let bad = text.replace("3 0 1 2", "3 0 1 7");
/// let err = halfedge::io::read_ply_from(bad.as_bytes(), "bad.ply").unwrap_err();
/// assert_eq!(err.to_string(), "bad.ply: face 0: vertex index 7 is out of range (the file has 3 vertices)");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_ply_from(reader: impl BufRead, name: &str) -> Result<PolygonMesh> {
    read_ply_within(reader, name, Budget::of(&ReadOptions::DEFAULT))
}

/// [`read_ply_from`] with the mesh's memory limited to `budget`.
pub(crate) fn read_ply_within(
    reader: impl BufRead,
    name: &str,
    budget: Budget,
) -> Result<PolygonMesh> {
    let mut source = Source {
        reader,
        file: escape_controls(name).into_owned(),
        buf: Vec::new(),
        line: 0,
    };
    let header = read_header(&mut source, budget)?;
    let mut body = Body::new(source, &header, budget);
    for element in &header.elements {
        match element.kind {
            Kind::Vertex => body.vertices(element)?,
            Kind::Face => body.faces(element)?,
            Kind::Other => body.skip_element(element)?,
        }
    }
    body.finish(header)
}

// ---------------------------------------------------------------------------------------
// The header.

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Type {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Type {
    fn parse(name: &str) -> Option<Type> {
        Some(match name {
            "char" | "int8" => Type::I8,
            "uchar" | "uint8" => Type::U8,
            "short" | "int16" => Type::I16,
            "ushort" | "uint16" => Type::U16,
            "int" | "int32" => Type::I32,
            "uint" | "uint32" => Type::U32,
            "float" | "float32" => Type::F32,
            "double" | "float64" => Type::F64,
            _ => return None,
        })
    }

    /// The type's name in messages.
    fn name(self) -> &'static str {
        match self {
            Type::I8 => "char",
            Type::U8 => "uchar",
            Type::I16 => "short",
            Type::U16 => "ushort",
            Type::I32 => "int",
            Type::U32 => "uint",
            Type::F32 => "float",
            Type::F64 => "double",
        }
    }

    fn size(self) -> usize {
        match self {
            Type::I8 | Type::U8 => 1,
            Type::I16 | Type::U16 => 2,
            Type::I32 | Type::U32 | Type::F32 => 4,
            Type::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Type::F32 | Type::F64)
    }

    /// The value of `bytes` (exactly [`size`](Self::size) of them): every PLY type is exact
    /// in `f64`.
    fn decode(self, bytes: &[u8], big_endian: bool) -> f64 {
        macro_rules! decode {
            ($t:ty, $n:literal) => {{
                let mut a = [0u8; $n];
                a.copy_from_slice(&bytes[..$n]);
                f64::from(if big_endian {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                })
            }};
        }
        match self {
            Type::I8 => decode!(i8, 1),
            Type::U8 => decode!(u8, 1),
            Type::I16 => decode!(i16, 2),
            Type::U16 => decode!(u16, 2),
            Type::I32 => decode!(i32, 4),
            Type::U32 => decode!(u32, 4),
            Type::F32 => decode!(f32, 4),
            Type::F64 => decode!(f64, 8),
        }
    }

    /// The value of an ASCII token: an integer in the type's range, or a float read in the
    /// type's precision (a `float` is rounded to `f32`, as its binary form would be).
    fn parse_text(self, token: &str) -> Option<f64> {
        let (low, high): (i64, i64) = match self {
            Type::F32 => return token.parse::<f32>().ok().map(f64::from),
            Type::F64 => return token.parse::<f64>().ok(),
            Type::I8 => (i8::MIN.into(), i8::MAX.into()),
            Type::U8 => (0, u8::MAX.into()),
            Type::I16 => (i16::MIN.into(), i16::MAX.into()),
            Type::U16 => (0, u16::MAX.into()),
            Type::I32 => (i32::MIN.into(), i32::MAX.into()),
            Type::U32 => (0, u32::MAX.into()),
        };
        let value = token.parse::<i64>().ok()?;
        (low..=high).contains(&value).then_some(value as f64)
    }
}

/// A property's values: one scalar, or a list (a count, then that many items).
#[derive(Clone, Copy, Debug)]
enum Shape {
    Scalar(Type),
    List { count: Type, item: Type },
}

/// What the reader does with a property's values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Skip,
    /// Coordinate `k` of a vertex position (`x`, `y`, `z`).
    Position(usize),
    /// Component `k` of a vertex color (`red`, `green`, `blue`).
    Color(usize),
    /// Component `k` of a vertex's texture coordinate (`s t`, `u v`, `texture_u texture_v`).
    VertexUv(usize),
    /// A face's corners (`vertex_indices` or `vertex_index`).
    Indices,
    /// A face's texture coordinates, `u v` per corner (`texcoord`).
    TexCoord,
}

#[derive(Debug)]
struct Property {
    name: String,
    /// The name for messages (shortened, control characters escaped).
    label: String,
    shape: Shape,
    line: u64,
    role: Role,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Vertex,
    Face,
    Other,
}

#[derive(Debug)]
struct Element {
    /// The name for messages (shortened, control characters escaped).
    label: String,
    count: u64,
    line: u64,
    kind: Kind,
    properties: Vec<Property>,
}

/// Where the texture coordinates come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum UvSource {
    PerVertex,
    PerFace,
}

#[derive(Debug)]
struct Header {
    /// `None` for ASCII, else whether the data is big-endian.
    big_endian: Option<bool>,
    elements: Vec<Element>,
    /// The line of `end_header`.
    end_line: u64,
    vertices: u64,
    colors: bool,
    uvs: Option<UvSource>,
    uncarried: Vec<Uncarried>,
    /// The bytes the header's lists occupy (an estimate), counted against the budget.
    bytes: usize,
}

/// Reads lines of a PLY file, counting them.
struct Source<R> {
    reader: R,
    file: String,
    buf: Vec<u8>,
    line: u64,
}

/// Why a line could not be read.
enum LineError {
    Io(std::io::Error),
    Bad(ParseError),
}

impl<R: BufRead> Source<R> {
    /// The next line without its end and trailing whitespace, into `text`; false at the end
    /// of the file. At most [`MAX_LINE_BYTES`] are read of a line, which must be text.
    fn next_line(&mut self, text: &mut String) -> std::result::Result<bool, LineError> {
        text.clear();
        self.buf.clear();
        let n = (&mut self.reader)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', &mut self.buf)
            .map_err(LineError::Io)?;
        if n == 0 {
            return Ok(false);
        }
        self.line += 1;
        if n > MAX_LINE_BYTES {
            return Err(LineError::Bad(ParseError::LineTooLong {
                limit: MAX_LINE_BYTES,
            }));
        }
        if self.buf.contains(&0) {
            return Err(LineError::Bad(ParseError::NotText));
        }
        let s = std::str::from_utf8(&self.buf).map_err(|_| LineError::Bad(ParseError::NotText))?;
        text.push_str(s.trim_end());
        Ok(true)
    }

    fn io(&self, source: std::io::Error) -> Error {
        Error::Io {
            path: self.file.clone().into(),
            source,
        }
    }

    /// An error of the header line just read.
    fn header_error(&self, kind: ParseError) -> Error {
        self.error_at(self.line, kind)
    }

    fn error_at(&self, line: u64, kind: ParseError) -> Error {
        Error::Parse {
            file: self.file.clone(),
            line,
            kind,
        }
    }

    fn line_error(&self, e: LineError) -> Error {
        match e {
            LineError::Io(e) => self.io(e),
            LineError::Bad(kind) => self.header_error(kind),
        }
    }
}

fn malformed(what: impl Into<String>) -> ParseError {
    ParseError::Malformed { what: what.into() }
}

/// Reads the header, up to and including `end_header`, and decides what each property is.
fn read_header<R: BufRead>(source: &mut Source<R>, budget: Budget) -> Result<Header> {
    let mut text = String::new();
    if !source
        .next_line(&mut text)
        .map_err(|e| source.line_error(e))?
    {
        return Err(source.error_at(
            1,
            malformed("expected `ply` on the first line, the file is empty"),
        ));
    }
    if text != "ply" {
        let what = format!(
            "expected `ply` on the first line, found `{}`",
            shorten(&text)
        );
        return Err(source.header_error(malformed(what)));
    }
    let mut format: Option<Option<bool>> = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut bytes = 0usize;
    loop {
        if !source
            .next_line(&mut text)
            .map_err(|e| source.line_error(e))?
        {
            return Err(source.header_error(ParseError::UnexpectedEnd {
                what: "the header has no `end_header` line".into(),
            }));
        }
        let mut tokens = text.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        let rest: Vec<&str> = tokens.collect();
        match keyword {
            "comment" | "obj_info" => {}
            "format" => {
                if format.is_some() {
                    return Err(source.header_error(malformed("a second `format` line")));
                }
                let one = rest.get(1).and_then(|v| v.parse::<f64>().ok()) == Some(1.0);
                let kind = match (rest.first().copied(), one, rest.len()) {
                    (Some("ascii"), true, 2) => None,
                    (Some("binary_little_endian"), true, 2) => Some(false),
                    (Some("binary_big_endian"), true, 2) => Some(true),
                    _ => {
                        let what = format!(
                            "unknown format `{}` (expected ascii 1.0, binary_little_endian 1.0 \
                             or binary_big_endian 1.0)",
                            shorten(&rest.join(" "))
                        );
                        return Err(source.header_error(malformed(what)));
                    }
                };
                format = Some(kind);
            }
            "element" => {
                let &[name, count] = rest.as_slice() else {
                    return Err(source.header_error(malformed("expected `element NAME COUNT`")));
                };
                let count = count.parse::<u64>().map_err(|_| {
                    source.header_error(ParseError::InvalidNumber {
                        token: shorten(count),
                        expected: "element count",
                    })
                })?;
                let kind = match name {
                    "vertex" => Kind::Vertex,
                    "face" => Kind::Face,
                    _ => Kind::Other,
                };
                if kind != Kind::Other && elements.iter().any(|e| e.kind == kind) {
                    let what = format!("a second `{name}` element");
                    return Err(source.header_error(malformed(what)));
                }
                if kind == Kind::Vertex && count >= u64::from(u32::MAX) {
                    let what = format!("{count} vertices do not fit 32-bit indices");
                    return Err(source.header_error(malformed(what)));
                }
                bytes += std::mem::size_of::<Element>() + name.len();
                elements.push(Element {
                    label: shorten(name),
                    count,
                    line: source.line,
                    kind,
                    properties: Vec::new(),
                });
            }
            "property" => {
                let Some(element) = elements.last_mut() else {
                    let what = "`property` line before any `element` line";
                    return Err(source.header_error(malformed(what)));
                };
                let (shape, name) = parse_property(&rest).map_err(|k| source.header_error(k))?;
                if element.properties.iter().any(|p| p.name == name) {
                    let what = format!(
                        "a second property `{}` in element `{}`",
                        shorten(name),
                        element.label
                    );
                    return Err(source.header_error(malformed(what)));
                }
                bytes += std::mem::size_of::<Property>() + 2 * name.len();
                element.properties.push(Property {
                    name: name.to_string(),
                    label: shorten(name),
                    shape,
                    line: source.line,
                    role: Role::Skip,
                });
            }
            "end_header" => {
                if !rest.is_empty() {
                    let what = format!("unexpected `{}` after `end_header`", shorten(rest[0]));
                    return Err(source.header_error(malformed(what)));
                }
                break;
            }
            other => {
                let what = format!(
                    "unknown header line `{}` (expected format, comment, obj_info, element, \
                     property or end_header)",
                    shorten(other)
                );
                return Err(source.header_error(malformed(what)));
            }
        }
        if bytes as u64 > budget.bytes {
            return Err(Error::MeshTooLarge {
                file: source.file.clone(),
                line: source.line,
                limit: budget.bytes,
            });
        }
    }
    let Some(big_endian) = format else {
        return Err(source.header_error(malformed("the header has no `format` line")));
    };
    let mut header = Header {
        big_endian,
        elements,
        end_line: source.line,
        vertices: 0,
        colors: false,
        uvs: None,
        uncarried: Vec::new(),
        bytes,
    };
    plan(&mut header, source)?;
    Ok(header)
}

/// `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME` (the tokens after
/// `property`): the shape and the name.
fn parse_property<'a>(rest: &[&'a str]) -> std::result::Result<(Shape, &'a str), ParseError> {
    let ty = |name: &str| {
        Type::parse(name)
            .ok_or_else(|| malformed(format!("unknown property type `{}`", shorten(name))))
    };
    match *rest {
        ["list", count, item, name] => {
            let count = ty(count)?;
            if !count.is_integer() {
                let what = format!("list count type `{}` is not an integer type", count.name());
                return Err(malformed(what));
            }
            Ok((
                Shape::List {
                    count,
                    item: ty(item)?,
                },
                name,
            ))
        }
        [t, name] if t != "list" => Ok((Shape::Scalar(ty(t)?), name)),
        _ => Err(malformed(
            "expected `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`",
        )),
    }
}

/// Gives every property its role, checks that the vertex and face elements have what they
/// need, and lists what is not carried.
fn plan<R: BufRead>(header: &mut Header, source: &Source<R>) -> Result<()> {
    let end = header.end_line;
    let find = |kind: Kind| header.elements.iter().position(|e| e.kind == kind);
    let Some(v) = find(Kind::Vertex) else {
        return Err(source.error_at(end, malformed("the header has no `vertex` element")));
    };
    let Some(f) = find(Kind::Face) else {
        return Err(source.error_at(end, malformed("the header has no `face` element")));
    };
    // The face element: its corners and texture coordinates.
    let face = &mut header.elements[f];
    let corners = ["vertex_indices", "vertex_index"]
        .iter()
        .find_map(|name| face.properties.iter().position(|p| p.name == *name));
    let Some(corners) = corners else {
        let what = "element `face` has no list property `vertex_indices` (or `vertex_index`)";
        return Err(source.error_at(face.line, malformed(what)));
    };
    let p = &mut face.properties[corners];
    match p.shape {
        Shape::List { item, .. } if item.is_integer() => p.role = Role::Indices,
        Shape::List { item, .. } => {
            let what = format!(
                "property `{}` of element `face` has `{}` items, expected an integer type",
                p.label,
                item.name()
            );
            return Err(source.error_at(p.line, malformed(what)));
        }
        Shape::Scalar(_) => {
            let what = format!("property `{}` of element `face` is not a list", p.label);
            return Err(source.error_at(p.line, malformed(what)));
        }
    }
    let per_face = match face
        .properties
        .iter_mut()
        .find(|p| p.name == "texcoord" && matches!(p.shape, Shape::List { .. }))
    {
        Some(p) => {
            p.role = Role::TexCoord;
            true
        }
        None => false,
    };
    // The vertex element: positions, colors, texture coordinates.
    let vertex = &mut header.elements[v];
    header.vertices = vertex.count;
    for (k, name) in ["x", "y", "z"].into_iter().enumerate() {
        let Some(i) = vertex.properties.iter().position(|p| p.name == name) else {
            let what = format!("element `vertex` has no property `{name}`");
            return Err(source.error_at(vertex.line, malformed(what)));
        };
        let p = &mut vertex.properties[i];
        if let Shape::List { .. } = p.shape {
            let what =
                format!("property `{name}` of element `vertex` is a list, expected a number");
            return Err(source.error_at(p.line, malformed(what)));
        }
        p.role = Role::Position(k);
    }
    let scalar = |vertex: &Element, name: &str| {
        vertex
            .properties
            .iter()
            .position(|p| p.name == name && matches!(p.shape, Shape::Scalar(_)))
    };
    let rgb: Vec<usize> = ["red", "green", "blue"]
        .iter()
        .filter_map(|name| scalar(vertex, name))
        .collect();
    if rgb.len() == 3 {
        for (k, i) in rgb.into_iter().enumerate() {
            vertex.properties[i].role = Role::Color(k);
        }
        header.colors = true;
    }
    let pair = [("s", "t"), ("u", "v"), ("texture_u", "texture_v")]
        .iter()
        .find_map(|(a, b)| Some((scalar(vertex, a)?, scalar(vertex, b)?)));
    header.uvs = match (per_face, pair) {
        (true, _) => Some(UvSource::PerFace),
        (false, Some((a, b))) => {
            vertex.properties[a].role = Role::VertexUv(0);
            vertex.properties[b].role = Role::VertexUv(1);
            Some(UvSource::PerVertex)
        }
        (false, None) => None,
    };
    // What is not carried: whole elements, and the skipped properties of `vertex` and `face`.
    let mut uncarried: BTreeMap<String, u64> = BTreeMap::new();
    for e in header.elements.iter().filter(|e| e.count > 0) {
        if e.kind == Kind::Other {
            *uncarried
                .entry(format!("`{}` elements", e.label))
                .or_default() += e.count;
            continue;
        }
        for p in e.properties.iter().filter(|p| p.role == Role::Skip) {
            let what = format!("values of `{}` property `{}`", e.label, p.label);
            *uncarried.entry(what).or_default() += e.count;
        }
    }
    header.bytes += uncarried.keys().map(|k| k.len() + 64).sum::<usize>();
    header.uncarried = uncarried
        .into_iter()
        .map(|(what, count)| Uncarried { what, count })
        .collect();
    Ok(())
}

// ---------------------------------------------------------------------------------------
// The data.

/// The faces read so far: with the line of each (ASCII data: [`PolygonMesh::face_line`]), or
/// plain arrays (binary data has no lines).
enum Faces {
    Lines(Box<PolygonMesh>),
    Plain {
        offsets: Vec<usize>,
        indices: Vec<u32>,
    },
}

impl Faces {
    fn bytes(&self) -> usize {
        match self {
            Faces::Lines(mesh) => mesh.heap_bytes(),
            Faces::Plain { offsets, indices } => {
                std::mem::size_of_val(offsets.as_slice())
                    + std::mem::size_of_val(indices.as_slice())
            }
        }
    }

    fn n_faces(&self) -> usize {
        match self {
            Faces::Lines(mesh) => mesh.n_faces(),
            Faces::Plain { offsets, .. } => offsets.len() - 1,
        }
    }

    fn indices(&self) -> &[u32] {
        match self {
            Faces::Lines(mesh) => mesh.face_indices(),
            Faces::Plain { indices, .. } => indices,
        }
    }

    fn push(
        &mut self,
        corners: &[u32],
        line: u64,
    ) -> std::result::Result<(), std::collections::TryReserveError> {
        match self {
            Faces::Lines(mesh) => mesh.try_push_face_from_line(corners, line),
            Faces::Plain { offsets, indices } => {
                offsets.try_reserve(1)?;
                indices.try_reserve(corners.len())?;
                indices.extend_from_slice(corners);
                offsets.push(indices.len());
                Ok(())
            }
        }
    }

    fn into_mesh(self, positions: Vec<DVec3>) -> PolygonMesh {
        match self {
            Faces::Lines(mut mesh) => {
                mesh.positions = positions;
                *mesh
            }
            Faces::Plain { offsets, indices } => {
                PolygonMesh::from_raw_parts(positions, offsets, indices)
            }
        }
    }
}

/// Per-face texture coordinates: the distinct (bit-for-bit) `(u, v)` pairs in order of first
/// appearance, and the value of every corner.
#[derive(Default)]
struct FaceUvs {
    coords: Vec<DVec2>,
    corners: Vec<u32>,
    ids: HashMap<[u64; 2], u32>,
}

impl FaceUvs {
    fn bytes(&self) -> usize {
        std::mem::size_of_val(self.coords.as_slice())
            + std::mem::size_of_val(self.corners.as_slice())
            + 32 * self.ids.capacity()
    }
}

/// The reader of the data after the header, and what it keeps.
struct Body<R> {
    source: Source<R>,
    /// `None` for ASCII.
    big_endian: Option<bool>,
    /// ASCII: the current line and the position of its next token.
    text: String,
    pos: usize,
    /// The line where binary data starts (for [`Error::MeshTooLarge`]).
    data_line: u64,
    budget: Budget,
    header_bytes: usize,
    vertices: u64,
    positions: Vec<DVec3>,
    colors: Vec<[f64; 3]>,
    vertex_uvs: Vec<DVec2>,
    faces: Faces,
    face_uvs: FaceUvs,
    /// The corners and texture coordinates of the face being read.
    corners: Vec<u32>,
    texcoord: Vec<f64>,
}

/// Where a value is: an element and its index, and the property.
#[derive(Clone, Copy)]
struct At<'a> {
    element: &'a Element,
    index: u64,
}

impl<R: BufRead> Body<R> {
    fn new(source: Source<R>, header: &Header, budget: Budget) -> Body<R> {
        let faces = match header.big_endian {
            None => Faces::Lines(Box::default()),
            Some(_) => Faces::Plain {
                offsets: vec![0],
                indices: Vec::new(),
            },
        };
        let data_line = header.end_line + 1;
        Body {
            source,
            big_endian: header.big_endian,
            text: String::new(),
            pos: 0,
            data_line,
            budget,
            header_bytes: header.bytes,
            vertices: header.vertices,
            positions: Vec::new(),
            colors: Vec::new(),
            vertex_uvs: Vec::new(),
            faces,
            face_uvs: FaceUvs::default(),
            corners: Vec::new(),
            texcoord: Vec::new(),
        }
    }

    fn error(&self, at: At<'_>, property: Option<&Property>, kind: ParseError) -> Error {
        Error::PlyData {
            file: self.source.file.clone(),
            element: at.element.label.clone(),
            index: at.index,
            property: property.map(|p| p.label.clone()),
            kind: Box::new(kind),
        }
    }

    fn truncated(&self, at: At<'_>, property: Option<&Property>) -> Error {
        let what = format!(
            "the header declares {} `{}` elements",
            at.element.count, at.element.label
        );
        self.error(at, property, ParseError::UnexpectedEnd { what })
    }

    fn allocation_failed(
        &self,
        at: At<'_>,
        bytes: u128,
        e: std::collections::TryReserveError,
    ) -> Error {
        Error::AllocationFailed {
            what: format!(
                "the mesh read from {} ({} {})",
                self.source.file, at.element.label, at.index
            ),
            bytes,
            reason: e.to_string(),
        }
    }

    /// The bytes of everything kept so far (the mesh, the reader's lists, the header's).
    fn used(&self) -> u128 {
        let kept = std::mem::size_of_val(self.positions.as_slice())
            + std::mem::size_of_val(self.colors.as_slice())
            + std::mem::size_of_val(self.vertex_uvs.as_slice())
            + self.faces.bytes()
            + self.face_uvs.bytes()
            + 4 * self.corners.capacity()
            + 8 * self.texcoord.capacity()
            + self.header_bytes;
        kept as u128
    }

    /// Refuses once `used() + adding` bytes outgrow the budget.
    fn check(&self, adding: u128) -> Result<()> {
        if self.used() + adding > u128::from(self.budget.bytes) {
            let line = match self.big_endian {
                None => self.source.line,
                Some(_) => self.data_line,
            };
            return Err(Error::MeshTooLarge {
                file: self.source.file.clone(),
                line,
                limit: self.budget.bytes,
            });
        }
        Ok(())
    }

    /// Starts an element: ASCII data reads its line (blank lines are skipped).
    fn begin(&mut self, at: At<'_>) -> Result<()> {
        if self.big_endian.is_some() {
            return Ok(());
        }
        loop {
            match self.source.next_line(&mut self.text) {
                Ok(true) if self.text.is_empty() => continue,
                Ok(true) => {
                    self.pos = 0;
                    return Ok(());
                }
                Ok(false) => return Err(self.truncated(at, None)),
                Err(LineError::Io(e)) => return Err(self.source.io(e)),
                Err(LineError::Bad(kind)) => return Err(self.error(at, None, kind)),
            }
        }
    }

    /// Ends an element: ASCII data must have no value left on its line.
    fn end(&mut self, at: At<'_>) -> Result<()> {
        if self.big_endian.is_none() {
            if let Some((a, b)) = self.token() {
                let token = shorten(&self.text[a..b]);
                return Err(self.error(at, None, ParseError::UnexpectedToken { token }));
            }
        }
        Ok(())
    }

    /// The next whitespace-separated token of the ASCII line, as a range of `text`.
    fn token(&mut self) -> Option<(usize, usize)> {
        let bytes = self.text.as_bytes();
        let mut i = self.pos;
        while i < bytes.len() && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        let start = i;
        while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        self.pos = i;
        (i > start).then_some((start, i))
    }

    /// The next value, of type `ty`, of `property`; with `finite`, a NaN or infinite value is
    /// an error.
    fn scalar(&mut self, ty: Type, at: At<'_>, property: &Property, finite: bool) -> Result<f64> {
        let (value, token) = match self.big_endian {
            None => {
                let Some((a, b)) = self.token() else {
                    let kind = malformed("no value on the line");
                    return Err(self.error(at, Some(property), kind));
                };
                let token = &self.text[a..b];
                let Some(value) = ty.parse_text(token) else {
                    let kind = ParseError::InvalidNumber {
                        token: shorten(token),
                        expected: ty.name(),
                    };
                    return Err(self.error(at, Some(property), kind));
                };
                (value, Some((a, b)))
            }
            Some(big_endian) => {
                let mut bytes = [0u8; 8];
                let bytes = &mut bytes[..ty.size()];
                if let Err(e) = self.source.reader.read_exact(bytes) {
                    return Err(match e.kind() {
                        std::io::ErrorKind::UnexpectedEof => self.truncated(at, Some(property)),
                        _ => self.source.io(e),
                    });
                }
                (ty.decode(bytes, big_endian), None)
            }
        };
        if finite && !value.is_finite() {
            let token = match token {
                Some((a, b)) => shorten(&self.text[a..b]),
                None => value.to_string(),
            };
            let kind = ParseError::NonFiniteCoordinate { token };
            return Err(self.error(at, Some(property), kind));
        }
        Ok(value)
    }

    /// A list's count: an integer from 0 to [`MAX_LIST_ITEMS`].
    fn list_count(&mut self, ty: Type, at: At<'_>, property: &Property) -> Result<u64> {
        let count = self.scalar(ty, at, property, false)?;
        if !(0.0..=MAX_LIST_ITEMS as f64).contains(&count) {
            let kind = ParseError::ListCount {
                count: count as i64,
                limit: MAX_LIST_ITEMS,
            };
            return Err(self.error(at, Some(property), kind));
        }
        Ok(count as u64)
    }

    /// Skips `n` values of type `ty` (ASCII values are checked to be numbers of the type).
    fn skip(&mut self, ty: Type, n: u64, at: At<'_>, property: &Property) -> Result<()> {
        match self.big_endian {
            None => {
                for _ in 0..n {
                    self.scalar(ty, at, property, false)?;
                }
                Ok(())
            }
            Some(_) => {
                let bytes = n * ty.size() as u64;
                if self.skip_bytes(bytes)? < bytes {
                    return Err(self.truncated(at, Some(property)));
                }
                Ok(())
            }
        }
    }

    /// Skips up to `n` bytes of binary data; the bytes skipped.
    fn skip_bytes(&mut self, n: u64) -> Result<u64> {
        let mut data = (&mut self.source.reader).take(n);
        std::io::copy(&mut data, &mut std::io::sink()).map_err(|e| self.source.io(e))
    }

    /// Skips a property's value or list, checking it.
    fn skip_property(&mut self, at: At<'_>, property: &Property) -> Result<()> {
        match property.shape {
            Shape::Scalar(ty) => self.skip(ty, 1, at, property),
            Shape::List { count, item } => {
                let n = self.list_count(count, at, property)?;
                self.skip(item, n, at, property)
            }
        }
    }

    /// Skips every value of an element no output carries.
    fn skip_element(&mut self, element: &Element) -> Result<()> {
        if element.properties.is_empty() {
            return Ok(());
        }
        let scalars: Option<u64> = element
            .properties
            .iter()
            .map(|p| match p.shape {
                Shape::Scalar(ty) => Some(ty.size() as u64),
                Shape::List { .. } => None,
            })
            .sum();
        if let (Some(_), Some(stride)) = (self.big_endian, scalars) {
            // Fixed-size elements: skipped in one go.
            let total = u128::from(element.count) * u128::from(stride);
            let skipped = self.skip_bytes(u64::try_from(total).unwrap_or(u64::MAX))?;
            if u128::from(skipped) < total {
                let at = At {
                    element,
                    index: skipped / stride,
                };
                return Err(self.truncated(at, None));
            }
            return Ok(());
        }
        for index in 0..element.count {
            let at = At { element, index };
            self.begin(at)?;
            for property in &element.properties {
                self.skip_property(at, property)?;
            }
            self.end(at)?;
        }
        Ok(())
    }

    /// Reads the vertex element: positions, and colors and texture coordinates if the header
    /// has them.
    fn vertices(&mut self, element: &Element) -> Result<()> {
        let colors = element
            .properties
            .iter()
            .any(|p| matches!(p.role, Role::Color(_)));
        let uvs = element
            .properties
            .iter()
            .any(|p| matches!(p.role, Role::VertexUv(_)));
        let room = |bytes: u64| {
            element
                .count
                .min(MAX_PREALLOCATED)
                .min(self.budget.bytes / 4 / bytes) as usize
        };
        let _ = self.positions.try_reserve_exact(room(24));
        if colors {
            let _ = self.colors.try_reserve_exact(room(24));
        }
        if uvs {
            let _ = self.vertex_uvs.try_reserve_exact(room(16));
        }
        for index in 0..element.count {
            let at = At { element, index };
            self.begin(at)?;
            let (mut p, mut c, mut t) = ([0.0; 3], [0.0; 3], [0.0; 2]);
            for property in &element.properties {
                match (property.shape, property.role) {
                    (Shape::Scalar(ty), Role::Position(k)) => {
                        p[k] = self.scalar(ty, at, property, true)?;
                    }
                    (Shape::Scalar(ty), Role::Color(k)) => {
                        let value = self.scalar(ty, at, property, true)?;
                        c[k] = if ty == Type::U8 { value / 255.0 } else { value };
                    }
                    (Shape::Scalar(ty), Role::VertexUv(k)) => {
                        t[k] = self.scalar(ty, at, property, true)?;
                    }
                    _ => self.skip_property(at, property)?,
                }
            }
            self.end(at)?;
            let adding = 24 + if colors { 24 } else { 0 } + if uvs { 16 } else { 0 };
            self.check(adding)?;
            let refused = |body: &Self, e| body.allocation_failed(at, adding, e);
            self.positions
                .try_reserve(1)
                .map_err(|e| refused(self, e))?;
            self.positions.push(DVec3::from_array(p));
            if colors {
                self.colors.try_reserve(1).map_err(|e| refused(self, e))?;
                self.colors.push(c);
            }
            if uvs {
                self.vertex_uvs
                    .try_reserve(1)
                    .map_err(|e| refused(self, e))?;
                self.vertex_uvs.push(DVec2::from_array(t));
            }
        }
        Ok(())
    }

    /// Reads the face element: corners, and texture coordinates if it has `texcoord`.
    fn faces(&mut self, element: &Element) -> Result<()> {
        let texcoord = element.properties.iter().find(|p| p.role == Role::TexCoord);
        for index in 0..element.count {
            let at = At { element, index };
            self.begin(at)?;
            let line = self.source.line;
            self.corners.clear();
            self.texcoord.clear();
            for property in &element.properties {
                match (property.shape, property.role) {
                    (Shape::List { count, item }, Role::Indices) => {
                        let n = self.list_count(count, at, property)?;
                        if n < 3 {
                            let kind = ParseError::FaceTooSmall {
                                corners: n as usize,
                            };
                            return Err(self.error(at, None, kind));
                        }
                        for _ in 0..n {
                            let value = self.scalar(item, at, property, false)?;
                            let index = value as i64;
                            if index < 0 || index as u64 >= self.vertices {
                                let kind = ParseError::VertexIndexOutOfRange {
                                    index,
                                    vertices: self.vertices,
                                };
                                return Err(self.error(at, None, kind));
                            }
                            self.check(4)?;
                            self.corners
                                .try_reserve(1)
                                .map_err(|e| self.allocation_failed(at, 4, e))?;
                            self.corners.push(index as u32);
                        }
                    }
                    (Shape::List { count, item }, Role::TexCoord) => {
                        let n = self.list_count(count, at, property)?;
                        for _ in 0..n {
                            let value = self.scalar(item, at, property, true)?;
                            self.check(8)?;
                            self.texcoord
                                .try_reserve(1)
                                .map_err(|e| self.allocation_failed(at, 8, e))?;
                            self.texcoord.push(value);
                        }
                    }
                    _ => self.skip_property(at, property)?,
                }
            }
            self.end(at)?;
            let k = self.corners.len();
            if let Some(property) = texcoord {
                if self.texcoord.len() != 2 * k {
                    let what = format!(
                        "{} values for a face of {k} corners (expected {}: u v per corner)",
                        self.texcoord.len(),
                        2 * k
                    );
                    return Err(self.error(at, Some(property), malformed(what)));
                }
            }
            // The face's corners, offset and line; its corners' texture coordinates (at most
            // a new value, 16 bytes and a map entry, each).
            let uv_bytes = if texcoord.is_some() { 4 + 16 + 32 } else { 0 };
            let adding = (k * (4 + uv_bytes) + 16) as u128;
            self.check(adding)?;
            let corners = std::mem::take(&mut self.corners);
            let pushed = self.faces.push(&corners, line);
            self.corners = corners;
            pushed.map_err(|e| self.allocation_failed(at, adding, e))?;
            if texcoord.is_some() {
                self.push_face_uvs(at)?;
            }
        }
        Ok(())
    }

    /// Records the texture coordinates of the face just read, a value per distinct pair.
    fn push_face_uvs(&mut self, at: At<'_>) -> Result<()> {
        let uvs = &mut self.face_uvs;
        let failed = uvs
            .corners
            .try_reserve(self.texcoord.len() / 2)
            .and_then(|()| uvs.ids.try_reserve(self.texcoord.len() / 2))
            .and_then(|()| uvs.coords.try_reserve(self.texcoord.len() / 2));
        if let Err(e) = failed {
            return Err(self.allocation_failed(at, 52 * self.texcoord.len() as u128 / 2, e));
        }
        for uv in self.texcoord.chunks_exact(2) {
            let next = uvs.coords.len();
            if next >= u32::MAX as usize {
                let kind = malformed("more than 4294967294 distinct texture coordinates");
                return Err(self.error(at, None, kind));
            }
            let id = *uvs
                .ids
                .entry([uv[0].to_bits(), uv[1].to_bits()])
                .or_insert(next as u32);
            if id as usize == next {
                uvs.coords.push(DVec2::new(uv[0], uv[1]));
            }
            uvs.corners.push(id);
        }
        Ok(())
    }

    /// The mesh read, with its colors, texture coordinates and what it does not carry.
    fn finish(mut self, header: Header) -> Result<PolygonMesh> {
        if self.faces.n_faces() == 0 {
            return Err(Error::NoFaces {
                file: self.source.file.clone(),
            });
        }
        let uvs = match header.uvs {
            None => None,
            Some(UvSource::PerFace) => {
                let uvs = std::mem::take(&mut self.face_uvs);
                Some(Uvs::from_read(uvs.coords, uvs.corners))
            }
            Some(UvSource::PerVertex) => {
                // A value per vertex: each corner names its vertex's.
                let indices = self.faces.indices();
                self.check(4 * indices.len() as u128)?;
                let mut corners = Vec::new();
                if let Err(e) = corners.try_reserve_exact(indices.len()) {
                    return Err(Error::AllocationFailed {
                        what: format!("the texture coordinates read from {}", self.source.file),
                        bytes: 4 * indices.len() as u128,
                        reason: e.to_string(),
                    });
                }
                corners.extend_from_slice(indices);
                Some(Uvs::from_read(
                    std::mem::take(&mut self.vertex_uvs),
                    corners,
                ))
            }
        };
        let colors = header.colors.then(|| std::mem::take(&mut self.colors));
        let mut mesh = self.faces.into_mesh(self.positions);
        mesh.set_read_uvs(uvs, None);
        mesh.set_read_extras((colors, None), None, header.uncarried);
        Ok(mesh)
    }
}

// ---------------------------------------------------------------------------------------
// Writing.

/// Writes a mesh from caller-owned buffers as binary little-endian PLY: the vertex element
/// (`x y z` as `double`, or `float` when `T` is `f32`; the colors as `uchar` when every
/// component is in `[0, 1]` (rounded `c * 255`), else in `T`; with
/// [`ObjWriteOptions::normals`], `nx ny nz`, the area-weighted vertex normals of the faces;
/// with [`ObjWriteOptions::uvs`] and texture coordinates without seams (one UV value per
/// vertex across its corners), `s t`, 0 at vertices no face uses) and the face element
/// (`vertex_indices`, an `int` per corner after a `uchar` count, `uint` for a face of more
/// than 255 corners; texture coordinates with seams as `texcoord`, `u v` per corner, after a
/// `uchar` count, `uint` for a face of more than 127 corners). Groups are not written.
///
/// # Errors
///
/// [`std::io::ErrorKind::InvalidInput`] as [`write_mesh_buffers_obj`](super::write_mesh_buffers_obj)
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
    let uvs = mesh.uvs.filter(|_| options.uvs);
    let list = MeshBuffers { uvs, ..*mesh }.checked_faces()?;
    let positions = mesh.positions;
    let normals = options.normals.then(|| {
        let position = |v: u32| {
            let [x, y, z] = positions[v as usize];
            DVec3::new(x.to_f64(), y.to_f64(), z.to_f64())
        };
        normals::vertex_normals_by(positions.len(), position, &list)
    });
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
        let ty = if bytes { "uchar" } else { float };
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
                    put(&mut w, c)?;
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
fn per_vertex_uvs<T: Scalar>(
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
fn put<T: Scalar>(w: &mut impl Write, x: T) -> std::io::Result<()> {
    if std::mem::size_of::<T>() == 4 {
        w.write_all(&(x.to_f64() as f32).to_le_bytes())
    } else {
        w.write_all(&x.to_f64().to_le_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
                        property float y\nproperty float z\nelement face 1\n\
                        property list uchar int vertex_indices\nend_header\n";

    fn message(bytes: &[u8]) -> String {
        match read_ply_from(bytes, "m.ply") {
            Ok(mesh) => format!("accepted with {} faces", mesh.n_faces()),
            Err(e) => e.to_string(),
        }
    }

    fn text(s: &str) -> String {
        message(s.as_bytes())
    }

    #[test]
    fn header_errors_name_the_line() {
        let cases: &[(&str, &str)] = &[
            ("", "m.ply: line 1: expected `ply` on the first line, the file is empty"),
            ("PLY\n", "m.ply: line 1: expected `ply` on the first line, found `PLY`"),
            ("ply\n", "m.ply: line 1: the file ends early: the header has no `end_header` line"),
            ("ply\nformat ascii 1.0\nelement vertex 3\n", "m.ply: line 3: the file ends early: the header has no `end_header` line"),
            ("ply\nelement vertex 3\nend_header\n", "m.ply: line 3: the header has no `format` line"),
            ("ply\nformat binary_middle_endian 1.0\n", "m.ply: line 2: unknown format `binary_middle_endian 1.0` (expected ascii 1.0, binary_little_endian 1.0 or binary_big_endian 1.0)"),
            ("ply\nformat ascii 2.0\n", "m.ply: line 2: unknown format `ascii 2.0` (expected ascii 1.0, binary_little_endian 1.0 or binary_big_endian 1.0)"),
            ("ply\nformat ascii 1.0\nformat ascii 1.0\n", "m.ply: line 3: a second `format` line"),
            ("ply\nformat ascii 1.0\nproperty float x\n", "m.ply: line 3: `property` line before any `element` line"),
            ("ply\nformat ascii 1.0\nelement vertex many\n", "m.ply: line 3: `many` is not a valid element count"),
            ("ply\nformat ascii 1.0\nelement vertex -1\n", "m.ply: line 3: `-1` is not a valid element count"),
            ("ply\nformat ascii 1.0\nelement vertex\n", "m.ply: line 3: expected `element NAME COUNT`"),
            ("ply\nformat ascii 1.0\nelement vertex 4294967295\n", "m.ply: line 3: 4294967295 vertices do not fit 32-bit indices"),
            ("ply\nformat ascii 1.0\nelement vertex 3\nproperty half x\n", "m.ply: line 4: unknown property type `half`"),
            ("ply\nformat ascii 1.0\nelement vertex 3\nproperty list float int x\n", "m.ply: line 4: list count type `float` is not an integer type"),
            ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float\n", "m.ply: line 4: expected `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`"),
            ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty double x\n", "m.ply: line 5: a second property `x` in element `vertex`"),
            ("ply\nformat ascii 1.0\nelement vertex 3\nelement vertex 3\n", "m.ply: line 4: a second `vertex` element"),
            ("ply\nformat ascii 1.0\nvertex 3\n", "m.ply: line 3: unknown header line `vertex` (expected format, comment, obj_info, element, property or end_header)"),
            ("ply\nformat ascii 1.0\nend_header now\n", "m.ply: line 3: unexpected `now` after `end_header`"),
            ("ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", "m.ply: line 5: the header has no `vertex` element"),
            ("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n", "m.ply: line 7: the header has no `face` element"),
            ("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", "m.ply: line 3: element `vertex` has no property `z`"),
            ("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty list uchar float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", "m.ply: line 5: property `y` of element `vertex` is a list, expected a number"),
            ("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_index\nend_header\n", "m.ply: the file has no faces"),
            ("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty uchar flags\nend_header\n", "m.ply: line 7: element `face` has no list property `vertex_indices` (or `vertex_index`)"),
            ("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty int vertex_indices\nend_header\n", "m.ply: line 8: property `vertex_indices` of element `face` is not a list"),
            ("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n", "m.ply: line 8: property `vertex_indices` of element `face` has `float` items, expected an integer type"),
            ("ply\nformat ascii 1.0\ncomment \u{1b}[2J\nelement \u{1b}x 1\nend_header\n", "m.ply: line 5: the header has no `vertex` element"),
            ("ply\nformat ascii 1.0\nbogus\u{1b}[2J\n", "m.ply: line 3: unknown header line `bogus\\u{1b}[2J` (expected format, comment, obj_info, element, property or end_header)"),
        ];
        for (input, expected) in cases {
            assert_eq!(text(input), *expected, "{input:?}");
        }
        assert_eq!(
            message(b"ply\nformat binary_little_endian 1.0\n\xff\xfe\n"),
            "m.ply: line 3: not a text line (binary data?)"
        );
    }

    #[test]
    fn data_errors_name_the_element_index_and_property() {
        let cases: &[(&str, &str)] = &[
            (
                "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                "m.ply: face 0: vertex index 3 is out of range (the file has 3 vertices)",
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                "m.ply: face 0: vertex index -1 is out of range (the file has 3 vertices)",
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                "m.ply: face 0: face has 2 vertices, at least 3 are needed",
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
                "m.ply: face 0, property `vertex_indices`: no value on the line",
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 5\n",
                "m.ply: face 0: unexpected `5`",
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n",
                "m.ply: face 0, property `vertex_indices`: `2.5` is not a valid int",
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n",
                "m.ply: face 0, property `vertex_indices`: `300` is not a valid uchar",
            ),
            (
                "0 0 0\n1 0 x\n",
                "m.ply: vertex 1, property `z`: `x` is not a valid float",
            ),
            (
                "0 0 0\n1 0 inf\n",
                "m.ply: vertex 1, property `z`: coordinate `inf` is not finite",
            ),
            (
                "0 0 0\n1 0 1e39\n",
                "m.ply: vertex 1, property `z`: coordinate `1e39` is not finite",
            ),
            (
                "0 0 0\n1 0 0\n",
                "m.ply: vertex 2: the file ends early: the header declares 3 `vertex` elements",
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n",
                "m.ply: face 0: the file ends early: the header declares 1 `face` elements",
            ),
            (
                "0 0 0\n\n1 0 0\n  \n0 1 0\n3 0 1 2\n",
                "accepted with 1 faces",
            ),
        ];
        for (data, expected) in cases {
            assert_eq!(text(&format!("{HEAD}{data}")), *expected, "{data:?}");
        }
        let long = HEAD.replace("uchar int", "int int");
        assert_eq!(
            text(&format!("{long}0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n")),
            "m.ply: face 0, property `vertex_indices`: list count -3 is not valid (expected 0 to 16777216)"
        );
        assert_eq!(
            text(&format!("{long}0 0 0\n1 0 0\n0 1 0\n16777217 0 1 2\n")),
            "m.ply: face 0, property `vertex_indices`: list count 16777217 is not valid (expected 0 to 16777216)"
        );
    }

    /// A binary file: the header, then `body`.
    fn binary(header: &str, body: &[u8]) -> Vec<u8> {
        let mut bytes = header.as_bytes().to_vec();
        bytes.extend_from_slice(body);
        bytes
    }

    #[test]
    fn binary_truncation_and_hostile_counts() {
        let header = HEAD.replace("ascii", "binary_little_endian");
        let mut body: Vec<u8> = Vec::new();
        for p in [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]] {
            for x in p {
                body.extend_from_slice(&x.to_le_bytes());
            }
        }
        body.push(3);
        for i in [0i32, 1, 2] {
            body.extend_from_slice(&i.to_le_bytes());
        }
        assert_eq!(message(&binary(&header, &body)), "accepted with 1 faces");
        // Cut anywhere: a typed error naming the element and property.
        for cut in 0..body.len() {
            let m = message(&binary(&header, &body[..cut]));
            assert!(m.contains("the file ends early"), "{cut}: {m}");
        }
        assert_eq!(
            message(&binary(&header, &body[..17])),
            "m.ply: vertex 1, property `y`: the file ends early: the header declares 3 `vertex` elements"
        );
        // A header claiming a billion vertices over a few bytes.
        let huge = header.replace("vertex 3", "vertex 1000000000");
        assert_eq!(
            message(&binary(&huge, &body)),
            "m.ply: vertex 4, property `x`: the file ends early: the header declares 1000000000 `vertex` elements"
        );
        // A skipped element of 2^64 - 1 fixed-size elements, and one without properties.
        let skipped = header.replace(
            "end_header",
            "element edge 18446744073709551615\nproperty int a\nproperty int b\nelement nothing 18446744073709551615\nend_header",
        );
        assert_eq!(
            message(&binary(&skipped, &body)),
            "m.ply: edge 0: the file ends early: the header declares 18446744073709551615 `edge` elements"
        );
        let nothing = header.replace(
            "end_header",
            "element nothing 18446744073709551615\nend_header",
        );
        assert_eq!(message(&binary(&nothing, &body)), "accepted with 1 faces");
        // A list count of 2^32 - 1 in a skipped list property: refused before reading.
        let listed = header.replace(
            "end_header",
            "element material 1\nproperty list uint uchar name\nend_header",
        );
        let mut more = body.clone();
        more.extend_from_slice(&u32::MAX.to_le_bytes());
        assert_eq!(
            message(&binary(&listed, &more)),
            "m.ply: material 0, property `name`: list count 4294967295 is not valid (expected 0 to 16777216)"
        );
        // A non-finite binary coordinate.
        let mut nan = body.clone();
        nan[4..8].copy_from_slice(&f32::NAN.to_le_bytes());
        assert_eq!(
            message(&binary(&header, &nan)),
            "m.ply: vertex 0, property `y`: coordinate `NaN` is not finite"
        );
    }

    #[test]
    fn the_budget_counts_the_header_and_the_data() {
        let budget = Budget { bytes: 4000 };
        let vertices = "0 0 0\n".repeat(1000);
        let big = format!(
            "{}{vertices}3 0 1 2\n",
            HEAD.replace("vertex 3", "vertex 1000")
        );
        let err = read_ply_within(big.as_bytes(), "big.ply", budget).unwrap_err();
        assert!(
            matches!(err, Error::MeshTooLarge { line: 155, .. }),
            "{err}"
        );
        assert!(err.is_resource_limit());
        let properties: String = (0..200).map(|i| format!("property float p{i}\n")).collect();
        let header = HEAD.replace(
            "end_header",
            &format!("element junk 0\n{properties}end_header"),
        );
        let err = read_ply_within(header.as_bytes(), "h.ply", budget).unwrap_err();
        assert!(matches!(err, Error::MeshTooLarge { .. }), "{err}");
    }

    #[test]
    fn per_face_texture_coordinates_win_and_are_deduplicated() {
        let header = HEAD
            .replace(
                "property float z\n",
                "property float z\nproperty float s\nproperty float t\n",
            )
            .replace("element face 1", "element face 2")
            .replace(
                "vertex_indices\n",
                "vertex_indices\nproperty list uchar float texcoord\n",
            )
            .replace("vertex 3", "vertex 4");
        let data = "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n1 1 0 1 1\n\
                    3 0 1 2 6 0 0 0.5 0 0 0.5\n3 2 1 3 6 0 0.5 0.5 0 1 1\n";
        let mesh = read_ply_from(format!("{header}{data}").as_bytes(), "t.ply").expect("valid");
        let uvs = mesh.uvs().expect("texcoord");
        assert_eq!(uvs.corners(), [0, 1, 2, 2, 1, 3]);
        assert_eq!(uvs.coords()[3], DVec2::new(1.0, 1.0));
        let what: Vec<String> = mesh.uncarried().iter().map(|u| u.to_string()).collect();
        assert_eq!(
            what,
            [
                "4 values of `vertex` property `s`",
                "4 values of `vertex` property `t`"
            ]
        );
        let bad = data.replace("6 0 0 0.5 0 0 0.5", "4 0 0 0.5 0");
        assert_eq!(
            read_ply_from(format!("{header}{bad}").as_bytes(), "t.ply").unwrap_err().to_string(),
            "t.ply: face 0, property `texcoord`: 4 values for a face of 3 corners (expected 6: u v per corner)"
        );
        let nan = data.replace("0 0.5 0.5 0 1 1", "0 0.5 nan 0 1 1");
        assert_eq!(
            read_ply_from(format!("{header}{nan}").as_bytes(), "t.ply")
                .unwrap_err()
                .to_string(),
            "t.ply: face 1, property `texcoord`: coordinate `nan` is not finite"
        );
    }
}
