//! A user-given spring law, differentiated by the macro.
use rotor_chain::prelude::*;

#[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4,
              law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2))]
pub struct Quartic;

pub fn main() {
    let c = Quartic;
    let rest = [0.58f64; 6];
    assert!(c.energy(&rest).abs() < 1e-9);
    assert!(c.gradient(&rest).iter().all(|g| g.abs() < 1e-6));
    let theta = [0.58, 0.5, 0.58, 0.6, 0.58, 0.55];
    assert!(c.energy(&theta) > 0.0);
    let t = c.tangent_stiffness(&theta);
    assert!(t.diag.iter().chain(&t.off).all(|x| x.is_finite()));
}
