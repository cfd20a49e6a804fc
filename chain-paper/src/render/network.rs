//! Drawings of a network's patch ([`NetworkDrawing`]) at equal scale in x and y: the unit cell
//! dashed, bonds grey, rotor arms black (or coloured by a signed tilt) from pivot crosses, nodes (joints, rotor tips) blue, and
//! a mode's displacements as green arrows.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::chain::arrow;
use super::{Drawn, title_font};
use crate::model::Quantity;
use crate::network::NetworkDrawing;

/// Length of the largest arrow, as a fraction of the drawing's smaller extent.
const ARROW: f64 = 0.08;

/// Draw `d` into `area`: its title on top, the patch below.
pub fn draw<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, d: &NetworkDrawing) -> Drawn
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
    let body = area.clone().margin(TOP, SIDE, SIDE, SIDE);
    let Some(Bounds { x0, x1, y0, y1, extent }) = bounds(d) else {
        return Ok(());
    };
    let arrow_length = ARROW * extent;
    let (bw, bh) = body.dim_in_pixel();
    let scale = (f64::from(bw) / (x1 - x0)).min(f64::from(bh) / (y1 - y0));
    let (ox, oy) = (0.5 * (f64::from(bw) - scale * (x1 - x0)), 0.5 * (f64::from(bh) - scale * (y1 - y0)));
    let px = |(x, y): (f64, f64)| -> (i32, i32) {
        ((ox + scale * (x - x0)).round() as i32, (oy + scale * (y1 - y)).round() as i32)
    };
    if d.cell.len() > 1 {
        let mut outline: Vec<(i32, i32)> = d.cell.iter().map(|&p| px(p)).collect();
        outline.push(outline[0]);
        for pair in outline.windows(2) {
            dashed(&body, pair[0], pair[1])?;
        }
    }
    let line = (0.012 * scale * extent / 10.0).clamp(1.0, 4.0) as u32;
    for &(a, b) in &d.bonds {
        body.draw(&PathElement::new(vec![px(a), px(b)], RGBColor(110, 110, 110).stroke_width(line + 1)))?;
    }
    // Arms coloured by a tilt are the picture: drawn thicker, their pivots small dots, the tips
    // left bare, so dense lattices stay readable.
    let coloured = !d.arm_tilts.is_empty();
    for (i, &(pivot, tip)) in d.arms.iter().enumerate() {
        let colour = d.arm_tilts.get(i).map_or(BLACK, |&t| tilt_colour(t));
        let width = if coloured { 2 * line + 1 } else { line + 1 };
        body.draw(&PathElement::new(vec![px(pivot), px(tip)], colour.stroke_width(width)))?;
        let (cx, cy) = px(pivot);
        if coloured {
            body.draw(&Circle::new((cx, cy), 2, BLACK.filled()))?;
            continue;
        }
        let s = 4;
        body.draw(&PathElement::new(vec![(cx - s, cy - s), (cx + s, cy + s)], BLACK.stroke_width(2)))?;
        body.draw(&PathElement::new(vec![(cx - s, cy + s), (cx + s, cy - s)], BLACK.stroke_width(2)))?;
    }
    let dot = (0.025 * scale * extent / 10.0).clamp(2.0, 7.0) as u32;
    if !coloured {
        for &p in &d.nodes {
            body.draw(&Circle::new(px(p), dot, Quantity::Rotor.colour().filled()))?;
        }
    }
    for &(from, (dx, dy)) in &d.arrows {
        if dx.hypot(dy) * arrow_length * scale >= 3.0 {
            arrow(&body, px(from), px((from.0 + arrow_length * dx, from.1 + arrow_length * dy)))?;
        }
    }
    Ok(())
}

/// Margin above the drawing (its title), pixels.
const TOP: u32 = 40;
/// Margin on the other sides, pixels.
const SIDE: u32 = 12;

/// The region drawn: everything in `d` with a margin of 5 % of the larger extent, plus the longest
/// arrow's length when there are arrows, so arrows at the edge stay inside.
struct Bounds {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    /// The larger extent of what is drawn, before the margin.
    extent: f64,
}

fn bounds(d: &NetworkDrawing) -> Option<Bounds> {
    let mut points = d
        .bonds
        .iter()
        .chain(&d.arms)
        .flat_map(|&(a, b)| [a, b])
        .chain(d.cell.iter().copied())
        .chain(d.nodes.iter().copied())
        .peekable();
    points.peek()?;
    let (x0, x1, y0, y1) = points
        .fold((f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY), |(a, b, c, e), p| {
            (a.min(p.0), b.max(p.0), c.min(p.1), e.max(p.1))
        });
    let extent = (x1 - x0).max(y1 - y0).max(1e-9);
    let arrows = if d.arrows.is_empty() { 0.0 } else { ARROW * extent };
    let pad = 0.05 * extent + arrows;
    Some(Bounds { x0: x0 - pad, x1: x1 + pad, y0: y0 - pad, y1: y1 + pad, extent })
}

/// The height in pixels that `d` fills when drawn `width` pixels wide at equal scale in x and y,
/// title and margins included, at most `max` (a drawing taller than wide is then narrower). A wide
/// lattice gets a short panel instead of white space above and below it.
pub fn natural_height(d: &NetworkDrawing, width: u32, max: u32) -> u32 {
    let Some(b) = bounds(d) else { return max };
    let inner = f64::from(width.saturating_sub(2 * SIDE));
    let height = inner * (b.y1 - b.y0) / (b.x1 - b.x0);
    // `as` saturates a NaN or a huge ratio; the `min` keeps the panel within `max`.
    (TOP + SIDE + height.ceil() as u32).min(max)
}

/// Blue for a tilt of +1, red for -1, through grey at 0 (clamped to `[-1, 1]`).
fn tilt_colour(t: f64) -> RGBColor {
    let t = if t.is_finite() { t.clamp(-1.0, 1.0) } else { 0.0 };
    let (grey, end) =
        ((150.0, 150.0, 150.0), if t >= 0.0 { (20.0, 60.0, 200.0) } else { (210.0, 30.0, 30.0) });
    let mix = |g: f64, e: f64| (g + t.abs() * (e - g)).round() as u8;
    RGBColor(mix(grey.0, end.0), mix(grey.1, end.1), mix(grey.2, end.2))
}

/// A grey dashed line from `a` to `b` (pixels): dashes of 6, gaps of 5.
fn dashed<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, a: (i32, i32), b: (i32, i32)) -> Drawn
where
    DB::ErrorType: 'static,
{
    let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
    let length = dx.hypot(dy);
    let mut s = 0.0;
    while s < length {
        let e = (s + 6.0).min(length);
        let at = |t: f64| {
            (
                (f64::from(a.0) + dx * t / length).round() as i32,
                (f64::from(a.1) + dy * t / length).round() as i32,
            )
        };
        area.draw(&PathElement::new(vec![at(s), at(e)], RGBColor(150, 150, 150).stroke_width(2)))?;
        s += 11.0;
    }
    Ok(())
}
