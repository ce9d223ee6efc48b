//! Face-varying refinement of UVs (`halfedge::refine::face_varying`) without OpenSubdiv:
//! refused rules, layouts and buffers; value counts against `schemes::uv`'s recurrences
//! (OpenSubdiv's sibling values included); the one-shot face list carrying the refined UVs;
//! holes; linear rules; positions untouched by the channel. `tests/opensubdiv_uv.rs` compares
//! the values with OpenSubdiv.

use halfedge::glam::DVec2;
use halfedge::holes::HoleSet;
use halfedge::refine::Refinement;
use halfedge::subdivide::{subdivide_to_face_list, SubdivideOptions};
use halfedge::tags::{FaceVaryingInterpolation, SubdivisionOptions};
use halfedge::uv::{UvLayout, Uvs};
use halfedge::{io, shapes, stats, Error, HalfEdgeMesh, PolygonMesh, Rule};
use schemes::uv::uv_scheme;
use schemes::BigInt;

/// A `w` x `h` quad grid (or its triangles) whose UVs are not affine, with a seam along the
/// column `x = w / 2`, and at the vertex `(1, 1)` two `vt` used in the order A, B, A, B
/// around it (OpenSubdiv makes three values of them).
fn grid_with_uvs(w: u32, h: u32, triangles: bool) -> PolygonMesh {
    let mut mesh = if triangles {
        shapes::grid(w, h)
    } else {
        shapes::quad_grid(w, h)
    }
    .expect("a grid");
    let id = |i: u32, j: u32| j * (w + 1) + i;
    let n = (w + 1) * (h + 1);
    let mut coords = Vec::new();
    for chart in 0..2 {
        for j in 0..=h {
            for i in 0..=w {
                let (x, y) = (f64::from(i), f64::from(j));
                coords.push(DVec2::new(
                    0.1 * x + 0.01 * x * y + 0.2 * f64::from(chart),
                    0.1 * y + 0.02 * x * x,
                ));
            }
        }
    }
    let (a, b) = (2 * n, 2 * n + 1);
    coords.push(DVec2::new(0.5, 0.5));
    coords.push(DVec2::new(0.7, 0.6));
    let positions = mesh.positions.clone();
    let mut corners = Vec::new();
    for face in mesh.faces() {
        // The face's cell: the lowest corner (each grid face has its cell's lower-left corner).
        let (ci, cj) = face
            .iter()
            .map(|&v| (v % (w + 1), v / (w + 1)))
            .min_by_key(|&(i, j)| (j, i))
            .expect("corners");
        let centre = face.iter().fold(DVec2::ZERO, |acc, &v| {
            acc + positions[v as usize].truncate()
        }) / face.len() as f64;
        for &v in face {
            let (i, j) = (v % (w + 1), v / (w + 1));
            let chart = u32::from(centre.x > f64::from(w / 2));
            if (i, j) == (1, 1) && ci < 2 && cj < 2 {
                // Cells (0, 0) and (1, 1) use A, cells (1, 0) and (0, 1) use B.
                corners.push(if ci == cj { a } else { b });
            } else {
                corners.push(chart * n + id(i, j));
            }
        }
    }
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("a vt per corner");
    mesh
}

fn opts_with<'a>(layout: &'a UvLayout, mode: FaceVaryingInterpolation) -> SubdivideOptions<'a> {
    SubdivideOptions::default()
        .with_uvs(layout)
        .with_subdivision(SubdivisionOptions::default().with_face_varying(mode))
}

/// The UV at every corner of the last level.
fn corner_uvs(r: &Refinement, layout: &UvLayout) -> Vec<[f64; 2]> {
    let levels = r.levels();
    let base: Vec<[f64; 2]> = layout.values().iter().map(|v| v.to_array()).collect();
    let mut uvs = vec![[0.0; 2]; r.n_uvs(levels)];
    r.evaluate_uvs(&base, &mut uvs).expect("evaluated");
    let mut indices = vec![0u32; r.n_corners(levels)];
    r.write_uv_indices(&mut indices).expect("written");
    indices.iter().map(|&i| uvs[i as usize]).collect()
}

#[test]
fn layouts_of_other_meshes_and_missing_uvs_are_refused() {
    let grid = grid_with_uvs(4, 4, true);
    let layout = grid.uv_layout().expect("a layout");
    let mesh = HalfEdgeMesh::try_from(&grid).expect("valid");
    let opts = SubdivideOptions::default().with_uvs(&layout);
    // A layout of another mesh: other corners, or a value at two vertices.
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("valid");
    let err = Refinement::new(&ico, Rule::Loop, 1, &opts).unwrap_err();
    assert!(matches!(err, Error::UvLayoutMismatch { .. }), "{err}");
    let mut rotated: Vec<u32> = Vec::new();
    for face in grid.faces() {
        rotated.extend(face[1..].iter().chain(&face[..1]));
    }
    let wrong = UvLayout::new(&rotated, grid.uvs().expect("uvs"));
    let err = Refinement::new(
        &mesh,
        Rule::Loop,
        1,
        &SubdivideOptions::default().with_uvs(&wrong),
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("the UV layout does not match the mesh: value"),
        "{err}"
    );
    // UVs of a refinement built without them (the mesh's own layout left out).
    let opts = SubdivideOptions::default().with_descriptor(false);
    let plain = Refinement::new(&mesh, Rule::Loop, 1, &opts).expect("ok");
    assert!(!plain.has_uvs());
    assert_eq!(plain.n_uvs(1), 0);
    let err = plain
        .evaluate_uvs(&[[0.0f64; 2]; 3], &mut [[0.0; 2]; 3])
        .unwrap_err();
    assert!(matches!(err, Error::NoUvs), "{err}");
    assert!(matches!(
        plain.write_uv_indices(&mut [0; 3]).unwrap_err(),
        Error::NoUvs
    ));
}

#[test]
fn uv_buffers_of_the_wrong_length_are_refused_naming_them() {
    let grid = grid_with_uvs(4, 3, false);
    let layout = grid.uv_layout().expect("a layout");
    let mesh = HalfEdgeMesh::try_from(&grid).expect("valid");
    let r = Refinement::new(
        &mesh,
        Rule::CatmullClark,
        2,
        &SubdivideOptions::default().with_uvs(&layout),
    )
    .expect("refined");
    let n0 = layout.n_values();
    let n2 = r.n_uvs(2);
    let base = vec![[0.0f32; 2]; n0];
    let mut out = vec![[0.0f32; 2]; n2];
    let err = r.evaluate_uvs(&base[1..], &mut out).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("uv base buffer has {} entries, expected {n0}", n0 - 1)
    );
    let err = r.evaluate_uvs(&base, &mut out[1..]).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("uv out buffer has {} entries, expected {n2}", n2 - 1)
    );
    r.evaluate_uvs(&base, &mut out).expect("f32 evaluates");
    let mut indices = vec![0u32; r.n_corners(2) + 1];
    let err = r.write_uv_indices(&mut indices).unwrap_err();
    assert!(
        matches!(
            err,
            Error::BufferSize {
                what: "uv indices",
                ..
            }
        ),
        "{err}"
    );
}

/// `n_uvs` at levels 1-3 is `schemes::uv`'s prediction on the layout's statistics, for every
/// rule with UVs and every mode (the mode changes values, never their number).
#[test]
fn value_counts_are_the_uv_recurrences() {
    for triangles in [false, true] {
        let grid = grid_with_uvs(5, 4, triangles);
        let layout = grid.uv_layout().expect("a layout");
        let mesh = HalfEdgeMesh::try_from(&grid).expect("valid");
        let uv = stats::uv_counts(&grid).expect("a layout");
        let rules: &[Rule] = if triangles {
            &[
                Rule::Loop,
                Rule::Midpoint,
                Rule::Butterfly,
                Rule::TriSplit(3),
                Rule::CatmullClark,
            ]
        } else {
            &[Rule::CatmullClark]
        };
        for &rule in rules {
            let scheme = uv_scheme(rule).expect("counted");
            for &mode in FaceVaryingInterpolation::ALL {
                let r = Refinement::new(&mesh, rule, 3, &opts_with(&layout, mode)).expect("ok");
                assert_eq!(r.n_uvs(0), layout.n_values());
                for level in 1..=3 {
                    assert_eq!(
                        BigInt::from(r.n_uvs(level)),
                        scheme.values_at(&uv, u64::from(level)).expect("counted"),
                        "{rule} {mode} level {level} (triangles: {triangles})"
                    );
                }
                let mut indices = vec![0u32; r.n_corners(3)];
                r.write_uv_indices(&mut indices).expect("written");
                let mut used = vec![false; r.n_uvs(3)];
                for &i in &indices {
                    used[i as usize] = true;
                }
                assert!(
                    used.iter().all(|&u| u),
                    "{rule} {mode}: every value is used"
                );
            }
        }
    }
}

#[test]
fn the_a_b_a_b_vertex_gives_three_values_as_in_opensubdiv() {
    // 2 x 2 quads, the seam along x = 1: 9 vertices, (1, 0) and (1, 2) with two values, the
    // centre with A and B (12 pairs). OpenSubdiv makes A, B and the second run of B three
    // values at level 1: 6 + 2 * 2 + 3 vertex values, 4 seams of two values and 8 boundary
    // edges of one, 4 faces: 13 + 16 + 4, one more than the pairs give.
    let grid = grid_with_uvs(2, 2, false);
    let layout = grid.uv_layout().expect("a layout");
    assert_eq!(layout.n_values(), 12);
    let mesh = HalfEdgeMesh::try_from(&grid).expect("valid");
    let r = Refinement::new(
        &mesh,
        Rule::CatmullClark,
        2,
        &SubdivideOptions::default().with_uvs(&layout),
    )
    .expect("ok");
    assert_eq!(r.n_uvs(1), 13 + 16 + 4);
    // Level 2 keeps the three centre values (and so 3 more than from the pairs).
    let uv = stats::uv_counts(&grid).expect("a layout");
    let scheme = uv_scheme(Rule::CatmullClark).expect("counted");
    assert_eq!(
        BigInt::from(r.n_uvs(2)),
        scheme.values_at(&uv, 2).expect("ok")
    );
}

/// The one-shot face list carries the refined UVs: per corner the refinement's, to the bit,
/// with holes too; without a layout it has none.
#[test]
fn subdivide_to_face_list_writes_the_refined_uvs() {
    for (triangles, rule) in [
        (false, Rule::CatmullClark),
        (true, Rule::Loop),
        (true, Rule::TriSplit(3)),
    ] {
        let grid = grid_with_uvs(4, 4, triangles);
        let layout = grid.uv_layout().expect("a layout");
        let mesh = HalfEdgeMesh::try_from(&grid).expect("valid");
        let holes = HoleSet::new(mesh.n_faces(), [1, 6]).expect("holes");
        for with_holes in [false, true] {
            let mut opts = opts_with(&layout, FaceVaryingInterpolation::CornersPlus1);
            if with_holes {
                opts = opts.with_holes(&holes);
            }
            let level = subdivide_to_face_list(&mesh, rule, 2, &opts).expect("subdivided");
            let r = Refinement::new(&mesh, rule, 2, &opts).expect("refined");
            let uvs = level.mesh.uvs().expect("the face list has UVs");
            assert_eq!(uvs.coords().len(), r.n_uvs(2), "{rule} holes {with_holes}");
            assert_eq!(uvs.corners().len(), level.mesh.n_corners());
            let ours: Vec<[f64; 2]> = uvs
                .corners()
                .iter()
                .map(|&c| uvs.coords()[c as usize].to_array())
                .collect();
            assert_eq!(ours, corner_uvs(&r, &layout), "{rule} holes {with_holes}");
            // The face list's counts are the written layout's.
            let written = if with_holes {
                holes.written_uv_counts(&grid).expect("a layout")
            } else {
                stats::uv_counts(&grid).expect("a layout")
            };
            let scheme = uv_scheme(rule).expect("counted");
            assert_eq!(
                BigInt::from(r.n_uvs(2)),
                scheme.values_at(&written, 2).expect("counted"),
                "{rule} holes {with_holes}"
            );
            // Positions are those without UVs.
            let mut plain = opts;
            plain.uvs = None;
            plain.descriptor = false;
            let without = subdivide_to_face_list(&mesh, rule, 2, &plain).expect("subdivided");
            assert!(without.mesh.uvs().is_none());
            assert_eq!(without.mesh.positions, level.mesh.positions);
            assert_eq!(without.mesh.face_indices(), level.mesh.face_indices());
        }
    }
}

/// Linear UVs: Loop under `all`, midpoint, butterfly and the icosphere give the same corner
/// UVs (edge midpoints, old values kept); Catmull-Clark under `all` is bilinear.
#[test]
fn linear_rules_put_uvs_on_the_flat_triangles() {
    let grid = grid_with_uvs(3, 3, true);
    let layout = grid.uv_layout().expect("a layout");
    let mesh = HalfEdgeMesh::try_from(&grid).expect("valid");
    let all = opts_with(&layout, FaceVaryingInterpolation::All);
    let reference = corner_uvs(
        &Refinement::new(&mesh, Rule::Midpoint, 2, &all).expect("ok"),
        &layout,
    );
    for rule in [Rule::Loop, Rule::Butterfly] {
        let r = Refinement::new(&mesh, rule, 2, &all).expect("ok");
        let got = corner_uvs(&r, &layout);
        for (a, b) in got.iter().zip(&reference) {
            assert!(
                (a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15,
                "{rule}"
            );
        }
    }
    // Level 1 of the midpoint rule: the middle child of each triangle has the midpoints.
    let r = Refinement::new(&mesh, Rule::Midpoint, 1, &all).expect("ok");
    let got = corner_uvs(&r, &layout);
    let corners = layout.corners();
    let value = |c: usize| layout.values()[corners[c] as usize];
    for f in 0..mesh.n_faces() {
        let (p, q, s) = (value(3 * f), value(3 * f + 1), value(3 * f + 2));
        let mids = [(p + q) / 2.0, (q + s) / 2.0, (s + p) / 2.0];
        // Each child uv is a parent value or a midpoint of two.
        for k in 0..12 {
            let uv = DVec2::from(got[12 * f + k]);
            let known = [p, q, s]
                .iter()
                .chain(&mids)
                .any(|m| m.distance(uv) < 1e-15);
            assert!(known, "face {f} child corner {k}: {uv}");
        }
    }
}

#[test]
fn positions_do_not_depend_on_the_uvs() {
    let grid = grid_with_uvs(4, 4, false);
    let layout = grid.uv_layout().expect("a layout");
    let mesh = HalfEdgeMesh::try_from(&grid).expect("valid");
    let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    let with = Refinement::new(
        &mesh,
        Rule::CatmullClark,
        2,
        &SubdivideOptions::default().with_uvs(&layout),
    )
    .expect("ok");
    let plain = SubdivideOptions::default().with_descriptor(false);
    let without = Refinement::new(&mesh, Rule::CatmullClark, 2, &plain).expect("ok");
    // The mesh carries its layout: the default options refine it.
    let carried =
        Refinement::new(&mesh, Rule::CatmullClark, 2, &SubdivideOptions::default()).expect("ok");
    assert!(carried.has_uvs() && !without.has_uvs());
    let mut a = vec![[0.0; 3]; with.n_vertices(2)];
    let mut b = vec![[0.0; 3]; without.n_vertices(2)];
    with.evaluate(&base, &mut a).expect("ok");
    without.evaluate(&base, &mut b).expect("ok");
    assert_eq!(a, b);
    assert!(with.heap_bytes() > without.heap_bytes());
}

/// Every shared mesh with `vt`: the refinement's value counts at levels 1-2 are
/// `schemes::uv`'s (which the OpenSubdiv comparisons pin to OpenSubdiv's).
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn shared_meshes_value_counts_are_the_uv_recurrences() {
    for (file, rule) in [
        ("spot_control_mesh.obj", Rule::CatmullClark),
        ("spot_triangulated.obj", Rule::Loop),
        ("blub_control_mesh.obj", Rule::CatmullClark),
        ("cylinder_ngon.obj", Rule::CatmullClark),
        ("osd_catmark_bishop.obj", Rule::CatmullClark),
        ("osd_catmark_pawn.obj", Rule::CatmullClark),
        ("osd_loop_icosahedron.obj", Rule::Loop),
        ("osd_loop_icosahedron.obj", Rule::Butterfly),
    ] {
        let path = testdata::mesh(file);
        let polygons = io::read_obj(&path).unwrap_or_else(|e| panic!("{e}"));
        let layout = polygons.uv_layout().expect("vt on every corner");
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
        let uv = stats::uv_counts(&polygons).expect("a layout");
        let scheme = uv_scheme(rule).expect("counted");
        let r = Refinement::new(
            &mesh,
            rule,
            2,
            &SubdivideOptions::default().with_uvs(&layout),
        )
        .expect("refined");
        for level in 1..=2 {
            assert_eq!(
                BigInt::from(r.n_uvs(level)),
                scheme.values_at(&uv, u64::from(level)).expect("counted"),
                "{file} {rule} level {level}"
            );
        }
    }
}
