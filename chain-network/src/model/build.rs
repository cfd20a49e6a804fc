//! Building a [`NetworkModel`] from a patch: the law, node masses and overrides (impurities: any
//! bond's constant or rest length, any node's mass), checked, and the bonds grouped by type.

use super::NetworkModel;
use super::bonds::{Group, Kind};
use super::kernels::Kernels;
use super::law::{IntoBondLaw, Kernel, kernel_of};
use super::stencil::Stencil;
use crate::cell::{BondLaw, NodeKind};
use crate::error::NetworkError;
use crate::patch::Patch;
use chain_core::allocation::{try_filled, try_vec};
use std::collections::HashMap;
use std::sync::OnceLock;

/// A builder for a [`NetworkModel`]; see [`NetworkModel::builder`]. Overrides name a spring by
/// its index in the patch's bonds (`Patch::bonds`) and a node by its cell and its index in the
/// unit cell.
#[derive(Clone, Debug)]
pub struct NetworkModelBuilder<'p, 'c> {
    patch: &'p Patch<'c>,
    law: Option<BondLaw>,
    spring_laws: Vec<(usize, BondLaw)>,
    kernels: Option<super::kernels::Kernels>,
    mass: f64,
    node_masses: Vec<([usize; 2], usize, f64)>,
    constants: Vec<(usize, f64)>,
    rest_lengths: Vec<(usize, f64)>,
}

/// `Ok` if `value` is finite and positive; the error names the parameter and the value.
fn positive(what: &'static str, index: String, value: f64) -> Result<f64, NetworkError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(NetworkError::Argument {
            what,
            problem: format!("{index}: {value} is not a finite positive number"),
        })
    }
}

impl<'p, 'c> NetworkModelBuilder<'p, 'c> {
    pub(super) fn new(patch: &'p Patch<'c>) -> Self {
        Self {
            patch,
            law: None,
            spring_laws: Vec::new(),
            kernels: None,
            mass: 1.0,
            node_masses: Vec::new(),
            constants: Vec::new(),
            rest_lengths: Vec::new(),
        }
    }

    /// The spring law of every bond (default: each bond's law in the cell, harmonic unless the
    /// cell says otherwise): a cell's [`BondLaw`] or chain-core's `Law`.
    pub fn law(mut self, law: impl IntoBondLaw) -> Self {
        self.law = Some(law.into_bond_law());
        self
    }

    /// The spring law of spring `p` (the patch's bond `p`), over [`law`](Self::law) and the
    /// cell. Quartic springs cannot be mixed with others (the build's error says which).
    pub fn spring_law(mut self, p: usize, law: impl IntoBondLaw) -> Self {
        self.spring_laws.push((p, law.into_bond_law()));
        self
    }

    /// Evaluates every bond with the kernels `K` instead of the checked-in ones of the law: the
    /// `#[rotor_network]` attribute's, rendered at compile time for its law (which may be a
    /// custom one; [`NetworkModel::spring_law`] then still reports the builder's laws). Not public
    /// API: the attribute's generated code calls it through `rotor_chain::__private`.
    #[doc(hidden)]
    pub fn kernels<K: crate::kernel::LawKernels>(mut self) -> Self {
        self.kernels = Some(Kernels::of::<K>());
        self
    }

    /// The mass `M` of every node (default 1): a joint's inertia, `M r^2` a rotor's.
    pub fn mass(mut self, mass: f64) -> Self {
        self.mass = mass;
        self
    }

    /// The mass of node `node` (its index in the unit cell) in cell `cell`.
    pub fn node_mass(mut self, cell: [usize; 2], node: usize, mass: f64) -> Self {
        self.node_masses.push((cell, node, mass));
        self
    }

    /// The spring constant of spring `p` (the patch's bond `p`).
    pub fn spring_constant(mut self, p: usize, k: f64) -> Self {
        self.constants.push((p, k));
        self
    }

    /// The rest length of spring `p` (the patch's bond `p`).
    pub fn rest_length(mut self, p: usize, l0: f64) -> Self {
        self.rest_lengths.push((p, l0));
        self
    }

    /// The model; an error names the first parameter out of range (not finite and positive) or
    /// the override whose spring, cell or node does not exist, with its numbers.
    pub fn build(self) -> Result<NetworkModel, NetworkError> {
        let patch = self.patch;
        let cell = patch.cell();
        let [n1, n2] = patch.cells();
        let nodes = cell.nodes();
        let springs_count = patch.bonds().len();
        positive("mass", "every node".into(), self.mass)?;
        // Every array sized by the patch is allocated fallibly (`NetworkError::OutOfMemory`).
        let mut masses = try_filled(patch.cell_count() * nodes.len(), self.mass, "the node masses")?;
        for &(c, n, m) in &self.node_masses {
            if c[0] >= n1 || c[1] >= n2 || n >= nodes.len() {
                return Err(NetworkError::Argument {
                    what: "node mass",
                    problem: format!(
                        "cell {c:?}, node {n}: the patch has {n1} x {n2} cells of {} nodes",
                        nodes.len()
                    ),
                });
            }
            masses[patch.cell_index(c) * nodes.len() + n] =
                positive("node mass", format!("cell {c:?}, node {n}"), m)?;
        }
        let mut springs: Vec<[f64; 2]> = try_vec(springs_count, "the springs' constants and rest lengths")?;
        springs.extend(
            patch.bonds().iter().map(|pb| [cell.bonds()[pb.bond].k, cell.bonds()[pb.bond].rest_length]),
        );
        for (what, list, slot) in
            [("spring constant", &self.constants, 0), ("rest length", &self.rest_lengths, 1)]
        {
            for &(p, value) in list {
                if p >= springs_count {
                    return Err(NetworkError::Argument {
                        what,
                        problem: format!("spring {p}: the patch has {springs_count} springs"),
                    });
                }
                springs[p][slot] = positive(what, format!("spring {p}"), value)?;
            }
        }

        // Each spring's law, looked up rather than listed: a list would hold 48 B per spring
        // during the build (a million-cell patch's peak).
        let mut overrides: HashMap<usize, BondLaw> = HashMap::new();
        for &(p, law) in &self.spring_laws {
            if p >= springs_count {
                return Err(NetworkError::Argument {
                    what: "spring law",
                    problem: format!("spring {p}: the patch has {springs_count} springs"),
                });
            }
            overrides.insert(p, law);
        }
        let law_of = |p: usize| {
            overrides
                .get(&p)
                .copied()
                .unwrap_or_else(|| self.law.unwrap_or(cell.bonds()[patch.bonds()[p].bond].law))
        };
        let (kernel, coefficients) = kernel_of(springs_count, law_of)?;

        let dof = patch.dof();
        let mut inertia = try_filled(dof, 0.0, "the inertia")?;
        let mut reference = try_filled(dof, 0.0, "the reference coordinates")?;
        let mut rotor_of = try_filled(dof, u32::MAX, "the rotor index")?;
        let rotors_per_cell = nodes.iter().filter(|n| matches!(n.kind, NodeKind::Rotor { .. })).count();
        let mut rotors = try_vec(rotors_per_cell * patch.cell_count(), "the rotor index")?;
        for c2 in 0..n2 {
            for c1 in 0..n1 {
                let c = [c1, c2];
                let shift = cell.shift([c1 as i64, c2 as i64]);
                for (n, node) in nodes.iter().enumerate() {
                    let d = patch.column(c, cell.dof_offset(n));
                    let m = masses[patch.cell_index(c) * nodes.len() + n];
                    match node.kind {
                        NodeKind::Joint { position } => {
                            reference[d] = position[0] + shift[0];
                            reference[d + 1] = position[1] + shift[1];
                            inertia[d] = m;
                            inertia[d + 1] = m;
                        }
                        NodeKind::Rotor { length, angle, .. } => {
                            reference[d] = angle;
                            inertia[d] = m * length * length;
                            rotor_of[d] =
                                u32::try_from(rotors.len()).map_err(|_| NetworkError::Argument {
                                    what: "patch",
                                    problem: format!("more than {} rotors", u32::MAX),
                                })?;
                            rotors.push(d);
                        }
                    }
                }
            }
        }

        let mut groups =
            [Group::new(Kind::JointJoint), Group::new(Kind::JointRotor), Group::new(Kind::RotorRotor)];
        let joint = |n: usize| matches!(nodes[n].kind, NodeKind::Joint { .. });
        let mut per_kind = [0; 3];
        for pb in patch.bonds() {
            let bond = &cell.bonds()[pb.bond];
            per_kind[usize::from(!joint(bond.from)) + usize::from(!joint(bond.to))] += 1;
        }
        for (g, &bonds) in groups.iter_mut().zip(&per_kind) {
            g.try_reserve(bonds, !coefficients.is_empty())?;
        }
        let anchor = |n: usize, c: [usize; 2]| {
            let s = cell.shift([c[0] as i64, c[1] as i64]);
            match nodes[n].kind {
                NodeKind::Joint { .. } => ([s[0], s[1]], 0.0),
                NodeKind::Rotor { pivot, length, .. } => ([pivot[0] + s[0], pivot[1] + s[1]], length),
            }
        };
        for (p, pb) in patch.bonds().iter().enumerate() {
            let bond = &cell.bonds()[pb.bond];
            // The shift that takes the wrapped `to` cell back to the unwrapped one (zero on a free
            // patch): the bond vector is `to + wrap - from`.
            let unwrapped = [pb.from_cell[0] as i64 + bond.cell[0], pb.from_cell[1] as i64 + bond.cell[1]];
            let (su, st) = (cell.shift(unwrapped), cell.shift([pb.to_cell[0] as i64, pb.to_cell[1] as i64]));
            let wrap = [su[0] - st[0], su[1] - st[1]];
            let (df, dt) = (
                patch.column(pb.from_cell, cell.dof_offset(bond.from)),
                patch.column(pb.to_cell, cell.dof_offset(bond.to)),
            );
            let ((pf, rf), (pt, rt)) = (anchor(bond.from, pb.from_cell), anchor(bond.to, pb.to_cell));
            let (kind, dofs, offset, radius) = match (joint(bond.from), joint(bond.to)) {
                (true, true) => (Kind::JointJoint, [df, df + 1, dt, dt + 1], wrap, [0.0, 0.0]),
                (true, false) => {
                    (Kind::JointRotor, [df, df + 1, dt, 0], [pt[0] + wrap[0], pt[1] + wrap[1]], [0.0, rt])
                }
                // Read from the joint end: the vector reverses, so the rotor's pivot minus the wrap.
                (false, true) => {
                    (Kind::JointRotor, [dt, dt + 1, df, 0], [pf[0] - wrap[0], pf[1] - wrap[1]], [0.0, rf])
                }
                (false, false) => (
                    Kind::RotorRotor,
                    [df, dt, 0, 0],
                    [pt[0] + wrap[0] - pf[0], pt[1] + wrap[1] - pf[1]],
                    [rf, rt],
                ),
            };
            let g = &mut groups[kind as usize];
            g.spring.push(p);
            g.dofs.push(dofs);
            g.offset.push(offset);
            g.radius.push(radius);
            g.k.push(springs[p][0]);
            g.l0.push(springs[p][1]);
            if let Some(c) = coefficients.get(p) {
                g.coefficients.push(*c);
            }
        }
        let stencil = Stencil::new(&groups, cell.dof(), patch.cell_count(), |j| rotor_of[j] != u32::MAX)?;
        let kernels = self.kernels.unwrap_or_else(|| match kernel {
            Kernel::Harmonic => Kernels::of::<crate::kernel::harmonic::Law>(),
            Kernel::Quartic => Kernels::of::<crate::kernel::quartic::Law>(),
            Kernel::Polynomial => Kernels::with_arguments::<crate::kernel::polynomial::Law, 13, 14, 15>(),
        });
        Ok(NetworkModel {
            law: kernel,
            kernels,
            inertia,
            reference,
            rotor_of,
            rotors,
            springs,
            groups,
            stencil,
            length_scale: cell.length_scale(),
            stiffness: OnceLock::new(),
            compatibility: OnceLock::new(),
        })
    }
}
