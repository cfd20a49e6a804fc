//! Compile errors of `#[rotor_network]`, one module per case (one compilation for the group);
//! each error at its key. The cell files are in `tests/ui/cells/`, read relative to this
//! package's folder (`ROTOR_NETWORK_MANIFEST_DIR`, set by `tests/ui.rs`).

mod missing_file {
    #[rotor_chain::rotor_network(cell = "tests/ui/cells/missing.toml", cells = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod bad_cell_line {
    // The cell's validation names the line and the key.
    #[rotor_chain::rotor_network(cell = "tests/ui/cells/unknown_node.toml", cells = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod not_toml {
    #[rotor_chain::rotor_network(cell = "tests/ui/cells/not_toml.toml", cells = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod unknown_key {
    #[rotor_chain::rotor_network(cell = "tests/ui/cells/square.toml", cels = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod cell_and_ready {
    #[rotor_chain::rotor_network(cell = "tests/ui/cells/square.toml", ready = "kagome", cells = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod no_cell {
    #[rotor_chain::rotor_network(cells = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod unknown_ready_cell {
    #[rotor_chain::rotor_network(ready = "kagom", cells = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod ready_cell_with_parameters {
    #[rotor_chain::rotor_network(ready = "twisted-kagome", cells = (4, 4), boundary = "free")]
    pub struct Network;

    pub fn main() {}
}

mod bad_cells {
    // One entry for a two-dimensional cell.
    #[rotor_chain::rotor_network(ready = "kagome", cells = 4, boundary = "free")]
    pub struct OneEntry;

    // No cells along a direction.
    #[rotor_chain::rotor_network(ready = "kagome", cells = (0, 4), boundary = "free")]
    pub struct Zero;

    // Too few for a periodic direction.
    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 2), boundary = "periodic")]
    pub struct Periodic;

    // A second direction for a one-dimensional cell.
    #[rotor_chain::rotor_network(ready = "paper-chain-right", cells = (20, 2), boundary = "free")]
    pub struct OneDimensional;

    // More than a patch may have (2^25 bonds).
    #[rotor_chain::rotor_network(ready = "kagome", cells = (100000, 100000), boundary = "free")]
    pub struct TooLarge;

    // Not a size at all.
    #[rotor_chain::rotor_network(ready = "kagome", cells = "4x4", boundary = "free")]
    pub struct Text;

    pub fn main() {}
}

mod bad_boundary {
    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = "fre")]
    pub struct Typo;

    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = free)]
    pub struct NotAString;

    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4))]
    pub struct Missing;

    pub fn main() {}
}

mod bad_law {
    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = "free", law = k * (l - x0).powi(2))]
    pub struct UnknownSymbol;

    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = "free", law = k * (l - l0).tanh())]
    pub struct UnknownMethod;

    pub fn main() {}
}

mod bad_overrides {
    // A 4 x 4 free kagome patch has 66 bonds, 0 to 65 (tests/network_attribute.rs declares 65).
    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = "free", spring(66, k = 2.0))]
    pub struct NoSuchSpring;

    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = "free", mass = -1.0, spring(3, k = 0.0))]
    pub struct NotPositive;

    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = "free", spring(3, stiffness = 2.0))]
    pub struct UnknownArgument;

    pub fn main() {}
}

mod generic_struct {
    #[rotor_chain::rotor_network(ready = "kagome", cells = (4, 4), boundary = "free")]
    pub struct Network<T>(T);

    pub fn main() {}
}

mod node_overrides {
    // A node's cell outside the patch, a node the cell does not have (by index and by name), a
    // mass that is not positive, an override without a mass, an unknown key in it.
    #[rotor_chain::rotor_network(
        cell = "tests/ui/cells/square.toml",
        cells = (4, 3),
        boundary = "free",
        node((4, 0), 0, mass = 2.0),
        node((1, 1), 3, mass = 2.0),
        node((1, 1), "bb", mass = 2.0),
        node((1, 1), 0, mass = -1.0),
        node((1, 1), 0),
        node((1, 1), 0, mas = 2.0),
        node(2, 0, mass = 1.0)
    )]
    pub struct Network;

    pub fn main() {}
}

// The stubs keep the struct usable: no "trait not implemented" errors beside the attribute's.
fn uses(network: &missing_file::Network) -> f64 {
    use rotor_chain::Potential;
    network.energy(&network.reference())
}

fn main() {
    let _ = uses;
}
