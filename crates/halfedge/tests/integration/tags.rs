//! OpenSubdiv's tags in the shared meshes (`SUBCOUNT_MESHES`): what each tagged file holds,
//! and that every other mesh of the folder has none.

use halfedge::io::{self, ReadOptions};
use halfedge::tags::{BoundaryInterpolation, CreaseMethod};
use testdata::meshes_dir;

/// The tagged shared meshes: (file, sharp edges, boundary tag, crease method tag).
const TAGGED: &[(
    &str,
    usize,
    Option<BoundaryInterpolation>,
    Option<CreaseMethod>,
)] = &[
    ("osd_catmark_pawn.obj", 120, None, None),
    ("osd_catmark_bishop.obj", 224, None, None),
    (
        "osd_catmark_chaikin2.obj",
        4,
        None,
        Some(CreaseMethod::Chaikin),
    ),
    (
        "osd_catmark_nonquads.obj",
        0,
        Some(BoundaryInterpolation::EdgeAndCorner),
        None,
    ),
    (
        "osd_loop_icosahedron.obj",
        0,
        Some(BoundaryInterpolation::Edge),
        None,
    ),
];

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn the_tagged_shared_meshes_hold_what_their_t_lines_say() {
    let dir = meshes_dir();
    for &(name, edges, boundary, method) in TAGGED {
        let mesh = io::read_mesh(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let tags = mesh.tags();
        assert_eq!(tags.sharp_edges().len(), edges, "{name}");
        assert_eq!(
            tags.creases().len(),
            edges,
            "{name}: one crease line per edge"
        );
        assert!(
            tags.corners().is_empty() && tags.holes().is_empty(),
            "{name}"
        );
        assert_eq!(tags.options.boundary, boundary, "{name}");
        assert_eq!(tags.options.crease_method, method, "{name}");
        assert!(mesh.ignored_tags().is_empty(), "{name}");
        let plain = io::read_mesh_with(dir.join(name), &ReadOptions::without_tags())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!plain.has_tags(), "{name}");
        assert_eq!(plain.positions, mesh.positions, "{name}");
        assert_eq!(plain.face_indices(), mesh.face_indices(), "{name}");
    }
    // The pawn's creases are semi-sharp (6 < 10), every one.
    let pawn = io::read_mesh(dir.join("osd_catmark_pawn.obj")).expect("pawn");
    assert!(pawn.tags().sharp_edges().iter().all(|c| c.sharpness == 6.0));
    let chaikin = io::read_mesh(dir.join("osd_catmark_chaikin2.obj")).expect("chaikin2");
    let sharpness: Vec<f32> = chaikin
        .tags()
        .sharp_edges()
        .iter()
        .map(|c| c.sharpness)
        .collect();
    assert_eq!(sharpness, [0.5, 1.5, 2.5, 3.5]);
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn no_other_shared_mesh_has_tags_and_none_has_holes() {
    let dir = meshes_dir();
    let mut seen = 0;
    for sub in ["", "broken"] {
        for entry in std::fs::read_dir(dir.join(sub)).expect("meshes folder") {
            let path = entry.expect("entry").path();
            if path.extension().and_then(|e| e.to_str()) != Some("obj") {
                continue;
            }
            let name = path
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or("")
                .to_string();
            let mesh = io::read_mesh(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(mesh.tags().holes().is_empty(), "{name} has holes");
            assert!(mesh.ignored_tags().is_empty(), "{name}");
            let tagged = TAGGED.iter().any(|t| t.0 == name);
            let broken_tagged = sub == "broken" && mesh.tags().options.boundary.is_some();
            assert_eq!(mesh.has_tags(), tagged || broken_tagged, "{sub}/{name}");
            seen += 1;
        }
    }
    assert!(seen >= 50, "read {seen} OBJ files");
}
