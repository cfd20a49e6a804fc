//! fig:network-wall (issue 36, demonstration 2): the figure's data are the run's, and the GIF
//! decodes to one frame per sample showing both polarizations. A small lattice (4 chains of 32
//! rotors), fast in the debug build; the run's physics is tested in
//! chain-network/tests/motion_wall.rs.

use chain_network::motion::wall::CoupledChains;
use chain_paper::model::Chart;
use chain_paper::network::{wall_figure, write_gif};
use image::AnimationDecoder;
use image::codecs::gif::GifDecoder;

fn small() -> CoupledChains {
    CoupledChains { chains: 4, cells: 16, start: 6.0, duration: 200.0, frames: 9, ..CoupledChains::default() }
}

#[test]
fn the_figure_plots_the_runs_walls_and_frames() {
    let c = small();
    let (figure, run) = wall_figure(&c).unwrap();
    assert_eq!(figure.label, "fig:network-wall");
    assert_eq!(figure.panels.len(), 6);
    // Four frames: every rotor's arm, coloured by theta / theta_bar of that sample.
    let last = run.times.len() - 1;
    for (panel, k) in figure.panels[..4].iter().zip([0, last / 3, 2 * last / 3, last]) {
        let Chart::Network(d) = panel else { panic!("a frame is a drawing") };
        assert_eq!(d.arms.len(), c.chains * c.rotors());
        for (j, row) in run.theta[k].iter().enumerate() {
            for (i, t) in row.iter().enumerate() {
                assert_eq!(d.arm_tilts[j * c.rotors() + i], t / c.theta_bar);
            }
        }
    }
    // The walls panel: one series per chain with its positions, then the fitted line.
    let Chart::Lines(walls) = &figure.panels[4] else { panic!("walls") };
    for j in 0..c.chains {
        let expected: Vec<(f64, f64)> = run.times.iter().zip(&run.walls).map(|(&t, w)| (t, w[j])).collect();
        assert_eq!(walls.series[j].points, expected);
    }
    let fit = walls.series[c.chains].points.clone();
    assert!((fit[1].1 - fit[0].1) / (fit[1].0 - fit[0].0) - run.fit.slope < 1e-12);
    // The caption names the crossed region's flip, winding 1 to 0.
    let (b, a) = (&run.crossed_before, &run.crossed_after);
    assert_eq!((b.uniform.winding.winding[0], a.uniform.winding.winding[0]), (1, 0));
    assert!(figure.caption.contains(&format!("Rotors {}..{}", b.from, b.to)), "{}", figure.caption);
    assert!(figure.caption.contains("winding 1; after") && figure.caption.ends_with("along the chains."));
}

#[test]
fn the_gif_has_a_frame_per_sample_with_both_polarizations() {
    let c = small();
    let (_, run) = wall_figure(&c).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("network-wall.gif");
    let bytes = write_gif(&c, &run, &path, 150).unwrap();
    assert_eq!(std::fs::metadata(&path).unwrap().len() as usize, bytes);
    assert!(bytes < 2 << 20, "{bytes} bytes");
    let frames =
        GifDecoder::new(std::fs::File::open(&path).unwrap()).unwrap().into_frames().collect_frames().unwrap();
    assert_eq!(frames.len(), run.times.len());
    let size = frames[0].buffer().dimensions();
    assert!(frames.iter().all(|f| f.buffer().dimensions() == size));
    for f in [&frames[0], &frames[frames.len() - 1]] {
        // Blue (+theta_bar) and red (-theta_bar) arms both present (the palette's 20/60/200 and 210/30/30).
        let px = f.buffer().pixels();
        let blue = px.clone().filter(|p| p[2] > 150 && p[0] < 80).count();
        let red = px.filter(|p| p[0] > 160 && p[2] < 80).count();
        assert!(blue > 100 && red > 100, "blue {blue}, red {red}");
    }
}
