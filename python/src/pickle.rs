//! Pickling of the result classes, so that multiprocessing and Dask can send them between
//! processes. A result pickles as `_native._restore(class name, {field: value})`: every field as
//! Python holds it (numpy arrays, floats, strings, nested results), so the copy is exact; its
//! class rebuilds itself from that dict (`Pickle::from_state`). `Chain` and `PhaseDiagram`
//! pickle through their constructors' arguments instead (`__getnewargs_ex__`), which checks them
//! again; a `ResultsFile` holds an open, locked file and does not pickle.

use pyo3::PyClass;
use pyo3::prelude::*;
use pyo3::pyclass_init::PyClassInitializer;
use pyo3::types::PyDict;

use crate::chain::Continuum;
use crate::dynamics::{Launch, Run, Scattering};
use crate::errors::value_error;
use crate::statics::{Antikink, Counting, Modes, PeierlsNabarro};

/// A class that pickles as its state dict (under its name, `PyClass::NAME`, which `_restore`
/// dispatches on).
pub trait Pickle: PyClass + Into<PyClassInitializer<Self>> {
    /// Every field, by name.
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>>;

    /// The object again from its `state`.
    fn from_state(state: &Bound<'_, PyDict>) -> PyResult<Self>;
}

/// `Pickle` for a class whose fields all cross to Python and back as they are: its name and
/// every field.
macro_rules! pickle_fields {
    ($class:ident { $($field:ident),+ $(,)? }) => {
        impl $crate::pickle::Pickle for $class {
            fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
                let state = pyo3::types::PyDict::new(py);
                $(state.set_item(stringify!($field), &self.$field)?;)+
                Ok(state)
            }

            fn from_state(state: &Bound<'_, pyo3::types::PyDict>) -> PyResult<Self> {
                let what = concat!("pickled ", stringify!($class), " state");
                Ok(Self { $($field: $crate::args::item(state, what, stringify!($field))?,)+ })
            }
        }
    };
}
pub(crate) use pickle_fields;

/// What `__reduce__` gives pickle: `(_restore, (name, state))`.
pub type Reduced<'py> = (Bound<'py, PyAny>, (&'static str, Bound<'py, PyDict>));

/// `__reduce__` of a `Pickle` class.
pub fn reduce<'py, T: Pickle>(slf: &Bound<'py, T>) -> PyResult<Reduced<'py>> {
    let py = slf.py();
    let restore = py.import("rotor_chain._native")?.getattr("_restore")?;
    Ok((restore, (<T as PyClass>::NAME, slf.borrow().state(py)?)))
}

fn restore_as<T: Pickle>(state: &Bound<'_, PyDict>) -> PyResult<Py<PyAny>> {
    Ok(Py::new(state.py(), T::from_state(state)?)?.into_any())
}

/// A pickled result again: the object of class ``name`` with the fields of ``state`` (what the
/// classes' ``__reduce__`` gives pickle).
#[pyfunction(name = "_restore")]
pub fn restore(name: &str, state: &Bound<'_, PyDict>) -> PyResult<Py<PyAny>> {
    match name {
        <Antikink as PyClass>::NAME => restore_as::<Antikink>(state),
        <PeierlsNabarro as PyClass>::NAME => restore_as::<PeierlsNabarro>(state),
        <Modes as PyClass>::NAME => restore_as::<Modes>(state),
        <Counting as PyClass>::NAME => restore_as::<Counting>(state),
        <Continuum as PyClass>::NAME => restore_as::<Continuum>(state),
        <Launch as PyClass>::NAME => restore_as::<Launch>(state),
        <Run as PyClass>::NAME => restore_as::<Run>(state),
        <Scattering as PyClass>::NAME => restore_as::<Scattering>(state),
        _ => Err(value_error(format!("cannot unpickle: rotor_chain._native has no result class `{name}`"))),
    }
}
