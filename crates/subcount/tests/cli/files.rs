//! Issue 27: what a production mesh carries survives `subdivide -o`: materials, objects,
//! groups and smoothing groups (each output face takes its base face's), vertex colors
//! (refined with the positions' weights), and a note on what is not carried.

use halfedge::groups::Statement;
use halfedge::{io, HalfEdgeMesh, Refinement};

use crate::util::{ok, subcount};

/// A cube whose face `f` has the material `m{f}`, the group `g{f % 2}` and the smoothing
/// group `s {f / 3}`, in one object; `extra` lines are added at the end.
fn grouped_cube(extra: &str) -> String {
    let mut text = String::from("mtllib a.mtl b.mtl\nmtllib c.mtl\no box\n");
    for v in 0..8 {
        let (x, y, z) = (v & 1, (v >> 1) & 1, (v >> 2) & 1);
        text.push_str(&format!("v {x} {y} {z}\n"));
    }
    let faces = [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [2, 4, 8, 6],
        [4, 3, 7, 8],
        [3, 1, 5, 7],
    ];
    for (f, face) in faces.iter().enumerate() {
        text.push_str(&format!("usemtl m{f}\ng g{}\ns {}\n", f % 2, f / 3));
        text.push_str(&format!(
            "f {} {} {} {}\n",
            face[0], face[1], face[2], face[3]
        ));
    }
    text + extra
}

/// An octahedron, each face its own material and group.
fn grouped_octahedron() -> String {
    let mut text = String::from("mtllib o.mtl\n");
    for p in ["1 0 0", "-1 0 0", "0 1 0", "0 -1 0", "0 0 1", "0 0 -1"] {
        text.push_str(&format!("v {p}\n"));
    }
    let faces = [
        [1, 3, 5],
        [3, 2, 5],
        [2, 4, 5],
        [4, 1, 5],
        [3, 1, 6],
        [2, 3, 6],
        [4, 2, 6],
        [1, 4, 6],
    ];
    for (f, face) in faces.iter().enumerate() {
        text.push_str(&format!("usemtl m{f}\ng g{f}\n"));
        text.push_str(&format!("f {} {} {}\n", face[0], face[1], face[2]));
    }
    text
}

/// The arguments of `subcount subdivide --mesh input --scheme scheme --levels levels`, then
/// `rest` (`-o FILE`, flags).
fn subdivide_args<'a>(
    input: &'a str,
    scheme: &'a str,
    levels: &'a str,
    rest: &[&'a str],
) -> Vec<&'a str> {
    let mut args = vec![
        "subdivide",
        "--mesh",
        input,
        "--scheme",
        scheme,
        "--levels",
        levels,
    ];
    args.extend_from_slice(rest);
    args
}

/// Writes `text` to `dir/name` and returns the path.
fn write(dir: &tempfile::TempDir, name: &str, text: &str) -> String {
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("written");
    path.to_string_lossy().into_owned()
}

/// The base face of every written face, from the library: the refinement's (the raw face
/// list's nesting splits number faces alike).
fn library_base_faces(input: &str, rule: halfedge::Rule, levels: u32) -> Vec<u32> {
    let poly = io::read_obj(input).expect("read");
    let mesh = HalfEdgeMesh::try_from(&poly).expect("a manifold");
    let opts = halfedge::subdivide::SubdivideOptions::default();
    let r = Refinement::new(&mesh, rule, levels, &opts).expect("refined");
    r.base_faces(levels).expect("base faces")
}

/// Checks that every face of `output` has the material and group of its base face
/// (`m{b}`, `g{…}` as the input names them) and that a statement line is written only where
/// the value changes.
fn check_groups(input: &str, output: &str, base: &[u32], what: &str) {
    let read_in = io::read_obj(input).expect("input");
    let read_out = io::read_obj(output).expect("output");
    let (gin, gout) = (
        read_in.groups().expect("input groups"),
        read_out
            .groups()
            .unwrap_or_else(|| panic!("{what}: no groups written")),
    );
    assert_eq!(gout.mtllib(), gin.mtllib(), "{what}");
    assert_eq!(gout.n_faces(), base.len(), "{what}");
    for (f, &b) in base.iter().enumerate() {
        for s in Statement::ALL {
            assert_eq!(
                gout.value(f, s),
                gin.value(b as usize, s),
                "{what}: face {f} (base {b}), {s:?}"
            );
        }
    }
    let text = std::fs::read_to_string(output).expect("output text");
    let mut last: Option<&str> = None;
    let mut changes = 0;
    for f in 0..base.len() {
        let m = gout.value(f, Statement::Material);
        if m != last {
            changes += 1;
        }
        last = m;
    }
    let usemtl = text.lines().filter(|l| l.starts_with("usemtl ")).count();
    assert_eq!(
        usemtl, changes,
        "{what}: a usemtl line per change, never one per face"
    );
    let first_v = text.lines().position(|l| l.starts_with("v ")).expect("v");
    let mtllib: Vec<&str> = text.lines().filter(|l| l.starts_with("mtllib")).collect();
    assert_eq!(mtllib, gin.mtllib(), "{what}");
    assert!(
        text.lines().take(first_v).all(|l| l.starts_with("mtllib")),
        "{what}: mtllib lines first"
    );
}

#[test]
fn every_output_face_has_its_base_faces_material_and_group_under_every_scheme() {
    use halfedge::Rule;
    let dir = tempfile::tempdir().expect("temp dir");
    let cube = write(&dir, "cube.obj", &grouped_cube(""));
    let holed = write(&dir, "holed.obj", &grouped_cube("t hole 1/0/0 2\n"));
    let octa = write(&dir, "octa.obj", &grouped_octahedron());
    let out = dir.path().join("out.obj").to_string_lossy().into_owned();
    let cases: &[(&str, &str, Rule, &[&str])] = &[
        (&cube, "catmull-clark", Rule::CatmullClark, &[]),
        (
            &cube,
            "catmull-clark",
            Rule::CatmullClark,
            &["--precision", "f32"],
        ),
        (&cube, "catmull-clark-general", Rule::CatmullClark, &[]),
        (&cube, "doo-sabin", Rule::DooSabin, &[]),
        (&cube, "mid-edge", Rule::MidEdge, &["--frames", "1"]),
        (&holed, "catmull-clark", Rule::CatmullClark, &[]),
        (
            &holed,
            "catmull-clark",
            Rule::CatmullClark,
            &["--precision", "f32"],
        ),
        (&octa, "loop", Rule::Loop, &[]),
        (&octa, "loop-general", Rule::Loop, &[]),
        (&octa, "midpoint", Rule::Midpoint, &[]),
        (&octa, "butterfly", Rule::Butterfly, &[]),
        (&octa, "icosphere", Rule::Icosphere, &[]),
        (&octa, "tri-split-3", Rule::TriSplit(3), &[]),
        (&octa, "sqrt3", Rule::Sqrt3, &[]),
        (&octa, "sqrt3", Rule::Sqrt3, &["--precision", "f32"]),
    ];
    for &(input, scheme, rule, flags) in cases {
        for levels in 0..=2u32 {
            let l = levels.to_string();
            let mut args = subdivide_args(input, scheme, &l, &["-o", &out]);
            args.extend_from_slice(flags);
            ok(&args);
            let base = library_base_faces(input, rule, levels);
            let what = format!("{scheme} {flags:?} level {levels} on {input}");
            check_groups(input, &out, &base, &what);
        }
    }
}

#[test]
fn a_file_without_statements_or_colors_is_written_without_them() {
    let dir = tempfile::tempdir().expect("temp dir");
    let plain: String = grouped_cube("")
        .lines()
        .filter(|l| l.starts_with("v ") || l.starts_with("f "))
        .map(|l| format!("{l}\n"))
        .collect();
    let input = write(&dir, "plain.obj", &plain);
    let out = dir.path().join("out.obj").to_string_lossy().into_owned();
    ok(&subdivide_args(&input, "catmull-clark", "1", &["-o", &out]));
    let text = std::fs::read_to_string(&out).expect("output");
    assert!(text
        .lines()
        .all(|l| (l.starts_with("v ") && l.split(' ').count() == 4) || l.starts_with("f ")));
}

/// The colors `r g b` of a point: an affine function of its position.
fn affine(p: [f64; 3]) -> [f64; 3] {
    [
        0.25 + 0.5 * p[0] - 0.125 * p[1],
        -0.5 + 2.0 * p[2],
        3.0 * p[0] + p[1] - p[2] + 1.0,
    ]
}

/// `mesh` (OBJ text with `v x y z` lines) with each vertex given its affine color.
fn colored(mesh: &str) -> String {
    mesh.lines()
        .map(|l| match l.strip_prefix("v ") {
            Some(rest) => {
                let p: Vec<f64> = rest.split(' ').map(|t| t.parse().expect("f64")).collect();
                let [r, g, b] = affine([p[0], p[1], p[2]]);
                format!("v {} {} {} {r} {g} {b}\n", p[0], p[1], p[2])
            }
            None => format!("{l}\n"),
        })
        .collect()
}

/// A color field that is an affine function of position stays that function of the refined
/// positions under every rule but the icosphere's projection (up to rounding), in `f64`, in
/// `f32` and with frames; under the icosphere the colors are the midpoint rule's.
#[test]
fn affine_colors_stay_affine_functions_of_the_refined_positions() {
    let dir = tempfile::tempdir().expect("temp dir");
    let cube = write(&dir, "cube.obj", &colored(&grouped_cube("")));
    let octa = write(&dir, "octa.obj", &colored(&grouped_octahedron()));
    let out = dir.path().join("out.obj").to_string_lossy().into_owned();
    let cases: &[(&str, &str, &[&str], f64)] = &[
        (&cube, "catmull-clark", &[], 1e-12),
        (&cube, "catmull-clark", &["--precision", "f32"], 1e-5),
        (&cube, "catmull-clark-general", &[], 1e-12),
        (&cube, "doo-sabin", &["--frames", "2"], 1e-12),
        (&cube, "mid-edge", &[], 1e-12),
        (&octa, "loop", &[], 1e-12),
        (&octa, "loop-general", &[], 1e-12),
        (&octa, "midpoint", &[], 1e-12),
        (&octa, "butterfly", &[], 1e-12),
        (&octa, "tri-split-3", &[], 1e-12),
        (&octa, "loop", &["--precision", "f32"], 1e-5),
        (&octa, "sqrt3", &[], 1e-12),
    ];
    for &(input, scheme, flags, tolerance) in cases {
        for levels in 0..=2u32 {
            let l = levels.to_string();
            let mut args = subdivide_args(input, scheme, &l, &["-o", &out]);
            args.extend_from_slice(flags);
            ok(&args);
            let mesh = io::read_obj(&out).expect("output");
            let colors = mesh.colors().expect("colors written");
            for (p, c) in mesh.positions.iter().zip(colors) {
                let want = affine(p.to_array());
                for k in 0..3 {
                    assert!(
                        (c[k] - want[k]).abs() <= tolerance * (1.0 + want[k].abs()),
                        "{scheme} {flags:?} level {levels}: {c:?} at {p:?}, expected {want:?}"
                    );
                }
            }
        }
    }
    // The icosphere: positions projected, colors those of the midpoint rule.
    for levels in 1..=2u32 {
        let l = levels.to_string();
        let mid = dir.path().join("mid.obj").to_string_lossy().into_owned();
        ok(&subdivide_args(&octa, "icosphere", &l, &["-o", &out]));
        ok(&subdivide_args(&octa, "midpoint", &l, &["-o", &mid]));
        let sphere = io::read_obj(&out).expect("icosphere");
        let midpoint = io::read_obj(&mid).expect("midpoint");
        assert_eq!(sphere.colors(), midpoint.colors(), "level {levels}");
        assert_ne!(sphere.positions, midpoint.positions);
    }
}

#[test]
fn colors_and_groups_change_no_count() {
    let dir = tempfile::tempdir().expect("temp dir");
    let plain_of = |text: String| -> String {
        text.lines()
            .filter(|l| !l.starts_with("usemtl") && !l.starts_with("g ") && !l.starts_with("s "))
            .filter(|l| !l.starts_with("o ") && !l.starts_with("mtllib"))
            .map(|l| format!("{l}\n"))
            .collect()
    };
    for (scheme, hole) in [("catmull-clark", "t hole 1/0/0 2\n"), ("doo-sabin", "")] {
        let rich = write(&dir, "rich.obj", &colored(&grouped_cube(hole)));
        let plain = write(&dir, "plain.obj", &plain_of(grouped_cube(hole)));
        let table = |m: &str| ok(&["table", "--mesh", m, "--scheme", scheme, "--levels", "3"]);
        assert_eq!(table(&rich), table(&plain), "{scheme}");
        let verify = |m: &str| ok(&["verify", "--mesh", m, "--scheme", scheme, "--levels", "2"]);
        assert_eq!(
            verify(&rich).replace(&rich, "M"),
            verify(&plain).replace(&plain, "M")
        );
        let summary = |m: &str| {
            let out = ok(&subdivide_args(m, scheme, "2", &[]));
            out.replace(m, "M")
        };
        assert_eq!(summary(&rich), summary(&plain));
    }
}

#[test]
fn partial_colors_uncarried_lines_and_stats() {
    let dir = tempfile::tempdir().expect("temp dir");
    let text = "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nv 1 1 0 0.5 0.5 0.5\nvn 0 0 1\nvn 0 0 1\n\
                f 1 2 4 3\nl 1 2\np 3\ncstype bezier\n";
    let input = write(&dir, "partial.obj", text);
    let out = dir.path().join("out.obj").to_string_lossy().into_owned();
    let run = subcount(&subdivide_args(&input, "catmull-clark", "1", &["-o", &out]));
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        run.stderr,
        format!(
            "note: {input}: 3 of 4 vertices have colors: no color channel\n\
             note: {input}: not carried into the output: 1 cstype lines, 1 l lines, 1 p lines, 2 vn lines\n"
        )
    );
    assert!(io::read_obj(&out).expect("output").colors().is_none());
    // Without -o nothing is written, so nothing is said about carrying.
    let run = subcount(&subdivide_args(&input, "catmull-clark", "1", &[]));
    assert!(!run.stderr.contains("not carried"), "{}", run.stderr);
    let rich = write(&dir, "rich.obj", &colored(&grouped_cube("")));
    let text = ok(&["stats", "--mesh", &rich]);
    assert!(text.contains("\nvertex colors: 3 channels\n"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["stats", "--mesh", &rich, "--format", "json"])).expect("json");
    assert_eq!(json["colors"], 3);
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["stats", "--mesh", &input, "--format", "json"])).expect("json");
    assert!(json.get("colors").is_none());
    // COFF colors are the channel too, alpha left out.
    let off = "COFF\n4 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 255\n4 0 1 2 3\n";
    let input = write(&dir, "c.off", off);
    let text = ok(&["stats", "--mesh", &input]);
    assert!(text.contains("vertex colors: 3 channels"), "{text}");
    ok(&subdivide_args(&input, "catmull-clark", "0", &["-o", &out]));
    let mesh = io::read_obj(&out).expect("output");
    assert_eq!(mesh.colors().expect("colors")[3], [9.0, 9.0, 9.0]);
}

/// A shared mesh's text with a material per face (`usemtl m{f}`) and a group every third face,
/// its own statements removed, and `extra` lines added.
fn per_face_materials(text: &str, extra: &str) -> String {
    let mut out = String::new();
    let mut f = 0usize;
    for line in text.lines() {
        let keyword = line.split_whitespace().next().unwrap_or("");
        if matches!(keyword, "usemtl" | "g" | "o" | "s") {
            continue;
        }
        if keyword == "f" {
            out.push_str(&format!("usemtl m{f}\n"));
            if f % 3 == 0 {
                out.push_str(&format!("g g{}\n", f / 3));
            }
            f += 1;
        }
        out.push_str(line);
        out.push('\n');
    }
    out + extra
}

/// Shared meshes (triangles, quads, n-gons, boundaries, creases) with a material per face:
/// under every scheme that applies, at level 1, every output face has its base face's
/// material and group, with a hole under the schemes whose faces nest.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn shared_meshes_keep_every_faces_material_under_every_scheme() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("out.obj").to_string_lossy().into_owned();
    for name in [
        "bob_tri.obj",
        "spot_control_mesh.obj",
        "cylinder_ngon.obj",
        "planexy.obj",
        "osd_catmark_pyramid.obj",
        "osd_catmark_pawn.obj",
    ] {
        let text = std::fs::read_to_string(testdata::mesh(name)).expect("a shared mesh");
        let json: serde_json::Value = serde_json::from_str(&ok(&[
            "stats",
            "--mesh",
            &testdata::mesh(name).to_string_lossy(),
            "--format",
            "json",
        ]))
        .expect("json");
        let schemes: Vec<String> = json["applicable_schemes"]
            .as_array()
            .expect("schemes")
            .iter()
            .map(|s| s.as_str().expect("a name").to_owned())
            .collect();
        for scheme in &schemes {
            let nests = !["sqrt3", "doo-sabin", "mid-edge"]
                .iter()
                .any(|p| scheme.starts_with(p));
            let variants: &[&str] = if nests {
                &["", "t hole 1/0/0 1\n"]
            } else {
                &[""]
            };
            for extra in variants {
                let input = write(&dir, name, &per_face_materials(&text, extra));
                let run = subcount(&subdivide_args(&input, scheme, "1", &["-o", &out]));
                assert_eq!(run.code, 0, "{scheme} on {name}: {}", run.stderr);
                let poly = io::read_obj(&input).expect("input");
                let counts = halfedge::stats::face_list_counts(&poly);
                let builtin = halfedge::schemes::builtin(scheme).expect("a scheme");
                let rule = halfedge::subdivide::checked_rule(&builtin, &counts).expect("rule");
                let base = library_base_faces(&input, rule, 1);
                check_groups(
                    &input,
                    &out,
                    &base,
                    &format!("{scheme} on {name} {extra:?}"),
                );
            }
        }
    }
}

/// `-o NAME.ply` writes binary PLY: the same mesh as the OBJ output (positions to the bit,
/// faces, colors as `uchar` when in [0, 1] else as floats, UVs per corner), in `f64` and
/// `f32`, through every path; `--mesh x.ply` reads it back.
#[test]
fn ply_output_is_the_obj_output_in_binary() {
    let dir = tempfile::tempdir().expect("temp dir");
    // Colors outside [0, 1] (the affine field): written as floats, read back exactly.
    let wide = write(&dir, "wide.obj", &colored(&grouped_cube("")));
    // Colors in [0, 1] at multiples of 1/255: written as uchar, read back exactly.
    let narrow_text: String = grouped_cube("")
        .lines()
        .enumerate()
        .map(|(i, l)| match l.strip_prefix("v ") {
            Some(p) => format!("v {p} {} 0 1\n", (i % 7) as f64 * 17.0 / 255.0),
            None => format!("{l}\n"),
        })
        .collect();
    let narrow = write(&dir, "narrow.obj", &narrow_text);
    let uv = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n\
              vt 0 1\nvt 0.5 0\nvt 0.5 1\nf 1/1 2/2 3/3 4/4\nf 2/5 5/2 6/3 3/6\n";
    let seams = write(&dir, "seams.obj", uv);
    let obj = dir.path().join("out.obj").to_string_lossy().into_owned();
    let ply = dir.path().join("out.ply").to_string_lossy().into_owned();
    let cases: &[(&str, &str, &[&str])] = &[
        (&wide, "catmull-clark", &[]),
        (&wide, "catmull-clark", &["--precision", "f32"]),
        (&narrow, "catmull-clark", &["--normals"]),
        (&narrow, "doo-sabin", &[]),
        (&narrow, "catmull-clark-general", &[]),
        (&seams, "catmull-clark", &[]),
        (
            &seams,
            "catmull-clark",
            &["--precision", "f32", "--normals"],
        ),
    ];
    for &(input, scheme, flags) in cases {
        for levels in ["0", "1", "2"] {
            let what = format!("{scheme} {flags:?} level {levels} on {input}");
            for out in [&obj, &ply] {
                let mut args = subdivide_args(input, scheme, levels, &["-o", out]);
                args.extend_from_slice(flags);
                let run = subcount(&args);
                assert_eq!(run.code, 0, "{what}: {}", run.stderr);
                // PLY has no place for materials: said once, never silently.
                let grouped = out == &ply && input != seams;
                let note = format!(
                    "note: {input}: materials and groups are not written to PLY: name the output .obj to keep them\n"
                );
                assert_eq!(
                    run.stderr,
                    if grouped { note } else { String::new() },
                    "{what}"
                );
            }
            let a = io::read_obj(&obj).expect("obj");
            let b = io::read_ply(&ply).unwrap_or_else(|e| panic!("{what}: {e}"));
            // In f32 the OBJ text is the shortest f32 text: equal once read as f32.
            let f32 = flags.contains(&"f32");
            let round = |x: f64| if f32 { f64::from(x as f32) } else { x };
            let points = |m: &halfedge::PolygonMesh| -> Vec<[f64; 3]> {
                m.positions
                    .iter()
                    .map(|p| p.to_array().map(round))
                    .collect()
            };
            assert_eq!(points(&a), points(&b), "{what}");
            assert_eq!(a.face_indices(), b.face_indices(), "{what}");
            // Colors in [0, 1] are written as uchar: round(c · 255) / 255 read back; others
            // as float.
            let unit = a
                .colors()
                .is_some_and(|c| c.iter().flatten().all(|x| (0.0..=1.0).contains(x)));
            let quantize = |x: f64| match unit {
                true => (x * 255.0).round() / 255.0,
                false => f64::from(x as f32),
            };
            let colors = |m: &halfedge::PolygonMesh| -> Option<Vec<[f64; 3]>> {
                m.colors()
                    .map(|c| c.iter().map(|c| c.map(quantize)).collect())
            };
            assert_eq!(colors(&a), colors(&b), "{what}");
            let corner_uvs = |m: &halfedge::PolygonMesh| {
                m.uvs().map(|u| {
                    u.corners()
                        .iter()
                        .map(|&c| u.coords()[c as usize].to_array().map(round))
                        .collect::<Vec<_>>()
                })
            };
            assert_eq!(corner_uvs(&a), corner_uvs(&b), "{what}");
            // The PLY reads back as a mesh subcount takes.
            let stats = ok(&["stats", "--mesh", &ply]);
            assert!(stats.contains("manifold"), "{what}: {stats}");
        }
    }
    let header = std::fs::read(&ply).expect("ply");
    let text = String::from_utf8_lossy(&header[..200]);
    assert!(text.contains("property float x\n"), "f32 positions: {text}");
    assert!(text.contains("property float nx\n"), "normals: {text}");
}

/// Compositions carry groups and colors stage by stage: after `loop:1,sqrt3` each face has
/// the material of the base face it comes from through both stages, and affine colors stay
/// affine.
#[test]
fn compositions_carry_groups_and_colors() {
    use halfedge::Rule;
    let dir = tempfile::tempdir().expect("temp dir");
    let input = write(&dir, "octa.obj", &colored(&grouped_octahedron()));
    let one = dir.path().join("one.obj").to_string_lossy().into_owned();
    let two = dir.path().join("two.obj").to_string_lossy().into_owned();
    let run = |levels: &str, out: &str| {
        ok(&subdivide_args(
            &input,
            "loop:1,sqrt3",
            levels,
            &["-o", out],
        ))
    };
    run("1", &one);
    run("2", &two);
    let first = library_base_faces(&input, Rule::Loop, 1);
    let second = library_base_faces(&one, Rule::Sqrt3, 1);
    let base: Vec<u32> = second.iter().map(|&f| first[f as usize]).collect();
    check_groups(&input, &two, &base, "loop:1,sqrt3 level 2");
    // PLY and the refusal of other formats as for one scheme; the notes too.
    let ply = dir.path().join("two.ply").to_string_lossy().into_owned();
    let args = subdivide_args(&input, "loop:1,sqrt3", "2", &[]);
    let run = subcount(&[&args[..], &["-o", &ply]].concat());
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stderr.contains("not written to PLY"), "{}", run.stderr);
    let back = io::read_ply(&ply).expect("PLY");
    assert_eq!(back.positions, io::read_obj(&two).expect("obj").positions);
    let stl = dir.path().join("two.stl").to_string_lossy().into_owned();
    crate::util::fails(
        &[&args[..], &["-o", &stl]].concat(),
        2,
        "does not write STL files",
    );
    let mesh = io::read_obj(&two).expect("output");
    for (p, c) in mesh.positions.iter().zip(mesh.colors().expect("colors")) {
        let want = affine(p.to_array());
        for k in 0..3 {
            assert!(
                (c[k] - want[k]).abs() <= 1e-12 * (1.0 + want[k].abs()),
                "{c:?} {want:?}"
            );
        }
    }
}
