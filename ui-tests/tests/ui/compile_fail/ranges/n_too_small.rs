use rotor_chain::prelude::*;

#[rotor_chain(n = 1, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct Chain;

fn main() {}
