//! Speed of the static analyses (issue targets: n = 60 kink + antikink minimum and saddle + full
//! spectrum <= 20 ms; n = 2000 antikink + lowest 10 modes <= 2 s).
//!
//! Run: `cargo bench --bench statics`

use divan::black_box;
use rotor_chain::RuntimeChain;
use rotor_chain::linalg::SymmetricMatrix;
use rotor_chain::linalg::eigenvalues;
use rotor_chain::prelude::*;
use rotor_chain::statics::antikink::{AntikinkOptions, antikink_at, peierls_nabarro};
use rotor_chain::statics::kink::kink;
use rotor_chain::statics::modes::{ModeOptions, modes};

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Paper;

fn main() {
    divan::main();
}

/// n = 60: the kink, the antikink minimum and saddle, and the full spectrum of each.
#[divan::bench(sample_count = 50)]
fn n60_kink_antikink_spectrum() -> f64 {
    let chain = black_box(&Paper);
    let k = kink(chain, 29.5).unwrap();
    let pn = peierls_nabarro(chain, &AntikinkOptions::default()).unwrap();
    let mut total = pn.barrier;
    for theta in [&k, &pn.rotor_centred.theta, &pn.spring_centred.theta] {
        let k = SymmetricMatrix::tangent_stiffness(chain, theta).unwrap();
        let (diag, off) = k.bands().unwrap();
        total += eigenvalues(diag, off).unwrap()[1];
    }
    total
}

/// n = 2000: the antikink (minimum centring) and its lowest 10 modes.
#[divan::bench(sample_count = 10)]
fn n2000_antikink_lowest_10_modes(bencher: divan::Bencher) {
    let chain = RuntimeChain::builder(2000, 0.8, 1.0e4, 0.58).build().unwrap();
    bencher.bench(|| {
        let ak = antikink_at(black_box(&chain), 999.0, &AntikinkOptions::default()).unwrap();
        let lowest =
            modes(&chain, &ak.theta, &ModeOptions { count: Some(10), ..ModeOptions::default() }).unwrap();
        lowest[9].frequency
    });
}
