//! The lines of the text readers (OBJ, OFF): read in large chunks, checked a chunk at a time,
//! handed out without a copy.
//!
//! What a line is has not changed from the reader that read one line at a time (a test keeps
//! that reader as the reference: `every_chunk_size_gives_the_lines_of_the_reference`): a
//! physical line ends at `\n` (or the end of the file); a line with a NUL byte or bytes that
//! are not UTF-8 is [`ParseError::NotText`]; a byte-order mark before the file's first line is
//! dropped; a comment (from the first `#`) and trailing whitespace are cut; a line then ending
//! in a backslash is joined with the next one by a space (the joined line counts as one, named
//! by the number of its first part, and is held to [`MAX_LINE_BYTES`] as a whole). A line
//! longer than [`MAX_LINE_BYTES`] (its newline included) is [`ParseError::LineTooLong`] after
//! a bounded read (at most one byte past the limit is looked for). A read error is returned
//! when the line it cuts short is asked for, as a line-by-line reader would meet it.
//!
//! The file is read [`CHUNK`] bytes at a time; the complete lines of a chunk are checked at
//! once (no NUL, UTF-8) and kept as a `String`, so each line is a `&str` slice of it. A chunk
//! that fails the check is read line by line, each line checked on its own, so the first bad
//! line is still the one named.

use std::io::Read;

use super::MAX_LINE_BYTES;
use crate::error::{Error, ParseError, Result};

/// The bytes read from the file at a time.
pub(super) const CHUNK: usize = 1 << 20;

/// Where a reader is: the file's name for messages (control characters escaped) and the
/// number of the line read last (1-based; 0 before the first).
pub(super) struct Place {
    pub(super) name: String,
    pub(super) line: u64,
}

impl Place {
    pub(super) fn new(name: &str) -> Place {
        Place {
            name: super::escape_controls(name).into_owned(),
            line: 0,
        }
    }

    /// A refused allocation of `bytes` more bytes while reading this line.
    pub(super) fn allocation_failed(
        &self,
        bytes: u128,
        e: std::collections::TryReserveError,
    ) -> Error {
        Error::AllocationFailed {
            what: format!("the mesh read from {} (line {})", self.name, self.line),
            bytes,
            reason: e.to_string(),
        }
    }

    /// An error of this line.
    pub(super) fn error(&self, kind: ParseError) -> Error {
        Error::Parse {
            file: self.name.clone(),
            line: self.line,
            kind,
        }
    }
}

/// A physical line found in the chunk: where it is, and its length with its newline.
enum Physical {
    /// `start..end` of the current chunk (without the newline), `len` with it.
    Line {
        start: usize,
        end: usize,
        len: usize,
    },
    /// No newline within the limit: the line is too long.
    TooLong,
    /// The end of the file.
    End,
}

/// Reads the lines of a text file (see the module docs).
pub(super) struct LineSource<R> {
    reader: R,
    /// The bytes read at a time.
    chunk: usize,
    /// The complete lines of the current chunk, when they passed the check (else empty).
    text: String,
    /// The complete lines of the current chunk, when they did not (else empty).
    raw: Vec<u8>,
    /// The next line's first byte in `text` or `raw`.
    pos: usize,
    /// Whether the current chunk is `raw`.
    dirty: bool,
    /// Whether the current chunk has a `#` (else no line of it needs cutting).
    hash: bool,
    /// The bytes after the chunk's last complete line (the start of the next line).
    tail: Vec<u8>,
    /// The file has no more bytes after `tail`.
    eof: bool,
    /// The read error met after `tail`: returned when the line it cuts short is asked for.
    error: Option<std::io::Error>,
    /// A continued line joined so far.
    joined: String,
    /// No line has been read yet (a byte-order mark is dropped from the first).
    start: bool,
}

impl<R: Read> LineSource<R> {
    pub(super) fn new(reader: R) -> LineSource<R> {
        LineSource::with_chunk(reader, CHUNK)
    }

    /// A source reading `chunk` bytes at a time (the tests try small ones).
    pub(super) fn with_chunk(reader: R, chunk: usize) -> LineSource<R> {
        LineSource {
            reader,
            chunk: chunk.max(1),
            text: String::new(),
            raw: Vec::new(),
            pos: 0,
            dirty: false,
            hash: false,
            tail: Vec::new(),
            eof: false,
            error: None,
            joined: String::new(),
            start: true,
        }
    }

    /// The next line (comment removed, trailing whitespace cut, continuations joined), or
    /// `None` at the end of the file; `at.line` becomes its number.
    pub(super) fn next_line(&mut self, at: &mut Place) -> Result<Option<&str>> {
        self.joined.clear();
        let mut first = true;
        loop {
            let room = MAX_LINE_BYTES.saturating_sub(self.joined.len()) + 1;
            let (start, end, len) = match self.physical(room, at)? {
                Physical::End if first => return Ok(None),
                Physical::End => break,
                Physical::TooLong => {
                    if first {
                        at.line += 1;
                    }
                    return Err(too_long(at));
                }
                Physical::Line { start, end, len } => (start, end, len),
            };
            if first {
                at.line += 1;
            }
            if self.joined.len() + len > MAX_LINE_BYTES {
                return Err(too_long(at));
            }
            let s = if self.dirty {
                let bytes = &self.raw[start..start + len];
                if bytes.contains(&0) {
                    return Err(at.error(ParseError::NotText));
                }
                if std::str::from_utf8(bytes).is_err() {
                    return Err(at.error(ParseError::NotText));
                }
                std::str::from_utf8(&self.raw[start..end]).unwrap_or_default()
            } else {
                &self.text[start..end]
            };
            // A UTF-8 byte-order mark (what some Windows editors put first) is not part of
            // the first statement: without this, `\u{feff}v` is an unknown keyword and the
            // first line would be skipped silently.
            let s = if std::mem::take(&mut self.start) {
                s.strip_prefix('\u{feff}').unwrap_or(s)
            } else {
                s
            };
            let s = if self.hash || self.dirty {
                match memchr::memchr(b'#', s.as_bytes()) {
                    Some(i) => &s[..i],
                    None => s,
                }
            } else {
                s
            };
            let s = trim_end(s);
            match s.strip_suffix('\\') {
                Some(head) => {
                    self.joined.push_str(head);
                    self.joined.push(' ');
                    first = false;
                }
                None if first => {
                    // The common case: the line as it is in the chunk, no copy.
                    return Ok(Some(if self.dirty {
                        let (a, b) = span(&self.raw, s);
                        std::str::from_utf8(&self.raw[a..b]).unwrap_or_default()
                    } else {
                        let (a, b) = span(self.text.as_bytes(), s);
                        &self.text[a..b]
                    }));
                }
                None => {
                    self.joined.push_str(s);
                    break;
                }
            }
        }
        Ok(Some(&self.joined))
    }

    /// The rest of the current chunk and the position of its next line, when its lines may be
    /// read in place: checked text without a `#`, no continued line pending, not the file's
    /// first line (a byte-order mark). The caller reads whole lines (up to a newline) and
    /// moves the position past them, counting them; [`next_line`](Self::next_line) goes on
    /// from there.
    pub(super) fn in_place(&mut self) -> Option<(&str, &mut usize)> {
        if self.dirty || self.hash || self.start {
            return None;
        }
        Some((&self.text, &mut self.pos))
    }

    /// The next physical line of the chunk, reading the next chunk when this one is done;
    /// a line without a newline in its first `room` bytes is too long.
    fn physical(&mut self, room: usize, at: &Place) -> Result<Physical> {
        loop {
            let chunk: &[u8] = if self.dirty {
                &self.raw
            } else {
                self.text.as_bytes()
            };
            if self.pos < chunk.len() {
                let start = self.pos;
                let rest = &chunk[start..];
                let (end, len) = match memchr::memchr(b'\n', rest) {
                    Some(i) => (start + i, i + 1),
                    None => (chunk.len(), rest.len()),
                };
                self.pos = start + len;
                return Ok(Physical::Line { start, end, len });
            }
            if let Some(done) = self.refill(room, at)? {
                return Ok(done);
            }
        }
    }

    /// Reads the next chunk (the tail and more bytes, up to the last complete line): `None`
    /// when there is one, else why not.
    fn refill(&mut self, room: usize, at: &Place) -> Result<Option<Physical>> {
        let mut buf = if self.dirty {
            std::mem::take(&mut self.raw)
        } else {
            std::mem::take(&mut self.text).into_bytes()
        };
        buf.clear();
        std::mem::swap(&mut buf, &mut self.tail);
        self.pos = 0;
        // The last newline of `buf`, and how much of it was searched for one.
        let (mut last, mut searched) = (None, 0);
        let complete = loop {
            if let Some(i) = memchr::memrchr(b'\n', &buf[searched..]) {
                last = Some(searched + i);
            }
            searched = buf.len();
            match last {
                Some(i) if buf.len() >= self.chunk || self.eof || self.error.is_some() => {
                    break i + 1;
                }
                Some(_) => {}
                None => {
                    // A line is too long once `room` bytes hold no newline: read no further.
                    if buf.len() >= room {
                        self.keep_tail(buf);
                        return Ok(Some(Physical::TooLong));
                    }
                    if self.eof {
                        break buf.len();
                    }
                    if let Some(source) = self.error.take() {
                        return Err(Error::Io {
                            path: at.name.clone().into(),
                            source,
                        });
                    }
                }
            }
            self.read_more(&mut buf);
        };
        if complete == 0 {
            self.keep_tail(buf);
            return Ok(Some(Physical::End));
        }
        self.tail.extend_from_slice(&buf[complete..]);
        buf.truncate(complete);
        self.hash = memchr::memchr(b'#', &buf).is_some();
        self.dirty = memchr::memchr(0, &buf).is_some();
        if !self.dirty {
            match String::from_utf8(buf) {
                Ok(text) => {
                    self.text = text;
                    return Ok(None);
                }
                Err(e) => {
                    buf = e.into_bytes();
                    self.dirty = true;
                }
            }
        }
        self.raw = buf;
        Ok(None)
    }

    /// Keeps `buf` as the tail (nothing of it is a complete line), the chunk empty.
    fn keep_tail(&mut self, buf: Vec<u8>) {
        self.tail = buf;
        self.dirty = false;
        self.text.clear();
    }

    /// Appends up to `chunk` more bytes of the file to `buf`, noting the end of the file or
    /// a read error.
    fn read_more(&mut self, buf: &mut Vec<u8>) {
        buf.reserve(self.chunk);
        let limit = self.chunk as u64;
        // `read_to_end` retries an interrupted read and keeps what it read before an error.
        match (&mut self.reader).take(limit).read_to_end(buf) {
            Ok(n) if (n as u64) < limit => self.eof = true,
            Ok(_) => {}
            Err(e) => self.error = Some(e),
        }
    }
}

/// The error of a line longer than [`MAX_LINE_BYTES`].
fn too_long(at: &Place) -> Error {
    at.error(ParseError::LineTooLong {
        limit: MAX_LINE_BYTES,
    })
}

/// Cuts trailing whitespace (Unicode's, as `str::trim_end`), quickly when the line ends in
/// ASCII.
fn trim_end(s: &str) -> &str {
    let bytes = s.as_bytes();
    let mut end = bytes.len();
    while end > 0 {
        match bytes[end - 1] {
            b' ' | b'\t' | b'\n' | b'\x0b' | b'\x0c' | b'\r' => end -= 1,
            b if b < 0x80 => return &s[..end],
            _ => return s[..end].trim_end(),
        }
    }
    &s[..0]
}

/// The range of `part` (a slice of `whole`'s text: every step above cuts a slice of the line
/// read) in `whole`.
fn span(whole: &[u8], part: &str) -> (usize, usize) {
    let start = part.as_ptr() as usize - whole.as_ptr() as usize;
    (start, start + part.len())
}

/// The words of a line: what `str::split_ascii_whitespace` gives, and the rest of the line.
#[derive(Clone)]
pub(super) struct Words<'a> {
    line: &'a str,
    pos: usize,
}

impl<'a> Words<'a> {
    pub(super) fn new(line: &'a str) -> Words<'a> {
        Words { line, pos: 0 }
    }

    /// The line after the words read so far.
    pub(super) fn rest(&self) -> &'a str {
        &self.line[self.pos..]
    }

    /// Skips whitespace: the bytes of the line from the next word on (empty at its end).
    #[inline]
    pub(super) fn ahead(&mut self) -> &'a [u8] {
        let bytes = self.line.as_bytes();
        while self.pos < bytes.len() && bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        &bytes[self.pos..]
    }

    /// Takes the next `n` bytes of [`ahead`](Self::ahead) as read: the word when they end
    /// it (whitespace or the line's end follows), else nothing.
    #[inline]
    pub(super) fn take_word(&mut self, n: usize) -> bool {
        let bytes = self.line.as_bytes();
        let end = self.pos + n;
        let ends = bytes.get(end).map_or(true, u8::is_ascii_whitespace);
        if ends {
            self.pos = end;
        }
        ends
    }

    /// The next word read as a finite number by `parse` (a coordinate, a texture coordinate,
    /// a color value), `None` at the end of the line; a plain decimal is read in place,
    /// without finding the word first, to the same value.
    #[inline]
    pub(super) fn next_value(
        &mut self,
        parse: fn(&str) -> std::result::Result<f64, ParseError>,
    ) -> Option<std::result::Result<f64, ParseError>> {
        if let Some((value, n)) = super::float::prefix(self.ahead()) {
            if self.take_word(n) {
                return Some(Ok(value));
            }
        }
        self.next().map(parse)
    }

    /// The next `N` words, each read by `parse` (as [`next_value`](Self::next_value)); a
    /// line with fewer is the error `missing(found)` (as `io::parse_values` reads them).
    #[inline]
    pub(super) fn values<const N: usize>(
        &mut self,
        at: &Place,
        parse: fn(&str) -> std::result::Result<f64, ParseError>,
        missing: fn(usize) -> ParseError,
    ) -> Result<[f64; N]> {
        super::values_from(|| self.next_value(parse), at, missing)
    }
}

impl<'a> Iterator for Words<'a> {
    type Item = &'a str;

    #[inline]
    fn next(&mut self) -> Option<&'a str> {
        // Both ends are an ASCII byte or an end of the line: char boundaries.
        next_word(self.line.as_bytes(), &mut self.pos).map(|(start, end)| &self.line[start..end])
    }
}

/// The next whitespace-separated word of `bytes` from `*pos` on, as a range; `*pos` moves
/// past it (to the end when there is none).
#[inline]
pub(super) fn next_word(bytes: &[u8], pos: &mut usize) -> Option<(usize, usize)> {
    let mut i = *pos;
    while i < bytes.len() && bytes[i].is_ascii_whitespace() {
        i += 1;
    }
    let start = i;
    while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
        i += 1;
    }
    *pos = i;
    (i > start).then_some((start, i))
}

/// What the readers' tests share: a random generator, and a reader that hands out its bytes
/// a few at a time and may fail.
#[cfg(test)]
pub(crate) mod testing {
    use std::io::Read;

    /// A small deterministic generator (xorshift).
    pub(crate) struct Rng(pub(crate) u64);

    impl Rng {
        pub(crate) fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        pub(crate) fn below(&mut self, n: usize) -> usize {
            (self.next() % n as u64) as usize
        }
    }

    /// Hands out the bytes of `data` a few at a time (1 to 7 a call, by `seed`), then, with
    /// `fail_at`, an error at that offset.
    pub(crate) struct Trickle<'a> {
        data: &'a [u8],
        pos: usize,
        rng: Rng,
        fail_at: Option<usize>,
    }

    impl<'a> Trickle<'a> {
        pub(crate) fn new(data: &'a [u8], seed: u64, fail_at: Option<usize>) -> Trickle<'a> {
            Trickle {
                data,
                pos: 0,
                rng: Rng(seed | 1),
                fail_at,
            }
        }
    }

    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let end = self.fail_at.unwrap_or(self.data.len()).min(self.data.len());
            if self.pos >= end && self.fail_at.is_some() {
                return Err(std::io::Error::other("the disk is gone"));
            }
            let n = (1 + self.rng.below(7)).min(buf.len()).min(end - self.pos);
            buf[..n].copy_from_slice(&self.data[self.pos..self.pos + n]);
            self.pos += n;
            Ok(n)
        }
    }

    /// What a read gives, to compare: the mesh in full with its lines, or the error.
    pub(crate) fn outcome(read: crate::error::Result<crate::PolygonMesh>) -> String {
        match read {
            Ok(mesh) => {
                let lines: Vec<Option<u64>> =
                    (0..mesh.n_faces()).map(|f| mesh.face_line(f)).collect();
                format!("{mesh:?} {lines:?}")
            }
            Err(e) => format!("{e} | {e:?}"),
        }
    }
}

#[cfg(test)]
mod tests {
    //! The chunked lines against the line-at-a-time reading they replaced (issue 30): the
    //! same lines and errors for every chunk size, every way a reader hands out its bytes,
    //! and a read error anywhere.

    use std::io::{BufRead, Read};

    use super::testing::{Rng, Trickle};
    use super::*;
    use crate::io::parse_coordinate;

    /// The lines as the readers read them before issue 30, one `read_until` at a time (the
    /// reference: `io::Lines::next_line` as it was).
    fn reference_lines(reader: impl BufRead) -> Vec<Result<(u64, String), String>> {
        let mut reader = reader;
        let mut out = Vec::new();
        let mut line = 0u64;
        let mut buf = Vec::new();
        'lines: loop {
            let mut text = String::new();
            let mut first = true;
            loop {
                buf.clear();
                let room = MAX_LINE_BYTES.saturating_sub(text.len()) + 1;
                let n = match (&mut reader).take(room as u64).read_until(b'\n', &mut buf) {
                    Ok(n) => n,
                    Err(e) => {
                        out.push(Err(format!("io {e}")));
                        break 'lines;
                    }
                };
                if n == 0 {
                    if first {
                        break 'lines;
                    }
                    break;
                }
                if first {
                    line += 1;
                }
                let bad = if text.len() + buf.len() > MAX_LINE_BYTES {
                    Some("too long")
                } else if buf.contains(&0) || std::str::from_utf8(&buf).is_err() {
                    Some("not text")
                } else {
                    None
                };
                if let Some(bad) = bad {
                    out.push(Err(format!("line {line}: {bad}")));
                    break 'lines;
                }
                let s = std::str::from_utf8(&buf).expect("checked");
                let s = if line == 1 && first {
                    s.strip_prefix('\u{feff}').unwrap_or(s)
                } else {
                    s
                };
                let s = s.split('#').next().unwrap_or("").trim_end();
                first = false;
                match s.strip_suffix('\\') {
                    Some(head) => {
                        text.push_str(head);
                        text.push(' ');
                    }
                    None => {
                        text.push_str(s);
                        break;
                    }
                }
            }
            out.push(Ok((line, text)));
        }
        out
    }

    /// The lines of a [`LineSource`] reading `chunk` bytes at a time, as [`reference_lines`]
    /// gives them.
    fn chunked_lines(reader: impl Read, chunk: usize) -> Vec<Result<(u64, String), String>> {
        let mut source = LineSource::with_chunk(reader, chunk);
        let mut at = Place::new("t");
        let mut out = Vec::new();
        loop {
            match source.next_line(&mut at) {
                Ok(Some(text)) => out.push(Ok((at.line, text.to_string()))),
                Ok(None) => break,
                Err(Error::Parse { line, kind, .. }) => {
                    let what = match kind {
                        ParseError::LineTooLong { .. } => "too long",
                        ParseError::NotText => "not text",
                        _ => "other",
                    };
                    out.push(Err(format!("line {line}: {what}")));
                    break;
                }
                Err(Error::Io { source, .. }) => {
                    out.push(Err(format!("io {source}")));
                    break;
                }
                Err(e) => panic!("{e}"),
            }
        }
        out
    }

    /// Random text from pieces that matter to lines: newlines, comments, continuations,
    /// whitespace of every kind, a byte-order mark, NUL, bytes that are not UTF-8, non-ASCII
    /// whitespace.
    fn random_text(rng: &mut Rng) -> Vec<u8> {
        const PIECES: &[&[u8]] = &[
            b"\n",
            b"\r\n",
            b"#",
            b"\\",
            b"\\\n",
            b" ",
            b"\t",
            b"\x0b",
            b"\x0c",
            b"\r",
            b"v 1 2 3",
            b"f 1 2 3",
            b"vt 0.5 1",
            b"x",
            b"\xef\xbb\xbf",
            b"\0",
            b"\xff",
            b"\xc3",
            b"\xc2\xa0",
            b"\xe2\x80\x83",
            b"# c \\\n",
            b"f 1/2/3 4//5",
            b"-0.5e3",
        ];
        let mut text = Vec::new();
        for _ in 0..rng.below(40) {
            text.extend_from_slice(PIECES[rng.below(PIECES.len())]);
        }
        text
    }

    #[test]
    fn every_chunk_size_gives_the_lines_of_the_reference() {
        let mut rng = Rng(0x0123_4567_89ab_cdef);
        let mut texts: Vec<Vec<u8>> = (0..3000).map(|_| random_text(&mut rng)).collect();
        texts.push(b"\xef\xbb\xbfv 0 0 0\n\xef\xbb\xbfv 1\n".to_vec());
        texts.push(b"a \\\n\\\n\\".to_vec());
        for text in &texts {
            let reference = reference_lines(text.as_slice());
            for chunk in [1, 2, 3, 5, 8, 64, 1 << 20] {
                assert_eq!(
                    chunked_lines(text.as_slice(), chunk),
                    reference,
                    "{text:?} {chunk}"
                );
            }
            // Bytes handed out a few at a time, and a read error at every offset.
            for fail_at in [
                None,
                Some(text.len() / 2),
                Some(text.len().saturating_sub(1)),
            ] {
                let seed = text.len() as u64;
                let reference = reference_lines(std::io::BufReader::with_capacity(
                    3,
                    Trickle::new(text, seed, fail_at),
                ));
                let lines = chunked_lines(Trickle::new(text, seed, fail_at), 4);
                assert_eq!(lines, reference, "{text:?} {fail_at:?}");
            }
        }
    }

    #[test]
    fn lines_longer_than_the_limit_are_refused_where_the_reference_refuses_them() {
        let long = |n: usize| {
            let mut text = b"v 0 0 0\n".to_vec();
            text.extend(std::iter::repeat(b'1').take(n));
            text.extend_from_slice(b"\nv 1 1 1\n");
            text
        };
        for n in [
            MAX_LINE_BYTES - 2,
            MAX_LINE_BYTES - 1,
            MAX_LINE_BYTES,
            MAX_LINE_BYTES + 5,
        ] {
            let text = long(n);
            let reference = reference_lines(text.as_slice());
            assert_eq!(chunked_lines(text.as_slice(), 1 << 20), reference, "{n}");
            assert_eq!(chunked_lines(text.as_slice(), 1000), reference, "{n}");
        }
    }

    #[test]
    fn the_words_are_those_of_split_ascii_whitespace() {
        let mut rng = Rng(0xfeed_beef_1234_5678);
        for _ in 0..20_000 {
            let bytes = random_text(&mut rng);
            let text = String::from_utf8_lossy(&bytes).replace('\n', " ");
            let words: Vec<&str> = Words::new(&text).collect();
            let reference: Vec<&str> = text.split_ascii_whitespace().collect();
            assert_eq!(words, reference, "{text:?}");
            // Values read in place are the values of the words.
            let mut w = Words::new(&text);
            let mut r = text.split_ascii_whitespace();
            while let Some(value) = w.next_value(parse_coordinate) {
                let word = r.next().expect("as many words");
                assert_eq!(value, parse_coordinate(word), "{word:?}");
            }
            assert_eq!(r.next(), None);
        }
    }
}
