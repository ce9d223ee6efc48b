//! The OpenSubdiv driver's face-varying UV channel (`--fvar MODE`, `--fvar-counts`,
//! [`osd_support::fvar`](crate::osd_support::fvar)) checked against what is known of it: the
//! UV value counts issue 14 quotes (measured with OpenSubdiv 3.5), the file's own `vt` at
//! level 0, positions and faces unchanged by the channel, the `facevaryinginterpolateboundary`
//! tag, holes, and refusal of a mesh whose corners lack `vt`. These are the reference's own
//! tests; the value-by-value comparisons with `halfedge` build on the same functions. Ignored
//! like the rest of `opensubdiv.rs`: they need `SUBCOUNT_OSD_DRIVER` and `SUBCOUNT_MESHES`,
//! and fail, saying so, without them.

use std::path::{Path, PathBuf};
use std::process::Command;

use halfedge::glam::DVec2;
use halfedge::tags::FaceVaryingInterpolation;

use crate::osd_support::fvar::{
    opensubdiv_fvar, opensubdiv_fvar_counts, FvarCounts, FvarLevel, FvarMode,
};
use crate::osd_support::{driver, opensubdiv_with, Osd};

/// The shared mesh `file`.
fn shared(file: &str) -> PathBuf {
    testdata::meshes_dir().join(file)
}

/// Issue 14's UV value counts of spot_control_mesh under Catmull-Clark, levels 0-4.
const SPOT_CATMARK: [u64; 5] = [267, 885, 3225, 12297, 48009];
/// Issue 14's UV value counts of spot_triangulated under Loop, levels 0-2.
const SPOT_LOOP: [u64; 3] = [3225, 12297, 48009];

#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn fvar_counts_are_the_issues_in_every_mode() {
    driver();
    for mode in FvarMode::every_linear() {
        for (scheme, file, expected) in [
            (Osd::Catmark, "spot_control_mesh.obj", &SPOT_CATMARK[..]),
            (Osd::Loop, "spot_triangulated.obj", &SPOT_LOOP[..]),
        ] {
            let level = expected.len() as u32 - 1;
            let counts = opensubdiv_fvar_counts(&[], scheme, level, &shared(file), None, mode);
            assert_eq!(
                counts,
                FvarCounts {
                    mode: match mode {
                        FvarMode::Linear(m) => m,
                        FvarMode::Tag => unreachable!("every_linear names modes"),
                    },
                    values: expected.to_vec(),
                },
                "{file} {scheme:?} --fvar {}",
                mode.driver_name()
            );
        }
    }
}

/// `vt` lines and every corner's `vt` (0-based) of an OBJ file whose faces are all `v/vt`
/// (negative indices resolved), read here independently of the driver and of `halfedge::io`.
fn file_uvs(path: &Path) -> (Vec<DVec2>, Vec<u32>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut values = Vec::new();
    let mut corners = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vt") => {
                let uv: Vec<f64> = words.map(|w| w.parse().expect("a number")).collect();
                values.push(DVec2::new(uv[0], uv[1]));
            }
            Some("f") => {
                for corner in words {
                    let vt: i64 = corner.split('/').nth(1).expect("v/vt").parse().expect("vt");
                    let resolved = if vt > 0 {
                        vt - 1
                    } else {
                        values.len() as i64 + vt
                    };
                    corners.push(u32::try_from(resolved).expect("in range"));
                }
            }
            _ => {}
        }
    }
    (values, corners)
}

#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn fvar_level_0_is_the_files_vt() {
    driver();
    for file in ["spot_control_mesh.obj", "spot_control_mesh_negidx.obj"] {
        let path = shared(file);
        let (values, corners) = file_uvs(&path);
        for mode in FvarMode::every_linear() {
            let level = opensubdiv_fvar(&[], Osd::Catmark, 0, &path, None, mode).fvar_level();
            assert_eq!(level.values(), values.as_slice(), "{file} values");
            assert_eq!(level.corner_values(), corners.as_slice(), "{file} corners");
        }
    }
}

/// Runs `scheme` at `level` on `path` with `--fvar MODE` and without, and requires the same
/// positions (bit for bit) and faces, one value per corner, and as many values as
/// `--fvar-counts` gives for the level. Returns the `--fvar` level.
fn check_channel_moves_nothing(
    flags: &[&str],
    scheme: Osd,
    level: u32,
    path: &Path,
    mode: FvarMode,
) -> FvarLevel {
    let at = format!(
        "{} {scheme:?} level {level} --fvar {}",
        path.display(),
        mode.driver_name()
    );
    let with = opensubdiv_fvar(flags, scheme, level, path, None, mode).fvar_level();
    let without = opensubdiv_with(flags, scheme, level, path, None).mesh();
    assert_eq!(with.mesh.positions, without.positions, "{at}: positions");
    assert_eq!(
        with.mesh.face_offsets(),
        without.face_offsets(),
        "{at}: face sizes"
    );
    assert_eq!(
        with.mesh.face_indices(),
        without.face_indices(),
        "{at}: faces"
    );
    assert_eq!(with.corner_values().len(), with.mesh.n_corners(), "{at}");
    let counts = opensubdiv_fvar_counts(flags, scheme, level, path, None, mode);
    assert_eq!(
        Some(&(with.values().len() as u64)),
        counts.values.last(),
        "{at}: vt lines against GetNumFVarValues"
    );
    with
}

#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn fvar_leaves_positions_and_faces_as_they_are() {
    driver();
    let mut distinct = Vec::new();
    for mode in FvarMode::every_linear() {
        let catmark = check_channel_moves_nothing(
            &[],
            Osd::Catmark,
            2,
            &shared("spot_control_mesh.obj"),
            mode,
        );
        check_channel_moves_nothing(&[], Osd::Loop, 1, &shared("spot_triangulated.obj"), mode);
        check_channel_moves_nothing(&[], Osd::Catmark, 1, &shared("osd_catmark_pawn.obj"), mode);
        distinct.push(catmark.values().to_vec());
    }
    // The mode moves values: six modes, six different value lists on spot at level 2.
    for (i, a) in distinct.iter().enumerate() {
        for b in &distinct[i + 1..] {
            assert_ne!(a, b, "two modes give the same values");
        }
    }
}

/// A copy of a shared mesh with lines appended, in the system's temporary folder (one file per
/// name and process, removed on drop).
struct TempObj(PathBuf);

impl TempObj {
    fn new(file: &str, name: &str, extra: &str) -> TempObj {
        let source = shared(file);
        let text = std::fs::read_to_string(&source)
            .unwrap_or_else(|e| panic!("{}: {e}", source.display()));
        let path =
            std::env::temp_dir().join(format!("subcount-fvar-{}-{name}.obj", std::process::id()));
        std::fs::write(&path, format!("{text}\n{extra}\n"))
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        TempObj(path)
    }
}

impl Drop for TempObj {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn fvar_tag_sets_the_mode_and_a_named_mode_wins() {
    driver();
    let tagged = TempObj::new(
        "spot_control_mesh.obj",
        "tag3",
        "t facevaryinginterpolateboundary 1/0/0 3",
    );
    let tags = ["--tags"];
    let counts = opensubdiv_fvar_counts(&tags, Osd::Catmark, 1, &tagged.0, None, FvarMode::Tag);
    assert_eq!(counts.mode, FaceVaryingInterpolation::CornersPlus2);
    assert_eq!(counts.values, SPOT_CATMARK[..2]);
    let by_tag =
        opensubdiv_fvar(&tags, Osd::Catmark, 2, &tagged.0, None, FvarMode::Tag).fvar_level();
    let plus2 = FaceVaryingInterpolation::CornersPlus2.into();
    let named = opensubdiv_fvar(&tags, Osd::Catmark, 2, &tagged.0, None, plus2).fvar_level();
    assert_eq!(by_tag.values(), named.values());
    assert_eq!(by_tag.corner_values(), named.corner_values());
    let all = FaceVaryingInterpolation::All.into();
    let counts = opensubdiv_fvar_counts(&tags, Osd::Catmark, 1, &tagged.0, None, all);
    assert_eq!(
        counts.mode,
        FaceVaryingInterpolation::All,
        "a named mode wins"
    );

    // No tag: corners-plus1.
    let untagged = shared("spot_control_mesh.obj");
    let counts = opensubdiv_fvar_counts(&tags, Osd::Catmark, 1, &untagged, None, FvarMode::Tag);
    assert_eq!(counts.mode, FaceVaryingInterpolation::CornersPlus1);
}

#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn fvar_holes_keep_the_values_only_they_use() {
    driver();
    let holed = TempObj::new("spot_control_mesh.obj", "holes", "t hole 3/0/0 0 1 2");
    let tags = ["--tags"];
    let all = FaceVaryingInterpolation::All.into();
    let counts = opensubdiv_fvar_counts(&tags, Osd::Catmark, 4, &holed.0, None, all);
    assert_eq!(counts.values, SPOT_CATMARK, "holes change no count");
    let level = check_channel_moves_nothing(&tags, Osd::Catmark, 1, &holed.0, all);
    // Each hole face has one child per corner at level 1, all of them holes.
    let hole_children: usize = [0, 1, 2].iter().map(|&f| spot_face_size(f)).sum();
    assert_eq!(level.holes.len(), hole_children);
    let kept = level.without_holes();
    assert_eq!(kept.mesh.n_faces(), level.mesh.n_faces() - hole_children);
    assert!(kept.holes.is_empty());
    // Measured: 10 of the 885 values are used by hole faces only.
    assert_eq!(kept.values().len(), 875);
    // Every kept value is some kept corner's, and every kept corner keeps its UV.
    let mut used = vec![false; kept.values().len()];
    for &i in kept.corner_values() {
        used[i as usize] = true;
    }
    assert!(used.iter().all(|&u| u));
    let originals = (0..level.mesh.n_faces())
        .filter(|f| !level.holes.contains(f))
        .flat_map(|f| level.face_values(f).iter().copied());
    let mut compared = 0;
    for (original, &new) in originals.zip(kept.corner_values()) {
        assert_eq!(
            level.values()[original as usize],
            kept.values()[new as usize]
        );
        compared += 1;
    }
    assert_eq!(compared, kept.mesh.n_corners());
}

/// The number of corners of spot_control_mesh's face `f` (its children under Catmull-Clark).
fn spot_face_size(f: usize) -> usize {
    let path = shared("spot_control_mesh.obj");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| l.starts_with("f "))
        .nth(f)
        .map(|l| l.split_whitespace().count() - 1)
        .unwrap_or_else(|| panic!("spot_control_mesh has no face {f}"))
}

#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn fvar_refuses_a_corner_without_vt() {
    let output = Command::new(driver())
        .args(["--fvar", "all", "catmark", "1"])
        .arg(shared("planexy.obj"))
        .output()
        .expect("the driver runs");
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("planexy.obj: line ") && stderr.contains("no texture coordinate index"),
        "{stderr}"
    );
    // `--fvar tag` without `--tags` is a usage error.
    let output = Command::new(driver())
        .args(["--fvar", "tag", "catmark", "1"])
        .arg(shared("spot_control_mesh.obj"))
        .output()
        .expect("the driver runs");
    assert_eq!(output.status.code(), Some(2));
}
