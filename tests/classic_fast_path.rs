//! The 1D fast path of the classic-albedo tables (`src/kernels/classic_lobes.rs`, used by
//! `table::classic::fast_albedo`) against the energy-law integrator it replaces (nested
//! adaptive Gauss–Kronrod over the half vector, a different parameterization and rule) at
//! 100× tighter tolerance, and against the independent l-space reference integrator of
//! `tests/common/reference.rs`: every texel of the three tables of the `classic-albedo`
//! preset, exponent 0, huge exponents and grazing views, the original Phong lobe, the
//! Lambert weights, and a texel where the fast path must refuse (and the table still gets
//! the right value from the fallback).

#[path = "common/reference.rs"]
mod reference;

use brdfbake::laws::Albedo;
use brdfbake::lut::{Axis, Convention, Quantity};
use brdfbake::model::{Fresnel, Masking};
use brdfbake::table::classic::{fast_albedo, view_albedo, ClassicModel};
use brdfbake::table::{bake, ModelSpec, Storage, TableKind, TableSpec};

/// The preset's tolerance (presets/classic-albedo.json leaves it at the default).
const TOL: f64 = 1e-7;

/// The three tables of presets/classic-albedo.json: model and parameter range (16 cosines
/// and 8 parameters at texel centres).
fn preset_tables() -> [(ClassicModel, [f64; 2]); 3] {
    [
        (ClassicModel::BlinnPhong { ks: 1.0 }, [0.0, 256.0]),
        (
            ClassicModel::ModifiedPhong { kd: 0.0, ks: 1.0 },
            [0.0, 256.0],
        ),
        (
            ClassicModel::WardGmd {
                rho_d: 0.0,
                rho_s: 1.0,
            },
            [0.0, 0.8],
        ),
    ]
}

fn centre(i: usize, n: usize, [lo, hi]: [f64; 2]) -> f64 {
    lo + (hi - lo) * (i as f64 + 0.5) / n as f64
}

/// The energy-law integrator (what the table used before) at `tol`.
fn laws(c: &ClassicModel, mu: f64, p: f64, tol: f64) -> Albedo {
    view_albedo(c.reflectance(p, 1.0), mu, 0.0, tol)
}

/// Checks one fast-path value against a reference: within the tolerance the fast path was
/// asked for (plus the reference's own estimate), and within the fast path's estimate plus
/// the reference's (the estimate must not be optimistic).
fn check(what: &str, fast: &Albedo, reference: f64, ref_err: f64, tol: f64) {
    let d = (fast.value - reference).abs();
    assert!(
        d <= tol + ref_err,
        "{what}: fast {} vs reference {reference}: |diff| {d:e} > tol {tol:e} + ref. estimate {ref_err:e}",
        fast.value
    );
    assert!(
        d <= fast.error + ref_err,
        "{what}: fast {} vs reference {reference}: |diff| {d:e} > estimate {:e} + ref. estimate {ref_err:e}",
        fast.value,
        fast.error
    );
    assert!(
        fast.error <= tol,
        "{what}: estimate {:e} over {tol:e}",
        fast.error
    );
}

/// Every texel of the preset's three tables: the fast path takes all of them (none falls
/// back), each within the preset tolerance and within its estimate of the energy-law
/// integrator at TOL/100 — and uses far fewer evaluations (≤ 300 per texel; the laws
/// integrator spent ~9,000–16,000).
#[test]
fn every_preset_texel_matches_the_laws_integrator() {
    let mut worst = 0.0f64;
    let mut most = 0u64;
    for (c, range) in preset_tables() {
        for i in 0..16 {
            let mu = centre(i, 16, [0.0, 1.0]);
            for j in 0..8 {
                let p = centre(j, 8, range);
                let what = format!("{} mu {mu} p {p}", c.name());
                let fast = match fast_albedo(&c, mu, p, TOL) {
                    Some(Ok(a)) => a,
                    other => panic!("{what}: the fast path did not take the texel: {other:?}"),
                };
                let r = laws(&c, mu, p, TOL / 100.0);
                check(&what, &fast, r.value, r.error, TOL);
                worst = worst.max((fast.value - r.value).abs());
                most = most.max(fast.evals);
            }
        }
    }
    eprintln!("preset texels: largest |fast - laws(1e-9)| = {worst:e}, most evaluations {most}");
    assert!(most <= 300, "most evaluations per texel {most}");
}

/// A dense-ish subset against the independent l-space reference integrator (a different
/// coordinate system and rule from both library integrators), at reference tolerance 1e-10.
#[test]
fn preset_models_match_the_independent_reference() {
    for (c, range) in preset_tables() {
        for &mu in &[1.0 / 32.0, 0.2, 0.55, 31.0 / 32.0] {
            for j in [0, 3, 7] {
                let p = centre(j, 8, range);
                let fast = fast_albedo(&c, mu, p, TOL).unwrap().unwrap();
                let f = c.reflectance(p, 1.0);
                let v = reference::view(mu);
                let r = reference::over_l(mu, 2.0 * f.lobe_width(), 1e-10, |d| {
                    [f.eval(d.l, v) * d.l[2]]
                });
                check(
                    &format!("{} mu {mu} p {p} (l-space reference)", c.name()),
                    &fast,
                    r.value[0],
                    r.error,
                    TOL,
                );
            }
        }
    }
}

/// Closed forms: the modified Phong lobe reflects exactly ks at normal view (Lafortune &
/// Willems 1994), and at a grazing view (μ = 1e-12) with n = 0 (a flat lobe over the
/// half-space about r ≈ −x) it is (1 + μ)/2 ([`low_order_lobe`]), 1/2 within 1e-12; the original Phong
/// lobe at normal view is 2π/(n+1); Blinn-Phong at normal view is the closed form of
/// `brdfbake laws` (README). The fast path's estimate must cover the difference (rounding:
/// 1e-14).
#[test]
fn closed_forms() {
    let mp = ClassicModel::ModifiedPhong { kd: 0.0, ks: 1.0 };
    for n in [0.0, 1.0, 37.5, 1e5] {
        let a = fast_albedo(&mp, 1.0, n, TOL).unwrap().unwrap();
        assert!((a.value - 1.0).abs() <= a.error + 1e-14, "n {n}: {a:?}");
    }
    let a = fast_albedo(&mp, 1e-12, 0.0, TOL).unwrap().unwrap();
    assert!(
        (a.value - 0.5).abs() <= a.error + 1e-12,
        "grazing n = 0: {a:?}"
    );
    let ph = ClassicModel::Phong { ks: 1.0 };
    for n in [0.0, 3.0, 200.0] {
        let a = fast_albedo(&ph, 1.0, n, TOL).unwrap().unwrap();
        let e = 2.0 * std::f64::consts::PI / (n + 1.0);
        assert!((a.value - e).abs() <= a.error + 1e-14, "phong n {n}: {a:?}");
    }
    let bp = ClassicModel::BlinnPhong { ks: 1.0 };
    for s in [0.0, 8.0, 1000.0] {
        let a = fast_albedo(&bp, 1.0, s, TOL).unwrap().unwrap();
        let e = (s + 8.0)
            * (2.0 * (1.0 - 2f64.powf(-(s + 4.0) / 2.0)) / (s + 4.0)
                - (1.0 - 2f64.powf(-(s + 2.0) / 2.0)) / (s + 2.0));
        assert!((a.value - e).abs() <= a.error + 1e-13, "blinn s {s}: {a:?}");
    }
}

/// The exact albedo of a flat lobe (exponent 0) about the mirror direction r, where the
/// laws integrator, whose half-vector coordinates cut across the lobe's edge r·l = 0 (a
/// step), is unreliable (asked for 1e-9 at μ = 0.5 it reports an estimate of 6e-5 after
/// 8·10⁶ evaluations). In the projected disk (x, y) of the hemisphere, ∫ (n·l) dω over a region
/// is its area; the edge r·l = 0 (a great circle tilted by θv) projects to the ellipse of
/// semi-axes μ and 1, and the region r·l > 0 is half the disk plus half that ellipse:
/// π(1 + μ)/2. So modified Phong (2/(2π))·π(1 + μ)/2 = (1 + μ)/2, and the original Phong
/// lobe ∫ dω over the lune between the two half-spaces (dihedral angle π − θv) = 2(π − θv).
/// The original Phong lobe at n = 1 also has a kink at r·l = 0 that the laws integrator's
/// estimate misjudges (μ = 0.5: off by 2.4e-10, estimate 6.7e-11), and a closed form: ∫ l dω
/// over a spherical polygon is −½ Σ (edge arc length)(edge plane's outward normal) (Arvo
/// 1995, "Applications of irradiance tensors", §3), for the lune (two half great circles,
/// inward normals n and r) (π/2)(n + r), so ∫ (r·l) dω = (π/2)(1 + μ).
fn low_order_lobe(c: &ClassicModel, mu: f64, p: f64) -> Option<f64> {
    use std::f64::consts::{FRAC_PI_2, PI};
    match (*c, p) {
        (ClassicModel::ModifiedPhong { kd, ks }, 0.0) => Some(kd + ks * 0.5 * (1.0 + mu)),
        (ClassicModel::Phong { ks }, 0.0) => Some(ks * 2.0 * (PI - mu.acos())),
        (ClassicModel::Phong { ks }, 1.0) => Some(ks * FRAC_PI_2 * (1.0 + mu)),
        // (s+8)/(8π) (n·h)^0 = 1/π everywhere: E = ks
        (ClassicModel::BlinnPhong { ks }, 0.0) => Some(ks),
        _ => None,
    }
}

/// Exponent 0 (the start of the preset's axes), huge exponents (near-delta lobes) and views
/// down to cos θv = 1e-3, for the four models with a fast path and with Lambert weights:
/// the fast path takes every one of these texels at the preset tolerance, and agrees with
/// the laws integrator at TOL/100 (exponents 0 and 1: the closed forms of [`low_order_lobe`],
/// rounding 1e-15) within its estimate and the tolerance.
#[test]
fn extremes_exponent_zero_huge_and_grazing() {
    let models = [
        (ClassicModel::BlinnPhong { ks: 0.9 }, [0.0, 1.0, 1e3, 1e5]),
        (
            ClassicModel::ModifiedPhong { kd: 0.3, ks: 0.7 },
            [0.0, 1.0, 1e3, 1e5],
        ),
        (ClassicModel::Phong { ks: 0.5 }, [0.0, 1.0, 1e3, 1e5]),
        (
            ClassicModel::WardGmd {
                rho_d: 0.2,
                rho_s: 0.8,
            },
            [1e-3, 0.01, 0.3, 1.0],
        ),
    ];
    for (c, ps) in models {
        for mu in [1e-3, 0.02, 0.5, 0.999] {
            for p in ps {
                let what = format!("{} mu {mu} p {p}", c.name());
                let fast = match fast_albedo(&c, mu, p, TOL).unwrap() {
                    Ok(a) => a,
                    Err(spent) => panic!("{what}: refused after {spent} evaluations"),
                };
                match low_order_lobe(&c, mu, p) {
                    Some(e) => check(&what, &fast, e, 1e-15, TOL),
                    None => {
                        let r = laws(&c, mu, p, TOL / 100.0);
                        check(&what, &fast, r.value, r.error, TOL);
                    }
                }
            }
        }
    }
}

fn axis(name: &str, q: Quantity, size: usize, range: [f64; 2], c: Convention) -> Axis {
    Axis {
        name: name.into(),
        quantity: q,
        size,
        range,
        convention: c,
        warp: Default::default(),
        clamp: None,
    }
}

/// A texel the fast path must refuse: Ward's narrowest lobes at a grazing view, asked for
/// 1e-10 (the lobe, α = 0.01 wide, sits where the horizon cut starts, and 129 nodes do not
/// bring the nested estimate that far), so `fast_albedo` says `Err`, and a table with that
/// tolerance gets its value from the laws integrator — the same value, bit for bit, as
/// calling that integrator directly, with the evaluations of the abandoned attempt counted
/// on top.
#[test]
fn refused_texel_falls_back_to_the_laws_integrator() {
    let c = ClassicModel::WardGmd {
        rho_d: 0.0,
        rho_s: 1.0,
    };
    let (mu, alpha, tol) = (1e-3, 0.01, 1e-10);
    let spent = match fast_albedo(&c, mu, alpha, tol).unwrap() {
        Err(spent) => spent,
        Ok(a) => panic!("the fast path should refuse tol {tol:e}: {a:?}"),
    };
    let spec = TableSpec {
        name: "t".into(),
        kind: TableKind::ClassicAlbedo,
        model: ModelSpec {
            ndf: None,
            masking: Masking::None,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: Some(c),
        },
        axes: vec![
            axis(
                "cos_theta_v",
                Quantity::Cosine,
                1,
                [mu, mu],
                Convention::Centers,
            ),
            axis(
                "roughness",
                Quantity::Roughness(c.parameter_quantity()),
                1,
                [alpha, alpha],
                Convention::Centers,
            ),
        ],
        dfg_layout: None,
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: tol,
    };
    let lut = bake(&spec).expect("bakes");
    let direct = laws(&c, mu, alpha, tol);
    assert_eq!(lut.texel([0, 0, 0], 0), direct.value as f32);
    assert_eq!(lut.error_estimate[0], direct.error);
    assert_eq!(lut.evaluations, direct.evals + spent);
}
