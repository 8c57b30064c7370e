//! Cost of the rough dielectric integrator (src/table/dielectric.rs) per η slice of the
//! `dielectric-btdf` preset's grid (N × N texels of perceptual roughness and cos θv at texel
//! centres, η = (1 + p)/(1 − p), p = −0.5 … 0.5 in 8 endpoints), texel by texel on one thread:
//! evaluations per texel, the largest estimate, CPU ms.
//!
//! `cargo run --release --example diel_probe [-- N TOL]` (default 16, 1e-6)
use brdfbake::model::btdf::RoughDielectric;
use brdfbake::model::{Ndf, NdfKind};
use brdfbake::table::dielectric::reflect_transmit;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map_or(16, |s| s.parse().unwrap());
    let tol: f64 = args.get(2).map_or(1e-6, |s| s.parse().unwrap());
    for k in 0..8 {
        let p = -0.5 + k as f64 / 7.0;
        let eta = (1.0 + p) / (1.0 - p);
        let mut ev = 0u64;
        let mut maxerr: f64 = 0.0;
        let t0 = std::time::Instant::now();
        for j in 0..n {
            let r = (j as f64 + 0.5) / n as f64;
            let m = RoughDielectric {
                ndf: Ndf::new(NdfKind::Ggx, r * r).unwrap(),
                eta,
            };
            for i in 0..n {
                let mu = (i as f64 + 0.5) / n as f64;
                let e = reflect_transmit(&m, mu, tol);
                ev += e.evals;
                maxerr = maxerr.max(e.error[0]).max(e.error[1]);
            }
        }
        println!(
            "eta {eta:.3}: evals/texel {:.0}  est {maxerr:.2e}  {:.1} ms",
            ev as f64 / (n * n) as f64,
            t0.elapsed().as_secs_f64() * 1e3
        );
    }
}
