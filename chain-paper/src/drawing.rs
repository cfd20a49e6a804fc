//! A drawing of the chain itself, as the paper's configuration figures draw it (Figs. 1,
//! `fig:kconfig`, `fig:akconfig`, `fig:mode-config`, `fig:longbar`): pivots (crosses), rigid
//! rotors (black) with their tip masses (blue), springs between the tips coloured by their stretch
//! `l_p − l0_p` (a diverging map centred on zero, with a colour bar), the impurity spring
//! outlined, and optionally a mode's displacement of each tip (green arrows) or a tensional
//! mode's amplitude on each spring (green bars).
//!
//! Geometry (`docs/theory.md` §1): pivot `i` at `(i a, 0)`, tip `i` at
//! `(i a + r_i sin θ_i, (−1)^i r_i cos θ_i)`.

use std::ops::Range;

use rotor_chain::ChainModel;

/// A chain, or a window of it, ready to draw. Lengths are in units of the lattice spacing `a`.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainDrawing {
    /// Title above the drawing.
    pub title: String,
    /// The rotors drawn, by their index in the chain.
    pub rotors: Range<usize>,
    /// Pivot and tip of each rotor drawn.
    pub pivots: Vec<(f64, f64)>,
    /// Tip positions `(x, y)`, in `a`.
    pub tips: Vec<(f64, f64)>,
    /// Rotor angles `θ_i` of the rotors drawn (rad), for the data file.
    pub angles: Vec<f64>,
    /// `(l_j − l0_j) / a` of the spring between tips `j` and `j + 1` (one fewer than the tips).
    pub stretch: Vec<f64>,
    /// Springs (indices into `stretch`) that are impurities: a rest length or stiffness unlike
    /// the chain's most common one.
    pub impurities: Vec<usize>,
    /// Per tip, a mode's displacement of it, the largest of length 1 (empty: no arrows).
    pub arrows: Vec<(f64, f64)>,
    /// Per spring, a tensional mode's amplitude `|t_j|`, the largest 1 (empty: no bars).
    pub tensions: Vec<f64>,
    /// The limit of the stretch colour scale, in `a`, when it is shared with other drawings
    /// ([`ChainDrawing::share_stretch_scale`]); `None`: this drawing's largest `|stretch|`.
    pub stretch_scale: Option<f64>,
}

/// Why a drawing could not be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DrawingError {
    #[error("{what} has {}, the chain has {expected}", rotor_chain::geometry::Counted(*len, "value"))]
    /// An input with the wrong length.
    WrongLength {
        /// Which input.
        what: &'static str,
        /// Its length.
        len: usize,
        /// The length it must have.
        expected: usize,
    },
    #[error("rotors {start}..{end} of a chain of {n}: at least two rotors must be drawn")]
    /// A window of rotors that is empty or off the chain.
    EmptyWindow {
        /// First rotor of the window.
        start: usize,
        /// One past its last rotor.
        end: usize,
        /// Rotors of the chain.
        n: usize,
    },
}

/// Stretches below this fraction of the rest length are rounding in the spring lengths and are
/// drawn as zero (a kink built by the branch solve has `|l − l0| ≈ 1e-15 l0`).
const ROUNDING: f64 = 1e-9;

impl ChainDrawing {
    /// Rotors `rotors` (clipped to the chain) of `model` at angles `theta`.
    pub fn new<M: ChainModel>(
        title: impl Into<String>,
        model: &M,
        theta: &[f64],
        rotors: Range<usize>,
    ) -> Result<Self, DrawingError> {
        let n = model.rotor_count();
        if theta.len() != n {
            return Err(DrawingError::WrongLength { what: "theta", len: theta.len(), expected: n });
        }
        let rotors = rotors.start.min(n)..rotors.end.min(n);
        if rotors.len() < 2 {
            return Err(DrawingError::EmptyWindow { start: rotors.start, end: rotors.end, n });
        }
        let a = model.lattice_spacing();
        let mut lengths = vec![0.0; n - 1];
        model.spring_lengths_into(theta, &mut lengths);
        let pivots = rotors.clone().map(|i| (i as f64, 0.0)).collect();
        let tips = rotors
            .clone()
            .map(|i| {
                let (s, c) = theta[i].sin_cos();
                let r = model.rotor_length(i) / a;
                (i as f64 + r * s, if i.is_multiple_of(2) { r * c } else { -r * c })
            })
            .collect();
        let springs = rotors.start..rotors.end - 1;
        let stretch = springs
            .clone()
            .map(|p| {
                let (l, l0) = (lengths[p], model.rest_length(p));
                if (l - l0).abs() <= ROUNDING * l0 { 0.0 } else { (l - l0) / a }
            })
            .collect();
        // The most common (stiffness, rest length) of the chain's springs; the others are impurities.
        let key = |p: usize| (model.spring_constant(p).to_bits(), model.rest_length(p).to_bits());
        let mut counts: Vec<((u64, u64), usize)> = Vec::new();
        for p in 0..n - 1 {
            match counts.iter_mut().find(|(k, _)| *k == key(p)) {
                Some((_, count)) => *count += 1,
                None => counts.push((key(p), 1)),
            }
        }
        let common = counts.iter().max_by_key(|(_, count)| *count).map(|(k, _)| *k);
        let impurities =
            springs.clone().filter(|&p| Some(key(p)) != common).map(|p| p - rotors.start).collect();
        Ok(Self {
            title: title.into(),
            angles: theta[rotors.clone()].to_vec(),
            rotors,
            pivots,
            tips,
            stretch,
            impurities,
            arrows: Vec::new(),
            tensions: Vec::new(),
            stretch_scale: None,
        })
    }

    /// Whether every spring drawn is at rest (its stretch below the rounding of the spring
    /// lengths, drawn as zero): the drawing then has no colour scale to show.
    pub fn at_rest(&self) -> bool {
        self.stretch.iter().all(|&s| s == 0.0)
    }

    /// One stretch colour scale for all of `drawings` (their largest `|stretch|`), so that
    /// panels shown side by side compare by colour.
    pub fn share_stretch_scale(drawings: &mut [ChainDrawing]) {
        let largest = drawings.iter().flat_map(|d| &d.stretch).map(|s| s.abs()).fold(0.0, f64::max);
        for d in drawings {
            d.stretch_scale = (largest > 0.0).then_some(largest);
        }
    }

    /// With a mode `shape` (`δθ_i` of every rotor of the chain) drawn as the displacement of each
    /// tip, `r_i δθ_i` along its circle, scaled so that the largest arrow has length 1.
    pub fn with_mode(mut self, shape: &[f64]) -> Result<Self, DrawingError> {
        let n_drawn = self.rotors.len();
        if shape.len() < self.rotors.end {
            return Err(DrawingError::WrongLength {
                what: "mode",
                len: shape.len(),
                expected: self.rotors.end,
            });
        }
        let arrows: Vec<(f64, f64)> = (0..n_drawn)
            .map(|j| {
                let i = self.rotors.start + j;
                let (pivot, tip) = (self.pivots[j], self.tips[j]);
                // d(tip)/dθ: the arm turned a quarter towards +x for positive θ on every rotor.
                let (dx, dy) = (tip.0 - pivot.0, tip.1 - pivot.1);
                let tangent = if i.is_multiple_of(2) { (dy, -dx) } else { (-dy, dx) };
                (shape[i] * tangent.0, shape[i] * tangent.1)
            })
            .collect();
        let largest = arrows.iter().map(|v| v.0.hypot(v.1)).fold(0.0, f64::max);
        self.arrows = if largest > 0.0 {
            arrows.iter().map(|v| (v.0 / largest, v.1 / largest)).collect()
        } else {
            arrows
        };
        Ok(self)
    }

    /// With a tensional mode's amplitude on every spring of the chain (`tensions[p]`), drawn as
    /// bars whose thickness is `|t_p|`, the largest 1.
    pub fn with_tensions(mut self, tensions: &[f64]) -> Result<Self, DrawingError> {
        let springs = self.rotors.start..self.rotors.end - 1;
        if tensions.len() < springs.end {
            return Err(DrawingError::WrongLength {
                what: "tensions",
                len: tensions.len(),
                expected: springs.end,
            });
        }
        let largest = tensions[springs.clone()].iter().map(|t| t.abs()).fold(0.0, f64::max);
        self.tensions =
            tensions[springs].iter().map(|t| if largest > 0.0 { t.abs() / largest } else { 0.0 }).collect();
        Ok(self)
    }
}

/// `half` rotors either side of `centre`, inside a chain of `n`: the window of a long chain shown
/// around its defect.
pub fn window(centre: f64, half: usize, n: usize) -> Range<usize> {
    let c = centre.round().clamp(0.0, n.saturating_sub(1) as f64) as usize;
    c.saturating_sub(half)..(c + half + 1).min(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rotor_chain::{RuntimeChain, SpringNetwork};

    #[test]
    fn tips_follow_the_alternating_convention_and_springs_their_lengths() {
        let model = RuntimeChain::builder(4, 0.8, 1.0, 0.5).spring_rest_length(1, 2.0).build().unwrap();
        let theta = [0.5, 0.5, 0.5, 0.3];
        let d = ChainDrawing::new("t", &model, &theta, 0..10).unwrap();
        assert_eq!(d.rotors, 0..4);
        let (s, c) = 0.5f64.sin_cos();
        assert!((d.tips[0].0 - 0.8 * s).abs() < 1e-15 && (d.tips[0].1 - 0.8 * c).abs() < 1e-15);
        assert!((d.tips[1].0 - (1.0 + 0.8 * s)).abs() < 1e-15 && (d.tips[1].1 + 0.8 * c).abs() < 1e-15);
        // The tips' distance is the spring's length: spring 0 at rest (uniform state), spring 1
        // the impurity (rest length 2.0), spring 2 stretched or compressed by theta_3 = 0.3.
        for j in 0..3 {
            let (p, q) = (d.tips[j], d.tips[j + 1]);
            let l = (q.0 - p.0).hypot(q.1 - p.1);
            let expected = model.rest_length(j) + d.stretch[j];
            assert!((l - expected).abs() < 1e-12, "spring {j}: {l} vs {expected}");
        }
        assert_eq!(d.stretch[0], 0.0);
        assert_eq!(d.impurities, vec![1]);
        let err = ChainDrawing::new("t", &model, &theta[..3], 0..4).unwrap_err();
        assert!(matches!(err, DrawingError::WrongLength { len: 3, expected: 4, .. }));
        assert!(ChainDrawing::new("t", &model, &theta, 3..9).is_err());
    }

    #[test]
    fn drawings_know_when_every_spring_is_at_rest_and_can_share_one_scale() {
        let model = RuntimeChain::builder(4, 0.8, 1.0, 0.5).build().unwrap();
        let uniform = ChainDrawing::new("t", &model, &[0.5; 4], 0..4).unwrap();
        assert!(uniform.at_rest());
        let bent = ChainDrawing::new("t", &model, &[0.5, 0.5, 0.2, -0.4], 0..4).unwrap();
        assert!(!bent.at_rest());
        let largest = bent.stretch.iter().map(|s| s.abs()).fold(0.0, f64::max);
        let mut both = [uniform, bent];
        ChainDrawing::share_stretch_scale(&mut both);
        assert_eq!(both.map(|d| d.stretch_scale), [Some(largest); 2]);
        // Nothing stretched anywhere: no shared scale, each drawing says "at rest".
        let mut rest = [ChainDrawing::new("t", &model, &[0.5; 4], 0..4).unwrap()];
        ChainDrawing::share_stretch_scale(&mut rest);
        assert_eq!(rest[0].stretch_scale, None);
    }

    #[test]
    fn mode_arrows_are_tangent_to_the_tip_circles() {
        let model = RuntimeChain::builder(3, 0.8, 1.0, 0.5).build().unwrap();
        let theta = [0.5, -0.2, 0.1];
        let shape = [1.0, 0.5, -0.25];
        let d = ChainDrawing::new("t", &model, &theta, 0..3).unwrap().with_mode(&shape).unwrap();
        // Finite difference of each tip in its own angle.
        let h = 1e-7;
        for i in 0..3 {
            let mut moved = theta;
            moved[i] += h * shape[i];
            let e = ChainDrawing::new("t", &model, &moved, 0..3).unwrap();
            let fd = ((e.tips[i].0 - d.tips[i].0) / h, (e.tips[i].1 - d.tips[i].1) / h);
            // Arrows are scaled so that the largest (rotor 0: 0.8 * 1.0) has length 1.
            let scale = 0.8;
            assert!((d.arrows[i].0 * scale - fd.0).abs() < 1e-6, "{i}: {:?} vs {fd:?}", d.arrows[i]);
            assert!((d.arrows[i].1 * scale - fd.1).abs() < 1e-6, "{i}: {:?} vs {fd:?}", d.arrows[i]);
        }
        assert_eq!(window(7.4, 3, 60), 4..11);
        assert_eq!(window(1.0, 3, 60), 0..5);
        assert_eq!(window(59.0, 3, 60), 56..60);
    }
}
