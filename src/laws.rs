//! The two laws of the lecture, measured for any [`Reflectance`]:
//!
//! - **Helmholtz reciprocity** `f(ωi, ωo) = f(ωo, ωi)`: the largest |f(ωi,ωo) − f(ωo,ωi)|
//!   over a fixed direction set ([`reciprocity_directions`]), with where it occurs;
//! - **energy conservation** `∀ωi: E(ωi) = ∫ f(ωi, ωo) cos θo dωo ≤ 1`: the directional
//!   albedo E by adaptive quadrature (with its error estimate) over a fixed set of incoming
//!   directions ([`incoming_directions`]), the largest E and every direction where
//!   E exceeds 1 by more than its error estimate.
//!
//! **Azimuth.** For an isotropic model E depends on θi only and is computed at φi = 0. For
//! an anisotropic one (Ward, Ashikhmin–Shirley, Lafortune with Cx ≠ Cy) E is computed at the
//! stated azimuths φi ∈ {0°, 22.5°, 45°, 67.5°, 90°} from the tangent (the anisotropy axis
//! +x): all these models depend on the tangent components only through x², y² or the
//! products ωi,x ωo,x, ωi,y ωo,y, so E(φ) = E(−φ) = E(π − φ) and [0°, 90°] covers every
//! azimuth. [`azimuth_averaged_albedo`] gives the average over φi instead.
//!
//! **Quadrature.** E is integrated over the half vector h = (θh, φh) of ωi and ωo with
//! dωo = 4(ωi·h) dωh (Walter et al. 2007, eq. 14), in a frame where ωi lies in the xz
//! plane (the model is evaluated back in the surface frame), up to the exact horizon
//! θh < π/4 + ψ/2, tan ψ = tan θi cos φh (the same geometry as
//! [`crate::hemisphere`]), with the inner variable u = asinh(tan θh / w), w the
//! model's lobe width, and nested adaptive Gauss–Kronrod G7/K15 whose |K15 − G7| error
//! estimates are summed into the reported error.

use crate::hemisphere::tan_theta_h_max;
use crate::model::classic::{dir, Dir, Reflectance};
use crate::quadrature::adaptive::{integrate, Tolerance};
use crate::quadrature::budget::{with_budget, INTEGRAL_EVAL_BUDGET};
use std::f64::consts::{FRAC_PI_2, PI};

/// A directional albedo with its estimated absolute error.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Albedo {
    pub value: f64,
    pub error: f64,
    pub evals: u64,
}

/// Rotation about +z by φ.
#[inline]
fn rot_z(w: Dir, (s, c): (f64, f64)) -> Dir {
    [c * w[0] - s * w[1], s * w[0] + c * w[1], w[2]]
}

/// `∫ f(ωi, ωo) cos θo dωo` for ωi at polar angle `theta_i` ∈ [0, π/2) and azimuth `phi_i`,
/// to the absolute tolerance `tol` (estimated); see the module documentation.
/// The tolerance is raised to the model's [`Reflectance::tolerance_floor`].
/// All its integrals share one budget of
/// [`crate::quadrature::budget::INTEGRAL_EVAL_BUDGET`] evaluations
/// (≈ 1 s): an integrand that cannot reach `tol` stops there and reports the error reached.
pub fn directional_albedo(m: &dyn Reflectance, theta_i: f64, phi_i: f64, tol: f64) -> Albedo {
    with_budget(INTEGRAL_EVAL_BUDGET, || {
        directional_albedo_unbounded(m, theta_i, phi_i, tol)
    })
}

fn directional_albedo_unbounded(m: &dyn Reflectance, theta_i: f64, phi_i: f64, tol: f64) -> Albedo {
    let tol = tol.max(m.tolerance_floor());
    let mu = theta_i.cos().clamp(0.0, 1.0);
    if mu <= 0.0 {
        return Albedo {
            value: 0.0,
            error: 0.0,
            evals: 0,
        };
    }
    let sin_i = (1.0 - mu * mu).max(0.0).sqrt();
    let tan_i = sin_i / mu;
    let v = [sin_i, 0.0, mu];
    let rot = phi_i.sin_cos();
    let wi = rot_z(v, rot);
    let w = m.lobe_width();
    // error budget as in the hemisphere integrator: half to the outer (φ over 2π) rule, half
    // to the inner integrals; the inner error is a noise floor for the outer rule
    let inner_abs = tol / (8.0 * PI);
    let inner = Tolerance {
        abs: inner_abs,
        initial_panels: 4,
        max_depth: 40,
        max_evals: 50_000,
        ..Default::default()
    };
    let outer = Tolerance {
        abs: tol / 2.0,
        initial_panels: 8,
        max_depth: 40,
        noise_floor: 2.0 * inner_abs,
        max_evals: 10_000,
    };
    let inner_err = std::cell::Cell::new(0.0f64);
    let inner_evals = std::cell::Cell::new(0u64);
    let est = integrate(
        |phi: f64| {
            let (sp, cp) = phi.sin_cos();
            let umax = (tan_theta_h_max(tan_i, cp) / w).asinh();
            let e = integrate(
                |u: f64| {
                    let t = w * u.sinh();
                    let c2 = 1.0 / (1.0 + t * t);
                    let ch = c2.sqrt();
                    let sh = t * ch;
                    let h = [sh * cp, sh * sp, ch];
                    let vh = v[0] * h[0] + v[2] * h[2];
                    let lo = [
                        2.0 * vh * h[0] - v[0],
                        2.0 * vh * h[1],
                        2.0 * vh * h[2] - v[2],
                    ];
                    if lo[2] <= 0.0 || vh <= 0.0 {
                        return [0.0];
                    }
                    let f = m.eval(wi, rot_z(lo, rot));
                    // dωh = sin θh dθh dφ, dθh/du = w cosh u cos²θh; dωo = 4 (ωi·h) dωh
                    let jac = 4.0 * vh * sh * w * u.cosh() * c2;
                    [f * lo[2] * jac]
                },
                0.0,
                umax,
                inner,
            );
            inner_err.set(inner_err.get().max(e.error[0]));
            inner_evals.set(inner_evals.get() + e.evals);
            [e.value[0]]
        },
        0.0,
        2.0 * PI,
        outer,
    );
    // the outer rule weights the inner results by positive weights summing to the 2π
    // length of the φ range, so their errors add up to at most 2π × the largest one
    let inner_bound = inner_err.get() * 2.0 * PI;
    Albedo {
        value: est.value[0],
        error: est.error[0] + inner_bound,
        evals: est.evals + inner_evals.get(),
    }
}

/// The albedo averaged over the incoming azimuth, `(1/2π)∫ E(θi, φ) dφ`, by adaptive
/// Gauss–Kronrod over φ ∈ [0, π/2] (enough by the symmetry stated in the module
/// documentation); the error adds the outer estimate and the largest per-node estimate. Every
/// albedo it takes shares one budget, as in [`directional_albedo`].
pub fn azimuth_averaged_albedo(m: &dyn Reflectance, theta_i: f64, tol: f64) -> Albedo {
    with_budget(INTEGRAL_EVAL_BUDGET, || azimuth_average(m, theta_i, tol))
}

fn azimuth_average(m: &dyn Reflectance, theta_i: f64, tol: f64) -> Albedo {
    if m.isotropic() {
        return directional_albedo(m, theta_i, 0.0, tol);
    }
    let errs = std::cell::Cell::new(0.0f64); // largest per-node albedo error
    let evals = std::cell::Cell::new(0u64);
    let t = Tolerance {
        abs: tol,
        initial_panels: 2,
        max_depth: 12,
        max_evals: 2_000,
        ..Default::default()
    };
    let e = integrate(
        |phi| {
            let a = directional_albedo(m, theta_i, phi, tol);
            errs.set(errs.get().max(a.error));
            evals.set(evals.get() + a.evals);
            [a.value]
        },
        0.0,
        FRAC_PI_2,
        t,
    );
    // weights sum to π/2, divided by π/2 for the mean: the node errors add at most their max
    Albedo {
        value: e.value[0] / FRAC_PI_2,
        error: e.error[0] / FRAC_PI_2 + errs.get(),
        evals: evals.get(),
    }
}

/// The incoming polar angles at which the energy law is checked, in degrees: 0° (normal
/// incidence), 5°, 10°, …, 85°, then the grazing 87.5°, 89°, 89.5° and 89.9° where
/// normalizations with 1/cos θ fail.
pub fn incoming_thetas_deg() -> Vec<f64> {
    let mut v: Vec<f64> = (0..18).map(|i| 5.0 * i as f64).collect();
    v.extend_from_slice(&[87.5, 89.0, 89.5, 89.9]);
    v
}

/// The incoming azimuths (degrees from the tangent) for a model: {0} when isotropic,
/// {0, 22.5, 45, 67.5, 90} otherwise (see the module documentation).
pub fn incoming_phis_deg(isotropic: bool) -> Vec<f64> {
    if isotropic {
        vec![0.0]
    } else {
        vec![0.0, 22.5, 45.0, 67.5, 90.0]
    }
}

/// The (θ, φ) pairs of [`incoming_thetas_deg`] × [`incoming_phis_deg`], in degrees.
pub fn incoming_directions(isotropic: bool) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for t in incoming_thetas_deg() {
        for p in incoming_phis_deg(isotropic) {
            out.push((t, p));
        }
    }
    out
}

/// The fixed direction set for reciprocity, as (θ, φ) in degrees: θ ∈ {1°, 10°, 20°, …,
/// 80°, 89°} × φ ∈ {0°, 30°, …, 330°} (≤ 120 directions, all pairs are tested), plus for
/// every direction its mirror image and four directions 2° off the mirror (where
/// specular lobes are large), appended as pairs by [`reciprocity_pairs`].
pub fn reciprocity_directions() -> Vec<(f64, f64)> {
    let mut thetas = vec![1.0];
    thetas.extend((1..9).map(|i| 10.0 * i as f64));
    thetas.push(89.0);
    let mut out = Vec::new();
    for &t in &thetas {
        for j in 0..12 {
            out.push((t, 30.0 * j as f64));
        }
    }
    out
}

/// The (ωi, ωo) pairs tested for reciprocity (see [`reciprocity_directions`]).
pub fn reciprocity_pairs() -> Vec<((f64, f64), (f64, f64))> {
    let d = reciprocity_directions();
    let mut pairs = Vec::new();
    for &a in &d {
        for &b in &d {
            pairs.push((a, b));
        }
    }
    for &(t, p) in &d {
        if t > 85.0 {
            continue;
        }
        for (dt, dp) in [(0.0, 0.0), (2.0, 0.0), (-2.0, 0.0), (0.0, 2.0), (0.0, -2.0)] {
            let tt: f64 = t + dt;
            if tt > 0.0 {
                pairs.push(((t, p), (tt, p + 180.0 + dp)));
            }
        }
    }
    pairs
}

fn deg_dir((t, p): (f64, f64)) -> Dir {
    dir(t.to_radians(), p.to_radians())
}

/// Result of the reciprocity measurement.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Reciprocity {
    /// Largest |f(ωi,ωo) − f(ωo,ωi)| (1/sr).
    pub max_abs: f64,
    /// Largest |f(ωi,ωo) − f(ωo,ωi)| / max(|f(ωi,ωo)|, |f(ωo,ωi)|).
    pub max_rel: f64,
    /// Where `max_abs` occurs: (θ, φ) of ωi and ωo in degrees, and both values.
    pub at: ((f64, f64), (f64, f64), f64, f64),
    /// Where `max_rel` occurs, as `at`.
    pub at_rel: ((f64, f64), (f64, f64), f64, f64),
    /// Pairs tested.
    pub pairs: usize,
    /// Whether every pair agrees to relative [`RECIPROCITY_REL`] (rounding of a few dozen
    /// f64 operations: the largest difference a reciprocal formula produces).
    pub holds: bool,
}

/// Relative difference accepted as rounding (a formula of a few dozen f64 operations
/// evaluated in two orders differs by ~1e-14 relative; 1e-10 leaves ample room while any
/// real asymmetry, e.g. a cos θi factor, gives differences of order 1).
pub const RECIPROCITY_REL: f64 = 1e-10;

/// Measures reciprocity over [`reciprocity_pairs`].
pub fn reciprocity(m: &dyn Reflectance) -> Reciprocity {
    let mut r = Reciprocity {
        max_abs: 0.0,
        max_rel: 0.0,
        at: ((0.0, 0.0), (0.0, 0.0), 0.0, 0.0),
        at_rel: ((0.0, 0.0), (0.0, 0.0), 0.0, 0.0),
        pairs: 0,
        holds: true,
    };
    for (a, b) in reciprocity_pairs() {
        let (wa, wb) = (deg_dir(a), deg_dir(b));
        let (f1, f2) = (m.eval(wa, wb), m.eval(wb, wa));
        r.pairs += 1;
        let d = (f1 - f2).abs();
        let scale = f1.abs().max(f2.abs());
        let rel = if scale > 0.0 { d / scale } else { 0.0 };
        if d > r.max_abs {
            r.max_abs = d;
            r.at = (a, b, f1, f2);
        }
        if rel > r.max_rel {
            r.max_rel = rel;
            r.at_rel = (a, b, f1, f2);
        }
    }
    r.holds = r.max_rel <= RECIPROCITY_REL;
    r
}

/// One measured directional albedo.
#[derive(Clone, Debug, serde::Serialize)]
pub struct AlbedoAt {
    pub theta_i_deg: f64,
    pub phi_i_deg: f64,
    pub albedo: f64,
    pub error: f64,
}

/// Result of the energy measurement.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Energy {
    /// Largest directional albedo found, where, and its error estimate.
    pub max: AlbedoAt,
    /// Every direction where E − error > 1 (the law fails there beyond doubt).
    pub fails_at: Vec<AlbedoAt>,
    /// Every albedo computed.
    pub albedo: Vec<AlbedoAt>,
    /// Whether E ≤ 1 (within its error estimate) at every direction tested.
    pub holds: bool,
}

/// Measures energy conservation at [`incoming_directions`] with quadrature tolerance `tol`.
pub fn energy(m: &dyn Reflectance, tol: f64) -> Energy {
    energy_until(m, tol, None).expect("no deadline")
}

/// [`energy`], the directions in parallel (each albedo is a pure function of its direction,
/// so the result does not depend on the threads), giving up (`None`) once `deadline` has
/// passed (checked before every albedo).
pub fn energy_until(
    m: &dyn Reflectance,
    tol: f64,
    deadline: Option<&crate::deadline::Deadline>,
) -> Option<Energy> {
    use rayon::prelude::*;
    let stopped = std::sync::atomic::AtomicBool::new(false);
    let all: Vec<AlbedoAt> = incoming_directions(m.isotropic())
        .into_par_iter()
        .with_min_len(1)
        .map(|(t, p)| {
            use std::sync::atomic::Ordering::Relaxed;
            if stopped.load(Relaxed) || deadline.is_some_and(|d| d.passed()) {
                stopped.store(true, Relaxed);
            }
            let a = if stopped.load(Relaxed) {
                Albedo {
                    value: 0.0,
                    error: 0.0,
                    evals: 0,
                }
            } else {
                match deadline {
                    // (the rules inside stop refining once it passes: crate::quadrature::budget)
                    Some(d) => crate::deadline::scoped(d, || {
                        directional_albedo(m, t.to_radians(), p.to_radians(), tol)
                    }),
                    None => directional_albedo(m, t.to_radians(), p.to_radians(), tol),
                }
            };
            AlbedoAt {
                theta_i_deg: t,
                phi_i_deg: p,
                albedo: a.value,
                error: a.error,
            }
        })
        .collect();
    // (an albedo cut short by the deadline is not a value)
    if stopped.into_inner() || deadline.is_some_and(|d| d.passed()) {
        return None;
    }
    let max = all
        .iter()
        .fold(None::<&AlbedoAt>, |b, a| match b {
            Some(b) if b.albedo >= a.albedo => Some(b),
            _ => Some(a),
        })
        .cloned()
        .expect("the direction set is not empty");
    let fails_at: Vec<AlbedoAt> = all
        .iter()
        .filter(|a| a.albedo - a.error > 1.0)
        .cloned()
        .collect();
    Some(Energy {
        holds: fails_at.is_empty(),
        max,
        fails_at,
        albedo: all,
    })
}
