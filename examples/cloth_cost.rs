//! Cost of the cloth channel of a `filament-dfg`-style table (μ = (i + ½)/N, α = ((j + ½)/N)²),
//! per path, on one thread: evaluations per texel and the thread's CPU time, for the narrow rows
//! (α < 1/16) and the wide rows separately. Narrow rows: `sheen_l`, then the half-vector
//! kernel where it gives up (as the bake does). Wide rows: `sheen_wide` first (the
//! experiment; the kernel where it gives up), or with `old` the half-vector kernel alone (as
//! the bake does).
//!
//! ```text
//! cargo run --release --example cloth_cost -- [N] [TOL] [old]   (defaults 128, 1e-7)
//! ```

use brdfbake::integrate::dfg_kernel::{charlie_sheen_shared, Column, SheenCache};
use brdfbake::integrate::sheen_l::{charlie_sheen_l, MAX_ALPHA};
use brdfbake::integrate::sheen_wide::{charlie_sheen_wide_shared, WideCache};
use std::cell::RefCell;

#[path = "common/cpu_time.rs"]
mod cpu_time;
use cpu_time::thread_cpu_seconds;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map_or(128, |s| s.parse().expect("N"));
    let tol: f64 = args.get(2).map_or(1e-7, |s| s.parse().expect("TOL"));
    // "old": wide lobes straight to the half-vector kernel (before sheen_wide)
    let old = args.get(3).is_some_and(|s| s == "old");
    // (texels, evaluations, seconds, fallbacks) for narrow and wide rows
    let mut acc = [(0u64, 0u64, 0.0f64, 0u64); 2];
    for i in 0..n {
        let mu = (i as f64 + 0.5) / n as f64;
        let col = Column::new(mu);
        let cache = RefCell::new(SheenCache::default());
        let mut wide_cache = WideCache::default();
        for j in 0..n {
            let r = (j as f64 + 0.5) / n as f64;
            let alpha = r * r;
            let wide = alpha >= MAX_ALPHA;
            let t0 = thread_cpu_seconds();
            let mut spent = 0;
            let mut fell = 0;
            if !wide || !old {
                let r = if wide {
                    charlie_sheen_wide_shared(mu, alpha, tol, &mut wide_cache)
                } else {
                    charlie_sheen_l(mu, alpha, tol)
                };
                match r {
                    Ok(e) => spent += e.evals,
                    Err(m) => {
                        spent += m;
                        fell = 1;
                    }
                }
            }
            if (wide && old) || fell == 1 {
                match charlie_sheen_shared(&col, Some(&cache), alpha, tol) {
                    Ok(e) => spent += e.evals,
                    Err(m) => {
                        spent += m;
                        fell = 1;
                    }
                }
            }
            let dt = thread_cpu_seconds() - t0;
            let a = &mut acc[wide as usize];
            a.0 += 1;
            a.1 += spent;
            a.2 += dt;
            a.3 += fell;
        }
    }
    for (name, a) in ["narrow (alpha < 1/16)", "wide (alpha >= 1/16)"]
        .iter()
        .zip(acc)
    {
        println!(
            "{name}: {} texels, {:.0} evaluations/texel, {:.1} ms CPU ({:.2} us/texel), {} fell back",
            a.0,
            a.1 as f64 / a.0 as f64,
            a.2 * 1e3,
            a.2 * 1e6 / a.0 as f64,
            a.3
        );
    }
}
