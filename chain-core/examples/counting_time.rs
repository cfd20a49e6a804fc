//! Times the Maxwell-Calladine counting: a long chain's kink (the bidiagonal path, O(n) per Sturm
//! count), `cargo run --release -p rotor-chain-core --example counting_time -- 8192`, and with
//! `dense N` the two dense SVDs a network's counting takes of an `N x N` compatibility matrix
//! (the chain's, padded square), the basis of `counting::MAX_DENSE_SVD_SIDE`.

use std::time::Instant;

use nalgebra::DMatrix;
use rotor_chain::RuntimeChain;
use rotor_chain::statics::counting::{compatibility, maxwell_calladine};
use rotor_chain::statics::kink::kink;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let first = args.next().unwrap_or_else(|| "8192".to_owned());
    let dense = first == "dense";
    let n: usize = if dense { args.next().unwrap_or_else(|| "1024".to_owned()) } else { first }.parse()?;
    let chain = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build()?;
    let theta = kink(&chain, 0.4 * n as f64)?;
    let start = Instant::now();
    if dense {
        let (left, right) = compatibility(&chain, &theta);
        let mut c = DMatrix::zeros(n, n);
        for p in 0..n - 1 {
            c[(p, p)] = left[p];
            c[(p, p + 1)] = right[p];
        }
        let budget = 6 * n * n;
        let values = c.clone().try_svd(false, false, f64::EPSILON, budget).ok_or("no convergence")?;
        let values_time = start.elapsed().as_secs_f64();
        let full = c.try_svd(true, true, f64::EPSILON, budget).ok_or("no convergence")?;
        println!(
            "dense {n} x {n}: values {values_time:.2} s, with vectors {:.2} s more (smallest {:e}, {:e})",
            start.elapsed().as_secs_f64() - values_time,
            values.singular_values.min(),
            full.singular_values.min()
        );
        return Ok(());
    }
    let counting = maxwell_calladine(&chain, &theta, None)?;
    println!(
        "n = {n}: rank {} of {}, {} zero mode(s), {} self-stress(es), smallest singular value {:e}, in {:.2} s",
        counting.rank,
        counting.springs,
        counting.zero_modes.len(),
        counting.self_stresses.len(),
        counting.singular_values.last().copied().unwrap_or(f64::NAN),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
