use rotor_chain::prelude::*;

#[rotor_chain(
    n = 10,
    r = 0.8,
    theta_bar = 0.58,
    k = 1.0e4,
    law = k / 2.0 * (l - lbar).powi(2)
)]
pub struct Chain;

fn main() {}
