//! The light-direction cloth path (src/integrate/sheen_l.rs) — the first choice for the
//! narrow sheen lobes (α < 1/16) of a dfg table's cloth channel — against the independent
//! reference (tests/common/reference.rs: l-space polar coordinates with geometric
//! breakpoints, adaptive Gauss–Legendre, textbook Charlie and Ashikhmin formulas), including
//! the first row and column of 128² and 512² tables (α = (½/N)², μ = ½/N).
//!
//! The reference validates Charlie lobes down to α = 0.01 (tests/dfg_kernel.rs); narrower
//! lobes are checked, as tests/dfg_kernel.rs does beyond the reference's range, against the
//! library's adaptive Gauss–Kronrod integrator in half-vector coordinates (a different
//! parameterization, rule and error estimate from the path under test) at a 10× tighter
//! tolerance, and at normal view against a closed form (the module's unit test).
//!
//! Tolerances (as tests/dfg_kernel.rs):
//! * `REQ = 1e-6`: the required accuracy of every baked value, relative where it exceeds 1.
//! * |path − reference| ≤ est + ref_est + `round`: the path's estimate must bound its true
//!   error. `round = 1e-12·max(1, |value|)` is rounding, which no quadrature estimate
//!   covers: the path sums ≤ 129 outer terms of inner sums of ≤ 1025 terms, each of the
//!   magnitude of its total ((129 + 1025)·2⁻⁵³ ≈ 1.3e-13 relative), and the integrand's own
//!   relative rounding (`exp(k ln(sin²θh/s0))`: |k ln|·2⁻⁵³ ≤ 700·2⁻⁵³ ≈ 8e-14 before it is
//!   cut) is of the same order.

#[path = "common/cloth_reference.rs"]
mod cloth_reference;
#[path = "common/reference.rs"]
mod reference;

use brdfbake::integrate::sheen_l::{charlie_sheen_l, EVAL_CAP, MAX_ALPHA};
use cloth_reference::{cloth_reference, fails};
use rayon::prelude::*;

const LIB_TOL: f64 = 1e-7;

fn round(v: f64) -> f64 {
    1e-12 * v.abs().max(1.0)
}

/// Every (μ, α) of the grid where the path converges agrees with the reference within
/// `REQ` and within its own estimate (+ the reference's); it must converge at the table
/// corners that matter most (the first row and column of 128² and 512² tables), at every
/// view μ ≥ 0.1, at the grazing views of a 128² table's first two columns (μ = 0.5/128,
/// 1.5/128) for α ≤ 0.03 (the inner rule's 1025 nodes resolve the φ integrand's features
/// at both φ = 0 and φ = π there; with 257 it gave up for α ≳ 1e-3), and at ≥ 85% of the
/// points (it still gives up at μ = 0.5/512 for α ≥ 5e-3 and at μ = 0.5/128 for α = 0.06,
/// where those texels go to the half-vector kernel).
#[test]
fn lspace_cloth_matches_reference_and_its_estimate_holds() {
    let mus = [
        0.5 / 512.0,
        0.5 / 128.0,
        1.5 / 128.0,
        0.02,
        0.1,
        0.35,
        0.7,
        0.999,
        1.0,
    ];
    let alphas = [
        (0.5f64 / 512.0).powi(2),
        (0.5f64 / 128.0).powi(2),
        1e-4,
        1e-3,
        0.01,
        0.03,
        0.06,
    ];
    let must = |mu: f64, alpha: f64| {
        mu >= 0.1
            || ([0.5 / 128.0, 1.5 / 128.0].contains(&mu) && alpha <= 0.03)
            || ([0.5 / 512.0, 0.5 / 128.0].contains(&mu)
                && [(0.5f64 / 512.0).powi(2), (0.5f64 / 128.0).powi(2)].contains(&alpha))
    };
    let pts: Vec<(f64, f64)> = mus.iter().flat_map(|&m| alphas.map(|a| (m, a))).collect();
    let res: Vec<(bool, Option<String>)> = pts
        .par_iter()
        .map(|&(mu, alpha)| {
            match charlie_sheen_l(mu, alpha, LIB_TOL) {
                Ok(e) => {
                    let r = cloth_reference(mu, alpha, 0.1 * LIB_TOL);
                    let d = (e.value[0] - r.value[0]).abs();
                    let bad = fails(e.value[0], e.error[0], LIB_TOL, &r, round(r.value[0]));
                    (
                        true,
                        bad.then(|| {
                            format!(
                                "mu={mu} alpha={alpha}: l-space {} (est {:e}, {} evals) reference {} (est {:e}) diff {d:e}",
                                e.value[0], e.error[0], e.evals, r.value[0], r.error
                            )
                        }),
                    )
                }
                Err(n) => (
                    false,
                    must(mu, alpha).then(|| {
                        format!("mu={mu} alpha={alpha}: l-space path gave up after {n} evaluations")
                    }),
                ),
            }
        })
        .collect();
    let used = res.iter().filter(|r| r.0).count();
    let gave_up: Vec<(f64, f64)> = pts
        .iter()
        .zip(&res)
        .filter(|(_, r)| !r.0)
        .map(|(p, _)| *p)
        .collect();
    let failures: Vec<String> = res.into_iter().filter_map(|r| r.1).collect();
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(
        used * 100 >= pts.len() * 85,
        "l-space path converged at {used} of {} points; gave up at (mu, alpha) {gave_up:?}",
        pts.len()
    );
}

/// The path is the one the narrow rows of a 128² filament-dfg table use, and it is cheap
/// there: over every texel with α < 1/16 (rows 0–31: μ = (i + ½)/128, α = ((j + ½)/128)²)
/// it converges at ≥ 97% of them, with at most 1,200 evaluations per texel on average
/// (the half-vector kernel spent ~1,800 there, each costlier), and never beyond
/// [`EVAL_CAP`]; wider lobes are refused (they go to the half-vector kernel).
#[test]
fn lspace_cloth_covers_the_narrow_rows_cheaply() {
    let n = 128;
    let (mut ok, mut total, mut evals) = (0u64, 0u64, 0u64);
    for i in 0..n {
        let mu = (i as f64 + 0.5) / n as f64;
        for j in 0..n {
            let r = (j as f64 + 0.5) / n as f64;
            let alpha = r * r;
            let res = charlie_sheen_l(mu, alpha, LIB_TOL);
            if alpha >= MAX_ALPHA {
                assert_eq!(res.unwrap_err(), 0, "alpha={alpha} must be refused");
                continue;
            }
            total += 1;
            match res {
                Ok(e) => {
                    assert!(e.error[0] <= LIB_TOL && e.value[0].is_finite());
                    ok += 1;
                    evals += e.evals;
                }
                Err(spent) => assert!(spent <= EVAL_CAP + 257, "mu={mu} alpha={alpha}"),
            }
        }
    }
    assert!(
        ok * 100 >= total * 97,
        "converged at {ok} of {total} texels"
    );
    assert!(
        evals <= 1200 * ok,
        "{} evaluations per converged texel",
        evals as f64 / ok as f64
    );
}

/// Bad arguments are refused without evaluations, never a panic or NaN.
#[test]
fn lspace_cloth_refuses_what_it_does_not_cover() {
    for (mu, alpha) in [
        (0.0, 0.01),
        (-0.5, 0.01),
        (1.5, 0.01),
        (f64::NAN, 0.01),
        (0.5, 0.0),
        (0.5, f64::NAN),
        (0.5, MAX_ALPHA),
        (0.5, 1.0),
    ] {
        assert_eq!(
            charlie_sheen_l(mu, alpha, LIB_TOL).unwrap_err(),
            0,
            "{mu} {alpha}"
        );
    }
}

// ---- wide lobes (1/16 ≤ α ≤ 1): src/integrate/sheen_wide.rs ----

use brdfbake::integrate::sheen_wide::{self, charlie_sheen_wide};

/// Wide lobes against the independent reference (valid there: α ≥ 0.01) over μv =
/// 1/1024 … 1 and α = 1/16 … 1: every point must converge, agree within `REQ` and within its
/// own estimate plus the reference's (+ rounding, as above), and meet the tolerance. The
/// breakpoint θl = θv (where h = n makes (sin θh)^{1/α} non-analytic) lies inside the
/// μl range of every μv < 1, so every point exercises it; μv = 1 puts it at the end of the
/// range, μv = 0.999 right next to it, and μv = 1/1024 at the horizon layer.
#[test]
fn wide_lspace_cloth_matches_reference_and_its_estimate_holds() {
    let mus = [1.0 / 1024.0, 1.0 / 256.0, 0.03, 0.2, 0.5, 0.8, 0.999, 1.0];
    let alphas = [1.0 / 16.0, 0.1, 0.25, 0.5, 0.75, 1.0];
    let pts: Vec<(f64, f64)> = mus.iter().flat_map(|&m| alphas.map(|a| (m, a))).collect();
    let failures: Vec<String> = pts
        .par_iter()
        .filter_map(|&(mu, alpha)| {
            let e = match charlie_sheen_wide(mu, alpha, LIB_TOL) {
                Ok(e) => e,
                Err(n) => return Some(format!("mu={mu} alpha={alpha}: gave up after {n} evaluations")),
            };
            // (α ≥ 1/16: the independent reference)
            let r = cloth_reference(mu, alpha, 0.1 * LIB_TOL);
            let d = (e.value[0] - r.value[0]).abs();
            let bad = fails(e.value[0], e.error[0], LIB_TOL, &r, round(r.value[0]))
                || e.evals > sheen_wide::EVAL_CAP + 2 * 65;
            bad.then(|| {
                format!(
                    "mu={mu} alpha={alpha}: wide l-space {} (est {:e}, {} evals) reference {} (est {:e}) diff {d:e}",
                    e.value[0], e.error[0], e.evals, r.value[0], r.error
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

/// Arguments outside the wide path's range are refused without evaluations.
#[test]
fn wide_lspace_cloth_refuses_what_it_does_not_cover() {
    for (mu, alpha) in [
        (0.0, 0.5),
        (-0.5, 0.5),
        (1.5, 0.5),
        (f64::NAN, 0.5),
        (0.5, 0.05),
        (0.5, 1.5),
        (0.5, f64::NAN),
    ] {
        assert_eq!(
            charlie_sheen_wide(mu, alpha, LIB_TOL).unwrap_err(),
            0,
            "{mu} {alpha}"
        );
    }
    assert_eq!(charlie_sheen_wide(0.5, 0.5, 0.0).unwrap_err(), 0);
}

/// The wide path is the one the wide rows of a 128² filament-dfg table use (rows 32–127:
/// μ = (i + ½)/128, α = ((j + ½)/128)² ≥ 1/16), column by column with the shared node data:
/// it must converge at every texel within the tolerance, with at most 1,450 evaluations per
/// texel on average (the half-vector kernel spends 1,761 there), and give the same bits as
/// the same texel computed alone (every 9th column and row: the value is a pure function
/// of (μ, α, tol), whatever the cache held before).
#[test]
fn wide_lspace_cloth_covers_the_wide_rows_and_sharing_changes_no_bit() {
    let n = 128;
    let (mut total, mut evals) = (0u64, 0u64);
    for i in 0..n {
        let mu = (i as f64 + 0.5) / n as f64;
        let mut cache = sheen_wide::WideCache::default();
        for j in 32..n {
            let r = (j as f64 + 0.5) / n as f64;
            let alpha = r * r;
            let e = sheen_wide::charlie_sheen_wide_shared(mu, alpha, LIB_TOL, &mut cache)
                .unwrap_or_else(|n| panic!("mu={mu} alpha={alpha}: gave up after {n} evaluations"));
            assert!(e.error[0] <= LIB_TOL && e.value[0].is_finite() && e.value[0] > 0.0);
            total += 1;
            evals += e.evals;
            if i % 9 == 0 && j % 9 == 0 {
                let alone = charlie_sheen_wide(mu, alpha, LIB_TOL).expect("converges alone");
                assert_eq!(
                    alone.value[0].to_bits(),
                    e.value[0].to_bits(),
                    "mu={mu} alpha={alpha}"
                );
                assert_eq!(alone.error[0].to_bits(), e.error[0].to_bits());
                assert_eq!(alone.evals, e.evals);
            }
        }
    }
    assert!(
        evals <= 1450 * total,
        "{} evaluations per texel",
        evals as f64 / total as f64
    );
}
