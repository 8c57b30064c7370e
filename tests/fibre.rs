//! The fibre paths of `dielectric-btdf` and `albedo-fresnel` tables (src/table/mod.rs
//! `FibreFn`, src/table/dielectric.rs `reflect_transmit_fibre`, src/table/energy.rs
//! `directional_albedo_fresnels`): the texels of one (μ, roughness) pair, every Fresnel slice,
//! integrated as the channels of one shared rule, against the same texels integrated one by
//! one; the roughness fibres of the η < 1 slices of the dielectric kinds
//! (src/kernels/roughness_fibre.rs: every roughness of one (μ, η) by shared rules) likewise;
//! and the baked tables' bytes on 1 and 2 threads.
//!
//! Tolerances: both paths report an error estimate per texel that over-estimates its own
//! error (nested-rule differences, |K15 − G7| where they fall back), so two results of the
//! same integral differ by at most the sum of both estimates. A baked texel is stored in f32
//! (rounding ≤ 2⁻²⁴ relative) and the table keeps the largest estimate per channel, which
//! bounds its texel's fibre estimate. (The values themselves are checked against the
//! independent reference in tests/energy.rs and tests/dielectric_fast.rs, whose tables now
//! go through the fibre path.)

use brdfbake::lut::{Axis, Convention, Lut, Quantity};
use brdfbake::model::btdf::RoughDielectric;
use brdfbake::model::{Fresnel, FresnelQuantity, Masking, Ndf, NdfKind, RoughnessQuantity};
use brdfbake::table::albedo::directional_albedo;
use brdfbake::table::dielectric::{fibre_groups, reflect_transmit, reflect_transmit_fibre};
use brdfbake::table::energy::directional_albedo_fresnels;
use brdfbake::table::{bake, ModelSpec, Storage, TableKind, TableSpec};

const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;

/// R and T of every η of a fibre that mixes both sides of 1 (a shared group of 4 with η = 1,
/// where R = 0, and lone η < 1 slices) agree with `reflect_transmit` texel by texel within
/// the sum of both estimates, at normal, middle and grazing views and narrow to wide lobes.
#[test]
fn btdf_fibre_matches_per_texel() {
    let tol = 1e-6;
    let etas = [1.0 / 3.0, 0.8, 1.0, 1.2, 1.5, 3.0];
    let groups = fibre_groups(&etas);
    assert_eq!(
        groups,
        vec![vec![0], vec![1], vec![2, 3, 4, 5]],
        "η < 1 alone, η ≥ 1 shared"
    );
    for alpha in [0.02, 0.3, 1.0] {
        let ndf = Ndf::new(NdfKind::Ggx, alpha).unwrap();
        for mu in [0.05, 0.5, 0.97] {
            let fib = reflect_transmit_fibre(&ndf, &etas, mu, tol);
            let mut shared_evals = 0;
            for (z, &eta) in etas.iter().enumerate() {
                let e = reflect_transmit(
                    &RoughDielectric {
                        ndf: ndf.clone(),
                        eta,
                    },
                    mu,
                    tol,
                );
                let (v, err, _) = fib[z];
                for c in 0..2 {
                    assert!(
                        err[c] <= tol,
                        "alpha {alpha} mu {mu} eta {eta} c {c}: {err:?}"
                    );
                    assert!(
                        (v[c] - e.value[c]).abs() <= err[c] + e.error[c],
                        "alpha {alpha} mu {mu} eta {eta} channel {c}: fibre {} ± {} vs texel {} ± {}",
                        v[c],
                        err[c],
                        e.value[c],
                        e.error[c]
                    );
                }
                if eta >= 1.0 {
                    shared_evals += fib[z].2;
                }
            }
            // η = 1: F = 0, nothing is reflected, exactly
            assert_eq!(fib[2].0[0], 0.0);
            // the group's nodes are counted once, at its first slice
            assert!(shared_evals > 0 && fib[3].2 == 0 && fib[5].2 == 0);
        }
    }
}

/// R and T of every roughness of a roughness fibre (EEVEE's 15 layers α = (k/15)² in one
/// rule, and Cycles' clamped α = 1e-8 beside (0.1)² … 1 in two runs) agree with
/// `reflect_transmit_with`, whose integrand is the model's own (`BelowOne`: `Ndf::g1`,
/// `SmithForm::g`, the exact Fresnel term), texel by texel within the sum of both estimates,
/// each estimate within the tolerance, for both masking forms, indices from 1/3 to 0.99
/// and views from grazing (1e-4, Cycles' clamp) to normal.
#[test]
fn roughness_fibre_matches_per_texel() {
    use brdfbake::kernels::roughness_fibre::{roughness_fibre_with, ROUGHNESS_FIBRE};
    use brdfbake::model::btdf::SmithForm;
    use brdfbake::model::fresnel::dielectric;
    use brdfbake::table::dielectric::reflect_transmit_with;
    let tol = 1e-6;
    let eevee: Vec<f64> = (1..16).map(|k| (k as f64 / 15.0).powi(2)).collect();
    let cycles: Vec<f64> = std::iter::once(1e-8)
        .chain((3..=10).map(|k| (k as f64 / 10.0).powi(2)))
        .collect();
    for (alphas, smith) in [
        (&eevee, SmithForm::Separable),
        (&cycles, SmithForm::HeightCorrelated),
    ] {
        let ndfs: Vec<Ndf> = alphas
            .iter()
            .map(|&a| Ndf::new(NdfKind::Ggx, a).unwrap())
            .collect();
        for eta in [1.0 / 3.0, 0.75, 0.99] {
            for mu in [1e-4, 0.05, 0.5, 0.97] {
                let fib = roughness_fibre_with::<{ 2 * ROUGHNESS_FIBRE }, 2>(
                    &ndfs,
                    smith,
                    eta,
                    mu,
                    tol,
                    |c| {
                        let f = dielectric(c, eta);
                        [[f, 0.0], [0.0, 1.0 - f]]
                    },
                );
                for (ndf, e) in ndfs.iter().zip(&fib) {
                    let m = RoughDielectric {
                        ndf: ndf.clone(),
                        eta,
                    };
                    let r = reflect_transmit_with(&m, smith, mu, tol);
                    for c in 0..2 {
                        assert!(e.error[c] <= tol, "{smith:?} eta {eta} mu {mu}: {e:?}");
                        assert!(
                            (e.value[c] - r.value[c]).abs() <= e.error[c] + r.error[c],
                            "{smith:?} alpha {} eta {eta} mu {mu} channel {c}: fibre {} ± {} vs texel {} ± {}",
                            ndf.alpha(),
                            e.value[c],
                            e.error[c],
                            r.value[c],
                            r.error[c]
                        );
                    }
                }
            }
        }
    }
}

/// E of one GGX lobe for ten Fresnel terms (two groups: 8 + 2; exact dielectrics η = 1…3,
/// conductors) agrees with `directional_albedo` term by term within the sum of both
/// estimates.
#[test]
fn albedo_fresnel_fibre_matches_per_texel() {
    let tol = 1e-7;
    let fresnels: Vec<Fresnel> = [1.0, 1.1, 1.3, 1.5, 1.8, 2.2, 3.0]
        .iter()
        .map(|&eta| Fresnel::Dielectric { eta })
        .chain([
            Fresnel::Conductor { eta: 0.2, k: 3.0 },
            Fresnel::Conductor { eta: 1.0, k: 1.0 },
            Fresnel::Conductor { eta: 2.5, k: 0.5 },
        ])
        .collect();
    for masking in [Masking::SmithHeightCorrelated, Masking::SmithSeparable] {
        let model = ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        };
        for alpha in [0.03, 0.4, 1.0] {
            let brdf = model.brdf(alpha).unwrap();
            for mu in [0.02, 0.3, 1.0] {
                let fib = directional_albedo_fresnels(&brdf, &fresnels, mu, tol);
                assert_eq!(fib.len(), fresnels.len());
                for (z, &f) in fresnels.iter().enumerate() {
                    let mut m = model.clone();
                    m.fresnel = f;
                    let (v, e, _) = directional_albedo(&m.brdf(alpha).unwrap(), mu, tol);
                    let (fv, fe, _) = fib[z];
                    assert!(
                        fe[0] <= tol,
                        "{masking:?} alpha {alpha} mu {mu} {f:?}: {fe:?}"
                    );
                    assert!(
                        (fv[0] - v[0]).abs() <= fe[0] + e[0],
                        "{masking:?} alpha {alpha} mu {mu} {f:?}: fibre {} ± {} vs texel {} ± {}",
                        fv[0],
                        fe[0],
                        v[0],
                        e[0]
                    );
                }
                // nodes counted once per group, at its first slice (slices 0 and 8)
                assert!(fib[0].2 > 0 && fib[8].2 > 0);
                assert!(fib.iter().enumerate().all(|(z, r)| z % 8 == 0 || r.2 == 0));
            }
        }
    }
}

/// Outside the shared rule's scope (V-groove masking: kinked; Charlie: sheen warps) every
/// term goes by `directional_albedo` itself: the same bits.
#[test]
fn albedo_fresnel_fibre_outside_its_scope_is_per_texel() {
    let tol = 1e-7;
    let fresnels = [
        Fresnel::Dielectric { eta: 1.5 },
        Fresnel::Conductor { eta: 0.2, k: 3.0 },
    ];
    for (ndf, masking) in [
        (NdfKind::Beckmann, Masking::VGroove),
        (NdfKind::Charlie, Masking::Ashikhmin),
    ] {
        let model = ModelSpec {
            ndf: Some(ndf),
            masking,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        };
        let fib = directional_albedo_fresnels(&model.brdf(0.3).unwrap(), &fresnels, 0.6, tol);
        for (z, &f) in fresnels.iter().enumerate() {
            let mut m = model.clone();
            m.fresnel = f;
            let per = directional_albedo(&m.brdf(0.3).unwrap(), 0.6, tol);
            assert_eq!(fib[z], per, "{ndf:?} {masking:?} {f:?}");
        }
    }
}

fn table(
    kind: TableKind,
    masking: Masking,
    fresnel: Fresnel,
    eta: [f64; 2],
    nz: usize,
) -> TableSpec {
    let axis = |name: &str, quantity, size, range, convention| Axis {
        name: String::from(name),
        quantity,
        size,
        range,
        convention,
        warp: Default::default(),
        clamp: None,
    };
    TableSpec {
        name: "fibre".into(),
        kind,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking,
            fresnel,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes: vec![
            axis(
                "cos_theta_v",
                Quantity::Cosine,
                4,
                [0.0, 1.0],
                Convention::Centers,
            ),
            axis(
                "roughness",
                Quantity::Roughness(RoughnessQuantity::Perceptual),
                3,
                [0.0, 1.0],
                Convention::Centers,
            ),
            axis(
                "fresnel",
                Quantity::Fresnel(FresnelQuantity::Eta),
                nz,
                eta,
                Convention::Endpoints,
            ),
        ],
        dfg_layout: None,
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-6,
    }
}

fn bake_on(threads: usize, spec: &TableSpec) -> Lut {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| bake(spec).unwrap())
}

/// The fibre kinds (`dielectric-btdf`, `albedo-fresnel`, and with η on both sides of 1
/// `dielectric-schlick` and `dielectric-albedo`, whose η < 1 slices go by roughness fibres)
/// bake the same bytes, estimates and evaluation counts on 1 and 2 threads, and every texel
/// sits where the per-texel path puts it (the fibres' texels placed in texel order): within
/// the per-texel estimate, the table's estimate and f32 rounding of it.
#[test]
fn fibre_tables_are_bit_identical_across_threads_and_in_place() {
    let btdf = table(
        TableKind::DielectricBtdf,
        Masking::SmithSeparable,
        Fresnel::None,
        [0.5, 2.0],
        6,
    );
    let albedo = table(
        TableKind::AlbedoFresnel,
        Masking::SmithHeightCorrelated,
        Fresnel::None,
        [1.0, 3.0],
        10,
    );
    // η from 1/2 to 2: the η < 1 slices by roughness fibres, the others by Fresnel fibres
    let schlick = table(
        TableKind::DielectricSchlick,
        Masking::SmithSeparable,
        Fresnel::None,
        [0.5, 2.0],
        6,
    );
    let glass = table(
        TableKind::DielectricAlbedo,
        Masking::SmithHeightCorrelated,
        Fresnel::None,
        [0.5, 2.0],
        6,
    );
    for spec in [&btdf, &albedo, &schlick, &glass] {
        let one = bake_on(1, spec);
        let two = bake_on(2, spec);
        let bits = |l: &Lut| l.data.iter().map(|v| v.to_bits()).collect::<Vec<u32>>();
        let ebits = |l: &Lut| {
            l.error_estimate
                .iter()
                .map(|v| v.to_bits())
                .collect::<Vec<u64>>()
        };
        assert_eq!(bits(&one), bits(&two), "{:?}: texels differ", spec.kind);
        assert_eq!(
            ebits(&one),
            ebits(&two),
            "{:?}: estimates differ",
            spec.kind
        );
        assert_eq!(one.evaluations, two.evaluations, "{:?}", spec.kind);
        let ax = &spec.axes;
        for z in 0..ax[2].size {
            let eta = ax[2].fresnel_parameter(z).unwrap();
            for j in 0..ax[1].size {
                let alpha = ax[1].alpha(j).unwrap();
                for i in 0..ax[0].size {
                    let mu = ax[0].coord(i);
                    let ndf = Ndf::new(NdfKind::Ggx, alpha).unwrap();
                    let (value, error): (Vec<f64>, Vec<f64>) = match spec.kind {
                        TableKind::DielectricBtdf => {
                            let m = RoughDielectric { ndf, eta };
                            let e = reflect_transmit(&m, mu, spec.tolerance);
                            (e.value.to_vec(), e.error.to_vec())
                        }
                        TableKind::DielectricAlbedo => {
                            let m = RoughDielectric { ndf, eta };
                            let e = brdfbake::table::dielectric::reflect_transmit_with(
                                &m,
                                brdfbake::model::btdf::SmithForm::HeightCorrelated,
                                mu,
                                spec.tolerance,
                            );
                            (vec![e.value[0] + e.value[1]], vec![e.error[0] + e.error[1]])
                        }
                        TableKind::DielectricSchlick => {
                            use brdfbake::kernels::micro_normals::{integrate_micro_normals, Rule};
                            let smith = brdfbake::model::btdf::SmithForm::Separable;
                            let g1v = ndf.g1(mu);
                            let e = integrate_micro_normals(
                                &ndf,
                                Rule::standard(&[eta]),
                                mu,
                                spec.tolerance,
                                |h| {
                                    brdfbake::model::schlick_dielectric::integrands(
                                        &ndf, smith, eta, mu, g1v, h,
                                    )
                                },
                            );
                            (e.value.to_vec(), e.error.to_vec())
                        }
                        _ => {
                            let mut m = spec.model.clone();
                            m.fresnel = Fresnel::Dielectric { eta };
                            let (v, e, _) =
                                directional_albedo(&m.brdf(alpha).unwrap(), mu, spec.tolerance);
                            (v.to_vec(), e.to_vec())
                        }
                    };
                    for c in 0..value.len() {
                        let t = one.texel([i, j, z], c) as f64;
                        assert!(
                            (t - value[c]).abs()
                                <= error[c] + one.error_estimate[c] + F32_REL * t.abs(),
                            "{:?} texel {:?} channel {c}: {t} vs {} ± {}",
                            spec.kind,
                            [i, j, z],
                            value[c],
                            error[c]
                        );
                    }
                }
            }
        }
    }
}
