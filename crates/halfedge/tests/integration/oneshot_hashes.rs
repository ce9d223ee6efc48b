//! The one-shot subdivision's output, hashed to the bit for every rule at levels 1 to 3 on
//! closed, boundary and mixed meshes: positions (their `f64` bits), every half-edge array of
//! the returned [`HalfEdgeMesh`] (so its half-edge numbering), and the face list of
//! [`subdivide_to_face_list`] (face order, corner order, positions). The expected hashes were
//! computed on the one-shot code before it became a wrapper over the refinement; a change in
//! any bit of any output changes them. Through the public API only (a test of what users get).

use halfedge::glam::DVec3;
use halfedge::subdivide::{subdivide, subdivide_to_face_list, FaceListLevel, SubdivideOptions};
use halfedge::{shapes, HalfEdgeMesh, PolygonMesh, Rule};

/// FNV-1a, 64 bits (stable across Rust versions, unlike `DefaultHasher`).
struct Fnv(u64);

impl Fnv {
    fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn u64(&mut self, x: u64) {
        self.bytes(&x.to_le_bytes());
    }
    fn u32s(&mut self, xs: &[u32]) {
        self.u64(xs.len() as u64);
        for &x in xs {
            self.bytes(&x.to_le_bytes());
        }
    }
    fn points(&mut self, ps: &[DVec3]) {
        self.u64(ps.len() as u64);
        for p in ps {
            for c in p.to_array() {
                self.u64(c.to_bits());
            }
        }
    }
}

/// The positions and the six half-edge arrays of `m` (read through its accessors: a
/// boundary half-edge's face is `u32::MAX`, as the arrays hold it).
fn hash_mesh(h: &mut Fnv, m: &HalfEdgeMesh) {
    h.points(m.positions());
    let vertex_halfedge: Vec<u32> = m.vertices().map(|v| m.vertex_halfedge(v).0).collect();
    let halfedge_vertex: Vec<u32> = m.halfedges().map(|e| m.to_vertex(e).0).collect();
    let halfedge_face: Vec<u32> = m
        .halfedges()
        .map(|e| m.face(e).map_or(u32::MAX, |f| f.0))
        .collect();
    let halfedge_next: Vec<u32> = m.halfedges().map(|e| m.next(e).0).collect();
    let halfedge_prev: Vec<u32> = m.halfedges().map(|e| m.prev(e).0).collect();
    let face_halfedge: Vec<u32> = m.faces().map(|f| m.face_halfedge(f).0).collect();
    for a in [
        &vertex_halfedge,
        &halfedge_vertex,
        &halfedge_face,
        &halfedge_next,
        &halfedge_prev,
        &face_halfedge,
    ] {
        h.u32s(a);
    }
}

fn hash_faces(h: &mut Fnv, level: &FaceListLevel) {
    h.points(&level.mesh.positions);
    h.u64(level.edges as u64);
    h.u64(level.mesh.face_offsets().len() as u64);
    for &o in level.mesh.face_offsets() {
        h.u64(o as u64);
    }
    h.u32s(level.mesh.face_indices());
}

const RULES: [Rule; 11] = [
    Rule::Loop,
    Rule::Midpoint,
    Rule::Icosphere,
    Rule::Butterfly,
    Rule::TriSplit(2),
    Rule::TriSplit(3),
    Rule::CatmullClark,
    Rule::Sqrt3,
    Rule::DooSabin,
    Rule::MidEdge,
    Rule::TriSplit(4),
];

fn meshes() -> Vec<(&'static str, HalfEdgeMesh)> {
    let he = |p: PolygonMesh| HalfEdgeMesh::try_from(&p).expect("a valid shape");
    vec![
        ("icosahedron", he(shapes::icosahedron())),
        ("cube", he(shapes::cube())),
        ("torus", he(shapes::torus(1).expect("a torus"))),
        ("grid", he(shapes::grid(3, 2).expect("a grid"))),
        (
            "quad_grid",
            he(shapes::quad_grid(2, 3).expect("a quad grid")),
        ),
        ("holes", he(shapes::icosahedron_holes(2).expect("holes"))),
        ("mixed", he(shapes::mixed())),
    ]
}

/// One hash per (mesh, rule): every level 1..=3, `subdivide` with preallocation on and off
/// and on 2 threads, and `subdivide_to_face_list`; an error is hashed by its message.
fn hashes() -> Vec<(String, u64)> {
    let mut out = Vec::new();
    for (name, mesh) in meshes() {
        for rule in RULES {
            let mut h = Fnv::new();
            for levels in 1..=3 {
                for opts in [
                    SubdivideOptions::default(),
                    SubdivideOptions::default().with_preallocate(false),
                    SubdivideOptions::default().with_threads(2),
                ] {
                    match subdivide(&mesh, rule, levels, &opts) {
                        Ok(m) => hash_mesh(&mut h, &m),
                        Err(e) => h.bytes(e.to_string().as_bytes()),
                    }
                    match subdivide_to_face_list(&mesh, rule, levels, &opts) {
                        Ok(level) => hash_faces(&mut h, &level),
                        Err(e) => h.bytes(e.to_string().as_bytes()),
                    }
                }
            }
            out.push((format!("{name} {rule}"), h.0));
        }
    }
    out
}

/// The hashes of the one-shot code before it became a wrapper over the refinement; Doo-Sabin
/// and mid-edge on the meshes with boundary (grid, quad_grid, holes, mixed) were refusals then
/// and are their boundary rules' output since.
const EXPECTED: &[(&str, u64)] = &[
    ("icosahedron loop", 0xcc408ad6e1ae3f6a),
    ("icosahedron midpoint", 0x4ff986cb7cd22d0a),
    ("icosahedron icosphere", 0xf869617cfae3b502),
    ("icosahedron butterfly", 0x14c1b05c1acf6dc2),
    ("icosahedron tri-split-2", 0xefb44498e1fec7e2),
    ("icosahedron tri-split-3", 0x1f4b568b2a4dc24b),
    ("icosahedron catmull-clark", 0xc4a9d052f8118788),
    ("icosahedron sqrt3", 0x27111f3a96693483),
    ("icosahedron doo-sabin", 0x1712db44a79a2198),
    ("icosahedron mid-edge", 0xda7279d4fa2ff046),
    ("icosahedron tri-split-4", 0xc0f50b189ebad1ae),
    ("cube loop", 0xb0ef41c6c107f349),
    ("cube midpoint", 0x130dbf6c7356588d),
    ("cube icosphere", 0xdc4749567abf5b4d),
    ("cube butterfly", 0x83107e4fb4d3d2eb),
    ("cube tri-split-2", 0x15a7637e632a7ab3),
    ("cube tri-split-3", 0x5b7feafd2194a289),
    ("cube catmull-clark", 0xf2753b3ac706c0c4),
    ("cube sqrt3", 0x78f886bfad2e8d0f),
    ("cube doo-sabin", 0xa0c07d8a0fac0ff1),
    ("cube mid-edge", 0xa4dc6fb76138b888),
    ("cube tri-split-4", 0x0bb89eda29e893d3),
    ("torus loop", 0x676107b12368f186),
    ("torus midpoint", 0xb8bcb37c8ffbbcbe),
    ("torus icosphere", 0x4628c9c1c5503ef6),
    ("torus butterfly", 0x25863a68529cb8de),
    ("torus tri-split-2", 0xb8bcb37c8ffbbcbe),
    ("torus tri-split-3", 0xecd118ae70c62801),
    ("torus catmull-clark", 0xb8cc00442d71d5a9),
    ("torus sqrt3", 0xb060583ace63e032),
    ("torus doo-sabin", 0x29594fd6c69e5fc0),
    ("torus mid-edge", 0x4b5cc9d6cb18dc67),
    ("torus tri-split-4", 0x3df3395462a9c8e4),
    ("grid loop", 0xf2bf7c1c81e73578),
    ("grid midpoint", 0x424f954ccf67ff9c),
    ("grid icosphere", 0x311e39fa124a5a7c),
    ("grid butterfly", 0x75448cb02a8a9eb4),
    ("grid tri-split-2", 0x424f954ccf67ff9c),
    ("grid tri-split-3", 0x517aa136c72ad887),
    ("grid catmull-clark", 0x64d47e09f1f9ba5c),
    ("grid sqrt3", 0x385f6a4e5ea7509d),
    ("grid doo-sabin", 0x72f55552589abb91),
    ("grid mid-edge", 0x4a04b95efed6c67b),
    ("grid tri-split-4", 0x23223c3ea7d59cad),
    ("quad_grid loop", 0xb0ef41c6c107f349),
    ("quad_grid midpoint", 0x130dbf6c7356588d),
    ("quad_grid icosphere", 0xdc4749567abf5b4d),
    ("quad_grid butterfly", 0x83107e4fb4d3d2eb),
    ("quad_grid tri-split-2", 0x15a7637e632a7ab3),
    ("quad_grid tri-split-3", 0x5b7feafd2194a289),
    ("quad_grid catmull-clark", 0xfa9327cfb479c180),
    ("quad_grid sqrt3", 0x78f886bfad2e8d0f),
    ("quad_grid doo-sabin", 0xcaf23f88c6f6cbd4),
    ("quad_grid mid-edge", 0x036d3815b5e6c7db),
    ("quad_grid tri-split-4", 0x0bb89eda29e893d3),
    ("holes loop", 0x0d932273f1189e65),
    ("holes midpoint", 0x1d30dc0f30ffb235),
    ("holes icosphere", 0x4dfb2c5c0196217d),
    ("holes butterfly", 0xaf221573b738abe5),
    ("holes tri-split-2", 0x7b55f1c822f4c98d),
    ("holes tri-split-3", 0x8015fb2a7ff0a3a7),
    ("holes catmull-clark", 0xbace4d2c95f4f34a),
    ("holes sqrt3", 0x4e0e37951de1465b),
    ("holes doo-sabin", 0x930b78f5e74a2348),
    ("holes mid-edge", 0x5a21692e3e104c05),
    ("holes tri-split-4", 0x5a8920d6e46055dd),
    ("mixed loop", 0x3f7556deb1231b25),
    ("mixed midpoint", 0x609e7af292604375),
    ("mixed icosphere", 0xcdf3dd4fc23c7105),
    ("mixed butterfly", 0xd9a0b89173d81f97),
    ("mixed tri-split-2", 0x0c61c373e616142f),
    ("mixed tri-split-3", 0x101f7fd00a5eb85d),
    ("mixed catmull-clark", 0x1c6e8f4bd9913f18),
    ("mixed sqrt3", 0x937fd42b1a84f17b),
    ("mixed doo-sabin", 0xf4ab622bcea32ac1),
    ("mixed mid-edge", 0x6890479f614a401f),
    ("mixed tri-split-4", 0xf31cdf1c5a16eb8f),
];

#[test]
fn one_shot_output_is_bit_identical_to_the_level_loop_it_replaced() {
    let got = hashes();
    for (k, v) in &got {
        println!("    (\"{k}\", {v:#018x}),");
    }
    let got: Vec<(&str, u64)> = got.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    assert_eq!(got, EXPECTED);
}
