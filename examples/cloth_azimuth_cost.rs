//! Cost of the θh cloth kernel (src/kernels/sheen_azimuth.rs) over every texel of a
//! 128² filament-dfg cloth channel (μ and perceptual roughness at texel centres, α = r²),
//! on one thread, texel by texel (no node data shared) and column by column (each view's
//! node data shared by its roughnesses, as the bake does): milliseconds, evaluations, and
//! the sum of the values (the two must agree bit for bit).
//!
//! ```text
//! cargo run --release --example cloth_azimuth_cost
//! ```

use brdfbake::kernels::sheen_azimuth::{
    charlie_sheen_azimuth, charlie_sheen_azimuth_shared, AzimuthCache,
};
use std::time::Instant;

const N: usize = 128;
const TOL: f64 = 1e-7;

fn main() {
    let coord = |i: usize| (i as f64 + 0.5) / N as f64;
    for shared in [false, true] {
        let t0 = Instant::now();
        let (mut evals, mut sum) = (0u64, 0.0f64);
        for i in 0..N {
            let mut cache = AzimuthCache::default();
            for j in 0..N {
                let (mu, alpha) = (coord(i), coord(j) * coord(j));
                let e = if shared {
                    charlie_sheen_azimuth_shared(mu, alpha, TOL, &mut cache)
                } else {
                    charlie_sheen_azimuth(mu, alpha, TOL)
                };
                match e {
                    Ok(e) => {
                        evals += e.evals;
                        sum += e.value[0];
                    }
                    Err(n) => println!("mu {mu} alpha {alpha}: declined after {n} evaluations"),
                }
            }
        }
        println!(
            "{}: {:.1} ms, {evals} evaluations, sum of values {sum:e}",
            if shared {
                "by columns"
            } else {
                "texel by texel"
            },
            t0.elapsed().as_secs_f64() * 1e3
        );
    }
}
