//! Every model combination × every table kind at tiny sizes: it either bakes, with every
//! texel finite and within its physical bounds, or is rejected with a message — never a
//! panic, never NaN.

use brdfbake::lut::{Axis, Convention, Quantity};
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
                            },
                            axes: axes(kind, 3, q),
                            dfg_layout: layout,
                            cloth: layout.is_some(),
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
