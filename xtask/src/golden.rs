//! `cargo xtask golden OLD_BIN NEW_BIN [--meshes DIR] [--cases DIR] [--record] [--list]`: a
//! fixed matrix of runs on two `subcount` binaries, compared run by run (exit code, stdout,
//! stderr with the values of the `timings:` line masked, and the SHA-256 of every file a run
//! leaves in its scratch folder). One `DIFF` line per difference and a summary; exit 1 when
//! anything differs.
//!
//! The matrix, on every mesh of the meshes folder (`DIR`, default `$SUBCOUNT_MESHES` or
//! `../shared/meshes`) and of its `broken/` folder:
//!
//! - `stats` (text and JSON);
//! - for every applicable scheme (the union of what both binaries' `stats --format json` list):
//!   `table --levels 2` (text and JSON), `formula`, `verify --max-faces 200000`;
//! - `subdivide -o --timings` at levels 1 and 2 when the predicted face count (OLD's `table`)
//!   is at most 1 M, and with each of `--threads 1`, `--precision f32`, `--frames 2`,
//!   `--no-uv`, `--normals`, `--ignore-tags` when it is at most 200 k;
//! - the error cases recorded from `crates/subcount/tests/cli` (every run there that exited
//!   non-zero; see `util.rs`'s `SUBCOUNT_GOLDEN_RECORD`), from `--cases DIR` (default
//!   `target/golden-cases`, recorded by running the tests when missing or with `--record`).
//!
//! Each binary runs every case in its own empty scratch folder (also its working directory);
//! `{OUT}` in the arguments is a file in it, and the folder's path is replaced by `<DIR>` in
//! stdout and stderr before comparing. Cases run in parallel (rayon), OLD then NEW per case.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

use anyhow::Context as _;
use rayon::prelude::*;
use sha2::{Digest as _, Sha256};

/// Face caps on the predicted output of a `subdivide` run.
const MAX_FACES_DEFAULT: u64 = 1_000_000;
const MAX_FACES_VARIANT: u64 = 200_000;
/// The options each tried alone on top of the default `subdivide` run.
const VARIANTS: [&[&str]; 6] = [
    &["--threads", "1"],
    &["--precision", "f32"],
    &["--frames", "2"],
    &["--no-uv"],
    &["--normals"],
    &["--ignore-tags"],
];
/// Stands for the scratch output file in a case's arguments.
const OUT: &str = "{OUT}";
/// Stands for the recorded-files folder in a recorded error case's arguments.
const FILES: &str = "@FILES@";
/// In a recorded error case, the run's own scratch folder (an `-o` path of the test's temporary
/// folder, gone when the harness replays it, is recorded under this).
const SCRATCH: &str = "@SCRATCH@";
/// Stands for a run's scratch folder in its normalised output.
const DIR_PLACEHOLDER: &str = "<DIR>";

const USAGE: &str = "usage: cargo xtask golden OLD_BIN NEW_BIN [--meshes DIR] [--cases DIR] \
                     [--record] [--no-errors] [--list]";

#[derive(Debug)]
struct Options {
    old: PathBuf,
    new: PathBuf,
    meshes: PathBuf,
    cases: PathBuf,
    record: bool,
    errors: bool,
    list: bool,
}

/// One run of the matrix: its id and its arguments (`{OUT}`, `@FILES@` substituted per run).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Case {
    id: String,
    args: Vec<String>,
}

/// What one binary did on one case, normalised.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Outcome {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    /// The files left in the scratch folder: name -> SHA-256 (hex).
    files: BTreeMap<String, String>,
}

fn parse(args: &[String]) -> anyhow::Result<Options> {
    let root = crate::project_root();
    let mut bins = Vec::new();
    let mut meshes = None;
    let mut cases = None;
    let (mut record, mut errors, mut list) = (false, true, false);
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--meshes" => {
                meshes = Some(PathBuf::from(it.next().context("--meshes needs a folder")?))
            }
            "--cases" => cases = Some(PathBuf::from(it.next().context("--cases needs a folder")?)),
            "--record" => record = true,
            "--no-errors" => errors = false,
            "--list" => list = true,
            flag if flag.starts_with("--") => {
                anyhow::bail!("golden: unknown option `{flag}`\n{USAGE}")
            }
            bin => bins.push(PathBuf::from(bin)),
        }
    }
    let [old, new] = <[PathBuf; 2]>::try_from(bins)
        .map_err(|_| anyhow::anyhow!("golden: give two binaries\n{USAGE}"))?;
    // As the `testdata` crate: `$SUBCOUNT_MESHES` (relative to the workspace root), else
    // `../shared/meshes` beside the repository.
    let meshes = meshes.unwrap_or_else(|| match std::env::var_os("SUBCOUNT_MESHES") {
        Some(v) if !v.is_empty() => root.join(v),
        _ => root.join("../shared/meshes"),
    });
    anyhow::ensure!(
        meshes.is_dir(),
        "golden: {} is not a folder",
        meshes.display()
    );
    let absolute = |p: PathBuf| std::path::absolute(&p).unwrap_or(p);
    Ok(Options {
        old: absolute(old),
        new: absolute(new),
        meshes: absolute(meshes),
        cases: absolute(cases.unwrap_or_else(|| root.join("target/golden-cases"))),
        record,
        errors,
        list,
    })
}

/// Entry point.
pub(crate) fn run(args: &[String]) -> anyhow::Result<()> {
    let options = parse(args)?;
    let started = Instant::now();
    let mut cases = mesh_cases(&options)?;
    if options.errors {
        if options.record || !options.cases.join("runs").is_dir() {
            record_error_cases(&options.cases)?;
        }
        cases.extend(error_cases(&options.cases)?);
    }
    if options.list {
        for case in &cases {
            println!("{}\t{}", case.id, case.args.join(" "));
        }
        println!("golden: {} cases", cases.len());
        return Ok(());
    }
    let scratch = std::env::temp_dir().join(format!("subcount-golden-{}", std::process::id()));
    let files = options.cases.join("files");
    let diffs: Vec<String> = cases
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, case)| {
            let run = |bin: &Path, side: &str| {
                let dir = scratch.join(side).join(i.to_string());
                run_case(bin, case, &dir, &files)
            };
            let old = run(&options.old, "old");
            let new = run(&options.new, "new");
            compare(&case.id, &old, &new)
        })
        .collect();
    let _ = std::fs::remove_dir_all(&scratch);
    for diff in &diffs {
        println!("{diff}");
    }
    println!(
        "golden: {} cases, {} differences ({:.0} s)",
        cases.len(),
        diffs.len(),
        started.elapsed().as_secs_f64()
    );
    if !diffs.is_empty() {
        std::process::exit(1);
    }
    Ok(())
}

/// The mesh files of `dir` (not recursive), sorted.
fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let path = entry?.path();
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if path.is_file() && matches!(ext.to_ascii_lowercase().as_str(), "obj" | "off") {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| (*s).to_string()).collect()
}

/// Runs `bin args` and returns (exit code, stdout) when it ran.
fn query(bin: &Path, args: &[&str]) -> Option<(i32, String)> {
    let out = Command::new(bin)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .ok()?;
    Some((
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    ))
}

/// The strings of the JSON array under `"key":` in `json` (no escapes expected in them).
pub(crate) fn json_strings(json: &str, key: &str) -> Vec<String> {
    let Some(start) = json.find(&format!("\"{key}\"")) else {
        return Vec::new();
    };
    let rest = &json[start + key.len() + 2..];
    let (Some(open), Some(close)) = (rest.find('['), rest.find(']')) else {
        return Vec::new();
    };
    rest[open + 1..close]
        .split('"')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The `"F"` value of each line (one level per line) of `table --format json`.
pub(crate) fn table_faces(json: &str) -> Vec<u64> {
    json.lines()
        .filter_map(|line| {
            let rest = &line[line.find("\"F\": ")? + 5..];
            let end = rest
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(rest.len());
            // A count past u64 is past every cap.
            Some(rest[..end].parse().unwrap_or(u64::MAX))
        })
        .collect()
}

/// The cases of one mesh.
fn cases_of_mesh(options: &Options, mesh: &Path, name: &str) -> Vec<Case> {
    let m = mesh.to_string_lossy().into_owned();
    let mut cases = vec![
        Case {
            id: format!("stats/{name}"),
            args: strings(&["stats", "--mesh", &m]),
        },
        Case {
            id: format!("stats-json/{name}"),
            args: strings(&["stats", "--mesh", &m, "--format", "json"]),
        },
    ];
    let mut schemes = BTreeSet::new();
    for bin in [&options.old, &options.new] {
        if let Some((0, json)) = query(bin, &["stats", "--mesh", &m, "--format", "json"]) {
            schemes.extend(json_strings(&json, "applicable_schemes"));
        }
    }
    for s in &schemes {
        let id = |what: &str| format!("{what}/{name}/{s}");
        cases.push(Case {
            id: id("table"),
            args: strings(&["table", "--mesh", &m, "--scheme", s, "--levels", "2"]),
        });
        cases.push(Case {
            id: id("table-json"),
            args: strings(&[
                "table", "--mesh", &m, "--scheme", s, "--levels", "2", "--format", "json",
            ]),
        });
        cases.push(Case {
            id: id("formula"),
            args: strings(&["formula", "--mesh", &m, "--scheme", s]),
        });
        cases.push(Case {
            id: id("verify"),
            args: strings(&[
                "verify",
                "--mesh",
                &m,
                "--scheme",
                s,
                "--max-faces",
                "200000",
            ]),
        });
        let table = [
            "table", "--mesh", &m, "--scheme", s, "--levels", "2", "--format", "json",
        ];
        let faces = [&options.old, &options.new]
            .iter()
            .find_map(|bin| match query(bin, &table) {
                Some((0, json)) => Some(table_faces(&json)),
                _ => None,
            })
            .unwrap_or_default();
        for level in 1..=2u32 {
            let Some(&f) = faces.get(level as usize) else {
                continue;
            };
            let l = level.to_string();
            let base = [
                "subdivide",
                "--mesh",
                &m,
                "--scheme",
                s,
                "--levels",
                &l,
                "-o",
                OUT,
                "--timings",
            ];
            if f <= MAX_FACES_DEFAULT {
                cases.push(Case {
                    id: format!("subdivide/{name}/{s}/L{l}"),
                    args: strings(&base),
                });
            }
            if f <= MAX_FACES_VARIANT {
                for variant in VARIANTS {
                    let mut args = strings(&base);
                    args.extend(strings(variant));
                    let tag = variant.join("").trim_start_matches("--").replace("--", "");
                    cases.push(Case {
                        id: format!("subdivide/{name}/{s}/L{l}/{tag}"),
                        args,
                    });
                }
            }
        }
    }
    cases
}

/// Every mesh case, in a stable order.
fn mesh_cases(options: &Options) -> anyhow::Result<Vec<Case>> {
    let mut meshes: Vec<(PathBuf, String)> = Vec::new();
    for (dir, prefix) in [
        (options.meshes.clone(), ""),
        (options.meshes.join("broken"), "broken/"),
    ] {
        if dir.is_dir() {
            for path in mesh_files(&dir)? {
                let name = format!(
                    "{prefix}{}",
                    path.file_name().unwrap_or_default().to_string_lossy()
                );
                meshes.push((path, name));
            }
        }
    }
    anyhow::ensure!(
        !meshes.is_empty(),
        "golden: no mesh in {}",
        options.meshes.display()
    );
    Ok(meshes
        .par_iter()
        .flat_map_iter(|(path, name)| cases_of_mesh(options, path, name))
        .collect())
}

/// Fills `dir` by running the CLI tests with `SUBCOUNT_GOLDEN_RECORD` set.
fn record_error_cases(dir: &Path) -> anyhow::Result<()> {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir)?;
    eprintln!(
        "golden: recording the error cases of the CLI tests into {}",
        dir.display()
    );
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .current_dir(crate::project_root())
        .args(["test", "-p", "subcount", "--test", "cli", "--quiet"])
        .env("SUBCOUNT_GOLDEN_RECORD", dir)
        .stdout(Stdio::null())
        .status()
        .context("cannot run cargo test")?;
    // A failing test still records its runs; say so, and go on.
    if !status.success() {
        eprintln!("golden: warning: `cargo test -p subcount --test cli` failed ({status})");
    }
    Ok(())
}

/// The recorded runs of `dir/runs` (written by `crates/subcount/tests/cli/util.rs`): each
/// file holds NUL-separated fields: the test's name, the exit code, then the arguments.
fn error_cases(dir: &Path) -> anyhow::Result<Vec<Case>> {
    let runs = dir.join("runs");
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&runs)
        .with_context(|| format!("cannot read {}", runs.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    let mut cases = Vec::new();
    for path in entries {
        let text = std::fs::read_to_string(&path)?;
        let mut fields = text.split('\0');
        let (Some(test), Some(code)) = (fields.next(), fields.next()) else {
            continue;
        };
        if code == "0" {
            continue;
        }
        let stem = path.file_stem().unwrap_or_default().to_string_lossy();
        cases.push(Case {
            id: format!("error/{test}/{}", &stem[..stem.len().min(8)]),
            args: fields.map(str::to_string).collect(),
        });
    }
    Ok(cases)
}

/// Runs `case` with `bin` in the fresh scratch folder `dir`, then removes the folder.
fn run_case(bin: &Path, case: &Case, dir: &Path, files: &Path) -> Outcome {
    let _ = std::fs::remove_dir_all(dir);
    if let Err(e) = std::fs::create_dir_all(dir) {
        return Outcome {
            stderr: format!("golden: cannot create {}: {e}", dir.display()),
            ..Outcome::default()
        };
    }
    let out_file = dir.join("out.obj").to_string_lossy().into_owned();
    let files = files.to_string_lossy();
    let args: Vec<String> = case
        .args
        .iter()
        .map(|a| {
            a.replace(OUT, &out_file)
                .replace(FILES, &files)
                .replace(SCRATCH, &dir.to_string_lossy())
        })
        .collect();
    let outcome = match Command::new(bin)
        .args(&args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
    {
        Ok(out) => {
            let dir_text = dir.to_string_lossy();
            Outcome {
                code: out.status.code(),
                stdout: normalise(&String::from_utf8_lossy(&out.stdout), &dir_text),
                stderr: normalise(&String::from_utf8_lossy(&out.stderr), &dir_text),
                files: hash_files(dir),
            }
        }
        Err(e) => Outcome {
            stderr: format!("golden: cannot run {}: {e}", bin.display()),
            ..Outcome::default()
        },
    };
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

/// SHA-256 of every file in `dir` (not recursive), by name.
fn hash_files(dir: &Path) -> BTreeMap<String, String> {
    let mut hashes = BTreeMap::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let hash = match std::fs::File::open(entry.path()) {
            Ok(mut file) => {
                let mut hasher = Sha256::new();
                match std::io::copy(&mut file, &mut hasher) {
                    Ok(_) => hex(&hasher.finalize()),
                    Err(e) => format!("unreadable ({e})"),
                }
            }
            Err(e) => format!("unreadable ({e})"),
        };
        hashes.insert(name, hash);
    }
    hashes
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Output made comparable: the scratch folder's path replaced by `<DIR>`, each line's text
/// before its last carriage return dropped (progress redraws), and the numbers after
/// `timings:` replaced by `#` (the keys kept).
pub(crate) fn normalise(text: &str, dir: &str) -> String {
    let text = if dir.is_empty() {
        text.to_string()
    } else {
        text.replace(dir, DIR_PLACEHOLDER)
    };
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let line = line.rsplit_once('\r').map_or(line, |(_, last)| last);
        match line.find("timings: ") {
            Some(at) => {
                out.push_str(&line[..at + 9]);
                out.push_str(&mask_numbers(&line[at + 9..]));
            }
            None => out.push_str(line),
        }
    }
    out
}

/// `text` with every number outside a quoted string replaced by `#`.
fn mask_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let (mut quoted, mut in_number) = (false, false);
    for c in text.chars() {
        if quoted {
            out.push(c);
            quoted = c != '"';
            continue;
        }
        let numeric = c.is_ascii_digit()
            || (in_number && matches!(c, '.' | 'e' | 'E' | '+' | '-'))
            || (c == '-' && !in_number);
        if numeric {
            if !in_number {
                out.push('#');
            }
            in_number = true;
        } else {
            in_number = false;
            quoted = c == '"';
            out.push(c);
        }
    }
    out
}

/// One `DIFF` line per difference between two outcomes of case `id`.
pub(crate) fn compare(id: &str, old: &Outcome, new: &Outcome) -> Vec<String> {
    let mut diffs = Vec::new();
    let code = |c: Option<i32>| c.map_or_else(|| "none".to_string(), |c| c.to_string());
    if old.code != new.code {
        diffs.push(format!(
            "DIFF {id}: exit {} vs {}",
            code(old.code),
            code(new.code)
        ));
    }
    for (what, a, b) in [
        ("stdout", &old.stdout, &new.stdout),
        ("stderr", &old.stderr, &new.stderr),
    ] {
        if a != b {
            diffs.push(format!("DIFF {id}: {what} ({})", first_difference(a, b)));
        }
    }
    let names: BTreeSet<&String> = old.files.keys().chain(new.files.keys()).collect();
    for name in names {
        match (old.files.get(name), new.files.get(name)) {
            (Some(a), Some(b)) if a != b => {
                diffs.push(format!(
                    "DIFF {id}: file {name} sha {} vs {}",
                    &a[..a.len().min(12)],
                    &b[..b.len().min(12)]
                ));
            }
            (Some(_), None) => diffs.push(format!("DIFF {id}: file {name} written by OLD only")),
            (None, Some(_)) => diffs.push(format!("DIFF {id}: file {name} written by NEW only")),
            _ => {}
        }
    }
    diffs
}

/// The first differing line of two texts, shortened, as `line N: "old" vs "new"`.
fn first_difference(a: &str, b: &str) -> String {
    let (mut la, mut lb) = (a.lines(), b.lines());
    let short = |s: Option<&str>| -> String {
        s.map_or_else(
            || "<end>".to_string(),
            |s| format!("{:?}", s.chars().take(80).collect::<String>()),
        )
    };
    for n in 1.. {
        let (x, y) = (la.next(), lb.next());
        if x != y || (x.is_none() && y.is_none()) {
            if x.is_none() && y.is_none() {
                return "line endings differ".to_string();
            }
            return format!("line {n}: {} vs {}", short(x), short(y));
        }
    }
    unreachable!()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outcome(code: i32, stdout: &str, stderr: &str, files: &[(&str, &str)]) -> Outcome {
        Outcome {
            code: Some(code),
            stdout: stdout.into(),
            stderr: stderr.into(),
            files: files
                .iter()
                .map(|(n, h)| ((*n).to_string(), (*h).to_string()))
                .collect(),
        }
    }

    #[test]
    fn timings_values_do_not_count_but_their_keys_do() {
        let a = normalise(
            "timings: {\"load_s\": 0.000957, \"peak_bytes\": 7950336}\n",
            "",
        );
        let b = normalise("timings: {\"load_s\": 1.5e-3, \"peak_bytes\": -12}\n", "");
        assert_eq!(a, "timings: {\"load_s\": #, \"peak_bytes\": #}\n");
        assert_eq!(a, b);
        let c = normalise("timings: {\"load_s\": 0.1, \"write_s\": 2}\n", "");
        assert_ne!(a, c);
        let old = outcome(0, "level 1\n", &a, &[("out.obj", "ab")]);
        let new = outcome(0, "level 1\n", &b, &[("out.obj", "ab")]);
        assert!(compare("x", &old, &new).is_empty());
    }

    #[test]
    fn stdout_exit_and_file_differences_are_each_reported() {
        let old = outcome(
            0,
            "V = 12\nF = 20\n",
            "",
            &[("out.obj", "aaaa"), ("a", "1")],
        );
        let new = outcome(
            3,
            "V = 12\nF = 21\n",
            "",
            &[("out.obj", "bbbb"), ("b", "1")],
        );
        let diffs = compare("subdivide/m/loop/L1", &old, &new);
        assert_eq!(
            diffs,
            [
                "DIFF subdivide/m/loop/L1: exit 0 vs 3",
                "DIFF subdivide/m/loop/L1: stdout (line 2: \"F = 20\" vs \"F = 21\")",
                "DIFF subdivide/m/loop/L1: file a written by OLD only",
                "DIFF subdivide/m/loop/L1: file b written by NEW only",
                "DIFF subdivide/m/loop/L1: file out.obj sha aaaa vs bbbb",
            ]
        );
    }

    #[test]
    fn scratch_folders_and_progress_redraws_are_normalised() {
        assert_eq!(
            normalise(
                "wrote /tmp/g/old/3/out.obj\n10%\r50%\rdone\n",
                "/tmp/g/old/3"
            ),
            "wrote <DIR>/out.obj\ndone\n"
        );
    }

    #[test]
    fn json_queries() {
        let stats = r#"{"V": 4, "applicable_schemes": ["loop", "sqrt3"]}"#;
        assert_eq!(json_strings(stats, "applicable_schemes"), ["loop", "sqrt3"]);
        let table =
            "[\n{\"level\": 0, \"V\": 4, \"F\": 4, \"H\": 12},\n{\"level\": 1, \"F\": 16}\n]";
        assert_eq!(table_faces(table), [4, 16]);
    }
}
