//! Cost of the 1D polar GGX split-sum kernel (src/kernels/ggx_polar.rs) per call, on one
//! thread: evaluations (outer θl lines and inner azimuthal nodes together), the outer lines
//! alone (`ggx_albedo`'s count: one evaluation per line) and the thread's CPU time per call,
//! over a grid of views μ and perceptual roughness r (α = r²), height-correlated Smith, at
//! the node tolerance of the split-sum rows (tol/4 = 2.5e-8 for the default 1e-7) and at
//! 1e-7 (texels computed directly). A failure (`Err`: the caller would fall back) is
//! counted and marked.
//!
//! ```text
//! cargo run --release --example polar_cost -- [REPEATS]   (default 20)
//! ```

use brdfbake::kernels::ggx_polar::Smith;
use brdfbake::kernels::ggx_polar::{ggx_albedo, ggx_split_sum};

#[path = "common/cpu_time.rs"]
mod cpu_time;
use cpu_time::thread_cpu_seconds;

fn main() {
    let reps: usize = std::env::args()
        .nth(1)
        .map_or(20, |s| s.parse().expect("REPEATS"));
    let mus = [0.01, 0.05, 0.1, 0.3, 0.5, 0.8, 1.0];
    let rs = [0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0];
    for tol in [2.5e-8, 1e-7] {
        println!("tol {tol:e}: evaluations / lines / µs CPU per call (rows r, columns μ)");
        print!("{:>6}", "r\\mu");
        for mu in mus {
            print!(" {mu:>17}");
        }
        println!();
        let (mut sum_ev, mut sum_lines, mut sum_t, mut fails) = (0u64, 0u64, 0.0f64, 0);
        for r in rs {
            let alpha = r * r;
            print!("{r:>6}");
            for mu in mus {
                let res = ggx_split_sum(mu, alpha, Smith::HeightCorrelated, tol);
                let (ev, ok) = match res {
                    Ok(e) => (e.evals, true),
                    Err(n) => (n, false),
                };
                let lines = match ggx_albedo(mu, alpha, Smith::HeightCorrelated, tol) {
                    Ok(e) => e.evals,
                    Err(n) => n,
                };
                let t0 = thread_cpu_seconds();
                for _ in 0..reps {
                    std::hint::black_box(ggx_split_sum(
                        std::hint::black_box(mu),
                        alpha,
                        Smith::HeightCorrelated,
                        tol,
                    ))
                    .ok();
                }
                let us = (thread_cpu_seconds() - t0) / reps as f64 * 1e6;
                sum_ev += ev;
                sum_lines += lines;
                sum_t += us;
                if !ok {
                    fails += 1;
                }
                let mark = if ok { ' ' } else { '!' };
                print!(" {ev:>5}/{lines:>3}/{us:>6.1}{mark}");
            }
            println!();
        }
        let n = (mus.len() * rs.len()) as f64;
        println!(
            "mean over the grid: {:.0} evaluations, {:.1} lines, {:.1} µs CPU per call; {fails} failure(s) (!)\n",
            sum_ev as f64 / n,
            sum_lines as f64 / n,
            sum_t / n
        );
    }
}
