//! A malformed item of the attribute is one error at that item; the other items still count (no
//! "missing key" for keys that were given).
use rotor_chain::prelude::*;

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

fn main() {}
