//! The text the firmware prints and the host reads back: one line per record, `key=value` fields
//! in a fixed order. Numbers are written with `{:e}`, the shortest digits that parse back to the
//! same value, so the text carries every bit of the firmware's results.
//!
//! ```text
//! rotor-chain kink run: n=16 float=f64 centre=4.25e0 v0=4e0 dt=4.8828125e-4 steps=4096 every=256
//! sample step=0 t=0e0 kinetic=8e0 potential=1.2e-27 walls=1 kink@4.25e0
//! done steps=4096 energy_initial=8e0 energy_final=8.0000001e0 max_energy_error=1e-7
//! ```
//!
//! (The numbers above only show the shape.) Formatting and parsing live together here so that the
//! two sides of the comparison read the same format.

use core::fmt;
use core::str::{FromStr, SplitWhitespace};

use rotor_chain::embedded::{Charge, Real, Wall};

use crate::run::{MAX_WALLS, Sample, Scenario, Summary};

/// The first line of a run: what was run, on which chain size and float type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Header<'a> {
    /// Rotors in the chain.
    pub n: usize,
    /// [`Real::NAME`] of the float type the chain computed in.
    pub float: &'a str,
    /// The run's settings.
    pub scenario: Scenario,
}

/// A line of the firmware's output that is not one of the three records.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ParseError {
    /// The field `key=...` was expected next.
    #[error("expected the field `{key}=...`")]
    Missing {
        /// The key.
        key: &'static str,
    },
    /// The field's value does not parse as the number it should be.
    #[error("the value of `{key}` is not a valid number")]
    Number {
        /// The key.
        key: &'static str,
    },
    /// A wall is written `kink@position` or `antikink@position`.
    #[error("expected a wall `kink@x` or `antikink@x`")]
    Wall,
    /// More fields than the record has.
    #[error("unexpected text after the last field")]
    Trailing,
}

const HEADER: &str = "rotor-chain kink run:";
const SAMPLE: &str = "sample";
const DONE: &str = "done";

impl fmt::Display for Header<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = &self.scenario;
        write!(
            f,
            "{HEADER} n={} float={} centre={:e} v0={:e} dt={:e} steps={} every={}",
            self.n, self.float, s.centre, s.v0, s.dt, s.steps, s.every
        )
    }
}

impl<T: Real> fmt::Display for Sample<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{SAMPLE} step={} t={:e} kinetic={:e} potential={:e} walls={}",
            self.step, self.time, self.kinetic, self.potential, self.wall_count
        )?;
        for wall in self.walls() {
            write!(f, " {}@{:e}", wall.charge.name(), wall.position)?;
        }
        Ok(())
    }
}

impl<T: Real> fmt::Display for Summary<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{DONE} steps={} energy_initial={:e} energy_final={:e} max_energy_error={:e}",
            self.steps, self.energy_initial, self.energy_final, self.max_energy_error
        )
    }
}

/// One line of the firmware's output, recognised by its first word.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Record<'a, T> {
    /// The first line: chain and scenario.
    Header(Header<'a>),
    /// One sample.
    Sample(Sample<T>),
    /// The last line: the summary.
    Done(Summary<T>),
    /// Any other line (a panic message, an error report).
    Other(&'a str),
}

impl<'a, T: Real> Record<'a, T> {
    /// Reads one line. Lines that start like a record but do not parse are errors; other lines
    /// are [`Record::Other`].
    pub fn parse(line: &'a str) -> Result<Self, ParseError> {
        let line = line.trim();
        if let Some(rest) = line.strip_prefix(HEADER) {
            parse_header(rest).map(Record::Header)
        } else if let Some(rest) = line.strip_prefix(SAMPLE).filter(|r| r.starts_with(' ')) {
            parse_sample(rest).map(Record::Sample)
        } else if let Some(rest) = line.strip_prefix(DONE).filter(|r| r.starts_with(' ')) {
            parse_summary(rest).map(Record::Done)
        } else {
            Ok(Record::Other(line))
        }
    }
}

fn parse_header(rest: &str) -> Result<Header<'_>, ParseError> {
    let mut fields = rest.split_whitespace();
    let n = number(&mut fields, "n")?;
    let float = field(&mut fields, "float")?;
    let scenario = Scenario {
        centre: number(&mut fields, "centre")?,
        v0: number(&mut fields, "v0")?,
        dt: number(&mut fields, "dt")?,
        steps: number(&mut fields, "steps")?,
        every: number(&mut fields, "every")?,
    };
    end(fields)?;
    Ok(Header { n, float, scenario })
}

fn parse_sample<T: Real>(rest: &str) -> Result<Sample<T>, ParseError> {
    let mut fields = rest.split_whitespace();
    let step = number(&mut fields, "step")?;
    let time = number(&mut fields, "t")?;
    let kinetic = number(&mut fields, "kinetic")?;
    let potential = number(&mut fields, "potential")?;
    let wall_count: usize = number(&mut fields, "walls")?;
    let mut walls = [Wall { position: T::ZERO, charge: Charge::Kink }; MAX_WALLS];
    for slot in walls.iter_mut().take(wall_count) {
        let (name, position) = fields.next().and_then(|w| w.split_once('@')).ok_or(ParseError::Wall)?;
        let charge = match name {
            "kink" => Charge::Kink,
            "antikink" => Charge::Antikink,
            _ => return Err(ParseError::Wall),
        };
        let position = position.parse().map_err(|_| ParseError::Wall)?;
        *slot = Wall { position, charge };
    }
    end(fields)?;
    Ok(Sample { step, time, kinetic, potential, wall_count, walls })
}

fn parse_summary<T: Real>(rest: &str) -> Result<Summary<T>, ParseError> {
    let mut fields = rest.split_whitespace();
    let summary = Summary {
        steps: number(&mut fields, "steps")?,
        energy_initial: number(&mut fields, "energy_initial")?,
        energy_final: number(&mut fields, "energy_final")?,
        max_energy_error: number(&mut fields, "max_energy_error")?,
    };
    end(fields)?;
    Ok(summary)
}

/// The value of the next field, which must be `key=value`.
fn field<'a>(fields: &mut SplitWhitespace<'a>, key: &'static str) -> Result<&'a str, ParseError> {
    fields
        .next()
        .and_then(|f| f.strip_prefix(key))
        .and_then(|f| f.strip_prefix('='))
        .ok_or(ParseError::Missing { key })
}

fn number<X: FromStr>(fields: &mut SplitWhitespace<'_>, key: &'static str) -> Result<X, ParseError> {
    field(fields, key)?.parse().map_err(|_| ParseError::Number { key })
}

fn end(mut fields: SplitWhitespace<'_>) -> Result<(), ParseError> {
    if fields.next().is_none() { Ok(()) } else { Err(ParseError::Trailing) }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::string::ToString;

    use super::*;

    #[test]
    fn records_read_back_what_was_written() {
        let header = Header { n: 16, float: "f64", scenario: Scenario::FIRMWARE };
        let text = header.to_string();
        assert_eq!(Record::<f64>::parse(&text), Ok(Record::Header(header)));

        let wall = |position, charge| Wall { position, charge };
        let sample = Sample::<f32> {
            step: 512,
            time: 0.25,
            kinetic: 7.999_999_5,
            potential: 1.0e-30,
            wall_count: 5,
            walls: [
                wall(1.5, Charge::Kink),
                wall(2.25, Charge::Antikink),
                wall(3.125, Charge::Kink),
                wall(-0.0, Charge::Antikink),
            ],
        };
        let text = sample.to_string();
        assert_eq!(Record::parse(&text), Ok(Record::Sample(sample)), "{text}");

        let summary = Summary { steps: 9, energy_initial: 8.0, energy_final: 8.1, max_energy_error: 0.1f64 };
        assert_eq!(Record::parse(&summary.to_string()), Ok(Record::Done(summary)));
        assert_eq!(
            Record::<f64>::parse("panicked at src/main.rs"),
            Ok(Record::Other("panicked at src/main.rs"))
        );
    }

    #[test]
    fn malformed_records_are_errors_naming_the_field() {
        assert_eq!(Record::<f64>::parse("sample step=1 t=x"), Err(ParseError::Number { key: "t" }));
        assert_eq!(Record::<f64>::parse("done steps=1"), Err(ParseError::Missing { key: "energy_initial" }));
        let sample = "sample step=0 t=0e0 kinetic=1e0 potential=0e0 walls=1 wall@2";
        assert_eq!(Record::<f64>::parse(sample), Err(ParseError::Wall));
        let sample = "sample step=0 t=0e0 kinetic=1e0 potential=0e0 walls=0 extra";
        assert_eq!(Record::<f64>::parse(sample), Err(ParseError::Trailing));
    }
}
