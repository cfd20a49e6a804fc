//! The layout of the hot path (energy and gradient: every step of a run or a relaxation): the
//! bonds of a patch as **runs** over which both ends' cells advance by one cell per bond, on
//! coordinates laid out as structures of arrays, so a driver loads a run's endpoints and adds its
//! gradient back with contiguous vector loads and stores instead of a gather and a scatter per bond.
//!
//! A patch repeats its cell, so the bonds of one cell bond (say, node 0 of a cell to node 2 of the
//! cell to its right) join degree of freedom `j1` of cell `c` to `j2` of cell `c + delta` for every
//! cell of a row. In the layout `input[j * cells + c] = x[c * D + j]` (`D` the cell's degrees of
//! freedom; `patch.rs`'s numbering is `c * D + j`) the first ends of such bonds are contiguous, and
//! so are the second ends. A run ends where the bond wraps round a periodic patch (its offset
//! changes) or leaves a free one. The runs are found from the bonds themselves (grouped by their
//! two slots and `delta`, then cut wherever consecutive bonds are not one cell apart or their
//! constants differ), so every patch and override is covered; a kagome patch of `N x N` cells has
//! at most two runs per cell bond and row.
//!
//! A rotor's angle has a sine and a cosine array after the coordinates
//! (`input[(D + 2 r) * cells + c]`, `input[(D + 2 r + 1) * cells + c]` for the `r`-th rotor slot of
//! the cell), computed once per call. The gradient is accumulated in the same layout
//! (`grad[j * cells + c]`) and transposed back; within one run no two bonds share a first end or a
//! second end, so the adds of a vector of bonds never collide.

use super::bonds::{Group, Kind};
use std::collections::HashMap;

/// A run of bonds of one type: bond `i` of the run reads its four end arguments at
/// `ends[a] + i` of the input, adds its gradient entries at `grads[a] + i`, and its `k`, `l0` at
/// `param + i` of the group's arrays.
#[derive(Debug)]
pub(super) struct Run {
    /// The bonds in the run.
    pub len: usize,
    /// Where the kernel's first four arguments of the run's first bond are in the input
    /// (`x1 y1 x2 y2`, `x1 y1 s2 c2` or `s1 c1 s2 c2`).
    pub ends: [usize; 4],
    /// Where the first bond's gradient entries go in the gradient (the kernel's order; only the
    /// first `Kind::dofs` are used).
    pub grads: [usize; 4],
    /// The kernel's constant arguments after the ends: `ox, oy` and the rotor lengths the kernel
    /// takes (none, `r2`, or `r1 r2`), zero-padded.
    pub constants: [f64; 4],
    /// The first bond's index in [`Runs::k`] and [`Runs::l0`].
    pub param: usize,
    /// `[k, l0]` when every bond of the run has the same (a cell bond without overrides: the
    /// common case), passed as constants: a large patch's step then streams 16 bytes per bond
    /// less, and the model holds them once per run.
    pub uniform: Option<[f64; 2]>,
}

/// The runs of one bond type, with the `k` and `l0` of the bonds of every run that has not one
/// pair for all its bonds ([`Run::uniform`]), in run order.
#[derive(Debug)]
pub(super) struct Runs {
    pub runs: Vec<Run>,
    pub k: Vec<f64>,
    pub l0: Vec<f64>,
}

/// The runs of a patch's bonds by type (in the order of `NetworkModel::groups`) and the shape of
/// the structure-of-arrays buffers they index.
#[derive(Debug)]
pub(super) struct Stencil {
    /// Cells of the patch.
    pub cells: usize,
    /// Degrees of freedom per cell (`D`).
    pub per_cell: usize,
    /// The cell's degrees of freedom that are rotor angles, in order (the `r`-th has the `r`-th
    /// sine and cosine arrays).
    pub rotor_slots: Vec<usize>,
    pub kinds: [Runs; 3],
}

impl Stencil {
    /// The runs of `groups`' bonds on a patch of `cells` cells of `per_cell` degrees of freedom;
    /// `is_rotor(d)` says whether degree of freedom `d` is a rotor angle (the same in every cell).
    pub fn new(groups: &[Group; 3], per_cell: usize, cells: usize, is_rotor: impl Fn(usize) -> bool) -> Self {
        let rotor_slots: Vec<usize> = (0..per_cell).filter(|&j| is_rotor(j)).collect();
        let mut rotor_index = vec![usize::MAX; per_cell];
        for (r, &j) in rotor_slots.iter().enumerate() {
            rotor_index[j] = r;
        }
        // Where an end's arguments and gradient entries are, for the degree of freedom `d` of
        // its first value: a joint's `x, y` (two gradient entries), a rotor's sine and cosine
        // (one entry, its angle's).
        let place = |d: usize, joint: bool| {
            let (c, j) = (d / per_cell, d % per_cell);
            if joint {
                ([j * cells + c, (j + 1) * cells + c], [j * cells + c, (j + 1) * cells + c], 2)
            } else {
                let r = rotor_index[j];
                ([(per_cell + 2 * r) * cells + c, (per_cell + 2 * r + 1) * cells + c], [j * cells + c, 0], 1)
            }
        };
        let kinds = groups.each_ref().map(|g| {
            let (first_joint, second_joint, second_at) = match g.kind {
                Kind::JointJoint => (true, true, 2),
                Kind::JointRotor => (true, false, 2),
                Kind::RotorRotor => (false, false, 1),
            };
            let bond = |i: usize| {
                let d = g.dofs[i];
                let (a1, g1, n1) = place(d[0], first_joint);
                let (a2, g2, n2) = place(d[second_at], second_joint);
                let mut grads = [0; 4];
                grads[..n1].copy_from_slice(&g1[..n1]);
                grads[n1..n1 + n2].copy_from_slice(&g2[..n2]);
                let [ox, oy] = g.offset[i];
                let [r1, r2] = g.radius[i];
                let constants = match g.kind {
                    Kind::JointJoint => [ox, oy, 0.0, 0.0],
                    Kind::JointRotor => [ox, oy, r2, 0.0],
                    Kind::RotorRotor => [ox, oy, r1, r2],
                };
                ([a1[0], a1[1], a2[0], a2[1]], grads, constants)
            };
            // Bonds with the same two slots and cell distance, in the group's (the patch's) order,
            // which is ascending in the first end's cell.
            let mut buckets: HashMap<(usize, usize, isize), Vec<usize>> = HashMap::new();
            let mut keys = Vec::new();
            for i in 0..g.len() {
                let d = g.dofs[i];
                let (d1, d2) = (d[0], d[second_at]);
                let key = (d1 % per_cell, d2 % per_cell, (d2 / per_cell) as isize - (d1 / per_cell) as isize);
                buckets
                    .entry(key)
                    .or_insert_with(|| {
                        keys.push(key);
                        Vec::new()
                    })
                    .push(i);
            }
            let mut runs =
                Runs { runs: Vec::new(), k: Vec::with_capacity(g.len()), l0: Vec::with_capacity(g.len()) };
            let used = g.kind.dofs();
            for key in keys {
                let mut last: Option<([usize; 4], [usize; 4], [f64; 4])> = None;
                for &i in &buckets[&key] {
                    let (ends, grads, constants) = bond(i);
                    let follows = last.is_some_and(|(e, gr, c)| {
                        (0..4).all(|a| ends[a] == e[a] + 1)
                            && (0..used).all(|a| grads[a] == gr[a] + 1)
                            && c.map(f64::to_bits) == constants.map(f64::to_bits)
                    });
                    match runs.runs.last_mut() {
                        Some(run) if follows => run.len += 1,
                        _ => runs.runs.push(Run {
                            len: 1,
                            ends,
                            grads,
                            constants,
                            param: runs.k.len(),
                            uniform: None,
                        }),
                    }
                    runs.k.push(g.k[i]);
                    runs.l0.push(g.l0[i]);
                    last = Some((ends, grads, constants));
                }
            }
            // Keep per-bond parameters only for the runs that need them.
            let same = |v: &[f64]| v.iter().all(|x| x.to_bits() == v[0].to_bits());
            let (k, l0) = (std::mem::take(&mut runs.k), std::mem::take(&mut runs.l0));
            for run in &mut runs.runs {
                let range = run.param..run.param + run.len;
                if same(&k[range.clone()]) && same(&l0[range.clone()]) {
                    run.uniform = Some([k[run.param], l0[run.param]]);
                } else {
                    run.param = runs.k.len();
                    runs.k.extend_from_slice(&k[range.clone()]);
                    runs.l0.extend_from_slice(&l0[range]);
                }
            }
            runs
        });
        Self { cells, per_cell, rotor_slots, kinds }
    }

    /// Values of the input buffer: the coordinates, then a sine and a cosine per rotor slot.
    pub fn input_len(&self) -> usize {
        (self.per_cell + 2 * self.rotor_slots.len()) * self.cells
    }

    /// Values of the gradient buffer.
    pub fn grad_len(&self) -> usize {
        self.per_cell * self.cells
    }

    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(&self.rotor_slots[..])
            + self
                .kinds
                .iter()
                .map(|r| size_of_val(&r.runs[..]) + size_of_val(&r.k[..]) + size_of_val(&r.l0[..]))
                .sum::<usize>()
    }

    /// Fills `input`'s coordinates from `x` (in the patch's order) and the rotors' sines and
    /// cosines.
    #[inline(always)]
    pub fn gather(&self, x: &[f64], input: &mut [f64]) {
        let (cells, d) = (self.cells, self.per_cell);
        let (coordinates, trig) = input.split_at_mut(d * cells);
        transposes!(d, |D| to_columns::<D>(x, coordinates, cells), to_columns_any(x, coordinates, cells, d));
        for (r, &j) in self.rotor_slots.iter().enumerate() {
            let (sin, cos) = trig[2 * r * cells..(2 * r + 2) * cells].split_at_mut(cells);
            chain_core::simd::sin_cos_into(&coordinates[j * cells..(j + 1) * cells], sin, cos);
        }
    }

    /// Writes the gradient `grad` (this layout) into `out` (the patch's order).
    #[inline(always)]
    pub fn scatter(&self, grad: &[f64], out: &mut [f64]) {
        let (cells, d) = (self.cells, self.per_cell);
        transposes!(d, |D| to_rows::<D>(grad, out, cells), to_rows_any(grad, out, cells, d));
    }
}

/// `$fixed` with the const `D` equal to `$d` for the cells of up to 8 degrees of freedom (the
/// compiler then turns the strided accesses into vector shuffles), else `$any`.
macro_rules! transposes {
    ($d:expr, |D| $fixed:expr, $any:expr) => {
        match $d {
            1 => {
                const D: usize = 1;
                $fixed
            }
            2 => {
                const D: usize = 2;
                $fixed
            }
            3 => {
                const D: usize = 3;
                $fixed
            }
            4 => {
                const D: usize = 4;
                $fixed
            }
            5 => {
                const D: usize = 5;
                $fixed
            }
            6 => {
                const D: usize = 6;
                $fixed
            }
            7 => {
                const D: usize = 7;
                $fixed
            }
            8 => {
                const D: usize = 8;
                $fixed
            }
            _ => $any,
        }
    };
}
use transposes;

/// `columns[j * cells + c] = x[c * D + j]`.
#[inline(always)]
fn to_columns<const D: usize>(x: &[f64], columns: &mut [f64], cells: usize) {
    let columns: [&mut [f64]; D] = split::<D>(columns, cells);
    for (c, row) in x.chunks_exact(D).enumerate().take(cells) {
        for j in 0..D {
            columns[j][c] = row[j];
        }
    }
}

/// `out[c * D + j] = columns[j * cells + c]`.
#[inline(always)]
fn to_rows<const D: usize>(columns: &[f64], out: &mut [f64], cells: usize) {
    let columns: [&[f64]; D] = core::array::from_fn(|j| &columns[j * cells..(j + 1) * cells]);
    for (c, row) in out.chunks_exact_mut(D).enumerate().take(cells) {
        for j in 0..D {
            row[j] = columns[j][c];
        }
    }
}

/// `s`'s first `D` pieces of `len` values.
#[inline(always)]
fn split<const D: usize>(mut s: &mut [f64], len: usize) -> [&mut [f64]; D] {
    let mut parts: [&mut [f64]; D] = [(); D].map(|_| <&mut [f64]>::default());
    for part in &mut parts {
        let (head, tail) = core::mem::take(&mut s).split_at_mut(len);
        *part = head;
        s = tail;
    }
    parts
}

/// [`to_columns`] for any `d`.
#[inline(always)]
fn to_columns_any(x: &[f64], columns: &mut [f64], cells: usize, d: usize) {
    for (j, column) in columns.chunks_exact_mut(cells).enumerate() {
        for (v, &x) in column.iter_mut().zip(x.iter().skip(j).step_by(d)) {
            *v = x;
        }
    }
}

/// [`to_rows`] for any `d`.
#[inline(always)]
fn to_rows_any(columns: &[f64], out: &mut [f64], cells: usize, d: usize) {
    for (j, column) in columns.chunks_exact(cells).enumerate() {
        for (o, &g) in out.iter_mut().skip(j).step_by(d).zip(column) {
            *o = g;
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::Cell;
    use crate::cell::ready;
    use crate::model::NetworkModel;
    use crate::model::bonds::each_bond;
    use crate::patch::{Boundary, Patch};
    use chain_core::simd::{Level, with_level};
    use chain_core::{Law, Potential};
    use test_support::random::SplitMix;

    /// Every bond type, a joint-rotor bond from either end, a rotor bonded to its own image, and
    /// eleven degrees of freedom per cell (more than the transposes' fixed sizes).
    fn wide() -> Cell {
        Cell::builder(2, &[[1.0, 0.1], [0.2, 1.3]])
            .joint("a", [0.1, 0.2])
            .rotor("p", [0.5, 0.4], 0.3, 0.7)
            .joint("c", [0.7, 0.9])
            .joint("e", [0.3, 0.6])
            .joint("f", [0.9, 0.2])
            .joint("g", [0.6, 0.1])
            .bond("a", "p", &[0, 0])
            .bond("p", "c", &[1, 0])
            .bond("c", "a", &[0, 1])
            .bond("p", "p", &[1, -1])
            .bond("e", "a", &[1, 1])
            .bond("f", "e", &[-1, 0])
            .bond("g", "c", &[0, 0])
            .bond("g", "f", &[2, 1])
            .build()
            .unwrap()
    }

    /// The stencil's energy and gradient against the scalar kernels summed bond by bond (the
    /// order of `Patch::bonds`): every bond's terms are the same numbers, so the two sums of a
    /// degree of freedom's `n` terms differ by at most `2 n eps` times the sum of their
    /// magnitudes. At every level the machine runs, on periodic and free patches, with and without
    /// each bond's constant and rest length overridden.
    #[test]
    fn runs_give_the_bond_by_bond_energy_and_gradient_to_rounding() {
        let cells = [(ready::kagome(), [11, 7]), (wide(), [10, 9]), (wide(), [3, 3])];
        // Whether bond types with their own `k` and `l0` per bond, and with one for all, were met.
        let mut seen = [false; 2];
        for (cell, size) in &cells {
            for boundary in [Boundary::Periodic, Boundary::Free] {
                let patch = Patch::new(cell, *size, boundary).unwrap();
                for (law, overrides) in [(Law::Harmonic, false), (Law::Harmonic, true), (Law::Quartic, true)]
                {
                    let mut rng = SplitMix(patch.bonds().len() as u64);
                    let mut builder = NetworkModel::builder(&patch).law(law);
                    // Without overrides every run has one `k` and `l0` (`Run::uniform`).
                    for p in (0..patch.bonds().len()).filter(|_| overrides) {
                        builder = builder
                            .spring_constant(p, rng.range(0.5, 2.0))
                            .rest_length(p, rng.range(0.5, 1.5));
                    }
                    let model = builder.build().unwrap();
                    for run in model.stencil.kinds.iter().flat_map(|r| &r.runs) {
                        seen[usize::from(run.uniform.is_some())] = true;
                    }
                    let x: Vec<f64> = model.reference().iter().map(|x| x + 0.1 * rng.symmetric()).collect();
                    let n = x.len();
                    // The reference at the same level: the rotors' sines and cosines differ
                    // between levels (2 ulp).
                    let bond_by_bond = || {
                        let trig = model.trig(&x);
                        let (mut reference, mut magnitude, mut terms) =
                            (vec![0.0; n], vec![0.0; n], vec![0usize; n]);
                        let mut energy = 0.0;
                        let mut add = |g: &crate::model::bonds::Group, i: usize, out: &[f64]| {
                            energy += out[0];
                            for (&d, &v) in g.bond_dofs(i).iter().zip(&out[1..]) {
                                reference[d] += v;
                                magnitude[d] += v.abs();
                                terms[d] += 1;
                            }
                        };
                        match law {
                            Law::Quartic => each_bond!(
                                &model,
                                crate::kernel::quartic::Law,
                                &x,
                                &trig,
                                EnergyGradient,
                                [5, 4, 3],
                                |g, i, out| { add(g, i, out) }
                            ),
                            _ => each_bond!(
                                &model,
                                crate::kernel::harmonic::Law,
                                &x,
                                &trig,
                                EnergyGradient,
                                [5, 4, 3],
                                |g, i, out| { add(g, i, out) }
                            ),
                        }
                        (energy, reference, magnitude, terms)
                    };
                    for level in Level::ALL {
                        let Some((e, grad, alone, (energy, reference, magnitude, terms))) =
                            with_level(level, || {
                                let mut grad = vec![f64::NAN; n];
                                let e = model.energy_and_gradient_into(&x, &mut grad);
                                (e, grad, model.gradient(&x), bond_by_bond())
                            })
                        else {
                            continue;
                        };
                        let what = format!("{size:?} {boundary:?} {law:?} overrides {overrides} {level:?}");
                        assert_eq!(grad, alone, "{what}: fused and alone");
                        // Both energies are sums of the same bond energies (positive).
                        let bonds = patch.bonds().len() as f64;
                        assert!(
                            (e - energy).abs() <= 2.0 * bonds * f64::EPSILON * energy,
                            "{what}: {e} vs {energy}"
                        );
                        for d in 0..n {
                            let bound = 2.0 * terms[d] as f64 * f64::EPSILON * magnitude[d];
                            assert!(
                                (grad[d] - reference[d]).abs() <= bound,
                                "{what}: dof {d}: {} vs {} (bound {bound:e})",
                                grad[d],
                                reference[d]
                            );
                        }
                    }
                }
            }
        }
        assert_eq!(seen, [true, true], "both parameter layouts");
    }
}
