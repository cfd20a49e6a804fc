//! The zero-energy kink at any centre (paper Sec. II), and the mechanism it moves along.
//!
//! Forward iteration of the branch map from the left end cannot centre a kink deep in a long
//! chain: near `+theta_bar` the map's slope is `F' = (a + 2 r sin theta_bar)/(a - 2 r sin theta_bar)`
//! (15.2 at `theta_bar = 0.58`), so a kink 30 sites in needs a starting offset of `F'^-30`, far
//! below double precision. Instead the kink is built **outward from its centre**: the forward map
//! to the right and the inverse map to the left. Each runs into the *attracting* fixed point of its
//! direction (`-theta_bar` to the right, `+theta_bar` to the left), so rounding errors shrink at
//! every step, whatever the length of the chain.
//!
//! The centre is the wall position of Appendix C: for an integer centre `c` rotor `c` stands
//! vertical; for `c = i + f` the angles of rotors `i` and `i + 1` are chosen on the spring-`i`
//! constraint so that the interpolated sign change sits at `i + f`.

use alloc::vec;
use alloc::vec::Vec;

use super::error::StaticsError;
use crate::embedded::{self, EmbeddedError};
use crate::model::ChainModel;

/// The zero-energy kink of `model` centred at `centre` (in rotor indices, `0 <= centre <= n - 1`).
/// At `centre = 0` or `n - 1` the wall sits on the end rotor, which stands vertical: the wall has
/// reached the end, the chain is one domain, and [`domain_walls`](super::walls::domain_walls)
/// finds no wall (it reports sign changes between two leaning rotors). A centre inside the chain
/// whose profile shows no wall (a `theta_bar` so small that the wall is far wider than the chain
/// and its angles round to zero) is [`StaticsError::NoWall`].
///
/// **How exactly the wall sits at `centre`.** The branch solve gives each angle to a rounding of
/// the O(1) geometry, an absolute `eps` (2.2e-16), not `eps` relative to the angle; near the core
/// of a wide wall neighbouring angles differ by about `2 r theta_bar^2 / a`, so the interpolated
/// sign change is placed to about `eps a / (r theta_bar^2)` sites: below 1e-12 from
/// `theta_bar = 0.01` up, 3e-8 at 1e-4 and 2e-4 at 1e-6 (`r = 0.8 a`). The kink still has zero
/// energy to rounding; only its label `centre` is that uncertain (a test checks the bound for
/// `r / a` from 0.3 to 1.5).
///
/// # Example
///
/// ```
/// use rotor_chain::RuntimeChain;
/// use rotor_chain::statics::kink::kink;
/// use rotor_chain::statics::walls::domain_walls;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build()?; // n, r, k, theta_bar
/// let theta = kink(&chain, 41.25)?;                               // any centre, fractional too
/// assert!((domain_walls(&theta)[0].position - 41.25).abs() < 1e-9);
/// assert!(rotor_chain::ChainModel::energy(&chain, &theta) < 1e-16); // zero energy, in M a^2/t^2
/// # Ok(())
/// # }
/// ```
pub fn kink<M: ChainModel + ?Sized>(model: &M, centre: f64) -> Result<Vec<f64>, StaticsError> {
    wall_profile(model, centre, Wall::Kink)
}

/// The paper's first approximation of the antikink (Sec. II, Fig. `fig:akcobweb`): the kink's
/// spring points reflected across the diagonal of the cobweb plot. Every spring `p` is at rest,
/// but with its two angles swapped: `(theta_{p+1}, theta_p)` lies on spring `p`'s flipper branch.
/// It runs from `-theta_bar` to `+theta_bar`, centred at `centre`, and is not an equilibrium: the
/// antikink analysis relaxes it.
pub fn reflected_kink<M: ChainModel + ?Sized>(model: &M, centre: f64) -> Result<Vec<f64>, StaticsError> {
    wall_profile(model, centre, Wall::Reflected)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Wall {
    Kink,
    Reflected,
}

/// Builds a wall outward from its centre: the no-alloc construction of `crate::embedded`
/// ([`embedded::kink_into`], [`embedded::reflected_kink_into`]) into a `Vec`.
fn wall_profile<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    wall: Wall,
) -> Result<Vec<f64>, StaticsError> {
    let n = model.rotor_count();
    let max = (n - 1) as f64;
    if !(centre.is_finite() && (0.0..=max).contains(&centre)) {
        return Err(StaticsError::CentreOutOfRange { centre, n, max });
    }
    let mut theta = vec![0.0; n];
    let built = match wall {
        Wall::Kink => embedded::kink_into(model, centre, &mut theta),
        Wall::Reflected => embedded::reflected_kink_into(model, centre, &mut theta),
    };
    match built {
        Ok(()) => Ok(theta),
        Err(EmbeddedError::Branch(e)) => Err(StaticsError::Branch(e)),
        Err(EmbeddedError::NoWall { expected, centre, kinks, antikinks }) => {
            Err(StaticsError::NoWall { expected, centre, theta_bar: model.theta_bar(), kinks, antikinks })
        }
        // The centre and the length are checked above; a chain of one rotor has no wall.
        Err(_) => Err(StaticsError::CentreOutOfRange { centre, n, max }),
    }
}

/// The most steps [`mechanism_path`] takes.
pub const MAX_PATH_STEPS: usize = 1_000_000;

/// The mechanism: kinks at `steps + 1` evenly spaced centres from `from` to `to`, each a
/// zero-energy configuration (paper Sec. II: the kink can sit anywhere along the chain).
///
/// # Errors
/// A centre outside the chain or not finite, more than [`MAX_PATH_STEPS`] steps, or a failed
/// branch solve.
pub fn mechanism_path<M: ChainModel + ?Sized>(
    model: &M,
    from: f64,
    to: f64,
    steps: usize,
) -> Result<Vec<(f64, Vec<f64>)>, StaticsError> {
    super::validate::at_most("steps", steps, MAX_PATH_STEPS)?;
    (0..=steps)
        .map(|s| {
            let c = if steps == 0 { from } else { from + (to - from) * s as f64 / steps as f64 };
            kink(model, c).map(|theta| (c, theta))
        })
        .collect()
}
