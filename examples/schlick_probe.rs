//! Cost and accuracy of the micro-normal rule on EEVEE's `bsdf_ggx` grid (η < 1,
//! critical-angle view axis) and `btdf_ggx` grid (η > 1): a subset of texels (every `S`th
//! per axis), nodes per texel, CPU ms on one thread, the largest estimate and the largest
//! and median true error against the same rule at tolerance 1e-12.
//!
//! `cargo run --release --example schlick_probe [-- bsdf|btdf S]`, or `-- one ALPHA ETA MU`
//! for one texel's value, estimate and nodes: the texel rule; the
//! `btdf` grid's bake shares rules across η (`dielectric_schlick::fibre_fn`), whose nodes
//! the bake's sidecar counts.
use brdfbake::kernels::micro_normals::{integrate_micro_normals, Rule};
use brdfbake::model::btdf::{MicroNormal, SmithForm};
use brdfbake::model::schlick_dielectric::integrands;
use brdfbake::model::{Ndf, NdfKind};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("bsdf", |s| s.as_str()).to_string();
    let step: usize = args.get(2).map_or(4, |s| s.parse().unwrap_or(4));
    let tol = 1e-6;
    let mut texels = Vec::new();
    if which == "one" {
        let v: Vec<f64> = args[2..5].iter().map(|s| s.parse().unwrap()).collect();
        let ndf = Ndf::new(NdfKind::Ggx, v[0]).unwrap();
        let (eta, mu) = (v[1], v[2]);
        let g1v = ndf.g1(mu);
        let e =
            integrate_micro_normals(&ndf, Rule::standard(&[eta]), mu, tol, |h: &MicroNormal| {
                integrands(&ndf, SmithForm::Separable, eta, mu, g1v, h)
            });
        println!("{e:?}");
        return;
    }
    for k in (1..16).step_by(2) {
        let r = k as f64 / 15.0;
        let alpha = r * r;
        for i in (0..64).step_by(step) {
            for j in (0..64).step_by(step) {
                let p = j as f64 / 63.0;
                let (eta, mu) = if which == "bsdf" {
                    let eta = (i as f64 / 63.0).clamp(1e-4, 0.9999).sqrt();
                    let c = (1.0 - eta * eta).sqrt();
                    let t = 2.0 * p - 1.0;
                    let mu = if t < 0.0 {
                        c + t * c
                    } else {
                        c + t * (1.0 - c)
                    };
                    (eta, mu.clamp(1e-4, 0.9999))
                } else {
                    let u = i as f64 / 63.0;
                    let f0 = (u * u).clamp(1e-4, 0.9801);
                    let s = f0.sqrt();
                    let eta = (1.0 + s) / (1.0 - s);
                    let mu = (1.0 - p * p).clamp(1e-4, 0.9999);
                    (eta, mu)
                };
                texels.push((alpha, eta, mu));
            }
        }
    }
    let run = |tol: f64| {
        let mut out = Vec::with_capacity(texels.len());
        let mut evals = 0u64;
        let t0 = std::time::Instant::now();
        for &(alpha, eta, mu) in &texels {
            let ndf = Ndf::new(NdfKind::Ggx, alpha).unwrap();
            let g1v = ndf.g1(mu);
            let e = integrate_micro_normals(
                &ndf,
                Rule::standard(&[eta]),
                mu,
                tol,
                |h: &MicroNormal| integrands(&ndf, SmithForm::Separable, eta, mu, g1v, h),
            );
            evals += e.evals;
            out.push(e);
        }
        (out, evals, t0.elapsed().as_secs_f64())
    };
    let (got, evals, secs) = run(tol);
    let (reference, _, _) = run(1e-12);
    let mut errs = Vec::new();
    let mut est: f64 = 0.0;
    let mut bad = 0;
    for (g, r) in got.iter().zip(&reference) {
        for c in 0..3 {
            let e = (g.value[c] - r.value[c]).abs();
            errs.push(e);
            est = est.max(g.error[c]);
            if e > g.error[c] || e > tol {
                bad += 1;
            }
        }
    }
    errs.sort_by(f64::total_cmp);
    let mut by: Vec<(u64, usize)> = got.iter().enumerate().map(|(i, e)| (e.evals, i)).collect();
    by.sort();
    for &(n, i) in by
        .iter()
        .rev()
        .take(6)
        .chain(by.iter().skip(by.len() / 2).take(3))
    {
        println!(
            "  {n} nodes at alpha {:.4} eta {:.4} mu {:.4}",
            texels[i].0, texels[i].1, texels[i].2
        );
    }
    println!(
        "{which}: {} texels, {:.0} nodes/texel, {:.1} µs/texel ({:.0} ns/node), est max {est:.1e}, true max {:.1e} median {:.1e}, over estimate or tol: {bad}",
        texels.len(),
        evals as f64 / texels.len() as f64,
        secs * 1e6 / texels.len() as f64,
        secs * 1e9 / evals as f64,
        errs.last().unwrap(),
        errs[errs.len() / 2],
    );
}
