//! Times the Maxwell-Calladine counting of a long chain's kink (the bidiagonal path, O(n) per
//! Sturm count): `cargo run --release -p rotor-chain-core --example counting_time -- 8192`.

use std::time::Instant;

use rotor_chain::RuntimeChain;
use rotor_chain::statics::counting::maxwell_calladine;
use rotor_chain::statics::kink::kink;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map_or(Ok(8192), |s| s.parse())?;
    let chain = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build()?;
    let theta = kink(&chain, 0.4 * n as f64)?;
    let start = Instant::now();
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
