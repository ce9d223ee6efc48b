//! The memory of the UV channel: [`memory::predicted_uv_bytes`] of the layout's statistics
//! ([`stats::uv_layout_counts`]) against what a [`Refinement`] with UVs keeps on the heap
//! beyond the same refinement without them, plus the caller's buffers (the last level's values
//! and corner indices).
//!
//! Tolerance: the prediction is at least what is measured (the channel's heap and the
//! caller's buffers) and at most four times it: it also counts the evaluation's intermediate
//! levels and whole last level, the merged numbering and the corner buffer it is built from,
//! the channel's base (the layout as a face list and a half-edge mesh, and the arrays that
//! build the latter: the peak at low levels) (freed or transient, so not in `heap_bytes`),
//! and bounds the crease tables by the dense
//! weight table of every child vertex (what a channel whose every edge is sharp keeps), where
//! a channel whose only sharp edges are its boundary keeps the flattened Loop or Catmull-Clark
//! tables and the rows of its corners.

use halfedge::glam::{DVec2, DVec3};
use halfedge::memory::predicted_uv_bytes;
use halfedge::subdivide::SubdivideOptions;
use halfedge::uv::Uvs;
use halfedge::{io, stats, BigInt, HalfEdgeMesh, PolygonMesh, Refinement, Rule};

/// The measured bytes of the UV channel of `rule` at `levels` on `poly` (the heap the channel
/// adds and the caller's `f64` values and corner indices), and the prediction.
fn measured_and_predicted(poly: &PolygonMesh, rule: Rule, levels: u32) -> (BigInt, BigInt) {
    let mesh = HalfEdgeMesh::try_from(poly).expect("manifold");
    let layout = poly.uv_layout().expect("a layout");
    // Without the layout the mesh carries (its descriptor): the channel's bytes alone.
    let opts = SubdivideOptions::default().with_descriptor(false);
    let plain = Refinement::new(&mesh, rule, levels, &opts).expect("refines");
    let with = Refinement::new(&mesh, rule, levels, &opts.with_uvs(&layout)).expect("refines");
    let channel = with.heap_bytes() - plain.heap_bytes();
    let buffers = 16 * with.n_uvs(levels) + 4 * with.n_corners(levels);
    let counts = stats::uv_layout_counts(poly).expect("layout counts");
    let predicted = predicted_uv_bytes(rule, &counts, levels, 8, false).expect("predicted");
    (BigInt::from(channel + buffers), predicted)
}

fn assert_within(name: &str, rule: Rule, levels: u32, measured: &BigInt, predicted: &BigInt) {
    println!("{name} {rule} level {levels}: measured {measured}, predicted {predicted}");
    assert!(
        predicted >= measured,
        "{name} {rule} {levels}: {predicted} < {measured}"
    );
    assert!(
        *predicted <= measured * 4u32,
        "{name} {rule} {levels}: {predicted} > 4 x {measured}"
    );
}

/// A `w` x `h` grid of quads (or triangles) cut into four charts by a seam along the middle
/// column and one along the middle row: each vertex on a seam has one value per chart.
fn grid_of_four_charts(w: u32, h: u32, triangles: bool) -> PolygonMesh {
    let id = |x: u32, y: u32| y * (w + 1) + x;
    let positions: Vec<DVec3> = (0..(w + 1) * (h + 1))
        .map(|i| DVec3::new(f64::from(i % (w + 1)), f64::from(i / (w + 1)), 0.0))
        .collect();
    let n = positions.len() as u32;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let chart = u32::from(x >= w / 2) + 2 * u32::from(y >= h / 2);
            let quad = [id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1)];
            let split: Vec<Vec<u32>> = if triangles {
                vec![
                    vec![quad[0], quad[1], quad[2]],
                    vec![quad[0], quad[2], quad[3]],
                ]
            } else {
                vec![quad.to_vec()]
            };
            for face in split {
                corners.extend(face.iter().map(|&v| chart * n + v));
                faces.push(face);
            }
        }
    }
    let coords: Vec<DVec2> = (0..4 * n)
        .map(|t| {
            let v = t % n;
            DVec2::new(f64::from(v % (w + 1)), f64::from(v / (w + 1)))
        })
        .collect();
    let mut mesh = PolygonMesh::from_faces(positions, faces);
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("one vt per corner");
    mesh
}

#[test]
fn the_uv_prediction_bounds_the_channel_on_a_grid_with_seams() {
    let quads = grid_of_four_charts(12, 8, false);
    let triangles = grid_of_four_charts(12, 8, true);
    let uv = stats::uv_counts(&quads).expect("a layout");
    assert_eq!(uv.seam_edges, 8 + 12);
    // The layout as a mesh of its own has the layout's V, E and BE.
    let layout = stats::uv_layout_counts(&quads).expect("layout counts");
    assert_eq!(
        (layout.vertices, layout.edges, layout.boundary_edges),
        (uv.values, uv.edges, uv.boundary_edges)
    );
    assert_eq!(uv.values, 13 * 9 + 9 + 13 + 1);
    for (name, poly, rule) in [
        ("quads", &quads, Rule::CatmullClark),
        ("triangles", &triangles, Rule::Loop),
        ("triangles", &triangles, Rule::Midpoint),
        ("triangles", &triangles, Rule::TriSplit(3)),
    ] {
        for levels in 1..=3 {
            let (measured, predicted) = measured_and_predicted(poly, rule, levels);
            assert_within(name, rule, levels, &measured, &predicted);
        }
    }
}

/// The corner channel's estimate (Doo-Sabin, mid-edge, √3 on the triangles) against the channel's heap and the
/// caller's buffers: at least it, at most three times it (it also counts the surface
/// refinement the one-shot path builds, and sizes the values from the extreme layouts;
/// measured 1.6 to 2.6 times).
#[test]
fn the_corner_channel_estimate_is_near_what_it_keeps() {
    for (name, poly) in [
        ("quads", grid_of_four_charts(12, 8, false)),
        ("triangles", grid_of_four_charts(12, 8, true)),
    ] {
        let mut rules = vec![Rule::DooSabin, Rule::MidEdge];
        if name == "triangles" {
            rules.push(Rule::Sqrt3);
        }
        for rule in rules {
            for levels in 1..=3 {
                let (measured, predicted) = measured_and_predicted(&poly, rule, levels);
                println!(
                    "{name} {rule} level {levels}: measured {measured}, predicted {predicted}"
                );
                assert!(predicted >= measured, "{name} {rule} {levels}");
                assert!(predicted <= &measured * 3u32, "{name} {rule} {levels}");
            }
        }
    }
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn the_uv_prediction_bounds_the_channel_on_spot() {
    for (file, rule, levels) in [
        ("spot_control_mesh.obj", Rule::CatmullClark, 3),
        ("spot_quadrangulated.obj", Rule::CatmullClark, 3),
        ("spot_triangulated.obj", Rule::Loop, 2),
    ] {
        let poly = io::read_obj(testdata::mesh(file)).unwrap_or_else(|e| panic!("{e}"));
        let (measured, predicted) = measured_and_predicted(&poly, rule, levels);
        assert_within(file, rule, levels, &measured, &predicted);
    }
}
