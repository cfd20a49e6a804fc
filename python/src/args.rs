//! Arguments in, arrays out: the checks every method shares.

use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayLike1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_chain::statics::walls::Charge;

use crate::errors::value_error;

/// A float64 array-like of length `n` (angles, velocities), copied, every entry finite.
pub fn vector(x: &Bound<'_, PyAny>, what: &str, n: usize) -> PyResult<Vec<f64>> {
    let values = floats(x, what)?;
    if values.len() != n {
        let len = rotor_chain::geometry::Counted(values.len(), "value");
        return Err(value_error(format!("{what} has {len}, the chain has {n} rotors")));
    }
    finite(values, what)
}

/// A one-dimensional float64 array-like of any length, copied, every entry finite.
pub fn finite_floats(x: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    finite(floats(x, what)?, what)
}

fn finite(values: Vec<f64>, what: &str) -> PyResult<Vec<f64>> {
    match values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((index, value)) => Err(value_error(format!("{what}[{index}] = {value} is not finite"))),
        None => Ok(values),
    }
}

/// A one-dimensional float64 array-like, copied (numpy converts lists and integer arrays). An
/// array of another dimension is a `ValueError` that gives its shape, like a wrong length; what
/// numpy cannot read as numbers at all stays a `TypeError` that names the argument.
fn floats(x: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    match x.extract::<PyArrayLike1<'_, f64, AllowTypeChange>>() {
        Ok(array) => Ok(array.as_array().to_vec()),
        Err(e) => {
            // numpy's reading of `x`: its shape, if its values are real numbers.
            let numbers = |array: Bound<'_, PyAny>| -> PyResult<Option<Vec<usize>>> {
                let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
                Ok(if "biuf".contains(kind.as_str()) {
                    Some(array.getattr("shape")?.extract()?)
                } else {
                    None
                })
            };
            let array = x.py().import("numpy")?.getattr("asarray")?.call1((x,));
            match array.and_then(numbers) {
                Ok(Some(shape)) if shape.len() != 1 => {
                    let shape: Vec<String> = shape.iter().map(usize::to_string).collect();
                    Err(value_error(format!(
                        "{what} must be a one-dimensional array, got one of shape ({})",
                        shape.join(", ")
                    )))
                }
                _ => Err(pyo3::exceptions::PyTypeError::new_err(format!("argument '{what}': {e}"))),
            }
        }
    }
}

/// A Python int (or an object with `__index__`, such as numpy's integers) as an `i64`: `None` for
/// an int beyond `i64` (`10**20`), so that callers can give the documented error rather than
/// Python's `OverflowError`; `TypeError` for anything else, as Python's own conversion gives.
pub fn int(x: &Bound<'_, PyAny>) -> PyResult<Option<i64>> {
    match x.extract::<i64>() {
        Ok(i) => Ok(Some(i)),
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(x.py()) => Ok(None),
        Err(e) => Err(e),
    }
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
