//! The estimates of `dielectric-albedo-avg`'s rule (`kernels::dielectric_average`) on
//! Cycles' grids, 16 × 16: α = (j/15)² clamped at r = 1e-4 as the presets clamp it, and
//! x = (k/15)² clamped to [1e-8, 0.9801] with η = (1 − x)/(1 + x) (`glass_inv_Eavg`, each
//! texel by its own rule) or, with `glass`, η = (1 + x)/(1 − x) (`glass_Eavg`, 8
//! consecutive indices per rule as the bake groups them); height-correlated Smith; every
//! texel at the tolerance TOL (the presets' 1e-7) against its own rule at 1e-10: the
//! texels whose error exceeds their own estimate, the largest error and the nodes.
//!
//! `cargo run --release --example eavg_probe [-- inv|glass [TOL]]`
use brdfbake::kernels::dielectric_average::average_albedo;
use brdfbake::model::btdf::SmithForm;
use brdfbake::model::{Ndf, NdfKind};

fn main() {
    let glass = std::env::args().nth(1).as_deref() == Some("glass");
    let tol: f64 = std::env::args()
        .nth(2)
        .map_or(1e-7, |s| s.parse().expect("a tolerance"));
    let smith = SmithForm::HeightCorrelated;
    let etas: Vec<f64> = (0..16)
        .map(|k| {
            let x = (k as f64 / 15.0).powi(2).clamp(1e-8, 0.9801);
            if glass {
                (1.0 + x) / (1.0 - x)
            } else {
                (1.0 - x) / (1.0 + x)
            }
        })
        .collect();
    let (mut max, mut over, mut nodes, mut n) = (0.0f64, 0, 0u64, 0);
    for j in 0..16 {
        let r = (j as f64 / 15.0).clamp(1e-4, 1.0);
        let ndf = Ndf::new(NdfKind::Ggx, r * r).unwrap();
        let group = if glass { 8 } else { 1 };
        for g in etas.chunks(group) {
            let e = average_albedo::<8>(&ndf, smith, g, tol);
            nodes += e.evals;
            for (c, &eta) in g.iter().enumerate() {
                let reference = average_albedo::<1>(&ndf, smith, &[eta], 1e-10);
                let d = (e.value[c] - reference.value[0]).abs();
                max = max.max(d);
                n += 1;
                if d > e.error[c] {
                    over += 1;
                    println!(
                        "  alpha {:.3e} eta {eta:.5}: error {d:.2e} over its estimate {:.2e} (reference estimate {:.1e})",
                        r * r,
                        e.error[c],
                        reference.error[0]
                    );
                }
            }
        }
    }
    println!(
        "{n} texels at {tol:e}: max error {max:.1e}, {over} over their estimate, {:.0} nodes/texel",
        nodes as f64 / n as f64
    );
}
