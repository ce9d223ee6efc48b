//! `subdivide --limit` and `--normals limit`: the limit surface (OpenSubdiv's limit masks,
//! `halfedge`'s `Refinement::evaluate_limit`) written in place of the last level's points, its
//! UVs and colors too, and its normals; refused, naming the schemes that have it, elsewhere.
//! The masks themselves are checked against OpenSubdiv in `crates/halfedge/tests/opensubdiv.rs`.

use halfedge::glam::DVec3;
use halfedge::refine::Refinement;
use halfedge::subdivide::SubdivideOptions;
use halfedge::{io, HalfEdgeMesh, PolygonMesh, Rule};

use crate::util::{fails, subcount};

/// A closed cube, slightly irregular, with a hard edge, two semi-sharp ones and a semi-sharp
/// corner (OpenSubdiv's tags).
const CUBE: &str =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1.25 -1 1\nv 1 1 1\nv -1 1.5 1\n\
     f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n\
     t crease 2/1/0 0 1 10\nt crease 4/2/0 1 2 2 3 1.5 2.25\nt corner 1/1/0 6 2.5\n";

/// The cube's faces split into triangles, with the same tags (Loop).
const TRIANGLES: &str =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1.25 -1 1\nv 1 1 1\nv -1 1.5 1\n\
     f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n\
     f 4 1 5\nf 4 5 8\nt crease 2/1/0 0 1 10\nt corner 1/1/0 6 2.5\n";

/// A 2 x 2 grid of quads with a UV seam down its middle column, colors an affine function of
/// the position, and a hole (face 3).
const GRID: &str = "v 0 0 0 0.1 0.2 0.3\nv 1 0 0.2 0.3 0.2 0.7\nv 2 0 0 0.5 0.2 0.3\n\
     v 0 1 0.3 0.1 0.4 0.9\nv 1 1 -0.2 0.3 0.4 -0.1\nv 2 1 0.4 0.5 0.4 1.1\n\
     v 0 2 0 0.1 0.6 0.3\nv 1 2 0.1 0.3 0.6 0.5\nv 2 2 -0.3 0.5 0.6 -0.3\n\
     vt 0 0\nvt 0.5 0\nvt 0 0.5\nvt 0.5 0.5\nvt 0 1\nvt 0.5 1\n\
     vt 0.6 0\nvt 1 0\nvt 0.6 0.5\nvt 1 0.5\nvt 0.6 1\nvt 1 1\n\
     f 1/1 2/2 5/4 4/3\nf 2/7 3/8 6/10 5/9\nf 4/3 5/4 8/6 7/5\nf 5/9 6/10 9/12 8/11\n";

/// Writes `text` as `name` in a fresh folder; returns the folder (kept alive) and the path.
fn file(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("written");
    let path = path.to_str().expect("UTF-8 path").to_owned();
    (dir, path)
}

/// `subcount subdivide --mesh path --scheme scheme --levels levels -o out.obj` with `extra`:
/// the output's text (exit 0 asserted).
fn subdivided(path: &str, scheme: &str, levels: u32, extra: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("out.obj");
    let out = out.to_str().expect("UTF-8 path");
    let levels = levels.to_string();
    let mut args = vec![
        "subdivide",
        "--mesh",
        path,
        "--scheme",
        scheme,
        "--levels",
        &levels,
    ];
    args.extend_from_slice(&["-o", out]);
    args.extend_from_slice(extra);
    let run = subcount(&args);
    assert_eq!(run.code, 0, "subcount {args:?} failed: {}", run.stderr);
    std::fs::read_to_string(out).expect("the output file")
}

/// `subcount subdivide --mesh path -o out.obj` with `args`: the output's text.
fn subdivided_with(path: &str, args: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("out.obj");
    let out = out.to_str().expect("UTF-8 path");
    let mut all = vec!["subdivide", "--mesh", path, "-o", out];
    all.extend_from_slice(args);
    let run = subcount(&all);
    assert_eq!(run.code, 0, "subcount {all:?} failed: {}", run.stderr);
    std::fs::read_to_string(out).expect("the output file")
}

/// The library's limit of the file: positions, both tangents, and the UVs' limit when the
/// file has `vt`.
struct Library {
    positions: Vec<[f64; 3]>,
    tangents: (Vec<[f64; 3]>, Vec<[f64; 3]>),
    uvs: Option<Vec<[f64; 2]>>,
}

fn library(path: &str, rule: Rule, levels: u32) -> Library {
    let polygons = io::read_mesh(path).expect("read");
    let mesh = HalfEdgeMesh::try_from(&polygons).expect("valid");
    let layout = polygons.uv_layout();
    let mut opts = SubdivideOptions::default().with_limit(true);
    if let Some(layout) = &layout {
        opts = opts.with_uvs(layout);
    }
    let r = Refinement::new(&mesh, rule, levels, &opts).expect("refined");
    let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    let n = r.n_vertices(levels);
    let mut positions = vec![[0.0; 3]; n];
    let (mut t1, mut t2) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
    r.evaluate_limit(&base, &mut positions, Some((&mut t1, &mut t2)))
        .expect("evaluated");
    let uvs = layout.map(|layout| {
        let base: Vec<[f64; 2]> = layout.values().iter().map(|v| v.to_array()).collect();
        let mut out = vec![[0.0; 2]; r.n_uvs(levels)];
        r.evaluate_limit_uvs(&base, &mut out).expect("uvs");
        out
    });
    Library {
        positions,
        tangents: (t1, t2),
        uvs,
    }
}

fn read(text: &str) -> PolygonMesh {
    io::read_obj_from(text.as_bytes(), "output").expect("an OBJ")
}

/// The `vn` lines of an OBJ text.
fn normals(text: &str) -> Vec<DVec3> {
    text.lines()
        .filter_map(|l| l.strip_prefix("vn "))
        .map(|l| {
            let x: Vec<f64> = l
                .split_whitespace()
                .map(|w| w.parse().expect("a number"))
                .collect();
            DVec3::new(x[0], x[1], x[2])
        })
        .collect()
}

#[test]
fn the_limit_written_is_the_librarys_to_the_bit() {
    let (_d1, cube) = file("cube.obj", CUBE);
    let (_d2, tri) = file("tri.obj", TRIANGLES);
    for (path, scheme, rule) in [
        (&cube, "catmull-clark", Rule::CatmullClark),
        (&tri, "loop", Rule::Loop),
        (&tri, "catmull-clark", Rule::CatmullClark),
    ] {
        for levels in 0..=3 {
            if rule == Rule::CatmullClark && path == &tri && levels == 0 {
                continue;
            }
            let text = subdivided(path, scheme, levels, &["--limit", "--normals", "limit"]);
            let written = read(&text);
            let lib = library(path, rule, levels);
            let ours: Vec<[f64; 3]> = written.positions.iter().map(|p| p.to_array()).collect();
            assert_eq!(ours, lib.positions, "{scheme} level {levels}");
            // The normals: normalize(T1 x T2), turned towards the area-weighted normal.
            let area = halfedge::normals::vertex_normals(&written.positions, written.faces());
            let vn = normals(&text);
            assert_eq!(vn.len(), written.n_vertices());
            let (t1, t2) = &lib.tangents;
            for (v, n) in vn.iter().enumerate() {
                let (a, b) = (DVec3::from_array(t1[v]), DVec3::from_array(t2[v]));
                let expected = halfedge::normals::limit_normal(a, b, area[v]);
                assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-12, "{n}");
                assert!(n.dot(area[v]) >= 0.0);
                assert!(
                    (*n - expected).length() < 1e-15,
                    "{scheme} {levels} vertex {v}"
                );
            }
            // Threads and precision: the same bytes for every thread count; f32 close.
            let two = subdivided(
                path,
                scheme,
                levels,
                &["--limit", "--normals", "limit", "--threads", "2"],
            );
            assert_eq!(two, text, "{scheme} level {levels}: --threads 2");
            let f32_text = subdivided(path, scheme, levels, &["--limit", "--precision", "f32"]);
            let f32_mesh = read(&f32_text);
            for (a, b) in f32_mesh.positions.iter().zip(&written.positions) {
                assert!(
                    a.distance(*b) < 1e-5,
                    "{scheme} level {levels}: f32 {a} vs {b}"
                );
            }
        }
    }
}

#[test]
fn normals_alone_stay_area_weighted_and_limit_normals_need_no_limit() {
    let (_d, cube) = file("cube.obj", CUBE);
    let plain = subdivided(&cube, "catmull-clark", 2, &["--normals"]);
    assert_eq!(
        plain,
        subdivided(&cube, "catmull-clark", 2, &["--normals", "area"])
    );
    let written = read(&plain);
    let area = halfedge::normals::vertex_normals(&written.positions, written.faces());
    assert_eq!(normals(&plain), area);
    // The last level's points, with the limit surface's normals.
    let limit_normals = subdivided(&cube, "catmull-clark", 2, &["--normals", "limit"]);
    let points = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| l.starts_with("v "))
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(points(&limit_normals), points(&plain));
    let lib = library(&cube, Rule::CatmullClark, 2);
    let (t1, t2) = &lib.tangents;
    let expected: Vec<DVec3> = (0..area.len())
        .map(|v| {
            let (a, b) = (DVec3::from_array(t1[v]), DVec3::from_array(t2[v]));
            halfedge::normals::limit_normal(a, b, area[v])
        })
        .collect();
    assert_eq!(normals(&limit_normals), expected);
    assert_ne!(expected, area);
    // --limit with area normals: those of the limit positions written.
    let text = subdivided(&cube, "catmull-clark", 2, &["--limit", "--normals"]);
    let limit = read(&text);
    assert_eq!(
        normals(&text),
        halfedge::normals::vertex_normals(&limit.positions, limit.faces())
    );
}

#[test]
fn uvs_and_colors_are_written_at_the_limit_too() {
    let (_d, grid) = file("grid.obj", GRID);
    for (scheme, levels) in [
        ("catmull-clark", 0),
        ("catmull-clark", 1),
        ("catmull-clark", 2),
    ] {
        let text = subdivided(&grid, scheme, levels, &["--limit"]);
        let written = read(&text);
        let lib = library(&grid, Rule::CatmullClark, levels);
        let uvs = written.uvs().expect("the limit UVs");
        let ours: Vec<[f64; 2]> = uvs.coords().iter().map(|v| v.to_array()).collect();
        assert_eq!(Some(ours), lib.uvs, "{scheme} {levels}");
        // The colors: an affine function of the position in the input, the same function of
        // the limit positions (the masks are affine).
        let colors = written.colors().expect("colors");
        let f = |p: DVec3| [0.1 + 0.2 * p.x, 0.2 + 0.2 * p.y, 0.3 + 2.0 * p.z];
        for (c, p) in colors.iter().zip(&written.positions) {
            for (a, b) in c.iter().zip(f(*p)) {
                assert!((a - b).abs() < 1e-12, "color {c:?} at {p}");
            }
        }
    }
    // With a hole: the written vertices' limit is the whole grid's at the same vertex (matched
    // by the last level's points, which a hole does not move either).
    let (_d2, holed) = file("holed.obj", &format!("{GRID}t hole 1/0/0 3\n"));
    let points = |path: &str| read(&subdivided(path, "catmull-clark", 2, &[])).positions;
    let (whole_points, part_points) = (points(&grid), points(&holed));
    let whole = read(&subdivided(&grid, "catmull-clark", 2, &["--limit"]));
    let part = read(&subdivided(&holed, "catmull-clark", 2, &["--limit"]));
    assert!(part.n_vertices() < whole.n_vertices());
    assert_eq!(part.n_vertices(), part_points.len());
    for (v, p) in part_points.iter().enumerate() {
        let w = whole_points
            .iter()
            .position(|q| q == p)
            .expect("a written vertex is a vertex of the whole grid");
        assert_eq!(part.positions[v], whole.positions[w], "vertex {v}");
    }
}

#[test]
fn the_limit_is_the_same_for_every_thread_count() {
    // Levels of more than 16,384 vertices: the rows are evaluated in parallel chunks.
    for (base, scheme, levels) in [("cube", "catmull-clark", "6"), ("icosahedron", "loop", "6")] {
        let run = |threads: &str| {
            let dir = tempfile::tempdir().expect("a temporary folder");
            let out = dir.path().join("out.obj");
            let out = out.to_str().expect("UTF-8 path").to_owned();
            let args = [
                "subdivide",
                "--base",
                base,
                "--scheme",
                scheme,
                "--levels",
                levels,
                "--limit",
                "--normals",
                "limit",
                "--threads",
                threads,
                "-o",
                &out,
            ];
            let run = subcount(&args);
            assert_eq!(run.code, 0, "{}", run.stderr);
            std::fs::read(&out).expect("written")
        };
        let one = run("1");
        assert!(read(std::str::from_utf8(&one).expect("text")).n_vertices() > 16_384);
        assert!(one == run("2"), "{scheme}: --threads 1 and 2 differ");
    }
}

#[test]
fn the_limit_is_refused_where_there_are_no_limit_masks() {
    let (_d, cube) = file("cube.obj", CUBE);
    let (_d2, tri) = file("tri.obj", TRIANGLES);
    let named = "loop, loop-boundary and catmull-clark";
    for (path, scheme) in [(&cube, "doo-sabin"), (&tri, "sqrt3"), (&tri, "butterfly")] {
        for flags in [&["--limit"][..], &["--normals", "limit"][..]] {
            let mut args = vec![
                "subdivide",
                "--mesh",
                path,
                "--scheme",
                scheme,
                "--levels",
                "1",
            ];
            args.extend_from_slice(flags);
            fails(&args, 2, named);
        }
    }
    let args = [
        "subdivide",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark:1,doo-sabin",
        "--levels",
        "2",
        "--limit",
    ];
    fails(&args, 2, named);
    // Catmull-Clark at level 0 of a mesh with triangles: OpenSubdiv's masks need quads.
    let args = [
        "subdivide",
        "--mesh",
        &tri,
        "--scheme",
        "catmull-clark",
        "--levels",
        "0",
        "--limit",
    ];
    fails(&args, 3, "tri.obj: line 9: face 0 has 3 sides");
    // Loop's other name and scheme files that run Loop or Catmull-Clark have it, giving its
    // limit; one that runs √3 has not.
    let expected = subdivided(&tri, "loop", 1, &["--limit"]);
    assert_eq!(subdivided(&tri, "loop-boundary", 1, &["--limit"]), expected);
    let file = crate::util::example_scheme("loop-boundary.toml");
    let text = subdivided_with(&tri, &["--scheme-file", &file, "--levels", "1", "--limit"]);
    assert_eq!(text, expected);
    let file = crate::util::example_scheme("sqrt3-boundary.toml");
    let args = [
        "subdivide",
        "--mesh",
        &tri,
        "--scheme-file",
        &file,
        "--levels",
        "1",
        "--limit",
    ];
    fails(&args, 2, named);
}

#[test]
fn frames_evaluate_the_limit() {
    let (_d, cube) = file("cube.obj", CUBE);
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("out.obj");
    let out = out.to_str().expect("UTF-8 path");
    let args = [
        "subdivide",
        "--mesh",
        &cube,
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--limit",
        "--normals",
        "limit",
        "--frames",
        "3",
        "--timings",
        "-o",
        out,
    ];
    let run = subcount(&args);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stderr.contains("evaluate_s"), "{}", run.stderr);
    // The unmoved evaluation is written.
    assert_eq!(
        std::fs::read_to_string(out).expect("written"),
        subdivided(
            &cube,
            "catmull-clark",
            2,
            &["--limit", "--normals", "limit"]
        )
    );
}
