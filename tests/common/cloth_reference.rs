//! What the cloth kernel's tests (tests/cloth_azimuth.rs) compare with, and how. The including test crate declares `mod reference` (common/reference.rs).

use super::reference::{self, Est, RefModel};
use brdfbake::model::{Masking, NdfKind};
use brdfbake::table::dfg::sheen_albedo_adaptive;

/// The reference validates Charlie lobes down to this α (tests/accuracy.rs); narrower
/// lobes are compared with the library's adaptive integrator instead.
pub const REF_MIN_ALPHA: f64 = 0.01;
/// The independent reference's tolerance.
pub const REF_TOL: f64 = 1e-10;
/// The required accuracy of every baked value, relative where it exceeds 1.
pub const REQ: f64 = 1e-6;

/// The cloth albedo at (μ, α): the independent reference for α ≥ [`REF_MIN_ALPHA`], else the
/// library's adaptive Gauss–Kronrod integrator in half-vector coordinates (a different
/// parameterization, rule and estimate from the kernels under test) at `adaptive_tol`.
pub fn cloth_reference(mu: f64, alpha: f64, adaptive_tol: f64) -> Est<1> {
    if alpha >= REF_MIN_ALPHA {
        let m = RefModel::new(NdfKind::Charlie, alpha, Masking::Ashikhmin);
        reference::albedo(&m, mu, REF_TOL)
    } else {
        let (v, e, n) = sheen_albedo_adaptive(alpha, mu, adaptive_tol);
        Est {
            value: [v],
            error: e,
            evals: n,
        }
    }
}

/// Whether a kernel's `value` with estimate `est` (asked for `tol`) fails against `r`: off by
/// more than [`REQ`], or by more than both estimates plus `round` (rounding, which no
/// quadrature estimate covers), or an estimate above what it was asked for.
pub fn fails(value: f64, est: f64, tol: f64, r: &Est<1>, round: f64) -> bool {
    let d = (value - r.value[0]).abs();
    d > REQ * r.value[0].abs().max(1.0) || d > est + r.error + round || est > tol
}
