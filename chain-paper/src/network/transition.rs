//! The figure of demonstration 3 (issue 36): a transition wave in a chain of bistable elements
//! declared as a network ([`chain_network::motion::transition`]): the x-t diagram of the
//! displacements, and the front's position against time with the fitted line beside the
//! continuum's speed.

use chain_network::motion::MotionError;
use chain_network::motion::transition::{BistableChain, TransitionWave};

use crate::model::{Chart, Figure, Heatmap, Panel, Quantity, Series, Style};

/// The figure of `chain`'s run, and the run (for a caller that prints its numbers).
pub fn transition_figure(chain: &BistableChain) -> Result<(Figure, TransitionWave), MotionError> {
    let wave = chain.run()?;
    let sites: Vec<f64> = (0..chain.sites).map(|s| s as f64).collect();
    let map = Heatmap {
        title: "displacement u_n / b (x-t diagram)".into(),
        x_label: "site n".into(),
        y_label: "time t (sqrt(M/k))".into(),
        x: sites,
        y: wave.times.clone(),
        values: wave.displacement.clone(),
        categories: Vec::new(),
        value_label: "u_n / b".into(),
        log_x: false,
        // u / b runs from 0 to 1; the launch overshoots a little below 0.
        colour_limit: Some(1.0),
    };
    let fronts: Vec<(f64, f64)> =
        wave.times.iter().zip(&wave.fronts).filter_map(|(&t, f)| f.map(|x| (t, x))).collect();
    let fit = wave.fit;
    let (t0, t1) = (chain.fit_from, chain.duration);
    let line = |slope: f64| {
        // Through the fit's value at the window's middle, so the two slopes compare by eye.
        let mid = 0.5 * (t0 + t1);
        let x_mid = fit.intercept + fit.slope * mid;
        vec![(t0, x_mid + slope * (t0 - mid)), (t1, x_mid + slope * (t1 - mid))]
    };
    let panel = Panel::new(
        "front position (u = b/2, by the area within five widths)",
        "time t (sqrt(M/k))",
        "front position (sites)",
        vec![
            Series::new(Quantity::Lattice, "lattice front", fronts, Style::Points),
            Series::new(
                Quantity::Fit,
                format!("fit from t = {t0}: v = {:.4}", fit.slope),
                line(fit.slope),
                Style::Line,
            ),
            Series::new(
                Quantity::Continuum,
                format!("continuum v = {:.4}", wave.predicted),
                line(wave.predicted),
                Style::Dashed,
            ),
        ],
    );
    let caption = format!(
        "A transition wave in a chain of {} bistable elements declared as a network (harmonic coupling k_c = {}, \
         on-site double well beta u (u - a)(u - b) with beta = {}, a = {}, b = {}, damping gamma = {}; the \
         polynomial bond law), launched from a step of {} sites at rest. Fitted front speed {:.4} sites per \
         unit time (rms residual {:.3} sites, {} samples) against the continuum's v = c0 sqrt(Q / (gamma^2 + Q)) = {:.4} \
         ({:+.2} %); the continuum front is {:.2} sites wide.",
        chain.sites,
        chain.coupling,
        chain.on_site,
        chain.barrier,
        chain.well,
        chain.damping,
        chain.launch_sites,
        fit.slope,
        fit.rms_residual,
        fit.points,
        wave.predicted,
        100.0 * wave.relative_difference(),
        chain.continuum_width()
    );
    let figure = Figure {
        label: "fig:network-transition",
        caption,
        panels: vec![Chart::Heat(map), Chart::Lines(panel)],
        rows: Vec::new(),
    };
    Ok((figure, wave))
}
