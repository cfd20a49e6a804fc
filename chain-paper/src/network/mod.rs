//! Figures of periodic networks (issue 33) for the `network` command: drawings of a patch
//! ([`NetworkDrawing`], rendered by `render`'s `network` part), the bands along a path, the
//! phase of `det Q(k)` over the zone, a strip's spectrum with its edge zero modes, a zero mode's
//! arrows, the polarization phase diagram ([`diagram`]), and issue 36's demonstrations
//! ([`demonstration`]: the paper's chain declared as a network; [`transition_figure`]: a
//! transition wave in a bistable chain; [`wall_figure`]: a moving domain wall between two
//! polarizations in coupled chains, and its frames as a GIF). Every figure is a [`Figure`](crate::Figure) of
//! the paper's model, rendered to PNG and SVG by [`crate::render::render`].

pub mod demonstration;
pub mod diagram;
mod figures;
mod transition;
mod wall;

pub use figures::{bands_figure, cell_figure};
pub use transition::transition_figure;
pub use wall::{wall_figure, wall_frame, write_gif};

use std::fmt::Write as _;

use chain_network::patch::Patch;
use chain_network::{Cell, NodeKind};

/// A patch of a network, ready to draw. Lengths in the cell's units.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct NetworkDrawing {
    /// Title above the drawing.
    pub title: String,
    /// Bonds, end to end.
    pub bonds: Vec<((f64, f64), (f64, f64))>,
    /// Rotor arms, pivot to tip.
    pub arms: Vec<((f64, f64), (f64, f64))>,
    /// Joints and rotor tips.
    pub nodes: Vec<(f64, f64)>,
    /// The outline of cell (0, 0) (a parallelogram; a segment in one dimension).
    pub cell: Vec<(f64, f64)>,
    /// Arrows: start and displacement, the largest of length 1.
    pub arrows: Vec<((f64, f64), (f64, f64))>,
    /// Per arm, a signed tilt in `[-1, 1]` that colours it (blue positive, red negative, grey
    /// at zero: the two polarizations of [`wall_figure`]); empty: every arm black.
    pub arm_tilts: Vec<f64>,
}

impl NetworkDrawing {
    /// The bonds, rotors and nodes of `patch` (every bond drawn from its `from` end, so a bond
    /// that wraps around a periodic patch is drawn leaving it), with cell (0, 0) outlined.
    pub fn of_patch(title: impl Into<String>, patch: &Patch) -> Self {
        let cell = patch.cell();
        let mut d = NetworkDrawing { title: title.into(), ..Self::default() };
        let [n1, n2] = patch.cells();
        for c2 in 0..n2 {
            for c1 in 0..n1 {
                for (n, node) in cell.nodes().iter().enumerate() {
                    let p = patch.point([c1, c2], n);
                    d.nodes.push((p[0], p[1]));
                    if let NodeKind::Rotor { pivot, .. } = node.kind {
                        let s = cell.shift([c1 as i64, c2 as i64]);
                        d.arms.push(((pivot[0] + s[0], pivot[1] + s[1]), (p[0], p[1])));
                    }
                }
            }
        }
        for pb in patch.bonds() {
            let from = patch.point(pb.from_cell, cell.bonds()[pb.bond].from);
            let v = cell.bond_vector(pb.bond);
            d.bonds.push(((from[0], from[1]), (from[0] + v[0], from[1] + v[1])));
        }
        d.cell = cell_outline(cell);
        d
    }

    /// The same drawing with `mode` (one value per degree of freedom of the patch) as arrows on
    /// the nodes: a joint's `(dx, dy)`, a rotor tip's `r dphi` along its tangent.
    pub fn with_mode(mut self, patch: &Patch, mode: &[f64]) -> Self {
        let cell = patch.cell();
        let [n1, n2] = patch.cells();
        let mut arrows = Vec::new();
        for c2 in 0..n2 {
            for c1 in 0..n1 {
                for (n, node) in cell.nodes().iter().enumerate() {
                    let col = patch.column([c1, c2], cell.dof_offset(n));
                    let (d0, d1) = node.directions();
                    let mut v = [d0[0] * mode[col], d0[1] * mode[col]];
                    if let Some(d1) = d1 {
                        v[0] += d1[0] * mode[col + 1];
                        v[1] += d1[1] * mode[col + 1];
                    }
                    let p = patch.point([c1, c2], n);
                    arrows.push(((p[0], p[1]), (v[0], v[1])));
                }
            }
        }
        let largest = arrows.iter().map(|(_, v)| v.0.hypot(v.1)).fold(0.0, f64::max);
        if largest > 0.0 {
            for a in &mut arrows {
                a.1 = (a.1.0 / largest, a.1.1 / largest);
            }
        }
        self.arrows = arrows;
        self
    }

    /// The drawing's data: one line per part, `part,index,x0,y0,x1,y1`.
    pub fn csv(&self) -> String {
        let mut csv = String::from("part,index,x0,y0,x1,y1\n");
        let mut row = |part: &str, i: usize, a: (f64, f64), b: (f64, f64)| {
            writeln!(csv, "{part},{i},{},{},{},{}", a.0, a.1, b.0, b.1).expect("writing to a String");
        };
        for (i, &(a, b)) in self.bonds.iter().enumerate() {
            row("bond", i, a, b);
        }
        for (i, &(a, b)) in self.arms.iter().enumerate() {
            row("arm", i, a, b);
        }
        for (i, &p) in self.nodes.iter().enumerate() {
            row("node", i, p, p);
        }
        for (i, &(p, v)) in self.arrows.iter().enumerate() {
            row("arrow", i, p, (p.0 + v.0, p.1 + v.1));
        }
        for (i, &p) in self.cell.iter().enumerate() {
            row("cell", i, p, p);
        }
        csv
    }
}

/// The corners of cell (0, 0): `0, a1, a1 + a2, a2` (a segment `0, a1` in one dimension).
fn cell_outline(cell: &Cell) -> Vec<(f64, f64)> {
    let a1 = cell.lattice_vector(0);
    if cell.dimension() == 1 {
        return vec![(0.0, 0.0), (a1[0], a1[1])];
    }
    let a2 = cell.lattice_vector(1);
    vec![(0.0, 0.0), (a1[0], a1[1]), (a1[0] + a2[0], a1[1] + a2[1]), (a2[0], a2[1])]
}
