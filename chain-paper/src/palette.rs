//! One colour per quantity, for every figure: a [`Series`](crate::Series) names the quantity it
//! shows and the renderer looks its colour up here, so the same quantity has the same colour in
//! every panel of every figure. Where a caption of the paper names a colour, it is the paper's:
//!
//! | quantity | colour | the paper |
//! | --- | --- | --- |
//! | [`Rotor`](Quantity::Rotor): rotor angles `θ_i`, rotor points of a cobweb plot, rotor tips | blue | "rotors (blue)", "the blue point (θ_i, θ_i) represents rotor i" (Figs. 1, `fig:kcobweb`) |
//! | [`Spring`](Quantity::Spring): spring points, stretch, the cobweb staircase | red | "springs (red dashed lines)", "the red point … represents the spring", "red dashed lines … the iterative process" |
//! | [`Mode`](Quantity::Mode): mode components, tensional-mode amplitudes | green | "the green arrows depict the mode component" (`fig:mode-config`), "green bars" (`fig:longbar`) |
//! | [`Impurity`](Quantity::Impurity): the impurity spring | purple | green in Fig. 1 (not reproduced); green is kept for modes, which share `fig:longbar` with the impurity |
//! | [`Constraint`](Quantity::Constraint): the rest-length curve of a cobweb plot | black | "the black curve is the constraint equation" |
//! | [`Diagonal`](Quantity::Diagonal), [`Reference`](Quantity::Reference): `θ_{i+1} = θ_i`, levels such as `±θ̄` | grey | "the gray diagonal line" |
//! | [`Lattice`](Quantity::Lattice): a number of the discrete model against a theory | black | "the discrete model (black circles)" (`fig:logvpn-theta`) |
//! | [`Continuum`](Quantity::Continuum): the continuum theory | orange | a "solid line"; not black, so it stays apart from the black lattice points |
//! | [`Fit`](Quantity::Fit): a fitted line | grey (dashed) | "the dashed line (fit to simulation)" |
//! | [`Kink`](Quantity::Kink), [`Antikink`](Quantity::Antikink): a quantity of the kink beside the antikink's | blue, orange | solid and dashed (`fig:ketimeplot`) |
//! | [`Configuration`](Quantity::Configuration): the configuration drawn below an orbit | red | "the big red dots" (`fig:orbit`) |
//! | outcomes, regions | see [`Quantity::colour`] | "the gray area … is energetically forbidden" (`fig:ELdiagram`) |
//!
//! Continuous maps: a signed quantity (values of both signs) gets the diverging map [`diverging`]
//! centred on zero, otherwise the sequential viridis map ([`sequential`]). The renderer decides
//! from the values, never per figure.

use plotters::style::RGBColor;
use plotters::style::colors::colormaps::{ColorMap as _, ViridisRGB};

/// What a series, a category or a drawn part of the chain shows; its colour is
/// [`Quantity::colour`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Quantity {
    /// Rotor angles `θ_i`, the rotor points `(θ_i, θ_i)` of a cobweb plot, rotor tips.
    Rotor,
    /// Spring quantities: the spring points `(θ_i, θ_{i+1})`, stretch `l_p − l̄`, the staircase.
    Spring,
    /// Mode components (arrows, profiles) and tensional-mode amplitudes.
    Mode,
    /// The impurity spring.
    Impurity,
    /// The rest-length curve `θ_{i+1} = F(θ_i)` of a cobweb plot.
    Constraint,
    /// The diagonal `θ_{i+1} = θ_i` of a cobweb plot.
    Diagonal,
    /// A reference level or line: `±θ̄`, `l0 = l_critical`.
    Reference,
    /// A number of the discrete model compared with a theory (energies, barriers, frequencies).
    Lattice,
    /// The continuum theory.
    Continuum,
    /// A fitted line.
    Fit,
    /// Points below the rounding level of their computation.
    Rounding,
    /// A quantity of the kink, beside the antikink's.
    Kink,
    /// A quantity of the antikink, beside the kink's.
    Antikink,
    /// A potential energy curve.
    Potential,
    /// A bound orbit (energy below the separatrix's).
    Bound,
    /// An unbound orbit (energy above the separatrix's).
    Unbound,
    /// A trajectory in configuration space.
    Trajectory,
    /// The configuration drawn beside an orbit (its starting point).
    Configuration,
    /// Scattering outcomes (Sec. VI).
    Transmitted,
    /// Outcome: reflected.
    Reflected,
    /// Outcome: trapped.
    Trapped,
    /// Outcome: split.
    Split,
    /// Outcome: annihilated.
    Annihilated,
    /// Outcome: disintegrated.
    Disintegrated,
    /// Outcome: pair creation.
    PairCreation,
    /// Outcome: undecided.
    Undecided,
    /// A scattering point whose outcome is not the impurity's alone (the integrators disagree,
    /// or a wall from a free end reached the impurity first): grey, drawn hatched
    /// ([`hatched`]) so it never reads as an outcome.
    Unresolved,
    /// A sweep point that failed (energy budget, unreadable walls): shown, never hidden.
    Failed,
    /// Member `index` of a family of `of` curves that differ in one parameter (e.g. the launch
    /// speed): shades of the sequential map, in the parameter's order.
    Parameter {
        /// Which member, from 0.
        index: usize,
        /// How many members.
        of: usize,
    },
    /// Regions of the `(E, l0)` diagram (Sec. VII-B).
    Annulus,
    /// Region of the disk orbits.
    Disk,
    /// Region no orbit reaches.
    Forbidden,
}

const BLUE: RGBColor = RGBColor(31, 119, 180);
const ORANGE: RGBColor = RGBColor(230, 120, 0);
const GREEN: RGBColor = RGBColor(30, 150, 30);
const RED: RGBColor = RGBColor(214, 39, 40);
const PURPLE: RGBColor = RGBColor(148, 80, 189);
const BROWN: RGBColor = RGBColor(140, 86, 75);
const BLACK: RGBColor = RGBColor(0, 0, 0);
const GREY: RGBColor = RGBColor(127, 127, 127);
const LIGHT_GREY: RGBColor = RGBColor(185, 185, 185);

impl Quantity {
    /// Its colour, the same in every figure.
    pub fn colour(self) -> RGBColor {
        match self {
            Quantity::Rotor | Quantity::Kink | Quantity::Bound | Quantity::Trajectory => BLUE,
            Quantity::Spring | Quantity::Configuration => RED,
            Quantity::Mode => GREEN,
            Quantity::Impurity => PURPLE,
            Quantity::Constraint | Quantity::Lattice => BLACK,
            Quantity::Diagonal | Quantity::Reference | Quantity::Fit => GREY,
            Quantity::Rounding => LIGHT_GREY,
            Quantity::Continuum | Quantity::Antikink | Quantity::Unbound => ORANGE,
            Quantity::Potential => BROWN,
            Quantity::Transmitted => RGBColor(120, 190, 120),
            Quantity::Reflected => RGBColor(110, 160, 215),
            Quantity::Trapped => RGBColor(225, 110, 100),
            Quantity::Split => RGBColor(180, 140, 210),
            Quantity::Annihilated => RGBColor(150, 150, 150),
            Quantity::Disintegrated => RGBColor(230, 190, 90),
            Quantity::PairCreation => RGBColor(240, 170, 210),
            Quantity::Undecided => RGBColor(205, 205, 205),
            Quantity::Unresolved => RGBColor(200, 200, 200),
            Quantity::Failed => BLACK,
            // Up to 0.85 of viridis: its last shades are too light for a line on white.
            Quantity::Parameter { index, of } => {
                sequential(0.85 * index as f64 / of.saturating_sub(1).max(1) as f64)
            }
            Quantity::Annulus => RGBColor(160, 200, 230),
            Quantity::Disk => RGBColor(250, 200, 140),
            Quantity::Forbidden => RGBColor(170, 170, 170),
        }
    }

    /// The quantity a category of a categorical map stands for, by its name: the scattering
    /// outcomes' names (`Outcome::name`), the `(E, l0)` regions' and the network diagram's
    /// `gapless` and `Weyl points`. `None` for other names.
    pub fn of_category(name: &str) -> Option<Quantity> {
        Some(match name {
            "transmitted" => Quantity::Transmitted,
            "reflected" => Quantity::Reflected,
            "trapped" => Quantity::Trapped,
            "split" => Quantity::Split,
            "annihilated" => Quantity::Annihilated,
            "disintegrated" => Quantity::Disintegrated,
            "pair-creation" => Quantity::PairCreation,
            "undecided" => Quantity::Undecided,
            "unresolved" => Quantity::Unresolved,
            "failed" => Quantity::Failed,
            "annulus" => Quantity::Annulus,
            "disk" => Quantity::Disk,
            "forbidden" => Quantity::Forbidden,
            // The network polarization diagram: where the gap closes.
            "gapless" => Quantity::Forbidden,
            "Weyl points" => Quantity::Undecided,
            _ => return None,
        })
    }
}

/// Colours for categories that name no quantity, in order (light, so text and lines on them
/// stay readable).
pub const OTHER_CATEGORIES: [RGBColor; 6] = [
    RGBColor(160, 200, 230),
    RGBColor(250, 200, 140),
    RGBColor(170, 220, 160),
    RGBColor(240, 160, 160),
    RGBColor(200, 180, 225),
    RGBColor(210, 190, 170),
];

/// The hatching's colour of a [`hatched`] category.
pub const HATCH: RGBColor = RGBColor(60, 60, 60);

/// Whether cells (and legend swatches) of the category named `name` are drawn hatched over their
/// colour: the unresolved scattering points, so that no reader takes them for an outcome.
pub fn hatched(name: &str) -> bool {
    Quantity::of_category(name) == Some(Quantity::Unresolved)
}

/// The colour of category `index` named `name`: its quantity's, or the next of
/// [`OTHER_CATEGORIES`].
pub fn category_colour(name: &str, index: usize) -> RGBColor {
    Quantity::of_category(name).map_or(OTHER_CATEGORIES[index % OTHER_CATEGORIES.len()], Quantity::colour)
}

/// Cells and springs without a value (NaN, or not a category).
pub const MISSING: RGBColor = RGBColor(220, 220, 220);

/// The sequential map (viridis) at `t` in `[0, 1]` (clamped).
pub fn sequential(t: f64) -> RGBColor {
    ViridisRGB.get_color_normalized(t.clamp(0.0, 1.0), 0.0, 1.0)
}

/// The diverging map at `t` in `[-1, 1]` (clamped): blue below zero, white at zero, red above,
/// through the nine colours of ColorBrewer's RdBu (reversed), linearly interpolated.
pub fn diverging(t: f64) -> RGBColor {
    const STOPS: [(u8, u8, u8); 9] = [
        (33, 102, 172),
        (67, 147, 195),
        (146, 197, 222),
        (209, 229, 240),
        (247, 247, 247),
        (253, 219, 199),
        (244, 165, 130),
        (214, 96, 77),
        (178, 24, 43),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(-1.0, 1.0) };
    let at = (t + 1.0) / 2.0 * (STOPS.len() - 1) as f64;
    let i = (at.floor() as usize).min(STOPS.len() - 2);
    let f = at - i as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_papers_colours() {
        assert_eq!(Quantity::Rotor.colour(), BLUE);
        assert_eq!(Quantity::Spring.colour(), RED);
        assert_eq!(Quantity::Mode.colour(), GREEN);
        assert_eq!(Quantity::Constraint.colour(), BLACK);
        assert_eq!(Quantity::Diagonal.colour(), GREY);
        assert_eq!(category_colour("forbidden", 2), Quantity::Forbidden.colour());
        assert_eq!(category_colour("something else", 1), OTHER_CATEGORIES[1]);
    }

    #[test]
    fn the_diverging_map_is_white_at_zero_and_symmetric_in_lightness() {
        assert_eq!(diverging(0.0), RGBColor(247, 247, 247));
        assert_eq!(diverging(-1.0), RGBColor(33, 102, 172));
        assert_eq!(diverging(1.0), RGBColor(178, 24, 43));
        assert_eq!(diverging(7.0), diverging(1.0));
        let lightness = |c: RGBColor| u32::from(c.0) + u32::from(c.1) + u32::from(c.2);
        for t in [0.1, 0.3, 0.6, 0.9] {
            let (below, above) = (lightness(diverging(-t)), lightness(diverging(t)));
            assert!(below.abs_diff(above) < 90, "{t}: {below} vs {above}");
            assert!(lightness(diverging(t)) < lightness(diverging(0.0)));
        }
    }
}
