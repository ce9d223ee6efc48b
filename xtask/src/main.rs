//! Project chores for subcount, run as `cargo xtask <task>` (the
//! [cargo-xtask](https://github.com/matklad/cargo-xtask) pattern, as in rust-analyzer).
//!
//! - `cargo xtask formulas [--check]` regenerates `docs/formulas.md` from the `schemes` and
//!   `recurrence` crates; `--check` fails when the file is stale (also a `#[test]`, so
//!   `cargo test --workspace` catches it).
//! - `cargo xtask verify DIR [--max-faces N] [--schemes a,b]` really subdivides every mesh of
//!   `DIR` (and of `DIR/broken`) with every applicable built-in scheme, level by level up to a
//!   face cap, and prints a pass/fail table; it exits non-zero on any failure. It re-runs
//!   itself in release mode when built in debug.
//! - `cargo xtask golden OLD_BIN NEW_BIN [--meshes DIR]` runs a fixed matrix of commands on
//!   two `subcount` binaries and prints every difference in exit code, stdout, stderr and
//!   output files (see `golden.rs` and `docs/golden.md`).
//! - `cargo xtask tidy` fails on import cycles between files, a crate depending on one of its
//!   own layer or above, and the budgets (the CLI's size, README.md and ARCHITECTURE.md).

mod formulas;
mod golden;
mod paper;
mod tidy;
mod verify;

use std::path::{Path, PathBuf};

const USAGE: &str = "\
usage: cargo xtask <task>

tasks:
  formulas [--check]                          regenerate docs/formulas.md (--check: fail when stale)
  verify DIR [--max-faces N] [--schemes a,b]  subdivide every mesh of DIR and DIR/broken, compare counts
  golden OLD_BIN NEW_BIN [--meshes DIR] [--cases DIR] [--record] [--no-errors] [--list]
                                              run a fixed matrix on two binaries, print every difference
  tidy                                        structure checks: import cycles, layers, budgets";

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let task = args.next();
    let rest: Vec<String> = args.collect();
    match task.as_deref() {
        Some("formulas") => {
            let check = match rest.as_slice() {
                [] => false,
                [flag] if flag == "--check" => true,
                _ => anyhow::bail!("unexpected arguments {rest:?} for `formulas`\n{USAGE}"),
            };
            formulas::generate(check)
        }
        Some("verify") => verify::run(&rest),
        Some("golden") => golden::run(&rest),
        Some("tidy") => tidy::run(&project_root()),
        Some("help" | "--help" | "-h") => {
            println!("{USAGE}");
            Ok(())
        }
        Some(other) => anyhow::bail!("unknown task `{other}`\n{USAGE}"),
        None => anyhow::bail!("no task given\n{USAGE}"),
    }
}

/// The workspace root (the parent of this crate's manifest directory), so tasks run from
/// anywhere.
fn project_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
}
