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
}

/// The runs of one bond type, with every bond's `k` and `l0` in run order.
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
            let mut runs = Runs { runs: Vec::new(), k: Vec::with_capacity(g.len()), l0: Vec::with_capacity(g.len()) };
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
                        _ => runs.runs.push(Run { len: 1, ends, grads, constants, param: runs.k.len() }),
                    }
                    runs.k.push(g.k[i]);
                    runs.l0.push(g.l0[i]);
                    last = Some((ends, grads, constants));
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
        // A tile of cells at a time, slot by slot, so the tile's part of `x` stays in the L1
        // cache while its slots are copied out (whole-array passes per slot were 3x slower).
        for start in (0..cells).step_by(TILE) {
            let end = (start + TILE).min(cells);
            let tile = &x[start * d..end * d];
            for (j, column) in coordinates.chunks_exact_mut(cells).enumerate() {
                for (v, &x) in column[start..end].iter_mut().zip(tile.iter().skip(j).step_by(d)) {
                    *v = x;
                }
            }
        }
        for (r, &j) in self.rotor_slots.iter().enumerate() {
            let (sin, cos) = trig[2 * r * cells..(2 * r + 2) * cells].split_at_mut(cells);
            chain_core::simd::sin_cos_into(&coordinates[j * cells..(j + 1) * cells], sin, cos);
        }
    }

    /// Writes the gradient `grad` (this layout) into `out` (the patch's order).
    #[inline(always)]
    pub fn scatter(&self, grad: &[f64], out: &mut [f64]) {
        let (cells, d) = (self.cells, self.per_cell);
        for start in (0..cells).step_by(TILE) {
            let end = (start + TILE).min(cells);
            let tile = &mut out[start * d..end * d];
            for (j, column) in grad.chunks_exact(cells).enumerate() {
                for (o, &g) in tile.iter_mut().skip(j).step_by(d).zip(&column[start..end]) {
                    *o = g;
                }
            }
        }
    }
}

/// Cells per tile of the transposes (a tile of a 6-value cell is 1.5 KB).
const TILE: usize = 32;
