//! Every closed form of the continuum theory at the paper's parameters (paper Secs. II-V, VII-B,
//! Appendix `app:AppendixPN`), with the paper's printed value beside it where it prints one.
//!
//! Run: `cargo run --example statics_continuum`

use core::f64::consts::PI;

use rotor_chain::geometry::flipper_limit;
use rotor_chain::statics::continuum::{ContinuumChain, PN_ASYMPTOTIC_LOG_SLOPE};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (a, r, theta_bar, k, m) = (1.0, 0.8, 0.58, 1.0e4, 1.0);
    let c = ContinuumChain::new(a, r, theta_bar, k, m)?;
    let unit = (r / a) * (k / m).sqrt(); // the paper's frequency unit (Sec. VII-A)
    let [bottom, top] = c.phonon_band_edges();
    let (alpha, beta) = c.spring_length_derivatives();
    let pn_peak_to_peak = c.pn_potential(0.0) - c.pn_potential(0.5 * a);
    println!("Continuum closed forms, a = 1, r = 0.8, theta_bar = 0.58 rad, k = 1e4, M = 1\n");
    println!("{:<44} | {:>14} | {:<14} | {:>6} | where", "quantity", "value", "unit", "paper");
    let rows: [(&str, f64, &str, Option<f64>, &str); 24] = [
        ("ubar = r sin theta_bar", c.u_bar(), "a", None, "Sec. III"),
        (
            "lbar = sqrt(a^2 + 4 r^2 cos^2 theta_bar)",
            c.rest_length(),
            "a",
            Some(1.68),
            "Fig. fig:longbar caption",
        ),
        ("wall width w = a^2 / (2 ubar)", c.width(), "a", None, "eq:kinksolution"),
        ("sound speed c = (a^2 / lbar) sqrt(k/M)", c.sound_speed(), "a/t", None, "eq:kinksolution"),
        ("cobweb slope F'(theta_bar)", c.cobweb_slope(), "1", None, "Sec. II"),
        ("decay length a / ln F'", c.decay_length(), "a", None, "Sec. II"),
        ("flipper limit asin(a / 2r)", flipper_limit(a, r), "rad", Some(0.67), "Fig. fig:akenergy caption"),
        ("antikink energy", c.antikink_energy() / k, "k a^2", None, "eq:akenergy"),
        ("antikink energy", c.antikink_energy(), "M a^2/t^2", None, "eq:akenergy"),
        (
            "translation mode omega_t",
            c.translation_mode_frequency(),
            "1/t",
            Some(0.0),
            "eq:continuumtheoryfrequency1",
        ),
        ("shape mode omega_s", c.shape_mode_frequency(), "1/t", None, "eq:continuumtheoryfrequency2"),
        (
            "shape mode omega_s",
            c.shape_mode_frequency() / unit,
            "(r/a)sqrt(k/M)",
            None,
            "eq:continuumtheoryfrequency2",
        ),
        ("continuum phonon gap 4 ubar sqrt(k/M)/lbar", c.continuum_phonon_gap(), "1/t", None, "eq:smallosci"),
        ("lattice band bottom omega(q = 0)", bottom, "1/t", None, "exact dispersion"),
        ("lattice band top omega(q = pi)", top, "1/t", None, "exact dispersion"),
        ("alpha = dl/dtheta_p (uniform state)", alpha, "a", None, "theory.md sec. 7"),
        ("beta = dl/dtheta_p+1 (uniform state)", beta, "a", None, "theory.md sec. 7"),
        ("PN barrier, derived (peak-to-peak)", c.pn_barrier() / k, "k a^2", None, "app:AppendixPN"),
        ("PN barrier as printed (= amplitude)", c.pn_barrier_as_printed() / k, "k a^2", None, "eq:PNB2"),
        ("V_PN(0) - V_PN(a/2), all harmonics", pn_peak_to_peak / k, "k a^2", None, "eq:PNpoisson"),
        ("d ln V_PNB / d(w/a) at theta_bar", c.pn_log_slope(), "1", None, "eq:PNB2"),
        ("large-w slope -pi^2", PN_ASYMPTOTIC_LOG_SLOPE, "1", Some(-9.9), "Fig. fig:logvpn-theta"),
        ("l_critical", c.l_critical(), "a", Some(2.31), "Sec. VII-B"),
        ("E_c at l0 = 2.30", c.critical_energy(2.30), "M a^2/t^2", None, "Sec. VII-B"),
    ];
    for (what, value, unit, paper, source) in rows {
        let paper = paper.map_or(String::from("-"), |p| format!("{p}"));
        println!("{what:<44} | {:>14} | {unit:<14} | {paper:>6} | {source}", number(value));
    }
    println!(
        "\nchecks: F' = -alpha/beta = {:.9} (closed form {:.9}); derived / printed PN barrier = {:.3}; \
         omega_s / gap = {:.6} (sqrt(3)/2 = {:.6}); pi^2 = {:.4}",
        -alpha / beta,
        c.cobweb_slope(),
        c.pn_barrier() / c.pn_barrier_as_printed(),
        c.shape_mode_frequency() / c.continuum_phonon_gap(),
        3f64.sqrt() / 2.0,
        PI * PI
    );
    Ok(())
}

/// Fixed point for moderate magnitudes, scientific otherwise.
fn number(x: f64) -> String {
    if x == 0.0 || (1e-2..1e5).contains(&x.abs()) { format!("{x:.7}") } else { format!("{x:.6e}") }
}
