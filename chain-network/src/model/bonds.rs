//! The bonds of a model grouped by type, as structs of arrays, and the loop that evaluates a
//! generated kernel ([`crate::kernel`]) on every bond of a group; the sparse patterns of the
//! tangent stiffness and the compatibility matrix, with where each bond's entries go.

use chain_core::allocation::{AllocationError, try_grow};
use chain_core::model::Pattern;

/// A bond type (the kernel modules `joint_joint`, `joint_rotor`, `rotor_rotor`), in the order
/// of `NetworkModel::groups`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    JointJoint,
    JointRotor,
    RotorRotor,
}

impl Kind {
    /// The bond's degrees of freedom.
    pub fn dofs(self) -> usize {
        match self {
            Kind::JointJoint => 4,
            Kind::JointRotor => 3,
            Kind::RotorRotor => 2,
        }
    }

    /// The kernel's arguments before a law's own parameters (`BondKind::args`).
    pub fn args(self) -> usize {
        match self {
            Kind::JointJoint => 8,
            Kind::JointRotor => 9,
            Kind::RotorRotor => 10,
        }
    }
}

/// The bonds of one type: per bond, its spring (the patch's bond index), its degrees of freedom
/// in the kernel's order (unused slots 0), the offset `(ox, oy)`, the rotor lengths
/// `[r1, r2]` (0 for a joint end), `k` and `l0`; for the polynomial kernel its coefficients
/// `c2 .. c6` (empty for the others).
#[derive(Debug)]
pub(super) struct Group {
    pub kind: Kind,
    pub spring: Vec<usize>,
    pub dofs: Vec<[usize; 4]>,
    pub offset: Vec<[f64; 2]>,
    pub radius: Vec<[f64; 2]>,
    pub k: Vec<f64>,
    pub l0: Vec<f64>,
    pub coefficients: Vec<[f64; 5]>,
}

impl Group {
    pub fn new(kind: Kind) -> Self {
        Self {
            kind,
            spring: Vec::new(),
            dofs: Vec::new(),
            offset: Vec::new(),
            radius: Vec::new(),
            k: Vec::new(),
            l0: Vec::new(),
            coefficients: Vec::new(),
        }
    }

    pub fn len(&self) -> usize {
        self.spring.len()
    }

    /// Room for `bonds` bonds in every array (`coefficients` too when `with_coefficients`),
    /// exactly, before they are pushed.
    pub fn try_reserve(&mut self, bonds: usize, with_coefficients: bool) -> Result<(), AllocationError> {
        let what = "the model's bonds";
        try_grow(&mut self.spring, bonds, what)?;
        try_grow(&mut self.dofs, bonds, what)?;
        try_grow(&mut self.offset, bonds, what)?;
        try_grow(&mut self.radius, bonds, what)?;
        try_grow(&mut self.k, bonds, what)?;
        try_grow(&mut self.l0, bonds, what)?;
        if with_coefficients {
            try_grow(&mut self.coefficients, bonds, what)?;
        }
        Ok(())
    }

    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(&self.spring[..])
            + size_of_val(&self.dofs[..])
            + size_of_val(&self.offset[..])
            + size_of_val(&self.radius[..])
            + size_of_val(&self.k[..])
            + size_of_val(&self.l0[..])
            + size_of_val(&self.coefficients[..])
    }

    /// The degrees of freedom of bond `i`, in the kernel's order.
    pub fn bond_dofs(&self, i: usize) -> &[usize] {
        &self.dofs[i][..self.kind.dofs()]
    }

    /// The kernel's arguments for bond `i` at `x` (`trig`: each rotor's `[sin, cos]`, through
    /// `rotor_of`), in the order of the kernel module's table.
    #[inline(always)]
    pub fn args<const A: usize>(&self, i: usize, x: &[f64], trig: &[[f64; 2]], rotor_of: &[u32]) -> [f64; A] {
        let d = self.dofs[i];
        let [ox, oy] = self.offset[i];
        let [r1, r2] = self.radius[i];
        let (k, l0) = (self.k[i], self.l0[i]);
        let sc = |dof: usize| trig[rotor_of[dof] as usize];
        let mut a = [0.0; A];
        match self.kind {
            Kind::JointJoint => a[..8].copy_from_slice(&[x[d[0]], x[d[1]], x[d[2]], x[d[3]], ox, oy, k, l0]),
            Kind::JointRotor => {
                let [s2, c2] = sc(d[2]);
                a[..9].copy_from_slice(&[x[d[0]], x[d[1]], s2, c2, ox, oy, r2, k, l0]);
            }
            Kind::RotorRotor => {
                let ([s1, c1], [s2, c2]) = (sc(d[0]), sc(d[1]));
                a[..10].copy_from_slice(&[s1, c1, s2, c2, ox, oy, r1, r2, k, l0]);
            }
        }
        // A law's own parameters (the polynomial's coefficients) come last; `A` is a constant,
        // so the other kernels compile without this.
        let base = self.kind.args();
        if A > base {
            a[base..].copy_from_slice(&self.coefficients[i][..A - base]);
        }
        a
    }
}

/// Evaluates kernel `$f` (a kernel of every bond type of the law's kernels `$K`, a
/// [`LawKernels`](crate::kernel::LawKernels)) on every bond of every group of `$model` at `$x`,
/// calling `$body` with the group, the bond's index in it and the outputs as a slice. `$m` lists
/// the kernel's output count per bond type (joint-joint, joint-rotor, rotor-rotor), `$a` the law's
/// argument counts (`LawKernels<A1, A2, A3>`).
macro_rules! each_bond {
    ($model:expr, $K:ty, [$a1:tt, $a2:tt, $a3:tt], $x:expr, $trig:expr, $f:ident, [$m1:literal, $m2:literal, $m3:literal], |$g:ident, $i:ident, $out:ident| $body:block) => {{
        use $crate::kernel::{BondFn, BondKernels, LawKernels};
        let model = $model;
        let (x, trig): (&[f64], &[[f64; 2]]) = ($x, $trig);
        let [jj, jr, rr] = &model.groups;
        for ($g, which) in [(jj, 0), (jr, 1), (rr, 2)] {
            for $i in 0..$g.len() {
                let outputs: &[f64] =
                    match which {
                        0 => &<<<$K as LawKernels<$a1, $a2, $a3>>::JointJoint as BondKernels<
                            $a1,
                            4,
                            5,
                            10,
                            15,
                        >>::$f as BondFn<$a1, $m1>>::eval::<f64>(
                            $g.args::<$a1>($i, x, trig, &model.rotor_of),
                        ),
                        1 => &<<<$K as LawKernels<$a1, $a2, $a3>>::JointRotor as BondKernels<
                            $a2,
                            3,
                            4,
                            6,
                            10,
                        >>::$f as BondFn<$a2, $m2>>::eval::<f64>(
                            $g.args::<$a2>($i, x, trig, &model.rotor_of),
                        ),
                        _ => &<<<$K as LawKernels<$a1, $a2, $a3>>::RotorRotor as BondKernels<
                            $a3,
                            2,
                            3,
                            3,
                            6,
                        >>::$f as BondFn<$a3, $m3>>::eval::<f64>(
                            $g.args::<$a3>($i, x, trig, &model.rotor_of),
                        ),
                    };
                let $out = outputs;
                $body
            }
        }
    }};
}
pub(super) use each_bond;

/// The upper triangle of the tangent stiffness: its pattern (every diagonal entry, and every
/// pair of degrees of freedom that share a bond), and per group the value slot of each bond's
/// block entry, bond after bond, upper triangle row by row in the kernel's order.
#[derive(Debug)]
pub(super) struct Upper {
    pub row_starts: Vec<usize>,
    pub columns: Vec<usize>,
    pub slots: [Vec<usize>; 3],
}

impl Upper {
    pub fn new(dof: usize, groups: &[Group; 3]) -> Self {
        let mut neighbours: Vec<Vec<usize>> = (0..dof).map(|i| vec![i]).collect();
        for g in groups {
            for i in 0..g.len() {
                let d = g.bond_dofs(i);
                for (a, &da) in d.iter().enumerate() {
                    for &db in &d[a..] {
                        neighbours[da.min(db)].push(da.max(db));
                    }
                }
            }
        }
        let mut row_starts = Vec::with_capacity(dof + 1);
        let mut columns = Vec::new();
        row_starts.push(0);
        for row in &mut neighbours {
            row.sort_unstable();
            row.dedup();
            columns.extend_from_slice(row);
            row_starts.push(columns.len());
        }
        let slot = |i: usize, j: usize| {
            let (r, c) = (i.min(j), i.max(j));
            let row = &columns[row_starts[r]..row_starts[r + 1]];
            row_starts[r] + row.binary_search(&c).expect("every bond pair is in the pattern")
        };
        let slots = [0, 1, 2].map(|k| {
            let g = &groups[k];
            let mut s = Vec::with_capacity(g.len() * 10);
            for i in 0..g.len() {
                let d = g.bond_dofs(i);
                for a in 0..d.len() {
                    for b in a..d.len() {
                        s.push(slot(d[a], d[b]));
                    }
                }
            }
            s
        });
        Self { row_starts, columns, slots }
    }

    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(&self.row_starts[..])
            + size_of_val(&self.columns[..])
            + self.slots.iter().map(|s| size_of_val(&s[..])).sum::<usize>()
    }

    pub fn pattern(&self) -> Pattern<'_> {
        Pattern {
            columns_count: self.row_starts.len() - 1,
            row_starts: &self.row_starts,
            columns: &self.columns,
        }
    }
}

/// The compatibility matrix's pattern (row `p`: spring `p`'s degrees of freedom, ascending) and
/// per group the value slot of each bond's entries in the kernel's order.
#[derive(Debug)]
pub(super) struct Rows {
    pub row_starts: Vec<usize>,
    pub columns: Vec<usize>,
    pub columns_count: usize,
    pub slots: [Vec<usize>; 3],
}

impl Rows {
    pub fn new(dof: usize, springs: usize, groups: &[Group; 3]) -> Self {
        let mut rows: Vec<Vec<usize>> = vec![Vec::new(); springs];
        for g in groups {
            for i in 0..g.len() {
                let mut d = g.bond_dofs(i).to_vec();
                d.sort_unstable();
                rows[g.spring[i]] = d;
            }
        }
        let mut row_starts = Vec::with_capacity(springs + 1);
        let mut columns = Vec::new();
        row_starts.push(0);
        for row in &rows {
            columns.extend_from_slice(row);
            row_starts.push(columns.len());
        }
        let slots = [0, 1, 2].map(|k| {
            let g = &groups[k];
            let mut s = Vec::with_capacity(g.len() * 4);
            for i in 0..g.len() {
                let p = g.spring[i];
                let row = &columns[row_starts[p]..row_starts[p + 1]];
                for d in g.bond_dofs(i) {
                    s.push(row_starts[p] + row.binary_search(d).expect("the bond's own columns"));
                }
            }
            s
        });
        Self { row_starts, columns, columns_count: dof, slots }
    }

    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(&self.row_starts[..])
            + size_of_val(&self.columns[..])
            + self.slots.iter().map(|s| size_of_val(&s[..])).sum::<usize>()
    }

    pub fn pattern(&self) -> Pattern<'_> {
        Pattern { columns_count: self.columns_count, row_starts: &self.row_starts, columns: &self.columns }
    }
}
