//! Geometry read from struct fields: checked at run time by the generated `check()`.
use rotor_chain::prelude::*;

#[rotor_chain(n = 5, a = aa, r = rr, theta_bar = tb, k = 1.0e4)]
pub struct Chain {
    pub tb: f64,
    pub rr: f64,
    pub aa: f64,
}

pub fn main() {
    let ok = Chain {
        tb: 0.58,
        rr: 0.8,
        aa: 1.0,
    };
    ok.check().expect("inside the flipper phase");
    assert!(ok.energy(&[0.58; 5]).abs() < 1e-9);

    let wobbler = Chain { tb: 0.7, ..ok };
    let err = wobbler.check().expect_err("past the flipper phase");
    assert!(err.to_string().contains("flipper phase"), "{err}");

    let negative = Chain { rr: -0.8, ..ok };
    assert!(negative.check().is_err());
}
