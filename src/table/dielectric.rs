//! `dielectric-btdf`: reflection and transmission albedo R, T of a rough dielectric
//! interface (GGX, separable Smith, exact Fresnel; Walter et al. 2007; the integrands are in
//! [`crate::model::btdf`]) over (cos θv; roughness; η).
//!
//! The integrals run over the micro-normal h in the hemisphere about n, with v in the
//! xz-plane and φ ∈ [0, π] doubled by symmetry, split at φ = π/2; the inner variable is the
//! lobe warp u = asinh(tan θh/α) of `hemisphere.rs`. The inner range ends where v·h = 0
//! (tan θh = n·v/(sin θv (−cos φ)) for cos φ < 0) or, where h reaches the equator with
//! v·h > 0, at u = 30 (the tail of the GGX measure beyond is < 4α e^(−30)/(π n·v) < 1e-12
//! for n·v ≥ 1e-3). Known kinks are panel boundaries: the reflected direction's horizon
//! (tan θh = `tan_theta_h_max`, exact) and, for η < 1, the critical angle v·h = √(1 − η²)
//! (v·h = A cos(θh − ψ), A = √((n·v)² + sin²θv cos²φ), tan ψ = sin θv cos φ/(n·v)). The
//! transmitted direction's horizon is left to the adaptive refinement (G1 vanishes there
//! continuously).

use super::{TableSpec, TexelResult};
use crate::integrate::hemisphere::{nested_tolerances, tan_theta_h_max};
use crate::integrate::{integrate, Estimate, Tolerance};
use crate::model::btdf::{MicroNormal, RoughDielectric};
use crate::model::{Fresnel, Ndf};
use std::f64::consts::{FRAC_PI_2, PI};

/// Upper end of the warped inner variable where the range is not cut by v·h = 0.
const U_CAP: f64 = 30.0;

/// A panel boundary; `singular` marks a square-root kink there (the critical angle), which
/// the panels on either side remove by the substitution x = end ± (b − a) t².
#[derive(Clone, Copy, Debug)]
struct Break {
    x: f64,
    singular: bool,
}

/// ∫ₐᵇ f over one panel to absolute tolerance `tol`. A square-root behaviour
/// f ~ √(x − a) at a singular end becomes smooth under x = a + (b − a) t²,
/// dx = 2(b − a) t dt (likewise at b); with both ends singular the panel is halved first.
/// Without it the proportional tolerance share would bisect towards the kink down to the
/// maximum depth (a panel of width h next to it errs by ~h^1.5 ≫ tol·h).
fn panel<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: &mut F,
    a: Break,
    b: Break,
    tol: Tolerance,
) -> Estimate<N> {
    let (x0, x1) = (a.x, b.x);
    let w = x1 - x0;
    match (a.singular, b.singular) {
        (false, false) => integrate(&mut *f, x0, x1, tol),
        (true, false) => integrate(
            |t: f64| {
                let mut y = f(x0 + w * t * t);
                y.iter_mut().for_each(|v| *v *= 2.0 * w * t);
                y
            },
            0.0,
            1.0,
            tol,
        ),
        (false, true) => integrate(
            |t: f64| {
                let mut y = f(x1 - w * t * t);
                y.iter_mut().for_each(|v| *v *= 2.0 * w * t);
                y
            },
            0.0,
            1.0,
            tol,
        ),
        (true, true) => {
            let m = Break {
                x: 0.5 * (x0 + x1),
                singular: false,
            };
            let half = Tolerance {
                abs: 0.5 * tol.abs,
                ..tol
            };
            let mut e = panel(f, a, m, half);
            let r = panel(f, m, b, half);
            for c in 0..N {
                e.value[c] += r.value[c];
                e.error[c] += r.error[c];
            }
            e.evals += r.evals;
            e
        }
    }
}

/// Integrates over the panels between sorted breakpoints, sharing `tol.abs` by length.
fn panels<const N: usize, F: FnMut(f64) -> [f64; N]>(
    mut f: F,
    mut breaks: Vec<Break>,
    tol: Tolerance,
) -> Estimate<N> {
    breaks.sort_by(|a, b| a.x.total_cmp(&b.x));
    let span = breaks.last().map_or(0.0, |l| l.x) - breaks.first().map_or(0.0, |f| f.x);
    let mut total = Estimate::<N>::zero();
    if span <= 0.0 {
        return total;
    }
    for w in breaks.windows(2) {
        if w[1].x <= w[0].x {
            continue;
        }
        let e = panel(
            &mut f,
            w[0],
            w[1],
            Tolerance {
                abs: tol.abs * (w[1].x - w[0].x) / span,
                ..tol
            },
        );
        for c in 0..N {
            total.value[c] += e.value[c];
            total.error[c] += e.error[c];
        }
        total.evals += e.evals;
    }
    total
}

/// `[R, T]` at a view with n·v = `mu`, to absolute tolerance `tol` per channel.
pub fn reflect_transmit(m: &RoughDielectric, mu: f64, tol: f64) -> Estimate<2> {
    let mu = mu.min(1.0);
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let tan_v = sin_v / mu;
    let alpha = m.ndf.alpha();
    let crit = if m.eta < 1.0 {
        Some((1.0 - m.eta * m.eta).sqrt())
    } else {
        None
    };
    // budget as in `hemisphere::integrate_over_l`: half outer (over [0, π], doubled by
    // symmetry), half inner
    let (inner_tol, outer_tol) = nested_tolerances(tol);
    let inner_err = std::cell::Cell::new(0.0f64);
    let inner_evals = std::cell::Cell::new(0u64);
    let to_u = |t: f64| (t / alpha).asinh().min(U_CAP);
    let phi_integrand = |phi: f64| -> [f64; 2] {
        let cp = phi.cos();
        let u_end = if cp < 0.0 && sin_v > 0.0 {
            to_u(mu / (sin_v * -cp))
        } else {
            U_CAP
        };
        let brk = |x: f64, singular: bool| Break { x, singular };
        let mut breaks = vec![brk(0.0, false), brk(u_end, false)];
        let ur = to_u(tan_theta_h_max(tan_v, cp));
        if ur > 0.0 && ur < u_end {
            breaks.push(brk(ur, false));
        }
        if let Some(c) = crit {
            let a = (mu * mu + sin_v * sin_v * cp * cp).sqrt();
            if c < a {
                let psi = (sin_v * cp).atan2(mu);
                let d = (c / a).acos();
                for th in [psi - d, psi + d] {
                    if th > 0.0 && th < FRAC_PI_2 {
                        let u = to_u(th.tan());
                        if u > 0.0 && u < u_end {
                            breaks.push(brk(u, true));
                        }
                    }
                }
            }
        }
        // the transmitted direction's horizon n·l_t = 0 (a kink: T's G1 vanishes linearly
        // there): located by a sign scan of n·l_t on a fixed grid in u, refined by bisection
        // to rounding; two crossings within one grid step are left to the adaptive rule
        let micro = |u: f64| {
            let t = alpha * u.sinh();
            let c2 = 1.0 / (1.0 + t * t);
            let cos_h = c2.sqrt();
            let sin_h = t * cos_h;
            MicroNormal {
                n_dot_h: cos_h,
                sin2_h: sin_h * sin_h,
                v_dot_h: sin_v * sin_h * cp + mu * cos_h,
            }
        };
        let side = |u: f64| -> i8 {
            let h = micro(u);
            if h.v_dot_h <= 0.0 {
                return 0;
            }
            match m.n_dot_lt(mu, &h) {
                Some(x) if x < 0.0 => -1,
                Some(_) => 1,
                None => 0,
            }
        };
        const SCAN: usize = 48;
        let mut prev = (0.0, side(0.0));
        for k in 1..=SCAN {
            let u = u_end * k as f64 / SCAN as f64;
            let cur = (u, side(u));
            if prev.1 * cur.1 < 0 {
                let (mut lo, mut hi) = (prev.0, cur.0);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if !(mid > lo && mid < hi) {
                        break;
                    }
                    if side(mid) == prev.1 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                breaks.push(brk(0.5 * (lo + hi), false));
            }
            prev = cur;
        }
        let e = panels(
            |u: f64| {
                let t = alpha * u.sinh();
                let c2 = 1.0 / (1.0 + t * t);
                let cos_h = c2.sqrt();
                let sin_h = t * cos_h;
                let h = MicroNormal {
                    n_dot_h: cos_h,
                    sin2_h: sin_h * sin_h,
                    v_dot_h: sin_v * sin_h * cp + mu * cos_h,
                };
                // dω_h = sin θh dθh dφ, dθh/du = α cosh u cos²θh
                let jac = sin_h * alpha * u.cosh() * c2;
                let [r, tr] = m.integrands(mu, &h);
                [r * jac, tr * jac]
            },
            breaks,
            inner_tol,
        );
        inner_err.set(inner_err.get().max(e.max_error()));
        inner_evals.set(inner_evals.get() + e.evals);
        e.value
    };
    // outer panels: [0, π/2, π], plus (η < 1) the azimuths where the critical cone
    // v·h = √(1 − η²) touches the range of v·h along θh (A(φ) = √(1 − η²)): there the
    // inner integral's dependence on φ has a square-root kink
    let mut phi_breaks = vec![
        Break {
            x: 0.0,
            singular: false,
        },
        Break {
            x: FRAC_PI_2,
            singular: false,
        },
        Break {
            x: PI,
            singular: false,
        },
    ];
    if let Some(c) = crit {
        if sin_v > 0.0 && c > mu {
            let x = ((c * c - mu * mu).sqrt() / sin_v).min(1.0);
            for p in [x.acos(), PI - x.acos()] {
                if p > 0.0 && p < PI && (p - FRAC_PI_2).abs() > 1e-12 {
                    phi_breaks.push(Break {
                        x: p,
                        singular: true,
                    });
                }
            }
        }
    }
    let e = panels(phi_integrand, phi_breaks, outer_tol);
    let mut total = Estimate::<2>::zero();
    for c in 0..2 {
        total.value[c] = 2.0 * e.value[c];
        // inner errors integrate over φ ∈ [0, π], doubled
        total.error[c] = 2.0 * e.error[c] + 2.0 * PI * inner_err.get();
    }
    total.evals = inner_evals.get();
    total
}

pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    let kind = spec.model.ndf.expect("validated");
    let (ny, nz) = (axes[1].size, axes[2].size);
    let models: Vec<RoughDielectric> = (0..ny * nz)
        .map(|k| {
            let eta = match super::energy::fresnel_of_slice(spec, k / ny) {
                Fresnel::Dielectric { eta } => eta,
                _ => unreachable!("validated: an eta axis"),
            };
            RoughDielectric {
                ndf: Ndf::new(kind, axes[1].alpha(k % ny).expect("roughness axis"))
                    .expect("validated"),
                eta,
            }
        })
        .collect();
    Box::new(move |idx| {
        let e = reflect_transmit(&models[idx[2] * ny + idx[1]], axes[0].coord(idx[0]), tol);
        TexelResult {
            value: e.value.to_vec(),
            error: e.error.to_vec(),
            evals: e.evals,
        }
    })
}
