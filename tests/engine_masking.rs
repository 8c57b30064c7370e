//! The masking models engines use (issue 23): Schlick-GGX (Karis 2013; Unreal's
//! PreIntegratedGF, LearnOpenGL's BRDF LUT) in whole tables, baked as engines lay them out,
//! against the independent reference (tests/common/reference.rs: l-space polar coordinates,
//! adaptive Gauss–Legendre, Schlick's G1 and Karis' k written there again).
//!
//! Tolerances (per texel and channel):
//! * `REQ = 1e-6`, the accuracy every baked value needs;
//! * |stored − reference| ≤ the table's largest estimate for that channel + the
//!   reference's estimate + the f32 rounding of the stored value (half an ulp, 2⁻²⁴
//!   relative): both estimates claim to bound their errors, so their sum bounds the
//!   difference, and storage adds its rounding.
//!
//! The reference is run at `REF_TOL = 1e-10` inside its validated range (μ, α ≥ 1e-3,
//! tests/accuracy.rs); below it the library's adaptive Gauss–Kronrod integrator (a
//! different parameterization, rule and estimate from the table's kernels) at the same
//! tolerance.

#[path = "common/reference.rs"]
mod reference;

use brdfbake::lut::{Axis, Convention, Lut, Quantity};
use brdfbake::model::{Fresnel, Masking, Ndf, NdfKind, RoughnessQuantity, Specular};
use brdfbake::table::dfg::split_sum_adaptive;
use brdfbake::table::{bake, DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
use rayon::prelude::*;
use reference::RefModel;

const REQ: f64 = 1e-6;
const REF_TOL: f64 = 1e-10;
const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;

fn centers(name: &str, quantity: Quantity, size: usize) -> Axis {
    Axis::new(name, quantity, size, [0.0, 1.0], Convention::Centers)
}

fn karis(masking: Masking, nx: usize, ny: usize) -> TableSpec {
    TableSpec {
        name: "t".into(),
        kind: TableKind::Dfg,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes: vec![
            centers("cos_theta_v", Quantity::Cosine, nx),
            centers(
                "roughness",
                Quantity::Roughness(RoughnessQuantity::Perceptual),
                ny,
            ),
        ],
        dfg_layout: Some(DfgLayout::Karis),
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-7,
    }
}

/// Six indices spread over `0..n`, both ends included.
fn spread(n: usize) -> Vec<usize> {
    let mut v: Vec<usize> = (0..6).map(|k| k * (n - 1) / 5).collect();
    v.dedup();
    v
}

/// The split sum (A, B) at (μ, α) with its estimate: the reference inside its validated
/// range, else the library's adaptive integrator.
fn split_sum_ref(masking: Masking, mu: f64, alpha: f64) -> ([f64; 2], f64) {
    if mu >= 1e-3 && alpha >= 1e-3 {
        let r = reference::split_sum(&RefModel::new(NdfKind::Ggx, alpha, masking), mu, REF_TOL);
        (r.value, r.error)
    } else {
        let s = Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
            masking,
            fresnel: Fresnel::None,
        };
        let (v, e, _) = split_sum_adaptive(&s, mu, REF_TOL);
        (v, e[0].max(e[1]))
    }
}

/// Texel (i, j) of a Karis table against [`split_sum_ref`], within the tolerances above.
fn check_karis_texel(lut: &Lut, masking: Masking, i: usize, j: usize) -> Vec<String> {
    let mu = lut.axes[0].coord(i);
    let alpha = lut.axes[1].alpha(j).unwrap();
    let (r, re) = split_sum_ref(masking, mu, alpha);
    let mut f = Vec::new();
    for (c, &rc) in r.iter().enumerate() {
        let got = lut.texel([i, j, 0], c) as f64;
        let d = (got - rc).abs();
        let bound = lut.error_estimate[c] + re + F32_REL * rc.abs();
        if d > REQ || d > bound {
            f.push(format!(
                "{masking:?} {}x{} texel ({i},{j}) mu={mu} alpha={alpha} ch{c}: table {got}, reference {} diff {d:e} bound {bound:e}",
                lut.axes[0].size, lut.axes[1].size, rc
            ));
        }
    }
    f
}

fn assert_none(what: &str, failures: &[String]) {
    assert!(
        failures.is_empty(),
        "{what}: {} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Unreal's layout (128 × 32: u = n·v, v = perceptual roughness, texel centres, A and B)
/// with both Schlick-GGX forms, and LearnOpenGL's (512², the same axes) with k = α/2,
/// baked by lines (dfg_lines.rs, the polar kernel at each node): 6 × 6 texels each,
/// corners included, against the reference.
#[test]
fn karis_tables_of_schlick_ggx_match_the_reference() {
    let mut cases = vec![
        (Masking::SchlickGgx, 128, 32),
        (Masking::SchlickGgxDirect, 128, 32),
        (Masking::SchlickGgx, 512, 512),
    ];
    let mut failures = Vec::new();
    for (masking, nx, ny) in cases.drain(..) {
        let lut = bake(&karis(masking, nx, ny)).unwrap();
        let pts: Vec<(usize, usize)> = spread(ny)
            .into_iter()
            .flat_map(|j| spread(nx).into_iter().map(move |i| (i, j)))
            .collect();
        failures.extend(
            pts.par_iter()
                .flat_map_iter(|&(i, j)| check_karis_texel(&lut, masking, i, j))
                .collect::<Vec<_>>(),
        );
    }
    assert_none("schlick-ggx Karis tables", &failures);
}

/// The engine presets `unreal-preintegrated-gf` and `learnopengl-brdf-lut` are the tables
/// checked against the reference above: the same model, axes and layout (only the name,
/// storage and tolerance may differ), so what that test shows holds for what they bake.
#[test]
fn engine_presets_are_the_tables_checked_above() {
    for (name, masking, nx, ny) in [
        ("unreal-preintegrated-gf", Masking::SchlickGgx, 128, 32),
        ("learnopengl-brdf-lut", Masking::SchlickGgx, 512, 512),
    ] {
        let (_, text) = brdfbake::presets::ENGINES
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("no engine preset {name}"));
        let preset = brdfbake::preset::parse(text, name, name).unwrap();
        let spec = &preset.tables[0].spec;
        let want = karis(masking, nx, ny);
        assert_eq!(
            (
                &spec.kind,
                &spec.model,
                &spec.axes,
                &spec.dfg_layout,
                spec.cloth
            ),
            (
                &want.kind,
                &want.model,
                &want.axes,
                &want.dfg_layout,
                want.cloth
            ),
            "{name}"
        );
        assert!(
            spec.tolerance <= want.tolerance,
            "{name}: {}",
            spec.tolerance
        );
    }
}

/// The directional albedo with Schlick's Fresnel (E = F0·A + B from the polar split sum)
/// and with exact dielectric Fresnel (the generic path), both Schlick-GGX forms, on a
/// 7 × 5 table from μ = 0.02 and α = 0.01: against the reference's Fresnel albedo.
#[test]
fn albedo_of_schlick_ggx_matches_the_reference() {
    let mut failures = Vec::new();
    for masking in [Masking::SchlickGgx, Masking::SchlickGgxDirect] {
        for (fresnel, fr) in [
            (
                Fresnel::Schlick { f0: 0.04 },
                Box::new(|c: f64| 0.04 + 0.96 * reference::fc(c)) as Box<dyn Fn(f64) -> f64 + Sync>,
            ),
            (
                Fresnel::Dielectric { eta: 1.5 },
                Box::new(|c: f64| reference::fresnel_dielectric(c, 1.5)),
            ),
        ] {
            let spec = TableSpec {
                name: "e".into(),
                kind: TableKind::Albedo,
                model: ModelSpec {
                    ndf: Some(NdfKind::Ggx),
                    masking,
                    fresnel,
                    diffuse_weight: 0.0,
                    diffuse_model: brdfbake::model::DiffuseModel::Lambert,
                    classic: None,
                },
                axes: vec![
                    Axis::new(
                        "cos_theta_v",
                        Quantity::Cosine,
                        7,
                        [0.02, 1.0],
                        Convention::Endpoints,
                    ),
                    Axis::new(
                        "roughness",
                        Quantity::Roughness(RoughnessQuantity::Alpha),
                        5,
                        [0.01, 1.0],
                        Convention::Endpoints,
                    ),
                ],
                dfg_layout: None,
                cloth: false,
                cloth_alpha_min: None,
                ltc_channels: None,
                storage: Storage::F32,
                tolerance: 1e-7,
            };
            let lut = bake(&spec).unwrap();
            let pts: Vec<(usize, usize)> = (0..35).map(|k| (k % 7, k / 7)).collect();
            failures.extend(
                pts.par_iter()
                    .filter_map(|&(i, j)| {
                        let (mu, alpha) = (lut.axes[0].coord(i), lut.axes[1].alpha(j).unwrap());
                        let m = RefModel::new(NdfKind::Ggx, alpha, masking);
                        let r = reference::albedo_fresnel(&m, mu, REF_TOL, &fr);
                        let got = lut.texel([i, j, 0], 0) as f64;
                        let d = (got - r.value[0]).abs();
                        let bound = lut.error_estimate[0] + r.error + F32_REL * r.value[0];
                        (d > REQ || d > bound).then(|| {
                            format!(
                                "{masking:?} {fresnel:?} mu={mu} alpha={alpha}: table {got}, reference {} diff {d:e} bound {bound:e}",
                                r.value[0]
                            )
                        })
                    })
                    .collect::<Vec<_>>(),
            );
        }
    }
    assert_none("schlick-ggx albedo", &failures);
}
