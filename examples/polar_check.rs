//! Accuracy of the 1D polar GGX split-sum kernel (src/kernels/ggx_polar.rs) on a dense
//! grid against the adaptive 2D integrator (`dfg::split_sum_adaptive`) at 1e-12 (at μ = 1
//! against tests/common/normal_view.rs, where the 2D integrator's estimate is unreliable):
//! for each point and channel, |kernel − reference| must be within the kernel's
//! estimate plus the reference's (+ 1e-12 rounding), and the estimate within the requested
//! tolerance. Prints the violations, the declined points (`Err`: the caller falls back) and
//! the largest |error|/(estimate + reference's estimate + rounding). With `probe`, one point
//! at tolerances 1e-7 … 1e-12, kernel and reference side by side.
//!
//! ```text
//! cargo run --release --example polar_check -- [NMU] [NALPHA]   (defaults 24 24)
//! cargo run --release --example polar_check -- MU ALPHA probe
//! ```

use brdfbake::kernels::ggx_polar::ggx_split_sum;
use brdfbake::kernels::ggx_polar::Smith;
use brdfbake::model::{Fresnel, Masking, Ndf, NdfKind, Specular};
use brdfbake::table::dfg::split_sum_adaptive;
use rayon::prelude::*;

#[path = "../tests/common/normal_view.rs"]
mod normal_view;
use normal_view::normal_view_split_sum;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(3).is_some_and(|s| s == "probe") {
        let (mu, alpha) = (args[1].parse().unwrap(), args[2].parse().unwrap());
        let s = Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        };
        for t in [1e-7, 2.5e-8, 1e-9, 1e-10, 1e-11, 1e-12] {
            let k = ggx_split_sum(mu, alpha, Smith::HeightCorrelated, t);
            let r = split_sum_adaptive(&s, mu, t);
            println!("tol {t:e}: kernel {k:?}\n            ref {r:?}");
        }
        return;
    }
    let nmu: usize = args.get(1).map_or(24, |s| s.parse().expect("NMU"));
    let na: usize = args.get(2).map_or(24, |s| s.parse().expect("NALPHA"));
    // μ from 1/1024 to 1 and α from 1e-6 to 1, geometric
    let geo = |n: usize, lo: f64, i: usize| lo.powf(1.0 - i as f64 / (n - 1) as f64);
    let pts: Vec<(f64, f64)> = (0..nmu)
        .flat_map(|i| (0..na).map(move |j| (geo(nmu, 1.0 / 1024.0, i), geo(na, 1e-6, j))))
        .collect();
    let tols = [2.5e-8, 1e-7];
    let rows: Vec<Vec<String>> = pts
        .par_iter()
        .map(|&(mu, alpha)| {
            let s = Specular {
                ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
            };
            let (r, re) = if mu == 1.0 {
                normal_view_split_sum(alpha)
            } else {
                let (r, re, _) = split_sum_adaptive(&s, mu, 1e-12);
                (r, re)
            };
            let mut out = Vec::new();
            for tol in tols {
                match ggx_split_sum(mu, alpha, Smith::HeightCorrelated, tol) {
                    Ok(e) => {
                        for c in 0..2 {
                            let d = (e.value[c] - r[c]).abs();
                            let ratio = d / (e.error[c] + re[c] + 1e-12 * r[c].abs().max(1.0));
                            let bad = d > e.error[c] + re[c] + 1e-12 * r[c].abs().max(1.0)
                                || e.error[c] > tol;
                            out.push(format!(
                                "{} {ratio:e} tol={tol:e} mu={mu:.6e} alpha={alpha:.6e} ch{c}: kernel {} est {:e} ref {} est {:e} diff {d:e} evals {}",
                                if bad { "BAD" } else { "ok" },
                                e.value[c], e.error[c], r[c], re[c], e.evals
                            ));
                        }
                    }
                    Err(n) => out.push(format!(
                        "ERR tol={tol:e} mu={mu:.6e} alpha={alpha:.6e}: {n} evaluations"
                    )),
                }
            }
            out
        })
        .collect();
    let (mut bad, mut err, mut worst, mut worst_line) = (0, 0, 0.0f64, String::new());
    for l in rows.iter().flatten() {
        if l.starts_with("BAD") {
            bad += 1;
            println!("{l}");
        } else if l.starts_with("ERR") {
            err += 1;
            println!("{l}");
        }
        if let Some(r) = l.split(' ').nth(1).and_then(|s| s.parse::<f64>().ok()) {
            if r > worst {
                worst = r;
                worst_line = l.clone();
            }
        }
    }
    println!("{} points x {} tolerances x 2 channels: {bad} outside their estimate or tolerance, {err} Err; largest |error|/(estimates + rounding) {worst:.3e}:\n  {worst_line}", pts.len(), tols.len());
}
