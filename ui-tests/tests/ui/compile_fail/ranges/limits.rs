//! The documented limits, each an error at its key; and what a chain too long for an array on the
//! stack offers instead: the `ChainModel` slice methods.
use rotor_chain::prelude::*;

#[rotor_chain(n = 100000001, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct TooManyRotors;

#[rotor_chain(n = 513, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 513)]
pub struct UnrollTooLarge;

// 49153 rotors: `gradient()` would return 384 KiB and a byte on the stack, so it is not generated.
#[rotor_chain(n = 49153, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct Long;

fn main() {
    let theta = vec![0.58; Long::N];
    let mut g = vec![0.0; Long::N];
    ChainModel::gradient_into(&Long, &theta, &mut g);
    let fixed: &[f64; 49153] = theta.as_slice().try_into().unwrap();
    let _ = Long.gradient(fixed);
}
