//! The V-groove fast path (src/kernels/vgroove.rs: the tensor rule on the smooth branches
//! of Cook–Torrance's masking term) against the independent reference integrator
//! (`tests/common/reference.rs`: l-space polar coordinates, adaptive Gauss–Legendre, the
//! V-groove kink in l-space as an explicit breakpoint, BRDF terms re-implemented from their
//! formulas; nothing in it uses `brdfbake::integrate`).
//!
//! Tolerances:
//! * `LIB_TOL = 1e-7`: the presets' default per-texel tolerance, asked of the library.
//! * every library value must be within its own error estimate of the reference, plus the
//!   reference's estimate, plus 1e-15 (so that exact ties cannot fail on rounding): both
//!   estimates claim to bound their own errors, so their sum bounds the difference; a
//!   failure means the fast path's estimate is optimistic (false convergence).
//! * and within `LIB_TOL` itself (the estimate the library reports is ≤ `LIB_TOL` by
//!   construction: the tolerance shares of the pieces plus the tail cut add up to it).

#[path = "common/reference.rs"]
mod reference;

use brdfbake::hemisphere::Node;
use brdfbake::kernels::vgroove::{
    beckmann_vgroove_albedo, integrate_over_l_kinked, integrate_over_l_vgroove_cc, TailCut,
};
use brdfbake::model::fresnel::dielectric_one_division;
use brdfbake::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
use brdfbake::table::albedo::directional_albedo;
use rayon::prelude::*;
use reference::RefModel;

const LIB_TOL: f64 = 1e-7;
/// The reference's target: its estimates are then ≤ 1e-13 at these points (see
/// tests/accuracy.rs), far below the library's.
const REF_TOL: f64 = 1e-10;

fn specular(kind: NdfKind, alpha: f64, fresnel: Fresnel) -> Specular {
    Specular {
        ndf: Ndf::new(kind, alpha).unwrap(),
        masking: Masking::VGroove,
        fresnel,
    }
}

/// The reference albedo with a Fresnel factor of v·h.
fn reference_albedo<Fr: Fn(f64) -> f64 + Sync>(
    kind: NdfKind,
    alpha: f64,
    mu: f64,
    fr: Fr,
) -> (f64, f64) {
    let m = RefModel::new(kind, alpha, Masking::VGroove);
    let e = reference::over_l_kinked(
        mu,
        reference::lobe_scale(&m),
        REF_TOL,
        |d| [m.f_cos(mu, d).map_or(0.0, |(f, vh)| f * fr(vh))],
        |ct, st| m.phi_kink(mu, ct, st),
    );
    (e.value[0], e.error)
}

fn assert_none(what: &str, failures: &[String]) {
    assert!(
        failures.is_empty(),
        "{what}: {} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The `cook-torrance-1982` preset's `albedo` table (Beckmann, Cook–Torrance m = α at 32
/// endpoints in [0.05, 1], V-groove, dielectric Fresnel η = 1.5, n·v at 32 texel centres):
/// every one of its 1,024 texels takes the closed-form kernel (`beckmann_vgroove_albedo`:
/// `Ok`, no texel falls back to the adaptive integrator, which would cost ~100× more) and
/// the table driver returns its result bit for bit; at every texel the kernel agrees with
/// the fast path on the generic integrand (the library's D, G = min(…) and Fresnel at
/// each node: a different formula for the same integral on the same nodes) within the sum
/// of both estimates (each claims to bound its own error); and at an 8×8 subset — the
/// grazing column, the narrowest lobe and the normal view included — the kernel's value
/// is within its estimate of the independent reference and within `LIB_TOL`.
#[test]
fn cook_torrance_albedo_takes_the_fast_path_and_matches_reference() {
    let n = 32;
    let mus: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect();
    let ms: Vec<f64> = (0..n)
        .map(|j| 0.05 + 0.95 * j as f64 / (n - 1) as f64)
        .collect();
    let fresnel = Fresnel::Dielectric { eta: 1.5 };
    let texels: Vec<(f64, f64)> = ms
        .iter()
        .flat_map(|&m| mus.iter().map(move |&mu| (mu, m)))
        .collect();
    let tail = TailCut::beckmann_vgroove(1e-4 * LIB_TOL);
    let results: Vec<Result<[f64; 2], String>> = texels
        .par_iter()
        .map(|&(mu, m)| {
            // (the Fresnel form the table driver passes for a dielectric with η ≥ 1)
            let f = |c: f64| dielectric_one_division(c.clamp(0.0, 1.0), 1.5);
            let kernel = beckmann_vgroove_albedo(mu, m, tail, LIB_TOL, f)
                .map_err(|spent| format!("mu={mu} m={m}: fell back after {spent} evaluations"))?;
            let s = specular(NdfKind::Beckmann, m, fresnel);
            let generic = integrate_over_l_vgroove_cc(mu, m, tail, LIB_TOL, |nd: &Node| {
                [s.cosine_weighted(nd)]
            })
            .map_err(|spent| format!("mu={mu} m={m}: generic fast path fell back after {spent}"))?;
            let d = (kernel.value[0] - generic.value[0]).abs();
            if d > kernel.error[0] + generic.error[0] + 1e-15 {
                return Err(format!(
                    "mu={mu} m={m}: kernel {} ± {:e}, generic integrand {} ± {:e}",
                    kernel.value[0], kernel.error[0], generic.value[0], generic.error[0]
                ));
            }
            Ok([kernel.value[0], kernel.error[0]])
        })
        .collect();
    let mut failures: Vec<String> = results.iter().filter_map(|r| r.clone().err()).collect();
    // and the table driver uses the same path: its value is bit-identical
    for (k, &(mu, m)) in texels.iter().enumerate() {
        let brdf = Brdf {
            specular: Some(specular(NdfKind::Beckmann, m, fresnel)),
            diffuse_weight: 0.0,
            diffuse: brdfbake::model::DiffuseLobe::Lambert,
        };
        let (v, e, _) = directional_albedo(&brdf, mu, LIB_TOL);
        if let Ok(r) = &results[k] {
            if [v[0], e[0]] != *r {
                failures.push(format!(
                    "mu={mu} m={m}: table driver {v:?} ± {e:?}, kernel {r:?}"
                ));
            }
        }
    }
    let subset = [0usize, 1, 6, 12, 19, 25, 30, 31];
    let pts: Vec<(usize, usize)> = subset
        .iter()
        .flat_map(|&j| subset.map(|i| (i, j)))
        .collect();
    failures.extend(
        pts.par_iter()
            .filter_map(|&(i, j)| {
                let Ok([v, est]) = results[j * n + i] else {
                    return None;
                };
                let (want, ref_err) = reference_albedo(NdfKind::Beckmann, ms[j], mus[i], |vh| {
                    reference::fresnel_dielectric(vh, 1.5)
                });
                let d = (v - want).abs();
                (d > est + ref_err + 1e-15 || d > LIB_TOL).then(|| {
                    format!(
                        "mu={} m={}: {v} vs reference {want}: |error| {d:e}, estimate {est:e}",
                        mus[i], ms[j]
                    )
                })
            })
            .collect::<Vec<_>>(),
    );
    assert_none("cook-torrance albedo", &failures);
}

/// The closed-form kernel with the other Fresnel factors it takes (none, Schlick, a
/// conductor) and at the preset's corners, against the independent reference: within the
/// kernel's estimate plus the reference's, and within `LIB_TOL`.
#[test]
fn beckmann_vgroove_kernel_matches_reference_for_every_fresnel() {
    let tail = TailCut::beckmann_vgroove(1e-4 * LIB_TOL);
    let mut pts = Vec::new();
    for fresnel in [
        Fresnel::None,
        Fresnel::Schlick { f0: 0.04 },
        Fresnel::Conductor { eta: 0.2, k: 3.0 },
    ] {
        for &alpha in &[0.05, 1.0] {
            for &mu in &[0.01, 0.72, 1.0] {
                pts.push((fresnel, alpha, mu));
            }
        }
    }
    let failures: Vec<String> = pts
        .par_iter()
        .filter_map(|&(fresnel, alpha, mu)| {
            let e = match beckmann_vgroove_albedo(mu, alpha, tail, LIB_TOL, |c| fresnel.eval(c)) {
                Ok(e) => e,
                Err(n) => return Some(format!("{fresnel:?} alpha={alpha} mu={mu}: fell back after {n}")),
            };
            let (want, ref_err) = reference_albedo(NdfKind::Beckmann, alpha, mu, |vh| match fresnel {
                Fresnel::None => 1.0,
                Fresnel::Schlick { f0 } => f0 + (1.0 - f0) * reference::fc(vh),
                Fresnel::Conductor { eta, k } => reference::fresnel_conductor(vh, eta, k),
                Fresnel::Dielectric { eta } => reference::fresnel_dielectric(vh, eta),
            });
            let d = (e.value[0] - want).abs();
            (d > e.error[0] + ref_err + 1e-15 || d > LIB_TOL).then(|| {
                format!("{fresnel:?} alpha={alpha} mu={mu}: {} vs reference {want}: |error| {d:e}, estimate {:e}", e.value[0], e.error[0])
            })
        })
        .collect();
    assert_none("closed-form V-groove kernel", &failures);
}

/// Other lobes through the library's albedo entry point (fast path or, where a piece does
/// not converge, the adaptive fallback — either must be right): GGX (no tail cut: its tail
/// is polynomial) and Beckmann with Schlick's Fresnel, at views on both sides of 45° (the φ
/// split at tan ψ = 1 exists only beyond it), at grazing and normal incidence, for narrow
/// and wide lobes.
#[test]
fn other_vgroove_albedos_match_reference() {
    let mut pts = Vec::new();
    for kind in [NdfKind::Ggx, NdfKind::Beckmann] {
        for &alpha in &[0.02, 0.3, 1.0] {
            for &mu in &[0.01, 0.3, 0.72, 1.0] {
                pts.push((kind, alpha, mu));
            }
        }
    }
    let failures: Vec<String> = pts
        .par_iter()
        .filter_map(|&(kind, alpha, mu)| {
            let brdf = Brdf {
                specular: Some(specular(kind, alpha, Fresnel::Schlick { f0: 0.04 })),
                diffuse_weight: 0.0,
                diffuse: brdfbake::model::DiffuseLobe::Lambert,
            };
            let (v, e, _) = directional_albedo(&brdf, mu, LIB_TOL);
            let (want, ref_err) =
                reference_albedo(kind, alpha, mu, |vh| 0.04 + 0.96 * reference::fc(vh));
            let d = (v[0] - want).abs();
            (d > e[0] + ref_err + 1e-15 || d > LIB_TOL).then(|| {
                format!("{kind:?} alpha={alpha} mu={mu}: {} vs reference {want}: |error| {d:e}, estimate {:e}", v[0], e[0])
            })
        })
        .collect();
    assert_none("V-groove albedos", &failures);
}

/// The Beckmann tail cut's bound, checked in its two steps and end to end:
/// 1. pointwise, the integrand per unit solid angle of h, `f·(n·l)·4(v·h)` with every
///    Fresnel factor ≤ 1, is at most `2·D·(n·h)` (at 20,000 half vectors over the visible
///    range, views from grazing to normal; 1e-12 relative slack for rounding);
/// 2. the tail mass of the bound, `∫_{tan θh > T} D (n·h) dω_h = exp(−T²/α²)`, by the
///    reference's adaptive Gauss–Legendre in θh (to 1e-14; compared within 1e-12), and the
///    cut `TailCut::beckmann_vgroove(mass)` at `2·exp(−T²/α²) = mass` (1e-12 relative:
///    a log, a square root, asinh and back);
/// 3. the fast path with the production cut (10⁻⁴ of the tolerance) and without differ by
///    at most the claimed mass plus both estimates.
#[test]
fn beckmann_tail_cut_bound_holds() {
    let mut failures = Vec::new();
    for &alpha in &[0.05, 0.4, 1.0] {
        let ndf = Ndf::new(NdfKind::Beckmann, alpha).unwrap();
        // 1. pointwise
        for fresnel in [
            Fresnel::None,
            Fresnel::Dielectric { eta: 1.5 },
            Fresnel::Conductor { eta: 0.2, k: 3.0 },
        ] {
            let s = specular(NdfKind::Beckmann, alpha, fresnel);
            for iv in 0..20 {
                let mu = (iv as f64 + 0.5) / 20.0;
                let sin_v = (1.0 - mu * mu).sqrt();
                for k in 0..1000 {
                    let phi = std::f64::consts::PI * (k % 40) as f64 / 39.0;
                    let th = 1.5 * (k / 40) as f64 / 25.0;
                    let (sh, ch) = th.sin_cos();
                    let nd = Node::at(mu, sin_v, phi.cos(), sh, ch);
                    if nd.n_dot_l <= 0.0 || nd.v_dot_h <= 0.0 {
                        continue;
                    }
                    let lhs = s.cosine_weighted(&nd) * 4.0 * nd.v_dot_h;
                    let rhs = 2.0 * ndf.d(ch) * ch;
                    if lhs > rhs * (1.0 + 1e-12) {
                        failures.push(format!(
                            "alpha={alpha} mu={mu} th={th} phi={phi}: {lhs} > {rhs}"
                        ));
                    }
                }
            }
        }
        // 2. the tail mass, in closed form vs quadrature (D cos θ sin θ dθ dφ, 2π in φ)
        let m = RefModel::new(NdfKind::Beckmann, alpha, Masking::VGroove);
        for &x in &[0.5f64, 1.0, 2.0, 3.0] {
            let th0 = (x * alpha).atan();
            let q = reference::adaptive(
                |th: f64| {
                    let (st, ct) = th.sin_cos();
                    [2.0 * std::f64::consts::PI * m.d(ct, st * st) * ct * st]
                },
                &reference::normalize_breaks(vec![
                    th0,
                    th0 + 0.5 * (std::f64::consts::FRAC_PI_2 - th0),
                    std::f64::consts::FRAC_PI_2,
                ]),
                1e-14,
            );
            let want = (-x * x).exp();
            if (q.value[0] - want).abs() > 1e-12 {
                failures.push(format!(
                    "alpha={alpha} T/alpha={x}: tail {} vs exp(-x^2) {want}",
                    q.value[0]
                ));
            }
        }
        // ... and the cut's u is where twice that tail is the claimed mass
        for &mass in &[1e-3, 1e-11, 1e-17] {
            let x = TailCut::beckmann_vgroove(mass).u.sinh();
            let tail = 2.0 * (-x * x).exp();
            if (tail - mass).abs() > 1e-12 * mass {
                failures.push(format!("cut for mass {mass:e}: bound {tail:e}"));
            }
        }
        // 3. end to end
        for &mu in &[0.02, 0.5, 1.0] {
            let s = specular(NdfKind::Beckmann, alpha, Fresnel::None);
            let g = |nd: &Node| [s.cosine_weighted(nd)];
            let cut = TailCut::beckmann_vgroove(1e-4 * LIB_TOL);
            let a = integrate_over_l_kinked(mu, s.warp(), cut, LIB_TOL, g);
            let b = integrate_over_l_kinked(mu, s.warp(), TailCut::NONE, LIB_TOL, g);
            let d = (a.value[0] - b.value[0]).abs();
            if d > a.error[0] + b.error[0] + 1e-15 {
                failures.push(format!(
                    "alpha={alpha} mu={mu}: cut {} vs uncut {}: {d:e}",
                    a.value[0], b.value[0]
                ));
            }
        }
    }
    assert_none("tail cut", &failures);
}
