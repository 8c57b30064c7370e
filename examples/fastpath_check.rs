//! Compares the fast tensor rule with the adaptive integrator (at a 1000× tighter
//! tolerance) on a strided subset of the filament-dfg grid.
//! `cargo run --release --example fastpath_check -- [stride] [size] [tol]`
#![allow(clippy::needless_range_loop)]

use brdfbake::hemisphere::integrate_over_l;
use brdfbake::hemisphere::tensor::{integrate_over_l_cc, InnerWarp};
use brdfbake::model::fresnel::schlick_weight;
use brdfbake::model::{Fresnel, Masking, Ndf, NdfKind, Specular};
use rayon::prelude::*;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let stride: usize = a.get(1).map_or(4, |s| s.parse().unwrap());
    let size: usize = a.get(2).map_or(128, |s| s.parse().unwrap());
    let tol: f64 = a.get(3).map_or(1e-7, |s| s.parse().unwrap());
    let pts: Vec<(usize, usize)> = (0..size)
        .step_by(stride)
        .flat_map(|j| (0..size).step_by(stride).map(move |i| (i, j)))
        .collect();
    let res: Vec<_> = pts
        .par_iter()
        .map(|&(i, j)| {
            let mu = (i as f64 + 0.5) / size as f64;
            let r = (j as f64 + 0.5) / size as f64;
            let alpha = r * r;
            let spec = Specular {
                ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
            };
            let sheen = Specular {
                ndf: Ndf::new(NdfKind::Charlie, alpha).unwrap(),
                masking: Masking::Ashikhmin,
                fresnel: Fresnel::None,
            };
            let gs = |n: &brdfbake::hemisphere::Node| {
                let f = spec.cosine_weighted_with(n, 1.0);
                let fc = schlick_weight(n.v_dot_h);
                [f * (1.0 - fc), f * fc]
            };
            let gc = |n: &brdfbake::hemisphere::Node| [sheen.cosine_weighted(n)];
            let rs = integrate_over_l(mu, spec.ndf.warp(), tol * 1e-3, gs);
            let rc = integrate_over_l(mu, sheen.ndf.warp(), tol * 1e-3, gc);
            let fs = integrate_over_l_cc(mu, InnerWarp::for_ndf(&spec.ndf), tol, gs);
            let fcl = integrate_over_l_cc(mu, InnerWarp::for_ndf(&sheen.ndf), tol, gc);
            (mu, alpha, rs, rc, fs, fcl)
        })
        .collect();
    let mut worst = [0.0f64; 3];
    let mut under = 0;
    let (mut fb_s, mut fb_c, mut ev_s, mut ev_c, mut n_s, mut n_c) = (0, 0, 0u64, 0u64, 0u64, 0u64);
    for (mu, alpha, rs, rc, fs, fc) in &res {
        match fs {
            Some(f) => {
                n_s += 1;
                ev_s += f.evals;
                for c in 0..2 {
                    let d = (f.value[c] - rs.value[c]).abs();
                    worst[c] = worst[c].max(d);
                    if d > f.error[c] + rs.error[c] {
                        under += 1;
                        if d > 1e-8 {
                            println!(
                                "underest spec mu={mu} a={alpha} c={c} d={d:e} est={:e}",
                                f.error[c]
                            );
                        }
                    }
                }
            }
            None => {
                fb_s += 1;
                println!("fallback spec mu={mu} a={alpha}");
            }
        }
        match fc {
            Some(f) => {
                n_c += 1;
                ev_c += f.evals;
                let d = (f.value[0] - rc.value[0]).abs() / rc.value[0].max(1.0);
                worst[2] = worst[2].max(d);
                if d > f.error[0] + rc.error[0] {
                    under += 1;
                    if d > 1e-8 {
                        println!(
                            "underest sheen mu={mu} a={alpha} d={d:e} est={:e}",
                            f.error[0]
                        );
                    }
                }
            }
            None => {
                fb_c += 1;
                println!("fallback sheen mu={mu} a={alpha}");
            }
        }
    }
    println!(
        "texels {} worst R/G-ish {:e} {:e} sheen {:e}; fallbacks spec {fb_s} sheen {fb_c}; mean evals spec {} sheen {}; underestimates {under}",
        res.len(),
        worst[0],
        worst[1],
        worst[2],
        ev_s / n_s.max(1),
        ev_c / n_c.max(1)
    );
}
