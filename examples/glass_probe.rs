//! The estimates of `dielectric-albedo`'s η < 1 rule on Cycles' `glass_inv_E` grid
//! (16³: μ = i/15 clamped to 1e-4, α = (j/15)² clamped to 1e-8, (1 − η)/(1 + η) = (k/15)²
//! clamped to [1e-8, 0.9801]; height-correlated Smith): E integrated as one channel (the bake's
//! rule) and as R, T channels summed, against the R, T rule at 1e-10; per variant the texels
//! whose error exceeds their own estimate, the worst ratio, and the nodes.
//!
//! `cargo run --release --example glass_probe [-- tail|standard [TOL]]` (TOL 1e-6; the
//! `cycles-glass-inv-e` preset asks 1e-7), or `-- fibre [TOL]`: the bake's roughness fibres
//! (`kernels::roughness_fibre`, every roughness of one view and index by shared rules)
//! against the same reference.
use brdfbake::kernels::micro_normals::{integrate_micro_normals, Rule};
use brdfbake::kernels::roughness_fibre::{roughness_fibre_with, ROUGHNESS_FIBRE};
use brdfbake::model::btdf::{BelowOne, SmithForm};
use brdfbake::model::fresnel::dielectric;
use brdfbake::model::{Ndf, NdfKind};
use brdfbake::quadrature::cc1d::Estimator;
use brdfbake::table::dielectric::reflect_transmit_etas_with;

fn main() {
    if std::env::args().nth(1).as_deref() == Some("fibre") {
        fibre();
        return;
    }
    let est = match std::env::args().nth(1).as_deref() {
        Some("standard") => Estimator::Standard,
        _ => Estimator::Tail,
    };
    let smith = SmithForm::HeightCorrelated;
    let tol: f64 = std::env::args()
        .nth(2)
        .map_or(1e-6, |s| s.parse().expect("a tolerance"));
    let (mut n, mut bad1, mut bad2, mut w1, mut w2, mut ev1, mut ev2) =
        (0, 0, 0, 0.0f64, 0.0f64, 0u64, 0u64);
    let (mut x1, mut x2, mut m1, mut m2) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for i in 0..16 {
        let mu = (i as f64 / 15.0).max(1e-4);
        for j in 0..16 {
            let r = (j as f64 / 15.0).clamp(1e-4, 1.0);
            let ndf = Ndf::new(NdfKind::Ggx, r * r).unwrap();
            let g1v = ndf.g1(mu.min(1.0));
            for k in 0..16 {
                let x = ((k as f64 / 15.0).powi(2)).clamp(1e-8, 0.9801);
                let eta = (1.0 - x) / (1.0 + x);
                let etas = [eta];
                let rule = Rule {
                    estimator: est,
                    ..Rule::standard(&etas)
                };
                let b = BelowOne::new(eta, mu.min(1.0), g1v);
                let e1 = integrate_micro_normals(&ndf, rule, mu, tol, |h| {
                    let [r, t] = b.integrands(&ndf, smith, h);
                    [r + t]
                });
                let e2 =
                    integrate_micro_normals(&ndf, rule, mu, tol, |h| b.integrands(&ndf, smith, h));
                let re = reflect_transmit_etas_with::<2>(&ndf, smith, &[eta], mu, 1e-10);
                let exact = re.value[0] + re.value[1];
                let d1 = (e1.value[0] - exact).abs();
                let d2 = (e2.value[0] + e2.value[1] - exact).abs();
                let s1 = e1.error[0];
                let s2 = e2.error[0] + e2.error[1];
                n += 1;
                if d1 > s1 {
                    bad1 += 1;
                }
                if d2 > s2 {
                    bad2 += 1;
                }
                w1 = w1.max(d1 / s1.max(1e-300));
                w2 = w2.max(d2 / s2.max(1e-300));
                x1 = x1.max(d1 - s1);
                x2 = x2.max(d2 - s2);
                m1 = m1.max(d1);
                m2 = m2.max(d2);
                ev1 += e1.evals;
                ev2 += e2.evals;
            }
        }
    }
    println!("largest excess over the estimate: one channel {x1:.1e} (max error {m1:.1e}), R, T {x2:.1e} (max error {m2:.1e})");
    println!("{est:?}: {n} texels; E as one channel: {bad1} over their estimate (worst error/estimate {w1:.2}), {:.0} nodes/texel; R, T summed: {bad2} (worst {w2:.2}), {:.0} nodes/texel", ev1 as f64 / n as f64, ev2 as f64 / n as f64);
}

/// The roughness fibres of E on the same grid against the R, T rule at 1e-10.
fn fibre() {
    let smith = SmithForm::HeightCorrelated;
    let tol: f64 = std::env::args()
        .nth(2)
        .map_or(1e-6, |s| s.parse().expect("a tolerance"));
    let ndfs: Vec<Ndf> = (0..16)
        .map(|j| {
            let r = (j as f64 / 15.0).clamp(1e-4, 1.0);
            Ndf::new(NdfKind::Ggx, r * r).unwrap()
        })
        .collect();
    let (mut n, mut bad, mut worst, mut excess, mut max, mut evals) =
        (0, 0, 0.0f64, 0.0f64, 0.0f64, 0u64);
    let t0 = std::time::Instant::now();
    for i in 0..16 {
        let mu = (i as f64 / 15.0).max(1e-4);
        for k in 0..16 {
            let x = ((k as f64 / 15.0).powi(2)).clamp(1e-8, 0.9801);
            let eta = (1.0 - x) / (1.0 + x);
            let got = roughness_fibre_with::<ROUGHNESS_FIBRE, 1>(&ndfs, smith, eta, mu, tol, |c| {
                let f = dielectric(c, eta);
                [[f, 1.0 - f]]
            });
            for (ndf, e) in ndfs.iter().zip(&got) {
                let re = reflect_transmit_etas_with::<2>(ndf, smith, &[eta], mu, 1e-10);
                let d = (e.value[0] - re.value[0] - re.value[1]).abs();
                n += 1;
                bad += usize::from(d > e.error[0]);
                worst = worst.max(d / e.error[0].max(1e-300));
                excess = excess.max(d - e.error[0]);
                max = max.max(d);
                evals += e.evals;
            }
        }
    }
    println!(
        "fibres at {tol:.0e}: {n} texels, {bad} over their estimate (worst error/estimate {worst:.2}, largest excess {excess:.1e}), max error {max:.1e}, {:.0} nodes/texel ({:.2} s with the references)",
        evals as f64 / n as f64,
        t0.elapsed().as_secs_f64()
    );
}
