//! The 2-D parameter grid: two axes of sample values, points indexed `(i, j)` with `x = xs[i]`,
//! `y = ys[j]`.

use std::fmt::Write as _;
use std::str::FromStr;

use rotor_chain::validate::{Fields, InvalidOption, OptionError, Validate};

/// The most samples one axis may have. A point is one simulation (milliseconds to seconds), so a
/// larger count is a typo, and refusing it keeps a typo from allocating gigabytes.
pub const MAX_AXIS_COUNT: usize = 100_000;
/// The most points a grid may have, for the same reason.
pub const MAX_GRID_POINTS: usize = 10_000_000;

/// A grid or axis that cannot be built. Every variant carries the offending input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GridError {
    #[error("an axis needs at least 1 point, got count = {count}")]
    /// An axis of no points.
    EmptyAxis {
        /// The number of points asked for.
        count: usize,
    },
    #[error("an axis may have at most {MAX_AXIS_COUNT} points, got count = {count}")]
    /// An axis of more points than allowed.
    TooManyPoints {
        /// The number of points asked for.
        count: usize,
    },
    #[error("the grid has {nx} x {ny} points, more than the limit of {MAX_GRID_POINTS}")]
    /// A grid of more points than allowed.
    TooLarge {
        /// Points along x.
        nx: usize,
        /// Points along y.
        ny: usize,
    },
    #[error("axis value {value} is not a finite number")]
    /// A bound that is NaN or infinite.
    NotFinite {
        /// The value.
        value: f64,
    },
    #[error("a 1-point axis needs FROM = TO, got {from}:{to}:1 (write {from}:{from}:1)")]
    /// One point asked for between two different bounds.
    AmbiguousSinglePoint {
        /// The range's start.
        from: f64,
        /// Its end.
        to: f64,
    },
    #[error("`{text}` is not a range FROM:TO:COUNT or FROM:TO:COUNT:log: {reason}")]
    /// A range that cannot be read (`from:to:count[:log]`).
    BadRange {
        /// The range as written.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    #[error("a logarithmic axis needs FROM and TO > 0, got {from}:{to}")]
    /// A logarithmic axis with a bound <= 0.
    NotPositive {
        /// The range's start.
        from: f64,
        /// Its end.
        to: f64,
    },
    #[error(transparent)]
    /// A field of a [`Grid`] outside its range ([`Validate`]): an axis's count or a value.
    InvalidOption(#[from] InvalidOption),
}

impl OptionError for GridError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            Self::InvalidOption(o) => Some(*o),
            _ => None,
        }
    }
}

/// The sample values of one axis.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    values: Vec<f64>,
}

impl Axis {
    /// `count` evenly spaced values from `from` to `to`, both included (descending if
    /// `to < from`). A 1-point axis is `[from]` and needs `from == to`, so that `0.5:1:1` is not
    /// silently read as `0.5`.
    pub fn linspace(from: f64, to: f64, count: usize) -> Result<Self, GridError> {
        check_count(count)?;
        for value in [from, to] {
            check_finite(value)?;
        }
        if count == 1 {
            return if from == to {
                Ok(Self { values: vec![from] })
            } else {
                Err(GridError::AmbiguousSinglePoint { from, to })
            };
        }
        // numpy's rule: a fixed step from `from`, and the last value exactly `to`.
        let step = (to - from) / (count - 1) as f64;
        check_finite(step)?;
        let values = (0..count).map(|k| if k + 1 == count { to } else { from + k as f64 * step }).collect();
        Ok(Self { values })
    }

    /// `count` values from `from` to `to`, both included, evenly spaced in the logarithm (a
    /// constant ratio between neighbours); both ends must be positive. A 1-point axis is `[from]`
    /// and needs `from == to`.
    pub fn geomspace(from: f64, to: f64, count: usize) -> Result<Self, GridError> {
        check_count(count)?;
        for value in [from, to] {
            check_finite(value)?;
        }
        if !(from > 0.0 && to > 0.0) {
            return Err(GridError::NotPositive { from, to });
        }
        if count == 1 {
            return if from == to {
                Ok(Self { values: vec![from] })
            } else {
                Err(GridError::AmbiguousSinglePoint { from, to })
            };
        }
        let (a, b) = (from.ln(), to.ln());
        let step = (b - a) / (count - 1) as f64;
        let values = (0..count)
            .map(|k| match k {
                0 => from,
                k if k + 1 == count => to,
                k => (a + k as f64 * step).exp(),
            })
            .collect();
        Ok(Self { values })
    }

    /// An axis of explicit values (at least one, all finite).
    pub fn from_values(values: Vec<f64>) -> Result<Self, GridError> {
        check_count(values.len())?;
        values.iter().try_for_each(|&v| check_finite(v))?;
        Ok(Self { values })
    }

    /// The axis's values, in order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// How many values.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Always false: an axis has at least one point.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }
}

/// `FROM:TO:COUNT` (evenly spaced), or `FROM:TO:COUNT:log` (evenly spaced in the logarithm), as
/// on the command line (`--ki 0.01:3:40:log`).
impl FromStr for Axis {
    type Err = GridError;

    fn from_str(text: &str) -> Result<Self, GridError> {
        let bad = |reason: String| GridError::BadRange { text: text.to_owned(), reason };
        let parts: Vec<&str> = text.split(':').map(str::trim).collect();
        let (from, to, count, log) = match parts[..] {
            [from, to, count] => (from, to, count, false),
            [from, to, count, "log"] => (from, to, count, true),
            [_, _, _, other] => return Err(bad(format!("the fourth part must be `log`, found `{other}`"))),
            _ => return Err(bad(format!("expected 3 or 4 parts separated by `:`, found {}", parts.len()))),
        };
        let number =
            |name: &str, s: &str| s.parse::<f64>().map_err(|_| bad(format!("{name} `{s}` is not a number")));
        let (from, to) = (number("FROM", from)?, number("TO", to)?);
        let count =
            count.parse::<usize>().map_err(|_| bad(format!("COUNT `{count}` is not a whole number >= 1")))?;
        if log { Self::geomspace(from, to, count) } else { Self::linspace(from, to, count) }
    }
}

/// The points `(xs[i], ys[j])`. Both axes are non-empty and finite; the grid has at most
/// [`MAX_GRID_POINTS`] points.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    xs: Vec<f64>,
    ys: Vec<f64>,
}

impl Grid {
    /// The grid of every `(x, y)` pair of the two axes.
    pub fn new(x: Axis, y: Axis) -> Result<Self, GridError> {
        let (nx, ny) = (x.len(), y.len());
        if nx.checked_mul(ny).is_none_or(|points| points > MAX_GRID_POINTS) {
            return Err(GridError::TooLarge { nx, ny });
        }
        Ok(Self { xs: x.values, ys: y.values })
    }

    /// The x values.
    pub fn xs(&self) -> &[f64] {
        &self.xs
    }

    /// The y values.
    pub fn ys(&self) -> &[f64] {
        &self.ys
    }

    /// The number of points, `xs.len() * ys.len()`.
    pub fn len(&self) -> usize {
        self.xs.len() * self.ys.len()
    }

    /// Always false: a grid has at least one point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The coordinates of point `(i, j)`, or `None` outside the grid.
    pub fn point(&self, i: usize, j: usize) -> Option<(f64, f64)> {
        Some((*self.xs.get(i)?, *self.ys.get(j)?))
    }

    /// Every index pair, `i` outer, `j` inner.
    pub fn indices(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.xs.len()).flat_map(|i| (0..self.ys.len()).map(move |j| (i, j)))
    }

    /// One line that identifies this grid exactly, stored in a results file so that a resumed
    /// sweep refuses a file of another grid: the readable ranges and counts, plus an FNV-1a hash
    /// of every value's bits (two grids with the same ends and counts but different interior
    /// values differ in the hash).
    ///
    /// Deliberately a function of the values only, not of how they were specified: a `:log` axis
    /// reads `x=0.01:3.0:40` like the even one, and the hash tells the two apart. A spec in the
    /// signature would break `merge`, which rebuilds the grid from the points' coordinates
    /// ([`Axis::from_values`], no spec) and compares signatures, and `signature_dims`, which
    /// reads the count after the last `:`.
    pub fn signature(&self) -> String {
        let mut hash = Fnv1a::new();
        for axis in [&self.xs, &self.ys] {
            hash.write(&(axis.len() as u64).to_le_bytes());
            axis.iter().for_each(|v| hash.write(&v.to_bits().to_le_bytes()));
        }
        let mut out = String::new();
        for (name, axis) in [("x", &self.xs), ("y", &self.ys)] {
            let (first, last) = (axis[0], axis[axis.len() - 1]);
            let _ = write!(out, "{name}={first:?}:{last:?}:{} ", axis.len());
        }
        let _ = write!(out, "fnv1a={:016x}", hash.0);
        out
    }
}

impl Validate for Grid {
    type Error = GridError;

    /// Both axes hold between 1 and [`MAX_AXIS_COUNT`] finite values, and `ys` at most
    /// [`MAX_GRID_POINTS`]` / xs.len()` (the grid at most [`MAX_GRID_POINTS`] points): what
    /// [`Grid::new`] and the [`Axis`] constructors establish (the fields are private), checked
    /// again where a sweep starts. The error is [`GridError::InvalidOption`], naming `Grid.xs`
    /// or `Grid.ys` with the count (or the value that is not finite).
    fn validate(&self) -> Result<(), GridError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { xs, ys } = self;
        let fields = Fields("Grid");
        for (name, axis) in [("xs", xs), ("ys", ys)] {
            let rule = "between 1 and MAX_AXIS_COUNT = 100000 values";
            fields.count_in(name, axis.len() as u64, 1, MAX_AXIS_COUNT as u64, rule)?;
            axis.iter().try_for_each(|&v| fields.finite(name, v))?;
        }
        let most = (MAX_GRID_POINTS / xs.len()) as u64;
        let rule = "at most MAX_GRID_POINTS / xs.len() = 10000000 / xs.len() values (the grid's points)";
        fields.count_in("ys", ys.len() as u64, 1, most, rule)?;
        Ok(())
    }
}

/// The point counts `(nx, ny)` that a [`Grid::signature`] states.
pub(crate) fn signature_dims(signature: &str) -> Option<(usize, usize)> {
    let count = |key: &str| -> Option<usize> {
        let part = signature.split(' ').find_map(|p| p.strip_prefix(key))?;
        part.rsplit(':').next()?.parse().ok()
    };
    Some((count("x=")?, count("y=")?))
}

/// 64-bit FNV-1a: a tiny, stable, dependency-free hash (std's `DefaultHasher` may change between
/// Rust releases, and the signature must not).
struct Fnv1a(u64);

impl Fnv1a {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

fn check_count(count: usize) -> Result<(), GridError> {
    match count {
        0 => Err(GridError::EmptyAxis { count }),
        c if c > MAX_AXIS_COUNT => Err(GridError::TooManyPoints { count }),
        _ => Ok(()),
    }
}

fn check_finite(value: f64) -> Result<(), GridError> {
    if value.is_finite() { Ok(()) } else { Err(GridError::NotFinite { value }) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linspace_includes_both_ends() {
        let axis = Axis::linspace(0.0, 1.0, 5).unwrap();
        assert_eq!(axis.values(), [0.0, 0.25, 0.5, 0.75, 1.0]);
        let down = Axis::linspace(12.0, 0.5, 3).unwrap();
        assert_eq!(down.values(), [12.0, 6.25, 0.5]);
        assert_eq!(Axis::linspace(0.3, 0.3, 1).unwrap().values(), [0.3]);
    }

    #[test]
    fn geomspace_has_a_constant_ratio_and_exact_ends() {
        let axis = "0.01:3:40:log".parse::<Axis>().unwrap();
        let v = axis.values();
        assert_eq!((v[0], v[39], v.len()), (0.01, 3.0, 40));
        let ratio = 300f64.powf(1.0 / 39.0);
        for w in v.windows(2) {
            assert!((w[1] / w[0] - ratio).abs() < 1e-12, "{w:?}");
        }
        assert_eq!(Axis::geomspace(2.0, 2.0, 1).unwrap().values(), [2.0]);
        assert_eq!(Axis::geomspace(-1.0, 2.0, 3), Err(GridError::NotPositive { from: -1.0, to: 2.0 }));
    }

    #[test]
    fn parses_ranges() {
        assert_eq!("0.01:1:3".parse::<Axis>().unwrap().values(), [0.01, 0.505, 1.0]);
        assert_eq!(" 1e-2 : 1 : 2 ".parse::<Axis>().unwrap().values(), [0.01, 1.0]);
        assert_eq!("-1:1:3".parse::<Axis>().unwrap().values(), [-1.0, 0.0, 1.0]);
    }

    #[test]
    fn rejects_bad_ranges_with_the_reason() {
        let err = |s: &str| s.parse::<Axis>().unwrap_err();
        assert_eq!(err("0:1:0"), GridError::EmptyAxis { count: 0 });
        assert!(matches!(err("0:1:-3"), GridError::BadRange { reason, .. } if reason.contains("COUNT `-3`")));
        assert!(
            matches!(err("0:1:2.5"), GridError::BadRange { reason, .. } if reason.contains("whole number"))
        );
        assert!(matches!(err("0:1"), GridError::BadRange { reason, .. } if reason.contains("found 2")));
        assert!(matches!(err("0.1:1:3:lin"), GridError::BadRange { reason, .. } if reason.contains("`lin`")));
        assert_eq!(err("0:1:3:log"), GridError::NotPositive { from: 0.0, to: 1.0 });
        assert!(matches!(err("a:1:3"), GridError::BadRange { reason, .. } if reason.contains("FROM `a`")));
        assert!(matches!(err("0:1:3:4"), GridError::BadRange { .. }));
        assert!(matches!(err("0:1:3:log:x"), GridError::BadRange { .. }));
        assert!(matches!(err(""), GridError::BadRange { .. }));
        assert!(matches!(err("0:inf:3"), GridError::NotFinite { .. }));
        assert!(matches!(err("NaN:1:3"), GridError::NotFinite { .. }));
        assert_eq!(err("0.5:1:1"), GridError::AmbiguousSinglePoint { from: 0.5, to: 1.0 });
        assert_eq!(err("0:1:100001"), GridError::TooManyPoints { count: 100_001 });
        let message = err("0:1:x").to_string();
        assert!(message.contains("`0:1:x`") && message.contains("COUNT `x`"), "{message}");
    }

    #[test]
    fn grid_indexes_points_and_limits_size() {
        let grid =
            Grid::new(Axis::linspace(0.0, 1.0, 2).unwrap(), Axis::linspace(5.0, 7.0, 3).unwrap()).unwrap();
        assert_eq!(grid.len(), 6);
        assert_eq!(grid.point(1, 2), Some((1.0, 7.0)));
        assert_eq!(grid.point(2, 0), None);
        assert_eq!(grid.indices().collect::<Vec<_>>()[..3], [(0, 0), (0, 1), (0, 2)]);
        let big = Axis::linspace(0.0, 1.0, MAX_AXIS_COUNT).unwrap();
        assert_eq!(
            Grid::new(big.clone(), big).unwrap_err(),
            GridError::TooLarge { nx: MAX_AXIS_COUNT, ny: MAX_AXIS_COUNT }
        );
    }

    #[test]
    fn signature_tells_grids_apart() {
        let grid = |x: &str, y: &str| Grid::new(x.parse().unwrap(), y.parse().unwrap()).unwrap();
        let a = grid("0.01:1:6", "0.5:12:6");
        assert_eq!(a.signature(), grid("0.01:1:6", "0.5:12:6").signature());
        assert!(a.signature().starts_with("x=0.01:1.0:6 y=0.5:12.0:6 fnv1a="), "{}", a.signature());
        assert_ne!(a.signature(), grid("0.01:1:7", "0.5:12:6").signature());
        assert_ne!(a.signature(), grid("0.5:12:6", "0.01:1:6").signature());
        let uneven = Axis::from_values(vec![0.01, 0.02, 0.03, 0.04, 0.05, 1.0]).unwrap();
        let b = Grid::new(uneven, "0.5:12:6".parse().unwrap()).unwrap();
        assert_ne!(a.signature(), b.signature());
        // A log axis: the same label as the even one (no `:log`), told apart by the hash; the
        // signature of its values, rebuilt without a spec (as `merge` does), is the same.
        let log = grid("0.01:1:6:log", "0.5:12:6");
        let label = |g: &Grid| g.signature().split(" fnv1a=").next().unwrap().to_owned();
        assert_eq!(label(&log), label(&a));
        assert_ne!(log.signature(), a.signature());
        let rebuilt =
            Grid::new(Axis::from_values(log.xs.clone()).unwrap(), "0.5:12:6".parse().unwrap()).unwrap();
        assert_eq!(rebuilt.signature(), log.signature());
        assert_eq!(signature_dims(&log.signature()), Some((6, 6)));
    }

    /// `validate` names `Grid`, the field and the count or value (the fields are private, so only
    /// this module can make a grid its constructors would refuse).
    #[test]
    fn validate_names_the_field_the_count_and_the_rule() {
        let names = |g: Grid| match g.validate() {
            Err(GridError::InvalidOption(o)) => (o.options, o.field, o.value, o.rule),
            other => panic!("expected an invalid option, got {other:?}"),
        };
        let ok = |xs: Vec<f64>, ys: Vec<f64>| assert_eq!(Grid { xs, ys }.validate(), Ok(()));
        let axis = |n: usize| vec![0.5; n];
        let count_rule = "between 1 and MAX_AXIS_COUNT = 100000 values";
        assert_eq!(names(Grid { xs: vec![], ys: axis(2) }), ("Grid", "xs", 0.0, count_rule));
        assert_eq!(names(Grid { xs: axis(2), ys: vec![] }), ("Grid", "ys", 0.0, count_rule));
        ok(axis(MAX_AXIS_COUNT), axis(1));
        let over = (MAX_AXIS_COUNT + 1) as f64;
        assert_eq!(
            names(Grid { xs: axis(MAX_AXIS_COUNT + 1), ys: axis(1) }),
            ("Grid", "xs", over, count_rule)
        );
        let (_, field, value, _) = names(Grid { xs: vec![0.1, f64::NAN], ys: axis(1) });
        assert!(field == "xs" && value.is_nan());
        assert_eq!(names(Grid { xs: axis(1), ys: vec![f64::INFINITY] }).1, "ys");
        // The grid's points: MAX_GRID_POINTS passes, one row more does not.
        let nx = MAX_GRID_POINTS / MAX_AXIS_COUNT;
        ok(axis(nx), axis(MAX_AXIS_COUNT));
        let (_, field, value, rule) = names(Grid { xs: axis(nx + 1), ys: axis(MAX_AXIS_COUNT) });
        assert_eq!((field, value), ("ys", MAX_AXIS_COUNT as f64));
        assert!(rule.contains("MAX_GRID_POINTS") && rule.contains(&MAX_GRID_POINTS.to_string()), "{rule}");
        let text = Grid { xs: vec![], ys: axis(1) }.validate().unwrap_err().to_string();
        assert!(text.starts_with("Grid.xs = 0 is invalid: it must be between 1 and"), "{text}");
    }
}
