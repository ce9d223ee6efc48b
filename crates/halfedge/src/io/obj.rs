//! OBJ reading: `v` and `f` statements, everything else ignored.

use std::io::BufRead;
use std::path::Path;

use glam::DVec3;

use super::{open, parse_coordinate, shorten, Budget, Lines};
use crate::error::{Error, ParseError, Result};
use crate::polygon::PolygonMesh;

/// Reads an OBJ file as a face list, keeping polygons (no triangulation) and every `v` line
/// (used or not) in file order.
///
/// # Errors
///
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] naming the file and line of
/// the first malformed statement, [`Error::NoFaces`] for a file without faces,
/// [`Error::FileTooLarge`] for a file larger than the memory available to the process
/// (refused before reading), [`Error::MeshTooLarge`] once the mesh read so far needs more
/// than half of it.
///
/// # Example
///
/// ```no_run
/// let mesh = halfedge::io::read_obj("spot_control_mesh.obj")?;
/// assert_eq!(mesh.n_faces(), 180);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_obj(path: impl AsRef<Path>) -> Result<PolygonMesh> {
    let path = path.as_ref();
    read_obj_from(open(path)?, &path.display().to_string())
}

/// Reads OBJ text from any buffered reader; `name` is the file name used in error messages.
///
/// Reads `v x y z` (further values such as `w` or colours are ignored) and `f` with corners
/// `v`, `v/vt`, `v/vt/vn` or `v//vn`, where `v` is 1-based or negative (relative to the
/// vertices read so far). Positive indices may refer to vertices defined later in the file.
/// Comments (`#`), blank lines, backslash line continuations and all other statements are
/// skipped.
///
/// # Errors
///
/// As [`read_obj`]: a bad or non-finite coordinate, a vertex with fewer than three
/// coordinates, a face index that is 0, not a number, too large or out of range, a face with
/// fewer than three corners, binary data, no faces at all, a mesh beyond the memory budget.
///
/// # Example
///
/// ```
/// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\ng a\nf 1/1 2/2 3/3\ng b\nf -3//1 -1//1 -2//1\n";
/// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "two.obj")?;
/// assert_eq!(mesh.n_faces(), 2);
/// assert_eq!(mesh.face(1), &[0, 2, 1]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_obj_from(reader: impl BufRead, name: &str) -> Result<PolygonMesh> {
    read_obj_within(reader, name, Budget::of_process())
}

/// [`read_obj_from`] with the mesh's memory limited to `budget`.
pub(crate) fn read_obj_within(
    reader: impl BufRead,
    name: &str,
    budget: Budget,
) -> Result<PolygonMesh> {
    let mut lines = Lines::new(reader, name);
    let mut mesh = PolygonMesh::default();
    let mut corners: Vec<u32> = Vec::new();
    // Positive indices beyond the vertices read so far: checked at the end.
    let mut forward: Vec<(u64, i64)> = Vec::new();
    loop {
        if !lines.next_line()? {
            break;
        }
        let line = lines.text.as_str();
        let mut tokens = line.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        match keyword {
            "v" => {
                let mut xyz = [0.0f64; 3];
                for (i, slot) in xyz.iter_mut().enumerate() {
                    let Some(token) = tokens.next() else {
                        let kind = ParseError::MissingCoordinates { found: i };
                        return Err(lines.error(kind));
                    };
                    *slot = parse_coordinate(token).map_err(|kind| lines.error(kind))?;
                }
                if mesh.positions.len() >= u32::MAX as usize - 1 {
                    return Err(Error::TooManyElements {
                        what: "vertices",
                        count: mesh.positions.len() as u64 + 1,
                    });
                }
                mesh.positions.push(DVec3::from_array(xyz));
                budget.check(&mesh, &lines)?;
            }
            "f" => {
                corners.clear();
                let count = mesh.positions.len() as u64;
                for token in tokens {
                    let field = token.split('/').next().unwrap_or("");
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
                        if index as u64 > count {
                            forward.push((lines.line, index));
                        }
                        index as u64 - 1
                    };
                    corners.push(resolved as u32);
                }
                if corners.len() < 3 {
                    let kind = ParseError::FaceTooSmall {
                        corners: corners.len(),
                    };
                    return Err(lines.error(kind));
                }
                mesh.push_face_from_line(&corners, lines.line);
                budget.check(&mesh, &lines)?;
            }
            _ => {}
        }
    }
    let count = mesh.positions.len() as u64;
    if let Some(&(line, index)) = forward.iter().find(|&&(_, index)| index as u64 > count) {
        return Err(Error::Parse {
            file: name.to_string(),
            line,
            kind: ParseError::IndexOutOfRange {
                index,
                vertices: count,
            },
        });
    }
    if mesh.n_faces() == 0 {
        return Err(Error::NoFaces {
            file: name.to_string(),
        });
    }
    Ok(mesh)
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

    #[test]
    fn corner_forms_groups_and_ignored_statements() {
        let text = "mtllib x.mtl\no one\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0 0.5 0.5 0.5\n\
                    vt 0 0\nvn 0 0 1\nvp 0.5\ns off\ng a b\nusemtl m\n\
                    f 1/1 2/1/1 3//1\nt crease 2 1 0 1 2\nl 1 2\ng c\nf -4 -2 \\\n -1 # tail\n\
                    f 1 3 4\n";
        let mesh = read_obj_from(text.as_bytes(), "x.obj").expect("valid");
        assert_eq!(mesh.n_vertices(), 4);
        assert_eq!(mesh.positions[3], DVec3::new(0.0, 1.0, 0.0));
        let faces: Vec<&[u32]> = mesh.faces().collect();
        assert_eq!(faces, [&[0, 1, 2][..], &[0, 2, 3], &[0, 2, 3]]);
    }

    #[test]
    fn crlf_and_plus_signs() {
        let text = "v +1 -2.5e1 .5\r\nv 0 0 0\r\nv 0 1 0\r\nf +1 2 3\r\n";
        let mesh = read_obj_from(text.as_bytes(), "x.obj").expect("valid");
        assert_eq!(mesh.positions[0], DVec3::new(1.0, -25.0, 0.5));
        assert_eq!(mesh.face(0), &[0, 1, 2]);
    }
}
