//! A patch, or a model of it, that the allocator cannot hold is `NetworkError::OutOfMemory` with
//! the bytes of the array asked for, never an abort (issue 37): under an address-space limit set
//! on this test process by `prlimit` (util-linux), 64 MiB above what it has mapped. This file
//! holds one test, so no other test shares the limit.

use chain_core::allocation::AllocationError;
use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch, PatchBond};
use chain_network::{NetworkError, NetworkModel};
use test_support::memory::with_headroom;

#[test]
fn a_patch_and_a_model_too_large_for_the_memory_limit_are_out_of_memory_errors() {
    let square = ready::square();
    // The patch: 4000 x 4000 cells of 2 bonds, under the patch rule's 2^25 bonds.
    let err = with_headroom(64 << 20, || Patch::new(&square, [4000, 4000], Boundary::Periodic).unwrap_err());
    let bonds = 4000 * 4000 * 2;
    let expected =
        AllocationError { bytes: bonds * std::mem::size_of::<PatchBond>(), what: "the patch's bonds" };
    assert_eq!(err, NetworkError::OutOfMemory(expected), "{err}");
    assert_eq!(err.to_string(), format!("cannot allocate {} bytes for the patch's bonds", bonds * 40));

    // The model of a patch that fits: 1000 x 500 cells, 500 000 nodes, 1 000 000 bonds and
    // degrees of freedom; the limit leaves 8 MiB, less than the larger arrays of its model.
    let patch = Patch::new(&square, [1000, 500], Boundary::Periodic).unwrap();
    let (nodes, bonds, dof) = (500_000, 1_000_000, 1_000_000);
    assert_eq!((patch.bonds().len(), patch.dof()), (bonds, dof));
    let err = with_headroom(8 << 20, || NetworkModel::builder(&patch).build().unwrap_err());
    let NetworkError::OutOfMemory(AllocationError { bytes, what }) = err else { panic!("{err}") };
    // Each array's size from the patch's counts: 8 B per node's mass, 16 B per spring's constant
    // and rest length, 8 B per degree of freedom's inertia or coordinate, 4 B per rotor index;
    // per bond of a group, its index, stiffness and rest length (8 B each), its 4 degrees of
    // freedom (32 B), its offset and radii (16 B each).
    let sizes = [
        ("the node masses", nodes * 8),
        ("the springs' constants and rest lengths", bonds * 16),
        ("the inertia", dof * 8),
        ("the reference coordinates", dof * 8),
        ("the rotor index", dof * 4),
        ("the model's bonds", bonds * 8),
        ("the model's bonds", bonds * 16),
        ("the model's bonds", bonds * 32),
    ];
    assert!(sizes.contains(&(what, bytes)), "{what}: {bytes} bytes");
    assert!(bytes > 8 << 20, "{what}: {bytes} bytes fit the limit");
    // Without the limit the same model builds.
    assert!(NetworkModel::builder(&patch).build().is_ok());
}
