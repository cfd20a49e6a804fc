//! Compile errors of `#[rotor_chain]`: the uniform state outside the flipper phase.
//! One module per case, so the whole group is checked in one compilation; each error is
//! reported at its key and the snapshot (`.stderr`) lists them in the order of the modules.

mod theta_bar_past_wobbler {
    use rotor_chain::prelude::*;

    // The flipper phase ends at asin(a / 2r) = 0.675 for a = 1, r = 0.8.
    #[rotor_chain(n = 10, a = 1.0, r = 0.8, theta_bar = 0.7, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod theta_bar_zero {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, a = 1.0, r = 0.8, theta_bar = 0.0, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

fn main() {
    theta_bar_past_wobbler::main();
    theta_bar_zero::main();
}
