//! Every method that returns its result on the stack runs, at the largest chain it is generated
//! for, within the documented budget (`STACK_BUDGET` in `chain-macros/src/expand.rs`: 1 MiB in a
//! debug build, the caller's copy of the result and the evaluation's own frames included). Each call runs on a thread whose
//! stack is that budget plus 64 KiB for the thread itself; an overflow aborts the test binary.

use std::hint::black_box;

use rotor_chain::prelude::*;

const BUDGET: usize = 1 << 20;

/// The largest chain with `gradient()` (49152 values), `spring_lengths()` and `tensions()`.
#[rotor_chain(n = 49152, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Arrays;

/// The largest chain with the banded matrices (2n - 1 = 32767 values).
#[rotor_chain(n = 16384, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Banded;

/// The largest chain with `compatibility()` (2 (n - 1) = 32768 values).
#[rotor_chain(n = 16385, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Compatibility;

/// The largest chain with the dense `hessian()`, unrolled.
#[rotor_chain(n = 104, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Dense;

/// An unrolled chain (outputs are stored as computed: its stack use does not grow with n; the
/// 512-rotor measurement is in docs/macro.md, left out here for the suite's build time).
#[rotor_chain(n = 128, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Unrolled;

fn within_budget(what: &str, f: impl FnOnce() -> f64 + Send + 'static) {
    let value = std::thread::Builder::new()
        .stack_size(BUDGET + 64 * 1024)
        .spawn(f)
        .expect("thread")
        .join()
        .unwrap_or_else(|_| panic!("{what} panicked"));
    assert!(value.is_finite(), "{what}: {value}");
}

fn angles<const N: usize>() -> Box<[f64; N]> {
    let theta: Vec<f64> = (0..N).map(|i| 0.58 - 0.1 * (i as f64 * 0.01).sin()).collect();
    theta.into_boxed_slice().try_into().expect("N angles")
}

#[test]
fn arrays_of_49152_values() {
    within_budget("gradient", || black_box(Arrays.gradient(&angles())[7]));
    within_budget("spring_lengths", || black_box(Arrays.spring_lengths(&angles())[7]));
    within_budget("tensions", || black_box(Arrays.tensions(&angles())[7]));
}

#[test]
fn banded_matrices_of_16384_rotors() {
    within_budget("tangent_stiffness", || black_box(Banded.tangent_stiffness(&angles()).off[7]));
    within_budget("material_stiffness", || black_box(Banded.material_stiffness(&angles()).diag[7]));
    within_budget("stress_matrix", || black_box(Banded.stress_matrix(&angles()).diag[7]));
    within_budget("compatibility", || black_box(Compatibility.compatibility(&angles()).right[7]));
}

#[test]
fn the_dense_hessian_of_104_rotors_and_an_unrolled_chain() {
    within_budget("hessian", || black_box(Dense.hessian(&angles())[(7, 8)]));
    within_budget("unrolled gradient", || black_box(Unrolled.gradient(&angles())[7]));
    within_budget("unrolled tangent_stiffness", || black_box(Unrolled.tangent_stiffness(&angles()).off[7]));
    within_budget("unrolled compatibility", || black_box(Unrolled.compatibility(&angles()).left[7]));
    within_budget("unrolled energy", || black_box(Unrolled.energy(&angles())));
}
