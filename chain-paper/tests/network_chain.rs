//! Issue 36, demonstration 1 as a figure (`fig:network-chain`): the paper's chain declared as a
//! rotor network agrees with the chain code in every row, and the figure shows what it says.

use chain_paper::Chart;
use chain_paper::figures::Params;
use chain_paper::network::demonstration::chain_as_network;

/// The first number after `marker` in `text`.
fn after(text: &str, marker: &str) -> f64 {
    let rest = text.split_once(marker).unwrap_or_else(|| panic!("no {marker:?} in {text:?}")).1;
    rest.split([' ', ',', ';'])
        .find(|s| !s.is_empty())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{text:?}"))
}

#[test]
fn the_chain_declared_as_a_network_is_the_chain_code() {
    let figure = chain_as_network(&Params::default()).unwrap();
    assert_eq!(figure.label, "fig:network-chain");
    assert_eq!(figure.rows.len(), 6);
    // Energies to nine decimals in both columns: at 1e-9 relative they print the same digits, and
    // the minimum is the reference-verified 1392.029215 (tests/statics_antikink.rs).
    for row in &figure.rows[..2] {
        let (chain, network): (f64, f64) = (row.paper.parse().unwrap(), row.ours.parse().unwrap());
        assert!(
            (chain - network).abs() <= 1e-9 * chain.abs().max(1.0),
            "{}: {chain} vs {network}",
            row.quantity
        );
    }
    assert!((figure.rows[0].ours.parse::<f64>().unwrap() - 1392.029215).abs() <= 5e-7);
    // Each scattering point: the chain code's outcome, the one expected, the same walls at every
    // output (to 1e-6 sites: the two evaluate the same springs in another order) and energies.
    for (row, expected) in figure.rows[2..].iter().zip(["transmitted", "split", "trapped", "reflected"]) {
        assert_eq!((row.paper.as_str(), row.ours.as_str()), (expected, expected), "{}", row.quantity);
        assert!(after(&row.note, "at most ") <= 1e-6, "{}", row.note);
        assert_eq!(after(&row.note, "wall counts differ at "), 0.0, "{}", row.note);
        assert!(after(&row.note, "relative difference ") <= 1e-9, "{}", row.note);
    }
    // (a) the two antikinks point for point; (b) one series of walls per outcome, inside the chain.
    let [Chart::Lines(statics), Chart::Lines(walls)] = &figure.panels[..] else { panic!("two line panels") };
    let (chain, network) = (&statics.series[0].points, &statics.series[1].points);
    assert_eq!(chain.len(), 60);
    assert!(chain.iter().zip(network).all(|(a, b)| a.0 == b.0 && (a.1 - b.1).abs() < 1e-9));
    assert_eq!(walls.series.len(), 4);
    for series in &walls.series {
        assert!(series.points.len() > 100, "{}", series.name);
        assert!(series.points.iter().all(|&(t, x)| t >= 0.0 && (0.0..=59.0).contains(&x)), "{}", series.name);
    }
}
