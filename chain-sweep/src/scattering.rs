//! The record of one point of a scattering phase diagram (paper Sec. VI, Fig.
//! `fig:phasediagram`): a kink or antikink launched at speed `v0` towards an impurity spring of
//! stiffness `k_i`, and what became of it. Written by the `phase-diagram` tool; read back with
//! [`crate::read_results`] for plotting.

use crate::record::{ParseError, Record, expect_fields, format_f64, parse_field};

/// What the impurity did to the incident defect: the dynamics' own outcome type, with its names
/// (`transmitted`, ...) as the `outcome` column.
pub use rotor_chain::dynamics::scatter::{Outcome, UnknownOutcome};

/// One scattering simulation's result: the columns of a phase-diagram results file.
#[derive(Clone, Debug, PartialEq)]
pub struct PointRecord {
    pub outcome: Outcome,
    /// The simulation time at which the outcome was decided, in the time unit of the dynamics.
    pub t_decided: f64,
    /// Kinks in the chain at the end of the run.
    pub kinks_final: usize,
    /// Antikinks in the chain at the end of the run.
    pub antikinks_final: usize,
    /// The integrator's energy error over the run, as the dynamics reports it.
    pub energy_error: f64,
}

impl Record for PointRecord {
    fn header() -> &'static [&'static str] {
        &["outcome", "t_decided", "kinks_final", "antikinks_final", "energy_error"]
    }

    fn to_fields(&self) -> Vec<String> {
        vec![
            self.outcome.name().to_owned(),
            format_f64(self.t_decided),
            self.kinks_final.to_string(),
            self.antikinks_final.to_string(),
            format_f64(self.energy_error),
        ]
    }

    fn from_fields(fields: &[&str]) -> Result<Self, ParseError> {
        let header = Self::header();
        expect_fields(fields, header.len())?;
        Ok(Self {
            outcome: parse_field(fields, 0, header[0])?,
            t_decided: parse_field(fields, 1, header[1])?,
            kinks_final: parse_field(fields, 2, header[2])?,
            antikinks_final: parse_field(fields, 3, header[3])?,
            energy_error: parse_field(fields, 4, header[4])?,
        })
    }
}

/// A stand-in for the physics, for testing the sweep machinery only: a record that depends on
/// nothing but `(ki_ratio, v0)`, with every outcome appearing across a grid. It is not physics.
#[doc(hidden)]
pub fn fake_point(ki_ratio: f64, v0: f64) -> PointRecord {
    let cell = (ki_ratio * 10.0).floor() + v0.floor();
    let outcome = Outcome::ALL[cell.rem_euclid(Outcome::ALL.len() as f64) as usize];
    let (kinks_final, antikinks_final) = if outcome == Outcome::Split { (2, 1) } else { (1, 0) };
    PointRecord {
        outcome,
        t_decided: 10.0 + ki_ratio + v0,
        kinks_final,
        antikinks_final,
        energy_error: 1e-9 * (1.0 + ki_ratio * v0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outcome_names_round_trip() {
        for outcome in Outcome::ALL {
            assert_eq!(outcome.name().parse::<Outcome>(), Ok(outcome));
        }
        assert_eq!("bounced".parse::<Outcome>(), Err(UnknownOutcome("bounced".to_owned())));
    }

    #[test]
    fn records_round_trip_through_fields() {
        let record = PointRecord {
            outcome: Outcome::Split,
            t_decided: 1.0 / 3.0,
            kinks_final: 2,
            antikinks_final: 1,
            energy_error: 2.5e-13,
        };
        let fields = record.to_fields();
        let fields: Vec<&str> = fields.iter().map(String::as_str).collect();
        assert_eq!(fields, ["split", "0.3333333333333333", "2", "1", "2.5e-13"]);
        assert_eq!(PointRecord::from_fields(&fields), Ok(record));
        let err = PointRecord::from_fields(&["split", "x", "2", "1", "0"]).unwrap_err();
        assert!(err.to_string().contains("column `t_decided`"), "{err}");
        assert!(PointRecord::from_fields(&["split"]).is_err());
    }

    #[test]
    fn fake_points_are_deterministic_and_cover_every_outcome() {
        assert_eq!(fake_point(0.3, 4.5), fake_point(0.3, 4.5));
        let seen: Vec<Outcome> = (0..5).map(|k| fake_point(0.0, k as f64).outcome).collect();
        assert_eq!(seen, Outcome::ALL);
    }
}
