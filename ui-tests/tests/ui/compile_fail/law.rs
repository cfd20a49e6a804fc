//! Compile errors of `#[rotor_chain]`: custom spring laws: malformed, unknown symbols, unsupported methods.
//! One module per case, so the whole group is checked in one compilation; each error is
//! reported at its key and the snapshot (`.stderr`) lists them in the order of the modules.

mod malformed_laws {
    use rotor_chain::prelude::*;

    // One error per malformed law, at the law, and nothing else: no "missing key" for the keys that
    // were given, no "no method" at the calls below (the macro emits stubs beside its errors).

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = struct Foo;)]
    pub struct NotAnExpression;

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = k * (l - l0) +)]
    pub struct Incomplete;

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = k * sqrt(l - l0))]
    pub struct FunctionCall;

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = k * (l - l0).powi(2.0))]
    pub struct FloatExponent;

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = k * (l - l0) % 2.0)]
    pub struct Remainder;

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = 1e400 * k * (l - l0).powi(2))]
    pub struct LiteralOutOfRange;

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = 0.5f32 * k * (l - l0).powi(2))]
    pub struct LiteralWithSuffix;

    #[rotor_chain(n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = k * (((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((l - l0))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))]
    pub struct TooDeep;

    // Unrolled code grows with the law: the quartic law's derivation is larger than the harmonic
    // one's, so 512 rotors are too many to unroll with it.
    #[rotor_chain(n = 512, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 512,
                  law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2))]
    pub struct TooLargeToUnroll;

    pub fn main() {
        let theta = [0.58f64; 4];
        let _ = NotAnExpression.energy(&theta) + Incomplete.gradient(&theta)[0];
        let _ = FunctionCall.tangent_stiffness(&theta).diag[0] + FloatExponent.tensions(&theta)[0];
        let _ = Remainder.hessian(&theta)[(0, 0)] + LiteralOutOfRange.spring_lengths(&theta)[1];
        let _ = TooDeep.compatibility(&theta).left[0] + TooLargeToUnroll.energy(&[0.58; 512]);
    }
}

mod unknown_symbol {
    use rotor_chain::prelude::*;

    #[rotor_chain(
        n = 10,
        r = 0.8,
        theta_bar = 0.58,
        k = 1.0e4,
        law = k / 2.0 * (l - lbar).powi(2)
    )]
    pub struct Chain;

    pub fn main() {}
}

mod unsupported_method {
    use rotor_chain::prelude::*;

    #[rotor_chain(
        n = 10,
        r = 0.8,
        theta_bar = 0.58,
        k = 1.0e4,
        law = k * l0 * l0 * (l / l0 - 1.0).cosh()
    )]
    pub struct Chain;

    pub fn main() {}
}

fn main() {
    malformed_laws::main();
    unknown_symbol::main();
    unsupported_method::main();
}
