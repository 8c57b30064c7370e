//! The `karis-f82` dfg layout (Karis' A, B and the F82-tint channel
//! `F82 = ∫ (v·h)(1 − v·h)⁶ f cos dω_l`, f with F = 1; src/table/dfg.rs integrates it over
//! micro-normals, [`brdfbake::kernels::micro_normals`]) against the independent l-space
//! reference (`tests/common/reference.rs`: adaptive Gauss–Legendre over l, its own
//! half-vector and Jacobian), for both Smith forms, at grazing, middle and steep views and
//! narrow to wide lobes.
//!
//! Tolerance: the table's own estimate (its channel's max over texels; the bake asserts it
//! meets the requested 1e-6), plus the reference's estimate (requested 1e-8), plus the f32
//! rounding of a value ≤ 1 (2⁻²⁴ ≈ 6e-8).

#[path = "common/reference.rs"]
mod reference;

use brdfbake::model::{Masking, NdfKind};

#[test]
fn f82_channel_matches_reference() {
    for (masking, m) in [
        ("smith-height-correlated", Masking::SmithHeightCorrelated),
        ("smith-separable", Masking::SmithSeparable),
    ] {
        let text = format!(
            r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "t", "kind": "dfg",
                "layout": "karis-f82", "model": {{"ndf": "ggx", "masking": "{masking}"}},
                "tolerance": 1e-6,
                "axes": {{"cos_theta_v": {{"size": 3, "range": [0.05, 0.95], "convention": "endpoints"}},
                          "roughness": {{"size": 3, "quantity": "perceptual", "range": [0.2, 0.9], "convention": "endpoints"}}}}}}]}}"#
        );
        let p = brdfbake::preset::parse(&text, "t.json", "t").expect("preset");
        let lut = brdfbake::table::bake(&p.tables[0].spec).expect("bake");
        assert_eq!(lut.channels.len(), 3);
        assert_eq!(lut.channels[2].name, "F82");
        assert!(
            lut.error_estimate.iter().all(|&e| e <= 1e-6),
            "{:?}",
            lut.error_estimate
        );
        let mut largest: f64 = 0.0;
        let mut worst = [0.0f64; 3];
        for i in 0..3 {
            for j in 0..3 {
                let mu = 0.05 + 0.45 * i as f64;
                let r = 0.2 + 0.35 * j as f64;
                let rm = reference::RefModel::new(NdfKind::Ggx, r * r, m);
                let f82 = reference::over_l_kinked(
                    mu,
                    reference::lobe_scale(&rm),
                    1e-8,
                    |d| {
                        [rm.f_cos(mu, d).map_or(0.0, |(f, vh)| {
                            let x = (1.0 - vh).clamp(0.0, 1.0);
                            f * vh * x.powi(6)
                        })]
                    },
                    |ct, st| rm.phi_kink(mu, ct, st),
                );
                let ab = reference::split_sum(&rm, mu, 1e-8);
                let want = [ab.value[0], ab.value[1], f82.value[0]];
                let ref_err = [ab.error, ab.error, f82.error];
                for c in 0..3 {
                    let got = lut.texel([i, j, 0], c) as f64;
                    let bound = lut.error_estimate[c] + ref_err[c] + 6e-8;
                    worst[c] = worst[c].max((got - want[c]).abs());
                    assert!(
                        (got - want[c]).abs() <= bound,
                        "{masking} mu {mu} r {r} channel {}: {got} vs reference {} (bound {bound:e})",
                        lut.channels[c].name,
                        want[c]
                    );
                }
                largest = largest.max(want[2]);
            }
        }
        eprintln!(
            "{masking}: max |table - reference| A {:.2e}, B {:.2e}, F82 {:.2e}; largest estimate {:.2e}",
            worst[0],
            worst[1],
            worst[2],
            lut.error_estimate.iter().cloned().fold(0.0, f64::max)
        );
        // the channel is not trivially small where it is compared
        assert!(largest > 1e-3, "{masking}: F82 at most {largest}");
    }
}

/// A built-in engine preset's one table as stored (its axis order and channels).
fn engine_lut(name: &str, edit: impl Fn(String) -> String) -> brdfbake::lut::Lut {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no engine preset {name}"));
    let t = brdfbake::preset::parse(&edit(text.to_string()), name, name)
        .unwrap()
        .tables
        .remove(0);
    t.stored(brdfbake::table::bake(&t.spec).unwrap())
}

/// The `eevee-brdf-ggx` preset, EEVEE's `brdf_ggx[64][64][3]` {scale, bias, metal_bias} on
/// EEVEE's grid (column x: r = x/63, α = r²; row y: μ = clamp(1 − (y/63)², 1e-4, 0.9999)).
/// EEVEE's data file for this table was not located (no shipped values are compared), so
/// the preset is checked against what must hold:
///
/// * its scale and bias are the same integrals as `bsdf_split_sum_ggx` on the same grid
///   (tests/engines.rs compares that one with EEVEE's quoted values): equal within both
///   tables' estimates (≤ 1e-6 each) plus two f32 roundings (2·6e-8);
/// * its α = 0 column is the smooth limit in closed form (every micro-normal is n, v·h = μ,
///   f cos a unit mass at the mirror direction): scale = 1 − (1 − μ)⁵, bias = (1 − μ)⁵,
///   metal_bias = μ(1 − μ)⁶, within f32 rounding (6e-8);
/// * its metal_bias at interior texels (grazing, middle and steep rows; narrow to wide
///   lobes) against the l-space reference, bound as in the test above.
///
/// Negative control: the same preset with cos θ linear along v (no `sqrt-one-minus` warp)
/// misses the reference at the same texels by far more than the bound.
#[test]
fn eevee_brdf_ggx_preset_is_the_split_sum_plus_f82_on_eevees_grid() {
    let lut = engine_lut("eevee-brdf-ggx", |s| s);
    let split = engine_lut("eevee-bsdf-split-sum-ggx", |s| s);
    assert_eq!(lut.channels.len(), 3);
    assert_eq!((lut.dim(0), lut.dim(1)), (64, 64));
    let est = |l: &brdfbake::lut::Lut, c: usize| l.error_estimate[c];
    for y in 0..64 {
        for x in 0..64 {
            for c in 0..2 {
                let (a, b) = (
                    lut.texel([x, y, 0], c) as f64,
                    split.texel([x, y, 0], c) as f64,
                );
                let bound = est(&lut, c) + est(&split, c) + 1.2e-7;
                assert!(
                    (a - b).abs() <= bound,
                    "x {x} y {y} channel {c}: brdf_ggx {a} vs bsdf_split_sum_ggx {b}"
                );
            }
        }
    }
    let mu_of = |y: usize| (1.0 - (y as f64 / 63.0).powi(2)).clamp(1e-4, 0.9999);
    for y in 0..64 {
        let mu = mu_of(y);
        let fc = (1.0 - mu).powi(5);
        let want = [1.0 - fc, fc, mu * (1.0 - mu).powi(6)];
        for (c, w) in want.iter().enumerate() {
            let got = lut.texel([0, y, 0], c) as f64;
            assert!(
                (got - w).abs() <= 6e-8,
                "alpha = 0, y {y}, channel {c}: {got} vs closed form {w}"
            );
        }
    }
    let texels = [(8, 62), (16, 40), (32, 10), (48, 55), (63, 32), (4, 63)];
    let f82_ref = |x: usize, y: usize| {
        let (mu, r) = (mu_of(y), x as f64 / 63.0);
        let rm = reference::RefModel::new(NdfKind::Ggx, r * r, Masking::SmithSeparable);
        reference::over_l_kinked(
            mu,
            reference::lobe_scale(&rm),
            1e-8,
            |d| {
                [rm.f_cos(mu, d).map_or(0.0, |(f, vh)| {
                    let x = (1.0 - vh).clamp(0.0, 1.0);
                    f * vh * x.powi(6)
                })]
            },
            |ct, st| rm.phi_kink(mu, ct, st),
        )
    };
    let linear = engine_lut("eevee-brdf-ggx", |s| {
        s.replace("\"warp\": \"sqrt-one-minus\", ", "")
    });
    let mut control: f64 = 0.0;
    for &(x, y) in &texels {
        let r = f82_ref(x, y);
        let got = lut.texel([x, y, 0], 2) as f64;
        let bound = est(&lut, 2) + r.error + 6e-8;
        assert!(
            (got - r.value[0]).abs() <= bound,
            "x {x} y {y}: metal_bias {got} vs reference {} (bound {bound:e})",
            r.value[0]
        );
        control = control.max((linear.texel([x, y, 0], 2) as f64 - r.value[0]).abs());
    }
    assert!(
        control > 100.0 * 1e-6,
        "a linear cos theta axis should miss the reference: {control:e}"
    );
}
