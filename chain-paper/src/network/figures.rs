//! The `network draw` and `network bands` figures of a cell.

use std::f64::consts::{PI, TAU};

use chain_network::bloch::{self, PathPoint};
use chain_network::counts::null_spaces;
use chain_network::faer::Mat;
use chain_network::linalg::hermitian_eigen;
use chain_network::patch::{Boundary, Patch};
use chain_network::strip::{DEFAULT_Q, Strip, strip_frequencies, strip_modes};
use chain_network::winding::determinant;
use chain_network::{Cell, NetworkError};

use super::NetworkDrawing;
use crate::model::{Chart, Figure, Heatmap, Panel, Quantity, Series, Style};

/// Samples of the zone per direction for the phase of `det Q(k)`.
const ZONE: usize = 81;
/// Cells across the strip of the spectrum, and wave numbers sampled.
const STRIP_CELLS: usize = 16;
const STRIP_QS: usize = 61;
/// Bands of the strip shown (the lowest).
const STRIP_BANDS: usize = 12;

/// The bands of `cell` along `path` (`samples` per segment): one curve per band.
pub fn bands_figure(
    cell: &Cell,
    name: &str,
    path: &[PathPoint],
    samples: usize,
) -> Result<Figure, NetworkError> {
    let bands = bloch::bands(cell, path, samples)?;
    let count = bands.frequencies.first().map_or(0, Vec::len);
    let series = (0..count)
        .map(|n| {
            let points = bands.distance.iter().zip(&bands.frequencies).map(|(&s, w)| (s, w[n])).collect();
            Series::new(Quantity::Parameter { index: n, of: count }, "", points, Style::Line)
        })
        .collect();
    let corners: Vec<String> = bands.ticks.iter().map(|(s, l)| format!("{l} at {s:.3}")).collect();
    let panel = Panel::new(
        format!(
            "bands of {name} along {}",
            path.iter().map(|p| p.label.as_str()).collect::<Vec<_>>().join("-")
        ),
        "distance along the path |k| (1/length)",
        "ω (unit masses and spring constants)",
        series,
    );
    Ok(Figure {
        label: "fig:network-bands",
        caption: format!(
            "Bands ω_n(k) = sqrt(eig Q(k)^H K Q(k)) of {name}, {} bands, {samples} samples per segment; corners: {}.",
            count,
            corners.join(", ")
        ),
        panels: vec![Chart::Lines(panel)],
        rows: Vec::new(),
    })
}

/// The overview of a cell: a patch with its unit cell, the phase of `det Q(k)` over the zone (or
/// the lowest frequency, for a cell that is not square), a strip's spectrum with its edge zero
/// modes (two dimensions), and the zero mode of a free patch most localized on its low edge.
pub fn cell_figure(cell: &Cell, name: &str) -> Result<Figure, NetworkError> {
    let two = cell.dimension() == 2;
    let mut panels: Vec<Chart> = Vec::new();
    let shown = if two { [3, 3] } else { [6, 1] };
    let patch = Patch::new(cell, shown, Boundary::Free)?;
    panels.push(
        NetworkDrawing::of_patch(
            format!("{name}: {} x {} free patch, cell (0, 0) dashed", shown[0], shown[1]),
            &patch,
        )
        .into(),
    );
    panels.push(zone_panel(cell)?);
    if two {
        panels.extend(strip_panels(cell)?);
    }
    panels.push(zero_mode_panel(cell, name)?);
    Ok(Figure {
        label: "fig:network-cell",
        caption: format!(
            "{name}: {} nodes, {} degrees of freedom, {} bonds per cell; the zone plot uses k.a_i from 0 to 2π{}.",
            cell.nodes().len(),
            cell.dof(),
            cell.bonds().len(),
            if two {
                format!("; the strip is periodic along a1, {STRIP_CELLS} cells wide along a2")
            } else {
                String::new()
            }
        ),
        panels,
        rows: Vec::new(),
    })
}

/// `arg det Q(k)` over the zone for a square cell, else the lowest frequency.
fn zone_panel(cell: &Cell) -> Result<Chart, NetworkError> {
    let square = cell.bonds().len() == cell.dof();
    let grid: Vec<f64> = (0..ZONE).map(|i| TAU * i as f64 / (ZONE - 1) as f64).collect();
    let value = |t1: f64, t2: f64| -> Result<f64, NetworkError> {
        let q = bloch::compatibility(cell, [t1, t2]);
        if square {
            let d = determinant(&q);
            Ok(d.im.atan2(d.re))
        } else {
            Ok(bloch::frequencies(cell, [t1, t2])?.first().copied().unwrap_or(0.0))
        }
    };
    if cell.dimension() == 1 {
        if square {
            // det Q(k) as k.a1 runs over the zone: a closed curve whose turns around the origin
            // are the winding number.
            let fine: Vec<f64> = (0..=720).map(|i| TAU * i as f64 / 720.0).collect();
            let curve: Vec<(f64, f64)> = fine
                .iter()
                .map(|&t| {
                    let d = determinant(&bloch::compatibility(cell, [t, 0.0]));
                    (d.re, d.im)
                })
                .collect();
            return Ok(Chart::Lines(Panel::new(
                "det Q(k) for k.a1 from 0 to 2π: its turns around 0 are the winding",
                "Re det Q",
                "Im det Q",
                vec![
                    Series::new(Quantity::Lattice, "det Q(k)", curve, Style::Line),
                    Series::new(Quantity::Reference, "origin", vec![(0.0, 0.0)], Style::Points),
                ],
            )));
        }
        let points: Result<Vec<(f64, f64)>, NetworkError> =
            grid.iter().map(|&t| Ok((t, value(t, 0.0)?))).collect();
        return Ok(Chart::Lines(Panel::new(
            "lowest frequency",
            "k.a1 (rad)",
            "ω",
            vec![Series::new(Quantity::Lattice, "", points?, Style::Line)],
        )));
    }
    let mut values = Vec::with_capacity(ZONE);
    for &t2 in &grid {
        values.push(grid.iter().map(|&t1| value(t1, t2)).collect::<Result<Vec<f64>, _>>()?);
    }
    Ok(Chart::Heat(Heatmap {
        title: if square {
            "arg det Q(k) over the zone".into()
        } else {
            "lowest frequency over the zone".into()
        },
        x_label: "k.a1 (rad)".into(),
        y_label: "k.a2 (rad)".into(),
        x: grid.clone(),
        y: grid,
        values,
        categories: Vec::new(),
        value_label: if square { "arg det Q (rad)".into() } else { "ω".into() },
        log_x: false,
        // A phase lives on [-π, π]: the scale is fixed there, not by the values drawn.
        colour_limit: square.then_some(std::f64::consts::PI),
    }))
}

/// The spectrum of a strip periodic along a1 against `q = k.a1`, and its edge zero modes.
fn strip_panels(cell: &Cell) -> Result<Vec<Chart>, NetworkError> {
    let qs: Vec<f64> = (0..STRIP_QS).map(|i| -PI + TAU * i as f64 / (STRIP_QS - 1) as f64).collect();
    let mut bands: Vec<Vec<(f64, f64)>> = vec![Vec::new(); STRIP_BANDS];
    let (mut low, mut high) = (Vec::new(), Vec::new());
    for &q in &qs {
        let strip = Strip { along: 0, cells: STRIP_CELLS, q };
        let w = strip_frequencies(cell, &strip)?;
        for (n, band) in bands.iter_mut().enumerate() {
            if let Some(&x) = w.get(n) {
                band.push((q, x));
            }
        }
        if q.abs() > 1e-9 {
            let modes = strip_modes(cell, &strip)?;
            low.push((q, modes.low as f64));
            high.push((q, modes.high as f64));
        }
    }
    let series = bands
        .into_iter()
        .enumerate()
        .map(|(n, points)| {
            Series::new(Quantity::Parameter { index: n, of: STRIP_BANDS }, "", points, Style::Points)
        })
        .collect();
    let spectrum =
        Panel::new(format!("strip spectrum, lowest {STRIP_BANDS} bands"), "q = k.a1 (rad)", "ω", series);
    let edges = Panel::new(
        format!("zero modes per edge (default q = {DEFAULT_Q})"),
        "q = k.a1 (rad)",
        "zero modes",
        vec![
            Series::new(Quantity::Kink, "low edge (cell 0 along a2)", low, Style::LinePoints),
            Series::new(Quantity::Antikink, "high edge (cell M-1)", high, Style::Dashed),
        ],
    );
    Ok(vec![Chart::Lines(spectrum), Chart::Lines(edges)])
}

/// The zero mode of a free patch most localized at its low edge along the last lattice vector:
/// the eigenvector of the cell-index operator restricted to the zero modes with the smallest
/// centre.
fn zero_mode_panel(cell: &Cell, name: &str) -> Result<Chart, NetworkError> {
    let n = if cell.dimension() == 2 { [6, 6] } else { [10, 1] };
    let patch = Patch::new(cell, n, Boundary::Free)?;
    let null = null_spaces(&patch)?;
    let z = &null.zero_modes;
    let axis = cell.dimension() - 1;
    let index: Vec<f64> = (0..patch.dof())
        .map(|col| {
            let c = col / cell.dof();
            (if axis == 1 { c / n[0] } else { c % n[0] }) as f64
        })
        .collect();
    let x = Mat::<f64>::from_fn(z.ncols(), z.ncols(), |a, b| {
        (0..z.nrows()).map(|r| z[(r, a)] * z[(r, b)] * index[r]).sum()
    });
    let (centres, rotation) = hermitian_eigen("position operator on the zero modes", x.as_ref())?;
    let mode: Vec<f64> =
        (0..z.nrows()).map(|r| (0..z.ncols()).map(|a| z[(r, a)] * rotation[(a, 0)]).sum()).collect();
    let drawing = NetworkDrawing::of_patch(
        format!(
            "{name}: the zero mode of lowest centre along a{} ({} zero modes; centre at cell {:.2})",
            axis + 1,
            z.ncols(),
            centres.first().copied().unwrap_or(f64::NAN)
        ),
        &patch,
    )
    .with_mode(&patch, &mode);
    Ok(drawing.into())
}
