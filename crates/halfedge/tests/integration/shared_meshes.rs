//! Every mesh of the shared folder (`SUBCOUNT_MESHES`): face-list statistics against
//! `stats.json`, the half-edge build (accepted, or refused with the right error for the
//! meshes in `broken/`), and a cross-check of our OBJ reader against tobj.

use halfedge::{io, stats, Error, HalfEdgeMesh};
use serde_json::Value;
use testdata::meshes_dir;

fn stats_json(dir: &std::path::Path) -> serde_json::Map<String, Value> {
    let text = std::fs::read_to_string(dir.join("stats.json")).expect("stats.json is readable");
    match serde_json::from_str(&text).expect("stats.json is JSON") {
        Value::Object(map) => map,
        other => panic!("stats.json is not an object: {other}"),
    }
}

fn int(entry: &Value, key: &str) -> i64 {
    entry[key]
        .as_i64()
        .unwrap_or_else(|| panic!("{key} is not an integer: {}", entry[key]))
}

/// The error kind each broken mesh must be refused with (the first check that fails in the
/// documented order of `HalfEdgeMesh::try_from_polygons`).
fn expected_refusal(name: &str) -> &'static str {
    match name {
        "broken/beetle_nonmanifold.obj" => "NonManifoldEdge",
        "broken/cow_nonmanifold_vertex.obj" => "NonManifoldVertex",
        "broken/teapot_nonmanifold.obj" => "NonManifoldVertex",
        "broken/truck_nonmanifold.obj" => "NonManifoldEdge",
        "broken/osd_catmark_nonman_edges.obj" => "RepeatedVertex",
        "broken/osd_catmark_nonman_verts.obj" => "NonManifoldVertex",
        "broken/osd_loop_nonman_edges.obj" => "RepeatedVertex",
        "broken/osd_catmark_fan.obj" => "NonManifoldEdge",
        "broken/osd_catmark_val2_back2back.obj" => "DuplicateFace",
        "broken/osd_catmark_nonman_quadpole8.obj" => "RepeatedVertex",
        other => panic!("no expected refusal listed for {other}"),
    }
}

fn kind(err: &Error) -> &'static str {
    match err {
        Error::NonManifoldEdge { .. } => "NonManifoldEdge",
        Error::NonManifoldVertex { .. } => "NonManifoldVertex",
        Error::RepeatedVertex { .. } => "RepeatedVertex",
        Error::DuplicateFace { .. } => "DuplicateFace",
        Error::InconsistentOrientation { .. } => "InconsistentOrientation",
        Error::NonOrientable { .. } => "NonOrientable",
        _ => "other",
    }
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn every_shared_mesh_matches_stats_json() {
    let dir = meshes_dir();
    let all = stats_json(&dir);
    assert!(all.len() >= 58, "stats.json lists {} meshes", all.len());
    let mut failures = Vec::new();
    for (name, entry) in &all {
        let path = dir.join(name);
        let polygons = io::read_obj(&path).unwrap_or_else(|e| panic!("{e}"));
        let c = stats::face_list_counts(&polygons);
        let unreferenced = int(entry, "unreferenced_vertices");
        let expected = [
            ("V", int(entry, "V") - unreferenced, c.vertices as i64),
            ("E", int(entry, "E"), c.edges as i64),
            ("F", int(entry, "F"), c.faces as i64),
            ("corners", int(entry, "corners"), c.corners as i64),
            (
                "boundary_edges",
                int(entry, "boundary_edges"),
                c.boundary_edges as i64,
            ),
            (
                "nonmanifold_edges",
                int(entry, "nonmanifold_edges"),
                c.nonmanifold_edges as i64,
            ),
            (
                "boundary_loops",
                int(entry, "boundary_loops"),
                c.boundary_loops as i64,
            ),
            ("components", int(entry, "components"), c.components as i64),
            (
                "chi_used_vertices",
                int(entry, "chi_used_vertices"),
                c.euler_characteristic,
            ),
            (
                "unreferenced_vertices",
                unreferenced,
                c.unreferenced_vertices as i64,
            ),
            ("v lines", int(entry, "V"), polygons.n_vertices() as i64),
        ];
        for (what, want, got) in expected {
            if want != got {
                failures.push(format!("{name}: {what} is {got}, stats.json says {want}"));
            }
        }
        let degrees: Vec<(u32, u64)> = entry["face_degrees"]
            .as_object()
            .expect("face_degrees is an object")
            .iter()
            .map(|(k, v)| (k.parse().expect("degree"), v.as_u64().expect("count")))
            .collect();
        let ours: Vec<(u32, u64)> = c.faces_by_degree.iter().map(|(&k, &v)| (k, v)).collect();
        let mut sorted = degrees.clone();
        sorted.sort_unstable();
        if sorted != ours {
            failures.push(format!(
                "{name}: faces by degree {ours:?}, stats.json {sorted:?}"
            ));
        }
        let problems = stats::face_list_problems(&polygons);
        let found = [
            ("degenerate_faces", problems.faces_with_repeated_vertex),
            ("duplicate_faces", problems.duplicate_faces),
            ("nonmanifold_edges", problems.nonmanifold_edges),
            ("nonmanifold_vertices", problems.nonmanifold_vertices),
            (
                "inconsistently_oriented_edges",
                problems.inconsistently_oriented_edges,
            ),
        ];
        for (what, got) in found {
            if int(entry, what) != got as i64 {
                failures.push(format!(
                    "{name}: {what} is {got}, stats.json says {}",
                    entry[what]
                ));
            }
        }
        if entry["manifold"].as_bool() != Some(problems.is_manifold()) {
            failures.push(format!("{name}: manifold is {}", problems.is_manifold()));
        }
        if problems.is_empty() == name.starts_with("broken/") {
            failures.push(format!("{name}: problems {problems:?}"));
        }
        // The schemes crate counts valid face lists its own way: both must agree.
        if problems.faces_with_repeated_vertex == 0 && polygons.n_faces() < 100_000 {
            let faces: Vec<&[u32]> = polygons.faces().collect();
            let theirs = schemes::MeshCounts::from_polygons(&faces).expect("no repeated vertex");
            let ours = schemes::MeshCounts {
                unreferenced_vertices: 0,
                ..c.clone()
            };
            if theirs != ours {
                failures.push(format!(
                    "{name}: schemes::MeshCounts::from_polygons {theirs:?}"
                ));
            }
        }
        // Interior edges follow: E = IE + BE + NME.
        assert_eq!(
            c.interior_edges + c.boundary_edges + c.nonmanifold_edges,
            c.edges,
            "{name}"
        );

        match HalfEdgeMesh::try_from(&polygons) {
            Ok(mesh) => {
                if name.starts_with("broken/") {
                    failures.push(format!("{name}: accepted, but it is broken"));
                    continue;
                }
                mesh.check_invariants()
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                let counts = mesh.counts();
                if counts != c {
                    failures.push(format!("{name}: half-edge counts {counts:?} != {c:?}"));
                }
                let genus = entry["genus"].as_i64().map(|g| g as u64);
                if Some(mesh.genus()) != genus || stats::genus(&c) != genus {
                    failures.push(format!("{name}: genus {} != {genus:?}", mesh.genus()));
                }
            }
            Err(err) => {
                eprintln!("{name}: refused: {err}");
                // The face named by the error maps back to an `f` line of the file.
                if let Some(face) = err.face() {
                    let line = polygons.face_line(face as usize).expect("read from a file");
                    let text = std::fs::read_to_string(&path).expect("readable");
                    let at = text.lines().nth(line as usize - 1).unwrap_or_default();
                    assert!(at.starts_with("f "), "{name}: line {line} is `{at}`");
                }
                if !name.starts_with("broken/") {
                    failures.push(format!("{name}: refused: {err}"));
                } else if kind(&err) != expected_refusal(name) {
                    failures.push(format!(
                        "{name}: refused as {} ({err}), expected {}",
                        kind(&err),
                        expected_refusal(name)
                    ));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} mismatches:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// tobj, asked to keep polygons and not merge anything, must see the same faces (its indices
/// are per model, into its own position list, so compare face by face through positions).
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn our_obj_reader_agrees_with_tobj() {
    let dir = meshes_dir();
    let all = stats_json(&dir);
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ..Default::default()
    };
    for name in all.keys() {
        let path = dir.join(name);
        let ours = io::read_obj(&path).unwrap_or_else(|e| panic!("{e}"));
        let (models, _) = tobj::load_obj(&path, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut faces = 0usize;
        let mut ours_faces = ours.faces();
        for model in &models {
            let m = &model.mesh;
            let mut start = 0usize;
            let arities: Vec<u32> = if m.face_arities.is_empty() {
                vec![3; m.indices.len() / 3]
            } else {
                m.face_arities.clone()
            };
            for arity in arities {
                let theirs = &m.indices[start..start + arity as usize];
                start += arity as usize;
                let mine = ours_faces
                    .next()
                    .unwrap_or_else(|| panic!("{name}: tobj has more faces"));
                assert_eq!(mine.len(), theirs.len(), "{name}: face {faces}");
                for (&a, &b) in mine.iter().zip(theirs) {
                    let p = ours.positions[a as usize];
                    let q = &m.positions[3 * b as usize..3 * b as usize + 3];
                    for (x, y) in [p.x, p.y, p.z].into_iter().zip(q) {
                        let y = f64::from(*y);
                        assert!(
                            (x - y).abs() <= 1e-6 * y.abs().max(1.0),
                            "{name}: face {faces}"
                        );
                    }
                }
                faces += 1;
            }
        }
        assert_eq!(faces, ours.n_faces(), "{name}");
    }
}

/// The big mesh (400,020 faces, 26 components, 27 pairs of distinct vertices at the same
/// position) builds, and survives `write_obj` and `read_obj` exactly: the same positions
/// bit for bit, the same faces in the same order, the same counts.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn the_big_mesh_builds_and_writes_back() {
    let polygons =
        io::read_obj(testdata::mesh("buildings_400k.obj")).unwrap_or_else(|e| panic!("{e}"));
    let mesh = HalfEdgeMesh::try_from(&polygons).unwrap_or_else(|e| panic!("{e}"));
    let counts = mesh.counts();
    assert_eq!(stats::face_list_counts(&polygons), counts);
    assert_eq!(
        (mesh.n_vertices(), mesh.n_edges(), mesh.n_faces()),
        (200_062, 600_030, 400_020)
    );
    assert_eq!((mesh.genus(), counts.components), (0, 26));

    let dir = std::env::temp_dir().join(format!("halfedge-big-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let path = dir.join("buildings_400k.obj");
    let file = std::fs::File::create(&path).unwrap_or_else(|e| panic!("{e}"));
    io::write_obj(&mesh, file).unwrap_or_else(|e| panic!("{e}"));
    let back = io::read_obj(&path);
    std::fs::remove_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let back = back.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.n_faces(), 400_020);
    // The file uses every vertex, so the numbering is kept: the written mesh is the one read
    // (its geometry: a half-edge mesh carries no groups; the face list's writer does).
    assert!(
        back.positions == polygons.positions
            && back.face_offsets() == polygons.face_offsets()
            && back.face_indices() == polygons.face_indices(),
        "buildings_400k.obj changed on the way back"
    );
    let mut text = Vec::new();
    io::write_polygon_obj(&polygons, &mut text).unwrap_or_else(|e| panic!("{e}"));
    let again = io::read_obj_from(text.as_slice(), "again.obj").unwrap_or_else(|e| panic!("{e}"));
    assert!(polygons.groups().is_some(), "the file has groups");
    assert!(again == polygons, "the face list's writer keeps everything");
    assert_eq!(
        HalfEdgeMesh::try_from(&back)
            .unwrap_or_else(|e| panic!("{e}"))
            .counts(),
        counts
    );
}
