//! The `eevee-bsdf-ggx` and `eevee-btdf-ggx` presets: EEVEE's `bsdf_ggx[16][64][64]{scale,
//! bias, transmission_factor}` (relative index η < 1, the view inside the denser medium) and
//! `btdf_ggx[16][64][64]{transmission_factor}` (η > 1), the Schlick split sum of a rough
//! dielectric interface (`dielectric-schlick`: R = F0·A + F90·B, transmittance (1 − F0)·T,
//! Schlick's weight on the less dense side; `src/model/schlick_dielectric.rs`), checked
//!
//! * for their layout: texel coordinates are EEVEE's (`bsdf_ggx`: u = η², EEVEE's
//!   critical-angle view axis; `btdf_ggx`: u = √((η − 1)/(η + 1)), v = √(1 − cos θ); layers
//!   α = (z/15)²);
//! * against the smooth limit in closed form and an independent integrator (h-space
//!   quadrature of `tests/common/reference.rs`, [`expected`]);
//! * against the texels of EEVEE's shipped tables quoted in
//!   `tests/data/engines/eevee/bsdf_ggx.txt` and `btdf_ggx.txt` (GPL-2.0-or-later,
//!   Copyright Blender Authors; headers there), within EEVEE's own error.
//!
//! **EEVEE's generator.** Its `ggx_bsdf_split_sum` (the version that samples with
//! `bxdf_ggx_sample_reflection`/`_refraction`) averages, over 512² visible-normal samples,
//! scale += (1 − s) G1(r), bias += s G1(r), transmission_factor += (1 − s) G1(t) with
//! t = refract(−V, H, 1/η) and s = (1 − |H·L|)⁵, L the refracted direction (s = 1 under total
//! internal reflection); `ggx_btdf_gt_one` averages (1 − s) G1(t) with s = (1 − V·H)⁵. Both
//! are the integrals of `dielectric-schlick` (the ratio 1/η is the physical one here, unlike
//! `btdf_split_sum_ggx`'s `refract(−V, H, η)`: tests/eevee_btdf.rs). An earlier generator
//! took s from HL = 1 − (1 − (V·H)²)/η², the *squared* transmitted cosine; the shipped
//! `bsdf_ggx` is not that one ([`Weight::CosSquaredT`], a negative control below). EEVEE
//! clamps btdf_ggx's (η − 1)/(η + 1) to 0.9999 (η = 19999) in column 63; brdfbake's fresnel
//! axes end at η = 100, so the preset clamps it to 0.9801 (η = 99.5) and that column differs
//! by what [`expected`] computes between the two indices (≤ 4e-3 at the quoted texels).

#[path = "common/eevee.rs"]
mod eevee;
#[path = "common/reference.rs"]
mod reference;
use eevee::{refract, EEVEE_ERROR};

use brdfbake::lut::Lut;
use brdfbake::model::{Masking, NdfKind};
use brdfbake::preset::PresetTable;
use reference::{dot, view, RefModel};
use std::sync::OnceLock;

const BSDF: &str = "eevee-bsdf-ggx";
const BTDF: &str = "eevee-btdf-ggx";

fn table(preset: &str, edit: impl Fn(String) -> String) -> PresetTable {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == preset)
        .expect("the preset is built in");
    brdfbake::preset::parse(&edit(text.to_string()), preset, preset)
        .unwrap()
        .tables
        .remove(0)
}

/// A preset's table as stored ([x column][y row][z layer], its stored channels), baked once.
fn baked(preset: &'static str) -> &'static Lut {
    static BSDF_LUT: OnceLock<Lut> = OnceLock::new();
    static BTDF_LUT: OnceLock<Lut> = OnceLock::new();
    let cell = if preset == BSDF { &BSDF_LUT } else { &BTDF_LUT };
    cell.get_or_init(|| {
        let t = table(preset, |s| s);
        let clock = std::time::Instant::now();
        let lut = brdfbake::table::bake(&t.spec).unwrap();
        eprintln!("{preset} baked in {:.1} s", clock.elapsed().as_secs_f64());
        // the bake meets its requested tolerance (its estimates are the bounds below)
        assert!(lut.error_estimate.iter().all(|&e| e <= t.spec.tolerance));
        t.stored(lut)
    })
}

/// btdf_ggx's largest (η − 1)/(η + 1): EEVEE's clamp (η = 19999) and the preset's (η = 99.5).
const EEVEE_TOP: f64 = 0.9999;
const OUR_TOP: f64 = 0.9801;

/// A texel of either table: the fresnel axis' coordinate (η for bsdf_ggx, (η − 1)/(η + 1)
/// for btdf_ggx), η, μ, α.
#[derive(Clone, Copy, Debug)]
struct Texel {
    coord: f64,
    eta: f64,
    mu: f64,
    alpha: f64,
}

/// bsdf_ggx's texel (x, y, z) as EEVEE's generator computes it: η = clamp(√(x/63), 1e-4,
/// 0.9999), the critical-angle remap of p = y/63 (continuous in `y`, for the half-texel
/// control), α = (z/15)².
fn bsdf_texel(x: usize, y: f64, z: usize) -> Texel {
    let eta = (x as f64 / 63.0).sqrt().clamp(1e-4, 0.9999);
    let c = (1.0 - eta * eta).sqrt();
    let t = 2.0 * (y / 63.0) - 1.0;
    let mu = (c + t * if t > 0.0 { 1.0 - c } else { c }).clamp(1e-4, 0.9999);
    Texel {
        coord: eta,
        eta,
        mu,
        alpha: (z as f64 / 15.0).powi(2),
    }
}

/// btdf_ggx's texel (x, y, z): f0 = clamp((x/63)², 1e-4, `top`) (EEVEE's name for
/// (η − 1)/(η + 1)), η = (1 + f0)/(1 − f0), μ = clamp(1 − (y/63)², 1e-4, 0.9999).
fn btdf_texel(x: usize, y: f64, z: usize, top: f64) -> Texel {
    let f0 = (x as f64 / 63.0).powi(2).clamp(1e-4, top);
    Texel {
        coord: f0,
        eta: (1.0 + f0) / (1.0 - f0),
        mu: (1.0 - (y / 63.0).powi(2)).clamp(1e-4, 0.9999),
        alpha: (z as f64 / 15.0).powi(2),
    }
}

/// The quoted texels of `file`: (z, y, x, values).
fn shipped(file: &str) -> Vec<(usize, usize, usize, Vec<f64>)> {
    let path = format!(
        "{}/tests/data/engines/eevee/{file}",
        env!("CARGO_MANIFEST_DIR")
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
                w[3..].iter().map(|v| v.parse().unwrap()).collect(),
            )
        })
        .collect()
}

/// Which cosine Schlick's weight s = (1 − cos)⁵ takes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Weight {
    /// EEVEE's (and the preset's): |h·l_t| for η < 1 (1 under total internal reflection),
    /// v·h for η > 1 — the cosine on the less dense side.
    Outer,
    /// v·h whatever η (wrong for η < 1).
    View,
    /// The early generator's HL = 1 − (1 − (v·h)²)/η², the squared transmitted cosine.
    CosSquaredT,
    /// |h·l_t| whatever η (wrong for η > 1).
    Transmitted,
}

fn weight(w: Weight, eta: f64, c: f64, t: Option<[f64; 3]>, h: [f64; 3]) -> f64 {
    let pow5 = |x: f64| (1.0 - x.clamp(0.0, 1.0)).powi(5);
    let transmitted = || t.map_or(1.0, |t| pow5(dot(h, t).abs()));
    match w {
        Weight::Outer if eta < 1.0 => transmitted(),
        Weight::Outer | Weight::View => pow5(c),
        Weight::CosSquaredT => pow5(1.0 - (1.0 - c * c) / (eta * eta)),
        Weight::Transmitted => transmitted(),
    }
}

/// `[A, B, T]` of EEVEE's estimator in expectation at texel `p` with Schlick weight `w`:
/// over visible micro-normals h (density D(h) G1(v) (v·h)/μ), A = (1 − s) G1(n·r),
/// B = s G1(n·r) with r the mirror of v about h above the surface, T = (1 − s) G1(|n·t|)
/// with t = refract(−v, h, 1/η) below it; by h-space quadrature (independent of brdfbake's
/// rule), and in closed form at α = 0 (h = n, G1 = 1). Its estimate: `error`.
fn expected(p: Texel, w: Weight, tol: f64) -> ([f64; 3], f64) {
    let v = view(p.mu);
    let minus_v = [-v[0], -v[1], -v[2]];
    if p.alpha == 0.0 {
        let n = [0.0, 0.0, 1.0];
        let t = refract(minus_v, n, 1.0 / p.eta);
        let s = weight(w, p.eta, p.mu, t, n);
        return ([1.0 - s, s, if t.is_some() { 1.0 - s } else { 0.0 }], 1e-15);
    }
    let m = RefModel::new(NdfKind::Ggx, p.alpha, Masking::SmithSeparable);
    let g1v = m.g1(p.mu);
    let e = reference::over_h_front(p.mu, p.alpha, tol, |h| {
        let c = dot(v, h);
        if c <= 0.0 {
            return [0.0; 3];
        }
        let dens = m.d_vec(h) * g1v * c / p.mu;
        let t = refract(minus_v, h, 1.0 / p.eta);
        let s = weight(w, p.eta, c, t, h);
        let nr = 2.0 * c * h[2] - p.mu;
        let g1r = if nr > 0.0 { m.g1(nr.min(1.0)) } else { 0.0 };
        let tt = match t {
            Some(t) if t[2] < 0.0 => dens * (1.0 - s) * m.g1((-t[2]).min(1.0)),
            _ => 0.0,
        };
        [dens * (1.0 - s) * g1r, dens * s * g1r, tt]
    });
    (e.value, e.error)
}

/// f32 rounding of a stored value ≤ 1 (half an ulp below 1: 2⁻²⁴ ≈ 6e-8).
const F32: f64 = 6e-8;

/// The stored channels of a preset and the channels of [`expected`] they are.
fn channel_map(preset: &str) -> &'static [usize] {
    if preset == BSDF {
        &[0, 1, 2]
    } else {
        &[2]
    }
}

/// EEVEE's texel (x, y, z) of `preset` and ours (equal but for btdf_ggx's column 63).
fn texels(preset: &str, x: usize, y: f64, z: usize) -> (Texel, Texel) {
    if preset == BSDF {
        (bsdf_texel(x, y, z), bsdf_texel(x, y, z))
    } else {
        (btdf_texel(x, y, z, EEVEE_TOP), btdf_texel(x, y, z, OUR_TOP))
    }
}

/// The texel coordinates are EEVEE's formulas (in f64, by the same operations: within a few
/// ulp, 1e-14), every texel of four layers; η of each column is EEVEE's within 1e-12
/// relative, but for btdf_ggx's column 63 (η = 99.5 against EEVEE's 19999, the module doc).
/// Negative controls: a linear view axis for bsdf_ggx, a linear fresnel axis for btdf_ggx,
/// put texels elsewhere by more than 0.1.
#[test]
fn texels_sit_where_eevee_puts_them() {
    for preset in [BSDF, BTDF] {
        let t = table(preset, |s| s);
        let axes = t.stored_axes();
        assert_eq!(
            axes.iter().map(|a| a.name.as_str()).collect::<Vec<_>>(),
            ["fresnel", "cos_theta_v", "roughness"]
        );
        for z in [0, 1, 8, 15] {
            for y in 0..64 {
                for x in 0..64 {
                    let (eevee, ours) = texels(preset, x, y as f64, z);
                    let got = brdfbake::lut::texel_coordinates(&axes, &[x, y, z]);
                    assert!(
                        (got[0] - ours.coord).abs() <= 1e-14
                            && (got[1] - ours.mu).abs() <= 1e-14
                            && (got[2] - z as f64 / 15.0).abs() <= 1e-14,
                        "{preset} texel ({x}, {y}, {z}): {got:?} vs {ours:?}"
                    );
                    let eta = axes[0].fresnel_parameter(x).unwrap();
                    if x < 63 || preset == BSDF {
                        assert!(
                            (eta / eevee.eta - 1.0).abs() <= 1e-12,
                            "{preset} column {x}: eta {eta} vs EEVEE's {}",
                            eevee.eta
                        );
                    } else {
                        let ours_eta = (1.0 + OUR_TOP) / (1.0 - OUR_TOP);
                        assert!(
                            (eta / ours_eta - 1.0).abs() <= 1e-12 && eevee.eta > 19998.0,
                            "column 63: eta {eta}, EEVEE's {}",
                            eevee.eta
                        );
                    }
                }
            }
        }
    }
    let linear = table(BSDF, |s| s.replace("\"warp\": \"critical-angle\", ", ""));
    let la = linear.stored_axes();
    let worst = (0..64)
        .map(|y| {
            let got = brdfbake::lut::texel_coordinates(&la, &[32, y, 8]);
            (got[1] - bsdf_texel(32, y as f64, 8).mu).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst > 0.1, "a linear view axis should not fit: {worst}");
    let linear = table(BTDF, |s| s.replace("\"warp\": \"sqrt\", ", ""));
    let la = linear.stored_axes();
    let worst = (0..63)
        .map(|x| {
            let got = brdfbake::lut::texel_coordinates(&la, &[x, 10, 8]);
            (got[0] - btdf_texel(x, 10.0, 8, OUR_TOP).coord).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst > 0.1, "a linear fresnel axis should not fit: {worst}");
}

/// The smooth layer (α = 0) at every texel: A = 1 − s(μ), B = s(μ), T = 1 − s(μ) (0 under
/// total internal reflection) with Schlick's weight on the less dense side at h = n, within
/// f32 rounding plus f64 rounding (1e-12). And interior texels (both sides of the critical
/// angle, smooth to rough, small to large η) against the independent integrator
/// ([`expected`], requested 1e-7): within the bake's estimate per channel plus the
/// integrator's plus f32 rounding. Negative control: with the view's cosine in Schlick's weight (wrong for
/// η < 1) the integrator misses bsdf_ggx by more than 0.05 somewhere among these texels.
#[test]
fn tables_meet_the_smooth_limit_and_the_independent_integrator() {
    for preset in [BSDF, BTDF] {
        let lut = baked(preset);
        let map = channel_map(preset);
        for y in 0..64 {
            for x in 0..64 {
                let (_, p) = texels(preset, x, y as f64, 0);
                let (want, _) = expected(p, Weight::Outer, 0.0);
                for (ch, &k) in map.iter().enumerate() {
                    let got = lut.texel([x, y, 0], ch) as f64;
                    assert!(
                        (got - want[k]).abs() <= F32 + 1e-12,
                        "{preset} alpha = 0, texel ({x}, {y}) channel {ch}: {got} vs {}",
                        want[k]
                    );
                }
            }
        }
    }
    let interior: &[(&str, usize, usize, usize)] = &[
        (BSDF, 1, 49, 1),
        (BSDF, 1, 49, 63),
        (BSDF, 4, 20, 10),
        (BSDF, 8, 31, 62),
        (BSDF, 8, 32, 32),
        (BSDF, 8, 33, 63),
        (BSDF, 12, 10, 55),
        (BSDF, 15, 45, 63),
        (BTDF, 3, 40, 20),
        (BTDF, 7, 63, 1),
        (BTDF, 8, 0, 63),
        (BTDF, 11, 50, 45),
        (BTDF, 15, 20, 8),
    ];
    let mut control: f64 = 0.0;
    for &(preset, z, y, x) in interior {
        let lut = baked(preset);
        let (_, p) = texels(preset, x, y as f64, z);
        let (want, err) = expected(p, Weight::Outer, 1e-7);
        for (ch, &k) in channel_map(preset).iter().enumerate() {
            let got = lut.texel([x, y, z], ch) as f64;
            let bound = lut.error_estimate[ch] + err + F32;
            assert!(
                (got - want[k]).abs() <= bound,
                "{preset} texel ({x}, {y}, {z}) {p:?} channel {ch}: {got} vs {} (bound {bound:e})",
                want[k]
            );
        }
        if preset == BSDF {
            let (wrong, _) = expected(p, Weight::View, 1e-5);
            for (k, w) in wrong.iter().enumerate() {
                control = control.max((lut.texel([x, y, z], k) as f64 - w).abs());
            }
        }
    }
    assert!(
        control > 0.05,
        "the view's cosine in Schlick's weight should not fit bsdf_ggx: {control}"
    );
}

/// Against EEVEE's quoted texels. For each: the shipped value is within B ([`EEVEE_ERROR`])
/// of EEVEE's estimator in expectation at EEVEE's own texel ([`expected`], requested 1e-6:
/// the check is on our reading of its generator); ours is within B + Δ + our estimate + the
/// integrator's + f32 of it, Δ the integrator's difference between EEVEE's texel and ours
/// (0 but in btdf_ggx's column 63: η = 19999 against 99.5).
///
/// Negative controls, where they can fail: (1) ours read half a texel off along the view
/// axis (p + 0.5/63, through the lookup) misses the shipped value by more than B at three or
/// more quoted texels of each table; (2) where another Schlick weight changes the
/// expectation by more than 2B — the early generator's squared transmitted cosine and the
/// view's cosine for bsdf_ggx, the transmitted cosine for btdf_ggx — the shipped value
/// misses it by more than B, at three or more quoted texels per weight.
#[test]
fn eevee_shipped_values_are_its_estimator_within_its_error() {
    let wrong_weights: [(&str, &[Weight]); 2] = [
        (BSDF, &[Weight::CosSquaredT, Weight::View]),
        (BTDF, &[Weight::Transmitted]),
    ];
    for (preset, wrongs) in wrong_weights {
        let lut = baked(preset);
        let file = if preset == BSDF {
            "bsdf_ggx.txt"
        } else {
            "btdf_ggx.txt"
        };
        let map = channel_map(preset);
        let quotes = shipped(file);
        assert!(quotes.len() >= 40, "{file}: {} quotes", quotes.len());
        let (mut worst, mut worst_delta, mut shifted_misses) = (0.0f64, 0.0f64, 0);
        // (btdf_ggx's column 63 on its own: its η differs)
        let mut worst_63 = 0.0f64;
        let mut wrong_misses = vec![0; wrongs.len()];
        for (z, y, x, ship) in &quotes {
            let (z, y, x) = (*z, *y, *x);
            let (eevee, ours_p) = texels(preset, x, y as f64, z);
            let (aw, aw_err) = expected(eevee, Weight::Outer, 1e-6);
            let (ours_exp, ours_err) = if x == 63 && preset == BTDF {
                expected(ours_p, Weight::Outer, 1e-6)
            } else {
                (aw, aw_err)
            };
            for (ch, &k) in map.iter().enumerate() {
                assert!(
                    (ship[ch] - aw[k]).abs() <= EEVEE_ERROR + aw_err,
                    "{preset} ({z}, {y}, {x}) channel {ch}: EEVEE {} is not its estimator {} (bound {EEVEE_ERROR:e})",
                    ship[ch],
                    aw[k]
                );
                let ours = lut.texel([x, y, z], ch) as f64;
                let delta = (aw[k] - ours_exp[k]).abs();
                let bound = EEVEE_ERROR + delta + lut.error_estimate[ch] + aw_err + ours_err + F32;
                assert!(
                    (ours - ship[ch]).abs() <= bound,
                    "{preset} ({z}, {y}, {x}) channel {ch}: ours {ours} vs EEVEE {} (bound {bound:e})",
                    ship[ch]
                );
                if x == 63 && preset == BTDF {
                    worst_63 = worst_63.max((ours - ship[ch]).abs());
                } else {
                    worst = worst.max((ours - ship[ch]).abs());
                }
                worst_delta = worst_delta.max(delta);
            }
            // (1) half a texel off along the view axis
            let (_, off) = texels(preset, x, y as f64 + 0.5, z);
            let read = lut.lookup(&[off.coord, off.mu, z as f64 / 15.0]);
            if map
                .iter()
                .enumerate()
                .any(|(ch, _)| (read[ch] - ship[ch]).abs() > EEVEE_ERROR)
            {
                shifted_misses += 1;
            }
            // (2) the other Schlick weights
            for (i, &w) in wrongs.iter().enumerate() {
                let (other, _) = expected(eevee, w, 1e-5);
                for (ch, &k) in map.iter().enumerate() {
                    if (other[k] - aw[k]).abs() > 2.0 * EEVEE_ERROR {
                        assert!(
                            (ship[ch] - other[k]).abs() > EEVEE_ERROR,
                            "{preset} ({z}, {y}, {x}) channel {ch}: EEVEE {} fits the {w:?} weight's {}",
                            ship[ch],
                            other[k]
                        );
                        wrong_misses[i] += 1;
                    }
                }
            }
        }
        eprintln!(
            "{preset}: {} quoted texels, worst |ours - EEVEE| {worst:.2e} (btdf_ggx's column 63: {worst_63:.2e}, its delta up to {worst_delta:.2e}); half-texel shift misses at {shifted_misses}; wrong weights {wrongs:?} miss at {wrong_misses:?}",
            quotes.len()
        );
        assert!(
            shifted_misses >= 3,
            "{preset}: a half-texel shift should miss: {shifted_misses}"
        );
        for (w, n) in wrongs.iter().zip(&wrong_misses) {
            assert!(
                *n >= 3,
                "{preset}: the {w:?} weight should miss at 3 or more texels: {n}"
            );
        }
    }
}

/// For η > 1 Schlick's weight is the view's s = (1 − v·h)⁵ and the reflected direction does
/// not depend on η, so a `dielectric-schlick` table's A and B are, in every η ≥ 1 slice,
/// Karis' split sum A, B of the GGX BRDF with the same masking — a `dfg` table, which
/// brdfbake integrates by another kernel (`table::dfg`). Both baked at 1e-7 here: equal
/// within the two bakes' estimates plus f32 rounding of each. Negative control: an η < 1
/// slice (its s from the refracted cosine, total internal reflection in B) differs from the
/// split sum by more than 0.01 somewhere.
#[test]
fn above_one_the_reflected_channels_are_the_brdf_split_sum() {
    use brdfbake::lut::{Axis, Convention, Quantity};
    use brdfbake::model::{Fresnel, FresnelQuantity, RoughnessQuantity};
    use brdfbake::table::{bake, DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
    let model = ModelSpec {
        ndf: Some(NdfKind::Ggx),
        masking: Masking::SmithSeparable,
        fresnel: Fresnel::None,
        diffuse_weight: 0.0,
        diffuse_model: brdfbake::model::DiffuseModel::Lambert,
        classic: None,
    };
    let mus = Axis::new(
        "cos_theta_v",
        Quantity::Cosine,
        6,
        [0.0, 1.0],
        Convention::Centers,
    );
    let rough = Axis::new(
        "roughness",
        Quantity::Roughness(RoughnessQuantity::Perceptual),
        4,
        [0.2, 1.0],
        Convention::Endpoints,
    );
    let etas = Axis::new(
        "fresnel",
        Quantity::Fresnel(FresnelQuantity::Eta),
        3,
        [0.8, 2.4],
        Convention::Endpoints,
    );
    let spec = |kind: TableKind, axes: Vec<Axis>| TableSpec {
        name: "t".into(),
        kind,
        model: model.clone(),
        axes,
        dfg_layout: (kind == TableKind::Dfg).then_some(DfgLayout::Karis),
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-7,
    };
    let schlick = bake(&spec(
        TableKind::DielectricSchlick,
        vec![mus.clone(), rough.clone(), etas.clone()],
    ))
    .unwrap();
    let dfg = bake(&spec(TableKind::Dfg, vec![mus, rough])).unwrap();
    let mut control: f64 = 0.0;
    for z in 0..3 {
        let eta = etas.coord(z);
        for j in 0..4 {
            for i in 0..6 {
                for c in 0..2 {
                    let (s, d) = (
                        schlick.texel([i, j, z], c) as f64,
                        dfg.texel([i, j, 0], c) as f64,
                    );
                    if eta < 1.0 {
                        control = control.max((s - d).abs());
                        continue;
                    }
                    let bound = schlick.error_estimate[c] + dfg.error_estimate[c] + 2.0 * F32;
                    assert!(
                        (s - d).abs() <= bound,
                        "eta {eta}, texel ({i}, {j}) channel {c}: {s} vs the split sum {d} (bound {bound:e})"
                    );
                }
            }
        }
    }
    assert!(
        control > 0.01,
        "an eta < 1 slice should not be the split sum: {control}"
    );
}
