//! A transition wave in a chain of bistable elements (issue 36, demonstration 3).
//!
//! The lattice of Nadkarni, Chong, Kochmann and Daraio (*Dynamics of periodic mechanical
//! structures containing bistable elements*, PRE 90, 023204 (2014); Nadkarni, Arrieta, Chong,
//! Kochmann and Daraio, *Unidirectional transition waves in bistable lattices*, PRL 116, 244501
//! (2016)): masses `M` a distance `a` apart, each tied to its neighbours by linear springs `k_c`
//! and to the ground by a bistable element of on-site energy `V(u)`, with linear damping `gamma`:
//!
//! `M u_n'' = k_c (u_{n+1} - 2 u_n + u_{n-1}) - V'(u_n) - gamma M u_n'`.
//!
//! Declared as a network: a one-dimensional cell of two joints, the mass `m` and its ground `g`
//! (held), the coupling bond `m -> m` (next cell) harmonic and the bistable bond `g -> m` of the
//! run-time polynomial law [`Polynomial::double_well`]`(a, b)` with `k = beta`, so
//! `V'(u) = beta u (u - a) (u - b)`: stable at `u = 0` and `u = b`, with the well at `b` deeper
//! for `a < b / 2`. Both bonds lie along `x`, so the `y` degrees of freedom are held too and `u_n`
//! is joint `m`'s `x` displacement. Released from a step (the deeper state on the left, at rest),
//! the deeper state invades the other: a transition wave whose front moves at a constant speed
//! once the damping balances the energy released.
//!
//! **The continuum's speed.** In the continuum limit (`u_n(t) = u(n a, t)`) the front is a
//! travelling wave `u = b W((x - v t) / s)` of
//! `(c_0^2 - v^2) u'' + gamma v u' - V'(u) / M = 0` with `c_0 = a sqrt(k_c / M)`: after scaling,
//! Nagumo's equation `W'' + c W' + W (W - alpha)(1 - W) = 0`, `alpha = a / b`, whose front
//! `W = 1 / (1 + exp(z / sqrt 2))` moves at `c = sqrt(2) (1/2 - alpha)` (McKean, *Nagumo's
//! equation*, Adv. Math. 4, 209 (1970); the same reduction as the PRE's Sec. IV for the
//! damped chain). With `kappa = beta b^2 / M` and `Q = 2 kappa (1/2 - alpha)^2` this gives
//!
//! `v = c_0 sqrt(Q / (gamma^2 + Q))`, the front's width `w = sqrt(2 (c_0^2 - v^2) / kappa)`
//!
//! ([`BistableChain::continuum_speed`], [`BistableChain::continuum_width`]). The lattice differs
//! from it through the discreteness of the front (the coupling's dispersion, relative size
//! `~ (a / w)^2 / 12`, and the Peierls-Nabarro pinning, exponentially small in `w / a`), which
//! the defaults keep below a percent ([`BistableChain::default`]); the measured speed is fitted to
//! the front's positions after the launch's transient.

use super::MotionError;
use super::front::{LineFit, fit_line, front_by_area};
use crate::cell::{BondLaw, Cell, Polynomial};
use crate::model::NetworkModel;
use crate::patch::{Boundary, MAX_PATCH_BONDS, Patch};
use chain_core::dynamics::run::MAX_SPACE_TIME_VALUES;
use chain_core::integrate::{MAX_STEP_BUDGET, Phase, Verlet};
use chain_core::validate::{Fields, Validate};

/// The chain's parameters. Units: the spacing `a = 1`, the mass `M = 1`; time in
/// `sqrt(M / k)` of a unit spring.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BistableChain {
    /// Sites (masses). Default 200: the front crosses 150 sites in the default run. Between 8
    /// and [`MAX_PATCH_BONDS`] (the patch rule's bound, checked here before any cell is built).
    pub sites: usize,
    /// Coupling spring constant `k_c`. Default 16: sound speed `c_0 = 4` and a front about 4.6
    /// sites wide, so the lattice's discreteness changes the speed by well under a percent.
    pub coupling: f64,
    /// The bistable element's scale `beta` (its bond's `k`). Default 25: with `b = 0.2`,
    /// `kappa = beta b^2 / M = 1`.
    pub on_site: f64,
    /// The barrier's elongation `a` (`0 < a < b / 2`). Default 0.05 (`alpha = a / b = 1/4`): the
    /// wells differ by `beta b^3 (b - 2 a) / 12 = 1/600`.
    pub barrier: f64,
    /// The second well's elongation `b`. Default 0.2: a fifth of the spacing, so neighbouring
    /// masses stay apart (`a + u_{n+1} - u_n > 0`: the coupling bonds keep their direction).
    pub well: f64,
    /// The damping rate `gamma` (1 / time). Default 0.5: the front settles to `0.58 c_0`.
    pub damping: f64,
    /// Length of the run. Default 70. At most [`MAX_STEP_BUDGET`] Verlet steps of `0.2 /
    /// omega_max` (every integrator's bound).
    pub duration: f64,
    /// Samples of the state during the run (the x-t diagram's rows). Default 141 (every 0.5).
    /// Between 2 (a speed needs two times) and [`MAX_SPACE_TIME_VALUES`]` / sites`: the x-t
    /// diagram holds `samples x sites` values, bounded as a run's space-time image.
    pub samples: usize,
    /// Sites of the step's deeper state at the launch. Default 10.
    pub launch_sites: usize,
    /// The fit of the front's speed starts at this time (the launch's transient, a few
    /// `1 / gamma`, left out). Default 15.
    pub fit_from: f64,
}

impl Default for BistableChain {
    fn default() -> Self {
        Self {
            sites: 200,
            coupling: 16.0,
            on_site: 25.0,
            barrier: 0.05,
            well: 0.2,
            damping: 0.5,
            duration: 70.0,
            samples: 141,
            launch_sites: 10,
            fit_from: 15.0,
        }
    }
}

/// The run: the sampled displacements and the front's fitted speed beside the continuum's.
#[derive(Clone, Debug)]
pub struct TransitionWave {
    /// Sample times.
    pub times: Vec<f64>,
    /// `u_n / b` per sample, site by site (the x-t diagram).
    pub displacement: Vec<Vec<f64>>,
    /// The front's position (sites) per sample ([`front_by_area`] over five continuum widths on
    /// each side of its crossing of `u = b / 2`), where there is one.
    pub fronts: Vec<Option<f64>>,
    /// The line fitted to the front's positions from `fit_from` on, while the front is at least
    /// a width from the last site.
    pub fit: LineFit,
    /// The continuum's speed [`BistableChain::continuum_speed`].
    pub predicted: f64,
}

impl TransitionWave {
    /// The measured speed (sites per unit time).
    pub fn speed(&self) -> f64 {
        self.fit.slope
    }

    /// `measured / predicted - 1`.
    pub fn relative_difference(&self) -> f64 {
        self.fit.slope / self.predicted - 1.0
    }
}

/// Verlet's steps are `omega_max dt = 0.2`.
const STEP_FRACTION: f64 = 0.2;

impl BistableChain {
    /// A bound on the fastest mode: `omega^2 <= (4 k_c + max |V''|) / M`, `V''` largest at the
    /// wells' ends of [0, b] (`beta a b` and `beta b (b - a)`).
    fn omega_max(&self) -> f64 {
        let curvature = self.on_site * self.well * self.barrier.max(self.well - self.barrier);
        (4.0 * self.coupling + curvature).sqrt()
    }
}

/// Distance of the ground joint behind its mass: the bistable bond's rest length (any positive
/// length; the elongation, not the length, enters the law).
const GROUND_OFFSET: f64 = 0.5;

impl Validate for BistableChain {
    type Error = MotionError;

    /// `coupling`, `on_site`, `well`, `barrier`, `damping` and `duration` positive and finite,
    /// `barrier < well / 2` (the well at `well` is the deeper one), `0 <= fit_from < duration`,
    /// `8 <= sites <=` [`MAX_PATCH_BONDS`], `1 <= launch_sites < sites / 2` (the front needs room
    /// to run), `2 <= samples <=` [`MAX_SPACE_TIME_VALUES`]` / sites` (a speed needs two times;
    /// the x-t diagram's values are bounded as a space-time image), and a run of at most
    /// [`MAX_STEP_BUDGET`] steps (`duration`).
    fn validate(&self) -> Result<(), MotionError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self {
            sites,
            coupling,
            on_site,
            barrier,
            well,
            damping,
            duration,
            samples,
            launch_sites,
            fit_from,
        } = *self;
        let fields = Fields("BistableChain");
        fields.positive("coupling", coupling)?;
        fields.positive("on_site", on_site)?;
        fields.positive("well", well)?;
        fields.positive("barrier", barrier)?;
        fields.rule(
            "barrier",
            barrier,
            barrier < well / 2.0,
            "below well / 2, so the well at `well` is the deeper one",
        )?;
        fields.positive("damping", damping)?;
        fields.positive("duration", duration)?;
        fields.rule(
            "duration",
            duration,
            duration * self.omega_max() / STEP_FRACTION <= MAX_STEP_BUDGET as f64,
            "at most MAX_STEP_BUDGET = 10000000000 Verlet steps of 0.2 / omega_max",
        )?;
        fields.rule("fit_from", fit_from, fit_from >= 0.0 && fit_from < duration, "in [0, duration)")?;
        let rule = "between 8 and MAX_PATCH_BONDS = 33554432 (the patch rule)";
        fields.count_in("sites", sites as u64, 8, MAX_PATCH_BONDS as u64, rule)?;
        fields.rule(
            "launch_sites",
            launch_sites as f64,
            launch_sites >= 1 && launch_sites < sites / 2,
            "at least 1 and below sites / 2",
        )?;
        fields.count_in(
            "samples",
            samples as u64,
            2,
            (MAX_SPACE_TIME_VALUES / sites) as u64,
            "between 2 and MAX_SPACE_TIME_VALUES / sites = 134217728 / sites (the x-t diagram's values)",
        )?;
        Ok(())
    }
}

impl BistableChain {
    /// The unit cell: the mass `m` at the origin, its ground `g` `GROUND_OFFSET` behind it,
    /// the harmonic coupling `m -> m` to the next cell and the bistable bond `g -> m`.
    pub fn cell(&self) -> Result<Cell, MotionError> {
        Ok(Cell::builder(1, &[[1.0, 0.0]])
            .joint("m", [0.0, 0.0])
            .joint("g", [-GROUND_OFFSET, 0.0])
            .spring("m", "m", &[1], self.coupling, None)
            .bond_law(BondLaw::Harmonic)
            .spring("g", "m", &[0], self.on_site, None)
            .bond_law(BondLaw::Polynomial(Polynomial::double_well(self.barrier, self.well)))
            .build()?)
    }

    /// The continuum's sound speed `c_0 = a sqrt(k_c / M)`.
    pub fn sound_speed(&self) -> f64 {
        self.coupling.sqrt()
    }

    fn q(&self) -> f64 {
        let kappa = self.on_site * self.well * self.well;
        2.0 * kappa * (0.5 - self.barrier / self.well).powi(2)
    }

    /// The continuum's front speed `v = c_0 sqrt(Q / (gamma^2 + Q))` (module doc).
    pub fn continuum_speed(&self) -> f64 {
        let q = self.q();
        self.sound_speed() * (q / (self.damping * self.damping + q)).sqrt()
    }

    /// The continuum front's width `w = sqrt(2 (c_0^2 - v^2) / kappa)` (sites): the front is
    /// `b / (1 + exp((x - v t) / w))`.
    pub fn continuum_width(&self) -> f64 {
        let v = self.continuum_speed();
        let kappa = self.on_site * self.well * self.well;
        (2.0 * (self.coupling - v * v) / kappa).sqrt()
    }

    /// Launches the wave from the step and measures its speed.
    ///
    /// # Errors
    /// A parameter out of range, a failed integration, or a front not found in at least a
    /// quarter of the samples of the fitting window ([`MotionError::NoFront`]).
    pub fn run(&self) -> Result<TransitionWave, MotionError> {
        self.validate()?;
        let cell = self.cell()?;
        let patch = Patch::new(&cell, [self.sites, 1], Boundary::Free)?;
        let model = NetworkModel::builder(&patch).build()?;
        let n = self.sites;
        let (m_dof, g_dof) = (cell.dof_offset(0), cell.dof_offset(1));
        let x_of = |site: usize| patch.column([site, 0], m_dof);
        let mut theta = model.reference();
        for site in 0..self.launch_sites {
            theta[x_of(site)] += self.well;
        }
        let mut rates = vec![0.0; theta.len()];
        for site in 0..n {
            rates[x_of(site)] = self.damping;
        }
        let steps_per_sample =
            (self.duration / (self.samples - 1) as f64 * self.omega_max() / STEP_FRACTION).ceil() as u64;
        let dt = self.duration / ((self.samples - 1) as u64 * steps_per_sample) as f64;
        let start = Phase { time: 0.0, theta, omega: vec![0.0; model.reference().len()] };
        let mut verlet = Verlet::damped(&model, start, dt, &rates)?;
        for site in 0..n {
            let (m, g) = (patch.column([site, 0], m_dof), patch.column([site, 0], g_dof));
            for held in [m + 1, g, g + 1] {
                verlet.hold(held);
            }
        }
        let reference = model.reference();
        let sample = |theta: &[f64]| -> Vec<f64> {
            (0..n).map(|s| (theta[x_of(s)] - reference[x_of(s)]) / self.well).collect()
        };
        // Five widths on each side: the window's tails are below a percent of a site.
        let window = (5.0 * self.continuum_width()).ceil() as usize;
        let (mut times, mut displacement, mut fronts) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..self.samples {
            if k > 0 {
                for _ in 0..steps_per_sample {
                    verlet.step(&model)?;
                }
            }
            let u = sample(verlet.theta());
            times.push(verlet.state().time);
            fronts.push(front_by_area(&u, window));
            displacement.push(u);
        }
        // The fit: from `fit_from` on, while the front is a width or more inside the patch
        // (near the free end the missing neighbour changes the front).
        let margin = (n - 1) as f64 - 2.0 * self.continuum_width().max(1.0);
        let window: Vec<usize> = (0..times.len()).filter(|&k| times[k] >= self.fit_from).collect();
        let points: Vec<(f64, f64)> =
            window.iter().filter_map(|&k| fronts[k].filter(|&x| x < margin).map(|x| (times[k], x))).collect();
        let needed = (window.len() / 4).max(3);
        let fit = fit_line(&points)
            .filter(|_| points.len() >= needed)
            .ok_or(MotionError::NoFront { found: points.len(), needed })?;
        Ok(TransitionWave { times, displacement, fronts, fit, predicted: self.continuum_speed() })
    }
}
