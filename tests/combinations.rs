//! Every model combination × every table kind at tiny sizes: it either bakes, with every
//! texel finite and within its physical bounds, or is rejected with a message — never a
//! panic, never NaN.

use brdfbake::lut::{Axis, Convention, Quantity};
use brdfbake::model::ndf::MIN_ALPHA;
use brdfbake::model::{Fresnel, Masking, NdfKind, RoughnessQuantity};
use brdfbake::table::{bake, DfgLayout, ModelSpec, Storage, TableKind, TableSpec};

fn axes(kind: TableKind, n: usize, q: RoughnessQuantity) -> Vec<Axis> {
    kind.axis_names()
        .iter()
        .map(|name| {
            let rough = *name == "roughness";
            let (quantity, range) = if rough {
                match q {
                    RoughnessQuantity::BlinnPhongExponent => (Quantity::Roughness(q), [1.0, 200.0]),
                    _ => (Quantity::Roughness(q), [0.0, 1.0]),
                }
            } else if *name == "fresnel" {
                // η from 1 to 3: both Fresnel-axis kinds accept it
                (
                    Quantity::Fresnel(brdfbake::model::FresnelQuantity::EtaReflectance),
                    [0.0, 0.5],
                )
            } else {
                (Quantity::Cosine, [0.0, 1.0])
            };
            Axis {
                name: name.to_string(),
                quantity,
                size: n,
                range,
                convention: Convention::Centers,
                warp: Default::default(),
                clamp: None,
            }
        })
        .collect()
}

#[test]
fn every_combination_bakes_or_is_rejected() {
    let fresnels = [
        Fresnel::None,
        Fresnel::Schlick { f0: 0.5 },
        Fresnel::Dielectric { eta: 1.5 },
    ];
    let mut baked = 0;
    let mut rejected = 0;
    for kind in TableKind::ALL {
        for ndf in NdfKind::ALL.map(Some).into_iter().chain([None]) {
            for masking in Masking::ALL {
                for fresnel in fresnels {
                    for diffuse in [0.0, 0.5] {
                        let q = match ndf {
                            Some(NdfKind::BlinnPhong) => RoughnessQuantity::BlinnPhongExponent,
                            _ => RoughnessQuantity::Perceptual,
                        };
                        let layout = (kind == TableKind::Dfg).then_some(DfgLayout::Filament);
                        let spec = TableSpec {
                            name: "t".into(),
                            kind,
                            model: ModelSpec {
                                ndf,
                                masking,
                                fresnel,
                                diffuse_weight: diffuse,
                                diffuse_model: brdfbake::model::DiffuseModel::Lambert,
                                classic: None,
                            },
                            axes: axes(kind, 3, q),
                            dfg_layout: layout,
                            cloth: layout.is_some(),
                            cloth_alpha_min: None,
                            ltc_channels: None,
                            storage: Storage::F32,
                            tolerance: 1e-6,
                        };
                        let what =
                            format!("{kind:?} {ndf:?} {masking:?} {fresnel:?} diffuse {diffuse}");
                        match bake(&spec) {
                            Err(e) => {
                                let msg = e.to_string();
                                assert!(msg.len() > 20, "{what}: unhelpful error {msg:?}");
                                rejected += 1;
                            }
                            Ok(lut) => {
                                baked += 1;
                                let nc = lut.channels.len();
                                for (i, v) in lut.data.iter().enumerate() {
                                    let ch = &lut.channels[i % nc].name;
                                    assert!(v.is_finite(), "{what}: texel {i} {ch} = {v}");
                                    assert!(*v >= 0.0, "{what}: texel {i} {ch} = {v} < 0");
                                    // G and the realizability mask are in [0, 1]
                                    if matches!(
                                        kind,
                                        TableKind::G1 | TableKind::G2 | TableKind::Vgroove
                                    ) {
                                        assert!(*v <= 1.0, "{what}: texel {i} {ch} = {v} > 1");
                                    }
                                    // With masking and F ≤ 1, a single-scattering microfacet BRDF
                                    // (plus a Lambert lobe of weight w ≤ 1 − ... ) reflects at most
                                    // w_s·1 + w_d: allow the bake tolerance 1e-6.
                                    let energy_bounded = matches!(
                                        masking,
                                        Masking::SmithSeparable | Masking::SmithHeightCorrelated
                                    ) && ndf != Some(NdfKind::Charlie);
                                    if matches!(kind, TableKind::Albedo | TableKind::AlbedoAvg)
                                        && energy_bounded
                                    {
                                        assert!(
                                            *v as f64 <= 1.0 + diffuse + 1e-6,
                                            "{what}: texel {i} E = {v}"
                                        );
                                    }
                                    if matches!(
                                        kind,
                                        TableKind::KullaConty
                                            | TableKind::AlbedoFresnel
                                            | TableKind::DielectricBtdf
                                            | TableKind::DielectricSchlick
                                    ) && energy_bounded
                                    {
                                        assert!(
                                            *v as f64 <= 1.0 + 1e-6,
                                            "{what}: texel {i} {ch} = {v}"
                                        );
                                    }
                                    if kind == TableKind::Dfg && ch != "B" && energy_bounded {
                                        assert!(
                                            *v as f64 <= 1.0 + 1e-6,
                                            "{what}: texel {i} {ch} = {v}"
                                        );
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    // the sweep must exercise both outcomes substantially
    assert!(
        baked > 50 && rejected > 50,
        "baked {baked}, rejected {rejected}"
    );
}

/// The axes of `kind` at their edges: 2 texels with the endpoints convention, so the texels
/// sit exactly on the range ends. Cosines run from 1e-6 (grazing; a texel at cos θ = 0 is
/// refused by validation) to 1; roughness runs from just above the smallest accepted α
/// (1e-9, [`MIN_ALPHA`]) — as perceptual roughness √1e-9 — to 1 for every kind and NDF
/// (Blinn-Phong: exponent ≈ 2e18 down to 0).
fn edge_axes(kind: TableKind, q: RoughnessQuantity) -> Vec<Axis> {
    kind.axis_names()
        .iter()
        .map(|name| {
            let (quantity, range) = if *name == "roughness" {
                match q {
                    // exponent 0 (α = 1) and s = 2/α² − 2 at α just above MIN_ALPHA (≈ 2e18)
                    RoughnessQuantity::BlinnPhongExponent => {
                        let a = MIN_ALPHA * 1.000001;
                        (Quantity::Roughness(q), [0.0, 2.0 / (a * a) - 2.0])
                    }
                    // just above √MIN_ALPHA (rounding cannot square it below)
                    _ => (Quantity::Roughness(q), [(MIN_ALPHA * 1.000001).sqrt(), 1.0]),
                }
            } else if *name == "fresnel" {
                // η = 1 (index-matched: no reflection) to η = 3, both ends sampled
                (
                    Quantity::Fresnel(brdfbake::model::FresnelQuantity::EtaReflectance),
                    [0.0, 0.5],
                )
            } else {
                // cos θ = 0 itself is refused by validation (the tables divide by it)
                (Quantity::Cosine, [1e-6, 1.0])
            };
            Axis {
                name: name.to_string(),
                quantity,
                size: 2,
                range,
                convention: Convention::Endpoints,
                warp: Default::default(),
                clamp: None,
            }
        })
        .collect()
}

/// Every table kind × model at its edge texels (cos θ → 0, grazing, roughness → 0 and 1):
/// every texel finite and within its physical bounds — D ≥ 0; G1, G2, the V-groove term in
/// [0, 1]; albedo and the DFG scale/bias of an energy-bounded model (Smith masking, F ≤ 1)
/// in [0, 1 + tolerance] (+ the Lambert weight for albedo) — or a rejection with a message.
#[test]
fn edge_texels_are_finite_and_bounded() {
    let mut baked = std::collections::BTreeMap::new();
    for kind in TableKind::ALL {
        for ndf in NdfKind::ALL.map(Some).into_iter().chain([None]) {
            for masking in Masking::ALL {
                for fresnel in [Fresnel::None, Fresnel::Dielectric { eta: 1.5 }] {
                    let q = match ndf {
                        Some(NdfKind::BlinnPhong) => RoughnessQuantity::BlinnPhongExponent,
                        _ => RoughnessQuantity::Perceptual,
                    };
                    let layout = (kind == TableKind::Dfg).then_some(DfgLayout::Filament);
                    let spec = TableSpec {
                        name: "t".into(),
                        kind,
                        model: ModelSpec {
                            ndf,
                            masking,
                            fresnel,
                            diffuse_weight: 0.0,
                            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
                            classic: None,
                        },
                        axes: edge_axes(kind, q),
                        dfg_layout: layout,
                        cloth: layout.is_some(),
                        cloth_alpha_min: None,
                        ltc_channels: None,
                        storage: Storage::F32,
                        // only finiteness and bounds are checked here: a loose tolerance
                        // keeps the near-delta lobes fast
                        tolerance: 1e-4,
                    };
                    let what = format!("edges: {kind:?} {ndf:?} {masking:?} {fresnel:?}");
                    let lut = match bake(&spec) {
                        Err(e) => {
                            let msg = e.to_string();
                            assert!(msg.len() > 20, "{what}: unhelpful error {msg:?}");
                            continue;
                        }
                        Ok(lut) => lut,
                    };
                    *baked.entry(kind.name()).or_insert(0) += 1;
                    let nc = lut.channels.len();
                    let energy_bounded = masking.is_smith() && ndf != Some(NdfKind::Charlie);
                    for (i, v) in lut.data.iter().enumerate() {
                        let ch = &lut.channels[i % nc].name;
                        assert!(v.is_finite() && *v >= 0.0, "{what}: texel {i} {ch} = {v}");
                        let bounded_by_1 =
                            // (a schlick-weight table is a mean of s in [0, 1]; a
                            // dielectric-schlick channel is at most A + B or T, each ≤ 1 by
                            // the visible normals' normalization)
                            matches!(
                                kind,
                                TableKind::G1
                                    | TableKind::G2
                                    | TableKind::Vgroove
                                    | TableKind::SchlickWeightVndf
                                    | TableKind::SchlickWeightAlbedo
                                    | TableKind::DielectricSchlick
                            )
                                || (energy_bounded
                                    && (matches!(kind, TableKind::Albedo | TableKind::AlbedoAvg)
                                        || (kind == TableKind::Dfg && ch != "B")));
                        // the bake's own tolerance 1e-4 on top of the physical bound 1
                        if bounded_by_1 {
                            assert!(*v as f64 <= 1.0 + 1e-4, "{what}: texel {i} {ch} = {v} > 1");
                        }
                    }
                }
            }
        }
    }
    // every kind must bake at its edges for some model
    assert_eq!(
        baked.len(),
        TableKind::ALL.len(),
        "kinds baked at their edges: {baked:?}"
    );
}
