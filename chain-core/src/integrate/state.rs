//! A point of a trajectory, in the model's float type and in storage of the caller's choice: a
//! `Vec` (the runs, sweeps and analyses) or a fixed-size array (the firmware, without a heap).

use super::IntegrateError;
use crate::model::Potential;
use crate::real::Real;

/// Where a trajectory's numbers live: a `Vec<T>` (with `alloc`) or an array `[T; N]`. The
/// integrators work on the slices; `filled` makes a buffer of the model's size.
pub trait Storage<T>: AsRef<[T]> + AsMut<[T]> + Clone {
    /// `n` copies of `value`, or `None` if this storage cannot hold `n` (an array of another
    /// length).
    fn filled(n: usize, value: T) -> Option<Self>;
}

impl<T: Copy, const N: usize> Storage<T> for [T; N] {
    fn filled(n: usize, value: T) -> Option<Self> {
        (n == N).then_some([value; N])
    }
}

#[cfg(feature = "alloc")]
impl<T: Copy> Storage<T> for alloc::vec::Vec<T> {
    fn filled(n: usize, value: T) -> Option<Self> {
        Some(alloc::vec![value; n])
    }
}

/// A point of a trajectory: the degrees of freedom `theta` (a chain's angles) and their rates
/// `omega = dtheta/dt` at a time, in the time unit `t` of paper Appendix B, in the float type `T`
/// and the storage `S` of the caller's choice (`[T; N]` on a microcontroller; [`State`] is the
/// `f64` and `Vec` one of the runs).
#[derive(Clone, Debug, PartialEq)]
pub struct Phase<T, S> {
    /// Time, in `t`.
    pub time: T,
    /// The degrees of freedom (radians for a rotor chain, measured from the vertical,
    /// docs/theory.md §1), one per degree of freedom.
    pub theta: S,
    /// Their rates `dtheta/dt`.
    pub omega: S,
}

/// The state of a run: a [`Phase`] in `f64`, in `Vec`s.
#[cfg(feature = "alloc")]
pub type State = Phase<f64, alloc::vec::Vec<f64>>;

#[cfg(feature = "alloc")]
impl State {
    /// The angles `theta` at rest at time 0.
    pub fn at_rest(theta: alloc::vec::Vec<f64>) -> Self {
        let omega = alloc::vec![0.0; theta.len()];
        Self { time: 0.0, theta, omega }
    }
}

impl<T: Real, S: Storage<T>> Phase<T, S> {
    /// `Ok` if the state fits `model` (one value of each kind per degree of freedom) and every
    /// number in it is finite. The integrators check this before they start.
    pub fn check<M: Potential<T> + ?Sized>(&self, model: &M) -> Result<(), IntegrateError> {
        let n = model.dof_count();
        for (what, v) in [("theta", self.theta.as_ref()), ("omega", self.omega.as_ref())] {
            if v.len() != n {
                return Err(IntegrateError::WrongLength { what, len: v.len(), expected: n });
            }
        }
        if !self.time.is_finite() {
            let time = self.time.widen();
            return Err(IntegrateError::NotFinite { what: "time", time, index: 0, value: time });
        }
        for (what, v) in [("theta", self.theta.as_ref()), ("omega", self.omega.as_ref())] {
            super::not_finite(what, self.time.widen(), v)?;
        }
        Ok(())
    }
}
