//! Tracking kinks and antikinks through a run (paper Appendix C; Figs. `fig:k-scatter`,
//! `fig:ak-scatter`, `fig:akpntrapprofile`).
//!
//! At every output the walls are the interpolated sign changes of the alternately measured
//! angles ([`crate::statics::walls::domain_walls`]). A wall that leaves through a free end is kept
//! at the end, as Appendix C does ("a kink is at the origin when the end rotor is collinear with the
//! spring", its sign from the end rotor's lean): when the end rotor's lean differs from the one
//! the run started with, a *boundary wall* sits at that end. With boundary walls, the net charge
//! `N_kink - N_antikink` equals half the jump of the lean across the whole chain at time 0, and the
//! tracker checks it at every output: a violation means the angles left the range in which signs
//! mean leans (a rotor spinning through `|theta| = pi`).

use alloc::vec::Vec;

use crate::statics::walls::{Charge, Wall, domain_walls};

/// The walls at one output time.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// Time of the output, in `t`.
    pub time: f64,
    /// Interior walls, left to right, then boundary walls (at `0` or `n - 1`).
    pub walls: Vec<Wall>,
    /// Whether each entry of `walls` is a boundary wall.
    pub at_boundary: Vec<bool>,
}

impl Snapshot {
    /// `(kinks, antikinks)`, boundary walls included.
    pub fn counts(&self) -> (usize, usize) {
        let kinks = self.walls.iter().filter(|w| w.charge == Charge::Kink).count();
        (kinks, self.walls.len() - kinks)
    }

    /// `N_kink - N_antikink`.
    pub fn net_charge(&self) -> isize {
        let (k, a) = self.counts();
        k as isize - a as isize
    }

    /// Interior walls of one charge.
    pub fn interior(&self, charge: Charge) -> impl Iterator<Item = f64> + '_ {
        self.walls
            .iter()
            .zip(&self.at_boundary)
            .filter(move |(w, b)| !**b && w.charge == charge)
            .map(|(w, _)| w.position)
    }
}

/// Records the walls of a run and checks the conservation of `N_kink - N_antikink`.
#[derive(Clone, Debug, PartialEq)]
pub struct Tracker {
    left_lean: f64,
    right_lean: f64,
    charge: isize,
    /// One snapshot per output, in time order.
    pub snapshots: Vec<Snapshot>,
    /// Outputs at which the net charge differed from the initial one.
    pub violations: Vec<f64>,
}

impl Tracker {
    /// Starts tracking from the initial angles.
    pub fn new(theta: &[f64]) -> Self {
        let (left_lean, right_lean) =
            (crate::math::sign(theta[0]), crate::math::sign(theta[theta.len() - 1]));
        let charge = domain_walls(theta).iter().map(|w| if w.charge == Charge::Kink { 1 } else { -1 }).sum();
        Self { left_lean, right_lean, charge, snapshots: Vec::new(), violations: Vec::new() }
    }

    /// The walls of `theta` at `time`, with the boundary walls of Appendix C's convention.
    pub fn snapshot(&self, time: f64, theta: &[f64]) -> Snapshot {
        let n = theta.len();
        let mut walls = domain_walls(theta);
        let mut at_boundary = alloc::vec![false; walls.len()];
        // A flipped left end: a wall left through it. Moving left, a kink (+ to -) leaves the
        // left end leaning -, an antikink leaves it leaning +.
        let (l, r) = (crate::math::sign(theta[0]), crate::math::sign(theta[n - 1]));
        if l != 0.0 && l != self.left_lean {
            walls.push(Wall { position: 0.0, charge: if l < 0.0 { Charge::Kink } else { Charge::Antikink } });
            at_boundary.push(true);
        }
        if r != 0.0 && r != self.right_lean {
            walls.push(Wall {
                position: (n - 1) as f64,
                charge: if r > 0.0 { Charge::Kink } else { Charge::Antikink },
            });
            at_boundary.push(true);
        }
        Snapshot { time, walls, at_boundary }
    }

    /// Records the walls at `time` and checks the net charge.
    pub fn record(&mut self, time: f64, theta: &[f64]) -> &Snapshot {
        let s = self.snapshot(time, theta);
        if s.net_charge() != self.charge {
            self.violations.push(time);
        }
        self.snapshots.push(s);
        self.snapshots.last().expect("just pushed")
    }

    /// The conserved `N_kink - N_antikink`.
    pub fn charge(&self) -> isize {
        self.charge
    }
}

/// The angles at every output, for a space-time image (rows: times, columns: rotors).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpaceTime {
    /// Output times, in `t`.
    pub times: Vec<f64>,
    /// The angles at each output time, radians.
    pub theta: Vec<Vec<f64>>,
}

impl SpaceTime {
    /// Records the angles `theta` (radians) at `time` (in `t`).
    pub fn push(&mut self, time: f64, theta: &[f64]) {
        self.times.push(time);
        self.theta.push(theta.to_vec());
    }

    /// [`SpaceTime::push`] with fallible allocations, room reserved for `outputs` frames in all.
    ///
    /// # Errors
    /// [`AllocationError`](crate::allocation::AllocationError) with the bytes of the whole image
    /// (`outputs` frames of `theta.len()` angles) when a frame cannot be allocated.
    pub fn try_push(
        &mut self,
        time: f64,
        theta: &[f64],
        outputs: usize,
    ) -> Result<(), crate::allocation::AllocationError> {
        use crate::allocation::{AllocationError, bytes_of, try_grow, try_vec};
        let image =
            AllocationError { bytes: bytes_of::<f64>(outputs.saturating_mul(theta.len())), what: WHAT };
        let more = outputs.saturating_sub(self.times.len()).max(1);
        try_grow(&mut self.times, more, WHAT).map_err(|_| image)?;
        try_grow(&mut self.theta, more, WHAT).map_err(|_| image)?;
        let mut frame = try_vec(theta.len(), WHAT).map_err(|_| image)?;
        frame.extend_from_slice(theta);
        self.times.push(time);
        self.theta.push(frame);
        Ok(())
    }
}

/// What a space-time image's allocations are for (in errors).
const WHAT: &str = "the space-time image";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_space_time_image_beyond_the_address_space_is_an_error_with_its_bytes() {
        // 2^58 outputs of 4 angles: 2^63 bytes, more than any allocation may be (isize::MAX).
        let outputs = 1usize << 58;
        let err = SpaceTime::default().try_push(0.0, &[0.1; 4], outputs).unwrap_err();
        assert_eq!((err.bytes, err.what), (outputs * 4 * 8, "the space-time image"));
        let mut image = SpaceTime::default();
        image.try_push(0.5, &[0.1, 0.2], 3).unwrap();
        assert_eq!((image.times, image.theta), (alloc::vec![0.5], alloc::vec![alloc::vec![0.1, 0.2]]));
    }

    #[test]
    fn a_kink_leaving_through_the_left_end_stays_as_a_boundary_wall() {
        let start = [0.3, 0.3, 0.1, -0.3, -0.3];
        let mut t = Tracker::new(&start);
        assert_eq!(t.charge(), 1);
        let gone = [-0.3, -0.3, -0.3, -0.3, -0.3];
        let s = t.record(1.0, &gone).clone();
        assert_eq!(s.walls, alloc::vec![Wall { position: 0.0, charge: Charge::Kink }]);
        assert_eq!(s.at_boundary, alloc::vec![true]);
        assert!(t.violations.is_empty());
    }
}
