//! The 1D polar GGX kernel (src/kernels/ggx_polar.rs) against the independent reference
//! (tests/common/reference.rs: l-space, adaptive Gauss–Legendre, textbook formulas, no
//! closed-form azimuthal integral), over views μ = 1e-3 … 1 and roughness α = 1e-3 … 1 (the
//! reference's validated range), and beyond it (μ down to 1/1024, α down to (1/1024)², the
//! first texel of a 512² table) against the library's adaptive Gauss–Kronrod integrator at
//! a 100× tighter tolerance; and on a dense grid (down to α = 1e-6) against that integrator at
//! a 1e-12 tolerance.
//!
//! Tolerances: `REQ = 1e-6` is the accuracy every baked value needs; every kernel result
//! must also satisfy |kernel − reference| ≤ est + ref_est + `ROUND`, i.e. its error estimate
//! must bound its true error. `ROUND = 1e-12·max(1, |value|)`: the kernel sums at most a few
//! hundred outer terms of the value's magnitude and its azimuthal sums (≤ 65 terms each)
//! are of terms below 40·2⁻⁵³ relative (the Schlick polynomial's coefficients sum to 32 in
//! magnitude), far below 1e-12.

#![allow(clippy::needless_range_loop)]

#[path = "common/normal_view.rs"]
mod normal_view;
#[path = "common/reference.rs"]
mod reference;
use normal_view::normal_view_split_sum;

use brdfbake::kernels::ggx_polar::Smith;
use brdfbake::kernels::ggx_polar::{ggx_albedo, ggx_split_sum};
use brdfbake::model::{Fresnel, Masking, Ndf, NdfKind, Specular};
use brdfbake::table::dfg::split_sum_adaptive;
use rayon::prelude::*;
use reference::RefModel;

const LIB_TOL: f64 = 1e-7;
const REQ: f64 = 1e-6;
const REF_TOL: f64 = 1e-10;

fn round(v: f64) -> f64 {
    1e-12 * v.abs().max(1.0)
}

/// The masking terms the kernel takes.
const FORMS: [Masking; 4] = [
    Masking::SmithHeightCorrelated,
    Masking::SmithSeparable,
    Masking::SchlickGgx,
    Masking::SchlickGgxDirect,
];

/// The kernel's form of a masking term at α, with Schlick's k written here from Karis
/// (2013): α/2, and (√α + 1)²/8 for analytic lights.
fn smith(m: Masking, alpha: f64) -> Smith {
    match m {
        Masking::SmithHeightCorrelated => Smith::HeightCorrelated,
        Masking::SmithSeparable => Smith::Separable,
        Masking::SchlickGgx => Smith::Schlick { k: alpha / 2.0 },
        Masking::SchlickGgxDirect => Smith::Schlick {
            k: (alpha.sqrt() + 1.0).powi(2) / 8.0,
        },
        other => panic!("not a kernel form: {other:?}"),
    }
}

/// Both Smith forms and both Schlick-GGX forms (Karis' k = α/2 and (√α + 1)²/8), split sum
/// and albedo: the kernel must converge at EVERY point (it is the table path's first
/// choice; a fallback would cost the speed it exists for) and be within REQ of the reference
/// (which writes Schlick's G1 and Karis' k itself) and within its own estimate plus the
/// reference's.
#[test]
fn matches_reference_everywhere_and_its_estimate_holds() {
    let mus = [1e-3, 0.02, 0.1, 0.35, 0.7, 0.999, 1.0];
    let alphas = [1e-3, 0.01, 0.1, 0.3, 0.6, 1.0];
    let pts: Vec<(f64, f64, Masking)> = mus
        .iter()
        .flat_map(|&mu| alphas.iter().flat_map(move |&a| FORMS.map(|m| (mu, a, m))))
        .collect();
    let failures: Vec<String> = pts
        .par_iter()
        .flat_map_iter(|&(mu, alpha, masking)| {
            let smith = smith(masking, alpha);
            let r = reference::split_sum(
                &RefModel::new(NdfKind::Ggx, alpha, masking),
                mu,
                REF_TOL,
            );
            let mut f = Vec::new();
            let check = |f: &mut Vec<String>, what: &str, v: f64, est: f64, rv: f64, rest: f64| {
                let d = (v - rv).abs();
                if d > REQ * rv.abs().max(1.0) || d > est + rest + round(rv) {
                    f.push(format!(
                        "{smith:?} mu={mu} alpha={alpha} {what}: kernel {v} (est {est:e}) reference {rv} (est {rest:e}) diff {d:e}"
                    ));
                }
            };
            match ggx_split_sum(mu, alpha, smith, LIB_TOL) {
                Ok(e) => {
                    for c in 0..2 {
                        check(&mut f, &format!("ch{c}"), e.value[c], e.error[c], r.value[c], r.error);
                    }
                }
                Err(n) => f.push(format!("{smith:?} mu={mu} alpha={alpha}: split sum did not converge ({n} evaluations)")),
            }
            match ggx_albedo(mu, alpha, smith, LIB_TOL) {
                // the reference's two channels each carry an estimate r.error
                Ok(e) => check(&mut f, "albedo", e.value[0], e.error[0], r.value[0] + r.value[1], 2.0 * r.error),
                Err(n) => f.push(format!("{smith:?} mu={mu} alpha={alpha}: albedo did not converge ({n} evaluations)")),
            }
            f
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The corners of real tables, beyond the reference's range: first/last texel centres of
/// 128² and 512² tables (μ = 0.5/N, 1 − 0.5/N; perceptual roughness 0.5/N → α = (0.5/N)²)
/// and μ = α = 1. The kernel must converge and agree with the adaptive integrator run at a
/// 100× tighter tolerance within both estimates (+ rounding) and REQ.
#[test]
fn table_corners_converge_and_match_tight_adaptive() {
    let mut pts = Vec::new();
    for n in [128.0, 512.0] {
        let lo = 0.5 / n;
        for mu in [lo, 1.0 - lo, 1.0] {
            for r in [lo, 0.5, 1.0 - lo, 1.0] {
                pts.push((mu, r * r));
            }
        }
    }
    let failures: Vec<String> = pts
        .par_iter()
        .flat_map_iter(|&(mu, alpha)| {
            let mut f = Vec::new();
            match ggx_split_sum(mu, alpha, Smith::HeightCorrelated, LIB_TOL) {
                Ok(e) => {
                    let (r, re, _) = split_sum_adaptive(&ggx_hc(alpha), mu, LIB_TOL * 1e-2);
                    for c in 0..2 {
                        let d = (e.value[c] - r[c]).abs();
                        if d > REQ || d > e.error[c] + re[c] + round(r[c]) {
                            f.push(format!(
                                "mu={mu} alpha={alpha} ch{c}: kernel {} (est {:e}) adaptive {} (est {:e})",
                                e.value[c], e.error[c], r[c], re[c]
                            ));
                        }
                    }
                }
                Err(n) => f.push(format!("mu={mu} alpha={alpha}: did not converge ({n} evaluations)")),
            }
            f
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Out-of-domain inputs are refused (the caller falls back), never answered: α > 1 (the
/// closed forms assume M = m(1 − α²) ≥ 0), α ≤ 0, μ ≤ 0, NaN, and a Schlick k outside (0, 1)
/// (at k = 1 its G1 is μ, at k ≤ 0 it is 1 or negative).
#[test]
fn refuses_what_it_does_not_cover() {
    for k in [0.0, 1.0, -0.1, f64::NAN] {
        assert!(
            ggx_split_sum(0.5, 0.5, Smith::Schlick { k }, LIB_TOL).is_err(),
            "{k}"
        );
    }
    for (mu, a) in [
        (0.5, 1.5),
        (0.5, 0.0),
        (0.0, 0.5),
        (f64::NAN, 0.5),
        (0.5, f64::NAN),
    ] {
        assert!(
            ggx_split_sum(mu, a, Smith::HeightCorrelated, LIB_TOL).is_err(),
            "{mu} {a}"
        );
        assert!(
            ggx_albedo(mu, a, Smith::Separable, LIB_TOL).is_err(),
            "{mu} {a}"
        );
    }
}

/// The outer Clenshaw–Curtis rule with its Chebyshev-tail estimate and the inner trapezoid
/// accepted from 4 intervals (and Möbius-mapped near grazing) on a dense grid, μ = 1/1024 … 1
/// and α = 1e-6 … 1 (24 × 24, geometric: grazing views and the tiny α of a 512² table's first
/// rows), at the split-sum rows' node tolerance tol/4 = 2.5e-8 and at 1e-7, against the
/// adaptive 2D integrator (`split_sum_adaptive`, l-space, no closed forms) at 1e-12, and at
/// μ = 1 against [`normal_view_split_sum`]: there the 2D integrator's estimate does not
/// bound its error for narrow lobes (at α = 1.2e-4, 2.4e-12 off with an estimate of 8e-14;
/// an mpmath quadrature at 40 digits agrees with the 1D reference and the kernel to 3e-15).
/// Every result must be within its own estimate plus the reference's plus
/// `round` (the estimate must bound the true error), and its estimates within the requested
/// tolerance. The kernel may not decline (`Err`) anywhere: it did in the corner α < 2e-6,
/// μ < 2e-3 at tol 2.5e-8 while it took sin θv − sin θl as a difference (rounding noise
/// ~1e-10 relative near the lobe's peak kept the outer estimate above tol/8).
#[test]
fn dense_grid_within_estimates_against_tight_adaptive() {
    let n = 24;
    let geo = |lo: f64, i: usize| lo.powf(1.0 - i as f64 / (n - 1) as f64);
    let pts: Vec<(f64, f64)> = (0..n)
        .flat_map(|i| (0..n).map(move |j| (geo(1.0 / 1024.0, i), geo(1e-6, j))))
        .collect();
    let tols = [2.5e-8, 1e-7];
    let failures: Vec<String> = pts
        .par_iter()
        .flat_map_iter(|&(mu, alpha)| {
            let reference = if mu == 1.0 {
                normal_view_split_sum(alpha)
            } else {
                let (r, re, _) = split_sum_adaptive(&ggx_hc(alpha), mu, 1e-12);
                (r, re)
            };
            tols.into_iter()
                .flat_map(move |tol| within_estimates(mu, alpha, tol, reference))
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// As [`dense_grid_within_estimates_against_tight_adaptive`] for the two Schlick-GGX
/// forms (Unreal's and LearnOpenGL's k = α/2, Karis' direct-light k = (√α + 1)²/8), on a
/// 12 × 12 geometric grid μ = 1/1024 … 0.999 (the normal view needs the 1D reference, written
/// for Smith's form), α = 1e-6 … 1, at tol 1e-7 and 2.5e-8 against the adaptive 2D integrator
/// at 1e-12: Schlick's G1 turns over at μl ≈ k/(1 − k) instead of Smith's ≈ min(μv, α)
/// (`horizon_scale`), so its panels differ, and the estimates must still hold everywhere.
#[test]
fn schlick_forms_within_estimates_against_tight_adaptive() {
    let n = 12;
    let geo = |lo: f64, hi: f64, i: usize| lo * (hi / lo).powf(i as f64 / (n - 1) as f64);
    let pts: Vec<(f64, f64, Masking)> = (0..n)
        .flat_map(|i| {
            (0..n).flat_map(move |j| {
                [Masking::SchlickGgx, Masking::SchlickGgxDirect]
                    .map(|m| (geo(1.0 / 1024.0, 0.999, i), geo(1e-6, 1.0, j), m))
            })
        })
        .collect();
    let failures: Vec<String> = pts
        .par_iter()
        .flat_map_iter(|&(mu, alpha, m)| {
            let (r, re, _) = split_sum_adaptive(&ggx(alpha, m), mu, 1e-12);
            [2.5e-8, 1e-7]
                .into_iter()
                .flat_map(move |tol| within_estimates_of(smith(m, alpha), mu, alpha, tol, (r, re)))
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// GGX with height-correlated Smith masking and F = 1, the model of the kernel's split sum.
fn ggx_hc(alpha: f64) -> Specular {
    ggx(alpha, Masking::SmithHeightCorrelated)
}

/// GGX with `masking` and F = 1.
fn ggx(alpha: f64, masking: Masking) -> Specular {
    Specular {
        ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
        masking,
        fresnel: Fresnel::None,
    }
}

/// The kernel at (μ, α) and `tol` against a reference (values, estimates): a failure where
/// it declines, where it differs from the reference by more than both estimates plus
/// `round`, or where its own estimate exceeds `tol`.
fn within_estimates(mu: f64, alpha: f64, tol: f64, r: ([f64; 2], [f64; 2])) -> Vec<String> {
    within_estimates_of(Smith::HeightCorrelated, mu, alpha, tol, r)
}

fn within_estimates_of(
    smith: Smith,
    mu: f64,
    alpha: f64,
    tol: f64,
    (r, re): ([f64; 2], [f64; 2]),
) -> Vec<String> {
    let mut f = Vec::new();
    match ggx_split_sum(mu, alpha, smith, tol) {
        Ok(e) => {
            for c in 0..2 {
                let d = (e.value[c] - r[c]).abs();
                if d > e.error[c] + re[c] + round(r[c]) || e.error[c] > tol {
                    f.push(format!(
                        "{smith:?} tol={tol:e} mu={mu:e} alpha={alpha:e} ch{c}: kernel {} (est {:e}) reference {} (est {:e}) diff {d:e}",
                        e.value[c], e.error[c], r[c], re[c]
                    ));
                }
            }
        }
        Err(m) => f.push(format!(
            "tol={tol:e} mu={mu:e} alpha={alpha:e}: declined ({m} evaluations)"
        )),
    }
    f
}

/// Narrow lobes at tight tolerances (α = 1e-6 … 1e-5, tol = 1e-10): the integrand's values
/// near the lobe's peak must be accurate to near f64 rounding, or the outer rule cannot
/// converge (with sin θv − sin θl taken as a difference the kernel declined at 1e-9 already:
/// relative noise ~1e-16/α). Against the adaptive 2D integrator at 1e-12 (no closed forms,
/// l-space): within both estimates plus `round`.
#[test]
fn narrow_lobes_converge_at_tight_tolerances() {
    let pts = [
        (8.05e-3, 1e-6),
        (0.05, 3e-6),
        (0.3, 1e-6),
        (0.74, 2e-6),
        (0.97, 1e-5),
    ];
    let tol = 1e-10;
    let failures: Vec<String> = pts
        .par_iter()
        .flat_map_iter(|&(mu, alpha)| {
            let (r, re, _) = split_sum_adaptive(&ggx_hc(alpha), mu, 1e-12);
            within_estimates(mu, alpha, tol, (r, re))
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}
