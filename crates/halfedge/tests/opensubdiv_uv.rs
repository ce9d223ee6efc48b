//! Face-varying UVs against OpenSubdiv 3.5 (`PrimvarRefiner::InterpolateFaceVarying`
//! through the driver's `--fvar MODE`): every linear-interpolation mode, levels 1-2, on the
//! shared meshes with `vt` and on generated grids with seams, creases and holes. UVs must
//! agree to 1e-12 of the UV bounding box's diagonal corner for corner (faces matched through
//! the positions, so the numbering may differ), the value counts must be OpenSubdiv's, and
//! the positions are unchanged by the channel. Ignored: they need `SUBCOUNT_OSD_DRIVER` (the
//! driver, `tools/osd-driver/build.sh`) and `SUBCOUNT_MESHES`, and fail, saying so, without
//! them.

// Shared with `tests/opensubdiv.rs`, which uses all of it.
#[allow(dead_code)]
mod osd_support;

use std::path::{Path, PathBuf};

use halfedge::glam::{DVec2, DVec3};
use halfedge::holes::HoleSet;
use halfedge::refine::Refinement;
use halfedge::subdivide::{Sharpness, SubdivideOptions};
use halfedge::tags::{FaceVaryingInterpolation, SubdivisionOptions};
use halfedge::{io, HalfEdgeMesh, PolygonMesh, Rule};

use osd_support::fvar::{corner_uv_error, opensubdiv_fvar};
use osd_support::{
    bounding_box_diagonal, correspondence, driver, without_bare_vertices, Osd, TOLERANCE,
};

/// The shared mesh `file`.
fn shared(file: &str) -> PathBuf {
    testdata::meshes_dir().join(file)
}

/// `path` read by `halfedge::io`, with its `vt`.
fn read_with_uvs(path: &Path) -> PolygonMesh {
    let mesh = io::read_obj(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        mesh.uvs().is_some(),
        "{}: a vt on every corner",
        path.display()
    );
    mesh
}

/// What one comparison found.
struct Compared {
    worst: f64,
}

/// Refines `mesh` (written to `path` for the driver) by `scheme` to `level` under `mode`
/// (with the file's sharpness and holes when `sharpness`) and compares its UVs with
/// OpenSubdiv's, or with `limit` their limit (`LimitFaceVarying`, the driver's `--limit`)
/// against [`Refinement::evaluate_limit_uvs`].
fn compare(
    path: &Path,
    mesh: &PolygonMesh,
    scheme: Osd,
    level: u32,
    mode: FaceVaryingInterpolation,
    sharpness: bool,
    limit: bool,
) -> Compared {
    let mut flags: Vec<&str> = if sharpness { vec!["--tags"] } else { vec![] };
    if limit {
        flags.push("--limit");
    }
    let flags = flags.as_slice();
    let running = opensubdiv_fvar(flags, scheme, level, path, None, mode.into());
    let he = HalfEdgeMesh::try_from_polygon_mesh(mesh).expect("a manifold mesh");
    let layout = mesh.uv_layout().expect("a layout");
    let resolved = Sharpness::from_tags_of(mesh, &he, mesh.tags()).expect("tags");
    let holes = HoleSet::new(he.n_faces(), mesh.tags().holes().iter().copied());
    let options = if sharpness {
        mesh.tags().options.over(SubdivisionOptions::default())
    } else {
        SubdivisionOptions::default()
    }
    .with_face_varying(mode);
    let mut opts = SubdivideOptions::default()
        .with_uvs(&layout)
        .with_subdivision(options)
        .with_limit(limit);
    if sharpness {
        opts = opts.with_sharpness(&resolved);
        if let Ok(h) = &holes {
            opts = opts.with_holes(h);
        }
    }
    let rule = match scheme {
        Osd::Loop => Rule::Loop,
        Osd::Catmark => Rule::CatmullClark,
    };
    let r = Refinement::new(&he, rule, level, &opts).expect("refined");
    let base: Vec<[f64; 3]> = he.positions().iter().map(|p| p.to_array()).collect();
    let mut positions = vec![[0.0; 3]; r.n_vertices(level)];
    r.evaluate(&base, &mut positions).expect("evaluated");
    let mut offsets = vec![0u32; r.n_faces(level) + 1];
    let mut indices = vec![0u32; r.n_corners(level)];
    r.write_polygons(&mut offsets, &mut indices).expect("faces");
    let uv_base: Vec<[f64; 2]> = layout.values().iter().map(|v| v.to_array()).collect();
    let mut uvs = vec![[0.0; 2]; r.n_uvs(level)];
    match limit {
        true => r.evaluate_limit_uvs(&uv_base, &mut uvs).expect("limit uvs"),
        false => r.evaluate_uvs(&uv_base, &mut uvs).expect("uvs"),
    }
    let mut uv_indices = vec![0u32; r.n_corners(level)];
    r.write_uv_indices(&mut uv_indices).expect("uv indices");

    let theirs = running.fvar_level();
    let theirs = if limit {
        theirs.with_limit_values()
    } else {
        theirs
    };
    let theirs = if theirs.holes.is_empty() {
        theirs
    } else {
        theirs.without_holes()
    };
    let what = format!(
        "{} {scheme:?} level {level} --fvar {}{}",
        path.display(),
        mode.name(),
        if limit { " --limit" } else { "" }
    );
    let ours = PolygonMesh::from_faces(
        positions.iter().map(|&p| DVec3::from(p)).collect(),
        offsets
            .windows(2)
            .map(|w| indices[w[0] as usize..w[1] as usize].to_vec()),
    );
    assert_eq!(theirs.mesh.n_faces(), ours.n_faces(), "{what}: faces");
    // OpenSubdiv gives a vertex in no face a vertex and a value at every level; neither is
    // written here: the values compared are those faces use.
    let mut used = vec![false; theirs.values().len()];
    for &c in theirs.corner_values() {
        used[c as usize] = true;
    }
    let used = used.iter().filter(|&&u| u).count();
    assert_eq!(used, uvs.len(), "{what}: UV values");
    if mesh.n_vertices() == he.n_vertices() {
        assert_eq!(theirs.values().len(), uvs.len(), "{what}: UV values");
    }
    let diagonal = bounding_box_diagonal(&mesh.positions);
    let their_mesh = without_bare_vertices(&theirs.mesh);
    let to_ours = correspondence(&their_mesh, &ours, TOLERANCE * diagonal)
        .unwrap_or_else(|e| panic!("{what}: positions: {e}"));
    Compared {
        worst: {
            let (worst, at) = corner_uv_error(&theirs, &their_mesh, &ours, &to_ours, |g, k| {
                DVec2::from(uvs[uv_indices[offsets[g] as usize + k] as usize])
            })
            .unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(worst <= 1e-12, "{what}: {at}");
            worst
        },
    }
}

/// The shared meshes with `vt` on every corner, and the scheme each is compared under.
const MESHES: &[(&str, Osd)] = &[
    ("spot_control_mesh.obj", Osd::Catmark),
    ("spot_control_mesh_negidx.obj", Osd::Catmark),
    ("spot_triangulated.obj", Osd::Loop),
    ("spot_quadrangulated.obj", Osd::Catmark),
    ("blub_control_mesh.obj", Osd::Catmark),
    ("blub_quadrangulated.obj", Osd::Catmark),
    ("blub_triangulated.obj", Osd::Loop),
    ("bob_tri.obj", Osd::Loop),
    ("beast.obj", Osd::Catmark),
    ("cylinder_ngon.obj", Osd::Catmark),
    ("osd_catmark_bishop.obj", Osd::Catmark),
    ("osd_catmark_cube.obj", Osd::Catmark),
    ("osd_catmark_nonman_bareverts.obj", Osd::Catmark),
    ("osd_catmark_nonquads.obj", Osd::Catmark),
    ("osd_catmark_pawn.obj", Osd::Catmark),
    ("osd_catmark_pyramid.obj", Osd::Catmark),
    ("osd_catmark_toroidal_tet.obj", Osd::Catmark),
    ("osd_catmark_torus.obj", Osd::Catmark),
    ("osd_loop_icosahedron.obj", Osd::Loop),
    ("osd_loop_toroidal_tet.obj", Osd::Loop),
];

#[test]
#[ignore = "needs the OpenSubdiv driver (SUBCOUNT_OSD_DRIVER) and the shared meshes (SUBCOUNT_MESHES)"]
fn shared_meshes_match_opensubdiv_in_every_mode() {
    driver();
    for &(file, scheme) in MESHES {
        let path = shared(file);
        let mesh = read_with_uvs(&path);
        for &mode in FaceVaryingInterpolation::ALL {
            let levels: &[u32] = if mesh.n_corners() > 5000 {
                &[1]
            } else {
                &[1, 2]
            };
            for &level in levels {
                let start = std::time::Instant::now();
                let c = compare(&path, &mesh, scheme, level, mode, false, false);
                eprintln!(
                    "{file} L{level} {}: {:.1e} {:?}",
                    mode.name(),
                    c.worst,
                    start.elapsed()
                );
            }
        }
    }
}

/// A `n` x `n` grid of quads (or of triangles, two per quad) on `[0, n]²` with a UV layout
/// of two charts (a seam along the column `x = n / 2`, boundary to boundary), a dart (a seam
/// along the row `y = n / 2` from the boundary to the interior vertex `(n / 2 - 1, n / 2)`),
/// and OpenSubdiv tags: a semi-sharp crease across the seam, an infinitely sharp crease along
/// part of a column, a semi-sharp corner, a sharp vertex on the seam, two holes and `extra`
/// (more tag lines) as OBJ text.
fn grid_obj(n: u32, triangles: bool, extra: &str) -> String {
    use std::fmt::Write;
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let z = 0.1 * f64::from((i * 7 + j * 3) % 5);
            writeln!(text, "v {i} {j} {z}").expect("text");
        }
    }
    // vt: per vertex a base value, a second chart's value (x >= n / 2) and a dart value.
    let vts = (n + 1) * (n + 1);
    let half = n / 2;
    for chart in 0..3 {
        for j in 0..=n {
            for i in 0..=n {
                // Not affine in the grid: subdivision reproduces affine data whatever the rule.
                let (u, v) = (
                    f64::from(i) / f64::from(n) + 0.02 * f64::from((i * i + 3 * j) % 7),
                    f64::from(j) / f64::from(n) + 0.015 * f64::from((j * j + 5 * i) % 4),
                );
                let (u, v) = match chart {
                    0 => (u, v),
                    1 => (u + 0.1, v * 0.9),
                    _ => (u * 0.8, v + 0.07),
                };
                writeln!(text, "vt {u} {v}").expect("text");
            }
        }
    }
    let vt = |i: u32, j: u32, fi: u32, fj: u32| {
        let chart = if fi >= half {
            1
        } else if j == half && fj >= half && i + 1 < half {
            2
        } else {
            0
        };
        chart * vts + id(i, j) + 1
    };
    for fj in 0..n {
        for fi in 0..n {
            let quad = [(fi, fj), (fi + 1, fj), (fi + 1, fj + 1), (fi, fj + 1)];
            let corner = |&(i, j): &(u32, u32)| format!("{}/{}", id(i, j) + 1, vt(i, j, fi, fj));
            if triangles {
                for tri in [[0, 1, 2], [0, 2, 3]] {
                    let c: Vec<String> = tri.iter().map(|&k| corner(&quad[k])).collect();
                    writeln!(text, "f {}", c.join(" ")).expect("text");
                }
            } else {
                let c: Vec<String> = quad.iter().map(corner).collect();
                writeln!(text, "f {}", c.join(" ")).expect("text");
            }
        }
    }
    // A semi-sharp crease along the row y = 1 (across the seam).
    for i in 0..n {
        writeln!(text, "t crease 2/1/0 {} {} 1.5", id(i, 1), id(i + 1, 1)).expect("text");
    }
    // An infinitely sharp crease up part of the column x = n - 1.
    for j in 1..half {
        writeln!(
            text,
            "t crease 2/1/0 {} {} 10",
            id(n - 1, j),
            id(n - 1, j + 1)
        )
        .expect("text");
    }
    writeln!(text, "t corner 1/1/0 {} 2", id(1, n - 1)).expect("text");
    writeln!(text, "t corner 1/1/0 {} 10", id(half, n - 2)).expect("text");
    let per_quad = if triangles { 2 } else { 1 };
    writeln!(
        text,
        "t hole 2/0/0 {} {}",
        per_quad * (n * (n - 2) + n - 2),
        per_quad * (n * (n - 1))
    )
    .expect("text");
    text.push_str(extra);
    text
}

/// Compares every grid variant (Catmull-Clark on quads, Loop on triangles; edge,
/// edge-and-corner, Chaikin), every mode, at `levels`, the UVs or with `limit` their limit, to
/// 1e-12 of the UV box; returns the worst error. The files go to a folder named from `what`.
fn compare_grids(what: &str, levels: std::ops::RangeInclusive<u32>, limit: bool) -> f64 {
    driver();
    let dir = std::env::temp_dir().join(format!("halfedge-osd-{what}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let mut worst = 0.0f64;
    for (scheme, triangles) in [(Osd::Catmark, false), (Osd::Loop, true)] {
        for (boundary, extra) in [
            ("edge", ""),
            ("edge-and-corner", "t interpolateboundary 1/0/0 1\n"),
            ("chaikin", "t creasemethod 0/0/1 chaikin\n"),
        ] {
            let path = dir.join(format!("grid_{scheme:?}_{boundary}.obj"));
            std::fs::write(&path, grid_obj(6, triangles, extra)).expect("written");
            let mesh = read_with_uvs(&path);
            assert!(mesh.tags().holes().len() == 2, "the grid has its holes");
            for &mode in FaceVaryingInterpolation::ALL {
                for level in levels.clone() {
                    let c = compare(&path, &mesh, scheme, level, mode, true, limit);
                    worst = worst.max(c.worst);
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    worst
}

#[test]
#[ignore = "needs the OpenSubdiv driver (SUBCOUNT_OSD_DRIVER)"]
fn grids_with_seams_creases_and_holes_match_opensubdiv() {
    let worst = compare_grids("uv", 1..=2, false);
    eprintln!("worst corner error on the grids: {worst:.1e} of the UV box");
}

/// The limit of the UVs (`LimitFaceVarying`) on every shared mesh with `vt`, every mode,
/// levels 1-3 (the larger ones at level 1), to 1e-12 of the UV box. Not level 0: there
/// OpenSubdiv's channel has not tagged its seams yet (a refinement tags them), so its
/// `LimitFaceVarying` mixes the values on both sides of a seam at a seam vertex and leaves
/// the vertex's other values unwritten; `halfedge` takes each side's own limit, as at every
/// later level.
#[test]
#[ignore = "needs the OpenSubdiv driver (SUBCOUNT_OSD_DRIVER) and the shared meshes (SUBCOUNT_MESHES)"]
fn the_limit_of_uvs_matches_opensubdiv_on_shared_meshes() {
    driver();
    let mut compared = 0;
    for &(file, scheme) in MESHES {
        let path = shared(file);
        let mesh = read_with_uvs(&path);
        let top = if mesh.n_corners() > 5000 { 1 } else { 3 };
        for &mode in FaceVaryingInterpolation::ALL {
            for level in 1..=top {
                let c = compare(&path, &mesh, scheme, level, mode, false, true);
                eprintln!("{file} L{level} {} limit: {:.1e}", mode.name(), c.worst);
                compared += 1;
            }
        }
    }
    assert!(compared >= MESHES.len() * FaceVaryingInterpolation::ALL.len());
}

/// The limit of the UVs on the grids with seams, a dart, creases across and along seams,
/// corners and holes, every mode, levels 1-3 (level 0: see above).
#[test]
#[ignore = "needs the OpenSubdiv driver (SUBCOUNT_OSD_DRIVER)"]
fn the_limit_of_uvs_matches_opensubdiv_on_grids() {
    let worst = compare_grids("uv-limit", 1..=3, true);
    eprintln!("worst limit UV error on the grids: {worst:.1e} of the UV box");
}
