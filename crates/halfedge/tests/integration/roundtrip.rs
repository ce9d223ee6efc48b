//! Writing OBJ and reading it back; atomic file output.

use halfedge::{io, shapes, HalfEdgeMesh};

fn temp_dir(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("halfedge-test-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn every_shape_survives_a_round_trip_exactly() {
    for name in [
        "tetrahedron",
        "octahedron",
        "icosahedron",
        "cube",
        "torus:2",
        "icosahedron-holes:3",
        "grid:3x2",
        "quad-grid:2x5",
        "mixed",
    ] {
        let polygons = shapes::from_name(name).expect("shape");
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
        let mut text = Vec::new();
        io::write_obj(&mesh, &mut text).expect("write");
        let back = io::read_obj_from(text.as_slice(), name).expect("read back");
        // Same positions bit for bit, same faces in the same order.
        assert_eq!(back, mesh.to_polygon_mesh(), "{name}");
        assert_eq!(
            back, polygons,
            "{name}: shapes use every vertex, so numbering is kept"
        );
        assert_eq!(
            HalfEdgeMesh::try_from(&back).expect("valid").counts(),
            mesh.counts()
        );
    }
}

#[test]
fn off_files_read_like_obj() {
    let dir = temp_dir("off");
    let path = dir.join("square.OFF");
    std::fs::write(
        &path,
        "OFF\n# a comment\n4 1 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
    )
    .expect("write");
    let polygons = io::read_mesh(&path).expect("read");
    assert_eq!(polygons.face(0), &[0, 1, 2, 3]);
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
    assert_eq!(mesh.counts().boundary_edges, 4);
    std::fs::remove_dir_all(&dir).expect("cleanup");
}
