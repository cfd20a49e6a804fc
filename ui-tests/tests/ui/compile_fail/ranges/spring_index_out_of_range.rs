use rotor_chain::prelude::*;

// 10 rotors have springs 0..9.
#[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(9, k = 2.0e4))]
pub struct Chain;

fn main() {}
