//! PLY reading (`ascii`, `binary_little_endian`, `binary_big_endian` 1.0) and writing
//! (`binary_little_endian` 1.0): positions, faces, vertex colors and texture coordinates.

mod binary;
mod body;
mod header;
mod records;
mod write;

use self::body::*;
use self::header::*;
pub use self::write::{write_mesh_buffers_ply, write_polygon_ply};

use std::io::BufRead;
use std::path::Path;

use super::{escape_controls, Budget, ReadOptions};
use crate::error::Result;
use crate::polygon::PolygonMesh;

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
/// [`Error::Io`](crate::Error::Io) when the file cannot be read; [`Error::Parse`](crate::Error::Parse) naming the file and the
/// header line for a malformed header; [`Error::PlyData`](crate::Error::PlyData) naming the file, the element, its
/// index and the property for bad data (a vertex index out of range, a face of fewer than 3
/// corners, a list count that is negative or above 16 Mi, a non-finite coordinate, color or
/// texture coordinate, text that is not a number in ASCII data, data that ends early);
/// [`Error::NoFaces`](crate::Error::NoFaces) for a file without faces.
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
/// larger file is [`Error::FileTooLarge`](crate::Error::FileTooLarge) before it is read, a mesh outgrowing half of it
/// [`Error::MeshTooLarge`](crate::Error::MeshTooLarge)); PLY has no tags.
///
/// # Errors
///
/// As [`read_ply`], and the memory refusals.
pub fn read_ply_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<PolygonMesh> {
    super::read_file(path.as_ref(), options, read_ply_within)
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
    let unlimited = Budget::of(&ReadOptions::DEFAULT);
    read_ply_within(reader, name, unlimited)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use crate::io::lines::testing::{outcome, Trickle};
    use glam::DVec2;

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
        let max = "18446744073709551615";
        for (extra, expected) in [
            (
                format!(
                    "element edge {max}\nproperty int a\nproperty int b\nelement nothing {max}\n"
                ),
                format!(
                    "m.ply: edge 0: the file ends early: the header declares {max} `edge` elements"
                ),
            ),
            (
                format!("element nothing {max}\n"),
                "accepted with 1 faces".to_string(),
            ),
        ] {
            let skipped = header.replace("end_header", &format!("{extra}end_header"));
            assert_eq!(message(&binary(&skipped, &body)), expected);
        }
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

    /// A binary PLY of a few faces, `big_endian` or not, its corners as `int`.
    fn binary_ply(big_endian: bool, faces: &[&[i32]], positions: &[[f64; 3]]) -> Vec<u8> {
        let format = if big_endian {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let mut bytes = format!(
            "ply\nformat {format} 1.0\nelement vertex {}\nproperty double x\nproperty double y\n\
             property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
             element face {}\nproperty list uchar int vertex_indices\nend_header\n",
            positions.len(),
            faces.len()
        )
        .into_bytes();
        for (i, p) in positions.iter().enumerate() {
            for x in p {
                bytes.extend(if big_endian {
                    x.to_be_bytes()
                } else {
                    x.to_le_bytes()
                });
            }
            bytes.extend([i as u8, 2 * i as u8, 255]);
        }
        for face in faces {
            bytes.push(face.len() as u8);
            for &v in *face {
                bytes.extend(if big_endian {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                });
            }
        }
        bytes
    }

    #[test]
    fn a_list_longer_than_what_is_read_whole_is_read_value_by_value() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let long: Vec<i32> = (0..20_000).map(|i| i % 3).collect();
        let bytes = binary_ply(false, &[&[0, 1, 2], &long], &positions);
        let bytes = String::from_utf8_lossy(&bytes)
            .replace("list uchar int", "list int int")
            .into_bytes();
        // The count of a face as `int`: rebuild the data with four-byte counts.
        let header_end = bytes
            .windows(11)
            .position(|w| w == b"end_header\n")
            .unwrap()
            + 11;
        let mut data = bytes[..header_end].to_vec();
        for p in positions {
            for x in p {
                data.extend(x.to_le_bytes());
            }
            data.extend([0, 0, 255]);
        }
        for face in [&[0, 1, 2][..], &long] {
            data.extend((face.len() as i32).to_le_bytes());
            for &v in face {
                data.extend(v.to_le_bytes());
            }
        }
        let mesh = read_ply_from(data.as_slice(), "long.ply").expect("valid");
        assert_eq!(
            mesh.face(1),
            long.iter().map(|&v| v as u32).collect::<Vec<_>>()
        );
        let cut = &data[..data.len() - 10];
        assert_eq!(
            read_ply_from(cut, "long.ply").unwrap_err().to_string(),
            "long.ply: face 1, property `vertex_indices`: the file ends early: the header declares 2 `face` elements"
        );
    }

    #[test]
    fn binary_ply_reads_the_same_however_its_bytes_come() {
        let positions = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, f64::NAN],
        ];
        let cases: &[&[&[i32]]] = &[
            &[&[0, 1, 2], &[2, 1, 0, 1]],
            &[&[0, 1, 2], &[2, 1, 7]],
            &[&[0, 1, 2], &[2, -1, 0]],
            &[&[0, 1], &[0, 1, 2]],
            &[&[0, 1, 2, 0, 1, 2, 0, 1, 2], &[0, 1, 2], &[0, 1, 2, 0, 1]],
        ];
        for big_endian in [false, true] {
            for faces in cases {
                for vertices in [3, 4] {
                    let bytes = binary_ply(big_endian, faces, &positions[..vertices]);
                    for cut in (0..=bytes.len()).rev() {
                        let data = &bytes[..cut];
                        for budget in [u64::MAX, 300, 180] {
                            let budget = Budget { bytes: budget };
                            let whole = outcome(read_ply_within(data, "t.ply", budget));
                            let trickle = std::io::BufReader::with_capacity(
                                2,
                                Trickle::new(data, cut as u64, None),
                            );
                            let read = read_ply_within(trickle, "t.ply", budget);
                            assert_eq!(outcome(read), whole, "{cut}");
                        }
                        // A read error at `cut`: what the data up to it gives (an error before
                        // the cut), or the read error; never the end of the data.
                        let unlimited = Budget { bytes: u64::MAX };
                        let failing = std::io::BufReader::with_capacity(
                            2,
                            Trickle::new(&bytes, 3, Some(cut)),
                        );
                        let read = read_ply_within(failing, "t.ply", unlimited);
                        let ended = read_ply_within(data, "t.ply", unlimited);
                        if cut < bytes.len() && !matches!(read, Err(Error::Io { .. })) {
                            let message = outcome(ended);
                            assert!(!message.contains("ends early"), "{cut}: {message}");
                            assert_eq!(outcome(read), message, "{cut}");
                        }
                    }
                }
            }
        }
    }
}
