//! A grid whose results cannot be held is `SweepError::OutOfMemory` with the bytes, before any
//! point is computed, never an abort after the work (issue 37): `compute_grid` under an
//! address-space limit set on this test process by `prlimit` (util-linux), 64 MiB above what it
//! has mapped. This file holds one test, so no other test shares the limit.

use chain_sweep::{Axis, Grid, Point, SweepError, compute_grid};
use rotor_chain::allocation::AllocationError;
use std::sync::atomic::{AtomicUsize, Ordering};
use test_support::memory::with_headroom;

/// A record of 64 numbers per point.
type Record = [f64; 64];

#[test]
fn a_grid_whose_results_cannot_be_held_is_an_error_before_any_point() {
    // 4000 x 2500 = 10^7 points (the grid limit), about 5.6 GB of points.
    let grid =
        Grid::new(Axis::linspace(0.1, 1.0, 4000).unwrap(), Axis::linspace(0.1, 5.0, 2500).unwrap()).unwrap();
    let calls = AtomicUsize::new(0);
    let compute = |_: f64, _: f64| -> Result<Record, String> {
        calls.fetch_add(1, Ordering::Relaxed);
        Ok([0.0; 64])
    };
    let result = with_headroom(64 << 20, || compute_grid(&grid, compute, Some(2)));
    let err = result.unwrap_err();
    let bytes = 10_000_000 * std::mem::size_of::<Point<Record>>();
    assert!(bytes > 5_000_000_000);
    let SweepError::OutOfMemory(e) = err else { panic!("{err}") };
    assert_eq!(e, AllocationError { bytes, what: "the grid's points" });
    assert_eq!(calls.load(Ordering::Relaxed), 0, "no point computed");
    // A grid that fits computes every point, in grid order.
    let small =
        Grid::new(Axis::linspace(0.1, 1.0, 3).unwrap(), Axis::linspace(0.1, 5.0, 4).unwrap()).unwrap();
    let points = compute_grid(&small, compute, Some(2)).unwrap();
    let order: Vec<(usize, usize)> = points.iter().map(|p| p.index).collect();
    assert_eq!(order, small.indices().collect::<Vec<_>>());
    assert!(points.iter().all(|p| p.coords == small.point(p.index.0, p.index.1).unwrap()));
    assert_eq!(calls.load(Ordering::Relaxed), 12);
}
