//! Reading OpenSubdiv's OBJ tags (`t` lines): their grammar and forms, the range and edge
//! checks once the faces are known, the tags this crate does not read counted by name.

use std::collections::BTreeMap;

use super::shorten;
use crate::error::ParseError;
use crate::polygon::PolygonMesh;
use crate::tags::{
    BoundaryInterpolation, Corner, Crease, CreaseMethod, FaceVaryingInterpolation, IgnoredTag,
    TagError, Tags, TriangleRule, INFINITELY_SHARP,
};

/// The tags read so far, with the line of every crease, corner and hole (for errors found
/// once the faces are known).
#[derive(Default)]
pub(super) struct TagReader {
    tags: Tags,
    crease_lines: Vec<u64>,
    corner_lines: Vec<u64>,
    hole_lines: Vec<u64>,
    ignored: BTreeMap<String, u64>,
    /// The heap bytes of `ignored`, kept as names are added (summed per line, it would make
    /// a file of many distinct unknown tags quadratic).
    ignored_bytes: usize,
}

/// What each known tag takes, for [`ParseError::TagForm`].
const CREASE_FORM: &str =
    "vertex pairs and one sharpness for all pairs or one per pair (2k/1/0 or 2k/k/0, k >= 1)";
const CORNER_FORM: &str =
    "vertices and one sharpness for all or one per vertex (k/1/0 or k/k/0, k >= 1)";
const HOLE_FORM: &str = "face indices only (k/0/0, k >= 1)";
const ONE_INT_FORM: &str = "one integer (1/0/0)";
const ONE_STRING_FORM: &str = "one string (0/0/1)";

/// Why a tag line was not taken.
pub(super) enum TagFailure {
    /// The line is malformed.
    Parse(ParseError),
    /// Its entries would take more memory than the reader's budget has room for.
    OverBudget,
    /// The allocator refused room for its entries.
    Allocation {
        bytes: u128,
        error: std::collections::TryReserveError,
    },
}

impl From<ParseError> for TagFailure {
    fn from(kind: ParseError) -> Self {
        TagFailure::Parse(kind)
    }
}

/// The bytes one entry of each list takes in the reader (the entry and its line).
const CREASE_ENTRY: usize = std::mem::size_of::<Crease>() + std::mem::size_of::<u64>();
const CORNER_ENTRY: usize = std::mem::size_of::<Corner>() + std::mem::size_of::<u64>();
const HOLE_ENTRY: usize = std::mem::size_of::<u32>() + std::mem::size_of::<u64>();

impl TagReader {
    /// Room for a line's `creases`, `corners` and `holes` before any is added: refused when
    /// they take more than `room` bytes (the budget's) or the allocator refuses them.
    pub(super) fn reserve(
        &mut self,
        [creases, corners, holes]: [usize; 3],
        room: u128,
    ) -> std::result::Result<(), TagFailure> {
        let bytes = creases as u128 * CREASE_ENTRY as u128
            + corners as u128 * CORNER_ENTRY as u128
            + holes as u128 * HOLE_ENTRY as u128;
        if bytes > room {
            return Err(TagFailure::OverBudget);
        }
        self.tags
            .try_reserve(creases, corners, holes)
            .and_then(|()| self.crease_lines.try_reserve(creases))
            .and_then(|()| self.corner_lines.try_reserve(corners))
            .and_then(|()| self.hole_lines.try_reserve(holes))
            .map_err(|error| TagFailure::Allocation { bytes, error })
    }

    pub(super) fn heap_bytes(&self) -> usize {
        self.tags.heap_bytes()
            + (self.crease_lines.len() + self.corner_lines.len() + self.hole_lines.len())
                * std::mem::size_of::<u64>()
            + self.ignored_bytes
    }

    /// Reads one `t` line (the tokens after `t`); its entries may take at most `room` bytes.
    pub(super) fn read(
        &mut self,
        mut tokens: std::str::SplitAsciiWhitespace<'_>,
        line: u64,
        room: u128,
    ) -> std::result::Result<(), TagFailure> {
        let (Some(name), Some(counts_token)) = (tokens.next(), tokens.next()) else {
            return Err(ParseError::TagIncomplete.into());
        };
        let counts = parse_counts(counts_token).ok_or_else(|| ParseError::TagCounts {
            token: shorten(counts_token),
        })?;
        // The values are walked, never collected: a 16 MiB line of indices stays 16 MiB.
        let found = tokens.clone().count() as u64;
        // Three u64 counts: their sum may pass 2^64 (and is then never the values found).
        let declared = counts.iter().map(|&c| u128::from(c)).sum::<u128>();
        if u128::from(found) != declared {
            return Err(ParseError::TagValueCount {
                name: shorten(name),
                declared,
                found,
            }
            .into());
        }
        let [n_ints, n_floats, n_strings] = counts.map(|c| c as usize);
        let mut ints = tokens.clone().take(n_ints);
        let floats = tokens.clone().skip(n_ints).take(n_floats);
        let mut strings = tokens.skip(n_ints + n_floats);
        let form = |ok: bool, expected: &'static str| {
            if ok {
                Ok(())
            } else {
                Err(ParseError::TagForm {
                    name: shorten(name),
                    counts: shorten(counts_token),
                    expected,
                })
            }
        };
        match name {
            "crease" => {
                let pairs = n_ints / 2;
                form(
                    n_ints >= 2
                        && n_ints % 2 == 0
                        && (n_floats == 1 || n_floats == pairs)
                        && n_strings == 0,
                    CREASE_FORM,
                )?;
                let mut sharpness = sharpnesses(name, floats)?;
                self.reserve([pairs, 0, 0], room)?;
                while let (Some(a), Some(b)) = (ints.next(), ints.next()) {
                    let a = parse_tag_index(name, a, "0-based vertex index")?;
                    let b = parse_tag_index(name, b, "0-based vertex index")?;
                    let s = sharpness.next_value(name)?;
                    self.tags
                        .add_crease(a, b, s)
                        .map_err(|e| sharpness_error(name, &e.value.to_string()))?;
                    self.crease_lines.push(line);
                }
            }
            "corner" => {
                form(
                    n_ints >= 1 && (n_floats == 1 || n_floats == n_ints) && n_strings == 0,
                    CORNER_FORM,
                )?;
                let mut sharpness = sharpnesses(name, floats)?;
                self.reserve([0, n_ints, 0], room)?;
                for token in ints {
                    let v = parse_tag_index(name, token, "0-based vertex index")?;
                    let s = sharpness.next_value(name)?;
                    self.tags
                        .add_corner(v, s)
                        .map_err(|e| sharpness_error(name, &e.value.to_string()))?;
                    self.corner_lines.push(line);
                }
            }
            "hole" => {
                form(n_ints >= 1 && n_floats == 0 && n_strings == 0, HOLE_FORM)?;
                self.reserve([0, 0, n_ints], room)?;
                for token in ints {
                    let f = parse_tag_index(name, token, "0-based face index")?;
                    self.tags.add_hole(f);
                    self.hole_lines.push(line);
                }
            }
            "interpolateboundary" => {
                form(counts == [1, 0, 0], ONE_INT_FORM)?;
                let parse = |t: &str| option_int(t).and_then(BoundaryInterpolation::from_tag_value);
                let expected = "0 none, 1 edge-and-corner, 2 edge-only";
                self.tags.options.boundary = Some(tag_option(name, ints.next(), parse, expected)?);
            }
            "facevaryinginterpolateboundary" => {
                form(counts == [1, 0, 0], ONE_INT_FORM)?;
                let parse =
                    |t: &str| option_int(t).and_then(FaceVaryingInterpolation::from_tag_value);
                let expected =
                    "0 none, 1 corners-only, 2 corners-plus1, 3 corners-plus2, 4 boundaries, 5 all";
                self.tags.options.face_varying =
                    Some(tag_option(name, ints.next(), parse, expected)?);
            }
            "creasemethod" | "smoothtriangles" => {
                form(counts == [0, 0, 1], ONE_STRING_FORM)?;
                let token = strings.next();
                let options = &mut self.tags.options;
                if name == "creasemethod" {
                    let parse = CreaseMethod::from_tag_name;
                    options.crease_method =
                        Some(tag_option(name, token, parse, "normal or chaikin")?);
                } else {
                    let parse = TriangleRule::from_tag_name;
                    options.triangle_rule =
                        Some(tag_option(name, token, parse, "catmark or smooth")?);
                }
            }
            _ => {
                let key = shorten(name);
                if let Some(count) = self.ignored.get_mut(&key) {
                    *count += 1;
                } else {
                    self.ignored_bytes += key.len() + std::mem::size_of::<(String, u64)>();
                    self.ignored.insert(key, 1);
                }
            }
        }
        Ok(())
    }

    /// Checks the tags against the mesh read and hands them over; an error comes with the
    /// line of the tag.
    pub(super) fn finish(
        self,
        mesh: &mut PolygonMesh,
    ) -> std::result::Result<(), (u64, ParseError)> {
        if let Err(e) = self.tags.check_against(mesh) {
            let line = match &e {
                TagError::VertexOutOfRange {
                    tag: "corner",
                    entry,
                    ..
                } => self.corner_lines[*entry],
                TagError::VertexOutOfRange { entry, .. } | TagError::NotAnEdge { entry, .. } => {
                    self.crease_lines[*entry]
                }
                TagError::FaceOutOfRange { entry, .. } => self.hole_lines[*entry],
            };
            return Err((line, ParseError::Tag(e)));
        }
        let ignored = self
            .ignored
            .into_iter()
            .map(|(name, count)| IgnoredTag { name, count })
            .collect();
        mesh.set_read_tags(self.tags, ignored);
        Ok(())
    }
}

/// Parses `nInts/nFloats/nStrings` (three unsigned decimal numbers).
fn parse_counts(token: &str) -> Option<[u64; 3]> {
    let mut parts = token.split('/');
    let mut counts = [0u64; 3];
    for slot in &mut counts {
        let part = parts.next()?;
        if part.is_empty() || !part.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        *slot = part.parse().ok()?;
    }
    parts.next().is_none().then_some(counts)
}

/// Parses a tag's 0-based vertex or face index.
fn parse_tag_index(
    name: &str,
    token: &str,
    expected: &'static str,
) -> std::result::Result<u32, ParseError> {
    if token.is_empty() || !token.bytes().all(|b| b.is_ascii_digit()) {
        return Err(ParseError::InvalidNumber {
            token: shorten(token),
            expected,
        });
    }
    match token.parse::<u32>() {
        Ok(i) if i < u32::MAX => Ok(i),
        _ => Err(ParseError::TagIndexTooLarge {
            name: shorten(name),
            token: shorten(token),
        }),
    }
}

/// An option tag's integer (`None` when it is not one, reported as an invalid value).
/// An option tag's one value (`token`), read by `parse`; otherwise the values it accepts.
fn tag_option<T>(
    name: &str,
    token: Option<&str>,
    parse: impl Fn(&str) -> Option<T>,
    expected: &'static str,
) -> std::result::Result<T, ParseError> {
    token.and_then(parse).ok_or_else(|| ParseError::TagOption {
        name: shorten(name),
        value: shorten(token.unwrap_or("")),
        expected,
    })
}

fn option_int(token: &str) -> Option<i64> {
    token.parse().ok()
}

/// A tag's sharpness values, each checked once before any entry is added, then handed out
/// one per entry (or the one value for every entry), walked again rather than collected.
struct Sharpnesses<I> {
    tokens: I,
    one: Option<f32>,
}

impl<'a, I: Iterator<Item = &'a str>> Sharpnesses<I> {
    /// The next entry's sharpness.
    fn next_value(&mut self, name: &str) -> std::result::Result<f32, ParseError> {
        match (self.one, self.tokens.next()) {
            (Some(s), _) => Ok(s),
            (None, Some(token)) => parse_sharpness(name, token),
            // The form checked one value per entry.
            (None, None) => Err(ParseError::TagIncomplete),
        }
    }
}

/// Checks a tag's sharpness values (`tokens`, one for all entries or one per entry) and
/// walks them.
fn sharpnesses<'a, I: Iterator<Item = &'a str> + Clone>(
    name: &str,
    tokens: I,
) -> std::result::Result<Sharpnesses<I>, ParseError> {
    let mut count = 0;
    let mut first = None;
    for token in tokens.clone() {
        let s = parse_sharpness(name, token)?;
        first.get_or_insert(s);
        count += 1;
    }
    Ok(Sharpnesses {
        tokens,
        one: if count == 1 { first } else { None },
    })
}

/// Parses a tag's sharpness: read in `f64`, so any finite value `>= 0` is accepted, and one
/// above [`INFINITELY_SHARP`] is clamped to it (OpenSubdiv's `Sdc::Crease` clamps to
/// `[0, SHARPNESS_INFINITE]`; either is infinitely sharp). A value up to it is parsed as
/// `f32` from its text, the rounding it always had, so the crease arithmetic is unchanged.
fn parse_sharpness(name: &str, token: &str) -> std::result::Result<f32, ParseError> {
    match token.parse::<f64>() {
        Ok(s) if s.is_finite() && s > f64::from(INFINITELY_SHARP) => Ok(INFINITELY_SHARP),
        Ok(s) if s.is_finite() && s >= 0.0 => token
            .parse::<f32>()
            .map_err(|_| sharpness_error(name, token)),
        Ok(_) => Err(sharpness_error(name, token)),
        Err(_) => Err(ParseError::InvalidNumber {
            token: shorten(token),
            expected: "sharpness",
        }),
    }
}

fn sharpness_error(name: &str, token: &str) -> ParseError {
    ParseError::TagSharpness {
        name: shorten(name),
        token: shorten(token),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::{Error, Result};
    use crate::io::{read_obj_from, read_obj_from_with, ReadOptions};

    fn read(text: &str) -> Result<PolygonMesh> {
        read_obj_from(text.as_bytes(), "t.obj")
    }

    /// A quad strip: vertices 0-5, faces (0 1 4 3) and (1 2 5 4); then `tags`.
    fn strip(tags: &str) -> String {
        format!(
            "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n{tags}"
        )
    }

    #[test]
    fn every_tag_kind_is_read() {
        let mesh = read(&strip(
            "t crease 4/1/0 0 1 1 4 10\nt crease 2/1/0 4 1 2.5\nt crease 4/2/0 2 5 5 4 0.5 0\n\
             t corner 2/1/0 0 2 3\nt corner 2/2/0 3 5 1 10\nt hole 2/0/0 1 1\n\
             t interpolateboundary 1/0/0 1\nt facevaryinginterpolateboundary 1/0/0 5\n\
             t creasemethod 0/0/1 chaikin\nt smoothtriangles 0/0/1 smooth\n\
             t vertexedit 1/0/2 3 P add\nt vertexedit 0/0/0\nt facevaryingpropagatecorners 1/0/0 1\n",
        ))
        .expect("valid");
        let t = mesh.tags();
        assert_eq!(t.creases().len(), 5);
        // (1, 4) given twice: the later 2.5 wins; (4, 5) has sharpness 0: not sharp.
        let sharp: Vec<(u32, u32, f32)> = t
            .sharp_edges()
            .iter()
            .map(|c| (c.a, c.b, c.sharpness))
            .collect();
        assert_eq!(sharp, [(0, 1, 10.0), (1, 4, 2.5), (2, 5, 0.5)]);
        let corners: Vec<(u32, f32)> = t
            .sharp_vertices()
            .iter()
            .map(|c| (c.vertex, c.sharpness))
            .collect();
        assert_eq!(corners, [(0, 3.0), (2, 3.0), (3, 1.0), (5, 10.0)]);
        assert_eq!((t.holes(), t.hole_faces()), (&[1, 1][..], vec![1]));
        assert_eq!(
            t.options.boundary,
            Some(BoundaryInterpolation::EdgeAndCorner)
        );
        assert_eq!(t.options.face_varying, Some(FaceVaryingInterpolation::All));
        assert_eq!(t.options.crease_method, Some(CreaseMethod::Chaikin));
        assert_eq!(t.options.triangle_rule, Some(TriangleRule::Smooth));
        let ignored: Vec<(&str, u64)> = mesh
            .ignored_tags()
            .iter()
            .map(|i| (i.name.as_str(), i.count))
            .collect();
        assert_eq!(
            ignored,
            [("facevaryingpropagatecorners", 1), ("vertexedit", 2)]
        );
        assert!(mesh.has_tags());
        // Every option value by number.
        for (value, b) in [
            (0, BoundaryInterpolation::None),
            (2, BoundaryInterpolation::Edge),
        ] {
            let m = read(&strip(&format!("t interpolateboundary 1/0/0 {value}\n"))).expect("valid");
            assert_eq!(m.tags().options.boundary, Some(b));
        }
        let m = read(&strip(
            "t creasemethod 0/0/1 normal\nt facevaryinginterpolateboundary 1/0/0 0\n",
        ))
        .expect("valid");
        assert_eq!(m.tags().options.crease_method, Some(CreaseMethod::Uniform));
        assert_eq!(
            m.tags().options.face_varying,
            Some(FaceVaryingInterpolation::None)
        );
    }

    #[test]
    fn a_long_tag_line_is_walked_and_a_repeated_edge_counts_once() {
        let pairs = 200_000;
        let line = format!(
            "t crease {}/1/0 {} 10\n",
            2 * pairs,
            "0 1 4 1 ".repeat(pairs / 2)
        );
        let mesh = read(&strip(&line)).expect("valid");
        assert_eq!(mesh.tags().creases().len(), pairs);
        assert_eq!(mesh.tags().sharp_edges().len(), 2);
        // Per-pair sharpness: the k-th float belongs to the k-th pair.
        let mesh = read(&strip("t crease 4/2/0 0 1 1 2 3 4\n")).expect("valid");
        let s: Vec<f32> = mesh.tags().creases().iter().map(|c| c.sharpness).collect();
        assert_eq!(s, [3.0, 4.0]);
    }

    /// Issue 24: sharpness was read as `f32`, so `1e308` was refused while `3.4e38` was
    /// accepted. It is read in `f64` and clamped to [`INFINITELY_SHARP`] as OpenSubdiv
    /// clamps; values up to it keep the `f32` they always had.
    #[test]
    fn sharpness_is_read_in_f64_and_clamped_to_infinitely_sharp() {
        for (token, expected) in [
            ("1e308", INFINITELY_SHARP),
            ("3.4e38", INFINITELY_SHARP),
            ("1e39", INFINITELY_SHARP),
            ("10.000001", INFINITELY_SHARP),
            ("10", 10.0),
            ("2.5", 2.5),
            ("0.1", 0.1f32),
            ("0", 0.0),
        ] {
            let mesh = read(&strip(&format!(
                "t crease 2/1/0 0 1 {token}\nt corner 1/1/0 2 {token}\n"
            )))
            .expect(token);
            assert_eq!(mesh.tags().creases()[0].sharpness, expected, "{token}");
            assert_eq!(mesh.tags().corners()[0].sharpness, expected, "{token}");
        }
        // Per-pair values, each clamped on its own.
        let mesh = read(&strip("t crease 4/2/0 0 1 1 4 1e300 1.5\n")).expect("valid");
        let s: Vec<f32> = mesh.tags().creases().iter().map(|c| c.sharpness).collect();
        assert_eq!(s, [INFINITELY_SHARP, 1.5]);
        for token in ["1e309", "inf", "nan", "-1e-300", "-5"] {
            let err = read(&strip(&format!("t crease 2/1/0 0 1 {token}\n"))).unwrap_err();
            assert_eq!(
                err.to_string(),
                format!("t.obj: line 9: tag `crease`: sharpness `{token}` is not valid (expected a finite number >= 0)")
            );
        }
    }

    #[test]
    fn tags_are_compared_and_can_be_skipped() {
        let tagged = read(&strip("t crease 2/1/0 0 1 10\n")).expect("valid");
        let plain = read(&strip("")).expect("valid");
        assert!(!plain.has_tags() && plain.tags().is_empty());
        assert_ne!(tagged, plain, "creases change the surface");
        let skipped = read_obj_from_with(
            strip("t crease 2/1/0 0 1 10\nt nonsense\nt crease 1/1/0 0 1\n").as_bytes(),
            "t.obj",
            &ReadOptions::without_tags(),
        )
        .expect("tags skipped unread");
        assert_eq!(skipped, plain);
        assert!(!skipped.has_tags());
        // Ignored tags are provenance, not part of the surface.
        let ignored = read(&strip("t vertexedit 0/0/0\n")).expect("valid");
        assert_eq!(ignored, plain);
        assert!(ignored.has_tags() && ignored.tags().is_empty());
    }

    #[test]
    fn every_tag_error_names_the_file_and_line() {
        let cases: &[(&str, &str)] = &[
            ("t\n", "a tag line needs a name and value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)"),
            ("t crease\n", "a tag line needs a name and value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)"),
            ("t crease 2 1 0 0 1\n", "`2` is not a tag's value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)"),
            ("t crease 2/1 0 1 1\n", "`2/1` is not a tag's value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)"),
            ("t crease 2/1/0/0 0 1 1\n", "`2/1/0/0` is not a tag's value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)"),
            ("t crease -2/1/0 0 1 1\n", "`-2/1/0` is not a tag's value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)"),
            ("t crease 2/1/0 0 1\n", "tag `crease` declares 3 values but the line has 2"),
            ("t crease 2/1/0 0 1 1 7\n", "tag `crease` declares 3 values but the line has 4"),
            ("t vertexedit 99999999999999999999/0/0 1\n", "`99999999999999999999/0/0` is not a tag's value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)"),
            ("t vertexedit 18446744073709551615/18446744073709551615/2 1\n", "tag `vertexedit` declares 36893488147419103232 values but the line has 1"),
            ("t vertexedit 18446744073709551615/1/0 1\n", "tag `vertexedit` declares 18446744073709551616 values but the line has 1"),
            ("t crease 3/1/0 0 1 4 1\n", "tag `crease` has 3/1/0 values: expected vertex pairs and one sharpness for all pairs or one per pair (2k/1/0 or 2k/k/0, k >= 1)"),
            ("t crease 4/3/0 0 1 1 4 1 1 1\n", "tag `crease` has 4/3/0 values: expected vertex pairs and one sharpness for all pairs or one per pair (2k/1/0 or 2k/k/0, k >= 1)"),
            ("t crease 2/0/0 0 1\n", "tag `crease` has 2/0/0 values: expected vertex pairs and one sharpness for all pairs or one per pair (2k/1/0 or 2k/k/0, k >= 1)"),
            ("t crease 0/1/0 1\n", "tag `crease` has 0/1/0 values: expected vertex pairs and one sharpness for all pairs or one per pair (2k/1/0 or 2k/k/0, k >= 1)"),
            ("t crease 2/1/1 0 1 1 x\n", "tag `crease` has 2/1/1 values: expected vertex pairs and one sharpness for all pairs or one per pair (2k/1/0 or 2k/k/0, k >= 1)"),
            ("t corner 2/3/0 0 1 1 1 1\n", "tag `corner` has 2/3/0 values: expected vertices and one sharpness for all or one per vertex (k/1/0 or k/k/0, k >= 1)"),
            ("t hole 1/1/0 0 1\n", "tag `hole` has 1/1/0 values: expected face indices only (k/0/0, k >= 1)"),
            ("t interpolateboundary 2/0/0 1 1\n", "tag `interpolateboundary` has 2/0/0 values: expected one integer (1/0/0)"),
            ("t creasemethod 1/0/0 1\n", "tag `creasemethod` has 1/0/0 values: expected one string (0/0/1)"),
            ("t crease 2/1/0 0 x 1\n", "`x` is not a valid 0-based vertex index"),
            ("t crease 2/1/0 0 -1 1\n", "`-1` is not a valid 0-based vertex index"),
            ("t crease 2/1/0 0 1 sharp\n", "`sharp` is not a valid sharpness"),
            ("t crease 2/1/0 0 1 -1\n", "tag `crease`: sharpness `-1` is not valid (expected a finite number >= 0)"),
            ("t corner 1/1/0 0 nan\n", "tag `corner`: sharpness `nan` is not valid (expected a finite number >= 0)"),
            ("t corner 1/1/0 0 1e309\n", "tag `corner`: sharpness `1e309` is not valid (expected a finite number >= 0)"),
            ("t corner 1/1/0 0 -inf\n", "tag `corner`: sharpness `-inf` is not valid (expected a finite number >= 0)"),
            ("t hole 1/0/0 4294967295\n", "tag `hole`: index `4294967295` is too large"),
            ("t hole 1/0/0 1.0\n", "`1.0` is not a valid 0-based face index"),
            ("t interpolateboundary 1/0/0 3\n", "tag `interpolateboundary`: `3` is not a valid value (expected 0 none, 1 edge-and-corner, 2 edge-only)"),
            ("t interpolateboundary 1/0/0 x\n", "tag `interpolateboundary`: `x` is not a valid value (expected 0 none, 1 edge-and-corner, 2 edge-only)"),
            ("t facevaryinginterpolateboundary 1/0/0 6\n", "tag `facevaryinginterpolateboundary`: `6` is not a valid value (expected 0 none, 1 corners-only, 2 corners-plus1, 3 corners-plus2, 4 boundaries, 5 all)"),
            ("t creasemethod 0/0/1 uniform\n", "tag `creasemethod`: `uniform` is not a valid value (expected normal or chaikin)"),
            ("t smoothtriangles 0/0/1 loop\n", "tag `smoothtriangles`: `loop` is not a valid value (expected catmark or smooth)"),
            ("t crease 2/1/0 0 6 10\n", "tag `crease`: vertex 6 is out of range (the mesh has 6 vertices; tag indices are 0-based)"),
            ("t corner 1/1/0 6 10\n", "tag `corner`: vertex 6 is out of range (the mesh has 6 vertices; tag indices are 0-based)"),
            ("t hole 1/0/0 2\n", "tag `hole`: face 2 is out of range (the mesh has 2 faces; tag indices are 0-based)"),
            ("t crease 2/1/0 0 4 10\n", "tag `crease`: vertices 0 and 4 are not an edge of the mesh's faces"),
            ("t crease 2/1/0 3 3 10\n", "tag `crease`: vertices 3 and 3 are not an edge of the mesh's faces"),
        ];
        for (tags, message) in cases {
            let text = strip(&format!("# tags\n{tags}"));
            let err = read(&text).unwrap_err();
            assert!(
                matches!(err, Error::Parse { line: 10, .. }),
                "{tags}: {err}"
            );
            assert_eq!(
                err.to_string(),
                format!("t.obj: line 10: {message}"),
                "{tags}"
            );
        }
        // Errors found once the faces are known name the tag's own line, even when faces follow.
        let text = "t crease 2/1/0 0 1 10\nt crease 2/1/0 0 2 10\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
        let err = read(text).unwrap_err();
        assert_eq!(
            err.to_string(),
            "t.obj: line 2: tag `crease`: vertices 0 and 2 are not an edge of the mesh's faces"
        );
        // A long value-counts token is shortened in the message, as every other token is.
        let counts = format!("{}1/1/0", "0".repeat(1000));
        let err = read(&strip(&format!("t hole {counts} 0 1\n"))).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "t.obj: line 9: tag `hole` has {}... values: expected {HOLE_FORM}",
                "0".repeat(40)
            )
        );
        // A face repeating a vertex has a side from it to itself: no edge for a crease
        // (found by the fuzzer's `obj` target: the crease `1 1` was accepted).
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2 3\nt crease 2/1/0 1 1 10\n";
        let err = read(text).unwrap_err();
        assert_eq!(
            err.to_string(),
            "t.obj: line 5: tag `crease`: vertices 1 and 1 are not an edge of the mesh's faces"
        );
    }
}
