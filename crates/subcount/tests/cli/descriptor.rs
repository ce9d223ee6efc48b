//! Issue 26, item 6: the mesh carries what its file says. A Rust user who reads a tagged OBJ,
//! builds `HalfEdgeMesh::try_from` and subdivides with the default options gets exactly what
//! `subcount subdivide` writes for that file: creases, corners, holes, boundary modes, the
//! face-varying mode and UVs honoured, under every rule as the command line applies them.

use halfedge::subdivide::{subdivide_to_face_list, SubdivideOptions};
use halfedge::{io, HalfEdgeMesh, PolygonMesh, Rule};

use crate::util::{data, subcount};

/// A closed cube with a hard edge, two semi-sharp ones and a semi-sharp corner.
const CUBE: &str =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1.25 -1 1\nv 1 1 1\nv -1 1.5 1\n\
     f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n\
     t crease 2/1/0 0 1 10\nt crease 4/2/0 1 2 2 3 1.5 2.25\nt corner 1/1/0 6 2.5\n";

/// A 3 x 2 grid of quads with boundary.
const GRID: &str =
    "v 0 0 0\nv 1 0 0.2\nv 2 0 0\nv 3 0 0.1\nv 0 1 0.3\nv 1 1 -0.2\nv 2 1 0.4\nv 3 1 0\n\
     v 0 2 0\nv 1 2 0.1\nv 2 2 -0.3\nv 3 2 0.2\n\
     f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 5 6 10 9\nf 6 7 11 10\nf 7 8 12 11\n";

/// An `n` x `n` grid of quads with boundary, not flat, with `tags`.
fn quad_grid(n: u32, tags: &str) -> String {
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            text.push_str(&format!(
                "v {i} {j} {}\n",
                f64::from((i * 7 + j * 3) % 5) / 10.0
            ));
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            text.push_str(&format!("f {a} {} {} {}\n", a + 1, a + n + 2, a + n + 1));
        }
    }
    format!("{text}{tags}")
}

/// The grid's quads split into triangles, with a crease along the middle row.
fn triangle_grid(tags: &str) -> String {
    let head: String = GRID
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| format!("{l}\n"))
        .collect();
    let mut faces = String::new();
    for l in GRID.lines().filter(|l| l.starts_with("f ")) {
        let v: Vec<&str> = l.split_whitespace().skip(1).collect();
        faces.push_str(&format!(
            "f {} {} {}\nf {} {} {}\n",
            v[0], v[1], v[2], v[0], v[2], v[3]
        ));
    }
    format!("{head}{faces}{tags}")
}

/// What `subcount subdivide` writes for `path`, read back.
fn command_line(path: &str, scheme: &str, levels: u32) -> PolygonMesh {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("out.obj");
    let out = out.to_str().expect("UTF-8 path");
    let levels = levels.to_string();
    let run = subcount(&[
        "subdivide",
        "--mesh",
        path,
        "--scheme",
        scheme,
        "--levels",
        &levels,
        "-o",
        out,
    ]);
    assert_eq!(run.code, 0, "{scheme} on {path}: {}", run.stderr);
    io::read_obj(out).expect("the output reads back")
}

/// The library's default path: read, `try_from`, subdivide with the default options.
fn library(path: &str, rule: Rule, levels: u32) -> PolygonMesh {
    let file = io::read_obj(path).expect("the file reads");
    let mesh = HalfEdgeMesh::try_from(&file).expect("a manifold mesh");
    subdivide_to_face_list(&mesh, rule, levels, &SubdivideOptions::default())
        .expect("subdivides")
        .mesh
}

fn assert_same(what: &str, cli: &PolygonMesh, lib: &PolygonMesh) {
    assert_eq!(cli.positions, lib.positions, "{what}: positions");
    assert_eq!(cli.face_offsets(), lib.face_offsets(), "{what}: faces");
    assert_eq!(cli.face_indices(), lib.face_indices(), "{what}: faces");
    let uvs = |m: &PolygonMesh| m.uvs().map(|u| (u.coords().to_vec(), u.corners().to_vec()));
    assert_eq!(uvs(cli), uvs(lib), "{what}: UVs");
}

#[test]
fn the_default_library_path_writes_what_the_command_line_writes() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let write = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).expect("written");
        path.to_str().expect("UTF-8 path").to_owned()
    };
    let cases: Vec<(String, &str, Rule, u32)> = vec![
        (
            write("cube.obj", CUBE),
            "catmull-clark",
            Rule::CatmullClark,
            2,
        ),
        (
            write(
                "cube-chaikin.obj",
                &format!("{CUBE}t creasemethod 0/0/1 chaikin\n"),
            ),
            "catmull-clark",
            Rule::CatmullClark,
            2,
        ),
        (
            write(
                "corner.obj",
                &format!("{GRID}t interpolateboundary 1/0/0 1\n"),
            ),
            "catmull-clark",
            Rule::CatmullClark,
            2,
        ),
        (
            write(
                "none.obj",
                &quad_grid(4, "t interpolateboundary 1/0/0 0\nt crease 2/1/0 6 7 10\n"),
            ),
            "catmull-clark",
            Rule::CatmullClark,
            2,
        ),
        (
            write("hole.obj", &quad_grid(4, "t hole 2/0/0 5 10\n")),
            "catmull-clark",
            Rule::CatmullClark,
            2,
        ),
        (
            write(
                "tri.obj",
                &triangle_grid("t crease 6/1/0 4 5 5 6 6 7 3\nt interpolateboundary 1/0/0 1\n"),
            ),
            "loop",
            Rule::Loop,
            2,
        ),
        // Rules without crease rules leave creases out (the CLI's note); holes still apply.
        (
            write(
                "tri-hole.obj",
                &triangle_grid("t crease 2/1/0 4 5 3\nt hole 1/0/0 2\n"),
            ),
            "midpoint",
            Rule::Midpoint,
            2,
        ),
        (
            write("tri-sqrt3.obj", &triangle_grid("t crease 2/1/0 4 5 3\n")),
            "sqrt3-boundary",
            Rule::Sqrt3,
            2,
        ),
        (
            data("uv_cube_tagged.obj"),
            "catmull-clark",
            Rule::CatmullClark,
            2,
        ),
        (
            data("uv_cube_hole.obj"),
            "catmull-clark",
            Rule::CatmullClark,
            2,
        ),
        (data("uv_cube.obj"), "doo-sabin", Rule::DooSabin, 1),
    ];
    for (path, scheme, rule, levels) in &cases {
        let what = format!("{scheme} on {path}");
        assert_same(
            &what,
            &command_line(path, scheme, *levels),
            &library(path, *rule, *levels),
        );
    }
    // The tags change the output (the comparison above is not between two untagged runs).
    let file = io::read_obj(&cases[0].0).expect("reads");
    let mesh = HalfEdgeMesh::try_from(&file).expect("valid");
    let plain = SubdivideOptions::default().with_descriptor(false);
    let smooth = subdivide_to_face_list(&mesh, Rule::CatmullClark, 2, &plain).expect("smooth");
    assert_ne!(
        smooth.mesh.positions,
        library(&cases[0].0, Rule::CatmullClark, 2).positions
    );
}

/// Options override what the mesh carries, as a flag overrides a tag.
#[test]
fn options_override_the_descriptor_as_flags_override_tags() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("corner.obj");
    std::fs::write(&path, format!("{GRID}t interpolateboundary 1/0/0 1\n")).expect("written");
    let path = path.to_str().expect("UTF-8 path");
    let out = dir.path().join("out.obj");
    let out = out.to_str().expect("UTF-8 path");
    let run = subcount(&[
        "subdivide",
        "--mesh",
        path,
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--boundary",
        "edge",
        "-o",
        out,
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr.contains("--boundary edge overrides the tag"),
        "{}",
        run.stderr
    );
    let cli = io::read_obj(out).expect("reads back");
    let file = io::read_obj(path).expect("reads");
    let mesh = HalfEdgeMesh::try_from(&file).expect("valid");
    let mut edge = halfedge::tags::SubdivisionOptions::default();
    edge.boundary = halfedge::tags::BoundaryInterpolation::Edge;
    // `Edge` is the default value: an option equal to the default leaves the tag in force, so
    // overriding a tag with the default takes `with_descriptor(false)`.
    let opts = SubdivideOptions::default()
        .with_descriptor(false)
        .with_subdivision(edge);
    let lib = subdivide_to_face_list(&mesh, Rule::CatmullClark, 2, &opts).expect("runs");
    assert_same("--boundary edge over the tag", &cli, &lib.mesh);
    let tagged = library(path, Rule::CatmullClark, 2);
    assert_ne!(
        tagged.positions, cli.positions,
        "the tag changes the corners"
    );
}

/// Boundary `none` under a rule without crease rules is refused, as the command line refuses it.
#[test]
fn boundary_none_under_a_rule_without_crease_rules_is_refused() {
    let file = io::read_obj_from(
        triangle_grid("t interpolateboundary 1/0/0 0\n").as_bytes(),
        "none.obj",
    )
    .expect("reads");
    let mesh = HalfEdgeMesh::try_from(&file).expect("valid");
    let err = subdivide_to_face_list(&mesh, Rule::Sqrt3, 1, &SubdivideOptions::default())
        .expect_err("refused");
    assert!(err.to_string().contains("boundary none"), "{err}");
    let plain = SubdivideOptions::default().with_descriptor(false);
    assert!(subdivide_to_face_list(&mesh, Rule::Sqrt3, 1, &plain).is_ok());
}
