//! `subdivide` and `verify` follow the file's creases and corners and the resolved options
//! (OpenSubdiv's crease rules, `halfedge::subdivide::sdc`): the output differs from
//! `--ignore-tags` and is the library's with the tags' sharpness, a flag overrides a tag, an
//! untagged mesh gives what it always gave; and, against OpenSubdiv's driver, every tagged
//! shared mesh.

use halfedge::subdivide::{subdivide_to_face_list, Sharpness, SubdivideOptions};
use halfedge::tags::{BoundaryInterpolation, CreaseMethod, SubdivisionOptions};
use halfedge::{HalfEdgeMesh, Rule};

use crate::util::{ok, subcount};

/// A closed cube (vertices 0-7, 0-based), slightly irregular so no rule is exact by symmetry.
const CUBE: &str =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1.25 -1 1\nv 1 1 1\nv -1 1.5 1\n\
     f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

/// A hard edge, two semi-sharp ones of different sharpness (a crease through vertex 2, where
/// Chaikin's rule differs) and a semi-sharp corner.
const CUBE_TAGS: &str =
    "t crease 2/1/0 0 1 10\nt crease 4/2/0 1 2 2 3 1.5 2.25\nt corner 1/1/0 6 2.5\n";

/// The cube's faces split into triangles (for Loop).
const TRIANGLES: &str =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1.25 -1 1\nv 1 1 1\nv -1 1.5 1\n\
     f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

/// A 3 x 2 grid of quads with boundary (vertices `4 j + i`).
const GRID: &str =
    "v 0 0 0\nv 1 0 0.2\nv 2 0 0\nv 3 0 0.1\nv 0 1 0.3\nv 1 1 -0.2\nv 2 1 0.4\nv 3 1 0\n\
     v 0 2 0\nv 1 2 0.1\nv 2 2 -0.3\nv 3 2 0.2\n\
     f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 5 6 10 9\nf 6 7 11 10\nf 7 8 12 11\n";

/// Writes `text` as `name` in a fresh folder; returns the folder (kept alive) and the path.
fn file(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("written");
    let path = path.to_str().expect("UTF-8 path").to_owned();
    (dir, path)
}

/// `subcount subdivide` of `mesh` by `scheme` to `levels` with `extra` flags, written to a file:
/// its text.
fn subdivided(mesh: &str, scheme: &str, levels: u32, extra: &[&str]) -> String {
    let levels = levels.to_string();
    let mut args = vec!["--scheme", scheme, "--levels", &levels];
    args.extend(extra);
    subdivided_with_stderr(mesh, &args).0
}

/// `subcount subdivide` of `mesh` with `args` written to a file: its text and stderr
/// (exit 0 asserted).
fn subdivided_with_stderr(mesh: &str, args: &[&str]) -> (String, String) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("out.obj");
    let out = out.to_str().expect("UTF-8 path");
    let mut all = vec!["subdivide", "--mesh", mesh, "-o", out];
    all.extend_from_slice(args);
    let run = crate::util::subcount(&all);
    assert_eq!(run.code, 0, "subcount {all:?} failed: {}", run.stderr);
    (
        std::fs::read_to_string(out).expect("the output file"),
        run.stderr,
    )
}

/// The library's one-shot subdivision of the file with its tags' sharpness and `options`,
/// as OBJ text.
fn library(path: &str, rule: Rule, levels: u32, options: SubdivisionOptions) -> String {
    let polygons = halfedge::io::read_mesh(path).expect("read");
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
    let sharpness = Sharpness::from_tags(&mesh, polygons.tags()).expect("resolved");
    let opts = SubdivideOptions::default()
        .with_sharpness(&sharpness)
        .with_subdivision(options);
    let level = subdivide_to_face_list(&mesh, rule, levels, &opts).expect("subdivided");
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("lib.obj");
    halfedge::io::write_polygon_obj(&level.mesh, std::fs::File::create(&out).expect("created"))
        .expect("written");
    std::fs::read_to_string(out).expect("the output")
}

#[test]
fn a_tagged_mesh_subdivides_with_its_creases_as_the_library_does() {
    let (_d1, cube) = file("cube.obj", &format!("{CUBE}{CUBE_TAGS}"));
    let (_d2, tri) = file("tri.obj", &format!("{TRIANGLES}{CUBE_TAGS}"));
    let default = SubdivisionOptions::default();
    for (path, scheme, rule) in [
        (&cube, "catmull-clark", Rule::CatmullClark),
        (&tri, "loop", Rule::Loop),
        (&tri, "catmull-clark", Rule::CatmullClark),
    ] {
        for levels in 1..=3 {
            let with = subdivided(path, scheme, levels, &[]);
            let without = subdivided(path, scheme, levels, &["--ignore-tags"]);
            assert_ne!(
                with, without,
                "{scheme} level {levels}: the tags changed nothing"
            );
            assert_eq!(
                with,
                library(path, rule, levels, default),
                "{scheme} level {levels}"
            );
            // The same counts in the summary; threads and the refine-once path agree.
            assert_eq!(
                with,
                subdivided(path, scheme, levels, &["--threads", "2"]),
                "{scheme} level {levels}, 2 threads"
            );
            assert_eq!(
                with,
                subdivided(path, scheme, levels, &["--frames", "1"]),
                "{scheme} level {levels}, refined once"
            );
        }
        // In f32 too (the refinement's evaluation, rounded): every coordinate within 1e-5.
        let f64_text = subdivided(path, scheme, 2, &[]);
        let f32_text = subdivided(path, scheme, 2, &["--precision", "f32"]);
        let coordinates = |text: &str| -> Vec<f64> {
            text.lines()
                .filter(|l| l.starts_with("v "))
                .flat_map(|l| {
                    l[2..]
                        .split(' ')
                        .map(|x| x.parse::<f64>().expect("a number"))
                })
                .collect::<Vec<_>>()
        };
        let (a, b) = (coordinates(&f64_text), coordinates(&f32_text));
        assert_eq!(a.len(), b.len());
        assert!(
            a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-5),
            "{scheme} in f32"
        );
        let plain = subdivided(path, scheme, 2, &["--ignore-tags", "--precision", "f32"]);
        assert_ne!(f32_text, plain, "{scheme}: f32 ignored the tags");
    }
    // verify runs the creased subdivision and its counts still match.
    let run = subcount(&[
        "verify",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "3",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stdout.ends_with("all counts match the prediction\n"),
        "{}",
        run.stdout
    );
}

#[test]
fn a_flag_overrides_the_tag_in_the_geometry() {
    // Chaikin from the tag, uniform from the flag: the file without the tag.
    let (_d1, chaikin) = file(
        "chaikin.obj",
        &format!("{CUBE}{CUBE_TAGS}t creasemethod 0/0/1 chaikin\n"),
    );
    let (_d2, uniform) = file("uniform.obj", &format!("{CUBE}{CUBE_TAGS}"));
    let by_tag = subdivided(&chaikin, "catmull-clark", 3, &[]);
    let plain = subdivided(&uniform, "catmull-clark", 3, &[]);
    assert_ne!(by_tag, plain, "Chaikin's rule changed nothing");
    let chaikin_options = SubdivisionOptions::default().with_crease_method(CreaseMethod::Chaikin);
    assert_eq!(
        by_tag,
        library(&chaikin, Rule::CatmullClark, 3, chaikin_options)
    );
    let run = subcount(&[
        "subdivide",
        "--mesh",
        &chaikin,
        "--scheme",
        "catmull-clark",
        "--levels",
        "1",
        "--crease-method",
        "uniform",
    ]);
    assert_eq!(
        run.stderr,
        format!("note: {chaikin}: --crease-method uniform overrides the tag creasemethod chaikin (chaikin)\n")
    );
    assert_eq!(
        subdivided(
            &chaikin,
            "catmull-clark",
            3,
            &["--crease-method", "uniform"]
        ),
        plain
    );
    assert_eq!(
        subdivided(
            &uniform,
            "catmull-clark",
            3,
            &["--crease-method", "chaikin"]
        ),
        by_tag
    );

    // The boundary: edge-and-corner from the tag or the flag, edge from the flag.
    let (_d3, grid) = file("grid.obj", GRID);
    let (_d4, corners) = file(
        "corners.obj",
        &format!("{GRID}t interpolateboundary 1/0/0 1\n"),
    );
    let edge = subdivided(&grid, "catmull-clark", 2, &[]);
    let by_tag = subdivided(&corners, "catmull-clark", 2, &[]);
    assert_ne!(edge, by_tag, "edge-and-corner changed nothing");
    assert_eq!(
        subdivided(
            &grid,
            "catmull-clark",
            2,
            &["--boundary", "edge-and-corner"]
        ),
        by_tag
    );
    assert_eq!(
        subdivided(&corners, "catmull-clark", 2, &["--boundary", "edge"]),
        edge
    );
    let corner_options =
        SubdivisionOptions::default().with_boundary(BoundaryInterpolation::EdgeAndCorner);
    assert_eq!(
        by_tag,
        library(&corners, Rule::CatmullClark, 2, corner_options)
    );
    // Loop takes the boundary mode too.
    let (_d5, tris) = file(
        "tris.obj",
        "v 0 0 0\nv 1 0 0.2\nv 0 1 0.1\nv 1 1 0.3\nv 2 0 0\nf 1 2 4\nf 1 4 3\nf 2 5 4\n",
    );
    assert_ne!(
        subdivided(&tris, "loop", 2, &["--boundary", "edge-and-corner"]),
        subdivided(&tris, "loop", 2, &[])
    );

    // The triangle rule (Catmull-Clark on triangles).
    let (_d6, tri) = file("tri.obj", TRIANGLES);
    let (_d7, smooth) = file(
        "smooth.obj",
        &format!("{TRIANGLES}t smoothtriangles 0/0/1 smooth\n"),
    );
    let catmark = subdivided(&tri, "catmull-clark", 2, &[]);
    let by_tag = subdivided(&smooth, "catmull-clark", 2, &[]);
    assert_ne!(catmark, by_tag, "the smooth triangle rule changed nothing");
    assert_eq!(
        subdivided(&tri, "catmull-clark", 2, &["--triangle-rule", "smooth"]),
        by_tag
    );
    assert_eq!(
        subdivided(&smooth, "catmull-clark", 2, &["--triangle-rule", "catmark"]),
        catmark
    );
}

#[test]
fn an_untagged_mesh_subdivides_as_before() {
    let (_d1, cube) = file("cube.obj", CUBE);
    let (_d2, grid) = file("grid.obj", GRID);
    for (path, scheme) in [
        (&cube, "catmull-clark"),
        (&grid, "catmull-clark"),
        (&grid, "doo-sabin"),
    ] {
        for levels in 1..=2 {
            let plain = subdivided(path, scheme, levels, &[]);
            assert_eq!(
                plain,
                subdivided(path, scheme, levels, &["--ignore-tags"]),
                "{scheme}"
            );
        }
    }
    let plain = subdivided(&cube, "catmull-clark", 2, &[]);
    let lib = {
        let polygons = halfedge::io::read_mesh(&cube).expect("read");
        let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
        let level =
            subdivide_to_face_list(&mesh, Rule::CatmullClark, 2, &SubdivideOptions::default())
                .expect("subdivided");
        let dir = tempfile::tempdir().expect("a temporary folder");
        let out = dir.path().join("lib.obj");
        halfedge::io::write_polygon_obj(&level.mesh, std::fs::File::create(&out).expect("created"))
            .expect("written");
        std::fs::read_to_string(out).expect("the output")
    };
    assert_eq!(plain, lib);
    // A file whose tags change nothing (a crease of sharpness 0, the default options).
    let (_d3, zero) = file(
        "zero.obj",
        &format!("{CUBE}t crease 2/1/0 0 1 0\nt interpolateboundary 1/0/0 2\nt creasemethod 0/0/1 normal\n"),
    );
    assert_eq!(subdivided(&zero, "catmull-clark", 2, &[]), plain);
}

/// Only Loop and Catmull-Clark have crease rules: under any other rule a tagged file still
/// subdivides (and verifies), its creases, corners and options left out with one note, the
/// output that of `--ignore-tags`.
#[test]
fn creases_under_a_rule_without_crease_rules_are_left_out_with_a_note() {
    let (_d1, tri) = file("tri.obj", &format!("{TRIANGLES}{CUBE_TAGS}"));
    for scheme in ["butterfly", "sqrt3", "midpoint", "doo-sabin"] {
        let flags = ["--scheme", scheme, "--levels", "1"];
        let (tagged, stderr) = subdivided_with_stderr(&tri, &flags);
        assert!(
            stderr.contains(&format!(
                "are not applied by {scheme}: only loop and catmull-clark have crease rules"
            )),
            "{scheme}: {stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "{scheme}: {stderr}");
        let mut ignoring = flags.to_vec();
        ignoring.push("--ignore-tags");
        let (plain, quiet) = subdivided_with_stderr(&tri, &ignoring);
        assert_eq!(quiet, "", "{scheme}");
        assert_eq!(tagged, plain, "{scheme}");
    }
    let run = crate::util::subcount(&[
        "verify",
        "--mesh",
        &tri,
        "--scheme",
        "butterfly",
        "--levels",
        "1",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr.contains("not applied by butterfly"),
        "{}",
        run.stderr
    );
    // A corner to sharpen, asked by the flag, under Doo-Sabin: left out too.
    let (_d2, grid) = file("grid.obj", GRID);
    let flags = [
        "--scheme",
        "doo-sabin",
        "--levels",
        "1",
        "--boundary",
        "edge-and-corner",
    ];
    let (with_flag, stderr) = subdivided_with_stderr(&grid, &flags);
    assert!(stderr.contains("not applied by doo-sabin"), "{stderr}");
    let (plain, _) = subdivided_with_stderr(&grid, &flags[..4]);
    assert_eq!(with_flag, plain);
    // The general (face-list) schemes place points linearly and read no tags.
    ok(&[
        "subdivide",
        "--mesh",
        &tri,
        "--scheme",
        "loop-general",
        "--levels",
        "1",
    ]);
}

/// The differential tests' driver and comparison (`crates/halfedge/tests/osd_support`), shared
/// with `halfedge`'s `tests/opensubdiv.rs` (and `uv_subdivide.rs`).
#[allow(dead_code)]
#[path = "../../../halfedge/tests/osd_support/mod.rs"]
pub(crate) mod osd_support;

/// A level is compared when its output has at most this many faces (about 2 M).
const MAX_FACES: u64 = 2_100_000;

/// `subcount subdivide -o out.obj` of every tagged shared mesh (a file with `t` lines) against
/// OpenSubdiv's driver reading the same tags (`osd_driver --tags`: creases, corners, the
/// boundary mode and the crease method of the file), Catmull-Clark on every one and Loop on the
/// triangle ones, levels 1-3 up to [`MAX_FACES`]: positions within 1e-12 of the bounding-box
/// diagonal, faces one for one.
#[test]
#[ignore = "needs the OpenSubdiv driver (SUBCOUNT_OSD_DRIVER) and SUBCOUNT_MESHES"]
fn subdivide_matches_opensubdiv_on_every_tagged_shared_mesh() {
    use osd_support::{compare_levels, opensubdiv_with, Osd};
    osd_support::driver();
    let dir = testdata::meshes_dir();
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("listed").path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj") && p.is_file())
        .filter(|p| {
            let text = std::fs::read_to_string(p).unwrap_or_default();
            text.lines().any(|l| l.starts_with("t "))
        })
        .collect();
    files.sort();
    assert!(
        files.len() >= 5,
        "{} tagged meshes in {}",
        files.len(),
        dir.display()
    );
    let out_dir = tempfile::tempdir().expect("a temporary folder");
    let mut failures = Vec::new();
    let mut compared = Vec::new();
    for path in &files {
        let name = path
            .file_name()
            .expect("a name")
            .to_string_lossy()
            .into_owned();
        let polygons = halfedge::io::read_mesh(path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let triangles = polygons.faces().all(|f| f.len() == 3);
        let mut schemes = vec![(Osd::Catmark, "catmull-clark")];
        if triangles {
            schemes.push((Osd::Loop, "loop"));
        }
        for (osd, scheme) in schemes {
            for level in 1..=3u32 {
                let faces = osd.faces_at(polygons.n_faces(), polygons.n_corners(), level);
                if faces > MAX_FACES {
                    eprintln!("{name} {scheme} level {level}: {faces} faces, not compared");
                    continue;
                }
                let at = format!("{name}, subcount subdivide --scheme {scheme} --levels {level} vs osd_driver --tags");
                let running = opensubdiv_with(&["--tags"], osd, level, path, None);
                let out = out_dir.path().join(format!("{name}-{scheme}-{level}.obj"));
                let (mesh, out_str) = (path.to_str().expect("UTF-8"), out.to_str().expect("UTF-8"));
                let levels = level.to_string();
                let run = subcount(&[
                    "subdivide",
                    "--mesh",
                    mesh,
                    "--scheme",
                    scheme,
                    "--levels",
                    &levels,
                    "-o",
                    out_str,
                ]);
                let theirs = running.mesh();
                if run.code != 0 {
                    failures.push(format!("{at}: exit {}: {}", run.code, run.stderr));
                    continue;
                }
                let ours = halfedge::io::read_mesh(&out).expect("subcount's output");
                std::fs::remove_file(&out).expect("removed");
                match compare_levels(&at, &polygons, &ours, &theirs) {
                    Ok(outcome) => {
                        eprintln!(
                            "{at}: max deviation {:.3e} of the diagonal",
                            outcome.max_deviation
                        );
                        compared.push((name.clone(), scheme, level));
                    }
                    Err(message) => failures.push(message),
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "subcount disagrees with OpenSubdiv:\n{}",
        failures.join("\n")
    );
    // The comparison tells the creases apart: without the tags the creased meshes disagree.
    for name in ["osd_catmark_pawn.obj", "osd_catmark_chaikin2.obj"] {
        let path = dir.join(name);
        let running = opensubdiv_with(&["--tags"], Osd::Catmark, 1, &path, None);
        let out = out_dir.path().join("ignored.obj");
        let (mesh, out_str) = (path.to_str().expect("UTF-8"), out.to_str().expect("UTF-8"));
        ok(&[
            "subdivide",
            "--mesh",
            mesh,
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "-o",
            out_str,
            "--ignore-tags",
        ]);
        let theirs = running.mesh();
        let polygons = halfedge::io::read_mesh(&path).expect("read");
        let ours = halfedge::io::read_mesh(&out).expect("subcount's output");
        assert!(
            compare_levels(name, &polygons, &ours, &theirs).is_err(),
            "{name}: --ignore-tags matches OpenSubdiv with the tags"
        );
    }
    for name in [
        "osd_catmark_pawn.obj",
        "osd_catmark_chaikin2.obj",
        "osd_loop_icosahedron.obj",
    ] {
        for level in 1..=3 {
            assert!(
                compared.iter().any(|(n, _, l)| n == name && *l == level),
                "{name} level {level} was not compared"
            );
        }
    }
}

/// OpenSubdiv's `VTX_BOUNDARY_NONE` holes only the faces at a vertex with a boundary edge that
/// is not infinitely sharp: a 2x2 grid whose whole boundary is creased at 10 keeps its four
/// faces (16 at level 1, as OpenSubdiv writes), at 9.99 it keeps none; counts, `verify` and
/// the written file agree.
#[test]
fn boundary_none_keeps_the_faces_of_an_infinitely_sharp_boundary() {
    let grid = |sharpness: &str| {
        format!(
            "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nv 0 2 0\nv 1 2 0\nv 2 2 0\n\
             f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\n\
             t crease 16/1/0 0 1 1 2 2 5 5 8 8 7 7 6 6 3 3 0 {sharpness}\n\
             t interpolateboundary 1/0/0 0\n"
        )
    };
    for (sharpness, faces) in [("10.0", 16), ("1e3", 16), ("9.99", 0)] {
        let (dir, mesh) = file("grid.obj", &grid(sharpness));
        let scheme = "catmull-clark";
        let table = ok(&["at", "--mesh", &mesh, "--scheme", scheme, "--level", "1"]);
        assert!(
            table.contains(&format!("F = {faces}")),
            "{sharpness}: {table}"
        );
        let verify = ok(&[
            "verify", "--mesh", &mesh, "--scheme", scheme, "--levels", "2",
        ]);
        assert!(verify.contains("all counts match"), "{verify}");
        let out = dir.path().join("out.obj");
        let summary = ok(&[
            "subdivide",
            "--mesh",
            &mesh,
            "--scheme",
            scheme,
            "--levels",
            "1",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(summary.contains(&format!("F = {faces}")), "{summary}");
        let written = std::fs::read_to_string(&out).unwrap();
        let n = written.lines().filter(|l| l.starts_with("f ")).count();
        assert_eq!(n, faces, "{sharpness}: {written}");
    }
}
