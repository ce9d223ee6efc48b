//! UV value counts predicted by `schemes::uv` against OpenSubdiv's `GetNumFVarValues`
//! (the driver's `--fvar MODE --fvar-counts`): every shared mesh whose face corners all have a
//! `vt`, under Catmull-Clark and, for the triangle meshes, Loop, at levels 0-2, in each of the
//! six linear-interpolation modes (the mode moves values, it never changes their number).
//!
//! The prediction is the layout's statistics ([`stats::uv_counts`]) through the rule's UV
//! recurrence ([`UvScheme::values_at`]), OpenSubdiv's sibling values included. OpenSubdiv
//! counts two things that no face uses, compared as documented in `schemes::uv`: at level 0
//! every `vt` line, used or not (its level 0 is `used_vt + unreferenced`), and from level 1 on
//! one value at each bare vertex (a position no face uses gets one sibling value, which its
//! child keeps at every level: osd_catmark_nonman_bareverts' 10 bare vertices). So from level
//! 1 on OpenSubdiv's count is ours plus the bare vertices.
//!
//! Ignored: they need `SUBCOUNT_OSD_DRIVER` and `SUBCOUNT_MESHES`, and fail, saying so,
//! without them.

use std::path::PathBuf;

use halfedge::{io, stats, PolygonMesh, Rule};
use schemes::uv::{uv_scheme, UvCounts};
use schemes::BigInt;

use crate::osd_support::fvar::{opensubdiv_fvar_counts, FvarMode};
use crate::osd_support::{driver, Osd};

/// The levels compared.
const LEVELS: u32 = 2;

/// Every shared mesh (not the `broken/` ones) with UVs (`vt` at every corner), read by
/// `io::read_obj`.
fn meshes_with_uvs() -> Vec<(PathBuf, PolygonMesh)> {
    let dir = testdata::meshes_dir();
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    paths.sort();
    let mut meshes = Vec::new();
    for path in paths {
        let mesh = io::read_obj(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        if mesh.uvs().is_some() {
            meshes.push((path, mesh));
        }
    }
    meshes
}

/// The predicted values at levels `0..=LEVELS` as OpenSubdiv counts them: every `vt` line
/// at level 0, a value per bare vertex (of `bare`) from level 1 on.
fn predicted(rule: Rule, uv: &UvCounts, bare: u64) -> Vec<u64> {
    let scheme = uv_scheme(rule).unwrap_or_else(|e| panic!("{e}"));
    (0..=u64::from(LEVELS))
        .map(|s| {
            if s == 0 {
                return uv.used_vt + uv.unreferenced;
            }
            let v = scheme.values_at(uv, s).unwrap_or_else(|e| panic!("{e}"));
            u64::try_from(v).unwrap_or_else(|e| panic!("{e}")) + bare
        })
        .collect()
}

#[test]
#[ignore = "needs the OpenSubdiv driver and SUBCOUNT_MESHES"]
fn predicted_uv_values_are_opensubdivs_on_every_shared_mesh_with_uvs() {
    driver();
    let meshes = meshes_with_uvs();
    assert!(
        meshes.len() >= 15,
        "only {} shared meshes with UVs in {}",
        meshes.len(),
        testdata::meshes_dir().display()
    );
    let mut compared = 0;
    for (path, mesh) in &meshes {
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into());
        let uv = stats::uv_counts(mesh).unwrap_or_else(|| panic!("{name}: no layout"));
        let bare = stats::face_list_counts(mesh).unreferenced_vertices;
        let triangles = mesh.faces().all(|f| f.len() == 3);
        let mut schemes = vec![(Osd::Catmark, Rule::CatmullClark)];
        if triangles {
            schemes.push((Osd::Loop, Rule::Loop));
        }
        for (osd, rule) in schemes {
            let ours = predicted(rule, &uv, bare);
            for mode in FvarMode::every_linear() {
                let theirs = opensubdiv_fvar_counts(&[], osd, LEVELS, path, None, mode).values;
                assert_eq!(
                    ours,
                    theirs,
                    "{name} {rule} --fvar {}: predicted (left) against OpenSubdiv (right); \
                     layout {uv:?}",
                    mode.driver_name()
                );
                compared += 1;
            }
        }
    }
    // Six modes per scheme; at least the meshes under Catmull-Clark.
    assert!(compared >= 6 * meshes.len(), "{compared} comparisons");
    // The counts agree with the recurrence as a closed form too (spot, level 2).
    let spot = meshes
        .iter()
        .find(|(p, _)| p.ends_with("spot_control_mesh.obj"))
        .and_then(|(_, m)| stats::uv_counts(m))
        .expect("spot_control_mesh has UVs");
    let cc = uv_scheme(Rule::CatmullClark).expect("counted");
    assert_eq!(cc.values_at(&spot, 2).expect("counts"), BigInt::from(3225));
}
