//! The fast tensor rule (src/hemisphere/tensor.rs) against the adaptive Gauss–Kronrod
//! integrator it replaces for smooth integrands (kept as the reference and the fallback).
//!
//! Tolerances:
//! * `REQ = 1e-6`: the required accuracy of every baked value, relative where it exceeds 1
//!   (the sheen albedo does at grazing views).
//! * each comparison also requires |fast − adaptive| ≤ est_fast + est_adaptive (+ f32
//!   rounding for baked values): both estimates claim to bound their own errors, so their
//!   sum bounds the difference; a failure means one of them is optimistic.
//!
//! The adaptive integrator's own accuracy against an independent reference is checked in
//! tests/accuracy.rs (which, through `split_sum`, `sheen_albedo` and `directional_albedo`,
//! now also checks the fast path against that reference).

use brdfbake::hemisphere::tensor::{integrate_over_l_cc, InnerWarp};
use brdfbake::lut::{Axis, Convention, Quantity};
use brdfbake::model::fresnel::schlick_weight;
use brdfbake::model::{Fresnel, Masking, Ndf, NdfKind, RoughnessQuantity, Specular};
use brdfbake::table::dfg::{sheen_albedo, sheen_albedo_adaptive, split_sum, split_sum_adaptive};
use brdfbake::table::{bake, DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
use rayon::prelude::*;

const LIB_TOL: f64 = 1e-7;
const REQ: f64 = 1e-6;
/// Relative rounding of f64 → f32 (half an ulp).
const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;

fn spec(kind: NdfKind, alpha: f64, masking: Masking) -> Specular {
    Specular {
        ndf: Ndf::new(kind, alpha).unwrap(),
        masking,
        fresnel: Fresnel::None,
    }
}

fn fail_all(what: &str, failures: &[String]) {
    assert!(
        failures.is_empty(),
        "{what}: {} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The default `filament-dfg` table (128², GGX + height-correlated Smith, Filament layout
/// R = B_karis, G = A + B, cloth) baked by the library (fast path) against the adaptive
/// integrator at the same tolerance, at every 4th texel of each axis plus the whole first
/// and last rows and columns (grazing view, normal view, smallest and largest roughness):
/// 1,472 texels, a few seconds in release.
#[test]
fn filament_dfg_table_matches_adaptive_at_every_texel() {
    let n = 128;
    let axes = vec![
        Axis {
            name: "cos_theta_v".into(),
            quantity: Quantity::Cosine,
            size: n,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        },
        Axis {
            name: "roughness".into(),
            quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
            size: n,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        },
    ];
    let t = TableSpec {
        name: "dfg".into(),
        kind: TableKind::Dfg,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes: axes.clone(),
        dfg_layout: Some(DfgLayout::Filament),
        cloth: true,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: LIB_TOL,
    };
    let lut = bake(&t).unwrap();
    let est = lut.error_estimate.clone();
    let picked: Vec<(usize, usize)> = (0..n * n)
        .map(|k| (k % n, k / n))
        .filter(|&(i, j)| {
            (i % 4 == 0 && j % 4 == 0) || i == 0 || j == 0 || i == n - 1 || j == n - 1
        })
        .collect();
    let failures: Vec<String> = picked
        .par_iter()
        .flat_map_iter(|&(i, j)| {
            let mu = axes[0].coord(i);
            let alpha = axes[1].alpha(j).unwrap();
            let s = spec(NdfKind::Ggx, alpha, Masking::SmithHeightCorrelated);
            let ([a, b], [ea, eb], _) = split_sum_adaptive(&s, mu, LIB_TOL);
            let (c, ec, _) = sheen_albedo_adaptive(alpha, mu, LIB_TOL);
            let want = [(b, eb), (a + b, ea + eb), (c, ec)];
            let mut f = Vec::new();
            for (ch, &(w, ew)) in want.iter().enumerate() {
                let got = lut.texel([i, j, 0], ch) as f64;
                let diff = (got - w).abs();
                let bound = est[ch] + ew + F32_REL * w.abs();
                if diff > REQ * w.abs().max(1.0) || diff > bound {
                    f.push(format!(
                        "texel ({i},{j}) mu={mu} alpha={alpha} channel {ch}: table {got} adaptive {w} diff {diff:e} bound {bound:e}"
                    ));
                }
            }
            f
        })
        .collect();
    fail_all("filament-dfg fast vs adaptive", &failures);
}

/// Hard corners: grazing views (μ down to 1e-4), mirror-like lobes (α down to 1e-6) and
/// α = 1, for GGX + height-correlated Smith, Beckmann + separable Smith and the sheen
/// lobe, against the adaptive integrator at a 100× tighter tolerance. Values above 1
/// (sheen at grazing views) are compared relatively.
#[test]
fn hard_corners_match_tight_adaptive() {
    // (μ = 1e-4 with α = 1e-6 is left out: there the sheen albedo is ~314 and neither
    // integrator reaches 1e-6 relative — both say so in their estimates, ~1 and ~6.)
    let pts: Vec<(f64, f64)> = [1e-4, 0.01, 0.6, 1.0]
        .iter()
        .flat_map(|&m| [1e-6, 1e-2, 0.3, 1.0].map(|a| (m, a)))
        .filter(|&(m, a)| !(m == 1e-4 && a == 1e-6))
        .collect();
    let failures: Vec<String> = pts
        .par_iter()
        .flat_map_iter(|&(mu, alpha)| {
            let mut f = Vec::new();
            let mut check = |what: &str, got: f64, est: f64, want: f64, west: f64| {
                let diff = (got - want).abs();
                if diff > REQ * want.abs().max(1.0) || diff > est + west + 1e-15 {
                    f.push(format!(
                        "{what} mu={mu} alpha={alpha}: fast {got} (est {est:e}) reference {want} (est {west:e}) diff {diff:e}"
                    ));
                }
            };
            for (kind, masking) in [
                (NdfKind::Ggx, Masking::SmithHeightCorrelated),
                (NdfKind::Beckmann, Masking::SmithSeparable),
            ] {
                let s = spec(kind, alpha, masking);
                let (v, e, _) = split_sum(&s, mu, LIB_TOL);
                let (r, re, _) = split_sum_adaptive(&s, mu, LIB_TOL * 1e-2);
                for c in 0..2 {
                    check(&format!("{kind:?} {masking:?} ch{c}"), v[c], e[c], r[c], re[c]);
                }
            }
            let (v, e, _) = sheen_albedo(alpha, mu, LIB_TOL);
            let (r, re, _) = sheen_albedo_adaptive(alpha, mu, LIB_TOL * 1e-2);
            check("sheen", v, e, r, re);
            f
        })
        .collect();
    fail_all("hard corners", &failures);
}

/// The fast path itself (no fallback) is what most texels use: over the Filament grid at
/// 16², it must succeed for at least 95% of the GGX split sums and sheen albedos (a
/// regression that sent everything to the fallback would keep the results right but lose
/// the speed), and where it succeeds its result must be within its estimate of the adaptive
/// value (at a 100× tighter tolerance).
#[test]
fn fast_path_is_used_and_its_estimates_hold() {
    let n = 16;
    let pts: Vec<(f64, f64)> = (0..n * n)
        .map(|k| {
            let mu = ((k % n) as f64 + 0.5) / n as f64;
            let r = ((k / n) as f64 + 0.5) / n as f64;
            (mu, r * r)
        })
        .collect();
    let res: Vec<(bool, bool, Option<String>)> = pts
        .par_iter()
        .map(|&(mu, alpha)| {
            let s = spec(NdfKind::Ggx, alpha, Masking::SmithHeightCorrelated);
            let sheen = spec(NdfKind::Charlie, alpha, Masking::Ashikhmin);
            let g = |n: &brdfbake::hemisphere::Node| {
                let f = s.cosine_weighted_with(n, 1.0);
                let fc = schlick_weight(n.v_dot_h);
                [f * (1.0 - fc), f * fc]
            };
            let fs = integrate_over_l_cc(mu, InnerWarp::for_ndf(&s.ndf), LIB_TOL, g);
            let fc = integrate_over_l_cc(mu, InnerWarp::for_ndf(&sheen.ndf), LIB_TOL, |n| {
                [sheen.cosine_weighted(n)]
            });
            let mut msg = None;
            if let Some(e) = &fs {
                let (r, re, _) = split_sum_adaptive(&s, mu, LIB_TOL * 1e-2);
                for c in 0..2 {
                    let d = (e.value[c] - r[c]).abs();
                    if d > e.error[c] + re[c] + 1e-15 {
                        msg = Some(format!(
                            "split sum mu={mu} alpha={alpha} ch{c}: diff {d:e} > est {:e}",
                            e.error[c]
                        ));
                    }
                }
            }
            if let Some(e) = &fc {
                let (r, re, _) = sheen_albedo_adaptive(alpha, mu, LIB_TOL * 1e-2);
                let d = (e.value[0] - r).abs();
                if d > e.error[0] + re + 1e-15 {
                    msg = Some(format!(
                        "sheen mu={mu} alpha={alpha}: diff {d:e} > est {:e}",
                        e.error[0]
                    ));
                }
            }
            (fs.is_some(), fc.is_some(), msg)
        })
        .collect();
    let used_s = res.iter().filter(|r| r.0).count();
    let used_c = res.iter().filter(|r| r.1).count();
    let msgs: Vec<String> = res.into_iter().filter_map(|r| r.2).collect();
    fail_all("fast-path estimates", &msgs);
    assert!(
        used_s * 100 >= 95 * n * n && used_c * 100 >= 95 * n * n,
        "fast path used for {used_s} split sums and {used_c} sheen albedos of {}",
        n * n
    );
}
