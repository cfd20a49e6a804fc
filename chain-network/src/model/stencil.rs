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
//! at most two runs per cell bond and row. A bond's parameters (`k`, `l0`, and a law's own: the
//! polynomial's coefficients) go to the kernel as constants where every bond of the run has the
//! same (a cell bond without overrides), else as one array per parameter, contiguous per run; the
//! generated kernels stay the only arithmetic.
//!
//! A rotor's angle has a sine and a cosine array after the coordinates
//! (`input[(D + 2 r) * cells + c]`, `input[(D + 2 r + 1) * cells + c]` for the `r`-th rotor slot of
//! the cell), computed once per call. The gradient is accumulated in the same layout
//! (`grad[j * cells + c]`) and transposed back; within one run no two bonds share a first end or a
//! second end, so the adds of a vector of bonds never collide.

use super::bonds::{Group, Kind};
use chain_core::allocation::{AllocationError, bytes_of, try_vec};
use std::collections::HashMap;

/// The most parameters a bond passes after its geometry: `k`, `l0` and a law's own (the
/// polynomial's five coefficients, `Group::coefficients`).
pub(super) const PARAMETERS: usize = 7;

/// One of a run's parameters (`k`, `l0`, a coefficient): one value for every bond of the run,
/// passed to the kernel as a constant (the common case: a cell bond without overrides; a large
/// patch's step then streams 8 bytes per bond and parameter less, and the model holds it once per
/// run), or the run's own values from `Runs::values[at]` on, one per bond.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Parameter {
    Shared(f64),
    PerBond(usize),
}

/// A run of bonds of one type: bond `i` of the run reads its four end arguments at
/// `ends[a] + i` of the input, adds its gradient entries at `grads[a] + i`, and takes its
/// parameters from [`Run::parameters`].
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
    /// `k`, `l0`, then the law's coefficients `c2 .. c6` (the polynomial's; `Shared(0.0)` for a
    /// law without them), each shared by the run's bonds or per bond.
    pub parameters: [Parameter; PARAMETERS],
}

/// The runs of one bond type, with the values of every parameter that is not shared by a run's
/// bonds ([`Parameter::PerBond`]), run after run.
#[derive(Debug)]
pub(super) struct Runs {
    pub runs: Vec<Run>,
    pub values: Vec<f64>,
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

/// Room for `additional` more values in `v`, growing by doubling (the runs' count is found as they
/// are built).
fn reserve<T>(v: &mut Vec<T>, additional: usize, what: &'static str) -> Result<(), AllocationError> {
    v.try_reserve(additional)
        .map_err(|_| AllocationError { bytes: bytes_of::<T>(v.len().saturating_add(additional)), what })
}

impl Stencil {
    /// The runs of `groups`' bonds on a patch of `cells` cells of `per_cell` degrees of freedom;
    /// `is_rotor(d)` says whether degree of freedom `d` is a rotor angle (the same in every cell).
    ///
    /// # Errors
    /// The arrays sized by the bonds (their order, the runs, the per-bond parameters) allocated
    /// fallibly; the cell's slots are bounded by the cell.
    pub fn new(
        groups: &[Group; 3],
        per_cell: usize,
        cells: usize,
        is_rotor: impl Fn(usize) -> bool,
    ) -> Result<Self, AllocationError> {
        let what = "the model's runs of bonds";
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
        let runs_of = |g: &Group| -> Result<Runs, AllocationError> {
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
            // Bonds with the same two slots and cell distance (a key; a few per bond of the cell),
            // keys in order of first appearance, each key's bonds in the group's (the patch's)
            // order, which is ascending in the first end's cell: the bonds sorted by (key's rank,
            // index), in place.
            // As `u32` pairs, 8 bytes a bond (the buckets this replaced held one `usize` a bond): a
            // group has at most `MAX_PATCH_BONDS` = 2^25 bonds, and as many keys.
            debug_assert!(
                g.len() <= crate::patch::MAX_PATCH_BONDS && crate::patch::MAX_PATCH_BONDS < 1 << 32
            );
            let mut ranks: HashMap<(usize, usize, isize), u32> = HashMap::new();
            let mut order: Vec<(u32, u32)> = try_vec(g.len(), what)?;
            for i in 0..g.len() {
                let d = g.dofs[i];
                let (d1, d2) = (d[0], d[second_at]);
                let key = (d1 % per_cell, d2 % per_cell, (d2 / per_cell) as isize - (d1 / per_cell) as isize);
                let next = ranks.len() as u32;
                order.push((*ranks.entry(key).or_insert(next), i as u32));
            }
            order.sort_unstable();
            // The bonds of each run, found first; its parameters are then shared or per bond.
            let mut runs = Runs { runs: Vec::new(), values: Vec::new() };
            let mut members: Vec<usize> = try_vec(g.len(), what)?;
            let used = g.kind.dofs();
            let mut rank = u32::MAX;
            let mut last: Option<([usize; 4], [usize; 4], [f64; 4])> = None;
            for &(key, i) in &order {
                let i = i as usize;
                if key != rank {
                    (rank, last) = (key, None);
                }
                let (ends, grads, constants) = bond(i);
                let follows = last.is_some_and(|(e, gr, c)| {
                    (0..4).all(|a| ends[a] == e[a] + 1)
                        && (0..used).all(|a| grads[a] == gr[a] + 1)
                        && c.map(f64::to_bits) == constants.map(f64::to_bits)
                });
                match runs.runs.last_mut() {
                    Some(run) if follows => run.len += 1,
                    _ => {
                        reserve(&mut runs.runs, 1, what)?;
                        runs.runs.push(Run {
                            len: 1,
                            ends,
                            grads,
                            constants,
                            parameters: [Parameter::Shared(0.0); PARAMETERS],
                        });
                    }
                }
                members.push(i);
                last = Some((ends, grads, constants));
            }
            // Bond `i`'s parameter `j` (`k`, `l0`, then the coefficients where the law has them).
            let parameter = |i: usize, j: usize| match j {
                0 => g.k[i],
                1 => g.l0[i],
                _ => g.coefficients.get(i).map_or(0.0, |c| c[j - 2]),
            };
            let mut start = 0;
            for run in &mut runs.runs {
                let bonds = &members[start..start + run.len];
                for (j, slot) in run.parameters.iter_mut().enumerate() {
                    let first = parameter(bonds[0], j);
                    *slot = if bonds.iter().all(|&i| parameter(i, j).to_bits() == first.to_bits()) {
                        Parameter::Shared(first)
                    } else {
                        reserve(&mut runs.values, run.len, what)?;
                        runs.values.extend(bonds.iter().map(|&i| parameter(i, j)));
                        Parameter::PerBond(runs.values.len() - run.len)
                    };
                }
                start += run.len;
            }
            Ok(runs)
        };
        let [a, b, c] = groups.each_ref().map(runs_of);
        Ok(Self { cells, per_cell, rotor_slots, kinds: [a?, b?, c?] })
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
            + self.kinds.iter().map(|r| size_of_val(&r.runs[..]) + size_of_val(&r.values[..])).sum::<usize>()
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

    /// The laws and parameters of a case of the test below.
    #[derive(Clone, Copy, Debug)]
    enum Laws {
        /// Harmonic, the cell's constants and rest lengths (every parameter shared by a run).
        Harmonic,
        /// Harmonic, every spring's `k` and `l0` overridden.
        HarmonicOverridden,
        /// Quartic, every spring's `k` and `l0` overridden.
        QuarticOverridden,
        /// One polynomial for every spring, every spring's `k` overridden: `k` per bond, `l0`
        /// and the coefficients shared.
        PolynomialShared,
        /// A polynomial of its own for every spring (every coefficient per bond), every `l0`
        /// overridden.
        PolynomialPerBond,
        /// Harmonic springs (the polynomial `c2 = 1`) and every third spring one polynomial:
        /// runs with coefficients per bond beside runs that share them.
        Mixed,
    }

    /// The stencil's energy and gradient against the scalar kernels summed bond by bond (the
    /// order of `Patch::bonds`) for every law's kernels (harmonic, quartic, the polynomial with
    /// its coefficients shared or per bond): every bond's terms are the same numbers, so the two
    /// sums of a degree of freedom's `n` terms differ by at most `2 n eps` times the sum of their
    /// magnitudes, and the energies by `2 b eps` times the sum of the `b` bond energies'
    /// magnitudes. At every level the machine runs, on periodic and free patches.
    #[test]
    fn runs_give_the_bond_by_bond_energy_and_gradient_to_rounding() {
        use super::Parameter;
        use crate::cell::Polynomial;
        use crate::model::law::Kernel;
        let cells = [(ready::kagome(), [11, 7]), (wide(), [10, 9]), (wide(), [3, 3])];
        let cases = [
            Laws::Harmonic,
            Laws::HarmonicOverridden,
            Laws::QuarticOverridden,
            Laws::PolynomialShared,
            Laws::PolynomialPerBond,
            Laws::Mixed,
        ];
        // Whether runs whose `k` (first index 0) and whose coefficients (1) are shared (second
        // index 0) and per bond (1) were met.
        let mut seen = [[false; 2]; 2];
        for (cell, size) in &cells {
            for boundary in [Boundary::Periodic, Boundary::Free] {
                let patch = Patch::new(cell, *size, boundary).unwrap();
                let springs = patch.bonds().len();
                for laws in cases {
                    let mut rng = SplitMix(springs as u64);
                    let random_polynomial = |rng: &mut SplitMix| {
                        let c = [rng.range(0.5, 2.0), rng.symmetric(), rng.symmetric(), rng.symmetric(), 0.5];
                        Polynomial::new(&c).unwrap()
                    };
                    let one = random_polynomial(&mut rng);
                    let mut builder = NetworkModel::builder(&patch);
                    for p in 0..springs {
                        let (k, l0) = (rng.range(0.5, 2.0), rng.range(0.5, 1.5));
                        builder = match laws {
                            Laws::Harmonic => builder,
                            Laws::HarmonicOverridden => builder.spring_constant(p, k).rest_length(p, l0),
                            Laws::QuarticOverridden => {
                                builder.law(Law::Quartic).spring_constant(p, k).rest_length(p, l0)
                            }
                            Laws::PolynomialShared => builder.law(one).spring_constant(p, k),
                            Laws::PolynomialPerBond => {
                                builder.spring_law(p, random_polynomial(&mut rng)).rest_length(p, l0)
                            }
                            Laws::Mixed if p % 3 == 0 => builder.spring_law(p, one),
                            Laws::Mixed => builder,
                        };
                    }
                    let model = builder.build().unwrap();
                    let expected = match laws {
                        Laws::Harmonic | Laws::HarmonicOverridden => Kernel::Harmonic,
                        Laws::QuarticOverridden => Kernel::Quartic,
                        _ => Kernel::Polynomial,
                    };
                    assert_eq!(model.law, expected, "{laws:?}");
                    for run in model.stencil.kinds.iter().flat_map(|r| &r.runs) {
                        let per_bond =
                            |j: usize| usize::from(matches!(run.parameters[j], Parameter::PerBond(_)));
                        seen[0][per_bond(0)] = true;
                        if model.law == Kernel::Polynomial {
                            (2..super::PARAMETERS).for_each(|j| seen[1][per_bond(j)] = true);
                        }
                    }
                    let x: Vec<f64> = model.reference().iter().map(|x| x + 0.1 * rng.symmetric()).collect();
                    let n = x.len();
                    // The reference at the same level: the rotors' sines and cosines differ
                    // between levels (2 ulp).
                    let bond_by_bond = || {
                        let trig = model.trig(&x);
                        let (mut reference, mut magnitude, mut terms) =
                            (vec![0.0; n], vec![0.0; n], vec![0usize; n]);
                        let (mut energy, mut energies) = (0.0, 0.0);
                        let mut add = |g: &crate::model::bonds::Group, i: usize, out: &[f64]| {
                            energy += out[0];
                            energies += out[0].abs();
                            for (&d, &v) in g.bond_dofs(i).iter().zip(&out[1..]) {
                                reference[d] += v;
                                magnitude[d] += v.abs();
                                terms[d] += 1;
                            }
                        };
                        match model.law {
                            Kernel::Harmonic => each_bond!(
                                &model,
                                crate::kernel::harmonic::Law,
                                [8, 9, 10],
                                &x,
                                &trig,
                                EnergyGradient,
                                [5, 4, 3],
                                |g, i, out| { add(g, i, out) }
                            ),
                            Kernel::Quartic => each_bond!(
                                &model,
                                crate::kernel::quartic::Law,
                                [8, 9, 10],
                                &x,
                                &trig,
                                EnergyGradient,
                                [5, 4, 3],
                                |g, i, out| { add(g, i, out) }
                            ),
                            Kernel::Polynomial => each_bond!(
                                &model,
                                crate::kernel::polynomial::Law,
                                [13, 14, 15],
                                &x,
                                &trig,
                                EnergyGradient,
                                [5, 4, 3],
                                |g, i, out| { add(g, i, out) }
                            ),
                        }
                        (energy, energies, reference, magnitude, terms)
                    };
                    for level in Level::ALL {
                        let Some((e, grad, alone, (energy, energies, reference, magnitude, terms))) =
                            with_level(level, || {
                                let mut grad = vec![f64::NAN; n];
                                let e = model.energy_and_gradient_into(&x, &mut grad);
                                (e, grad, model.gradient(&x), bond_by_bond())
                            })
                        else {
                            continue;
                        };
                        let what = format!("{size:?} {boundary:?} {laws:?} {level:?}");
                        assert_eq!(grad, alone, "{what}: fused and alone");
                        let bound = 2.0 * springs as f64 * f64::EPSILON * energies;
                        assert!((e - energy).abs() <= bound, "{what}: {e} vs {energy} (bound {bound:e})");
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
        assert_eq!(seen, [[true, true], [true, true]], "every parameter layout");
    }
}
