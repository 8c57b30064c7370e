//! Cost of a `sheen-e` albedo table (Charlie + Ashikhmin, F = 1) per path, on one thread:
//! the half-vector kernel ([`charlie_sheen_shared`], what `directional_albedo` used before
//! round 6) against the light-direction kernels ([`charlie_sheen_l`] for α < 1/16,
//! [`charlie_sheen_wide_shared`] beyond, each falling back to the half-vector kernel where
//! it gives up). Grid: μ = (i + ½)/NMU, perceptual r = R0 + (R1 − R0)·j/(NR − 1), α = r²
//! (the `sheen-charlie` preset's axes by default). Prints evaluations per texel, the
//! thread's CPU time and fallbacks per path and lobe width, and the largest difference
//! between the two paths' values next to the sum of their estimates.
//!
//! ```text
//! cargo run --release --example sheen_albedo_cost -- [NMU] [NR] [R0] [R1] [TOL]
//! ```
//! (defaults 32 32 0.1 1 1e-7)

use brdfbake::integrate::dfg_kernel::{charlie_sheen_shared, Column, SheenCache};
use brdfbake::integrate::sheen_l::{charlie_sheen_l, MAX_ALPHA};
use brdfbake::integrate::sheen_wide::{charlie_sheen_wide_shared, WideCache};
use std::cell::RefCell;

#[path = "common/cpu_time.rs"]
mod cpu_time;
use cpu_time::thread_cpu_seconds;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| a.get(i).map_or(d, |s| s.parse().expect("number"));
    let (nmu, nr) = (arg(1, 32.0) as usize, arg(2, 32.0) as usize);
    let (r0, r1, tol) = (arg(3, 0.1), arg(4, 1.0), arg(5, 1e-7));
    // [path][narrow/wide]: (texels, evaluations, seconds, fallbacks)
    let mut acc = [[(0u64, 0u64, 0.0f64, 0u64); 2]; 2];
    let (mut worst, mut worst_at) = (0.0f64, (0.0, 0.0, 0.0));
    for i in 0..nmu {
        let mu = (i as f64 + 0.5) / nmu as f64;
        let col = Column::new(mu);
        let old_cache = RefCell::new(SheenCache::default());
        let new_cache = RefCell::new(SheenCache::default());
        let mut wide_cache = WideCache::default();
        for j in 0..nr {
            let r = r0 + (r1 - r0) * j as f64 / (nr.max(2) - 1) as f64;
            let alpha = r * r;
            let wide = alpha >= MAX_ALPHA;
            // the half-vector kernel alone
            let t0 = thread_cpu_seconds();
            let old = charlie_sheen_shared(&col, Some(&old_cache), alpha, tol);
            let dt = thread_cpu_seconds() - t0;
            let o = &mut acc[0][wide as usize];
            o.0 += 1;
            o.2 += dt;
            let old = match old {
                Ok(e) => {
                    o.1 += e.evals;
                    Some(e)
                }
                Err(n) => {
                    o.1 += n;
                    o.3 += 1;
                    None
                }
            };
            // light-direction kernel first
            let t0 = thread_cpu_seconds();
            let first = if wide {
                charlie_sheen_wide_shared(mu, alpha, tol, &mut wide_cache)
            } else {
                charlie_sheen_l(mu, alpha, tol)
            };
            let (new, spent, fell) = match first {
                Ok(e) => (Some(e), e.evals, 0),
                Err(n) => match charlie_sheen_shared(&col, Some(&new_cache), alpha, tol) {
                    Ok(e) => (Some(e), n + e.evals, 1),
                    Err(m) => (None, n + m, 1),
                },
            };
            let dt = thread_cpu_seconds() - t0;
            let n = &mut acc[1][wide as usize];
            n.0 += 1;
            n.1 += spent;
            n.2 += dt;
            n.3 += fell;
            if let (Some(o), Some(n)) = (old, new) {
                let d = (o.value[0] - n.value[0]).abs();
                if d > worst {
                    worst = d;
                    worst_at = (mu, alpha, o.error[0] + n.error[0]);
                }
            }
        }
    }
    for (p, path) in ["half-vector kernel", "light-direction kernels"]
        .iter()
        .enumerate()
    {
        for (w, name) in ["narrow (alpha < 1/16)", "wide (alpha >= 1/16)"]
            .iter()
            .enumerate()
        {
            let a = acc[p][w];
            if a.0 == 0 {
                continue;
            }
            println!(
                "{path}, {name}: {} texels, {:.0} evaluations/texel, {:.1} ms CPU ({:.2} us/texel), {} fell back",
                a.0,
                a.1 as f64 / a.0 as f64,
                a.2 * 1e3,
                a.2 * 1e6 / a.0 as f64,
                a.3
            );
        }
    }
    println!(
        "largest difference between the paths: {worst:.2e} at mu = {:.4}, alpha = {:.4} (sum of their estimates {:.2e})",
        worst_at.0, worst_at.1, worst_at.2
    );
}
