//! One function per subcommand: call the libraries, format the result.

use std::io::Write;

use crate::args::{AtArgs, AtFormat, Command, FormulaArgs, FormulaFormat, TableArgs, TableFormat};
use crate::failure::{usage, Failure, Kind};
use crate::levels::parse_levels;
use crate::model::Dynamics;
use crate::output::{self, DigitSummary};

/// Most decimal digits `at` materializes per count without `--allow-large`.
const MAX_DIGITS: f64 = 1e7;

/// Runs one subcommand, writing its result to `out`; returns the exit code.
pub(crate) fn run(command: Command, out: &mut impl Write) -> Result<u8, Failure> {
    match command {
        Command::Table(args) => table(args, out),
        Command::At(args) => at(args, out),
        Command::Formula(args) => formula(args, out),
        Command::Fit(args) => crate::report::fit(args, out),
        Command::Density(args) => crate::report::density(args, out),
        Command::Schemes(args) => crate::report::list_schemes(args, out),
        Command::Stats(args) => crate::mesh::stats(args, out),
        Command::Verify(args) => crate::mesh::verify(args, out),
        Command::Subdivide(args) => crate::mesh::subdivide(args, out),
        Command::Plot(args) => crate::plot::plot(args, out),
    }
}

pub(crate) fn write_failure(e: std::io::Error) -> Failure {
    Failure::new(
        Kind::Input,
        anyhow::Error::new(e).context("cannot write the output"),
    )
}

fn table(args: TableArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let levels = parse_levels(&args.levels).map_err(|e| usage!("invalid --levels: {e}"))?;
    let dynamics = Dynamics::from_source(&args.source)?;
    let x0 = dynamics.initial_state(&args.source)?;
    guard_table(&dynamics, &x0, &levels)?;
    let rows = dynamics.rows(&x0, levels)?;
    let columns = dynamics.columns();
    match args.format {
        TableFormat::Text => output::write_table_text(out, &columns, &rows),
        TableFormat::Json => output::write_table_json(out, &columns, &rows),
        TableFormat::Csv => output::write_table_csv(out, &columns, &rows),
    }
    .map_err(write_failure)?;
    Ok(0)
}

pub(crate) fn parse_level(text: &str) -> Result<u64, Failure> {
    let t = text.trim();
    t.parse::<u64>().map_err(|_| {
        if t.starts_with('-') {
            usage!("invalid --level: `{t}` is negative; levels start at 0")
        } else {
            usage!(
                "invalid --level: `{t}` is not a whole number from 0 to {}",
                u64::MAX
            )
        }
    })
}

/// Refuses, with exit 4, to materialize counts of more than [`MAX_DIGITS`] decimal digits.
pub(crate) fn guard_digits(
    dynamics: &Dynamics,
    x0: &[num_bigint::BigInt],
    s: u64,
    allow_large: bool,
    summary: bool,
) -> Result<(), Failure> {
    guard_digits_for(
        dynamics,
        x0,
        s,
        allow_large,
        if summary { Hint::AtSummary } else { Hint::At },
    )
}

/// What the digit guard suggests: `at` has `--summary` and `--allow-large`; the commands
/// that print every level (`table`, `plot`, `density`) can only ask for fewer levels.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Hint {
    At,
    AtSummary,
    Levels,
}

/// Refuses, with exit 4, counts of more than [`MAX_DIGITS`] decimal digits.
pub(crate) fn guard_digits_for(
    dynamics: &Dynamics,
    x0: &[num_bigint::BigInt],
    s: u64,
    allow_large: bool,
    hint: Hint,
) -> Result<(), Failure> {
    if allow_large {
        return Ok(());
    }
    let worst = dynamics.estimate_log10_max(x0, s)?;
    if worst > MAX_DIGITS {
        let bytes = worst * std::f64::consts::LOG2_10 / 8.0;
        let hint = match hint {
            Hint::AtSummary => "--summary works without materializing the counts only with an exact closed form from level 0 (not for periodic or composed schemes, nor irrational eigenvalues at such levels); use --allow-large to try anyway",
            Hint::At => "use --summary, or --allow-large to try anyway",
            Hint::Levels => "ask for lower levels (or use `at --summary` for one huge level)",
        };
        return Err(Failure::new(
            Kind::Guard,
            anyhow::anyhow!(
                "the counts at level {s} would have about {:.3e} decimal digits ({} per count); the limit is 10^7 digits: {hint}",
                worst.ceil(),
                human_bytes(bytes)
            ),
        ));
    }
    Ok(())
}

/// Most decimal digits a table (all rows and columns together) may hold.
const MAX_TABLE_DIGITS: f64 = 1e8;
/// Most cells a table may hold.
const MAX_TABLE_CELLS: f64 = 1e7;

/// The guard of the commands that hold every level of a range (`table`, `plot`): the largest
/// count, then the whole table (rows times columns times digits), before anything is computed.
pub(crate) fn guard_table(
    dynamics: &Dynamics,
    x0: &[num_bigint::BigInt],
    levels: &std::ops::RangeInclusive<u64>,
) -> Result<(), Failure> {
    guard_digits_for(dynamics, x0, *levels.end(), false, Hint::Levels)?;
    let rows = (*levels.end() - *levels.start()) as f64 + 1.0;
    let cells = rows * dynamics.columns().len() as f64;
    let digits = dynamics.estimate_log10_max(x0, *levels.end())?.max(0.0) + 1.0;
    if cells > MAX_TABLE_CELLS || cells * digits > MAX_TABLE_DIGITS {
        return Err(Failure::new(
            Kind::Guard,
            anyhow::anyhow!(
                "levels {}..={} would make a table of {rows:.0} rows and about {:.3e} decimal digits; the limits are 10^7 cells and 10^8 digits: ask for fewer levels",
                levels.start(),
                levels.end(),
                (cells * digits).ceil()
            ),
        ));
    }
    Ok(())
}

/// `1.5 GiB`-style rendering of a byte count.
pub(crate) fn human_bytes(bytes: f64) -> String {
    if !bytes.is_finite() || bytes > 1e30 {
        return "10^30+ bytes".to_string();
    }
    const UNITS: [&str; 7] = ["bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = bytes;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{v:.0} bytes")
    } else if v >= 1024.0 {
        format!("{:.3e} {}", v, UNITS[unit])
    } else {
        format!("{v:.1} {}", UNITS[unit])
    }
}

fn at(args: AtArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let s = parse_level(&args.level)?;
    let dynamics = Dynamics::from_source(&args.source)?;
    let x0 = dynamics.initial_state(&args.source)?;
    let columns = dynamics.columns();
    // With --summary, an exact closed form summarizes every count without materializing it
    // (any level); otherwise the counts are computed under the digit guard.
    let cheap = if args.summary {
        dynamics
            .direct_form_within(args.allow_large)
            .filter(|f| f.is_exact())
            .and_then(|form| crate::huge::summaries(&dynamics, &form, &x0, s))
    } else {
        None
    };
    let row = match cheap {
        Some(_) => None,
        None => {
            guard_digits(&dynamics, &x0, s, args.allow_large, args.summary)?;
            Some(dynamics.row_at(&x0, s)?)
        }
    };
    let result = if args.summary {
        let sums: Vec<Option<DigitSummary>> = match (cheap, &row) {
            (Some(sums), _) => sums,
            (None, Some(row)) => row
                .values
                .iter()
                .map(|v| {
                    v.as_ref()
                        .map(|v| recurrence::digit_summary(v, crate::huge::DIGITS))
                })
                .collect(),
            (None, None) => unreachable!("a row is computed whenever there is no summary"),
        };
        match args.format {
            AtFormat::Text => {
                let mut r = writeln!(out, "level {s}");
                for (name, d) in columns.iter().zip(&sums) {
                    if let Some(d) = d {
                        r = r.and_then(|_| writeln!(out, "{name}: {}", output::summary_text(d)));
                    }
                }
                r
            }
            AtFormat::Json => {
                let mut text = format!("{{\"level\": {s}");
                for (name, d) in columns.iter().zip(&sums) {
                    let d = d
                        .as_ref()
                        .map_or_else(|| "null".to_string(), output::summary_json);
                    text.push_str(&format!(", {}: {}", output::json_string(name), d));
                }
                text.push('}');
                writeln!(out, "{text}")
            }
        }
    } else {
        let row = row.expect("a row is computed without --summary");
        match args.format {
            AtFormat::Text => {
                let mut r = writeln!(out, "level {s}");
                for (name, v) in columns.iter().zip(&row.values) {
                    if let Some(v) = v {
                        r = r.and_then(|_| writeln!(out, "{name} = {}", decimal::Decimal::from(v)));
                    }
                }
                r
            }
            AtFormat::Json => {
                output::write_row_json(out, &columns, &row).and_then(|_| writeln!(out))
            }
        }
    };
    result.map_err(write_failure)?;
    Ok(0)
}

fn formula(args: FormulaArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let dynamics = Dynamics::from_source(&args.source)?;
    crate::model::guard_closed_forms(&dynamics, args.allow_large)?;
    // With an initial state (--init, --counts, --mesh, --base), the text form also shows the
    // numbers substituted.
    let given = args.source.init.is_some()
        || args.source.counts.is_some()
        || args.source.mesh.mesh.is_some()
        || args.source.mesh.base.is_some();
    let x0 = if given {
        Some(dynamics.initial_state(&args.source)?)
    } else {
        None
    };
    let mut text = match &dynamics {
        Dynamics::Matrix(r) => render_form(&r.closed_form(), args.format, "counts")?,
        Dynamics::Plan(plan) => {
            let phases = plan.phases();
            let fn_base = plan
                .name()
                .replace(|c: char| !c.is_ascii_alphanumeric(), "_");
            if phases.len() == 1 && phases[0].first_level == 0 && phases[0].period == 1 {
                render_form(
                    &phases[0].recurrence.closed_form(),
                    args.format,
                    &format!("{fn_base}_counts"),
                )?
            } else {
                render_phases(&phases, args.format, &fn_base)?
            }
        }
    };
    if let (Some(x0), FormulaFormat::Text) = (&x0, args.format) {
        text = format!("{}\n\n{}", text.trim_end(), specialized_text(&dynamics, x0));
    }
    writeln!(out, "{}", text.trim_end()).map_err(write_failure)?;
    Ok(0)
}

/// The closed forms with the initial values substituted (one block per phase).
fn specialized_text(dynamics: &Dynamics, x0: &[num_bigint::BigInt]) -> String {
    let names = match dynamics {
        Dynamics::Matrix(r) => r.names().to_vec(),
        Dynamics::Plan(plan) => plan.state_names().to_vec(),
    };
    let given: Vec<String> = names
        .iter()
        .zip(x0)
        .map(|(n, v)| format!("{n}(0) = {v}"))
        .collect();
    let mut text = format!("# with {}\n", given.join(", "));
    let symbolic = "(not rational: see the symbolic form above)".to_string();
    match dynamics {
        Dynamics::Matrix(r) => {
            let lines = crate::specialize::specialized_lines(&r.closed_form(), x0, "s");
            text.push_str(&lines.map_or(symbolic, |l| l.join("\n")));
        }
        Dynamics::Plan(plan) => {
            let phases = plan.phases();
            let single = phases.len() == 1 && phases[0].first_level == 0 && phases[0].period == 1;
            for phase in &phases {
                let var = if single { "s" } else { "t" };
                let start = match plan.phase_initial(phase, x0) {
                    Ok(start) => start,
                    Err(e) => {
                        text.push_str(&format!("{}: {e}\n", phase.description));
                        continue;
                    }
                };
                if !single {
                    text.push_str(&format!("{}:\n", phase.description));
                }
                let lines = crate::specialize::specialized_lines(
                    &phase.recurrence.closed_form(),
                    &start,
                    var,
                );
                text.push_str(&lines.map_or(symbolic.clone(), |l| l.join("\n")));
                text.push('\n');
            }
        }
    }
    text
}

fn render_form(
    form: &recurrence::ClosedForm,
    format: FormulaFormat,
    fn_name: &str,
) -> Result<String, Failure> {
    Ok(match format {
        FormulaFormat::Text => form.to_text(),
        FormulaFormat::Latex => form.to_latex(),
        FormulaFormat::Rust => form.to_rust(fn_name),
        FormulaFormat::Json => serde_json::to_string_pretty(&form.to_json())
            .map_err(|e| Failure::new(Kind::Input, e))?,
    })
}

/// One closed form per phase (residue class of a periodic scheme, or stage of a composition).
/// Within a phase, `t` counts periods from the phase's first level, and the subscript-0 values
/// are the counts at that first level.
fn render_phases(
    phases: &[schemes::Phase],
    format: FormulaFormat,
    fn_base: &str,
) -> Result<String, Failure> {
    let mut text = String::new();
    let mut json = Vec::new();
    for (i, phase) in phases.iter().enumerate() {
        let form = phase.recurrence.closed_form();
        let heading = phase_heading(phase);
        match format {
            FormulaFormat::Json => {
                let body = form.to_json();
                json.push(serde_json::json!({
                    "phase": phase.description,
                    "first_level": phase.first_level,
                    "period": phase.period,
                    "last_level": phase.last_level,
                    "stage": phase.stage,
                    "forms": body,
                }));
            }
            FormulaFormat::Text => {
                text.push_str(&format!(
                    "# {heading}
{}
",
                    form.to_text().replace("(s)", "(t)").replace("^s", "^t")
                ));
            }
            FormulaFormat::Latex => {
                text.push_str(&format!(
                    "% {heading}
{}
",
                    form.to_latex()
                ));
            }
            FormulaFormat::Rust => {
                text.push_str(&format!(
                    "// {heading}
{}
",
                    form.to_rust(&format!("{fn_base}_phase{i}"))
                ));
            }
        }
    }
    if format == FormulaFormat::Json {
        text = serde_json::to_string_pretty(&json).map_err(|e| Failure::new(Kind::Input, e))?;
    }
    Ok(text)
}

fn phase_heading(phase: &schemes::Phase) -> String {
    let until = phase
        .last_level
        .map(|l| format!(" up to level {l}"))
        .unwrap_or_default();
    format!(
        "{}: level s = {} + {}t{until}; X0 below means the count X at level {}",
        phase.description, phase.first_level, phase.period, phase.first_level
    )
}
