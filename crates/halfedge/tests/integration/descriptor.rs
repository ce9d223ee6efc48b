//! What a mesh carries from its file (`halfedge::Descriptor`): resolved once by
//! `HalfEdgeMesh::try_from`, refused there with a typed error when it cannot be, and checked
//! against the mesh when a subdivision reads one set by hand.

use halfedge::subdivide::{subdivide_to_face_list, Rule, SubdivideOptions};
use halfedge::tags::BoundaryInterpolation;
use halfedge::{io, shapes, Error, HalfEdgeMesh};

const SQUARES: &str = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
                       f 1 2 5 4\nf 2 3 6 5\n";

#[test]
fn what_the_file_says_is_resolved_on_construction() {
    let text =
        format!("{SQUARES}t crease 2/1/0 1 4 10\nt hole 1/0/0 1\nt interpolateboundary 1/0/0 1\n");
    let file = io::read_obj_from(text.as_bytes(), "squares.obj").expect("reads");
    let mesh = HalfEdgeMesh::try_from(&file).expect("valid");
    let d = mesh.descriptor().expect("tags");
    assert_eq!(d.sharpness.as_ref().map(|s| s.n_sharp_edges()), Some(1));
    assert_eq!(d.holes.as_ref().map(|h| h.faces().to_vec()), Some(vec![1]));
    assert_eq!(d.subdivision.boundary, BoundaryInterpolation::EdgeAndCorner);
    assert!(d.uvs.is_none());
    // Nothing to carry: no descriptor; the faces alone: none either.
    let plain = io::read_obj_from(SQUARES.as_bytes(), "plain.obj").expect("reads");
    assert!(HalfEdgeMesh::try_from(&plain)
        .expect("valid")
        .descriptor()
        .is_none());
    assert!(HalfEdgeMesh::try_from_polygon_mesh(&file)
        .expect("valid")
        .descriptor()
        .is_none());
}

#[test]
fn a_crease_that_is_not_an_edge_never_reaches_the_descriptor() {
    // Vertices 0 and 5 (0-based) share no edge: the reader refuses the tag, naming its line,
    // so `try_from` only ever resolves tags that are edges of the mesh.
    let text = format!("{SQUARES}t crease 2/1/0 0 5 2\n");
    let err = io::read_obj_from(text.as_bytes(), "bad.obj").unwrap_err();
    assert!(err.to_string().contains("line 9"), "{err}");
    assert!(
        err.to_string().contains("vertices 0 and 5 are not an edge"),
        "{err}"
    );
}

#[test]
fn a_descriptor_of_another_mesh_is_refused_when_read() {
    let text = format!("{SQUARES}t crease 2/1/0 1 4 10\n");
    let file = io::read_obj_from(text.as_bytes(), "squares.obj").expect("reads");
    let tagged = HalfEdgeMesh::try_from(&file).expect("valid");
    let mut cube = HalfEdgeMesh::try_from(&shapes::cube()).expect("valid");
    cube.set_descriptor(tagged.descriptor().cloned());
    let opts = SubdivideOptions::default();
    let err = subdivide_to_face_list(&cube, Rule::CatmullClark, 1, &opts).unwrap_err();
    assert!(matches!(err, Error::SharpnessMismatch { .. }), "{err}");
    // Left out, or taken away, it is not read.
    assert!(
        subdivide_to_face_list(&cube, Rule::CatmullClark, 1, &opts.with_descriptor(false)).is_ok()
    );
    cube.set_descriptor(None);
    assert!(subdivide_to_face_list(&cube, Rule::CatmullClark, 1, &opts).is_ok());
}
