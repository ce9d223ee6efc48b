//! Hostile input, round 3 (issue 24, items 2-4): Doo-Sabin on faces of huge degree and
//! vertices of huge valence, with and without UVs, and the memory guard's prediction on them.
//! The inputs are generated here; the bounds are ten times what a linear pass takes, and well
//! under what the quadratic passes they replace took (a 20,000-gon at Doo-Sabin level 1: 4.2 s
//! in release; a valence-4,000 bipyramid with UVs at level 2: a 413 MB peak).

use std::fmt::Write as _;
use std::time::{Duration, Instant};

use serde_json::Value;

use crate::util::subcount;

/// A temporary folder holding one generated OBJ.
struct Generated {
    dir: tempfile::TempDir,
}

impl Generated {
    fn new(text: &str) -> Generated {
        let dir = tempfile::tempdir().expect("a temporary folder");
        std::fs::write(dir.path().join("in.obj"), text).expect("written");
        Generated { dir }
    }

    fn path(&self) -> String {
        self.dir.path().join("in.obj").display().to_string()
    }

    fn out(&self) -> String {
        self.dir.path().join("out.obj").display().to_string()
    }
}

/// One `n`-gon on the unit circle.
fn ngon(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        writeln!(s, "v {:.9} {:.9} 0", a.cos(), a.sin()).expect("text");
    }
    s.push('f');
    for i in 1..=n {
        write!(s, " {i}").expect("text");
    }
    s.push('\n');
    s
}

/// A bipyramid over an `n`-gon (two apexes of valence `n`), a `vt` per vertex.
pub(crate) fn bipyramid(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        writeln!(s, "v {:.9} {:.9} 0", a.cos(), a.sin()).expect("text");
    }
    s.push_str("v 0 0 1\nv 0 0 -1\n");
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        writeln!(
            s,
            "vt {:.9} {:.9}",
            0.5 + 0.4 * a.cos(),
            0.5 + 0.4 * a.sin()
        )
        .expect("text");
    }
    s.push_str("vt 0.5 0.6\nvt 0.5 0.4\n");
    let (top, bottom) = (n + 1, n + 2);
    for i in 0..n {
        let (a, b) = (i + 1, (i + 1) % n + 1);
        writeln!(s, "f {top}/{top} {a}/{a} {b}/{b}").expect("text");
        writeln!(s, "f {bottom}/{bottom} {b}/{b} {a}/{a}").expect("text");
    }
    s
}

/// A prism with `n`-sided caps, a `vt` per vertex.
fn prism(n: usize) -> String {
    let mut s = String::new();
    for z in 0..2 {
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            writeln!(s, "v {:.9} {:.9} {z}", a.cos(), a.sin()).expect("text");
        }
    }
    for z in 0..2 {
        let r = 0.2 * (1 + z) as f64;
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            writeln!(s, "vt {:.9} {:.9}", 0.5 + r * a.cos(), 0.5 + r * a.sin()).expect("text");
        }
    }
    s.push('f');
    for i in (1..=n).rev() {
        write!(s, " {i}/{i}").expect("text");
    }
    s.push_str("\nf");
    for i in n + 1..=2 * n {
        write!(s, " {i}/{i}").expect("text");
    }
    s.push('\n');
    for i in 0..n {
        let (a, b) = (i + 1, (i + 1) % n + 1);
        let (c, d) = (b + n, a + n);
        writeln!(s, "f {a}/{a} {b}/{b} {c}/{c} {d}/{d}").expect("text");
    }
    s
}

/// A `k` by `k` quad grid with a `vt` per vertex.
fn grid(k: usize) -> String {
    let mut s = String::new();
    for y in 0..=k {
        for x in 0..=k {
            writeln!(s, "v {x} {y} 0").expect("text");
        }
    }
    for y in 0..=k {
        for x in 0..=k {
            writeln!(
                s,
                "vt {:.6} {:.6}",
                x as f64 / k as f64,
                y as f64 / k as f64
            )
            .expect("text");
        }
    }
    for y in 0..k {
        for x in 0..k {
            let a = y * (k + 1) + x + 1;
            let (b, c, d) = (a + 1, a + k + 2, a + k + 1);
            writeln!(s, "f {a}/{a} {b}/{b} {c}/{c} {d}/{d}").expect("text");
        }
    }
    s
}

/// A successful `subdivide ... --timings`: its wall time, `peak_bytes` and
/// `predicted_peak_bytes`.
pub(crate) fn timed(args: &[&str]) -> (Duration, u64, u64) {
    let mut all = vec!["subdivide", "--timings"];
    all.extend_from_slice(args);
    let start = Instant::now();
    let run = subcount(&all);
    let elapsed = start.elapsed();
    assert_eq!(run.code, 0, "subcount {all:?}: {}", run.stderr);
    let json = run
        .stderr
        .lines()
        .find_map(|l| l.strip_prefix("timings: "))
        .expect("a timings line");
    let v: Value = serde_json::from_str(json).expect("timings JSON");
    let number = |key: &str| v[key].as_u64().unwrap_or_else(|| panic!("{key} in {json}"));
    (
        elapsed,
        number("peak_bytes"),
        number("predicted_peak_bytes"),
    )
}

/// The resident bytes of this build of the binary before it allocates a mesh (the peak of
/// level 0 of a tetrahedron): the guard's `PROCESS_BYTES` is the release binary's, and the
/// test profile's is larger.
fn process_bytes() -> u64 {
    let (_, peak, _) = timed(&["--base", "tetrahedron", "--scheme", "loop", "--levels", "0"]);
    peak
}

/// The guard's prediction is never more than 10 % under the measured peak nor more than
/// twice it, with the process's own bytes those of this build ([`process_bytes`]). A system
/// that reports no peak (`peak_bytes` 0) is skipped.
pub(crate) fn assert_predicted(what: &str, peak: u64, predicted: u64) {
    assert_predicted_within(what, peak, predicted, 2.0);
}

/// [`assert_predicted`] with the prediction allowed up to `most` times the peak.
fn assert_predicted_within(what: &str, peak: u64, predicted: u64, most: f64) {
    eprintln!("{what}: peak {peak}, predicted {predicted}");
    if peak == 0 {
        return;
    }
    let predicted = (predicted + process_bytes()).saturating_sub(halfedge::memory::PROCESS_BYTES);
    assert!(
        predicted as f64 >= 0.9 * peak as f64,
        "{what}: predicted {predicted} is more than 10 % under the peak {peak}"
    );
    assert!(
        predicted as f64 <= most * peak as f64,
        "{what}: predicted {predicted} is more than {most} times the peak {peak}"
    );
}

/// Item 3: Doo-Sabin's corner points of a 20,000-gon are linear in its degree (they were a
/// sum over the whole face per corner: 4.2 s in release). One-shot, refined once in `f32`,
/// with frames and `verify` alike.
#[test]
fn doo_sabin_on_a_20000_gon_is_linear() {
    let mesh = Generated::new(&ngon(20_000));
    let (path, out) = (mesh.path(), mesh.out());
    let base = [
        "--mesh",
        &path,
        "--scheme",
        "doo-sabin",
        "--levels",
        "1",
        "-o",
        &out,
    ];
    for extra in [&[][..], &["--precision", "f32"], &["--frames", "2"]] {
        let mut args = base.to_vec();
        args.extend_from_slice(extra);
        let (elapsed, peak, predicted) = timed(&args);
        assert!(
            elapsed < Duration::from_secs(3),
            "{extra:?}: {elapsed:?} on a 20,000-gon"
        );
        assert!(peak < 60_000_000, "{extra:?}: a peak of {peak} bytes");
        assert_predicted(&format!("20,000-gon {extra:?}"), peak, predicted);
    }
    let start = Instant::now();
    let run = subcount(&[
        "verify",
        "--mesh",
        &path,
        "--scheme",
        "doo-sabin",
        "--levels",
        "1",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        start.elapsed() < Duration::from_secs(3),
        "verify: {:?}",
        start.elapsed()
    );
}

/// Item 2: the Doo-Sabin UV corner channel of two vertices of valence 4,000 is linear in
/// their valence (its weight table held 4,000 weights per corner of their faces from level 2
/// on: a 413 MB peak, 35 MB predicted); with UVs the run stays near the one without.
#[test]
fn doo_sabin_uvs_at_a_valence_4000_vertex_are_linear() {
    let mesh = Generated::new(&bipyramid(4_000));
    let (path, out) = (mesh.path(), mesh.out());
    let args = [
        "--mesh",
        &path,
        "--scheme",
        "doo-sabin",
        "--levels",
        "2",
        "-o",
        &out,
    ];
    let (elapsed, peak, predicted) = timed(&args);
    assert!(elapsed < Duration::from_secs(3), "{elapsed:?}");
    assert!(peak < 100_000_000, "a peak of {peak} bytes with UVs");
    assert_predicted("valence 4,000 with UVs", peak, predicted);
    let mut no_uv = args.to_vec();
    no_uv.push("--no-uv");
    let (_, peak_without, predicted_without) = timed(&no_uv);
    assert_predicted("valence 4,000 without UVs", peak_without, predicted_without);
    let mut f32 = args.to_vec();
    f32.extend_from_slice(&["--precision", "f32"]);
    let (_, peak_f32, predicted_f32) = timed(&f32);
    assert!(peak_f32 < 100_000_000, "a peak of {peak_f32} bytes in f32");
    assert_predicted("valence 4,000 with UVs, f32", peak_f32, predicted_f32);
}

/// Item 4: the guard no longer refuses work that fits. A prism with 8,000-sided caps and
/// UVs under Catmull-Clark (a 2.9 GiB prediction for a 17.5 MB run: its UV channel's crease
/// tables were bounded by `d²` per face) and one with 2,000-sided caps under Doo-Sabin to
/// level 4 (23.0 GiB for 0.57 GB: the corner tables by the largest face's degree per value).
#[test]
fn the_guard_predicts_wide_faces_with_uvs_within_bounds() {
    let wide = Generated::new(&prism(8_000));
    let (path, out) = (wide.path(), wide.out());
    let args = [
        "--mesh",
        &path,
        "--scheme",
        "catmull-clark",
        "--levels",
        "1",
        "-o",
        &out,
    ];
    let (_, peak, predicted) = timed(&args);
    assert!(predicted < 100_000_000, "predicted {predicted} bytes");
    // The prediction is about twice this peak (1.96-2.01 times over runs on 2026-12-05: the
    // peak moves by 2 % from run to run), so twice would be a coin toss; issue 30 tightens it.
    assert_predicted_within("8,000-gon prism, Catmull-Clark 1", peak, predicted, 2.2);

    let prism = Generated::new(&prism(2_000));
    let (path, out) = (prism.path(), prism.out());
    for levels in ["1", "2", "3"] {
        let args = [
            "--mesh",
            &path,
            "--scheme",
            "doo-sabin",
            "--levels",
            levels,
            "-o",
            &out,
        ];
        let (_, peak, predicted) = timed(&args);
        assert_predicted(
            &format!("2,000-gon prism, Doo-Sabin {levels}"),
            peak,
            predicted,
        );
    }
}

/// Item 4, the other way: level 0 of a quad grid with UVs (the file's lines and `vt`, the
/// half-edge mesh's construction and the face list written were not counted: 549 MB predicted
/// for a 1,146 MB peak on a 310 MB file).
#[test]
fn the_guard_counts_level_0() {
    let mesh = Generated::new(&grid(400));
    let (path, out) = (mesh.path(), mesh.out());
    for uv in [&[][..], &["--no-uv"]] {
        let mut args = vec![
            "--mesh",
            &path,
            "--scheme",
            "catmull-clark",
            "--levels",
            "0",
        ];
        args.extend_from_slice(&["-o", &out]);
        args.extend_from_slice(uv);
        let (_, peak, predicted) = timed(&args);
        assert_predicted(&format!("grid level 0 {uv:?}"), peak, predicted);
    }
}

/// Issue 24: a crease-tagged 80,000-gon under Catmull-Clark. The guard bounded each face's
/// crease table rows by `d²` (286 GiB predicted, refused without `--allow-large`); an
/// overriding row now names a face of more than 32 sides by its child point, so the rows and
/// the bound are linear in the degree. Semi-sharp (2.0) and fractional (0.5) creases on every
/// edge and a few sharp corners, one-shot and refined once in `f32`.
#[test]
fn crease_tags_on_an_80000_gon_are_linear() {
    let n = 80_000;
    for sharpness in ["2.0", "0.5"] {
        let mut text = ngon(n);
        write!(text, "t crease {}/1/0", 2 * n).expect("text");
        for i in 0..n {
            write!(text, " {i} {}", (i + 1) % n).expect("text");
        }
        writeln!(text, " {sharpness}").expect("text");
        writeln!(text, "t corner 3/3/0 0 1 40000 3.0 3.0 3.0").expect("text");
        let mesh = Generated::new(&text);
        let (path, out) = (mesh.path(), mesh.out());
        let base = [
            "--mesh",
            &path,
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "-o",
            &out,
        ];
        for extra in [&[][..], &["--precision", "f32"]] {
            let mut args = base.to_vec();
            args.extend_from_slice(extra);
            let (elapsed, peak, predicted) = timed(&args);
            assert!(
                elapsed < Duration::from_secs(3),
                "{sharpness} {extra:?}: {elapsed:?} on an 80,000-gon"
            );
            assert!(
                peak < 150_000_000,
                "{sharpness} {extra:?}: a peak of {peak} bytes"
            );
            assert_predicted(
                &format!("80,000-gon {sharpness} {extra:?}"),
                peak,
                predicted,
            );
        }
    }
}

/// A bipyramid over an `n`-gon without UVs (two apexes of valence `n`).
fn bare_bipyramid(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        writeln!(s, "v {:.9} {:.9} 0", a.cos(), a.sin()).expect("text");
    }
    s.push_str("v 0 0 1\nv 0 0 -1\n");
    let (top, bottom) = (n + 1, n + 2);
    for i in 0..n {
        let (a, b) = (i + 1, (i + 1) % n + 1);
        writeln!(s, "f {a} {b} {top}\nf {b} {a} {bottom}").expect("text");
    }
    s
}

/// Issue 24: refined once in `f32`, the guard's prediction on two vertices of valence 16,000
/// (√3, Doo-Sabin and mid-edge build their last level's whole connectivity, and the freed
/// connectivity stays resident: 0.71 to 0.86 of the peak before).
#[test]
fn the_refine_once_guard_predicts_a_valence_16000_bipyramid() {
    let mesh = Generated::new(&bare_bipyramid(16_000));
    let (path, out) = (mesh.path(), mesh.out());
    for scheme in [
        "loop",
        "catmull-clark",
        "butterfly",
        "sqrt3",
        "doo-sabin",
        "mid-edge",
    ] {
        for levels in ["1", "2"] {
            let args = [
                "--mesh",
                &path,
                "--scheme",
                scheme,
                "--levels",
                levels,
                "--precision",
                "f32",
                "-o",
                &out,
            ];
            let (_, peak, predicted) = timed(&args);
            assert_predicted(
                &format!("valence 16,000, {scheme} {levels}, f32"),
                peak,
                predicted,
            );
        }
    }
}
