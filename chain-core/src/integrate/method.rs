//! The one way to choose an integrator: runs, scattering, the phase-diagram sweeps, the command
//! line and Python all name it with a [`Method`], by the names `verlet` and `dop853`.

use core::fmt;
use core::str::FromStr;

/// Which integrator a run uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Velocity Verlet ([`Verlet`](super::Verlet)): a fixed step, symplectic, one gradient per
    /// step. The run chooses the step (a tenth of the stability limit unless given).
    Verlet,
    /// DOP853 with these tolerances (the run's damping, sponge and energy limit apply).
    Dop853 {
        /// Relative tolerance of the error control.
        rtol: f64,
        /// Absolute tolerance of the error control, in the units of the degrees of freedom (radians
        /// for a chain) and of their rates.
        atol: f64,
    },
}

impl Method {
    /// DOP853's default tolerances: `rtol = 1e-10`, `atol = 1e-11` (energy errors near 1e-9 on the
    /// paper's runs, docs/dynamics.md §6).
    pub const DOP853_RTOL: f64 = 1e-10;
    /// See [`Method::DOP853_RTOL`].
    pub const DOP853_ATOL: f64 = 1e-11;

    /// Every method's name, the default first.
    pub const NAMES: [&'static str; 2] = ["verlet", "dop853"];

    /// DOP853 at its default tolerances.
    pub const fn dop853() -> Self {
        Method::Dop853 { rtol: Self::DOP853_RTOL, atol: Self::DOP853_ATOL }
    }

    /// The method's name: `verlet` or `dop853` (the command line, the results files, Python).
    pub fn name(&self) -> &'static str {
        match self {
            Method::Verlet => "verlet",
            Method::Dop853 { .. } => "dop853",
        }
    }
}

impl Default for Method {
    /// Velocity Verlet: the workhorse of the runs and sweeps.
    fn default() -> Self {
        Method::Verlet
    }
}

impl fmt::Display for Method {
    /// The name ([`Method::name`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a [`Method`]'s.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the integrator must be 'verlet' or 'dop853'")]
pub struct UnknownMethod;

impl FromStr for Method {
    type Err = UnknownMethod;

    /// `verlet`, or `dop853` at its default tolerances.
    fn from_str(s: &str) -> Result<Self, UnknownMethod> {
        match s {
            "verlet" => Ok(Method::Verlet),
            "dop853" => Ok(Method::dop853()),
            _ => Err(UnknownMethod),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for name in Method::NAMES {
            assert_eq!(name.parse::<Method>().unwrap().to_string(), name);
        }
        assert_eq!("rk4".parse::<Method>(), Err(UnknownMethod));
        assert_eq!(Method::default(), Method::Verlet);
    }
}
