//! Demonstration 2 of issue 36: a moving domain wall between two polarizations in a lattice of
//! coupled Kane-Lubensky chains (`chain_network::motion::wall`). Small lattices (4 chains of 32
//! rotors), each run well under a second in the debug build. References, none of them the code
//! under test: the chain code's own kink run (`RuntimeChain`, its specialised kernels), the
//! energies summed in this file from the tips' positions, the closed-form determinant of the
//! chain's Bloch compatibility matrix (its winding), and the exact count of a patch whose chains
//! are locked together.

use chain_core::RuntimeChain;
use chain_core::dynamics::launch::{Direction, launch};
use chain_core::integrate::{Phase, Verlet};
use chain_core::statics::walls::{Charge, domain_walls};
use chain_network::Cell;
use chain_network::motion::MotionError;
use chain_network::motion::wall::{CoupledChains, MovingWall};

/// 4 chains of 32 rotors; the wall goes from rotor 6 to about 21.6.
fn small(stagger: f64) -> CoupledChains {
    CoupledChains {
        chains: 4,
        cells: 16,
        start: 6.0,
        stagger,
        duration: 200.0,
        frames: 21,
        ..CoupledChains::default()
    }
}

/// The chain angles' tips: rotor `i` of chain `j` at `(i a + r sin theta, j h + (-1)^i r cos theta)`.
fn tip(c: &CoupledChains, j: usize, i: usize, theta: f64) -> [f64; 2] {
    let sign = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
    let r = c.rotor_length;
    [i as f64 * c.spacing + r * theta.sin(), j as f64 * c.row_spacing + sign * r * theta.cos()]
}

/// The potential energy from the tips: the chain's springs (rest length
/// `sqrt(a^2 + 4 r^2 cos^2 theta_bar)`, `k = 1`) and the inter-chain springs (rest `h`, `k_c`).
/// Returns (chain springs, inter-chain springs).
fn energies(c: &CoupledChains, theta: &[Vec<f64>]) -> (f64, f64) {
    let rest = (c.spacing.powi(2) + 4.0 * (c.rotor_length * c.theta_bar.cos()).powi(2)).sqrt();
    let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let (mut chain, mut inter) = (0.0, 0.0);
    for (j, row) in theta.iter().enumerate() {
        for i in 0..row.len() {
            if i + 1 < row.len() {
                chain += 0.5 * (dist(tip(c, j, i, row[i]), tip(c, j, i + 1, row[i + 1])) - rest).powi(2);
            }
            if let Some(next) = theta.get(j + 1) {
                let l = dist(tip(c, j, i, row[i]), tip(c, j + 1, i, next[i]));
                inter += 0.5 * c.coupling * (l - c.row_spacing).powi(2);
            }
        }
    }
    (chain, inter)
}

/// Kane and Lubensky's winding of the chain's cell, from its 2 x 2 Bloch compatibility matrix
/// written out here: rotors `u` (angle `pi/2 - t`) and `d` (`-pi/2 + t`), bond 0 `u -> d` in the
/// cell, bond 1 `d -> u` of the next cell (phase `z` on its `to` end), a tip's velocity
/// `r (-sin phi, cos phi) dphi`. `det Q(z) = A - B z`, one zero at `z = A / B`: the winding
/// along the chain is 1 when it lies inside the unit circle.
fn chain_winding(c: &CoupledChains, t: f64) -> i64 {
    let (a, r) = (c.spacing, c.rotor_length);
    let (pu, pd) = (std::f64::consts::FRAC_PI_2 - t, -std::f64::consts::FRAC_PI_2 + t);
    let tip_u = |shift: f64| [shift + r * pu.cos(), r * pu.sin()];
    let tip_d = [a + r * pd.cos(), r * pd.sin()];
    let unit = |p: [f64; 2], q: [f64; 2]| {
        let l = (q[0] - p[0]).hypot(q[1] - p[1]);
        [(q[0] - p[0]) / l, (q[1] - p[1]) / l]
    };
    let dot = |e: [f64; 2], phi: f64| r * (-e[0] * phi.sin() + e[1] * phi.cos());
    let (e0, e1) = (unit(tip_u(0.0), tip_d), unit(tip_d, tip_u(2.0 * a)));
    // Rows: bond 0 [-e0.t_u, e0.t_d], bond 1 [z e1.t_u, -e1.t_d].
    let big_a = dot(e0, pu) * dot(e1, pd);
    let big_b = dot(e0, pd) * dot(e1, pu);
    i64::from(big_a.abs() < big_b.abs())
}

#[test]
fn the_cell_file_is_the_cell_at_the_defaults() {
    let file =
        Cell::from_toml_file(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/coupled_chains.toml")).unwrap();
    let defaults = CoupledChains::default();
    assert_eq!(file, defaults.cell(defaults.theta_bar).unwrap());
}

#[test]
fn unstaggered_walls_move_as_the_chain_codes_kink() {
    let c = small(0.0);
    let run = c.run().unwrap();
    // The chain code: its own model, launch and Verlet at the run's step.
    let chain = RuntimeChain::builder(c.rotors(), c.rotor_length, 1.0, c.theta_bar).build().unwrap();
    let kink = launch(&chain, Charge::Kink, c.start, c.speed, Direction::Right).unwrap();
    let mut verlet =
        Verlet::new(&chain, Phase { time: 0.0, theta: kink.state.theta, omega: kink.state.omega }, run.dt)
            .unwrap();
    let steps = ((run.times[1] - run.times[0]) / run.dt).round() as usize;
    let mut worst: f64 = 0.0;
    for (k, walls) in run.walls.iter().enumerate() {
        if k > 0 {
            for _ in 0..steps {
                verlet.step(&chain).unwrap();
            }
        }
        assert!((verlet.state().time - run.times[k]).abs() < 1e-9 * run.times[k].max(1.0));
        let reference: Vec<f64> = domain_walls(verlet.theta())
            .iter()
            .filter(|w| w.charge == Charge::Kink)
            .map(|w| w.position)
            .collect();
        assert_eq!(reference.len(), 1, "the chain code's kink at t = {}", run.times[k]);
        for &x in walls {
            worst = worst.max((x - reference[0]).abs());
        }
    }
    assert!(worst < 1e-7, "walls differ from the chain code's by {worst:e} sites");
    // It moved: more than 10 rotors, every chain, at a steady speed.
    let last = run.walls.last().unwrap();
    assert!(last.iter().all(|&x| x - c.start > 10.0), "{last:?}");
    assert!(run.fit.slope > 0.0 && run.fit.rms_residual < 0.5, "{:?}", run.fit);
}

fn staggered() -> (CoupledChains, MovingWall) {
    let c = small(1.0);
    let run = c.run().unwrap();
    (c, run)
}

#[test]
fn staggered_walls_stay_together_and_keep_the_launch_energy() {
    let (c, run) = staggered();
    // The chains' walls start 1 rotor apart; the inter-chain springs hold them within it.
    let spread = run.spread();
    assert!((spread[0] - c.stagger).abs() < 0.05, "{spread:?}");
    assert!(spread.iter().all(|&s| s < 1.1 * c.stagger), "{spread:?}");
    let moved: Vec<f64> = run.walls.last().unwrap().iter().zip(&run.walls[0]).map(|(b, a)| b - a).collect();
    assert!(moved.iter().all(|&d| d > 10.0), "{moved:?}");
    // Energies from the tips, at every sample, against the run's.
    for k in 0..run.times.len() {
        let (chain, inter) = energies(&c, &run.theta[k]);
        assert!((run.potential[k] - chain - inter).abs() < 1e-12, "t = {}", run.times[k]);
        assert!((run.coupling_energy[k] - inter).abs() < 1e-12, "t = {}", run.times[k]);
    }
    // At the launch: the kinks' energy is zero (the chain springs at rest), the kinetic energy is
    // M v0^2 / 2 per chain (Appendix B's launch), the rest is the stagger in the inter-chain springs.
    let (chain0, inter0) = energies(&c, &run.theta[0]);
    assert!(chain0 < 1e-20, "{chain0:e}");
    assert!(inter0 > 1e-4);
    let launched = c.chains as f64 * 0.5 * c.speed * c.speed;
    assert!((run.kinetic[0] - launched).abs() < 1e-9 * launched);
    // No damping: the total stays the launch's (Verlet's error at 0.1 / omega_max).
    let total0 = launched + inter0;
    let drift =
        run.kinetic.iter().zip(&run.potential).map(|(k, p)| (k + p - total0).abs()).fold(0.0, f64::max);
    assert!(drift < 1e-4 * total0, "energy drift {drift:e} of {total0:e}");
}

#[test]
fn the_crossed_region_flips_its_polarization() {
    let (c, run) = staggered();
    let (n, m) = (c.cells, c.chains);
    // The exact count: the inter-chain springs lock the chains' linear motions (cos phi != 0), so
    // the free patch keeps the single chain's one floppy mode; the rest of the springs are
    // states of self-stress.
    let (dof, springs) = (2 * n * m, m * (2 * n - 1) + 2 * n * (m - 1));
    for side in [&run.before.left, &run.before.right, &run.after.left, &run.after.right] {
        let u = &side.uniform;
        assert_eq!((u.counts.dof, u.counts.bonds), (dof, springs));
        assert_eq!((u.counts.zero_modes, u.counts.self_stresses), (1, springs - dof + 1));
        // Relaxed to the uniform state: the mean tilt is its +-theta_bar.
        assert!((side.mean_tilt.abs() - c.theta_bar).abs() < 0.01, "{}", side.mean_tilt);
        assert_eq!(u.tilt, c.theta_bar.copysign(side.mean_tilt));
        // The polarization against the closed-form determinant, and where the floppy mode lives.
        assert_eq!(u.winding.winding, vec![chain_winding(&c, u.tilt)]);
        let last = (2 * n - 1) as f64;
        if u.winding.winding[0] == 0 {
            assert!(u.floppy_mode_centre > last - 1.0, "{}", u.floppy_mode_centre);
        } else {
            assert!(u.floppy_mode_centre < 1.0, "{}", u.floppy_mode_centre);
        }
    }
    // The kink: +theta_bar (winding 0) on its left, -theta_bar (winding 1) on its right, before
    // and after.
    for sides in [&run.before, &run.after] {
        assert_eq!(chain_winding(&c, sides.left.uniform.tilt), 0);
        assert_eq!(chain_winding(&c, sides.right.uniform.tilt), 1);
        assert!(sides.left.mean_tilt > 0.0 && sides.right.mean_tilt < 0.0);
    }
    // The region the wall crossed: 1 -> 0.
    let (b, a) = (&run.crossed_before, &run.crossed_after);
    assert!(b.to - b.from >= 4, "{}..{}", b.from, b.to);
    assert_eq!((b.from, b.to), (a.from, a.to));
    assert!((b.mean_tilt + c.theta_bar).abs() < 0.01 && (a.mean_tilt - c.theta_bar).abs() < 0.01);
    assert_eq!((b.uniform.winding.winding[0], a.uniform.winding.winding[0]), (1, 0));
}

#[test]
fn bad_parameters_are_refused_with_their_values() {
    let bad = |c: CoupledChains, name: &str| match c.run() {
        Err(MotionError::Parameter { name: n, .. }) => assert_eq!(n, name),
        other => panic!("{name}: {other:?}"),
    };
    let d = small(0.0);
    bad(CoupledChains { chains: 1, ..d }, "chains");
    bad(CoupledChains { cells: 4, ..d }, "cells");
    bad(CoupledChains { theta_bar: -0.3, ..d }, "theta_bar");
    bad(CoupledChains { speed: f64::NAN, ..d }, "speed");
    bad(CoupledChains { coupling: 0.0, ..d }, "coupling");
    bad(CoupledChains { start: 2.0, ..d }, "start");
    bad(CoupledChains { damping: -1.0, ..d }, "damping");
    bad(CoupledChains { frames: 1, ..d }, "frames");
    // A wall too slow to cross a region.
    match (CoupledChains { duration: 5.0, ..d }).run() {
        Err(MotionError::WallDidNotCross { start, end, margin }) => {
            assert!(start > 5.5 && end < start + 2.0 * margin, "{start} {end} {margin}")
        }
        other => panic!("{other:?}"),
    }
}
