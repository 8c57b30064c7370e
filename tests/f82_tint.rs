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
