use rotor_chain::prelude::*;

#[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(4, k = impurity))]
pub struct Chain {
    pub k_imp: f64,
}

fn main() {
    let _ = Chain { k_imp: 100.0 }.k_imp;
}
