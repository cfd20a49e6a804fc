//! The uniform state given by the springs' rest length instead of the angle.
use rotor_chain::prelude::*;

#[rotor_chain(n = 8, a = 1.0, r = 0.8, rest_length = 1.7, k = 1.0e4)]
pub struct Chain;

pub fn main() {
    let c = Chain;
    c.check().expect("valid parameters");
    let tb = c.theta_bar();
    assert!(tb > 0.0 && tb < 0.675, "{tb}");
    let theta = [tb; 8];
    assert!(c.energy(&theta).abs() < 1e-9);
    for l in c.spring_lengths(&theta) {
        assert!((l - 1.7).abs() < 1e-12, "{l}");
    }
}
