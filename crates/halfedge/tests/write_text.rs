//! The OBJ and PLY writers against references written the plain way (OBJ: std's `{:?}` line
//! by line, what the writers wrote before they formatted in parallel chunks; PLY: each value's
//! `to_le_bytes`), on one thread, two and rayon's pool: the same bytes every time. The mesh
//! has every kind of line (colors, UVs with seams, normals, groups changing every few faces,
//! triangles among quads) and sections long enough for several windows of chunks, with
//! coordinates of every magnitude (exponential forms, ties of `f32` digits, zeros).

use std::fmt::Write as _;

use halfedge::glam::{DVec2, DVec3};
use halfedge::groups::{FaceGroups, Statement};
use halfedge::io::{
    write_mesh_buffers_obj, write_mesh_buffers_ply, write_obj_with, write_polygon_obj_with,
    write_polygon_ply, FaceBuffers, MeshBuffers, ObjWriteOptions, UvBuffers,
};
use halfedge::normals::{limit_normal, vertex_normals, vertex_normals_by};
use halfedge::uv::Uvs;
use halfedge::{HalfEdgeMesh, PolygonMesh};

/// Quads per side of the grid: 90,601 vertices, enough for two windows on two threads.
const SIDE: u32 = 300;

/// A seeded xorshift generator of bits and of values of every kind.
struct Random(u64);

impl Random {
    fn bits(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.bits() % n
    }

    /// Mostly coordinates near 1 to 100, with tiny, huge, short (tying) values and zeros.
    fn value(&mut self) -> f64 {
        let b = self.bits();
        match b % 16 {
            0 => 0.0,
            1 => -0.0,
            2 => f64::from((b >> 20) as u16) / 64.0 - 512.0,
            3 => f64::from((b >> 20) as u32) * 1e-12,
            4 => f64::from((b >> 20) as u32) * 1e9,
            5 => f64::from((b >> 24) as u16) / 16.0 + 30_000.0,
            _ => (b >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0,
        }
    }
}

/// A grid of quads (a few split into triangles) with colors, seamed UVs and groups.
fn mesh() -> PolygonMesh {
    let mut random = Random(0x2545_f491_4f6c_dd1d);
    let n = SIDE + 1;
    let positions = (0..n * n)
        .map(|i| {
            let (x, y) = (f64::from(i % n), f64::from(i / n));
            match random.below(4) {
                0 => DVec3::new(random.value(), random.value(), random.value()),
                _ => DVec3::new(x * 0.37, y * 0.37, random.value() * 1e-3),
            }
        })
        .collect();
    let mut mesh = PolygonMesh::with_positions(positions);
    let mut faces = 0;
    for y in 0..SIDE {
        for x in 0..SIDE {
            let v = y * n + x;
            if random.below(7) == 0 {
                mesh.push_face(&[v, v + 1, v + n + 1]);
                mesh.push_face(&[v, v + n + 1, v + n]);
                faces += 2;
            } else {
                mesh.push_face(&[v, v + 1, v + n + 1, v + n]);
                faces += 1;
            }
        }
    }
    let coords: Vec<DVec2> = (0..2 * n * n)
        .map(|_| DVec2::new(random.value(), random.value()))
        .collect();
    let corners = mesh
        .face_indices()
        .iter()
        .map(|&v| v + n * n * random.below(2) as u32)
        .collect();
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("a value per corner");
    let colors = (0..n * n)
        .map(|_| [0, 1, 2].map(|_| random.below(256) as f64 / 255.0))
        .collect();
    mesh.set_colors(Some(colors)).expect("a color per vertex");
    let mut groups = FaceGroups::new(vec!["mtllib grid.mtl".into(), "mtllib more.mtl".into()]);
    let names = ["a", "b", "c"];
    let mut values = [None; 4];
    for f in 0..faces {
        if f % 3 == 0 {
            let k = random.below(4) as usize;
            values[k] = match random.below(4) {
                0 => None,
                i => Some(names[i as usize - 1]),
            };
        }
        groups.push_face(values);
    }
    mesh.set_groups(Some(groups)).expect("a class per face");
    mesh
}

/// The statement lines before face `f`, written the plain way.
fn reference_statements(out: &mut String, groups: &FaceGroups, f: usize) {
    for statement in Statement::ALL {
        let now = groups.value_index(f, statement);
        let changed = match f {
            0 => now.is_some(),
            _ => groups.value_index(f - 1, statement) != now,
        };
        if changed {
            let value = groups.value(f, statement).unwrap_or(statement.unset());
            match value.is_empty() {
                true => writeln!(out, "{}", statement.keyword()),
                false => writeln!(out, "{} {value}", statement.keyword()),
            }
            .expect("a String");
        }
    }
}

/// What the OBJ writers write, line by line with `{:?}`: positions (with colors), `vt`,
/// `vn`, statements and faces. `T` is `f32` or `f64`, given as a conversion.
fn reference_obj<T: std::fmt::Debug>(
    convert: impl Fn(f64) -> T,
    mesh: &PolygonMesh,
    uvs: bool,
    normals: Option<&[DVec3]>,
    groups: bool,
) -> String {
    let mut out = String::new();
    let groups = mesh.groups().filter(|_| groups);
    for line in groups.map_or(&[][..], |g| g.mtllib()) {
        writeln!(out, "{line}").expect("a String");
    }
    let colors = mesh.colors();
    for (i, p) in mesh.positions.iter().enumerate() {
        let [x, y, z] = p.to_array().map(&convert);
        write!(out, "v {x:?} {y:?} {z:?}").expect("a String");
        if let Some(colors) = colors {
            let [r, g, b] = colors[i].map(&convert);
            write!(out, " {r:?} {g:?} {b:?}").expect("a String");
        }
        out.push('\n');
    }
    let uvs = mesh.uvs().filter(|_| uvs);
    for c in uvs.map_or(&[][..], |u| u.coords()) {
        writeln!(out, "vt {:?} {:?}", convert(c.x), convert(c.y)).expect("a String");
    }
    for n in normals.unwrap_or(&[]) {
        let [x, y, z] = n.to_array().map(&convert);
        writeln!(out, "vn {x:?} {y:?} {z:?}").expect("a String");
    }
    let mut corner = 0;
    for f in 0..mesh.n_faces() {
        if let Some(groups) = groups {
            reference_statements(&mut out, groups, f);
        }
        out.push('f');
        for &v in mesh.face(f) {
            let v = u64::from(v) + 1;
            match (uvs.map(|u| u64::from(u.corners()[corner]) + 1), normals) {
                (None, None) => write!(out, " {v}"),
                (None, Some(_)) => write!(out, " {v}//{v}"),
                (Some(t), None) => write!(out, " {v}/{t}"),
                (Some(t), Some(_)) => write!(out, " {v}/{t}/{v}"),
            }
            .expect("a String");
            corner += 1;
        }
        out.push('\n');
    }
    out
}

/// `write` on one thread, two and rayon's pool, each the same bytes, returned.
fn on_every_thread_count(
    write: impl Fn(&mut Vec<u8>, &ObjWriteOptions) -> std::io::Result<()>,
    options: ObjWriteOptions,
) -> Vec<u8> {
    let mut one = Vec::new();
    write(&mut one, &options.with_threads(1)).expect("written");
    for threads in [2, 0] {
        let mut out = Vec::new();
        write(&mut out, &options.with_threads(threads)).expect("written");
        assert!(out == one, "{threads} threads wrote other bytes");
    }
    one
}

#[test]
fn obj_text_is_std_debug_text_on_every_thread_count() {
    let mesh = mesh();
    let area = vertex_normals(&mesh.positions, mesh.faces());
    for (uvs, normals) in [(true, false), (false, false), (true, true), (false, true)] {
        let options = ObjWriteOptions::default()
            .with_uvs(uvs)
            .with_normals(normals);
        let written = on_every_thread_count(
            |out, options| write_polygon_obj_with(&mesh, out, options),
            options,
        );
        let expected = reference_obj(|x| x, &mesh, uvs, normals.then_some(&area[..]), true);
        assert!(
            String::from_utf8(written).expect("text") == expected,
            "uvs {uvs}, normals {normals}"
        );
    }
    // The half-edge writer: positions, normals and faces only.
    let mut plain = mesh.clone();
    plain.set_uvs(None).expect("no UVs");
    plain.set_colors(None).expect("no colors");
    let half_edge = HalfEdgeMesh::try_from(&plain).expect("a manifold grid");
    let options = ObjWriteOptions::default().with_normals(true);
    let written = on_every_thread_count(
        |out, options| write_obj_with(&half_edge, out, options),
        options,
    );
    let faces = half_edge.to_polygon_mesh();
    let area = vertex_normals(&faces.positions, faces.faces());
    let expected = reference_obj(|x| x, &faces, false, Some(&area), false);
    assert!(String::from_utf8(written).expect("text") == expected);
}

/// The mesh in `f32` buffers, with limit tangents for the normals.
struct Buffers32 {
    positions: Vec<[f32; 3]>,
    offsets: Vec<u32>,
    values: Vec<[f32; 2]>,
    colors: Vec<[f32; 3]>,
    tangents: (Vec<[f32; 3]>, Vec<[f32; 3]>),
}

impl Buffers32 {
    /// `source` with its positions and texture coordinates these `f32` values, widened
    /// (exactly).
    fn widened(&self, source: &PolygonMesh) -> PolygonMesh {
        let mut widened = source.clone();
        widened.positions = (self.positions.iter())
            .map(|p| DVec3::from_array(p.map(f64::from)))
            .collect();
        let coords = (self.values.iter())
            .map(|v| DVec2::new(f64::from(v[0]), f64::from(v[1])))
            .collect();
        let corners = source.uvs().expect("UVs").corners().to_vec();
        widened
            .set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
            .expect("a value per corner");
        widened
    }

    fn new(mesh: &PolygonMesh) -> Buffers32 {
        let f32s = |v: [f64; 3]| v.map(|x| x as f32);
        let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| f32s(p.to_array())).collect();
        let first = positions.iter().map(|p| [p[1], p[2], 1.0]).collect();
        let second = positions.iter().map(|p| [p[2], -1.0, p[0]]).collect();
        Buffers32 {
            offsets: mesh.face_offsets().iter().map(|&o| o as u32).collect(),
            values: (mesh.uvs().expect("UVs").coords().iter())
                .map(|c| [c.x as f32, c.y as f32])
                .collect(),
            colors: mesh
                .colors()
                .expect("colors")
                .iter()
                .map(|&c| f32s(c))
                .collect(),
            positions,
            tangents: (first, second),
        }
    }

    fn mesh<'a>(&'a self, source: &'a PolygonMesh) -> MeshBuffers<'a, f32> {
        let faces = FaceBuffers::Polygons {
            offsets: &self.offsets,
            indices: source.face_indices(),
        };
        let uvs = UvBuffers {
            values: &self.values,
            corners: source.uvs().expect("UVs").corners(),
        };
        MeshBuffers::new(&self.positions, faces)
            .with_uvs(uvs)
            .with_colors(&self.colors)
            .with_groups(source.groups().expect("groups"))
            .with_tangents(&self.tangents.0, &self.tangents.1)
    }
}

#[test]
fn f32_buffers_are_written_in_f32_on_every_thread_count() {
    let source = mesh();
    let buffers = Buffers32::new(&source);
    let mesh = buffers.mesh(&source);
    // The reference: the same mesh with the `f32` values widened (exactly).
    let mut widened = buffers.widened(&source);
    let colors = buffers.colors.iter().map(|c| c.map(f64::from)).collect();
    widened
        .set_colors(Some(colors))
        .expect("a color per vertex");
    let d = |x: &[f32; 3]| DVec3::from_array(x.map(f64::from));
    let area = vertex_normals_by(
        widened.n_vertices(),
        |v| widened.positions[v as usize],
        widened.faces(),
    );
    let limit: Vec<DVec3> = (area.iter().enumerate())
        .map(|(v, &n)| limit_normal(d(&buffers.tangents.0[v]), d(&buffers.tangents.1[v]), n))
        .collect();
    for (uvs, normals) in [(true, false), (false, true), (true, true)] {
        let options = ObjWriteOptions::default()
            .with_uvs(uvs)
            .with_normals(normals);
        let written = on_every_thread_count(
            |out, options| write_mesh_buffers_obj(&mesh, out, options),
            options,
        );
        let expected = reference_obj(
            |x| x as f32,
            &widened,
            uvs,
            normals.then_some(&limit[..]),
            true,
        );
        assert!(
            String::from_utf8(written).expect("text") == expected,
            "uvs {uvs}, normals {normals}"
        );
    }
}

/// The body of a binary PLY file the plain way: each vertex's values then each face's list,
/// every value by `to_le_bytes`; `T` as `f32` or `f64` bytes.
fn reference_ply_body(
    value: &dyn Fn(f64) -> Vec<u8>,
    mesh: &PolygonMesh,
    normals: Option<&[DVec3]>,
    texcoords: bool,
) -> Vec<u8> {
    let mut out = Vec::new();
    let colors = mesh.colors().expect("colors");
    for (v, p) in mesh.positions.iter().enumerate() {
        for x in p.to_array() {
            out.extend(value(x));
        }
        out.extend(colors[v].map(|c| (c * 255.0).round() as u8));
        for n in normals.map_or(&[][..], |n| &n[v..v + 1]) {
            for x in n.to_array() {
                out.extend(value(x));
            }
        }
    }
    let uvs = mesh.uvs().expect("UVs");
    for f in 0..mesh.n_faces() {
        let face = mesh.face(f);
        out.push(face.len() as u8);
        for &v in face {
            out.extend((v as i32).to_le_bytes());
        }
        if texcoords {
            out.push(2 * face.len() as u8);
            let first = mesh.face_offsets()[f];
            for &t in &uvs.corners()[first..first + face.len()] {
                let c = uvs.coords()[t as usize];
                out.extend(value(c.x));
                out.extend(value(c.y));
            }
        }
    }
    out
}

/// The bytes after the header.
fn body(ply: &[u8]) -> &[u8] {
    let end = b"end_header\n";
    let at = ply
        .windows(end.len())
        .position(|w| w == end)
        .expect("a header");
    &ply[at + end.len()..]
}

#[test]
fn ply_bytes_are_the_values_bytes_on_every_thread_count() {
    let mesh = mesh();
    let area = vertex_normals(&mesh.positions, mesh.faces());
    let f64_bytes = |x: f64| x.to_le_bytes().to_vec();
    for (uvs, normals) in [(true, false), (false, true)] {
        let options = ObjWriteOptions::default()
            .with_uvs(uvs)
            .with_normals(normals);
        let written = on_every_thread_count(
            |out, options| write_polygon_ply(&mesh, out, options),
            options,
        );
        let expected = reference_ply_body(&f64_bytes, &mesh, normals.then_some(&area[..]), uvs);
        assert!(body(&written) == expected, "uvs {uvs}, normals {normals}");
    }
    // `f32` buffers: positions and texture coordinates as `float`.
    let buffers = Buffers32::new(&mesh);
    let widened = buffers.widened(&mesh);
    let f32_bytes = |x: f64| (x as f32).to_le_bytes().to_vec();
    let written = on_every_thread_count(
        |out, options| write_mesh_buffers_ply(&buffers.mesh(&mesh), out, options),
        ObjWriteOptions::default(),
    );
    assert!(body(&written) == reference_ply_body(&f32_bytes, &widened, None, true));
}
