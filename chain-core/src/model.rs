//! The model trait every analysis is generic over.
//!
//! Both kinds of chain implement it: the structs of `#[rotor_chain]` (sizes and constants fixed at
//! compile time, code unrolled) and [`crate::RuntimeChain`] (sizes and parameters chosen at run
//! time). The trait works on slices so it needs no allocation; the structs' inherent methods add
//! array-typed conveniences.
//!
//! Units: angles in radians, lengths in the units of `a`, stiffnesses `k` in energy per length
//! squared, so energies are absolute, in the unit of `k` times the length unit squared (`M a^2 /
//! t^2` with the paper's `k` in `M / t^2`; not divided by `k a^2`). Slices of rotor quantities have
//! length `n`, slices of spring quantities `n - 1`.
//!
//! # Panics
//! The slice methods panic if a slice has the wrong length: that is a programming error, not a
//! property of the model. Both kinds of chain check with [`check_lengths`], whose message names
//! the slice and both counts; an implementation of your own can call it too.

use crate::branch;
use crate::error::BranchError;

/// A topological rotor chain: `n` rotors on a line, their tips joined by `n - 1` springs.
pub trait ChainModel {
    /// Number of rotors `n`.
    fn rotor_count(&self) -> usize;

    /// Number of springs `n - 1`.
    fn spring_count(&self) -> usize {
        self.rotor_count() - 1
    }

    /// Lattice spacing `a` (distance between neighbouring pivots).
    fn lattice_spacing(&self) -> f64;

    /// Length `r_i` of rotor `i`.
    fn rotor_length(&self, i: usize) -> f64;

    /// Mass `M` at each rotor tip.
    fn mass(&self) -> f64;

    /// Moment of inertia `M r_i^2` of rotor `i` (the kinetic energy is `sum_i M r_i^2 thetadot_i^2 / 2`).
    fn inertia(&self, i: usize) -> f64 {
        let r = self.rotor_length(i);
        self.mass() * r * r
    }

    /// Equilibrium angle `theta_bar` of the uniform states `theta_i = +-theta_bar`.
    fn theta_bar(&self) -> f64;

    /// Stiffness `k_p` of spring `p`.
    fn stiffness(&self, p: usize) -> f64;

    /// Rest length `l0_p` of spring `p`.
    fn rest_length(&self, p: usize) -> f64;

    /// Potential energy `V = sum_p law(l_p)`.
    fn energy(&self, theta: &[f64]) -> f64;

    /// `out[i] = dV/dtheta_i` (the forces are `-out`).
    fn gradient_into(&self, theta: &[f64], out: &mut [f64]);

    /// The tangent stiffness `d2V/dtheta_i dtheta_j`: `diag` (length `n`) and `off` (length
    /// `n - 1`, entry `(p, p + 1)`).
    fn tangent_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]);

    /// The energy, with the gradient into `out`, in one pass: each angle's `sin_cos` and each
    /// spring's length computed once. The default calls [`ChainModel::gradient_into`] and
    /// [`ChainModel::energy`]; both kinds of chain override it.
    fn energy_and_gradient_into(&self, theta: &[f64], out: &mut [f64]) -> f64 {
        self.gradient_into(theta, out);
        self.energy(theta)
    }

    /// The energy, with the gradient into `grad` and the tangent stiffness into `diag` / `off`
    /// (as [`ChainModel::tangent_stiffness_into`]), in one pass. The default calls the three
    /// separate methods; both kinds of chain override it.
    fn energy_gradient_stiffness_into(
        &self,
        theta: &[f64],
        grad: &mut [f64],
        diag: &mut [f64],
        off: &mut [f64],
    ) -> f64 {
        self.gradient_into(theta, grad);
        self.tangent_stiffness_into(theta, diag, off);
        self.energy(theta)
    }

    /// The gradients of many configurations laid back to back (`thetas` holds `count * n`
    /// angles, configuration after configuration), into `out` laid out the same way: each as
    /// [`ChainModel::gradient_into`] gives it. The default evaluates them one by one;
    /// [`crate::RuntimeChain`] streams them through its vector loop as one long chain, which
    /// saves the loop's start and end per configuration (`crate::batch`, docs/benchmarks.md).
    ///
    /// # Panics
    /// If `thetas` is not a whole number of configurations or `out` is not as long.
    #[track_caller]
    fn batch_gradient_into(&self, thetas: &[f64], out: &mut [f64]) {
        let n = self.rotor_count();
        batch_count(n, thetas, out, None);
        for (t, g) in thetas.chunks(n).zip(out.chunks_mut(n)) {
            self.gradient_into(t, g);
        }
    }

    /// The energies (one per configuration, into `energies`) and gradients of many
    /// configurations laid back to back, as [`ChainModel::batch_gradient_into`]. The default
    /// evaluates them one by one; [`crate::RuntimeChain`] as one long chain, whose energies then
    /// agree with [`ChainModel::energy_and_gradient_into`]'s to rounding (their terms are summed
    /// in another order) and whose gradients are the same.
    ///
    /// # Panics
    /// As [`ChainModel::batch_gradient_into`], or if `energies` does not have one entry per
    /// configuration.
    #[track_caller]
    fn batch_energy_and_gradient_into(&self, thetas: &[f64], energies: &mut [f64], out: &mut [f64]) {
        let n = self.rotor_count();
        batch_count(n, thetas, out, Some(energies));
        for ((t, g), e) in thetas.chunks(n).zip(out.chunks_mut(n)).zip(energies) {
            *e = self.energy_and_gradient_into(t, g);
        }
    }

    /// The material part `sum_p g^_p a_p a_p^T` of the tangent stiffness (paper Appendix D), with
    /// `a_p = dl_p/dtheta` (the paper's `a_p` is per tip displacement `r theta`: ours is `r` times it).
    fn material_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]);

    /// The stress matrix `sum_p S_p` (paper Appendix D); material part + stress matrix = tangent stiffness.
    fn stress_matrix_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]);

    /// Spring lengths `l_p`.
    fn spring_lengths_into(&self, theta: &[f64], out: &mut [f64]);

    /// Spring tensions `t_p = dlaw/dl` at the current lengths.
    fn tensions_into(&self, theta: &[f64], out: &mut [f64]);

    /// The compatibility matrix `C[p][i] = dl_p / d(r_i theta_i)`: `left[p] = C[p][p]`,
    /// `right[p] = C[p][p+1]`.
    fn compatibility_into(&self, theta: &[f64], left: &mut [f64], right: &mut [f64]);

    /// Both `theta_{p+1}` that put spring `p` at its rest length given `theta_p` (paper Appendix A),
    /// flipper branch first.
    fn next_angles(&self, p: usize, theta_p: f64) -> Result<[f64; 2], BranchError> {
        self.check_spring(p)?;
        branch::next_angles(
            p,
            self.lattice_spacing(),
            self.rotor_length(p),
            self.rotor_length(p + 1),
            self.rest_length(p),
            theta_p,
        )
    }

    /// Both `theta_p` that put spring `p` at its rest length given `theta_{p+1}`: the inverse map.
    fn previous_angles(&self, p: usize, theta_next: f64) -> Result<[f64; 2], BranchError> {
        self.check_spring(p)?;
        branch::previous_angles(
            p,
            self.lattice_spacing(),
            self.rotor_length(p),
            self.rotor_length(p + 1),
            self.rest_length(p),
            theta_next,
        )
    }

    /// `Ok` if `p` is a spring of this chain.
    fn check_spring(&self, p: usize) -> Result<(), BranchError> {
        if p < self.spring_count() {
            Ok(())
        } else {
            Err(BranchError::NoSuchSpring { spring: p, springs: self.spring_count() })
        }
    }
}

/// The number of configurations of `n` rotors in a batch, checking the slices' lengths as the
/// batch methods of [`ChainModel`] document (panics: a programming error; `crate::batch` returns
/// typed errors first).
#[track_caller]
pub(crate) fn batch_count(n: usize, thetas: &[f64], out: &[f64], energies: Option<&[f64]>) -> usize {
    use chain_geometry::Counted;
    assert!(
        n > 0 && thetas.len().is_multiple_of(n),
        "thetas has {}, not a whole number of configurations of {}",
        Counted(thetas.len(), "angle"),
        Counted(n, "rotor")
    );
    assert!(
        out.len() == thetas.len(),
        "out has {}, thetas {}: one gradient entry per angle",
        Counted(out.len(), "value"),
        Counted(thetas.len(), "angle")
    );
    let count = thetas.len() / n;
    if let Some(e) = energies {
        assert!(
            e.len() == count,
            "energies has {}, the batch {}: one energy per configuration",
            Counted(e.len(), "value"),
            Counted(count, "configuration")
        );
    }
    count
}

/// Panics unless a chain of `n` rotors gets `theta` (of length `theta`) and slices of one value
/// per rotor (`rotors`: name and length) and one per spring (`springs`): the check of every
/// slice method of [`crate::RuntimeChain`] and of the `#[rotor_chain]` chains. A wrong length is
/// a programming error of the caller, so the message names the slice and both counts ("off has
/// 60 values, the chain has 59 springs (one value per spring)"), and `#[track_caller]` (here and
/// on the methods that call it) points it at the call. Inlined, it is a few compares on the hot
/// path; the message is built out of line.
///
/// ```should_panic
/// // A chain of 6 rotors: `diag` holds one value per rotor, `off` one per spring.
/// rotor_chain::model::check_lengths(6, 6, &[("diag", 6)], &[("off", 6)]);
/// // panics: "off has 6 values, the chain has 5 springs (one value per spring)"
/// ```
#[inline(always)]
#[track_caller]
pub fn check_lengths(n: usize, theta: usize, rotors: &[(&str, usize)], springs: &[(&str, usize)]) {
    if theta != n || rotors.iter().any(|r| r.1 != n) || springs.iter().any(|s| s.1 + 1 != n) {
        wrong_length(n, theta, rotors, springs);
    }
}

/// The panic of [`check_lengths`]: the first slice of the wrong length, by name.
#[cold]
#[inline(never)]
#[track_caller]
fn wrong_length(n: usize, theta: usize, rotors: &[(&str, usize)], springs: &[(&str, usize)]) -> ! {
    use chain_geometry::Counted;
    let theta = [("theta", theta)];
    let per_rotor = theta.iter().chain(rotors).map(|&(s, l)| (s, l, n, "rotor"));
    let per_spring = springs.iter().map(|&(s, l)| (s, l, n - 1, "spring"));
    let (name, len, count, what) =
        per_rotor.chain(per_spring).find(|&(_, l, c, _)| l != c).unwrap_or(("a slice", 0, n, "rotor"));
    panic!(
        "{name} has {}, the chain has {} (one value per {what})",
        Counted(len, "value"),
        Counted(count, what)
    )
}
