//! The cloth kernel in θh with the azimuthal integral in closed form
//! (src/kernels/sheen_azimuth.rs) — the first choice for every cloth texel of a dfg table
//! and of Charlie albedo tables — against the independent reference
//! (tests/common/reference.rs: l-space polar coordinates with geometric breakpoints,
//! adaptive Gauss–Legendre, textbook Charlie and Ashikhmin formulas) for α ≥ 0.01, and below
//! it (beyond the reference's validated range, as tests/cloth_lspace.rs does) against the
//! library's adaptive Gauss–Kronrod integrator in half-vector coordinates at a 10× tighter
//! tolerance: a different parameterization (2D, no closed form), rule and estimate.
//!
//! Tolerances (as tests/cloth_lspace.rs):
//! * `REQ = 1e-6`: the required accuracy of every baked value, relative where it exceeds 1.
//! * |kernel − reference| ≤ est + ref_est + `round`: the kernel's estimate must bound its
//!   true error. `round = 1e-10·max(1, |value|)`: the closed form's partial fractions have
//!   terms up to μv²/c² = 1e6 times the integrand's scale at μv = 0.999 (c = 1 − μv), which
//!   cancel to ~1e6·2⁻⁵³ ≈ 1e-10; the rule sums ≤ 3·129 terms (≈ 4e-14 relative).

#[path = "common/cloth_reference.rs"]
mod cloth_reference;
#[path = "common/reference.rs"]
mod reference;

use brdfbake::kernels::sheen_azimuth::charlie_sheen_azimuth;
use cloth_reference::{cloth_reference, fails};
use rayon::prelude::*;

const LIB_TOL: f64 = 1e-7;

fn round(v: f64) -> f64 {
    1e-10 * v.abs().max(1.0)
}

/// Every point of a grid over the whole domain the kernel accepts (μ from the first texel
/// of a 512² table to 0.999, α from that table's first row to 1) converges, agrees with the
/// reference within `REQ` and within its own estimate plus the reference's, and the estimate
/// is within the tolerance asked for.
#[test]
fn azimuth_cloth_matches_reference_and_its_estimate_holds() {
    let mus = [
        0.5 / 512.0,
        0.5 / 128.0,
        1.5 / 128.0,
        0.02,
        0.1,
        0.35,
        0.7,
        0.95,
        0.999,
    ];
    let alphas = [
        (0.5f64 / 512.0).powi(2),
        (0.5f64 / 128.0).powi(2),
        1e-4,
        1e-3,
        0.01,
        0.03,
        0.0625,
        0.1,
        0.3,
        0.7,
        1.0,
    ];
    let pts: Vec<(f64, f64)> = mus.iter().flat_map(|&m| alphas.map(|a| (m, a))).collect();
    let failures: Vec<String> = pts
        .par_iter()
        .filter_map(|&(mu, alpha)| {
            let e = match charlie_sheen_azimuth(mu, alpha, LIB_TOL) {
                Ok(e) => e,
                Err(n) => return Some(format!("mu={mu} alpha={alpha}: gave up after {n}")),
            };
            let r = cloth_reference(mu, alpha, 0.1 * LIB_TOL);
            let bad = fails(e.value[0], e.error[0], LIB_TOL, &r, round(r.value[0]));
            bad.then(|| {
                format!(
                    "mu={mu} alpha={alpha}: kernel {} (est {:e}, {} evals) reference {} (est {:e}) diff {:e}",
                    e.value[0],
                    e.error[0],
                    e.evals,
                    r.value[0],
                    r.error,
                    (e.value[0] - r.value[0]).abs()
                )
            })
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Views within 1e-3 of the normal are declined (the partial fractions would cancel), and so
/// are arguments outside the domain: the callers then use the other kernels.
#[test]
fn azimuth_cloth_declines_near_normal_and_bad_arguments() {
    for (mu, alpha, tol) in [
        (1.0, 0.1, LIB_TOL),
        (0.9995, 0.1, LIB_TOL),
        (0.0, 0.1, LIB_TOL),
        (0.5, 0.0, LIB_TOL),
        (0.5, f64::NAN, LIB_TOL),
        (0.5, 0.1, 0.0),
    ] {
        assert_eq!(charlie_sheen_azimuth(mu, alpha, tol).unwrap_err(), 0);
    }
}
