//! The PLY header: its elements, their properties and what the reader makes of them.

use std::collections::BTreeMap;
use std::io::{BufRead, Read};

use super::super::{shorten, Budget, MAX_LINE_BYTES};
use crate::error::{Error, ParseError, Result};
use crate::polygon::Uncarried;

// ---------------------------------------------------------------------------------------
// The header.

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Type {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

/// The first `$n` bytes of `$bytes` as a `$t` in the file's byte order, converted to `$to`.
macro_rules! decode_as {
    ($to:ty, $t:ty, $n:literal, $bytes:expr, $big_endian:expr) => {{
        let mut a = [0u8; $n];
        a.copy_from_slice(&$bytes[..$n]);
        <$to>::from(if $big_endian {
            <$t>::from_be_bytes(a)
        } else {
            <$t>::from_le_bytes(a)
        })
    }};
}

impl Type {
    pub(super) fn parse(name: &str) -> Option<Type> {
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
    pub(super) fn name(self) -> &'static str {
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

    #[inline]
    pub(super) fn size(self) -> usize {
        match self {
            Type::I8 | Type::U8 => 1,
            Type::I16 | Type::U16 => 2,
            Type::I32 | Type::U32 | Type::F32 => 4,
            Type::F64 => 8,
        }
    }

    pub(super) fn is_integer(self) -> bool {
        !matches!(self, Type::F32 | Type::F64)
    }

    /// The value of `bytes` (exactly [`size`](Self::size) of them): every PLY type is exact
    /// in `f64`.
    #[inline(always)]
    pub(super) fn decode(self, bytes: &[u8], big_endian: bool) -> f64 {
        match self {
            Type::F32 => decode_as!(f64, f32, 4, bytes, big_endian),
            Type::F64 => decode_as!(f64, f64, 8, bytes, big_endian),
            // Integers (`decode_int` is `Some` for each) fit in 32 bits: exact in `f64`.
            _ => self.decode_int(bytes, big_endian).unwrap_or_default() as f64,
        }
    }

    /// The value of `bytes` (at least [`size`](Self::size) of them) of an integer type, as
    /// [`decode`](Self::decode) reads it (every PLY integer is exact in `f64`); `None` for
    /// `float` and `double`.
    #[inline(always)]
    pub(super) fn decode_int(self, bytes: &[u8], big_endian: bool) -> Option<i64> {
        Some(match self {
            Type::I8 => decode_as!(i64, i8, 1, bytes, big_endian),
            Type::U8 => decode_as!(i64, u8, 1, bytes, big_endian),
            Type::I16 => decode_as!(i64, i16, 2, bytes, big_endian),
            Type::U16 => decode_as!(i64, u16, 2, bytes, big_endian),
            Type::I32 => decode_as!(i64, i32, 4, bytes, big_endian),
            Type::U32 => decode_as!(i64, u32, 4, bytes, big_endian),
            Type::F32 | Type::F64 => return None,
        })
    }

    /// The value of an ASCII token: an integer in the type's range, or a float read in the
    /// type's precision (a `float` is rounded to `f32`, as its binary form would be).
    pub(super) fn parse_text(self, token: &str) -> Option<f64> {
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
pub(super) enum Shape {
    Scalar(Type),
    List { count: Type, item: Type },
}

/// What the reader does with a property's values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Role {
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

/// A property of an element, as the header declares it: its name as written and for
/// messages (shortened, control characters escaped), a scalar or a list and their types, the
/// header line declaring it, and what the reader makes of its values.
#[derive(Clone, Debug)]
pub(super) struct Property {
    pub(super) name: String,
    pub(super) label: String,
    pub(super) shape: Shape,
    pub(super) line: u64,
    pub(super) role: Role,
}

/// An element of the header (`element NAME COUNT`) and its properties, in file order.
#[derive(Debug)]
pub(super) struct Element {
    /// The name for messages (shortened, control characters escaped); what it is.
    pub(super) label: String,
    pub(super) kind: Kind,
    /// How many the data holds: not trusted for allocations (a few bytes may claim
    /// 2^64 - 1 elements).
    pub(super) count: u64,
    /// The header line declaring it.
    pub(super) line: u64,
    /// Its properties, in the order of the data (each element's values come in this
    /// order).
    pub(super) properties: Vec<Property>,
}

/// What an element is to the reader.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Vertex,
    Face,
    Other,
}

/// Where the texture coordinates come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum UvSource {
    PerVertex,
    PerFace,
}

#[derive(Debug)]
pub(super) struct Header {
    /// `None` for ASCII, else whether the data is big-endian.
    pub(super) big_endian: Option<bool>,
    pub(super) elements: Vec<Element>,
    /// The line of `end_header`.
    pub(super) end_line: u64,
    pub(super) vertices: u64,
    pub(super) colors: bool,
    pub(super) uvs: Option<UvSource>,
    pub(super) uncarried: Vec<Uncarried>,
    /// The bytes the header's lists occupy (an estimate), counted against the budget.
    pub(super) bytes: usize,
}

/// Reads lines of a PLY file, counting them.
pub(super) struct Source<R> {
    pub(super) reader: R,
    pub(super) file: String,
    pub(super) buf: Vec<u8>,
    pub(super) line: u64,
}

/// Why a line could not be read.
pub(super) enum LineError {
    Io(std::io::Error),
    Bad(ParseError),
}

impl<R: BufRead> Source<R> {
    /// The next line without its end and trailing whitespace, into `text`; false at the end
    /// of the file. At most [`MAX_LINE_BYTES`] are read of a line, which must be text.
    pub(super) fn next_line(&mut self, text: &mut String) -> std::result::Result<bool, LineError> {
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

    pub(super) fn io(&self, source: std::io::Error) -> Error {
        Error::Io {
            path: self.file.clone().into(),
            source,
        }
    }

    /// An error of the header line just read.
    pub(super) fn header_error(&self, kind: ParseError) -> Error {
        self.error_at(self.line, kind)
    }

    pub(super) fn error_at(&self, line: u64, kind: ParseError) -> Error {
        Error::Parse {
            file: self.file.clone(),
            line,
            kind,
        }
    }

    pub(super) fn line_error(&self, e: LineError) -> Error {
        match e {
            LineError::Io(e) => self.io(e),
            LineError::Bad(kind) => self.header_error(kind),
        }
    }
}

pub(super) fn malformed(what: impl Into<String>) -> ParseError {
    ParseError::Malformed { what: what.into() }
}

/// Reads the header, up to and including `end_header`, and decides what each property is.
pub(super) fn read_header<R: BufRead>(source: &mut Source<R>, budget: Budget) -> Result<Header> {
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
pub(super) fn parse_property<'a>(
    rest: &[&'a str],
) -> std::result::Result<(Shape, &'a str), ParseError> {
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
pub(super) fn plan<R: BufRead>(header: &mut Header, source: &Source<R>) -> Result<()> {
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
