//! `subcount`: how big will a subdivision surface be?
//!
//! The binary is thin: it parses flags, calls one library function per subcommand, formats the
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
//! to exit codes: `driver::Kind`, the advice a flag gives), `levels.rs` (every level parser),
//! `output.rs` (text, CSV and JSON: serde values in a `{"a": 1, "b": 2}` layout, counts as JSON
//! integers of any size).

mod args;
mod commands;
mod compose;
mod failure;
mod levels;
mod mesh;
mod model;
mod output;
mod plot;
mod report;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
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
            // clap's message is its first paragraph (before the usage text), joined to one line.
            let rendered = e.render().to_string();
            let paragraph: Vec<&str> = rendered
                .trim_start()
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let message = paragraph.join(" ");
            let message = message.strip_prefix("error: ").unwrap_or(&message);
            let message = if message.is_empty() {
                "invalid arguments"
            } else {
                message
            };
            let _ = writeln!(io::stderr(), "error: {message}");
            ExitCode::from(2)
        }
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
