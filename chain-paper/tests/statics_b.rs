//! Every figure of `statics_b` in Quick mode: panels non-empty, numbers finite.

use chain_paper::figures::{Params, statics_b};
use chain_paper::render::missing_glyphs;
use chain_paper::{Chart, Comparison, Quality};

#[test]
fn every_statics_b_figure_runs_in_quick_mode() {
    let params = Params::default();
    for (label, figure) in statics_b::figures() {
        let start = std::time::Instant::now();
        let fig = figure(&params, Quality::Quick).unwrap_or_else(|e| panic!("{label}: {e}"));
        eprintln!("{label}: {:.2?}", start.elapsed());
        assert_eq!(fig.label, label);
        assert!(!fig.caption.is_empty() && !fig.caption.contains('\n'), "{label}: caption");
        assert_eq!(missing_glyphs(&fig), Vec::<char>::new(), "{label}: characters the font cannot draw");
        assert!(!fig.panels.is_empty(), "{label}: no panels");
        for chart in &fig.panels {
            match chart {
                Chart::Lines(panel) => {
                    assert!(!panel.series.is_empty(), "{label}: {} has no series", panel.title);
                    for s in &panel.series {
                        assert!(!s.points.is_empty(), "{label}: {} / {} is empty", panel.title, s.name);
                        assert!(!s.name.contains(','), "{label}: series name {} has a comma", s.name);
                        assert!(
                            s.points.iter().all(|(x, y)| x.is_finite() && y.is_finite()),
                            "{label}: {} / {} has a non-finite point",
                            panel.title,
                            s.name
                        );
                        if panel.log_y {
                            assert!(
                                s.points.iter().all(|p| p.1 > 0.0),
                                "{label}: non-positive on a log axis"
                            );
                        }
                    }
                }
                Chart::Heat(map) => {
                    assert!(!map.x.is_empty() && !map.y.is_empty(), "{label}: empty heat map");
                    assert_eq!(map.values.len(), map.y.len(), "{label}: heat map rows");
                    assert!(
                        map.values.iter().all(|row| row.len() == map.x.len()),
                        "{label}: heat map columns"
                    );
                    assert!(map.values.iter().flatten().all(|v| v.is_finite()), "{label}: non-finite value");
                }
                Chart::Chain(d) => {
                    assert_eq!(d.pivots.len(), d.tips.len(), "{label}: drawing");
                    assert!(d.arrows.is_empty() || d.arrows.len() == d.tips.len(), "{label}: arrows");
                    assert!(d.tensions.is_empty() || d.tensions.len() == d.stretch.len(), "{label}: bars");
                }
                Chart::Network(d) => assert!(!d.nodes.is_empty(), "{label}: network drawing"),
            }
        }
        assert!(
            label == "fig:mode-config" || label == "fig:ELdiagram" || !fig.rows.is_empty(),
            "{label}: no rows"
        );
        for row in &fig.rows {
            eprintln!(
                "  {} | paper {} | ours {} | continuum {:?}",
                row.quantity, row.paper, row.ours, row.continuum
            );
            assert!(
                !row.ours.contains("NaN") && !row.ours.contains("inf"),
                "{label}: {} not finite",
                row.quantity
            );
            // A numeric row: both values parse and are finite.
            if let Comparison::Relative { difference, .. } = row.comparison {
                assert!(difference.is_finite(), "{label}: {} relative difference", row.quantity);
                for text in [&row.paper, &row.ours] {
                    let x: f64 = text.parse().unwrap_or_else(|_| panic!("{label}: {text} is not a number"));
                    assert!(x.is_finite(), "{label}: {} = {text}", row.quantity);
                }
            }
            if let Some(c) = &row.continuum {
                assert!(c.parse::<f64>().is_ok_and(f64::is_finite), "{label}: continuum {c}");
            }
        }
    }
}

/// The paper's soft-mode frequency, 7.7e-9, lies below what a double-precision omega^2 resolves:
/// the summary says the two are not comparable instead of printing a relative difference.
#[test]
fn the_soft_mode_row_is_not_compared_below_the_resolution() {
    let fig = statics_b::longbar(&Params::default(), Quality::Quick).unwrap();
    let row = fig.rows.iter().find(|r| r.quantity.starts_with("soft-mode frequency")).unwrap();
    let Comparison::NotComparable { reason } = &row.comparison else { panic!("{:?}", row.comparison) };
    assert!(reason.starts_with("the paper's 7.7e-9 is at or below"), "{reason}");
    let ours: f64 = row.ours.parse().unwrap();
    assert!(ours > 1e-3, "ours {ours} is resolved");
}
