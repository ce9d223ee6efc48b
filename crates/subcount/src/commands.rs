//! One function per subcommand: call the libraries, format the result. `table`, `at` and
//! `formula` live here; the others in `report`, `mesh` and `plot`.

use std::io::Write;

use num_bigint::BigInt;
use recurrence::{ClosedForm, DigitSummary};
use schemes::{Counter, Phase};
use serde_json::{json, Value};

use crate::args::{AtArgs, AtFormat, Command, FormulaArgs, FormulaFormat, TableArgs, TableFormat};
use crate::failure::{print_note, usage, write_failure, Failure, Kind};
use crate::levels::{parse_level, parse_levels};
use crate::model::Input;
use driver::limits::{self as guard, Hint};
use schemes::output::{self, Field};

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
        Command::Verify(args) => match crate::compose::composition(&args.scheme)? {
            Some(plan) => crate::compose::verify(args, plan, out),
            None => crate::mesh::verify(args, out),
        },
        Command::Subdivide(args) => match crate::compose::composition(&args.scheme)? {
            Some(plan) => crate::compose::subdivide(args, plan, out),
            None => crate::mesh::subdivide(args, out),
        },
        Command::Plot(args) => crate::plot::plot(args, out),
    }
}

fn table(args: TableArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let levels = parse_levels(&args.levels).map_err(|e| usage!("invalid --levels: {e}"))?;
    let input = Input::new(&args.source);
    let counter = input.counter()?;
    let x0 = input.initial_state(&counter)?;
    let uv = input.uv_counter(&counter)?;
    guard::table(&counter, &x0, &levels, uv.as_ref())?;
    let mut rows = counter.rows(&x0, levels)?;
    let mut columns = counter.columns();
    if let Some(uv) = &uv {
        uv.extend_rows(&mut columns, &mut rows)?;
    }
    let table = output::Table {
        columns: &columns,
        rows: &rows,
    };
    match args.format {
        TableFormat::Text => table.write_text(out),
        TableFormat::Json => table.write_json(out),
        TableFormat::Csv => table.write_csv(out),
    }
    .map_err(write_failure)?;
    Ok(0)
}

fn at(args: AtArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let s = parse_level(&args.level)?;
    let input = Input::new(&args.source);
    let counter = input.counter()?;
    let x0 = input.initial_state(&counter)?;
    let mut columns = counter.columns();
    let uv = input.uv_counter(&counter)?;
    if uv.is_some() {
        columns.push(schemes::uv::UV_COLUMN.to_string());
    }
    if args.summary {
        // An exact closed form summarizes every count without materializing it (any
        // level); otherwise the counts are computed under the digit guard.
        let summary = |v: &BigInt| recurrence::digit_summary(v, schemes::SUMMARY_DIGITS);
        let mut sums = match counter.summaries(&x0, s, args.allow_large) {
            Some(sums) => sums,
            None => {
                guard::digits(&counter, &x0, s, args.allow_large, Hint::AtSummary)?;
                let row = counter.row_at(&x0, s)?;
                row.values.iter().map(|v| v.as_ref().map(summary)).collect()
            }
        };
        if let Some(uv) = &uv {
            let sum = match uv.summary_at(s) {
                Some(sum) => sum,
                None => {
                    guard::digits(&counter, &x0, s, args.allow_large, Hint::AtSummary)?;
                    summary(&uv.values_at(s)?)
                }
            };
            sums.push(Some(sum));
        }
        write_summaries(out, args.format, s, &columns, &sums).map_err(write_failure)?;
        return Ok(0);
    }
    guard::digits(&counter, &x0, s, args.allow_large, Hint::At)?;
    let mut row = counter.row_at(&x0, s)?;
    if let Some(uv) = &uv {
        row.values.push(Some(uv.values_at(s)?));
    }
    match args.format {
        AtFormat::Text => {
            let mut text = format!("level {s}\n");
            for (name, v) in columns.iter().zip(&row.values) {
                if let Some(v) = v {
                    text.push_str(&format!("{name} = {}\n", decimal::Decimal::from(v)));
                }
            }
            write!(out, "{text}")
        }
        AtFormat::Json => output::write_row_json(out, &columns, &row).and_then(|_| writeln!(out)),
    }
    .map_err(write_failure)?;
    Ok(0)
}

fn write_summaries(
    out: &mut impl Write,
    format: AtFormat,
    s: u64,
    columns: &[String],
    sums: &[Option<DigitSummary>],
) -> std::io::Result<()> {
    match format {
        AtFormat::Text => {
            writeln!(out, "level {s}")?;
            for (name, d) in columns.iter().zip(sums) {
                if let Some(d) = d {
                    writeln!(out, "{name}: {}", output::summary_text(d))?;
                }
            }
            Ok(())
        }
        AtFormat::Json => {
            let fields: Vec<(&str, Field)> = std::iter::once(("level", Field::Json(s.into())))
                .chain(columns.iter().zip(sums).map(|(name, d)| {
                    let d = d.as_ref().map_or(Value::Null, output::summary_json);
                    (name.as_str(), Field::Json(d))
                }))
                .collect();
            output::write_object(out, &fields)?;
            writeln!(out)
        }
    }
}

fn formula(args: FormulaArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let input = Input::new(&args.source);
    let counter = input.counter()?;
    guard::closed_forms(&counter, args.allow_large)?;
    // With an initial state (--init, --counts, --mesh, --base), the text form also shows the
    // numbers substituted.
    let x0 = if input.has_state() {
        Some(input.initial_state(&counter)?)
    } else {
        None
    };
    let mut text = match &counter {
        Counter::Matrix(r) => render_form(&verified_form(r, args.format)?, args.format, "counts")?,
        Counter::Plan(plan) => {
            let phases = plan.phases();
            let fn_base = plan
                .name()
                .replace(|c: char| !c.is_ascii_alphanumeric(), "_");
            if phases.len() == 1 && phases[0].first_level == 0 && phases[0].period == 1 {
                render_form(
                    &verified_form(&phases[0].recurrence, args.format)?,
                    args.format,
                    &format!("{fn_base}_counts"),
                )?
            } else {
                render_phases(&phases, args.format, &fn_base)?
            }
        }
    };
    if let (Some(x0), FormulaFormat::Text) = (&x0, args.format) {
        text = format!("{}\n\n{}", text.trim_end(), counter.specialized_text(x0));
    }
    if let Some(uv) = input.uv_counter(&counter)? {
        let fn_base = counter.plan().map_or_else(String::new, |p| {
            p.name().replace(|c: char| !c.is_ascii_alphanumeric(), "_")
        });
        text = uv_formula(&uv, args.format, text, &fn_base)?;
    }
    writeln!(out, "{}", text.trim_end()).map_err(write_failure)?;
    Ok(0)
}

/// `formula --mesh FILE` for a mesh with a UV layout: `text` (the counts' forms) followed by
/// the closed form of the UV values `UV(s)` over the layout's statistics `UV0`, `UE0`, `UBE0`
/// and the scheme's `F0` (and `H0` for Catmull-Clark), in the format asked: the `UV(s)` line
/// in text (with the layout's numbers substituted, as for the counts) and LaTeX, a second
/// function `<scheme>_uv_counts` in Rust, and a `"UV"` component appended to the JSON list.
/// A composition has no single UV form: one note on stderr says so and `text` is unchanged.
fn uv_formula(
    uv: &schemes::uv::UvCounter,
    format: FormulaFormat,
    text: String,
    fn_base: &str,
) -> Result<String, Failure> {
    let Some(single) = uv.single() else {
        print_note(
            "note: the UV values of a composition have no single closed form: `subcount table` counts them (its UV column)".into(),
        );
        return Ok(text);
    };
    if single.period() > 1 {
        return uv_phase_formula(uv, single, format, text, fn_base);
    }
    let form = verified_form(single.recurrence(), format)?;
    let layout = uv.uv_counts();
    // The UV values: the recurrence's first component (`UV`) from `VALID_FROM` on (or later,
    // where the form has early levels), the `vt` the faces use at level 0.
    let uv_index = 0;
    let valid_from = schemes::uv::UvScheme::VALID_FROM;
    let early = [(0, BigInt::from(layout.used_vt))];
    let line = |latex: bool| {
        form.component_line_from(uv_index, "s", latex, valid_from, &early)
            .ok_or_else(|| {
                Failure::new(
                    Kind::Input,
                    anyhow::anyhow!("the UV recurrence has no UV component"),
                )
            })
    };
    let text = text.trim_end();
    Ok(match format {
        FormulaFormat::Text => {
            let x0 = single.initial_state(layout);
            let given = initial_values(single, &x0);
            let numbers =
                schemes::specialized_line_from(&form, uv_index, &x0, "s", valid_from, &early)
                    .unwrap_or_else(|| "(not rational: see the symbolic form above)".into());
            let sqrt3 = format!("UV values over the UV layout: {SQRT3_UV_STATE_TEXT}");
            let over = if single.recurrence().names() == schemes::uv::UV_SEAM_STATE {
                "UV values over the UV layout and its seams: UV0 values (the (vertex, vt) pairs), UE0 layout edges, UBE0 layout boundary edges, S0 seam edges"
            } else if single.rule() == schemes::Rule::Sqrt3 {
                &sqrt3
            } else {
                "UV values over the UV layout: UV0 values (the (vertex, vt) pairs, with OpenSubdiv's split values), UE0 layout edges, UBE0 layout boundary edges"
            };
            format!(
                "{text}\n\n# {over}; UV(0) is the number of vt the faces use\n{}\n\n# with {}; the real count at level 0 is the {} vt the faces use\n{numbers}",
                line(false)?,
                given,
                layout.used_vt,
            )
        }
        FormulaFormat::Latex => format!("{text}\n{}", line(true)?),
        FormulaFormat::Rust => {
            let counts = format!("{fn_base}_uv_counts");
            let dim = single.recurrence().dim();
            format!(
                "{text}\n\n/// UV values: the state ({}) of the UV layout, `UV` from level {valid_from} on.\n{}\n\n/// The UV values at level `s`: `used_vt` (the `vt` the faces use) at level 0, the `UV` of\n/// `{counts}` from level {valid_from} on.\npub fn {fn_base}_uv_values(x0: [i128; {dim}], used_vt: i128, s: u64) -> Option<i128> {{\n    if s < {valid_from} {{\n        return Some(used_vt);\n    }}\n    {counts}(x0, s).map(|x| x[{uv_index}])\n}}",
                single.recurrence().names().join(", "),
                form.to_rust(&counts).trim_end()
            )
        }
        FormulaFormat::Json => {
            let mut value: Value =
                serde_json::from_str(text).map_err(|e| Failure::new(Kind::Input, e))?;
            let c = form.components().get(uv_index).ok_or_else(|| {
                Failure::new(
                    Kind::Input,
                    anyhow::anyhow!("the UV recurrence has no UV component"),
                )
            })?;
            let mut component = form.to_json()[uv_index].take();
            let from = valid_from.max(c.valid_from);
            component["valid_from"] = json!(from);
            // Below `from`: the `vt` used at level 0 (`"value"`, not a combination of the
            // initial values), the form's own early levels after it.
            let mut levels = vec![json!({ "level": 0, "value": layout.used_vt.to_string() })];
            if let Some(own) = component["early_levels"].as_array() {
                levels.extend(own.iter().filter(|e| e["level"] != 0).cloned());
            }
            component["early_levels"] = Value::Array(levels);
            match &mut value {
                Value::Array(list) => list.push(component),
                other => *other = json!({ "forms": other.clone(), "UV": component }),
            }
            pretty(&value)?
        }
    })
}

/// `UV0 = 267, UE0 = 438, ...`: the UV recurrence's components named with the values `x`.
fn initial_values(single: &schemes::uv::UvScheme, x: &[BigInt]) -> String {
    let names = single.recurrence().names();
    let given: Vec<String> = names
        .iter()
        .zip(x)
        .map(|(n, v)| format!("{n}0 = {v}"))
        .collect();
    given.join(", ")
}

/// What √3's UV state counts (`formula --mesh`).
const SQRT3_UV_STATE_TEXT: &str =
    "UV0 values (the (vertex, vt) pairs), UBE0 layout boundary edges, S0 seam edges, F0 faces";

/// [`uv_formula`] for a UV recurrence that alternates steps (`sqrt3-boundary`): one closed
/// form of the UV state per phase, as the counts' phases ([`render_phases`]), in `t` with the
/// state at the phase's first level (the text gives those states); JSON appends
/// `{"UV": [phases]}`. Level 0's UV count is the `vt` the faces use.
fn uv_phase_formula(
    uv: &schemes::uv::UvCounter,
    single: &schemes::uv::UvScheme,
    format: FormulaFormat,
    text: String,
    fn_base: &str,
) -> Result<String, Failure> {
    let phases = single.phases();
    let layout = uv.uv_counts();
    let body = render_phases(&phases, format, &format!("{fn_base}_uv"))?;
    let text = text.trim_end();
    Ok(match format {
        FormulaFormat::Json => {
            let mut value: Value =
                serde_json::from_str(text).map_err(|e| Failure::new(Kind::Input, e))?;
            let forms: Value =
                serde_json::from_str(&body).map_err(|e| Failure::new(Kind::Input, e))?;
            let uv_value = json!({ "phases": forms, "level0": layout.used_vt.to_string() });
            match &mut value {
                Value::Array(list) => list.push(json!({ "UV": uv_value })),
                other => *other = json!({ "forms": other.clone(), "UV": uv_value }),
            }
            pretty(&value)?
        }
        FormulaFormat::Text => {
            let mut starts = Vec::new();
            for phase in &phases {
                let x = single
                    .state_at(layout, phase.first_level)
                    .map_err(crate::failure::scheme_failure)?;
                let given = initial_values(single, &x);
                starts.push(format!("# {}: {given}", phase.description));
            }
            format!(
                "{text}\n\n# UV values over the UV layout: {SQRT3_UV_STATE_TEXT}; the UV of each phase from level {} on; UV(0) is the {} vt the faces use\n{}\n\n# the state at each phase's first level\n{}",
                schemes::uv::UvScheme::VALID_FROM,
                layout.used_vt,
                body.trim_end(),
                starts.join("\n")
            )
        }
        _ => format!("{text}\n\n{}", body.trim_end()),
    })
}

fn render_form(form: &ClosedForm, format: FormulaFormat, fn_name: &str) -> Result<String, Failure> {
    Ok(match format {
        FormulaFormat::Text => form.to_text(),
        FormulaFormat::Latex => form.to_latex(),
        FormulaFormat::Rust => form.to_rust(fn_name),
        FormulaFormat::Json => pretty(&form.to_json())?,
    })
}

/// The closed form of `r`, or exit 3 when its numeric terms miss the exact counts (the Rust
/// rendering of a form that is not all integers powers the matrix, so it needs no terms).
fn verified_form(r: &recurrence::Recurrence, format: FormulaFormat) -> Result<ClosedForm, Failure> {
    let form = r.closed_form();
    if format != FormulaFormat::Rust {
        form.verify().map_err(|e| Failure::new(Kind::Input, e))?;
    }
    Ok(form)
}

fn pretty(value: &Value) -> Result<String, Failure> {
    serde_json::to_string_pretty(value).map_err(|e| Failure::new(Kind::Input, e))
}

/// One closed form per phase (residue class of a periodic scheme, or stage of a composition).
/// Within a phase, `t` counts periods from the phase's first level, and the subscript-0 values
/// are the counts at that first level.
fn render_phases(
    phases: &[Phase],
    format: FormulaFormat,
    fn_base: &str,
) -> Result<String, Failure> {
    if format == FormulaFormat::Json {
        let forms = phases
            .iter()
            .map(|phase| {
                Ok(json!({
                    "phase": phase.description,
                    "first_level": phase.first_level,
                    "period": phase.period,
                    "last_level": phase.last_level,
                    "stage": phase.stage,
                    "forms": verified_form(&phase.recurrence, format)?.to_json(),
                }))
            })
            .collect::<Result<Vec<Value>, Failure>>()?;
        return pretty(&Value::Array(forms));
    }
    let mut text = String::new();
    for (i, phase) in phases.iter().enumerate() {
        let form = verified_form(&phase.recurrence, format)?;
        let heading = phase_heading(phase);
        let (comment, body) = match format {
            // The closed form reads in `s`; within a phase the variable is `t`.
            FormulaFormat::Text => ("#", form.to_text_in("t")),
            FormulaFormat::Latex => ("%", form.to_latex()),
            _ => ("//", form.to_rust(&format!("{fn_base}_phase{i}"))),
        };
        text.push_str(&format!("{comment} {heading}\n{body}\n"));
    }
    Ok(text)
}

fn phase_heading(phase: &Phase) -> String {
    let until = phase
        .last_level
        .map(|l| format!(" up to level {l}"))
        .unwrap_or_default();
    format!(
        "{}: level s = {} + {}t{until}; X0 below means the count X at level {}",
        phase.description, phase.first_level, phase.period, phase.first_level
    )
}
