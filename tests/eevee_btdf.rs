//! The `eevee-btdf-split-sum-ggx` preset: EEVEE's `btdf_split_sum_ggx[16][64][64]{T, R}`
//! (early EEVEE Next) on EEVEE's own grid — u = η² (column x, η = √(x/63)), v = EEVEE's
//! critical-angle remap of the view cosine (row y: t = 2y/63 − 1, μ = c + t·c below and
//! c + t·(1 − c) above the critical cosine c = √(1 − η²), clamped to [1e-4, 0.9999]), layers
//! α = (z/15)² — checked
//!
//! * for its layout: texel coordinates and the lookup's inverse are EEVEE's formulas;
//! * against closed forms (α = 0: R = F(μ; η), T = 1 − R; η = 1: R = 0, T = G1(μ)) and an
//!   independent integrator (`tests/common/reference.rs`: Walter's BRDF and BTDF in l-space);
//! * against the 38 texels of EEVEE's shipped table quoted in
//!   `tests/data/engines/eevee/btdf_split_sum_ggx.txt` (GPL-2.0-or-later, Copyright Blender
//!   Authors; README there).
//!
//! **EEVEE's refraction.** EEVEE's generator averages, over 512² visible-normal samples,
//! T = (1 − F(v·h)) G1(t) and R = F(v·h) G1(r), with t = GLSL `refract(−V, H, η)`. GLSL's
//! `refract(I, N, r)` takes the ratio r = n_incident/n_transmitted; the view here is inside
//! the denser medium (η = n_outside/n_inside < 1), so the consistent ratio is 1/η (the
//! later generator passes `1.0 / ior`). With η the refracted ray bends towards −h instead
//! of away from it, which changes G1(t) (not F, and not R). brdfbake's table is the physical
//! one; the two agree where G1(t) does not matter (α = 0, where G1 = 1; η = 1, where t = −v
//! either way; total internal reflection, where 1 − F = 0) and differ by up to 0.09
//! elsewhere. The test integrates EEVEE's as-written estimator independently (h-space
//! quadrature, [`as_written`]) and requires: the shipped values match it within EEVEE's own
//! error; ours match the physical reference; and where as-written and physical differ by
//! more than twice EEVEE's error, the shipped value misses ours.

#[path = "common/docs.rs"]
mod docs;
#[path = "common/eevee.rs"]
mod eevee;
#[path = "common/reference.rs"]
mod reference;
use eevee::{refract, EEVEE_ERROR};

use brdfbake::lut::Lut;
use brdfbake::model::{Masking, NdfKind};
use brdfbake::preset::PresetTable;
use reference::{dot, fresnel_dielectric, view, RefModel};
use std::sync::OnceLock;

const PRESET: &str = "eevee-btdf-split-sum-ggx";

fn table(edit: impl Fn(String) -> String) -> PresetTable {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == PRESET)
        .expect("the preset is built in");
    brdfbake::preset::parse(&edit(text.to_string()), PRESET, PRESET)
        .unwrap()
        .tables
        .remove(0)
}

/// The preset's table as stored ([x = η² column][y = row][z = layer], channels T, R), baked
/// once for all tests.
fn baked() -> &'static Lut {
    static LUT: OnceLock<Lut> = OnceLock::new();
    LUT.get_or_init(|| {
        let t = table(|s| s);
        let clock = std::time::Instant::now();
        let lut = brdfbake::table::bake(&t.spec).unwrap();
        eprintln!("baked in {:.1} s", clock.elapsed().as_secs_f64());
        // the bake meets its requested tolerance (its estimates are the bounds below)
        assert!(lut.error_estimate.iter().all(|&e| e <= t.spec.tolerance));
        t.stored(lut)
    })
}

/// EEVEE's texel (x, y, z): (η, μ, α) as its generator computes them, η clamped at 1e-4 as
/// the preset does (EEVEE's column 0 is η = 0, where F = 1 at every v·h < 1: the same
/// values); also the unclamped μ.
fn eevee_texel(x: usize, y: usize, z: usize) -> (f64, f64, f64, f64) {
    let eta = (x as f64 / 63.0).sqrt().max(1e-4);
    let c = (1.0 - eta * eta).sqrt();
    let t = 2.0 * (y as f64 / 63.0) - 1.0;
    let nominal = c + t * if t > 0.0 { 1.0 - c } else { c };
    let alpha = (z as f64 / 15.0).powi(2);
    (eta, nominal.clamp(1e-4, 0.9999), alpha, nominal)
}

/// The quoted texels: (z, y, x, T, R).
fn shipped() -> Vec<(usize, usize, usize, f64, f64)> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/engines/eevee/btdf_split_sum_ggx.txt"
    );
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (
                w[0].parse().unwrap(),
                w[1].parse().unwrap(),
                w[2].parse().unwrap(),
                w[3].parse().unwrap(),
                w[4].parse().unwrap(),
            )
        })
        .collect()
}

/// [T, R] of EEVEE's estimator in expectation, by h-space quadrature (independent of
/// brdfbake and of the l-space reference): over visible micro-normals h with density
/// D(h) G1(v) (v·h)/μ, T = (1 − F(v·h; η)) G1(|n·t|) with t = refract(−v, h, `ratio`)
/// below the surface, R = F G1(n·r) with r the mirror of v about h above it. `ratio` = η
/// is EEVEE's as-written refraction, 1/η the physical one.
fn h_space(alpha: f64, eta: f64, mu: f64, ratio: f64, tol: f64) -> reference::Est<2> {
    let m = RefModel::new(NdfKind::Ggx, alpha, Masking::SmithSeparable);
    let v = view(mu);
    let g1v = m.g1(mu);
    reference::over_h_front(mu, alpha, tol, |h| {
        let c = dot(v, h);
        if c <= 0.0 {
            return [0.0, 0.0];
        }
        let w = m.d_vec(h) * g1v * c / mu;
        let f = fresnel_dielectric(c, eta);
        let nr = 2.0 * c * h[2] - mu;
        let r = if nr > 0.0 {
            w * f * m.g1(nr.min(1.0))
        } else {
            0.0
        };
        let t = match refract([-v[0], -v[1], -v[2]], h, ratio) {
            Some(t) if t[2] < 0.0 => w * (1.0 - f) * m.g1((-t[2]).min(1.0)),
            _ => 0.0,
        };
        [t, r]
    })
}

/// EEVEE's estimator as written (see the module doc).
fn as_written(alpha: f64, eta: f64, mu: f64, tol: f64) -> reference::Est<2> {
    h_space(alpha, eta, mu, eta, tol)
}

/// f32 rounding of a stored value ≤ 1 (half an ulp below 1: 2⁻²⁴ ≈ 6e-8).
const F32: f64 = 6e-8;

/// The texel coordinates are EEVEE's (the critical-angle remap in every column, η² along u),
/// and a lookup inverts them as EEVEE's `lut_coords_btdf` does: u = η², v = (μ − c)/(μ > c ?
/// 1 − c : c)/2 + 1/2, each remapped by 63/64 and 0.5/64 (its UTIL_TEX_UV_SCALE/BIAS). Both
/// computed in f64 by the same operations: equal within a few ulp (1e-14). Column 0 is left
/// out of the inverse: there the preset clamps η to 1e-4 (c = 1 − 5e-9, EEVEE's c = 1), so
/// above the critical cosine (1 − c)·t is 5e-9·t: v of a given μ differs, while the value
/// (clamped to μ = 0.9999) does not; and so is μ = 0 at η = 1, where EEVEE's formula is 0/0. A lookup at a texel's coordinates returns the texel
/// (within f64 interpolation weights, 1e-9). Negative control: the same preset with a linear
/// view axis puts its texels elsewhere (by more than 0.1 in μ).
#[test]
fn texels_sit_where_eevee_puts_them_and_lookups_invert_the_remap() {
    let t = table(|s| s);
    let axes = t.stored_axes();
    assert_eq!(
        axes.iter().map(|a| a.name.as_str()).collect::<Vec<_>>(),
        ["fresnel", "cos_theta_v", "roughness"]
    );
    let shell = Lut {
        axes: axes.clone(),
        channels: Vec::new(),
        data: Vec::new(),
        error_estimate: Vec::new(),
        evaluations: 0,
    };
    for z in [0, 1, 8, 15] {
        for y in 0..64 {
            for x in 0..64 {
                let (eta, mu, alpha, nominal) = eevee_texel(x, y, z);
                let got = brdfbake::lut::texel_coordinates(&axes, &[x, y, z]);
                let r = (z as f64) / 15.0;
                assert!(
                    (got[0] - eta).abs() <= 1e-14
                        && (got[1] - mu).abs() <= 1e-14
                        && (got[2] - r).abs() <= 1e-14,
                    "texel ({x}, {y}, {z}): {got:?} vs EEVEE's eta {eta}, mu {mu}, alpha {alpha}"
                );
                if x == 0 {
                    continue;
                }
                let c = (1.0 - eta * eta).sqrt();
                let d = nominal - c;
                if c == 0.0 && d <= 0.0 {
                    // η = 1, μ = 0: EEVEE's lookup divides 0 by c = 0 there (ours reads
                    // p = 0; every texel of the lower half of that column holds μ = 0)
                    continue;
                }
                let v = d / if d > 0.0 { 1.0 - c } else { c } * 0.5 + 0.5;
                let remap = |s: f64| s * 63.0 / 64.0 + 0.5 / 64.0;
                let want = [remap(eta * eta), remap(v), (z as f64 + 0.5) / 16.0];
                let s = brdfbake::encode::shader::texture_coordinates(&shell, &[eta, nominal, r]);
                for k in 0..3 {
                    assert!(
                        (s[k] - want[k]).abs() <= 1e-12,
                        "texel ({x}, {y}, {z}) axis {k}: texture coordinate {} vs EEVEE's {}",
                        s[k],
                        want[k]
                    );
                }
            }
        }
    }
    let lut = baked();
    for &(x, y, z) in &[
        (1, 0, 1),
        (16, 31, 8),
        (32, 32, 8),
        (48, 40, 15),
        (62, 63, 3),
    ] {
        let (eta, _, _, nominal) = eevee_texel(x, y, z);
        let back = lut.lookup(&[eta, nominal, z as f64 / 15.0]);
        for (ch, b) in back.iter().enumerate() {
            let held = lut.texel([x, y, z], ch) as f64;
            assert!(
                (b - held).abs() <= 1e-9,
                "lookup at texel ({x}, {y}, {z})'s coordinates: {b}, the texel holds {held}"
            );
        }
    }
    // the negative control
    let linear = table(|s| s.replace("\"warp\": \"critical-angle\", ", ""));
    let la = linear.stored_axes();
    let worst = (0..64)
        .map(|y| {
            let got = brdfbake::lut::texel_coordinates(&la, &[32, y, 8]);
            (got[1] - eevee_texel(32, y, 8).1).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst > 0.1, "a linear view axis should not fit: {worst}");
}

/// Closed forms at the limits, at every texel they cover:
/// * α = 0 (layer 0): R = F(μ; η) (exact dielectric Fresnel, total internal reflection
///   included), T = 1 − R (`table::smooth`; here checked with the reference's own Fresnel);
///   equal within f32 rounding (6e-8) plus the two Fresnel codes' f64 rounding (1e-12);
/// * η = 1 (column 63), α > 0: F = 0 and the refracted direction is −v, so R = 0 and
///   T = G1(μ)·∫ D G1(v) (v·h)/μ dω_h = G1(μ) (the visible normals' normalization); within
///   the bake's estimate for T (≤ 1e-6) plus f32 rounding.
///
/// And at interior texels (0 < η < 1, α > 0, grazing to steep views, below and above the
/// critical angle, including EEVEE's quoted ones) against the l-space reference
/// (`reference::dielectric_rt`: Walter's BRDF and BTDF with their own Jacobians and half
/// vectors), bound = the bake's estimate per channel + the reference's estimate (requested
/// 1e-7) + f32 rounding. Negative control: the reference at the coordinates of a linear view
/// axis misses the table by far more than the bound.
#[test]
fn table_meets_closed_forms_and_the_independent_integrator() {
    let lut = baked();
    let g1 =
        |alpha: f64, mu: f64| RefModel::new(NdfKind::Ggx, alpha, Masking::SmithSeparable).g1(mu);
    for y in 0..64 {
        for x in 0..64 {
            let (eta, mu, _, _) = eevee_texel(x, y, 0);
            let f = fresnel_dielectric(mu, eta);
            let (tt, rr) = (
                lut.texel([x, y, 0], 0) as f64,
                lut.texel([x, y, 0], 1) as f64,
            );
            assert!(
                (rr - f).abs() <= F32 + 1e-12 && (tt - (1.0 - f)).abs() <= F32 + 1e-12,
                "alpha = 0, texel ({x}, {y}): (T, R) = ({tt}, {rr}), closed form ({}, {f})",
                1.0 - f
            );
        }
    }
    for z in 1..16 {
        for y in 0..64 {
            let (_, mu, alpha, _) = eevee_texel(63, y, z);
            let (tt, rr) = (
                lut.texel([63, y, z], 0) as f64,
                lut.texel([63, y, z], 1) as f64,
            );
            let want = g1(alpha, mu);
            assert!(
                rr.abs() <= F32 && (tt - want).abs() <= lut.error_estimate[0] + F32,
                "eta = 1, texel (63, {y}, {z}): (T, R) = ({tt}, {rr}), closed form ({want}, 0)"
            );
        }
    }
    let texels = [
        (1, 0, 62),
        (1, 3, 32),
        (4, 20, 10),
        (8, 32, 1),
        (8, 32, 16),
        (8, 32, 32),
        (8, 32, 48),
        (8, 32, 62),
        (8, 50, 40),
        (12, 10, 55),
        (15, 32, 32),
        (15, 63, 20),
    ];
    let mut control: f64 = 0.0;
    for &(z, y, x) in &texels {
        let (eta, mu, alpha, _) = eevee_texel(x, y, z);
        let r = reference::dielectric_rt(alpha, eta, mu, 1e-7);
        let want = [r.value[1], r.value[0]];
        for (ch, want) in want.iter().enumerate() {
            let got = lut.texel([x, y, z], ch) as f64;
            let bound = lut.error_estimate[ch] + r.error + F32;
            assert!(
                (got - want).abs() <= bound,
                "texel ({x}, {y}, {z}) eta {eta} mu {mu} alpha {alpha} channel {ch}: {got} vs reference {want} (bound {bound:e})"
            );
        }
        // the negative control: mu as a linear axis would put it
        let mu_lin = (y as f64 / 63.0).clamp(1e-4, 0.9999);
        let w = reference::dielectric_rt(alpha, eta, mu_lin, 1e-6);
        control = control.max((lut.texel([x, y, z], 0) as f64 - w.value[1]).abs());
    }
    assert!(
        control > 0.05,
        "the reference at a linear axis' view cosines should miss: {control}"
    );
}

/// Against EEVEE's quoted texels. For each: the shipped (T, R) is within B of EEVEE's
/// estimator as written in expectation (h-space quadrature, requested 1e-6, so the check is
/// on our reading of EEVEE's generator: it fails with the physical refraction at the
/// texels below); ours is within our estimate + the l-space reference's + f32 of the
/// physical value. Where the as-written and physical values agree within the quadratures'
/// estimates (R everywhere; T at α = 0, η = 1, η ≈ 0, and below the critical angle of a
/// smooth lobe), ours is within B of the shipped value. Where they differ by more than 2B,
/// the shipped value misses ours by more than B — EEVEE's refraction defect, found at 5 of
/// the quoted texels (at least 4 asserted; the largest: T at z = 8, y = 32, x = 62, EEVEE
/// 0.606 vs 0.518). Excluded and asserted on its own: (z, y, x) = (0, 31, 63), α = 0,
/// η = 1, μ = 1e-4, where every sample transmits (T = 1 exactly, ours) but EEVEE's table
/// holds 0.050858 (a float32 artefact of its generator at η = 1, μ → 0).
#[test]
fn eevee_shipped_values_agree_where_its_refraction_is_physical() {
    let lut = baked();
    let mut differ = 0;
    let mut agree = 0;
    let mut worst_defect: (f64, (usize, usize, usize)) = (0.0, (0, 0, 0));
    for (z, y, x, st, sr) in shipped() {
        let ours = [
            lut.texel([x, y, z], 0) as f64,
            lut.texel([x, y, z], 1) as f64,
        ];
        let ship = [st, sr];
        let (eta, mu, alpha, _) = eevee_texel(x, y, z);
        if (z, y, x) == (0, 31, 63) {
            assert!((ours[0] - 1.0).abs() <= F32 && ours[1].abs() <= F32);
            assert!((st - 1.0).abs() > 0.9, "the known corner: {st}");
            continue;
        }
        let (aw, phys, bound_ours): ([f64; 2], [f64; 2], [f64; 2]) = if alpha == 0.0 {
            // the smooth limit: t is irrelevant (G1 = 1), both are F, 1 − F
            let f = fresnel_dielectric(mu, eta);
            ([1.0 - f, f], [1.0 - f, f], [F32 + 1e-12; 2])
        } else if x == 63 {
            // η = 1: F = 0 and t = −v for either ratio, T = G1(μ), R = 0 (see above)
            let g = RefModel::new(NdfKind::Ggx, alpha, Masking::SmithSeparable).g1(mu);
            ([g, 0.0], [g, 0.0], [lut.error_estimate[0] + F32, F32])
        } else {
            let a = as_written(alpha, eta, mu, 1e-6);
            let p = reference::dielectric_rt(alpha, eta, mu, 1e-7);
            (
                a.value,
                [p.value[1], p.value[0]],
                [
                    lut.error_estimate[0] + p.error + F32,
                    lut.error_estimate[1] + p.error + F32,
                ],
            )
        };
        for ch in 0..2 {
            let name = ["T", "R"][ch];
            assert!(
                (ship[ch] - aw[ch]).abs() <= EEVEE_ERROR,
                "({z}, {y}, {x}) {name}: EEVEE {} is not its estimator as written {} (bound {EEVEE_ERROR:e})",
                ship[ch],
                aw[ch]
            );
            assert!(
                (ours[ch] - phys[ch]).abs() <= bound_ours[ch],
                "({z}, {y}, {x}) {name}: ours {} vs physical reference {} (bound {:e})",
                ours[ch],
                phys[ch],
                bound_ours[ch]
            );
            let gap = (aw[ch] - phys[ch]).abs();
            if gap <= 1e-6 {
                agree += 1;
                assert!(
                    (ours[ch] - ship[ch]).abs() <= EEVEE_ERROR,
                    "({z}, {y}, {x}) {name}: ours {} vs EEVEE {} (bound {EEVEE_ERROR:e})",
                    ours[ch],
                    ship[ch]
                );
            } else if gap > 2.0 * EEVEE_ERROR {
                differ += 1;
                let miss = (ours[ch] - ship[ch]).abs();
                assert!(
                    miss > EEVEE_ERROR,
                    "({z}, {y}, {x}) {name}: EEVEE's {} should miss the physical {} (as written {})",
                    ship[ch],
                    ours[ch],
                    aw[ch]
                );
                if miss > worst_defect.0 {
                    worst_defect = (miss, (z, y, x));
                }
            }
        }
    }
    eprintln!(
        "EEVEE btdf_split_sum_ggx: {agree} channel values agree, {differ} differ by EEVEE's refraction; worst {:.4} at (z, y, x) = {:?}",
        worst_defect.0, worst_defect.1
    );
    assert!(agree >= 40, "agreeing channel values: {agree}");
    assert!(differ >= 4, "EEVEE's refraction defect at {differ} texels");
    // the negative control of the as-written integrator: with the physical ratio it does
    // not reproduce EEVEE's values where the defect shows
    let (eta, mu, alpha, _) = eevee_texel(62, 32, 8);
    let p = h_space(alpha, eta, mu, 1.0 / eta, 1e-6);
    assert!(
        (p.value[0] - 0.606337).abs() > EEVEE_ERROR,
        "the physical refraction should not reproduce EEVEE: {}",
        p.value[0]
    );
    // and the h-space integrator's physical T is the l-space reference's
    let l = reference::dielectric_rt(alpha, eta, mu, 1e-7);
    assert!(
        (p.value[0] - l.value[1]).abs() <= p.error + l.error,
        "h-space {} vs l-space {}",
        p.value[0],
        l.value[1]
    );
}

/// Gauss–Legendre nodes and weights on [0, 1] (Newton on P_n from the Chebyshev guesses).
fn gauss_legendre01(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-15 {
                    break;
                }
            }
            ((1.0 - x) / 2.0, 1.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// [T as written (ratio η), T physical (ratio 1/η)] of EEVEE's estimator in expectation, by a
/// fixed tensor rule over the visible-normal sampling square (Heitz 2018's map, whose
/// density is the VNDF D G1(v) (v·h)/μ): Gauss–Legendre in √u₁ (`nr` nodes), the midpoint
/// rule in the azimuth u₂ (`nphi`, periodic). Cheap enough for every texel of the table;
/// its error is measured against the physical table below.
fn vndf_rule(alpha: f64, eta: f64, mu: f64, rule: &[(f64, f64)], nphi: usize) -> [f64; 2] {
    let m = RefModel::new(NdfKind::Ggx, alpha, Masking::SmithSeparable);
    let v = view(mu);
    let vh = {
        let w = [alpha * v[0], alpha * v[1], v[2]];
        let l = dot(w, w).sqrt();
        [w[0] / l, w[1] / l, w[2] / l]
    };
    let lensq = vh[0] * vh[0] + vh[1] * vh[1];
    let t1v = if lensq > 0.0 {
        [-vh[1] / lensq.sqrt(), vh[0] / lensq.sqrt(), 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let t2v = [
        vh[1] * t1v[2] - vh[2] * t1v[1],
        vh[2] * t1v[0] - vh[0] * t1v[2],
        vh[0] * t1v[1] - vh[1] * t1v[0],
    ];
    let s = 0.5 * (1.0 + vh[2]);
    let mut out = [0.0; 2];
    for &(r, wr) in rule {
        for j in 0..nphi {
            let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / nphi as f64;
            let (t1, t2) = (r * phi.cos(), r * phi.sin());
            let t2 = (1.0 - s) * (1.0 - t1 * t1).max(0.0).sqrt() + s * t2;
            let t3 = (1.0 - t1 * t1 - t2 * t2).max(0.0).sqrt();
            let nh = [
                t1 * t1v[0] + t2 * t2v[0] + t3 * vh[0],
                t1 * t1v[1] + t2 * t2v[1] + t3 * vh[1],
                t1 * t1v[2] + t2 * t2v[2] + t3 * vh[2],
            ];
            let ne = [alpha * nh[0], alpha * nh[1], nh[2].max(0.0)];
            let l = dot(ne, ne).sqrt();
            if l == 0.0 {
                continue;
            }
            let h = [ne[0] / l, ne[1] / l, ne[2] / l];
            let c = dot(v, h);
            if c <= 0.0 {
                continue;
            }
            // (u₁ = r²: du₁ = 2r dr)
            let w = wr * 2.0 * r / nphi as f64 * (1.0 - fresnel_dielectric(c, eta));
            for (k, ratio) in [eta, 1.0 / eta].into_iter().enumerate() {
                if let Some(t) = refract([-v[0], -v[1], -v[2]], h, ratio) {
                    if t[2] < 0.0 {
                        out[k] += w * m.g1((-t[2]).min(1.0));
                    }
                }
            }
        }
    }
    out
}

/// **The whole table, as far as it can be known.** EEVEE's file is GPL: only 41 texels are
/// quoted here. Its estimator in expectation (T as written) is computed at every texel of
/// the 61,440 with α > 0 and η < 1 by [`vndf_rule`], whose error is measured by the same rule
/// with the physical ratio against brdfbake's table at every texel (`rule_error`), and which
/// reproduces every quoted T within EEVEE's own error plus that. The largest excess of T
/// as written over the physical value lies at (z, y, x) = (5, 8, 62), α = 0.11, η = 0.992,
/// μ = 0.032, where EEVEE ships 0.383 (a quoted value): the figure docs/engines.md and the
/// README's engine table give for the shipped table is this one, and the test fails when
/// they say otherwise.
#[test]
fn eevee_refraction_defect_over_the_whole_table() {
    use rayon::prelude::*;
    let lut = baked();
    let rule = gauss_legendre01(64);
    let nphi = 128;
    let texels: Vec<(usize, usize, usize)> = (1..16)
        .flat_map(|z| (0..64).flat_map(move |y| (0..63).map(move |x| (z, y, x))))
        .collect();
    let rows: Vec<((usize, usize, usize), f64, f64)> = texels
        .par_iter()
        .map(|&(z, y, x)| {
            let (eta, mu, alpha, _) = eevee_texel(x, y, z);
            let [aw, ph] = vndf_rule(alpha, eta, mu, &rule, nphi);
            let ours = lut.texel([x, y, z], 0) as f64;
            ((z, y, x), aw - ours, (ph - ours).abs())
        })
        .collect();
    let rule_error = rows.iter().fold(0.0f64, |m, r| m.max(r.2));
    let mut ranked: Vec<&((usize, usize, usize), f64, f64)> = rows.iter().collect();
    ranked.sort_by(|a, b| b.1.total_cmp(&a.1));
    let worst = ranked[0];
    eprintln!(
        "EEVEE btdf_split_sum_ggx T as written - physical: max {:.4} at (z, y, x) = {:?}; the rule's largest error {rule_error:.2e}",
        worst.1, worst.0
    );
    // the rule is good enough to rank the texels: its error is far below the defect, and
    // the worst texel leads the next by more than twice it
    assert!(rule_error < 1e-2, "the VNDF rule's error {rule_error}");
    // the quoted values are EEVEE's estimator as the rule computes it
    for (z, y, x, st, _) in shipped() {
        if z == 0 || x == 63 {
            continue;
        }
        let (eta, mu, alpha, _) = eevee_texel(x, y, z);
        let [aw, _] = vndf_rule(alpha, eta, mu, &rule, nphi);
        assert!(
            (st - aw).abs() <= EEVEE_ERROR + rule_error,
            "({z}, {y}, {x}): EEVEE {st} vs its estimator {aw}"
        );
    }
    // the worst texel, quoted: its shipped value less brdfbake's
    assert_eq!(worst.0, (5, 8, 62), "the worst texel moved: {worst:?}");
    // (the runner-up is a neighbour: the rule's own error at both, measured by the physical
    // ratio, is far below the gap between them, so the ranking holds)
    assert!(
        worst.1 - ranked[1].1 > 2.0 * (worst.2 + ranked[1].2),
        "the worst texel {worst:?} does not lead {:?} by more than the rule's error there",
        ranked[1]
    );
    let (_, _, _, st, _) = shipped()
        .into_iter()
        .find(|q| (q.0, q.1, q.2) == (5, 8, 62))
        .expect("the worst texel is quoted");
    let excess = st - lut.texel([62, 8, 5], 0) as f64;
    assert!((excess - worst.1).abs() <= EEVEE_ERROR + rule_error);
    let figure = brdfbake::numfmt::fig(excess);
    docs::assert_says(
        "docs/engines.md",
        &format!("its T is up to {figure} above the physical value"),
    );
}
