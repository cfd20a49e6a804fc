use rotor_chain::prelude::*;

// The flipper phase ends at asin(a / 2r) = 0.675 for a = 1, r = 0.8.
#[rotor_chain(n = 10, a = 1.0, r = 0.8, theta_bar = 0.7, k = 1.0e4)]
pub struct Chain;

fn main() {}
