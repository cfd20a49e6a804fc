//! A `#![no_std]` library without `alloc`: a 16-rotor chain, stepped with fixed-size arrays.
//!
//! CI builds this crate on its own (`cargo build -p embedded-check`), so `rotor-chain` resolves
//! without its default `std` feature, and checks that no `std` feature reaches it.
#![no_std]

use rotor_chain::prelude::*;

/// The paper's chain geometry on a microcontroller-sized chain.
#[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0)]
pub struct Chain16;

/// State of the chain: angles and angular velocities.
#[derive(Clone, Copy, Debug)]
pub struct State {
    pub theta: [f64; 16],
    pub omega: [f64; 16],
}

/// One velocity-Verlet step of `M r^2 thetadd = -dV/dtheta` (no heap, no std).
pub fn step(chain: &Chain16, state: &mut State, dt: f64) {
    let inertia = 1.0 * 0.8 * 0.8;
    let g = chain.gradient(&state.theta);
    for ((w, t), g) in state.omega.iter_mut().zip(&mut state.theta).zip(g) {
        *w -= 0.5 * dt * g / inertia;
        *t += dt * *w;
    }
    let g = chain.gradient(&state.theta);
    for (w, g) in state.omega.iter_mut().zip(g) {
        *w -= 0.5 * dt * g / inertia;
    }
}

/// Total energy, for a monitor.
pub fn energy(chain: &Chain16, state: &State) -> f64 {
    let kinetic: f64 = state.omega.iter().map(|w| 0.5 * 0.64 * w * w).sum();
    kinetic + chain.energy(&state.theta)
}

/// The stiffness spectrum needs no heap either: the banded form and its dense view are arrays.
pub fn stiffness_trace(chain: &Chain16, theta: &[f64; 16]) -> f64 {
    chain.hessian(theta).trace()
}
