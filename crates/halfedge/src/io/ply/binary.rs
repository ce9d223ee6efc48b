//! Binary PLY data read a chunk at a time ([`Bytes`]), and the layout of a vertex record of
//! scalars ([`Layout`]), read whole by `records.rs`.

use std::io::Read;

use super::header::{Element, Role, Shape, Type};

/// The bytes read from the file at a time.
const CHUNK: u64 = 1 << 20;

/// The most bytes of a record or list read whole (a larger one is read value by value, as
/// before: the data read ahead stays within about a chunk).
pub(super) const MAX_WHOLE: usize = 1 << 16;

/// The binary data read ahead of the reader.
#[derive(Default)]
pub(super) struct Bytes {
    pub(super) buf: Vec<u8>,
    /// The next byte to hand out.
    pub(super) pos: usize,
    /// The file has no bytes after `buf`.
    eof: bool,
    /// The read error met after `buf`: returned when its bytes are asked for.
    error: Option<std::io::Error>,
}

impl Bytes {
    /// Whether `n` more bytes are there, reading them if needed (false: the file ends first,
    /// or a read error withheld them: [`failure`](Self::failure)).
    #[inline(always)]
    pub(super) fn fill(&mut self, reader: &mut impl Read, n: usize) -> bool {
        self.buf.len() - self.pos >= n || self.refill(reader, n)
    }

    /// [`fill`](Self::fill) when the bytes are not there yet.
    #[inline(never)]
    fn refill(&mut self, reader: &mut impl Read, n: usize) -> bool {
        self.buf.drain(..self.pos);
        self.pos = 0;
        while self.buf.len() < n && !self.eof && self.error.is_none() {
            let want = (n - self.buf.len()) as u64;
            let limit = want.max(CHUNK);
            self.buf.reserve(limit as usize);
            match reader.take(limit).read_to_end(&mut self.buf) {
                Ok(got) if (got as u64) < limit => self.eof = true,
                Ok(_) => {}
                Err(e) => self.error = Some(e),
            }
        }
        self.buf.len() >= n
    }

    /// The next `n` bytes, [`fill`](Self::fill)ed before.
    #[inline]
    pub(super) fn take(&mut self, n: usize) -> &[u8] {
        let bytes = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        bytes
    }

    /// Why [`fill`](Self::fill) failed: the read error, or `None` at the end of the file.
    pub(super) fn failure(&mut self) -> Option<std::io::Error> {
        self.error.take()
    }

    /// Skips up to `n` bytes; the bytes skipped (fewer at the end of the file), or the read
    /// error met before.
    pub(super) fn skip(&mut self, reader: &mut impl Read, n: u64) -> std::io::Result<u64> {
        let mut skipped = 0u64;
        while skipped < n {
            let available = (self.buf.len() - self.pos) as u64;
            if available == 0 {
                let want = (n - skipped).min(CHUNK) as usize;
                if !self.fill(reader, want) && self.buf.len() == self.pos {
                    return match self.failure() {
                        Some(e) => Err(e),
                        None => Ok(skipped),
                    };
                }
                continue;
            }
            let k = available.min(n - skipped);
            self.pos += k as usize;
            skipped += k;
        }
        Ok(skipped)
    }
}

/// Where each property of a vertex record of scalars is (its offset and type) and what it is;
/// the record's size.
pub(super) struct Layout {
    fields: Vec<(usize, Type, Role)>,
    pub(super) stride: usize,
}

impl Layout {
    /// The layout of `element`'s records, when every property is a scalar.
    pub(super) fn of(element: &Element) -> Option<Layout> {
        let mut fields = Vec::with_capacity(element.properties.len());
        let mut stride = 0;
        for property in &element.properties {
            let Shape::Scalar(ty) = property.shape else {
                return None;
            };
            fields.push((stride, ty, property.role));
            stride += ty.size();
        }
        (stride <= MAX_WHOLE).then_some(Layout { fields, stride })
    }
}

/// A vertex's position, color and texture coordinate.
pub(super) type Vertex = ([f64; 3], [f64; 3], [f64; 2]);

impl Layout {
    /// The type of the coordinates when a record is `x y z` of one float type and nothing
    /// else, in that order.
    pub(super) fn xyz(&self) -> Option<Type> {
        let [(0, ty, Role::Position(0)), (b, ty1, Role::Position(1)), (c, ty2, Role::Position(2))] =
            self.fields[..]
        else {
            return None;
        };
        let floats = matches!(ty, Type::F32 | Type::F64) && ty1 == ty && ty2 == ty;
        (floats && b == ty.size() && c == 2 * ty.size()).then_some(ty)
    }

    /// The values of a record: the vertex, or the first value (in the order of the
    /// properties) that is not finite, with its property's index.
    #[inline]
    pub(super) fn read(
        &self,
        record: &[u8],
        big_endian: bool,
    ) -> std::result::Result<Vertex, (usize, f64)> {
        let (mut p, mut c, mut t) = ([0.0; 3], [0.0; 3], [0.0; 2]);
        for (i, &(offset, ty, role)) in self.fields.iter().enumerate() {
            let slot = match role {
                Role::Position(k) => &mut p[k],
                Role::Color(k) => &mut c[k],
                Role::VertexUv(k) => &mut t[k],
                _ => continue,
            };
            let value = ty.decode(&record[offset..], big_endian);
            if !value.is_finite() {
                return Err((i, value));
            }
            *slot = match role {
                Role::Color(_) if ty == Type::U8 => value / 255.0,
                _ => value,
            };
        }
        Ok((p, c, t))
    }
}

/// The vertices read whole at a time.
pub(super) const BATCH: u64 = 1024;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::ply::header::{Kind, Property};

    fn layout(properties: &[(Type, Role)]) -> Option<Type> {
        let property = |&(ty, role): &(Type, Role)| Property {
            name: String::new(),
            label: String::new(),
            shape: Shape::Scalar(ty),
            line: 0,
            role,
        };
        let element = Element {
            label: "vertex".into(),
            kind: Kind::Vertex,
            count: 1,
            line: 0,
            properties: properties.iter().map(property).collect(),
        };
        Layout::of(&element)?.xyz()
    }

    /// The records the loop of their own reads: `x y z` of one float type, nothing else.
    #[test]
    fn only_x_y_z_of_one_float_type_is_xyz() {
        let p = Role::Position;
        let xyz = |ty| [(ty, p(0)), (ty, p(1)), (ty, p(2))];
        assert_eq!(layout(&xyz(Type::F32)), Some(Type::F32));
        assert_eq!(layout(&xyz(Type::F64)), Some(Type::F64));
        assert_eq!(layout(&xyz(Type::I32)), None);
        let (f, d) = (Type::F32, Type::F64);
        assert_eq!(layout(&[(f, p(2)), (f, p(1)), (f, p(0))]), None);
        assert_eq!(layout(&[(f, p(0)), (d, p(1)), (f, p(2))]), None);
        assert_eq!(layout(&[(f, p(0)), (f, p(1))]), None);
        let mut more = xyz(Type::F32).to_vec();
        more.push((Type::U8, Role::Color(0)));
        assert_eq!(layout(&more), None);
        assert_eq!(
            layout(&[(f, Role::Skip), (f, p(0)), (f, p(1)), (f, p(2))]),
            None
        );
    }
}
