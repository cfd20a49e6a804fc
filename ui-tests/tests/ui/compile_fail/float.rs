//! Compile errors of `#[rotor_chain]`: `float = f32` values and the rules of single-precision chains.
//! One module per case, so the whole group is checked in one compilation; each error is
//! reported at its key and the snapshot (`.stderr`) lists them in the order of the modules.

mod bad_float_value {
    use rotor_chain::prelude::*;

    // A type the chain cannot compute in, with the nearest supported one suggested.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f16)]
    pub struct Half;

    // A misspelled type.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f23)]
    pub struct Typo;

    // A string, not a type.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = "f32")]
    pub struct Quoted;

    // A bit width, not a type.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = 32)]
    pub struct Width;

    // An integer type.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = u32)]
    pub struct Integer;

    // No value.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float =)]
    pub struct Missing;

    // Given twice.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f32, float = f64)]
    pub struct Twice;

    pub fn main() {}
}

mod f32_chain_rules {
    use rotor_chain::prelude::*;

    // A parameter field of an f32 chain must be declared f32.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = stiffness, float = f32)]
    pub struct WideField {
        pub stiffness: f64,
    }

    // A literal beyond f32's range.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e40, float = f32)]
    pub struct TooStiff;

    // A literal that rounds to zero in f32.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0e-50, float = f32)]
    pub struct TooLight;

    // f32 chains are unrolled only.
    #[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0, float = f32)]
    pub struct Looped;

    pub fn main() {}
}

fn main() {
    bad_float_value::main();
    f32_chain_rules::main();
}
