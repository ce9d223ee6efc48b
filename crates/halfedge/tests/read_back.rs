//! Issue 30: the readers (OBJ read in place, binary PLY read a record at a time) read back
//! exactly what the writers write: the same positions to the bit, the same faces, the same
//! texture coordinates per corner, from OBJ and from PLY; and what they read from the shared
//! meshes is what a plain reference reader of `v` and `f` lines reads.

use halfedge::io::{self, ObjWriteOptions, ReadOptions};
use halfedge::subdivide::{subdivide_to_face_list, SubdivideOptions};
use halfedge::{shapes, HalfEdgeMesh, PolygonMesh, Rule};

/// Positions to the bit, faces, and the texture coordinate of every corner.
fn assert_same(a: &PolygonMesh, b: &PolygonMesh, what: &str) {
    let bits = |m: &PolygonMesh| -> Vec<[u64; 3]> {
        m.positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect()
    };
    assert_eq!(bits(a), bits(b), "{what}: positions");
    assert_eq!(a.face_offsets(), b.face_offsets(), "{what}: faces");
    assert_eq!(a.face_indices(), b.face_indices(), "{what}: corners");
    let corner_uvs = |m: &PolygonMesh| {
        m.uvs().map(|uvs| {
            let corners = uvs.corners().iter();
            corners
                .map(|&c| uvs.coords()[c as usize].to_array().map(f64::to_bits))
                .collect::<Vec<_>>()
        })
    };
    assert_eq!(corner_uvs(a), corner_uvs(b), "{what}: texture coordinates");
}

/// Writes `mesh` as OBJ and as PLY, reads both back and compares them with it.
fn round_trip(mesh: &PolygonMesh, what: &str) {
    let options = ObjWriteOptions::default();
    let mut obj = Vec::new();
    io::write_polygon_obj(mesh, &mut obj).expect("OBJ written");
    let from_obj = io::read_obj_from(obj.as_slice(), "back.obj").expect("OBJ read back");
    assert_same(mesh, &from_obj, &format!("{what} (OBJ)"));
    let mut ply = Vec::new();
    io::write_polygon_ply(mesh, &mut ply, &options).expect("PLY written");
    let from_ply = io::read_ply_from(ply.as_slice(), "back.ply").expect("PLY read back");
    assert_same(mesh, &from_ply, &format!("{what} (PLY)"));
    assert_same(&from_obj, &from_ply, &format!("{what} (OBJ and PLY)"));
}

#[test]
fn generated_meshes_written_read_back_to_the_same_mesh() {
    for (name, rule) in [
        ("icosahedron", Rule::Loop),
        ("torus:2", Rule::Loop),
        ("mixed", Rule::CatmullClark),
        ("quad-grid:3x5", Rule::CatmullClark),
    ] {
        let base = shapes::from_name(name).expect("shape");
        round_trip(&base, name);
        let half_edge = HalfEdgeMesh::try_from(&base).expect("manifold");
        for levels in 1..=3 {
            let level =
                subdivide_to_face_list(&half_edge, rule, levels, &SubdivideOptions::default())
                    .expect("subdivided");
            round_trip(&level.mesh, &format!("{name} level {levels}"));
        }
    }
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn obj_and_ply_written_read_back_to_the_same_mesh() {
    for name in [
        "armadillo.obj",
        "spot_control_mesh.obj",
        "osd_catmark_pawn.obj",
        "cylinder_ngon.obj",
        "osd_catmark_nonquads.obj",
    ] {
        let path = testdata::mesh(name);
        let base = io::read_mesh_with(&path, &ReadOptions::default()).expect("shared mesh");
        round_trip(&base, name);
        // A subdivided level: coordinates of 16 and 17 significant digits, every kind of
        // float the reader reads in place.
        let half_edge = HalfEdgeMesh::try_from(&base).expect("manifold");
        let rule = if base.faces().all(|f| f.len() == 3) {
            Rule::Loop
        } else {
            Rule::CatmullClark
        };
        let level = subdivide_to_face_list(&half_edge, rule, 1, &SubdivideOptions::default())
            .expect("subdivided");
        round_trip(&level.mesh, &format!("{name} level 1"));
    }
}

/// The shared meshes' `v` and `f` lines read by a plain reference (split, `str::parse`)
/// give the mesh the reader gives.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn shared_meshes_read_as_a_plain_reference_reads_them() {
    let mut read = 0;
    for entry in std::fs::read_dir(testdata::meshes_dir()).expect("shared meshes") {
        let path = entry.expect("entry").path();
        if path.extension().and_then(|e| e.to_str()) != Some("obj") {
            continue;
        }
        let mesh = io::read_mesh_with(&path, &ReadOptions::default()).expect("readable");
        let text = std::fs::read_to_string(&path).expect("text");
        let (mut positions, mut faces) = (Vec::new(), Vec::new());
        let mut joined = String::new();
        for line in text.lines() {
            let line = line.split('#').next().unwrap_or("").trim_end();
            if let Some(head) = line.strip_suffix('\\') {
                joined.push_str(head);
                joined.push(' ');
                continue;
            }
            joined.push_str(line);
            let words: Vec<&str> = joined.split_ascii_whitespace().collect();
            match words.first() {
                Some(&"v") => {
                    let p: Vec<f64> = words[1..4].iter().map(|w| w.parse().unwrap()).collect();
                    positions.push([p[0].to_bits(), p[1].to_bits(), p[2].to_bits()]);
                }
                Some(&"f") => {
                    let face: Vec<u32> = words[1..]
                        .iter()
                        .map(|w| {
                            let i: i64 = w.split('/').next().unwrap().parse().unwrap();
                            let count = positions.len() as i64;
                            (if i < 0 { count + i } else { i - 1 }) as u32
                        })
                        .collect();
                    faces.push(face);
                }
                _ => {}
            }
            joined.clear();
        }
        let bits: Vec<[u64; 3]> = mesh
            .positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect();
        let name = path.display();
        assert_eq!(bits, positions, "{name}");
        let got: Vec<Vec<u32>> = mesh.faces().map(<[u32]>::to_vec).collect();
        assert_eq!(got, faces, "{name}");
        read += 1;
    }
    assert!(read > 10, "{read} meshes");
}
