//! Energy compensation, Fresnel-resolved albedo and rough dielectric tables (issue 7),
//! against the independent l-space reference (`tests/common/reference.rs`), closed forms
//! and the identities they must satisfy.
//!
//! Tolerances: a baked value differs from the truth by at most its table's own error
//! estimate (`Lut::error_estimate`, an over-estimate |K15 − G7|, see `quadrature/adaptive.rs`)
//! plus f32 rounding (relative 2⁻²⁴); the reference is run at a target far below that and
//! its own estimate is added.

#[path = "common/reference.rs"]
mod reference;

use brdfbake::lut::{Axis, Convention, Lut, Quantity};
use brdfbake::model::energy::{f_avg, kulla_conty_f_ms, turquin_factor};
use brdfbake::model::{Fresnel, FresnelQuantity, Masking, NdfKind, RoughnessQuantity};
use brdfbake::table::{bake, DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
use reference::RefModel;
use std::f64::consts::PI;

const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;
const REF_TOL: f64 = 1e-9;

fn axis(name: &str, quantity: Quantity, size: usize, range: [f64; 2], c: Convention) -> Axis {
    Axis {
        name: name.into(),
        quantity,
        size,
        range,
        convention: c,
        warp: Default::default(),
        clamp: None,
    }
}

fn spec(kind: TableKind, masking: Masking, fresnel: Fresnel, axes: Vec<Axis>) -> TableSpec {
    TableSpec {
        name: "t".into(),
        kind,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking,
            fresnel,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes,
        dfg_layout: None,
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-7,
    }
}

fn mu_axis(n: usize) -> Axis {
    axis(
        "cos_theta_v",
        Quantity::Cosine,
        n,
        [0.0, 1.0],
        Convention::Centers,
    )
}

fn alpha_axis(n: usize, range: [f64; 2], c: Convention) -> Axis {
    axis(
        "roughness",
        Quantity::Roughness(RoughnessQuantity::Alpha),
        n,
        range,
        c,
    )
}

/// |stored − exact| allowed for channel `c` of `lut` at value `v`.
fn bound(lut: &Lut, c: usize, v: f64) -> f64 {
    lut.error_estimate[c] + F32_REL * v.abs()
}

/// Kulla–Conty white furnace: with F = 1, the albedo of f + f_ms is
/// E(μo) + (1 − E_tab(μo))·2π∫(1 − E(μi)) μi dμi/(π(1 − E_avg,tab)), where E and its
/// average are the truth (reference) and E_tab, E_avg,tab what the shader reads from the
/// `kulla-conty` table. It equals 1 exactly when the table is exact; the deviation is
/// bounded by δE + (1 − E_tab)/(1 − E_avg,tab)·δE_avg (δ: table bound plus reference error).
#[test]
fn kulla_conty_white_furnace() {
    let s = spec(
        TableKind::KullaConty,
        Masking::SmithHeightCorrelated,
        Fresnel::None,
        vec![mu_axis(5), alpha_axis(3, [0.1, 1.0], Convention::Endpoints)],
    );
    let lut = bake(&s).unwrap();
    for j in 0..3 {
        let alpha = s.axes[1].alpha(j).unwrap();
        let m = RefModel::new(NdfKind::Ggx, alpha, Masking::SmithHeightCorrelated);
        let avg = reference::average_albedo(&m, REF_TOL);
        for i in 0..5 {
            let mu = s.axes[0].coord(i);
            let e_ref = reference::albedo(&m, mu, REF_TOL);
            let e_tab = lut.texel([i, j, 0], 0) as f64;
            let avg_tab = lut.texel([i, j, 0], 1) as f64;
            // albedo of f_ms: ∫ f_ms(μo, μi) μi dω_i = 2π ∫ f_ms μi dμi, and
            // 2∫(1 − E)μ dμ = 1 − E_avg (the reference's average)
            let ms = kulla_conty_f_ms(e_tab, 0.0, avg_tab) * PI * (1.0 - avg.value[0]);
            let furnace = e_ref.value[0] + ms;
            let tol = bound(&lut, 0, e_tab)
                + e_ref.error
                + (1.0 - e_tab) / (1.0 - avg_tab) * (bound(&lut, 1, avg_tab) + avg.error);
            assert!(
                (furnace - 1.0).abs() <= tol,
                "alpha {alpha} mu {mu}: furnace {furnace} (tolerance {tol:e})"
            );
            // the E_avg channel is the same in every texel of a row
            assert_eq!(lut.texel([i, j, 0], 1), lut.texel([0, j, 0], 1));
        }
        // GGX at α = 1, μ = 1 has the closed form E = 1 − ln 2 (see tests/accuracy.rs)
    }
}

/// F_avg = 2∫F(μ)μ dμ for exact conductor and dielectric Fresnel against the reference's
/// own Fresnel forms (Lagarde's real-arithmetic conductor, s/p amplitudes for dielectrics)
/// integrated by the reference rule, with the critical angle as a breakpoint. Both are asked
/// for ≤ 1e-12; we allow 1e-11.
#[test]
fn average_fresnel_matches_reference() {
    type RefFresnel = Box<dyn Fn(f64) -> f64>;
    let cases: [(Fresnel, RefFresnel, f64); 4] = [
        (
            Fresnel::Conductor { eta: 0.2, k: 3.0 },
            Box::new(|c| reference::fresnel_conductor(c, 0.2, 3.0)),
            0.0,
        ),
        (
            Fresnel::Conductor { eta: 1.1, k: 0.5 },
            Box::new(|c| reference::fresnel_conductor(c, 1.1, 0.5)),
            0.0,
        ),
        (
            Fresnel::Dielectric { eta: 1.5 },
            Box::new(|c| reference::fresnel_dielectric(c, 1.5)),
            0.0,
        ),
        (
            Fresnel::Dielectric { eta: 1.0 / 1.5 },
            Box::new(|c| reference::fresnel_dielectric(c, 1.0 / 1.5)),
            (1.0 - 1.0 / 2.25f64).sqrt(),
        ),
    ];
    for (fr, reff, crit) in cases {
        let mut br = vec![0.0, 1.0];
        if crit > 0.0 {
            br.insert(1, crit);
        }
        let want = reference::adaptive(|mu: f64| [2.0 * reff(mu) * mu], &br, 1e-13);
        let (got, err) = f_avg(&fr, 1e-12);
        assert!(
            (got - want.value[0]).abs() <= 1e-11,
            "{fr:?}: {got} vs {} (estimates {err:e}, {:e})",
            want.value[0],
            want.error
        );
    }
}

/// Turquin 2019 on baked values: the `G` channel of a Filament `dfg` table is the F = 1
/// albedo E (checked against the reference), and E·(1 + F0 (1 − E)/E) at F0 = 1 is 1 —
/// to the rounding of the f64 arithmetic on the stored f32 (a few ulps of 1: 1e-15).
#[test]
fn turquin_compensation_restores_the_furnace() {
    let mut s = spec(
        TableKind::Dfg,
        Masking::SmithHeightCorrelated,
        Fresnel::None,
        vec![mu_axis(4), alpha_axis(3, [0.1, 1.0], Convention::Endpoints)],
    );
    s.dfg_layout = Some(DfgLayout::Filament);
    let lut = bake(&s).unwrap();
    for j in 0..3 {
        let alpha = s.axes[1].alpha(j).unwrap();
        let m = RefModel::new(NdfKind::Ggx, alpha, Masking::SmithHeightCorrelated);
        for i in 0..4 {
            let e = lut.texel([i, j, 0], 1) as f64;
            let r = reference::albedo(&m, s.axes[0].coord(i), REF_TOL);
            assert!((e - r.value[0]).abs() <= bound(&lut, 1, e) + r.error);
            assert!(e < 1.0, "single scattering loses energy at alpha {alpha}");
            assert!((e * turquin_factor(1.0, e) - 1.0).abs() <= 1e-15);
            // with F0 < 1 the compensation adds F0 (1 − E) ≤ the energy lost
            let f0 = 0.04;
            assert!(e * turquin_factor(f0, e) - e <= (1.0 - e) + 1e-15);
        }
    }
}

/// `albedo-fresnel` with Schlick's F0 on a √F0 axis: against the reference with Schlick's
/// Fresnel, and the split-sum identity E(F0) = (1 − F0) R + F0 G with a Filament `dfg`
/// table of the same model (bounds: the estimates of all three channels plus f32 rounding).
#[test]
fn albedo_fresnel_schlick_matches_reference_and_split_sum() {
    let fax = axis(
        "fresnel",
        Quantity::Fresnel(FresnelQuantity::SqrtF0),
        3,
        [0.0, 1.0],
        Convention::Endpoints,
    );
    let mk = |kind| {
        spec(
            kind,
            Masking::SmithHeightCorrelated,
            Fresnel::None,
            vec![mu_axis(4), alpha_axis(2, [0.1, 0.8], Convention::Endpoints)],
        )
    };
    let mut s = mk(TableKind::AlbedoFresnel);
    s.axes.push(fax);
    let lut = bake(&s).unwrap();
    let mut d = mk(TableKind::Dfg);
    d.dfg_layout = Some(DfgLayout::Filament);
    let dfg = bake(&d).unwrap();
    for k in 0..3 {
        let f0 = s.axes[2].fresnel_parameter(k).unwrap();
        for j in 0..2 {
            let m = RefModel::new(
                NdfKind::Ggx,
                s.axes[1].alpha(j).unwrap(),
                Masking::SmithHeightCorrelated,
            );
            for i in 0..4 {
                let mu = s.axes[0].coord(i);
                let e = lut.texel([i, j, k], 0) as f64;
                let r = reference::albedo_fresnel(&m, mu, REF_TOL, |c| {
                    f0 + (1.0 - f0) * reference::fc(c)
                });
                assert!(
                    (e - r.value[0]).abs() <= bound(&lut, 0, e) + r.error,
                    "F0 {f0} mu {mu}: {e} vs {}",
                    r.value[0]
                );
                let (rr, gg) = (
                    dfg.texel([i, j, 0], 0) as f64,
                    dfg.texel([i, j, 0], 1) as f64,
                );
                let split = (1.0 - f0) * rr + f0 * gg;
                let tol = bound(&lut, 0, e) + bound(&dfg, 0, rr) + bound(&dfg, 1, gg);
                assert!((e - split).abs() <= tol, "F0 {f0} mu {mu}: {e} vs {split}");
            }
        }
    }
}

/// `albedo-fresnel` with exact Fresnel: dielectric on an η axis and conductor (η axis, the
/// model's k), against the reference's independently written Fresnel forms.
#[test]
fn albedo_fresnel_exact_matches_reference() {
    for (fresnel, range) in [
        (Fresnel::None, [1.2, 2.4]),
        (Fresnel::Conductor { eta: 1.0, k: 3.0 }, [0.2, 1.0]),
    ] {
        let mut s = spec(
            TableKind::AlbedoFresnel,
            Masking::SmithHeightCorrelated,
            fresnel,
            vec![mu_axis(3), alpha_axis(2, [0.2, 0.7], Convention::Endpoints)],
        );
        s.axes.push(axis(
            "fresnel",
            Quantity::Fresnel(FresnelQuantity::Eta),
            2,
            range,
            Convention::Endpoints,
        ));
        let lut = bake(&s).unwrap();
        for k in 0..2 {
            let eta = s.axes[2].fresnel_parameter(k).unwrap();
            for j in 0..2 {
                let m = RefModel::new(
                    NdfKind::Ggx,
                    s.axes[1].alpha(j).unwrap(),
                    Masking::SmithHeightCorrelated,
                );
                for i in 0..3 {
                    let mu = s.axes[0].coord(i);
                    let e = lut.texel([i, j, k], 0) as f64;
                    let r = reference::albedo_fresnel(&m, mu, REF_TOL, |c| match fresnel {
                        Fresnel::Conductor { k, .. } => reference::fresnel_conductor(c, eta, k),
                        _ => reference::fresnel_dielectric(c, eta),
                    });
                    assert!(
                        (e - r.value[0]).abs() <= bound(&lut, 0, e) + r.error,
                        "{fresnel:?} eta {eta} mu {mu}: {e} vs {}",
                        r.value[0]
                    );
                }
            }
        }
    }
}

fn btdf_spec(mu: Axis, alpha: Axis, eta: [f64; 2], n: usize) -> TableSpec {
    let mut s = spec(
        TableKind::DielectricBtdf,
        Masking::SmithSeparable,
        Fresnel::None,
        vec![mu, alpha],
    );
    s.axes.push(axis(
        "fresnel",
        Quantity::Fresnel(FresnelQuantity::Eta),
        n,
        eta,
        Convention::Endpoints,
    ));
    s
}

/// `dielectric-btdf` against the reference's l-space integration of Walter's BRDF and BTDF
/// (a different parameterization, the BTDF with its own Jacobian) for η > 1 and η < 1.
#[test]
fn dielectric_btdf_matches_reference() {
    let s = btdf_spec(
        axis(
            "cos_theta_v",
            Quantity::Cosine,
            2,
            [0.3, 0.8],
            Convention::Endpoints,
        ),
        alpha_axis(2, [0.3, 0.7], Convention::Endpoints),
        [1.0 / 1.5, 1.5],
        2,
    );
    let lut = bake(&s).unwrap();
    for k in 0..2 {
        let eta = s.axes[2].fresnel_parameter(k).unwrap();
        for j in 0..2 {
            let alpha = s.axes[1].alpha(j).unwrap();
            for i in 0..2 {
                let mu = s.axes[0].coord(i);
                let r = reference::dielectric_rt(alpha, eta, mu, 1e-8);
                for c in 0..2 {
                    let v = lut.texel([i, j, k], c) as f64;
                    assert!(
                        (v - r.value[c]).abs() <= bound(&lut, c, v) + r.error,
                        "eta {eta} alpha {alpha} mu {mu} channel {c}: {v} vs {} (ref error {:e})",
                        r.value[c],
                        r.error
                    );
                }
            }
        }
    }
}

/// Energy: R, T ≥ 0 and R + T ≤ 1 everywhere (up to the estimates), and in the smooth limit
/// R → F(μ), T → 1 − F(μ). At α = 1e-4 the remaining deviation is O(α²): Smith's
/// 1 − G1 ≤ Λ = (√(1 + α² tan²θ) − 1)/2 ≤ α² tan²θ/4 per side, and the Fresnel term varies
/// over a lobe of width O(α) around v·h = μ, whose first-order term is odd and cancels:
/// with tan θ ≤ 4 (μ ≥ 0.25) and |F''| ≲ 10 away from the critical angle, 1e-6 is generous.
#[test]
fn dielectric_btdf_energy_and_smooth_limit() {
    let s = btdf_spec(
        axis(
            "cos_theta_v",
            Quantity::Cosine,
            6,
            [0.02, 1.0],
            Convention::Endpoints,
        ),
        alpha_axis(3, [0.05, 1.0], Convention::Endpoints),
        [0.5, 2.0],
        3,
    );
    let mut s = s;
    s.tolerance = 1e-6;
    let lut = bake(&s).unwrap();
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..6 {
                let (r, t) = (
                    lut.texel([i, j, k], 0) as f64,
                    lut.texel([i, j, k], 1) as f64,
                );
                let tol = bound(&lut, 0, r) + bound(&lut, 1, t);
                assert!(
                    r >= -tol && t >= -tol && r + t <= 1.0 + tol,
                    "{i} {j} {k}: {r} {t}"
                );
            }
        }
    }
    // smooth limit: views away from the critical angle of η = 1/1.5 (μc = 0.745)
    let s = btdf_spec(
        axis(
            "cos_theta_v",
            Quantity::Cosine,
            3,
            [0.25, 1.0],
            Convention::Endpoints,
        ),
        alpha_axis(1, [1e-4, 1e-4], Convention::Centers),
        [1.0 / 1.5, 1.5],
        2,
    );
    let lut = bake(&s).unwrap();
    for k in 0..2 {
        let eta = s.axes[2].fresnel_parameter(k).unwrap();
        for i in [0usize, 2] {
            let mu = s.axes[0].coord(i);
            let f = reference::fresnel_dielectric(mu, eta);
            let (r, t) = (
                lut.texel([i, 0, k], 0) as f64,
                lut.texel([i, 0, k], 1) as f64,
            );
            assert!(
                (r - f).abs() <= 1e-6 && (t - (1.0 - f)).abs() <= 1e-6,
                "eta {eta} mu {mu}: R {r} T {t} F {f}"
            );
        }
    }
}

/// `sheen-charlie`'s table kind and model (albedo of Charlie + Ashikhmin, perceptual
/// roughness) against the reference, at r ∈ [0.1, 1] like the preset.
#[test]
fn sheen_albedo_matches_reference() {
    let mut s = spec(
        TableKind::Albedo,
        Masking::Ashikhmin,
        Fresnel::None,
        vec![
            mu_axis(4),
            axis(
                "roughness",
                Quantity::Roughness(RoughnessQuantity::Perceptual),
                3,
                [0.1, 1.0],
                Convention::Endpoints,
            ),
        ],
    );
    s.model.ndf = Some(NdfKind::Charlie);
    let lut = bake(&s).unwrap();
    for j in 0..3 {
        let m = RefModel::new(
            NdfKind::Charlie,
            s.axes[1].alpha(j).unwrap(),
            Masking::Ashikhmin,
        );
        for i in 0..4 {
            let e = lut.texel([i, j, 0], 0) as f64;
            let r = reference::albedo(&m, s.axes[0].coord(i), REF_TOL);
            assert!(
                (e - r.value[0]).abs() <= bound(&lut, 0, e) + r.error,
                "{i} {j}: {e} vs {}",
                r.value[0]
            );
        }
    }
}

/// Bad Fresnel axes are input errors naming the field and what is accepted.
#[test]
fn fresnel_axis_errors_name_the_field() {
    let preset = |kind: &str, model: &str, fresnel: &str| {
        format!(
            r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "t", "kind": "{kind}",
              "model": {model},
              "axes": {{"cos_theta_v": {{"size": 2}}, "roughness": {{"size": 2, "quantity": "alpha"}},
                        "fresnel": {fresnel}}}}}]}}"#
        )
    };
    let ggx = r#"{"ndf": "ggx", "masking": "smith-separable"}"#;
    let cases = [
        (
            preset("albedo-fresnel", ggx, r#"{"size": 2}"#),
            vec!["tables[0].axes.fresnel.quantity", "is required", "sqrt-f0"],
        ),
        (
            preset(
                "albedo-fresnel",
                ggx,
                r#"{"size": 2, "quantity": "perceptual"}"#,
            ),
            vec!["tables[0].axes.fresnel.quantity", "is required"],
        ),
        (
            preset(
                "albedo-fresnel",
                ggx,
                r#"{"size": 2, "quantity": "eta", "range": [0.5, 0.9]}"#,
            ),
            vec!["tables[0]", "eta >= 1", "dielectric-btdf"],
        ),
        (
            preset(
                "dielectric-btdf",
                ggx,
                r#"{"size": 2, "quantity": "sqrt-f0"}"#,
            ),
            vec!["tables[0]", "eta, eta-reflectance, inverse-eta-reflectance"],
        ),
        (
            preset(
                "dielectric-btdf",
                r#"{"ndf": "ggx", "masking": "v-groove"}"#,
                r#"{"size": 2, "quantity": "eta", "range": [1.1, 2]}"#,
            ),
            vec!["tables[0]", "smith-separable", "smith-height-correlated"],
        ),
        (
            preset(
                "albedo-fresnel",
                ggx,
                r#"{"size": 2, "quantity": "eta-reflectance", "range": [0.5, 1], "convention": "endpoints"}"#,
            ),
            vec!["axes.fresnel", "eta must be in [1e-4, 100]"],
        ),
        (
            preset("albedo-fresnel", ggx, r#"{"size": 2, "quantity": "f00"}"#),
            vec![
                "tables[0].axes.fresnel.quantity",
                "unknown quantity",
                "eta-reflectance",
            ],
        ),
    ];
    for (text, want) in cases {
        let e = brdfbake::preset::parse(&text, "t", "t")
            .unwrap_err()
            .to_string();
        for w in want {
            assert!(e.contains(w), "{w:?} not in {e}");
        }
    }
}
