//! The error family of the analyses: [`NetworkError`] for an analysis that cannot be carried out
//! (with the numbers that say why). A cell that cannot be read or is not valid is a [`CellError`]
//! (crate `chain-cell`, re-exported here).

pub use chain_cell::{CellError, Location};
use chain_core::validate::{InvalidOption, OptionError};

/// An analysis of a valid cell that cannot be carried out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum NetworkError {
    /// A patch or strip size that cannot be built.
    #[error("{what}: {found} cells along lattice vector {direction}; {rule}")]
    PatchSize {
        /// What was being built (`periodic patch`, `strip`).
        what: &'static str,
        /// 1-based lattice direction.
        direction: usize,
        /// The number of cells asked for.
        found: usize,
        /// The rule it breaks.
        rule: String,
    },
    /// A periodic patch on which a bond would join a node to itself or repeat another bond.
    #[error("periodic patch {cells:?}: bond {bond} {problem}; use more cells along that direction")]
    PeriodicImage {
        /// The patch size.
        cells: [usize; 2],
        /// The bond.
        bond: usize,
        /// What happens to it.
        problem: String,
    },
    /// A dense decomposition too large for this machine's memory.
    #[error("{what}: a dense {rows} x {cols} matrix exceeds the limit of {limit} entries")]
    TooLarge {
        /// What was asked.
        what: &'static str,
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// The limit on rows x cols.
        limit: usize,
    },
    /// A decomposition that did not converge.
    #[error("{what}: the {decomposition} did not converge ({rows} x {cols})")]
    NoConvergence {
        /// What was being computed.
        what: &'static str,
        /// Which decomposition.
        decomposition: &'static str,
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
    },
    /// The index theorem N0 - Nss = dof - bonds failed: a bookkeeping error.
    #[error(
        "index theorem violated: N0 - Nss = {zero_modes} - {self_stresses} but dof - bonds = {dof} - {bonds}"
    )]
    IndexTheorem {
        /// Zero modes counted.
        zero_modes: usize,
        /// States of self-stress counted.
        self_stresses: usize,
        /// Degrees of freedom.
        dof: usize,
        /// Bonds.
        bonds: usize,
    },
    /// The winding number needs a square compatibility matrix (bonds = degrees of freedom).
    #[error(
        "winding needs a square cell (bonds = degrees of freedom); this cell has {bonds} bonds and {dof} degrees of freedom"
    )]
    NotSquare {
        /// Bonds per cell.
        bonds: usize,
        /// Degrees of freedom per cell.
        dof: usize,
    },
    /// det Q(k) vanishes on every path tried along a reciprocal direction: no winding number.
    #[error("winding undefined along b{direction}: det Q(k) vanishes on every path tried ({reason})")]
    WindingUndefined {
        /// 1-based reciprocal direction.
        direction: usize,
        /// Why, with the numbers.
        reason: String,
    },
    /// det Q(k) winds differently on different paths along the same direction: zeros of det Q
    /// (Weyl points) lie between them.
    #[error(
        "winding undefined along b{direction}: {windings:?} on paths at transverse k.a = {transverse:?} (det Q(k) has point zeros, Weyl points, between them)"
    )]
    WeylPoints {
        /// 1-based reciprocal direction.
        direction: usize,
        /// The transverse coordinates k.a_j of the paths (radians).
        transverse: Vec<f64>,
        /// The winding on each.
        windings: Vec<i64>,
    },
    /// A field of an options struct ([`crate::winding::WindingOptions`], [`crate::strip::Strip`])
    /// outside its range ([`chain_core::Validate`]).
    #[error(transparent)]
    InvalidOption(#[from] InvalidOption),
    /// Memory for a patch or its model (sized by the patch's cells) that the allocator could not
    /// give: the bytes asked for and what they were for.
    #[error(transparent)]
    OutOfMemory(#[from] chain_core::allocation::AllocationError),
    /// A count on the sparse path ([`crate::counts`] of a large free patch) that failed or was
    /// stopped by its question (`LinalgError::Stopped` inside).
    #[error(transparent)]
    Statics(#[from] chain_core::statics::StaticsError),
    /// An argument out of its range (lattice direction, wave number, path).
    #[error("{what}: {problem}")]
    Argument {
        /// The argument.
        what: &'static str,
        /// What is wrong.
        problem: String,
    },
}

impl OptionError for NetworkError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            Self::InvalidOption(o) => Some(*o),
            _ => None,
        }
    }
}
