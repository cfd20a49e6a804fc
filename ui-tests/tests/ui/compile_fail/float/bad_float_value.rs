use rotor_chain::prelude::*;

// A type the chain cannot compute in, with the nearest supported one suggested.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f16)]
pub struct Half;

// A misspelled type.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f23)]
pub struct Typo;

// A string, not a type.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = "f32")]
pub struct Quoted;

// A bit width, not a type.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = 32)]
pub struct Width;

// An integer type.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = u32)]
pub struct Integer;

// No value.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float =)]
pub struct Missing;

// Given twice.
#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f32, float = f64)]
pub struct Twice;

fn main() {}
