//! `plot`: V, E, F, the state components and, for a mesh with a UV layout, its UV values
//! versus level on a log10 scale, as SVG or PNG.
//!
//! The counts come from [`Counter`] exactly as `table` computes them; only the drawing is
//! approximate. log10 of a count comes from its bit length and leading 64 bits, so counts of
//! any size map to finite positions (plotters' log coordinates take `f64` counts, which end at
//! about 10^308): the `chart` crate draws them on an axis linear in log10, labelled 10^k. This
//! module turns the rows into its series, legend labels and notes, and writes the file.

use std::io::Write;
use std::path::Path;

use chart::{Chart, Series};

use crate::args::{PlotArgs, Source};
use crate::failure::{input, usage, write_failure, Failure};
use crate::levels::parse_levels;
use crate::model::{Input, DEFAULT_COUNTS};
use schemes::output::Row;
use schemes::Counter;

/// The most levels one plot draws (each is a point on every line).
const MAX_LEVELS: u64 = 1000;

/// `subcount plot`: writes the image named by `-o` and prints one line saying so.
pub(crate) fn plot(args: PlotArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let svg = is_svg(&args.output)?;
    let levels = parse_levels(&args.levels).map_err(|e| usage!("invalid --levels: {e}"))?;
    let (first, last) = (*levels.start(), *levels.end());
    if last - first >= MAX_LEVELS {
        let (given, n) = (args.levels.trim(), u128::from(last - first) + 1);
        return Err(usage!(
            "invalid --levels: `{given}` has {n} levels; a plot shows at most {MAX_LEVELS}"
        ));
    }
    let input = Input::new(&args.source);
    let counter = input.counter()?;
    let x0 = input.initial_state(&counter)?;
    // A mesh with a UV layout adds the UV values as a series of their own.
    let uv = input.uv_counter(&counter)?;
    driver::limits::table(&counter, &x0, &levels, uv.as_ref())?;
    let mut rows = counter.rows(&x0, levels.clone())?;
    let mut columns = counter.columns();
    if let Some(uv) = &uv {
        uv.extend_rows(&mut columns, &mut rows)?;
    }
    let series = series_of(&columns, &rows);
    // Columns without a positive count in range cannot be drawn on a log scale: the legend
    // says so.
    let notes: Vec<String> = columns
        .iter()
        .filter(|c| !series.iter().any(|s| &s.name == *c))
        .map(|n| format!("{n}: no positive count"))
        .collect();
    if series.is_empty() {
        let why = format!("no count is positive at levels {first}..={last}");
        return Err(usage!("nothing to plot: {why}"));
    }
    let chart = Chart {
        title: title(&counter, &args.source),
        subtitle: format!("exact counts at levels {first}..={last}, log scale"),
        x_label: "level".to_string(),
        y_label: "count (log scale)".to_string(),
        levels,
        series,
        notes,
    };
    let drawn = if svg {
        chart::render_svg(&chart).map(String::into_bytes)
    } else {
        chart::render_png(&chart)
    };
    let bytes = drawn.map_err(|e| input!("{e}"))?;
    let written = driver::output::write_atomically(&args.output, |file| file.write_all(&bytes));
    written.map_err(|e| match e {
        driver::Error::Geometry(halfedge::Error::Io { path, source }) => {
            input!("cannot write {}: {source}", path.display())
        }
        other => input!("cannot write {}: {other}", args.output.display()),
    })?;
    let (path, n) = (args.output.display(), chart.series.len());
    writeln!(out, "wrote {path} ({n} series, levels {first}..={last})").map_err(write_failure)?;
    Ok(0)
}

/// Whether `-o` names an SVG (else a PNG), by its extension in any case.
fn is_svg(path: &Path) -> Result<bool, Failure> {
    let ext = path.extension().and_then(|e| e.to_str());
    match ext.map(str::to_ascii_lowercase).as_deref() {
        Some("svg") => Ok(true),
        Some("png") => Ok(false),
        Some(other) => Err(usage!(
            "unknown image format `.{other}` in -o {}: use a .svg or .png file name",
            path.display()
        )),
        None => Err(usage!(
            "-o {} has no extension: use a .svg or .png file name",
            path.display()
        )),
    }
}

/// One line per column with a positive count: its name, its legend label and its positive
/// counts as (level, log10 count).
fn series_of(columns: &[String], rows: &[Row]) -> Vec<Series> {
    columns
        .iter()
        .enumerate()
        .map(|(j, name)| Series {
            name: name.clone(),
            label: legend_label(name),
            points: rows
                .iter()
                .filter_map(|r| {
                    let v = r.values.get(j)?.as_ref()?;
                    Some((r.level, decimal::log10(v)?))
                })
                .collect(),
        })
        .filter(|s| !s.points.is_empty())
        .collect()
}

/// The legend text of a column: the name, and what it counts for the mesh statistics.
fn legend_label(name: &str) -> String {
    schemes::Stat::from_short_name(name)
        .map_or_else(|| name.to_string(), |s| format!("{name} ({})", s.brief()))
}

/// "loop on icosahedron"-style title naming the rule and the initial mesh or state.
fn title(counter: &Counter, source: &Source) -> String {
    let rule = match counter {
        Counter::Matrix(_) => format!("matrix {}", source.matrix.as_deref().unwrap_or("")),
        Counter::Plan(plan) => plan.name().to_string(),
    };
    let start = if let Some(path) = &source.mesh.mesh {
        path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    } else if let Some(base) = &source.mesh.base {
        base.clone()
    } else if let Some(counts) = &source.counts {
        counts.trim().to_string()
    } else if let Some(init) = &source.init {
        format!("initial state {}", init.trim())
    } else {
        format!("the icosahedron ({DEFAULT_COUNTS})")
    };
    format!("{rule} on {start}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    #[test]
    fn series_skip_missing_and_nonpositive_values() {
        let row = |level, values: [i64; 2]| Row {
            level,
            values: values
                .into_iter()
                .map(|v| Some(BigInt::from(v)))
                .chain([None])
                .collect(),
        };
        let columns = ["A", "B", "C"].map(String::from);
        let s = series_of(&columns, &[row(0, [0, 10]), row(1, [100, -1])]);
        let got: Vec<_> = s.iter().map(|s| (s.name.as_str(), &s.points[..])).collect();
        assert_eq!(got, [("A", &[(1, 2.0)][..]), ("B", &[(0, 1.0)][..])]);
        assert_eq!(s[0].label, "A");
        let columns = ["E", "BE"].map(String::from);
        let s = series_of(&columns, &[row(0, [1, 1])]);
        let labels: Vec<_> = s.iter().map(|s| s.label.as_str()).collect();
        assert_eq!(labels, ["E (edges)", "BE (boundary edges)"]);
    }
}
