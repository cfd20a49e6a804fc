//! One row of the summary table: a number the paper states beside ours, and whether the two can
//! be compared.
//!
//! **The rule.** A row compares one quantity at the same parameters on both sides (a row that
//! would set our A against the paper's B is written as two like-for-like numbers, or in words).
//! Given that, two numbers are compared by their relative difference unless one of them carries no
//! information at that scale:
//! - a number at or below the *resolution* of its quantity (declared with [`Row::resolution`],
//!   e.g. the smallest frequency a double-precision `ω²` resolves) is indistinguishable from zero,
//!   and a relative difference to it means nothing: the row says "not comparable" and why;
//! - a paper's value of zero has no relative difference;
//! - a difference no larger than half a unit in the last digit the paper prints is within the
//!   paper's rounding, and the row says so beside the percentage.

use std::fmt;

/// A number as the paper prints it: its value and its precision, half a unit in its last digit
/// (`"2.31"` is 2.31 ± 0.005, `"7.7e-9"` is 7.7e-9 ± 5e-11). From an `f64`, the digits of
/// [`format_number`] are taken as printed (write the paper's text to keep its trailing zeros:
/// `"0.60"`).
#[derive(Clone, Debug, PartialEq)]
pub struct Printed {
    /// The number as printed.
    pub text: String,
    /// The value, `None` when the text is not a number.
    pub value: Option<f64>,
    /// Half a unit in the last printed digit.
    pub precision: f64,
}

impl From<&str> for Printed {
    fn from(text: &str) -> Self {
        let text = text.trim();
        let (mantissa, exponent) = match text.split_once(['e', 'E']) {
            Some((m, e)) => (m, e.parse::<i32>().ok()),
            None => (text, Some(0)),
        };
        let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
        let value = text.parse::<f64>().ok().filter(|v| v.is_finite());
        let precision = exponent.map_or(f64::NAN, |e| 0.5 * 10f64.powi(e - decimals));
        Self { text: text.to_owned(), value, precision }
    }
}

impl From<String> for Printed {
    fn from(text: String) -> Self {
        Printed::from(text.as_str())
    }
}

impl From<f64> for Printed {
    fn from(value: f64) -> Self {
        Printed::from(format_number(value).as_str())
    }
}

/// How the paper's number and ours compare, by the rule of this module.
#[derive(Clone, Debug, PartialEq)]
pub enum Comparison {
    /// A row in words: nothing to compute.
    Words,
    /// `|ours − paper| / |paper|`; `within_rounding` when `|ours − paper|` is at most the
    /// paper's printed precision.
    Relative {
        /// Relative difference `(ours - paper) / paper`.
        difference: f64,
        /// Whether the difference is within the paper's printed precision.
        within_rounding: bool,
    },
    /// The two numbers cannot be compared as a relative difference, and why.
    NotComparable {
        /// Why the two numbers cannot be compared.
        reason: String,
    },
}

impl fmt::Display for Comparison {
    /// The summary's cell: `11.38`, `0.21 (within the paper's rounding)`, `not comparable: …`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Comparison::Words => Ok(()),
            Comparison::Relative { difference, within_rounding } => {
                let percent = 100.0 * difference;
                // Two decimals; below 0.01 %, six significant digits.
                if percent >= 0.01 {
                    write!(f, "{percent:.2}")?;
                } else {
                    write!(f, "{}", format_number(percent))?;
                }
                if *within_rounding { write!(f, " (within the paper's rounding)") } else { Ok(()) }
            }
            Comparison::NotComparable { reason } => write!(f, "not comparable: {reason}"),
        }
    }
}

/// The resolution of a quantity: the smallest magnitude that is not rounding, and what sets it.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolution {
    /// The value.
    pub value: f64,
    /// E.g. "the smallest ω a double-precision ω² resolves here".
    pub what: String,
}

/// Compare the paper's number with ours by the rule of this module.
pub fn compare(paper: &Printed, ours: f64, resolution: Option<&Resolution>) -> Comparison {
    let not = |reason: String| Comparison::NotComparable { reason };
    let Some(value) = paper.value else {
        return not(format!("the paper's \"{}\" is not a number", paper.text));
    };
    if !ours.is_finite() {
        return not(format!("ours is {ours}"));
    }
    if let Some(r) = resolution {
        let floor = format_number(r.value);
        if value.abs() <= r.value {
            return not(format!(
                "the paper's {} is at or below {floor}, {}: indistinguishable from zero",
                paper.text, r.what
            ));
        }
        if ours.abs() <= r.value {
            return not(format!(
                "ours, {}, is at or below {floor}, {}: indistinguishable from zero",
                format_number(ours),
                r.what
            ));
        }
    }
    if value == 0.0 {
        return not(format!("the paper's value is 0; ours is {}", format_number(ours)));
    }
    let gap = (ours - value).abs();
    Comparison::Relative { difference: gap / value.abs(), within_rounding: gap <= paper.precision }
}

/// One row of the summary table: a number the paper states, beside ours.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// What the number is, with its parameters.
    pub quantity: String,
    /// The paper's statement (a number or a word such as "transmitted").
    pub paper: String,
    /// Our number, as printed.
    pub ours: String,
    /// The continuum theory's value where one exists.
    pub continuum: Option<String>,
    /// The paper's number against ours ([`compare`]).
    pub comparison: Comparison,
    /// One line on why they differ, where they do.
    pub note: String,
    /// For a numeric row: the paper's number, ours, and the quantity's resolution.
    numbers: Option<(Printed, f64, Option<Resolution>)>,
}

impl Row {
    /// A numeric row: `paper` as the paper prints it (`"2.31"`, or an `f64`), ours, the
    /// continuum's. The comparison follows the rule of this module.
    pub fn number(
        quantity: impl Into<String>,
        paper: impl Into<Printed>,
        ours: f64,
        continuum: Option<f64>,
        note: impl Into<String>,
    ) -> Self {
        let paper = paper.into();
        Self {
            quantity: quantity.into(),
            paper: paper.text.clone(),
            ours: format_number(ours),
            continuum: continuum.map(format_number),
            comparison: compare(&paper, ours, None),
            note: note.into(),
            numbers: Some((paper, ours, None)),
        }
    }

    /// A row whose values are words (outcomes, qualitative statements).
    pub fn words(quantity: impl Into<String>, paper: &str, ours: &str, note: impl Into<String>) -> Self {
        Self {
            quantity: quantity.into(),
            paper: paper.to_owned(),
            ours: ours.to_owned(),
            continuum: None,
            comparison: Comparison::Words,
            note: note.into(),
            numbers: None,
        }
    }

    /// The smallest magnitude of this quantity that is not rounding, and what sets it: a number
    /// at or below it is not compared. No effect on a row in words.
    pub fn resolution(mut self, value: f64, what: impl Into<String>) -> Self {
        if let Some((paper, ours, resolution)) = &mut self.numbers {
            *resolution = Some(Resolution { value, what: what.into() });
            self.comparison = compare(paper, *ours, resolution.as_ref());
        }
        self
    }

    /// The same row with a continuum value in words or a number already formatted.
    pub fn with_continuum(self, continuum: impl Into<String>) -> Self {
        Self { continuum: Some(continuum.into()), ..self }
    }
}

/// Six significant digits with trailing zeros dropped (the paper's 1359.15 and 1359.75, whose
/// difference is its barrier, must stay apart), scientific notation outside `[1e-3, 1e5)`.
pub fn format_number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 {
        return "0".to_owned();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    if !(1e-3..1e5).contains(&a) {
        let text = format!("{x:.5e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        return format!("{}e{exponent}", trim_zeros(mantissa));
    }
    let digits = (5 - a.log10().floor() as i32).max(0) as usize;
    trim_zeros(&format!("{x:.digits$}")).to_owned()
}

/// `1.500` -> `1.5`, `2.000` -> `2`; integers untouched.
fn trim_zeros(text: &str) -> &str {
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { text }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_printed_with_six_significant_digits() {
        assert_eq!(format_number(1359.15), "1359.15");
        assert_eq!(format_number(1392.029215), "1392.03");
        assert_eq!(format_number(7.7e-9), "7.7e-9");
        assert_eq!(format_number(-10.6), "-10.6");
        assert_eq!(format_number(f64::NAN), "NaN");
    }

    #[test]
    fn the_printed_precision_is_half_a_unit_in_the_last_digit() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert!(close(Printed::from("2.31").precision, 0.005));
        assert!(close(Printed::from("0.60").precision, 0.005));
        assert!(close(Printed::from("7.7e-9").precision, 5e-11));
        assert!(close(Printed::from("8").precision, 0.5));
        assert!(close(Printed::from("-10.6").precision, 0.05));
        assert!(close(Printed::from(0.6).precision, 0.05), "an f64 keeps only its shortest digits");
        assert_eq!(Printed::from("about 8").value, None);
    }

    #[test]
    fn rows_compute_their_relative_difference() {
        let r = Row::number("barrier", "0.60", 0.668, None, "");
        let Comparison::Relative { difference, within_rounding } = r.comparison else { panic!() };
        assert!((difference - 0.1133).abs() < 1e-3 && !within_rounding);
        assert_eq!(r.paper, "0.60");
        assert_eq!(r.comparison.to_string(), "11.33");
        // 2.30514 against the printed 2.31: inside 2.31 +- 0.005.
        let r = Row::number("l_critical", "2.31", 2.30514, None, "");
        assert_eq!(r.comparison.to_string(), "0.21 (within the paper's rounding)");
    }

    #[test]
    fn a_number_below_its_resolution_is_not_compared() {
        let r = Row::number("soft mode", "7.7e-9", 0.020132, None, "")
            .resolution(2.1e-8, "the smallest ω a double-precision ω² resolves here");
        let text = r.comparison.to_string();
        assert!(text.starts_with("not comparable: the paper's 7.7e-9 is at or below 2.1e-8"), "{text}");
        let r = Row::number("soft mode", "0.02", 1e-9, None, "").resolution(2.1e-8, "rounding");
        assert!(r.comparison.to_string().starts_with("not comparable: ours, 1e-9,"), "{}", r.comparison);
        // Above the resolution both are compared as usual.
        let r = Row::number("soft mode", "0.020", 0.021, None, "").resolution(2.1e-8, "rounding");
        assert_eq!(r.comparison.to_string(), "5.00");
        let r = Row::number("zero", "0", 0.5, None, "");
        assert!(matches!(r.comparison, Comparison::NotComparable { .. }));
        assert_eq!(Row::words("w", "a", "b", "").resolution(1.0, "x").comparison, Comparison::Words);
    }
}
