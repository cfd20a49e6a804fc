//! Past the unroll limit the generated code drives a per-spring kernel in a loop.
use rotor_chain::prelude::*;

#[rotor_chain(n = 300, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(150, k = 50.0))]
pub struct Long;

pub fn main() {
    let c = Long;
    let theta = [0.58f64; 300];
    assert!(c.energy(&theta).abs() < 1e-9);
    let mut bent = theta;
    bent[150] = 0.4;
    assert!(c.energy(&bent) > 0.0);
    let t = c.tangent_stiffness(&bent);
    assert_eq!(t.diag.len(), 300);
    assert_eq!(t.off.len(), 299);
    assert!(t.diag.iter().all(|x| x.is_finite()));
}
