//! Ready cells of the standard lattices: square, kagome, Kane-Lubensky's deformed kagome by
//! `(x1, x2, x3; z)`, the twisted kagome, and the paper's rotor chain with either lean.
//!
//! Every joint lattice here has unit lattice constant; bonds have `k = 1` and rest at their
//! reference length.

use super::Cell;
use std::f64::consts::{FRAC_PI_2, PI};

/// The square lattice: one joint per cell, bonds along `a1 = (1, 0)` and `a2 = (0, 1)`.
pub fn square() -> Cell {
    Cell::builder(2, &[[1.0, 0.0], [0.0, 1.0]])
        .joint("a", [0.0, 0.0])
        .bond("a", "a", &[1, 0])
        .bond("a", "a", &[0, 1])
        .build()
        .expect("the square cell is valid")
}

/// The regular kagome lattice: [`deformed_kagome`] at `(0, 0, 0; 0)`.
pub fn kagome() -> Cell {
    deformed_kagome(0.0, 0.0, 0.0, 0.0).expect("the kagome cell is valid")
}

/// Kane and Lubensky's lattice vectors `a_p = (cos 2 pi (p-1)/3, sin 2 pi (p-1)/3)`, `p = 1, 2, 3`
/// (Nature Physics 10, 39 (2014), "Deformed Kagome Lattice Model"): `a3 = -a1 - a2`. The cell's
/// lattice vectors are `a1` and `a2`.
pub fn kane_lubensky_vectors() -> [[f64; 2]; 3] {
    std::array::from_fn(|p| {
        let angle = 2.0 * PI * p as f64 / 3.0;
        [angle.cos(), angle.sin()]
    })
}

/// Kane and Lubensky's deformed kagome lattice `(x1, x2, x3; z)`.
///
/// Their parametrisation: sites `d1 = a1/2 + s2`, `d2 = a2/2 - s1`, `d3 = a3/2` with
/// `s_p = x_p (a_{p-1} - a_{p+1}) + y_p a_p` and `y_p = z/3 + x_{p-1} - x_{p+1}` (indices mod 3).
/// `x_p` buckles the line of bonds along `a_p` (straight when `x_p = 0`, where the gap closes on
/// the line `k . a_p = 0`); `z` makes the two triangles unequal; `(x, x, x; 0)` is the twisted
/// kagome lattice with twist `atan(2 sqrt 3 x)`; `(0, 0, 0; 0)` the regular kagome lattice.
///
/// The six bonds are the edges of the hexagon around the origin (`d_p` to `d_q - a_q`), their
/// "standard unit cell": its dipole `r0 = 2 sum d_i - sum d_bond` is zero, so the polarization
/// is `R_T = -(n1 a1 + n2 a2)` (eq. 11 there: `R_T = sum_p a_p sign(x_p) / 2`).
///
/// Errors if the parameters make two sites coincide (a zero-length bond).
pub fn deformed_kagome(x1: f64, x2: f64, x3: f64, z: f64) -> Result<Cell, crate::CellError> {
    let a = kane_lubensky_vectors();
    let x = [x1, x2, x3];
    let s: [[f64; 2]; 3] = std::array::from_fn(|p| {
        let (prev, next) = ((p + 2) % 3, (p + 1) % 3);
        let y = z / 3.0 + x[prev] - x[next];
        [x[p] * (a[prev][0] - a[next][0]) + y * a[p][0], x[p] * (a[prev][1] - a[next][1]) + y * a[p][1]]
    });
    let half = |v: [f64; 2]| [0.5 * v[0], 0.5 * v[1]];
    let d1 = [0.5 * a[0][0] + s[1][0], 0.5 * a[0][1] + s[1][1]];
    let d2 = [0.5 * a[1][0] - s[0][0], 0.5 * a[1][1] - s[0][1]];
    let d3 = half(a[2]);
    // a3 = -a1 - a2: the cell offset of -a3 is [1, 1].
    Cell::builder(2, &[a[0], a[1]])
        .joint("d1", d1)
        .joint("d2", d2)
        .joint("d3", d3)
        .bond("d1", "d3", &[1, 1])
        .bond("d2", "d3", &[1, 1])
        .bond("d2", "d1", &[-1, 0])
        .bond("d3", "d1", &[-1, 0])
        .bond("d3", "d2", &[0, -1])
        .bond("d1", "d2", &[0, -1])
        .build()
}

/// The twisted kagome lattice of Sun, Souslov, Mao and Lubensky (PNAS 109, 12369 (2012)) with
/// twist angle `alpha` (radians): [`deformed_kagome`] at `(x, x, x; 0)`, `x = tan(alpha)/(2 sqrt 3)`.
pub fn twisted_kagome(alpha: f64) -> Result<Cell, crate::CellError> {
    let x = alpha.tan() / (2.0 * 3f64.sqrt());
    deformed_kagome(x, x, x, 0.0)
}

/// Which way the paper's rotors lean in the uniform state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lean {
    /// `theta_bar > 0`: every tip leans towards `+x`.
    Right,
    /// `theta_bar < 0`: every tip leans towards `-x`.
    Left,
}

/// The paper's rotor chain as a periodic rotor network (`docs/theory.md` section 1): a cell of
/// two rotors of length `r` on pivots `(0, 0)` ("up") and `(a, 0)` ("down"), lattice vector
/// `(2a, 0)`, in the uniform state `theta_i = theta_bar`. The chain's angle is measured from the
/// vertical, so the file format's angles are `phi = pi/2 - theta_bar` (up) and
/// `phi = -pi/2 + theta_bar` (down), and the degrees of freedom are `r dphi = -r dtheta` (up) and
/// `+r dtheta` (down). Bonds: up to down in cell 0, down to up in cell 1.
pub fn rotor_chain(a: f64, r: f64, theta_bar: f64) -> Result<Cell, crate::CellError> {
    Cell::builder(1, &[[2.0 * a, 0.0]])
        .rotor("up", [0.0, 0.0], r, FRAC_PI_2 - theta_bar)
        .rotor("down", [a, 0.0], r, -FRAC_PI_2 + theta_bar)
        .bond("up", "down", &[0])
        .bond("down", "up", &[1])
        .build()
}

/// The paper's chain (`a = 1`, `r = 0.8`, `theta_bar = 0.58`) leaning `lean`.
pub fn paper_chain(lean: Lean) -> Cell {
    let theta_bar = match lean {
        Lean::Right => 0.58,
        Lean::Left => -0.58,
    };
    rotor_chain(1.0, 0.8, theta_bar).expect("the paper's chain is valid")
}
