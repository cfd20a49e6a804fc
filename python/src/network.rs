//! `Network`: a periodic spring and rotor network (`rotor_chain::network`, issue 33) from a cell
//! file, TOML text, keyword arguments or a ready lattice; counts, null spaces, Bloch matrices,
//! windings, strips, bands and Guest modes, with numpy arrays out. Errors: `CellError` (the
//! cell, naming its key and line) and `NetworkError` (an analysis), with their numbers.

use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use rotor_chain::network::cell::{BondDescription, NodeDescription, ready};
use rotor_chain::network::counts::{Counts, Method, counts_with, null_spaces_with};
use rotor_chain::network::faer::Mat;
use rotor_chain::network::patch::{Boundary, Patch};
use rotor_chain::network::strip::{Strip, strip_modes};
use rotor_chain::network::winding::{WindingOptions, winding};
use rotor_chain::network::{Cell, CellDescription, bloch, c64, guest};

use crate::dynamics::Interrupt;
use crate::errors::{self, value_error};

/// Two real arrays.
type ArrayPair<'py, A, B> = PyResult<(Bound<'py, A>, Bound<'py, B>)>;

/// A periodic network's unit cell, validated.
#[pyclass(module = "rotor_chain._native", frozen)]
pub struct Network {
    cell: Cell,
}

fn real_matrix<'py>(py: Python<'py>, m: &Mat<f64>) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((m.nrows(), m.ncols()), |(i, j)| m[(i, j)]).into_pyarray(py)
}

fn complex_matrix<'py>(py: Python<'py>, m: &Mat<c64>) -> Bound<'py, PyArray2<numpy::Complex64>> {
    Array2::from_shape_fn((m.nrows(), m.ncols()), |(i, j)| numpy::Complex64::new(m[(i, j)].re, m[(i, j)].im))
        .into_pyarray(py)
}

pub(crate) fn boundary_of(name: &str) -> PyResult<Boundary> {
    match name {
        "periodic" => Ok(Boundary::Periodic),
        "free" => Ok(Boundary::Free),
        other => Err(value_error(format!("boundary must be 'periodic' or 'free', got '{other}'"))),
    }
}

/// `cells` as `[N1, N2]`: an int (one dimension) or a pair.
pub(crate) fn cells_of(cell: &Cell, cells: &Bound<'_, PyAny>) -> PyResult<[usize; 2]> {
    if let Ok(n) = cells.extract::<usize>() {
        return if cell.dimension() == 1 {
            Ok([n, 1])
        } else {
            Err(value_error("cells: a pair (N1, N2) for a two-dimensional cell"))
        };
    }
    let pair: Vec<usize> = cells
        .extract()
        .map_err(|_| value_error("cells: an int N or a pair (N1, N2) of non-negative ints"))?;
    match (cell.dimension(), pair.as_slice()) {
        (1, [n]) => Ok([*n, 1]),
        (2, [a, b]) => Ok([*a, *b]),
        _ => Err(value_error(format!(
            "cells: {} numbers for a {}-dimensional cell",
            pair.len(),
            cell.dimension()
        ))),
    }
}

fn counts_dict<'py>(py: Python<'py>, c: &Counts) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("dof", c.dof)?;
    d.set_item("bonds", c.bonds)?;
    d.set_item("rank", c.rank)?;
    d.set_item("zero_modes", c.zero_modes)?;
    d.set_item("self_stresses", c.self_stresses)?;
    d.set_item("largest_singular_value", c.largest_singular_value)?;
    d.set_item("smallest_kept", c.smallest_kept)?;
    d.set_item("largest_dropped", c.largest_dropped)?;
    d.set_item(
        "method",
        match c.method {
            Method::BlochBlocks { .. } => "bloch-blocks",
            Method::DenseSvd => "dense-svd",
            Method::Sparse => "sparse",
        },
    )?;
    Ok(d)
}

/// Read one table (a dict) of the keyword form: every key known, values of the right type.
fn table<'py>(value: &Bound<'py, PyAny>, what: &str, keys: &[&str]) -> PyResult<Bound<'py, PyDict>> {
    let d = value.cast::<PyDict>().map_err(|_| value_error(format!("{what} must be a dict")))?.clone();
    for key in d.keys() {
        let key: String = key.extract().map_err(|_| value_error(format!("{what}: keys are strings")))?;
        if !keys.contains(&key.as_str()) {
            return Err(value_error(format!(
                "{what}: unknown key '{key}' (expected one of {})",
                keys.join(", ")
            )));
        }
    }
    Ok(d)
}

fn get<'py, T: FromPyObjectOwned<'py>>(d: &Bound<'py, PyDict>, what: &str, key: &str) -> PyResult<Option<T>> {
    match d.get_item(key)? {
        None => Ok(None),
        Some(v) => {
            v.extract::<T>().map(Some).map_err(|_| value_error(format!("{what}['{key}'] has the wrong type")))
        }
    }
}

use pyo3::conversion::FromPyObjectOwned;

impl Network {
    /// The validated cell.
    pub(crate) fn cell(&self) -> &Cell {
        &self.cell
    }
}

#[pymethods]
impl Network {
    /// A cell from keyword arguments: the keys of the cell file. `nodes` is a list of dicts with
    /// `name`, `kind` and `position` (joint) or `pivot`, `length`, `angle` (rotor); `bonds` a list
    /// of dicts with `from`, `to` and optionally `cell`, `k`, `rest_length`.
    #[new]
    #[pyo3(signature = (*, dimension, lattice, nodes, bonds = None))]
    fn new(
        py: Python<'_>,
        dimension: i64,
        lattice: Vec<Vec<f64>>,
        nodes: &Bound<'_, PyList>,
        bonds: Option<&Bound<'_, PyList>>,
    ) -> PyResult<Self> {
        let mut desc =
            CellDescription { dimension: Some(dimension), lattice: Some(lattice), ..Default::default() };
        for (i, n) in nodes.iter().enumerate() {
            let what = format!("nodes[{i}]");
            let d = table(&n, &what, &["name", "kind", "position", "pivot", "length", "angle"])?;
            desc.nodes.push(NodeDescription {
                name: get(&d, &what, "name")?,
                kind: get(&d, &what, "kind")?,
                position: get(&d, &what, "position")?,
                pivot: get(&d, &what, "pivot")?,
                length: get(&d, &what, "length")?,
                angle: get(&d, &what, "angle")?,
            });
        }
        if let Some(bonds) = bonds {
            for (i, b) in bonds.iter().enumerate() {
                let what = format!("bonds[{i}]");
                let d = table(&b, &what, &["from", "to", "cell", "k", "rest_length"])?;
                desc.bonds.push(BondDescription {
                    from: get(&d, &what, "from")?,
                    to: get(&d, &what, "to")?,
                    cell: get(&d, &what, "cell")?,
                    k: get(&d, &what, "k")?,
                    rest_length: get(&d, &what, "rest_length")?,
                });
            }
        }
        let cell = desc.build().map_err(|e| errors::cell(py, &e))?;
        Ok(Network { cell })
    }

    /// A cell from the TOML text of the cell format.
    #[staticmethod]
    fn from_string(py: Python<'_>, text: &str) -> PyResult<Self> {
        Cell::from_toml_str(text).map(|cell| Network { cell }).map_err(|e| errors::cell(py, &e))
    }

    /// A cell from a cell file.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        Cell::from_toml_file(&path).map(|cell| Network { cell }).map_err(|e| errors::cell(py, &e))
    }

    /// A ready cell: `square`, `kagome`, `deformed-kagome` (x1, x2, x3, z), `twisted-kagome`
    /// (alpha), `rotor-chain` (a, r, theta_bar), `paper-chain-right`, `paper-chain-left`.
    #[staticmethod]
    #[pyo3(signature = (name, *parameters))]
    fn ready(py: Python<'_>, name: &str, parameters: Vec<f64>) -> PyResult<Self> {
        ready::by_name(name, &parameters).map(|cell| Network { cell }).map_err(|e| errors::network(py, &e))
    }

    /// The cell in the TOML cell format (reads back exactly).
    fn to_toml(&self) -> String {
        self.cell.to_toml()
    }

    /// 1 or 2.
    #[getter]
    fn dimension(&self) -> usize {
        self.cell.dimension()
    }

    /// Degrees of freedom per cell.
    #[getter]
    fn dof(&self) -> usize {
        self.cell.dof()
    }

    /// Bonds per cell.
    #[getter]
    fn bond_count(&self) -> usize {
        self.cell.bonds().len()
    }

    /// The lattice vectors as rows.
    #[getter]
    fn lattice<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let l = self.cell.lattice();
        Array2::from_shape_fn((l.len(), 2), |(i, j)| l[i][j]).into_pyarray(py)
    }

    /// Zero modes and states of self-stress of a patch of `cells` (an int in one dimension, a
    /// pair in two), `boundary` 'periodic' or 'free': a dict with `zero_modes`, `self_stresses`,
    /// `dof`, `bonds`, `rank`, the singular values at the threshold, `method`.
    #[pyo3(signature = (cells, boundary = "periodic"))]
    fn counts<'py>(
        &self,
        py: Python<'py>,
        cells: &Bound<'py, PyAny>,
        boundary: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let n = cells_of(&self.cell, cells)?;
        let boundary = boundary_of(boundary)?;
        let cell = &self.cell;
        let mut interrupt = Interrupt::default();
        let c = py.detach(|| {
            Patch::new(cell, n, boundary).and_then(|p| counts_with(&p, &mut || interrupt.pending()))
        });
        interrupt.raise()?;
        counts_dict(py, &c.map_err(|e| errors::network(py, &e))?)
    }

    /// `(zero_modes, self_stresses)` of a patch as orthonormal columns (`dof x N0`,
    /// `bonds x Nss`).
    #[pyo3(signature = (cells, boundary = "periodic"))]
    fn null_spaces<'py>(
        &self,
        py: Python<'py>,
        cells: &Bound<'py, PyAny>,
        boundary: &str,
    ) -> ArrayPair<'py, PyArray2<f64>, PyArray2<f64>> {
        let n = cells_of(&self.cell, cells)?;
        let boundary = boundary_of(boundary)?;
        let cell = &self.cell;
        let mut interrupt = Interrupt::default();
        let ns = py.detach(|| {
            Patch::new(cell, n, boundary).and_then(|p| null_spaces_with(&p, &mut || interrupt.pending()))
        });
        interrupt.raise()?;
        let ns = ns.map_err(|e| errors::network(py, &e))?;
        Ok((real_matrix(py, &ns.zero_modes), real_matrix(py, &ns.self_stresses)))
    }

    /// The dense compatibility matrix of a patch (bonds x dof).
    #[pyo3(signature = (cells, boundary = "free"))]
    fn compatibility<'py>(
        &self,
        py: Python<'py>,
        cells: &Bound<'py, PyAny>,
        boundary: &str,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let n = cells_of(&self.cell, cells)?;
        let boundary = boundary_of(boundary)?;
        let m = Patch::new(&self.cell, n, boundary)
            .and_then(|p| p.compatibility_matrix())
            .map_err(|e| errors::network(py, &e))?;
        Ok(real_matrix(py, &m))
    }

    /// The Bloch compatibility matrix Q(k) at the phases `theta = (k.a1, k.a2)` (complex, bonds x
    /// dof; the phase `exp(i k.R)` on each bond's `to` end).
    fn bloch<'py>(
        &self,
        py: Python<'py>,
        theta: Vec<f64>,
    ) -> PyResult<Bound<'py, PyArray2<numpy::Complex64>>> {
        let t = phases(&self.cell, &theta)?;
        Ok(complex_matrix(py, &bloch::compatibility(&self.cell, t)))
    }

    /// The frequencies at the phases `theta` (unit masses), ascending.
    fn frequencies<'py>(&self, py: Python<'py>, theta: Vec<f64>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let t = phases(&self.cell, &theta)?;
        let w = bloch::frequencies(&self.cell, t).map_err(|e| errors::network(py, &e))?;
        Ok(Array1::from(w).into_pyarray(py))
    }

    /// Bands along `path` (`G-X-M-G`, or reduced coordinates `f1,f2-...`): `(distance,
    /// frequencies)` with `frequencies[s, n]`.
    #[pyo3(signature = (path = "G-X-M-G", samples = 60))]
    fn bands<'py>(
        &self,
        py: Python<'py>,
        path: &str,
        samples: usize,
    ) -> ArrayPair<'py, PyArray1<f64>, PyArray2<f64>> {
        let cell = &self.cell;
        let b = py
            .detach(|| bloch::parse_path(cell, path).and_then(|p| bloch::bands(cell, &p, samples)))
            .map_err(|e| errors::network(py, &e))?;
        let m = b.frequencies.first().map_or(0, Vec::len);
        let f = Array2::from_shape_fn((b.frequencies.len(), m), |(s, n)| b.frequencies[s][n]);
        Ok((Array1::from(b.distance).into_pyarray(py), f.into_pyarray(py)))
    }

    /// The winding numbers and polarization: a dict with `winding` (one int per lattice
    /// direction), `polarization` (R_T in lattice coordinates), `dipole` (r0), `closest_approach`.
    fn winding<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let cell = &self.cell;
        let w =
            py.detach(|| winding(cell, &WindingOptions::default())).map_err(|e| errors::network(py, &e))?;
        let d = PyDict::new(py);
        d.set_item("winding", w.winding)?;
        d.set_item("polarization", Array1::from(w.polarization).into_pyarray(py))?;
        d.set_item("dipole", Array1::from(w.dipole).into_pyarray(py))?;
        d.set_item("closest_approach", w.closest_approach)?;
        Ok(d)
    }

    /// The zero modes of a strip periodic along lattice vector `along` (1 or 2), `cells` wide,
    /// at `q = k.a_along` (default 2.0 rad, `strip::DEFAULT_Q`): a dict with `edge_zero_modes` (`low`, `high`), `zero_modes`,
    /// `bulk_zero_modes`, `centres`, `modes` (complex columns), `predicted` (or None).
    #[pyo3(signature = (along, cells, q = 2.0))]
    fn strip<'py>(
        &self,
        py: Python<'py>,
        along: usize,
        cells: usize,
        q: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        if along == 0 || along > self.cell.dimension() {
            return Err(value_error(format!(
                "along = {along}: the cell has {} lattice vector(s)",
                self.cell.dimension()
            )));
        }
        let strip = Strip { along: along - 1, cells, q };
        let cell = &self.cell;
        let m = py.detach(|| strip_modes(cell, &strip)).map_err(|e| errors::network(py, &e))?;
        let d = PyDict::new(py);
        let edges = PyDict::new(py);
        edges.set_item("low", m.low)?;
        edges.set_item("high", m.high)?;
        d.set_item("edge_zero_modes", edges)?;
        d.set_item("zero_modes", m.zero_modes)?;
        d.set_item("self_stresses", m.self_stresses)?;
        d.set_item("bulk_zero_modes", m.bulk)?;
        d.set_item("centres", Array1::from(m.centres.clone()).into_pyarray(py))?;
        d.set_item("modes", complex_matrix(py, &m.modes))?;
        let predicted = m.predicted.map(|(l, h)| {
            let p = PyDict::new(py);
            let _ = p.set_item("low", l);
            let _ = p.set_item("high", h);
            p
        });
        d.set_item("predicted", predicted)?;
        Ok(d)
    }

    /// `(count, strains)`: the Guest modes, strains as an array `(count, 2, 2)` (orthonormal,
    /// symmetric).
    fn guest_modes<'py>(&self, py: Python<'py>) -> PyResult<(usize, Bound<'py, PyArray3<f64>>)> {
        let g = guest::guest_modes(&self.cell).map_err(|e| errors::network(py, &e))?;
        let s = Array3::from_shape_fn((g.count, 2, 2), |(m, i, j)| g.strains[m][i][j]);
        Ok((g.count, s.into_pyarray(py)))
    }

    fn __repr__(&self) -> String {
        format!(
            "Network(dimension={}, nodes={}, dof={}, bonds={})",
            self.cell.dimension(),
            self.cell.nodes().len(),
            self.cell.dof(),
            self.cell.bonds().len()
        )
    }

    /// Pickles as its TOML text.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let ctor = py.get_type::<Network>().getattr("from_string")?;
        let args = PyTuple::new(py, [slf.get().cell.to_toml()])?;
        Ok((ctor, args))
    }
}

fn phases(cell: &Cell, theta: &[f64]) -> PyResult<[f64; 2]> {
    if theta.len() != cell.dimension() || theta.iter().any(|t| !t.is_finite()) {
        return Err(value_error(format!(
            "theta: {} finite phases k.a_i for a {}-dimensional cell",
            cell.dimension(),
            cell.dimension()
        )));
    }
    Ok([theta[0], theta.get(1).copied().unwrap_or(0.0)])
}
