//! Cost and accuracy of the micro-normal rule on EEVEE's `bsdf_ggx` grid (η < 1,
//! critical-angle view axis) and `btdf_ggx` grid (η > 1): a subset of texels (every `S`th
//! per axis), nodes per texel, CPU ms on one thread, the largest estimate and the largest
//! and median true error against the same rule at tolerance 1e-12.
//!
//! `cargo run --release --example schlick_probe [-- bsdf|btdf S]`, or `-- one ALPHA ETA MU`
//! for one texel's value, estimate and nodes: the texel rule; the
//! `btdf` grid's bake shares rules across η (`dielectric_schlick::fibre_fn`), whose nodes
//! the bake's sidecar counts. `-- fibre S`: the `bsdf` grid's bake, which shares rules across
//! the roughness layers (`kernels::roughness_fibre`), against the texel rule: nodes, time
//! and both errors against the texel rule at 1e-12.
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
    if which == "fibre" {
        fibre(step, tol);
        return;
    }
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

/// EEVEE's `bsdf_ggx` grid (every `step`th η and view texel, all 15 roughness layers): each
/// texel by its own rule and by the roughness fibres of the bake; nodes, time, and both
/// errors against the texel rule at 1e-12.
fn fibre(step: usize, tol: f64) {
    use brdfbake::kernels::roughness_fibre::{roughness_fibre_with, ROUGHNESS_FIBRE};
    use brdfbake::model::schlick_dielectric::outer_schlick_weight;
    let smith = SmithForm::Separable;
    let ndfs: Vec<Ndf> = (1..16)
        .map(|k| Ndf::new(NdfKind::Ggx, (k as f64 / 15.0).powi(2)).unwrap())
        .collect();
    let mut views = Vec::new();
    for i in (0..64).step_by(step) {
        for j in (0..64).step_by(step) {
            let eta = (i as f64 / 63.0).clamp(1e-4, 0.9999).sqrt();
            let c = (1.0 - eta * eta).sqrt();
            let t = 2.0 * (j as f64 / 63.0) - 1.0;
            let mu = if t < 0.0 {
                c + t * c
            } else {
                c + t * (1.0 - c)
            };
            views.push((eta, mu.clamp(1e-4, 0.9999)));
        }
    }
    let one = |ndf: &Ndf, eta: f64, mu: f64, tol: f64| {
        let g1v = ndf.g1(mu);
        integrate_micro_normals(ndf, Rule::standard(&[eta]), mu, tol, |h: &MicroNormal| {
            integrands(ndf, smith, eta, mu, g1v, h)
        })
    };
    let t0 = std::time::Instant::now();
    let (mut ev1, mut v1) = (0u64, Vec::new());
    for &(eta, mu) in &views {
        for ndf in &ndfs {
            let e = one(ndf, eta, mu, tol);
            ev1 += e.evals;
            v1.push(e);
        }
    }
    let s1 = t0.elapsed().as_secs_f64();
    let t0 = std::time::Instant::now();
    let (mut ev2, mut v2) = (0u64, Vec::new());
    for &(eta, mu) in &views {
        let got =
            roughness_fibre_with::<{ 3 * ROUGHNESS_FIBRE }, 3>(&ndfs, smith, eta, mu, tol, |c| {
                let s = outer_schlick_weight(eta, c);
                [[1.0 - s, 0.0], [s, 0.0], [0.0, 1.0 - s]]
            });
        ev2 += got.iter().map(|e| e.evals).sum::<u64>();
        v2.extend(got);
    }
    let s2 = t0.elapsed().as_secs_f64();
    let (mut m1, mut m2, mut bad1, mut bad2) = (0.0f64, 0.0f64, 0, 0);
    let mut k = 0;
    for &(eta, mu) in &views {
        for ndf in &ndfs {
            let r = one(ndf, eta, mu, 1e-12).value;
            for (c, &r) in r.iter().enumerate() {
                let e1 = (v1[k].value[c] - r).abs();
                let e2 = (v2[k].value[c] - r).abs();
                m1 = m1.max(e1);
                m2 = m2.max(e2);
                bad1 += usize::from(e1 > v1[k].error[c] || e1 > tol);
                bad2 += usize::from(e2 > v2[k].error[c] || e2 > tol);
            }
            k += 1;
        }
    }
    let n = v1.len() as f64;
    println!(
        "texel rule: {:.0} nodes/texel, {:.1} ms, true max {m1:.1e}, over estimate or tol: {bad1}",
        ev1 as f64 / n,
        s1 * 1e3
    );
    println!(
        "roughness fibres: {:.0} nodes/texel, {:.1} ms, true max {m2:.1e}, over estimate or tol: {bad2}",
        ev2 as f64 / n,
        s2 * 1e3
    );
}
