//! The fibre path of `dielectric-btdf` and `albedo-fresnel` (src/table/dielectric.rs,
//! src/table/energy.rs) against the per-texel path on the default presets' tables: integrand
//! evaluations per texel (nodes, counted once however many slices they serve), single-thread
//! CPU time of each path, and the largest difference between the two, absolute and relative
//! to the sum of both estimates (must stay ≤ 1). `union` also times the η < 1 slices of the
//! btdf as one shared rule (union of their breakpoints) instead of one rule each.
//!
//! `cargo run --release --example fibre_check [-- union]`
use brdfbake::model::btdf::RoughDielectric;
use brdfbake::model::{Fresnel, Ndf, NdfKind};
use brdfbake::table::albedo::directional_albedo;
use brdfbake::table::dielectric::{
    reflect_transmit, reflect_transmit_etas, reflect_transmit_fibre,
};
use brdfbake::table::energy::{directional_albedo_fresnels, fresnel_of_slice};
use std::time::Instant;

fn table(preset: &str, name: &str) -> brdfbake::TableSpec {
    let p = brdfbake::preset::load(std::path::Path::new(preset)).expect("preset");
    p.tables
        .into_iter()
        .find(|t| t.spec.name == name)
        .expect("table")
        .spec
}

fn main() {
    let union = std::env::args().any(|a| a == "union");
    // dielectric-btdf
    let spec = table("presets/dielectric-btdf.json", "btdf");
    let (nx, ny, nz) = (spec.axes[0].size, spec.axes[1].size, spec.axes[2].size);
    let etas: Vec<f64> = (0..nz)
        .map(|z| match fresnel_of_slice(&spec, z) {
            Fresnel::Dielectric { eta } => eta,
            _ => unreachable!(),
        })
        .collect();
    let tol = spec.tolerance;
    let (mut ev_f, mut ev_t, mut t_f, mut t_t) = (vec![0u64; nz], vec![0u64; nz], 0.0, 0.0);
    let (mut dmax, mut ratio) = (0.0f64, 0.0f64);
    let (mut ev_u, mut t_u) = (0u64, 0.0);
    for j in 0..ny {
        let ndf = Ndf::new(NdfKind::Ggx, spec.axes[1].alpha(j).unwrap()).unwrap();
        for i in 0..nx {
            let mu = spec.axes[0].coord(i);
            let t0 = Instant::now();
            let fib = reflect_transmit_fibre(&ndf, &etas, mu, tol);
            t_f += t0.elapsed().as_secs_f64();
            for z in 0..nz {
                let t0 = Instant::now();
                let e = reflect_transmit(
                    &RoughDielectric {
                        ndf: ndf.clone(),
                        eta: etas[z],
                    },
                    mu,
                    tol,
                );
                t_t += t0.elapsed().as_secs_f64();
                ev_t[z] += e.evals;
                ev_f[z] += fib[z].2;
                for c in 0..2 {
                    let d = (fib[z].0[c] - e.value[c]).abs();
                    dmax = dmax.max(d);
                    ratio = ratio.max(d / (fib[z].1[c] + e.error[c]).max(1e-300));
                }
            }
            if union {
                let below: Vec<f64> = etas.iter().copied().filter(|&e| e < 1.0).collect();
                let t0 = Instant::now();
                let e = reflect_transmit_etas::<8>(&ndf, &below, mu, tol);
                t_u += t0.elapsed().as_secs_f64();
                ev_u += e.evals;
            }
        }
    }
    let per = (nx * ny) as f64;
    println!("dielectric-btdf/btdf ({nx}x{ny}x{nz}, tol {tol:e}):");
    for z in 0..nz {
        println!(
            "  eta {:.3}: evaluations per texel per-texel {:>6.0}  fibre {:>6.0} (group total at its first slice)",
            etas[z], ev_t[z] as f64 / per, ev_f[z] as f64 / per
        );
    }
    let (sf, st): (u64, u64) = (ev_f.iter().sum(), ev_t.iter().sum());
    println!(
        "  total: per-texel {st} evaluations ({:.0}/texel) {:.1} ms; fibre {sf} ({:.0}/texel) {:.1} ms; max |diff| {dmax:.2e}, max |diff|/(est1+est2) {ratio:.3}",
        st as f64 / (per * nz as f64), t_t * 1e3, sf as f64 / (per * nz as f64), t_f * 1e3
    );
    if union {
        println!(
            "  eta < 1 slices as one shared rule (union of breaks): {ev_u} evaluations ({:.0} per fibre), {:.1} ms",
            ev_u as f64 / per, t_u * 1e3
        );
    }

    // fresnel-albedo/e-dielectric
    let spec = table("presets/fresnel-albedo.json", "e-dielectric");
    let (nx, ny, nz) = (spec.axes[0].size, spec.axes[1].size, spec.axes[2].size);
    let tol = spec.tolerance;
    let fres: Vec<Fresnel> = (0..nz).map(|z| fresnel_of_slice(&spec, z)).collect();
    let (mut ev_f, mut ev_t, mut t_f, mut t_t) = (0u64, 0u64, 0.0, 0.0);
    let (mut dmax, mut ratio) = (0.0f64, 0.0f64);
    for j in 0..ny {
        let brdf = spec.model.brdf(spec.axes[1].alpha(j).unwrap()).unwrap();
        for i in 0..nx {
            let mu = spec.axes[0].coord(i);
            let t0 = Instant::now();
            let fib = directional_albedo_fresnels(&brdf, &fres, mu, tol);
            t_f += t0.elapsed().as_secs_f64();
            for z in 0..nz {
                let mut m = spec.model.clone();
                m.fresnel = fres[z];
                let b = m.brdf(spec.axes[1].alpha(j).unwrap()).unwrap();
                let t0 = Instant::now();
                let (v, e, n) = directional_albedo(&b, mu, tol);
                t_t += t0.elapsed().as_secs_f64();
                ev_t += n;
                ev_f += fib[z].2;
                let d = (fib[z].0[0] - v[0]).abs();
                dmax = dmax.max(d);
                ratio = ratio.max(d / (fib[z].1[0] + e[0]).max(1e-300));
            }
        }
    }
    let n = (nx * ny * nz) as f64;
    println!(
        "fresnel-albedo/e-dielectric ({nx}x{ny}x{nz}, tol {tol:e}): per-texel {ev_t} evaluations ({:.0}/texel) {:.1} ms; fibre {ev_f} ({:.0}/texel) {:.1} ms; max |diff| {dmax:.2e}, max |diff|/(est1+est2) {ratio:.3}",
        ev_t as f64 / n, t_t * 1e3, ev_f as f64 / n, t_f * 1e3
    );
}
