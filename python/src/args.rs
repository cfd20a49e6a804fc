//! Arguments in, arrays out: the checks every method shares.

use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayLike1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_chain::statics::walls::Charge;

use rotor_chain::geometry::{CountText, IndexKind, MAX_ROTORS, check_index};

use crate::errors::{self, value_error};

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
/// numpy does not read as real numbers (`None`, strings, complex values, which numpy would cast
/// to their real part) is a `TypeError` that names the argument.
fn floats(x: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    let not_real = |got: String| {
        pyo3::exceptions::PyTypeError::new_err(format!("{what} must be an array of real numbers, got {got}"))
    };
    // The common case, a float64 vector, is read directly, without the numpy calls below.
    if let Ok(array) = x.cast::<PyArray1<f64>>()
        && let Ok(values) = numpy::PyArrayMethods::try_readonly(array)
    {
        return copied(values.as_array(), what);
    }
    if x.is_none() {
        return Err(not_real("None".to_owned()));
    }
    // numpy's reading of `x` (free for a numpy array): its kind of values and its shape.
    let array = match x.py().import("numpy")?.getattr("asarray")?.call1((x,)) {
        Ok(array) => array,
        Err(e) => return Err(not_real(format!("{} ({e})", type_name(x)))),
    };
    let dtype = array.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "b" | "i" | "u" | "f") {
        return Err(not_real(format!("{} of dtype {}", type_name(x), dtype.str()?)));
    }
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    if shape.len() != 1 {
        let shape: Vec<String> = shape.iter().map(usize::to_string).collect();
        return Err(value_error(format!(
            "{what} must be a one-dimensional array, got one of shape ({})",
            shape.join(", ")
        )));
    }
    match array.extract::<PyArrayLike1<'_, f64, AllowTypeChange>>() {
        Ok(array) => copied(array.as_array(), what),
        Err(e) => Err(not_real(format!("{} ({})", type_name(x), e))),
    }
}

/// A copy of an argument's values, made fallibly: memory that cannot be allocated (a large
/// array under a memory limit) is Python's `MemoryError` with the bytes asked for, never an
/// abort of the interpreter.
fn copied(values: numpy::ndarray::ArrayView1<'_, f64>, what: &str) -> PyResult<Vec<f64>> {
    let mut copy = Vec::new();
    copy.try_reserve_exact(values.len()).map_err(|_| {
        let bytes = values.len().saturating_mul(size_of::<f64>());
        pyo3::exceptions::PyMemoryError::new_err(format!("cannot allocate {bytes} bytes to copy {what}"))
    })?;
    copy.extend(values.iter().copied());
    Ok(copy)
}

/// The name of `x`'s type, for messages (`str`, `NoneType`, `ndarray`).
fn type_name(x: &Bound<'_, PyAny>) -> String {
    x.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "object".to_owned())
}

/// `x` for a message: its repr (cut at 60 characters) and its type, `'0.58' (str)`.
pub fn described(x: &Bound<'_, PyAny>) -> String {
    let repr = x.repr().map(|r| r.to_string()).unwrap_or_default();
    let repr = match repr.char_indices().nth(60) {
        Some((cut, _)) => format!("{}...", &repr[..cut]),
        None => repr,
    };
    format!("{repr} ({})", type_name(x))
}

/// A real-number argument as Python gave it: the value, or the type that is not one, kept so
/// that [`Real::get`] raises a `TypeError` that names the argument (pyo3's own conversion says
/// only `must be real number, not str`).
#[derive(Clone)]
pub struct Real(Result<f64, String>);

impl Real {
    /// A default value.
    pub const fn of(value: f64) -> Self {
        Self(Ok(value))
    }

    /// The value, or the `TypeError` of argument `what`.
    pub fn get(self, what: &str) -> PyResult<f64> {
        self.0.map_err(|got| {
            pyo3::exceptions::PyTypeError::new_err(format!("`{what}` must be a real number, got {got}"))
        })
    }
    /// [`Real::get`] of an optional argument (`None`: not given).
    pub fn optional(x: Option<Self>, what: &str) -> PyResult<Option<f64>> {
        x.map(|x| x.get(what)).transpose()
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Real {
    type Error = PyErr;
    fn extract(x: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        Ok(Self(x.extract::<f64>().map_err(|_| described(&x))))
    }
}

/// A Python int (or an object with `__index__`, such as numpy's integers), however large.
pub enum Int {
    /// An `i64` holds it.
    Fits(i64),
    /// Above `i64::MAX` (`10**20`).
    Above,
    /// Below `i64::MIN`.
    Below,
}

/// `x` as an [`Int`], so that an int beyond `i64` gets the documented error rather than
/// Python's `OverflowError`; what is not an int is Python's own `TypeError`.
pub fn int(x: &Bound<'_, PyAny>) -> PyResult<Int> {
    match x.extract::<i64>() {
        Ok(i) => Ok(Int::Fits(i)),
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(x.py()) => {
            Ok(if x.lt(0)? { Int::Below } else { Int::Above })
        }
        Err(e) => Err(e),
    }
}

/// A rotor count `n`, for the Rust checks to judge (`TooFewRotors` below 2, `TooManyRotors`
/// past `MAX_ROTORS`); an int no `usize` holds gets the same error here, with its own number.
/// A bool (`True` is an int to Python) or a value that is not an int (`60.0`, `"60"`) is a
/// `TypeError` that names `n`.
pub fn rotor_count(n: &Bound<'_, PyAny>) -> PyResult<usize> {
    let whole = if n.is_instance_of::<pyo3::types::PyBool>() { None } else { int(n).ok() };
    let Some(whole) = whole else {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "`n` must be an int (a number of rotors), got {}",
            described(n)
        )));
    };
    let text = match whole {
        Int::Fits(i) => match usize::try_from(i) {
            Ok(count) => return Ok(count),
            Err(_) if i < 0 => CountText::TooFew(n),
            Err(_) => CountText::TooMany { n, max: MAX_ROTORS },
        },
        Int::Below => CountText::TooFew(n),
        Int::Above => CountText::TooMany { n, max: MAX_ROTORS },
    };
    Err(errors::unbounded(n.py(), text))
}

/// A rotor count as Python gave it (any int, however large, default arguments too), checked as
/// [`rotor_count`] checks it. The result is kept rather than raised, so that each caller raises
/// it in its own family: `ParameterError`, or `ConfigError` for a phase diagram's settings.
pub struct RotorCount(pub PyResult<usize>);

impl<'a, 'py> FromPyObject<'a, 'py> for RotorCount {
    type Error = PyErr;
    fn extract(n: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        Ok(Self(rotor_count(&n)))
    }
}

/// An upper bound on how many things to return (`modes(count=...)`): any int that is not
/// negative, however large (past the number there are, it means all of them).
pub struct AtMost(pub usize);

impl<'a, 'py> FromPyObject<'a, 'py> for AtMost {
    type Error = PyErr;
    fn extract(x: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        match int(&x)? {
            Int::Fits(i) if i >= 0 => Ok(Self(usize::try_from(i).unwrap_or(usize::MAX))),
            Int::Above => Ok(Self(usize::MAX)),
            Int::Fits(_) | Int::Below => Err(value_error(format!("a count must be >= 0, got {}", *x))),
        }
    }
}

/// A spring or rotor index that is not negative and fits a `usize`, else `IndexOutOfRange` with
/// Python's own int. The upper end is left to the caller: the constructor's overrides are
/// checked by the builder, after its checks of `n`; [`index`] checks it.
pub fn unsigned_index(x: &Bound<'_, PyAny>, kind: IndexKind, count: usize) -> PyResult<usize> {
    if let Int::Fits(i) = int(x)?
        && let Ok(i) = usize::try_from(i)
    {
        return Ok(i);
    }
    Err(errors::unbounded(x.py(), CountText::OutOfRange { kind, index: x, count }))
}

/// A spring or rotor index of a chain with `count` of them. Out of range either way (negative,
/// past the end, or beyond any machine integer), it is the builder's
/// `ParameterError::IndexOutOfRange`, whichever method was given it (the Rust methods that take an
/// index report one past the end in their own error families, `BranchError::NoSuchSpring` and
/// `DynamicsError::NoSuchSpring`).
pub fn index(x: &Bound<'_, PyAny>, kind: IndexKind, count: usize) -> PyResult<usize> {
    let i = unsigned_index(x, kind, count)?;
    check_index(kind, i, count).map_err(|e| errors::parameter(x.py(), &e))
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

/// A `rows x cols` numpy array (float64 for `f64`, int64 for `i64`) from row-major `values`.
pub fn matrix<T: numpy::Element + Clone + Default>(
    py: Python<'_>,
    rows: usize,
    cols: usize,
    values: Vec<T>,
) -> Py<PyArray2<T>> {
    // The length is rows * cols by construction at every call site.
    let a = Array2::from_shape_vec((rows, cols), values)
        .unwrap_or_else(|_| Array2::from_elem((rows, cols), T::default()));
    a.into_pyarray(py).unbind()
}

/// Rows of equal length as a 2-D array (`rows x cols`; `0 x cols` when empty), for a result
/// sized by the input (modes, frames): its copy allocated fallibly, a `MemoryError` with the
/// bytes asked for instead of an abort.
pub fn try_rows(
    py: Python<'_>,
    rows: &[Vec<f64>],
    cols: usize,
    what: &'static str,
) -> PyResult<Py<PyArray2<f64>>> {
    let mut flat =
        rotor_chain::allocation::try_vec(rows.len().saturating_mul(cols), what).map_err(memory_error)?;
    flat.extend(rows.iter().flatten().copied());
    Ok(matrix(py, rows.len(), cols, flat))
}

/// Python's `MemoryError` for an allocation that failed: `cannot allocate N bytes for <what>`.
pub fn memory_error(e: rotor_chain::allocation::AllocationError) -> PyErr {
    pyo3::exceptions::PyMemoryError::new_err(e.to_string())
}

/// One of `choices` (case-sensitive), or a `ValueError` naming them.
pub fn choice<T: Copy>(what: &str, value: &str, choices: &[(&str, T)]) -> PyResult<T> {
    choices.iter().find(|(name, _)| *name == value).map(|(_, t)| *t).ok_or_else(|| {
        let names: Vec<String> = choices.iter().map(|(n, _)| format!("'{n}'")).collect();
        value_error(format!("{what} must be one of {}, got '{value}'", names.join(", ")))
    })
}

/// The wall charge of a defect's name (`kink` or `antikink`, chain-sweep's `Defect`).
pub fn charge(defect: &str) -> PyResult<Charge> {
    use core::str::FromStr;
    chain_sweep::scattering::Defect::from_str(defect)
        .map(|d| d.charge())
        .map_err(|e| value_error(e.to_string()))
}
