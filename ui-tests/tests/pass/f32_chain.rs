//! A chain declared with `float = f32`, literal and field parameters, stepped without a heap.
use rotor_chain::embedded::{kink_into, kink_launch_velocities};
use rotor_chain::prelude::*;

#[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f32)]
pub struct Literal;

#[rotor_chain(n = 6, r = radius, theta_bar = 0.58, k = stiffness, float = core::primitive::f32)]
pub struct Fields {
    pub radius: f32,
    pub stiffness: f32,
}

/// The example of docs/macro.md ("`float = f32`").
#[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0, float = f32)]
pub struct Chain16F32;

fn go() -> Result<(), rotor_chain::embedded::DynamicsError> {
    let chain = Chain16F32;
    let mut theta = [0.0f32; 16];
    kink_into(&chain, 4.25, &mut theta)?;
    let omega = kink_launch_velocities(&chain, &theta, 2.0)?;
    let mut stepper = chain.verlet(theta, omega, 1.953125e-3)?;
    for _ in 0..1024 {
        stepper.step(&chain)?;
    }
    let energy: f32 = stepper.kinetic_energy(&chain) + stepper.potential_energy(&chain);
    assert!((energy - 2.0).abs() < 1e-3, "{energy}");
    Ok(())
}

pub fn main() {
    go().unwrap();
    let theta = [0.58f32; 6];
    let chain = Literal;
    let e: f32 = chain.energy(&theta);
    assert!(e.abs() < 1e-3, "{e}");
    let g: [f32; 6] = chain.gradient(&theta);
    assert!(g.iter().all(|x| x.is_finite()));
    let [flipper, _] = chain.next_angles(0, 0.58).unwrap();
    assert!((flipper - 0.58).abs() < 1e-5, "{flipper}");
    let fields = Fields { radius: 0.8, stiffness: 1.0e4 };
    fields.check().unwrap();
    let mut stepper = fields.verlet(theta, [0.0; 6], 1.0e-3).unwrap();
    stepper.step(&fields).unwrap();
}
