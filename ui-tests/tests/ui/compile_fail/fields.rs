//! Compile errors of `#[rotor_chain]`: field parameters: a name that is no field, a field that is not `f64`.
//! One module per case, so the whole group is checked in one compilation; each error is
//! reported at its key and the snapshot (`.stderr`) lists them in the order of the modules.

mod field_not_f64 {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(4, k = k_imp))]
    pub struct Chain {
        pub k_imp: f32,
    }

    pub fn main() {
        let _ = Chain { k_imp: 100.0 }.k_imp;
    }
}

mod not_a_field {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(4, k = impurity))]
    pub struct Chain {
        pub k_imp: f64,
    }

    pub fn main() {
        let _ = Chain { k_imp: 100.0 }.k_imp;
    }
}

mod not_a_field_suggestion {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(4, k = k_impurity))]
    pub struct Chain {
        pub k_imp: f64,
    }

    pub fn main() {
        let _ = Chain { k_imp: 100.0 }.k_imp;
    }
}

fn main() {
    field_not_f64::main();
    not_a_field::main();
    not_a_field_suggestion::main();
}
