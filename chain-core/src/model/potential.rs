//! The first rung: a potential energy over degrees of freedom with inertia. All that the
//! integrators (Verlet, DOP853), the dissipative relaxation and the firmware loop touch.

use crate::real::Real;

/// A mechanical model's potential energy `V(x)` over `dof_count()` degrees of freedom, each with
/// an inertia, so that its dynamics is `I_i x''_i = -dV/dx_i`.
///
/// Generic over the float type: `f64` (every analysis) or `f32` (chains declared with
/// `float = f32`, for microcontrollers). The required methods work in place on slices and need
/// no allocation; the batch methods and the fused energy-and-gradient are provided (defaults call
/// the required ones; a fast model overrides them).
///
/// For a rotor chain the degrees of freedom are the angles `theta_i` (radians) and the inertia is
/// `M r_i^2`; for a spring network a joint has two (its `x` and `y`), a rotor one (its angle).
///
/// # Panics
/// The slice methods may panic if a slice has the wrong length: that is a programming error of
/// the caller, not a property of the model (the models of this crate panic with a message that
/// names the slice and both counts, [`check_lengths`](super::check_lengths)).
///
/// # Example: a model of your own
///
/// A Frenkel-Kontorova chain (masses on a line, harmonic neighbours, a sinusoidal substrate)
/// needs only these methods to be run by Verlet; the guide `rotor_chain::guide::models` runs it
/// through every analysis.
///
/// ```
/// use rotor_chain::Potential;
///
/// /// `V = sum k (x_{i+1} - x_i - a)^2 / 2 + sum U (1 - cos(2 pi x_i / a))`.
/// struct FrenkelKontorova { n: usize, k: f64, u: f64, a: f64 }
///
/// impl Potential for FrenkelKontorova {
///     fn dof_count(&self) -> usize { self.n }
///     fn inertia(&self, _i: usize) -> f64 { 1.0 }
///     fn energy(&self, x: &[f64]) -> f64 {
///         let q = 2.0 * std::f64::consts::PI / self.a;
///         let springs: f64 = x.windows(2).map(|w| 0.5 * self.k * (w[1] - w[0] - self.a).powi(2)).sum();
///         springs + x.iter().map(|xi| self.u * (1.0 - (q * xi).cos())).sum::<f64>()
///     }
///     fn gradient_into(&self, x: &[f64], out: &mut [f64]) {
///         let q = 2.0 * std::f64::consts::PI / self.a;
///         for (i, g) in out.iter_mut().enumerate() {
///             *g = self.u * q * (q * x[i]).sin();
///             if i > 0 { *g += self.k * (x[i] - x[i - 1] - self.a); }
///             if i + 1 < self.n { *g -= self.k * (x[i + 1] - x[i] - self.a); }
///         }
///     }
/// }
///
/// let fk = FrenkelKontorova { n: 8, k: 1.0, u: 0.1, a: 1.0 };
/// let ground: Vec<f64> = (0..8).map(|i| i as f64).collect();
/// assert!(fk.energy(&ground).abs() < 1e-12);
/// assert!(fk.gradient(&ground).iter().all(|g| g.abs() < 1e-12)); // the allocating convenience
/// ```
pub trait Potential<T: Real = f64> {
    /// The number of degrees of freedom.
    fn dof_count(&self) -> usize;

    /// The inertia of degree of freedom `i` (a mass, or a moment of inertia `M r^2` for an
    /// angle): the kinetic energy is `sum_i inertia(i) x'_i^2 / 2`.
    fn inertia(&self, i: usize) -> T;

    /// The potential energy `V(x)`.
    fn energy(&self, x: &[T]) -> T;

    /// `out[i] = dV/dx_i` (the forces are `-out`).
    fn gradient_into(&self, x: &[T], out: &mut [T]);

    /// The energy, with the gradient into `out`, in one pass. The default calls
    /// [`Potential::gradient_into`] and [`Potential::energy`]; the chains of this crate override
    /// it (each angle's `sin_cos` and each spring's length computed once).
    fn energy_and_gradient_into(&self, x: &[T], out: &mut [T]) -> T {
        self.gradient_into(x, out);
        self.energy(x)
    }

    /// The gradients of many configurations laid back to back (`xs` holds `count * dof_count()`
    /// numbers, configuration after configuration), into `out` laid out the same way. The
    /// default evaluates them one by one; `RuntimeChain` streams them through its vector loop as
    /// one long chain (`batch`, docs/benchmarks.md).
    ///
    /// # Panics
    /// If `xs` is not a whole number of configurations or `out` is not as long.
    #[track_caller]
    fn batch_gradient_into(&self, xs: &[T], out: &mut [T]) {
        let n = self.dof_count();
        super::batch_count(n, xs.len(), out.len(), None);
        for (x, g) in xs.chunks(n).zip(out.chunks_mut(n)) {
            self.gradient_into(x, g);
        }
    }

    /// The energies (one per configuration, into `energies`) and gradients of many
    /// configurations laid back to back, as [`Potential::batch_gradient_into`]. A model that
    /// overrides it may sum each energy's terms in another order than
    /// [`Potential::energy_and_gradient_into`] (equal to rounding); its gradients are the same.
    ///
    /// # Panics
    /// As [`Potential::batch_gradient_into`], or if `energies` does not have one entry per
    /// configuration.
    #[track_caller]
    fn batch_energy_and_gradient_into(&self, xs: &[T], energies: &mut [T], out: &mut [T]) {
        let n = self.dof_count();
        super::batch_count(n, xs.len(), out.len(), Some(energies.len()));
        for ((x, g), e) in xs.chunks(n).zip(out.chunks_mut(n)).zip(energies) {
            *e = self.energy_and_gradient_into(x, g);
        }
    }

    /// The smallest energy the model resolves, for measuring relative energy errors of states
    /// whose energy is about zero (a zero-energy kink at rest has `E ~ 1e-27`, rounding): the
    /// integrators' reports measure errors against `max(|E0|, energy_floor())`. Default 0 (no
    /// floor); a rotor chain gives `1e-12 k_max a^2`, the energy of a spring stretched by a
    /// millionth of the lattice spacing.
    fn energy_floor(&self) -> T {
        T::ZERO
    }

    /// The gradient as a new vector: [`Potential::gradient_into`], allocating.
    #[cfg(feature = "alloc")]
    fn gradient(&self, x: &[T]) -> alloc::vec::Vec<T> {
        let mut out = alloc::vec![T::ZERO; self.dof_count()];
        self.gradient_into(x, &mut out);
        out
    }
}
