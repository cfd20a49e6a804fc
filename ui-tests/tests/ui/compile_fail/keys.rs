//! Compile errors of `#[rotor_chain]`: the attribute's keys: missing, unknown, repeated, malformed.
//! One module per case, so the whole group is checked in one compilation; each error is
//! reported at its key and the snapshot (`.stderr`) lists them in the order of the modules.

mod duplicate_key {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, k = 2.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod empty_attribute {
    use rotor_chain::prelude::*;

    #[rotor_chain]
    pub struct Chain;

    pub fn main() {}
}

mod malformed_items {
    use rotor_chain::prelude::*;

    // A malformed item of the attribute is one error at that item; the other items still count (no
    // "missing key" for keys that were given).

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4 2.0)]
    pub struct TwoValues;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(3 k = 2.0))]
    pub struct MissingComma;

    #[rotor_chain(= 10, n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct NoKey;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1e400)]
    pub struct OutOfRange;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = type)]
    pub struct Keyword;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, rotor(2))]
    pub struct EmptyRotor;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, rotor(2, r = 0.7), rotor(2, r = 0.6))]
    pub struct RotorTwice;

    #[rotor_chain(n: 10, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct Colon;

    // A type suffix would be ignored (every value is in the chain's float type): refused, on a
    // value, a negated value, an integer, a spring override and `n`.
    #[rotor_chain(n = 10, r = 0.8f32, theta_bar = 0.58, k = 1.0e4)]
    pub struct SuffixF32;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58f64, k = 10000u32, spring(3, k = -2.0f64))]
    pub struct Suffixes;

    #[rotor_chain(n = 10usize, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct SuffixN;

    pub fn main() {}
}

mod missing_n {
    use rotor_chain::prelude::*;

    #[rotor_chain(r = 0.8, theta_bar = 0.58, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod missing_theta_bar {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod spring_overridden_twice {
    use rotor_chain::prelude::*;

    #[rotor_chain(
        n = 10,
        r = 0.8,
        theta_bar = 0.58,
        k = 1.0e4,
        spring(3, k = 2.0e4),
        spring(3, l0 = 1.7)
    )]
    pub struct Chain;

    pub fn main() {}
}

mod spring_overrides_nothing {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(3))]
    pub struct Chain;

    pub fn main() {}
}

mod spring_unknown_key {
    use rotor_chain::prelude::*;

    #[rotor_chain(
        n = 10,
        r = 0.8,
        theta_bar = 0.58,
        k = 1.0e4,
        spring(3, stiffness = 2.0e4)
    )]
    pub struct Chain;

    pub fn main() {}
}

mod theta_bar_and_rest_length {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, rest_length = 1.7, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

mod unknown_key {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, theta_bar = 0.58, k = 1.0e4, damping = 0.1)]
    pub struct Chain;

    pub fn main() {}
}

mod unknown_key_suggestion {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 10, r = 0.8, thetabar = 0.58, k = 1.0e4)]
    pub struct Chain;

    pub fn main() {}
}

fn main() {
    duplicate_key::main();
    empty_attribute::main();
    malformed_items::main();
    missing_n::main();
    missing_theta_bar::main();
    spring_overridden_twice::main();
    spring_overrides_nothing::main();
    spring_unknown_key::main();
    theta_bar_and_rest_length::main();
    unknown_key::main();
    unknown_key_suggestion::main();
}
