//! Unresolved points in the sweep (issue 34): a point whose outcome is not the impurity's alone
//! carries its reason through the results file; files written before the reason's columns
//! existed still read.
//!
//! The points are from the chaotic corner (antikink, k_i/k ~ 0.01, v0 ~ 1, the paper's
//! chain of Sec. VI), where a kink-antikink pair nucleates at the impurity before the antikink
//! arrives. The references are computed here by the library's runs of each integrator, and the
//! end-born walls are checked against the run's own wall snapshots and against absorbing ends.

use chain_sweep::scattering::{
    Defect, Ends, Method, Outcome, PhaseDiagram, PointRecord, Unresolved, fake_point,
};
use chain_sweep::{Axis, Grid, SweepError, SweepOptions, merge_shards, read_points, read_results, run_sweep};
use rotor_chain::dynamics::scatter::{EnergyBudget, scatter_within_budget};

fn antikinks() -> PhaseDiagram {
    PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink).unwrap()
}

/// (k_i/k, v0) = (0.01, 1.1), where Verlet and DOP853 decide differently (docs/dynamics.md §6),
/// is unresolved in a cross-checked sweep, with each integrator's outcome and decision time as
/// the library's single runs give them; the paper's reflected point (0.2, 4.8) is not.
#[test]
fn the_chaotic_corners_known_point_is_unresolved_in_a_cross_checked_sweep() {
    let d = PhaseDiagram { cross_check: true, ..antikinks() };
    assert!(d.run_label().ends_with(" cross_check=true"), "{}", d.run_label());
    let grid =
        Grid::new(Axis::from_values(vec![0.01, 0.2]).unwrap(), Axis::from_values(vec![1.1, 4.8]).unwrap())
            .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("antikink.csv");
    run_sweep(&grid, &path, |ki, v0| d.compute_point(ki, v0), &SweepOptions::new("antikink", d.run_label()))
        .unwrap();
    let points = read_results::<PointRecord>(&path).unwrap();
    let at = |ki: f64, v0: f64| points.iter().find(|p| p.1 == (ki, v0)).map(|p| p.2.clone()).unwrap();

    let model = d.chain(0.01).unwrap();
    let single = |method: Method| {
        let run = scatter_within_budget(&model, &d.setup(1.1, method), &EnergyBudget::default()).unwrap();
        (run.scattering.outcome, run.scattering.decided_at)
    };
    let (verlet, dop853) = (single(Method::Verlet), single(Method::dop853()));
    assert_ne!(verlet.0, dop853.0);
    let record = at(0.01, 1.1);
    assert_eq!(record.unresolved, Some(Unresolved::IntegratorsDisagree { verlet, dop853 }));
    assert_eq!((record.outcome, record.t_decided), verlet);

    let robust = at(0.2, 4.8);
    assert_eq!((robust.outcome, robust.unresolved), (Outcome::Reflected, None));
    // Without the cross-check the same point has no reason to doubt it (no end-born wall came).
    assert_eq!(antikinks().compute_point(0.01, 1.1).unwrap().unresolved, None);
}

/// (0.008, 1.2): a wall born at a free end reaches the impurity before the outcome is decided.
/// The record says so without any cross-check. Checked against the run itself (a wall stood in
/// an end zone before it arrived, and one stood within `reach` of the impurity then, besides the
/// defect's), and against absorbing ends, from which no wall comes.
#[test]
fn a_wall_from_a_free_end_that_reaches_the_impurity_first_makes_the_point_unresolved() {
    let d = antikinks();
    let record = d.compute_point(0.008, 1.2).unwrap();
    let Some(Unresolved::EndWallFirst { arrived, decided }) = record.unresolved else {
        panic!("{record:?}");
    };
    assert_eq!(decided, (record.outcome, record.t_decided));
    assert!(arrived <= record.t_decided, "{arrived} after {}", record.t_decided);

    let model = d.chain(0.008).unwrap();
    let setup = d.setup(1.2, Method::Verlet);
    let run = scatter_within_budget(&model, &setup, &EnergyBudget::default()).unwrap().scattering;
    assert_eq!(run.end_wall_at_impurity, Some(arrived));
    let last = (d.n - 1) as f64;
    let zone = setup.edge_margin + 1.0;
    let snapshots = &run.run.tracker.snapshots;
    let in_end_zone = snapshots.iter().filter(|s| s.time > 0.0 && s.time < arrived).any(|s| {
        let interior = s.walls.iter().zip(&s.at_boundary).filter(|(_, b)| !**b);
        interior.into_iter().any(|(w, _)| w.position <= zone || w.position >= last - zone)
    });
    assert!(in_end_zone, "no wall in an end zone before t = {arrived}");
    let then = snapshots.iter().find(|s| s.time == arrived).unwrap();
    let x_imp = d.impurity() as f64 + 0.5;
    let interior: Vec<_> =
        then.walls.iter().zip(&then.at_boundary).filter(|(_, b)| !**b).map(|(w, _)| w).collect();
    let near = interior.iter().filter(|w| (w.position - x_imp).abs() <= setup.reach).count();
    assert!(near >= 1 && interior.len() >= 2, "at t = {arrived}: {interior:?}");

    let absorbing = PhaseDiagram { ends: Ends::Absorbing, ..antikinks() }.compute_point(0.008, 1.2).unwrap();
    assert!(!matches!(absorbing.unresolved, Some(Unresolved::EndWallFirst { .. })), "{absorbing:?}");
}

/// The results file of physics v3 (nine record columns, no `unresolved`): it reads, every point
/// resolved; its shards merge into a file with every column; a sweep does not append to it.
#[test]
fn a_file_without_the_unresolved_columns_still_reads_and_merges() {
    let dir = tempfile::tempdir().unwrap();
    let grid =
        Grid::new(Axis::linspace(0.1, 0.2, 2).unwrap(), Axis::from_values(vec![1.0]).unwrap()).unwrap();
    let old_header = "i,j,x,y,outcome,t_decided,confirmed,later,t_later,kinks_final,antikinks_final,energy_error,integrator,error";
    let line = |i: usize, x: f64| format!("{i},0,{x:?},1.0,trapped,4.25,true,,,1,0,1e-9,verlet,\n");
    let write = |name: &str, shard: &str, lines: &[String]| {
        let path = dir.path().join(name);
        let preamble = format!(
            "# chain-sweep v1; grid {}; run old run{shard}\n{old_header}\n{}",
            grid.signature(),
            lines.concat()
        );
        std::fs::write(&path, preamble).unwrap();
        path
    };
    let (x0, x1) = (grid.xs()[0], grid.xs()[1]);
    let whole = write("old.csv", "", &[line(0, x0), line(1, x1)]);
    let points = read_points::<PointRecord>(&whole).unwrap();
    assert_eq!(points.len(), 2);
    for p in &points {
        let record = p.outcome.as_ref().unwrap();
        assert_eq!((record.outcome, record.t_decided, record.unresolved), (Outcome::Trapped, 4.25, None));
    }

    let shards =
        [write("s0.csv", "; shard 0/2", &[line(0, x0)]), write("s1.csv", "; shard 1/2", &[line(1, x1)])];
    let merged = dir.path().join("merged.csv");
    merge_shards::<PointRecord>(&shards, &merged).unwrap();
    let text = std::fs::read_to_string(&merged).unwrap();
    assert!(
        text.lines().nth(1).unwrap().ends_with("integrator,unresolved,unresolved_outcome,t_unresolved,error")
    );
    assert_eq!(
        read_points::<PointRecord>(&merged).unwrap().into_iter().map(|p| p.outcome).collect::<Vec<_>>(),
        points.into_iter().map(|p| p.outcome).collect::<Vec<_>>()
    );

    // A sweep with the old file's own label does not append lines of another width to it.
    let options = SweepOptions::new("old", "old run");
    let err = run_sweep(&grid, &whole, |ki, v0| Ok::<_, String>(fake_point(ki, v0)), &options).unwrap_err();
    assert!(matches!(err, SweepError::HeaderMismatch { .. }), "{err}");
}
