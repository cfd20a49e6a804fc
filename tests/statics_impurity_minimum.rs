//! The antikink's Peierls-Nabarro minimum next to impurities, where the well lies between the
//! rotor and spring centrings (issue 34): `antikink_relaxed` descends the adiabatic path and
//! returns the minimum, never a saddle, or says where the antikink went.
//!
//! Every minimum is checked against the Cartesian reference model of tests/common (tip positions
//! from the angles, the springs' energies summed there; it shares no code with the library), with
//! derivatives taken here by finite differences:
//! - its gradient by central differences vanishes at the returned angles (moving rotors; the end
//!   rotors are held at `-theta_bar`, `+theta_bar`);
//! - its Hessian by second differences is positive definite (index 0: every pivot of its `LDL^T`
//!   positive) and its lowest eigenvalue (bisection of Sturm counts) is printed for the report;
//! - the energy along an independent constrained path (one core rotor's angle held on a grid,
//!   every other moving rotor relaxed by the test's own Newton iteration on the reference) is
//!   lowest at the returned configuration, to the grid's resolution.
//!
//! The same reference checks the saddle a descent steps off (index 1, its unstable direction
//! lowering the energy both ways) and `peierls_nabarro`'s landscape next to impurities: every free
//! equilibrium's index, and next to a stiff spring the reference's own path, the wall held on a
//! grid by a bordered Newton iteration written here, with its minima and maxima where the
//! landscape's are.

mod common;

use common::{K, R, Reference, chains, count_below, lowest, solve};
use rotor_chain::statics::StaticsError;
use rotor_chain::statics::antikink::{
    AntikinkOptions, Ends, PeierlsNabarro, antikink_at, antikink_relaxed, peierls_nabarro,
};
use rotor_chain::statics::kink::reflected_kink;
use rotor_chain::statics::path::{Descent, at_centre, descend};

/// Impurity springs: (spring, stiffness factor, rest-length factor).
type Overrides = &'static [(usize, f64, f64)];

/// The reference energy with rotor `i` moved by `hi` and rotor `j` by `hj`.
fn energy_moved(reference: &Reference, theta: &[f64], (i, hi): (usize, f64), (j, hj): (usize, f64)) -> f64 {
    let mut t = theta.to_vec();
    t[i] += hi;
    t[j] += hj;
    reference.energy(&t)
}

/// `dV/dtheta_i` of the reference by central differences (step 1e-6 rad).
fn fd_gradient(reference: &Reference, theta: &[f64], i: usize) -> f64 {
    let h = 1e-6;
    (energy_moved(reference, theta, (i, h), (i, 0.0)) - energy_moved(reference, theta, (i, -h), (i, 0.0)))
        / (2.0 * h)
}

/// The reference's Hessian on the moving rotors `1..n-1` by second differences (step 1e-4 rad),
/// tridiagonal: each spring couples two neighbouring rotors only.
fn fd_hessian(reference: &Reference, theta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = theta.len();
    let h = 1e-4;
    let v0 = reference.energy(theta);
    let d = (1..n - 1)
        .map(|i| {
            (energy_moved(reference, theta, (i, h), (i, 0.0)) - 2.0 * v0
                + energy_moved(reference, theta, (i, -h), (i, 0.0)))
                / (h * h)
        })
        .collect();
    let o = (1..n - 2)
        .map(|i| {
            let e = |a: f64, b: f64| energy_moved(reference, theta, (i, a), (i + 1, b));
            (e(h, h) - e(h, -h) - e(-h, h) + e(-h, -h)) / (4.0 * h * h)
        })
        .collect();
    (d, o)
}

/// The reference's lowest energy with rotor `j` held at `t` (and the ends held), by Newton's
/// method on its exact (num-dual) gradient and Hessian: holding `theta_j` splits the moving rotors
/// into the two tridiagonal blocks `1..j` and `j+1..n-1`, each solved on its own.
fn constrained_minimum(reference: &Reference, start: &[f64], j: usize, t: f64) -> Vec<f64> {
    let n = start.len();
    let mut theta = start.to_vec();
    theta[j] = t;
    for _ in 0..30 {
        let g = reference.gradient(&theta);
        for block in [1..j, j + 1..n - 1] {
            let rows: Vec<usize> = block.collect();
            let d: Vec<f64> = rows.iter().map(|&i| reference.hessian_entry(&theta, i, i)).collect();
            let o: Vec<f64> = rows.windows(2).map(|w| reference.hessian_entry(&theta, w[0], w[1])).collect();
            let rhs: Vec<f64> = rows.iter().map(|&i| -g[i]).collect();
            for (&i, s) in rows.iter().zip(solve(&d, &o, &rhs)) {
                theta[i] += s;
            }
        }
    }
    let g = reference.gradient(&theta);
    let force = (1..n - 1).filter(|&i| i != j).fold(0.0f64, |m, i| m.max(g[i].abs()));
    assert!(force < 1e-8, "the test's constrained Newton: force {force:e}");
    theta
}

/// The antikink's wall position (Appendix C), written here: the sign change from `-` to `+`.
fn wall(theta: &[f64]) -> f64 {
    let i = (0..theta.len() - 1).find(|&i| theta[i] < 0.0 && theta[i + 1] >= 0.0).expect("an antikink");
    i as f64 + theta[i] / (theta[i] - theta[i + 1])
}

/// What the reference says about a returned minimum: `(centre, energy, lowest curvature)`.
fn check_minimum(reference: &Reference, theta: &[f64], what: &str) -> (f64, f64, f64) {
    let n = theta.len();
    // Gradient: zero to the differences' accuracy. Scale: a spring's stiffness times r^2 (the
    // force on a rotor displaced by 1 rad); a point a hundredth of a site off the minimum carries
    // forces above 1e-4 of it.
    let force = (1..n - 1).fold(0.0f64, |m, i| m.max(fd_gradient(reference, theta, i).abs()));
    assert!(force < 1e-6 * K * R * R, "{what}: finite-difference force {force:e}");
    // Hessian: positive definite (every pivot positive), index 0.
    let (d, o) = fd_hessian(reference, theta);
    let negative = count_below(&d, &o, 0.0);
    assert_eq!(negative, 0, "{what}: finite-difference Hessian index");
    let curvature = lowest(&d, &o);
    assert!(curvature > 0.0, "{what}: lowest curvature {curvature:e}");
    // The constrained path: the core rotor nearest the wall held at t on a grid of 0.004 rad
    // (about 1/100 site) either side of its returned angle; the energy is lowest at the middle.
    let centre = wall(theta);
    let j = centre.round() as usize;
    let dt = 0.004;
    let path: Vec<(f64, f64)> = (-5..=5)
        .map(|m| {
            let t = constrained_minimum(reference, theta, j, theta[j] + m as f64 * dt);
            (wall(&t), reference.energy(&t))
        })
        .collect();
    let lowest_at = (0..path.len()).min_by(|&a, &b| path[a].1.total_cmp(&path[b].1)).unwrap();
    assert_eq!(lowest_at, 5, "{what}: the constrained path {path:?}");
    // The path passes through the centre and moves the wall monotonically.
    assert!(path.windows(2).all(|w| (w[1].0 - w[0].0) * (path[10].0 - path[0].0) > 0.0), "{what}: {path:?}");
    assert!((path[5].0 - centre).abs() < 1e-6, "{what}: {path:?}");
    (centre, reference.energy(theta), curvature)
}

/// The distance from `c` to the nearest rotor or spring centring.
fn off_centring(c: f64) -> f64 {
    (c - (2.0 * c).round() / 2.0).abs()
}

/// Impurities whose minimum lies between the centrings: stiff (2k, 5k), soft (0.3k), a shorter
/// rest length, and two impurities. `antikink_relaxed` from a start on the impurity's slope ends
/// at the minimum of the reference.
#[test]
fn the_minimum_between_centrings_next_to_impurities_is_the_references_minimum() {
    // (overrides, theta_bar, start, the least distance of the well from every centring)
    let cases: [(Overrides, f64, f64, f64); 6] = [
        (&[(19, 2.0, 1.0)], 0.4, 15.0, 0.02),
        (&[(19, 5.0, 1.0)], 0.4, 15.0, 0.02),
        (&[(19, 0.3, 1.0)], 0.55, 16.0, 0.02),
        (&[(19, 1.0, 0.995)], 0.4, 13.0, 0.2),
        (&[(19, 1.0, 1.01)], 0.5, 15.0, 0.1),
        (&[(16, 2.0, 1.0), (22, 0.3, 1.0)], 0.4, 12.0, 0.02),
    ];
    for (overrides, theta_bar, start, off) in cases {
        let what = format!("{overrides:?} at theta_bar = {theta_bar} from {start}");
        let (model, reference) = chains(40, theta_bar, overrides);
        let ours = antikink_relaxed(&model, start, &AntikinkOptions::default())
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(ours.is_free_minimum() && ours.classification.index == 0, "{what}");
        assert!(off_centring(ours.centre) >= off, "{what}: {} is on a centring", ours.centre);
        let (centre, energy, curvature) = check_minimum(&reference, &ours.theta, &what);
        assert!(
            (centre - ours.centre).abs() < 1e-12 && (energy - ours.energy).abs() < 1e-9 * energy,
            "{what}"
        );
        println!("{what}: centre {centre:.6}, energy {energy:.9}, lowest curvature {curvature:.6e}");
    }
}

/// With free ends there is no descent: the relaxed antikink is a centring solved as it is (the
/// lower of the two next to where the relaxation stopped), not a point between centrings.
#[test]
fn free_ends_keep_a_centring() {
    let (model, _) = chains(40, 0.4, &[(19, 2.0, 1.0)]);
    let free = AntikinkOptions { ends: Ends::Free, ..AntikinkOptions::default() };
    let a = antikink_relaxed(&model, 15.0, &free).unwrap();
    assert_eq!(a.requested, (2.0 * a.requested).round() / 2.0, "{}", a.requested);
    let at = antikink_at(&model, a.requested, &free).unwrap();
    assert_eq!((at.energy, at.centre, at.held), (a.energy, a.centre, a.held));
    // With held ends the same start ends between centrings (the first test's case).
    let held = antikink_relaxed(&model, 15.0, &AntikinkOptions::default()).unwrap();
    assert!(off_centring(held.centre) > 0.02, "{}", held.centre);
}

/// A descent confined to a region narrower than the way down says where it went: the region's
/// edge, its energy (lower than the start's) and the slope still falling outward.
#[test]
fn a_descent_that_leaves_its_region_reports_where_it_went() {
    let (model, reference) = chains(40, 0.4, &[(19, 2.0, 1.0)]);
    let options = AntikinkOptions::default();
    // On the impurity's slope: the antikink held at 17.0 by the path, descended within 0.3 sites.
    let guess = reflected_kink(&model, 17.0).unwrap();
    let slope = at_centre(&model, &guess, 17.0, &options).unwrap();
    // The reference's energy falls leftwards from there (the impurity repels).
    let mut left = slope.theta.clone();
    let j = 17;
    left = constrained_minimum(&reference, &left, j, left[j] + 0.02);
    assert!(wall(&left) < 17.0 && reference.energy(&left) < reference.energy(&slope.theta));
    assert!(slope.slope > 0.0, "{}", slope.slope);
    match descend(&model, &slope.theta, 0.3, &options) {
        Err(StaticsError::DescentLeftRegion { start, lo, hi, reached, energy, slope: s }) => {
            assert!((start - 17.0).abs() < 1e-9 && (lo - 16.7).abs() < 1e-9 && (hi - 17.3).abs() < 1e-9);
            assert_eq!(reached, lo);
            assert!(energy < slope.energy && s > 0.0, "{energy} {s}");
            // The reported energy is the reference's at that centre (the path's own point).
            let at = at_centre(&model, &slope.theta, reached, &options).unwrap();
            assert!((reference.energy(&at.theta) - energy).abs() < 1e-9 * energy);
        }
        other => panic!("{other:?}"),
    }
    // A reach that is no region is an error with the value, not a panic.
    for reach in [-1.0, f64::NAN] {
        match descend(&model, &slope.theta, reach, &options) {
            Err(StaticsError::InvalidValue { value, .. }) => assert!(value.is_nan() || value == reach),
            other => panic!("{reach}: {other:?}"),
        }
    }
    // With room the same descent ends at the bottom of a well.
    match descend(&model, &slope.theta, 8.0, &options).unwrap() {
        Descent::Bottom(b) => assert!(b.centre < 17.0 && b.slope.abs() < 1e-6 && b.index == 0, "{b:?}"),
        other => panic!("{other:?}"),
    }
}

/// A wide antikink (`theta_bar = 0.2`, n = 60, ends held): the ends push it toward the middle with
/// a force above the Peierls-Nabarro pinning until about nine sites from it. From the saddle the
/// descent ends at the minimum next to it (its translation curvature, `6e-11 ||K||`, is resolved
/// and not held); from near an end at the first well that holds it, off the centrings. Checked
/// with the reference's exact (num-dual) gradient and Hessian: the finite differences above do
/// not resolve a curvature of `4e-7`.
#[test]
fn a_wide_antikink_stops_in_the_first_well_that_holds_it() {
    let (model, reference) = chains(60, 0.2, &[]);
    let options = AntikinkOptions::default();
    let pn = peierls_nabarro(&model, &options).unwrap();
    let minimum = pn.minimum().unwrap();
    let from_saddle = antikink_relaxed(&model, 29.5, &options).unwrap();
    assert!(from_saddle.is_free_minimum());
    assert!(
        (from_saddle.centre - minimum.centre).abs() < 1e-4,
        "{} vs {}",
        from_saddle.centre,
        minimum.centre
    );
    assert!((from_saddle.energy - minimum.energy).abs() < 1e-11 * minimum.energy);
    let from_end = antikink_relaxed(&model, 3.0, &options).unwrap();
    assert!(from_end.is_free_minimum() && off_centring(from_end.centre) > 0.05, "{}", from_end.centre);
    let n = from_end.theta.len();
    for a in [&from_saddle, &from_end] {
        let d: Vec<f64> = (1..n - 1).map(|i| reference.hessian_entry(&a.theta, i, i)).collect();
        let o: Vec<f64> = (1..n - 2).map(|i| reference.hessian_entry(&a.theta, i, i + 1)).collect();
        let scale = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let force = reference.gradient(&a.theta)[1..n - 1].iter().fold(0.0f64, |m, g| m.max(g.abs()));
        assert!(force < 1e-12 * scale, "at {}: force {force:e}", a.centre);
        let curvature = lowest(&d, &o);
        // Above the rounding of a Sturm count (64 n eps ||K|| ~ 1e-12 ||K||), so resolved and positive.
        assert!(curvature > 1e-11 * scale, "at {}: lowest curvature {curvature:e}", a.centre);
        println!(
            "theta_bar = 0.2, n = 60: centre {:.6}, energy {:.12}, lowest curvature {curvature:.4e}",
            a.centre,
            reference.energy(&a.theta)
        );
    }
    // Higher than the middle's minimum: a local well, held by the pinning against the ends' pull.
    assert!(from_end.energy > minimum.energy);
}

/// Next to a soft spring the adiabatic path folds: from start 14.5 (n = 40, `theta_bar = 0.4`,
/// 0.3k at spring 19) the energy falls along it to c = 16.56, where Newton's method at a held
/// centre stops converging and a pair nucleates for a few steps beyond. The descent must not
/// take a step that converged to another branch there (a configuration of energy 4166, whose
/// bracket once led it to an index-1 saddle of that branch, stepped off to reach the minimum):
/// it ends the path at its last point and relaxes on down, into the pinned minimum at 19.5. The
/// reference checks the minimum; no saddle is stepped off, and the energy never rose above the
/// start's.
#[test]
fn a_descent_past_the_fold_of_the_path_reaches_the_pinned_minimum_without_climbing() {
    let what = "0.3k at spring 19, theta_bar = 0.4, from 14.5";
    let (model, reference) = chains(40, 0.4, &[(19, 0.3, 1.0)]);
    let ours =
        antikink_relaxed(&model, 14.5, &AntikinkOptions::default()).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(ours.is_free_minimum(), "{what}");
    let (centre, energy, curvature) = check_minimum(&reference, &ours.theta, what);
    assert!((centre - ours.centre).abs() < 1e-12 && (energy - ours.energy).abs() < 1e-9 * energy, "{what}");
    // Pinned on the soft spring: centred on it, far below the free antikink (475.48 at this
    // theta_bar, the closing note's table).
    assert!((centre - 19.5).abs() < 1e-6 && energy < 300.0, "{what}: {centre} {energy}");
    assert!(ours.step_offs.is_empty(), "{what}: a descent that climbed: {:?}", ours.step_offs);
    println!("{what}: minimum centre {centre:.6}, energy {energy:.9}, lowest curvature {curvature:.6e}");
    // The path itself, walked here with the library's `at_centre` on a 1/16-site grid from the
    // start: downhill until it folds, never above the start's energy where it converges.
    let start = antikink_at(&model, 14.5, &AntikinkOptions::default()).unwrap();
    let mut theta = start.theta.clone();
    let (mut converged, mut lowest_so_far) = (0, f64::INFINITY);
    for step in 0..=80 {
        let c = 14.5 + step as f64 / 16.0;
        if let Ok(p) = at_centre(&model, &theta, c, &AntikinkOptions::default()) {
            // Downhill all the way to the well's bottom at 19.5: each point at or below the last.
            assert!(p.energy <= lowest_so_far + 1e-9, "{what}: the path at {c} rose to {}", p.energy);
            lowest_so_far = p.energy;
            assert!((reference.energy(&p.theta) - p.energy).abs() < 1e-9 * p.energy, "{what}: at {c}");
            theta = p.theta;
            converged += 1;
        }
    }
    assert!(converged > 60, "{what}: the path converged at {converged} of 81 centres");
}

/// Solves the dense system `a` (each row: the coefficients, then the right-hand side) by Gaussian
/// elimination with partial pivoting.
fn gauss(mut a: Vec<Vec<f64>>) -> Vec<f64> {
    let m = a.len();
    for col in 0..m {
        let pivot = (col..m).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs())).unwrap();
        a.swap(col, pivot);
        let (top, below) = a.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for row in below {
            let factor = row[col] / pivot_row[col];
            row.iter_mut().zip(pivot_row).skip(col).for_each(|(x, p)| *x -= factor * p);
        }
    }
    let mut x = vec![0.0; m];
    for row in (0..m).rev() {
        let s: f64 = (row + 1..m).map(|k| a[row][k] * x[k]).sum();
        x[row] = (a[row][m] - s) / a[row][row];
    }
    x
}

/// The reference's lowest energy with the wall coordinate held at `c = i + f` (ends held):
/// Newton's method on the Lagrangian `V - mu ((1 - f) theta_i + f theta_{i+1})` with its exact
/// (num-dual) gradient and Hessian, each step the bordered system `[[H, -a], [a^T, 0]]` solved
/// densely (the free Hessian is singular where its lowest eigenvalue changes sign along the path;
/// the bordered matrix is not). Not the library's method (it eliminates an angle).
fn held_wall(reference: &Reference, start: &[f64], c: f64) -> Vec<f64> {
    let n = start.len();
    let (i, f) = (c.floor() as usize, c - c.floor());
    let m = n - 2;
    let weight = |r: usize| {
        if r == i {
            1.0 - f
        } else if r == i + 1 {
            f
        } else {
            0.0
        }
    };
    let mut theta = start.to_vec();
    for _ in 0..20 {
        let g = reference.gradient(&theta);
        let mut a = vec![vec![0.0; m + 2]; m + 1];
        for k in 0..m {
            let r = k + 1;
            a[k][k] = reference.hessian_entry(&theta, r, r);
            if k + 1 < m {
                let h = reference.hessian_entry(&theta, r, r + 1);
                (a[k][k + 1], a[k + 1][k]) = (h, h);
            }
            (a[k][m], a[m][k], a[k][m + 1]) = (-weight(r), weight(r), -g[r]);
        }
        a[m][m + 1] = -((1.0 - f) * theta[i] + f * theta[i + 1]);
        let x = gauss(a);
        theta[1..n - 1].iter_mut().zip(&x).for_each(|(t, d)| *t += d);
        if x[..m].iter().fold(0.0f64, |s, d| s.max(d.abs())) < 1e-13 {
            break;
        }
    }
    // Converged: the force is along the constraint's normal only.
    let g = reference.gradient(&theta);
    let norm2 = (1.0 - f) * (1.0 - f) + f * f;
    let lambda = ((1.0 - f) * g[i] + f * g[i + 1]) / norm2;
    let across = (1..n - 1).fold(0.0f64, |s, r| s.max((g[r] - lambda * weight(r)).abs()));
    assert!(across < 1e-8 * K * R * R, "the test's held wall at {c}: force {across:e}");
    assert!((wall(&theta) - c).abs() < 1e-9, "the test's held wall at {c}: {}", wall(&theta));
    theta
}

/// Every free equilibrium of the landscape is one by the reference (finite-difference gradient
/// zero, finite-difference Hessian of the same Morse index, 0 or 1).
fn check_equilibria(reference: &Reference, pn: &PeierlsNabarro, what: &str) {
    for a in pn.landscape.iter().filter(|a| a.held == 0) {
        let n = a.theta.len();
        let force = (1..n - 1).fold(0.0f64, |m, i| m.max(fd_gradient(reference, &a.theta, i).abs()));
        assert!(force < 1e-6 * K * R * R, "{what}: at {}: force {force:e}", a.centre);
        let (d, o) = fd_hessian(reference, &a.theta);
        let index = count_below(&d, &o, 0.0);
        assert!(index <= 1 && index == a.classification.index, "{what}: at {}: index {index}", a.centre);
    }
}

/// `peierls_nabarro` next to a stiff spring (19 at 5k, n = 40, theta_bar = 0.4, 0.5, 0.6), where
/// the symmetric guesses of the middle centrings split into a kink-antikink pair (before: the
/// whole analysis failed with `DefectLost`): it reports the landscape of the adiabatic path. The
/// reference's own path (the wall held on a grid of 1/16 site, `held_wall`) has its minima and
/// maxima where the landscape's minima and saddles are, to the grid's resolution; the repulsion is
/// the reference's energy at the last point of the path before the impurity; `minimum()` is no
/// minimum near the impurity and says where the antikink goes.
#[test]
fn peierls_nabarro_next_to_a_stiff_impurity_reports_the_landscape_of_the_path() {
    let options = AntikinkOptions::default();
    for theta_bar in [0.4, 0.5, 0.6] {
        let what = format!("5k at spring 19, theta_bar = {theta_bar}");
        let (model, reference) = chains(40, theta_bar, &[(19, 5.0, 1.0)]);
        let pn = peierls_nabarro(&model, &options).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(!pn.resolved, "{what}");
        check_equilibria(&reference, &pn, &what);
        // The reference's path left of the impurity, from the centring 12 to 18.5.
        let start = pn.landscape.iter().find(|a| a.requested == 12.0).expect("the centring 12");
        let grid: Vec<f64> = (0..=104).map(|k| 12.0 + k as f64 / 16.0).collect();
        let mut theta = start.theta.clone();
        let energies: Vec<f64> = grid
            .iter()
            .map(|&c| {
                theta = held_wall(&reference, &theta, c);
                reference.energy(&theta)
            })
            .collect();
        let extrema: Vec<(f64, usize)> = (1..grid.len() - 1)
            .filter_map(|k| {
                let (l, e, r) = (energies[k - 1], energies[k], energies[k + 1]);
                if e < l && e < r {
                    Some((grid[k], 0))
                } else if e > l && e > r {
                    Some((grid[k], 1))
                } else {
                    None
                }
            })
            .collect();
        let ours: Vec<(f64, usize)> = pn
            .landscape
            .iter()
            .filter(|a| a.held == 0 && a.centre > grid[1] && a.centre < grid[grid.len() - 2])
            .map(|a| (a.centre, a.classification.index))
            .collect();
        assert!(
            !ours.is_empty() && ours.len() == extrema.len(),
            "{what}: ours {ours:?}, reference {extrema:?}"
        );
        for (&(c, index), &(x, kind)) in ours.iter().zip(&extrema) {
            assert!(
                index == kind && (c - x).abs() <= 1.0 / 16.0,
                "{what}: ours {ours:?}, reference {extrema:?}"
            );
        }
        // From the last minimum to the impurity the energy rises (repulsion); the path ends before
        // the impurity's centring, and the impurity's energy is the reference's at that end.
        let last = ours.iter().rev().find(|o| o.1 == 0).unwrap().0;
        let k0 = grid.iter().position(|&c| c > last).unwrap();
        assert!(energies[k0..].windows(2).all(|w| w[1] > w[0]), "{what}: {:?}", &energies[k0..]);
        let e = pn.impurities[0];
        assert!(e.spring == 19 && e.centre > 18.5 && e.centre < 19.5, "{what}: {e:?}");
        let end = pn.landscape.iter().find(|a| a.requested == e.centre).expect("the path's end");
        let far = antikink_at(&model, e.reference, &options).unwrap();
        let expected = reference.energy(&end.theta) - reference.energy(&far.theta);
        assert!(
            expected > 0.0 && (e.energy - expected).abs() < 1e-9 * expected,
            "{what}: {e:?} vs {expected}"
        );
        assert!(reference.energy(&end.theta) > energies[grid.len() - 1], "{what}");
        // No minimum at the middle: the antikink asked there goes to the first minimum downhill.
        match pn.minimum() {
            Err(StaticsError::NoMinimum { found, index: 0, held: 0, .. }) => {
                assert!((found - last).abs() < 1e-9 && pn.rotor_centred.moved(), "{what}: {found}");
            }
            other => panic!("{what}: {:?}", other.map(|a| a.centre)),
        }
        println!(
            "{what}: minima and saddles {ours:?}; the path ends at {:.6}, repulsion {:.6}",
            e.centre, e.energy
        );
    }
}

/// The landscape's equilibria near soft (0.3k), stiff (2k), rest-length (0.995 l0) impurities
/// and two impurities are equilibria of the reference with its Morse index, and its minima include
/// the well between the centrings that `antikink_relaxed` reaches from a start nearby (checked
/// against the reference above; the symmetric guesses of the landscape before found none there).
#[test]
fn the_landscape_near_every_kind_of_impurity_agrees_with_the_reference() {
    // (overrides, theta_bar, a start of antikink_relaxed whose minimum is in the window)
    let cases: [(Overrides, f64, f64); 4] = [
        (&[(19, 0.3, 1.0)], 0.4, 14.5),
        (&[(19, 2.0, 1.0)], 0.4, 15.0),
        (&[(19, 1.0, 0.995)], 0.4, 13.0),
        (&[(16, 2.0, 1.0), (22, 0.3, 1.0)], 0.4, 21.0),
    ];
    let options = AntikinkOptions::default();
    for (overrides, theta_bar, start) in cases {
        let what = format!("{overrides:?} at theta_bar = {theta_bar}");
        let (model, reference) = chains(40, theta_bar, overrides);
        let pn = peierls_nabarro(&model, &options).unwrap_or_else(|e| panic!("{what}: {e}"));
        check_equilibria(&reference, &pn, &what);
        let free: Vec<(f64, usize)> =
            pn.landscape.iter().filter(|a| a.held == 0).map(|a| (a.centre, a.classification.index)).collect();
        let relaxed = antikink_relaxed(&model, start, &options).unwrap();
        assert!(
            pn.minima().any(|m| (m.centre - relaxed.centre).abs() < 1e-9),
            "{what}: {} not among {free:?}",
            relaxed.centre
        );
        println!("{what}: {free:.6?}; impurities {:?}", pn.impurities);
    }
}
