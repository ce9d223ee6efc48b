//! Every invalid-input error path, each with a tiny OBJ text and its exact message.

use halfedge::{io, Error, HalfEdgeMesh};

/// Reads `text` as `t.obj`, builds the half-edge mesh and asserts the error message.
fn check(text: &str, expected: &str) {
    let result =
        io::read_obj_from(text.as_bytes(), "t.obj").and_then(|p| HalfEdgeMesh::try_from(&p));
    match result {
        Ok(mesh) => panic!("accepted ({} faces), expected: {expected}", mesh.n_faces()),
        Err(e) => assert_eq!(e.to_string(), expected),
    }
}

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn parse_errors_name_file_and_line() {
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 40\n",
        "t.obj: line 4: face index 40 is out of range (the file has 3 vertices)",
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n",
        "t.obj: line 4: face index -4 is out of range (the file has 3 vertices)",
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
        "t.obj: line 4: face index 0 is not valid (OBJ indices start at 1)",
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x3\n",
        "t.obj: line 4: `x3` is not a valid vertex index",
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 /3\n",
        "t.obj: line 4: `` is not a valid vertex index",
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n",
        "t.obj: line 4: face index `99999999999999999999999` is too large",
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967296\n",
        "t.obj: line 4: face index `4294967296` is too large",
    );
    check(
        "v 0 0 0\nv 1 0 0\nf 1 2\n",
        "t.obj: line 3: face has 2 vertices, at least 3 are needed",
    );
    check(
        "v 0 0 0\nf 1\n",
        "t.obj: line 2: face has 1 vertices, at least 3 are needed",
    );
    check(
        "v 0 0 0\nv 1 zero 0\n",
        "t.obj: line 2: `zero` is not a valid coordinate",
    );
    check(
        "v 0 0 0\nv 1 nan 0\n",
        "t.obj: line 2: coordinate `nan` is not finite",
    );
    check(
        "v 0 0 0\nv 1 0 -inf\n",
        "t.obj: line 2: coordinate `-inf` is not finite",
    );
    check(
        "v 0 0\n",
        "t.obj: line 1: vertex has 2 coordinates, expected 3",
    );
    check("# nothing\n\n", "t.obj: the file has no faces");
    check("", "t.obj: the file has no faces");
    check(
        "v 0 0 0\nv 1 0 0\n\x00\x01\x7fELF\x02\n",
        "t.obj: line 3: not a text line (binary data?)",
    );
    let err = io::read_obj_from(&b"v 0 0 0\nv 1 0 0\nf 1 2 \xff\xfe\n"[..], "t.obj").unwrap_err();
    assert_eq!(
        err.to_string(),
        "t.obj: line 3: not a text line (binary data?)"
    );
    // A forward reference is fine while the vertex exists by the end of the file.
    check(
        "f 1 2 5\nv 0 0 0\nv 1 0 0\nv 0 1 0\n",
        "t.obj: line 1: face index 5 is out of range (the file has 3 vertices)",
    );
}

#[test]
fn validation_errors_name_face_vertex_edge() {
    check(
        &format!("{SQUARE}f 1 2 3\nf 1 2 1\n"),
        "face 1 (vertices 0, 1, 0) repeats vertex 0",
    );
    check(
        &format!("{SQUARE}v 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n"),
        "edge (0, 1) is shared by 3 faces (0, 1, 2): non-manifold edge",
    );
    check(
        &format!("{SQUARE}f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\nf 1 2 4\n"),
        "faces 2 and 4 have the same vertices (0, 3, 1)",
    );
    check(
        &format!("{SQUARE}f 1 2 3\nf 1 4 3\n"),
        "faces 0 and 1 both use edge 2 -> 0 in the same direction: inconsistent orientation (flip one of them)",
    );
    // Two fans at vertex 1 (index 0): a bow-tie.
    check(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n",
        "vertex 0 is non-manifold: its faces form 2 separate fans",
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e309 0 0\nf 1 2 3\n",
        "t.obj: line 4: coordinate `1e309` is not finite",
    );
}

#[test]
fn non_finite_coordinates_in_a_face_list_are_refused() {
    use glam::DVec3;
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(f64::NAN, 0.0, 1.0)];
    let err = HalfEdgeMesh::try_from_polygons(p, &[[0, 1, 2]]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "vertex 2 has a non-finite coordinate (NaN, 0, 1)"
    );
}

/// A Moebius strip (5 triangles around a half-twisted band) cannot be oriented; a flipped
/// face in an orientable mesh is reported as inconsistent orientation instead.
#[test]
fn non_orientable_is_told_from_flipped() {
    // Moebius strip: a band of 6 vertices 0..5, quads (i, i+1, i+4, i+3 mod 6) with a twist.
    let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
                f 1 2 5\nf 1 5 4\nf 2 3 6\nf 2 6 5\nf 3 4 6\nf 6 4 1\n";
    let polygons = io::read_obj_from(text.as_bytes(), "moebius.obj").expect("parses");
    match HalfEdgeMesh::try_from(&polygons) {
        Err(Error::NonOrientable { .. }) => {}
        other => panic!("expected NonOrientable, got {other:?}"),
    }
    let flipped = format!("{SQUARE}f 1 2 3\nf 1 4 3\n");
    let polygons = io::read_obj_from(flipped.as_bytes(), "flipped.obj").expect("parses");
    assert!(matches!(
        HalfEdgeMesh::try_from(&polygons),
        Err(Error::InconsistentOrientation {
            a: 2,
            b: 0,
            first: 0,
            second: 1
        })
    ));
}

#[test]
fn unknown_extension_and_missing_file() {
    let err = io::read_mesh("mesh.stl").unwrap_err();
    assert_eq!(
        err.to_string(),
        "mesh.stl: unknown mesh format (expected .obj, .off or .ply)"
    );
    let err = io::read_mesh("/nonexistent/dir/mesh.obj").unwrap_err();
    assert!(matches!(err, Error::Io { .. }));
    assert!(
        err.to_string().starts_with("/nonexistent/dir/mesh.obj: "),
        "{err}"
    );
}
