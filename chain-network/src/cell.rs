//! The unit cell of a periodic network: crate `chain-cell` re-exported unchanged (the typed
//! [`Cell`], the TOML cell format, the builder, the one validation, the ready cells), plus
//! [`ready::by_name`] for the command line and Python, whose error is this crate's
//! [`NetworkError`](crate::NetworkError).

pub use chain_cell::{
    Bond, BondDescription, BondLaw, Cell, CellBuilder, CellDescription, MAX_CELL_BONDS, MAX_CELL_NODES, Node,
    NodeDescription, NodeKind, Polynomial, PolynomialProblem,
};

/// Ready cells of the standard lattices (`chain_cell::ready`), and a ready cell by name.
pub mod ready {
    pub use chain_cell::ready::*;

    use super::Cell;

    /// A ready cell by name, for the command line and Python: `square`, `kagome`,
    /// `deformed-kagome` (parameters `x1 x2 x3 z`), `twisted-kagome` (`alpha`), `rotor-chain`
    /// (`a r theta_bar`), `paper-chain-right`, `paper-chain-left`.
    pub fn by_name(name: &str, parameters: &[f64]) -> Result<Cell, crate::NetworkError> {
        let want = |n: usize| -> Result<(), crate::NetworkError> {
            if parameters.len() == n {
                Ok(())
            } else {
                Err(crate::NetworkError::Argument {
                    what: "ready cell",
                    problem: format!("`{name}` takes {n} parameters, found {}", parameters.len()),
                })
            }
        };
        let cell_error = |e: crate::CellError| crate::NetworkError::Argument {
            what: "ready cell",
            problem: e.to_string(),
        };
        let p = parameters;
        match name {
            "square" => want(0).map(|_| square()),
            "kagome" => want(0).map(|_| kagome()),
            "deformed-kagome" => {
                want(4)?;
                deformed_kagome(p[0], p[1], p[2], p[3]).map_err(cell_error)
            }
            "twisted-kagome" => {
                want(1)?;
                twisted_kagome(p[0]).map_err(cell_error)
            }
            "rotor-chain" => {
                want(3)?;
                rotor_chain(p[0], p[1], p[2]).map_err(cell_error)
            }
            "paper-chain-right" => want(0).map(|_| paper_chain(Lean::Right)),
            "paper-chain-left" => want(0).map(|_| paper_chain(Lean::Left)),
            other => Err(crate::NetworkError::Argument {
                what: "ready cell",
                problem: format!(
                    "unknown cell `{other}` (square, kagome, deformed-kagome, twisted-kagome, rotor-chain, paper-chain-right, paper-chain-left)"
                ),
            }),
        }
    }
}
