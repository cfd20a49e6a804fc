//! Demonstration 1 of issue 36 as a figure (`fig:network-chain`): the paper's chain declared as a
//! rotor network (chain-network's `rotor_chain` cell, a free patch of `n / 2` cells, every bond
//! `k`) and seen in the chain's angles through [`ChainView`] runs the chain's analyses unchanged.
//! Beside the chain code (`RuntimeChain`, its own generated kernels) it gives (a) the same
//! antikink at the Peierls-Nabarro minimum at `theta_bar = 0.58` (paper Sec. V, docs/statics.md
//! §3) and (b) the same domain walls in time for one scattering point of each of the paper's
//! outcomes at `theta_bar = 0.28` (Sec. VI; the robust points of tests/dynamics.rs). The rows
//! give the energies of both and the largest differences.

use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch};
use chain_network::{ChainView, NetworkModel};
use rotor_chain::dynamics::scatter::{Outcome, ScatterSetup, Scattering, scatter};
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::walls::Charge;
use rotor_chain::{ChainModel, RuntimeChain};

use crate::figures::{FigureError, Params};
use crate::model::{Chart, Figure, Panel, Quantity, Row, Series, Style, format_number};

const LABEL: &str = "fig:network-chain";
/// The antikink's angle (paper Sec. V).
const STATICS_THETA_BAR: f64 = 0.58;
/// The scattering angle and points `(charge, v0, k_i / k, expected)`: one robust point of each
/// outcome (tests/dynamics.rs, where Verlet and DOP853 agree).
const SCATTERING_THETA_BAR: f64 = 0.28;
const POINTS: [(Charge, f64, f64, Outcome); 4] = [
    (Charge::Kink, 2.0, 0.5, Outcome::Transmitted),
    (Charge::Kink, 11.0, 0.012, Outcome::Split),
    (Charge::Antikink, 2.0, 0.4, Outcome::Trapped),
    (Charge::Antikink, 6.0, 0.05, Outcome::Reflected),
];

/// The paper's chain of `params` at `theta_bar` declared as a network and seen as a chain, the
/// middle spring's constant `k_i` if given.
pub fn network_chain(params: &Params, theta_bar: f64, k_i: Option<f64>) -> Result<ChainView, FigureError> {
    let cell = ready::rotor_chain(1.0, params.r, theta_bar).map_err(FigureError::on(LABEL))?;
    let patch = Patch::new(&cell, [params.n / 2, 1], Boundary::Free).map_err(FigureError::on(LABEL))?;
    let mut builder = NetworkModel::builder(&patch);
    for bond in 0..patch.bonds().len() {
        builder = builder.spring_constant(bond, params.k);
    }
    if let Some(k_i) = k_i {
        builder = builder.spring_constant(middle(params), k_i);
    }
    ChainView::new(&patch, builder.mass(params.mass).build().map_err(FigureError::on(LABEL))?)
        .map_err(FigureError::on(LABEL))
}

/// The chain code's chain of `params` at `theta_bar`, the middle spring's constant `k_i` if given.
pub fn chain_code(params: &Params, theta_bar: f64, k_i: Option<f64>) -> Result<RuntimeChain, FigureError> {
    let mut builder = RuntimeChain::builder(params.n, params.r, params.k, theta_bar).mass(params.mass);
    if let Some(k_i) = k_i {
        builder = builder.spring_constant(middle(params), k_i);
    }
    builder.build().map_err(FigureError::on(LABEL))
}

/// The impurity spring of Sec. VI: the middle one.
fn middle(params: &Params) -> usize {
    (params.n - 1) / 2
}

/// Every interior wall of a run, `(t, position)`.
fn walls(run: &Scattering) -> Vec<(f64, f64)> {
    let snapshots = &run.run.tracker.snapshots;
    snapshots
        .iter()
        .flat_map(|s| {
            s.walls.iter().zip(&s.at_boundary).filter(|(_, b)| !**b).map(move |(w, _)| (s.time, w.position))
        })
        .collect()
}

/// The largest distance between walls at the same time and index in two runs (sites), and the
/// number of outputs whose wall counts differ.
fn wall_difference(a: &Scattering, b: &Scattering) -> (f64, usize) {
    let (mut largest, mut differ) = (0.0f64, 0);
    for (s, t) in a.run.tracker.snapshots.iter().zip(&b.run.tracker.snapshots) {
        if s.walls.len() != t.walls.len() {
            differ += 1;
            continue;
        }
        for (u, v) in s.walls.iter().zip(&t.walls) {
            largest = largest.max((u.position - v.position).abs());
        }
    }
    (largest, differ)
}

/// One scattering run of `setup` on `model`, its errors at the point.
fn run<M: ChainModel>(model: &M, setup: &ScatterSetup, ratio: f64) -> Result<Scattering, FigureError> {
    scatter(model, setup).map_err(|e| FigureError::new(LABEL, e).at("v0", setup.v0).at("k_i/k", ratio))
}

/// Fig. `fig:network-chain`: the chain code and the same chain declared as a network, side by side.
pub fn chain_as_network(params: &Params) -> Result<Figure, FigureError> {
    // (a) The antikink at the PN minimum.
    let options = AntikinkOptions::default();
    let (view, chain) =
        (network_chain(params, STATICS_THETA_BAR, None)?, chain_code(params, STATICS_THETA_BAR, None)?);
    let ours = peierls_nabarro(&view, &options).map_err(FigureError::on(LABEL))?;
    let theirs = peierls_nabarro(&chain, &options).map_err(FigureError::on(LABEL))?;
    let (min, min_chain) =
        (ours.minimum().map_err(FigureError::on(LABEL))?, theirs.minimum().map_err(FigureError::on(LABEL))?);
    let profile = |theta: &[f64]| theta.iter().enumerate().map(|(i, &t)| (i as f64, t)).collect::<Vec<_>>();
    let largest_angle = min.theta.iter().zip(&min_chain.theta).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let statics = Panel::new(
        format!("(a) antikink at the PN minimum, θ̄ = {STATICS_THETA_BAR}, n = {}", params.n),
        "rotor i",
        "θ_i (rad)",
        vec![
            Series::new(Quantity::Rotor, "chain code", profile(&min_chain.theta), Style::Line),
            Series::new(Quantity::Lattice, "network", profile(&min.theta), Style::Points),
        ],
    );
    // Energies to nine decimals in both columns: the agreement is at 1e-9 relative (issue 36).
    let mut rows = vec![
        Row::words(
            format!("antikink PN minimum energy (M a²/t²), θ̄ = {STATICS_THETA_BAR}, network"),
            &format!("{:.9}", min_chain.energy),
            &format!("{:.9}", min.energy),
            format!("paper column: the chain code's; angles differ by at most {largest_angle:.1e} rad"),
        ),
        Row::words(
            format!("PN barrier (M a²/t²), θ̄ = {STATICS_THETA_BAR}, network"),
            &format!("{:.9}", theirs.barrier),
            &format!("{:.9}", ours.barrier),
            "paper column: the chain code's",
        ),
    ];
    // (b) One scattering point of each outcome: the network's interior walls in time.
    let mut series = Vec::new();
    for (charge, v0, ratio, expected) in POINTS {
        let k_i = Some(ratio * params.k);
        let view = network_chain(params, SCATTERING_THETA_BAR, k_i)?;
        let chain = chain_code(params, SCATTERING_THETA_BAR, k_i)?;
        let setup = ScatterSetup::from_the_right(charge, v0, middle(params));
        let (ours, theirs) = (run(&view, &setup, ratio)?, run(&chain, &setup, ratio)?);
        let (largest, differ) = wall_difference(&ours, &theirs);
        series.push(Series::new(
            Quantity::of_category(ours.outcome.name()).unwrap_or(Quantity::Undecided),
            format!("{charge:?} v0 = {v0} k_i/k = {ratio}: {}", ours.outcome.name()).to_lowercase(),
            walls(&ours),
            Style::Points,
        ));
        rows.push(Row::words(
            format!("{charge:?} at v0 = {v0}, k_i/k = {ratio}, θ̄ = {SCATTERING_THETA_BAR}: outcome, network"),
            theirs.outcome.name(),
            ours.outcome.name(),
            format!(
                "paper column: the chain code's (expected {}); walls differ by at most {largest:.1e} sites, \
                 wall counts differ at {differ} of {} outputs; initial energy {}, relative difference {:.1e}",
                expected.name(),
                ours.run.tracker.snapshots.len(),
                format_number(theirs.run.report.energy_initial),
                (ours.run.report.energy_initial - theirs.run.report.energy_initial).abs()
                    / theirs.run.report.energy_initial.abs(),
            ),
        ));
    }
    let dynamics = Panel::new(
        format!("(b) walls in time, network, θ̄ = {SCATTERING_THETA_BAR}, impurity spring {}", middle(params)),
        "time t",
        "wall position (rotor index)",
        series,
    );
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "The paper's chain (n = {}, r/a = {}, k = {}) declared as a rotor network and run through the chain's \
             analyses: (a) the antikink at the Peierls-Nabarro minimum, chain code and network; (b) the network's \
             interior walls for one scattering point of each outcome (the chain code's coincide: rows).",
            params.n, params.r, params.k
        ),
        panels: vec![Chart::Lines(statics), Chart::Lines(dynamics)],
        rows,
    })
}
