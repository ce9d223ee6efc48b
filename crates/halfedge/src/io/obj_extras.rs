//! What the OBJ reader keeps besides positions and faces: vertex colors, the grouping
//! statements and the kinds of lines no output carries ([`Extras`]), the texture coordinates
//! ([`UvReader`]); and the parsing of indices.

use glam::DVec2;

use super::lines::Place;
use super::{grow, parse_finite, parse_values, shorten};
use crate::error::{Error, ParseError, Result};
use crate::groups::{GroupsReader, Statement};
use crate::polygon::{PartialColors, ReadColors, Uncarried};
use crate::uv::{PartialUvs, Uvs};

/// What the OBJ reader keeps besides positions, faces, texture coordinates and tags: vertex
/// colors, the grouping statements, and the kinds of lines no output carries.
#[derive(Default)]
pub(super) struct Extras {
    /// The colors of the `v` lines so far, while every one has `r g b` (else empty).
    colors: Vec<[f64; 3]>,
    /// The `v` lines with a color, and whether one had a count of values other than 3, 4 or 6.
    with_colors: usize,
    vertices: usize,
    odd: bool,
    groups: GroupsReader,
    /// Whether a grouping statement was read (before it, a face changes nothing).
    grouped: bool,
    /// `groups.heap_bytes()`, kept as the groups change (it sums every value's bytes).
    groups_bytes: usize,
    uncarried: std::collections::HashMap<String, u64>,
    /// The bytes of `uncarried`'s keys (48 more each), kept as keys are added.
    uncarried_bytes: usize,
}

impl Extras {
    /// The bytes held: the colors, the groups and the kinds of lines not carried.
    pub(super) fn heap_bytes(&self) -> usize {
        24 * self.colors.capacity() + self.groups_bytes + self.uncarried_bytes
    }

    /// Whether a grouping statement was read (each face is then recorded in the groups).
    pub(super) fn grouped(&self) -> bool {
        self.grouped
    }

    /// Records the next face in the groups.
    pub(super) fn face(&mut self) -> std::result::Result<(), std::collections::TryReserveError> {
        self.groups.face()?;
        if self.grouped {
            self.groups_bytes = self.groups.heap_bytes();
        }
        Ok(())
    }

    /// Records an `mtllib` line (its text after comments, trimmed).
    pub(super) fn mtllib(
        &mut self,
        line: &str,
    ) -> std::result::Result<(), std::collections::TryReserveError> {
        self.grouped = true;
        let done = self.groups.mtllib(line);
        self.groups_bytes = self.groups.heap_bytes();
        done
    }

    /// Records a grouping statement with the words after its keyword.
    pub(super) fn statement<'a>(
        &mut self,
        statement: Statement,
        words: impl Iterator<Item = &'a str>,
    ) {
        self.grouped = true;
        self.groups.statement(statement, words);
        self.groups_bytes = self.groups.heap_bytes();
    }

    /// Reads the values of a `v` line after its position: none, `w`, or `r g b`.
    pub(super) fn vertex<'a>(
        &mut self,
        mut rest: impl Iterator<Item = &'a str> + Clone,
        lines: &Place,
    ) -> Result<()> {
        // Counted without collecting: this runs once per `v` line.
        let count = rest.clone().take(4).count();
        let all_so_far = self.with_colors == self.vertices;
        self.vertices += 1;
        match count {
            3 => {
                let missing = |found| ParseError::MissingCoordinates { found };
                let rgb = parse_values::<3>(&mut rest, lines, parse_color, missing)?;
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

    /// What [`vertex`](Self::vertex) does for a `v` line with no value after its position.
    #[inline]
    pub(super) fn vertex_without_color(&mut self) {
        self.vertices += 1;
        self.colors = Vec::new();
    }

    /// Counts a line no output carries.
    pub(super) fn uncarried(&mut self, keyword: &str) {
        // A keyword of at most 40 printable ASCII characters is its own key: found without
        // making one (a file with a `vn` line per vertex).
        if keyword.len() <= 40 && keyword.bytes().all(|b| b.is_ascii_graphic()) {
            if let Some(count) = self.uncarried.get_mut(keyword) {
                *count += 1;
                return;
            }
        }
        match self.uncarried.entry(shorten(keyword)) {
            std::collections::hash_map::Entry::Occupied(mut entry) => *entry.get_mut() += 1,
            std::collections::hash_map::Entry::Vacant(entry) => {
                self.uncarried_bytes += entry.key().capacity() + 48;
                entry.insert(1);
            }
        }
    }

    pub(super) fn finish(
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
    parse_finite(token, "vertex color")
}

/// The texture coordinates read so far and the `vt` of the face corners.
#[derive(Default)]
pub(super) struct UvReader {
    /// The `vt` lines.
    pub(super) coords: Vec<DVec2>,
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
    pub(super) fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(self.coords.as_slice())
            + std::mem::size_of_val(self.vts.as_slice())
            + std::mem::size_of_val(self.forward.as_slice())
    }

    /// The 0-based `vt` of a corner's `vt` field (corner `corner` of the face on the line
    /// `lines` is at).
    pub(super) fn resolve(&mut self, field: &str, corner: usize, lines: &Place) -> Result<u32> {
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
    pub(super) fn push_face(&mut self, vts: &[u32], corners: usize, lines: &Place) -> Result<()> {
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
    pub(super) fn forward_error(&self) -> Option<(u64, ParseError)> {
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
    pub(super) fn finish(self) -> (Option<Uvs>, Option<PartialUvs>) {
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
pub(super) fn push_element<T>(
    list: &mut Vec<T>,
    item: T,
    what: &'static str,
    lines: &Place,
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
pub(super) fn parse_tex_coordinate(token: &str) -> std::result::Result<f64, ParseError> {
    parse_finite(token, "texture coordinate")
}

/// Parses an OBJ vertex index: a non-zero integer whose magnitude fits `u32`.
#[inline]
pub(super) fn parse_index(field: &str) -> std::result::Result<i64, ParseError> {
    match index_prefix(field.as_bytes()) {
        Some((index, n)) if n == field.len() => Ok(index),
        _ => parse_index_checked(field),
    }
}

/// The common start of a word holding a vertex index, read in place: a sign and at most 18
/// digits (no overflow) whose value is a valid index; the index and the bytes it takes.
/// Anything else (every error among it) is [`parse_index`]'s to read.
#[inline]
pub(super) fn index_prefix(bytes: &[u8]) -> Option<(i64, usize)> {
    let sign = usize::from(matches!(bytes.first(), Some(b'-' | b'+')));
    let (value, digits) = match bytes.get(sign..sign + 8) {
        // At most seven digits (an index below ten million): read at once.
        Some(eight) => match super::float::leading_digits(eight) {
            (8, _) => longer_index(&bytes[sign..])?,
            (n, value) => (value as i64, n),
        },
        None => longer_index(&bytes[sign..])?,
    };
    if digits == 0 || value == 0 || value >= i64::from(u32::MAX) {
        return None;
    }
    Some((
        if sign == 1 && bytes[0] == b'-' {
            -value
        } else {
            value
        },
        sign + digits,
    ))
}

/// The digits at the start of `bytes`, read one at a time: their value and number when
/// they are at most 18 (below 10^18, no wrap), `None` for more.
fn longer_index(bytes: &[u8]) -> Option<(i64, usize)> {
    let mut value = 0u64;
    let digits = super::float::one_by_one(bytes, 0, &mut value);
    // At most 18 digits: below 10^18, no wrap.
    (digits <= 18).then_some((value as i64, digits))
}

/// [`parse_index`], every case checked in turn.
fn parse_index_checked(field: &str) -> std::result::Result<i64, ParseError> {
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
