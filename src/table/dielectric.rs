//! `dielectric-btdf`: reflection and transmission albedo R, T of a rough dielectric
//! interface (GGX, separable Smith, exact Fresnel; Walter et al. 2007; the integrands are in
//! [`crate::model::btdf`]) over (cos θv; roughness; η).
//!
//! The integrals run over the micro-normal h in the hemisphere about n, with v in the
//! xz-plane and φ ∈ [0, π] doubled by symmetry; the inner variable is the lobe warp
//! u = asinh(tan θh/α) of `hemisphere.rs`. The inner range ends where v·h = 0
//! (tan θh = n·v/(sin θv (−cos φ)) for cos φ < 0) or, where h reaches the equator with
//! v·h > 0, at u = 30 (the tail of the GGX measure beyond is < 4α e^(−30)/(π n·v) < 1e-12
//! for n·v ≥ 1e-3).
//!
//! **Kinks are panel boundaries, in both variables.** Inside a panel the integrand is
//! smooth, so every panel is first integrated by nested Clenshaw–Curtis
//! ([`crate::quadrature::cc1d`], 9 to 129 nodes, geometric convergence) and only where its
//! estimate does not reach the panel's share of the tolerance by adaptive Gauss–Kronrod.
//! The inner (u) boundaries at a given φ:
//!
//! * the reflected direction's horizon n·l_r = 0 (tan θh = `tan_theta_h_max`);
//! * for η < 1, the critical angle v·h = c = √(1 − η²), where F has a square-root kink:
//!   v·h = A cos(θh − ψ), A = √((n·v)² + sin²θv cos²φ), tan ψ = sin θv cos φ/(n·v), so
//!   θh = ψ ± arccos(c/A); those panels are integrated in t with u = end ± (b − a) t²;
//! * for η < 1, the transmitted direction's horizon n·l_t = 0, in closed form: the
//!   refraction l_t = (c/η − cos θt) h − v/η (Walter eq. 40) gives v + η l_t = (c − η cos θt) h,
//!   and c > η cos θt whenever η < 1, so h = s/|s| with s = v + η l_t. For a horizontal
//!   l_t = (cos β, sin β, 0), s = (sin θv + η cos β, η sin β, n·v): the projections of
//!   these h onto the plane z = n·v lie on the circle of radius η about (sin θv, 0). The ray
//!   at azimuth φ meets it at ρ = sin θv cos φ ± √(η² − sin²θv sin²φ), tan θh = ρ/(n·v), and
//!   the point is a refraction (not total internal reflection, l_t·h < 0) iff
//!   v·l_t = sin θv (ρ cos φ − sin θv)/η < −η. For η ≥ 1, c < η cos θt always, h would be
//!   ∝ −s with n·h = −n·v < 0: no transmitted direction reaches the horizon before the
//!   equator.
//!
//! The outer (φ) boundaries are where the inner boundaries appear, vanish or cross, each a
//! kink of the inner integral as a function of φ: π/2 (v·h = 0 reaches the equator) and, for
//! η < 1, (i) where the line of azimuth φ touches the critical cone, A(φ) = c, which is also
//! where the transmitted horizon's circle is tangent to that line (sin φ = η/sin θv) and so
//! where its crossing ends; a square-root kink, integrated in t as above; (ii) where the
//! critical cone crosses the reflected horizon, l_r horizontal with v·l_r = 2c² − 1:
//! sin θv cos β = 2c² − 1, φ = atan2(sin β, sin θv + cos β); (iii) where it crosses the
//! equator, h = (cos φ, sin φ, 0): cos φ = c/sin θv.

use super::{TableSpec, TexelResult};
use crate::hemisphere::{nested_tolerances, tan_theta_h_max};
use crate::model::btdf::{integrands_many, MicroNormal, RoughDielectric};
use crate::model::{Fresnel, Ndf};
use crate::quadrature::cc1d::cc_or_adaptive;
use crate::quadrature::{Estimate, Tolerance};
use std::f64::consts::{FRAC_PI_2, PI};

/// Upper end of the warped inner variable where the range is not cut by v·h = 0.
const U_CAP: f64 = 30.0;

/// Finest nested Clenshaw–Curtis level of an inner (u) panel (129 nodes) and of an outer
/// (φ) panel, whose nodes are inner integrals (65 nodes).
const INNER_LEVEL: usize = 7;
const OUTER_LEVEL: usize = 6;

/// A panel boundary; `singular` marks a square-root kink there (the critical angle), which
/// the panels on either side remove by the substitution x = end ± (b − a) t².
#[derive(Clone, Copy, Debug)]
struct Break {
    x: f64,
    singular: bool,
}

/// ∫ₐᵇ f over one panel to absolute tolerance `tol` ([`cc_or_adaptive`] up to `level`). A
/// square-root behaviour f ~ √(x − a) at a singular end becomes smooth under
/// x = a + (b − a) t², dx = 2(b − a) t dt (likewise at b); with both ends singular the panel
/// is halved first. Without it the rule would converge only algebraically towards the kink.
fn panel<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: &mut F,
    a: Break,
    b: Break,
    tol: Tolerance,
    level: usize,
) -> Estimate<N> {
    let (x0, x1) = (a.x, b.x);
    let w = x1 - x0;
    match (a.singular, b.singular) {
        (false, false) => cc_or_adaptive(&mut *f, x0, x1, tol, level),
        (true, false) => cc_or_adaptive(
            |t: f64| {
                let mut y = f(x0 + w * t * t);
                y.iter_mut().for_each(|v| *v *= 2.0 * w * t);
                y
            },
            0.0,
            1.0,
            tol,
            level,
        ),
        (false, true) => cc_or_adaptive(
            |t: f64| {
                let mut y = f(x1 - w * t * t);
                y.iter_mut().for_each(|v| *v *= 2.0 * w * t);
                y
            },
            0.0,
            1.0,
            tol,
            level,
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
            let mut e = panel(f, a, m, half, level);
            let r = panel(f, m, b, half, level);
            for c in 0..N {
                e.value[c] += r.value[c];
                e.error[c] += r.error[c];
            }
            e.evals += r.evals;
            e
        }
    }
}

/// Most breakpoints of one integral: in u, 0, the end, the reflected horizon and 3 per η
/// (two critical-angle crossings, the transmitted horizon); in φ, 0, π, π/2 and 4 per η
/// ([`phi_breaks`]); for up to [`MAX_ETAS`] indices.
const MAX_BREAKS: usize = 3 + 4 * MAX_ETAS;

/// Most relative indices integrated together by [`reflect_transmit_etas`].
pub const MAX_ETAS: usize = 8;

/// The breakpoints of one integral in a fixed-size buffer on the stack (this runs once per
/// φ node: a growing `Vec` here cost ~8% of the bake in `realloc`).
#[derive(Clone, Copy)]
struct Breaks {
    b: [Break; MAX_BREAKS],
    len: usize,
}

impl Breaks {
    fn new() -> Breaks {
        Breaks {
            b: [Break {
                x: 0.0,
                singular: false,
            }; MAX_BREAKS],
            len: 0,
        }
    }

    fn push(&mut self, x: f64, singular: bool) {
        assert!(self.len < MAX_BREAKS, "more than {MAX_BREAKS} breakpoints");
        self.b[self.len] = Break { x, singular };
        self.len += 1;
    }

    /// Sorted by x (insertion sort: stable, no allocation, ≤ [`MAX_BREAKS`] entries).
    fn sorted(mut self) -> Breaks {
        for i in 1..self.len {
            let mut j = i;
            while j > 0 && self.b[j - 1].x > self.b[j].x {
                self.b.swap(j - 1, j);
                j -= 1;
            }
        }
        self
    }

    fn as_slice(&self) -> &[Break] {
        &self.b[..self.len]
    }
}

/// Integrates over the panels between the breakpoints. `tol.abs` is shared half by
/// length and half equally among the n non-empty panels (shares sum to `tol.abs`): by
/// length alone a short panel next to a kink, or the lobe's panel in front of the long
/// exponential tail up to u = 30, would get a tiny share and need the finest rule for
/// nothing.
fn panels<const N: usize, F: FnMut(f64) -> [f64; N]>(
    mut f: F,
    breaks: Breaks,
    tol: Tolerance,
    level: usize,
) -> Estimate<N> {
    let sorted = breaks.sorted();
    let breaks = sorted.as_slice();
    let span = breaks.last().map_or(0.0, |l| l.x) - breaks.first().map_or(0.0, |f| f.x);
    let mut total = Estimate::<N>::zero();
    if span <= 0.0 {
        return total;
    }
    let n = breaks.windows(2).filter(|w| w[1].x > w[0].x).count() as f64;
    for w in breaks.windows(2) {
        if w[1].x <= w[0].x {
            continue;
        }
        let e = panel(
            &mut f,
            w[0],
            w[1],
            Tolerance {
                abs: tol.abs * 0.5 * ((w[1].x - w[0].x) / span + 1.0 / n),
                ..tol
            },
            level,
        );
        for c in 0..N {
            total.value[c] += e.value[c];
            total.error[c] += e.error[c];
        }
        total.evals += e.evals;
    }
    total
}

/// tan θh of the micro-normal at azimuth φ (`cos_phi`, `sin_phi` ≥ 0) whose refracted
/// direction is horizontal, n·l_t = 0, if there is one (η < 1; module docs).
pub fn transmitted_horizon(
    eta: f64,
    mu: f64,
    sin_v: f64,
    cos_phi: f64,
    sin_phi: f64,
) -> Option<f64> {
    let disc = eta * eta - sin_v * sin_v * sin_phi * sin_phi;
    if eta >= 1.0 || disc < 0.0 || mu <= 0.0 {
        return None;
    }
    let q = disc.sqrt();
    [sin_v * cos_phi - q, sin_v * cos_phi + q]
        .into_iter()
        .find(|&rho| rho > 0.0 && sin_v * (rho * cos_phi - sin_v) < -eta * eta)
        .map(|rho| rho / mu)
}

/// The azimuths in (0, π) where the inner integral of `reflect_transmit` has a kink
/// (module docs), with whether it is a square-root kink; π/2 first.
pub fn phi_breaks(eta: f64, mu: f64) -> Vec<(f64, bool)> {
    let mu = mu.min(1.0);
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let mut out = vec![(FRAC_PI_2, false)];
    if eta >= 1.0 || sin_v <= 0.0 {
        return out;
    }
    let c = (1.0 - eta * eta).sqrt();
    let mut push = |p: f64, singular: bool| {
        if p > 0.0 && p < PI && (p - FRAC_PI_2).abs() > 1e-12 {
            out.push((p, singular));
        }
    };
    // (i) A(φ) = c: the critical cone touches the line of azimuth φ
    if c > mu {
        let x = ((c * c - mu * mu).sqrt() / sin_v).min(1.0);
        push(x.acos(), true);
        push(PI - x.acos(), true);
    }
    // (ii) the critical cone meets the reflected horizon
    let cb = (2.0 * c * c - 1.0) / sin_v;
    if cb.abs() < 1.0 {
        push((1.0 - cb * cb).sqrt().atan2(sin_v + cb), false);
    }
    // (iii) the critical cone meets the equator
    if c < sin_v {
        push((c / sin_v).acos(), false);
    }
    out
}

/// `[R, T]` at a view with n·v = `mu`, to absolute tolerance `tol` per channel.
pub fn reflect_transmit(m: &RoughDielectric, mu: f64, tol: f64) -> Estimate<2> {
    reflect_transmit_etas::<2>(&m.ndf, &[m.eta], mu, tol)
}

/// `[R, T]` for several relative indices `etas` at once (at most [`MAX_ETAS`], and
/// `2·etas.len() ≤ N`): channels `2k`, `2k + 1` are R and T of `etas[k]` (those beyond
/// `2·etas.len()` are 0), each to absolute tolerance `tol` with its own error estimate. One
/// nested rule serves them all: its panel boundaries are the union of every index's kinks
/// (for η ≥ 1 they are the same for all: the reflected horizon and π/2), a panel is refined
/// until every channel meets its share, and every node computes what does not depend on η
/// once ([`integrands_many`]). `evals` counts the u nodes, once however many indices they
/// serve.
pub fn reflect_transmit_etas<const N: usize>(
    ndf: &Ndf,
    etas: &[f64],
    mu: f64,
    tol: f64,
) -> Estimate<N> {
    assert!(
        etas.len() <= MAX_ETAS && 2 * etas.len() <= N,
        "{} indices in {N} channels",
        etas.len()
    );
    let mu = mu.min(1.0);
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let tan_v = sin_v / mu;
    let alpha = ndf.alpha();
    // budget as in `hemisphere::integrate_over_l`: half outer, half inner; the outer
    // integral over [0, π] is doubled by symmetry, so it gets half the outer share
    let (inner_tol, outer_whole) = nested_tolerances(tol);
    let outer_tol = Tolerance {
        abs: outer_whole.abs / 2.0,
        ..outer_whole
    };
    // per channel: the largest inner estimate over the φ nodes
    let inner_err = std::cell::Cell::new([0.0f64; N]);
    let inner_evals = std::cell::Cell::new(0u64);
    let to_u = |t: f64| (t / alpha).asinh().min(U_CAP);
    let g1v = ndf.g1(mu);
    let phi_integrand = |phi: f64| -> [f64; N] {
        let (sp, cp) = phi.sin_cos();
        let u_end = if cp < 0.0 && sin_v > 0.0 {
            to_u(mu / (sin_v * -cp))
        } else {
            U_CAP
        };
        let mut breaks = Breaks::new();
        breaks.push(0.0, false);
        breaks.push(u_end, false);
        let mut inside = |u: f64, singular: bool| {
            if u > 0.0 && u < u_end {
                breaks.push(u, singular);
            }
        };
        inside(to_u(tan_theta_h_max(tan_v, cp)), false);
        for &eta in etas.iter().filter(|&&eta| eta < 1.0) {
            let c = (1.0 - eta * eta).sqrt();
            let a = (mu * mu + sin_v * sin_v * cp * cp).sqrt();
            if c < a {
                let psi = (sin_v * cp).atan2(mu);
                let d = (c / a).acos();
                for th in [psi - d, psi + d] {
                    if th > 0.0 && th < FRAC_PI_2 {
                        inside(to_u(th.tan()), true);
                    }
                }
            }
            // the transmitted direction's horizon (a kink: T's G1 vanishes linearly there)
            if let Some(t) = transmitted_horizon(eta, mu, sin_v, cp, sp) {
                inside(to_u(t), false);
            }
        }
        let e = panels(
            |u: f64| {
                // sinh u and cosh u from one exp_m1 (u ≥ 0; no cancellation: sinh u =
                // (e + e/(1 + e))/2 with e = eᵘ − 1)
                let e = u.exp_m1();
                let inv = 1.0 / (1.0 + e);
                let (sinh_u, cosh_u) = (0.5 * (e + e * inv), 0.5 * (1.0 + e + inv));
                let t = alpha * sinh_u;
                let c2 = 1.0 / (1.0 + t * t);
                let cos_h = c2.sqrt();
                let sin_h = t * cos_h;
                let h = MicroNormal {
                    n_dot_h: cos_h,
                    sin2_h: sin_h * sin_h,
                    v_dot_h: sin_v * sin_h * cp + mu * cos_h,
                };
                // dω_h = sin θh dθh dφ, dθh/du = α cosh u cos²θh
                let jac = sin_h * alpha * cosh_u * c2;
                let mut y = integrands_many::<N>(ndf, etas, mu, g1v, &h);
                for v in y.iter_mut() {
                    *v *= jac;
                }
                y
            },
            breaks,
            inner_tol,
            INNER_LEVEL,
        );
        let mut ie = inner_err.get();
        for (m, &x) in ie.iter_mut().zip(&e.error) {
            *m = m.max(x);
        }
        inner_err.set(ie);
        inner_evals.set(inner_evals.get() + e.evals);
        e.value
    };
    let mut breaks = Breaks::new();
    breaks.push(0.0, false);
    breaks.push(PI, false);
    breaks.push(FRAC_PI_2, false);
    for &eta in etas {
        // (π/2, every index's first break, once)
        for (x, singular) in phi_breaks(eta, mu).into_iter().skip(1) {
            breaks.push(x, singular);
        }
    }
    let e = panels(phi_integrand, breaks, outer_tol, OUTER_LEVEL);
    let inner_err = inner_err.get();
    Estimate {
        value: e.value.map(|v| 2.0 * v),
        // inner errors integrate over φ ∈ [0, π], doubled
        error: std::array::from_fn(|c| 2.0 * e.error[c] + 2.0 * PI * inner_err[c]),
        evals: inner_evals.get(),
    }
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

/// Most indices per shared rule in a table's fibre (channels R, T each: 8 channels).
const FIBRE_ETAS: usize = 4;

/// How the slices of one fibre (fixed μ and roughness, every η) are grouped into shared
/// rules ([`reflect_transmit_etas`]): the η ≥ 1 slices, whose breakpoints are all the same,
/// in groups of up to `FIBRE_ETAS` consecutive slices; each η < 1 slice alone, since its
/// breakpoints (critical angle, transmitted horizon) depend on η and the union of several
/// slices' breakpoints costs more nodes than it shares (measured on the `dielectric-btdf`
/// preset, `examples/fibre_check.rs union`: its four η < 1 slices as one rule 37,340 nodes
/// per fibre against 29,707 for the four alone, and about twice the CPU time, each node then
/// serving 8 channels; BENCHMARKS.md, fib6). Returns slice indices per group, in slice order.
pub fn fibre_groups(etas: &[f64]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut open: Option<usize> = None;
    for (z, &eta) in etas.iter().enumerate() {
        if eta < 1.0 {
            groups.push(vec![z]);
            open = None;
            continue;
        }
        match open {
            Some(g) if groups[g].len() < FIBRE_ETAS => groups[g].push(z),
            _ => {
                open = Some(groups.len());
                groups.push(vec![z]);
            }
        }
    }
    groups
}

/// `[R, T]` of every slice of one fibre: `etas` at one view `mu` and one NDF, grouped by
/// [`fibre_groups`]; per slice its values, its own error estimates and the evaluations of
/// its group (counted at the group's first slice, 0 at the others).
pub fn reflect_transmit_fibre(
    ndf: &Ndf,
    etas: &[f64],
    mu: f64,
    tol: f64,
) -> Vec<([f64; 2], [f64; 2], u64)> {
    let mut out = vec![([0.0; 2], [0.0; 2], 0); etas.len()];
    for g in fibre_groups(etas) {
        let group: Vec<f64> = g.iter().map(|&z| etas[z]).collect();
        let (value, error, evals): (Vec<f64>, Vec<f64>, u64) = if group.len() == 1 {
            let e = reflect_transmit_etas::<2>(ndf, &group, mu, tol);
            (e.value.to_vec(), e.error.to_vec(), e.evals)
        } else {
            let e = reflect_transmit_etas::<{ 2 * FIBRE_ETAS }>(ndf, &group, mu, tol);
            (e.value.to_vec(), e.error.to_vec(), e.evals)
        };
        for (k, &z) in g.iter().enumerate() {
            out[z] = (
                [value[2 * k], value[2 * k + 1]],
                [error[2 * k], error[2 * k + 1]],
                if k == 0 { evals } else { 0 },
            );
        }
    }
    out
}

/// The fibre path of a `dielectric-btdf` table ([`super::FibreFn`]): every η slice of one
/// (μ, roughness) pair by [`reflect_transmit_fibre`].
pub(crate) fn fibre_fn(spec: &TableSpec) -> super::FibreFn {
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    let kind = spec.model.ndf.expect("validated");
    let ndfs: Vec<Ndf> = (0..axes[1].size)
        .map(|j| Ndf::new(kind, axes[1].alpha(j).expect("roughness axis")).expect("validated"))
        .collect();
    let etas: Vec<f64> = (0..axes[2].size)
        .map(|z| match super::energy::fresnel_of_slice(spec, z) {
            Fresnel::Dielectric { eta } => eta,
            _ => unreachable!("validated: an eta axis"),
        })
        .collect();
    Box::new(move |i, j| {
        reflect_transmit_fibre(&ndfs[j], &etas, axes[0].coord(i), tol)
            .into_iter()
            .map(|(value, error, evals)| TexelResult {
                value: value.to_vec(),
                error: error.to_vec(),
                evals,
            })
            .collect()
    })
}
