//! The Verlet comparison of docs/benchmarks.md ("Networks in motion"): a periodic kagome patch
//! (256 x 256 cells, 393 216 degrees of freedom, unless an argument says otherwise), started
//! `0.01 sin(0.37 i)` off its reference at rest, stepped `steps` times with velocity Verlet
//! (`dt = 0.01`, unit masses) by chain-core's `Verlet` on the `NetworkModel`, timed, and the
//! energy `T + V` after the steps printed to 17 digits. With a folder, the network is written
//! there as `.npy` files for `benches/network_numba.py` and `benches/network_jax.py`, which step
//! the same network and print the same numbers:
//!
//! - `first.npy`, `second.npy` (int64): per bond, the x degree of freedom of its two joints (y
//!   is the next one);
//! - `offset.npy` (bonds x 2): what the bond vector adds to `r_second - r_first` (the lattice
//!   shift of a bond that wraps round the torus, else 0);
//! - `k.npy`, `l0.npy`, `x0.npy` (the start), `inertia.npy`; `steps.npy` and `dt.npy`.
//!
//! `cargo run --release -p rotor-chain-network --example verlet_export -- [cells] [steps] [folder]`

use chain_core::integrate::{Phase, Verlet};
use chain_core::{Potential, SpringNetwork};
use chain_network::NetworkModel;
use chain_network::cell::{NodeKind, ready};
use chain_network::patch::{Boundary, Patch};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// Writes `data` as a `.npy` file (format 1.0) of `shape` with numpy's type string `dtype`
/// (`<f8`, `<i8`); `bytes` turns one value into its little-endian bytes.
fn npy<T: Copy>(
    path: &Path,
    dtype: &str,
    shape: &[usize],
    data: &[T],
    bytes: fn(T) -> [u8; 8],
) -> std::io::Result<()> {
    let shape = match shape {
        [n] => format!("({n},)"),
        _ => format!("({})", shape.iter().map(|s| s.to_string()).collect::<Vec<_>>().join(", ")),
    };
    let mut header = format!("{{'descr': '{dtype}', 'fortran_order': False, 'shape': {shape}, }}");
    // Magic (6), version (2) and length (2), then the header padded with spaces so the data
    // start on a multiple of 64 bytes, ending in a newline.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    out.write_all(b"\x93NUMPY\x01\x00")?;
    out.write_all(&u16::try_from(header.len()).expect("a short header").to_le_bytes())?;
    out.write_all(header.as_bytes())?;
    for &v in data {
        out.write_all(&bytes(v))?;
    }
    out.flush()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().map(|s| s.parse()).transpose()?.unwrap_or(256);
    let steps: usize = args.next().map(|s| s.parse()).transpose()?.unwrap_or(100);
    let folder = args.next();
    let dt = 0.01;
    let cell = ready::kagome();
    let patch = Patch::new(&cell, [n, n], Boundary::Periodic)?;
    let model = NetworkModel::builder(&patch).build()?;
    let dof = model.dof_count();
    let mut x0 = model.reference();
    for (i, x) in x0.iter_mut().enumerate() {
        *x += 0.01 * (i as f64 * 0.37).sin();
    }

    if let Some(folder) = &folder {
        let folder = Path::new(folder);
        std::fs::create_dir_all(folder)?;
        let m = patch.bonds().len();
        let (mut first, mut second, mut offset, mut k, mut l0) =
            (Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(2 * m), vec![], vec![]);
        for pb in patch.bonds() {
            let bond = &cell.bonds()[pb.bond];
            let joint = |n: usize| matches!(cell.nodes()[n].kind, NodeKind::Joint { .. });
            assert!(joint(bond.from) && joint(bond.to), "the export is for joint-joint bonds");
            first.push(patch.column(pb.from_cell, cell.dof_offset(bond.from)) as i64);
            second.push(patch.column(pb.to_cell, cell.dof_offset(bond.to)) as i64);
            // The bond joins `to` in the unwrapped cell `from_cell + bond.cell`: the shift from
            // the wrapped cell to it.
            let unwrapped = [pb.from_cell[0] as i64 + bond.cell[0], pb.from_cell[1] as i64 + bond.cell[1]];
            let (su, st) = (cell.shift(unwrapped), cell.shift([pb.to_cell[0] as i64, pb.to_cell[1] as i64]));
            offset.extend([su[0] - st[0], su[1] - st[1]]);
            k.push(bond.k);
            l0.push(bond.rest_length);
        }
        let f = |v: f64| v.to_le_bytes();
        let i = |v: i64| v.to_le_bytes();
        npy(&folder.join("first.npy"), "<i8", &[m], &first, i)?;
        npy(&folder.join("second.npy"), "<i8", &[m], &second, i)?;
        npy(&folder.join("offset.npy"), "<f8", &[m, 2], &offset, f)?;
        npy(&folder.join("k.npy"), "<f8", &[m], &k, f)?;
        npy(&folder.join("l0.npy"), "<f8", &[m], &l0, f)?;
        npy(&folder.join("x0.npy"), "<f8", &[dof], &x0, f)?;
        let inertia: Vec<f64> = (0..dof).map(|i| model.inertia(i)).collect();
        npy(&folder.join("inertia.npy"), "<f8", &[dof], &inertia, f)?;
        npy(&folder.join("steps.npy"), "<i8", &[1], &[steps as i64], i)?;
        npy(&folder.join("dt.npy"), "<f8", &[1], &[dt], f)?;
    }

    // Five runs of `steps` from the same start (the first warms the caches); the median time.
    let mut times = Vec::new();
    let mut energy = 0.0;
    for _ in 0..5 {
        let mut stepper =
            Verlet::new(&model, Phase { time: 0.0, theta: x0.clone(), omega: vec![0.0; dof] }, dt)?;
        let start = Instant::now();
        for _ in 0..steps {
            stepper.step(&model)?;
        }
        times.push(start.elapsed().as_secs_f64());
        energy = stepper.kinetic_energy(&model) + stepper.potential_energy(&model);
    }
    times.sort_by(f64::total_cmp);
    let per_dof = times[2] / steps as f64 / dof as f64 * 1e9;
    println!("kagome {n} x {n}: {dof} dof, {} bonds, {steps} Verlet steps of {dt}", model.spring_count());
    println!("energy after {steps} steps: {energy:.17e} (start {:.17e})", model.energy(&x0));
    println!(
        "step: {:.3} ms median of 5 = {per_dof:.2} ns per dof, level {:?}; memory per dof: model {:.1} B, \
         Verlet state 32 B, gradient buffers 16 B",
        times[2] / steps as f64 * 1e3,
        chain_core::simd::level(),
        model.heap_bytes() as f64 / dof as f64,
    );
    Ok(())
}
