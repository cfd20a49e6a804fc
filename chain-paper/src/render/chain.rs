//! Drawings of the chain ([`ChainDrawing`]) at equal scale in x and y: springs as tubes coloured
//! by their stretch on the diverging map centred on zero (white: at rest) with a colour bar (or,
//! when every spring is at rest, the words "springs at rest" in its place: a scale would span
//! only the rounding of the lengths),
//! impurity springs outlined in their colour, black rotor arms from pivot crosses to blue tips,
//! green arrows for a mode's displacements, green bars for a tensional mode, and the rotor
//! indices along the bottom.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::heatmap::{Scale, colour_bar};
use super::{Drawn, TICK_FONT, font, title_font};
use crate::model::{ChainDrawing, Quantity};

/// Length of the largest mode arrow, lattice spacings.
const ARROW: f64 = 0.9;
/// Width of the colour bar's column.
const BAR: u32 = 120;

/// Draw `d` into `area`: its title on top, the chain in the middle, the stretch colour bar right.
pub fn draw<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, d: &ChainDrawing) -> Drawn
where
    DB::ErrorType: 'static,
{
    let width = area.dim_in_pixel().0;
    let title = title_font(&d.title, width);
    area.draw(&Text::new(
        d.title.as_str(),
        (width as i32 / 2, 8),
        title.into_text_style(area).pos(Pos::new(HPos::Center, VPos::Top)),
    ))?;
    let (body, side) = area.clone().margin(40, 8, 16, 8).split_horizontally(width.saturating_sub(24 + BAR));

    // The drawing's extent in lattice units, arrows included, with room for the index labels.
    let ends = d
        .tips
        .iter()
        .zip(d.arrows.iter().chain(std::iter::repeat(&(0.0, 0.0))))
        .flat_map(|(&t, &a)| [t, (t.0 + ARROW * a.0, t.1 + ARROW * a.1)]);
    let points: Vec<(f64, f64)> = d.pivots.iter().copied().chain(ends).collect();
    let (x0, x1) =
        points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (y0, y1) =
        points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let (x0, x1, y0, y1) = (x0 - 0.3, x1 + 0.3, y0 - 0.2, y1 + 0.2);
    let label_room = 24.0;
    let (bw, bh) = body.dim_in_pixel();
    let scale = (f64::from(bw) / (x1 - x0)).min((f64::from(bh) - label_room) / (y1 - y0));
    // Centred in the body, y up.
    let (ox, oy) =
        (0.5 * (f64::from(bw) - scale * (x1 - x0)), 0.5 * (f64::from(bh) - label_room - scale * (y1 - y0)));
    let px = |(x, y): (f64, f64)| -> (i32, i32) {
        ((ox + scale * (x - x0)).round() as i32, (oy + scale * (y1 - y)).round() as i32)
    };

    let largest = d.stretch.iter().map(|s| s.abs()).fold(0.0, f64::max);
    // At rest every spring is white whatever the limit.
    let limit = d.stretch_scale.unwrap_or(largest);
    let colours = Scale::Diverging { limit: if limit > 0.0 { limit } else { 1.0 }, clipped: false };
    let tube = (0.11 * scale).clamp(4.0, 12.0) as u32;
    for (j, pair) in d.tips.windows(2).enumerate() {
        let ends = vec![px(pair[0]), px(pair[1])];
        let outline = if d.impurities.contains(&j) {
            Quantity::Impurity.colour().stroke_width(tube + 6)
        } else {
            RGBColor(90, 90, 90).stroke_width(tube + 2)
        };
        body.draw(&PathElement::new(ends.clone(), outline))?;
        body.draw(&PathElement::new(ends, colours.colour(d.stretch[j]).stroke_width(tube)))?;
    }
    for (pair, &t) in d.tips.windows(2).zip(&d.tensions) {
        let width = (t * 2.0 * f64::from(tube)).round() as u32;
        if width > 0 {
            body.draw(&PathElement::new(
                vec![px(pair[0]), px(pair[1])],
                Quantity::Mode.colour().mix(0.85).stroke_width(width),
            ))?;
        }
    }
    let arm = (0.04 * scale).clamp(2.0, 4.0) as u32;
    let dot = (0.09 * scale).clamp(3.0, 9.0) as i32;
    for (&pivot, &tip) in d.pivots.iter().zip(&d.tips) {
        body.draw(&PathElement::new(vec![px(pivot), px(tip)], BLACK.stroke_width(arm)))?;
        let (cx, cy) = px(pivot);
        let s = dot;
        body.draw(&PathElement::new(vec![(cx - s, cy - s), (cx + s, cy + s)], BLACK.stroke_width(2)))?;
        body.draw(&PathElement::new(vec![(cx - s, cy + s), (cx + s, cy - s)], BLACK.stroke_width(2)))?;
        body.draw(&Circle::new(px(tip), dot as u32, Quantity::Rotor.colour().filled()))?;
    }
    for (&tip, &(ax, ay)) in d.tips.iter().zip(&d.arrows) {
        if ax.hypot(ay) * ARROW * scale >= 3.0 {
            arrow(&body, px(tip), px((tip.0 + ARROW * ax, tip.1 + ARROW * ay)))?;
        }
    }
    // Rotor indices under the drawing, every one or every fifth.
    let every = if d.pivots.len() <= 20 { 1 } else { 5 };
    let label_y = (oy + scale * (y1 - y0) + 4.0).round() as i32;
    let style =
        font(TICK_FONT, FontStyle::Normal).into_text_style(&body).pos(Pos::new(HPos::Center, VPos::Top));
    for (j, pivot) in d.pivots.iter().enumerate() {
        let i = d.rotors.start + j;
        if i.is_multiple_of(every) {
            body.draw(&Text::new(format!("{i}"), (px(*pivot).0, label_y), style.clone()))?;
        }
    }
    let side = side.margin(0, label_room as i32, 0, 0);
    if d.at_rest() && d.stretch_scale.is_none() {
        let (w, h) = side.dim_in_pixel();
        let style = font(TICK_FONT, FontStyle::Normal)
            .into_text_style(&side)
            .pos(Pos::new(HPos::Center, VPos::Center));
        for (k, line) in ["springs", "at rest"].iter().enumerate() {
            let y = h as i32 / 2 + (2 * k as i32 - 1) * 10;
            side.draw(&Text::new(*line, (w as i32 / 2, y), style.clone()))?;
        }
        Ok(())
    } else {
        colour_bar(&side, "stretch l − l₀ (a)", &colours)
    }
}

/// A green arrow from `from` to `to` (pixels) with a filled head.
pub(super) fn arrow<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    from: (i32, i32),
    to: (i32, i32),
) -> Drawn
where
    DB::ErrorType: 'static,
{
    let colour = Quantity::Mode.colour();
    let (dx, dy) = (f64::from(to.0 - from.0), f64::from(to.1 - from.1));
    let length = dx.hypot(dy);
    let head = (0.35 * length).clamp(4.0, 11.0);
    let (ux, uy) = (dx / length, dy / length);
    let back = (f64::from(to.0) - head * ux, f64::from(to.1) - head * uy);
    area.draw(&PathElement::new(
        vec![from, (back.0.round() as i32, back.1.round() as i32)],
        colour.stroke_width(3),
    ))?;
    let side = 0.5 * head;
    let corners = vec![
        to,
        ((back.0 - side * uy).round() as i32, (back.1 + side * ux).round() as i32),
        ((back.0 + side * uy).round() as i32, (back.1 - side * ux).round() as i32),
    ];
    area.draw(&Polygon::new(corners, colour.filled()))?;
    Ok(())
}
