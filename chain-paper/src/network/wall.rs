//! The figure of demonstration 2 (issue 36): a domain wall between two polarizations moving
//! through coupled Kane-Lubensky chains ([`chain_network::motion::wall`]). Four frames of the
//! lattice (rotor arms coloured by their tilt `theta / theta_bar`: blue `+theta_bar`, red
//! `-theta_bar`), each chain's wall position against time with the fitted line, and the
//! energies; [`write_gif`] writes every frame as an animated GIF.

use std::path::Path;

use chain_network::motion::MotionError;
use chain_network::motion::wall::{CoupledChains, MovingWall, Polarized};
use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbaImage};

use crate::model::{Chart, Figure, Panel, Quantity, Series, Style};
use crate::network::NetworkDrawing;
use crate::output::write_atomic;
use crate::render::{RenderError, pixels};

/// The lattice at sample `k` of `run`: pivots `(i a, j h)`, tips from the chain angles, the
/// chains' springs and the inter-chain springs, arms coloured by `theta / theta_bar`.
pub fn wall_frame(c: &CoupledChains, run: &MovingWall, k: usize) -> NetworkDrawing {
    let theta = &run.theta[k];
    let (a, r, h) = (c.spacing, c.rotor_length, c.row_spacing);
    let tip = |j: usize, i: usize| {
        let up = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
        let t = theta[j][i];
        (i as f64 * a + r * t.sin(), j as f64 * h + up * r * t.cos())
    };
    let mut d = NetworkDrawing { title: format!("t = {:.0}", run.times[k]), ..NetworkDrawing::default() };
    for (j, row) in theta.iter().enumerate() {
        for (i, &t) in row.iter().enumerate() {
            d.arms.push(((i as f64 * a, j as f64 * h), tip(j, i)));
            d.arm_tilts.push(t / c.theta_bar);
            d.nodes.push(tip(j, i));
            if i + 1 < row.len() {
                d.bonds.push((tip(j, i), tip(j, i + 1)));
            }
            if j + 1 < theta.len() {
                d.bonds.push((tip(j, i), tip(j + 1, i)));
            }
        }
    }
    d
}

/// `N0 / S, winding n` of a side's uniform state, for the caption.
fn describe(p: &Polarized) -> String {
    format!(
        "tilt {:+.2}: N0 = {}, S = {}, floppy mode at rotor {:.1}, winding {}",
        p.tilt, p.counts.zero_modes, p.counts.self_stresses, p.floppy_mode_centre, p.winding.winding[0]
    )
}

/// The figure of `chain`'s run, and the run (for a caller that prints its numbers or writes the
/// GIF).
pub fn wall_figure(c: &CoupledChains) -> Result<(Figure, MovingWall), MotionError> {
    let run = c.run()?;
    let last = run.times.len() - 1;
    let mut panels: Vec<Chart> =
        [0, last / 3, (2 * last) / 3, last].iter().map(|&k| Chart::Network(wall_frame(c, &run, k))).collect();
    let mut walls: Vec<Series> = (0..c.chains)
        .map(|j| {
            let points = run.times.iter().zip(&run.walls).map(|(&t, w)| (t, w[j])).collect();
            let name = if j == 0 { format!("walls of the {} chains", c.chains) } else { String::new() };
            Series::new(Quantity::Kink, name, points, Style::Points)
        })
        .collect();
    let (t0, t1) = (run.times[0], run.times[last]);
    let fit = run.fit;
    walls.push(Series::new(
        Quantity::Fit,
        format!("fit: {:.4} rotors per unit time", fit.slope),
        vec![(t0, fit.intercept + fit.slope * t0), (t1, fit.intercept + fit.slope * t1)],
        Style::Line,
    ));
    panels.push(Chart::Lines(Panel::new(
        "wall position of each chain (Appendix C)",
        "time t (sqrt(M/k))",
        "wall position (rotors)",
        walls,
    )));
    let series = |q, name: &str, values: &[f64]| {
        Series::new(q, name, run.times.iter().copied().zip(values.iter().copied()).collect(), Style::Line)
    };
    let total: Vec<f64> = run.kinetic.iter().zip(&run.potential).map(|(k, p)| k + p).collect();
    panels.push(Chart::Lines(Panel::new(
        "energies",
        "time t (sqrt(M/k))",
        "energy (k a^2)",
        vec![
            series(Quantity::Reference, "total", &total),
            series(Quantity::Trajectory, "kinetic", &run.kinetic),
            series(Quantity::Potential, "potential", &run.potential),
            series(Quantity::Spring, "of which inter-chain springs", &run.coupling_energy),
        ],
    )));
    let spread = run.spread().into_iter().fold(0.0, f64::max);
    let (b, a) = (&run.crossed_before, &run.crossed_after);
    let caption = format!(
        "A domain wall moving through {} coupled Kane-Lubensky chains of {} rotors (a = {}, r = {}, theta_bar = {}, \
         chains h = {} apart, inter-chain springs k_c = {} at rest when two rotors share an angle): the chain's \
         zero-energy kink launched on every chain with v0 = {} (walls staggered by {} rotors), velocity Verlet, no \
         damping. Arms coloured by theta / theta_bar (blue +, red -). The wall moves at {:.4} rotors per unit time; \
         the chains' walls stay within {:.2} rotors of each other. Rotors {}..{} that it crossed went from mean tilt \
         {:+.3} to {:+.3}: before, {}; after, {}. Counts of the free {} x {} patch of each uniform state (its 2D \
         cell is over-constrained, 2 rotors and 4 springs); winding of the row cell along the chains.",
        c.chains,
        c.rotors(),
        c.spacing,
        c.rotor_length,
        c.theta_bar,
        c.row_spacing,
        c.coupling,
        c.speed,
        c.stagger,
        fit.slope,
        spread,
        b.from,
        b.to,
        b.mean_tilt,
        a.mean_tilt,
        describe(&b.uniform),
        describe(&a.uniform),
        c.cells,
        c.chains,
    );
    Ok((Figure { label: "fig:network-wall", caption, panels, rows: Vec::new() }, run))
}

/// Every sample of `run` as a frame of an animated GIF at `path` (written atomically), one
/// frame every `delay_ms`, looping; the frames cropped to what is drawn in any of them (the title
/// and the lattice), white gaps inside shortened to `2 GAP` rows. Returns the file's size in bytes.
pub fn write_gif(
    c: &CoupledChains,
    run: &MovingWall,
    path: &Path,
    delay_ms: u32,
) -> Result<usize, RenderError> {
    let mut rasters = Vec::with_capacity(run.times.len());
    // Rows drawn (not white) in any frame; every frame has the same size.
    let mut drawn: Vec<bool> = Vec::new();
    for k in 0..run.times.len() {
        let figure = Figure {
            label: "fig:network-wall",
            caption: String::new(),
            panels: vec![Chart::Network(wall_frame(c, run, k))],
            rows: Vec::new(),
        };
        let (width, height, rgb) = pixels(&figure, path)?;
        drawn.resize(height as usize, false);
        for (y, row) in rgb.chunks_exact(3 * width as usize).enumerate() {
            drawn[y] |= row.iter().any(|&v| v < 250);
        }
        rasters.push((width, rgb));
    }
    let rows = kept_rows(&drawn);
    let mut frames = Vec::with_capacity(rasters.len());
    for (width, rgb) in rasters {
        let image = RgbaImage::from_fn(width, rows.len() as u32, |x, y| {
            let i = 3 * (rows[y as usize] * width as usize + x as usize);
            image::Rgba([rgb[i], rgb[i + 1], rgb[i + 2], 255])
        });
        frames.push(Frame::from_parts(image, 0, 0, Delay::from_numer_denom_ms(delay_ms, 1)));
    }
    let mut bytes = Vec::new();
    {
        let mut encoder = GifEncoder::new_with_speed(&mut bytes, 10);
        let encode = |e| RenderError::Encode { path: path.to_owned(), source: e };
        encoder.set_repeat(Repeat::Infinite).map_err(encode)?;
        encoder.encode_frames(frames).map_err(encode)?;
    }
    write_atomic(path, &bytes)?;
    Ok(bytes.len())
}

/// White rows kept beside a drawn one: the margin around the drawing and half of a gap kept.
const GAP: usize = 10;

/// The rows of a frame to keep: those within `GAP` rows of a drawn row (all rows if none is).
fn kept_rows(drawn: &[bool]) -> Vec<usize> {
    let n = drawn.len();
    // Distance to the nearest drawn row above and below, in two passes.
    let mut near = vec![usize::MAX; n];
    let mut last = None;
    for y in 0..n {
        if drawn[y] {
            last = Some(y);
        }
        near[y] = last.map_or(usize::MAX, |l| y - l);
    }
    let mut next = None;
    for y in (0..n).rev() {
        if drawn[y] {
            next = Some(y);
        }
        near[y] = near[y].min(next.map_or(usize::MAX, |t| t - y));
    }
    let kept: Vec<usize> = (0..n).filter(|&y| near[y] <= GAP).collect();
    if kept.is_empty() { (0..n).collect() } else { kept }
}

#[cfg(test)]
mod tests {
    use super::{GAP, kept_rows};

    /// A drawn row, a gap of 40 white rows, three drawn rows, with 5 white rows at either edge:
    /// the edges are kept (within `GAP`), the gap keeps `GAP` rows beside each side.
    #[test]
    fn long_white_gaps_are_shortened_and_margins_kept() {
        let mut drawn = vec![false; 5];
        drawn.push(true);
        drawn.extend([false; 40]);
        drawn.extend([true; 3]);
        drawn.extend([false; 5]);
        let kept = kept_rows(&drawn);
        let expected: Vec<usize> = (0..=5 + GAP).chain(46 - GAP..drawn.len()).collect();
        assert_eq!(kept, expected);
        assert_eq!(kept.len(), 5 + 1 + 2 * GAP + 3 + 5);
        assert_eq!(kept_rows(&[false; 4]), vec![0, 1, 2, 3]);
    }
}
