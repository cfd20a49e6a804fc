//! Heat maps and colour bars.
//!
//! A categorical map has one colour per category ([`crate::palette::category_colour`]) and
//! beside it the names of the categories that occur in it (a legend of what the reader sees; a
//! category's colour never depends on which others occur). A continuous map of values of both
//! signs (a space-time image of the angles) uses the diverging map centred on zero, symmetric:
//! its limit is the figure's physical scale when it gives one ([`Heatmap::colour_limit`]),
//! otherwise the 99th percentile of `|value|`; a few extreme cells (a rotor of a trapped
//! antikink swinging far) then cannot wash out the two domains, and the colour bar marks the
//! clipped ends. Other continuous maps use viridis from their least to their largest value.
//!
//! An axis of `log10` values ([`Heatmap::log_x`]) is labelled with the values themselves
//! (`log_axis`).

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};

use super::lines::{extent, linear_ticks};
use super::log_axis::{Ticked, log_tick, log_ticks};
use super::{Drawn, LABEL_FONT, TICK_FONT, font, text_width, title_font};
use crate::data::category_index;
use crate::model::Heatmap;
use crate::palette::{self, MISSING};

/// Heat maps are drawn with at most this many cells along each axis (neighbouring cells are
/// merged), which keeps the SVG small; the CSV keeps every cell.
const MAX_CELLS: usize = 256;
/// Widths of a colour bar's parts, pixels: the bar, its tick labels, its label.
const BAR_WIDTH: i32 = 24;
const BAR_TICKS: i32 = 62;
const BAR_LABEL: i32 = 26;
/// The share of cells of a signed map allowed past its colour limit.
const CLIPPED_SHARE: f64 = 0.01;

/// How the values of a continuous map become colours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// Viridis from `lo` to `hi`.
    Sequential { lo: f64, hi: f64 },
    /// The diverging map over `[-limit, limit]`; `clipped` when some values lie beyond.
    Diverging { limit: f64, clipped: bool },
}

impl Scale {
    /// The scale of `map`: its fixed limit if it has one, otherwise [`Scale::of`] its values.
    pub fn of_map(map: &Heatmap) -> Scale {
        let values: Vec<f64> = map.values.iter().flatten().copied().collect();
        match map.colour_limit {
            Some(limit) if limit > 0.0 && limit.is_finite() => {
                let clipped = values.iter().any(|v| v.abs() > limit);
                Scale::Diverging { limit, clipped }
            }
            _ => Scale::of(&values),
        }
    }

    /// The scale of `values` (finite ones), by the rule of the module.
    pub fn of(values: &[f64]) -> Scale {
        let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        match extent(finite.iter().copied()) {
            Some((lo, hi)) if lo < 0.0 && hi > 0.0 => {
                let mut sizes: Vec<f64> = finite.iter().map(|v| v.abs()).collect();
                sizes.sort_by(f64::total_cmp);
                let at = ((1.0 - CLIPPED_SHARE) * (sizes.len() - 1) as f64).round() as usize;
                let largest = sizes[sizes.len() - 1];
                let limit = if sizes[at] > 0.0 { sizes[at] } else { largest };
                Scale::Diverging { limit, clipped: largest > limit }
            }
            Some((lo, hi)) if lo < hi => Scale::Sequential { lo, hi },
            Some((v, _)) => Scale::Sequential { lo: v - 0.5, hi: v + 0.5 },
            None => Scale::Sequential { lo: 0.0, hi: 1.0 },
        }
    }

    /// The colour of `value` (grey when not finite).
    pub fn colour(&self, value: f64) -> RGBColor {
        if !value.is_finite() {
            return MISSING;
        }
        match *self {
            Scale::Sequential { lo, hi } => palette::sequential((value - lo) / (hi - lo)),
            Scale::Diverging { limit, .. } => palette::diverging(value / limit),
        }
    }

    /// The range shown on the colour bar.
    pub fn range(&self) -> Range<f64> {
        match *self {
            Scale::Sequential { lo, hi } => lo..hi,
            Scale::Diverging { limit, .. } => -limit..limit,
        }
    }
}

/// Cell boundaries around the centres `c`: midpoints between neighbours, the ends as far out as
/// the nearest midpoint (a single centre gets a unit-wide cell).
fn edges(c: &[f64]) -> Vec<f64> {
    match c {
        [] => vec![0.0, 1.0],
        [only] => vec![only - 0.5, only + 0.5],
        _ => {
            let mid: Vec<f64> = c.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
            let first = c[0] - (mid[0] - c[0]);
            let last = c[c.len() - 1] + (c[c.len() - 1] - mid[mid.len() - 1]);
            [vec![first], mid, vec![last]].concat()
        }
    }
}

/// The axis range of a map: its outer cell edges, without room around them.
fn cell_range(edges: &[f64]) -> Range<f64> {
    let (lo, hi) = extent(edges.iter().copied()).unwrap_or((0.0, 1.0));
    if lo < hi { lo..hi } else { lo - 0.5..hi + 0.5 }
}

/// Split `0..n` into consecutive groups, at most [`MAX_CELLS`] of them.
fn groups(n: usize) -> Vec<Range<usize>> {
    let size = n.div_ceil(MAX_CELLS).max(1);
    (0..n).step_by(size).map(|start| start..(start + size).min(n)).collect()
}

/// Consecutive ranges of one colour merged into one range.
fn merge_runs(cells: impl Iterator<Item = (Range<usize>, RGBColor)>) -> Vec<(Range<usize>, RGBColor)> {
    let mut runs: Vec<(Range<usize>, RGBColor)> = Vec::new();
    for (range, colour) in cells {
        match runs.last_mut() {
            Some((run, same)) if *same == colour && run.end == range.start => run.end = range.end,
            _ => runs.push((range, colour)),
        }
    }
    runs
}

/// The value drawn for a block of cells: the mean of its finite values (continuous map), or its
/// middle cell's value (categorical map).
fn block_value(map: &Heatmap, rows: &Range<usize>, cols: &Range<usize>) -> f64 {
    let value =
        |r: usize, c: usize| map.values.get(r).and_then(|row| row.get(c)).copied().unwrap_or(f64::NAN);
    if !map.categories.is_empty() {
        return value((rows.start + rows.end) / 2, (cols.start + cols.end) / 2);
    }
    let finite: Vec<f64> =
        rows.clone().flat_map(|r| cols.clone().map(move |c| value(r, c))).filter(|v| v.is_finite()).collect();
    if finite.is_empty() { f64::NAN } else { finite.iter().sum::<f64>() / finite.len() as f64 }
}

/// Draw a heat map into `area`, its colour bar or category names on the right.
pub fn draw<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, map: &Heatmap) -> Drawn
where
    DB::ErrorType: 'static,
{
    let categorical = !map.categories.is_empty();
    let present = present_categories(map);
    let side_width = if categorical {
        let widest = present.iter().map(|&i| text_width(&map.categories[i], TICK_FONT)).fold(0.0, f64::max);
        (widest as u32 + 60).clamp(120, 300)
    } else {
        130
    };
    let (main, side) = area.split_horizontally(area.dim_in_pixel().0.saturating_sub(side_width));
    let xe = edges(&map.x);
    let x = cell_range(&xe);
    let plot_y = if map.log_x {
        let ticks = log_ticks(&x);
        cells(&main, map, &xe, Ticked { axis: x.into(), ticks }, &log_tick)?
    } else {
        let ticks = linear_ticks(&x);
        cells(&main, map, &xe, x, &ticks)?
    };

    // The side panel lines up with the plot area of the map.
    let side_top = side.get_base_pixel().1;
    let top = (plot_y.start - side_top).max(0);
    let bottom = (side.dim_in_pixel().1 as i32 - (plot_y.end - side_top)).max(0);
    let side = side.margin(top, bottom, 8, 10);
    if categorical {
        let missing = map.values.iter().flatten().any(|&v| category_index(v, map.categories.len()).is_none());
        category_legend(&side, &map.categories, &present, missing)
    } else {
        colour_bar(&side, &map.value_label, &Scale::of_map(map))
    }
}

/// The indices of the categories that occur in `map`'s cells, in order.
fn present_categories(map: &Heatmap) -> Vec<usize> {
    let mut present = vec![false; map.categories.len()];
    for &v in map.values.iter().flatten() {
        if let Some(i) = category_index(v, map.categories.len()) {
            present[i] = true;
        }
    }
    (0..present.len()).filter(|&i| present[i]).collect()
}

/// The map's axes, labels and cells in `main`, the x axis `x_axis` (cell edges `xe`) labelled
/// by `x_ticks`. Returns the plot area's pixel rows.
fn cells<DB, X>(
    main: &DrawingArea<DB, Shift>,
    map: &Heatmap,
    xe: &[f64],
    x_axis: X,
    x_ticks: &dyn Fn(&f64) -> String,
) -> Result<Range<i32>, Box<dyn std::error::Error>>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    X: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
{
    let categorical = !map.categories.is_empty();
    let ye = &edges(&map.y);
    let y = cell_range(ye);
    let y_ticks = linear_ticks(&y);
    let mut chart = ChartBuilder::on(main)
        .caption(&map.title, title_font(&map.title, main.dim_in_pixel().0))
        .margin(12)
        .x_label_area_size(55)
        .y_label_area_size(80)
        .build_cartesian_2d(x_axis, y)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(map.x_label.as_str())
        .y_desc(map.y_label.as_str())
        .axis_desc_style(font(LABEL_FONT, FontStyle::Normal))
        .label_style(font(TICK_FONT, FontStyle::Normal))
        .x_label_formatter(x_ticks)
        .y_label_formatter(&y_ticks)
        .draw()?;

    let scale = Scale::of_map(map);
    let colour = |v: f64| -> RGBColor {
        if categorical {
            category_index(v, map.categories.len())
                .map_or(MISSING, |i| palette::category_colour(&map.categories[i], i))
        } else {
            scale.colour(v)
        }
    };
    // Neighbouring cells of one colour in a row are drawn as one rectangle: much smaller SVGs of
    // phase diagrams.
    let (rows, cols) = (groups(map.y.len().min(map.values.len())), groups(map.x.len()));
    chart.draw_series(rows.iter().flat_map(|r| {
        merge_runs(cols.iter().map(|c| (c.clone(), colour(block_value(map, r, c))))).into_iter().map(
            move |(c, colour)| {
                Rectangle::new([(xe[c.start], ye[r.start]), (xe[c.end], ye[r.end])], colour.filled())
            },
        )
    }))?;
    // Hatched categories: three diagonal strokes over each such cell.
    let is_hatched = |v: f64| {
        categorical
            && category_index(v, map.categories.len()).is_some_and(|i| palette::hatched(&map.categories[i]))
    };
    let hatched: Vec<((f64, f64), (f64, f64))> = rows
        .iter()
        .flat_map(|r| cols.iter().map(move |c| (r.clone(), c.clone())))
        .filter(|(r, c)| is_hatched(block_value(map, r, c)))
        .map(|(r, c)| ((xe[c.start], ye[r.start]), (xe[c.end], ye[r.end])))
        .collect();
    chart.draw_series(hatched.iter().flat_map(|&((x0, y0), (x1, y1))| {
        hatch_strokes().map(move |[(u0, v0), (u1, v1)]| {
            let at = |u: f64, v: f64| (x0 + u * (x1 - x0), y0 + v * (y1 - y0));
            PathElement::new(vec![at(u0, v0), at(u1, v1)], palette::HATCH.stroke_width(1))
        })
    }))?;
    Ok(chart.plotting_area().get_pixel_range().1)
}

/// The hatching of a unit square: three strokes parallel to its rising diagonal (`v = u + c`,
/// `c` in -1/2, 0, 1/2), each clipped to the square, as `[(u, v) start, end]`.
fn hatch_strokes() -> impl Iterator<Item = [(f64, f64); 2]> {
    [-0.5f64, 0.0, 0.5]
        .into_iter()
        .map(|c| [(c.min(0.0).abs(), c.max(0.0)), (1.0 - c.max(0.0), 1.0 + c.min(0.0))])
}

/// A vertical colour bar of `scale` with ticks, and `label` beside them reading upwards (as the
/// y axis label does). A clipped diverging scale has pointed ends.
pub fn colour_bar<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, label: &str, scale: &Scale) -> Drawn
where
    DB::ErrorType: 'static,
{
    let range = scale.range();
    let (lo, hi) = (range.start, range.end);
    let clipped = matches!(scale, Scale::Diverging { clipped: true, .. });
    // From the right: the label, the tick labels, the bar; room above and below for pointed ends.
    let (width, height) = (area.dim_in_pixel().0 as i32, area.dim_in_pixel().1 as i32);
    let tip = if clipped { 12 } else { 0 };
    let left = (width - BAR_LABEL - BAR_TICKS - BAR_WIDTH).max(0);
    let inner = area.margin(tip, tip, left, BAR_LABEL);
    let mut bar = ChartBuilder::on(&inner)
        .set_label_area_size(LabelAreaPosition::Right, BAR_TICKS)
        .build_cartesian_2d(0.0..1.0, range.clone())?;
    let ticks = linear_ticks(&range);
    bar.configure_mesh()
        .disable_x_axis()
        .disable_mesh()
        .y_labels(if height < 200 { 5 } else { 9 })
        .label_style(font(TICK_FONT, FontStyle::Normal))
        .y_label_formatter(&ticks)
        .draw()?;
    const STEPS: usize = 128;
    let at = |i: usize| lo + (hi - lo) * i as f64 / STEPS as f64;
    bar.draw_series((0..STEPS).map(|i| {
        Rectangle::new([(0.0, at(i)), (1.0, at(i + 1))], scale.colour(0.5 * (at(i) + at(i + 1))).filled())
    }))?;
    bar.draw_series(std::iter::once(Rectangle::new([(0.0, lo), (1.0, hi)], BLACK.stroke_width(1))))?;
    let (px, _) = bar.plotting_area().get_pixel_range();
    let base = area.get_base_pixel();
    let (left, right) = (px.start - base.0, px.end - base.0);
    if clipped {
        let middle = (left + right) / 2;
        for (apex, base_y, value) in [(0, tip, hi), (height, height - tip, lo)] {
            let points = vec![(left, base_y), (right, base_y), (middle, apex)];
            area.draw(&Polygon::new(points.clone(), scale.colour(value).filled()))?;
            area.draw(&PathElement::new([points, vec![(left, base_y)]].concat(), BLACK.stroke_width(1)))?;
        }
    }
    let style = font(LABEL_FONT, FontStyle::Normal)
        .transform(FontTransform::Rotate270)
        .into_text_style(area)
        .pos(Pos::new(HPos::Center, VPos::Center));
    area.draw(&Text::new(label, (width - BAR_LABEL / 2, height / 2), style))?;
    Ok(())
}

/// The legend entry of cells without a category (a sweep's points not computed yet).
const MISSING_NAME: &str = "not computed";

/// One coloured square and name per category of `present` (indices into `categories`), top to
/// bottom, and one for cells without a category if there are any (`missing`).
fn category_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    categories: &[String],
    present: &[usize],
    missing: bool,
) -> Drawn
where
    DB::ErrorType: 'static,
{
    let entries = present
        .iter()
        .map(|&i| (categories[i].as_str(), palette::category_colour(&categories[i], i)))
        .chain(missing.then_some((MISSING_NAME, MISSING)));
    for (row, (name, colour)) in entries.enumerate() {
        let top = 4 + 26 * row as i32;
        let swatch = [(0, top), (18, top + 18)];
        area.draw(&Rectangle::new(swatch, colour.filled()))?;
        if palette::hatched(name) {
            for [(u0, v0), (u1, v1)] in hatch_strokes() {
                // Rising in the picture: pixel rows grow downwards.
                let at = |u: f64, v: f64| ((18.0 * u).round() as i32, top + 18 - (18.0 * v).round() as i32);
                area.draw(&PathElement::new(vec![at(u0, v0), at(u1, v1)], palette::HATCH.stroke_width(1)))?;
            }
        }
        area.draw(&Rectangle::new(swatch, BLACK.mix(0.5).stroke_width(1)))?;
        area.draw(&Text::new(name, (26, top + 1), font(TICK_FONT, FontStyle::Normal)))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_surround_their_centres() {
        assert_eq!(edges(&[0.0, 1.0, 3.0]), vec![-0.5, 0.5, 2.0, 4.0]);
        assert_eq!(edges(&[2.0]), vec![1.5, 2.5]);
        let g = groups(1000);
        assert!(g.len() <= MAX_CELLS && g[0] == (0..4) && g.last().unwrap().end == 1000);
        assert_eq!(groups(3), vec![0..1, 1..2, 2..3]);
        let (a, b) = (RGBColor(1, 2, 3), RGBColor(4, 5, 6));
        let merged = merge_runs([(0..1, a), (1..2, a), (2..4, b), (4..5, a)].into_iter());
        assert_eq!(merged, vec![(0..2, a), (2..4, b), (4..5, a)]);
    }

    #[test]
    fn legends_name_the_categories_present_and_a_figure_may_fix_the_colour_scale() {
        let map = Heatmap {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            x: vec![0.0, 1.0],
            y: vec![0.0, 1.0],
            values: vec![vec![2.0, 0.0], vec![2.0, f64::NAN]],
            categories: vec!["transmitted".into(), "reflected".into(), "trapped".into()],
            value_label: String::new(),
            log_x: false,
            colour_limit: None,
        };
        assert_eq!(present_categories(&map), vec![0, 2]);
        // Two domains at -+0.28 and one rotor far out: the figure's scale, clipped.
        let image = Heatmap {
            values: vec![vec![0.28, -0.28], vec![-1.1, 0.28]],
            categories: Vec::new(),
            colour_limit: Some(0.35),
            ..map
        };
        assert_eq!(Scale::of_map(&image), Scale::Diverging { limit: 0.35, clipped: true });
        assert_eq!(Scale::of_map(&Heatmap { colour_limit: None, ..image }).range(), -1.1..1.1);
    }

    #[test]
    fn signed_maps_are_diverging_around_zero_with_limits_from_the_data() {
        // Two domains at -+0.28 and a few cells of a rotor swinging to -1.2.
        let mut values: Vec<f64> = (0..1000).map(|i| if i % 2 == 0 { 0.28 } else { -0.28 }).collect();
        values.extend([-1.2, -1.1, -0.9, f64::NAN]);
        let scale = Scale::of(&values);
        assert_eq!(scale, Scale::Diverging { limit: 0.28, clipped: true });
        assert_eq!(scale.colour(0.0), palette::diverging(0.0));
        assert_eq!(scale.colour(0.28), palette::diverging(1.0));
        assert_eq!(scale.colour(-5.0), palette::diverging(-1.0));
        assert_eq!(scale.colour(f64::NAN), MISSING);
        // One sign: viridis over the data.
        assert_eq!(Scale::of(&[0.5, 2.0, 1.0]), Scale::Sequential { lo: 0.5, hi: 2.0 });
        assert_eq!(Scale::of(&[3.0]), Scale::Sequential { lo: 2.5, hi: 3.5 });
        // Both signs, nothing extreme: the limit is the largest size and nothing is clipped.
        assert_eq!(Scale::of(&[-1.0, 0.5, 1.0]), Scale::Diverging { limit: 1.0, clipped: false });
    }
}
