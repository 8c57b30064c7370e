//! Accuracy and cost of the Charlie light-cosine kernel (src/kernels/sheen_polar.rs) with
//! Conty–Kulla's masking (plain and softened) on a grid of views μ and Charlie α, against
//! the independent reference (tests/common/reference.rs, l-space adaptive Gauss–Legendre,
//! Λ written there again) for α ≥ 0.01 and the library's adaptive integrator below: for
//! each point, |kernel − reference| must be within both estimates (+ 1e-12 rounding) and
//! the estimate within the tolerance. Prints violations, declined points, the worst ratio
//! and the kernel's evaluations and time per texel.
//!
//! ```text
//! cargo run --release --example sheen_polar_check -- [NMU] [NALPHA] [TOL] [all]   (defaults 12 12 1e-7)
//! cargo run --release --example sheen_polar_check -- probe MU ALPHA [TOL]
//! ```

use brdfbake::model::Brdf;
use brdfbake::model::{Fresnel, Masking, Ndf, NdfKind, Specular};
use brdfbake::table::albedo::{directional_albedo, directional_albedo_adaptive};
use rayon::prelude::*;

#[path = "../tests/common/reference.rs"]
mod reference;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).is_some_and(|a| a == "probe") {
        let (mu, alpha): (f64, f64) = (args[2].parse().unwrap(), args[3].parse().unwrap());
        let tol: f64 = args.get(4).map_or(1e-7, |s| s.parse().unwrap());
        let b = brdf(alpha, Masking::ContyKulla);
        println!("{:?}", directional_albedo(&b, mu, tol));
        return;
    }
    let nmu: usize = args.get(1).map_or(12, |s| s.parse().unwrap());
    let na: usize = args.get(2).map_or(12, |s| s.parse().unwrap());
    let tol: f64 = args.get(3).map_or(1e-7, |s| s.parse().unwrap());
    let geo = |lo: f64, hi: f64, i: usize, n: usize| lo * (hi / lo).powf(i as f64 / (n - 1) as f64);
    let mut pts = Vec::new();
    for m in [Masking::ContyKulla, Masking::ContyKullaSoftened] {
        for i in 0..nmu {
            for j in 0..na {
                pts.push((geo(1e-3, 1.0, i, nmu), geo(1e-3, 1.0, j, na), m));
            }
        }
    }
    let t0 = std::time::Instant::now();
    let mut evals = 0u64;
    for &(mu, alpha, m) in &pts {
        let b = brdf(alpha, m);
        evals += directional_albedo(&b, mu, tol).2;
    }
    let per = t0.elapsed().as_secs_f64() / pts.len() as f64;
    println!(
        "{} points: {:.1} µs and {:.0} evaluations per texel (one thread)",
        pts.len(),
        per * 1e6,
        evals as f64 / pts.len() as f64
    );
    let out: Vec<(String, f64)> = pts
        .par_iter()
        .map(|&(mu, alpha, m)| {
            let b = brdf(alpha, m);
            let (v, e, n) = directional_albedo(&b, mu, tol);
            let (r, re) = if alpha >= 0.01 {
                let rm = reference::RefModel::new(NdfKind::Charlie, alpha, m);
                let r = reference::albedo(&rm, mu, 1e-10);
                (r.value[0], r.error)
            } else {
                let (r, re, _) = directional_albedo_adaptive(&b, mu, 1e-10);
                (r[0], re[0])
            };
            let d = (v[0] - r).abs();
            let bound = e[0] + re + 1e-12 * r.abs().max(1.0);
            let bad = d > bound || e[0] > tol;
            let line = format!(
                "{m:?} mu={mu:.4e} alpha={alpha:.4e}: kernel {} est {:.1e} ({n} evals) ref {r} est {re:.1e} diff {d:.1e}{}",
                v[0],
                e[0],
                if bad { "  <-- VIOLATION" } else { "" }
            );
            (line, d / bound)
        })
        .collect();
    let mut worst = 0.0f64;
    for (l, ratio) in &out {
        worst = worst.max(*ratio);
        if l.contains("VIOLATION") || args.iter().any(|a| a == "all") {
            println!("{l}");
        }
    }
    println!("worst |error|/bound {worst:.3}");
}

fn brdf(alpha: f64, m: Masking) -> Brdf {
    Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Charlie, alpha).unwrap(),
            masking: m,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
        diffuse: brdfbake::model::DiffuseLobe::Lambert,
    }
}
