//! `subdivide --levels 0` writes what its summary and `table` say: the vertices the faces use
//! (an unused `v` is left out on every path) and the file's `vt` entries as read (those the
//! written corners use, which is `table`'s `UV` at level 0), on the face-list path too.

use crate::util::{ok, subcount};

/// A textured triangle and a vertex no face uses.
const TRIANGLE_AND_UNUSED_VERTEX: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";

/// Two triangles whose vertices 1 and 4 share `vt 1`: two layout values, one `vt` entry.
const SHARED_VT: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2/2 4/1 3/3\n";

/// A book of three triangles on one edge (non-manifold), textured, and an unused vertex.
const NON_MANIFOLD: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 9 9 9\n\
    vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2/2 1/1 4/3\nf 1/1 2/2 5/3\n";

/// `(v lines, vt lines)` of an OBJ text.
fn lines(obj: &str) -> (usize, usize) {
    let count = |p: &str| obj.lines().filter(|l| l.starts_with(p)).count();
    (count("v "), count("vt "))
}

/// The number after `name = ` in a summary line.
fn summary_value(summary: &str, name: &str) -> usize {
    let at = summary
        .find(&format!("{name} = "))
        .unwrap_or_else(|| panic!("{name} in {summary:?}"));
    summary[at + name.len() + 3..]
        .split(|c: char| !c.is_ascii_digit())
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("a number after {name} in {summary:?}"))
}

/// `table`'s level-0 row as (V, UV).
fn table_level0(mesh: &str, scheme: &str) -> (usize, usize) {
    let out = ok(&[
        "table", "--mesh", mesh, "--scheme", scheme, "--levels", "0", "--format", "json",
    ]);
    let rows: serde_json::Value = serde_json::from_str(&out).expect("table's JSON");
    let row = &rows[0];
    let get = |k: &str| {
        row.get(k)
            .and_then(|v| {
                v.as_u64()
                    .or_else(|| v.as_str().and_then(|s| s.parse().ok()))
            })
            .unwrap_or_else(|| panic!("{k} in {row}")) as usize
    };
    (get("V"), get("UV"))
}

#[test]
fn level_zero_writes_what_the_summary_and_table_say() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &str, &[&str]); 3] = [
        (
            "unused.obj",
            TRIANGLE_AND_UNUSED_VERTEX,
            &[
                "loop-general",
                "catmull-clark-general",
                "loop",
                "catmull-clark",
                "tri-split-3",
            ],
        ),
        (
            "shared.obj",
            SHARED_VT,
            &[
                "loop",
                "loop-general",
                "catmull-clark",
                "doo-sabin",
                "mid-edge",
                "sqrt3-boundary",
            ],
        ),
        (
            "book.obj",
            NON_MANIFOLD,
            &["loop-general", "catmull-clark-general", "tri-split-2"],
        ),
    ];
    for (name, text, schemes) in cases {
        let mesh = dir.path().join(name);
        std::fs::write(&mesh, text).unwrap();
        let mesh = mesh.to_str().unwrap();
        for &scheme in schemes {
            let precisions: &[&str] = if scheme.ends_with("general") || name == "book.obj" {
                &["f64"]
            } else {
                &["f64", "f32"]
            };
            for precision in precisions {
                let out = dir.path().join("out.obj");
                let out = out.to_str().unwrap();
                let summary = ok(&[
                    "subdivide",
                    "--mesh",
                    mesh,
                    "--scheme",
                    scheme,
                    "--levels",
                    "0",
                    "--precision",
                    precision,
                    "-o",
                    out,
                ]);
                let written = std::fs::read_to_string(out).unwrap();
                let at = format!("{name} {scheme} {precision}: {summary}");
                let (v, vt) = lines(&written);
                assert_eq!(v, summary_value(&summary, "V"), "{at}");
                assert_eq!(vt, summary_value(&summary, "UV"), "{at}");
                assert_eq!((v, vt), table_level0(mesh, scheme), "{at}");
            }
        }
    }
}

#[test]
fn level_zero_keeps_the_vt_of_the_written_faces_as_read() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("shared.obj");
    std::fs::write(&mesh, SHARED_VT).unwrap();
    let out = dir.path().join("out.obj");
    let run = subcount(&[
        "subdivide",
        "--mesh",
        mesh.to_str().unwrap(),
        "--scheme",
        "loop-general",
        "--levels",
        "0",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let written = std::fs::read_to_string(&out).unwrap();
    let faces: Vec<&str> = written.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(faces, ["f 1/1 2/2 3/3", "f 2/2 4/1 3/3"], "{written}");
}
