//! Texture coordinates through the OBJ reader: spot_control_mesh's 267 `vt` and its pinned
//! UV layout, the same mesh written with negative indices, and every shared mesh's corners
//! against tobj's texture-coordinate indices.

use std::collections::HashSet;

use halfedge::glam::DVec2;
use halfedge::{io, stats};
use testdata::{mesh, meshes_dir};

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
