//! Demonstration 3 (issue 36): a transition wave in a chain of bistable elements declared as a
//! network with the run-time polynomial law, its speed fitted from the run against the
//! continuum's closed form (`chain_network::motion::transition`'s module doc).

use chain_network::motion::MotionError;
use chain_network::motion::transition::BistableChain;

/// A short chain (debug-fast): 80 sites, the front launched from a step at site 10 and fitted
/// from t = 14 (seven damping times: the launch overshoots to about 3.1 and settles) to t = 24
/// (about 23 sites of travel).
fn short() -> BistableChain {
    BistableChain { sites: 80, duration: 24.0, samples: 49, fit_from: 14.0, ..BistableChain::default() }
}

#[test]
fn the_front_moves_at_the_continuums_speed() {
    let chain = short();
    let wave = chain.run().unwrap();
    // The closed form at the defaults, by hand: Q = 2 (1/2 - 1/4)^2 = 1/8, v = 4 sqrt((1/8) / (1/4 + 1/8)).
    let by_hand = 4.0 * (1.0f64 / 3.0).sqrt();
    assert!((wave.predicted - by_hand).abs() < 1e-12, "{}", wave.predicted);
    let (v, fit) = (wave.speed(), wave.fit);
    eprintln!(
        "measured {v:.5}, continuum {:.5}, relative {:+.3e}, rms {:.2e} over {} points, width {:.3}",
        wave.predicted,
        wave.relative_difference(),
        fit.rms_residual,
        fit.points,
        chain.continuum_width()
    );
    // A steady front: the positions lie on the line to a few hundredths of a site (what is left
    // is the launch's decaying oscillation of the speed).
    assert!(fit.rms_residual < 0.06, "rms residual {}", fit.rms_residual);
    assert!(wave.relative_difference().abs() < 0.01, "measured {v}, continuum {}", wave.predicted);
}

#[test]
fn the_speed_follows_the_damping_as_the_closed_form_says() {
    // Twice the damping: the closed form's speed drops from 2.31 to 1.33; the lattice's follows.
    let chain = BistableChain { damping: 1.0, ..short() };
    let wave = chain.run().unwrap();
    eprintln!("gamma 1: measured {:.5}, continuum {:.5}", wave.speed(), wave.predicted);
    assert!((wave.predicted - 4.0 * (1.0f64 / 9.0).sqrt()).abs() < 1e-12);
    assert!(
        wave.relative_difference().abs() < 0.02,
        "measured {}, continuum {}",
        wave.speed(),
        wave.predicted
    );
}

#[test]
fn equal_wells_or_a_bad_parameter_are_refused() {
    let e = BistableChain { barrier: 0.5, ..short() }.run().unwrap_err();
    assert!(matches!(e, MotionError::InvalidOption(o) if o.field == "barrier"), "{e}");
    let e = BistableChain { damping: f64::NAN, ..short() }.run().unwrap_err();
    assert!(matches!(e, MotionError::InvalidOption(o) if o.field == "damping"), "{e}");
}
