use rotor_chain::prelude::*;

// 10 rotors have indices 0..10.
#[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, rotor(10, r = 0.9))]
pub struct Chain;

fn main() {}
