use rotor_chain::prelude::*;

// sqrt(a^2 + 4 r^2) = 1.887 for a = 1, r = 0.8: no uniform state has springs this long.
#[rotor_chain(n = 10, a = 1.0, r = 0.8, rest_length = 2.5, k = 1.0e4)]
pub struct Chain;

fn main() {}
