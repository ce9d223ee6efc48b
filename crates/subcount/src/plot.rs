//! `plot`: V, E, F and the state components versus level on a log10 scale, as SVG or PNG.
//!
//! The counts come from [`Dynamics`] exactly as `table` computes them; only the drawing is
//! approximate. Each count is turned into log10 from its bit length and its leading 64 bits, so
//! counts of any size (thousands of digits) map to finite plot positions without overflow.
//!
//! The picture is drawn with `plotters`, once for either back end: its SVG back end, or its
//! bitmap back end at [`SUPERSAMPLE`] times the size, averaged down to the image size (plotters
//! fills wide lines and polygons without anti-aliasing) and encoded with `png`. Text is drawn
//! with an embedded Noto Sans (the `notosans` crate) registered with plotters' `ab_glyph` font
//! table, so the image does not depend on the fonts of the machine. The file is written
//! atomically by `halfedge`'s writer.

use std::io::Write;
use std::path::Path;

use num_bigint::{BigInt, Sign};
use num_traits::ToPrimitive;
use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

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
    let bytes = match format {
        ImageFormat::Svg => chart.to_svg()?.into_bytes(),
        ImageFormat::Png => chart.to_png()?,
    };
    halfedge::io::write_atomically(&args.output, |file| file.write_all(&bytes)).map_err(
        |e| match e {
            halfedge::Error::Io { path, source } => {
                input!("cannot write {}: {source}", path.display())
            }
            other => input!("cannot write {}: {other}", args.output.display()),
        },
    )?;
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

/// `10^k` as the base and the exponent to raise; plain `1` and `10` for k = 0, 1.
fn power_label(k: i64) -> (&'static str, Option<String>) {
    match k {
        0 => ("1", None),
        1 => ("10", None),
        _ => ("10", Some(k.to_string())),
    }
}

const TEXT: RGBColor = RGBColor(0x22, 0x22, 0x22);
const AXIS: RGBColor = RGBColor(0x44, 0x44, 0x44);
const GRID: RGBColor = RGBColor(0xd4, 0xd4, 0xd4);
const GRID_MINOR: RGBColor = RGBColor(0xee, 0xee, 0xee);
const MUTED: RGBColor = RGBColor(0x66, 0x66, 0x66);

/// Series colors (the "tab10" palette), cycled.
const PALETTE: [RGBColor; 10] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0xbc, 0xbd, 0x22),
    RGBColor(0x17, 0xbe, 0xcf),
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
    /// The corners of a non-circle marker of radius `r` about its center (y down).
    fn corners(self, r: f64) -> Vec<(f64, f64)> {
        let (s, d, t) = (r * 0.85, r * 1.2, r * 1.25);
        match self {
            MarkerKind::Circle => Vec::new(),
            MarkerKind::Square => vec![(-s, -s), (s, -s), (s, s), (-s, s)],
            MarkerKind::Diamond => vec![(0.0, -d), (d, 0.0), (0.0, d), (-d, 0.0)],
            MarkerKind::TriangleUp => vec![(0.0, -t), (t * 0.95, t * 0.6), (-t * 0.95, t * 0.6)],
            MarkerKind::TriangleDown => {
                vec![(-t * 0.95, -t * 0.6), (t * 0.95, -t * 0.6), (0.0, t)]
            }
        }
    }
}

/// How one series is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Look {
    color: RGBColor,
    marker: MarkerKind,
    /// The series runs on an earlier one: its line is dashed (dash and gap in image pixels)
    /// and its markers are larger outlines, so the one underneath shows through.
    dash: Option<(f64, f64)>,
}

impl Look {
    /// Dash patterns of the series that run on earlier ones, cycled: two such series on the
    /// same line still differ.
    const DASHES: [(f64, f64); 3] = [(7.0, 5.0), (3.0, 3.0), (12.0, 4.0)];
}

/// The font family plotters' `ab_glyph` table knows the embedded font by; the SVG back end
/// writes it as the `font-family`, so viewers without Noto Sans fall back to a similar sans.
const FONT_FAMILY: &str = "'Noto Sans', 'DejaVu Sans', Arial, sans-serif";

/// Registers the embedded Noto Sans with plotters' `ab_glyph` font table and returns it.
fn embedded_font() -> Result<ab_glyph::FontRef<'static>, Failure> {
    let cannot = || input!("the embedded font cannot be read");
    plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, notosans::REGULAR_TTF)
        .map_err(|_| cannot())?;
    ab_glyph::FontRef::try_from_slice(notosans::REGULAR_TTF).map_err(|_| cannot())
}

/// Device sizes and text for one back end. The chart is laid out in image pixels (960 x 600)
/// and drawn at `scale` device pixels per image pixel; a font of `em` image pixels is given to
/// plotters as `em * size_per_em` (its back ends scale text differently).
struct Pen {
    scale: f64,
    size_per_em: f64,
    /// The embedded font, which measures text (as plotters' bitmap text does).
    face: ab_glyph::FontRef<'static>,
    /// The font's height (ascent to descent) per em: `ab_glyph` scales to the height.
    height_per_em: f64,
    /// Whether [`Pen::text`] places each glyph itself: plotters' `ab_glyph` text starts every
    /// glyph's bitmap at the pen position, without the glyph's left bearing, which opens a gap
    /// before a `j`. The SVG keeps whole strings for the viewer to lay out.
    per_glyph: bool,
}

impl Pen {
    /// The pen of the SVG back end, which writes `font-size` as the size / 1.24.
    fn svg(face: ab_glyph::FontRef<'static>) -> Pen {
        Pen::new(face, 1.0, Some(1.24))
    }

    /// The pen of the bitmap back end at `scale`, whose `ab_glyph` text scales the font's
    /// height to the size.
    fn bitmap(face: ab_glyph::FontRef<'static>, scale: f64) -> Pen {
        Pen::new(face, scale, None)
    }

    fn new(face: ab_glyph::FontRef<'static>, scale: f64, svg_size_per_em: Option<f64>) -> Pen {
        use ab_glyph::Font as _;
        let height = face.height_unscaled() / face.units_per_em().unwrap_or(1000.0);
        let height_per_em = f64::from(height);
        Pen {
            scale,
            size_per_em: svg_size_per_em.unwrap_or(height_per_em),
            face,
            height_per_em,
            per_glyph: svg_size_per_em.is_none(),
        }
    }

    fn px(&self, v: f64) -> i32 {
        (v * self.scale).round() as i32
    }

    fn at(&self, x: f64, y: f64) -> BackendCoordinate {
        (self.px(x), self.px(y))
    }

    fn stroke(&self, color: RGBColor, width: f64) -> ShapeStyle {
        color.stroke_width(self.px(width).max(1) as u32)
    }

    fn font(&self, em: f64, color: RGBColor, h: HPos, v: VPos) -> TextStyle<'static> {
        (FONT_FAMILY, em * self.size_per_em * self.scale)
            .into_font()
            .color(&color)
            .pos(Pos::new(h, v))
    }

    /// Each character of `text` at `em` device pixels with the left edge of its glyph's bitmap
    /// (from the start of the text), and the advance of the whole text.
    fn glyphs(&self, text: &str, em: f64) -> (Vec<(char, f64)>, f64) {
        use ab_glyph::{Font as _, ScaleFont as _};
        let scale = ab_glyph::PxScale::from((em * self.height_per_em) as f32);
        let scaled = self.face.as_scaled(scale);
        let mut caret = 0f32;
        let mut prev = None;
        let mut glyphs = Vec::new();
        for c in text.chars() {
            let id = scaled.glyph_id(c);
            if let Some(p) = prev {
                caret += scaled.kern(p, id);
            }
            if let Some(outline) = scaled.outline_glyph(id.with_scale(scale)) {
                glyphs.push((c, f64::from(caret + outline.px_bounds().min.x)));
            }
            caret += scaled.h_advance(id);
            prev = Some(id);
        }
        (glyphs, f64::from(caret))
    }

    /// The width of `text` at `em`, in image pixels.
    fn width(&self, text: &str, em: f64) -> f64 {
        self.glyphs(text, em).1
    }

    /// Draws `text` at `em` image pixels, centered vertically on `(x, y)` and aligned by `h`.
    fn text<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        text: &str,
        (x, y): (f64, f64),
        em: f64,
        color: RGBColor,
        h: HPos,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        if !self.per_glyph {
            let style = self.font(em, color, h, VPos::Center);
            return area.draw(&Text::new(text.to_string(), self.at(x, y), style));
        }
        let (glyphs, width) = self.glyphs(text, em * self.scale);
        let start = x * self.scale
            - match h {
                HPos::Left => 0.0,
                HPos::Center => width / 2.0,
                HPos::Right => width,
            };
        let style = self.font(em, color, HPos::Left, VPos::Center);
        for (c, left) in glyphs {
            let at = ((start + left).round() as i32, self.px(y));
            area.draw(&Text::new(c.to_string(), at, style.clone()))?;
        }
        Ok(())
    }

    /// A series marker at `at`: a filled shape on a white halo, or a larger outline when the
    /// series lies on an earlier one.
    fn marker<'a, DB: DrawingBackend + 'a, C: Clone + 'a>(
        &self,
        at: C,
        look: Look,
        radius: f64,
    ) -> DynElement<'a, DB, C> {
        let color = look.color;
        let points = |r: f64| -> Vec<BackendCoordinate> {
            let mut corners: Vec<_> = look
                .marker
                .corners(r)
                .into_iter()
                .map(|(x, y)| self.at(x, y))
                .collect();
            if look.dash.is_some() {
                corners.push(corners[0]);
            }
            corners
        };
        let anchor = EmptyElement::at(at);
        match (look.marker, look.dash.is_some()) {
            (MarkerKind::Circle, false) => (anchor
                + Circle::new((0, 0), self.px(radius + 1.0) as u32, WHITE.filled())
                + Circle::new((0, 0), self.px(radius) as u32, color.filled()))
            .into_dyn(),
            (MarkerKind::Circle, true) => (anchor
                + Circle::new(
                    (0, 0),
                    self.px(radius * 1.7) as u32,
                    self.stroke(color, 1.5),
                ))
            .into_dyn(),
            (_, false) => (anchor
                + Polygon::new(points(radius + 1.0), WHITE.filled())
                + Polygon::new(points(radius), color.filled()))
            .into_dyn(),
            (_, true) => (anchor + PathElement::new(points(radius * 1.7), self.stroke(color, 1.5)))
                .into_dyn(),
        }
    }
}

type BackendCoordinate = (i32, i32);

/// A linear axis with the key points we choose: `bold` ones are labelled and get a grid line,
/// `light` ones a fainter grid line (plotters' own numeric axes pick their own).
#[derive(Clone)]
struct Axis {
    range: Range<f64>,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ranged for Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let t = (value - self.range.start) / (self.range.end - self.range.start);
        limit.0 + (t * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.light.clone()
        } else {
            self.bold.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.range.clone()
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

/// Pixels of free space inside the plot frame around the data, so end markers are not cut.
const PAD: f64 = 12.0;

impl Chart {
    /// The chart as an SVG document.
    fn to_svg(&self) -> Result<String, Failure> {
        let pen = Pen::svg(embedded_font()?);
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (WIDTH, HEIGHT)).into_drawing_area();
            self.draw(&root, &pen)
                .and_then(|()| root.present())
                .map_err(|e| input!("cannot draw the plot: {e}"))?;
        }
        Ok(svg)
    }

    /// The chart as PNG bytes: drawn at `SUPERSAMPLE` times the size, then averaged down.
    fn to_png(&self) -> Result<Vec<u8>, Failure> {
        let pen = Pen::bitmap(embedded_font()?, f64::from(SUPERSAMPLE));
        let (w, h) = (WIDTH * SUPERSAMPLE, HEIGHT * SUPERSAMPLE);
        let mut big = vec![0u8; w as usize * h as usize * 3];
        {
            let root = BitMapBackend::with_buffer(&mut big, (w, h)).into_drawing_area();
            self.draw(&root, &pen)
                .and_then(|()| root.present())
                .map_err(|e| input!("cannot draw the plot: {e}"))?;
        }
        let pixels = downsample(&big, WIDTH as usize, SUPERSAMPLE as usize);
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, WIDTH, HEIGHT);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        let cannot = |e: png::EncodingError| input!("cannot encode the PNG: {e}");
        let mut writer = encoder.write_header().map_err(cannot)?;
        writer.write_image_data(&pixels).map_err(cannot)?;
        writer.finish().map_err(cannot)?;
        Ok(bytes)
    }

    /// How each series is drawn: palette color and marker by position, and a dash for a
    /// series that runs within `tolerance` (log10 units) of an earlier one at two consecutive
    /// levels, so that one segment of its line would hide the other's.
    fn looks(&self, tolerance: f64) -> Vec<Look> {
        let near = |a: &Series, b: &Series, level: u64| {
            // Points are in level order.
            let at = |s: &Series| {
                let i = s.points.binary_search_by_key(&level, |p| p.0).ok()?;
                Some(s.points[i].1)
            };
            matches!((at(a), at(b)), (Some(x), Some(y)) if (x - y).abs() <= tolerance)
        };
        let mut dashed = 0;
        (0..self.series.len())
            .map(|i| {
                let s = &self.series[i];
                let over = self.series[..i].iter().any(|earlier| {
                    s.points.windows(2).any(|w| {
                        w[1].0 == w[0].0 + 1 && near(s, earlier, w[0].0) && near(s, earlier, w[1].0)
                    })
                });
                let dash = over.then(|| {
                    dashed += 1;
                    Look::DASHES[(dashed - 1) % Look::DASHES.len()]
                });
                Look {
                    color: PALETTE[i % PALETTE.len()],
                    marker: MARKERS[i % MARKERS.len()],
                    dash,
                }
            })
            .collect()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        pen: &Pen,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (w, h) = (f64::from(WIDTH), f64::from(HEIGHT));
        root.fill(&WHITE)?;

        // Legend on the right, outside the plot area, so it never hides a line.
        // A line hidden under an earlier identical one says so in its label.
        let labels: Vec<String> = self
            .series
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let mut label = legend_label(&s.name);
                if let Some(same) = self.series[..i].iter().find(|e| e.points == s.points) {
                    label.push_str(&format!(" = {}", same.name));
                }
                label
            })
            .collect();
        let notes: Vec<String> = self
            .hidden
            .iter()
            .map(|name| format!("{name}: no positive count"))
            .collect();
        let label_w = labels
            .iter()
            .map(|l| pen.width(l, 14.0))
            .chain(notes.iter().map(|n| pen.width(n, 13.0) - 36.0))
            .fold(0.0, f64::max);
        // Room for the label in a wider fallback font of an SVG viewer, too.
        let legend_w = (label_w * 1.08 + 62.0).max(110.0);
        let (left, top) = (92.0, 78.0);
        let right = w - legend_w - 36.0;
        let bottom = h - 66.0;

        // Title and subtitle.
        let mut title = self.title.clone();
        while pen.width(&title, 20.0) > w - 40.0 && title.chars().count() > 4 {
            let keep = title.chars().count() - 4;
            title = title.chars().take(keep).collect::<String>() + "...";
        }
        pen.text(root, &title, (w / 2.0, 28.0), 20.0, TEXT, HPos::Center)?;
        pen.text(
            root,
            &self.subtitle,
            (w / 2.0, 51.0),
            13.0,
            MUTED,
            HPos::Center,
        )?;

        // Axes: levels as offsets from the first (exact in f64 for any u64 level), log10
        // counts, each with PAD pixels of room inside the frame.
        let (min, max) = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
                (a.min(y), b.max(y))
            });
        let ticks = LogTicks::covering(min, max);
        let span = (self.last_level - self.first_level) as f64;
        let (x_lo, x_hi) = if span > 0.0 { (0.0, span) } else { (-1.0, 1.0) };
        let (y_lo, y_hi) = (ticks.lo as f64, ticks.hi as f64);
        let x_pad = (x_hi - x_lo) * PAD / (right - left - 2.0 * PAD);
        let y_per_px = (y_hi - y_lo) / (bottom - top - 2.0 * PAD);
        let level_ticks: Vec<f64> = level_ticks(self.first_level, self.last_level)
            .into_iter()
            .map(|t| (t - self.first_level) as f64)
            .collect();
        let x_axis = Axis {
            range: (x_lo - x_pad)..(x_hi + x_pad),
            bold: level_ticks.clone(),
            light: Vec::new(),
        };
        let y_axis = Axis {
            range: (y_lo - PAD * y_per_px)..(y_hi + PAD * y_per_px),
            bold: ticks.majors().map(|k| k as f64).collect(),
            light: ticks.minors(),
        };
        let mut chart = ChartBuilder::on(root)
            .margin_top(pen.px(top))
            .margin_right(pen.px(w - right))
            .x_label_area_size(pen.px(h - bottom))
            .y_label_area_size(pen.px(left))
            .build_cartesian_2d(x_axis, y_axis)?;

        chart.draw_series(level_ticks.iter().map(|&t| {
            PathElement::new(
                vec![(t, y_lo - PAD * y_per_px), (t, y_hi + PAD * y_per_px)],
                pen.stroke(GRID_MINOR, 1.0),
            )
        }))?;
        let first = self.first_level;
        let x_label = |x: &f64| (first + x.round() as u64).to_string();
        chart
            .configure_mesh()
            .disable_x_mesh()
            .bold_line_style(pen.stroke(GRID, 1.0))
            .light_line_style(pen.stroke(GRID_MINOR, 1.0))
            .axis_style(pen.stroke(AXIS, 1.0))
            .set_all_tick_mark_size(pen.px(5.0))
            .x_label_formatter(&x_label)
            .x_label_style(pen.font(14.0, TEXT, HPos::Center, VPos::Top))
            // The y labels are drawn below, with raised exponents (plotters draws nothing for
            // a transparent text).
            .y_label_style(
                pen.font(14.0, TEXT, HPos::Right, VPos::Center)
                    .color(&TRANSPARENT),
            )
            .draw()?;
        let y_at = |log: f64| f64::from(chart.backend_coord(&(0.0, log)).1) / pen.scale;
        for k in ticks.majors() {
            let (base, exponent) = power_label(k);
            let small = 14.0 * 0.72;
            let base_w = pen.width(base, 14.0);
            let exponent_w = exponent.as_ref().map_or(0.0, |e| pen.width(e, small));
            let (x, y) = (left - 9.0 - base_w - exponent_w, y_at(k as f64));
            pen.text(root, base, (x, y), 14.0, TEXT, HPos::Left)?;
            if let Some(e) = exponent {
                pen.text(root, &e, (x + base_w, y - 5.5), small, TEXT, HPos::Left)?;
            }
        }
        for (log, label) in ticks.minor_labels() {
            pen.text(
                root,
                &label,
                (left - 9.0, y_at(log)),
                12.0,
                MUTED,
                HPos::Right,
            )?;
        }
        pen.text(
            root,
            "level",
            ((left + right) / 2.0, h - 20.0),
            15.0,
            TEXT,
            HPos::Center,
        )?;
        // Turned a quarter counter-clockwise about its center.
        root.draw(&Text::new(
            "count (log scale)",
            pen.at(24.0, (top + bottom) / 2.0),
            pen.font(15.0, TEXT, HPos::Center, VPos::Center)
                .transform(FontTransform::Rotate270),
        ))?;
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        root.draw(&Rectangle::new(
            [(xs.start, ys.start), (xs.end, ys.end)],
            pen.stroke(AXIS, 1.0),
        ))?;

        // The series, then the legend.
        let looks = self.looks(5.0 * y_per_px);
        for (s, &look) in self.series.iter().zip(&looks) {
            let line = pen.stroke(look.color, 2.0);
            // One line per run of consecutive levels: a level without a positive count (zero
            // or negative, off a log scale) leaves a gap rather than a misleading segment.
            for run in s.points.chunk_by(|a, b| b.0 == a.0 + 1) {
                if run.len() < 2 {
                    continue;
                }
                let points = run.iter().map(|&(l, y)| ((l - first) as f64, y));
                if let Some((dash, gap)) = look.dash {
                    let (dash, gap) = (pen.px(dash), pen.px(gap));
                    chart.draw_series(DashedLineSeries::new(points, dash, gap, line))?;
                } else {
                    chart.draw_series(LineSeries::new(points, line))?;
                }
            }
            // Markers only while they stay apart.
            if self.last_level - self.first_level <= 40 {
                for &(l, y) in &s.points {
                    let at = ((l - first) as f64, y);
                    chart.plotting_area().draw(&pen.marker(at, look, 4.0))?;
                }
            }
        }
        let lx = right + 18.0;
        let row = 24.0;
        let legend_h = row * (self.series.len() + notes.len()) as f64 + 14.0;
        let corners = [pen.at(lx, top), pen.at(lx + legend_w, top + legend_h)];
        root.draw(&Rectangle::new(corners, WHITE.filled()))?;
        root.draw(&Rectangle::new(corners, pen.stroke(GRID, 1.0)))?;
        for (i, (label, &look)) in labels.into_iter().zip(&looks).enumerate() {
            let y = top + 19.0 + row * i as f64;
            let segment = vec![pen.at(lx + 10.0, y), pen.at(lx + 38.0, y)];
            let line = pen.stroke(look.color, 2.0);
            if let Some((dash, gap)) = look.dash {
                let (dash, gap) = (pen.px(dash), pen.px(gap));
                root.draw(&DashedPathElement::new(segment, dash, gap, line))?;
            } else {
                root.draw(&PathElement::new(segment, line))?;
            }
            root.draw(&pen.marker(pen.at(lx + 24.0, y), look, 4.0))?;
            pen.text(root, &label, (lx + 46.0, y), 14.0, TEXT, HPos::Left)?;
        }
        for (i, note) in notes.into_iter().enumerate() {
            let y = top + 19.0 + row * (self.series.len() + i) as f64;
            pen.text(root, &note, (lx + 10.0, y), 13.0, MUTED, HPos::Left)?;
        }
        Ok(())
    }
}

/// Device pixels per image pixel (in each direction) of the PNG's drawing.
const SUPERSAMPLE: u32 = 3;

/// Averages each `factor` x `factor` block of an RGB image `width * factor` pixels wide into
/// one pixel: the anti-aliasing of the supersampled drawing.
fn downsample(big: &[u8], width: usize, factor: usize) -> Vec<u8> {
    let big_row = width * factor * 3;
    let height = big.len() / big_row / factor;
    let mut out = Vec::with_capacity(width * height * 3);
    let n = (factor * factor) as u32;
    for y in 0..height {
        for x in 0..width {
            for c in 0..3 {
                let sum: u32 = (0..factor * factor)
                    .map(|i| {
                        let (dy, dx) = (i / factor, i % factor);
                        u32::from(big[(y * factor + dy) * big_row + (x * factor + dx) * 3 + c])
                    })
                    .sum();
                out.push(((sum + n / 2) / n) as u8);
            }
        }
    }
    out
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
    fn labels() {
        assert_eq!(power_label(0), ("1", None));
        assert_eq!(power_label(1), ("10", None));
        assert_eq!(power_label(12), ("10", Some("12".to_string())));
        assert_eq!(power_label(-3), ("10", Some("-3".to_string())));
        assert_eq!(legend_label("IE"), "IE (interior edges)");
        assert_eq!(legend_label("x0"), "x0");
    }

    #[test]
    fn text_is_measured_with_the_embedded_font() {
        let pen = Pen::svg(embedded_font().unwrap());
        let one = pen.width("level", 14.0);
        assert!((20.0..50.0).contains(&one), "{one}");
        assert!((pen.width("level", 28.0) - 2.0 * one).abs() < 0.5);
        // Each glyph's bitmap starts at its left bearing: a `j` reaches left of its pen
        // position (Noto Sans), a `b` starts right of it.
        let (glyphs, _) = pen.glyphs("obj", 100.0);
        let caret_j = pen.width("ob", 100.0);
        assert!(glyphs[2].1 < caret_j, "{glyphs:?}");
        assert!(glyphs[1].1 > pen.width("o", 100.0), "{glyphs:?}");
        // The bitmap's font size has the em the SVG's has.
        let bitmap = Pen::bitmap(embedded_font().unwrap(), 3.0);
        assert!(
            (1.2..1.5).contains(&bitmap.size_per_em),
            "{}",
            bitmap.size_per_em
        );
    }

    #[test]
    fn downsample_averages_blocks() {
        // 2 x 1 pixels from 4 x 2 at factor 2: a white and a half-black block.
        let big = [
            [255, 255, 255],
            [255, 255, 255],
            [0, 0, 0],
            [255, 0, 0],
            [255, 255, 255],
            [255, 255, 255],
            [0, 0, 0],
            [255, 0, 0],
        ]
        .concat();
        assert_eq!(downsample(&big, 2, 2), [255, 255, 255, 128, 0, 0]);
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

    /// The 2-pixel polylines of an SVG (series lines and the legend's samples).
    fn wide_polylines(svg: &str) -> Vec<Vec<(f64, f64)>> {
        let doc = roxmltree::Document::parse(svg).expect("well-formed XML");
        doc.descendants()
            .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke-width") == Some("2"))
            .map(|n| {
                n.attribute("points")
                    .unwrap()
                    .split_whitespace()
                    .map(|p| {
                        let (x, y) = p.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect()
            })
            .collect()
    }

    #[test]
    fn lines_break_at_gaps_and_hidden_columns_are_noted() {
        let gap = Series {
            name: "x0".into(),
            points: vec![(0, 0.0), (1, 1.0), (3, 3.0), (4, 4.0), (5, 5.0)],
        };
        let chart = chart(vec![gap]);
        let svg = chart.to_svg().unwrap();
        let lines = wide_polylines(&svg);
        let lengths: Vec<usize> = lines.iter().map(Vec::len).collect();
        assert_eq!(lengths, [2, 3, 2], "two runs, and the legend's sample");
        // Higher counts are drawn higher (smaller y).
        assert!(lines[0][1].1 < lines[0][0].1);
        let markers = svg.matches("<circle").count();
        assert_eq!(
            markers,
            2 * (5 + 1),
            "one per point and the legend's, each on a halo"
        );
        assert!(svg.contains("\nBE: no positive count\n</text>"), "{svg}");
        assert!(svg.contains("\nt\n</text>"), "the title");
        let png = chart.to_png().unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    }

    #[test]
    fn a_series_on_an_earlier_one_is_dashed() {
        let line = |name: &str, lift: f64| Series {
            name: name.into(),
            points: (0..4).map(|l| (l, l as f64 + lift)).collect(),
        };
        // b lies on a (within the tolerance), c is apart, d lies on a and b, e touches a at
        // one level only (a crossing hides no segment).
        let e = Series {
            name: "e".into(),
            points: vec![(0, 0.0), (1, 3.0)],
        };
        let chart = chart(vec![
            line("a", 0.0),
            line("b", 0.01),
            line("c", 0.5),
            line("d", -0.01),
            e,
        ]);
        let dashes: Vec<_> = chart.looks(0.02).iter().map(|l| l.dash).collect();
        assert_eq!(
            dashes,
            [
                None,
                Some(Look::DASHES[0]),
                None,
                Some(Look::DASHES[1]),
                None
            ]
        );
        let svg = chart.to_svg().unwrap();
        assert!(
            wide_polylines(&svg).len() > 5 + 5,
            "dashes are polylines of their own"
        );
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
