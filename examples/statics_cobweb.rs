//! Cobweb analysis of the branch map (paper Sec. II, Fig. `fig:kcobweb`): the two fixed points
//! `-+theta_bar` of a spring's flipper branch, their slopes (numeric and closed form), stability
//! and decay lengths, and the cobweb staircase of a kink near its centre.
//!
//! Run: `cargo run --example statics_cobweb`

use rotor_chain::prelude::*;
use rotor_chain::statics::cobweb::{cobweb, fixed_points, slope_closed_form};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::kink::kink;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Chain;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = Chain;
    let continuum = ContinuumChain::new(1.0, 0.8, 0.58, 1.0e4, 1.0)?;
    let exact = slope_closed_form(1.0, 0.8, 0.58);
    println!("Branch map of spring 10 (paper Sec. II): r/a = 0.8, theta_bar = 0.58 rad, n = 60");
    println!(
        "F'(theta_bar) = (a + 2 r sin theta_bar) / (a - 2 r sin theta_bar); F'(-theta_bar) = 1 / F'(theta_bar)\n"
    );
    println!(
        "{:>10} | {:>12} | {:>12} | {:>12} | {:>10} | {:>13} | {:>13}",
        "fixed pt", "theta (rad)", "F' numeric", "F' closed", "stability", "decay (a)", "1/|ln F'|"
    );
    for (point, closed) in fixed_points(&chain, 10)?.iter().zip([1.0 / exact, exact]) {
        println!(
            "{:>10} | {:>+12.9} | {:>12.9} | {:>12.9} | {:>10} | {:>13.9} | {:>13.9}",
            if point.theta > 0.0 { "+theta_bar" } else { "-theta_bar" },
            point.theta,
            point.slope,
            closed,
            format!("{:?}", point.stability),
            point.decay_length,
            1.0 / closed.ln().abs(),
        )
    }
    println!(
        "continuum: decay length a / ln F' = {:.9} a, wall width w = {:.6} a (decay -> w/2 as theta_bar -> 0)",
        continuum.decay_length(),
        continuum.width()
    );

    // The kink centred on spring 29 (between rotors 29 and 30): its staircase near the centre,
    // paper Fig. fig:kcobweb(b) shows the same steps from theta_7 to theta_10 of its chain.
    let theta = kink(&chain, 29.5)?;
    let web = cobweb(&chain, 29, &theta, 0.7, 141)?;
    println!(
        "\nCobweb of the kink centred at 29.5: {} samples of the flipper branch, {} of the other branch, \
         {} staircase points",
        web.flipper_branch.len(),
        web.other_branch.len(),
        web.staircase.len()
    );
    println!(
        "staircase from rotor 27 to rotor 32 (rotor points (theta_i, theta_i), spring points (theta_i, theta_i+1)):"
    );
    println!("{:>6} | {:>22} | {:>10} | {:>24}", "point", "(x, y) (rad)", "on", "|F(theta_i) - theta_i+1|");
    for (s, [x, y]) in web.staircase.iter().enumerate().skip(2 * 27).take(11) {
        let i = s / 2;
        if s % 2 == 0 {
            println!("{:>6} | ({x:+.6}, {y:+.6}) | {:>10} | {:>24}", s, format!("rotor {i}"), "");
        } else {
            let off_curve = (chain.next_angles(i, *x)?[0] - y).abs();
            println!("{:>6} | ({x:+.6}, {y:+.6}) | {:>10} | {off_curve:>24.2e}", s, format!("spring {i}"));
        }
    }
    // Far from the centre the steps shrink by F'(-theta_bar) per site towards -theta_bar.
    let ratio = (theta[40] + 0.58) / (theta[39] + 0.58);
    println!(
        "\ncontraction towards -theta_bar at rotor 40: (theta_40 + theta_bar)/(theta_39 + theta_bar) = {ratio:.6} \
         (1/F' = {:.6})",
        1.0 / exact
    );
    Ok(())
}
