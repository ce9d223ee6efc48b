//! `cargo xtask verify DIR [--max-faces N] [--schemes a,b]`: every applicable built-in scheme
//! on every mesh file (`.obj`, `.off`) of `DIR` and of `DIR/broken`, really subdivided level by
//! level until the next level would pass the face cap, predicted counts compared with the
//! measured ones; one pass/fail row per (mesh, scheme).
//!
//! Files directly in `DIR` must be valid meshes: each applicable scheme runs on the half-edge
//! mesh (`halfedge::subdivide::verify`). Files in `DIR/broken` must be refused by the
//! validating loader (`HalfEdgeMesh::try_from`): the refusal is a pass, and the schemes that
//! need no manifold edges (`loop-general`, `catmull-clark-general`, `tri-split-N` on
//! triangles) are then verified on the raw face list (`halfedge::subdivide::verify_polygons`);
//! where the face list has faces with a repeated vertex or duplicate faces, the face-list
//! subdivider's typed refusal of them is the expected result.
//!
//! Meshes are checked in parallel (rayon, one mesh per task); each subdivision runs on one
//! thread.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use anyhow::Context as _;
use halfedge::subdivide::{self, LevelReport, SubdivideOptions};
use halfedge::{io, stats, HalfEdgeMesh, PolygonMesh};
use num_bigint::BigInt;
use rayon::prelude::*;
use schemes::{MeshCounts, Scheme};

/// The default cap on the faces of the last level built, per (mesh, scheme).
const DEFAULT_MAX_FACES: u64 = 2_000_000;

/// Levels are never taken past this, whatever the cap.
const MAX_LEVELS: u32 = 30;

#[derive(Debug)]
struct Options {
    dir: PathBuf,
    max_faces: u64,
    schemes: Option<Vec<String>>,
}

fn parse(args: &[String]) -> anyhow::Result<Options> {
    let mut dir = None;
    let mut max_faces = DEFAULT_MAX_FACES;
    let mut schemes = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--max-faces" => {
                let v = it.next().context("--max-faces needs a number")?;
                max_faces = v
                    .replace('_', "")
                    .parse()
                    .with_context(|| format!("--max-faces: `{v}` is not a number"))?;
            }
            "--schemes" => {
                let v = it
                    .next()
                    .context("--schemes needs a list such as loop,sqrt3")?;
                let names: Vec<String> = v.split(',').map(|s| s.trim().to_string()).collect();
                for n in &names {
                    schemes::builtin(n).with_context(|| format!("--schemes: `{n}`"))?;
                }
                schemes = Some(names);
            }
            flag if flag.starts_with("--") => anyhow::bail!("verify: unknown option `{flag}`"),
            path if dir.is_none() => dir = Some(PathBuf::from(path)),
            extra => anyhow::bail!("verify: unexpected argument `{extra}`"),
        }
    }
    Ok(Options {
        dir: dir.context("usage: cargo xtask verify DIR [--max-faces N] [--schemes a,b]")?,
        max_faces,
        schemes,
    })
}

/// Entry point: re-runs itself in release mode when built in debug, then verifies.
pub(crate) fn run(args: &[String]) -> anyhow::Result<()> {
    if cfg!(debug_assertions) && std::env::var_os("XTASK_VERIFY_DEBUG").is_none() {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let manifest = crate::project_root().join("Cargo.toml");
        eprintln!("xtask verify: rebuilding in release mode (set XTASK_VERIFY_DEBUG=1 to skip)");
        let status = Command::new(cargo)
            .arg("run")
            .arg("--release")
            .arg("--manifest-path")
            .arg(&manifest)
            .args(["--package", "xtask", "--bin", "xtask", "--", "verify"])
            .args(args)
            .status()
            .context("cannot run cargo")?;
        anyhow::ensure!(status.success(), "xtask verify failed ({status})");
        return Ok(());
    }
    let options = parse(args)?;
    let started = Instant::now();
    let rows = verify_dir(&options)?;
    print_table(&rows);
    let failed = rows.iter().filter(|r| r.outcome.is_failure()).count();
    println!(
        "{} rows, {failed} failed, {:.1} s in total (cap {} faces)",
        rows.len(),
        started.elapsed().as_secs_f64(),
        options.max_faces
    );
    anyhow::ensure!(failed == 0, "{failed} of {} checks failed", rows.len());
    Ok(())
}

/// The result of one (mesh, scheme) check.
#[derive(Debug)]
enum Outcome {
    /// Every level matched: the last level and its face count.
    Pass { levels: u32, faces: BigInt },
    /// The validating loader refused a broken mesh, as it must.
    Refused(String),
    /// Not run: the scheme's algorithm cannot run on this mesh (e.g. a vertex of valence 2
    /// under a dual scheme), with the library's reason.
    Skipped(String),
    /// A mismatch, an unexpected error or an unexpected acceptance.
    Fail(String),
}

impl Outcome {
    fn is_failure(&self) -> bool {
        matches!(self, Outcome::Fail(_))
    }
}

#[derive(Debug)]
struct Row {
    mesh: String,
    scheme: String,
    outcome: Outcome,
    time: Duration,
}

/// The mesh files of `dir` (not recursive), sorted.
fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let path = entry
            .with_context(|| format!("cannot read {}", dir.display()))?
            .path();
        let mesh = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("obj") || e.eq_ignore_ascii_case("off"));
        if mesh && path.is_file() {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

fn verify_dir(options: &Options) -> anyhow::Result<Vec<Row>> {
    let valid = mesh_files(&options.dir)?;
    let broken_dir = options.dir.join("broken");
    let broken = if broken_dir.is_dir() {
        mesh_files(&broken_dir)?
    } else {
        Vec::new()
    };
    anyhow::ensure!(
        !valid.is_empty() || !broken.is_empty(),
        "no .obj or .off file in {}",
        options.dir.display()
    );
    let jobs: Vec<(&PathBuf, bool)> = valid
        .iter()
        .map(|p| (p, false))
        .chain(broken.iter().map(|p| (p, true)))
        .collect();
    let rows: Vec<Vec<Row>> = jobs
        .par_iter()
        .map(|(path, broken)| verify_file(path, *broken, options))
        .collect();
    Ok(rows.into_iter().flatten().collect())
}

/// The schemes to try, as named by the user or all built-ins.
fn candidate_schemes(options: &Options) -> Vec<Scheme> {
    match &options.schemes {
        Some(names) => names
            .iter()
            .filter_map(|n| schemes::builtin(n).ok())
            .collect(),
        None => schemes::builtins(),
    }
}

/// The highest level whose predicted face count stays within the cap (0 when level 1 does
/// not fit).
fn levels_within(scheme: &Scheme, counts: &MeshCounts, max_faces: u64) -> anyhow::Result<u32> {
    let budget = schemes::Budget {
        max_faces: Some(BigInt::from(max_faces)),
        ..schemes::Budget::default()
    };
    let x0 = scheme.initial_state(counts)?;
    let fit = schemes::fit(&schemes::Plan::single(scheme.clone()), &x0, &budget)?;
    Ok(fit
        .highest_level(u64::from(MAX_LEVELS))
        .map_or(0, |l| l as u32))
}

fn verify_file(path: &Path, broken: bool, options: &Options) -> Vec<Row> {
    let label = if broken {
        format!("broken/{}", file_name(path))
    } else {
        file_name(path)
    };
    let row = |scheme: &str, outcome: Outcome, time: Duration| Row {
        mesh: label.clone(),
        scheme: scheme.to_string(),
        outcome,
        time,
    };
    let started = Instant::now();
    let polygons = match io::read_mesh(path) {
        Ok(p) => p,
        Err(e) => {
            return vec![row(
                "(load)",
                Outcome::Fail(e.to_string()),
                started.elapsed(),
            )]
        }
    };
    let counts = stats::face_list_counts(&polygons);
    let problems = stats::face_list_problems(&polygons);
    let degenerate = problems.faces_with_repeated_vertex > 0 || problems.duplicate_faces > 0;
    let validated = HalfEdgeMesh::try_from_polygon_mesh(&polygons);
    let mut rows = Vec::new();
    let mesh = match (validated, broken) {
        (Ok(mesh), false) => Some(mesh),
        (Err(e), false) => {
            let outcome = Outcome::Fail(format!("valid mesh refused: {e}"));
            return vec![row("(load)", outcome, started.elapsed())];
        }
        (Ok(_), true) => {
            let outcome = Outcome::Fail("the validating loader accepted a broken mesh".into());
            rows.push(row("(load)", outcome, started.elapsed()));
            None
        }
        (Err(e), true) => {
            rows.push(row(
                "(load)",
                Outcome::Refused(e.to_string()),
                started.elapsed(),
            ));
            None
        }
    };
    for scheme in candidate_schemes(options) {
        let name = scheme.name().to_string();
        let applies = scheme.initial_state(&counts).is_ok()
            && match (&mesh, scheme.subdivision_rule()) {
                (_, None) => false,
                (Some(_), Some(_)) => true,
                (None, Some(rule)) => !scheme.mesh_class().needs_manifold() && rule.refines_faces(),
            };
        if !applies {
            continue;
        }
        let started = Instant::now();
        let outcome = match check_scheme(&scheme, mesh.as_ref(), &polygons, &counts, options) {
            Ok(outcome) => outcome,
            Err(e @ halfedge::Error::SchemeNotApplicable { .. }) => Outcome::Skipped(e.to_string()),
            // The face-list subdivider refuses degenerate faces on every path, with a type.
            Err(
                e
                @ (halfedge::Error::RepeatedVertex { .. } | halfedge::Error::DuplicateFace { .. }),
            ) if mesh.is_none() && degenerate => Outcome::Refused(e.to_string()),
            Err(e) => Outcome::Fail(e.to_string()),
        };
        rows.push(row(&name, outcome, started.elapsed()));
    }
    rows
}

fn check_scheme(
    scheme: &Scheme,
    mesh: Option<&HalfEdgeMesh>,
    polygons: &PolygonMesh,
    counts: &MeshCounts,
    options: &Options,
) -> Result<Outcome, halfedge::Error> {
    let levels = match levels_within(scheme, counts, options.max_faces) {
        Ok(l) => l,
        Err(e) => return Ok(Outcome::Fail(format!("prediction failed: {e:#}"))),
    };
    let opts = SubdivideOptions::default();
    let result = match mesh {
        Some(m) => subdivide::verify(m, scheme, levels, &opts),
        None => subdivide::verify_polygons(polygons, scheme, levels, &opts),
    };
    Ok(judge(&result?, levels))
}

fn judge(reports: &[LevelReport], levels: u32) -> Outcome {
    if let Some(bad) = reports.iter().find(|r| !r.is_match()) {
        let diffs: Vec<String> = bad
            .predicted
            .iter()
            .zip(&bad.measured)
            .filter(|(p, m)| p != m)
            .map(|((name, p), (_, m))| format!("{name} predicted {p}, measured {m}"))
            .collect();
        return Outcome::Fail(format!("level {}: {}", bad.level, diffs.join(", ")));
    }
    if reports.len() != levels as usize + 1 {
        return Outcome::Fail(format!("{} reports for levels 0..={levels}", reports.len()));
    }
    let faces = reports
        .last()
        .and_then(|r| r.measured.iter().find(|(n, _)| n == "F"))
        .map(|(_, f)| f.clone())
        .unwrap_or_default();
    Outcome::Pass { levels, faces }
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

fn print_table(rows: &[Row]) {
    let mesh_width = rows.iter().map(|r| r.mesh.len()).max().unwrap_or(4).max(4);
    let scheme_width = rows
        .iter()
        .map(|r| r.scheme.len())
        .max()
        .unwrap_or(6)
        .max(6);
    println!(
        "{:<mesh_width$}  {:<scheme_width$}  {:<6}  {:>6}  {:>10}  {:>8}  detail",
        "mesh", "scheme", "result", "levels", "faces", "time"
    );
    for r in rows {
        let (result, levels, faces, detail) = match &r.outcome {
            Outcome::Pass { levels, faces } => (
                "PASS",
                format!("0..={levels}"),
                faces.to_string(),
                String::new(),
            ),
            Outcome::Refused(e) => ("PASS", "-".into(), "-".into(), format!("refused: {e}")),
            Outcome::Skipped(e) => ("SKIP", "-".into(), "-".into(), e.clone()),
            Outcome::Fail(e) => ("FAIL", "-".into(), "-".into(), e.clone()),
        };
        println!(
            "{:<mesh_width$}  {:<scheme_width$}  {result:<6}  {levels:>6}  {faces:>10}  {:>7.2}s  {detail}",
            r.mesh,
            r.scheme,
            r.time.as_secs_f64()
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn options_parse_with_defaults_and_errors() -> anyhow::Result<()> {
        let o = parse(&args(&["meshes"]))?;
        assert_eq!(
            (o.dir, o.max_faces, o.schemes),
            ("meshes".into(), 2_000_000, None)
        );
        let o = parse(&args(&[
            "m",
            "--max-faces",
            "1_000",
            "--schemes",
            "loop,ternary",
        ]))?;
        assert_eq!(o.max_faces, 1000);
        assert_eq!(o.schemes, Some(args(&["loop", "ternary"])));
        let err = parse(&args(&["m", "--schemes", "lop"])).unwrap_err();
        assert!(format!("{err:#}").contains("unknown"), "{err:#}");
        assert!(parse(&args(&[])).is_err());
        assert!(parse(&args(&["a", "b"])).is_err());
        Ok(())
    }

    #[test]
    fn levels_stop_before_the_cap() -> anyhow::Result<()> {
        let counts = stats::face_list_counts(&halfedge::shapes::icosahedron());
        let scheme = schemes::builtin("loop")?;
        // 20, 80, 320, 1280, 5120 faces.
        assert_eq!(levels_within(&scheme, &counts, 5119)?, 3);
        assert_eq!(levels_within(&scheme, &counts, 5120)?, 4);
        assert_eq!(levels_within(&scheme, &counts, 19)?, 0);
        Ok(())
    }

    /// A folder with one valid and one broken mesh: every row passes, the broken one is
    /// refused and still verified on its face list.
    #[test]
    fn a_small_folder_passes() -> anyhow::Result<()> {
        let dir = std::env::temp_dir().join(format!("xtask-verify-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("broken"))?;
        let tetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
        std::fs::write(dir.join("tetra.obj"), tetra)?;
        // Three triangles on the edge 1-2: a non-manifold "book".
        let book = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
        std::fs::write(dir.join("broken").join("book.obj"), book)?;
        // A face that repeats a vertex: refused by the loader and by the face-list path.
        let degenerate = format!("{tetra}f 1 1 2\n");
        std::fs::write(dir.join("broken").join("degenerate.obj"), degenerate)?;
        let options = Options {
            dir: dir.clone(),
            max_faces: 1000,
            schemes: None,
        };
        let rows = verify_dir(&options);
        std::fs::remove_dir_all(&dir)?;
        let rows = rows?;
        for r in &rows {
            assert!(!r.outcome.is_failure(), "{r:?}");
        }
        let schemes_of = |mesh: &str| -> Vec<&str> {
            rows.iter()
                .filter(|r| r.mesh == mesh)
                .map(|r| r.scheme.as_str())
                .collect()
        };
        assert_eq!(
            schemes_of("broken/book.obj"),
            [
                "(load)",
                "loop-general",
                "catmull-clark-general",
                "tri-split-2",
                "tri-split-3"
            ]
        );
        assert!(matches!(
            rows.iter()
                .find(|r| r.mesh == "broken/book.obj")
                .map(|r| &r.outcome),
            Some(Outcome::Refused(_))
        ));
        assert!(schemes_of("tetra.obj").contains(&"loop"));
        let degenerate: Vec<_> = rows
            .iter()
            .filter(|r| r.mesh == "broken/degenerate.obj")
            .collect();
        assert!(degenerate.len() >= 2, "{degenerate:?}");
        for r in degenerate {
            assert!(
                matches!(&r.outcome, Outcome::Refused(e) if e.contains("repeats vertex")),
                "{r:?}"
            );
        }
        let loop_row = rows
            .iter()
            .find(|r| r.mesh == "tetra.obj" && r.scheme == "loop");
        // 4 * 4^3 = 256 faces at level 3, 1024 would pass the cap.
        assert!(matches!(
            loop_row.map(|r| &r.outcome),
            Some(Outcome::Pass { levels: 3, faces }) if *faces == BigInt::from(256)
        ));
        Ok(())
    }
}
