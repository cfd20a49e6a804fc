//! Singular values and the null spaces of an upper bidiagonal `m x (m + 1)` matrix `B` (a chain's
//! compatibility matrix, `B[p][p] = diag[p]`, `B[p][p + 1] = sup[p]`) from its Golub-Kahan
//! tridiagonal, in O(m) per Sturm count and without forming `B^T B`.
//!
//! Interleaving the columns' and the rows' unknowns, `x_0, y_0, x_1, y_1, ..., y_{m-1}, x_m`,
//! turns `[[0, B^T], [B, 0]]` into the symmetric tridiagonal `T_GK` of size `2m + 1` with a zero
//! diagonal and the off-diagonal `diag[0], sup[0], diag[1], sup[1], ...` (Golub & Kahan, *SIAM
//! J. Numer. Anal.* 2, 1965). Its eigenvalues are `+-sigma_p` for the `m` singular values and one
//! `0` (`B` has one column more than rows); an eigenvector `(x; y)` of `+-sigma` holds a right
//! singular vector `x = v / sqrt 2` and a left one `y = +-u / sqrt 2`.
//!
//! - **Values**: the small ones (below `1e-2 sigma_max`, [`REFINED`]) by bisection on Sturm
//!   counts of `T_GK` ([`bisection`](super::bisection)) to relative accuracy: a Sturm count of a
//!   zero-diagonal tridiagonal in floating point is exact for off-diagonal entries perturbed by a
//!   few ulps, which moves each singular value by a few ulps of itself (Demmel & Kahan, *SIAM J.
//!   Sci. Stat. Comput.* 11, 1990, Sec. 5). So a singular value of `1e-14 sigma_max` comes out
//!   with its own digits, where `sqrt` of an eigenvalue of `B B^T` knows it only to
//!   `sqrt(eps) sigma_max`. O(m) per count, about 27 counts per value. The others, where that
//!   square root is accurate, come from the implicit QL iteration on the tridiagonal `B B^T`
//!   ([`ql`](super::ql), values only): bisecting every value would cost about 27 counts of
//!   `2m + 1` rows each, 15 s at `m = 8191` against 1.4 s this way (release build, AMD EPYC
//!   Zen 4). The values at the rank tolerance are bisected ones, so the rank is the Sturm
//!   count at the tolerance.
//! - **Null spaces** (the singular values at or below a tolerance): the lowest eigenvectors of
//!   the tridiagonals `B^T B` and `B B^T` (bisection and inverse iteration, O(m) per vector),
//!   taken for every singular value below `1e-2 sigma_max` so that the squared gap to the rest
//!   keeps them from mixing with other vectors, then a Rayleigh-Ritz step with `B` itself picks
//!   the combinations `B` (or `B^T`) maps nearest to zero, and each is checked. Inverse iteration
//!   on `T_GK` itself could not span a cluster of eigenvalues tighter than eps (a symmetric
//!   antikink's self-stress has `sigma = 2.7e-34`: three eigenvalues of `T_GK` at zero), whose
//!   solves amplify one direction only; `B^T B` keeps `0` and `sigma^2` with `B B^T`'s
//!   `sigma^2` apart.
//!
//! Every loop asks the caller's stop question (every QL iteration, before each value's bisection
//! and each vector's inverse iteration), so Python's Ctrl-C ends a count of any length within
//! milliseconds.

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::DMatrix;

use super::bands;
use super::bisection::{Accuracy, bisect};
use super::error::{Input, LinalgError};
use super::inverse_iteration::eigenpairs_in_index_range_with;
use super::ql::eigenvalues_ql_with;
use super::sturm::Sturm;
use crate::math;

/// Singular values below `REFINED sigma_max` are bisected to relative accuracy; the others
/// come from the eigenvalues of `B B^T`, to `c eps sigma_max / (2 REFINED)` absolute (about
/// `100 c eps sigma_max`, `c` a small multiple of the QL iteration's rounding).
pub(crate) const REFINED: f64 = 1e-2;

/// Orthonormal bases of a bidiagonal's right and left null spaces.
pub(crate) struct NullSpaces {
    /// Vectors of `m + 1` entries that `B` maps to zero.
    pub right: Vec<Vec<f64>>,
    /// Vectors of `m` entries that `B^T` maps to zero.
    pub left: Vec<Vec<f64>>,
}

/// `T_GK` of the bidiagonal (`diag`, `sup`) prepared for Sturm counts, checked: equal lengths,
/// finite entries.
pub(crate) struct GolubKahan {
    sturm: Sturm,
    /// `m`, the rows of `B`.
    rows: usize,
}

impl GolubKahan {
    /// `diag` and `sup` of an `m x (m + 1)` upper bidiagonal, `m` entries each.
    pub fn new(diag: &[f64], sup: &[f64]) -> Result<Self, LinalgError> {
        if diag.len() != sup.len() {
            return Err(LinalgError::DimensionMismatch { diag: diag.len() + 1, off: sup.len() });
        }
        bands::check_finite(Input::Diag, diag)?;
        bands::check_finite(Input::Off, sup)?;
        let rows = diag.len();
        let off: Vec<f64> = diag.iter().zip(sup).flat_map(|(&d, &s)| [d, s]).collect();
        Ok(Self { sturm: Sturm::new(&vec![0.0; 2 * rows + 1], &off), rows })
    }

    /// The `m` singular values, ascending: those below [`REFINED`]` sigma_max` each to a few
    /// ulps of itself (bisection on `T_GK`, down to the pivot floor, about
    /// `1e-307 max |B_ij|`), the others as `sqrt` of the eigenvalues of the tridiagonal `B B^T`
    /// (implicit QL, O(m^2) with a small constant), whose absolute error `c eps sigma_max^2`
    /// becomes at most `c eps sigma_max / (2 REFINED)` on a value above the bound.
    pub fn singular_values(&self, stop: &mut dyn FnMut() -> bool) -> Result<Vec<f64>, LinalgError> {
        let m = self.rows;
        let scale = self.sturm.matrix.scale;
        // B B^T from the scaled entries (the largest in [1, 2): the squares neither overflow nor
        // lose more than B's own entries below 1e-154 sigma_max, which bisection recovers).
        let ((diag, off), _) = self.gram();
        let mut values: Vec<f64> = match eigenvalues_ql_with(&diag, &off, stop) {
            Ok(squares) => squares.into_iter().map(|x| math::sqrt(x.max(0.0))).collect(),
            Err(LinalgError::NoConvergence { .. }) => Vec::new(),
            Err(other) => return Err(other),
        };
        // The values below the bound (all of them should QL not converge) by bisection: `T_GK`
        // has m + 1 eigenvalues below every x > 0 that is no singular value (the -sigma and the
        // extra 0), one more for each singular value below x.
        let sigma_max = values.last().copied().unwrap_or(f64::INFINITY);
        let small = if values.len() == m {
            (self.sturm.count(REFINED * sigma_max) - (m + 1)).min(m)
        } else {
            values = vec![0.0; m];
            m
        };
        let refined = bisect(&self.sturm, m + 1, m + 1 + small, Accuracy::Relative, stop)?;
        values[..small].copy_from_slice(&refined);
        values.sort_by(f64::total_cmp);
        Ok(values.into_iter().map(|s| s / scale).collect())
    }

    /// Orthonormal bases of the right null space (`zero + 1` vectors of `m + 1` entries: the
    /// extra column's and those of the `zero` smallest singular values) and the left one (`zero`
    /// vectors of `m` entries), where `zero` singular values count as zero and the `near`
    /// smallest (`near >= zero`) are close enough to zero for their vectors to mix with the null
    /// vectors'. The `near + 1` lowest eigenvectors of the tridiagonal `B^T B` and the `near`
    /// lowest of `B B^T` (bisection and inverse iteration, O(m) per vector; `near` must leave a
    /// gap to the next singular value well above `sqrt(eps) sigma_max`, as squaring shrinks it
    /// to its square) span the singular subspaces of those values; within each, a Rayleigh-Ritz
    /// step with `B` itself (the eigenvectors of `(B Q)^T (B Q)` for the orthonormal basis `Q`,
    /// and of `(B^T Q)^T (B^T Q)` on the left) picks the vectors `B` maps nearest to zero.
    ///
    /// Each vector found is checked: `B` maps it within `tolerance` (the rank rule's, in `B`'s
    /// units) or the rounding of inverse iteration (`64 eps ||B|| sqrt(2m + 1)`) of zero, or the
    /// answer is [`LinalgError::NoConvergence`] with its residual.
    pub fn null_spaces(
        &self,
        zero: usize,
        near: usize,
        tolerance: f64,
        stop: &mut dyn FnMut() -> bool,
    ) -> Result<NullSpaces, LinalgError> {
        let m = self.rows;
        let near = near.clamp(zero, m);
        let (left_diag, right_diag) = self.gram();
        let vectors = |(diag, off): (Vec<f64>, Vec<f64>), count: usize, stop: &mut dyn FnMut() -> bool| {
            eigenpairs_in_index_range_with(&diag, &off, 0, count, stop)
                .map(|pairs| pairs.into_iter().map(|p| p.vector).collect::<Vec<_>>())
        };
        let right_basis = vectors(right_diag, near + 1, stop)?;
        let left_basis = vectors(left_diag, near, stop)?;
        let right = lowest(&right_basis, zero + 1, |v| self.times(v))?;
        let left = lowest(&left_basis, zero, |u| self.transpose_times(u))?;
        // Every null vector is mapped within the rank tolerance (or a few eps ||B|| of rounding)
        // of zero; otherwise the subspaces were wrong.
        let scale = self.sturm.matrix.scale;
        let rounding = 64.0 * f64::EPSILON * self.sturm.matrix.norm() * math::sqrt((2 * m + 1) as f64);
        let bound = (tolerance * scale).max(rounding);
        let residuals = right
            .iter()
            .map(|v| bands::norm2(&self.times(v)))
            .chain(left.iter().map(|u| bands::norm2(&self.transpose_times(u))));
        if let Some((index, residual)) = residuals.enumerate().find(|&(_, r)| r.is_nan() || r > bound) {
            return Err(LinalgError::NoConvergence { iterations: 0, index, residual: residual / scale });
        }
        Ok(NullSpaces { right, left })
    }

    /// The tridiagonal `B B^T` (`m x m`) and `B^T B` (`(m + 1) x (m + 1)`) of the scaled `B`, as
    /// `(diag, off)` pairs.
    #[allow(clippy::type_complexity)]
    fn gram(&self) -> ((Vec<f64>, Vec<f64>), (Vec<f64>, Vec<f64>)) {
        let m = self.rows;
        let b = &self.sturm.matrix.off;
        let (d, s) = (|p: usize| b[2 * p], |p: usize| b[2 * p + 1]);
        let bbt = (
            (0..m).map(|p| d(p) * d(p) + s(p) * s(p)).collect(),
            (0..m.saturating_sub(1)).map(|p| s(p) * d(p + 1)).collect(),
        );
        let btb = (
            (0..=m)
                .map(
                    |j| if j < m { d(j) * d(j) } else { 0.0 } + if j > 0 { s(j - 1) * s(j - 1) } else { 0.0 },
                )
                .collect(),
            (0..m).map(|j| d(j) * s(j)).collect(),
        );
        (bbt, btb)
    }

    /// `B v` (`v` of `m + 1` entries), in the scaled units.
    fn times(&self, v: &[f64]) -> Vec<f64> {
        let off = &self.sturm.matrix.off;
        (0..self.rows).map(|p| off[2 * p] * v[p] + off[2 * p + 1] * v[p + 1]).collect()
    }

    /// `B^T u` (`u` of `m` entries), in the scaled units.
    fn transpose_times(&self, u: &[f64]) -> Vec<f64> {
        let off = &self.sturm.matrix.off;
        (0..=self.rows)
            .map(|j| {
                let from_row = if j < self.rows { off[2 * j] * u[j] } else { 0.0 };
                let from_above = if j > 0 { off[2 * j - 1] * u[j - 1] } else { 0.0 };
                from_row + from_above
            })
            .collect()
    }
}

/// The eigenvectors of a small symmetric matrix, columns ordered by ascending eigenvalue.
fn eigenvectors_ascending(g: DMatrix<f64>) -> Result<(Vec<f64>, DMatrix<f64>), LinalgError> {
    let c = g.nrows();
    let budget = 64 * c * c + 64;
    let eigen = g.try_symmetric_eigen(f64::EPSILON, budget).ok_or(LinalgError::NoConvergence {
        iterations: budget,
        index: 0,
        residual: f64::NAN,
    })?;
    let mut order: Vec<usize> = (0..c).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let values = order.iter().map(|&i| eigen.eigenvalues[i]).collect();
    Ok((values, DMatrix::from_fn(c, c, |r, k| eigen.eigenvectors[(r, order[k])])))
}

/// `sum_k g[k] parts[k]`, normalised.
fn combine(parts: &[Vec<f64>], g: impl Fn(usize) -> f64) -> Vec<f64> {
    let mut out = vec![0.0; parts.first().map_or(0, Vec::len)];
    for (k, p) in parts.iter().enumerate() {
        let w = g(k);
        out.iter_mut().zip(p).for_each(|(o, x)| *o += w * x);
    }
    bands::normalize(&mut out);
    out
}

/// The `count` combinations of the orthonormal `basis` that `apply` maps nearest to zero
/// (Rayleigh-Ritz: eigenvectors of `(A Q)^T (A Q)`), orthonormal.
fn lowest(
    basis: &[Vec<f64>],
    count: usize,
    apply: impl Fn(&[f64]) -> Vec<f64>,
) -> Result<Vec<Vec<f64>>, LinalgError> {
    let c = basis.len();
    if count >= c {
        return Ok(basis.to_vec());
    }
    let images: Vec<Vec<f64>> = basis.iter().map(|q| apply(q)).collect();
    let (_, g) = eigenvectors_ascending(DMatrix::from_fn(c, c, |i, j| bands::dot(&images[i], &images[j])))?;
    Ok((0..count).map(|k| combine(basis, |r| g[(r, k)])).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dense `B`.
    fn dense(diag: &[f64], sup: &[f64]) -> DMatrix<f64> {
        let m = diag.len();
        let mut b = DMatrix::zeros(m, m + 1);
        for p in 0..m {
            b[(p, p)] = diag[p];
            b[(p, p + 1)] = sup[p];
        }
        b
    }

    #[test]
    fn graded_singular_values_keep_their_digits() {
        // B = [[1, 1], ...] graded by 1e-5 per row: singular values spanning 1e-35 .. 1, which
        // the eigenvalues of B B^T (squares, absolute error eps) cannot give. The exact values
        // of a 1x2 block [d, s] are sqrt(d^2 + s^2); build a direct sum of such blocks by zero
        // couplings: rows p and p + 1 share column p + 1, so alternate zero entries decouple.
        let diag = [3.0, 0.0, 3e-20, 0.0, 3e-40];
        let sup = [4.0, 0.0, 4e-20, 0.0, 4e-40];
        let gk = GolubKahan::new(&diag, &sup).unwrap();
        let values = gk.singular_values(&mut || false).unwrap();
        let expected = [0.0, 0.0, 5e-40, 5e-20, 5.0];
        for (got, want) in values.iter().zip(expected) {
            assert!((got - want).abs() <= 4.0 * f64::EPSILON * want + 1e-300, "{got:e} vs {want:e}");
        }
    }

    #[test]
    fn null_spaces_are_annihilated_and_orthonormal() {
        // Two exact zero singular values (rows 1 and 3 zero): three right, two left vectors.
        let diag = [1.0, 0.0, 2.0, 0.0, 0.5];
        let sup = [-0.7, 0.0, 0.3, 0.0, 1.5];
        let gk = GolubKahan::new(&diag, &sup).unwrap();
        let NullSpaces { right, left } = gk.null_spaces(2, 2, 0.0, &mut || false).unwrap();
        assert_eq!((right.len(), left.len()), (3, 2));
        let b = dense(&diag, &sup);
        for v in &right {
            let bv = &b * nalgebra::DVector::from_column_slice(v);
            assert!(bv.norm() < 1e-14, "{}", bv.norm());
        }
        for u in &left {
            let btu = b.transpose() * nalgebra::DVector::from_column_slice(u);
            assert!(btu.norm() < 1e-14, "{}", btu.norm());
        }
        for set in [&right, &left] {
            for (i, a) in set.iter().enumerate() {
                for (j, b) in set.iter().enumerate() {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((bands::dot(a, b) - want).abs() < 1e-13);
                }
            }
        }
    }

    #[test]
    fn a_stop_question_answered_yes_stops() {
        let gk = GolubKahan::new(&[1.0; 50], &[0.5; 50]).unwrap();
        let mut asked = 0;
        let result = gk.singular_values(&mut || {
            asked += 1;
            asked > 3
        });
        assert!(
            matches!(result, Err(LinalgError::Stopped { what: "eigenvalues", of: 50, .. })),
            "{result:?}"
        );
        assert_eq!(asked, 4, "asked until the first yes, then no more");
    }
}
