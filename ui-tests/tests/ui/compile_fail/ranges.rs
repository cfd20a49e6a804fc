//! Compile errors of `#[rotor_chain]`: values out of range, and the documented limits.
//! One module per case, so the whole group is checked in one compilation; each error is
//! reported at its key and the snapshot (`.stderr`) lists them in the order of the modules.

mod a_not_positive {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, a = 0.0, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod k_not_positive {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 0.0)]
    pub struct Chain;

    pub fn main() {}
}

mod limits {
    use rotor_chain::prelude::*;

    // The documented limits, each an error at its key; and what a chain too long for an array on the
    // stack offers instead: the `ChainModel` slice methods.

    #[rotor_chain(n = 100000001, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct TooManyRotors;

    #[rotor_chain(n = 513, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 513)]
    pub struct UnrollTooLarge;

    // 49153 rotors: `tangent_stiffness()` would return its 98305 numbers three times over on the
    // stack (2.3 MiB), so it is not generated (the allocating `Potential::gradient` exists for
    // every chain; the array-returning matrix methods have no such fallback).
    #[rotor_chain(n = 49153, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct Long;

    pub fn main() {
        let theta = vec![0.58; Long::N];
        let mut g = vec![0.0; Long::N];
        Potential::gradient_into(&Long, &theta, &mut g);
        let fixed: &[f64; 49153] = theta.as_slice().try_into().unwrap();
        let _ = Long.tangent_stiffness(fixed);
    }
}

mod mass_negative {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = -2.5)]
    pub struct Chain;

    pub fn main() {}
}

mod mass_zero {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 0.0)]
    pub struct Chain;

    pub fn main() {}
}

mod n_too_small {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 1, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct Chain;

    // One error, at `n`: the stubs beside it type-check without annotations (the spring-count
    // methods included), so these calls add none.
    pub fn main() {
        let theta = [0.58f64; 1];
        let _ = Chain.tangent_stiffness(&theta).diag[0] + Chain.material_stiffness(&theta).diag[0];
        let _ = Chain.spring_lengths(&theta)[0] + Chain.compatibility(&theta).left[0];
        let (e, g, k) = Chain.energy_gradient_stiffness(&theta);
        let _ = e + g[0] + k.diag[0] + Chain.tensions(&theta)[0] + Chain.stress_matrix(&theta).diag[0];
    }
}

mod r_not_positive {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.0, theta_bar = 0.58, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod rest_length_out_of_range {
    use rotor_chain::prelude::*;

    // sqrt(a^2 + 4 r^2) = 1.887 for a = 1, r = 0.8: no uniform state has springs this long.
    #[rotor_chain(n = 10, a = 1.0, r = 0.8, rest_length = 2.5, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod rotor_index_out_of_range {
    use rotor_chain::prelude::*;

    // 10 rotors have indices 0..10.
    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, rotor(10, r = 0.9))]
    pub struct Chain;

    pub fn main() {}
}

mod spring_index_out_of_range {
    use rotor_chain::prelude::*;

    // 10 rotors have springs 0..9.
    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(9, k = 2.0e4))]
    pub struct Chain;

    pub fn main() {}
}

fn main() {
    a_not_positive::main();
    k_not_positive::main();
    limits::main();
    mass_negative::main();
    mass_zero::main();
    n_too_small::main();
    r_not_positive::main();
    rest_length_out_of_range::main();
    rotor_index_out_of_range::main();
    spring_index_out_of_range::main();
}
