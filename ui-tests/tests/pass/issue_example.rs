//! The example of the issue: literal parameters folded in, one impurity read from a field.
use rotor_chain::prelude::*;

#[rotor_chain(n = 60, a = 1.0, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0,
              spring(29, k = k_imp),
              spring(7, l0 = 2.30))]
pub struct Chain {
    pub k_imp: f64,
}

pub fn main() {
    let c = Chain { k_imp: 100.0 };
    c.check().expect("valid parameters");
    let theta = [0.58f64; 60];
    let e: f64 = c.energy(&theta);
    let g: [f64; 60] = c.gradient(&theta);
    let h = c.hessian(&theta);
    let [z0, z1] = c
        .next_angles(10, 0.58)
        .expect("spring 10 has a branch solve");
    assert!(e.is_finite() && e > 0.0, "only spring 7 is stretched: {e}");
    assert!(g.iter().all(|x| x.is_finite()));
    assert_eq!(h[(3, 4)], h[(4, 3)]);
    // Spring 10 is a uniform spring at rest in the uniform state: theta_bar is a root.
    assert!(
        (z0 - 0.58).abs() < 1e-9 || (z1 - 0.58).abs() < 1e-9,
        "{z0} {z1}"
    );
    assert_eq!(Chain::N, 60);
    assert_eq!(Chain::SPRINGS, 59);
}
