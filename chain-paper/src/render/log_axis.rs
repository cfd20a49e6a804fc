//! An axis whose data are `log10` of a quantity (a phase diagram's `k_i/k`), ticked at 1, 2 and 5
//! times the powers of ten and labelled with the quantity's values (`0.01`, `0.2`, `5`).

use std::ops::Range;

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;

use super::lines::tick;

/// The tick positions of an axis of `log10` values over `range`: the logarithms of 1, 2 and 5
/// times each power of ten inside it (of the powers alone when that gives more than ten).
pub fn log_ticks(range: &Range<f64>) -> Vec<f64> {
    let (lo, hi) = (range.start.min(range.end), range.start.max(range.end));
    let decades = (lo.floor() as i32)..=(hi.ceil() as i32);
    let inside = |steps: &[f64]| -> Vec<f64> {
        decades
            .clone()
            .flat_map(|d| steps.iter().map(move |m| f64::from(d) + m.log10()))
            .filter(|t| (lo..=hi).contains(t))
            .collect()
    };
    let fine = inside(&[1.0, 2.0, 5.0]);
    if fine.len() > 10 { inside(&[1.0]) } else { fine }
}

/// A linear `f64` axis whose ticks are given (plotters' `WithKeyPoints` has no value formatter
/// for `f64`, which the mesh needs).
pub struct Ticked {
    pub axis: RangedCoordf64,
    pub ticks: Vec<f64>,
}

impl Ranged for Ticked {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.axis.map(value, limit)
    }

    /// The ticks as the bold points; no light points (the mesh draws none).
    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() { Vec::new() } else { self.ticks.clone() }
    }

    fn range(&self) -> Range<f64> {
        self.axis.range()
    }
}

impl ValueFormatter<f64> for Ticked {
    fn format(value: &f64) -> String {
        RangedCoordf64::format(value)
    }
}

/// The label of the tick at `log10` value `v`: the value itself (`0.01`, `0.2`, `5`).
pub fn log_tick(v: &f64) -> String {
    // Round to the 1-2-5 value the tick stands for, so that 10^(log10 0.2) shows as 0.2.
    let value = 10f64.powf(*v);
    tick(&format!("{value:.2e}").parse().unwrap_or(value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_axes_are_ticked_at_one_two_five_and_labelled_with_the_values() {
        let ticks = log_ticks(&(-2.05..0.5));
        let labels: Vec<String> = ticks.iter().map(log_tick).collect();
        assert_eq!(labels, ["0.01", "0.02", "0.05", "0.1", "0.2", "0.5", "1", "2"]);
        // Many decades: the powers of ten alone.
        let labels: Vec<String> = log_ticks(&(-6.0..6.0)).iter().map(log_tick).collect();
        assert_eq!(labels.first().map(String::as_str), Some("1e-6"));
        assert_eq!(labels.len(), 13);
    }
}
