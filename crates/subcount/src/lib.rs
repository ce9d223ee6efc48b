//! `subcount`: how big will a subdivision surface be? The command line, as a library: the
//! binary (`main.rs`) calls [`main`], and the Python bindings call [`run_captured`] (the same
//! parsing, commands, JSON and messages; notes collected instead of printed).
//!
//! The program is thin: it parses flags, calls one library function per subcommand, formats the
//! result and maps errors to exit codes (0 ok, 1 verification mismatch, 2 usage, 3 bad input or
//! scheme not applicable, 4 refused by a resource guard). Errors are exactly one line on stderr.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! The command-line program: argument parsing, printing and exit codes, nothing else; every count
//! comes from `schemes::Counter`, every mesh and real subdivision from the `driver` crate.
//! `args.rs` holds the clap flags (a public contract); `model.rs` turns flags into a `Counter`
//! and its initial state (`Input` reads the mesh at most once per command through `load_mesh`,
//! which hands `--mesh`/`--base` and `--boundary`, `--crease-method`, `--triangle-rule`,
//! `--ignore-tags` to `driver::load`); `commands.rs` dispatches and runs `table`, `at` and
//! `formula`; `report.rs` (fit, density, schemes), `mesh.rs` (stats, verify, subdivide: the flags
//! into `driver::subdivide::SubdivideJob` and `driver::SchemeChoice`, the summary and
//! `--timings` out), `compose.rs` (compositions: `driver::compose`) and `plot.rs` (log10 of each
//! count, the series, legend labels and notes it gives the `chart` crate, which draws) call the
//! libraries and format. The leaf modules they share import nothing back: `failure.rs` (errors
//! to exit codes: `driver::Kind`, the advice a flag gives), `levels.rs` (every level parser).
//! Text, CSV and JSON layouts are `schemes::output`'s.

mod args;
mod commands;
mod compose;
mod failure;
mod levels;
mod mesh;
mod model;
mod plot;
mod report;

use std::ffi::OsString;
use std::io::{self, Write};
use std::process::ExitCode;

use clap::Parser;

/// Runs the command line of this process: output on stdout, one line `error: ...` on stderr,
/// the exit code of the failure's kind (0 ok, 1 a mismatch, 2 usage, 3 input, 4 a guard).
pub fn main() -> ExitCode {
    let cli = match args::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return clap_error(&e),
    };
    let stdout = io::stdout();
    let mut out = io::BufWriter::new(stdout.lock());
    let result = commands::run(cli.command, &mut out).and_then(|code| {
        out.flush().map_err(failure::write_failure)?;
        Ok(code)
    });
    match result {
        Ok(code) => ExitCode::from(code),
        Err(failure) => {
            if is_broken_pipe(&failure.error) {
                return ExitCode::SUCCESS;
            }
            let message = one_line(&failure.error);
            let _ = writeln!(io::stderr(), "error: {message}");
            ExitCode::from(failure.kind.exit_code())
        }
    }
}

/// What a captured run ([`run_captured`]) printed and how it ended.
#[derive(Debug, Default)]
pub struct Captured {
    /// The exit code: 0 ok, 1 a verification mismatch, 2 usage, 3 input, 4 a resource guard.
    pub exit_code: u8,
    /// What the command wrote on stdout.
    pub stdout: Vec<u8>,
    /// The notes it would have printed on stderr, one per line, in order.
    pub notes: Vec<String>,
    /// The error line's message (without `error: `) when it failed.
    pub error: Option<String>,
}

/// Runs the command line `args` (the program name excluded) as the binary would, with the
/// mesh of `--mesh`/`--base` replaced by `mesh` (a face list in memory and how messages name
/// it) when given; collects stdout and the notes instead of printing them. Help and version
/// requests are usage errors here. Not captured: `subdivide`'s lines about the file written
/// and `--timings` (stderr), and `-o -` (the process's stdout).
pub fn run_captured(
    args: impl IntoIterator<Item = OsString>,
    mesh: Option<(std::sync::Arc<halfedge::PolygonMesh>, String)>,
) -> Captured {
    let argv = std::iter::once(OsString::from("subcount")).chain(args);
    let mut cli = match args::Cli::try_parse_from(argv) {
        Ok(cli) => cli,
        Err(e) => {
            return Captured {
                exit_code: 2,
                error: Some(clap_message(&e)),
                ..Captured::default()
            }
        }
    };
    if let Some(mesh) = mesh {
        cli.command.set_memory_mesh(mesh);
    }
    let mut captured = Captured::default();
    let (result, notes) =
        failure::capturing_notes(|| commands::run(cli.command, &mut captured.stdout));
    captured.notes = notes;
    match result {
        Ok(code) => captured.exit_code = code,
        Err(failure) => {
            captured.exit_code = failure.kind.exit_code();
            captured.error = Some(one_line(&failure.error));
        }
    }
    captured
}

/// Help and version go to stdout with exit 0; every other clap error becomes one line.
fn clap_error(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            }
        }
        _ => {
            let _ = writeln!(io::stderr(), "error: {}", clap_message(e));
            ExitCode::from(2)
        }
    }
}

/// clap's message: its first paragraph (before the usage text), joined to one line.
fn clap_message(e: &clap::Error) -> String {
    let rendered = e.render().to_string();
    let paragraph: Vec<&str> = rendered
        .trim_start()
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .map(str::trim)
        .collect();
    let message = paragraph.join(" ");
    let message = message.strip_prefix("error: ").unwrap_or(&message);
    match message.is_empty() {
        true => "invalid arguments".to_owned(),
        false => message.to_owned(),
    }
}

/// The error and its causes on one line, `outer: inner`, skipping a cause whose text the
/// message already contains (library errors often embed their source).
fn one_line(error: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in error.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    // Control characters from a file (a name, a token) are never echoed raw to the terminal.
    halfedge::io::escape_controls(&message.replace('\n', " ")).into_owned()
}

fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|cause| {
        cause
            .downcast_ref::<io::Error>()
            .is_some_and(|io| io.kind() == io::ErrorKind::BrokenPipe)
    })
}
