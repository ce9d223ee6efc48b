//! OFF reading (ASCII `OFF`, `COFF`, `NOFF`, `CNOFF`).

use std::io::BufRead;
use std::path::Path;

use super::lines::{LineSource, Place};
use super::{grow, parse_position, shorten, Budget, ReadOptions};
use crate::error::{Error, ParseError, Result};
use crate::polygon::{PartialColors, PolygonMesh};

/// Reads an OFF file as a face list (polygons kept, 0-based indices).
///
/// # Errors
///
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] naming the file and line of
/// the first malformed line, [`Error::NoFaces`] for a file without faces, and the memory
/// refusals of [`read_obj`](super::read_obj) ([`Error::FileTooLarge`],
/// [`Error::MeshTooLarge`]).
///
/// # Example
///
/// ```no_run
/// let mesh = halfedge::io::read_off("torus.off")?;
/// assert!(mesh.n_faces() > 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_off(path: impl AsRef<Path>) -> Result<PolygonMesh> {
    read_off_with(path.as_ref(), &ReadOptions::DEFAULT)
}

/// [`read_off`] within the memory limit of `options` ([`ReadOptions::available_bytes`]; OFF
/// has no tags).
pub(crate) fn read_off_with(path: &Path, options: &ReadOptions) -> Result<PolygonMesh> {
    super::read_file(path, options, read_off_within)
}

/// Reads OFF text from any buffered reader; `name` is the file name used in error messages.
///
/// The header keyword (`OFF`, `COFF`, `NOFF`, `CNOFF`) may be followed by the counts on the
/// same line; then come `V F E`, `V` vertex lines (the first three numbers are the position,
/// then a normal under `N`, ignored; under `C` a color `r g b`, its alpha ignored, kept as read:
/// [`PolygonMesh::colors`] when every vertex line has one) and `F` face lines `k i1 .. ik` (anything after
/// the `k` indices, such as a colour, is ignored).
///
/// # Errors
///
/// As [`read_off`].
///
/// # Example
///
/// ```
/// let text = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
/// let mesh = halfedge::io::read_off_from(text.as_bytes(), "triangle.off")?;
/// assert_eq!((mesh.n_vertices(), mesh.n_faces()), (3, 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_off_from(reader: impl BufRead, name: &str) -> Result<PolygonMesh> {
    read_off_within(reader, name, Budget::of(&ReadOptions::DEFAULT))
}

/// [`read_off_from`] with the mesh's memory limited to `budget`.
pub(crate) fn read_off_within(
    reader: impl BufRead,
    name: &str,
    budget: Budget,
) -> Result<PolygonMesh> {
    let mut source = LineSource::new(reader);
    let mut lines = Place::new(name);
    let malformed = |what: String| ParseError::Malformed { what };

    // Header keyword, possibly followed by the counts.
    let mut counts: Vec<String> = Vec::new();
    let (colored, normals);
    loop {
        let Some(line) = source.next_line(&mut lines)? else {
            return Err(Error::NoFaces {
                file: lines.name.clone(),
            });
        };
        let mut tokens = line.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        if !matches!(keyword, "OFF" | "COFF" | "NOFF" | "CNOFF" | "NCOFF") {
            let what = format!("expected the OFF header, found `{}`", shorten(keyword));
            return Err(lines.error(malformed(what)));
        }
        if tokens.clone().next() == Some("BINARY") {
            let what = "binary OFF is not supported".to_string();
            return Err(lines.error(malformed(what)));
        }
        counts.extend(tokens.map(str::to_string));
        (colored, normals) = (keyword.contains('C'), keyword.contains('N'));
        break;
    }
    while counts.is_empty() {
        let Some(line) = source.next_line(&mut lines)? else {
            return Err(lines.error(ParseError::UnexpectedEnd {
                what: "no vertex and face counts".into(),
            }));
        };
        counts.extend(line.split_ascii_whitespace().map(str::to_string));
    }
    if counts.len() < 2 {
        let what = "expected the vertex, face and edge counts".to_string();
        return Err(lines.error(malformed(what)));
    }
    let parse_count = |token: &str| {
        token.parse::<u32>().map_err(|_| ParseError::InvalidNumber {
            token: shorten(token),
            expected: "count",
        })
    };
    let n_vertices = parse_count(&counts[0]).map_err(|kind| lines.error(kind))?;
    let n_faces = parse_count(&counts[1]).map_err(|kind| lines.error(kind))?;

    // Do not trust the counts for preallocation beyond a sane bound (and what the budget
    // holds); a refused reservation only leaves the lists to grow, each step checked.
    let mut mesh = PolygonMesh::default();
    let cap = |n: u32, bytes: u64| (n.min(1 << 20) as u64).min(budget.bytes / 4 / bytes) as usize;
    let _ = mesh.positions.try_reserve_exact(cap(n_vertices, 24));
    let _ = mesh.try_reserve_faces(cap(n_faces, 8), 0);
    let (mut colors, mut with_colors): (Vec<[f64; 3]>, usize) = (Vec::new(), 0);
    while mesh.positions.len() < n_vertices as usize {
        let Some(line) = source.next_line(&mut lines)? else {
            let what = format!("{} of {n_vertices} vertices read", mesh.positions.len());
            return Err(lines.error(ParseError::UnexpectedEnd { what }));
        };
        let mut tokens = line.split_ascii_whitespace().peekable();
        if tokens.peek().is_none() {
            continue;
        }
        let position = parse_position(&mut tokens, &lines)?;
        grow(&mut mesh.positions, 1, &lines)?;
        mesh.positions.push(position);
        if colored {
            // `x y z [nx ny nz] r g b [a]`: the color after the normal, alpha not kept.
            let rgb: Vec<&str> = tokens.skip(if normals { 3 } else { 0 }).take(3).collect();
            let all_so_far = with_colors + 1 == mesh.positions.len();
            if rgb.len() == 3 {
                with_colors += 1;
                let missing = |found| ParseError::MissingCoordinates { found };
                let rgb = super::parse_values::<3>(
                    &mut rgb.into_iter(),
                    &lines,
                    super::obj_extras::parse_color,
                    missing,
                )?;
                if all_so_far {
                    grow(&mut colors, 1, &lines)?;
                    colors.push(rgb);
                }
            } else {
                colors = Vec::new();
            }
        }
        budget.check(&mesh, 24 * colors.capacity(), &lines)?;
    }
    let mut corners: Vec<u32> = Vec::new();
    while mesh.n_faces() < n_faces as usize {
        let Some(line) = source.next_line(&mut lines)? else {
            let what = format!("{} of {n_faces} faces read", mesh.n_faces());
            return Err(lines.error(ParseError::UnexpectedEnd { what }));
        };
        let mut tokens = line.split_ascii_whitespace();
        let Some(first) = tokens.next() else { continue };
        let degree = first.parse::<u32>().map_err(|_| {
            lines.error(ParseError::InvalidNumber {
                token: shorten(first),
                expected: "face size",
            })
        })?;
        if degree < 3 {
            return Err(lines.error(ParseError::FaceTooSmall {
                corners: degree as usize,
            }));
        }
        corners.clear();
        for _ in 0..degree {
            let Some(token) = tokens.next() else {
                let what = format!("face has {} of its {degree} vertex indices", corners.len());
                return Err(lines.error(malformed(what)));
            };
            let index = match token.parse::<i64>() {
                Ok(i) => i,
                Err(_) if token.bytes().all(|b| b.is_ascii_digit()) => {
                    return Err(lines.error(ParseError::IndexTooLarge {
                        token: shorten(token),
                    }))
                }
                Err(_) => {
                    return Err(lines.error(ParseError::InvalidNumber {
                        token: shorten(token),
                        expected: "vertex index",
                    }))
                }
            };
            if index < 0 || index >= i64::from(n_vertices) {
                let kind = ParseError::IndexOutOfRange {
                    index,
                    vertices: u64::from(n_vertices),
                };
                return Err(lines.error(kind));
            }
            grow(&mut corners, 1, &lines)?;
            corners.push(index as u32);
        }
        let adding = corners.len() * 4 + std::mem::size_of::<usize>() + 8;
        let extra = 4 * corners.capacity() + 24 * colors.capacity();
        if budget.room(&mesh, extra) < adding as u128 {
            return Err(budget.refused(&lines));
        }
        mesh.try_push_face_from_line(&corners, lines.line)
            .map_err(|e| lines.allocation_failed(adding as u128, e))?;
        budget.check(&mesh, extra, &lines)?;
    }
    if mesh.n_faces() == 0 {
        return Err(Error::NoFaces {
            file: lines.name.clone(),
        });
    }
    let vertices = mesh.n_vertices();
    let colors = match (colored, with_colors) {
        (false, _) | (true, 0) => (None, None),
        (true, n) if n == vertices => (Some(colors), None),
        (true, with_colors) => (
            None,
            Some(PartialColors {
                with_colors,
                vertices,
            }),
        ),
    };
    mesh.set_read_extras(colors, None, Vec::new());
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(text: &str) -> String {
        match read_off_from(text.as_bytes(), "m.off") {
            Ok(mesh) => format!("accepted with {} faces", mesh.n_faces()),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn off_errors_name_file_and_line() {
        assert_eq!(
            message("PLY\n"),
            "m.off: line 1: expected the OFF header, found `PLY`"
        );
        assert_eq!(
            message("OFF BINARY\n"),
            "m.off: line 1: binary OFF is not supported"
        );
        assert_eq!(
            message("OFF\n3\n"),
            "m.off: line 2: expected the vertex, face and edge counts"
        );
        assert_eq!(
            message("OFF\nx 1 0\n"),
            "m.off: line 2: `x` is not a valid count"
        );
        assert_eq!(
            message("OFF\n3 1 0\n0 0 0\n1 0 0\n"),
            "m.off: line 4: the file ends early: 2 of 3 vertices read"
        );
        assert_eq!(
            message("OFF\n3 1 0\n0 0 0\n1 0\n"),
            "m.off: line 4: vertex has 2 coordinates, expected 3"
        );
        assert_eq!(
            message("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            "m.off: line 6: face index 3 is out of range (the file has 3 vertices)"
        );
        assert_eq!(
            message("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
            "m.off: line 6: face has 2 of its 3 vertex indices"
        );
        assert_eq!(
            message("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
            "m.off: line 6: face has 2 vertices, at least 3 are needed"
        );
        assert_eq!(
            message("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"),
            "m.off: the file has no faces"
        );
        assert_eq!(message(""), "m.off: the file has no faces");
        assert_eq!(
            message("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0 0.5 0.5 0.5\n3 0 1 2 255 0 0\n"),
            "accepted with 1 faces"
        );
        assert_eq!(
            message("OFF\n3 1 0\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n"),
            "m.off: line 4: coordinate `inf` is not finite"
        );
    }
}
