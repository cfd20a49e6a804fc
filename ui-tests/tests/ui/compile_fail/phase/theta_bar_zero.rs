use rotor_chain::prelude::*;

#[rotor_chain(n = 10, a = 1.0, r = 0.8, theta_bar = 0.0, k = 1.0e4)]
pub struct Chain;

fn main() {}
