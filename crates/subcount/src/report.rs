//! `fit`, `density` and `schemes`: budgets, the paper's eq. (1), and the scheme table.

use std::io::Write;

use num_bigint::BigInt;
use schemes::{Budget, Fit, MemoryBudget};

use crate::args::{DensityArgs, FitArgs, ReportFormat, SchemesArgs, SchemesFormat};
use crate::commands::{parse_level, write_failure};
use crate::failure::{input, usage, Failure, Kind};
use crate::model::{scheme_failure, Dynamics};
use crate::output::{self, Row};

fn plan_of(dynamics: &Dynamics, command: &str) -> Result<schemes::Plan, Failure> {
    match dynamics {
        Dynamics::Plan(plan) => Ok(plan.clone()),
        Dynamics::Matrix(_) => Err(usage!(
            "{command} needs a scheme (--scheme or --scheme-file), not --matrix"
        )),
    }
}

fn parse_limit(flag: &str, text: &Option<String>) -> Result<Option<BigInt>, Failure> {
    let Some(t) = text else { return Ok(None) };
    let t = t.trim();
    let v: BigInt = t
        .parse()
        .map_err(|_| usage!("invalid --{flag}: `{t}` is not a whole number"))?;
    if v.sign() == num_bigint::Sign::Minus {
        return Err(usage!("invalid --{flag}: `{t}` is negative"));
    }
    Ok(Some(v))
}

fn level_row(dynamics: &Dynamics, counts: &schemes::LevelCounts) -> Result<Row, Failure> {
    dynamics.row_from_state(counts.level, counts.state.clone())
}

pub(crate) fn fit(args: FitArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let dynamics = Dynamics::from_source(&args.source)?;
    let plan = plan_of(&dynamics, "fit")?;
    let memory = match &args.memory {
        Some(text) => Some(MemoryBudget {
            bytes: BigInt::from(
                schemes::parse_byte_size(text).map_err(|e| usage!("invalid --memory: {e}"))?,
            ),
            bytes_per_vertex: args.bytes_per_vertex,
            bytes_per_edge: args.bytes_per_edge,
            bytes_per_face: args.bytes_per_face,
        }),
        None => None,
    };
    let budget = Budget {
        max_vertices: parse_limit("max-vertices", &args.max_vertices)?,
        max_edges: parse_limit("max-edges", &args.max_edges)?,
        max_faces: parse_limit("max-faces", &args.max_faces)?,
        memory,
    };
    if budget == Budget::default() {
        return Err(usage!(
            "fit needs a limit: --max-vertices, --max-edges, --max-faces or --memory"
        ));
    }
    let x0 = dynamics.initial_state(&args.source)?;
    let fit = schemes::fit(&plan, &x0, &budget).map_err(scheme_failure)?;
    let columns = dynamics.columns();
    let text = match (&fit, args.format) {
        (Fit::Level(counts), ReportFormat::Json) => {
            let mut buf = Vec::new();
            output::write_row_json(&mut buf, &columns, &level_row(&dynamics, counts)?)
                .map_err(write_failure)?;
            String::from_utf8_lossy(&buf).into_owned()
        }
        (Fit::Level(counts), ReportFormat::Text) => {
            let row = level_row(&dynamics, counts)?;
            format!(
                "highest level within the budget: {}\n{}",
                counts.level,
                row_text(&columns, &row)
            )
        }
        (Fit::Unbounded { counts }, ReportFormat::Json) => {
            let row = level_row(&dynamics, counts)?;
            let mut buf = Vec::new();
            output::write_row_json(&mut buf, &columns, &row).map_err(write_failure)?;
            let body = String::from_utf8_lossy(&buf).into_owned();
            let rest = body
                .split_once(", ")
                .map(|(_, r)| r.trim_end_matches('}'))
                .unwrap_or("");
            format!(
                "{{\"level\": null, \"note\": {}, \"from_level\": {}, {rest}}}",
                output::json_string(&unbounded_note(counts.level)),
                counts.level
            )
        }
        (Fit::Unbounded { counts }, ReportFormat::Text) => {
            let row = level_row(&dynamics, counts)?;
            format!(
                "{}\n{}",
                unbounded_note(counts.level),
                row_text(&columns, &row)
            )
        }
    };
    writeln!(out, "{}", text.trim_end()).map_err(write_failure)?;
    Ok(0)
}

/// The note of a [`Fit::Unbounded`] answer: the limited counts are the same at `level` and
/// every later level, and `level` is the least such level.
fn unbounded_note(level: u64) -> String {
    if level == 0 {
        "every level fits: the limited counts never change (level 0 and every later level have the same counts)".to_string()
    } else {
        format!("every level fits: the limited counts stop changing at level {level} (level {level} and every later level have the same counts)")
    }
}

fn row_text(columns: &[String], row: &Row) -> String {
    columns
        .iter()
        .zip(&row.values)
        .filter_map(|(c, v)| v.as_ref().map(|v| format!("{c} = {v}")))
        .collect::<Vec<_>>()
        .join("\n")
}

pub(crate) fn density(args: DensityArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let dynamics = Dynamics::from_source(&args.source)?;
    let plan = plan_of(&dynamics, "density")?;
    let x0 = dynamics.initial_state(&args.source)?;
    let counts = match (&args.level, args.target_area) {
        (Some(level), _) => {
            let s = parse_level(level)?;
            crate::commands::guard_digits_for(
                &dynamics,
                &x0,
                s,
                false,
                crate::commands::Hint::Levels,
            )?;
            plan.level_counts(&x0, s).map_err(scheme_failure)?
        }
        (None, Some(area)) => {
            schemes::level_for_area(&plan, &x0, args.radius, area).map_err(scheme_failure)?
        }
        (None, None) => return Err(usage!("density needs --level or --target-area")),
    };
    let tau = args.tau.unwrap_or(0.0);
    let d = schemes::density(&counts.vertices, args.radius, tau)
        .map_err(|e| Failure::new(Kind::Usage, e))?;
    let phi = args.tau.map(|_| d.phi);
    let text = match args.format {
        ReportFormat::Json => {
            let num = |x: f64| serde_json::to_string(&x).unwrap_or_else(|_| "null".into());
            let mut t = format!(
                "{{\"level\": {}, \"V\": {}, \"radius\": {}",
                counts.level,
                counts.vertices,
                num(args.radius)
            );
            if let Some(a) = args.target_area {
                t.push_str(&format!(", \"target_area\": {}", num(a)));
            }
            t.push_str(&format!(", \"mean_area\": {}", num(d.mean_area)));
            if let (Some(tau), Some(p)) = (args.tau, phi) {
                t.push_str(&format!(", \"tau\": {}, \"phi\": {}", num(tau), num(p)));
            }
            t.push('}');
            t
        }
        ReportFormat::Text => {
            let mut t = format!(
                "level {}\nV = {}\nmean co-volume area 4 pi r^2 / V = {:e}",
                counts.level, counts.vertices, d.mean_area
            );
            if let Some(p) = phi {
                t.push_str(&format!("\nscale factor phi = sqrt(tau / area) = {p:e}"));
            }
            t
        }
    };
    writeln!(out, "{text}").map_err(write_failure)?;
    Ok(0)
}

pub(crate) fn list_schemes(args: SchemesArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let list = match &args.name {
        Some(name) => vec![schemes::builtin(name).map_err(scheme_failure)?],
        None => schemes::builtins(),
    };
    let text = match args.format {
        SchemesFormat::Toml => {
            if args.name.is_none() {
                return Err(usage!("--format toml exports one scheme: name it, e.g. `subcount schemes --format toml loop`"));
            }
            list[0].to_toml()
        }
        SchemesFormat::Json => {
            let arr: Vec<serde_json::Value> = list.iter().map(|s| s.to_json()).collect();
            serde_json::to_string_pretty(&arr).map_err(|e| input!("{e}"))?
        }
        SchemesFormat::Text => {
            let mut t = String::new();
            for s in &list {
                t.push_str(&format!(
                    "{}\n  {}\n  state ({}), for {}\n",
                    s.name(),
                    s.description(),
                    s.state_names().join(", "),
                    s.mesh_class()
                ));
                if let Some(first) = s.first_step() {
                    t.push_str(&format!("  first step {first}\n"));
                }
                if s.cycle().len() > 1 {
                    for (i, m) in s.cycle().iter().enumerate() {
                        t.push_str(&format!("  step {} of each cycle {m}\n", i + 1));
                    }
                } else {
                    t.push_str(&format!("  matrix {}\n", s.matrix()));
                }
                for (stat, formula) in s.derived() {
                    t.push_str(&format!("  {stat} = {formula}\n"));
                }
            }
            t
        }
    };
    writeln!(out, "{}", text.trim_end()).map_err(write_failure)?;
    Ok(0)
}
