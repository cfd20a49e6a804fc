//! The polarization phase diagram of Kane and Lubensky's deformed kagome lattice: `R_T` over a
//! plane `(x1, x2)` at fixed `x3` and `z`, computed through chain-sweep's resumable sweep
//! ([`chain_sweep::run_sweep`], one CSV line per point; `--shard I/N` or `slurm` and
//! `--merge` through chain-sweep's shards and checked merge, as for the scattering diagrams),
//! drawn with the lines where the gap closes.
//!
//! Each point records the windings and `R_T` ([`chain_network::winding::winding`]), or
//! why they are undefined (`gapless`: `det Q` vanishes on every path, the critical lines
//! `x_p = 0` of straight bonds; `weyl`: point zeros between the paths), and the zone's smallest
//! relative gap `min_k sigma_min(Q(k)) / sigma_max(Q(k))` on a grid of the zone without `k = 0`.

use chain_network::cell::ready;
use chain_network::winding::{WindingOptions, winding};
use chain_network::{NetworkError, bloch, linalg};
use chain_sweep::record::{ParseError, Record, expect_fields, format_f64, parse_field};
use chain_sweep::{Grid, ResultRow};

use crate::model::{Chart, Figure, Heatmap};

/// Samples per direction of the zone for the gap: `k . a_i = 2 pi m / GAP_GRID`, every point
/// but `k = 0` (the acoustic zero). The lines `k . a_p = 0` where the critical lattices' gap
/// closes are on the grid.
const GAP_GRID: usize = 12;

/// What the winding of one point was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Windings and `R_T` defined.
    Polarized,
    /// `det Q` vanishes on every path along some direction.
    Gapless,
    /// Paths along some direction disagree: point zeros (Weyl points).
    Weyl,
}

impl Status {
    fn name(self) -> &'static str {
        match self {
            Status::Polarized => "polarized",
            Status::Gapless => "gapless",
            Status::Weyl => "weyl",
        }
    }
}

/// One point of the diagram.
#[derive(Clone, Debug, PartialEq)]
pub struct PolarizationPoint {
    /// Whether `R_T` is defined.
    pub status: Status,
    /// `n1, n2` (0 when undefined).
    pub winding: [i64; 2],
    /// `R_T` in the lattice basis `(a1, a2)` (NaN when undefined).
    pub polarization: [f64; 2],
    /// `min_k sigma_min(Q(k)) / sigma_max(Q(k))` over the gap grid.
    pub gap: f64,
}

impl Record for PolarizationPoint {
    fn header() -> &'static [&'static str] {
        &["status", "n1", "n2", "rt1", "rt2", "gap"]
    }

    fn to_fields(&self) -> Vec<String> {
        vec![
            self.status.name().to_owned(),
            self.winding[0].to_string(),
            self.winding[1].to_string(),
            format_f64(self.polarization[0]),
            format_f64(self.polarization[1]),
            format_f64(self.gap),
        ]
    }

    fn from_fields(fields: &[&str]) -> Result<Self, ParseError> {
        expect_fields(fields, 6)?;
        let status = match fields[0] {
            "polarized" => Status::Polarized,
            "gapless" => Status::Gapless,
            "weyl" => Status::Weyl,
            other => {
                return Err(ParseError::Field {
                    column: "status".into(),
                    value: other.into(),
                    reason: "polarized, gapless or weyl".into(),
                });
            }
        };
        Ok(PolarizationPoint {
            status,
            winding: [parse_field(fields, 1, "n1")?, parse_field(fields, 2, "n2")?],
            polarization: [parse_field(fields, 3, "rt1")?, parse_field(fields, 4, "rt2")?],
            gap: parse_field(fields, 5, "gap")?,
        })
    }
}

/// The diagram's fixed parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiagramParams {
    /// Kane and Lubensky's `x3`.
    pub x3: f64,
    /// Their `z`.
    pub z: f64,
}

impl DiagramParams {
    /// The run label stored in the results file.
    pub fn run_label(&self) -> String {
        format!("deformed kagome R_T over (x1, x2), x3 = {}, z = {}", self.x3, self.z)
    }
}

/// The point `(x1, x2)`.
pub fn compute_point(params: &DiagramParams, x1: f64, x2: f64) -> Result<PolarizationPoint, NetworkError> {
    let cell = ready::deformed_kagome(x1, x2, params.x3, params.z)
        .map_err(|e| NetworkError::Argument { what: "cell", problem: e.to_string() })?;
    let mut gap = f64::INFINITY;
    for i in 0..GAP_GRID {
        for j in 0..GAP_GRID {
            if (i, j) == (0, 0) {
                continue;
            }
            let t = |m: usize| std::f64::consts::TAU * m as f64 / GAP_GRID as f64;
            let q = bloch::compatibility(&cell, [t(i), t(j)]);
            let s = linalg::singular_values("Q(k)", q.as_ref())?;
            gap = gap.min(s.last().copied().unwrap_or(0.0) / s[0]);
        }
    }
    let (status, w, p) = match winding(&cell, &WindingOptions::default()) {
        Ok(w) => (Status::Polarized, [w.winding[0], w.winding[1]], [w.polarization[0], w.polarization[1]]),
        Err(NetworkError::WindingUndefined { .. }) => (Status::Gapless, [0, 0], [f64::NAN, f64::NAN]),
        Err(NetworkError::WeylPoints { .. }) => (Status::Weyl, [0, 0], [f64::NAN, f64::NAN]),
        Err(e) => return Err(e),
    };
    Ok(PolarizationPoint { status, winding: w, polarization: p, gap })
}

/// The names of the polarizations a diagram can show, in legend order.
const POLARIZATIONS: [([i64; 2], &str); 7] = [
    ([0, 0], "R_T = 0"),
    ([1, 0], "R_T = a1"),
    ([-1, 0], "R_T = -a1"),
    ([0, 1], "R_T = a2"),
    ([0, -1], "R_T = -a2"),
    ([1, 1], "R_T = a1 + a2"),
    ([-1, -1], "R_T = -a1 - a2"),
];

/// A point's category name: its polarization, `gapless`, `Weyl points`, or `R_T = (c1, c2)`.
fn category(p: &PolarizationPoint) -> String {
    match p.status {
        Status::Gapless => "gapless".into(),
        Status::Weyl => "Weyl points".into(),
        Status::Polarized => {
            let r = [p.polarization[0].round() as i64, p.polarization[1].round() as i64];
            POLARIZATIONS
                .iter()
                .find(|(v, _)| *v == r)
                .map_or_else(|| format!("R_T = ({}, {})", r[0], r[1]), |(_, name)| (*name).to_owned())
        }
    }
}

/// The figure of a computed diagram: `R_T` by category (the gapless critical lines among them)
/// and the zone's smallest relative gap on a log scale.
pub fn diagram_figure(params: &DiagramParams, grid: &Grid, rows: &[ResultRow<PolarizationPoint>]) -> Figure {
    let (xs, ys) = (grid.xs().to_vec(), grid.ys().to_vec());
    let mut classes = vec![vec![f64::NAN; xs.len()]; ys.len()];
    let mut gaps = vec![vec![f64::NAN; xs.len()]; ys.len()];
    // Only the categories present, polarizations first in legend order: distinct colours.
    let mut names: Vec<String> = rows.iter().map(|(_, _, p)| category(p)).collect();
    let rank =
        |n: &String| POLARIZATIONS.iter().position(|(_, name)| name == n).unwrap_or(POLARIZATIONS.len());
    names.sort_by(|a, b| rank(a).cmp(&rank(b)).then(a.cmp(b)));
    names.dedup();
    for ((i, j), _, p) in rows {
        let c = category(p);
        classes[*j][*i] = names.iter().position(|n| *n == c).map_or(f64::NAN, |k| k as f64);
        gaps[*j][*i] = p.gap.max(1e-17).log10();
    }
    let base = |title: &str| Heatmap {
        title: title.to_owned(),
        x_label: "x1".into(),
        y_label: "x2".into(),
        x: xs.clone(),
        y: ys.clone(),
        values: Vec::new(),
        categories: Vec::new(),
        value_label: String::new(),
        log_x: false,
        colour_limit: None,
    };
    let polar = Heatmap { values: classes, categories: names, ..base("topological polarization R_T") };
    let gap = Heatmap {
        values: gaps,
        value_label: "log10 min_k σ_min(Q)/σ_max(Q)".into(),
        ..base("smallest relative gap over the zone")
    };
    Figure {
        label: "fig:network-diagram",
        caption: format!(
            "Kane-Lubensky deformed kagome at x3 = {}, z = {}: R_T (their eq. 11 predicts Σ_p a_p sign(x_p)/2) over {} x {} points; the gap closes on the critical lines x1 = 0 and x2 = 0 (straight lines of bonds).",
            params.x3,
            params.z,
            xs.len(),
            ys.len()
        ),
        panels: vec![Chart::Heat(polar), Chart::Heat(gap)],
        rows: Vec::new(),
    }
}
