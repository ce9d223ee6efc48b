//! OBJ lines read in place: plain `v x y z` and `f a b c ...` lines, the bulk of a large
//! file, read straight from the chunk of checked text (no search for the line's end, no
//! words), to the values [`ObjReader::statement`] reads from them.

use glam::DVec3;

use super::{ObjReader, Place};
use crate::error::Result;
use crate::io::obj_extras::{index_prefix, push_element};
use crate::io::MAX_LINE_BYTES;

impl ObjReader {
    /// Reads the lines of `text` from `*pos` on that are plain `v x y z` and `f a b c ...`
    /// lines, in place (no search for the line's end, no words), up to the first other line.
    ///
    /// A plain line is `v` or `f`, separators (ASCII whitespace but newlines), then three
    /// plain decimals ([`crate::io::float::prefix`]) or one to [`IN_PLACE_CORNERS`] plain
    /// indices ([`index_prefix`]) each followed by separators or the newline, and a newline:
    /// exactly what [`statement`](Self::statement) reads the same way, given a `text` of
    /// checked lines without comments ([`crate::io::lines::LineSource::in_place`]); every
    /// other line is left
    /// to it.
    pub(super) fn plain_lines(
        &mut self,
        text: &str,
        pos: &mut usize,
        at: &mut Place,
    ) -> Result<()> {
        let bytes = text.as_bytes();
        let mut indices = [0i64; IN_PLACE_CORNERS];
        loop {
            let rest = &bytes[*pos..];
            let (kind, len) = match rest {
                [b'v', s, ..] if separator(*s) => match plain_vertex(rest) {
                    Some((xyz, len)) => (Plain::Vertex(xyz), len),
                    None => return Ok(()),
                },
                [b'f', s, ..] if separator(*s) => match plain_face(rest, &mut indices) {
                    Some((n, len)) => (Plain::Face(n), len),
                    None => return Ok(()),
                },
                _ => return Ok(()),
            };
            if len > MAX_LINE_BYTES {
                return Ok(());
            }
            *pos += len;
            at.line += 1;
            match kind {
                Plain::Vertex(xyz) => {
                    let position = DVec3::from_array(xyz);
                    push_element(&mut self.mesh.positions, position, "vertices", at)?;
                    self.extras.vertex_without_color();
                    self.check(at)?;
                }
                Plain::Face(n) => {
                    self.corners.clear();
                    self.face_vts.clear();
                    let count = self.mesh.positions.len() as u64;
                    for &index in &indices[..n] {
                        self.corner(index, count, at)?;
                    }
                    self.end_face(at)?;
                }
            }
        }
    }
}

/// The most corners of a face line read in place (a longer one is read word by word).
const IN_PLACE_CORNERS: usize = 16;

/// A plain line read in place: a vertex's position, or the number of a face's indices.
enum Plain {
    Vertex([f64; 3]),
    Face(usize),
}

/// Whether `b` separates words without ending the line (ASCII whitespace but `\n`).
#[inline]
fn separator(b: u8) -> bool {
    // `\t`, `\x0c`, `\r` and ` `: `u8::is_ascii_whitespace` without `\n`.
    const SEPARATORS: u64 = 1 << b'\t' | 1 << 0x0c | 1 << b'\r' | 1 << b' ';
    b <= b' ' && SEPARATORS >> b & 1 == 1
}

/// What follows a word: separators then another word (the rest of the line from it), or
/// separators then the newline (`None`); `Err(())` for anything else (the word goes on, or
/// the text ends without a newline).
#[inline]
fn after_word(rest: &[u8]) -> std::result::Result<Option<&[u8]>, ()> {
    match rest {
        [b'\n', ..] => return Ok(None),
        [b, ..] if separator(*b) => {}
        _ => return Err(()),
    }
    let mut rest = &rest[1..];
    while let [b, tail @ ..] = rest {
        if !separator(*b) {
            break;
        }
        rest = tail;
    }
    match rest {
        [b'\n', ..] => Ok(None),
        [_, ..] => Ok(Some(rest)),
        [] => Err(()),
    }
}

/// A plain `v x y z` line at the start of `line`: the position and the line's length with
/// its newline.
#[inline]
fn plain_vertex(line: &[u8]) -> Option<([f64; 3], usize)> {
    let mut xyz = [0.0; 3];
    let mut rest = after_word(line.get(1..)?).ok()??;
    for (k, slot) in xyz.iter_mut().enumerate() {
        let (value, n) = crate::io::float::prefix(rest)?;
        *slot = value;
        match after_word(&rest[n..]).ok()? {
            Some(next) if k < 2 => rest = next,
            // The newline is the first byte of what is left.
            None if k == 2 => {
                return Some((xyz, line.len() - rest.len() + n + newline(&rest[n..])))
            }
            _ => return None,
        }
    }
    None
}

/// A plain `f a b c ...` line at the start of `line`: its indices into `indices`, their
/// number and the line's length with its newline.
#[inline]
fn plain_face(line: &[u8], indices: &mut [i64; IN_PLACE_CORNERS]) -> Option<(usize, usize)> {
    let mut rest = after_word(line.get(1..)?).ok()??;
    for (k, slot) in indices.iter_mut().enumerate() {
        let (index, n) = index_prefix(rest)?;
        *slot = index;
        match after_word(&rest[n..]).ok()? {
            Some(next) => rest = next,
            None => return Some((k + 1, line.len() - rest.len() + n + newline(&rest[n..]))),
        }
    }
    None
}

/// The bytes up to and with the newline of `rest` (separators, then `\n`).
#[inline]
fn newline(rest: &[u8]) -> usize {
    rest.iter()
        .position(|&b| b == b'\n')
        .map_or(rest.len(), |i| i + 1)
}
