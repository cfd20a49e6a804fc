//! The spring law of a bond: the stored energy as a function of the bond's length `l`, its rest
//! length `l0` and its constant `k`. The harmonic and the quartic laws are fixed formulas; the
//! [`Polynomial`] law takes its coefficients at run time, so a cell file can declare a hardening
//! spring or the double well of a bistable element without compiling anything.

/// A bond's spring law (cell file key `law`: `"harmonic"`, `"quartic"` or
/// `{ polynomial = [c2, c3, ...] }`, on the whole cell or on one `[[bond]]`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub enum BondLaw {
    /// `k (l - l0)^2 / 2` (the paper's Eq. `eq:discretelagrangian`).
    #[default]
    Harmonic,
    /// `k (l^2 - l0^2)^2 / (8 l0^2)` (the paper's Eq. `eq:discretepotential`).
    Quartic,
    /// `k sum_j c_j e^j / j` in the elongation `e = l - l0` ([`Polynomial`]).
    Polynomial(Polynomial),
}

/// The polynomial law in the elongation `e = l - l0`:
///
/// `E(e) = k (c2 e^2 / 2 + c3 e^3 / 3 + c4 e^4 / 4 + c5 e^5 / 5 + c6 e^6 / 6)`,
///
/// so that the tension is `k (c2 e + c3 e^2 + ... + c6 e^5)`. With `c2 = 1` alone it is the
/// harmonic law; [`Polynomial::double_well`] gives the bistable element of a transition-wave
/// chain. The coefficients are numbers per unit of `k`: `c_j` has units of length^(2 - j).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Polynomial {
    /// `[c2, c3, c4, c5, c6]`.
    pub coefficients: [f64; 5],
}

/// Why a list of coefficients is not a polynomial law (the cell reader turns it into a
/// `CellError` at the key's line).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PolynomialProblem {
    /// Empty, or more than the five coefficients `c2 .. c6`.
    #[error("{0} coefficients: a polynomial law takes one to five (c2 .. c6)")]
    Count(usize),
    /// Coefficient `c_{index + 2}` is NaN or infinite.
    #[error("coefficient c{} = {value} is not a finite number", index + 2)]
    NotFinite {
        /// The coefficient's index in the list (0 for `c2`).
        index: usize,
        /// Its value.
        value: f64,
    },
}

impl Polynomial {
    /// The most coefficients (`c2 .. c6`).
    pub const MAX_COEFFICIENTS: usize = 5;

    /// The law with coefficients `c2, c3, ...` (one to five; the missing higher ones are 0).
    pub fn new(coefficients: &[f64]) -> Result<Self, PolynomialProblem> {
        if coefficients.is_empty() || coefficients.len() > Self::MAX_COEFFICIENTS {
            return Err(PolynomialProblem::Count(coefficients.len()));
        }
        let mut c = [0.0; 5];
        for (index, &value) in coefficients.iter().enumerate() {
            if !value.is_finite() {
                return Err(PolynomialProblem::NotFinite { index, value });
            }
            c[index] = value;
        }
        Ok(Self { coefficients: c })
    }

    /// The harmonic law as a polynomial: `c2 = 1`.
    pub fn harmonic() -> Self {
        Self { coefficients: [1.0, 0.0, 0.0, 0.0, 0.0] }
    }

    /// The double well whose tension `k e (e - a) (e - b)` vanishes at `e = 0, a, b`: for
    /// `0 < a < b` the elongations `0` and `b` are stable, `a` the barrier between them, and the
    /// well at `b` lies lower than the one at `0` by `k b^3 (b - 2 a) / 12` (deeper for
    /// `a < b / 2`). Coefficients `c2 = a b`, `c3 = -(a + b)`, `c4 = 1`.
    pub fn double_well(a: f64, b: f64) -> Self {
        Self { coefficients: [a * b, -(a + b), 1.0, 0.0, 0.0] }
    }

    /// The energy per unit `k` at elongation `e`, summed term by term as defined (for checks).
    pub fn energy(&self, e: f64) -> f64 {
        (0..5).map(|j| self.coefficients[j] * e.powi(j as i32 + 2) / (j + 2) as f64).sum()
    }

    /// The tension per unit `k` at elongation `e`: `sum_j c_j e^(j - 1)`.
    pub fn tension(&self, e: f64) -> f64 {
        (0..5).map(|j| self.coefficients[j] * e.powi(j as i32 + 1)).sum()
    }

    /// The coefficients up to the last one that is not zero (at least `c2`), for writing.
    pub fn significant(&self) -> &[f64] {
        let last = self.coefficients.iter().rposition(|&c| c != 0.0).unwrap_or(0);
        &self.coefficients[..=last]
    }
}

impl BondLaw {
    /// The law's name in the cell format.
    pub fn name(&self) -> &'static str {
        match self {
            BondLaw::Harmonic => "harmonic",
            BondLaw::Quartic => "quartic",
            BondLaw::Polynomial(_) => "polynomial",
        }
    }

    /// The law as the cell format writes it (a TOML value).
    pub fn to_toml(&self) -> String {
        match self {
            BondLaw::Polynomial(p) => {
                let c: Vec<String> = p.significant().iter().map(|c| format!("{c:?}")).collect();
                format!("{{ polynomial = [{}] }}", c.join(", "))
            }
            other => format!("{:?}", other.name()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_double_well_has_its_three_zeros_and_the_stated_depth() {
        let (a, b) = (0.3, 1.0);
        let p = Polynomial::double_well(a, b);
        for e in [0.0, a, b] {
            assert!(p.tension(e).abs() < 1e-15, "tension at {e}: {}", p.tension(e));
        }
        let depth = p.energy(0.0) - p.energy(b);
        assert!((depth - b.powi(3) * (b - 2.0 * a) / 12.0).abs() < 1e-15, "{depth}");
    }

    #[test]
    fn coefficients_are_checked_and_written_back_without_trailing_zeros() {
        assert_eq!(Polynomial::new(&[]), Err(PolynomialProblem::Count(0)));
        assert_eq!(Polynomial::new(&[1.0; 6]), Err(PolynomialProblem::Count(6)));
        assert!(matches!(
            Polynomial::new(&[1.0, f64::NAN]),
            Err(PolynomialProblem::NotFinite { index: 1, .. })
        ));
        let p = Polynomial::new(&[1.0, 0.0, 2.5]).unwrap();
        assert_eq!(p.coefficients, [1.0, 0.0, 2.5, 0.0, 0.0]);
        assert_eq!(BondLaw::Polynomial(p).to_toml(), "{ polynomial = [1.0, 0.0, 2.5] }");
    }
}
