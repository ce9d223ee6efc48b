//! Real subdivision against the schemes' predictions, and the standard geometry.

use glam::DVec3;
mod named;

use halfedge::subdivide::{LevelReport, Rule, SubdivideOptions};
use halfedge::{shapes, Error, HalfEdgeMesh, PolygonMesh};
use named::{
    direct_face_degree, subdivide, subdivide_polygons, subdivide_to_face_list, verify,
    verify_polygons,
};

/// Every scheme name with a real subdivision (aliases included).
const SCHEMES: [&str; 19] = [
    "loop",
    "loop-boundary",
    "loop-general",
    "midpoint",
    "icosphere",
    "butterfly",
    "tri-split-2",
    "ternary",
    "tri-split-4",
    "catmull-clark",
    "catmull-clark-quad",
    "catmull-clark-general",
    "sqrt3",
    "sqrt3-boundary",
    "doo-sabin",
    "doo-sabin-boundary",
    "mid-edge",
    "mid-edge-boundary",
    "tri-split-5",
];

const BASES: [&str; 13] = [
    "tetrahedron",
    "octahedron",
    "icosahedron",
    "cube",
    "torus:1",
    "torus:2",
    "icosahedron-holes:1",
    "icosahedron-holes:2",
    "grid:3x2",
    "grid:1x1",
    "quad-grid:3x3",
    "quad-grid:1x2",
    "mixed",
];

fn base(name: &str) -> HalfEdgeMesh {
    let polygons = shapes::from_name(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    HalfEdgeMesh::try_from(&polygons).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn opts() -> SubdivideOptions<'static> {
    SubdivideOptions::default()
}

/// The number of levels to run so the last level stays small in debug builds.
fn levels_for(mesh_faces: usize, scheme: &str, max_levels: u32) -> u32 {
    let growth: usize = match scheme {
        "ternary" => 9,
        "tri-split-4" => 16,
        "tri-split-5" => 25,
        "doo-sabin" | "mid-edge" | "doo-sabin-boundary" | "mid-edge-boundary" => 4,
        _ => 4,
    };
    let mut faces = mesh_faces.max(1) * 4;
    let mut levels = 0;
    while levels < max_levels && faces * growth <= 400_000 {
        faces *= growth;
        levels += 1;
    }
    levels.max(1)
}

fn assert_reports(what: &str, reports: &[LevelReport]) {
    for r in reports {
        assert!(
            r.is_match(),
            "{what}: level {}: predicted {:?}, measured {:?}",
            r.level,
            r.predicted,
            r.measured
        );
    }
}

/// Whether the scheme's class admits the mesh (what `subdivide` must accept): `loop` and its
/// aliases count as `loop-boundary` on a mesh with boundary, `doo-sabin` and `mid-edge` as
/// their boundary twins.
fn admits(scheme: &str, mesh: &HalfEdgeMesh) -> bool {
    let counted_as = match scheme {
        "loop" | "midpoint" | "icosphere" | "butterfly" if mesh.counts().boundary_edges > 0 => {
            "loop-boundary"
        }
        "doo-sabin" if mesh.counts().boundary_edges > 0 => "doo-sabin-boundary",
        "mid-edge" if mesh.counts().boundary_edges > 0 => "mid-edge-boundary",
        _ => scheme,
    };
    schemes::builtin(counted_as)
        .and_then(|s| s.initial_state(&mesh.counts()))
        .is_ok()
}

#[test]
fn every_scheme_on_every_base_mesh_matches_its_prediction() {
    let mut ran = 0;
    for b in BASES {
        let mesh = base(b);
        for scheme in SCHEMES {
            let levels = levels_for(mesh.n_faces(), scheme, 4);
            let result = verify(&mesh, scheme, levels, &opts());
            if admits(scheme, &mesh) {
                let reports = result.unwrap_or_else(|e| panic!("{scheme} on {b}: {e}"));
                assert_eq!(reports.len(), levels as usize + 1);
                assert_reports(&format!("{scheme} on {b}"), &reports);
                let out = subdivide(&mesh, scheme, levels, &opts())
                    .unwrap_or_else(|e| panic!("{scheme} on {b}: {e}"));
                out.check_invariants()
                    .unwrap_or_else(|e| panic!("{scheme} on {b}: {e}"));
                assert!(
                    out.positions().iter().all(|p| p.is_finite()),
                    "{scheme} on {b}"
                );
                ran += 1;
            } else {
                let err = result
                    .err()
                    .unwrap_or_else(|| panic!("{scheme} on {b} should be refused"));
                assert!(matches!(err, Error::Scheme(_)), "{scheme} on {b}: {err}");
            }
        }
    }
    assert!(ran > 100, "only {ran} (scheme, mesh) pairs ran");
}

/// Every face as its vertex cycle rotated to start at its smallest vertex, sorted: equal for
/// two meshes with the same faces in any numbering of faces and half-edges.
fn face_sets(mesh: &HalfEdgeMesh) -> Vec<Vec<u32>> {
    let mut faces: Vec<Vec<u32>> = mesh
        .faces()
        .map(|f| {
            let vs: Vec<u32> = mesh.face_vertices(f).map(|v| v.0).collect();
            let i = vs
                .iter()
                .enumerate()
                .min_by_key(|(_, v)| **v)
                .map_or(0, |(i, _)| i);
            (0..vs.len()).map(|k| vs[(i + k) % vs.len()]).collect()
        })
        .collect();
    faces.sort();
    faces
}

/// One thread and two build the same mesh, numbered alike, with the same positions.
#[test]
fn threads_give_the_same_mesh() {
    for (b, scheme) in [
        ("icosahedron", "loop"),
        ("cube", "catmull-clark"),
        ("icosahedron-holes:2", "sqrt3-boundary"),
        ("mixed", "catmull-clark"),
        ("torus:1", "doo-sabin"),
        ("octahedron", "butterfly"),
        ("icosahedron-holes:2", "loop-boundary"),
        ("grid:3x2", "midpoint"),
        ("quad-grid:3x3", "catmull-clark"),
        ("icosahedron", "ternary"),
        ("torus:1", "mid-edge"),
        ("icosahedron", "sqrt3"),
        ("torus:2", "sqrt3-boundary"),
        ("mixed", "catmull-clark-general"),
        ("cube", "doo-sabin"),
    ] {
        let mesh = base(b);
        let three = subdivide(&mesh, scheme, 3, &opts()).expect("one thread");
        three.check_invariants().expect("valid");
        let threaded = subdivide(&mesh, scheme, 3, &opts().with_threads(2)).expect("threads");
        assert_eq!(face_sets(&threaded), face_sets(&three), "{scheme} on {b}");
        assert_eq!(threaded.positions(), three.positions(), "{scheme} on {b}");
    }
}

/// The face-list last level is the half-edge result converted, exactly, for every scheme on
/// every base mesh it admits, at levels 0 to 3.
#[test]
fn face_list_last_level_equals_the_converted_half_edge_mesh() {
    let mut direct = 0;
    for b in BASES {
        let mesh = base(b);
        for scheme in SCHEMES {
            if !admits(scheme, &mesh) {
                let err = subdivide_to_face_list(&mesh, scheme, 1, &opts()).unwrap_err();
                assert!(matches!(err, Error::Scheme(_)), "{scheme} on {b}: {err}");
                continue;
            }
            let max = levels_for(mesh.n_faces(), scheme, 3);
            for levels in 0..=max {
                let want = subdivide(&mesh, scheme, levels, &opts())
                    .unwrap_or_else(|e| panic!("{scheme} on {b}: {e}"));
                let got = subdivide_to_face_list(&mesh, scheme, levels, &opts())
                    .unwrap_or_else(|e| panic!("{scheme} on {b}: {e}"));
                let what = format!("{scheme} on {b}, level {levels}");
                assert_eq!(got.mesh, want.to_polygon_mesh(), "{what}");
                assert_eq!(got.edges, want.n_edges(), "{what}");
            }
            direct += usize::from(direct_face_degree(scheme).is_some());
        }
    }
    assert!(direct > 50, "only {direct} pairs took the direct path");
}

/// The parallel chunks of the face-list step (4,096 old faces per task) agree with the
/// sequential path, on meshes large enough to be split (at least 4,096 old faces).
#[test]
fn face_list_last_level_is_the_same_with_threads() {
    let ico = base("icosahedron");
    let cube = base("cube");
    for (mesh, scheme, levels) in [
        (&ico, "loop", 6),
        (&ico, "butterfly", 6),
        (&cube, "catmull-clark", 7),
        (&ico, "catmull-clark", 6),
    ] {
        let one = subdivide_to_face_list(mesh, scheme, levels, &opts()).expect("1 thread");
        let two = subdivide_to_face_list(mesh, scheme, levels, &opts().with_threads(2))
            .expect("2 threads");
        assert!(
            one.mesh.n_faces() > 4 * 4096,
            "{scheme}: too small to split"
        );
        assert_eq!(one, two, "{scheme}");
        let reference = subdivide(mesh, scheme, levels, &opts().with_threads(2)).expect("he");
        assert_eq!(two.mesh, reference.to_polygon_mesh(), "{scheme}");
    }
}

#[test]
fn icosphere_stays_on_the_unit_sphere() {
    let ico = base("icosahedron");
    assert!(ico
        .positions()
        .iter()
        .all(|p| (p.length() - 1.0).abs() < 1e-12));
    for level in 1..=4 {
        let sphere = subdivide(&ico, "icosphere", level, &opts()).expect("icosphere");
        let worst = sphere
            .positions()
            .iter()
            .map(|p| (p.length() - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-12, "level {level}: |v| off by {worst}");
        assert_eq!(sphere.n_faces(), 20 * 4usize.pow(level));
    }
}

#[test]
fn catmull_clark_of_the_cube_tightens_inside_the_cube() {
    let cube = base("cube");
    assert!(cube
        .positions()
        .iter()
        .all(|p| p.abs().max_element() == 1.0));
    for level in 1..=5 {
        let m = subdivide(&cube, "catmull-clark", level, &opts()).expect("catmull-clark");
        for p in m.positions() {
            assert!(
                p.abs().max_element() <= 1.0 + 1e-12,
                "level {level}: {p} outside the cube"
            );
            if level >= 4 {
                let r = p.length();
                assert!((0.83..=0.87).contains(&r), "level {level}: |{p}| = {r}");
            }
        }
    }
}

#[test]
fn loop_uses_loops_weights() {
    // Tetrahedron: valence 3, beta = (5/8 - (3/8 + 1/4 cos(2pi/3))^2) / 3 = 3/16.
    let tet = base("tetrahedron");
    let out = subdivide(&tet, "loop", 1, &opts()).expect("loop");
    for v in 0..4 {
        let p = tet.positions()[v];
        let sum: DVec3 = tet.positions().iter().sum::<DVec3>() - p;
        let expected = p * (1.0 - 3.0 * 3.0 / 16.0) + sum * (3.0 / 16.0);
        assert!(
            (out.positions()[v] - expected).length() < 1e-12,
            "vertex {v}"
        );
    }
    // A flat grid stays flat, and its boundary stays on the boundary lines.
    let grid = base("grid:3x2");
    let z0 = grid.positions()[0].z;
    let out = subdivide(&grid, "loop-boundary", 3, &opts()).expect("loop-boundary");
    assert!(out.positions().iter().all(|p| (p.z - z0).abs() < 1e-12));
}

#[test]
fn interpolating_schemes_keep_the_old_vertices() {
    for (b, scheme) in [
        ("icosahedron", "butterfly"),
        ("icosahedron-holes:2", "butterfly"),
        ("grid:3x2", "butterfly"),
        ("torus:1", "midpoint"),
        ("octahedron", "ternary"),
        ("icosahedron", "icosphere"),
    ] {
        let mesh = base(b);
        let out = subdivide(&mesh, scheme, 1, &opts()).expect(scheme);
        assert_eq!(
            &out.positions()[..mesh.n_vertices()],
            mesh.positions(),
            "{scheme} on {b}"
        );
    }
}

#[test]
fn mid_edge_of_a_tetrahedron_is_an_octahedron() {
    let out = subdivide(&base("tetrahedron"), "mid-edge", 1, &opts()).expect("mid-edge");
    assert_eq!((out.n_vertices(), out.n_edges(), out.n_faces()), (6, 12, 8));
    assert!(out.vertices().all(|v| out.valence(v) == 4));
}

#[test]
fn doo_sabin_of_the_cube_stays_inside_and_keeps_face_kinds() {
    let out = subdivide(&base("cube"), "doo-sabin", 1, &opts()).expect("doo-sabin");
    // 6 shrunken quads, 12 edge quads, 8 corner triangles.
    assert_eq!(
        (out.n_vertices(), out.n_edges(), out.n_faces()),
        (24, 48, 26)
    );
    let triangles = out.faces().filter(|&f| out.face_degree(f) == 3).count();
    assert_eq!(triangles, 8);
    // Corner of a square face: (n + 5)/(4n) = 9/16 on its own corner, 3/16 on each side
    // neighbour and 1/16 on the opposite one: (9 - 3 + 3 - 1)/16 = 1/2 along each of the
    // face's axes.
    for p in out.positions() {
        let a = p.abs();
        let mut c = [a.x, a.y, a.z];
        c.sort_by(f64::total_cmp);
        assert!(
            (c[0] - 0.5).abs() < 1e-12 && (c[1] - 0.5).abs() < 1e-12 && (c[2] - 1.0).abs() < 1e-12,
            "{p}"
        );
    }
}

#[test]
fn sqrt3_boundary_alternates_and_trisects_the_boundary() {
    let grid = base("grid:2x2");
    let be0 = grid.counts().boundary_edges;
    let mut be = Vec::new();
    for level in 0..=4 {
        let m = subdivide(&grid, "sqrt3-boundary", level, &opts()).expect("sqrt3-boundary");
        be.push(m.counts().boundary_edges);
        // The boundary polygon of a flat grid stays on the square's sides.
        assert!(m.positions().iter().all(|p| p.z.abs() < 1e-12));
    }
    assert_eq!(be, [be0, be0, 3 * be0, 3 * be0, 9 * be0]);
}

#[test]
fn refusals_are_typed() {
    let cube = base("cube");
    assert!(matches!(
        subdivide(&cube, "loop", 1, &opts()),
        Err(Error::Scheme(_))
    ));
    let grid = base("grid:2x2");
    assert!(matches!(
        subdivide(&grid, "sqrt3", 1, &opts()),
        Err(Error::Scheme(_))
    ));
    assert!(matches!(
        subdivide(&grid, "no-such", 1, &opts()),
        Err(Error::Scheme(_))
    ));
    assert!(matches!(
        subdivide(&grid, "tri-split-1", 1, &opts()),
        Err(Error::Scheme(_))
    ));
    assert!(halfedge::schemes::builtin("tri-split-1").is_err());
    let err = subdivide(&base("icosahedron"), "loop", 40, &opts()).unwrap_err();
    assert!(matches!(err, Error::TooLarge { .. }), "{err}");
    assert!(err.to_string().contains("loop level"), "{err}");
}

#[test]
fn zero_levels_return_the_input() {
    let ico = base("icosahedron");
    let out = subdivide(&ico, "loop", 0, &opts()).expect("loop");
    assert_eq!(out.positions(), ico.positions());
    assert_eq!(out.n_faces(), 20);
}

#[test]
fn progress_reports_every_level() {
    let seen = std::sync::Mutex::new(Vec::new());
    let cb = |d: &halfedge::subdivide::LevelDone| {
        seen.lock()
            .expect("lock")
            .push((d.level, d.levels, d.faces));
    };
    subdivide(
        &base("cube"),
        "catmull-clark",
        3,
        &opts().with_progress(&cb),
    )
    .expect("cc");
    assert_eq!(
        seen.into_inner().expect("lock"),
        [(1, 3, 24), (2, 3, 96), (3, 3, 384)]
    );
}

/// Three triangles on one edge plus a quad fan: non-manifold edges.
fn book() -> PolygonMesh {
    let p = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::NEG_Y,
        DVec3::new(1.0, 1.0, 0.0),
    ];
    PolygonMesh::from_faces(p, [[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 5, 2]])
}

#[test]
fn face_lists_subdivide_non_manifold_meshes() {
    let book = book();
    for scheme in [
        "loop-general",
        "tri-split-3",
        "tri-split-2",
        "catmull-clark-general",
    ] {
        let reports = verify_polygons(&book, scheme, 3, &opts()).expect(scheme);
        assert_eq!(reports.len(), 4);
        assert_reports(scheme, &reports);
    }
    // A mixed non-manifold polygon mesh under catmull-clark-general.
    let mut mixed = book.clone();
    mixed.positions.push(DVec3::new(2.0, 0.0, 0.0));
    mixed.push_face(&[1, 6, 5, 2, 0]);
    assert_reports(
        "cc-general mixed",
        &verify_polygons(&mixed, "catmull-clark-general", 3, &opts()).expect("cc"),
    );
    // Schemes that need a manifold mesh refuse, and others are not supported on face lists.
    assert!(matches!(
        verify_polygons(&book, "loop", 1, &opts()),
        Err(Error::Scheme(_))
    ));
    let err = halfedge::subdivide::subdivide_polygons(&book, Rule::Sqrt3, 1, &opts());
    assert!(matches!(err, Err(Error::NoSubdivision { .. })), "{err:?}");
}

#[test]
fn face_lists_agree_with_half_edge_subdivision_on_manifold_meshes() {
    for (b, scheme) in [
        ("icosahedron-holes:2", "loop-general"),
        ("torus:2", "ternary"),
        ("mixed", "catmull-clark"),
        ("quad-grid:3x3", "catmull-clark-quad"),
    ] {
        let polygons = shapes::from_name(b).expect(b);
        let he = subdivide(
            &HalfEdgeMesh::try_from(&polygons).expect(b),
            scheme,
            2,
            &opts(),
        )
        .expect(scheme);
        let fl = subdivide_polygons(&polygons, scheme, 2, &opts()).expect(scheme);
        assert_eq!(
            halfedge::stats::face_list_counts(&fl),
            he.counts(),
            "{scheme} on {b}"
        );
        // The same split: the same faces in the same order from the same corner, up to the
        // numbering of the vertices.
        same_faces_up_to_numbering(&fl, &he.to_polygon_mesh(), &format!("{scheme} on {b}"));
        assert_reports(
            scheme,
            &verify_polygons(&polygons, scheme, 2, &opts()).expect(scheme),
        );
    }
}

/// Panics unless `a` and `b` have the same faces, corner by corner, under one bijection of
/// their vertices.
fn same_faces_up_to_numbering(a: &PolygonMesh, b: &PolygonMesh, what: &str) {
    assert_eq!(a.n_faces(), b.n_faces(), "{what}: faces");
    assert_eq!(a.n_vertices(), b.n_vertices(), "{what}: vertices");
    let (mut to_b, mut to_a) = (
        vec![u32::MAX; a.n_vertices()],
        vec![u32::MAX; b.n_vertices()],
    );
    for (f, (fa, fb)) in a.faces().zip(b.faces()).enumerate() {
        assert_eq!(fa.len(), fb.len(), "{what}: face {f}");
        for (&va, &vb) in fa.iter().zip(fb) {
            let (x, y) = (&mut to_b[va as usize], &mut to_a[vb as usize]);
            assert!(*x == u32::MAX || *x == vb, "{what}: face {f}, vertex {va}");
            assert!(*y == u32::MAX || *y == va, "{what}: face {f}, vertex {vb}");
            (*x, *y) = (vb, va);
        }
    }
}

#[test]
fn face_lists_refuse_degenerate_faces() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let bad = PolygonMesh::from_faces(p.clone(), [[0, 1, 0]]);
    assert!(matches!(
        subdivide_polygons(&bad, "loop-general", 1, &opts()),
        Err(Error::RepeatedVertex { .. })
    ));
    let out = PolygonMesh::from_faces(p, [[0, 1, 7]]);
    assert!(matches!(
        subdivide_polygons(&out, "loop-general", 1, &opts()),
        Err(Error::VertexOutOfRange { .. })
    ));
}

/// Splits every quad of a face list into two triangles (other faces are kept).
fn triangulate_quads(mesh: &PolygonMesh) -> PolygonMesh {
    let mut out = PolygonMesh::with_positions(mesh.positions.clone());
    for face in mesh.faces() {
        if let [a, b, c, d] = *face {
            out.push_face(&[a, b, c]);
            out.push_face(&[a, c, d]);
        } else {
            out.push_face(face);
        }
    }
    out
}

/// The paper's Theorem 5.2 experiment: the icosahedron with two holes under the boundary-aware
/// 4:1 scheme (`BE` doubles, `V' = V + E`, `E' = 2E + 3F`, `F' = 4F`).
#[test]
fn paper_icosahedron_with_two_holes_under_loop_boundary() {
    let mesh = base("icosahedron-holes:2");
    let c = mesh.counts();
    assert_eq!(
        (
            c.vertices,
            c.edges,
            c.faces,
            c.boundary_edges,
            c.boundary_loops
        ),
        (12, 30, 18, 6, 2)
    );
    let reports = verify(&mesh, "loop-boundary", 4, &opts()).expect("loop-boundary");
    assert_reports("loop-boundary", &reports);
    let (mut v, mut e, mut f, mut be) = (12u64, 30u64, 18u64, 6u64);
    for level in 0..=4u32 {
        let m = subdivide(&mesh, "loop-boundary", level, &opts()).expect("loop-boundary");
        let c = m.counts();
        assert_eq!(
            (c.vertices, c.edges, c.faces, c.boundary_edges),
            (v, e, f, be),
            "level {level}"
        );
        assert_eq!(c.boundary_loops, 2, "level {level}");
        (v, e, f, be) = (v + e, 2 * e + 3 * f, 4 * f, 2 * be);
    }
    // Level 5 as predicted by the recurrence: F = 18 * 4^5.
    assert_eq!(f, 18 * 1024);
}

/// The paper's Corollary 5.1 experiment: closed triangle meshes of genus G under Loop keep
/// `V - E + F = 2 - 2G`, with `F(s) = 4^s F0`, `E(s) = 3/2 F(s)`, `V(s) = 2 - 2G + F(s)/2`.
#[test]
fn paper_tori_of_higher_genus_under_loop() {
    for genus in 1..=4u32 {
        let polygons = triangulate_quads(&shapes::torus(genus).expect("torus"));
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("triangulated torus");
        let f0 = mesh.n_faces() as i64;
        assert_eq!(mesh.counts().euler_characteristic, 2 - 2 * i64::from(genus));
        let reports = verify(&mesh, "loop", 3, &opts()).expect("loop");
        assert_reports(&format!("torus:{genus}"), &reports);
        for level in 0..=3u32 {
            let m = subdivide(&mesh, "loop", level, &opts()).expect("loop");
            let c = m.counts();
            let f = f0 * 4i64.pow(level);
            assert_eq!(c.faces as i64, f, "genus {genus} level {level}");
            assert_eq!(c.edges as i64, 3 * f / 2, "genus {genus} level {level}");
            assert_eq!(
                c.vertices as i64,
                2 - 2 * i64::from(genus) + f / 2,
                "genus {genus} level {level}"
            );
        }
        // The quad torus under Catmull-Clark keeps its genus too.
        let quads = HalfEdgeMesh::try_from(&shapes::torus(genus).expect("torus")).expect("torus");
        assert_reports(
            "catmull-clark torus",
            &verify(&quads, "catmull-clark", 3, &opts()).expect("cc"),
        );
        let out = subdivide(&quads, "catmull-clark", 3, &opts()).expect("cc");
        assert_eq!(out.counts().euler_characteristic, 2 - 2 * i64::from(genus));
    }
}

/// The paper's 3Holes mesh (genus 3): 3596 vertices, 10800 edges, 7200 faces, then Loop.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn paper_three_holes_counts() {
    let polygons = halfedge::io::read_mesh(testdata::mesh("3holes.obj")).expect("3holes.obj");
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("3holes is a valid mesh");
    let c = mesh.counts();
    assert_eq!((c.vertices, c.edges, c.faces), (3596, 10800, 7200));
    assert_eq!(c.euler_characteristic, -4);
    let reports = verify(&mesh, "loop", 2, &opts()).expect("loop");
    assert_reports("3holes", &reports);
    let last = &reports[2];
    let get = |name: &str| {
        last.measured
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.clone())
    };
    // V2 = V0 + E0 + E1 = 3596 + 10800 + (2 * 10800 + 3 * 7200) = 57596.
    assert_eq!(get("V"), Some(57596.into()));
    assert_eq!(get("F"), Some((7200 * 16).into()));
    // Real meshes through the other families too.
    for (file, scheme) in [
        ("3holes.obj", "sqrt3"),
        ("3holes.obj", "butterfly"),
        ("planexy.obj", "sqrt3-boundary"),
        ("face.obj", "loop-boundary"),
        ("halftunnel.obj", "catmull-clark"),
        ("fandisk_quads.obj", "doo-sabin"),
        ("osd_catmark_nonquads.obj", "catmull-clark"),
        ("eight.obj", "mid-edge"),
    ] {
        let polygons = halfedge::io::read_mesh(testdata::mesh(file)).expect(file);
        let mesh = HalfEdgeMesh::try_from(&polygons).expect(file);
        assert_reports(
            &format!("{scheme} on {file}"),
            &verify(&mesh, scheme, 2, &opts()).expect(scheme),
        );
    }
}

#[test]
fn named_functions_pick_the_boundary_variant() {
    use halfedge::subdivide::{
        butterfly_subdivide, catmull_clark_subdivide, doo_sabin_subdivide, icosphere_subdivide,
        loop_subdivide, mid_edge_subdivide, midpoint_subdivide, sqrt3_subdivide,
        tri_split_subdivide,
    };
    let grid = base("grid:2x2");
    let ico = base("icosahedron");
    let o = opts();
    assert_eq!(loop_subdivide(&grid, 1, &o).expect("loop").n_faces(), 32);
    assert_eq!(loop_subdivide(&ico, 1, &o).expect("loop").n_faces(), 80);
    assert_eq!(sqrt3_subdivide(&grid, 2, &o).expect("sqrt3").n_faces(), 72);
    assert_eq!(sqrt3_subdivide(&ico, 1, &o).expect("sqrt3").n_faces(), 60);
    assert_eq!(
        midpoint_subdivide(&grid, 1, &o)
            .expect("midpoint")
            .n_faces(),
        32
    );
    assert_eq!(
        icosphere_subdivide(&ico, 1, &o)
            .expect("icosphere")
            .n_faces(),
        80
    );
    assert_eq!(
        butterfly_subdivide(&grid, 1, &o)
            .expect("butterfly")
            .n_faces(),
        32
    );
    assert_eq!(
        tri_split_subdivide(&ico, 3, 1, &o)
            .expect("tri-split")
            .n_faces(),
        180
    );
    assert!(tri_split_subdivide(&ico, 1, 1, &o).is_err());
    assert_eq!(
        catmull_clark_subdivide(&grid, 1, &o).expect("cc").n_faces(),
        24
    );
    assert_eq!(
        doo_sabin_subdivide(&ico, 1, &o).expect("ds").n_faces(),
        20 + 30 + 12
    );
    assert_eq!(
        mid_edge_subdivide(&ico, 1, &o).expect("me").n_faces(),
        20 + 12
    );
    // On the 2x2 triangle grid (V 9, E 16, F 8): Doo-Sabin F' = F + E + V,
    // mid-edge F' = F + V, both by their boundary rules.
    assert_eq!(
        doo_sabin_subdivide(&grid, 1, &o).expect("ds").n_faces(),
        8 + 16 + 9
    );
    assert_eq!(
        mid_edge_subdivide(&grid, 1, &o).expect("me").n_faces(),
        8 + 9
    );
}

/// Big enough for the parallel passes (more than 2^14 elements per array).
#[test]
fn parallel_passes_match_the_single_thread_path() {
    let ico = base("icosahedron");
    for scheme in ["loop", "catmull-clark", "sqrt3", "doo-sabin"] {
        let levels = if scheme == "sqrt3" { 6 } else { 5 };
        let one = subdivide(&ico, scheme, levels, &opts()).expect("single");
        let two = subdivide(&ico, scheme, levels, &opts().with_threads(2)).expect("two threads");
        let pool = subdivide(&ico, scheme, levels, &opts().with_threads(0)).expect("global pool");
        assert!(
            one.n_halfedges() > 1 << 15,
            "{scheme}: too small to go parallel"
        );
        for other in [&two, &pool] {
            assert_eq!(other.positions(), one.positions(), "{scheme}");
            for h in one.halfedges() {
                assert_eq!(other.to_vertex(h), one.to_vertex(h), "{scheme}");
                assert_eq!(other.next(h), one.next(h), "{scheme}");
                assert_eq!(other.face(h), one.face(h), "{scheme}");
            }
        }
    }
}

#[test]
fn face_lists_drop_unused_vertices() {
    let mut mesh = book();
    mesh.positions.push(DVec3::splat(9.0)); // used by no face
    let reports = verify_polygons(&mesh, "loop-general", 2, &opts()).expect("loop-general");
    assert_reports("unused vertex", &reports);
    let out = subdivide_polygons(&mesh, "catmull-clark-general", 1, &opts()).expect("cc");
    let c = halfedge::stats::face_list_counts(&out);
    assert_eq!(c.unreferenced_vertices, 0);
    assert_eq!(out.n_vertices() as u64, c.vertices);
    assert!(out.positions.iter().all(|p| p.max_element() < 9.0));
}

/// A cube whose top front edge carries an extra vertex: two pentagons share the edges at a
/// vertex of valence 2. Catmull-Clark runs; the dual schemes refuse (the vertex face would be
/// a 2-gon) with the vertex named.
#[test]
fn dual_schemes_refuse_a_valence_two_vertex() {
    let cube = shapes::cube();
    let mut faces: Vec<Vec<u32>> = cube.faces().map(<[u32]>::to_vec).collect();
    // Find two faces sharing an edge (a, b) and insert vertex 8 between a and b in both.
    let (a, b) = (faces[0][0], faces[0][1]);
    let mut positions = cube.positions.clone();
    positions.push((positions[a as usize] + positions[b as usize]) * 0.5);
    for face in &mut faces {
        let n = face.len();
        if let Some(i) = (0..n).find(|&i| {
            let (x, y) = (face[i], face[(i + 1) % n]);
            (x, y) == (a, b) || (x, y) == (b, a)
        }) {
            face.insert(i + 1, 8);
        }
    }
    let polygons = PolygonMesh::from_faces(positions, faces);
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid polygon mesh");
    assert_eq!(mesh.valence(halfedge::VertexId(8)), 2);
    assert_reports(
        "cc",
        &verify(&mesh, "catmull-clark", 3, &opts()).expect("cc"),
    );
    for scheme in ["doo-sabin", "mid-edge"] {
        match subdivide(&mesh, scheme, 1, &opts()) {
            Err(Error::SchemeNotApplicable { scheme: s, reason }) => {
                assert_eq!(s, scheme);
                assert!(reason.contains("vertex 8 has valence 2"), "{reason}");
            }
            other => panic!("{scheme}: expected a refusal, got {other:?}"),
        }
    }
}

/// Meshes with boundary for the dual schemes: a triangle fan (a disk), one pentagon (every
/// vertex a corner of valence 2), mixed polygons with valence-2 corners, an open box of quads,
/// the icosahedron with three holes.
fn dual_boundary_meshes() -> Vec<(&'static str, HalfEdgeMesh)> {
    let disk = {
        let n = 7u32;
        let mut positions = vec![DVec3::ZERO];
        positions.extend((0..n).map(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / f64::from(n);
            DVec3::new(a.cos(), a.sin(), 0.1 * f64::from(k % 2))
        }));
        let faces: Vec<[u32; 3]> = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
        PolygonMesh::from_faces(positions, faces)
    };
    let pentagon = PolygonMesh::from_faces(
        (0..5)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::TAU / 5.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect(),
        [[0u32, 1, 2, 3, 4]],
    );
    let corners = PolygonMesh::from_faces(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.1),
            DVec3::new(2.0, 0.2, 0.0),
            DVec3::new(2.1, 1.0, 0.3),
            DVec3::new(1.0, 1.1, 0.0),
            DVec3::new(0.0, 1.0, 0.2),
            DVec3::new(1.5, 2.0, 0.1),
        ],
        [&[0u32, 1, 4, 5][..], &[1, 2, 3, 6, 4], &[4, 6, 5]],
    );
    let open_box = {
        let cube = shapes::cube();
        let faces: Vec<Vec<u32>> = cube.faces().skip(1).map(<[u32]>::to_vec).collect();
        PolygonMesh::from_faces(cube.positions.clone(), faces)
    };
    let valid = |name: &str, p: &PolygonMesh| {
        HalfEdgeMesh::try_from(p).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    vec![
        ("disk", valid("disk", &disk)),
        ("pentagon", valid("pentagon", &pentagon)),
        ("polygons with corners", valid("corners", &corners)),
        ("open box", valid("open box", &open_box)),
        ("icosahedron-holes:3", base("icosahedron-holes:3")),
        ("grid:4x3", base("grid:4x3")),
    ]
}

/// Issue 13, item 5: `doo-sabin` and `mid-edge` accept meshes with boundary, count by their
/// boundary twins, and every level matches its prediction, as a half-edge mesh and as a face
/// list.
#[test]
fn dual_schemes_with_boundary_match_their_predictions() {
    for (name, mesh) in dual_boundary_meshes() {
        assert!(!mesh.is_closed(), "{name}");
        for scheme in [
            "doo-sabin",
            "mid-edge",
            "doo-sabin-boundary",
            "mid-edge-boundary",
        ] {
            let what = format!("{scheme} on {name}");
            let reports =
                verify(&mesh, scheme, 3, &opts()).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_reports(&what, &reports);
            assert!(
                reports[0].predicted.iter().any(|(n, _)| n == "BE"),
                "{what}: counted by the boundary state"
            );
            let out = subdivide(&mesh, scheme, 3, &opts()).expect(&what);
            out.check_invariants()
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            let faces = subdivide_to_face_list(&mesh, scheme, 3, &opts()).expect(&what);
            assert_eq!(faces.mesh, out.to_polygon_mesh(), "{what}");
            // One boundary loop per input loop, twice as many boundary edges per level.
            let (c0, c3) = (mesh.counts(), out.counts());
            assert_eq!(c3.boundary_edges, 8 * c0.boundary_edges, "{what}");
            assert_eq!(c3.euler_characteristic, c0.euler_characteristic, "{what}");
        }
    }
}

/// The boundary geometry: Doo-Sabin's boundary points are Chaikin's `(3a + b)/4`, mid-edge keeps
/// the boundary vertices with the cubic B-spline rule `(a + 6v + b)/8` and the midpoints; a
/// corner of valence 2 becomes a triangle under both.
#[test]
fn dual_schemes_boundary_geometry() {
    let quad = PolygonMesh::from_faces(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(4.0, 4.0, 0.0),
            DVec3::new(0.0, 4.0, 0.0),
        ],
        [[0u32, 1, 2, 3]],
    );
    let quad = HalfEdgeMesh::try_from(&quad).expect("quad");
    let has = |m: &HalfEdgeMesh, p: DVec3| m.positions().iter().any(|q| q.distance(p) < 1e-12);
    let ds = subdivide(&quad, "doo-sabin", 1, &opts()).expect("doo-sabin");
    let sizes: Vec<usize> = ds.to_polygon_mesh().faces().map(<[u32]>::len).collect();
    assert_eq!(sizes, [4, 4, 4, 4, 4, 3, 3, 3, 3]);
    for p in [
        // The corners of the shrunken quad (weights 9/16, 3/16, 3/16, 1/16).
        (1.0, 1.0),
        (3.0, 3.0),
        // Chaikin's points on the four sides.
        (1.0, 0.0),
        (3.0, 0.0),
        (4.0, 1.0),
        (0.0, 3.0),
    ] {
        assert!(has(&ds, DVec3::new(p.0, p.1, 0.0)), "doo-sabin {p:?}");
    }
    let me = subdivide(&quad, "mid-edge", 1, &opts()).expect("mid-edge");
    let sizes: Vec<usize> = me.to_polygon_mesh().faces().map(<[u32]>::len).collect();
    assert_eq!(sizes, [4, 3, 3, 3, 3]);
    assert_eq!(me.n_vertices(), 8);
    for p in [(2.0, 0.0), (4.0, 2.0), (0.5, 0.5), (3.5, 3.5)] {
        assert!(has(&me, DVec3::new(p.0, p.1, 0.0)), "mid-edge {p:?}");
    }
    // Closed meshes are unchanged: the cube's Doo-Sabin level has no Chaikin point.
    let cube = base("cube");
    let closed = subdivide(&cube, "doo-sabin", 1, &opts()).expect("cube");
    assert_eq!(closed.n_vertices(), 24);
    assert!(closed.is_closed());
}

/// Every shared mesh with boundary under both dual schemes, levels as large as a debug build
/// handles quickly (at least 1).
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn dual_schemes_on_the_shared_meshes_with_boundary() {
    let dir = testdata::meshes_dir();
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("meshes dir")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "obj" || x == "off"))
        .collect();
    files.sort();
    let mut ran = 0;
    for file in files {
        let Ok(polygons) = halfedge::io::read_mesh(&file) else {
            continue;
        };
        let Ok(mesh) = HalfEdgeMesh::try_from(&polygons) else {
            continue;
        };
        if mesh.is_closed() {
            continue;
        }
        let mut levels = 1;
        while levels < 3 && mesh.n_faces() << (2 * (levels + 1)) <= 2_000_000 {
            levels += 1;
        }
        for scheme in ["doo-sabin", "mid-edge"] {
            let what = format!("{scheme} on {}", file.display());
            match verify(&mesh, scheme, levels, &opts()) {
                Ok(reports) => assert_reports(&what, &reports),
                // Only an interior vertex of valence 2 may refuse.
                Err(Error::SchemeNotApplicable { reason, .. }) => {
                    assert!(reason.contains("valence 2"), "{what}: {reason}");
                }
                Err(e) => panic!("{what}: {e}"),
            }
        }
        ran += 1;
    }
    assert!(ran >= 5, "only {ran} meshes with boundary");
}

/// A non-finite boundary point names its origin: mid-edge's kept boundary vertex, Doo-Sabin's
/// Chaikin point.
#[test]
fn dual_schemes_name_non_finite_boundary_points() {
    let quad = PolygonMesh::from_faces(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.5e308, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.5e308, 1.0, 0.0),
        ],
        [[0u32, 1, 2, 3]],
    );
    let quad = HalfEdgeMesh::try_from(&quad).expect("quad");
    match subdivide(&quad, "mid-edge", 1, &opts()) {
        Err(Error::NonFinitePosition { vertex, origin, .. }) => {
            assert_eq!(vertex, 5);
            assert_eq!(origin, "from boundary vertex 0 of the input");
        }
        other => panic!("expected a non-finite point, got {other:?}"),
    }
}
