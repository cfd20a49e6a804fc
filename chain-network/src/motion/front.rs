//! Where a front between two states lies along a row of sites, and the speed of a front from
//! its positions at several times (a least-squares line, with its residual).

/// The position of the last crossing of `level` going down along `values` (site `i` at position
/// `i`), linearly interpolated between the two sites that straddle it: the front of a state
/// above `level` (on the left) invading one below it (on the right). `None` without a crossing.
pub fn front_position(values: &[f64], level: f64) -> Option<f64> {
    let i = values.windows(2).rposition(|w| w[0] >= level && w[1] < level)?;
    let (a, b) = (values[i], values[i + 1]);
    Some(i as f64 + (a - level) / (a - b))
}

/// The position of a front from the area under it, near its crossing of 1/2
/// ([`front_position`]): `lo + sum_{lo <= i < hi} values[i] - 1/2` over the `half_window` sites on
/// each side of the crossing, for `values` that go from 1 (left) to 0 (right). For a smooth front
/// `1 / (1 + exp((i - x) / w))` this is `x` up to the tails beyond the window (`~ exp(-h / w)`,
/// and of opposite signs on the two sides) and terms `~ exp(-pi^2 w)` (Poisson summation), so it
/// moves smoothly as the front passes the sites, where the crossing's linear interpolation errs
/// periodically by a tenth of a site or more; the window keeps ringing far behind the front out.
pub fn front_by_area(values: &[f64], half_window: usize) -> Option<f64> {
    let crossing = front_position(values, 0.5)? as usize;
    let lo = crossing.saturating_sub(half_window);
    let hi = (crossing + half_window + 1).min(values.len());
    Some(lo as f64 + values[lo..hi].iter().sum::<f64>() - 0.5)
}

/// A straight line fitted to points `(t, x)` by least squares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineFit {
    /// The slope `dx/dt` (a speed, in sites per unit time).
    pub slope: f64,
    /// The value at `t = 0`.
    pub intercept: f64,
    /// The root-mean-square distance of the points from the line.
    pub rms_residual: f64,
    /// How many points.
    pub points: usize,
}

/// The least-squares line through `points` (`None` for fewer than two distinct times).
pub fn fit_line(points: &[(f64, f64)]) -> Option<LineFit> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let (mt, mx) = points.iter().fold((0.0, 0.0), |(a, b), &(t, x)| (a + t / n, b + x / n));
    let (stt, stx) =
        points.iter().fold((0.0, 0.0), |(a, b), &(t, x)| (a + (t - mt).powi(2), b + (t - mt) * (x - mx)));
    if stt <= 0.0 {
        return None;
    }
    let slope = stx / stt;
    let intercept = mx - slope * mt;
    let rms_residual =
        (points.iter().map(|&(t, x)| (x - intercept - slope * t).powi(2)).sum::<f64>() / n).sqrt();
    Some(LineFit { slope, intercept, rms_residual, points: points.len() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_front_is_the_last_downward_crossing_interpolated() {
        assert_eq!(front_position(&[1.0, 1.0, 0.75, 0.25, 0.0], 0.5), Some(2.5));
        assert_eq!(front_position(&[0.0, 0.0], 0.5), None);
        // A crossing back up (a second front the other way) does not count; the last down does.
        assert_eq!(front_position(&[1.0, 0.0, 1.0, 1.0, 0.0], 0.5), Some(3.5));
    }

    #[test]
    fn the_area_locates_a_smooth_front_between_sites() {
        for x in [20.0, 20.25, 20.5, 20.75] {
            let values: Vec<f64> = (0..60).map(|i| 1.0 / (1.0 + ((i as f64 - x) / 2.0).exp())).collect();
            let found = front_by_area(&values, 16).unwrap();
            assert!((found - x).abs() < 1e-3, "{x}: {found}");
        }
    }

    #[test]
    fn a_line_through_exact_points_has_their_slope_and_no_residual() {
        let fit = fit_line(&[(0.0, 1.0), (1.0, 3.0), (2.0, 5.0)]).unwrap();
        assert!((fit.slope - 2.0).abs() < 1e-15 && (fit.intercept - 1.0).abs() < 1e-15);
        assert!(fit.rms_residual < 1e-15);
        assert!(fit_line(&[(1.0, 1.0), (1.0, 2.0)]).is_none());
    }
}
