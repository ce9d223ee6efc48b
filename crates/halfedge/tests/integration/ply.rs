//! PLY through our reader and writer: round trips (`f64` and `f32`; triangles, quads,
//! polygons and a face of 300 corners; colors as `uchar` and as floats; UVs per vertex and
//! per face), `ply-rs` (an independent reader) reading what we write, ASCII and both binary
//! byte orders of one mesh, every error's message, and the memory budget.

use std::path::PathBuf;

use halfedge::glam::{DVec2, DVec3};
use halfedge::io::{self, FaceBuffers, MeshBuffers, ObjWriteOptions, ReadOptions, UvBuffers};
use halfedge::uv::Uvs;
use halfedge::{normals, shapes, Error, PolygonMesh};

/// A temporary file path for this test process.
fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("halfedge-ply-{}-{name}", std::process::id()))
}

fn write(mesh: &PolygonMesh, options: &ObjWriteOptions) -> Vec<u8> {
    let mut out = Vec::new();
    io::write_polygon_ply(mesh, &mut out, options).expect("written");
    out
}

fn read(bytes: &[u8]) -> PolygonMesh {
    io::read_ply_from(bytes, "t.ply").unwrap_or_else(|e| panic!("{e}"))
}

/// The header of a PLY file, up to and including `end_header`.
fn header(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let end = text.find("end_header\n").expect("a header") + "end_header\n".len();
    text[..end].to_string()
}

/// The UV value of every corner.
fn corner_uvs(mesh: &PolygonMesh) -> Vec<DVec2> {
    let uvs = mesh.uvs().expect("uvs");
    uvs.corners()
        .iter()
        .map(|&t| uvs.coords()[t as usize])
        .collect()
}

/// A polygon of 300 corners on the unit circle, and a triangle on three of them.
fn wide() -> PolygonMesh {
    let positions = (0..300)
        .map(|i| {
            let a = f64::from(i) * std::f64::consts::TAU / 300.0;
            DVec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    let ring: Vec<u32> = (0..300).collect();
    PolygonMesh::from_faces(positions, [ring, vec![2, 1, 0]])
}

/// Triangles, quads, mixed polygons and a 300-gon.
fn meshes() -> Vec<(&'static str, PolygonMesh)> {
    vec![
        ("icosahedron", shapes::icosahedron()),
        ("cube", shapes::cube()),
        ("mixed", shapes::mixed()),
        ("wide", wide()),
    ]
}

fn same_faces(a: &PolygonMesh, b: &PolygonMesh, what: &str) {
    assert_eq!(a.face_offsets(), b.face_offsets(), "{what}");
    assert_eq!(a.face_indices(), b.face_indices(), "{what}");
}

#[test]
fn polygon_meshes_round_trip_with_colors_on_both_paths() {
    let on = ObjWriteOptions::default();
    for (name, mesh) in meshes() {
        let n = mesh.n_vertices();
        let back = read(&write(&mesh, &on));
        assert_eq!(back, mesh, "{name}");
        assert_eq!((back.uvs(), back.colors()), (None, None), "{name}");
        let bytes = write(&mesh, &on);
        let head = header(&bytes);
        let count = if name == "wide" { "uint" } else { "uchar" };
        assert!(
            head.ends_with(&format!(
                "element face {}\nproperty list {count} int vertex_indices\nend_header\n",
                mesh.n_faces()
            )),
            "{name}: {head}"
        );
        // Colors k/255: written as uchar, read back as the same f64.
        let mut colored = mesh.clone();
        let bytes: Vec<[f64; 3]> = (0..n)
            .map(|v| [v % 256, (7 * v + 3) % 256, 255 - v % 256].map(|k| k as f64 / 255.0))
            .collect();
        colored.set_colors(Some(bytes)).expect("a color per vertex");
        let written = write(&colored, &on);
        assert!(header(&written)
            .contains("property uchar red\nproperty uchar green\nproperty uchar blue\n"));
        assert_eq!(read(&written), colored, "{name}: uchar colors");
        // Colors outside [0, 1]: written as float (as MeshLab writes them), read back as the
        // same f32 values.
        let floats: Vec<[f64; 3]> = (0..n)
            .map(|v| [v as f64 * 1.5 - 3.0, 0.1 * v as f64, 1.0 + 1e-9])
            .collect();
        colored
            .set_colors(Some(floats.clone()))
            .expect("a color per vertex");
        let written = write(&colored, &on);
        assert!(header(&written)
            .contains("property float red\nproperty float green\nproperty float blue\n"));
        let back = read(&written);
        let as_f32 =
            |c: &[[f64; 3]]| -> Vec<f32> { c.iter().flatten().map(|&x| x as f32).collect() };
        let read_back: Vec<f32> = back
            .colors()
            .expect("colors")
            .iter()
            .flatten()
            .map(|&x| x as f32)
            .collect();
        assert_eq!(read_back, as_f32(&floats), "{name}");
        assert!(back
            .colors()
            .expect("colors")
            .iter()
            .flatten()
            .all(|&x| f64::from(x as f32) == x));
        assert_eq!(
            (back.positions.clone(), back.face_indices()),
            (colored.positions.clone(), colored.face_indices()),
            "{name}"
        );
    }
    // Unused vertices are kept, in order.
    let mut mesh = shapes::cube();
    mesh.positions.push(DVec3::new(9.0, 9.0, 9.0));
    assert_eq!(read(&write(&mesh, &on)), mesh);
}

#[test]
fn texture_coordinates_round_trip_per_vertex_and_per_face() {
    let on = ObjWriteOptions::default();
    for (name, mesh) in meshes() {
        // Without seams: a value per corner, but every vertex's corners agree (bit for bit):
        // written as `s t` per vertex.
        let uv = |v: u32| DVec2::new(f64::from(v) * 0.125, 1.0 - f64::from(v) / 7.0);
        let coords: Vec<DVec2> = mesh.face_indices().iter().map(|&v| uv(v)).collect();
        let corners: Vec<u32> = (0..mesh.n_corners() as u32).collect();
        let mut textured = mesh.clone();
        textured
            .set_uvs(Some(Uvs::new(coords.clone(), corners).expect("in range")))
            .expect("a value per corner");
        let bytes = write(&textured, &on);
        let head = header(&bytes);
        assert!(
            head.contains("property double s\nproperty double t\nelement face"),
            "{name}: {head}"
        );
        assert!(!head.contains("texcoord"), "{name}");
        let back = read(&bytes);
        same_faces(&back, &mesh, name);
        assert_eq!(back.positions, mesh.positions, "{name}");
        assert_eq!(corner_uvs(&back), coords, "{name}: per vertex");
        assert_eq!(back.uvs().expect("uvs").coords().len(), mesh.n_vertices());
        // Without the option: no texture coordinates.
        let plain = read(&write(&textured, &on.with_uvs(false)));
        assert_eq!(plain.uvs(), None, "{name}");
        // With seams: a value per corner, written as `texcoord` lists.
        let coords: Vec<DVec2> = (0..mesh.n_corners())
            .map(|c| DVec2::new(c as f64 / 3.0, -(c as f64) * 0.25))
            .collect();
        let corners: Vec<u32> = (0..mesh.n_corners() as u32).collect();
        textured
            .set_uvs(Some(Uvs::new(coords.clone(), corners).expect("in range")))
            .expect("a value per corner");
        let bytes = write(&textured, &on);
        let head = header(&bytes);
        let count = if name == "wide" { "uint" } else { "uchar" };
        assert!(
            head.ends_with(&format!(
                "int vertex_indices\nproperty list {count} double texcoord\nend_header\n"
            )),
            "{name}: {head}"
        );
        let back = read(&bytes);
        same_faces(&back, &mesh, name);
        assert_eq!(corner_uvs(&back), coords, "{name}: per face");
        // Equal pairs at one vertex share a value, in order of first appearance (as the UV
        // layout counts values: a (vertex, u, v) each).
        let mut shared = mesh.clone();
        let few: Vec<DVec2> = vec![DVec2::ZERO, DVec2::X, DVec2::Y];
        let corners: Vec<u32> = (0..mesh.n_corners() as u32)
            .map(|c| (c * c + 1) % 3)
            .collect();
        shared
            .set_uvs(Some(
                Uvs::new(few.clone(), corners.clone()).expect("in range"),
            ))
            .expect("a value per corner");
        let back = read(&write(&shared, &on));
        let expected: Vec<DVec2> = corners.iter().map(|&t| few[t as usize]).collect();
        assert_eq!(corner_uvs(&back), expected, "{name}");
        let layout = back.uv_layout().expect("uvs");
        assert_eq!(back.uvs().expect("uvs").coords().len(), layout.n_values());
        assert_eq!(
            layout.n_values(),
            shared.uv_layout().expect("uvs").n_values()
        );
    }
}

/// `f32` buffers: positions, colors and UVs come back as the same `f32` values in `f64`.
#[test]
fn f32_buffers_round_trip() {
    let positions: Vec<[f32; 3]> = (0..300)
        .map(|i| {
            let x = i as f32;
            [x * 0.1, (x * 0.37).sin(), 1.0 / (x + 1.0)]
        })
        .collect();
    // Every used vertex in two corners (150 of the 300 positions are used).
    let indices: Vec<u32> = (0..300).map(|i| i % 150).collect();
    let offsets = [0u32, 3, 7, 12, 300];
    let buffers = [
        (
            FaceBuffers::Uniform {
                degree: 3,
                indices: &indices,
            },
            "uchar",
        ),
        (
            FaceBuffers::Uniform {
                degree: 4,
                indices: &indices[..296],
            },
            "uchar",
        ),
        (
            FaceBuffers::Polygons {
                offsets: &offsets,
                indices: &indices,
            },
            "uint",
        ),
    ];
    let widen = |p: &[[f32; 3]]| -> Vec<DVec3> {
        p.iter()
            .map(|&[x, y, z]| DVec3::new(x.into(), y.into(), z.into()))
            .collect()
    };
    let on = ObjWriteOptions::default();
    for (faces, count) in buffers {
        let write = |mesh: &MeshBuffers<'_, f32>, options: &ObjWriteOptions| {
            let mut out = Vec::new();
            io::write_mesh_buffers_ply(mesh, &mut out, options).expect("written");
            out
        };
        let mesh = MeshBuffers::new(&positions, faces);
        let bytes = write(&mesh, &on);
        let head = header(&bytes);
        assert!(
            head.contains("property float x\nproperty float y\nproperty float z\n"),
            "{head}"
        );
        assert!(
            head.contains(&format!("property list {count} int vertex_indices")),
            "{head}"
        );
        let back = read(&bytes);
        assert_eq!(back.positions, widen(&positions));
        let n_corners = back.n_corners();
        assert_eq!(back.face_indices(), &indices[..n_corners]);
        // Colors k/255 (uchar) and outside [0, 1] (float).
        let bytes_colors: Vec<[f32; 3]> = (0..300)
            .map(|v| [v % 256, 3, 255].map(|k| k as f32 / 255.0))
            .collect();
        let back = read(&write(&mesh.with_colors(&bytes_colors), &on));
        let expected: Vec<[f64; 3]> = (0..300)
            .map(|v| [v % 256, 3, 255].map(|k| k as f64 / 255.0))
            .collect();
        assert_eq!(back.colors().expect("colors"), expected.as_slice());
        let float_colors: Vec<[f32; 3]> = (0..300).map(|v| [v as f32 * 0.3, -0.1, 2.5]).collect();
        let bytes = write(&mesh.with_colors(&float_colors), &on);
        assert!(header(&bytes).contains("property float red\n"));
        let back = read(&bytes);
        let expected: Vec<[f64; 3]> = float_colors.iter().map(|c| c.map(f64::from)).collect();
        assert_eq!(back.colors().expect("colors"), expected.as_slice());
        // UVs per vertex (no seams) and per face.
        let per_vertex: Vec<[f32; 2]> = (0..300).map(|v| [v as f32 / 300.0, 0.5]).collect();
        let uvs = UvBuffers {
            values: &per_vertex,
            corners: &indices[..n_corners],
        };
        let bytes = write(&mesh.with_uvs(uvs), &on);
        assert!(header(&bytes).contains("property float s\nproperty float t\n"));
        let expected: Vec<DVec2> = indices[..n_corners]
            .iter()
            .map(|&v| DVec2::new(per_vertex[v as usize][0].into(), 0.5))
            .collect();
        assert_eq!(corner_uvs(&read(&bytes)), expected);
        let seams: Vec<u32> = (0..n_corners as u32).map(|c| c % 7).collect();
        let uvs = UvBuffers {
            values: &per_vertex[..7],
            corners: &seams,
        };
        let bytes = write(&mesh.with_uvs(uvs), &on);
        assert!(
            header(&bytes).contains("float texcoord\n"),
            "{}",
            header(&bytes)
        );
        let expected: Vec<DVec2> = seams
            .iter()
            .map(|&t| DVec2::new(per_vertex[t as usize][0].into(), 0.5))
            .collect();
        assert_eq!(corner_uvs(&read(&bytes)), expected);
    }
    // Inconsistent buffers are refused before anything is written.
    let mut out = Vec::new();
    let bad = FaceBuffers::Uniform {
        degree: 3,
        indices: &[0, 1, 300],
    };
    let err =
        io::write_mesh_buffers_ply(&MeshBuffers::new(&positions, bad), &mut out, &on).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert!(out.is_empty());
}

/// `ply-rs` reads what we write: the same positions, faces, colors and normals.
#[test]
fn ply_rs_reads_what_we_write() {
    use ply_rs::parser::Parser;
    use ply_rs::ply::{DefaultElement, Property};

    let number = |p: &Property| match *p {
        Property::Double(x) => x,
        Property::Float(x) => f64::from(x),
        Property::UChar(x) => f64::from(x) / 255.0,
        ref other => panic!("{other:?}"),
    };
    let list = |p: &Property| -> Vec<u32> {
        match p {
            Property::ListInt(v) => v.iter().map(|&i| i as u32).collect(),
            Property::ListUInt(v) => v.clone(),
            other => panic!("{other:?}"),
        }
    };
    let on = ObjWriteOptions::default();
    for (name, mesh) in meshes() {
        for float_colors in [false, true] {
            let mut colored = mesh.clone();
            let colors: Vec<[f64; 3]> = (0..mesh.n_vertices())
                .map(|v| match float_colors {
                    false => [(v % 256) as f64 / 255.0, 1.0, 0.0],
                    true => [v as f64 - 0.25, 1.0, -2.0],
                })
                .collect();
            colored
                .set_colors(Some(colors.clone()))
                .expect("a color per vertex");
            let bytes = write(&colored, &on.with_normals(true));
            let ply = Parser::<DefaultElement>::new()
                .read_ply(&mut bytes.as_slice())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let vertices = &ply.payload["vertex"];
            let faces = &ply.payload["face"];
            assert_eq!(vertices.len(), mesh.n_vertices(), "{name}");
            let expected = normals::vertex_normals(&mesh.positions, mesh.faces());
            for (v, e) in vertices.iter().enumerate() {
                let p = DVec3::new(number(&e["x"]), number(&e["y"]), number(&e["z"]));
                assert_eq!(p, mesh.positions[v], "{name}: vertex {v}");
                let c = [number(&e["red"]), number(&e["green"]), number(&e["blue"])];
                assert_eq!(c, colors[v], "{name}: color {v}");
                let n = DVec3::new(number(&e["nx"]), number(&e["ny"]), number(&e["nz"]));
                assert_eq!(n, expected[v], "{name}: normal {v}");
            }
            let theirs: Vec<Vec<u32>> = faces.iter().map(|f| list(&f["vertex_indices"])).collect();
            let ours: Vec<Vec<u32>> = mesh.faces().map(<[u32]>::to_vec).collect();
            assert_eq!(theirs, ours, "{name}");
        }
    }
}

/// A test encoder: PLY of any format, of elements given as declarations and rows.
mod encode {
    /// A PLY scalar type.
    #[derive(Clone, Copy)]
    pub(super) enum Ty {
        Char,
        UChar,
        Short,
        UShort,
        Int,
        UInt,
        Float,
        Double,
    }

    impl Ty {
        fn name(self) -> &'static str {
            [
                "int8", "uchar", "short", "uint16", "int", "uint32", "float", "float64",
            ][self as usize]
        }

        fn bytes(self, x: f64, big: bool) -> Vec<u8> {
            macro_rules! b {
                ($v:expr) => {
                    if big {
                        $v.to_be_bytes().to_vec()
                    } else {
                        $v.to_le_bytes().to_vec()
                    }
                };
            }
            match self {
                Ty::Char => b!(x as i8),
                Ty::UChar => b!(x as u8),
                Ty::Short => b!(x as i16),
                Ty::UShort => b!(x as u16),
                Ty::Int => b!(x as i32),
                Ty::UInt => b!(x as u32),
                Ty::Float => b!(x as f32),
                Ty::Double => b!(x),
            }
        }
    }

    /// A property: a scalar, or a list with its count type.
    pub(super) enum Decl {
        S(Ty),
        L(Ty, Ty),
    }

    /// A value: one number, or a list.
    pub(super) enum D {
        One(f64),
        Many(Vec<f64>),
    }

    pub(super) struct El {
        pub(super) name: &'static str,
        pub(super) props: Vec<(&'static str, Decl)>,
        pub(super) rows: Vec<Vec<D>>,
    }

    /// The file in `format` (`ascii`, `binary_little_endian`, `binary_big_endian`).
    pub(super) fn encode(format: &str, elements: &[El]) -> Vec<u8> {
        let mut out = format!("ply\nformat {format} 1.0\ncomment test\n");
        for e in elements {
            out += &format!("element {} {}\n", e.name, e.rows.len());
            for (name, decl) in &e.props {
                match decl {
                    Decl::S(t) => out += &format!("property {} {name}\n", t.name()),
                    Decl::L(c, t) => {
                        out += &format!("property list {} {} {name}\n", c.name(), t.name())
                    }
                }
            }
        }
        out += "end_header\n";
        let mut bytes = out.into_bytes();
        let big = format == "binary_big_endian";
        let ascii = format == "ascii";
        for e in elements {
            for row in &e.rows {
                let mut text: Vec<String> = Vec::new();
                for ((_, decl), value) in e.props.iter().zip(row) {
                    let mut put = |t: &Ty, x: f64| {
                        text.push(x.to_string());
                        if !ascii {
                            bytes.extend(t.bytes(x, big));
                        }
                    };
                    match (decl, value) {
                        (Decl::S(t), D::One(x)) => put(t, *x),
                        (Decl::L(c, t), D::Many(xs)) => {
                            put(c, xs.len() as f64);
                            for &x in xs {
                                put(t, x);
                            }
                        }
                        _ => panic!("a value of another shape than its property"),
                    }
                }
                if ascii {
                    bytes.extend(format!("{}\n", text.join(" ")).into_bytes());
                }
            }
        }
        bytes
    }
}

use encode::{Decl, El, Ty, D};

/// A pyramid in every scalar type, with colors, normals, a quality, per-face texture
/// coordinates and per-vertex ones (which lose), face flags, and `edge` and `material`
/// elements (skipped).
fn pyramid() -> Vec<El> {
    let positions = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
        [1.0, 1.0, 1.5],
    ];
    let faces: [&[f64]; 5] = [
        &[0.0, 1.0, 4.0],
        &[1.0, 2.0, 4.0],
        &[2.0, 3.0, 4.0],
        &[3.0, 0.0, 4.0],
        &[3.0, 2.0, 1.0, 0.0],
    ];
    let vertex = El {
        name: "vertex",
        props: vec![
            ("quality", Decl::S(Ty::UShort)),
            ("x", Decl::S(Ty::Float)),
            ("y", Decl::S(Ty::Double)),
            ("z", Decl::S(Ty::Float)),
            ("nx", Decl::S(Ty::Char)),
            ("red", Decl::S(Ty::UChar)),
            ("green", Decl::S(Ty::UChar)),
            ("blue", Decl::S(Ty::UChar)),
            ("u", Decl::S(Ty::Float)),
            ("v", Decl::S(Ty::Float)),
        ],
        rows: positions
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let i = i as f64;
                [
                    7.0 * i,
                    p[0],
                    p[1],
                    p[2],
                    -1.0,
                    50.0 * i,
                    255.0,
                    0.0,
                    0.5,
                    0.25,
                ]
                .into_iter()
                .map(D::One)
                .collect()
            })
            .collect(),
    };
    let face = El {
        name: "face",
        props: vec![
            ("flags", Decl::S(Ty::Int)),
            ("texcoord", Decl::L(Ty::UChar, Ty::Float)),
            ("vertex_indices", Decl::L(Ty::UChar, Ty::UInt)),
            ("extra", Decl::L(Ty::Short, Ty::Short)),
        ],
        rows: faces
            .iter()
            .enumerate()
            .map(|(f, corners)| {
                let uv: Vec<f64> = corners
                    .iter()
                    .flat_map(|&v| [v * 0.25, f as f64 * 0.5])
                    .collect();
                vec![
                    D::One(-(f as f64)),
                    D::Many(uv),
                    D::Many(corners.to_vec()),
                    D::Many(vec![-3.0; f]),
                ]
            })
            .collect(),
    };
    let edge = El {
        name: "edge",
        props: vec![("vertex1", Decl::S(Ty::Int)), ("vertex2", Decl::S(Ty::Int))],
        rows: vec![
            vec![D::One(0.0), D::One(1.0)],
            vec![D::One(1.0), D::One(2.0)],
        ],
    };
    let material = El {
        name: "material",
        props: vec![
            ("name", Decl::L(Ty::UInt, Ty::UChar)),
            ("shine", Decl::S(Ty::Double)),
        ],
        rows: vec![vec![
            D::Many(b"steel".iter().map(|&b| f64::from(b)).collect()),
            D::One(0.5),
        ]],
    };
    vec![vertex, edge, face, material]
}

#[test]
fn ascii_and_both_byte_orders_read_to_the_same_mesh() {
    let elements = pyramid();
    let meshes: Vec<PolygonMesh> = ["ascii", "binary_little_endian", "binary_big_endian"]
        .iter()
        .map(|format| {
            io::read_ply_from(encode::encode(format, &elements).as_slice(), "p.ply")
                .unwrap_or_else(|e| panic!("{format}: {e}"))
        })
        .collect();
    let mesh = &meshes[0];
    for other in &meshes[1..] {
        assert_eq!(other, mesh);
        assert_eq!(other.uncarried(), mesh.uncarried());
        assert_eq!(corner_uvs(other), corner_uvs(mesh));
    }
    assert_eq!(mesh.n_vertices(), 5);
    assert_eq!(mesh.positions[4], DVec3::new(1.0, 1.0, 1.5));
    assert_eq!(mesh.face(4), &[3, 2, 1, 0]);
    assert_eq!(mesh.colors().expect("colors")[2], [100.0 / 255.0, 1.0, 0.0]);
    // The per-face texture coordinates win over the vertices' `u v`.
    assert_eq!(
        corner_uvs(mesh)[..3],
        [
            DVec2::new(0.0, 0.0),
            DVec2::new(0.25, 0.0),
            DVec2::new(1.0, 0.0)
        ]
    );
    let uncarried: Vec<String> = mesh.uncarried().iter().map(ToString::to_string).collect();
    assert_eq!(
        uncarried,
        [
            "2 `edge` elements",
            "1 `material` elements",
            "5 values of `face` property `extra`",
            "5 values of `face` property `flags`",
            "5 values of `vertex` property `nx`",
            "5 values of `vertex` property `quality`",
            "5 values of `vertex` property `u`",
            "5 values of `vertex` property `v`",
        ]
    );
    // Without `texcoord`, the vertices' `u v` are the UVs; without `blue`, no colors.
    let mut elements = pyramid();
    elements[2].props[1].0 = "coords";
    elements[0].props[7].0 = "bleu";
    let bytes = encode::encode("binary_big_endian", &elements);
    let mesh = read(&bytes);
    assert_eq!(
        mesh.uvs().expect("uvs").coords(),
        [DVec2::new(0.5, 0.25); 5]
    );
    assert_eq!(mesh.uvs().expect("uvs").corners(), mesh.face_indices());
    assert_eq!(mesh.colors(), None);
    assert!(mesh
        .uncarried()
        .iter()
        .any(|u| u.to_string() == "5 values of `vertex` property `red`"));
}

#[test]
fn read_mesh_dispatches_on_the_extension_and_files_are_named() {
    let path = temp("Cube.PLY");
    std::fs::write(&path, write(&shapes::cube(), &ObjWriteOptions::default())).expect("written");
    assert_eq!(io::read_mesh(&path).expect("a .PLY file"), shapes::cube());
    assert_eq!(io::read_ply(&path).expect("read"), shapes::cube());
    // A header claiming 10^9 vertices over a small file: refused cleanly, without
    // allocating for the claim, with or without a memory limit.
    let bytes = std::fs::read(&path).expect("read");
    let text = String::from_utf8_lossy(&bytes)
        .replace("element vertex 8\n", "element vertex 1000000000\n");
    let mut claim = text.into_bytes();
    claim.truncate(header(&claim).len() + 100);
    std::fs::write(&path, &claim).expect("written");
    let expected = format!(
        "{}: vertex 4, property `x`: the file ends early: the header declares 1000000000 `vertex` elements",
        path.display()
    );
    assert_eq!(io::read_mesh(&path).unwrap_err().to_string(), expected);
    let limited = ReadOptions::default().with_available_bytes(Some(1 << 20));
    assert_eq!(
        io::read_ply_with(&path, &limited).unwrap_err().to_string(),
        expected
    );
    std::fs::remove_file(&path).expect("cleanup");
}

#[test]
fn the_budget_refuses_a_big_mesh() {
    let grid = shapes::grid(100, 100).expect("a grid");
    let bytes = write(&grid, &ObjWriteOptions::default());
    let path = temp("grid.ply");
    std::fs::write(&path, &bytes).expect("written");
    let size = bytes.len() as u64;
    assert_eq!(
        io::read_ply_with(&path, &ReadOptions::default()).expect("no limit"),
        grid
    );
    // The file fits what is available, the mesh not half of it.
    let err = io::read_ply_with(
        &path,
        &ReadOptions::default().with_available_bytes(Some(size)),
    )
    .unwrap_err();
    assert!(matches!(err, Error::MeshTooLarge { line: 11, .. }), "{err}");
    assert!(err.is_resource_limit());
    assert_eq!(
        err.to_string(),
        format!(
            "{}: line 11: the mesh read so far needs more than {} bytes of memory, half of what is available to this process",
            path.display(),
            size / 2
        )
    );
    let err = io::read_ply_with(
        &path,
        &ReadOptions::default().with_available_bytes(Some(size - 1)),
    )
    .unwrap_err();
    assert!(matches!(err, Error::FileTooLarge { .. }), "{err}");
    std::fs::remove_file(&path).expect("cleanup");
}

/// Every error the reader reports, with its message: the header's name the line, the
/// data's the element, its index and the property.
#[test]
fn every_error_names_the_file_and_where() {
    let v = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    let f = "element face 1\nproperty list uchar int vertex_indices\n";
    let ascii = |head: &str, data: &str| format!("ply\nformat ascii 1.0\n{head}end_header\n{data}");
    let ok = "0 0 0\n1 0 0\n0 1 0\n";
    let cases: Vec<(String, &str)> = vec![
        (ascii(&format!("{v}{f}"), &format!("{ok}3 0 1 500\n")), "m.ply: face 0: vertex index 500 is out of range (the file has 3 vertices)"),
        (ascii(&format!("{v}{f}"), &format!("{ok}2 0 1\n")), "m.ply: face 0: face has 2 vertices, at least 3 are needed"),
        (ascii(&format!("{v}{}", f.replace("uchar int", "int int")), &format!("{ok}-1 0 1 2\n")), "m.ply: face 0, property `vertex_indices`: list count -1 is not valid (expected 0 to 16777216)"),
        (ascii(&format!("{v}{f}"), "0 0 0\n1 nan 0\n"), "m.ply: vertex 1, property `y`: coordinate `nan` is not finite"),
        (ascii(&format!("{v}{f}"), "0 0 0\n1 zero 0\n"), "m.ply: vertex 1, property `y`: `zero` is not a valid float"),
        (ascii(&format!("{v}{f}"), ok), "m.ply: face 0: the file ends early: the header declares 1 `face` elements"),
        (ascii(&format!("{v}{f}").replace("face 1", "face 0"), ok), "m.ply: the file has no faces"),
        (format!("ply\n{v}{f}end_header\n"), "m.ply: line 8: the header has no `format` line"),
        ("ply\nformat ascii 1.1\n".into(), "m.ply: line 2: unknown format `ascii 1.1` (expected ascii 1.0, binary_little_endian 1.0 or binary_big_endian 1.0)"),
        (ascii(&v.replace("float y", "real y"), ""), "m.ply: line 5: unknown property type `real`"),
        (format!("ply\nformat ascii 1.0\n{v}{f}"), "m.ply: line 8: the file ends early: the header has no `end_header` line"),
        (ascii(&format!("property float x\n{v}{f}"), ""), "m.ply: line 3: `property` line before any `element` line"),
        (ascii(&v.replace("vertex 3", "vertex 3.0"), ""), "m.ply: line 3: `3.0` is not a valid element count"),
        (ascii(&format!("{}{f}", v.replace("float x", "list uchar float x")), ""), "m.ply: line 4: property `x` of element `vertex` is a list, expected a number"),
        (ascii(&format!("{v}{f}{v}"), ""), "m.ply: line 9: a second `vertex` element"),
        (ascii(f, ""), "m.ply: line 5: the header has no `vertex` element"),
        (ascii(v, ""), "m.ply: line 7: the header has no `face` element"),
    ];
    for (input, expected) in &cases {
        let err = io::read_ply_from(input.as_bytes(), "m.ply").unwrap_err();
        assert_eq!(err.to_string(), *expected, "{input:?}");
    }
    // Binary records read by the loops of the common layouts (`x y z` of one float type,
    // little-endian; a `uchar` count of `int` or `uint` corners): the same errors.
    for (ty, size) in [("float", 4), ("double", 8)] {
        for (coordinate, name) in ["x", "y", "z"].iter().enumerate() {
            for (bad, text) in [(f64::NAN, "NaN"), (f64::NEG_INFINITY, "-inf")] {
                let mut data = Vec::new();
                for k in 0..3 * 3 {
                    let value = if k == 3 + coordinate {
                        bad
                    } else {
                        (k % 2) as f64
                    };
                    match size {
                        4 => data.extend((value as f32).to_le_bytes()),
                        _ => data.extend(value.to_le_bytes()),
                    }
                }
                let head = v.replace("float", ty);
                let file = [
                    format!("ply\nformat binary_little_endian 1.0\n{head}{f}end_header\n")
                        .into_bytes(),
                    data,
                ]
                .concat();
                let err = io::read_ply_from(&file[..], "m.ply").unwrap_err();
                assert_eq!(
                    err.to_string(),
                    format!(
                        "m.ply: vertex 1, property `{name}`: coordinate `{text}` is not finite"
                    ),
                    "{ty}"
                );
            }
        }
    }
    for (ty, index, message) in [
        ("int", -1i64, "vertex index -1"),
        ("uint", 3, "vertex index 3"),
        ("uint", 1 << 31, "vertex index 2147483648"),
    ] {
        let mut data: Vec<u8> = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        // A good face first: the bad one is read on the loop whose corner list has room.
        for corners in [[0, 1, 2], [0, index, 1]] {
            data.push(3);
            for corner in corners {
                data.extend((corner as u32).to_le_bytes());
            }
        }
        let faces = f.replace("face 1", "face 2");
        let head = format!("{v}{}", faces.replace("uchar int", &format!("uchar {ty}")));
        let file = [
            format!("ply\nformat binary_little_endian 1.0\n{head}end_header\n").into_bytes(),
            data,
        ]
        .concat();
        let err = io::read_ply_from(&file[..], "m.ply").unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("m.ply: face 1: {message} is out of range (the file has 3 vertices)"),
            "{ty}"
        );
    }
    // Binary data cut short.
    let bytes = write(&shapes::cube(), &ObjWriteOptions::default());
    let cut = &bytes[..bytes.len() - 3];
    assert_eq!(
        io::read_ply_from(cut, "m.ply").unwrap_err().to_string(),
        "m.ply: face 5, property `vertex_indices`: the file ends early: the header declares 6 `face` elements"
    );
    let err = io::read_ply_from(cut, "m.ply").unwrap_err();
    let Error::PlyData {
        element,
        index,
        property,
        ..
    } = err
    else {
        panic!("{err}")
    };
    assert_eq!(
        (element.as_str(), index, property.as_deref()),
        ("face", 5, Some("vertex_indices"))
    );
}
