//! Every dynamics figure in quick mode: panels with data, and the paper's named scattering outcomes
//! in the summary rows.

use std::time::Instant;

use chain_paper::figures::Params;
use chain_paper::figures::dynamics::{
    ak_scatter, akpntrapprofile, figures, k_scatter, ketimeplot, phasediagram,
};
use chain_paper::{Chart, Figure, Quality};
use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::propagation;
use rotor_chain::dynamics::run::RunOptions;
use rotor_chain::integrate::Method;
use rotor_chain::statics::walls::Charge;

fn quick(name: &str, f: fn(&Params, Quality) -> Result<Figure, chain_paper::figures::FigureError>) -> Figure {
    let start = Instant::now();
    let figure = f(&Params::default(), Quality::Quick).unwrap_or_else(|e| panic!("{name}: {e}"));
    eprintln!("{} (quick): {:.2} s", figure.label, start.elapsed().as_secs_f64());
    for row in &figure.rows {
        eprintln!("  {} | paper: {} | ours: {} | {}", row.quantity, row.paper, row.ours, row.note);
    }
    assert!(!figure.panels.is_empty(), "{name}: no panels");
    for chart in &figure.panels {
        match chart {
            Chart::Lines(p) => {
                assert!(!p.series.is_empty(), "{name}: empty panel");
                assert!(p.series.iter().all(|s| s.points.len() > 1), "{name}: empty series");
            }
            Chart::Heat(h) => {
                assert!(!h.x.is_empty() && !h.y.is_empty(), "{name}: empty heat map");
                assert_eq!(h.values.len(), h.y.len(), "{name}: rows");
                assert!(h.values.iter().all(|r| r.len() == h.x.len()), "{name}: columns");
                assert!(h.y.len() <= 401, "{name}: {} rows", h.y.len());
                assert!(h.values.iter().flatten().all(|v| v.is_finite()), "{name}: values");
            }
            Chart::Chain(d) => assert!(d.tips.len() >= 2, "{name}: drawing"),
            Chart::Network(d) => assert!(!d.nodes.is_empty(), "{name}: network drawing"),
        }
    }
    assert!(!figure.rows.is_empty(), "{name}: no rows");
    assert!(!figure.caption.contains('\n'), "{name}: caption on one line");
    figure
}

#[test]
fn every_dynamics_figure_is_listed() {
    let labels: Vec<&str> = figures().iter().map(|(l, _)| *l).collect();
    assert_eq!(
        labels,
        ["fig:ketimeplot", "fig:akpntrapprofile", "fig:k-scatter", "fig:ak-scatter", "fig:phasediagram"]
    );
}

/// The time after "in t = " in a row's note (`... ran 26.3 sites in t = 2.71; ...`).
fn time_in(note: &str) -> f64 {
    let after = note.split_once("in t = ").unwrap_or_else(|| panic!("no time in {note:?}")).1;
    after.split([';', ' ']).next().and_then(|t| t.parse().ok()).unwrap_or_else(|| panic!("{note:?}"))
}

#[test]
fn kinetic_energy_figure() {
    let params = Params::default();
    let figure = quick("ketimeplot", ketimeplot);
    assert_eq!(figure.label, "fig:ketimeplot");
    // (b) is the start of (a), point for point.
    let [Chart::Lines(whole), Chart::Lines(start)] = &figure.panels[..] else { panic!("two line panels") };
    for (all, early) in whole.series.iter().zip(&start.series) {
        assert!(early.points.len() > 10 && early.points.len() < all.points.len());
        assert_eq!(early.points[..], all.points[..early.points.len()]);
    }
    assert_eq!(figure.rows[0].paper, "nearly constant");
    // A second integrator: the same launches (Sec. V: theta_bar = 0.58, v0 = 2.4, from 3/4 of the
    // chain towards the left, Quick's t <= 3) under DOP853 at its default tolerances (energy
    // errors near 1e-9) give the plotted kinetic energies at every plotted time. The figure's
    // Verlet step is a tenth of the stability limit; its O(dt^2) phase error grows along the run
    // to 7.8e-4 (kink) and 9.0e-4 (antikink) of the largest kinetic energy by t = 3 (measured at
    // 1.95.0 on x86-64), bounded here by 1.5e-3: a wrong launch or a dropped output would differ
    // by the kinetic energy itself.
    let (theta_bar, v0) = (params.propagation.theta_bar, params.propagation.v0);
    let model =
        RuntimeChain::builder(params.n, params.r, params.k, theta_bar).mass(params.mass).build().unwrap();
    let options = RunOptions { t_max: 3.0, method: Method::dop853(), ..RunOptions::default() };
    let begin = 0.75 * params.n as f64;
    for (series, charge, row) in [
        (&whole.series[0], Charge::Kink, &figure.rows[0]),
        (&whole.series[1], Charge::Antikink, &figure.rows[1]),
    ] {
        let second = propagation(&model, charge, begin, v0, Direction::Left, Some(8.0), &options).unwrap();
        let scale = series.points.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
        let mut compared = 0;
        let mut worst = 0.0f64;
        for &(t, plotted) in &series.points {
            let Some(&(_, k)) = second.run.kinetic.iter().find(|(s, _)| (s - t).abs() <= 1e-9) else {
                continue;
            };
            worst = worst.max((plotted - k).abs() / scale);
            compared += 1;
        }
        eprintln!("{}: {compared} times compared, worst |Verlet - DOP853| / scale = {worst:e}", series.name);
        assert!(
            compared * 10 >= series.points.len() * 9,
            "{}: {compared} of {}",
            series.name,
            series.points.len()
        );
        assert!(worst <= 1.5e-3, "{}: Verlet and DOP853 differ by {worst:e} of the scale", series.name);
        // The row's variation, (max - min) / mean of the kinetic energy until the track ends (the
        // time its note gives), recomputed from the plotted points, to the row's two decimals.
        let until = time_in(&row.note);
        let window: Vec<f64> = series.points.iter().filter(|p| p.0 <= until).map(|p| p.1).collect();
        let (lo, hi) =
            window.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &k| (a.min(k), b.max(k)));
        let mean = window.iter().sum::<f64>() / window.len() as f64;
        let shown: f64 = row.ours.trim_end_matches(" %").parse().unwrap_or_else(|_| panic!("{:?}", row.ours));
        assert!(
            (shown - 100.0 * (hi - lo) / mean).abs() <= 0.005 + 1e-9,
            "{}: {} vs {}",
            series.name,
            row.ours,
            100.0 * (hi - lo) / mean
        );
    }
}

#[test]
fn trapping_figure_shows_the_conservative_and_the_damped_antikink() {
    let figure = quick("akpntrapprofile", akpntrapprofile);
    assert_eq!(figure.panels.len(), 3);
    assert_eq!(figure.rows.len(), 4);
    // The damped run of the quick search stops; the conservative one at 0.575132 does not.
    assert!(figure.rows[1].ours.starts_with("not stopped"), "{}", figure.rows[1].ours);
    assert!(figure.rows[2].ours.contains("stopped at t ="), "{}", figure.rows[2].ours);
}

#[test]
fn scattering_figures_reproduce_the_papers_outcomes() {
    for (name, f, count) in
        [("k-scatter", k_scatter as fn(&Params, Quality) -> _, 2), ("ak-scatter", ak_scatter, 3)]
    {
        let figure = quick(name, f);
        // The antikink's figure adds the slowing of transmitted antikinks: a panel and a row.
        let extra = usize::from(name == "ak-scatter");
        assert_eq!(figure.panels.len(), count + extra, "{name}");
        assert_eq!(figure.rows.len(), count + extra, "{name}");
        for row in &figure.rows[..count] {
            assert_eq!(row.ours, row.paper, "{name}: {}", row.quantity);
        }
    }
}

#[test]
fn phase_diagram_figure() {
    let figure = quick("phasediagram", phasediagram);
    // Kink, antikink, and the antikink's walls and their time in a perfect chain: one quantity
    // per axis, no empty place in the 2 x 2 layout.
    assert_eq!(figure.panels.len(), 4);
    for chart in &figure.panels[..2] {
        let Chart::Heat(h) = chart else { panic!("phase diagrams are heat maps") };
        // Every outcome, "unresolved" and "failed".
        assert_eq!(h.categories.len(), 10);
        assert!(h.values.iter().flatten().all(|&v| v >= 0.0 && (v as usize) < h.categories.len()));
        // k_i/k from 0.01 to 3 on a logarithmic axis: the data are log10(k_i/k).
        assert!(h.log_x && h.x_label == "k_i / k");
        assert!(
            (h.x[0] + 2.0).abs() < 1e-12 && (h.x[h.x.len() - 1] - 3f64.log10()).abs() < 1e-12,
            "{:?}",
            h.x
        );
    }
    for chart in &figure.panels[2..] {
        let Chart::Lines(p) = chart else { panic!("the stability panels are line panels") };
        assert_eq!(p.series.len(), 1, "{}: one quantity", p.title);
    }
    // The kink is never trapped or reflected (paper Sec. VI).
    assert!(figure.rows[0].ours.starts_with("0 of"), "{}", figure.rows[0].ours);
}
