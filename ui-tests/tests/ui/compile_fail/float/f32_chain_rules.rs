use rotor_chain::prelude::*;

// A parameter field of an f32 chain must be declared f32.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = stiffness, float = f32)]
pub struct WideField {
    pub stiffness: f64,
}

// A literal beyond f32's range.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e40, float = f32)]
pub struct TooStiff;

// A literal that rounds to zero in f32.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0e-50, float = f32)]
pub struct TooLight;

// f32 chains are unrolled only.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0, float = f32)]
pub struct Looped;

fn main() {}
