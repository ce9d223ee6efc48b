//! The crease rules (`halfedge::subdivide::sdc`) without OpenSubdiv: values recorded from
//! OpenSubdiv 3.5 (`tools/osd-driver`) for a small tagged grid, so a plain `cargo test` catches
//! a change of the rules; the fast path's bits when nothing is sharp; the typed errors.

use glam::DVec3;
use halfedge::refine::Refinement;
use halfedge::subdivide::{Sharpness, SubdivideOptions};
use halfedge::tags::{BoundaryInterpolation, CreaseMethod, SubdivisionOptions, Tags, TriangleRule};
use halfedge::{shapes, Error, HalfEdgeMesh, HalfedgeId, PolygonMesh, Rule};

/// The 3 x 3 grid of the recorded values, vertex `(i, j)` numbered `3 j + i`, as quads or
/// split along one diagonal.
fn grid(triangles: bool) -> PolygonMesh {
    let z = [0.0, 0.25, 0.0, 0.5, -0.25, 0.125, 0.0, 0.375, -0.5];
    let positions = (0..9)
        .map(|v: usize| DVec3::new((v % 3) as f64, (v / 3) as f64, z[v]))
        .collect();
    let mut mesh = PolygonMesh::with_positions(positions);
    for [a, b, c, d] in [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]] {
        if triangles {
            mesh.push_face(&[a, b, c]);
            mesh.push_face(&[a, c, d]);
        } else {
            mesh.push_face(&[a, b, c, d]);
        }
    }
    mesh
}

/// Creases of 2.7 and 0.5 along the middle row, 1.3 down the middle column (three semi-sharp
/// edges at the centre: a corner), a semi-sharp corner of 0.5 at vertex 0.
fn grid_tags() -> Tags {
    let mut tags = Tags::default();
    tags.add_crease(3, 4, 2.7).expect("valid");
    tags.add_crease(4, 5, 0.5).expect("valid");
    tags.add_crease(1, 4, 1.3).expect("valid");
    tags.add_corner(0, 0.5).expect("valid");
    tags
}

/// OpenSubdiv 3.5's level 2 of [`grid`] (quads) with [`grid_tags`], Catmark, Chaikin,
/// `VTX_BOUNDARY_EDGE_AND_CORNER`, in its vertex order: `osd_driver --tags --crease-method
/// chaikin catmark 2 FILE edge-and-corner`.
const CATMARK_CHAIKIN_CORNERS_LEVEL2: [[f64; 3]; 81] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.22812499850988388],
    [2.0, 0.0, 0.0],
    [0.0, 1.0, 0.5],
    [0.93701171875, 0.93701171875, -0.0929107666015625],
    [2.0, 1.0, 0.04296875],
    [0.0, 2.0, 0.0],
    [1.0, 2.0, 0.1796875],
    [2.0, 2.0, -0.5],
    [0.4990234375, 0.4990234375, 0.126220703125],
    [1.4990234375, 0.4990234375, 0.0328369140625],
    [0.4990234375, 1.4990234375, 0.154296875],
    [1.4990234375, 1.4990234375, -0.0640869140625],
    [0.5, 0.0, 0.125],
    [
        0.9934814453590661,
        0.49348144535906613,
        0.021208954269241076,
    ],
    [0.4921875, 0.9921875, 0.134765625],
    [0.0, 0.5, 0.25],
    [1.5, 0.0, 0.125],
    [2.0, 0.5, 0.056640625],
    [1.494140625, 0.994140625, -0.0413818359375],
    [0.994140625, 1.494140625, 0.04705810546875],
    [0.5, 2.0, 0.16796875],
    [0.0, 1.5, 0.25],
    [2.0, 1.5, -0.193359375],
    [1.5, 2.0, -0.08203125],
    [0.25, 0.25, 0.125],
    [0.75, 0.25, 0.125],
    [0.734375, 0.734375, 0.01953125],
    [0.25, 0.75, 0.25],
    [1.25, 0.25, 0.1015625],
    [1.75, 0.25, 0.0546875],
    [1.75, 0.75, 0.0302734375],
    [1.234375, 0.734375, -0.0478515625],
    [0.25, 1.25, 0.2578125],
    [0.734375, 1.234375, 0.041015625],
    [0.75, 1.75, 0.154296875],
    [0.25, 1.75, 0.1484375],
    [1.234375, 1.234375, -0.0576171875],
    [1.75, 1.25, -0.0556640625],
    [1.75, 1.75, -0.203125],
    [1.25, 1.75, 0.037109375],
    [0.5, 0.25, 0.125],
    [0.74609375, 0.49609375, 0.0673828125],
    [0.49609375, 0.74609375, 0.1298828125],
    [0.25, 0.5, 0.1875],
    [1.5, 0.25, 0.078125],
    [1.75, 0.5, 0.044677734375],
    [1.49609375, 0.74609375, -0.00927734375],
    [1.24609375, 0.49609375, 0.021240234375],
    [0.49609375, 1.24609375, 0.14501953125],
    [0.74609375, 1.49609375, 0.1015625],
    [0.5, 1.75, 0.16162109375],
    [0.25, 1.5, 0.203125],
    [1.49609375, 1.24609375, -0.056640625],
    [1.75, 1.5, -0.127197265625],
    [1.5, 1.75, -0.07275390625],
    [1.24609375, 1.49609375, -0.007080078125],
    [0.25, 0.0, 0.0625],
    [0.75, 0.0, 0.1875],
    [1.0, 0.25, 0.12089843722060323],
    [0.9736328125, 0.7236328125, -0.063507080078125],
    [0.71875, 0.96875, -0.0234375],
    [0.25, 1.0, 0.3125],
    [0.0, 0.75, 0.375],
    [0.0, 0.25, 0.125],
    [1.25, 0.0, 0.1875],
    [1.75, 0.0, 0.0625],
    [2.0, 0.25, 0.03125],
    [2.0, 0.75, 0.0703125],
    [1.75, 1.0, 0.00048828125],
    [1.2265625, 0.9765625, -0.08203125],
    [0.9765625, 1.2265625, -0.033447265625],
    [1.0, 1.75, 0.1162109375],
    [0.75, 2.0, 0.203125],
    [0.25, 2.0, 0.09375],
    [0.0, 1.75, 0.125],
    [0.0, 1.25, 0.375],
    [2.0, 1.25, -0.0546875],
    [2.0, 1.75, -0.34375],
    [1.75, 2.0, -0.28125],
    [1.25, 2.0, 0.078125],
];

/// OpenSubdiv 3.5's level 2 of [`grid`] (triangles) with [`grid_tags`], Loop, uniform,
/// `VTX_BOUNDARY_EDGE_ONLY`: `osd_driver --tags loop 2 FILE edge-only`.
const LOOP_UNIFORM_EDGE_LEVEL2: [[f64; 3]; 81] = [
    [0.109375, 0.109375, 0.08203125],
    [1.0, 0.0, 0.22812499850988388],
    [1.84375, 0.15625, 0.05859375],
    [0.0, 1.0, 0.5],
    [0.9398437533527613, 0.9398437533527613, -0.1143066406948492],
    [2.0, 1.0, 0.04296875],
    [0.15625, 1.84375, 0.13671875],
    [1.0, 2.0, 0.1796875],
    [1.84375, 1.84375, -0.265625],
    [0.5078125, 0.0078125, 0.130859375],
    [0.9949218751862645, 0.4949218751862645, 0.013525390881113708],
    [0.5, 0.5, 0.0234375],
    [0.4921875, 0.9921875, 0.134765625],
    [0.0078125, 0.5078125, 0.255859375],
    [1.484375, 0.015625, 0.130859375],
    [1.984375, 0.515625, 0.0625],
    [1.5, 0.5, 0.09619140625],
    [1.49609375, 0.99609375, -0.068359375],
    [0.99609375, 1.49609375, 0.041015625],
    [0.5, 1.5, 0.2685546875],
    [0.515625, 1.984375, 0.181640625],
    [0.015625, 1.484375, 0.263671875],
    [1.984375, 1.484375, -0.169921875],
    [1.48828125, 1.48828125, -0.18408203125],
    [1.484375, 1.984375, -0.05859375],
    [0.5078125, 0.2578125, 0.052734375],
    [0.75, 0.25, 0.078125],
    [0.7421875, 0.4921875, -0.005859375],
    [0.2578125, 0.5078125, 0.115234375],
    [0.4921875, 0.7421875, 0.056640625],
    [0.25, 0.75, 0.203125],
    [1.5, 0.25, 0.126953125],
    [1.734375, 0.265625, 0.08984375],
    [1.75, 0.5, 0.08984375],
    [1.25, 0.5, 0.0634765625],
    [1.5, 0.75, 0.0244140625],
    [1.2421875, 0.7421875, -0.0341796875],
    [0.5, 1.25, 0.2265625],
    [0.7421875, 1.2421875, 0.080078125],
    [0.75, 1.5, 0.171875],
    [0.25, 1.5, 0.291015625],
    [0.5, 1.75, 0.240234375],
    [0.265625, 1.734375, 0.21484375],
    [1.4921875, 1.2421875, -0.1533203125],
    [1.75, 1.25, -0.1142578125],
    [1.734375, 1.484375, -0.2001953125],
    [1.2421875, 1.4921875, -0.09375],
    [1.484375, 1.734375, -0.138671875],
    [1.25, 1.75, -0.005859375],
    [0.28125, 0.03125, 0.0859375],
    [0.75, 0.0, 0.1875],
    [1.0, 0.25, 0.12363281240686774],
    [0.974218750372529, 0.724218750372529, -0.07705078064464033],
    [0.7265625, 0.7265625, -0.048828125],
    [0.2734375, 0.2734375, 0.064453125],
    [0.71875, 0.96875, -0.0234375],
    [0.25, 1.0, 0.3125],
    [0.0, 0.75, 0.375],
    [0.03125, 0.28125, 0.1484375],
    [1.25, 0.0, 0.1875],
    [1.6875, 0.0625, 0.0859375],
    [1.9375, 0.3125, 0.0546875],
    [2.0, 0.75, 0.0703125],
    [1.75, 0.75, 0.0693359375],
    [1.25, 0.25, 0.150390625],
    [1.75, 1.0, -0.0068359375],
    [1.2265625, 0.9765625, -0.1181640625],
    [0.9765625, 1.2265625, -0.05859375],
    [1.0, 1.75, 0.12890625],
    [0.75, 1.75, 0.22265625],
    [0.25, 1.25, 0.345703125],
    [0.75, 2.0, 0.203125],
    [0.3125, 1.9375, 0.1484375],
    [0.0625, 1.6875, 0.1796875],
    [0.0, 1.25, 0.375],
    [2.0, 1.25, -0.0546875],
    [1.9375, 1.6875, -0.25],
    [1.703125, 1.703125, -0.23046875],
    [1.2265625, 1.2265625, -0.1494140625],
    [1.6875, 1.9375, -0.1875],
    [1.25, 2.0, 0.078125],
];

/// `halfedge`'s last level of `rule` on `polygons` with `tags` and `options`.
fn refine(
    polygons: &PolygonMesh,
    rule: Rule,
    levels: u32,
    tags: &Tags,
    options: SubdivisionOptions,
) -> Result<Vec<[f64; 3]>, Error> {
    let mesh = HalfEdgeMesh::try_from(polygons)?;
    let sharpness = Sharpness::from_tags(&mesh, tags)?;
    let opts = SubdivideOptions::default()
        .with_sharpness(&sharpness)
        .with_subdivision(options);
    let r = Refinement::new(&mesh, rule, levels, &opts)?;
    let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    let mut out = vec![[0.0; 3]; r.n_vertices(levels)];
    r.evaluate(&base, &mut out)?;
    Ok(out)
}

/// Every recorded point has exactly one of `ours` within 1e-12 (the grid's diagonal is 3),
/// each of ours used once.
fn assert_same_points(ours: &[[f64; 3]], recorded: &[[f64; 3]]) {
    assert_eq!(ours.len(), recorded.len());
    let mut used = vec![false; ours.len()];
    for (k, p) in recorded.iter().enumerate() {
        let p = DVec3::from_array(*p);
        let near: Vec<usize> = (0..ours.len())
            .filter(|&i| DVec3::from_array(ours[i]).distance(p) < 1e-12)
            .collect();
        assert_eq!(
            near.len(),
            1,
            "OpenSubdiv vertex {k} at {p}: halfedge vertices {near:?}"
        );
        assert!(
            !std::mem::replace(&mut used[near[0]], true),
            "vertex {} twice",
            near[0]
        );
    }
}

#[test]
fn catmull_clark_creases_give_opensubdivs_recorded_values() {
    let options = SubdivisionOptions::default()
        .with_crease_method(CreaseMethod::Chaikin)
        .with_boundary(BoundaryInterpolation::EdgeAndCorner);
    let ours = refine(&grid(false), Rule::CatmullClark, 2, &grid_tags(), options).expect("refined");
    assert_same_points(&ours, &CATMARK_CHAIKIN_CORNERS_LEVEL2);
    // Without the tags, or with the uniform method, the surface is another one.
    let smooth = refine(
        &grid(false),
        Rule::CatmullClark,
        2,
        &Tags::default(),
        options,
    )
    .expect("refined");
    assert!(smooth.iter().zip(&ours).any(|(a, b)| a != b));
    let uniform = options.with_crease_method(CreaseMethod::Uniform);
    let uniform =
        refine(&grid(false), Rule::CatmullClark, 2, &grid_tags(), uniform).expect("refined");
    assert!(uniform.iter().zip(&ours).any(|(a, b)| a != b));
}

#[test]
fn loop_creases_give_opensubdivs_recorded_values() {
    let options = SubdivisionOptions::default();
    let ours = refine(&grid(true), Rule::Loop, 2, &grid_tags(), options).expect("refined");
    assert_same_points(&ours, &LOOP_UNIFORM_EDGE_LEVEL2);
}

#[test]
fn stencils_and_f32_follow_the_crease_rules() {
    let polygons = grid(false);
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
    let sharpness = Sharpness::from_tags(&mesh, &grid_tags()).expect("resolved");
    let opts = SubdivideOptions::default().with_sharpness(&sharpness);
    let r = Refinement::new(&mesh, Rule::CatmullClark, 3, &opts).expect("refined");
    let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    let mut out = vec![[0.0; 3]; r.n_vertices(3)];
    r.evaluate(&base, &mut out).expect("evaluated");
    let table = r.stencils().expect("stencils");
    let mut again = vec![[0.0; 3]; r.n_vertices(3)];
    table.apply(&base, &mut again).expect("applied");
    let base32: Vec<[f32; 3]> = base.iter().map(|p| p.map(|x| x as f32)).collect();
    let mut single = vec![[0f32; 3]; r.n_vertices(3)];
    r.evaluate(&base32, &mut single).expect("evaluated");
    for ((a, b), c) in out.iter().zip(&again).zip(&single) {
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() < 1e-14, "{a:?} {b:?}");
            assert!((a[k] - f64::from(c[k])).abs() < 1e-5, "{a:?} {c:?}");
        }
    }
    // Every row of the stencils sums to 1 (an affine combination).
    for i in 0..table.len() {
        let (_, weights) = table.row(i);
        assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }
}

/// Nothing sharp (an all-smooth sharpness, options that change nothing on these closed
/// meshes) runs the rules' own kernels: the same bits as a refinement without options.
#[test]
fn without_sharpness_the_fast_path_gives_the_same_bits() {
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("valid");
    let cube = HalfEdgeMesh::try_from(&shapes::cube()).expect("valid");
    for (mesh, rule) in [
        (&ico, Rule::Loop),
        (&cube, Rule::CatmullClark),
        (&ico, Rule::CatmullClark),
    ] {
        let smooth = Sharpness::smooth(mesh);
        let plain = Refinement::new(mesh, rule, 3, &SubdivideOptions::default()).expect("refined");
        let options = SubdivisionOptions::default()
            .with_crease_method(CreaseMethod::Chaikin)
            .with_boundary(BoundaryInterpolation::EdgeAndCorner);
        let opts = SubdivideOptions::default()
            .with_sharpness(&smooth)
            .with_subdivision(options);
        let same = Refinement::new(mesh, rule, 3, &opts).expect("refined");
        let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
        let mut a = vec![[0.0; 3]; plain.n_vertices(3)];
        let mut b = vec![[0.0; 3]; same.n_vertices(3)];
        plain.evaluate(&base, &mut a).expect("evaluated");
        same.evaluate(&base, &mut b).expect("evaluated");
        assert_eq!(a, b, "{rule}");
        assert_eq!(
            plain.heap_bytes(),
            same.heap_bytes(),
            "{rule}: no crease tables"
        );
    }
    // The same mesh with one sharp edge builds crease tables.
    let mut tags = Tags::default();
    tags.add_crease(0, 1, 10.0).expect("valid");
    let sharp = Sharpness::from_tags(&cube, &tags).expect("resolved");
    let opts = SubdivideOptions::default().with_sharpness(&sharp);
    let creased = Refinement::new(&cube, Rule::CatmullClark, 1, &opts).expect("refined");
    let plain = Refinement::new(&cube, Rule::CatmullClark, 1, &SubdivideOptions::default())
        .expect("refined");
    assert_ne!(creased.heap_bytes(), plain.heap_bytes());
}

/// An infinitely sharp crease around a face of a closed cube behaves as a boundary: its edge
/// points are midpoints and its vertices take 3/4, 1/8, 1/8.
#[test]
fn an_infinitely_sharp_crease_is_a_b_spline_curve() {
    let cube = shapes::cube();
    let mesh = HalfEdgeMesh::try_from(&cube).expect("valid");
    let face: Vec<u32> = cube.face(0).to_vec();
    let mut tags = Tags::default();
    for k in 0..4 {
        tags.add_crease(face[k], face[(k + 1) % 4], 10.0)
            .expect("valid");
    }
    let out = refine(
        &cube,
        Rule::CatmullClark,
        1,
        &tags,
        SubdivisionOptions::default(),
    )
    .expect("refined");
    let p = |v: u32| mesh.positions()[v as usize];
    for k in 0..4 {
        let (prev, v, next) = (face[(k + 3) % 4], face[k], face[(k + 1) % 4]);
        let expected = p(v) * 0.75 + (p(prev) + p(next)) * 0.125;
        assert!(DVec3::from_array(out[v as usize]).distance(expected) < 1e-15);
        let mid = (p(v) + p(next)) * 0.5;
        assert!(
            out.iter()
                .any(|q| DVec3::from_array(*q).distance(mid) < 1e-15),
            "edge {v}-{next}"
        );
    }
}

#[test]
fn bad_tags_and_rules_without_creases_are_typed_errors() {
    let cube = HalfEdgeMesh::try_from(&shapes::cube()).expect("valid");
    let mut tags = Tags::default();
    tags.add_crease(0, 9, 1.0).expect("valid sharpness");
    let err = Sharpness::from_tags(&cube, &tags).unwrap_err();
    assert_eq!(
        err.to_string(),
        "crease names vertex 9, but the mesh has 8 vertices"
    );
    let mut tags = Tags::default();
    tags.add_corner(8, 1.0).expect("valid sharpness");
    assert!(matches!(
        Sharpness::from_tags(&cube, &tags),
        Err(Error::TagVertexOutOfRange {
            what: "corner",
            vertex: 8,
            vertices: 8
        })
    ));
    let mut tags = Tags::default();
    tags.add_crease(0, 7, 1.0).expect("valid sharpness");
    assert!(matches!(
        Sharpness::from_tags(&cube, &tags),
        Err(Error::CreaseNotAnEdge { a: 0, b: 7 })
    ));

    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("valid");
    let mut tags = Tags::default();
    let (a, b) = (
        ico.from_vertex(HalfedgeId(0)).0,
        ico.to_vertex(HalfedgeId(0)).0,
    );
    tags.add_crease(a, b, 2.0).expect("valid sharpness");
    let sharp = Sharpness::from_tags(&ico, &tags).expect("resolved");
    let opts = SubdivideOptions::default().with_sharpness(&sharp);
    let err = Refinement::new(&ico, Rule::Butterfly, 1, &opts).unwrap_err();
    assert_eq!(
        err.to_string(),
        "creases apply to Loop and Catmull-Clark, not butterfly (creases and corners given)"
    );
    // A sharpness of another mesh.
    let err = Refinement::new(&cube, Rule::CatmullClark, 1, &opts).unwrap_err();
    assert!(matches!(err, Error::SharpnessMismatch { .. }), "{err}");
    // Smooth triangles are a Catmull-Clark rule: Loop and the others run their own kernels
    // (OpenSubdiv's Loop has no triangle option).
    let smooth = SubdivisionOptions::default().with_triangle_rule(TriangleRule::Smooth);
    let tri = SubdivideOptions::default().with_subdivision(smooth);
    assert!(Refinement::new(&ico, Rule::Loop, 1, &tri).is_ok());
    assert!(Refinement::new(&ico, Rule::Butterfly, 1, &tri).is_ok());
    assert!(Refinement::new(&ico, Rule::CatmullClark, 1, &tri).is_ok());
    // Corners to sharpen under another rule are refused too.
    let grid = HalfEdgeMesh::try_from(&grid(true)).expect("valid");
    let corners = SubdivisionOptions::default().with_boundary(BoundaryInterpolation::EdgeAndCorner);
    let err = Refinement::new(
        &grid,
        Rule::Butterfly,
        1,
        &SubdivideOptions::default().with_subdivision(corners),
    )
    .unwrap_err();
    assert!(matches!(err, Error::CreasesNotSupported { .. }), "{err}");
}

/// Tags numbering the vertices of a file in which some vertex is in no face: resolved through
/// the face list, the later vertices renumbered.
#[test]
fn tags_of_a_file_with_bare_vertices_are_renumbered() {
    let mut polygons = PolygonMesh::with_positions(vec![
        DVec3::ZERO,
        DVec3::new(9.0, 9.0, 9.0),
        DVec3::X,
        DVec3::Y,
    ]);
    polygons.push_face(&[0, 2, 3]);
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
    let mut tags = Tags::default();
    tags.add_crease(2, 3, 1.5).expect("valid");
    tags.add_corner(1, 3.0).expect("valid");
    let sharp = Sharpness::from_tags_of(&polygons, &mesh, &tags).expect("resolved");
    assert_eq!(sharp.n_sharp_edges(), 1);
    assert_eq!(
        sharp.n_sharp_vertices(),
        0,
        "the bare vertex's corner has no effect"
    );
    let mut bad = Tags::default();
    bad.add_crease(0, 1, 1.0).expect("valid");
    assert!(matches!(
        Sharpness::from_tags_of(&polygons, &mesh, &bad),
        Err(Error::CreaseNotAnEdge { a: 0, b: 1 })
    ));
}

/// The weight tables give the same bits on one thread and on several (a grid large enough for
/// the parallel passes).
#[test]
fn crease_rules_do_not_depend_on_the_threads() {
    let polygons = shapes::quad_grid(40, 40).expect("a grid");
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
    let mut tags = Tags::default();
    for i in 0..40 {
        tags.add_crease(20 * 41 + i, 20 * 41 + i + 1, 0.3 + 0.1 * i as f32)
            .expect("valid");
    }
    tags.add_corner(20 * 41 + 20, 1.5).expect("valid");
    let sharpness = Sharpness::from_tags(&mesh, &tags).expect("resolved");
    let chaikin = SubdivisionOptions::default().with_crease_method(CreaseMethod::Chaikin);
    let base: Vec<[f64; 3]> = mesh
        .positions()
        .iter()
        .enumerate()
        .map(|(v, p)| [p.x, p.y, (v as f64 * 0.37).sin()])
        .collect();
    let mut results = Vec::new();
    for threads in [1, 3] {
        let opts = SubdivideOptions::default()
            .with_threads(threads)
            .with_sharpness(&sharpness)
            .with_subdivision(chaikin);
        let r = Refinement::new(&mesh, Rule::CatmullClark, 3, &opts).expect("refined");
        let mut out = vec![[0.0; 3]; r.n_vertices(3)];
        r.evaluate(&base, &mut out).expect("evaluated");
        results.push(out);
    }
    assert_eq!(results[0], results[1]);
}

/// The predicted bytes under crease rules bound what a creased refinement keeps: closely at
/// level 1 when every edge is semi-sharp (every child vertex in a dense weight table, its
/// crease masks blended with the smooth ones), while one crease keeps
/// about what the refinement without it keeps (the flattened tables, the crease's rows over
/// them).
#[test]
fn predicted_crease_bytes_bound_the_refinement() {
    let cases = [
        (bumpy_free_grid(false), Rule::CatmullClark),
        (bumpy_free_grid(true), Rule::Loop),
        (bumpy_free_grid(true), Rule::CatmullClark),
        (shapes::mixed(), Rule::CatmullClark),
        (shapes::icosahedron(), Rule::Loop),
        (shapes::cube(), Rule::CatmullClark),
    ];
    for (polygons, rule) in cases {
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
        let mut one = Tags::default();
        let face = polygons.face(0);
        one.add_crease(face[0], face[1], 1.5).expect("valid");
        let mut every = Tags::default();
        for f in 0..polygons.n_faces() {
            let face = polygons.face(f);
            for (i, &a) in face.iter().enumerate() {
                let b = face[(i + 1) % face.len()];
                // Blended with the smooth masks: rows of their smooth size.
                every.add_crease(a, b, 0.5).expect("valid");
            }
        }
        let one = Sharpness::from_tags(&mesh, &one).expect("resolved");
        let every = Sharpness::from_tags(&mesh, &every).expect("resolved");
        for levels in 1..=3 {
            let bound = Refinement::predicted_bytes_with_creases(rule, &mesh.counts(), levels)
                .expect("bound");
            let plain = Refinement::predicted_bytes(rule, &mesh.counts(), levels).expect("plain");
            let kept = |sharpness: &Sharpness| {
                let opts = SubdivideOptions::default().with_sharpness(sharpness);
                let r = Refinement::new(&mesh, rule, levels, &opts).expect("refined");
                num_bigint::BigInt::from(r.heap_bytes())
            };
            let (one, every) = (kept(&one), kept(&every));
            assert!(bound >= every, "{rule} level {levels}: {bound} < {every}");
            // At level 1 every row of the one table has its smooth size; the next levels are
            // smooth inside (the sharpness has decayed), so their tables are the flattened ones.
            assert!(
                levels > 1 || &bound * 10u32 <= &every * 12u32,
                "{rule} level {levels}: {bound} over {every} by more than 20 %"
            );
            assert!(one <= every, "{rule} level {levels}: {one} > {every}");
            assert!(
                &one * 10u32 <= &plain * 13u32,
                "{rule} level {levels}: one crease {one} over {plain} by more than 30 %"
            );
        }
    }
}

/// A 6 x 6 grid of quads (or triangles), no crease: the meshes of the byte bounds.
fn bumpy_free_grid(triangles: bool) -> PolygonMesh {
    let n = 6u32;
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let positions = (0..(n + 1) * (n + 1))
        .map(|v| DVec3::new(f64::from(v % (n + 1)), f64::from(v / (n + 1)), 0.0))
        .collect();
    let mut mesh = PolygonMesh::with_positions(positions);
    for j in 0..n {
        for i in 0..n {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if triangles {
                mesh.push_face(&[a, b, c]);
                mesh.push_face(&[a, c, d]);
            } else {
                mesh.push_face(&[a, b, c, d]);
            }
        }
    }
    mesh
}

/// The tagged meshes of the one-shot comparison: the recorded grid (quads and triangles), a
/// larger grid with a row of semi-sharp creases (the parallel passes), the cube with a hard
/// edge, a semi-sharp one and a corner, the icosahedron with two creases.
fn tagged_meshes() -> Vec<(&'static str, PolygonMesh, Tags)> {
    let cube_polygons = shapes::cube();
    let c = cube_polygons.face(0).to_vec();
    let mut cube = Tags::default();
    cube.add_crease(c[0], c[1], 10.0).expect("valid");
    cube.add_crease(c[1], c[2], 1.5).expect("valid");
    cube.add_corner(6, 2.5).expect("valid");
    let ico_polygons = shapes::icosahedron();
    let f = ico_polygons.face(0).to_vec();
    let g = ico_polygons.face(7).to_vec();
    let mut ico = Tags::default();
    ico.add_crease(f[0], f[1], 2.25).expect("valid");
    ico.add_crease(g[1], g[2], 0.75).expect("valid");
    let mut big = shapes::quad_grid(40, 40).expect("a grid");
    for (v, p) in big.positions.iter_mut().enumerate() {
        p.z = (v as f64 * 0.37).sin();
    }
    let mut big_tags = Tags::default();
    for i in 0..40 {
        big_tags
            .add_crease(20 * 41 + i, 20 * 41 + i + 1, 0.3 + 0.1 * i as f32)
            .expect("valid");
    }
    big_tags.add_corner(20 * 41 + 20, 1.5).expect("valid");
    let mut big_triangles = PolygonMesh::with_positions(big.positions.clone());
    for face in big.faces() {
        big_triangles.push_face(&[face[0], face[1], face[2]]);
        big_triangles.push_face(&[face[0], face[2], face[3]]);
    }
    vec![
        ("grid", grid(false), grid_tags()),
        ("grid of triangles", grid(true), grid_tags()),
        ("40 x 40 grid", big, big_tags.clone()),
        ("40 x 40 grid of triangles", big_triangles, big_tags),
        ("cube", cube_polygons, cube),
        ("icosahedron", ico_polygons, ico),
    ]
}

/// The one-shot subdivision ([`subdivide_to_face_list`], [`subdivide`], [`verify`]) under
/// crease rules is the refinement's evaluation to the bit, its faces the refinement's index
/// buffers: Loop on the triangle meshes and Catmull-Clark on all, every boundary mode, both
/// crease methods and (Catmull-Clark) both triangle rules, levels 1-3, 1 and 2 threads.
#[test]
fn the_one_shot_subdivision_follows_the_crease_rules_to_the_bit() {
    use halfedge::subdivide::{subdivide, subdivide_to_face_list, verify};
    let mut modes = Vec::new();
    for boundary in [
        BoundaryInterpolation::Edge,
        BoundaryInterpolation::EdgeAndCorner,
    ] {
        for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
            for triangles in [TriangleRule::Catmark, TriangleRule::Smooth] {
                modes.push(
                    SubdivisionOptions::default()
                        .with_boundary(boundary)
                        .with_crease_method(method)
                        .with_triangle_rule(triangles),
                );
            }
        }
    }
    let mut compared = 0;
    for (name, polygons, tags) in tagged_meshes() {
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
        let sharpness = Sharpness::from_tags(&mesh, &tags).expect("resolved");
        let triangles = polygons.faces().all(|f| f.len() == 3);
        let large = polygons.n_faces() > 100;
        let rules: &[Rule] = if triangles {
            &[Rule::Loop, Rule::CatmullClark]
        } else {
            &[Rule::CatmullClark]
        };
        for &rule in rules {
            for &options in &modes {
                if rule == Rule::Loop && options.triangle_rule == TriangleRule::Smooth {
                    continue;
                }
                for levels in 1..=3 {
                    if large && levels == 3 && options != modes[3] {
                        continue;
                    }
                    for threads in [1, 2] {
                        let at =
                            format!("{name} {rule} {options:?} level {levels} threads {threads}");
                        let opts = SubdivideOptions::default()
                            .with_threads(threads)
                            .with_sharpness(&sharpness)
                            .with_subdivision(options);
                        let r = Refinement::new(&mesh, rule, levels, &opts).expect("refined");
                        let base: Vec<[f64; 3]> =
                            mesh.positions().iter().map(|p| p.to_array()).collect();
                        let mut expected = vec![[0.0; 3]; r.n_vertices(levels)];
                        r.evaluate(&base, &mut expected).expect("evaluated");
                        let mut offsets = vec![0u32; r.n_faces(levels) + 1];
                        let mut indices = vec![0u32; r.n_corners(levels)];
                        r.write_polygons(&mut offsets, &mut indices).expect("faces");

                        let level = subdivide_to_face_list(&mesh, rule, levels, &opts)
                            .unwrap_or_else(|e| panic!("{at}: {e}"));
                        let got: Vec<[f64; 3]> =
                            level.mesh.positions.iter().map(|p| p.to_array()).collect();
                        assert!(got == expected, "{at}: face list positions differ");
                        assert_eq!(level.mesh.face_indices(), &indices[..], "{at}: faces");
                        assert_eq!(level.edges, r.n_edges(levels), "{at}: edges");

                        let half = subdivide(&mesh, rule, levels, &opts)
                            .unwrap_or_else(|e| panic!("{at}: {e}"));
                        let got: Vec<[f64; 3]> =
                            half.positions().iter().map(|p| p.to_array()).collect();
                        assert!(got == expected, "{at}: half-edge positions differ");
                        compared += 1;
                    }
                }
            }
        }
        // verify runs the same levels (its reports are the counts, unchanged by creases).
        let rule = rules[0];
        let scheme = rule.scheme_for(&mesh.counts()).expect("a scheme");
        let opts = SubdivideOptions::default().with_sharpness(&sharpness);
        let reports = verify(&mesh, &scheme, 2, &opts).expect("verified");
        assert!(reports.iter().all(|r| r.is_match()), "{name}");
    }
    assert!(compared > 300, "{compared} comparisons");
}

/// The one-shot subdivision refuses crease rules for a rule that has none, as
/// [`Refinement::new`] does, and a sharpness of another mesh.
#[test]
fn the_one_shot_subdivision_refuses_creases_it_cannot_apply() {
    use halfedge::subdivide::{subdivide, subdivide_to_face_list};
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("valid");
    let f = shapes::icosahedron().face(0).to_vec();
    let mut tags = Tags::default();
    tags.add_crease(f[0], f[1], 2.0).expect("valid");
    let sharp = Sharpness::from_tags(&ico, &tags).expect("resolved");
    let opts = SubdivideOptions::default().with_sharpness(&sharp);
    for rule in [Rule::Butterfly, Rule::Sqrt3, Rule::Midpoint, Rule::DooSabin] {
        let err = subdivide(&ico, rule, 1, &opts).unwrap_err();
        assert!(
            matches!(err, Error::CreasesNotSupported { .. }),
            "{rule}: {err}"
        );
        let err = subdivide_to_face_list(&ico, rule, 2, &opts).unwrap_err();
        assert!(
            matches!(err, Error::CreasesNotSupported { .. }),
            "{rule}: {err}"
        );
    }
    let cube = HalfEdgeMesh::try_from(&shapes::cube()).expect("valid");
    let err = subdivide(&cube, Rule::CatmullClark, 1, &opts).unwrap_err();
    assert!(matches!(err, Error::SharpnessMismatch { .. }), "{err}");
}
