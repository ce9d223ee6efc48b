//! Texture coordinates through the OBJ reader and writer: spot_control_mesh's 267 `vt` and
//! its pinned UV layout, the same mesh written with negative indices, every shared mesh's
//! corners against tobj's texture-coordinate indices, and meshes with UVs (and normals)
//! written by us and read back by tobj, the independent reader, and by ours.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use halfedge::glam::{DVec2, DVec3};
use halfedge::io::{self, FaceBuffers, ObjWriteOptions, UvBuffers};
use halfedge::uv::Uvs;
use halfedge::{normals, shapes, stats, PolygonMesh};
use testdata::{mesh, meshes_dir};

/// A temporary file path for this test process.
fn temp_obj(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("halfedge-uv-io-{}-{name}.obj", std::process::id()))
}

fn close(a: f64, b: f32, what: &str) {
    let b = f64::from(b);
    assert!(
        (a - b).abs() <= 1e-6 * b.abs().max(1.0),
        "{what}: {a} against {b}"
    );
}

/// `ours` and `theirs` index the same corners one to one (tobj numbers each attribute in
/// order of first use, so the numbers differ but the pattern of equal ones does not).
fn same_pattern(ours: &[u32], theirs: &[u32], what: &str) {
    assert_eq!(ours.len(), theirs.len(), "{what}: corners");
    let (mut there, mut back) = (HashMap::new(), HashMap::new());
    for (corner, (&a, &b)) in ours.iter().zip(theirs).enumerate() {
        assert_eq!(*there.entry(a).or_insert(b), b, "{what}: corner {corner}");
        assert_eq!(*back.entry(b).or_insert(a), a, "{what}: corner {corner}");
    }
}

/// Reads `path` with tobj (polygons kept, an index per attribute) as one model, and checks
/// it against what was written, corner by corner: the faces' degrees, each corner's
/// position, UV value and (when `normals` is given) the normal of its vertex, and that the
/// indices of each attribute are ours renumbered (the `vn` index the vertex's).
fn check_with_tobj(
    path: &Path,
    positions: &[DVec3],
    faces: &[Vec<u32>],
    uv: Option<(&[DVec2], &[u32])>,
    normals: Option<&[DVec3]>,
) {
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(models.len(), 1);
    let m = &models[0].mesh;
    let arities: Vec<u32> = if m.face_arities.is_empty() {
        vec![3; m.indices.len() / 3]
    } else {
        m.face_arities.clone()
    };
    let degrees: Vec<u32> = faces.iter().map(|f| f.len() as u32).collect();
    assert_eq!(arities, degrees);
    let corners: Vec<u32> = faces.iter().flatten().copied().collect();
    same_pattern(&corners, &m.indices, "vertices");
    for (&v, &t) in corners.iter().zip(&m.indices) {
        let theirs = &m.positions[3 * t as usize..3 * t as usize + 3];
        for (a, b) in positions[v as usize].to_array().into_iter().zip(theirs) {
            close(a, *b, "position");
        }
    }
    match uv {
        Some((values, vts)) => {
            same_pattern(vts, &m.texcoord_indices, "texture coordinates");
            for (&ours, &t) in vts.iter().zip(&m.texcoord_indices) {
                let a = values[ours as usize];
                close(a.x, m.texcoords[2 * t as usize], "u");
                close(a.y, m.texcoords[2 * t as usize + 1], "v");
            }
        }
        None => assert!(m.texcoord_indices.is_empty() && m.texcoords.is_empty()),
    }
    match normals {
        Some(normals) => {
            same_pattern(&corners, &m.normal_indices, "normals");
            for (&v, &t) in corners.iter().zip(&m.normal_indices) {
                let theirs = &m.normals[3 * t as usize..3 * t as usize + 3];
                for (a, b) in normals[v as usize].to_array().into_iter().zip(theirs) {
                    close(a, *b, "normal");
                }
            }
        }
        None => assert!(m.normal_indices.is_empty() && m.normals.is_empty()),
    }
}

/// A torus of 4 x 3 quads with a UV seam around each way (the grid's values repeat at
/// the last row and column), two `vt` no corner uses and one `vt` shared by two vertices.
fn seamed_torus() -> PolygonMesh {
    let (n, m) = (4u32, 3u32);
    let mut positions = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (a, b) = (
                std::f64::consts::TAU * f64::from(i) / f64::from(n),
                std::f64::consts::TAU * f64::from(j) / f64::from(m),
            );
            let r = 2.0 + b.cos();
            positions.push(DVec3::new(r * a.cos(), r * a.sin(), b.sin()));
        }
    }
    let vertex = |i: u32, j: u32| (i % n) * m + j % m;
    let value = |i: u32, j: u32| i * (m + 1) + j;
    let mut faces = Vec::new();
    let mut vts = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            faces.push(quad.map(|(a, b)| vertex(a, b)));
            vts.extend(quad.map(|(a, b)| value(a, b)));
        }
    }
    // Corner (0, 0) of the first face uses the vt of (1, 1): one vt at two vertices.
    vts[0] = value(1, 1);
    let mut coords: Vec<DVec2> = (0..=n)
        .flat_map(|i| (0..=m).map(move |j| DVec2::new(f64::from(i) / 4.0, f64::from(j) / 3.0)))
        .collect();
    coords.extend([DVec2::splat(9.0), DVec2::splat(-9.0)]);
    let mut mesh = PolygonMesh::from_faces(positions, faces);
    mesh.set_uvs(Some(Uvs::new(coords, vts).expect("in range")))
        .expect("a vt per corner");
    mesh
}

fn faces_of(mesh: &PolygonMesh) -> Vec<Vec<u32>> {
    mesh.faces().map(<[u32]>::to_vec).collect()
}

/// Writes `mesh` with `options`, reads it back with tobj and with our reader.
fn round_trip(mesh: &PolygonMesh, name: &str) {
    let faces = faces_of(mesh);
    let uvs = mesh.uvs().expect("uvs");
    let computed = normals::vertex_normals(&mesh.positions, mesh.faces());
    for (options, tag) in [
        (ObjWriteOptions::default(), "uvs"),
        (ObjWriteOptions::default().with_normals(true), "uvs-normals"),
        (
            ObjWriteOptions::default()
                .with_uvs(false)
                .with_normals(true),
            "normals",
        ),
        (ObjWriteOptions::default().with_uvs(false), "plain"),
    ] {
        let path = temp_obj(&format!("{name}-{tag}"));
        let file = std::fs::File::create(&path).unwrap_or_else(|e| panic!("{e}"));
        io::write_polygon_obj_with(mesh, file, &options).unwrap_or_else(|e| panic!("{e}"));
        let uv = options.uvs.then(|| (uvs.coords(), uvs.corners()));
        let n = options.normals.then_some(computed.as_slice());
        check_with_tobj(&path, &mesh.positions, &faces, uv, n);
        // Our reader gives back the same mesh, UVs included, to the bit.
        let back = io::read_obj(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back.positions, mesh.positions, "{tag}");
        assert_eq!(back.face_indices(), mesh.face_indices(), "{tag}");
        assert_eq!(back.uvs(), options.uvs.then_some(uvs), "{tag}");
        std::fs::remove_file(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn a_seamed_torus_round_trips_through_tobj() {
    let torus = seamed_torus();
    let uv = stats::uv_counts(&torus).expect("a layout");
    // 19 of the 20 grid values (the first corner gave up (0, 0)) and the vt of (1, 1) at
    // vertex 0: 20 values; unused, the two extra vt and the one of (0, 0).
    assert_eq!((uv.values, uv.unreferenced), (20, 3));
    round_trip(&torus, "torus");
    // A mesh without uvs is written without vt, whatever the options say.
    let cube = shapes::cube();
    let path = temp_obj("cube");
    let file = std::fs::File::create(&path).unwrap_or_else(|e| panic!("{e}"));
    io::write_polygon_obj_with(&cube, file, &ObjWriteOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    check_with_tobj(&path, &cube.positions, &faces_of(&cube), None, None);
    std::fs::remove_file(&path).unwrap_or_else(|e| panic!("{e}"));
}

/// What a face-varying evaluation hands the writer: `f32` positions, quads, UV values and a
/// value per corner, written from caller-owned buffers and read back by tobj.
#[test]
fn uv_buffers_round_trip_through_tobj() {
    let torus = seamed_torus();
    let positions: Vec<[f32; 3]> = torus
        .positions
        .iter()
        .map(|p| p.to_array().map(|x| x as f32))
        .collect();
    let layout = torus.uv_layout().expect("a layout");
    let values: Vec<[f32; 2]> = layout
        .values()
        .iter()
        .map(|v| [v.x as f32, v.y as f32])
        .collect();
    let faces = FaceBuffers::Uniform {
        degree: 4,
        indices: torus.face_indices(),
    };
    let uvs = UvBuffers {
        values: &values,
        corners: layout.corners(),
    };
    let path = temp_obj("buffers");
    let options = ObjWriteOptions::default().with_normals(true);
    let file = std::fs::File::create(&path).unwrap_or_else(|e| panic!("{e}"));
    io::write_buffers_obj_with(&positions, faces, Some(uvs), file, &options)
        .unwrap_or_else(|e| panic!("{e}"));
    let as_f64: Vec<DVec3> = positions
        .iter()
        .map(|p| DVec3::from_array(p.map(f64::from)))
        .collect();
    let values64: Vec<DVec2> = values
        .iter()
        .map(|v| DVec2::new(f64::from(v[0]), f64::from(v[1])))
        .collect();
    let normals = normals::vertex_normals(&as_f64, torus.faces());
    check_with_tobj(
        &path,
        &as_f64,
        &faces_of(&torus),
        Some((&values64, layout.corners())),
        Some(&normals),
    );
    std::fs::remove_file(&path).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn the_shared_meshes_with_uvs_round_trip_through_tobj() {
    for name in [
        "spot_control_mesh.obj",
        "osd_catmark_pawn.obj",
        "cylinder_ngon.obj",
        "beast.obj",
    ] {
        let mesh = io::read_obj(mesh(name)).unwrap_or_else(|e| panic!("{e}"));
        round_trip(&mesh, name.trim_end_matches(".obj"));
    }
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn spot_control_mesh_reads_its_267_texture_coordinates() {
    let spot = io::read_obj(mesh("spot_control_mesh.obj")).unwrap_or_else(|e| panic!("{e}"));
    let uvs = spot.uvs().expect("every corner of spot has a vt");
    assert_eq!(spot.partial_uvs(), None);
    assert_eq!((uvs.coords().len(), uvs.corners().len()), (267, 732));
    let used: HashSet<u32> = uvs.corners().iter().copied().collect();
    assert_eq!((used.len(), uvs.unreferenced()), (267, 0));
    // The first face, `f 6/1 14/2 10/3 16/4`, and the first two `vt` lines as written.
    assert_eq!(spot.face(0), [5, 13, 9, 15]);
    assert_eq!(uvs.corners()[..4], [0, 1, 2, 3]);
    assert_eq!(
        uvs.coords()[..2],
        [
            DVec2::new(0.789172, 0.670062),
            DVec2::new(0.788538, 0.66243)
        ]
    );
    let layout = spot.uv_layout().expect("a layout");
    assert_eq!(layout.n_values(), 267);
    let uv = stats::uv_counts(&spot).expect("a layout");
    assert_eq!(
        serde_json::to_string(&uv).expect("serializes"),
        r#"{"V":267,"E":438,"BE":144,"seam_edges":72,"boundary_loops":13,"charts":13,"unreferenced":0}"#
    );
    // The same file with every index negative reads as the same mesh, UVs included.
    let negative =
        io::read_obj(mesh("spot_control_mesh_negidx.obj")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(negative.uvs(), spot.uvs());
    assert_eq!(negative.face_indices(), spot.face_indices());
}

/// For every shared mesh with `vt` at its corners, tobj (polygons kept, indices per
/// attribute) gives each corner the same texture coordinate as ours, and a mesh without `vt`
/// has no UVs.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn every_shared_meshs_texture_coordinates_agree_with_tobj() {
    let dir = meshes_dir();
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ..Default::default()
    };
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("the meshes folder is readable")
        .map(|e| {
            e.expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|n| n.ends_with(".obj"))
        .collect();
    names.sort();
    let mut textured = 0;
    for name in &names {
        let path = dir.join(name);
        let ours = io::read_obj(&path).unwrap_or_else(|e| panic!("{e}"));
        let (models, _) = tobj::load_obj(&path, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        let theirs: Vec<[f32; 2]> = models
            .iter()
            .flat_map(|m| {
                let mesh = &m.mesh;
                mesh.texcoord_indices.iter().map(|&t| {
                    let t = 2 * t as usize;
                    [mesh.texcoords[t], mesh.texcoords[t + 1]]
                })
            })
            .collect();
        let Some(uvs) = ours.uvs() else {
            assert!(
                theirs.len() < ours.n_corners(),
                "{name}: tobj has a vt at every corner, we read none"
            );
            assert_eq!(
                ours.partial_uvs().map(|p| p.with_vt),
                (!theirs.is_empty()).then_some(theirs.len()),
                "{name}"
            );
            continue;
        };
        textured += 1;
        assert_eq!(theirs.len(), uvs.corners().len(), "{name}");
        for (corner, (&t, b)) in uvs.corners().iter().zip(&theirs).enumerate() {
            let a = uvs.coords()[t as usize];
            for (x, y) in [a.x, a.y].into_iter().zip(b) {
                let y = f64::from(*y);
                assert!(
                    (x - y).abs() <= 1e-6 * y.abs().max(1.0),
                    "{name}: corner {corner}: {a} against {b:?}"
                );
            }
        }
    }
    assert!(textured >= 20, "only {textured} shared meshes have UVs");
}
