//! Heat maps and colour bars.
//!
//! A categorical map has one colour per category ([`crate::palette::category_colour`]) and
//! their names beside it. A continuous map of values of both signs (a space-time image of the
//! angles) uses the diverging map centred on zero, symmetric, its limit the 99th percentile of
//! `|value|`: a few extreme cells (a rotor of a trapped antikink swinging far) then cannot wash
//! out the two domains, and the colour bar marks the clipped ends. Other continuous maps use
//! viridis from their least to their largest value.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::lines::{extent, linear_ticks};
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
    let side_width = if categorical {
        let widest = map.categories.iter().map(|c| text_width(c, TICK_FONT)).fold(0.0, f64::max);
        (widest as u32 + 60).clamp(120, 300)
    } else {
        130
    };
    let (main, side) = area.split_horizontally(area.dim_in_pixel().0.saturating_sub(side_width));
    let (xe, ye) = (&edges(&map.x), &edges(&map.y));
    let (x, y) = (cell_range(xe), cell_range(ye));
    let (x_ticks, y_ticks) = (linear_ticks(&x), linear_ticks(&y));
    let mut chart = ChartBuilder::on(&main)
        .caption(&map.title, title_font(&map.title, main.dim_in_pixel().0))
        .margin(12)
        .x_label_area_size(55)
        .y_label_area_size(80)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(map.x_label.as_str())
        .y_desc(map.y_label.as_str())
        .axis_desc_style(font(LABEL_FONT, FontStyle::Normal))
        .label_style(font(TICK_FONT, FontStyle::Normal))
        .x_label_formatter(&x_ticks)
        .y_label_formatter(&y_ticks)
        .draw()?;

    let values: Vec<f64> = map.values.iter().flatten().copied().collect();
    let scale = Scale::of(&values);
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

    // The side panel lines up with the plot area of the map.
    let (_, plot_y) = chart.plotting_area().get_pixel_range();
    let side_top = side.get_base_pixel().1;
    let top = (plot_y.start - side_top).max(0);
    let bottom = (side.dim_in_pixel().1 as i32 - (plot_y.end - side_top)).max(0);
    let side = side.margin(top, bottom, 8, 10);
    if categorical {
        category_legend(&side, &map.categories)
    } else {
        colour_bar(&side, &map.value_label, &scale)
    }
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

/// One coloured square and name per category, top to bottom.
fn category_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, categories: &[String]) -> Drawn
where
    DB::ErrorType: 'static,
{
    for (i, name) in categories.iter().enumerate() {
        let top = 4 + 26 * i as i32;
        let swatch = [(0, top), (18, top + 18)];
        area.draw(&Rectangle::new(swatch, palette::category_colour(name, i).filled()))?;
        area.draw(&Rectangle::new(swatch, BLACK.mix(0.5).stroke_width(1)))?;
        area.draw(&Text::new(name.as_str(), (26, top + 1), font(TICK_FONT, FontStyle::Normal)))?;
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
