use rotor_chain::prelude::*;

#[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub enum Chain {
    Flipper,
    Wobbler,
}

fn main() {
    let _ = (Chain::Flipper, Chain::Wobbler);
}
