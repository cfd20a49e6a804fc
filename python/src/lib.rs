//! `rotor_chain._native`: the compiled half of the Python package `rotor_chain`.
//!
//! Every class and function wraps the Rust library one to one: `chain::Chain` is a
//! `RuntimeChain` (the same builder and its checks), its statics and dynamics methods call
//! `rotor_chain::statics` and `rotor_chain::dynamics`, and `sweep` exposes chain-sweep's
//! `PhaseDiagram::compute_point` and results files, which `rotor_chain/sweep.py` drives on one
//! machine or on a Dask cluster. Arrays cross as numpy `float64` arrays (copied in, so a computation
//! never reads memory Python may change); every computation longer than a few microseconds runs
//! with the GIL released (`Python::detach`). Errors become the exceptions of
//! `rotor_chain/errors.py` (`errors`).
#![deny(missing_docs)]

use pyo3::prelude::*;

mod args;
mod chain;
mod dynamics;
mod errors;
mod network;
mod network_model;
mod pickle;
mod statics;
mod sweep;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // numpy's C API (its capsule and version check) loaded now, while the module is imported:
    // rust-numpy loads it lazily by running Python code, and a Ctrl-C pending when a method made
    // the interpreter's first array was raised inside that code, which rust-numpy turned into a
    // panic ("Failed to access NumPy array API capsule") instead of a KeyboardInterrupt.
    numpy::PyArray1::<f64>::zeros(m.py(), 0, false);
    m.add_class::<chain::Chain>()?;
    m.add_class::<chain::Continuum>()?;
    m.add_class::<network::Network>()?;
    m.add_class::<network_model::NetworkModel>()?;
    m.add_class::<network_model::NetworkModes>()?;
    m.add_class::<network_model::NetworkRun>()?;
    m.add_class::<statics::Antikink>()?;
    m.add_class::<statics::PeierlsNabarro>()?;
    m.add_class::<statics::Modes>()?;
    m.add_class::<statics::Counting>()?;
    m.add_class::<dynamics::Launch>()?;
    m.add_class::<dynamics::Run>()?;
    m.add_class::<dynamics::Scattering>()?;
    m.add_class::<sweep::PhaseDiagram>()?;
    m.add_class::<sweep::ResultsFile>()?;
    m.add_function(wrap_pyfunction!(statics::domain_walls, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::axis, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::read_points, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::check_grid, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::check_threads, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::max_threads_py, m)?)?;
    m.add_function(wrap_pyfunction!(pickle::restore, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULT_ENERGY_TOLERANCE", chain_sweep::scattering::DEFAULT_ENERGY_TOLERANCE)?;
    m.add("MAX_AXIS_COUNT", chain_sweep::grid::MAX_AXIS_COUNT)?;
    m.add("MAX_GRID_POINTS", chain_sweep::grid::MAX_GRID_POINTS)?;
    Ok(())
}
