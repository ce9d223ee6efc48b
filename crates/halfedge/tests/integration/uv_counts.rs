//! UV layout statistics and UV counts: spot_control_mesh's layout is the one the issue pins,
//! and the UV recurrences give OpenSubdiv's measured value counts (Catmull-Clark on
//! spot_control_mesh, Loop on spot_triangulated); the written faces of a mesh with holes have
//! the layout of the mesh made of them alone.

use std::path::Path;

use halfedge::glam::DVec2;
use halfedge::holes::HoleSet;
use halfedge::uv::Uvs;
use halfedge::{io, shapes, stats, PolygonMesh, Rule};
use schemes::uv::{uv_scheme, UvCounts};
use schemes::BigInt;

/// The mesh of an OBJ file, with its texture coordinates.
fn read_with_uvs(path: &Path) -> PolygonMesh {
    let mesh = io::read_obj(path).unwrap_or_else(|e| panic!("{e}"));
    assert!(mesh.uvs().is_some(), "{}: no uvs", path.display());
    mesh
}

fn values(rule: Rule, uv: &UvCounts, levels: std::ops::RangeInclusive<u64>) -> Vec<BigInt> {
    let scheme = uv_scheme(rule).unwrap_or_else(|e| panic!("{e}"));
    levels
        .map(|s| scheme.values_at(uv, s).unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_control_mesh_has_the_pinned_layout_and_opensubdivs_counts() {
    let mesh = read_with_uvs(&testdata::mesh("spot_control_mesh.obj"));
    let uv = stats::uv_counts(&mesh).expect("spot has UVs");
    let json = serde_json::to_string(&uv).expect("serializes");
    assert_eq!(
        json,
        r#"{"V":267,"E":438,"BE":144,"seam_edges":72,"boundary_loops":13,"charts":13,"unreferenced":0}"#
    );
    assert_eq!((uv.used_vt, uv.faces, uv.corners), (267, 180, 732));
    // OpenSubdiv 3.5's GetNumFVarValues at levels 0-4.
    assert_eq!(
        values(Rule::CatmullClark, &uv, 0..=4),
        [267, 885, 3225, 12297, 48009].map(BigInt::from)
    );
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_triangulated_counts_opensubdivs_loop_values() {
    let mesh = read_with_uvs(&testdata::mesh("spot_triangulated.obj"));
    let uv = stats::uv_counts(&mesh).expect("spot has UVs");
    assert_eq!(
        values(Rule::Loop, &uv, 0..=2),
        [3225, 12297, 48009].map(BigInt::from)
    );
}

/// The cube with every face its own chart (a `vt` per corner): every edge is a seam.
fn cube_of_charts() -> PolygonMesh {
    let mut cube = shapes::cube();
    let coords: Vec<DVec2> = (0..24).map(|i| DVec2::new(f64::from(i), 0.0)).collect();
    cube.set_uvs(Some(Uvs::new(coords, (0..24).collect()).expect("in range")))
        .expect("one vt per corner");
    cube
}

#[test]
fn a_cube_of_separate_charts() {
    let uv = stats::uv_counts(&cube_of_charts()).expect("a layout");
    assert_eq!(
        (uv.values, uv.edges, uv.boundary_edges, uv.seam_edges),
        (24, 24, 24, 12)
    );
    assert_eq!((uv.boundary_loops, uv.charts, uv.unreferenced), (6, 6, 0));
    // Each quad refines on its own: (2^s + 1)^2 values per face.
    let expected: Vec<BigInt> = (0..4u32)
        .map(|s| BigInt::from(6 * (2u64.pow(s) + 1).pow(2)))
        .collect();
    assert_eq!(values(Rule::CatmullClark, &uv, 0..=3), expected);
}

#[test]
fn written_faces_have_the_layout_of_the_mesh_made_of_them() {
    let cube = cube_of_charts();
    let holes = HoleSet::new(cube.n_faces(), [0, 3]).expect("faces of the cube");
    let written = holes.written_uv_counts(&cube).expect("a layout");
    // The four written faces alone, with their vt.
    let kept: Vec<usize> = (0..6).filter(|f| ![0, 3].contains(f)).collect();
    let mut alone = PolygonMesh::from_faces(
        cube.positions.clone(),
        kept.iter().map(|&f| cube.face(f).to_vec()),
    );
    let vts: Vec<u32> = kept
        .iter()
        .flat_map(|&f| (4 * f as u32)..(4 * f as u32 + 4))
        .collect();
    let coords = cube.uvs().expect("uvs").coords().to_vec();
    alone
        .set_uvs(Some(Uvs::new(coords, vts).expect("in range")))
        .expect("one vt per corner");
    assert_eq!(Some(written.clone()), stats::uv_counts(&alone));
    assert_eq!(
        (written.values, written.charts, written.unreferenced),
        (16, 4, 8)
    );
    // No UVs, no layout.
    assert_eq!(holes.written_uv_counts(&shapes::cube()), None);
}
