//! The sparse `P (A - sigma I) P^T = L B L^T` factorization of a symmetric matrix given by its
//! upper triangle, its inertia, and solves with it.
//!
//! `P` is an approximate minimum degree ordering (fill-reducing) composed with the Bunch-Kaufman
//! pivoting faer applies within each supernode; `B` is block diagonal with `1 x 1` and `2 x 2`
//! blocks (faer's supernodal intranode `LBL^T`, forced supernodal so that the pivoting is on).
//!
//! **Inertia (Sylvester's law).** `A - sigma I` and `B` are congruent, so they have the same
//! numbers of negative, zero and positive eigenvalues: the number of eigenvalues of `A` below
//! `sigma` is the number of negative eigenvalues of `B`, read block by block (a `2 x 2` block
//! `[[a, c], [c, b]]` with `ab - c^2 < 0` has one of each sign, otherwise both of the sign of
//! `a + b`). In floating point the factorization is exact for a nearby matrix
//! `A - sigma I + E`; every count here is therefore checked by the backward error `eta` of a solve
//! with the factors (`||b - (A - sigma I) x|| / (||A - sigma I|| ||x|| + ||b||)`, max norms), and
//! refused above [`MAX_BACKWARD_ERROR_FACTOR`]` n eps` ([`LinalgError::Unstable`]): within it the
//! count is exact for a matrix within about `eta ||A||` of `A - sigma I`, so only eigenvalues
//! closer than that to `sigma` can be counted on the wrong side.

use alloc::vec::Vec;

use dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::supernodal::SupernodalIntranodeLbltRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, IntranodeLbltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use super::Upper;
use crate::linalg::LinalgError;

/// The backward error a factorization may have, in units of `n eps` (see the module doc).
///
/// Why 64: a backward-stable `LBL^T` has `eta` of a few `eps` times a modest growth factor; `n eps`
/// is the classical worst-case bound of the triangular solves, and 64 gives it the same margin as
/// the statics' rounding tolerance (`statics::classify::ROUNDING_FACTOR`), so a factorization
/// accepted here miscounts no eigenvalue that the classification resolves.
pub const MAX_BACKWARD_ERROR_FACTOR: f64 = 64.0;

/// The most values the factor `L` may hold: 2^28 (2 GiB). A larger fill is a typed error
/// ([`LinalgError::TooLarge`]) before the numeric factorization allocates it.
pub const MAX_FACTOR_VALUES: usize = 1 << 28;

/// How many eigenvalues of `A - sigma I` are negative, zero and positive (counts of `B`'s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Inertia {
    pub negative: usize,
    pub zero: usize,
    pub positive: usize,
    /// The eigenvalue of `B` of least magnitude (a `1 x 1` pivot, or an eigenvalue of a `2 x 2`
    /// block) and its row in the factorization's order: how near `A - sigma I` is to singular.
    pub smallest: (usize, f64),
}

/// `A - sigma I = P^T L B L^T P` for a sparse symmetric `A`.
pub(crate) struct Lblt {
    n: usize,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    subdiag: Vec<f64>,
    forward: Vec<usize>,
    inverse: Vec<usize>,
    /// `||A - sigma I||_inf`.
    norm: f64,
    /// `B`'s inertia, counted once after the factorization.
    inertia: Option<Inertia>,
    /// The diagonal of `A - sigma I` when it is a diagonal matrix (faer's simplicial form).
    diagonal: Vec<f64>,
}

/// `A - sigma I` as a lower triangle by columns (the transpose of the upper triangle by rows), a
/// diagonal entry present in every column.
struct Shifted {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
}

fn shifted(a: &Upper<'_>, sigma: f64) -> Result<Shifted, LinalgError> {
    let n = a.n;
    let mut col_ptr = try_vec(n + 1)?;
    let mut row_idx = try_vec(a.columns.len() + n)?;
    let mut values = try_vec(a.columns.len() + n)?;
    col_ptr.push(0);
    for i in 0..n {
        let row = a.row_starts[i]..a.row_starts[i + 1];
        let (columns, entries) = (&a.columns[row.clone()], &a.values[row]);
        if columns.first() != Some(&i) {
            row_idx.push(i);
            values.push(-sigma);
        }
        for (&j, &v) in columns.iter().zip(entries) {
            row_idx.push(j);
            values.push(if j == i { v - sigma } else { v });
        }
        col_ptr.push(row_idx.len());
    }
    Ok(Shifted { col_ptr, row_idx, values })
}

/// A vector of `len` capacity, or [`LinalgError::OutOfMemory`] (the crate's one fallible
/// allocation, [`crate::allocation::try_vec`]).
pub(crate) fn try_vec<T>(len: usize) -> Result<Vec<T>, LinalgError> {
    Ok(crate::allocation::try_vec(len, "the sparse factorization's arrays")?)
}

fn buffer(req: StackReq) -> Result<MemBuffer, LinalgError> {
    MemBuffer::try_new(req).map_err(|_| LinalgError::OutOfMemory {
        bytes: req.size_bytes(),
        what: "the sparse factorization's workspace",
    })
}

impl Lblt {
    /// Factors `A - sigma I` and checks the factorization's backward error.
    ///
    /// # Errors
    /// A fill beyond [`MAX_FACTOR_VALUES`] or an allocation that fails, or a backward error above
    /// [`MAX_BACKWARD_ERROR_FACTOR`]` n eps`.
    pub(crate) fn new(a: &Upper<'_>, sigma: f64) -> Result<Self, LinalgError> {
        let n = a.n;
        let s = shifted(a, sigma)?;
        let structure = SymbolicSparseColMatRef::new_checked(n, n, &s.col_ptr, None, &s.row_idx);
        let params = CholeskySymbolicParams {
            // Supernodal: the intranode Bunch-Kaufman pivoting exists only there (the simplicial
            // variant is an unpivoted LDL^T).
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(structure, Side::Lower, SymmetricOrdering::Amd, params)
            .map_err(|_| LinalgError::OutOfMemory {
                bytes: s.values.len().saturating_mul(16),
                what: "the symbolic factorization",
            })?;
        let len = symbolic.len_val();
        if len > MAX_FACTOR_VALUES {
            return Err(LinalgError::TooLarge { n, max: MAX_FACTOR_VALUES });
        }
        let mut values = try_vec(len)?;
        values.resize(len, 0.0);
        let mut subdiag = try_vec(n)?;
        subdiag.resize(n, 0.0);
        let (mut forward, mut inverse) = (try_vec(n)?, try_vec(n)?);
        forward.resize(n, 0);
        inverse.resize(n, 0);
        let matrix = SparseColMatRef::new(structure, &s.values);
        let mut mem =
            buffer(symbolic.factorize_numeric_intranode_lblt_scratch::<f64>(Par::Seq, Default::default()))?;
        symbolic.factorize_numeric_intranode_lblt(
            &mut values,
            &mut subdiag,
            &mut forward,
            &mut inverse,
            matrix,
            Side::Lower,
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        );
        let norm = inf_norm_lower(n, &s);
        let diagonal = match lblt_form(&symbolic, &s, n) {
            Some(diagonal) => diagonal,
            None => {
                return Err(LinalgError::Unstable {
                    shift: sigma,
                    backward_error: f64::INFINITY,
                    bound: 0.0,
                });
            }
        };
        let mut lblt = Self { n, symbolic, values, subdiag, forward, inverse, norm, inertia: None, diagonal };
        let inertia = lblt.count_inertia();
        lblt.inertia = Some(inertia);
        // A zero pivot has no solves to check (an eigenvalue at sigma: its inertia is still exact
        // for the factored matrix, and the callers that solve refuse it).
        if inertia.zero == 0 {
            lblt.check_backward_error(a, sigma)?;
        }
        Ok(lblt)
    }

    /// The pivoting permutation (checked: faer filled both arrays as mutual inverses).
    fn pivots(&self) -> faer::perm::PermRef<'_, usize> {
        faer::perm::PermRef::new_checked(&self.forward, &self.inverse, self.n)
    }

    fn factor(&self) -> IntranodeLbltRef<'_, usize, f64> {
        IntranodeLbltRef::new(&self.symbolic, &self.values, &self.subdiag, self.pivots())
    }

    /// The inertia of `B` (and so of `A - sigma I`, Sylvester's law of inertia).
    pub(crate) fn inertia(&self) -> Inertia {
        self.inertia.unwrap_or_else(|| self.count_inertia())
    }

    fn count_inertia(&self) -> Inertia {
        let mut inertia = Inertia { negative: 0, zero: 0, positive: 0, smallest: (0, f64::INFINITY) };
        let mut add = |row: usize, v: f64| {
            match v.partial_cmp(&0.0) {
                Some(core::cmp::Ordering::Less) => inertia.negative += 1,
                Some(core::cmp::Ordering::Greater) => inertia.positive += 1,
                _ => inertia.zero += 1,
            }
            if v.is_nan() || v.abs() < inertia.smallest.1.abs() {
                inertia.smallest = (row, v);
            }
        };
        let SymbolicCholeskyRaw::Supernodal(symbolic) = self.symbolic.raw() else {
            // faer keeps the simplicial form, even when supernodal is forced, only when the
            // ordering predicts no arithmetic at all: a diagonal matrix, whose pivots are its
            // diagonal (checked in `new`).
            self.diagonal.iter().enumerate().for_each(|(i, &d)| add(i, d));
            return inertia;
        };
        let factor = SupernodalIntranodeLbltRef::new(symbolic, &self.values, &self.subdiag, self.pivots());
        for s in 0..symbolic.n_supernodes() {
            let node = factor.supernode(s);
            let b = node.val();
            let (start, size) = (node.start(), b.ncols());
            let mut i = 0;
            while i < size {
                let c = self.subdiag[start + i];
                if c == 0.0 || i + 1 == size {
                    add(start + i, b[(i, i)]);
                    i += 1;
                } else {
                    // The block's eigenvalues (x + y)/2 -+ sqrt(((x - y)/2)^2 + c^2): of opposite
                    // signs exactly when the determinant x y - c^2 is negative.
                    let (x, y) = (b[(i, i)], b[(i + 1, i + 1)]);
                    let (mean, radius) = (0.5 * (x + y), libm::hypot(0.5 * (x - y), c));
                    let (low, high) = (mean - radius, mean + radius);
                    // The eigenvalue of least magnitude from the determinant (no cancellation).
                    let far = if low.abs() > high.abs() { low } else { high };
                    let near = if far == 0.0 { 0.0 } else { (x * y - c * c) / far };
                    add(start + i, far);
                    add(start + i + 1, near);
                    i += 2;
                }
            }
        }
        inertia
    }

    /// Solves `(A - sigma I) X = B` in place for the `columns` right-hand sides stored column after
    /// column in `b`.
    pub(crate) fn solve_in_place(&self, b: &mut [f64], columns: usize) -> Result<(), LinalgError> {
        let rhs = MatMut::from_column_major_slice_mut(b, self.n, columns);
        let mut mem = buffer(self.symbolic.solve_in_place_scratch::<f64>(columns, Par::Seq))?;
        self.factor().solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem));
        Ok(())
    }

    /// `||A - sigma I||_inf`.
    pub(crate) fn norm(&self) -> f64 {
        self.norm
    }

    /// Solves `A - sigma I` against the right-hand side of a known solution and compares.
    fn check_backward_error(&self, a: &Upper<'_>, sigma: f64) -> Result<(), LinalgError> {
        let n = self.n;
        // A fixed probe with entries of both signs and varied sizes (any generic vector serves).
        let y: Vec<f64> = (0..n)
            .map(|i| 1.0 + ((i * 7919) % 97) as f64 / 97.0 * if i % 2 == 0 { 1.0 } else { -1.5 })
            .collect();
        let mut b = try_vec(n)?;
        b.resize(n, 0.0);
        a.mul_vec_shifted(sigma, &y, &mut b);
        let mut x = b.clone();
        self.solve_in_place(&mut x, 1)?;
        let eta = backward_error(a, sigma, self.norm, &x, &b);
        let bound = MAX_BACKWARD_ERROR_FACTOR * n as f64 * f64::EPSILON;
        if eta.is_nan() || eta > bound {
            return Err(LinalgError::Unstable { shift: sigma, backward_error: eta, bound });
        }
        Ok(())
    }
}

/// `||b - (A - sigma I) x|| / (||A - sigma I|| ||x|| + ||b||)` in max norms (Rigal-Gaches), `inf`
/// for a non-finite `x`.
pub(crate) fn backward_error(a: &Upper<'_>, sigma: f64, norm: f64, x: &[f64], b: &[f64]) -> f64 {
    if x.iter().any(|v| !v.is_finite()) {
        return f64::INFINITY;
    }
    let mut r = alloc::vec![0.0; x.len()];
    a.mul_vec_shifted(sigma, x, &mut r);
    let max = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let residual = r.iter().zip(b).fold(0.0f64, |m, (r, b)| m.max((b - r).abs()));
    let scale = norm * max(x) + max(b);
    if scale == 0.0 { 0.0 } else { residual / scale }
}

/// `Some` of nothing for the supernodal form; for the simplicial form (which faer keeps only when
/// the ordering predicts no arithmetic) `Some` of the diagonal if `s` is indeed diagonal, else
/// `None` (the unpivoted simplicial `LDL^T` is not trusted with anything else).
fn lblt_form(symbolic: &SymbolicCholesky<usize>, s: &Shifted, n: usize) -> Option<Vec<f64>> {
    if matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)) {
        return Some(Vec::new());
    }
    (0..n)
        .map(|j| match s.col_ptr[j + 1] - s.col_ptr[j] {
            1 => Some(s.values[s.col_ptr[j]]),
            _ => None,
        })
        .collect()
}

/// `max_i sum_j |S_ij|` of the symmetric matrix whose lower triangle is `s`.
fn inf_norm_lower(n: usize, s: &Shifted) -> f64 {
    let mut rows = alloc::vec![0.0; n];
    for j in 0..n {
        for k in s.col_ptr[j]..s.col_ptr[j + 1] {
            let (i, v) = (s.row_idx[k], s.values[k].abs());
            rows[i] += v;
            if i != j {
                rows[j] += v;
            }
        }
    }
    rows.into_iter().fold(0.0, f64::max)
}
