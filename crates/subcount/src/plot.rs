//! `plot`: V, E, F and the state components versus level on a log10 scale, as SVG or PNG.
//!
//! The counts come from [`Dynamics`] exactly as `table` computes them; only the drawing is
//! approximate. Each count is turned into log10 from its bit length and its leading 64 bits, so
//! counts of any size (thousands of digits) map to finite plot positions without overflow.
//!
//! One [`Scene`] (lines, markers, text in pixel coordinates) is laid out once and then either
//! written as SVG by hand or rasterized here into RGB pixels and encoded with `png`. Text in the
//! PNG is drawn with an embedded Noto Sans (the `notosans` crate) through `ab_glyph`, so the image
//! does not depend on the fonts of the machine. Both files are written atomically.

use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};

use num_bigint::{BigInt, Sign};
use num_traits::ToPrimitive;

use crate::args::{PlotArgs, Source};
use crate::failure::{input, usage, write_failure, Failure};
use crate::levels::parse_levels;
use crate::model::{Input, DEFAULT_COUNTS};
use crate::output::Row;
use schemes::Counter as Dynamics;

/// The most levels one plot draws (each is a point on every line).
const MAX_LEVELS: u64 = 1000;
/// Image size in pixels (also the SVG's user units).
const WIDTH: u32 = 960;
const HEIGHT: u32 = 600;

/// `subcount plot`: writes the image named by `-o` and prints one line saying so.
pub(crate) fn plot(args: PlotArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let format = ImageFormat::from_path(&args.output)?;
    let levels = parse_levels(&args.levels).map_err(|e| usage!("invalid --levels: {e}"))?;
    if levels.end() - levels.start() >= MAX_LEVELS {
        return Err(usage!(
            "invalid --levels: `{}` has {} levels; a plot shows at most {MAX_LEVELS}",
            args.levels.trim(),
            u128::from(levels.end() - levels.start()) + 1
        ));
    }
    let input = Input::new(&args.source);
    let dynamics = input.counter()?;
    let x0 = input.initial_state(&dynamics)?;
    crate::guard::table(&dynamics, &x0, &levels)?;
    let rows = dynamics.rows(&x0, levels.clone())?;
    let columns = dynamics.columns();
    let series = series_of(&columns, &rows);
    let hidden: Vec<String> = columns
        .iter()
        .filter(|c| !series.iter().any(|s| &s.name == *c))
        .cloned()
        .collect();
    if series.is_empty() {
        return Err(usage!(
            "nothing to plot: no count is positive at levels {}..={}",
            levels.start(),
            levels.end()
        ));
    }
    let chart = Chart {
        title: title(&dynamics, &args.source),
        subtitle: format!(
            "exact counts at levels {}..={}, log scale",
            levels.start(),
            levels.end()
        ),
        first_level: *levels.start(),
        last_level: *levels.end(),
        series,
        hidden,
    };
    let font = Font::embedded()?;
    let scene = chart.layout(&font);
    let bytes = match format {
        ImageFormat::Svg => scene.to_svg().into_bytes(),
        ImageFormat::Png => raster::to_png(&scene, &font)?,
    };
    write_atomically(&args.output, &bytes)?;
    writeln!(
        out,
        "wrote {} ({} series, levels {}..={})",
        args.output.display(),
        chart.series.len(),
        levels.start(),
        levels.end()
    )
    .map_err(write_failure)?;
    Ok(0)
}

/// The output formats, chosen by the extension of `-o`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ImageFormat {
    Svg,
    Png,
}

impl ImageFormat {
    fn from_path(path: &Path) -> Result<ImageFormat, Failure> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("svg") => Ok(ImageFormat::Svg),
            Some("png") => Ok(ImageFormat::Png),
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
}

/// log10 of a positive count, from its bit length and leading 64 bits (no overflow at any
/// size); `None` for zero and negative values, which a log scale cannot show.
pub(crate) fn log10_count(v: &BigInt) -> Option<f64> {
    if v.sign() != Sign::Plus {
        return None;
    }
    let bits = v.bits();
    let shift = bits.saturating_sub(64);
    let top = (v.magnitude() >> shift).to_u64()?;
    // `top` has at most 64 bits; f64 keeps its leading 53, far below the plot's resolution.
    Some((top as f64).log10() + shift as f64 * std::f64::consts::LOG10_2)
}

/// One line of the plot: a column and its positive counts as (level, log10 count).
#[derive(Clone, Debug, PartialEq)]
struct Series {
    name: String,
    points: Vec<(u64, f64)>,
}

fn series_of(columns: &[String], rows: &[Row]) -> Vec<Series> {
    columns
        .iter()
        .enumerate()
        .map(|(j, name)| Series {
            name: name.clone(),
            points: rows
                .iter()
                .filter_map(|r| {
                    let v = r.values.get(j)?.as_ref()?;
                    Some((r.level, log10_count(v)?))
                })
                .collect(),
        })
        .filter(|s| !s.points.is_empty())
        .collect()
}

/// The legend text of a column: the name, and what it counts for the mesh statistics.
fn legend_label(name: &str) -> String {
    let meaning = match name {
        "V" => "vertices",
        "E" => "edges",
        "F" => "faces",
        "IE" => "interior edges",
        "BE" => "boundary edges",
        "NME" => "non-manifold edges",
        "H" => "face corners",
        _ => return name.to_string(),
    };
    format!("{name} ({meaning})")
}

/// "loop on icosahedron"-style title naming the rule and the initial mesh or state.
fn title(dynamics: &Dynamics, source: &Source) -> String {
    let rule = match dynamics {
        Dynamics::Matrix(_) => format!("matrix {}", source.matrix.as_deref().unwrap_or("")),
        Dynamics::Plan(plan) => plan.name().to_string(),
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

/// Major ticks of a log10 axis: every `step` decades from `lo` to `hi` (exponents).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct LogTicks {
    lo: i64,
    hi: i64,
    step: i64,
}

impl LogTicks {
    /// Ticks covering `[min, max]` (log10 values) with at most about 8 intervals, on multiples
    /// of a 1-2-5 step so labels read 10^0, 10^5, 10^10...
    fn covering(min: f64, max: f64) -> LogTicks {
        let (min, max) = if min.is_finite() && max.is_finite() && min <= max {
            (min, max)
        } else {
            (0.0, 1.0)
        };
        let mut lo = min.floor() as i64;
        let mut hi = max.ceil() as i64;
        if hi == lo {
            hi = lo + 1;
        }
        let span = hi - lo;
        let step = nice_step(span, 8);
        lo = lo.div_euclid(step) * step;
        hi = -((-hi).div_euclid(step) * step);
        LogTicks { lo, hi, step }
    }

    fn majors(&self) -> impl Iterator<Item = i64> + '_ {
        (0..=(self.hi - self.lo) / self.step).map(move |i| self.lo + i * self.step)
    }

    /// Labels for 2 and 5 times each decade (as plain numbers) when the axis spans at most two
    /// decades between 1 and 10^4, where major ticks alone would leave it almost unlabelled.
    fn minor_labels(&self) -> Vec<(f64, String)> {
        if self.step != 1 || self.hi - self.lo > 2 || self.lo < 0 || self.hi > 4 {
            return Vec::new();
        }
        (self.lo..self.hi)
            .flat_map(|k| {
                [2u32, 5].map(|m| {
                    let value = u64::from(m) * 10u64.pow(k as u32);
                    ((value as f64).log10(), value.to_string())
                })
            })
            .collect()
    }

    /// log10 of 2..=9 times each decade, when ticks are one decade apart and at most four.
    fn minors(&self) -> Vec<f64> {
        if self.step != 1 || self.hi - self.lo > 4 {
            return Vec::new();
        }
        (self.lo..self.hi)
            .flat_map(|k| (2..=9).map(move |m| k as f64 + f64::from(m).log10()))
            .collect()
    }
}

/// The smallest 1-2-5 step (1, 2, 5, 10, 20, ...) that cuts `span` into at most `max_parts`.
fn nice_step(span: i64, max_parts: i64) -> i64 {
    let mut base = 1i64;
    loop {
        for m in [1, 2, 5] {
            let step = base.saturating_mul(m);
            if span <= step.saturating_mul(max_parts) {
                return step;
            }
        }
        base = base.saturating_mul(10);
    }
}

/// The level ticks: multiples of a 1-2-5 step within `first..=last`, at most about 12.
fn level_ticks(first: u64, last: u64) -> Vec<u64> {
    let span = i64::try_from(last - first).unwrap_or(i64::MAX);
    let step = nice_step(span.max(1), 12) as u64;
    let Some(start) = first.div_ceil(step).checked_mul(step) else {
        return Vec::new();
    };
    (0..)
        .map_while(|i: u64| i.checked_mul(step)?.checked_add(start))
        .take_while(|&t| t <= last)
        .collect()
}

/// `10^k` as text runs (base, then a raised exponent); plain `1` and `10` for k = 0, 1.
fn power_label(k: i64, size: f64) -> Vec<Run> {
    match k {
        0 => vec![Run::new("1", size)],
        1 => vec![Run::new("10", size)],
        _ => vec![
            Run::new("10", size),
            Run {
                text: k.to_string(),
                size: size * 0.72,
                rise: size * 0.45,
            },
        ],
    }
}

/// An RGB color.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Color(u8, u8, u8);

impl Color {
    const WHITE: Color = Color(255, 255, 255);
    const TEXT: Color = Color(0x22, 0x22, 0x22);
    const AXIS: Color = Color(0x44, 0x44, 0x44);
    const GRID: Color = Color(0xd4, 0xd4, 0xd4);
    const GRID_MINOR: Color = Color(0xee, 0xee, 0xee);
    const MUTED: Color = Color(0x66, 0x66, 0x66);

    fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// Series colors (the "tab10" palette), cycled.
const PALETTE: [Color; 10] = [
    Color(0x1f, 0x77, 0xb4),
    Color(0xff, 0x7f, 0x0e),
    Color(0x2c, 0xa0, 0x2c),
    Color(0xd6, 0x27, 0x28),
    Color(0x94, 0x67, 0xbd),
    Color(0x8c, 0x56, 0x4b),
    Color(0xe3, 0x77, 0xc2),
    Color(0x7f, 0x7f, 0x7f),
    Color(0xbc, 0xbd, 0x22),
    Color(0x17, 0xbe, 0xcf),
];

/// Marker shapes, cycled (with the colors, 30 series stay distinct).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MarkerKind {
    Circle,
    Square,
    Diamond,
    TriangleUp,
    TriangleDown,
}

const MARKERS: [MarkerKind; 5] = [
    MarkerKind::Circle,
    MarkerKind::Square,
    MarkerKind::Diamond,
    MarkerKind::TriangleUp,
    MarkerKind::TriangleDown,
];

impl MarkerKind {
    /// The corners of the convex polygon of a non-circle marker of radius `r` at `(x, y)`.
    fn polygon(self, x: f64, y: f64, r: f64) -> Vec<(f64, f64)> {
        match self {
            MarkerKind::Circle => Vec::new(),
            MarkerKind::Square => {
                let h = r * 0.85;
                vec![
                    (x - h, y - h),
                    (x + h, y - h),
                    (x + h, y + h),
                    (x - h, y + h),
                ]
            }
            MarkerKind::Diamond => {
                let h = r * 1.2;
                vec![(x, y - h), (x + h, y), (x, y + h), (x - h, y)]
            }
            MarkerKind::TriangleUp => {
                let h = r * 1.25;
                vec![
                    (x, y - h),
                    (x + h * 0.95, y + h * 0.6),
                    (x - h * 0.95, y + h * 0.6),
                ]
            }
            MarkerKind::TriangleDown => {
                let h = r * 1.25;
                vec![
                    (x - h * 0.95, y - h * 0.6),
                    (x + h * 0.95, y - h * 0.6),
                    (x, y + h),
                ]
            }
        }
    }
}

/// A piece of text at one size, raised by `rise` pixels (for exponents).
#[derive(Clone, Debug, PartialEq)]
struct Run {
    text: String,
    size: f64,
    rise: f64,
}

impl Run {
    fn new(text: &str, size: f64) -> Run {
        Run {
            text: text.to_string(),
            size,
            rise: 0.0,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Anchor {
    Start,
    Middle,
    End,
}

/// Text whose baseline starts, centers or ends at `(x, y)`; `vertical` turns it a quarter
/// counter-clockwise about that point (for the y-axis label).
#[derive(Clone, Debug, PartialEq)]
struct Text {
    x: f64,
    y: f64,
    runs: Vec<Run>,
    anchor: Anchor,
    vertical: bool,
    color: Color,
}

/// One drawing primitive, in pixels (y down).
#[derive(Clone, Debug, PartialEq)]
enum Shape {
    Rect {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        fill: Option<Color>,
        stroke: Option<Color>,
    },
    Line {
        from: (f64, f64),
        to: (f64, f64),
        color: Color,
        width: f64,
    },
    Polyline {
        points: Vec<(f64, f64)>,
        color: Color,
        width: f64,
    },
    Marker {
        at: (f64, f64),
        kind: MarkerKind,
        radius: f64,
        color: Color,
    },
    Text(Text),
}

/// A laid-out drawing: the same for SVG and PNG.
struct Scene {
    width: u32,
    height: u32,
    title: String,
    shapes: Vec<Shape>,
}

/// The embedded font, for text widths (layout) and glyphs (PNG).
struct Font {
    face: ab_glyph::FontRef<'static>,
}

impl Font {
    fn embedded() -> Result<Font, Failure> {
        let face = ab_glyph::FontRef::try_from_slice(notosans::REGULAR_TTF)
            .map_err(|e| input!("the embedded font cannot be read: {e}"))?;
        Ok(Font { face })
    }

    /// The `ab_glyph` scale whose em is `size` pixels (CSS `font-size`).
    fn scale(&self, size: f64) -> ab_glyph::PxScale {
        use ab_glyph::Font as _;
        let em = self.face.units_per_em().unwrap_or(1000.0);
        ab_glyph::PxScale::from((size as f32) * self.face.height_unscaled() / em)
    }

    /// Glyphs of a run starting at `x` on `baseline`, and the caret after it.
    fn layout(&self, run: &Run, x: f64, baseline: f64) -> (Vec<ab_glyph::Glyph>, f64) {
        use ab_glyph::{Font as _, ScaleFont as _};
        let scale = self.scale(run.size);
        let scaled = self.face.as_scaled(scale);
        let mut caret = x as f32;
        let mut prev = None;
        let mut glyphs = Vec::new();
        for c in run.text.chars() {
            let id = scaled.glyph_id(c);
            if let Some(p) = prev {
                caret += scaled.kern(p, id);
            }
            glyphs.push(id.with_scale_and_position(
                scale,
                ab_glyph::point(caret, (baseline - run.rise) as f32),
            ));
            caret += scaled.h_advance(id);
            prev = Some(id);
        }
        (glyphs, f64::from(caret))
    }

    fn width(&self, runs: &[Run]) -> f64 {
        runs.iter().fold(0.0, |x, run| self.layout(run, x, 0.0).1)
    }
}

/// What to draw: the title and the series.
struct Chart {
    title: String,
    subtitle: String,
    first_level: u64,
    last_level: u64,
    series: Vec<Series>,
    /// Columns without a positive count in range (not drawable on a log scale).
    hidden: Vec<String>,
}

impl Chart {
    fn layout(&self, font: &Font) -> Scene {
        let (w, h) = (f64::from(WIDTH), f64::from(HEIGHT));
        let mut shapes = vec![Shape::Rect {
            x: 0.0,
            y: 0.0,
            w,
            h,
            fill: Some(Color::WHITE),
            stroke: None,
        }];
        let text = |x: f64, y: f64, runs: Vec<Run>, anchor: Anchor, color: Color| {
            Shape::Text(Text {
                x,
                y,
                runs,
                anchor,
                vertical: false,
                color,
            })
        };

        // Legend on the right, outside the plot area, so it never hides a line.
        // A line hidden under an earlier identical one says so in its label.
        let labels: Vec<Vec<Run>> = self
            .series
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let mut label = legend_label(&s.name);
                if let Some(same) = self.series[..i].iter().find(|e| e.points == s.points) {
                    label.push_str(&format!(" = {}", same.name));
                }
                vec![Run::new(&label, 14.0)]
            })
            .collect();
        let notes: Vec<Vec<Run>> = self
            .hidden
            .iter()
            .map(|name| vec![Run::new(&format!("{name}: no positive count"), 13.0)])
            .collect();
        let label_w = labels
            .iter()
            .map(|l| font.width(l))
            .chain(notes.iter().map(|l| font.width(l) - 36.0))
            .fold(0.0, f64::max);
        // Room for the label in a wider fallback font of an SVG viewer, too.
        let legend_w = (label_w * 1.08 + 62.0).max(110.0);
        let (left, top) = (92.0, 78.0);
        let right = w - legend_w - 36.0;
        let bottom = h - 66.0;

        // Title and subtitle.
        let mut title = self.title.clone();
        while font.width(&[Run::new(&title, 20.0)]) > w - 40.0 && title.chars().count() > 4 {
            let keep = title.chars().count() - 4;
            title = title.chars().take(keep).collect::<String>() + "...";
        }
        shapes.push(text(
            w / 2.0,
            34.0,
            vec![Run::new(&title, 20.0)],
            Anchor::Middle,
            Color::TEXT,
        ));
        shapes.push(text(
            w / 2.0,
            56.0,
            vec![Run::new(&self.subtitle, 13.0)],
            Anchor::Middle,
            Color::MUTED,
        ));

        // Axes: the data range, with a little room so end markers are not cut.
        let (min, max) = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
                (a.min(y), b.max(y))
            });
        let ticks = LogTicks::covering(min, max);
        let pad = 12.0;
        let (x0, x1) = if self.last_level > self.first_level {
            (self.first_level as f64, self.last_level as f64)
        } else {
            (self.first_level as f64 - 1.0, self.first_level as f64 + 1.0)
        };
        let px = |level: f64| left + pad + (level - x0) / (x1 - x0) * (right - left - 2.0 * pad);
        let py = |log: f64| {
            bottom
                - pad
                - (log - ticks.lo as f64) / (ticks.hi - ticks.lo) as f64
                    * (bottom - top - 2.0 * pad)
        };

        for m in ticks.minors() {
            let y = py(m);
            shapes.push(Shape::Line {
                from: (left, y),
                to: (right, y),
                color: Color::GRID_MINOR,
                width: 1.0,
            });
        }
        for (m, label) in ticks.minor_labels() {
            shapes.push(text(
                left - 9.0,
                py(m) + 5.0,
                vec![Run::new(&label, 12.0)],
                Anchor::End,
                Color::MUTED,
            ));
        }
        for k in ticks.majors() {
            let y = py(k as f64);
            shapes.push(Shape::Line {
                from: (left, y),
                to: (right, y),
                color: Color::GRID,
                width: 1.0,
            });
            shapes.push(Shape::Line {
                from: (left - 5.0, y),
                to: (left, y),
                color: Color::AXIS,
                width: 1.0,
            });
            shapes.push(text(
                left - 9.0,
                y + 5.0,
                power_label(k, 14.0),
                Anchor::End,
                Color::TEXT,
            ));
        }
        for t in level_ticks(self.first_level, self.last_level) {
            let x = px(t as f64);
            shapes.push(Shape::Line {
                from: (x, top),
                to: (x, bottom),
                color: Color::GRID_MINOR,
                width: 1.0,
            });
            shapes.push(Shape::Line {
                from: (x, bottom),
                to: (x, bottom + 5.0),
                color: Color::AXIS,
                width: 1.0,
            });
            shapes.push(text(
                x,
                bottom + 21.0,
                vec![Run::new(&t.to_string(), 14.0)],
                Anchor::Middle,
                Color::TEXT,
            ));
        }
        shapes.push(Shape::Rect {
            x: left,
            y: top,
            w: right - left,
            h: bottom - top,
            fill: None,
            stroke: Some(Color::AXIS),
        });
        shapes.push(text(
            (left + right) / 2.0,
            h - 16.0,
            vec![Run::new("level", 15.0)],
            Anchor::Middle,
            Color::TEXT,
        ));
        shapes.push(Shape::Text(Text {
            x: 24.0,
            y: (top + bottom) / 2.0,
            runs: vec![Run::new("count (log scale)", 15.0)],
            anchor: Anchor::Middle,
            vertical: true,
            color: Color::TEXT,
        }));

        // The series, then the legend.
        let style = |i: usize| (PALETTE[i % PALETTE.len()], MARKERS[i % MARKERS.len()]);
        for (i, s) in self.series.iter().enumerate() {
            let (color, kind) = style(i);
            // One line per run of consecutive levels: a level without a positive count (zero
            // or negative, off a log scale) leaves a gap rather than a misleading segment.
            for run in s.points.chunk_by(|a, b| b.0 == a.0 + 1) {
                if run.len() > 1 {
                    shapes.push(Shape::Polyline {
                        points: run.iter().map(|&(l, y)| (px(l as f64), py(y))).collect(),
                        color,
                        width: 2.0,
                    });
                }
            }
            let points: Vec<(f64, f64)> = s
                .points
                .iter()
                .map(|&(l, y)| (px(l as f64), py(y)))
                .collect();
            // Markers only while they stay apart.
            if self.last_level - self.first_level <= 40 {
                for at in points {
                    shapes.push(Shape::Marker {
                        at,
                        kind,
                        radius: 4.0,
                        color,
                    });
                }
            }
        }
        let lx = right + 18.0;
        let row = 24.0;
        shapes.push(Shape::Rect {
            x: lx,
            y: top,
            w: legend_w,
            h: row * (self.series.len() + notes.len()) as f64 + 14.0,
            fill: Some(Color::WHITE),
            stroke: Some(Color::GRID),
        });
        for (i, label) in labels.into_iter().enumerate() {
            let (color, kind) = style(i);
            let y = top + 19.0 + row * i as f64;
            shapes.push(Shape::Line {
                from: (lx + 10.0, y),
                to: (lx + 38.0, y),
                color,
                width: 2.0,
            });
            shapes.push(Shape::Marker {
                at: (lx + 24.0, y),
                kind,
                radius: 4.0,
                color,
            });
            shapes.push(text(lx + 46.0, y + 5.0, label, Anchor::Start, Color::TEXT));
        }
        for (i, note) in notes.into_iter().enumerate() {
            let y = top + 19.0 + row * (self.series.len() + i) as f64;
            shapes.push(text(lx + 10.0, y + 5.0, note, Anchor::Start, Color::MUTED));
        }
        Scene {
            width: WIDTH,
            height: HEIGHT,
            title: self.title.clone(),
            shapes,
        }
    }
}

/// Escapes text for XML content and attribute values.
fn xml_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // Control characters are not allowed in XML 1.0.
            c if (c as u32) < 0x20 && c != '\t' && c != '\n' && c != '\r' => out.push('?'),
            c => out.push(c),
        }
    }
    out
}

/// A coordinate with at most two decimals.
fn num(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

impl Scene {
    fn to_svg(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"'Noto Sans', 'DejaVu Sans', Arial, sans-serif\">",
            w = self.width,
            h = self.height
        );
        let _ = writeln!(s, "<title>{}</title>", xml_escape(&self.title));
        for shape in &self.shapes {
            match shape {
                Shape::Rect {
                    x,
                    y,
                    w,
                    h,
                    fill,
                    stroke,
                } => {
                    let _ = writeln!(
                        s,
                        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" stroke=\"{}\"/>",
                        num(*x),
                        num(*y),
                        num(*w),
                        num(*h),
                        fill.map_or_else(|| "none".to_string(), Color::hex),
                        stroke.map_or_else(|| "none".to_string(), Color::hex),
                    );
                }
                Shape::Line {
                    from,
                    to,
                    color,
                    width,
                } => {
                    let _ = writeln!(
                        s,
                        "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"{}\"/>",
                        num(from.0),
                        num(from.1),
                        num(to.0),
                        num(to.1),
                        color.hex(),
                        num(*width)
                    );
                }
                Shape::Polyline {
                    points,
                    color,
                    width,
                } => {
                    let pts: Vec<String> = points
                        .iter()
                        .map(|p| format!("{},{}", num(p.0), num(p.1)))
                        .collect();
                    let _ = writeln!(
                        s,
                        "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>",
                        pts.join(" "),
                        color.hex(),
                        num(*width)
                    );
                }
                Shape::Marker {
                    at,
                    kind,
                    radius,
                    color,
                } => {
                    if *kind == MarkerKind::Circle {
                        let _ = writeln!(
                            s,
                            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\" stroke=\"#ffffff\" stroke-width=\"1\"/>",
                            num(at.0),
                            num(at.1),
                            num(*radius),
                            color.hex()
                        );
                    } else {
                        let pts: Vec<String> = kind
                            .polygon(at.0, at.1, *radius)
                            .iter()
                            .map(|p| format!("{},{}", num(p.0), num(p.1)))
                            .collect();
                        let _ = writeln!(
                            s,
                            "<polygon points=\"{}\" fill=\"{}\" stroke=\"#ffffff\" stroke-width=\"1\"/>",
                            pts.join(" "),
                            color.hex()
                        );
                    }
                }
                Shape::Text(t) => {
                    let anchor = match t.anchor {
                        Anchor::Start => "start",
                        Anchor::Middle => "middle",
                        Anchor::End => "end",
                    };
                    let transform = if t.vertical {
                        format!(" transform=\"rotate(-90 {} {})\"", num(t.x), num(t.y))
                    } else {
                        String::new()
                    };
                    let first = t.runs.first().map_or(14.0, |r| r.size);
                    let _ = write!(
                        s,
                        "<text x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{}\" text-anchor=\"{anchor}\"{transform}>",
                        num(t.x),
                        num(t.y),
                        num(first),
                        t.color.hex()
                    );
                    let mut rise = 0.0;
                    for (i, run) in t.runs.iter().enumerate() {
                        if i == 0 && run.rise == 0.0 {
                            s.push_str(&xml_escape(&run.text));
                            continue;
                        }
                        let _ = write!(
                            s,
                            "<tspan dy=\"{}\" font-size=\"{}\">{}</tspan>",
                            num(rise - run.rise),
                            num(run.size),
                            xml_escape(&run.text)
                        );
                        rise = run.rise;
                    }
                    s.push_str("</text>\n");
                }
            }
        }
        s.push_str("</svg>\n");
        s
    }
}

/// The PNG rasterizer: anti-aliased coverage from distances for lines and markers, glyph
/// coverage from `ab_glyph` for text, blended over a white RGB canvas.
mod raster {
    use super::{Anchor, Color, Font, MarkerKind, Scene, Shape, Text};
    use crate::failure::{input, Failure};

    struct Canvas {
        width: usize,
        height: usize,
        rgb: Vec<[f32; 3]>,
        /// Per-pixel coverage of the shape being drawn (so overlapping segments of one line do
        /// not darken their joints), with the bounding box of what it touched.
        cover: Vec<f32>,
        touched: Option<(usize, usize, usize, usize)>,
    }

    impl Canvas {
        fn new(width: usize, height: usize) -> Canvas {
            Canvas {
                width,
                height,
                rgb: vec![[1.0; 3]; width * height],
                cover: vec![0.0; width * height],
                touched: None,
            }
        }

        /// Raises the coverage of pixel (x, y) to `c`.
        fn cover(&mut self, x: i64, y: i64, c: f32) {
            if c <= 0.0 || x < 0 || y < 0 || x as usize >= self.width || y as usize >= self.height {
                return;
            }
            let (x, y) = (x as usize, y as usize);
            let i = y * self.width + x;
            self.cover[i] = self.cover[i].max(c.min(1.0));
            self.touched = Some(match self.touched {
                None => (x, y, x, y),
                Some((a, b, c, d)) => (a.min(x), b.min(y), c.max(x), d.max(y)),
            });
        }

        /// Blends the accumulated coverage in `color` and clears it.
        fn flush(&mut self, color: Color) {
            let Some((x0, y0, x1, y1)) = self.touched.take() else {
                return;
            };
            let c = [
                f32::from(color.0) / 255.0,
                f32::from(color.1) / 255.0,
                f32::from(color.2) / 255.0,
            ];
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let i = y * self.width + x;
                    let a = self.cover[i];
                    if a > 0.0 {
                        for (dst, src) in self.rgb[i].iter_mut().zip(c) {
                            *dst += (src - *dst) * a;
                        }
                        self.cover[i] = 0.0;
                    }
                }
            }
        }

        /// Pixels whose centers may lie within `r` of the box (x0, y0)-(x1, y1).
        fn pixels_near(
            &self,
            (x0, y0): (f64, f64),
            (x1, y1): (f64, f64),
            r: f64,
        ) -> impl Iterator<Item = (i64, i64)> {
            let lo_x = ((x0.min(x1) - r - 1.0).floor() as i64).max(0);
            let hi_x = ((x0.max(x1) + r + 1.0).ceil() as i64).min(self.width as i64 - 1);
            let lo_y = ((y0.min(y1) - r - 1.0).floor() as i64).max(0);
            let hi_y = ((y0.max(y1) + r + 1.0).ceil() as i64).min(self.height as i64 - 1);
            (lo_y..=hi_y).flat_map(move |y| (lo_x..=hi_x).map(move |x| (x, y)))
        }

        fn segment(&mut self, a: (f64, f64), b: (f64, f64), width: f64) {
            let half = width / 2.0;
            let pixels: Vec<(i64, i64)> = self.pixels_near(a, b, half).collect();
            for (x, y) in pixels {
                let d = distance_to_segment((x as f64 + 0.5, y as f64 + 0.5), a, b);
                self.cover(x, y, (half + 0.5 - d).clamp(0.0, 1.0) as f32);
            }
        }

        fn rect_fill(&mut self, x: f64, y: f64, w: f64, h: f64) {
            let pixels: Vec<(i64, i64)> = self.pixels_near((x, y), (x + w, y + h), 0.0).collect();
            for (px, py) in pixels {
                let ox = (x + w).min(px as f64 + 1.0) - x.max(px as f64);
                let oy = (y + h).min(py as f64 + 1.0) - y.max(py as f64);
                self.cover(px, py, (ox.max(0.0) * oy.max(0.0)) as f32);
            }
        }

        /// A filled circle or convex polygon, through a signed distance.
        fn marker(&mut self, at: (f64, f64), kind: MarkerKind, r: f64) {
            let poly = kind.polygon(at.0, at.1, r);
            let reach = r * 1.3;
            let pixels: Vec<(i64, i64)> = self.pixels_near(at, at, reach).collect();
            for (x, y) in pixels {
                let p = (x as f64 + 0.5, y as f64 + 0.5);
                let sd = if poly.is_empty() {
                    ((p.0 - at.0).powi(2) + (p.1 - at.1).powi(2)).sqrt() - r
                } else {
                    convex_signed_distance(p, &poly)
                };
                self.cover(x, y, (0.5 - sd).clamp(0.0, 1.0) as f32);
            }
        }

        fn text(&mut self, t: &Text, font: &Font) {
            use ab_glyph::Font as _;
            let width = font.width(&t.runs);
            let start = match t.anchor {
                Anchor::Start => 0.0,
                Anchor::Middle => -width / 2.0,
                Anchor::End => -width,
            };
            let mut caret = start;
            for run in &t.runs {
                let (glyphs, next) = font.layout(run, caret, 0.0);
                caret = next;
                for g in glyphs {
                    let Some(outlined) = font.face.outline_glyph(g) else {
                        continue;
                    };
                    let b = outlined.px_bounds();
                    let mut pixels = Vec::new();
                    outlined.draw(|gx, gy, c| {
                        pixels.push((
                            f64::from(b.min.x) + f64::from(gx),
                            f64::from(b.min.y) + f64::from(gy),
                            c,
                        ));
                    });
                    for (dx, dy, c) in pixels {
                        // (dx, dy) is the pixel's top-left corner relative to the anchor.
                        let (x, y) = if t.vertical {
                            // A quarter turn counter-clockwise: (dx, dy) -> (dy, -dx).
                            (t.x + dy, t.y - dx - 1.0)
                        } else {
                            (t.x + dx, t.y + dy)
                        };
                        self.cover(x.round() as i64, y.round() as i64, c);
                    }
                }
            }
        }

        fn to_rgb8(&self) -> Vec<u8> {
            self.rgb
                .iter()
                .flat_map(|p| p.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8))
                .collect()
        }
    }

    fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (cx, cy) = (a.0 + t * dx, a.1 + t * dy);
        ((p.0 - cx).powi(2) + (p.1 - cy).powi(2)).sqrt()
    }

    /// max over edges of the distance to the edge's line, positive outside (any winding).
    fn convex_signed_distance(p: (f64, f64), poly: &[(f64, f64)]) -> f64 {
        let n = poly.len();
        let area2: f64 = (0..n)
            .map(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                a.0 * b.1 - b.0 * a.1
            })
            .sum();
        let orientation = if area2 >= 0.0 { 1.0 } else { -1.0 };
        (0..n)
            .map(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                let (ex, ey) = (b.0 - a.0, b.1 - a.1);
                let len = (ex * ex + ey * ey).sqrt().max(1e-12);
                // Inside lies on the side where the cross product has the area's sign.
                let cross = ex * (p.1 - a.1) - ey * (p.0 - a.0);
                -orientation * cross / len
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    pub(super) fn render(scene: &Scene, font: &Font) -> Vec<u8> {
        let mut canvas = Canvas::new(scene.width as usize, scene.height as usize);
        for shape in &scene.shapes {
            match shape {
                Shape::Rect {
                    x,
                    y,
                    w,
                    h,
                    fill,
                    stroke,
                } => {
                    if let Some(color) = fill {
                        canvas.rect_fill(*x, *y, *w, *h);
                        canvas.flush(*color);
                    }
                    if let Some(color) = stroke {
                        // A 1-pixel outline centered on the edges, like SVG's stroke.
                        canvas.rect_fill(x - 0.5, y - 0.5, w + 1.0, 1.0);
                        canvas.rect_fill(x - 0.5, y + h - 0.5, w + 1.0, 1.0);
                        canvas.rect_fill(x - 0.5, y - 0.5, 1.0, h + 1.0);
                        canvas.rect_fill(x + w - 0.5, y - 0.5, 1.0, h + 1.0);
                        canvas.flush(*color);
                    }
                }
                Shape::Line {
                    from,
                    to,
                    color,
                    width,
                } => {
                    if from.0 == to.0 || from.1 == to.1 {
                        // Axis-aligned: exact pixel coverage keeps grid lines crisp.
                        let (x0, x1) = (from.0.min(to.0), from.0.max(to.0));
                        let (y0, y1) = (from.1.min(to.1), from.1.max(to.1));
                        if from.1 == to.1 {
                            canvas.rect_fill(x0, y0 - width / 2.0, x1 - x0, *width);
                        } else {
                            canvas.rect_fill(x0 - width / 2.0, y0, *width, y1 - y0);
                        }
                    } else {
                        canvas.segment(*from, *to, *width);
                    }
                    canvas.flush(*color);
                }
                Shape::Polyline {
                    points,
                    color,
                    width,
                } => {
                    for pair in points.windows(2) {
                        canvas.segment(pair[0], pair[1], *width);
                    }
                    canvas.flush(*color);
                }
                Shape::Marker {
                    at,
                    kind,
                    radius,
                    color,
                } => {
                    canvas.marker(*at, *kind, radius + 1.0);
                    canvas.flush(Color::WHITE);
                    canvas.marker(*at, *kind, *radius);
                    canvas.flush(*color);
                }
                Shape::Text(t) => {
                    canvas.text(t, font);
                    canvas.flush(t.color);
                }
            }
        }
        canvas.to_rgb8()
    }

    /// The scene as PNG bytes.
    pub(super) fn to_png(scene: &Scene, font: &Font) -> Result<Vec<u8>, Failure> {
        let pixels = render(scene, font);
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, scene.width, scene.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        let mut writer = encoder
            .write_header()
            .map_err(|e| input!("cannot encode the PNG: {e}"))?;
        writer
            .write_image_data(&pixels)
            .map_err(|e| input!("cannot encode the PNG: {e}"))?;
        writer
            .finish()
            .map_err(|e| input!("cannot encode the PNG: {e}"))?;
        Ok(bytes)
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        #[test]
        fn signed_distance_of_a_square() {
            let sq = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)];
            assert!((convex_signed_distance((1.0, 1.0), &sq) + 1.0).abs() < 1e-12);
            assert!((convex_signed_distance((3.0, 1.0), &sq) - 1.0).abs() < 1e-12);
            let reversed: Vec<_> = sq.iter().rev().copied().collect();
            assert!((convex_signed_distance((3.0, 1.0), &reversed) - 1.0).abs() < 1e-12);
            assert!((distance_to_segment((1.0, 1.0), (0.0, 0.0), (2.0, 0.0)) - 1.0).abs() < 1e-12);
            assert!((distance_to_segment((3.0, 0.0), (0.0, 0.0), (2.0, 0.0)) - 1.0).abs() < 1e-12);
        }
    }
}

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so the
/// target is either the complete image or untouched.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map_or_else(|| "plot".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut file = std::fs::File::create(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        input!("cannot write {}: {e}", path.display())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::Pow;

    #[test]
    fn log10_of_small_and_huge_counts() {
        assert_eq!(log10_count(&BigInt::from(1)), Some(0.0));
        assert_eq!(log10_count(&BigInt::from(0)), None);
        assert_eq!(log10_count(&BigInt::from(-5)), None);
        let l = log10_count(&BigInt::from(1000)).unwrap();
        assert!((l - 3.0).abs() < 1e-12, "{l}");
        let l = log10_count(&BigInt::from(u64::MAX)).unwrap();
        assert!((l - 19.265_919_722_494_8).abs() < 1e-9, "{l}");
        // 10^5000 and 2^100000: far beyond f64, exact to the plot's resolution.
        let l = log10_count(&BigInt::from(10).pow(5000u32)).unwrap();
        assert!((l - 5000.0).abs() < 1e-9, "{l}");
        let l = log10_count(&(BigInt::from(10).pow(5000u32) * 3)).unwrap();
        assert!((l - 5000.0 - 3f64.log10()).abs() < 1e-9, "{l}");
        let l = log10_count(&BigInt::from(2).pow(100_000u32)).unwrap();
        assert!(
            (l - 100_000.0 * std::f64::consts::LOG10_2).abs() < 1e-6,
            "{l}"
        );
        // Digit count agrees: floor(log10 n) + 1.
        let n: BigInt = BigInt::from(20) * BigInt::from(4).pow(1000u32);
        let digits = n.to_string().len() as f64;
        assert_eq!(log10_count(&n).unwrap().floor() + 1.0, digits);
    }

    #[test]
    fn log_ticks_pick_decades_then_wider_steps() {
        let t = LogTicks::covering(1.08, 6.3);
        assert_eq!(
            t,
            LogTicks {
                lo: 1,
                hi: 7,
                step: 1
            }
        );
        assert_eq!(t.majors().collect::<Vec<_>>(), [1, 2, 3, 4, 5, 6, 7]);
        assert_eq!(t.minors().len(), 0, "more than 4 decades: no minor ticks");
        let t = LogTicks::covering(1.08, 4.2);
        assert_eq!(t.minors().len(), 4 * 8);
        assert_eq!(t.minor_labels(), []);
        let labels = LogTicks::covering(0.5, 1.9).minor_labels();
        let text: Vec<&str> = labels.iter().map(|l| l.1.as_str()).collect();
        assert_eq!(text, ["2", "5", "20", "50"]);
        assert!((labels[3].0 - 50f64.log10()).abs() < 1e-12);
        // One value: one decade around it.
        assert_eq!(
            LogTicks::covering(2.0, 2.0),
            LogTicks {
                lo: 2,
                hi: 3,
                step: 1
            }
        );
        // Loop from the icosahedron to level 100: 1.08 .. 61.5 decades, in steps of 10.
        let t = LogTicks::covering(1.08, 61.5);
        assert_eq!(
            t,
            LogTicks {
                lo: 0,
                hi: 70,
                step: 10
            }
        );
        let t = LogTicks::covering(0.0, 602.0);
        assert_eq!(
            t,
            LogTicks {
                lo: 0,
                hi: 700,
                step: 100
            }
        );
        let t = LogTicks::covering(3.0, 17.5);
        assert_eq!(
            t,
            LogTicks {
                lo: 2,
                hi: 18,
                step: 2
            }
        );
        assert_eq!(nice_step(1, 8), 1);
        assert_eq!(nice_step(9, 8), 2);
        assert_eq!(nice_step(41, 8), 10);
        assert_eq!(nice_step(i64::MAX, 8), 2_000_000_000_000_000_000);
    }

    #[test]
    fn level_ticks_are_round() {
        assert_eq!(level_ticks(0, 12), (0..=12).collect::<Vec<_>>());
        assert_eq!(level_ticks(0, 20), [0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20]);
        assert_eq!(level_ticks(3, 3), [3]);
        assert_eq!(
            level_ticks(7, 100),
            [10, 20, 30, 40, 50, 60, 70, 80, 90, 100]
        );
        assert_eq!(
            level_ticks(u64::MAX - 2, u64::MAX),
            [u64::MAX - 2, u64::MAX - 1, u64::MAX]
        );
    }

    #[test]
    fn text_escapes_and_formats() {
        assert_eq!(xml_escape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&apos;");
        assert_eq!(num(1.0), "1");
        assert_eq!(num(2.345), "2.35");
        assert_eq!(num(-0.001), "0");
        let label = power_label(12, 14.0);
        assert_eq!(label[0].text, "10");
        assert_eq!(label[1].text, "12");
        assert!(label[1].rise > 0.0);
        assert_eq!(legend_label("IE"), "IE (interior edges)");
        assert_eq!(legend_label("x0"), "x0");
    }

    #[test]
    fn formats_by_extension() {
        assert_eq!(
            ImageFormat::from_path(Path::new("a/counts.SVG")).unwrap(),
            ImageFormat::Svg
        );
        assert_eq!(
            ImageFormat::from_path(Path::new("counts.png")).unwrap(),
            ImageFormat::Png
        );
        let e = ImageFormat::from_path(Path::new("counts.jpg")).unwrap_err();
        assert_eq!(e.kind, crate::failure::Kind::Usage);
        assert!(format!("{:#}", e.error).contains("`.jpg`"));
        assert!(ImageFormat::from_path(Path::new("counts")).is_err());
    }

    fn chart(series: Vec<Series>) -> Chart {
        Chart {
            title: "t".into(),
            subtitle: "s".into(),
            first_level: 0,
            last_level: 5,
            series,
            hidden: vec!["BE".into()],
        }
    }

    #[test]
    fn layout_breaks_lines_at_gaps_and_notes_hidden_columns() {
        let font = Font::embedded().unwrap();
        let gap = Series {
            name: "x0".into(),
            points: vec![(0, 0.0), (1, 1.0), (3, 3.0), (4, 4.0), (5, 5.0)],
        };
        let scene = chart(vec![gap]).layout(&font);
        let lines: Vec<usize> = scene
            .shapes
            .iter()
            .filter_map(|s| match s {
                Shape::Polyline { points, .. } => Some(points.len()),
                _ => None,
            })
            .collect();
        assert_eq!(lines, [2, 3]);
        let markers = scene
            .shapes
            .iter()
            .filter(|s| matches!(s, Shape::Marker { .. }))
            .count();
        assert_eq!(markers, 5 + 1, "one per point, and the legend's");
        let svg = scene.to_svg();
        assert!(svg.contains(">BE: no positive count</text>"), "{svg}");
        assert!(svg.contains("<title>t</title>"));
        // Higher counts are drawn higher (smaller y).
        let Some(Shape::Polyline { points, .. }) = scene
            .shapes
            .iter()
            .find(|s| matches!(s, Shape::Polyline { .. }))
        else {
            unreachable!("a polyline was counted above")
        };
        assert!(points[1].1 < points[0].1);
        let png = raster::to_png(&scene, &font).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    }

    #[test]
    fn series_skip_missing_and_nonpositive_values() {
        let rows = vec![
            Row {
                level: 0,
                values: vec![Some(BigInt::from(0)), Some(BigInt::from(10)), None],
            },
            Row {
                level: 1,
                values: vec![Some(BigInt::from(100)), Some(BigInt::from(-1)), None],
            },
        ];
        let cols = vec!["A".to_string(), "B".to_string(), "C".to_string()];
        let s = series_of(&cols, &rows);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].name, "A");
        assert_eq!(s[0].points.len(), 1);
        assert_eq!(s[0].points[0].0, 1);
        assert!((s[0].points[0].1 - 2.0).abs() < 1e-12);
        assert_eq!(s[1].points.len(), 1);
        assert_eq!(s[1].points[0].0, 0);
    }
}
