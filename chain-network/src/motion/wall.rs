//! A moving domain wall between two polarizations in a 2D lattice of coupled Kane-Lubensky
//! chains (issue 36, demonstration 2).
//!
//! **The lattice.** `M` copies of the paper's rotor chain (Kane and Lubensky, *Topological
//! boundary modes in isostatic lattices*, Nature Physics 10, 39 (2014), arXiv:1308.0554, §2-3;
//! Chen, Upadhyaya and Vitelli, PNAS 111, 13004 (2014)) stacked a distance `h` apart along `y`:
//! pivots at `(i a, j h)`, rotor `i` of chain `j` up (even `i`) or down (odd `i`), arms `r`,
//! neighbouring rotors of a chain joined by springs, and every rotor tied to the same rotor of
//! the next chain by an **inter-chain spring** of constant `k_c` and rest length `h`. Two rotors
//! of one column at the same angle have tips exactly `(0, h)` apart, so every state in which all
//! chains carry the same angles, a straight wall across the chains among them, leaves the
//! inter-chain springs at rest: the chain's zero-energy kink (`+theta_bar` on its left,
//! `-theta_bar` on its right) is a zero-energy wall of the lattice, and it moves. The 2D cell
//! (two rotors, four springs) is built in code by [`CoupledChains::cell`] and read from
//! `chain-network/cells/coupled_chains.toml` at the defaults.
//!
//! **Why this lattice.** It is the chain's own kink, so the wall's energy (zero) and its launch
//! (the chain code's translation mode, [`launch`]) are known exactly, and the polarization on
//! each side is the chain's: the tilt decides which end carries the floppy mode. The price is
//! honesty about the counts: the inter-chain springs make the cell over-constrained (two degrees
//! of freedom, four springs), no coupling of rotor tips keeps it Maxwell (the chain alone already
//! has one spring per rotor), so the 2D cell has no winding number of its own (Kane and
//! Lubensky's winding needs a square `Q(k)`). What is reported is therefore:
//! - the Maxwell-Calladine counts `N0` and `S` of the free `N x M` patch of each side's uniform
//!   state (the dense SVD of [`counts`]), both of them, not only `N0 - S = dof - springs`; for
//!   every tilt `N0 = 1` (the inter-chain springs lock the chains' linear motions together,
//!   `cos phi != 0`, leaving the single chain's floppy mode) and `S = springs - dof + 1`;
//! - where that floppy mode lives ([`null_spaces`]: the centre of its weight, in rotors);
//! - the polarization as the [`winding`] number of each side's **row cell** (the chain's cell,
//!   [`ready::rotor_chain`]) along the chains: 0 for `theta_bar > 0` (the floppy mode at the
//!   right end), 1 for `theta_bar < 0` (at the left end), §4 and §5 of the network guide.
//!
//! **The run.** Every chain is launched with the chain code's kink [`launch`] on a chain view of
//! one row (`M v0^2 / 2` of kinetic energy along the kink's translation mode, towards the right),
//! optionally staggered from chain to chain, so the inter-chain springs pull the walls together.
//! Velocity Verlet (optional uniform damping) integrates the whole patch; each sample records
//! every angle, the energies and each chain's wall position (Appendix C, [`domain_walls`]).
//! Before and after, the regions left and right of the wall and the region the wall crossed are
//! measured (mean tilt, largest deviation from it) and given the counts and polarization of
//! their uniform state: the crossed region goes from the right side's (`-theta_bar`, winding 1)
//! to the left side's (`+theta_bar`, winding 0), its polarization flipped.

use super::MotionError;
use super::front::{LineFit, fit_line};
use crate::cell::{Cell, ready};
use crate::counts::{Counts, counts, null_spaces};
use crate::model::{ChainView, NetworkModel};
use crate::patch::{Boundary, MAX_PATCH_BONDS, Patch};
use crate::winding::{Winding, WindingOptions, winding};
use chain_core::dynamics::launch::{Direction, launch};
use chain_core::dynamics::run::MAX_SPACE_TIME_VALUES;
use chain_core::integrate::{MAX_STEP_BUDGET, Phase, Verlet};
use chain_core::statics::walls::{Charge, domain_walls, wall_width};
use chain_core::validate::{Fields, Validate};
use chain_core::{Potential, SpringNetwork};
use std::f64::consts::FRAC_PI_2;

/// Verlet's steps are `omega_max dt = 0.1`.
const STEP_FRACTION: f64 = 0.1;

/// The lattice and the run. Units: the pivot spacing `a`, the rotor mass `M = 1` (inertia
/// `M r^2`), the chain's spring constant `k = 1`; time in `sqrt(M / k)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoupledChains {
    /// Chains (rows), between 2 and [`MAX_PATCH_BONDS`]` / 8` (the patch rule's bound, at the
    /// fewest cells per chain). Default 6.
    pub chains: usize,
    /// Cells per chain, two rotors each, between 8 and [`MAX_PATCH_BONDS`]` / chains` (the patch
    /// holds `cells x chains` cells). Default 24 (48 rotors).
    pub cells: usize,
    /// Pivot spacing `a`. Default 1 (the paper's).
    pub spacing: f64,
    /// Rotor length `r`. Default 0.8 (the paper's).
    pub rotor_length: f64,
    /// The tilt `theta_bar` (radians, in `(0, pi/2)`) of the wall's left side; the right side has
    /// `-theta_bar`. Default 0.58 (the paper's).
    pub theta_bar: f64,
    /// Distance `h` between chains. Default 2: the tips (`r cos theta_bar = 0.67` above and
    /// below a chain's line) of neighbouring chains stay apart in the drawings.
    pub row_spacing: f64,
    /// Inter-chain spring constant `k_c`. Default 1, as the chain's springs.
    pub coupling: f64,
    /// The launch's speed amplitude `v0` (`a / t`, kinetic energy `M v0^2 / 2` per chain).
    /// Default 0.05: well below the sound speed, so the wall keeps its shape.
    pub speed: f64,
    /// Where the wall starts (rotor index, chains' mean). Default 12.
    pub start: f64,
    /// Offset between the walls of the first and the last chain at the launch (rotors; the
    /// chains' walls evenly between), so the inter-chain springs have something to do. Default 1.
    pub stagger: f64,
    /// Damping rate `gamma >= 0` of every rotor (1 / t). Default 0: the energy is conserved.
    pub damping: f64,
    /// Length of the run. Default 300: at the defaults the wall moves about 27 rotors, from 12
    /// to 39 of 48. At most [`MAX_STEP_BUDGET`] Verlet steps of `0.1 / omega_max`.
    pub duration: f64,
    /// Samples of the state (frames). Default 31 (every 10). Between 2 and
    /// [`MAX_SPACE_TIME_VALUES`]` / rotors`: a frame keeps every rotor's angle, bounded as a
    /// run's space-time image.
    pub frames: usize,
}

impl Default for CoupledChains {
    fn default() -> Self {
        Self {
            chains: 6,
            cells: 24,
            spacing: 1.0,
            rotor_length: 0.8,
            theta_bar: 0.58,
            row_spacing: 2.0,
            coupling: 1.0,
            speed: 0.05,
            start: 12.0,
            stagger: 1.0,
            damping: 0.0,
            duration: 300.0,
            frames: 31,
        }
    }
}

/// The uniform state of one tilt: the counts of its free patch, where its floppy mode lives and
/// the polarization of its row cell.
#[derive(Clone, Debug)]
pub struct Polarized {
    /// The tilt `+theta_bar` or `-theta_bar`.
    pub tilt: f64,
    /// Maxwell-Calladine counts of the free `cells x chains` patch of the 2D cell at this tilt.
    pub counts: Counts,
    /// The centre of the zero modes' weight along the chains (rotor index, `0 ..= 2 cells - 1`).
    pub floppy_mode_centre: f64,
    /// The winding number and polarization of the row cell (the chain's) at this tilt.
    pub winding: Winding,
}

/// A region of the lattice (rotors `from .. to` of every chain) in one sample.
#[derive(Clone, Debug)]
pub struct Region {
    /// First rotor.
    pub from: usize,
    /// One past the last rotor.
    pub to: usize,
    /// The mean chain angle `theta` over the region's rotors of every chain.
    pub mean_tilt: f64,
    /// The largest `|theta - mean_tilt|` in the region (the launch's phonons).
    pub largest_deviation: f64,
    /// The uniform state of the region's tilt (the sign of `mean_tilt`).
    pub uniform: Polarized,
}

/// The regions on the two sides of the wall in one sample.
#[derive(Clone, Debug)]
pub struct Sides {
    /// The sample's time.
    pub time: f64,
    /// The wall's position (chains' mean, rotors).
    pub wall: f64,
    /// Left of the wall.
    pub left: Region,
    /// Right of the wall.
    pub right: Region,
}

/// The run and its measurements.
#[derive(Clone, Debug)]
pub struct MovingWall {
    /// The Verlet step (`0.1 / omega_max` or just below, a whole number of steps per frame).
    pub dt: f64,
    /// Sample times.
    pub times: Vec<f64>,
    /// The chain angles `theta` per sample, chain by chain (`[sample][chain][rotor]`).
    pub theta: Vec<Vec<Vec<f64>>>,
    /// Each chain's wall position per sample (`[sample][chain]`, rotors; Appendix C).
    pub walls: Vec<Vec<f64>>,
    /// Kinetic energy per sample.
    pub kinetic: Vec<f64>,
    /// Potential energy per sample.
    pub potential: Vec<f64>,
    /// Of those, the inter-chain springs' energy per sample.
    pub coupling_energy: Vec<f64>,
    /// The line through the chains' mean wall position against time.
    pub fit: LineFit,
    /// The two sides at the launch.
    pub before: Sides,
    /// The two sides at the end.
    pub after: Sides,
    /// The region the wall crossed, at the launch.
    pub crossed_before: Region,
    /// The same region at the end.
    pub crossed_after: Region,
}

impl MovingWall {
    /// The largest distance between two chains' walls, per sample.
    pub fn spread(&self) -> Vec<f64> {
        self.walls.iter().map(|w| spread(w)).collect()
    }
}

fn spread(walls: &[f64]) -> f64 {
    let (lo, hi) = walls.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    hi - lo
}

impl Validate for CoupledChains {
    type Error = MotionError;

    /// `spacing`, `rotor_length`, `row_spacing`, `coupling`, `speed` and `duration` positive and
    /// finite, `theta_bar` in `(0, pi/2)`, `damping` and `stagger` finite and `>= 0`, `chains` in
    /// `2..=MAX_PATCH_BONDS / 8`, `cells` in `8..=MAX_PATCH_BONDS / chains`, `frames` in `2..=`
    /// the space-time bound over the rotors, a run of at most [`MAX_STEP_BUDGET`] steps, and
    /// every chain's wall (`start +- stagger / 2`) at least 4 rotors from an end.
    fn validate(&self) -> Result<(), MotionError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self {
            chains,
            cells,
            spacing,
            rotor_length,
            theta_bar,
            row_spacing,
            coupling,
            speed,
            start,
            stagger,
            damping,
            duration,
            frames,
        } = *self;
        let fields = Fields("CoupledChains");
        // The patch holds `cells x chains` cells; the patch rule bounds its bonds exactly when it
        // is built, these bounds its cells (so that the frames' bound below is at least 2).
        let rule = "between 2 and MAX_PATCH_BONDS / 8 = 4194304 (a patch of 8 cells per chain)";
        fields.count_in("chains", chains as u64, 2, (MAX_PATCH_BONDS / 8) as u64, rule)?;
        let rule = "between 8 and MAX_PATCH_BONDS / chains = 33554432 / chains (the patch's cells)";
        fields.count_in("cells", cells as u64, 8, (MAX_PATCH_BONDS / chains) as u64, rule)?;
        fields.positive("spacing", spacing)?;
        fields.positive("rotor_length", rotor_length)?;
        fields.rule(
            "theta_bar",
            theta_bar,
            theta_bar > 0.0 && theta_bar < FRAC_PI_2,
            "in (0, pi/2): the left side's tilt",
        )?;
        fields.positive("row_spacing", row_spacing)?;
        fields.positive("coupling", coupling)?;
        fields.positive("speed", speed)?;
        fields.non_negative("stagger", stagger)?;
        let n = 2.0 * cells as f64;
        fields.rule(
            "start",
            start,
            start - stagger / 2.0 >= 4.0 && start + stagger / 2.0 <= n - 5.0,
            "such that every chain's wall (start +- stagger / 2) is at least 4 rotors from an end",
        )?;
        fields.non_negative("damping", damping)?;
        fields.positive("duration", duration)?;
        fields.rule(
            "duration",
            duration,
            duration * self.omega_max() / STEP_FRACTION <= MAX_STEP_BUDGET as f64,
            "at most MAX_STEP_BUDGET = 10000000000 Verlet steps of 0.1 / omega_max",
        )?;
        let rotors = self.rotors().saturating_mul(chains).max(1);
        fields.count_in(
            "frames",
            frames as u64,
            2,
            (MAX_SPACE_TIME_VALUES / rotors) as u64,
            "between 2 and MAX_SPACE_TIME_VALUES / rotors = 134217728 / (2 cells x chains)",
        )?;
        Ok(())
    }
}

impl CoupledChains {
    /// Rotors per chain.
    pub fn rotors(&self) -> usize {
        2 * self.cells
    }

    /// Gershgorin: each rotor has two chain and two inter-chain springs, each adding at most
    /// `k r^2` to its row of the stiffness and as much off it: `omega^2 <= 4 (k + k_c) / M`.
    fn omega_max(&self) -> f64 {
        (4.0 * (1.0 + self.coupling)).sqrt()
    }

    /// The 2D cell at tilt `tilt`: the chain's cell (`up` at the origin, `down` at `(a, 0)`,
    /// springs `up -> down` and `down -> up` of the next cell, `k = 1`), stacked along
    /// `a2 = (0, h)` with the inter-chain springs `up -> up` and `down -> down` (`k_c`). Every
    /// spring is at rest in the uniform state of either tilt (the chain's springs have the same
    /// length at `+-theta_bar`).
    pub fn cell(&self, tilt: f64) -> Result<Cell, MotionError> {
        let (a, r, h) = (self.spacing, self.rotor_length, self.row_spacing);
        Ok(Cell::builder(2, &[[2.0 * a, 0.0], [0.0, h]])
            .rotor("up", [0.0, 0.0], r, FRAC_PI_2 - tilt)
            .rotor("down", [a, 0.0], r, -FRAC_PI_2 + tilt)
            .bond("up", "down", &[0, 0])
            .bond("down", "up", &[1, 0])
            .spring("up", "up", &[0, 1], self.coupling, None)
            .spring("down", "down", &[0, 1], self.coupling, None)
            .build()?)
    }

    /// The uniform state of tilt `tilt`: module doc.
    ///
    /// # Errors
    /// A cell or count that fails (it does not at valid parameters).
    pub fn polarized(&self, tilt: f64) -> Result<Polarized, MotionError> {
        let cell = self.cell(tilt)?;
        let patch = Patch::new(&cell, [self.cells, self.chains], Boundary::Free)?;
        let counts = counts(&patch)?;
        let modes = null_spaces(&patch)?.zero_modes;
        let (mut weight, mut moment) = (0.0, 0.0);
        for m in 0..modes.ncols() {
            for c in 0..self.cells {
                for j in 0..self.chains {
                    for node in 0..2 {
                        let u = modes[(patch.column([c, j], node), m)];
                        weight += u * u;
                        moment += u * u * (2 * c + node) as f64;
                    }
                }
            }
        }
        let row = ready::rotor_chain(self.spacing, self.rotor_length, tilt)?;
        let winding = winding(&row, &WindingOptions::default())?;
        Ok(Polarized { tilt, counts, floppy_mode_centre: moment / weight.max(f64::MIN_POSITIVE), winding })
    }

    /// Launches the wall, runs it and measures it (module doc).
    ///
    /// # Errors
    /// A parameter out of range, a failed launch or integration, a chain whose wall was lost
    /// ([`MotionError::WallLost`]) or a wall that crossed no region
    /// ([`MotionError::WallDidNotCross`]), or a wall too near an end to leave a region beside
    /// it ([`MotionError::WallNearEnd`]).
    pub fn run(&self) -> Result<MovingWall, MotionError> {
        self.validate()?;
        let (n, rows) = (self.rotors(), self.chains);
        let cell = self.cell(self.theta_bar)?;
        let patch = Patch::new(&cell, [self.cells, rows], Boundary::Free)?;
        let model = NetworkModel::builder(&patch).build()?;
        let row_cell = ready::rotor_chain(self.spacing, self.rotor_length, self.theta_bar)?;
        let row_patch = Patch::new(&row_cell, [self.cells, 1], Boundary::Free)?;
        let view = ChainView::new(&row_patch, NetworkModel::builder(&row_patch).build()?)?;
        let column = |j: usize, i: usize| patch.column([i / 2, j], i % 2);

        // Every chain's kink, launched on the chain view and copied into its row; `phi` of an up
        // rotor (even `i`) is `pi/2 - theta`, so its rate is `-thetadot`.
        let mut phi = vec![0.0; model.dof_count()];
        let mut rate = vec![0.0; model.dof_count()];
        for j in 0..rows {
            let offset = if rows > 1 { self.stagger * (j as f64 / (rows - 1) as f64 - 0.5) } else { 0.0 };
            let kink = launch(&view, Charge::Kink, self.start + offset, self.speed, Direction::Right)?;
            let angles = view.to_network(&kink.state.theta);
            for i in 0..n {
                phi[column(j, i)] = angles[i];
                rate[column(j, i)] =
                    if i.is_multiple_of(2) { -kink.state.omega[i] } else { kink.state.omega[i] };
            }
        }
        let steps_per_frame =
            (self.duration / (self.frames - 1) as f64 * self.omega_max() / STEP_FRACTION).ceil() as u64;
        let dt = self.duration / ((self.frames - 1) as u64 * steps_per_frame) as f64;
        let rates = vec![self.damping; model.dof_count()];
        let start = Phase { time: 0.0, theta: phi, omega: rate };
        let mut verlet = Verlet::damped(&model, start, dt, &rates)?;

        // The inter-chain springs (cell bonds 2 and 3) and their energy `k_c (l - h)^2 / 2`.
        let inter: Vec<usize> = (0..patch.bonds().len()).filter(|&p| patch.bonds()[p].bond >= 2).collect();
        let mut lengths = vec![0.0; model.spring_count()];
        let (mut times, mut angles, mut walls) = (Vec::new(), Vec::new(), Vec::new());
        let (mut kinetic, mut potential, mut coupling_energy) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..self.frames {
            if k > 0 {
                for _ in 0..steps_per_frame {
                    verlet.step(&model)?;
                }
            }
            let phi = verlet.theta();
            let time = verlet.state().time;
            let theta: Vec<Vec<f64>> = (0..rows)
                .map(|j| view.to_chain(&(0..n).map(|i| phi[column(j, i)]).collect::<Vec<_>>()))
                .collect();
            let mut found = Vec::with_capacity(rows);
            for (j, t) in theta.iter().enumerate() {
                let kinks: Vec<f64> =
                    domain_walls(t).iter().filter(|w| w.charge == Charge::Kink).map(|w| w.position).collect();
                match kinks.as_slice() {
                    [x] => found.push(*x),
                    _ => return Err(MotionError::WallLost { chain: j, time, kinks: kinks.len() }),
                }
            }
            model.spring_lengths_into(phi, &mut lengths);
            let h = self.row_spacing;
            coupling_energy.push(inter.iter().map(|&p| 0.5 * self.coupling * (lengths[p] - h).powi(2)).sum());
            times.push(time);
            kinetic.push(verlet.kinetic_energy(&model));
            potential.push(model.energy(phi));
            walls.push(found);
            angles.push(theta);
        }
        let mean = |w: &[f64]| w.iter().sum::<f64>() / w.len() as f64;
        let points: Vec<(f64, f64)> = times.iter().zip(&walls).map(|(&t, w)| (t, mean(w))).collect();
        let fit = fit_line(&points).ok_or(MotionError::NoFront { found: points.len(), needed: 2 })?;

        // The regions: three wall widths (plus the stagger) from the wall on each side.
        let plus = self.polarized(self.theta_bar)?;
        let minus = self.polarized(-self.theta_bar)?;
        let margin = 3.0 * wall_width(&view) + self.stagger;
        let region = |k: usize, from: f64, to: f64| -> Region {
            let from = from.clamp(0.0, n as f64).ceil() as usize;
            let to = (to.clamp(0.0, n as f64).floor() as usize).max(from);
            let values: Vec<f64> =
                angles[k].iter().flat_map(|t: &Vec<f64>| t[from..to].iter().copied()).collect();
            let mean_tilt = if values.is_empty() { 0.0 } else { mean(&values) };
            let largest_deviation = values.iter().map(|t| (t - mean_tilt).abs()).fold(0.0, f64::max);
            let uniform = if mean_tilt >= 0.0 { plus.clone() } else { minus.clone() };
            Region { from, to, mean_tilt, largest_deviation, uniform }
        };
        let sides = |k: usize| {
            let wall = mean(&walls[k]);
            let (left, right) = (region(k, 0.0, wall - margin), region(k, wall + margin, n as f64));
            if left.to == left.from || right.to == right.from {
                return Err(MotionError::WallNearEnd { time: times[k], wall, margin, rotors: n });
            }
            Ok(Sides { time: times[k], wall, left, right })
        };
        let last = self.frames - 1;
        let (start, end) = (mean(&walls[0]), mean(&walls[last]));
        let crossed_before = region(0, start + margin, end - margin);
        if crossed_before.to <= crossed_before.from {
            return Err(MotionError::WallDidNotCross { start, end, margin });
        }
        Ok(MovingWall {
            before: sides(0)?,
            after: sides(last)?,
            crossed_before,
            crossed_after: region(last, start + margin, end - margin),
            dt,
            times,
            theta: angles,
            walls,
            kinetic,
            potential,
            coupling_energy,
            fit,
        })
    }
}
