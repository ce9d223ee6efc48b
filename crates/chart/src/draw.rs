//! The drawing: layout, colors, markers and dashes, the axes' decades and labels, on plotters'
//! SVG back end or its bitmap back end at [`SUPERSAMPLE`] times the size (averaged down by
//! `image`), with the embedded Noto Sans registered with plotters' `ab_glyph` font table.

use plotters::coord::Shift;
use plotters::element::{DashedPathElement, Drawable, PointCollection};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters_backend::{BackendCoord, DrawingErrorKind};

use crate::glyphs::Glyphs;
use crate::{Chart, Error, Series, HEIGHT, WIDTH};

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

/// The decades of the count axis, `(lo, hi, step)` as exponents: `[min, max]` (log10 values)
/// covered in at most about 8 steps of a 1-2-5 number of decades, so labels read 10^0, 10^5...
fn decades(min: f64, max: f64) -> (i64, i64, i64) {
    if !(min.is_finite() && max.is_finite() && min <= max) {
        return decades(0.0, 1.0);
    }
    let lo = min.floor() as i64;
    let hi = (max.ceil() as i64).max(lo + 1);
    let step = nice_step(hi - lo, 8);
    let (lo, hi) = (lo.div_euclid(step), -(-hi).div_euclid(step));
    (lo * step, hi * step, step)
}

/// The label of 10^k: `1`, `10`, then 10 with a superscript exponent (`10¹²`).
fn power_label(k: i64) -> String {
    const SUPERSCRIPTS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digit = |c: char| c.to_digit(10).map_or('⁻', |d| SUPERSCRIPTS[d as usize]);
    match k {
        0 => "1".to_string(),
        1 => "10".to_string(),
        _ => format!("10{}", k.to_string().chars().map(digit).collect::<String>()),
    }
}

const TEXT: RGBColor = RGBColor(0x22, 0x22, 0x22);
const AXIS: RGBColor = RGBColor(0x44, 0x44, 0x44);
const GRID: RGBColor = RGBColor(0xd4, 0xd4, 0xd4);
const GRID_MINOR: RGBColor = RGBColor(0xee, 0xee, 0xee);
const MUTED: RGBColor = RGBColor(0x66, 0x66, 0x66);

/// Series colors (the "tab10" palette, as 0xRRGGBB), cycled.
const PALETTE: [u32; 10] = [
    0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b, 0xe377c2, 0x7f7f7f, 0xbcbd22,
    0x17becf,
];

/// Marker shapes, cycled (with the colors, 30 series stay distinct): a circle, then regular
/// polygons as (corners, turn of the first corner in degrees, its distance per radius): a
/// square, a diamond, triangles pointing up and down (y runs down).
const MARKERS: [(u32, f64, f64); 5] = [
    (0, 0.0, 1.0),
    (4, 45.0, 1.2),
    (4, 0.0, 1.2),
    (3, -90.0, 1.25),
    (3, 90.0, 1.25),
];

/// How one series is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Look {
    color: RGBColor,
    /// An index into [`MARKERS`].
    marker: usize,
    /// The series runs on an earlier one: its line is dashed (dash and gap in image pixels)
    /// and its markers are larger outlines, so the one underneath shows through.
    dash: Option<(f64, f64)>,
}

/// Dash patterns of the series that run on earlier ones, cycled: two on one line still differ.
const DASHES: [(f64, f64); 3] = [(7.0, 5.0), (3.0, 3.0), (12.0, 4.0)];

/// The font family plotters' `ab_glyph` table knows the embedded font by; the SVG back end
/// writes it as the `font-family`, so viewers without Noto Sans fall back to a similar sans.
const FONT_FAMILY: &str = "'Noto Sans', 'DejaVu Sans', Arial, sans-serif";

/// Noto Sans' height (ascent 2189 to descent 600 units) per em of 2048 units: plotters'
/// bitmap text scales this height to the font size, its SVG back end writes the size / 1.24.
const NOTO_HEIGHT_PER_EM: f64 = 1.362;

/// One back end's units: the chart is laid out in image pixels and drawn at `px` device pixels
/// per image pixel; a font of `em` image pixels is asked of plotters as `em * text`.
#[derive(Clone, Copy, Debug)]
struct Scale {
    px: f64,
    text: f64,
}

/// Device pixels per image pixel (in each direction) of the PNG's drawing.
const SUPERSAMPLE: u32 = 3;

impl Scale {
    const SVG: Scale = Scale {
        px: 1.0,
        text: 1.24,
    };
    const BITMAP: Scale = Scale {
        px: SUPERSAMPLE as f64,
        text: SUPERSAMPLE as f64 * NOTO_HEIGHT_PER_EM,
    };
    fn px(self, v: f64) -> i32 {
        (v * self.px).round() as i32
    }
    fn at(self, x: f64, y: f64) -> BackendCoord {
        (self.px(x), self.px(y))
    }
    fn stroke(self, color: RGBColor, width: f64) -> ShapeStyle {
        Color::stroke_width(&color, self.px(width).max(1) as u32)
    }
    fn font(self, em: f64, color: RGBColor) -> TextStyle<'static> {
        (FONT_FAMILY, em * self.text).into_font().color(&color)
    }
}

/// A plotters element: the marker of a series at `.0` as its look `.1` says at scale `.2`, a
/// filled shape on a white halo, or a larger outline when the series lies on an earlier one.
#[derive(Clone, Copy)]
struct Marker<C>(C, Look, Scale);

impl<'a, C> PointCollection<'a, C> for &'a Marker<C> {
    type Point = &'a C;
    type IntoIter = std::iter::Once<&'a C>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.0)
    }
}

impl<C, DB: DrawingBackend> Drawable<DB> for Marker<C> {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut at: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let (Some(c), s, look) = (at.next(), self.2, self.1) else {
            return Ok(());
        };
        let (corners, turn, reach) = MARKERS[look.marker];
        let shape = |r: f64| {
            (0..=corners).map(move |i| {
                let a = (turn + 360.0 * f64::from(i) / f64::from(corners)).to_radians();
                let (dx, dy) = s.at(reach * r * a.cos(), reach * r * a.sin());
                (c.0 + dx, c.1 + dy)
            })
        };
        let (color, outline) = (look.color, s.stroke(look.color, 1.5));
        match (corners, look.dash.is_some()) {
            (0, true) => backend.draw_circle(c, s.px(6.8) as u32, &outline, false),
            (0, false) => {
                backend.draw_circle(c, s.px(5.0) as u32, &WHITE.filled(), true)?;
                backend.draw_circle(c, s.px(4.0) as u32, &color.filled(), true)
            }
            (_, true) => backend.draw_path(shape(6.8), &outline),
            (_, false) => {
                backend.fill_polygon(shape(5.0), &WHITE.filled())?;
                backend.fill_polygon(shape(4.0), &color.filled())
            }
        }
    }
}

/// Pixels of free space inside the plot frame around the data, so end markers are not cut.
const PAD: f64 = 12.0;

impl Chart {
    /// Draws the chart on `backend`, with the embedded Noto Sans registered with plotters.
    fn render(&self, backend: impl DrawingBackend, scale: Scale) -> Result<(), Error> {
        plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, notosans::REGULAR_TTF)
            .map_err(|_| Error::Font)?;
        let root = backend.into_drawing_area();
        let drawn = self.draw(&root, scale).and_then(|()| root.present());
        drawn.map_err(|e| Error::Draw(e.to_string()))
    }

    /// The chart as an SVG document.
    pub(crate) fn to_svg(&self) -> Result<String, Error> {
        let mut svg = String::new();
        let backend = SVGBackend::with_string(&mut svg, (WIDTH, HEIGHT));
        self.render(backend, Scale::SVG)?;
        Ok(svg)
    }

    /// The chart as PNG bytes: drawn at `SUPERSAMPLE` times the size, each block of
    /// `SUPERSAMPLE` x `SUPERSAMPLE` pixels averaged into one (`image`'s thumbnail filter).
    pub(crate) fn to_png(&self) -> Result<Vec<u8>, Error> {
        let (w, h) = (WIDTH * SUPERSAMPLE, HEIGHT * SUPERSAMPLE);
        let mut big = vec![0u8; w as usize * h as usize * 3];
        let font =
            ab_glyph::FontRef::try_from_slice(notosans::REGULAR_TTF).map_err(|_| Error::Font)?;
        let bitmap = BitMapBackend::with_buffer(&mut big, (w, h));
        self.render(Glyphs(bitmap, font), Scale::BITMAP)?;
        let big = image::RgbImage::from_raw(w, h, big).ok_or(Error::Buffer {
            width: w,
            height: h,
        })?;
        let mut bytes = std::io::Cursor::new(Vec::new());
        image::imageops::thumbnail(&big, WIDTH, HEIGHT)
            .write_to(&mut bytes, image::ImageFormat::Png)
            .map_err(|e| Error::Encode(e.to_string()))?;
        Ok(bytes.into_inner())
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
                    DASHES[(dashed - 1) % DASHES.len()]
                });
                Look {
                    color: {
                        let [_, r, g, b] = PALETTE[i % PALETTE.len()].to_be_bytes();
                        RGBColor(r, g, b)
                    },
                    marker: i % MARKERS.len(),
                    dash,
                }
            })
            .collect()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        s: Scale,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (w, h) = (f64::from(WIDTH), f64::from(HEIGHT));
        root.fill(&WHITE)?;
        // Widths in image pixels, with room for a wider fallback font of an SVG viewer.
        let width = |text: &str, font: &TextStyle| {
            let (tw, _) = root.estimate_text_size(text, font)?;
            Ok(f64::from(tw) * 1.08 * NOTO_HEIGHT_PER_EM / s.text)
        };
        let centered = Pos::new(HPos::Center, VPos::Center);
        // What a legend entry is drawn on: it draws nothing in the chart.
        let no_points = std::iter::empty::<EmptyElement<(f64, f64), DB>>;

        // Title (shortened to fit) and subtitle.
        let font = s.font(20.0, TEXT).pos(centered);
        let mut title = self.title.clone();
        while width(&title, &font)? > w - 40.0 && title.chars().count() > 4 {
            let keep = title.chars().count() - 4;
            title = title.chars().take(keep).collect::<String>() + "...";
        }
        root.draw(&Text::new(title, s.at(w / 2.0, 28.0), font))?;
        let (first, last) = (*self.levels.start(), *self.levels.end());
        let font = s.font(13.0, MUTED).pos(centered);
        root.draw(&Text::new(
            self.subtitle.as_str(),
            s.at(w / 2.0, 51.0),
            font,
        ))?;

        // The legend sits right of the plot frame, so it never hides a line. A line hidden
        // under an earlier identical one says so in its label.
        let mut labels: Vec<String> = self.series.iter().map(|s| s.label.clone()).collect();
        for (i, s) in self.series.iter().enumerate() {
            if let Some(same) = self.series[..i].iter().find(|e| e.points == s.points) {
                labels[i] += &format!(" = {}", same.name);
            }
        }
        let notes = self.notes.iter().cloned();
        let legend_font = s.font(14.0, TEXT);
        let mut label_w: f64 = 0.0;
        for label in labels.iter().cloned().chain(notes.clone()) {
            label_w = label_w.max(width(&label, &legend_font)?);
        }
        // Plotters sizes the legend's box to its own estimate (for the SVG, 1.24 / 1.362 of
        // the text's width in Noto Sans); the margin adds what the text may need beyond it.
        let extra = label_w / 1.08 * (1.0 - s.text / (s.px * NOTO_HEIGHT_PER_EM));
        let legend_w = (label_w + extra + 62.0).max(110.0);
        let (left, top, right, bottom) = (92.0, 78.0, w - legend_w - 36.0, h - 66.0);

        // Axes: levels as offsets from a multiple of 1000 below the first (exact in f64, and
        // round ticks stay round levels), log10 counts over whole decades, PAD pixels of room
        // inside the frame. Plotters picks the finest 1-2-5 tick step within the number asked
        // for: at most 12 level steps, and the step of `decades` (never a fraction of either).
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for &(_, y) in self.series.iter().flat_map(|s| &s.points) {
            (min, max) = (min.min(y), max.max(y));
        }
        let (lo, hi, step) = decades(min, max);
        let base = first - first % 1000;
        let span = (last - first) as f64;
        let room = if span > 0.0 { 0.0 } else { 1.0 };
        let x_pad = room + (span + 2.0 * room) * PAD / (right - left - 2.0 * PAD);
        let (x_lo, x_hi) = ((first - base) as f64 - x_pad, (last - base) as f64 + x_pad);
        let y_pad = (hi - lo) as f64 * PAD / (bottom - top - 2.0 * PAD);
        // The plot left of the legend's strip, the legend in it (a chart without axes).
        let (main, side) = root.split_horizontally(s.px(right + 18.0));
        let mut legend = ChartBuilder::on(&side)
            .margin_top(s.px(top))
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
        let mut chart = ChartBuilder::on(&main)
            .margin_top(s.px(top))
            .margin_right(s.px(18.0))
            .margin_left(s.px(12.0))
            .margin_bottom(s.px(12.0))
            .x_label_area_size(s.px(h - bottom - 12.0))
            .y_label_area_size(s.px(left - 12.0))
            .build_cartesian_2d(x_lo..x_hi, (lo as f64 - y_pad)..(hi as f64 + y_pad))?;
        // Minor lines at 2..=9 times each decade, when decades are one step and few.
        let minor = |k| (2..=9).map(move |m| k as f64 + f64::from(m).log10());
        let few = step == 1 && hi - lo <= 4;
        let minors = (lo..hi).filter(|_| few).flat_map(minor);
        chart.draw_series(
            minors.map(|y| PathElement::new(vec![(x_lo, y), (x_hi, y)], s.stroke(GRID_MINOR, 1.0))),
        )?;
        // A tick past u64::MAX (in the padding of a chart ending there) is left unlabelled.
        let x_label = |x: &f64| {
            base.checked_add(x.round() as u64)
                .map_or(String::new(), |l| l.to_string())
        };
        let y_label = |y: &f64| power_label(y.round() as i64);
        chart
            .configure_mesh()
            .x_labels(span.min(12.0) as usize + 1)
            .y_labels(((hi - lo) / step + 1) as usize)
            .max_light_lines(0)
            .bold_line_style(s.stroke(GRID, 1.0))
            .axis_style(s.stroke(AXIS, 1.0))
            .set_all_tick_mark_size(s.px(5.0))
            .x_label_formatter(&x_label)
            .y_label_formatter(&y_label)
            .label_style(s.font(14.0, TEXT))
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .axis_desc_style(s.font(15.0, TEXT))
            .draw()?;
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        let frame = [(xs.start, ys.start), (xs.end, ys.end)];
        root.draw(&Rectangle::new(frame, s.stroke(AXIS, 1.0)))?;

        // The series, each with its legend entry, then the columns that cannot be drawn.
        let looks = self.looks(5.0 * y_pad / PAD);
        for ((series, &look), label) in self.series.iter().zip(&looks).zip(labels) {
            let line = s.stroke(look.color, 2.0);
            // A solid line is drawn as one dash that never ends.
            let (dash, gap) = look.dash.map_or((i32::MAX, 0), |(d, g)| (s.px(d), s.px(g)));
            // One line per run of consecutive levels: a level without a positive count (zero
            // or negative, off a log scale) leaves a gap rather than a misleading segment.
            for run in series.points.chunk_by(|a, b| b.0 == a.0 + 1) {
                let points = run.iter().map(|&(l, y)| ((l - base) as f64, y));
                if run.len() > 1 {
                    chart.draw_series(DashedLineSeries::new(points, dash, gap, line))?;
                }
            }
            // Markers only while they stay apart.
            let markers = series.points.iter().filter(|_| span <= 40.0);
            chart.draw_series(markers.map(|&(l, y)| Marker(((l - base) as f64, y), look, s)))?;
            // The legend's sample: a piece of the line with a marker.
            let ends = vec![(0, 0), (s.px(28.0), 0)];
            let marker = Marker((s.px(14.0), 0), look, s);
            legend
                .draw_series(no_points())?
                .label(label)
                .legend(move |at| {
                    let line = DashedPathElement::new(ends.clone(), dash, gap, line);
                    EmptyElement::at(at) + line + marker
                });
        }
        for note in notes {
            legend.draw_series(no_points())?.label(note);
        }
        legend
            .configure_series_labels()
            .position(SeriesLabelPosition::Coordinate(0, 0))
            .legend_area_size(s.px(36.0))
            .margin(s.px(10.0 + extra))
            .label_font(legend_font)
            .background_style(WHITE.filled())
            .border_style(s.stroke(GRID, 1.0))
            .draw()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_step_by_one_two_five() {
        // Loop from the icosahedron to level 6, 12, 100, 400, 1000.
        assert_eq!(decades(1.08, 6.3), (1, 7, 1));
        assert_eq!(decades(1.08, 8.5), (1, 9, 1));
        assert_eq!(decades(1.08, 61.5), (0, 70, 10));
        assert_eq!(decades(1.08, 242.1), (0, 250, 50));
        assert_eq!(decades(0.0, 602.0), (0, 700, 100));
        assert_eq!(decades(3.0, 17.5), (2, 18, 2));
        // One value: one decade around it; nothing to show: one decade.
        assert_eq!(decades(2.0, 2.0), (2, 3, 1));
        assert_eq!(decades(f64::INFINITY, f64::NEG_INFINITY), (0, 1, 1));
        assert_eq!(nice_step(i64::MAX, 8), 2_000_000_000_000_000_000);
        assert_eq!(power_label(1250), "10¹²⁵⁰");
    }

    fn chart(series: Vec<Series>) -> Chart {
        Chart {
            title: "t".into(),
            subtitle: "s".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            levels: 0..=5,
            series,
            notes: vec!["BE: no positive count".into()],
        }
    }

    #[test]
    fn a_series_on_an_earlier_one_is_dashed() {
        let line = |name: &str, lift: f64| Series {
            name: name.into(),
            label: name.into(),
            points: (0..4).map(|l| (l, l as f64 + lift)).collect(),
        };
        // b lies on a (within the tolerance), c is apart, d lies on a and b, e touches a at
        // one level only (a crossing hides no segment).
        let mut e = line("e", 0.0);
        e.points = vec![(0, 0.0), (1, 3.0)];
        let lines = vec![
            line("a", 0.0),
            line("b", 0.01),
            line("c", 0.5),
            line("d", -0.01),
        ];
        let chart = chart(lines.into_iter().chain([e]).collect());
        let dashes: Vec<_> = chart.looks(0.02).iter().map(|l| l.dash).collect();
        let d = DASHES;
        assert_eq!(dashes, [None, Some(d[0]), None, Some(d[1]), None]);
    }

    #[test]
    fn a_series_equal_to_an_earlier_one_names_it_and_notes_follow() {
        let line = |name: &str| Series {
            name: name.into(),
            label: format!("{name} (label)"),
            points: vec![(1, 1.0), (2, 2.0)],
        };
        let svg = chart(vec![line("IE"), line("E")]).to_svg().unwrap();
        let texts: Vec<&str> = svg.lines().map(str::trim).collect();
        let at = |t: &str| {
            texts
                .iter()
                .position(|l| *l == t)
                .unwrap_or_else(|| panic!("{t}"))
        };
        assert!(at("IE (label)") < at("E (label) = IE"));
        assert!(at("E (label) = IE") < at("BE: no positive count"));
        // The shorter title and subtitle are drawn as given, the axes described.
        for t in ["t", "s", "x", "y", "10", "10²"] {
            at(t);
        }
    }
}
