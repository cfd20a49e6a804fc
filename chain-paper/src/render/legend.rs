//! Legends: inside the plot where no data are, outside it (on the right) when every place inside
//! would cover some.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{Drawn, TICK_FONT, font, text_width};
use crate::model::Style;

/// One entry: a sample of the series and its name.
pub struct Entry {
    pub name: String,
    pub style: Style,
    pub colour: RGBColor,
}

/// Inner padding of the legend box, pixels.
const PADDING: f64 = 8.0;
/// Width of an entry's sample.
const MARK: f64 = 24.0;
/// Radius of [`Style::Rings`]' circles, pixels: clear of a line-and-dots series' dots (radius 3).
pub const RINGS: u32 = 6;
/// Distance of the box from the plot's edges.
pub const GAP: f64 = 6.0;

/// The pixel size of the legend box of `entries`.
pub fn size(entries: &[Entry]) -> (f64, f64) {
    let widest = entries.iter().map(|e| text_width(&e.name, TICK_FONT)).fold(0.0, f64::max);
    (2.0 * PADDING + MARK + 8.0 + widest, 2.0 * PADDING + 1.35 * TICK_FONT * entries.len() as f64)
}

/// Where the legend goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Place {
    /// Inside the plot, its top-left corner at these plot pixels (from the plot's top-left).
    Inside(f64, f64),
    /// Outside the plot, on its right.
    Outside,
}

/// Of eight places along the plot's edges (upper right first), the first whose box covers none
/// of the curves; [`Place::Outside`] if each covers some. `curves` are in plot fractions
/// (`0..1`, y up), each with whether it is drawn as a line: lines are sampled every 2 pixels,
/// dots where they are, with the dot's radius around them. `plot` is the plot's pixel size.
pub fn place(curves: &[(Vec<(f64, f64)>, bool)], plot: (f64, f64), size: (f64, f64)) -> Place {
    let start = |at: u8, size: f64, extent: f64| match at {
        0 => GAP,
        1 => 0.5 * (extent - size),
        _ => extent - size - GAP,
    };
    if size.0 + 2.0 * GAP > plot.0 || size.1 + 2.0 * GAP > plot.1 {
        return Place::Outside;
    }
    let places = [(2, 0), (0, 0), (2, 2), (0, 2), (2, 1), (0, 1), (1, 0), (1, 2)];
    let boxes: Vec<(f64, f64)> =
        places.iter().map(|&(h, v)| (start(h, size.0, plot.0), start(v, size.1, plot.1))).collect();
    let mut free = vec![true; boxes.len()];
    // A dot of radius 3 or a line of width 2 covers this far around its centre.
    let reach = 4.0;
    let mut sample = |(x, y): (f64, f64)| {
        for (ok, &(x0, y0)) in free.iter_mut().zip(&boxes) {
            if (x0 - reach..=x0 + size.0 + reach).contains(&x)
                && (y0 - reach..=y0 + size.1 + reach).contains(&y)
            {
                *ok = false;
            }
        }
    };
    for (curve, line) in curves {
        let pixels: Vec<(f64, f64)> =
            curve.iter().map(|&(fx, fy)| (fx * plot.0, (1.0 - fy) * plot.1)).collect();
        pixels.iter().for_each(|&p| sample(p));
        for pair in pixels.windows(2).filter(|_| *line) {
            let (a, b) = (pair[0], pair[1]);
            let steps = ((b.0 - a.0).hypot(b.1 - a.1) / 2.0).ceil().clamp(1.0, 5000.0) as usize;
            (1..steps).for_each(|k| {
                let t = k as f64 / steps as f64;
                sample((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            });
        }
    }
    match free.iter().position(|&ok| ok) {
        Some(i) => Place::Inside(boxes[i].0, boxes[i].1),
        None => Place::Outside,
    }
}

/// Draw the legend box with its top-left corner at `at` (pixels of `area`).
pub fn draw<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, at: (i32, i32), entries: &[Entry]) -> Drawn
where
    DB::ErrorType: 'static,
{
    let (w, h) = size(entries);
    let corner = (at.0 + w.round() as i32, at.1 + h.round() as i32);
    area.draw(&Rectangle::new([at, corner], WHITE.mix(0.92).filled()))?;
    area.draw(&Rectangle::new([at, corner], BLACK.mix(0.4).stroke_width(1)))?;
    let row = 1.35 * TICK_FONT;
    for (k, entry) in entries.iter().enumerate() {
        let y = at.1 + (PADDING + row * (k as f64 + 0.5)).round() as i32;
        let x = at.0 + PADDING as i32;
        mark(area, (x, y), entry)?;
        let style = font(TICK_FONT, FontStyle::Normal).into_text_style(area).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Left,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        area.draw(&Text::new(entry.name.as_str(), (x + MARK as i32 + 8, y), style))?;
    }
    Ok(())
}

/// An entry's sample: a short line, dashed line, dot, open circle, or line with a dot, its left
/// end at `at`.
fn mark<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, (x, y): (i32, i32), entry: &Entry) -> Drawn
where
    DB::ErrorType: 'static,
{
    let line = entry.colour.stroke_width(2);
    let m = MARK as i32;
    let segments: &[(i32, i32)] = match entry.style {
        Style::Line | Style::LinePoints => &[(0, m)],
        Style::Dashed => &[(0, 9), (15, m)],
        Style::Points | Style::OpenPoints | Style::Rings => &[],
    };
    for &(from, to) in segments {
        area.draw(&PathElement::new(vec![(x + from, y), (x + to, y)], line))?;
    }
    match entry.style {
        Style::Points | Style::LinePoints => {
            area.draw(&Circle::new((x + m / 2, y), 3, entry.colour.filled()))?
        }
        Style::OpenPoints => {
            area.draw(&Circle::new((x + m / 2, y), 4, WHITE.filled()))?;
            area.draw(&Circle::new((x + m / 2, y), 4, entry.colour.stroke_width(2)))?;
        }
        Style::Rings => area.draw(&Circle::new((x + m / 2, y), RINGS, entry.colour.stroke_width(2)))?,
        Style::Line | Style::Dashed => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_legend_goes_where_no_data_are_or_outside() {
        let plot = (600.0, 400.0);
        let size = (150.0, 60.0);
        // A rising diagonal leaves the upper left and lower right free: upper right is taken,
        // upper left is the first free place.
        let diagonal = vec![(vec![(0.0, 0.0), (1.0, 1.0)], true)];
        assert_eq!(place(&diagonal, plot, size), Place::Inside(GAP, GAP));
        // Points along the top row: the lower right is free.
        let top: Vec<(f64, f64)> = (0..=20).map(|i| (f64::from(i) / 20.0, 0.98)).collect();
        assert_eq!(
            place(&[(top, false)], plot, size),
            Place::Inside(600.0 - 150.0 - GAP, 400.0 - 60.0 - GAP)
        );
        // Data everywhere: outside.
        let everywhere: Vec<(f64, f64)> = (0..=40)
            .flat_map(|i| (0..=40).map(move |j| (f64::from(i) / 40.0, f64::from(j) / 40.0)))
            .collect();
        assert_eq!(place(&[(everywhere, false)], plot, size), Place::Outside);
        // A legend larger than the plot: outside.
        assert_eq!(place(&[], (100.0, 50.0), size), Place::Outside);
    }
}
