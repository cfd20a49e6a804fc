//! The error family of the cell description: [`CellError`] for a cell that cannot be read or is
//! not valid (every variant names the key, and the line when the cell came from a file).

use std::fmt;

/// Where in a cell description a problem sits: the key path (`bond[2].to`) and, for a cell read
/// from text, the 1-based line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The key path, e.g. `lattice`, `node[1].position`, `bond[0].cell`.
    pub key: String,
    /// The 1-based line of the file, when the cell was read from text.
    pub line: Option<usize>,
}

impl Location {
    /// A location without a line (a cell built in Rust or Python).
    pub fn key(key: impl Into<String>) -> Self {
        Self { key: key.into(), line: None }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: `{}`", self.key),
            None => write!(f, "`{}`", self.key),
        }
    }
}

/// A cell that cannot be read or is not valid. Every variant carries the [`Location`] of the
/// offending key; the `Display` text starts with it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CellError {
    /// The text is not TOML, or a value has the wrong type, or a key is unknown or missing
    /// (as the TOML reader reports it).
    #[error("{}{message}", line.map(|l| format!("line {l}, column {}: ", column.unwrap_or(1))).unwrap_or_default())]
    Syntax {
        /// 1-based line of the problem, when known.
        line: Option<usize>,
        /// 1-based column.
        column: Option<usize>,
        /// The reader's message (names the key for missing and unknown keys).
        message: String,
    },
    /// A required key is missing.
    #[error("{at}: missing (required {why})")]
    Missing {
        /// Where the key should be.
        at: Location,
        /// Why it is required.
        why: &'static str,
    },
    /// A key that this kind of node does not take.
    #[error("{at}: not a key of a {kind} node")]
    NotForKind {
        /// The key.
        at: Location,
        /// The node's kind.
        kind: &'static str,
    },
    /// A number that is NaN or infinite.
    #[error("{at}: not a finite number ({value})")]
    NotFinite {
        /// The key.
        at: Location,
        /// The value.
        value: f64,
    },
    /// A number outside its allowed range.
    #[error("{at}: {value} is out of range ({rule})")]
    OutOfRange {
        /// The key.
        at: Location,
        /// The value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// A list of the wrong length (lattice rows, positions, cell offsets).
    #[error("{at}: expected {expected} entries, found {found} ({why})")]
    Length {
        /// The key.
        at: Location,
        /// Entries expected.
        expected: usize,
        /// Entries found.
        found: usize,
        /// What fixes the length.
        why: &'static str,
    },
    /// `dimension` is not 1 or 2.
    #[error("{at}: dimension must be 1 or 2, found {found}")]
    Dimension {
        /// The key.
        at: Location,
        /// The value found.
        found: i64,
    },
    /// Lattice vectors that do not span the dimension (zero or parallel).
    #[error(
        "{at}: the lattice vectors are degenerate (|det| = {det:e}, relative {relative:e}): they span no {dimension}-dimensional cell"
    )]
    DegenerateLattice {
        /// The key.
        at: Location,
        /// The absolute determinant (1D: the vector's length).
        det: f64,
        /// The determinant over the product of the vectors' lengths.
        relative: f64,
        /// The dimension.
        dimension: usize,
    },
    /// The cell has no node.
    #[error("{at}: the cell has no node (an empty cell)")]
    Empty {
        /// The key.
        at: Location,
    },
    /// More nodes or bonds than a unit cell may have ([`crate::MAX_CELL_NODES`],
    /// [`crate::MAX_CELL_BONDS`]): the Bloch analyses hold dense bonds x degrees-of-freedom
    /// matrices at every wave vector.
    #[error(
        "{at}: the cell has {found} {what}, more than the limit of {max} (the Bloch analyses hold dense \
         bonds x degrees-of-freedom matrices at every wave vector; a patch of many cells is built with `--cells`)"
    )]
    TooLarge {
        /// The key (`node` or `bond`).
        at: Location,
        /// `nodes` or `bonds`.
        what: &'static str,
        /// How many the cell has.
        found: usize,
        /// The limit.
        max: usize,
    },
    /// `kind` is neither `joint` nor `rotor`.
    #[error("{at}: unknown kind `{found}` (expected `joint` or `rotor`)")]
    UnknownKind {
        /// The key.
        at: Location,
        /// The value found.
        found: String,
    },
    /// A node name that is empty or used twice.
    #[error("{at}: node name `{name}` {problem}")]
    BadName {
        /// The key.
        at: Location,
        /// The name.
        name: String,
        /// `is empty` or `is already the name of node[i]`.
        problem: String,
    },
    /// A bond end that names no node.
    #[error("{at}: no node is named `{name}`{}", suggestion.as_ref().map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default())]
    UnknownNode {
        /// The key (`bond[i].from` or `.to`).
        at: Location,
        /// The name.
        name: String,
        /// The closest node name, if one is close.
        suggestion: Option<String>,
    },
    /// A bond whose two ends coincide in the reference configuration: its length is not above
    /// `RELATIVE_TOLERANCE` (1e-9) times the cell's length scale, the longer lattice vector.
    #[error(
        "{at}: bond {bond} has length {length:e}, not above 1e-9 times the cell's length scale {scale:e} \
         (the longer lattice vector): its ends coincide"
    )]
    ZeroLengthBond {
        /// The bond's key.
        at: Location,
        /// The bond's index.
        bond: usize,
        /// Its length.
        length: f64,
        /// The cell's length scale: the longer lattice vector's length.
        scale: f64,
    },
    /// A `law` that is not a law of the cell format.
    #[error("{at}: {problem}")]
    Law {
        /// The `law` key.
        at: Location,
        /// What is wrong, and what the key accepts.
        problem: String,
    },
    /// Two bonds joining the same two node instances.
    #[error("{at}: bond {second} joins the same two nodes as bond {first} (a duplicate bond)")]
    DuplicateBond {
        /// The second bond's key.
        at: Location,
        /// The first bond.
        first: usize,
        /// The duplicate.
        second: usize,
    },
}

impl CellError {
    /// The location of the problem (`None` for a syntax error, which has only a line).
    pub fn location(&self) -> Option<&Location> {
        match self {
            CellError::Syntax { .. } => None,
            CellError::Missing { at, .. }
            | CellError::NotForKind { at, .. }
            | CellError::NotFinite { at, .. }
            | CellError::OutOfRange { at, .. }
            | CellError::Length { at, .. }
            | CellError::Dimension { at, .. }
            | CellError::DegenerateLattice { at, .. }
            | CellError::Empty { at }
            | CellError::TooLarge { at, .. }
            | CellError::UnknownKind { at, .. }
            | CellError::BadName { at, .. }
            | CellError::UnknownNode { at, .. }
            | CellError::Law { at, .. }
            | CellError::ZeroLengthBond { at, .. }
            | CellError::DuplicateBond { at, .. } => Some(at),
        }
    }

    /// The 1-based line of the problem, for a cell read from text.
    pub fn line(&self) -> Option<usize> {
        match self {
            CellError::Syntax { line, .. } => *line,
            other => other.location().and_then(|at| at.line),
        }
    }
}
