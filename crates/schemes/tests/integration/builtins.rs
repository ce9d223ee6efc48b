//! Every built-in matrix checked on hand-counted small meshes at levels 1 and 2.

use num_bigint::BigInt;
use schemes::{builtin, builtins, Error, MeshCounts, Scheme};

use crate::meshes::*;

fn big(v: &[i64]) -> Vec<BigInt> {
    v.iter().map(|&x| BigInt::from(x)).collect()
}

/// Asserts the state and `[V, E, F]` of `mesh` under `scheme` at `level`.
fn check(scheme: &str, mesh: &MeshCounts, level: u64, state: &[i64], vef: [i64; 3]) {
    let s = builtin(scheme).unwrap();
    let c = s.counts_at(mesh, level).unwrap();
    assert_eq!(c.state, big(state), "{scheme} state at level {level}");
    assert_eq!(
        [c.vertices, c.edges, c.faces],
        [vef[0], vef[1], vef[2]].map(BigInt::from),
        "{scheme} V, E, F at level {level}"
    );
    // Powering and step-by-step multiplication agree.
    let x0 = s.initial_state(mesh).unwrap();
    let seq = s.states_up_to(&x0, level).unwrap();
    assert_eq!(seq[level as usize], c.state);
}

#[test]
fn loop_on_closed_triangle_meshes() {
    // Tetrahedron (4, 6, 4). Level 1: V = 4 + 6 = 10, E = 2*6 + 3*4 = 24, F = 16.
    // Level 2: V = 10 + 24 = 34, E = 48 + 48 = 96, F = 64.
    check("loop", &tetrahedron(), 1, &[10, 24], [10, 24, 16]);
    check("loop", &tetrahedron(), 2, &[34, 96], [34, 96, 64]);
    // Octahedron (6, 12, 8). Level 1: 18, 48, 32. Level 2: 66, 192, 128.
    check("loop", &octahedron(), 1, &[18, 48], [18, 48, 32]);
    check("loop", &octahedron(), 2, &[66, 192], [66, 192, 128]);
    // Icosahedron: 12, 42, 162, 642 vertices.
    check(
        "icosphere",
        &icosahedron(),
        3,
        &[642, 1920],
        [642, 1920, 1280],
    );
    // The general and boundary variants agree on closed meshes.
    check(
        "loop-general",
        &octahedron(),
        2,
        &[66, 192, 128],
        [66, 192, 128],
    );
    check(
        "loop-boundary",
        &octahedron(),
        2,
        &[66, 192, 0],
        [66, 192, 128],
    );
}

#[test]
fn loop_boundary_on_open_meshes() {
    // One triangle (V 3, IE 0, BE 3). Level 1: 6 vertices, the 3 inner edges are interior,
    // 6 boundary halves, 4 faces. Level 2: V = 6 + 3 + 6 = 15, IE = 4*3 + 6 = 18, BE = 12,
    // F = 16 (E = 30; Euler 15 - 30 + 16 = 1).
    check("loop-boundary", &triangle(), 1, &[6, 3, 6], [6, 9, 4]);
    check("loop-boundary", &triangle(), 2, &[15, 18, 12], [15, 30, 16]);
    // Triangle strip (V 6, IE 3, BE 6, F 4). Level 1: V = 15, IE = 12 + 6 = 18, BE = 12,
    // F = 16. Level 2: V = 15 + 30 = 45, IE = 72 + 12 = 84, BE = 24, F = 64.
    check(
        "loop-boundary",
        &triangle_strip(),
        1,
        &[15, 18, 12],
        [15, 30, 16],
    );
    check(
        "loop-boundary",
        &triangle_strip(),
        2,
        &[45, 84, 24],
        [45, 108, 64],
    );
    check(
        "loop-general",
        &triangle_strip(),
        2,
        &[45, 108, 64],
        [45, 108, 64],
    );
}

#[test]
fn loop_general_on_a_non_manifold_book() {
    // Three triangles on one edge: V 5, E 7, F 3. Level 1: V = 12; each page has 9 edges,
    // the two halves of the spine are shared by all three: E = 27 - 4 = 23 = 2*7 + 3*3;
    // F = 12. Level 2: V = 12 + 23 = 35, E = 46 + 36 = 82, F = 48.
    check("loop-general", &book(), 1, &[12, 23, 12], [12, 23, 12]);
    check("loop-general", &book(), 2, &[35, 82, 48], [35, 82, 48]);
    check("tri-split-2", &book(), 2, &[35, 82, 48], [35, 82, 48]);
}

#[test]
fn catmull_clark_on_quads_and_polygons() {
    // Cube (8, 12, 6). Level 1: V = 8 + 12 + 6 = 26, E = 24 + 24 = 48, F = 24.
    // Level 2: V = 26 + 48 + 24 = 98, E = 96 + 96 = 192, F = 96.
    check(
        "catmull-clark-quad",
        &cube(),
        1,
        &[26, 48, 24],
        [26, 48, 24],
    );
    check(
        "catmull-clark-quad",
        &cube(),
        2,
        &[98, 192, 96],
        [98, 192, 96],
    );
    check(
        "catmull-clark",
        &cube(),
        2,
        &[98, 192, 0, 96, 384],
        [98, 192, 96],
    );
    check(
        "catmull-clark-general",
        &cube(),
        2,
        &[98, 192, 96, 384],
        [98, 192, 96],
    );
    // One quad (4, IE 0, BE 4, F 1, H 4). Level 1: a 3x3 grid: V 9, IE 4, BE 8, F 4, H 16.
    // Level 2: a 5x5 grid: V 25, IE 24, BE 16, F 16 (E 40).
    check("catmull-clark", &quad(), 1, &[9, 4, 8, 4, 16], [9, 12, 4]);
    check(
        "catmull-clark",
        &quad(),
        2,
        &[25, 24, 16, 16, 64],
        [25, 40, 16],
    );
    check(
        "catmull-clark-quad",
        &quad(),
        2,
        &[25, 40, 16],
        [25, 40, 16],
    );
    // Quad strip (V 8, IE 2, BE 8, F 3). Level 1: a 7x3 grid: V 21, horizontal edges 6*3,
    // vertical 7*2: E 32 = IE 16 + BE 16, F 12. Level 2: a 13x5 grid: V 65,
    // E = 12*5 + 13*4 = 112 = IE 80 + BE 32, F 48.
    check(
        "catmull-clark",
        &quad_strip(),
        1,
        &[21, 16, 16, 12, 48],
        [21, 32, 12],
    );
    check(
        "catmull-clark",
        &quad_strip(),
        2,
        &[65, 80, 32, 48, 192],
        [65, 112, 48],
    );
    // One triangle under Catmull-Clark: 3 quads around the centre: V 7, IE 3, BE 6, F 3.
    // Level 2: V = 7 + 9 + 3 = 19, IE = 6 + 12 = 18, BE 12, F 12 (Euler 19 - 30 + 12 = 1).
    check(
        "catmull-clark",
        &triangle(),
        1,
        &[7, 3, 6, 3, 12],
        [7, 9, 3],
    );
    check(
        "catmull-clark",
        &triangle(),
        2,
        &[19, 18, 12, 12, 48],
        [19, 30, 12],
    );
    // Pentagon: 5 quads: V 11, IE 5, BE 10, F 5. Level 2: V = 11 + 15 + 5 = 31,
    // IE = 10 + 20 = 30, BE 20, F 20 (Euler 31 - 50 + 20 = 1).
    check(
        "catmull-clark",
        &pentagon(),
        1,
        &[11, 5, 10, 5, 20],
        [11, 15, 5],
    );
    check(
        "catmull-clark",
        &pentagon(),
        2,
        &[31, 30, 20, 20, 80],
        [31, 50, 20],
    );
    // Tetrahedron (triangles, closed): V 4 + 6 + 4 = 14, E 12 + 12 = 24, F 12.
    check(
        "catmull-clark",
        &tetrahedron(),
        1,
        &[14, 24, 0, 12, 48],
        [14, 24, 12],
    );
    // Book under the general variant: V 5 + 7 + 3 = 15, E = 14 + 9 = 23, F = 9, H 36.
    check(
        "catmull-clark-general",
        &book(),
        1,
        &[15, 23, 9, 36],
        [15, 23, 9],
    );
    // Mixed closed mesh (V 8, E 13, F 7, H 26): V 28, E 52, F 26 (Euler 2).
    check(
        "catmull-clark",
        &mixed_closed(),
        1,
        &[28, 52, 0, 26, 104],
        [28, 52, 26],
    );
}

#[test]
fn sqrt3_closed_and_with_boundary() {
    // Octahedron (6, 12, 8). Level 1: V 6 + 8 = 14, E 12 + 24 = 36, F 24.
    // Level 2: V 14 + 24 = 38, E 36 + 72 = 108, F 72 (Euler 2).
    check("sqrt3", &octahedron(), 1, &[14, 36, 24], [14, 36, 24]);
    check("sqrt3", &octahedron(), 2, &[38, 108, 72], [38, 108, 72]);
    check(
        "sqrt3-boundary",
        &octahedron(),
        2,
        &[38, 108, 0, 72],
        [38, 108, 72],
    );
    // One triangle. Step A: centre vertex, V 4, IE 3 spokes, BE 3, F 3.
    // Step B: each of the 3 boundary edges trisected (6 new vertices): V 10, F 9, BE 9,
    // IE = 3 + 9 - 3 = 9: the 1:9 triadic split of a triangle (10 vertices, 18 edges).
    check("sqrt3-boundary", &triangle(), 1, &[4, 3, 3, 3], [4, 6, 3]);
    check(
        "sqrt3-boundary",
        &triangle(),
        2,
        &[10, 9, 9, 9],
        [10, 18, 9],
    );
    // Levels 3 and 4 give the 1:81 split: (9+1)(9+2)/2 = 55 vertices, 3*9*10/2 = 135 edges.
    check(
        "sqrt3-boundary",
        &triangle(),
        3,
        &[19, 36, 9, 27],
        [19, 45, 27],
    );
    check(
        "sqrt3-boundary",
        &triangle(),
        4,
        &[55, 108, 27, 81],
        [55, 135, 81],
    );
    // Triangle strip (V 6, IE 3, BE 6, F 4). Step A: V 10, IE 15, BE 6, F 12.
    // Step B: V 10 + 6 + 12 = 28, IE 15 - 6 + 36 = 45, BE 18, F 36 (Euler 28 - 63 + 36 = 1).
    check(
        "sqrt3-boundary",
        &triangle_strip(),
        1,
        &[10, 15, 6, 12],
        [10, 21, 12],
    );
    check(
        "sqrt3-boundary",
        &triangle_strip(),
        2,
        &[28, 45, 18, 36],
        [28, 63, 36],
    );
}

#[test]
fn doo_sabin_and_mid_edge_on_the_cube() {
    // Doo-Sabin on the cube: 24 corners -> V 24, each vertex of degree 4 -> E 48,
    // F = 6 + 12 + 8 = 26. Level 2: V 96, E 192, F = 26 + 48 + 24 = 98.
    check("doo-sabin", &cube(), 1, &[24, 48, 26], [24, 48, 26]);
    check("doo-sabin", &cube(), 2, &[96, 192, 98], [96, 192, 98]);
    // Tetrahedron: V 12 (corners), E 24, F = 4 + 6 + 4 = 14 (truncated-like, Euler 2).
    check("doo-sabin", &tetrahedron(), 1, &[12, 24, 14], [12, 24, 14]);
    // Mid-edge on the cube: the cuboctahedron (12, 24, 14), then (24, 48, 26).
    check("mid-edge", &cube(), 1, &[12, 24, 14], [12, 24, 14]);
    check("mid-edge", &cube(), 2, &[24, 48, 26], [24, 48, 26]);
    // Tetrahedron: the octahedron (6, 12, 8).
    check("mid-edge", &tetrahedron(), 1, &[6, 12, 8], [6, 12, 8]);
}

#[test]
fn doo_sabin_and_mid_edge_with_boundary() {
    // One quad under Doo-Sabin: 4 corners + 8 Chaikin points; edges 4 + 4 * 3 + 4;
    // faces: the quad, 4 boundary quads, 4 corner triangles. State (V, IE, BE, F).
    check(
        "doo-sabin-boundary",
        &quad(),
        1,
        &[12, 12, 8, 9],
        [12, 20, 9],
    );
    // The strip of three quads (V 8, IE 2, BE 8, F 3): V' = 2*2 + 3*8, F' = 3 + 10 + 8.
    check(
        "doo-sabin-boundary",
        &quad_strip(),
        1,
        &[28, 32, 16, 21],
        [28, 48, 21],
    );
    // Mid-edge on one quad: 4 midpoints + 4 kept corners; the midpoint quad and 4 triangles.
    check("mid-edge-boundary", &quad(), 1, &[8, 4, 8, 5], [8, 12, 5]);
    check(
        "mid-edge-boundary",
        &quad(),
        2,
        &[20, 16, 16, 13],
        [20, 32, 13],
    );
    // `doo-sabin` and `mid-edge` count as their twins on a boundary, keep their state closed.
    for (name, twin) in [
        ("doo-sabin", "doo-sabin-boundary"),
        ("mid-edge", "mid-edge-boundary"),
    ] {
        let s = builtin(name).unwrap();
        assert_eq!(s.for_mesh(&quad_strip()).canonical_name(), twin);
        assert_eq!(s.for_mesh(&quad_strip()).name(), name);
        assert_eq!(s.for_mesh(&cube()).canonical_name(), name);
        assert_eq!(s.for_mesh(&cube()).state_names(), ["V", "E", "F"]);
        let typed = |t: &str| {
            s.for_counts(&t.parse().unwrap())
                .canonical_name()
                .to_owned()
        };
        assert_eq!(typed("V=8,IE=2,BE=8,F=3"), twin);
        assert_eq!(typed("V=8,E=10,F=3"), name);
        assert_eq!(typed("V=8,E=12,F=6"), name);
    }
}

#[test]
fn tri_split_on_the_icosahedron() {
    // Paper ref. [12]: 10 N^2 + 2 vertices after one step.
    for n in 2..=12u64 {
        let s = builtin(&format!("tri-split-{n}")).unwrap();
        let c = s.counts_at(&icosahedron(), 1).unwrap();
        let n = i64::try_from(n).unwrap();
        assert_eq!(c.vertices, BigInt::from(10 * n * n + 2));
        assert_eq!(c.edges, BigInt::from(30 * n * n));
        assert_eq!(c.faces, BigInt::from(20 * n * n));
    }
    // Ternary on one triangle: 1:9 split, then 1:81.
    check("ternary", &triangle(), 1, &[10, 18, 9], [10, 18, 9]);
    check("ternary", &triangle(), 2, &[55, 135, 81], [55, 135, 81]);
}

#[test]
fn names_aliases_and_unknown_names() {
    for alias in ["midpoint", "butterfly", "icosphere"] {
        let s = builtin(alias).unwrap();
        assert_eq!(s.name(), alias);
        assert_eq!(s.canonical_name(), "loop");
        assert_eq!(s.topology(), "loop");
        assert_eq!(s.matrix(), builtin("loop").unwrap().matrix());
    }
    assert_eq!(builtin("ternary").unwrap().canonical_name(), "tri-split-3");
    let err = builtin("catmul-clark").unwrap_err();
    assert!(matches!(err, Error::UnknownScheme { .. }));
    assert_eq!(
        err.to_string(),
        "unknown scheme `catmul-clark`; built-in schemes: loop, loop-boundary, loop-general, \
         catmull-clark-quad, catmull-clark, catmull-clark-general, sqrt3, sqrt3-boundary, \
         doo-sabin, doo-sabin-boundary, mid-edge, mid-edge-boundary, tri-split-N (N >= 2); aliases: midpoint, butterfly, icosphere, ternary"
    );
    assert_eq!(
        builtin("tri-split-1").unwrap_err().to_string(),
        "`tri-split-1`: the split factor N must be at least 2"
    );
    assert!(matches!(
        builtin("tri-split-x"),
        Err(Error::InvalidSplitFactor { .. })
    ));
    assert!(matches!(
        builtin("tri-split-99999999999999999999999"),
        Err(Error::InvalidSplitFactor { .. })
    ));
    assert!(matches!(
        builtin("tri-split-4000000000"),
        Err(Error::InvalidSplitFactor { .. })
    ));
    let names: Vec<String> = builtins().iter().map(|s| s.name().to_string()).collect();
    assert_eq!(
        names,
        [
            "loop",
            "loop-boundary",
            "loop-general",
            "catmull-clark-quad",
            "catmull-clark",
            "catmull-clark-general",
            "sqrt3",
            "sqrt3-boundary",
            "doo-sabin",
            "doo-sabin-boundary",
            "mid-edge",
            "mid-edge-boundary",
            "tri-split-2",
            "tri-split-3"
        ]
    );
}

#[test]
fn states_are_exactly_as_specified() {
    let state = |n: &str| builtin(n).unwrap().state_names().join(",");
    assert_eq!(state("loop"), "V,E");
    assert_eq!(state("loop-boundary"), "V,IE,BE");
    assert_eq!(state("loop-general"), "V,E,F");
    assert_eq!(state("catmull-clark-quad"), "V,E,F");
    assert_eq!(state("catmull-clark"), "V,IE,BE,F,H");
    assert_eq!(state("catmull-clark-general"), "V,E,F,H");
    assert_eq!(state("sqrt3"), "V,E,F");
    assert_eq!(state("sqrt3-boundary"), "V,IE,BE,F");
    assert_eq!(state("doo-sabin"), "V,E,F");
    assert_eq!(state("mid-edge"), "V,E,F");
    assert_eq!(state("tri-split-5"), "V,E,F");
    let derived = |n: &str| builtin(n).unwrap().derived();
    assert_eq!(derived("loop"), [("F", "2E/3".to_string())]);
    assert_eq!(
        derived("loop-boundary"),
        [
            ("E", "IE + BE".to_string()),
            ("F", "(2IE + BE)/3".to_string())
        ]
    );
    assert!(builtins().iter().all(Scheme::has_mesh_counts));
}

#[test]
fn refusals_say_why_and_what_to_use() {
    let refuse = |scheme: &str, mesh: &MeshCounts| {
        builtin(scheme)
            .unwrap()
            .initial_state(mesh)
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        refuse("loop", &cube()),
        "loop needs a triangle mesh, but this mesh has 6 faces of degree 4; use catmull-clark"
    );
    assert_eq!(
        refuse("loop", &mixed_closed()),
        "loop needs a triangle mesh, but this mesh has 5 faces of degree 4; use catmull-clark"
    );
    assert_eq!(
        refuse("loop", &triangle_strip()),
        "loop needs a closed mesh, but this mesh has 6 boundary edges; use loop-boundary"
    );
    assert_eq!(
        refuse("loop-boundary", &book()),
        "loop-boundary needs every edge to have one or two faces, but this mesh has 1 \
         non-manifold edge (three or more faces); use loop-general"
    );
    assert_eq!(
        refuse("sqrt3", &triangle()),
        "sqrt3 needs a closed mesh, but this mesh has 3 boundary edges; use sqrt3-boundary"
    );
    assert_eq!(
        refuse("catmull-clark", &book()),
        "catmull-clark needs every edge to have one or two faces, but this mesh has 1 \
         non-manifold edge (three or more faces); use catmull-clark-general"
    );
    assert_eq!(
        refuse("catmull-clark-quad", &pentagon()),
        "catmull-clark-quad needs a quad mesh, but this mesh has 1 face of degree 5; use catmull-clark"
    );
    assert_eq!(
        refuse("doo-sabin", &quad()),
        "doo-sabin needs a closed mesh, but this mesh has 4 boundary edges; use doo-sabin-boundary"
    );
    assert_eq!(
        refuse("loop-general", &book().clone().tap_quads()),
        "loop-general needs a triangle mesh, but this mesh has 3 faces of degree 4; use catmull-clark-general"
    );
    // Hand-built counts without faces_by_degree: triangles are recognised by H = 3F.
    let by_hand = MeshCounts {
        vertices: 12,
        edges: 30,
        interior_edges: 30,
        faces: 20,
        corners: 60,
        ..MeshCounts::default()
    };
    assert!(builtin("loop").unwrap().initial_state(&by_hand).is_ok());
    let quads_by_hand = MeshCounts {
        corners: 80,
        ..by_hand
    };
    assert!(refuse("loop", &quads_by_hand).contains("the face degrees are not known"));
}

trait TapQuads {
    fn tap_quads(self) -> MeshCounts;
}

impl TapQuads for MeshCounts {
    /// The same counts with every face declared a quad (for refusal tests only).
    fn tap_quads(mut self) -> MeshCounts {
        self.faces_by_degree.clear();
        self.faces_by_degree.insert(4, self.faces);
        self
    }
}

#[test]
fn identities_hold_along_the_recurrences() {
    use num_traits::Zero;
    // loop-boundary: 3F = 2IE + BE at every level (F integral), Euler characteristic kept.
    let lb = builtin("loop-boundary").unwrap();
    let x0 = lb.initial_state(&triangle_strip()).unwrap();
    for x in lb.states_up_to(&x0, 12).unwrap() {
        let [v, e, f] = lb.vef(&x).unwrap();
        assert_eq!(BigInt::from(3) * &f, BigInt::from(2) * &x[1] + &x[2]);
        assert_eq!(v - e + f, BigInt::from(1));
    }
    // catmull-clark: H = 2IE + BE at every level; all quads from level 1 (H = 4F).
    let cc = builtin("catmull-clark").unwrap();
    let x0 = cc.initial_state(&pentagon()).unwrap();
    for (s, x) in cc.states_up_to(&x0, 12).unwrap().into_iter().enumerate() {
        assert_eq!(x[4], BigInt::from(2) * &x[1] + &x[2]);
        if s >= 1 {
            assert_eq!(x[4], BigInt::from(4) * &x[3]);
        }
        let [v, e, f] = cc.vef(&x).unwrap();
        assert_eq!(v - e + f, BigInt::from(1));
    }
    // sqrt3-boundary: 3F = 2IE + BE at every level and Euler characteristic kept.
    let sb = builtin("sqrt3-boundary").unwrap();
    let x0 = sb.initial_state(&triangle_strip()).unwrap();
    for (s, x) in sb.states_up_to(&x0, 13).unwrap().into_iter().enumerate() {
        assert_eq!(BigInt::from(3) * &x[3], BigInt::from(2) * &x[1] + &x[2]);
        let [v, e, f] = sb.vef(&x).unwrap();
        assert_eq!(v - e + f, BigInt::from(1));
        // Powering agrees with stepping for every residue.
        assert_eq!(sb.state_at(&x0, s as u64).unwrap(), x);
    }
    // The dual schemes with boundary keep V - E + F = 1 on a strip, and BE doubles.
    for name in ["doo-sabin-boundary", "mid-edge-boundary"] {
        let s = builtin(name).unwrap();
        let x0 = s.initial_state(&quad_strip()).unwrap();
        for (k, x) in s.states_up_to(&x0, 10).unwrap().into_iter().enumerate() {
            let [v, e, f] = s.vef(&x).unwrap();
            assert_eq!(v - e + f, BigInt::from(1), "{name}");
            assert_eq!(x[2], BigInt::from(8) << k, "{name}");
        }
    }
    // Closed schemes keep V - E + F = 2 on the cube / octahedron.
    for (name, mesh) in [
        ("doo-sabin", cube()),
        ("mid-edge", cube()),
        ("sqrt3", octahedron()),
        ("loop", octahedron()),
        ("catmull-clark-quad", cube()),
    ] {
        let s = builtin(name).unwrap();
        let x0 = s.initial_state(&mesh).unwrap();
        for x in s.states_up_to(&x0, 10).unwrap() {
            let [v, e, f] = s.vef(&x).unwrap();
            assert_eq!(v - e + f, BigInt::from(2), "{name}");
        }
    }
    // A state that no closed triangle mesh has: F = 2E/3 is not an integer.
    let l = builtin("loop").unwrap();
    let err = l.vef(&big(&[12, 31])).unwrap_err();
    assert_eq!(
        err.to_string(),
        "F = 2E/3 = 62/3 is not an integer for this state of loop"
    );
    assert!(matches!(
        l.state_at(&big(&[1, 2, 3]), 1),
        Err(Error::InitialLength {
            got: 3,
            expected: 2,
            ..
        })
    ));
    assert!(l
        .state_at(&big(&[0, 0]), 1000)
        .unwrap()
        .iter()
        .all(Zero::is_zero));
}

/// Checks `valid_from` as documented: with `q` the characteristic polynomial without its
/// factor `x^m`, component `i` satisfies the recurrence `q` from level `valid_from` on, but
/// not from one level earlier (for a generic initial state).
#[test]
fn valid_from_as_documented() {
    // (scheme, q coefficients from the constant term up, valid_from per component, mesh)
    let cases: [(&str, Vec<i64>, Vec<u64>, MeshCounts); 6] = [
        // cc: char poly x (x-1) (x-2)^2 (x-4); q = (x-1)(x-2)^2(x-4) = x^4 - 9x^3 + 28x^2 - 36x + 16.
        (
            "catmull-clark",
            vec![16, -36, 28, -9, 1],
            vec![1, 0, 0, 1, 0],
            pentagon(),
        ),
        (
            "catmull-clark-general",
            vec![-8, 14, -7, 1],
            vec![1, 0, 1, 0],
            pentagon(),
        ),
        // doo-sabin, mid-edge: x (x-4)(x-1), x (x-2)(x-1).
        ("doo-sabin", vec![4, -5, 1], vec![1, 0, 1], mixed_closed()),
        ("mid-edge", vec![2, -3, 1], vec![1, 0, 1], mixed_closed()),
        // doo-sabin-boundary: x (x-4)(x-2)(x-1); mid-edge-boundary: x (x-2)^2 (x-1).
        (
            "doo-sabin-boundary",
            vec![-8, 14, -7, 1],
            vec![1, 0, 0, 1],
            quad_strip(),
        ),
        (
            "mid-edge-boundary",
            vec![-4, 8, -5, 1],
            vec![1, 0, 0, 1],
            quad_strip(),
        ),
    ];
    for (name, q, valid_from, mesh) in cases {
        let s = builtin(name).unwrap();
        let x0 = s.initial_state(&mesh).unwrap();
        let xs = s.states_up_to(&x0, 12).unwrap();
        let holds_from = |i: usize, k: usize| {
            (k..xs.len() - q.len() + 1).all(|t| {
                let sum: BigInt = q
                    .iter()
                    .enumerate()
                    .map(|(j, c)| BigInt::from(*c) * &xs[t + j][i])
                    .sum();
                sum == BigInt::from(0)
            })
        };
        for (i, &k) in valid_from.iter().enumerate() {
            assert!(holds_from(i, k as usize), "{name} component {i} from {k}");
            if k > 0 {
                assert!(
                    !holds_from(i, k as usize - 1),
                    "{name} component {i} from {}",
                    k - 1
                );
            }
        }
    }
}

/// The exact closed forms (from the `recurrence` crate) agree with powering for every phase
/// of every built-in, and their `valid_from` levels are the documented ones.
#[test]
fn closed_forms_agree_and_valid_from_is_as_documented() {
    let documented: [(&str, &[u64]); 14] = [
        ("loop", &[0, 0]),
        ("loop-boundary", &[0, 0, 0]),
        ("loop-general", &[0, 0, 0]),
        ("catmull-clark-quad", &[0, 0, 0]),
        ("catmull-clark", &[1, 0, 0, 1, 0]),
        ("catmull-clark-general", &[1, 0, 1, 0]),
        ("sqrt3", &[0, 0, 0]),
        ("sqrt3-boundary", &[0, 0, 0, 0]),
        ("doo-sabin", &[1, 0, 1]),
        ("doo-sabin-boundary", &[1, 0, 0, 1]),
        ("mid-edge", &[1, 0, 1]),
        ("mid-edge-boundary", &[1, 0, 0, 1]),
        ("tri-split-2", &[0, 0, 0]),
        ("tri-split-3", &[0, 0, 0]),
    ];
    for (scheme, (name, valid_from)) in builtins().iter().zip(documented) {
        assert_eq!(scheme.name(), name);
        // A state with no special relation between components, to expose every term.
        let x0: Vec<BigInt> = (0..scheme.dim())
            .map(|i| BigInt::from(7 + 5 * i * i))
            .collect();
        for phase in scheme.phases() {
            let form = phase.closed_form();
            let got: Vec<u64> = form.components().iter().map(|c| c.valid_from).collect();
            assert_eq!(got, valid_from, "{name} {}", phase.description);
            let start = scheme.state_at(&x0, phase.first_level).unwrap();
            for t in 0..30u64 {
                let s = phase.first_level + phase.period * t;
                assert_eq!(
                    form.evaluate(&start, t).unwrap(),
                    scheme.state_at(&x0, s).unwrap(),
                    "{name} at level {s}"
                );
            }
        }
    }
}
