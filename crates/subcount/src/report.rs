//! `fit`, `density` and `schemes`: budgets, the paper's eq. (1), and the scheme table.

use std::io::Write;

use num_bigint::BigInt;
use schemes::{Budget, Counter, Fit, MemoryBudget, Plan};
use serde_json::Value;

use crate::args::{DensityArgs, FitArgs, ReportFormat, SchemesArgs, SchemesFormat};
use crate::failure::{input, scheme_failure, usage, write_failure, Failure, Kind};
use crate::levels::parse_level;
use crate::model::Input;
use driver::limits::{self as guard, Hint};
use schemes::output::{self, Field, Row};

fn plan_of(counter: Counter, command: &str) -> Result<Plan, Failure> {
    match counter {
        Counter::Plan(plan) => Ok(plan),
        Counter::Matrix(_) => Err(usage!(
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

pub(crate) fn fit(args: FitArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let input = Input::new(&args.source);
    let counter = input.counter()?;
    let plan = plan_of(counter.clone(), "fit")?;
    let memory = match &args.memory {
        Some(text) => Some(MemoryBudget {
            bytes: BigInt::from(
                schemes::parse_byte_size(text).map_err(|e| usage!("invalid --memory: {e}"))?,
            ),
            bytes_per_vertex: args.bytes_per_vertex,
            bytes_per_edge: args.bytes_per_edge,
            bytes_per_face: args.bytes_per_face,
            bytes_per_uv: args.bytes_per_uv.unwrap_or(0),
        }),
        None => None,
    };
    let budget = Budget {
        max_vertices: parse_limit("max-vertices", &args.max_vertices)?,
        max_edges: parse_limit("max-edges", &args.max_edges)?,
        max_faces: parse_limit("max-faces", &args.max_faces)?,
        max_uv: parse_limit("max-uv", &args.max_uv)?,
        memory,
    };
    if budget == Budget::default() {
        return Err(usage!(
            "fit needs a limit: --max-vertices, --max-edges, --max-faces, --max-uv or --memory"
        ));
    }
    let x0 = input.initial_state(&counter)?;
    let uv = uv_for_fit(&input, &counter, &plan, &args)?;
    let fit = match &uv {
        Some(uv) => schemes::fit_uv(&plan, &x0, uv, &budget)?,
        None => schemes::fit(&plan, &x0, &budget)?,
    };
    let mut columns = counter.columns();
    let counts = fit.counts()?;
    let note = matches!(fit, Fit::Unbounded { .. }).then(|| unbounded_note(counts.level));
    let mut row = counter.row_from_state(counts.level, counts.state.clone())?;
    if let Some(uv) = &uv {
        uv.extend_rows(&mut columns, std::slice::from_mut(&mut row))?;
    }
    let mut buf = Vec::new();
    match (note, args.format) {
        (None, ReportFormat::Json) => output::write_row_json(&mut buf, &columns, &row),
        (None, ReportFormat::Text) => write!(
            buf,
            "highest level within the budget: {}\n{}",
            counts.level,
            row_text(&columns, &row)
        ),
        (Some(note), ReportFormat::Json) => {
            let mut fields = vec![
                ("level", Field::Json(Value::Null)),
                ("note", Field::Json(note.into())),
                ("from_level", Field::Json(counts.level.into())),
            ];
            fields.extend(output::row_fields(&columns, &row).into_iter().skip(1));
            output::write_object(&mut buf, &fields)
        }
        (Some(note), ReportFormat::Text) => write!(buf, "{note}\n{}", row_text(&columns, &row)),
    }
    .map_err(write_failure)?;
    writeln!(out, "{}", String::from_utf8_lossy(&buf).trim_end()).map_err(write_failure)?;
    Ok(0)
}

/// The UV values `fit` counts: those of the mesh's UV layout under the plan, when it has one
/// and the plan counts UV values (a `UV` line in the answer). `--max-uv` and `--bytes-per-uv`
/// need them: without a mesh, on a mesh without a UV layout, or under a scheme that does not
/// count UV values, they are a usage error (exit 2).
fn uv_for_fit(
    input: &Input<'_>,
    counter: &Counter,
    plan: &Plan,
    args: &FitArgs,
) -> Result<Option<schemes::uv::UvCounter>, Failure> {
    let flag = match (&args.max_uv, args.bytes_per_uv) {
        (Some(_), _) => Some("--max-uv"),
        (None, Some(_)) => Some("--bytes-per-uv"),
        (None, None) => None,
    };
    let layout = if input.has_mesh() {
        input.uv_counts(plan)?
    } else {
        None
    };
    let Some(flag) = flag else {
        return Ok(layout.and_then(|uv| counter.uv_counter(&uv).ok()));
    };
    let Some(layout) = layout else {
        let what = if input.has_mesh() {
            format!(
                "{} has no UV layout",
                crate::model::mesh_label(&args.source.mesh)
            )
        } else {
            "no mesh is given".to_string()
        };
        return Err(usage!(
            "{flag} counts UV values, which needs --mesh FILE with texture coordinates (`vt`) at every face corner, but {what}"
        ));
    };
    counter
        .uv_counter(&layout)
        .map(Some)
        .map_err(|e| usage!("{flag}: {e}"))
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
    let input = Input::new(&args.source);
    let counter = input.counter()?;
    let plan = plan_of(counter.clone(), "density")?;
    let x0 = input.initial_state(&counter)?;
    let counts = match (&args.level, args.target_area) {
        (Some(level), _) => {
            let s = parse_level(level)?;
            guard::digits(&counter, &x0, s, false, Hint::Levels)?;
            plan.level_counts(&x0, s)?
        }
        (None, Some(area)) => schemes::level_for_area(&plan, &x0, args.radius, area)?,
        (None, None) => return Err(usage!("density needs --level or --target-area")),
    };
    if args.tau == Some(0.0) {
        return Err(usage!(
            "density: tau must be positive, got 0 (the scale factor phi = sqrt(tau / area) would be 0)"
        ));
    }
    let tau = args.tau.unwrap_or(0.0);
    let d = schemes::density(&counts.vertices, args.radius, tau).map_err(|e| match e {
        schemes::Error::Density { .. } => Failure::new(Kind::Usage, e),
        e => scheme_failure(e),
    })?;
    let phi = args.tau.map(|_| d.phi);
    let text = match args.format {
        ReportFormat::Json => {
            let mut fields = vec![
                ("level", Field::Json(counts.level.into())),
                ("V", Field::Count(Some(&counts.vertices))),
                ("radius", Field::Json(args.radius.into())),
            ];
            if let Some(a) = args.target_area {
                fields.push(("target_area", Field::Json(a.into())));
            }
            fields.push(("mean_area", Field::Json(d.mean_area.into())));
            if let (Some(tau), Some(p)) = (args.tau, phi) {
                fields.push(("tau", Field::Json(tau.into())));
                fields.push(("phi", Field::Json(p.into())));
            }
            let mut buf = Vec::new();
            output::write_object(&mut buf, &fields).map_err(write_failure)?;
            String::from_utf8_lossy(&buf).into_owned()
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
        Some(name) => vec![schemes::builtin(name)?],
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
