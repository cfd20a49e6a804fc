//! Demonstration 1 of issue 36: the paper's chain declared as a network (chain-network's
//! `rotor_chain` cell, a free patch of 30 cells = 60 rotors, `k = 1e4`, `M = 1`) and seen in the
//! chain's angles (`ChainView`) reproduces the chain code (`RuntimeChain`, its own kernels): the
//! zero-energy kink, the antikink's minimum 1392.029215 and barrier 0.668267 at `theta_bar = 0.58`
//! (docs/statics.md §3), and one scattering outcome of each of the paper's kinds at
//! `theta_bar = 0.28` (tests/dynamics.rs' robust points), energies to 1e-9 relative.

use chain_core::RuntimeChain;
use chain_core::dynamics::scatter::{Outcome, ScatterSetup, scatter};
use chain_core::statics::antikink::{AntikinkOptions, peierls_nabarro};
use chain_core::statics::kink::kink;
use chain_core::statics::walls::Charge;
use chain_core::{ChainGeometry, Potential};
use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch};
use chain_network::{ChainView, NetworkModel};

const K: f64 = 1.0e4;
const N: usize = 60;

/// The paper's chain at `theta_bar` as a network seen as a chain, with spring `impurity`'s
/// constant `k_i`.
fn network_chain(theta_bar: f64, impurity: Option<(usize, f64)>) -> ChainView {
    let cell = ready::rotor_chain(1.0, 0.8, theta_bar).unwrap();
    let patch = Patch::new(&cell, [N / 2, 1], Boundary::Free).unwrap();
    let mut builder = NetworkModel::builder(&patch);
    for p in 0..patch.bonds().len() {
        builder = builder.spring_constant(p, K);
    }
    if let Some((p, k)) = impurity {
        builder = builder.spring_constant(p, k);
    }
    ChainView::new(&patch, builder.build().unwrap()).unwrap()
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs())
}

#[test]
fn the_view_has_the_chains_geometry_and_energy() {
    let view = network_chain(0.58, None);
    let chain = RuntimeChain::builder(N, 0.8, K, 0.58).build().unwrap();
    assert_eq!(view.dof_count(), N);
    assert!((view.theta_bar() - 0.58).abs() < 1e-15 && (view.lattice_spacing() - 1.0).abs() < 1e-15);
    assert!((view.mass() - 1.0).abs() < 1e-15 && (view.inertia(7) - 0.64).abs() < 1e-15);
    let theta: Vec<f64> = (0..N).map(|i| 0.58 + 0.3 * (i as f64 * 0.7).sin()).collect();
    let (e_view, e_chain) = (view.energy(&theta), chain.energy(&theta));
    assert!(close(e_view, e_chain, 1e-12), "{e_view} vs {e_chain}");
    let (g_view, g_chain) = (view.gradient(&theta), chain.gradient(&theta));
    for i in 0..N {
        assert!((g_view[i] - g_chain[i]).abs() < 1e-9 * (1.0 + g_chain[i].abs()), "gradient {i}");
    }
}

#[test]
fn the_kink_has_zero_energy_in_the_network() {
    let view = network_chain(0.58, None);
    let theta = kink(&view, 29.5).unwrap();
    let energy = view.energy(&theta);
    assert!(energy.abs() <= view.energy_floor(), "kink energy {energy:e}, floor {:e}", view.energy_floor());
    let chain = RuntimeChain::builder(N, 0.8, K, 0.58).build().unwrap();
    let reference = kink(&chain, 29.5).unwrap();
    assert!(theta.iter().zip(&reference).all(|(a, b)| (a - b).abs() < 1e-12));
}

#[test]
fn the_antikink_minimum_and_barrier_are_the_chain_codes() {
    let view = network_chain(0.58, None);
    let chain = RuntimeChain::builder(N, 0.8, K, 0.58).build().unwrap();
    let options = AntikinkOptions::default();
    let (ours, theirs) =
        (peierls_nabarro(&view, &options).unwrap(), peierls_nabarro(&chain, &options).unwrap());
    assert!(ours.resolved && theirs.resolved);
    let (min, saddle) = (ours.minimum().unwrap().energy, ours.saddle().unwrap().energy);
    eprintln!("network: V_min = {min:.6}, V_saddle = {saddle:.6}, barrier = {:.6}", ours.barrier);
    assert!(
        close(min, theirs.minimum().unwrap().energy, 1e-9),
        "{min} vs {}",
        theirs.minimum().unwrap().energy
    );
    assert!(
        close(saddle, theirs.saddle().unwrap().energy, 1e-9),
        "{saddle} vs {}",
        theirs.saddle().unwrap().energy
    );
    assert!((ours.barrier - theirs.barrier).abs() <= 1e-9 * min, "{} vs {}", ours.barrier, theirs.barrier);
    // The printed values (docs/statics.md §3), within their last digit's rounding.
    assert!((min - 1392.029215).abs() <= 5e-7 + 1e-9 * min, "V_min {min}");
    assert!((ours.barrier - 0.668267).abs() <= 5e-7 + 1e-9 * min, "barrier {}", ours.barrier);
    assert_eq!(ours.minimum().unwrap().classification.index, 0);
    assert_eq!(ours.saddle().unwrap().classification.index, 1);
}

/// One robust point of each of the paper's kinds (tests/dynamics.rs): the network gives the chain
/// code's outcome, and the same initial energy to 1e-9.
#[test]
fn scattering_outcomes_are_the_chain_codes() {
    let points = [
        (Charge::Kink, 2.0, 0.5, Outcome::Transmitted),
        (Charge::Kink, 11.0, 0.012, Outcome::Split),
        (Charge::Antikink, 2.0, 0.4, Outcome::Trapped),
        (Charge::Antikink, 6.0, 0.05, Outcome::Reflected),
    ];
    for (charge, v0, ratio, expected) in points {
        let view = network_chain(0.28, Some((29, ratio * K)));
        let chain = RuntimeChain::builder(N, 0.8, K, 0.28).spring_constant(29, ratio * K).build().unwrap();
        let setup = ScatterSetup::from_the_right(charge, v0, 29);
        let (ours, theirs) = (scatter(&view, &setup).unwrap(), scatter(&chain, &setup).unwrap());
        let (e0, e1) = (ours.run.report.energy_initial, theirs.run.report.energy_initial);
        eprintln!(
            "{charge:?} v0 = {v0}, k_i/k = {ratio}: network {:?}, chain {:?}; E0 {e0} vs {e1}",
            ours.outcome, theirs.outcome
        );
        assert_eq!((ours.outcome, theirs.outcome), (expected, expected));
        assert!(close(e0, e1, 1e-9), "initial energy {e0} vs {e1}");
    }
}
