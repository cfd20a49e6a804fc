//! The largest chain compiles (looped, no arrays of its size on the stack), and so does the longest
//! unrolled one.
use rotor_chain::prelude::*;

#[rotor_chain(n = 100000000, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct Largest;

#[rotor_chain(n = 49152, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct LongestGradient;

pub fn main() {
    assert_eq!(Largest::N, 100_000_000);
    assert_eq!(SpringNetwork::spring_count(&Largest), 99_999_999);
    Largest.check().unwrap();
    let theta = vec![0.58; LongestGradient::N];
    let fixed: &[f64; 49152] = theta.as_slice().try_into().unwrap();
    let g = LongestGradient.gradient(fixed);
    assert!(g.iter().all(|x| x.abs() < 1e-6));
}
