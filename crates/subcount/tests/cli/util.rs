//! Running the built `subcount` binary, ripgrep-style.

use std::path::PathBuf;
use std::process::{Command, Output};

/// The outcome of one run: exit code, stdout and stderr as text.
pub(crate) struct Run {
    pub(crate) code: i32,
    pub(crate) stdout: String,
    pub(crate) stderr: String,
}

/// Runs `subcount` with the given arguments and no standard input.
pub(crate) fn subcount(args: &[&str]) -> Run {
    let output: Output = Command::new(env!("CARGO_BIN_EXE_subcount"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("the subcount binary runs");
    record(None, args, &output);
    Run {
        code: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8(output.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(output.stderr).expect("stderr is UTF-8"),
    }
}

/// Test-only: with `SUBCOUNT_GOLDEN_RECORD=DIR` set, a run that exited non-zero is written to
/// `DIR/runs/<hash>.run` (NUL-separated: the test's name, the exit code, the arguments) for
/// `cargo xtask golden` to replay on two binaries. An argument naming a file (at most 16 MB;
/// relative ones taken from `cwd`) is copied to `DIR/files/` and written as `@FILES@/<copy>`.
fn record(cwd: Option<&std::path::Path>, args: &[&str], output: &Output) {
    use std::hash::{Hash, Hasher};
    let Some(dir) = std::env::var_os("SUBCOUNT_GOLDEN_RECORD") else {
        return;
    };
    let code = output.status.code().unwrap_or(-1);
    if code == 0 {
        return;
    }
    let dir = PathBuf::from(dir);
    let hash = |bytes: &[u8]| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        bytes.hash(&mut h);
        format!("{:016x}", h.finish())
    };
    let test = std::thread::current()
        .name()
        .unwrap_or("unnamed")
        .to_string();
    let mut fields = vec![test, code.to_string()];
    let mut output_next = false;
    for arg in args {
        // An output path of the test's temporary folder (gone when the harness replays the
        // run): the replaying run's own folder, under the same file name.
        if std::mem::take(&mut output_next) && *arg != "-" {
            let name = std::path::Path::new(arg)
                .file_name()
                .map_or_else(|| "out".to_owned(), |n| n.to_string_lossy().into_owned());
            fields.push(format!("@SCRATCH@/{name}"));
            continue;
        }
        output_next = matches!(*arg, "-o" | "--output");
        let path = cwd.map_or_else(|| PathBuf::from(arg), |cwd| cwd.join(arg));
        let small = std::fs::metadata(&path).is_ok_and(|m| m.is_file() && m.len() <= 16 << 20);
        let copied = small
            .then(|| std::fs::read(&path).ok())
            .flatten()
            .and_then(|bytes| {
                let name = path.file_name()?.to_string_lossy().into_owned();
                let copy = format!("{}-{name}", hash(&bytes));
                std::fs::create_dir_all(dir.join("files")).ok()?;
                std::fs::write(dir.join("files").join(&copy), bytes).ok()?;
                Some(format!("@FILES@/{copy}"))
            });
        fields.push(copied.unwrap_or_else(|| (*arg).to_string()));
    }
    let text = fields.join("\0");
    let runs = dir.join("runs");
    std::fs::create_dir_all(&runs).expect("the recording folder can be created");
    std::fs::write(runs.join(format!("{}.run", hash(text.as_bytes()))), text)
        .expect("the recording is written");
}

/// Runs and asserts success with an empty stderr; returns stdout.
pub(crate) fn ok(args: &[&str]) -> String {
    let run = subcount(args);
    assert_eq!(run.code, 0, "subcount {args:?} failed: {}", run.stderr);
    assert_eq!(run.stderr, "", "subcount {args:?} wrote to stderr");
    run.stdout
}

/// Runs and asserts the exit code and a one-line `error: ...` containing `needle`.
pub(crate) fn fails(args: &[&str], code: i32, needle: &str) -> String {
    let run = subcount(args);
    assert_eq!(
        run.code, code,
        "subcount {args:?}: stdout {:?} stderr {:?}",
        run.stdout, run.stderr
    );
    assert!(
        run.stderr.starts_with("error: "),
        "stderr: {:?}",
        run.stderr
    );
    assert_eq!(
        run.stderr.lines().count(),
        1,
        "one line of stderr: {:?}",
        run.stderr
    );
    assert!(
        run.stderr.contains(needle),
        "stderr {:?} lacks {needle:?}",
        run.stderr
    );
    assert!(!run.stderr.contains("panicked"), "panic: {}", run.stderr);
    run.stderr
}

/// A fixture in `crates/subcount/tests/data/`, as an absolute path string.
#[allow(dead_code)]
pub(crate) fn data(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("data")
        .join(name);
    assert!(path.exists(), "missing fixture {}", path.display());
    path.to_string_lossy().into_owned()
}

/// An example scheme in the repository's `examples/schemes/`, as an absolute path string.
#[allow(dead_code)]
pub(crate) fn example_scheme(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/schemes")
        .join(name);
    assert!(path.exists(), "missing example {}", path.display());
    path.to_string_lossy().into_owned()
}

/// The file names in a directory, sorted (to check that nothing else was left there).
#[allow(dead_code)]
pub(crate) fn file_names(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("the directory is readable")
        .map(|e| {
            e.expect("a directory entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    names
}

/// Runs `subcount` with `dir` as the working directory.
#[allow(dead_code)]
pub(crate) fn subcount_in(dir: &std::path::Path, args: &[&str]) -> Run {
    let output: Output = Command::new(env!("CARGO_BIN_EXE_subcount"))
        .args(args)
        .current_dir(dir)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("the subcount binary runs");
    record(Some(dir), args, &output);
    Run {
        code: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8(output.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(output.stderr).expect("stderr is UTF-8"),
    }
}
