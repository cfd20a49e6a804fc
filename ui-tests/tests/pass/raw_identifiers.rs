//! Raw identifiers anywhere: the struct's name, its fields, the keys, the law's symbols. A raw
//! name is the same name (`r#k_imp` is `k_imp`).
use rotor_chain::prelude::*;

#[rotor_chain(r#n = 300, r = 0.8, theta_bar = 0.58, k = r#type, spring(10, r#k = k_imp))]
pub struct r#Chain {
    pub r#type: f64,
    pub r#k_imp: f64,
}

#[rotor_chain(n = 8, r = 0.8, theta_bar = 0.58, k = r#type, law = r#k * (r#l - l0).powi(2) / 2.0)]
pub struct r#Unrolled {
    pub r#type: f64,
}

pub fn main() {
    let looped = r#Chain { r#type: 1.0e4, k_imp: 50.0 };
    looped.check().unwrap();
    let reference = RuntimeChain::builder(300, 0.8, 1.0e4, 0.58).spring_constant(10, 50.0).build().unwrap();
    let mut theta = vec![0.58; 300];
    theta[10] = 0.3;
    let e = Potential::energy(&looped, &theta);
    assert!((e - reference.energy(&theta)).abs() <= 1e-9 * e.abs(), "{e}");

    let unrolled = Unrolled { r#type: 1.0e4 };
    let harmonic = RuntimeChain::builder(8, 0.8, 1.0e4, 0.58).build().unwrap();
    let theta = [0.58, 0.5, 0.3, 0.1, -0.2, -0.4, -0.5, -0.58];
    let e = unrolled.energy(&theta);
    assert!((e - harmonic.energy(&theta)).abs() <= 1e-9 * e.abs(), "{e}");
}
