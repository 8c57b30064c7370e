//! α = 0 exactly (the smooth-surface limit, `table::smooth`): a roughness axis that starts
//! at α = 0 holds the closed forms there, and the integrals at α → 0 approach them.
//!
//! The closed forms are written here again from their definitions (the mirror lobe: l the
//! reflection of v, F at v·h = μ, G → 1), not taken from the library. The limit check
//! bakes the same tables at small α with the library's quadrature: for μ away from
//! grazing, E(μ, α) − E(μ, 0) = O(α² ln(1/α)) (the lobe's width is α, and GGX's slope
//! distribution has a logarithmically divergent second moment; Smith's Λ ∝ α² tan²θ; the
//! lobe's mass beyond the horizon ∝ α²), so the difference must drop ~75× from α = 3e-3 to
//! 3e-4: the test asserts a drop of at least 30× (an O(α) error would give 10×; terms of
//! opposite sign make the split sum's B drop by ~33× there, measured against the
//! independent reference of tests/common/reference.rs) and a difference at α = 3e-4 of at
//! most 1e-6.

use brdfbake::lut::{Axis, Convention, Lut, Quantity};
use brdfbake::model::{Fresnel, FresnelQuantity, Masking, NdfKind, RoughnessQuantity};
use brdfbake::table::{bake, DfgLayout, ModelSpec, Storage, TableKind, TableSpec};

fn cos_axis(name: &str, size: usize, range: [f64; 2]) -> Axis {
    Axis::new(name, Quantity::Cosine, size, range, Convention::Centers)
}

/// A roughness (α) axis of `size` texels from 0 to 1 (endpoints), or the given α alone.
fn alpha_axis(size: usize) -> Axis {
    Axis::new(
        "roughness",
        Quantity::Roughness(RoughnessQuantity::Alpha),
        size,
        [0.0, 1.0],
        Convention::Endpoints,
    )
}

fn at_alpha(alpha: f64) -> Axis {
    Axis::new(
        "roughness",
        Quantity::Roughness(RoughnessQuantity::Alpha),
        1,
        [alpha, alpha],
        Convention::Centers,
    )
}

fn model(ndf: NdfKind, masking: Masking, fresnel: Fresnel, diffuse: f64) -> ModelSpec {
    ModelSpec {
        ndf: Some(ndf),
        masking,
        fresnel,
        diffuse_weight: diffuse,
        diffuse_model: brdfbake::model::DiffuseModel::Lambert,
        classic: None,
    }
}

fn spec(kind: TableKind, model: ModelSpec, axes: Vec<Axis>) -> TableSpec {
    TableSpec {
        name: "t".into(),
        kind,
        model,
        axes,
        dfg_layout: (kind == TableKind::Dfg).then_some(DfgLayout::Karis),
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-9,
    }
}

fn schlick_weight(mu: f64) -> f64 {
    (1.0 - mu).powi(5)
}

/// The exact unpolarized Fresnel reflectance of a dielectric (Walter et al. 2007, eq. 22),
/// 1 under total internal reflection.
fn fresnel_dielectric(c: f64, eta: f64) -> f64 {
    let g2 = eta * eta - 1.0 + c * c;
    if g2 < 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// Row `j` (roughness texel) of a 2D table, channel `c`.
fn row(l: &Lut, j: usize, c: usize) -> Vec<f64> {
    (0..l.axes[0].size)
        .map(|i| l.texel([i, j, 0], c) as f64)
        .collect()
}

fn close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tol,
            "{what}: texel {i}: {x} against {y} (tolerance {tol})"
        );
    }
}

/// f32 storage rounds a value of size ≤ ~2 by at most 2^-24·2 ≈ 1.2e-7.
const F32: f64 = 1.2e-7;

#[test]
fn the_alpha_zero_row_holds_the_closed_forms() {
    let mus = cos_axis("cos_theta_v", 16, [0.0, 1.0]);
    let mu: Vec<f64> = mus.coords();
    let ggx = NdfKind::Ggx;
    let hc = Masking::SmithHeightCorrelated;

    // albedo: E = F(μ) + w_d, for each Fresnel term
    for (fresnel, f) in [
        (
            Fresnel::None,
            Box::new(|_: f64| 1.0) as Box<dyn Fn(f64) -> f64>,
        ),
        (
            Fresnel::Schlick { f0: 0.04 },
            Box::new(|m: f64| 0.04 + 0.96 * schlick_weight(m)),
        ),
        (
            Fresnel::Dielectric { eta: 1.5 },
            Box::new(|m: f64| fresnel_dielectric(m, 1.5)),
        ),
    ] {
        for diffuse in [0.0, 0.5] {
            for (ndf, masking) in [
                (ggx, hc),
                (ggx, Masking::SmithSeparable),
                (NdfKind::Beckmann, hc),
                (NdfKind::Beckmann, Masking::VGroove),
            ] {
                let l = bake(&spec(
                    TableKind::Albedo,
                    model(ndf, masking, fresnel, diffuse),
                    vec![mus.clone(), alpha_axis(3)],
                ))
                .unwrap();
                let want: Vec<f64> = mu.iter().map(|&m| f(m) + diffuse).collect();
                close(
                    &row(&l, 0, 0),
                    &want,
                    F32,
                    &format!("albedo {fresnel:?} {ndf:?} {masking:?} w_d {diffuse}"),
                );
                // the other rows are the integrals, not the limit
                assert!(row(&l, 2, 0)[8] < want[8] - 1e-3, "alpha = 1 loses energy");
            }
        }
    }

    // split sum, both layouts
    let mut s = spec(
        TableKind::Dfg,
        model(ggx, hc, Fresnel::None, 0.0),
        vec![mus.clone(), alpha_axis(4)],
    );
    let l = bake(&s).unwrap();
    let fc: Vec<f64> = mu.iter().map(|&m| schlick_weight(m)).collect();
    close(
        &row(&l, 0, 0),
        &fc.iter().map(|w| 1.0 - w).collect::<Vec<_>>(),
        F32,
        "Karis A",
    );
    close(&row(&l, 0, 1), &fc, F32, "Karis B");
    s.dfg_layout = Some(DfgLayout::Filament);
    let l = bake(&s).unwrap();
    close(&row(&l, 0, 0), &fc, F32, "Filament R");
    close(&row(&l, 0, 1), &[1.0; 16], F32, "Filament G");

    // Kulla–Conty: E = 1, E_avg = 1
    let l = bake(&spec(
        TableKind::KullaConty,
        model(ggx, hc, Fresnel::None, 0.0),
        vec![mus.clone(), alpha_axis(3)],
    ))
    .unwrap();
    close(&row(&l, 0, 0), &[1.0; 16], F32, "Kulla-Conty E");
    close(&row(&l, 0, 1), &[1.0; 16], 1e-9 + F32, "Kulla-Conty E_avg");

    // albedo-avg with Schlick: 2∫(F0 + (1 − F0)(1 − μ)⁵)μ dμ = F0 + (1 − F0)/21
    let l = bake(&spec(
        TableKind::AlbedoAvg,
        model(ggx, hc, Fresnel::Schlick { f0: 0.2 }, 0.0),
        vec![alpha_axis(3)],
    ))
    .unwrap();
    let want = 0.2 + 0.8 / 21.0;
    assert!(
        (l.texel([0, 0, 0], 0) as f64 - want).abs() <= 1e-9 + F32,
        "E_avg at alpha 0: {} against {want}",
        l.texel([0, 0, 0], 0)
    );

    // albedo-fresnel over η, and the rough dielectric: R = F(μ; η), T = 1 − R
    let eta = Axis::new(
        "fresnel",
        Quantity::Fresnel(FresnelQuantity::Eta),
        3,
        [1.1, 2.0],
        Convention::Endpoints,
    );
    let l = bake(&spec(
        TableKind::AlbedoFresnel,
        model(ggx, hc, Fresnel::None, 0.0),
        vec![mus.clone(), alpha_axis(3), eta.clone()],
    ))
    .unwrap();
    for z in 0..3 {
        let e = eta.coord(z);
        let got: Vec<f64> = (0..16).map(|i| l.texel([i, 0, z], 0) as f64).collect();
        let want: Vec<f64> = mu.iter().map(|&m| fresnel_dielectric(m, e)).collect();
        close(&got, &want, F32, &format!("albedo-fresnel eta {e}"));
    }
    let eta_both = Axis::new(
        "fresnel",
        Quantity::Fresnel(FresnelQuantity::Eta),
        2,
        [0.7, 1.5],
        Convention::Endpoints,
    );
    let l = bake(&spec(
        TableKind::DielectricBtdf,
        model(ggx, Masking::SmithSeparable, Fresnel::None, 0.0),
        vec![mus.clone(), alpha_axis(3), eta_both.clone()],
    ))
    .unwrap();
    for z in 0..2 {
        let e = eta_both.coord(z);
        let r: Vec<f64> = mu.iter().map(|&m| fresnel_dielectric(m, e)).collect();
        let got_r: Vec<f64> = (0..16).map(|i| l.texel([i, 0, z], 0) as f64).collect();
        let got_t: Vec<f64> = (0..16).map(|i| l.texel([i, 0, z], 1) as f64).collect();
        close(&got_r, &r, F32, &format!("dielectric R eta {e}"));
        close(
            &got_t,
            &r.iter().map(|x| 1.0 - x).collect::<Vec<_>>(),
            F32,
            &format!("dielectric T eta {e}"),
        );
    }

    // Smith G1 = 1 for μ > 0 and 0 at μ = 0; G2 likewise
    let mu0 = Axis::new(
        "cos_theta",
        Quantity::Cosine,
        5,
        [0.0, 1.0],
        Convention::Endpoints,
    );
    let l = bake(&spec(
        TableKind::G1,
        model(ggx, Masking::SmithSeparable, Fresnel::None, 0.0),
        vec![mu0.clone(), alpha_axis(3)],
    ))
    .unwrap();
    close(&row(&l, 0, 0), &[0.0, 1.0, 1.0, 1.0, 1.0], 0.0, "G1");
}

#[test]
fn kinds_without_a_smooth_limit_refuse_alpha_zero() {
    let mus = cos_axis("cos_theta_h", 4, [0.0, 1.0]);
    let e = bake(&spec(
        TableKind::Ndf,
        model(NdfKind::Ggx, Masking::None, Fresnel::None, 0.0),
        vec![mus, alpha_axis(3)],
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("alpha = 0") && e.contains("Dirac delta"), "{e}");
    let e = bake(&spec(
        TableKind::Albedo,
        model(NdfKind::Charlie, Masking::Ashikhmin, Fresnel::None, 0.0),
        vec![cos_axis("cos_theta_v", 4, [0.0, 1.0]), alpha_axis(3)],
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("alpha = 0") && e.contains("charlie"), "{e}");
}

/// The integrals at small α approach the α = 0 closed forms at the rate O(α²) argued at the
/// top of this file.
#[test]
fn integrals_approach_the_smooth_limit() {
    let mus = cos_axis("cos_theta_v", 5, [0.3, 1.0]);
    let cases: Vec<(TableKind, ModelSpec)> = vec![
        (
            TableKind::Albedo,
            model(
                NdfKind::Ggx,
                Masking::SmithHeightCorrelated,
                Fresnel::Dielectric { eta: 1.5 },
                0.0,
            ),
        ),
        (
            TableKind::Albedo,
            model(
                NdfKind::Beckmann,
                Masking::SmithSeparable,
                Fresnel::Schlick { f0: 0.5 },
                0.0,
            ),
        ),
        (
            TableKind::Dfg,
            model(
                NdfKind::Ggx,
                Masking::SmithHeightCorrelated,
                Fresnel::None,
                0.0,
            ),
        ),
    ];
    for (kind, m) in cases {
        let limit = bake(&spec(kind, m.clone(), vec![mus.clone(), alpha_axis(2)])).unwrap();
        let at =
            |alpha: f64| bake(&spec(kind, m.clone(), vec![mus.clone(), at_alpha(alpha)])).unwrap();
        let (coarse, fine) = (at(3e-3), at(3e-4));
        for c in 0..limit.channels.len() {
            for i in 0..5 {
                let l0 = limit.texel([i, 0, 0], c) as f64;
                let d1 = (coarse.texel([i, 0, 0], c) as f64 - l0).abs();
                let d2 = (fine.texel([i, 0, 0], c) as f64 - l0).abs();
                let what = format!("{kind:?} {:?} channel {c} at mu {}", m.ndf, mus.coord(i));
                assert!(d2 <= 1e-6, "{what}: |E(3e-4) - E(0)| = {d2}");
                // (below ~1e-7 the f32 texels and the 1e-9 tolerance decide, not the rate)
                assert!(
                    d2 <= d1 / 30.0 + 3.0 * F32,
                    "{what}: the difference fell from {d1} (alpha 3e-3) to {d2} (3e-4) only"
                );
            }
        }
    }
}

/// Schlick-GGX at α = 0: the image-based form (k = α/2 → 0) is G1 = μ/μ = 1 like Smith's,
/// the direct-light form (k = (√α + 1)²/8 → 1/8) keeps `G1(μ) = μ/(7μ/8 + 1/8)`, so the
/// mirror lobe carries G1(μ)²: E = F(μ)·G1², Karis A = (1 − Fc)·G1², B = Fc·G1², and a g2
/// table holds G1(n·v)·G1(n·l). Written here from Schlick's G1 (not from the library).
#[test]
fn schlick_ggx_alpha_zero_rows_hold_the_closed_forms() {
    let mus = cos_axis("cos_theta_v", 16, [0.0, 1.0]);
    let mu: Vec<f64> = mus.coords();
    let g1_direct = |m: f64| m / (m * 7.0 / 8.0 + 1.0 / 8.0);
    for (masking, g1) in [
        (
            Masking::SchlickGgx,
            Box::new(|_: f64| 1.0) as Box<dyn Fn(f64) -> f64>,
        ),
        (Masking::SchlickGgxDirect, Box::new(g1_direct)),
    ] {
        let l = bake(&spec(
            TableKind::Albedo,
            model(NdfKind::Ggx, masking, Fresnel::Schlick { f0: 0.04 }, 0.0),
            vec![mus.clone(), alpha_axis(3)],
        ))
        .unwrap();
        let want: Vec<f64> = mu
            .iter()
            .map(|&m| (0.04 + 0.96 * schlick_weight(m)) * g1(m) * g1(m))
            .collect();
        close(&row(&l, 0, 0), &want, F32, &format!("albedo {masking:?}"));
        let l = bake(&spec(
            TableKind::Dfg,
            model(NdfKind::Ggx, masking, Fresnel::None, 0.0),
            vec![mus.clone(), alpha_axis(4)],
        ))
        .unwrap();
        let a: Vec<f64> = mu
            .iter()
            .map(|&m| (1.0 - schlick_weight(m)) * g1(m) * g1(m))
            .collect();
        let b: Vec<f64> = mu
            .iter()
            .map(|&m| schlick_weight(m) * g1(m) * g1(m))
            .collect();
        close(&row(&l, 0, 0), &a, F32, &format!("Karis A {masking:?}"));
        close(&row(&l, 0, 1), &b, F32, &format!("Karis B {masking:?}"));
        // g2 over (n.v, n.l), both from 0 (where G1 = 0)
        let c5 =
            |name: &str| Axis::new(name, Quantity::Cosine, 5, [0.0, 1.0], Convention::Endpoints);
        let l = bake(&spec(
            TableKind::G2,
            model(NdfKind::Ggx, masking, Fresnel::None, 0.0),
            vec![c5("cos_theta_v"), c5("cos_theta_l"), alpha_axis(3)],
        ))
        .unwrap();
        for j in 0..5 {
            for i in 0..5 {
                let (v, w) = (i as f64 / 4.0, j as f64 / 4.0);
                let want = if v > 0.0 && w > 0.0 {
                    g1(v) * g1(w)
                } else {
                    0.0
                };
                let got = l.texel([i, j, 0], 0) as f64;
                assert!(
                    (got - want).abs() <= F32,
                    "g2 {masking:?} at ({v}, {w}): {got} against {want}"
                );
            }
        }
    }
}

/// Schlick-GGX's integrals approach their α = 0 rows at the rate its k sets: the masking
/// moves by O(k − k₀), which dominates the lobe's O(α² ln(1/α)): for k = α/2 the difference
/// is O(α), for k = (√α + 1)²/8 = 1/8 + √α/4 + α/8 it is O(√α). From α = 3e-3 to 3e-4 (one
/// decade) the measured order log₁₀(d₁/d₂) must be that (1 or 1/2) within 0.1: the next
/// terms (O(α²ln α) for the first; O(α) against O(√α) for the second, a relative 1/2·√α ≤ 3%
/// of it) move it by less than 0.03, f32 storage and the 1e-9 tolerance (≤ 1.3e-7 against
/// differences ≥ 1e-5 where d₁ ≥ 1e-4) by less than 0.01. A wrong α = 0 row (say, the image-based closed form G1 = 1 for the
/// direct form) would leave d₁/d₂ near 1, order ~0.
#[test]
fn schlick_ggx_approaches_its_smooth_limit_at_its_order() {
    let mus = cos_axis("cos_theta_v", 5, [0.3, 1.0]);
    for (masking, order) in [(Masking::SchlickGgx, 1.0), (Masking::SchlickGgxDirect, 0.5)] {
        for kind in [TableKind::Albedo, TableKind::Dfg] {
            let m = model(NdfKind::Ggx, masking, Fresnel::None, 0.0);
            let limit = bake(&spec(kind, m.clone(), vec![mus.clone(), alpha_axis(2)])).unwrap();
            let at = |alpha: f64| {
                bake(&spec(kind, m.clone(), vec![mus.clone(), at_alpha(alpha)])).unwrap()
            };
            let (coarse, fine) = (at(3e-3), at(3e-4));
            for c in 0..limit.channels.len() {
                let mut checked = 0;
                for i in 0..5 {
                    let l0 = limit.texel([i, 0, 0], c) as f64;
                    let d1 = (coarse.texel([i, 0, 0], c) as f64 - l0).abs();
                    let d2 = (fine.texel([i, 0, 0], c) as f64 - l0).abs();
                    // (where the difference is small — B near normal views, where Fc ~ 0,
                    // and μ → 1, where G1 = 1 for every k — f32 storage and the 1e-9
                    // tolerance would decide the ratio, not the rate)
                    if d1 < 1e-4 {
                        continue;
                    }
                    checked += 1;
                    let p = (d1 / d2).log10();
                    assert!(
                        (p - order).abs() <= 0.1,
                        "{kind:?} {masking:?} channel {c} at mu {}: differences {d1:e} (alpha 3e-3), {d2:e} (3e-4): order {p}, expected {order}",
                        mus.coord(i)
                    );
                }
                assert!(
                    checked >= 1,
                    "{kind:?} {masking:?} channel {c}: no texel to measure"
                );
            }
        }
    }
}

/// `dielectric-schlick` on both sides of η = 1: its α = 0 row holds A = 1 − s, B = s,
/// T = 1 − s with Schlick's s = (1 − cos θ_o)⁵ on the less dense side — v·h = μ for η > 1,
/// the refracted cosine √(1 − (1 − μ²)/η²) from Snell's law for η < 1, s = 1 (T = 0) under
/// total internal reflection — written here, not from the library (within f32); and its
/// integrals at small α approach that row as the other kinds' do (`integrals_approach_the_
/// smooth_limit`: the difference falling 30× from α = 3e-3 to 3e-4, and within 1e-6 at
/// 3e-4). For η < 1 the limit has a kink at the critical angle θc, and GGX's tail reaches
/// it: a fraction α²/(α² + tan²δ) ≤ α²/tan²δ of the visible normals' projected area lies
/// beyond an angle δ from the normal, so the weight that crosses θc (δ = |θv − θc|, 5.1° at
/// the nearest view here) moves the values by up to that, 1.2e-5 at α = 3e-4: the bound
/// there is max(1e-6, α²/tan²δ).
#[test]
fn dielectric_schlick_meets_and_approaches_its_smooth_limit() {
    let mus = cos_axis("cos_theta_v", 5, [0.3, 1.0]);
    let eta = Axis::new(
        "fresnel",
        Quantity::Fresnel(FresnelQuantity::Eta),
        2,
        [0.7, 1.5],
        Convention::Endpoints,
    );
    let m = model(NdfKind::Ggx, Masking::SmithSeparable, Fresnel::None, 0.0);
    let kind = TableKind::DielectricSchlick;
    let limit = bake(&spec(
        kind,
        m.clone(),
        vec![mus.clone(), alpha_axis(2), eta.clone()],
    ))
    .unwrap();
    for z in 0..2 {
        let e = eta.coord(z);
        for i in 0..5 {
            let mu = mus.coord(i);
            let s = if e >= 1.0 {
                schlick_weight(mu)
            } else {
                let s2t = (1.0 - mu * mu) / (e * e);
                if s2t >= 1.0 {
                    1.0
                } else {
                    schlick_weight((1.0 - s2t).sqrt())
                }
            };
            for (c, want) in [1.0 - s, s, 1.0 - s].into_iter().enumerate() {
                let got = limit.texel([i, 0, z], c) as f64;
                assert!(
                    (got - want).abs() <= F32,
                    "alpha = 0, eta {e}, mu {mu}, channel {c}: {got} against {want}"
                );
            }
        }
    }
    let at = |alpha: f64| {
        bake(&spec(
            kind,
            m.clone(),
            vec![mus.clone(), at_alpha(alpha), eta.clone()],
        ))
        .unwrap()
    };
    let (coarse, fine) = (at(3e-3), at(3e-4));
    for z in 0..2 {
        for c in 0..3 {
            for i in 0..5 {
                let l0 = limit.texel([i, 0, z], c) as f64;
                let d1 = (coarse.texel([i, 0, z], c) as f64 - l0).abs();
                let d2 = (fine.texel([i, 0, z], c) as f64 - l0).abs();
                let (e, mu) = (eta.coord(z), mus.coord(i));
                let what = format!("eta {e} channel {c} at mu {mu}");
                let tail = if e < 1.0 {
                    let delta = (mu.acos() - (1.0 - e * e).sqrt().acos()).abs();
                    3e-4f64.powi(2) / delta.tan().powi(2)
                } else {
                    0.0
                };
                assert!(
                    d2 <= tail.max(1e-6),
                    "{what}: |(3e-4) - (0)| = {d2} (bound {tail:e})"
                );
                assert!(
                    d2 <= d1 / 30.0 + 3.0 * F32,
                    "{what}: the difference fell from {d1} (alpha 3e-3) to {d2} (3e-4) only"
                );
            }
        }
    }
}
