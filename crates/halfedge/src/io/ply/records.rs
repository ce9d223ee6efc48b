//! The common binary records read whole: a vertex of scalar properties, a face's list of
//! corners.
//!
//! What is read and every error are those of the per-value reader (`Body::scalar`): a record
//! is read whole only when all its bytes are there, otherwise value by value, so that data
//! ending early names the property it cuts short; a read error is returned when the bytes it
//! withheld are asked for.

use super::binary::{Layout, Vertex, BATCH, MAX_WHOLE};
use super::body::{At, Body, Faces};
use super::header::{Element, Type};
use super::MAX_LIST_ITEMS;
use crate::error::{ParseError, Result};

impl<R: std::io::BufRead> Body<R> {
    /// Reads binary vertices whole while their records are all there, keeping each (as
    /// [`Body::vertices`] does); the index of the first left to read.
    pub(super) fn vertex_records(
        &mut self,
        element: &Element,
        layout: &Layout,
        big_endian: bool,
        extras: (bool, bool),
    ) -> Result<u64> {
        // The common records (`x y z` alone, little-endian) get a loop of their own.
        let stride = layout.stride;
        match (layout.xyz(), big_endian) {
            (Some(Type::F64), false) => {
                self.vertex_records_by(element, stride, extras, xyz::<8, f64>)
            }
            (Some(Type::F32), false) => {
                self.vertex_records_by(element, stride, extras, xyz::<4, f32>)
            }
            _ => self.vertex_records_by(element, stride, extras, |record| {
                layout.read(record, big_endian)
            }),
        }
    }

    /// [`vertex_records`](Self::vertex_records) of `stride` bytes each, read by `read`.
    #[inline(always)]
    fn vertex_records_by(
        &mut self,
        element: &Element,
        stride: usize,
        (colors, uvs): (bool, bool),
        read: impl Fn(&[u8]) -> std::result::Result<Vertex, (usize, f64)>,
    ) -> Result<u64> {
        // What each vertex adds to `used()` (its lists grow by their lengths); nothing else
        // changes while the element is read.
        let adding = 24 + if colors { 24 } else { 0 } + if uvs { 16 } else { 0 };
        let limit = u128::from(self.budget.bytes);
        let mut index = 0;
        while index < element.count {
            let batch = (element.count - index).min(BATCH.min((MAX_WHOLE / stride.max(1)) as u64));
            self.bytes
                .fill(&mut self.source.reader, batch as usize * stride);
            let there = ((self.bytes.buf.len() - self.bytes.pos) / stride) as u64;
            let batch = batch.min(there);
            if batch == 0 {
                return Ok(index);
            }
            let mut used = self.used();
            for _ in 0..batch {
                let at = At { element, index };
                let record = &self.bytes.buf[self.bytes.pos..self.bytes.pos + stride];
                let (p, c, t) = match read(record) {
                    Ok(vertex) => vertex,
                    Err((i, value)) => {
                        let property = &element.properties[i];
                        let kind = ParseError::NonFiniteCoordinate {
                            token: value.to_string(),
                        };
                        return Err(self.error(at, Some(property), kind));
                    }
                };
                self.bytes.pos += stride;
                if used + adding > limit {
                    return Err(self.too_large());
                }
                used += adding;
                self.store_vertex(at, adding, p, (colors, c), (uvs, t))?;
                index += 1;
            }
        }
        Ok(element.count)
    }

    /// Reads binary faces whose only property is their list of corners while their bytes
    /// are all there, keeping each (as [`Body::faces`] does); the index of the first left to
    /// read.
    pub(super) fn corner_lists(
        &mut self,
        element: &Element,
        (count, item): (Type, Type),
        big_endian: bool,
    ) -> Result<u64> {
        // The list's count and items are integers (the header says so). The common layouts
        // (a `uchar` count, `int` or `uint` corners, little-endian) get a loop of their own.
        let any = |ty: Type| move |bytes: &[u8]| ty.decode_int(bytes, big_endian).unwrap_or(-1);
        let uint8 = |bytes: &[u8]| i64::from(bytes[0]);
        let int32 = |bytes: &[u8]| i64::from(i32::from_le_bytes(first_four(bytes)));
        let uint32 = |bytes: &[u8]| i64::from(u32::from_le_bytes(first_four(bytes)));
        let sizes = (count.size(), item.size());
        match (count, item, big_endian) {
            (Type::U8, Type::I32, false) => self.corner_lists_by(element, sizes, (uint8, int32)),
            (Type::U8, Type::U32, false) => self.corner_lists_by(element, sizes, (uint8, uint32)),
            _ => self.corner_lists_by(element, sizes, (any(count), any(item))),
        }
    }

    /// [`corner_lists`](Self::corner_lists) with the count and the items of each list, of
    /// `count_size` and `item_size` bytes, read by `count_int` and `item_int` (-1 for none).
    #[inline(always)]
    fn corner_lists_by(
        &mut self,
        element: &Element,
        (count_size, item_size): (usize, usize),
        (count_int, item_int): (impl Fn(&[u8]) -> i64, impl Fn(&[u8]) -> i64),
    ) -> Result<u64> {
        let limit = u128::from(self.budget.bytes);
        // `used()` but the corner list's capacity (which grows as the list fills), kept as
        // the faces grow: nothing else changes while the element is read.
        let mut used = self.used() - 4 * self.corners.capacity() as u128;
        for index in 0..element.count {
            let at = At { element, index };
            if !self.bytes.fill(&mut self.source.reader, count_size) {
                return Ok(index);
            }
            let n = count_int(&self.bytes.buf[self.bytes.pos..]);
            if !(3..=MAX_LIST_ITEMS as i64).contains(&n) || n as usize * item_size > MAX_WHOLE {
                // The count's error, or a long list: read one value at a time.
                return Ok(index);
            }
            let n = n as usize;
            if !self
                .bytes
                .fill(&mut self.source.reader, count_size + n * item_size)
            {
                return Ok(index);
            }
            self.bytes.pos += count_size;
            self.corners.clear();
            self.texcoord.clear();
            let adding = (n * 4 + 16) as u128;
            let capacity = self.corners.capacity();
            let data = &self.bytes.buf[self.bytes.pos..self.bytes.pos + n * item_size];
            if n <= capacity {
                // The corner list does not grow: one test of the budget for every corner, and
                // the corners go to the mesh without it.
                for k in 0..n {
                    let index = item_int(&data[k * item_size..]);
                    if index < 0 || index as u64 >= self.vertices {
                        let kind = ParseError::VertexIndexOutOfRange {
                            index,
                            vertices: self.vertices,
                        };
                        return Err(self.error(at, None, kind));
                    }
                    if k == 0 && used + 4 * capacity as u128 + 4 > limit {
                        return Err(self.too_large());
                    }
                }
                if used + 4 * capacity as u128 + adding > limit {
                    return Err(self.too_large());
                }
                let Faces::Plain { offsets, indices } = &mut self.faces else {
                    return Ok(index);
                };
                let reserved = offsets.try_reserve(1).and_then(|()| indices.try_reserve(n));
                if let Err(e) = reserved {
                    return Err(self.allocation_failed(at, adding, e));
                }
                // Checked above: every corner is a vertex index, and there is room for them.
                for b in data.chunks_exact(item_size) {
                    indices.push(item_int(b) as u32);
                }
                offsets.push(indices.len());
            } else {
                for k in 0..n {
                    let offset = self.bytes.pos + k * item_size;
                    let index = item_int(&self.bytes.buf[offset..]);
                    if index < 0 || index as u64 >= self.vertices {
                        let kind = ParseError::VertexIndexOutOfRange {
                            index,
                            vertices: self.vertices,
                        };
                        return Err(self.error(at, None, kind));
                    }
                    if used + 4 * self.corners.capacity() as u128 + 4 > limit {
                        return Err(self.too_large());
                    }
                    if let Err(e) = self.corners.try_reserve(1) {
                        return Err(self.allocation_failed(at, 4, e));
                    }
                    self.corners.push(index as u32);
                }
                if used + 4 * self.corners.capacity() as u128 + adding > limit {
                    return Err(self.too_large());
                }
                let pushed = self.faces.push(&self.corners, 0);
                pushed.map_err(|e| self.allocation_failed(at, adding, e))?;
            }
            self.bytes.pos += n * item_size;
            // The faces' offsets and corners grew by their lengths.
            used += 8 + 4 * n as u128;
        }
        Ok(element.count)
    }

    /// The `n` corners of a face's binary list of `item`s, read whole into `corners` (true),
    /// or nothing read when their bytes are not all there (false).
    #[inline]
    pub(super) fn corner_list(
        &mut self,
        item: Type,
        n: u64,
        big_endian: bool,
        at: At<'_>,
    ) -> Result<bool> {
        let size = item.size();
        let Ok(n) = usize::try_from(n) else {
            return Ok(false);
        };
        if n * size > MAX_WHOLE || !self.bytes.fill(&mut self.source.reader, n * size) {
            return Ok(false);
        }
        // The budget's room apart from the corner list, whose capacity grows as it fills.
        let used = self.used() - 4 * self.corners.capacity() as u128;
        let limit = u128::from(self.budget.bytes);
        for k in 0..n {
            let bytes = &self.bytes.buf[self.bytes.pos + k * size..];
            let index = item.decode(bytes, big_endian) as i64;
            if index < 0 || index as u64 >= self.vertices {
                self.bytes.pos += (k + 1) * size;
                let kind = ParseError::VertexIndexOutOfRange {
                    index,
                    vertices: self.vertices,
                };
                return Err(self.error(at, None, kind));
            }
            if used + 4 * self.corners.capacity() as u128 + 4 > limit {
                self.bytes.pos += (k + 1) * size;
                return Err(self.too_large());
            }
            if let Err(e) = self.corners.try_reserve(1) {
                self.bytes.pos += (k + 1) * size;
                return Err(self.allocation_failed(at, 4, e));
            }
            self.corners.push(index as u32);
        }
        self.bytes.pos += n * size;
        Ok(true)
    }
}

/// The first four bytes of `bytes` (at least four).
#[inline(always)]
fn first_four(bytes: &[u8]) -> [u8; 4] {
    let mut four = [0u8; 4];
    four.copy_from_slice(&bytes[..4]);
    four
}

/// A record of three little-endian coordinates of `N` bytes each, as [`Layout::read`] reads
/// it.
#[inline(always)]
fn xyz<const N: usize, T: Into<f64> + LittleEndian<N>>(
    record: &[u8],
) -> std::result::Result<Vertex, (usize, f64)> {
    let mut p = [0.0; 3];
    for (i, slot) in p.iter_mut().enumerate() {
        let mut bytes = [0u8; N];
        bytes.copy_from_slice(&record[i * N..(i + 1) * N]);
        let value: f64 = T::from_le(bytes).into();
        if !value.is_finite() {
            return Err((i, value));
        }
        *slot = value;
    }
    Ok((p, [0.0; 3], [0.0; 2]))
}

/// A float type read from its little-endian bytes.
trait LittleEndian<const N: usize> {
    fn from_le(bytes: [u8; N]) -> Self;
}

impl LittleEndian<4> for f32 {
    fn from_le(bytes: [u8; 4]) -> f32 {
        f32::from_le_bytes(bytes)
    }
}

impl LittleEndian<8> for f64 {
    fn from_le(bytes: [u8; 8]) -> f64 {
        f64::from_le_bytes(bytes)
    }
}
