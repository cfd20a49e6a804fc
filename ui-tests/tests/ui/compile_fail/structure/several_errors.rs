use rotor_chain::prelude::*;

// Every mistake is reported at once, each at its key, and the struct is still emitted: `main`
// compiles against it, with no follow-up error about the missing generated items.
#[rotor_chain(
    n = 10,
    r = -0.8,
    thetabar = 0.58,
    k = 1.0e4,
    k = 2.0e4,
    spring(12, k = k_impurity),
    law = k / 2.0 * (l - lbar).powi(2)
)]
pub struct Chain {
    pub k_imp: f64,
}

fn main() {
    let _ = Chain { k_imp: 100.0 }.k_imp;
}
