//! Arguments in, arrays out: the checks every method shares.

use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayLike1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_chain::statics::walls::Charge;

use crate::errors::value_error;

/// A float64 array-like of length `n` (angles, velocities), copied, every entry finite.
pub fn vector(x: PyArrayLike1<'_, f64, AllowTypeChange>, what: &str, n: usize) -> PyResult<Vec<f64>> {
    let values = x.as_array().to_vec();
    if values.len() != n {
        return Err(value_error(format!("{what} has {} entries, the chain has {n} rotors", values.len())));
    }
    if let Some((index, value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(value_error(format!("{what}[{index}] = {value} is not finite")));
    }
    Ok(values)
}

/// The entry `key` of `dict` (a record, a pickled object's state), or a `ValueError` that names
/// `what` and the key.
pub fn item<'py, T: FromPyObjectOwned<'py>>(dict: &Bound<'py, PyDict>, what: &str, key: &str) -> PyResult<T> {
    match dict.get_item(key)? {
        Some(v) => v.extract::<T>().map_err(|e| {
            let e: PyErr = e.into();
            value_error(format!("{what} field `{key}`: {e}"))
        }),
        None => Err(value_error(format!("the {what} has no field `{key}`"))),
    }
}

/// A 1-D float64 numpy array that owns `values`.
pub fn array(py: Python<'_>, values: Vec<f64>) -> Py<PyArray1<f64>> {
    values.into_pyarray(py).unbind()
}

/// A `rows x cols` float64 numpy array from row-major `values`.
pub fn matrix(py: Python<'_>, rows: usize, cols: usize, values: Vec<f64>) -> Py<PyArray2<f64>> {
    // The length is rows * cols by construction at every call site.
    let a = Array2::from_shape_vec((rows, cols), values).unwrap_or_else(|_| Array2::zeros((rows, cols)));
    a.into_pyarray(py).unbind()
}

/// Rows of equal length as a 2-D array (`rows x cols`; `0 x cols` when empty).
pub fn rows(py: Python<'_>, rows: &[Vec<f64>], cols: usize) -> Py<PyArray2<f64>> {
    matrix(py, rows.len(), cols, rows.iter().flatten().copied().collect())
}

/// One of `choices` (case-sensitive), or a `ValueError` naming them.
pub fn choice<T: Copy>(what: &str, value: &str, choices: &[(&str, T)]) -> PyResult<T> {
    choices.iter().find(|(name, _)| *name == value).map(|(_, t)| *t).ok_or_else(|| {
        let names: Vec<String> = choices.iter().map(|(n, _)| format!("'{n}'")).collect();
        value_error(format!("{what} must be one of {}, got '{value}'", names.join(", ")))
    })
}

pub fn charge(defect: &str) -> PyResult<Charge> {
    choice("defect", defect, &[("kink", Charge::Kink), ("antikink", Charge::Antikink)])
}

pub fn charge_name(charge: Charge) -> &'static str {
    match charge {
        Charge::Kink => "kink",
        Charge::Antikink => "antikink",
    }
}
