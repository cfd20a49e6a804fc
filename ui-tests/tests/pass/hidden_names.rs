//! Looped chains whose names differ only in case or underscores do not collide: everything the
//! macro generates besides the struct lives in an anonymous `const _`.
#![allow(non_camel_case_types)]
use rotor_chain::prelude::*;

#[rotor_chain(n = 200, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
pub struct FooBar;

#[rotor_chain(n = 200, r = 0.8, theta_bar = 0.58, k = 2.0e4, unroll = 0)]
pub struct Foo_Bar;

#[rotor_chain(n = 200, r = 0.8, theta_bar = 0.58, k = 4.0e4, unroll = 0)]
pub struct FOO_BAR;

mod inner {
    use rotor_chain::prelude::*;

    #[rotor_chain(n = 200, r = 0.8, theta_bar = 0.58, k = 8.0e4, unroll = 0)]
    pub struct FooBar;
}

pub fn main() {
    let mut theta = [0.58f64; 200];
    theta[100] = 0.2;
    let e = FooBar.energy(&theta);
    assert!(e > 0.0);
    for (ratio, other) in [(2.0, Foo_Bar.energy(&theta)), (4.0, FOO_BAR.energy(&theta)), (8.0, inner::FooBar.energy(&theta))] {
        assert!((other / e - ratio).abs() < 1e-12, "{other} / {e}");
    }
}
