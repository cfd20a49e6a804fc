use rotor_chain::prelude::*;

#[rotor_chain(
    n = 10,
    r = 0.8,
    theta_bar = 0.58,
    k = 1.0e4,
    law = k * l0 * l0 * (l / l0 - 1.0).cosh()
)]
pub struct Chain;

fn main() {}
