//! The LTC fit of every model the `ltc` kind accepts on a small grid, with the fit's
//! options given on the command line: per model, the lit error `Σ|X − Y|/ΣY` of the probe
//! quads (as `tests/ltc_models.rs` judges it) at the worst texel and the largest
//! `cond(M⁻¹)·α·μ`. For choosing the fit's floors (docs/presets.md, BENCHMARKS.md).
//!
//! ```text
//! cargo run --release --example ltc_models_check -- [--peak-floor K] [--floor F] [--side N]
//!                                                  [--models a,b,...] [--mus a,b,...]
//!                                                  [--heitz STRIDE]
//! ```
//! `--heitz STRIDE`: Heitz's 64² grid instead (fitted whole, as a bake fits it), judged at
//! every STRIDE-th view and roughness from the first: the distribution of the lit error over
//! those texels and the worst five. Texels whose norm is within the table's tolerance of 0
//! are not judged (every lit value is within it of 0; the fit leaves them the cosine).

use brdfbake::kernels::ltc_check::{lit_reference, PolygonLight};
use brdfbake::kernels::ltc_fit::{fit_grid, LtcFitOptions};
use brdfbake::kernels::ltc_polygon::ltc_polygon_integral;
use brdfbake::kernels::ltc_probe::probe_quads;
use rayon::prelude::*;
use std::time::Instant;

#[path = "../tests/common/ltc_models.rs"]
mod ltc_models;
use ltc_models::MODELS;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |f: &str| {
        args.iter()
            .position(|a| a == f)
            .and_then(|i| args.get(i + 1).cloned())
    };
    let mut opts = LtcFitOptions::default();
    let fixed_floor = value("--peak-floor").map(|v| v.parse::<f64>().expect("--peak-floor K"));
    if let Some(v) = value("--floor") {
        opts.floor = v.parse().expect("--floor F");
    }
    let side: usize = value("--side").map_or(3, |v| v.parse().expect("--side N"));
    let only: Option<Vec<String>> =
        value("--models").map(|v| v.split(',').map(str::to_string).collect());
    let lights: Vec<PolygonLight> = probe_quads()
        .into_iter()
        .take(48)
        .map(|q| PolygonLight {
            verts: q.to_vec(),
            crosses_horizon: false,
        })
        .collect();
    let grid = |n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| 0.35 + 0.65 * i as f64 / (n - 1).max(1) as f64)
            .collect()
    };
    let heitz: Option<usize> = value("--heitz").map(|v| v.parse().expect("--heitz STRIDE"));
    let mus: Vec<f64> = value("--mus").map_or_else(
        || grid(side),
        |v| {
            v.split(',')
                .map(|x| x.parse().expect("--mus a,b"))
                .collect()
        },
    );
    let mut alphas: Vec<f64> = grid(side).iter().map(|r| r * r).collect();
    let mut mus = mus;
    if heitz.is_some() {
        (mus, alphas) = brdfbake::table::ltc_layout::heitz_axes(64);
    }
    let judged = |i: usize, n: usize| match heitz {
        Some(st) => i.is_multiple_of(st) && i < n,
        None => true,
    };
    for (name, model) in MODELS {
        if only.as_ref().is_some_and(|o| !o.iter().any(|m| m == name)) {
            continue;
        }
        let text = format!(
            r#"{{ "schema": "brdfbake.preset/1", "tables": [ {{ "name": "t", "kind": "ltc", "model": {model},
            "axes": {{ "cos_theta_v": {{ "size": 2, "range": [0.35, 1] }},
                      "roughness": {{ "size": 2, "range": [0.35, 1], "quantity": "perceptual" }} }},
            "formats": ["exr"] }} ] }}"#
        );
        let spec = match brdfbake::preset::parse(&text, "check", "models") {
            Ok(p) => p.tables[0].spec.clone(),
            Err(e) => {
                println!("{name}: {e}");
                continue;
            }
        };
        let mut o = brdfbake::table::ltc::fit_options(&spec);
        o.floor = opts.floor;
        if let Some(k) = fixed_floor {
            o.peak_floor = k;
        }
        let model = |a: f64| spec.model.brdf(a);
        let t0 = Instant::now();
        let g = fit_grid(&model, &mus, &alphas, &o).expect("fit");
        let secs = t0.elapsed().as_secs_f64();
        let per: Vec<(f64, f64, f64, f64)> = g
            .texels
            .par_iter()
            .enumerate()
            .filter(|(k, t)| {
                judged(k / alphas.len(), mus.len())
                    && judged(k % alphas.len(), alphas.len())
                    && t.norm > o.tolerance
            })
            .map(|(k, t)| {
                let (mu, alpha) = (mus[k / alphas.len()], alphas[k % alphas.len()]);
                let brdf = spec.model.brdf(alpha).unwrap();
                if let Some(s) = &brdf.specular {
                    s.prepare();
                }
                let (mut num, mut den) = (0.0, 0.0);
                for l in &lights {
                    let y = lit_reference(&brdf, alpha, mu, l, 1e-6).unwrap().value;
                    let x = t.norm * ltc_polygon_integral(&t.ltc, &l.verts).unwrap();
                    num += (x - y).abs();
                    den += y;
                }
                (mu, alpha, num / den, t.ltc.condition_number() * alpha * mu)
            })
            .collect();
        let worst = per.iter().map(|p| p.2).fold(0.0, f64::max);
        let cond = per.iter().map(|p| p.3).fold(0.0, f64::max);
        println!(
            "{name}: peak_floor {:e}: lit error worst {worst:.4}, largest cond*alpha*mu {cond:.3}, fit {secs:.2} s",
            o.peak_floor
        );
        if heitz.is_some() {
            // the conditioning of every texel, the grazing row included
            let all = g
                .texels
                .iter()
                .enumerate()
                .map(|(k, t)| {
                    let (mu, alpha) = (mus[k / alphas.len()], alphas[k % alphas.len()]);
                    (t.ltc.condition_number() * alpha * mu, mu, alpha, t.norm)
                })
                .fold((0.0, 0.0, 0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
            println!(
                "    all {} texels: largest cond*alpha*mu {:.3} (mu {:.5}, alpha {:.3e}, norm {:.3e})",
                g.texels.len(),
                all.0,
                all.1,
                all.2,
                all.3
            );
            if per.is_empty() {
                println!("    no texel judged");
                continue;
            }
            let mut e: Vec<f64> = per.iter().map(|p| p.2).collect();
            e.sort_by(f64::total_cmp);
            let q = |p: f64| e[((e.len() - 1) as f64 * p).round() as usize];
            println!(
                "    {} texels judged: lit error median {:.4}, p90 {:.4}, max {:.4}",
                e.len(),
                q(0.5),
                q(0.9),
                q(1.0)
            );
            let mut w = per.clone();
            w.sort_by(|a, b| b.2.total_cmp(&a.2));
            w.truncate(5);
            for p in &w {
                println!(
                    "    worst: mu {:.5} alpha {:.3e}: lit error {:.4}, cond*alpha*mu {:.3}",
                    p.0, p.1, p.2, p.3
                );
            }
            continue;
        }
        for (p, t) in per.iter().zip(&g.texels) {
            let l = t.ltc;
            println!(
                "    mu {:.3} alpha {:.4}: lit error {:.4}, cond*alpha*mu {:.3}; M^-1 a {:.4} b {:.4} c {:.4} d {:.4}",
                p.0, p.1, p.2, p.3, l.a, l.b, l.c, l.d
            );
        }
    }
}
