//! After an error in the attribute, every use of the chain still type-checks against stubs of
//! the generated items: the only errors are the attribute's own. With `n` itself invalid, the
//! stubs take arrays of any length.
use rotor_chain::prelude::*;

#[rotor_chain(n = 6, r = -0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct BadRotor;

#[rotor_chain(n = 1, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct BadCount;

#[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(2, k = stiff))]
pub struct BadField {
    pub stiff: u32,
}

fn total(model: &impl ChainModel) -> f64 {
    model.energy(&vec![0.5; model.rotor_count()])
}

fn main() {
    let theta = [0.58f64; BadRotor::N];
    let c = BadRotor;
    let e: f64 = c.energy(&theta);
    let g: [f64; 6] = c.gradient(&theta);
    let h = c.hessian(&theta);
    let t = c.tangent_stiffness(&theta);
    let m = c.material_stiffness(&theta).diag[0] + c.stress_matrix(&theta).off[0];
    let l = c.spring_lengths(&theta)[0] + c.tensions(&theta)[1] + c.compatibility(&theta).right[0];
    let _ = (c.check(), c.next_angles(0, 0.5), BadRotor::SPRINGS);
    let _ = e + g[0] + h[(0, 0)] + t.diag[0] + t.off[0] + m + l + total(&c) + total(&BadCount);
    let _ = BadCount.gradient(&[0.58; 3])[2] + BadCount::N as f64;
    let _ = BadField { stiff: 3 }.energy(&theta);
}
