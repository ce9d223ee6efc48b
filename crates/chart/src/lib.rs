//! Log-scale line charts of counts versus level, as SVG or PNG, drawn by `plotters` with an
//! embedded Noto Sans (no system font is read).
//!
//! A [`Chart`] describes what to draw in plain numbers and strings: a title and subtitle, the
//! axis descriptions, the range of levels on the x axis, and [`Series`] of points
//! `(level, log10 value)`. The y axis is linear in log10 and labelled with powers of ten
//! (`1`, `10`, `10²`, ... `10¹²⁵⁰`), so values of any size (a count of 10^5000 is the point
//! 5000.0) have finite positions. [`render_svg`] and [`render_png`] draw it, 960 x 600 pixels
//! ([`WIDTH`], [`HEIGHT`]), the same layout on both:
//!
//! - the title (shortened with `...` to fit) and the subtitle above the plot;
//! - one line per run of consecutive levels of a series (a level missing from a series leaves
//!   a gap), with markers while the levels are at most 41; colors (the tab10 palette) and
//!   markers (a circle, a square, a diamond, two triangles) cycle with the series' position;
//! - a series that runs on an earlier one (within a few pixels at two consecutive levels) is
//!   drawn dashed with larger outline markers, so the one underneath shows through, and a
//!   series whose points equal an earlier one's has ` = NAME` of that one in its legend;
//! - the legend right of the plot frame (it never hides a line): each series' label with a
//!   sample of its line and marker, then the notes (lines without a sample).
//!
//! The SVG is drawn by plotters' SVG back end (text in the `font-family` Noto Sans with
//! similar sans fallbacks, laid out by Noto Sans' metrics). The PNG is drawn by its bitmap back
//! end at three times the size (it fills without anti-aliasing), averaged down and encoded by
//! `image`; its text is placed glyph by glyph from the embedded font. The output depends only
//! on the [`Chart`]: the same chart gives the same bytes.
//!
//! # Example
//!
//! ```
//! use chart::{render_png, render_svg, Chart, Error, Series};
//!
//! // 2^level and 3 * 4^level as log10 values, levels 0 to 8.
//! let line = |name: &str, label: &str, f: fn(f64) -> f64| Series {
//!     name: name.into(),
//!     label: label.into(),
//!     points: (0..=8).map(|l| (l, f(l as f64))).collect(),
//! };
//! let mut chart = Chart {
//!     title: "powers of two and four".into(),
//!     subtitle: "levels 0..=8, log scale".into(),
//!     x_label: "level".into(),
//!     y_label: "count (log scale)".into(),
//!     levels: 0..=8,
//!     series: vec![
//!         line("A", "A (doubling)", |l| l * 2f64.log10()),
//!         line("B", "B (quadrupling)", |l| 3f64.log10() + l * 4f64.log10()),
//!     ],
//!     notes: vec!["C: no positive count".into()],
//! };
//! let svg = render_svg(&chart)?;
//! assert!(svg.starts_with("<svg"));
//! assert!(svg.contains("B (quadrupling)") && svg.contains("C: no positive count"));
//! assert!(svg.contains("10⁵"));
//! let png = render_png(&chart)?;
//! assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
//!
//! // A point outside the levels is refused, naming the series and the level.
//! chart.series[1].points.push((9, 6.0));
//! let err = render_svg(&chart).unwrap_err();
//! assert!(matches!(err, Error::LevelOutsideRange { level: 9, .. }));
//! assert_eq!(err.to_string(), "series `B`: level 9 is outside the chart's levels 0..=8");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! **Invariant:** the crate knows nothing of subdivision schemes, meshes or counts: it takes
//! plain numbers and strings, and neither prints nor writes files (the caller writes the
//! bytes).
#![deny(missing_docs)]

mod draw;
mod glyphs;

use std::ops::RangeInclusive;

/// Width of the image in pixels (also the SVG's width in user units).
pub const WIDTH: u32 = 960;
/// Height of the image in pixels (also the SVG's height in user units).
pub const HEIGHT: u32 = 600;

/// What to draw: the texts, the levels on the x axis and the series.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    /// The title, centered above the plot; shortened with `...` when it does not fit.
    pub title: String,
    /// The line below the title.
    pub subtitle: String,
    /// The description of the x axis (the levels).
    pub x_label: String,
    /// The description of the y axis (the log10 values, labelled as powers of ten).
    pub y_label: String,
    /// The levels the x axis shows; every point's level lies in it.
    pub levels: RangeInclusive<u64>,
    /// The lines, drawn in order (later ones over earlier ones) and listed in the legend.
    pub series: Vec<Series>,
    /// Legend lines without a line sample, after the series (what the chart could not draw).
    pub notes: Vec<String>,
}

/// One line of a [`Chart`].
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The short name, used when the legend of a later identical series names this one
    /// (`E (edges) = IE`), and in errors.
    pub name: String,
    /// The legend text.
    pub label: String,
    /// `(level, log10 value)`, levels increasing within the chart's levels and values finite;
    /// a level without a point leaves a gap in the line.
    pub points: Vec<(u64, f64)>,
}

/// Why a chart cannot be drawn.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The chart's levels are empty (the first is past the last).
    #[error("the chart's levels {first}..={last} are empty")]
    EmptyLevels {
        /// The first level.
        first: u64,
        /// The last level.
        last: u64,
    },
    /// A point's level lies outside the chart's levels.
    #[error("series `{series}`: level {level} is outside the chart's levels {first}..={last}")]
    LevelOutsideRange {
        /// The series' name.
        series: String,
        /// The point's level.
        level: u64,
        /// The chart's first level.
        first: u64,
        /// The chart's last level.
        last: u64,
    },
    /// A point's level is not above the previous point's.
    #[error("series `{series}`: level {level} follows level {previous} (levels must increase)")]
    LevelsNotIncreasing {
        /// The series' name.
        series: String,
        /// The point's level.
        level: u64,
        /// The previous point's level.
        previous: u64,
    },
    /// A point's value is infinite or NaN.
    #[error("series `{series}`: the value at level {level} is not finite")]
    NonFiniteValue {
        /// The series' name.
        series: String,
        /// The point's level.
        level: u64,
    },
    /// The embedded Noto Sans cannot be read (a broken build).
    #[error("the embedded font cannot be read")]
    Font,
    /// plotters failed to draw; the text is its error.
    #[error("cannot draw the plot: {0}")]
    Draw(String),
    /// The supersampled bitmap has the wrong number of bytes for its size (a bug).
    #[error("the plot's {width} x {height} pixels do not fill its buffer")]
    Buffer {
        /// Width of the bitmap in pixels.
        width: u32,
        /// Height of the bitmap in pixels.
        height: u32,
    },
    /// `image` failed to encode the PNG; the text is its error.
    #[error("cannot encode the PNG: {0}")]
    Encode(String),
}

/// The chart as an SVG document.
///
/// # Errors
///
/// [`Error::EmptyLevels`], [`Error::LevelOutsideRange`], [`Error::LevelsNotIncreasing`] or
/// [`Error::NonFiniteValue`] for a chart that does not hold together; [`Error::Font`] or
/// [`Error::Draw`] if plotters fails.
pub fn render_svg(chart: &Chart) -> Result<String, Error> {
    check(chart)?;
    chart.to_svg()
}

/// The chart as PNG bytes (8-bit RGB): drawn at three times the size, each block of 3 x 3
/// pixels averaged into one.
///
/// # Errors
///
/// As [`render_svg`], and [`Error::Buffer`] or [`Error::Encode`] if the bitmap cannot be
/// encoded.
pub fn render_png(chart: &Chart) -> Result<Vec<u8>, Error> {
    check(chart)?;
    chart.to_png()
}

/// Refuses a chart whose levels are empty or whose points are out of range, out of order or
/// not finite (the drawing relies on all three).
fn check(chart: &Chart) -> Result<(), Error> {
    let (first, last) = (*chart.levels.start(), *chart.levels.end());
    if first > last {
        return Err(Error::EmptyLevels { first, last });
    }
    for s in &chart.series {
        let series = || s.name.clone();
        let mut previous: Option<u64> = None;
        for &(level, y) in &s.points {
            if !chart.levels.contains(&level) {
                let series = series();
                return Err(Error::LevelOutsideRange {
                    series,
                    level,
                    first,
                    last,
                });
            }
            if let Some(previous) = previous.filter(|&p| p >= level) {
                let series = series();
                return Err(Error::LevelsNotIncreasing {
                    series,
                    level,
                    previous,
                });
            }
            if !y.is_finite() {
                return Err(Error::NonFiniteValue {
                    series: series(),
                    level,
                });
            }
            previous = Some(level);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart(points: Vec<(u64, f64)>) -> Chart {
        Chart {
            title: "t".into(),
            subtitle: "s".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            levels: 2..=5,
            series: vec![Series {
                name: "A".into(),
                label: "A".into(),
                points,
            }],
            notes: vec![],
        }
    }

    #[test]
    fn incoherent_charts_are_refused() {
        let refused = |c: &Chart| render_svg(c).unwrap_err().to_string();
        assert_eq!(
            refused(&chart(vec![(2, 0.0), (6, 1.0)])),
            "series `A`: level 6 is outside the chart's levels 2..=5"
        );
        assert_eq!(
            refused(&chart(vec![(1, 0.0)])),
            "series `A`: level 1 is outside the chart's levels 2..=5"
        );
        assert_eq!(
            refused(&chart(vec![(3, 0.0), (3, 1.0)])),
            "series `A`: level 3 follows level 3 (levels must increase)"
        );
        assert_eq!(
            refused(&chart(vec![(4, 0.0), (3, 1.0)])),
            "series `A`: level 3 follows level 4 (levels must increase)"
        );
        assert_eq!(
            refused(&chart(vec![(3, f64::NAN)])),
            "series `A`: the value at level 3 is not finite"
        );
        let mut empty = chart(vec![]);
        let (first, last) = (5, 2);
        empty.levels = first..=last;
        assert_eq!(refused(&empty), "the chart's levels 5..=2 are empty");
        assert!(matches!(
            render_png(&empty),
            Err(Error::EmptyLevels { first: 5, last: 2 })
        ));
    }

    #[test]
    fn extreme_levels_and_no_series_draw() {
        // The largest levels (no overflow at u64::MAX), and a chart with nothing on it.
        let mut top = chart(vec![(u64::MAX - 1, 5000.0), (u64::MAX, 5000.6)]);
        top.levels = u64::MAX - 3..=u64::MAX;
        let svg = render_svg(&top).unwrap();
        assert!(
            svg.contains("18446744073709551615"),
            "the last level is labelled"
        );
        // One level at the end: the padding's ticks past u64::MAX are not labelled.
        let mut end = chart(vec![(u64::MAX, 3.0)]);
        end.levels = u64::MAX..=u64::MAX;
        assert!(render_svg(&end).unwrap().contains("18446744073709551615"));
        let mut nothing = chart(vec![]);
        nothing.series.clear();
        nothing.levels = 7..=7;
        assert!(render_svg(&nothing).unwrap().starts_with("<svg"));
    }

    #[test]
    fn the_same_chart_gives_the_same_bytes() {
        let c = chart(vec![(2, 1.0), (3, 1.5), (5, 2.5)]);
        assert_eq!(render_svg(&c).unwrap(), render_svg(&c).unwrap());
        let png = render_png(&c).unwrap();
        assert_eq!(png, render_png(&c).unwrap());
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        // The IHDR chunk: width and height.
        assert_eq!(&png[16..24], &[0, 0, 3, 0xc0, 0, 0, 2, 0x58]);
    }
}
