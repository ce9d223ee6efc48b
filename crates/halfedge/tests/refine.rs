//! `Refinement`: the topology refined once, any vertex data evaluated many times, against the
//! one-shot subdivision (bit for bit in `f64`), the face lists, the stencils and the errors.

use glam::DVec3;
use halfedge::refine::Refinement;
use halfedge::subdivide::{subdivide, subdivide_to_face_list, SubdivideOptions};
use halfedge::{shapes, Error, HalfEdgeMesh, PolygonMesh, Rule};

/// Every rule, with a 1:N² split for N = 2 and 3.
const RULES: [Rule; 10] = [
    Rule::Loop,
    Rule::Midpoint,
    Rule::Butterfly,
    Rule::Icosphere,
    Rule::TriSplit(2),
    Rule::TriSplit(3),
    Rule::CatmullClark,
    Rule::Sqrt3,
    Rule::DooSabin,
    Rule::MidEdge,
];

/// `mesh` with every vertex moved by a small deterministic offset (no symmetry to hide a
/// wrong index).
fn jittered(mesh: PolygonMesh) -> HalfEdgeMesh {
    let mut m = mesh;
    for (i, p) in m.positions.iter_mut().enumerate() {
        let t = i as f64;
        *p += DVec3::new(
            0.013 * (1.7 * t).sin(),
            0.011 * (2.3 * t).cos(),
            0.017 * (0.7 * t).sin(),
        );
    }
    HalfEdgeMesh::try_from(&m).expect("a valid mesh")
}

/// Closed meshes, meshes with boundary and mixed polygons.
fn meshes() -> Vec<(&'static str, HalfEdgeMesh)> {
    vec![
        ("icosahedron", jittered(shapes::icosahedron())),
        ("cube", jittered(shapes::cube())),
        ("torus", jittered(shapes::torus(1).expect("torus"))),
        ("grid", jittered(shapes::grid(3, 2).expect("grid"))),
        (
            "quad grid",
            jittered(shapes::quad_grid(3, 2).expect("quad grid")),
        ),
        (
            "icosahedron with holes",
            jittered(shapes::icosahedron_holes(2).expect("holes")),
        ),
        ("mixed", jittered(shapes::mixed())),
        // Boundary corners of valence 2 (one face), a pentagon and a triangle fan.
        (
            "polygons with corners",
            jittered(PolygonMesh::from_faces(
                vec![
                    DVec3::new(0.0, 0.0, 0.0),
                    DVec3::new(1.0, 0.0, 0.1),
                    DVec3::new(2.0, 0.2, 0.0),
                    DVec3::new(2.1, 1.0, 0.3),
                    DVec3::new(1.0, 1.1, 0.0),
                    DVec3::new(0.0, 1.0, 0.2),
                    DVec3::new(1.5, 2.0, 0.1),
                ],
                [&[0, 1, 4, 5][..], &[1, 2, 3, 6, 4], &[4, 6, 5]],
            )),
        ),
    ]
}

fn base_of(mesh: &HalfEdgeMesh) -> Vec<[f64; 3]> {
    mesh.positions().iter().map(|p| p.to_array()).collect()
}

fn opts(threads: usize) -> SubdivideOptions<'static> {
    SubdivideOptions::default().with_threads(threads)
}

/// Every (mesh, rule, level) the one-shot subdivision accepts, with the refinement agreeing
/// on the refusals.
fn cases() -> Vec<(String, HalfEdgeMesh, Rule, u32)> {
    let mut out = Vec::new();
    for (name, mesh) in meshes() {
        for rule in RULES {
            for levels in 1..=3 {
                let one_shot = subdivide(&mesh, rule, levels, &opts(1));
                let refined = Refinement::new(&mesh, rule, levels, &opts(1));
                match (&one_shot, &refined) {
                    (Ok(_), Ok(_)) => out.push((name.to_string(), mesh.clone(), rule, levels)),
                    (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name} {rule}"),
                    _ => panic!(
                        "{name} {rule} L{levels}: one-shot {:?}, refinement {:?}",
                        one_shot.err(),
                        refined.err()
                    ),
                }
            }
        }
    }
    out
}

#[test]
fn evaluate_is_the_one_shot_subdivision_to_the_bit() {
    let cases = cases();
    assert!(cases.len() >= 100, "{} cases", cases.len());
    for (name, mesh, rule, levels) in cases {
        let what = format!("{name} {rule} L{levels}");
        let one_shot = subdivide(&mesh, rule, levels, &opts(1)).expect("one-shot");
        let r = Refinement::new(&mesh, rule, levels, &opts(1)).expect("refinement");
        assert_eq!(r.rule(), rule);
        assert_eq!(r.levels(), levels);
        assert_eq!(r.n_vertices(levels), one_shot.n_vertices(), "{what}");
        assert_eq!(r.n_edges(levels), one_shot.n_edges(), "{what}");
        assert_eq!(r.n_faces(levels), one_shot.n_faces(), "{what}");
        assert_eq!(r.n_vertices(0), mesh.n_vertices(), "{what}");
        let mut out = vec![[0.0; 3]; r.n_vertices(levels)];
        r.evaluate(&base_of(&mesh), &mut out).expect("evaluate");
        let expected: Vec<[u64; 3]> = one_shot
            .positions()
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect();
        let got: Vec<[u64; 3]> = out.iter().map(|p| p.map(f64::to_bits)).collect();
        assert!(got == expected, "{what}: positions differ");

        // The face list: as subdivide_to_face_list and to_polygon_mesh number it.
        let faces = subdivide_to_face_list(&mesh, rule, levels, &opts(1)).expect("face list");
        assert_eq!(faces.mesh, one_shot.to_polygon_mesh(), "{what}");
        assert_eq!(faces.edges, r.n_edges(levels), "{what}");
        let polygon = one_shot.to_polygon_mesh();
        assert_eq!(r.n_corners(levels), polygon.face_indices().len(), "{what}");
        let mut offsets = vec![0u32; r.n_faces(levels) + 1];
        let mut indices = vec![0u32; r.n_corners(levels)];
        r.write_polygons(&mut offsets, &mut indices)
            .expect("polygons");
        assert_eq!(
            offsets.iter().map(|&o| o as usize).collect::<Vec<_>>(),
            polygon.face_offsets(),
            "{what}"
        );
        assert_eq!(indices, polygon.face_indices(), "{what}");
        match r.face_degree() {
            Some(3) => {
                let mut tris = vec![0u32; 3 * r.n_faces(levels)];
                r.write_triangles(&mut tris).expect("triangles");
                assert_eq!(tris, indices, "{what}");
                assert!(matches!(
                    r.write_quads(&mut tris),
                    Err(Error::FaceDegreeMismatch { wanted: 4, .. })
                ));
            }
            Some(4) => {
                let mut quads = vec![0u32; 4 * r.n_faces(levels)];
                r.write_quads(&mut quads).expect("quads");
                assert_eq!(quads, indices, "{what}");
                assert!(matches!(
                    r.write_triangles(&mut quads),
                    Err(Error::FaceDegreeMismatch { wanted: 3, .. })
                ));
            }
            other => {
                assert!(
                    polygon.faces().any(|f| Some(f.len()) != other),
                    "{what}: degree {other:?}"
                );
            }
        }
    }
}

#[test]
fn results_do_not_depend_on_the_threads() {
    for (name, mesh, rule, levels) in cases().into_iter().filter(|c| c.3 == 3) {
        let base = base_of(&mesh);
        let eval = |threads| {
            let r = Refinement::new(&mesh, rule, levels, &opts(threads)).expect("refinement");
            let mut out = vec![[0.0; 3]; r.n_vertices(levels)];
            r.evaluate(&base, &mut out).expect("evaluate");
            let mut offsets = vec![0u32; r.n_faces(levels) + 1];
            let mut indices = vec![0u32; r.n_corners(levels)];
            r.write_polygons(&mut offsets, &mut indices)
                .expect("polygons");
            (out, offsets, indices)
        };
        let one = eval(1);
        assert!(eval(2) == one, "{name} {rule}: 2 threads");
        assert!(eval(0) == one, "{name} {rule}: global pool");
    }
}

#[test]
fn levels_chain_to_the_last_level_and_evaluators_reuse_their_buffers() {
    for (name, mesh, rule, levels) in cases().into_iter().filter(|c| c.3 == 3) {
        let r = Refinement::new(&mesh, rule, levels, &opts(1)).expect("refinement");
        let mut data = base_of(&mesh);
        for s in 1..=levels {
            let mut next = vec![[0.0; 3]; r.n_vertices(s)];
            r.evaluate_level(s, &data, &mut next).expect("level");
            data = next;
        }
        let mut direct = vec![[0.0; 3]; r.n_vertices(levels)];
        let mut evaluator = r.evaluator::<f64, 3>();
        for _ in 0..2 {
            evaluator
                .evaluate(&base_of(&mesh), &mut direct)
                .expect("evaluate");
            assert!(direct == data, "{name} {rule}");
        }
        // The same refinement, other data: a moved base.
        let moved: Vec<[f64; 3]> = base_of(&mesh)
            .iter()
            .map(|p| [p[0] + 1.0, 2.0 * p[1], p[2]])
            .collect();
        evaluator.evaluate(&moved, &mut direct).expect("evaluate");
        assert!(
            direct != data,
            "{name} {rule}: the moved base changed nothing"
        );
        // Its buffers handed to the next evaluator (a binding's object owning the
        // refinement): the same bits.
        let mut next = r.evaluator_with(evaluator.into_scratch());
        next.evaluate(&base_of(&mesh), &mut direct)
            .expect("evaluate");
        assert!(direct == data, "{name} {rule}: after into_scratch");
    }
}

#[test]
fn any_width_and_strided_data() {
    for (name, mesh, rule, levels) in cases().into_iter().filter(|c| c.3 == 2) {
        let r = Refinement::new(&mesh, rule, levels, &opts(1)).expect("refinement");
        let base = base_of(&mesh);
        let mut xyz = vec![[0.0; 3]; r.n_vertices(levels)];
        r.evaluate(&base, &mut xyz).expect("evaluate");
        // Stride 3 is [f64; 3].
        let flat: Vec<f64> = base.iter().flatten().copied().collect();
        let mut out = vec![0.0; 3 * r.n_vertices(levels)];
        r.evaluate_strided(&flat, 3, &mut out).expect("strided");
        assert!(out == xyz.concat(), "{name} {rule}");
        if !rule.is_linear() {
            continue;
        }
        // Width 1 per coordinate gives the same numbers (the linear rules act componentwise).
        let xs: Vec<[f64; 1]> = base.iter().map(|p| [p[0]]).collect();
        let mut out1 = vec![[0.0; 1]; r.n_vertices(levels)];
        r.evaluate(&xs, &mut out1).expect("width 1");
        assert!(
            out1.iter().zip(&xyz).all(|(a, b)| a[0] == b[0]),
            "{name} {rule}"
        );
        // A stride of 20 (component by component).
        let wide: Vec<f64> = base
            .iter()
            .flat_map(|p| (0..20).map(move |c| p[c % 3] * (1 + c / 3) as f64))
            .collect();
        let mut out20 = vec![0.0; 20 * r.n_vertices(levels)];
        r.evaluate_strided(&wide, 20, &mut out20)
            .expect("stride 20");
        for (v, p) in xyz.iter().enumerate() {
            for c in 0..20 {
                let expected = p[c % 3] * (1 + c / 3) as f64;
                let got = out20[20 * v + c];
                assert!(
                    (got - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
                    "{name} {rule}"
                );
            }
        }
    }
}

#[test]
fn f32_follows_f64() {
    for (name, mesh, rule, levels) in cases().into_iter().filter(|c| c.3 == 3) {
        let r = Refinement::new(&mesh, rule, levels, &opts(1)).expect("refinement");
        let base = base_of(&mesh);
        let base32: Vec<[f32; 3]> = base.iter().map(|p| p.map(|x| x as f32)).collect();
        let mut out64 = vec![[0.0; 3]; r.n_vertices(levels)];
        let mut out32 = vec![[0.0f32; 3]; r.n_vertices(levels)];
        r.evaluate(&base, &mut out64).expect("f64");
        r.evaluate(&base32, &mut out32).expect("f32");
        for (a, b) in out64.iter().zip(&out32) {
            for c in 0..3 {
                assert!(
                    (a[c] - f64::from(b[c])).abs() < 1e-5,
                    "{name} {rule}: {a:?} {b:?}"
                );
            }
        }
    }
}

#[test]
fn stencil_sizes_are_the_sizes_of_the_built_table() {
    let mut checked = 0;
    for (name, mesh, rule, levels) in cases() {
        let what = format!("{name} {rule} L{levels}");
        for threads in [1, 2] {
            let r = Refinement::new(&mesh, rule, levels, &opts(threads)).expect("refinement");
            let sizes = match r.stencil_sizes() {
                Ok(sizes) => sizes,
                Err(e) => {
                    assert_eq!(rule, Rule::Icosphere, "{what}: {e}");
                    assert!(matches!(e, Error::NotLinear { .. }), "{what}: {e}");
                    continue;
                }
            };
            let table = r.stencils().expect("stencils");
            assert_eq!(sizes, table.sizes(), "{what}");
            assert_eq!(sizes.rows, r.n_vertices(levels), "{what}");
            assert_eq!(sizes.entries, table.indices().len(), "{what}");
            assert_eq!(sizes.entries, table.weights().len(), "{what}");
            assert_eq!(
                sizes.bytes(),
                4 * table.offsets().len() as u128 + 12 * table.n_entries() as u128,
                "{what}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 100, "{checked} tables");
}

#[test]
fn stencils_reproduce_the_evaluation() {
    for (name, mesh, rule, levels) in cases() {
        let r = Refinement::new(&mesh, rule, levels, &opts(1)).expect("refinement");
        let table = match r.stencils() {
            Ok(t) => t,
            Err(e) => {
                assert_eq!(rule, Rule::Icosphere, "{name}: {e}");
                assert!(matches!(e, Error::NotLinear { .. }));
                assert!(
                    e.to_string()
                        .contains("rule is not linear: the sphere projection"),
                    "{e}"
                );
                continue;
            }
        };
        assert_eq!(table.len(), r.n_vertices(levels));
        assert_eq!(table.base_vertices(), r.n_vertices(0));
        assert_eq!(table.offsets().len(), table.len() + 1);
        assert_eq!(table.indices().len(), table.n_entries());
        assert_eq!(table.weights().len(), table.n_entries());
        let base = base_of(&mesh);
        let mut evaluated = vec![[0.0; 3]; table.len()];
        r.evaluate(&base, &mut evaluated).expect("evaluate");
        let mut applied = vec![[0.0; 3]; table.len()];
        table.apply(&base, &mut applied).expect("apply");
        for (i, (a, b)) in evaluated.iter().zip(&applied).enumerate() {
            let (rows, weights) = table.row(i);
            assert!(
                rows.windows(2).all(|w| w[0] < w[1]),
                "{name} {rule}: sorted row"
            );
            let sum: f64 = weights.iter().sum();
            assert!(
                (sum - 1.0).abs() < 1e-12,
                "{name} {rule}: row {i} sums to {sum}"
            );
            for c in 0..3 {
                assert!(
                    (a[c] - b[c]).abs() <= 1e-12 * (1.0 + a[c].abs()),
                    "{name} {rule} L{levels}: vertex {i}: {a:?} vs {b:?}"
                );
            }
        }
    }
}

#[test]
fn wrong_buffers_and_levels_are_typed_errors() {
    let ico = jittered(shapes::icosahedron());
    let r = Refinement::new(&ico, Rule::Loop, 2, &opts(1)).expect("refinement");
    let base = base_of(&ico);
    let mut out = vec![[0.0; 3]; r.n_vertices(2)];
    let size = |e: Error| match e {
        Error::BufferSize {
            what,
            expected,
            given,
        } => (what, expected, given),
        other => panic!("{other}"),
    };
    assert_eq!(
        size(r.evaluate(&base[1..], &mut out).unwrap_err()),
        ("base", 12, 11)
    );
    assert_eq!(
        size(r.evaluate(&base, &mut out[1..]).unwrap_err()),
        ("out", 162, 161)
    );
    let mut level1 = vec![[0.0; 3]; 41];
    assert_eq!(
        size(r.evaluate_level(1, &base, &mut level1).unwrap_err()),
        ("dst", 42, 41)
    );
    for level in [0, 3] {
        let err = r.evaluate_level(level, &base, &mut level1).unwrap_err();
        assert!(
            matches!(err, Error::LevelOutOfRange { levels: 2, .. }),
            "{err}"
        );
        assert_eq!(
            err.to_string(),
            format!("level {level} is out of range: the refinement has levels 1..=2")
        );
    }
    let mut tris = vec![0u32; 3 * 320 - 1];
    assert_eq!(
        size(r.write_triangles(&mut tris).unwrap_err()),
        ("triangle indices", 960, 959)
    );
    let err = r.write_quads(&mut tris).unwrap_err();
    assert_eq!(
        err.to_string(),
        "quads need faces of 4 vertices, but face 0 of the last level has 3"
    );
    let (mut offsets, mut indices) = (vec![0u32; 320], vec![0u32; 960]);
    assert_eq!(
        size(r.write_polygons(&mut offsets, &mut indices).unwrap_err()),
        ("face offsets", 321, 320)
    );
    let flat: Vec<f64> = base.concat();
    let mut flat_out = vec![0.0; 3 * 162];
    assert!(matches!(
        r.evaluate_strided(&flat, 0, &mut flat_out),
        Err(Error::UnsupportedStride { stride: 0, .. })
    ));
    assert_eq!(
        size(r.evaluate_strided(&flat, 2, &mut flat_out).unwrap_err()),
        ("base", 24, 36)
    );
    // A mixed last level refuses triangles and quads, naming the first face that differs.
    let mixed = jittered(shapes::mixed());
    let r0 = Refinement::new(&mixed, Rule::CatmullClark, 0, &opts(1)).expect("level 0");
    assert_eq!(r0.face_degree(), None);
    let mut buf = vec![0u32; 3 * r0.n_faces(0)];
    assert!(matches!(
        r0.write_triangles(&mut buf),
        Err(Error::FaceDegreeMismatch { wanted: 3, .. })
    ));
    // Icosphere stencils: refused with the reason.
    let sphere = Refinement::new(&ico, Rule::Icosphere, 1, &opts(1)).expect("icosphere");
    assert_eq!(
        sphere.stencils().unwrap_err().to_string(),
        "no stencils for icosphere: rule is not linear: the sphere projection"
    );
}

#[test]
fn level_zero_is_the_base() {
    let cube = jittered(shapes::cube());
    let r = Refinement::new(&cube, Rule::CatmullClark, 0, &opts(1)).expect("level 0");
    let base = base_of(&cube);
    let mut out = vec![[0.0; 3]; 8];
    r.evaluate(&base, &mut out).expect("evaluate");
    assert_eq!(out, base);
    let mut quads = vec![0u32; 24];
    r.write_quads(&mut quads).expect("quads");
    assert_eq!(quads, cube.to_polygon_mesh().face_indices());
    let table = r.stencils().expect("stencils");
    assert_eq!(table.n_entries(), 8);
    let predicted = Refinement::predicted_bytes(Rule::CatmullClark, &cube.counts(), 0);
    assert_eq!(predicted.expect("predicted"), r.heap_bytes().into());
}

#[test]
fn progress_and_memory() {
    let ico = jittered(shapes::icosahedron());
    let seen = std::sync::Mutex::new(Vec::new());
    let progress = |d: &halfedge::subdivide::LevelDone| {
        seen.lock()
            .expect("lock")
            .push((d.level, d.vertices, d.edges, d.faces));
    };
    let o = SubdivideOptions::default().with_progress(&progress);
    let r = Refinement::new(&ico, Rule::Loop, 3, &o).expect("refinement");
    assert_eq!(
        *seen.lock().expect("lock"),
        [(1, 42, 120, 80), (2, 162, 480, 320), (3, 642, 1920, 1280)]
    );
    // Loop keeps levels 0-2 flattened (24 bytes per edge, 5 per vertex, 4 more), and the
    // connectivity of level 2 (4 bytes per vertex and face, 32 per edge).
    let sizes = [(12, 30, 20), (42, 120, 80), (162, 480, 320)];
    let flat: usize = sizes.iter().map(|(v, e, _)| 24 * e + 5 * v + 4).sum();
    let connectivity = |(v, e, f): (usize, usize, usize)| 4 * v + 32 * e + 4 * f;
    assert_eq!(r.heap_bytes(), flat + connectivity(sizes[2]));
    // Other rules keep the connectivity of levels 0-2.
    let mid = Refinement::new(&ico, Rule::Midpoint, 3, &opts(1)).expect("midpoint");
    let expected: usize = sizes.iter().map(|&s| connectivity(s)).sum();
    assert_eq!(mid.heap_bytes(), expected);
}

#[test]
fn large_meshes_take_the_parallel_paths_with_the_same_bits() {
    // Above the sizes where the passes split into parallel chunks.
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("icosahedron");
    let sphere = subdivide(&ico, Rule::Icosphere, 5, &opts(1)).expect("sphere");
    let sphere = jittered(sphere.to_polygon_mesh());
    let grid = jittered(shapes::grid(90, 90).expect("grid"));
    let cases = [
        (&sphere, Rule::Loop),
        (&sphere, Rule::Butterfly),
        (&sphere, Rule::CatmullClark),
        (&sphere, Rule::Sqrt3),
        (&sphere, Rule::DooSabin),
        (&grid, Rule::Loop),
        (&grid, Rule::CatmullClark),
        (&grid, Rule::Sqrt3),
        (&grid, Rule::DooSabin),
        (&grid, Rule::MidEdge),
    ];
    for (mesh, rule) in cases {
        let base = base_of(mesh);
        let expected = subdivide(mesh, rule, 2, &opts(1)).expect("one-shot");
        let expected: Vec<[f64; 3]> = expected.positions().iter().map(|p| p.to_array()).collect();
        let one_shot_2t = subdivide(mesh, rule, 2, &opts(2)).expect("one-shot, 2 threads");
        let faces = subdivide_to_face_list(mesh, rule, 2, &opts(1)).expect("faces");
        for threads in [1, 2] {
            let r = Refinement::new(mesh, rule, 2, &opts(threads)).expect("refinement");
            let mut out = vec![[0.0; 3]; r.n_vertices(2)];
            r.evaluate(&base, &mut out).expect("evaluate");
            assert!(out == expected, "{rule} {threads}t");
            let mut offsets = vec![0u32; r.n_faces(2) + 1];
            let mut indices = vec![0u32; r.n_corners(2)];
            r.write_polygons(&mut offsets, &mut indices)
                .expect("polygons");
            assert_eq!(indices, faces.mesh.face_indices(), "{rule} {threads}t");
        }
        let got: Vec<[f64; 3]> = one_shot_2t
            .positions()
            .iter()
            .map(|p| p.to_array())
            .collect();
        assert!(got == expected, "{rule}: one-shot in 2 threads");
    }
}

#[test]
fn predicted_bytes_bound_what_a_refinement_keeps() {
    for (name, mesh, rule, levels) in cases() {
        let r = Refinement::new(&mesh, rule, levels, &opts(1)).expect("refinement");
        let predicted =
            Refinement::predicted_bytes(rule, &mesh.counts(), levels).expect("predicted");
        let kept = halfedge::BigInt::from(r.heap_bytes());
        if mesh.is_closed() {
            assert_eq!(predicted, kept, "{name} {rule} L{levels}");
        } else {
            assert!(
                predicted >= kept,
                "{name} {rule} L{levels}: {predicted} < {kept}"
            );
            assert!(
                predicted.clone() * 10u32 <= kept.clone() * 11u32,
                "{name} {rule} L{levels}: {predicted} vs {kept}"
            );
        }
    }
}
