//! Line panels: each series in its quantity's colour (solid, dashed, dots, open circles, or line
//! and dots as its [`Style`] says; on a log axis the points with `y <= 0` are left out and the
//! line is broken there), a legend where the data leave room ([`super::legend`]).
//!
//! The y axis of a non-negative quantity starts at zero when the data come closer to zero than
//! their own spread; otherwise it starts where the data do, and the axis is marked broken (two
//! slanted strokes across it near the bottom), so a reader does not take the lowest tick for zero.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use super::legend::{self, Entry, Place};
use super::{Drawn, LABEL_FONT, TICK_FONT, font, title_font};
use crate::model::{Panel, Style};

/// The drawable stretches of a series: maximal runs of finite points (and, on a log axis,
/// positive `y`). A line is broken where a point is skipped.
pub fn runs(points: &[(f64, f64)], log_y: bool) -> Vec<Vec<(f64, f64)>> {
    let shown = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite() && (!log_y || y > 0.0);
    let mut runs = vec![Vec::new()];
    for p in points {
        match (shown(p), runs.last_mut()) {
            (true, Some(run)) => run.push(*p),
            (false, Some(run)) if !run.is_empty() => runs.push(Vec::new()),
            _ => {}
        }
    }
    runs.retain(|run| !run.is_empty());
    runs
}

/// `[min, max]` of the values, `None` if there are none.
pub fn extent(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

/// An axis range around `[lo, hi]` with 3% room on each side (a factor on a log axis); a single
/// value gets a unit-wide (a decade-wide) range, no values the range `[0, 1]` (`[1, 10]`).
pub fn padded(extent: Option<(f64, f64)>, log: bool) -> Range<f64> {
    match (extent, log) {
        (None, false) => 0.0..1.0,
        (None, true) => 1.0..10.0,
        (Some((lo, hi)), false) if lo == hi => lo - 0.5..hi + 0.5,
        (Some((lo, hi)), true) if lo == hi => lo / 10f64.sqrt()..hi * 10f64.sqrt(),
        (Some((lo, hi)), false) => lo - 0.03 * (hi - lo)..hi + 0.03 * (hi - lo),
        (Some((lo, hi)), true) => lo / (hi / lo).powf(0.03)..hi * (hi / lo).powf(0.03),
    }
}

/// The y range of a linear axis and whether it is broken (see the module): non-negative data
/// closer to zero than their spread start at zero; farther, the axis starts at the data and is
/// broken.
pub fn y_range(extent: Option<(f64, f64)>) -> (Range<f64>, bool) {
    match extent {
        Some((lo, hi)) if lo >= 0.0 && lo <= hi - lo => (padded(Some((0.0, hi)), false), false),
        Some((lo, _)) if lo >= 0.0 => {
            let range = padded(extent, false);
            let broken = range.start > 0.0;
            (range, broken)
        }
        _ => (padded(extent, false), false),
    }
}

/// A tick label: at most four significant digits, scientific notation for very large or small.
pub fn tick(v: &f64) -> String {
    let rounded: f64 = format!("{v:.3e}").parse().unwrap_or(*v);
    let a = rounded.abs();
    if a == 0.0 || (1e-3..1e5).contains(&a) { format!("{rounded}") } else { format!("{rounded:e}") }
}

/// Tick labels of a linear axis over `range`: [`tick`], with the rounding noise of a tick at
/// zero (`-2.2e-16`) shown as `0`.
pub fn linear_ticks(range: &Range<f64>) -> impl Fn(&f64) -> String + use<> {
    let noise = 1e-9 * (range.end - range.start).abs();
    move |v| if v.abs() < noise { "0".to_owned() } else { tick(v) }
}

/// Draw a line panel into `area`.
pub fn draw<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Drawn
where
    DB::ErrorType: 'static,
{
    let series: Vec<_> = panel.series.iter().map(|s| runs(&s.points, panel.log_y)).collect();
    let points = || series.iter().flatten().flatten();
    let x = padded(extent(points().map(|p| p.0)), false);
    if panel.log_y {
        let y = padded(extent(points().map(|p| p.1)), true);
        let log = y.start.log10()..y.end.log10();
        chart(area, panel, &series, x, y.log_scale(), log, &tick, false)
    } else {
        let (y, broken) = y_range(extent(points().map(|p| p.1)));
        chart(area, panel, &series, x, y.clone(), y.clone(), &linear_ticks(&y), broken)
    }
}

/// Margin around a panel's chart, pixels.
const MARGIN: u32 = 12;
const X_LABEL_AREA: u32 = 55;
const Y_LABEL_AREA: u32 = 80;
/// Height taken by a panel's title above the chart.
const TITLE_ROOM: u32 = 36;

/// The line panel on the y axis `y_axis`, labelled by `y_ticks`; `y_linear` is its range where
/// the plot is linear (`log10 y` on a log axis), for placing the legend.
#[allow(clippy::too_many_arguments)]
fn chart<'a, DB, Y>(
    area: &'a DrawingArea<DB, Shift>,
    panel: &Panel,
    series: &[Vec<Vec<(f64, f64)>>],
    x: Range<f64>,
    y_axis: Y,
    y_linear: Range<f64>,
    y_ticks: &dyn Fn(&f64) -> String,
    broken: bool,
) -> Drawn
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let entries: Vec<Entry> = panel
        .series
        .iter()
        .filter(|s| !s.name.is_empty())
        .map(|s| Entry { name: s.name.clone(), style: s.style, colour: s.quantity.colour() })
        .collect();
    // The legend's place, from the curves in plot fractions and the plot's size as the chart
    // below will lay it out.
    let fraction = |v: f64, r: &Range<f64>| (v - r.start) / (r.end - r.start);
    let curves: Vec<(Vec<(f64, f64)>, bool)> = series
        .iter()
        .zip(&panel.series)
        .flat_map(|(runs, s)| {
            runs.iter()
                .map(move |run| (run, !matches!(s.style, Style::Points | Style::OpenPoints | Style::Rings)))
        })
        .map(|(run, line)| {
            let y = |v: f64| if panel.log_y { v.log10() } else { v };
            (run.iter().map(|&(px, py)| (fraction(px, &x), fraction(y(py), &y_linear))).collect(), line)
        })
        .collect();
    let (width, height) = area.dim_in_pixel();
    let plot = (
        f64::from(width.saturating_sub(2 * MARGIN + Y_LABEL_AREA)),
        f64::from(height.saturating_sub(2 * MARGIN + X_LABEL_AREA + TITLE_ROOM)),
    );
    let legend_size = legend::size(&entries);
    let place = if entries.is_empty() { None } else { Some(legend::place(&curves, plot, legend_size)) };
    let right = match place {
        Some(Place::Outside) => MARGIN + legend_size.0.ceil() as u32 + 2 * legend::GAP as u32,
        _ => MARGIN,
    };

    let x_ticks = linear_ticks(&x);
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, title_font(&panel.title, width.saturating_sub(right - MARGIN)))
        .margin(MARGIN)
        .margin_right(right)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x, y_axis)?;
    chart
        .configure_mesh()
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.12))
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .axis_desc_style(font(LABEL_FONT, FontStyle::Normal))
        .label_style(font(TICK_FONT, FontStyle::Normal))
        .x_label_formatter(&x_ticks)
        .y_label_formatter(y_ticks)
        .draw()?;
    for (runs, s) in series.iter().zip(&panel.series) {
        let colour = s.quantity.colour();
        let line = colour.stroke_width(2);
        let dots = runs.iter().flatten();
        match s.style {
            Style::Line | Style::LinePoints => {
                chart.draw_series(runs.iter().map(|r| PathElement::new(r.clone(), line)))?;
            }
            Style::Dashed => {
                chart.draw_series(runs.iter().map(|r| DashedPathElement::new(r.clone(), 9, 6, line)))?;
            }
            Style::Points | Style::OpenPoints | Style::Rings => {}
        }
        match s.style {
            Style::Points | Style::LinePoints => {
                chart.draw_series(dots.map(|&p| Circle::new(p, 3, colour.filled())))?;
            }
            Style::OpenPoints => {
                chart.draw_series(dots.clone().map(|&p| Circle::new(p, 4, WHITE.filled())))?;
                chart.draw_series(dots.map(|&p| Circle::new(p, 4, colour.stroke_width(2))))?;
            }
            Style::Rings => {
                chart.draw_series(dots.map(|&p| Circle::new(p, legend::RINGS, colour.stroke_width(2))))?;
            }
            Style::Line | Style::Dashed => {}
        }
    }

    let (px, py) = chart.plotting_area().get_pixel_range();
    let base = area.get_base_pixel();
    let (left, top, right_edge, bottom) =
        (px.start - base.0, py.start - base.1, px.end - base.0, py.end - base.1);
    if broken {
        break_mark(area, (left, bottom))?;
    }
    match place {
        Some(Place::Inside(x, y)) => {
            legend::draw(area, (left + x.round() as i32, top + y.round() as i32), &entries)?
        }
        Some(Place::Outside) => legend::draw(area, (right_edge + legend::GAP as i32 + 4, top), &entries)?,
        None => {}
    }
    Ok(())
}

/// Two slanted strokes across the y axis just above its lower end, with the axis blanked
/// between them: the axis does not start at zero.
fn break_mark<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, (x, bottom): (i32, i32)) -> Drawn
where
    DB::ErrorType: 'static,
{
    let y = bottom - 14;
    area.draw(&Polygon::new(
        vec![(x - 8, y + 5), (x + 8, y - 1), (x + 8, y - 6), (x - 8, y)],
        WHITE.filled(),
    ))?;
    for dy in [0, 5] {
        area.draw(&PathElement::new(vec![(x - 9, y + dy + 1), (x + 9, y + dy - 6)], BLACK.stroke_width(2)))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_break_at_points_that_cannot_be_drawn() {
        let points = [(0.0, 1.0), (1.0, -1.0), (2.0, 2.0), (3.0, 3.0), (f64::NAN, 1.0)];
        assert_eq!(runs(&points, true), vec![vec![(0.0, 1.0)], vec![(2.0, 2.0), (3.0, 3.0)]]);
        assert_eq!(runs(&points, false).len(), 1);
    }

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(&0.30000000000000004), "0.3");
        assert_eq!(tick(&1.0e-5), "1e-5");
        assert_eq!(tick(&123456.0), "1.235e5");
        assert_eq!(tick(&-2.0), "-2");
    }

    #[test]
    fn a_positive_axis_starts_at_zero_or_is_marked_broken() {
        // Energies from 0.05 to 0.14: closer to zero than their spread, the axis starts at zero.
        let (range, broken) = y_range(Some((0.05, 0.14)));
        assert!(range.start <= 0.0 && !broken);
        // Kinetic energy from 2.2 to 2.9: zoomed in, and marked broken.
        let (range, broken) = y_range(Some((2.2, 2.9)));
        assert!(range.start > 2.1 && range.start < 2.2 && broken);
        // Signed data (a profile) or values at zero: not broken.
        assert!(!y_range(Some((-0.6, 0.6))).1);
        assert!(!y_range(Some((-17.0, -10.0))).1);
        assert!(!y_range(Some((0.0, 3.0))).1);
        assert!(!y_range(None).1);
    }
}
