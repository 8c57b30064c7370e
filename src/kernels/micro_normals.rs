//! Integrals over the micro-normals h of a GGX surface seen from a view v: the nested rule
//! of the dielectric kinds (`dielectric-btdf`, `dielectric-albedo`), of the `schlick-weight`
//! kind and of the `karis-f82` dfg channel, whose integrands are all of the form
//! D(h)·(factors of v·h, the reflected and refracted directions)·c/(n·v) with kinks only
//! where this rule puts panel boundaries ([`integrate_micro_normals`]); and of the roughness
//! fibres ([`crate::kernels::roughness_fibre`]), several such lobes at once.
//!
//! The integrals run over the micro-normal h in the hemisphere about n, with v in the
//! xz-plane and φ ∈ [0, π] doubled by symmetry; the inner variable is the lobe warp
//! u = asinh(tan θh/α) of `hemisphere.rs`, and in integrals without a critical angle
//! (no η < 1) or with several lobes (`Rule::alphas`) θh itself beyond θh = 45°
//! (`ThetaTail`: there the integrand is smooth in θh and decays like e^(−u) in u). The
//! inner range ends where v·h = 0 (tan θh = n·v/(sin θv (−cos φ)) for cos φ < 0) or,
//! where h reaches the equator with v·h > 0, at the equator itself (θ-tail) or at u = 30 or
//! beyond where a grazing view or a tight tolerance needs it (`u_cap`: the tail left out is
//! below 1e-3 of the tolerance).
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
//!   θh = ψ ± arccos(c/A); those panels are integrated in t with u = end ± (b − a) t², and
//!   so is a panel with smooth ends that has such a point s within half its length outside
//!   it, about s (`panels_reaching`, `NEAR_REACH`);
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
//! kink of the inner integral as a function of φ: π/2 (v·h = 0 reaches the equator); at a
//! view grazing on the lobe's scale, x = n·v/(α sin θv) < 1, also −cos φ = x, where that end
//! has fallen to tan θh = α (`layer_cosine`: beyond π/2 the end drops from the equator to the
//! lobe within Δφ ≈ x, a layer the rule does not see from π/2 alone); and, for
//! η < 1, (i) where the line of azimuth φ touches the critical cone, A(φ) = c, which is also
//! where the transmitted horizon's circle is tangent to that line (sin φ = η/sin θv) and so
//! where its crossing ends; a square-root kink, integrated in t as above; (ii) where the
//! critical cone crosses the reflected horizon, l_r horizontal with v·l_r = 2c² − 1:
//! sin θv cos β = 2c² − 1, φ = atan2(sin β, sin θv + cos β); (iii) where it crosses the
//! equator, h = (cos φ, sin φ, 0): cos φ = c/sin θv, where the inner integral goes like
//! |φ − φ₃|^(3/2) (the square-root kink enters at the range's end), also integrated in t.

use crate::hemisphere::{nested_tolerances, tan_theta_h_max};
use crate::model::btdf::MicroNormal;
use crate::model::Ndf;
use crate::quadrature::cc1d::{cc_or_adaptive_into, Estimator};
use crate::quadrature::{Estimate, Tolerance};
use std::f64::consts::{FRAC_PI_2, PI};

/// How near (in panel lengths) a square-root break outside a panel must be for the panel to
/// be integrated about it ([`panels_reaching`]). The transmitted horizon often lies just past
/// the critical angle (there l_t grazes the micro-surface and swings away from it as fast as
/// √(c − c_crit)), so the panel that begins there has the critical angle's branch point a
/// small fraction of its length away (2e-3 of it seen at η = 0.75, α = 0.54; that panel
/// then took 129 nodes or the adaptive fallback instead of 33): measured on the `eevee-btdf-split-sum-ggx`
/// preset (every 5th texel per axis), 0.5 takes 19% fewer nodes than none, 1 and 2 about
/// as many (18%, 14%).
const NEAR_REACH: f64 = 0.5;

/// Upper end of the warped inner variable where the range is not cut by v·h = 0.
const U_CAP: f64 = 30.0;

/// Finest nested Clenshaw–Curtis level of an inner (u) panel (129 nodes) and of an outer
/// (φ) panel, whose nodes are inner integrals (65 nodes).
const INNER_LEVEL: usize = 7;
const OUTER_LEVEL: usize = 6;

/// A panel boundary; `singular` marks a square-root kink there (the critical angle), which
/// the panels on either side remove by the substitution x = end ± (b − a) t².
#[derive(Clone, Copy, Debug)]
pub(crate) struct Break {
    pub x: f64,
    pub singular: bool,
}

/// ∫ₐᵇ f over one panel to absolute tolerance `tol` ([`cc_or_adaptive_into`] up to `level`;
/// `f` writes its values into the slot it is given). A
/// square-root behaviour f ~ √(x − a) at a singular end becomes smooth under
/// x = a + (b − a) t², dx = 2(b − a) t dt (likewise at b); with both ends singular the panel
/// is halved first. Without it the rule would converge only algebraically towards the kink.
fn panel<const N: usize, F: FnMut(f64, &mut [f64; N])>(
    f: &mut F,
    a: Break,
    b: Break,
    tol: Tolerance,
    level: usize,
    est: Estimator,
) -> Estimate<N> {
    let (x0, x1) = (a.x, b.x);
    let w = x1 - x0;
    match (a.singular, b.singular) {
        (false, false) => cc_or_adaptive_into(&mut *f, x0, x1, tol, level, est),
        (true, false) => cc_or_adaptive_into(
            |t: f64, y: &mut [f64; N]| {
                f(x0 + w * t * t, y);
                y.iter_mut().for_each(|v| *v *= 2.0 * w * t);
            },
            0.0,
            1.0,
            tol,
            level,
            est,
        ),
        (false, true) => cc_or_adaptive_into(
            |t: f64, y: &mut [f64; N]| {
                f(x1 - w * t * t, y);
                y.iter_mut().for_each(|v| *v *= 2.0 * w * t);
            },
            0.0,
            1.0,
            tol,
            level,
            est,
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
            let mut e = panel(f, a, m, half, level, est);
            let r = panel(f, m, b, half, level, est);
            for c in 0..N {
                e.value[c] += r.value[c];
                e.error[c] += r.error[c];
            }
            e.evals += r.evals;
            e
        }
    }
}

/// ∫ₐᵇ f over a panel with a square-root point `s` outside it (s ≤ a or s ≥ b) but near
/// it: f = g + √|x − s| h with g, h analytic about s, so on [a, b] f is analytic but its
/// Chebyshev series converges only like ρ⁻ⁿ with ρ − 1 ~ √(8 d/(b − a)), d the distance
/// of s from the panel. Under x = s + (b − s) t² (s ≤ a; mirrored for s ≥ b) the point
/// is no longer singular, for t ∈ [√((a − s)/(b − s)), 1].
fn panel_about<const N: usize, F: FnMut(f64, &mut [f64; N])>(
    f: &mut F,
    s: f64,
    a: f64,
    b: f64,
    tol: Tolerance,
    level: usize,
    est: Estimator,
) -> Estimate<N> {
    // x = s + sign w t², dx = 2 w t dt in the direction of increasing t
    let (w, sign, t0) = if s <= a {
        (b - s, 1.0, ((a - s) / (b - s)).sqrt())
    } else {
        (s - a, -1.0, ((s - b) / (s - a)).sqrt())
    };
    cc_or_adaptive_into(
        |t: f64, y: &mut [f64; N]| {
            f(s + sign * w * t * t, y);
            y.iter_mut().for_each(|v| *v *= 2.0 * w * t);
        },
        t0,
        1.0,
        tol,
        level,
        est,
    )
}

/// Most breakpoints of one integral: in u, 0, the end, the reflected horizon, the view peak
/// and 3 per η (two critical-angle crossings, the transmitted horizon); in φ, 0, π, π/2 and
/// 4 per η ([`phi_breaks`]); for up to [`MAX_ETAS`] indices.
const MAX_BREAKS: usize = 4 + 4 * MAX_ETAS;

/// Most relative indices whose kinks one integral takes ([`integrate_micro_normals`]).
pub const MAX_ETAS: usize = 8;

/// The breakpoints of one integral in a fixed-size buffer on the stack (this runs once per
/// φ node: a growing `Vec` here cost ~8% of the bake in `realloc`).
#[derive(Clone, Copy)]
pub(crate) struct Breaks {
    b: [Break; MAX_BREAKS],
    len: usize,
}

impl Breaks {
    pub fn new() -> Breaks {
        Breaks {
            b: [Break {
                x: 0.0,
                singular: false,
            }; MAX_BREAKS],
            len: 0,
        }
    }

    pub fn push(&mut self, x: f64, singular: bool) {
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
pub(crate) fn panels<const N: usize, F: FnMut(f64) -> [f64; N]>(
    mut f: F,
    breaks: Breaks,
    tol: Tolerance,
    level: usize,
    est: Estimator,
) -> Estimate<N> {
    panels_reaching(
        |x, y: &mut [f64; N]| *y = f(x),
        breaks,
        tol,
        level,
        est,
        0.0,
    )
}

/// [`panels`] where a panel with no square-root end but a square-root break outside it
/// closer than `reach` times its length is integrated in the variable of [`panel_about`]
/// about the nearest such break (`reach` 0: never). `f` writes its values into the slot it
/// is given.
pub(crate) fn panels_reaching<const N: usize, F: FnMut(f64, &mut [f64; N])>(
    mut f: F,
    breaks: Breaks,
    tol: Tolerance,
    level: usize,
    est: Estimator,
    reach: f64,
) -> Estimate<N> {
    let sorted = breaks.sorted();
    let breaks = sorted.as_slice();
    let span = breaks.last().map_or(0.0, |l| l.x) - breaks.first().map_or(0.0, |f| f.x);
    let mut total = Estimate::<N>::zero();
    if span <= 0.0 {
        return total;
    }
    let n = breaks.windows(2).filter(|w| w[1].x > w[0].x).count() as f64;
    for (k, w) in breaks.windows(2).enumerate() {
        if w[1].x <= w[0].x {
            continue;
        }
        let ptol = Tolerance {
            abs: tol.abs * 0.5 * ((w[1].x - w[0].x) / span + 1.0 / n),
            ..tol
        };
        let len = w[1].x - w[0].x;
        let e = if reach > 0.0 {
            // the nearest square-root points at or beyond each end
            let left = breaks[..=k].iter().rev().find(|b| b.singular).map(|b| b.x);
            let right = breaks[k + 1..].iter().find(|b| b.singular).map(|b| b.x);
            let near = |s: Option<f64>, d: f64| s.filter(|_| d < reach * len);
            let sl = near(left, left.map_or(f64::INFINITY, |s| w[0].x - s));
            let sr = near(right, right.map_or(f64::INFINITY, |s| s - w[1].x));
            match (sl, sr) {
                (Some(sl), Some(sr)) => {
                    let m = 0.5 * (w[0].x + w[1].x);
                    let half = Tolerance {
                        abs: 0.5 * ptol.abs,
                        ..ptol
                    };
                    let mut e = panel_about(&mut f, sl, w[0].x, m, half, level, est);
                    let r = panel_about(&mut f, sr, m, w[1].x, half, level, est);
                    for c in 0..N {
                        e.value[c] += r.value[c];
                        e.error[c] += r.error[c];
                    }
                    e.evals += r.evals;
                    e
                }
                (Some(s), None) | (None, Some(s)) => {
                    panel_about(&mut f, s, w[0].x, w[1].x, ptol, level, est)
                }
                (None, None) => panel(&mut f, w[0], w[1], ptol, level, est),
            }
        } else {
            panel(&mut f, w[0], w[1], ptol, level, est)
        };
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
    out.extend(cone_phi_breaks(c, mu, sin_v, true));
    out
}

/// The azimuths in (0, π), other than π/2, where an inner integral whose integrand has a
/// kink on the cone v·h = `c` about the view (the critical cone of η < 1, c = √(1 − η²), or
/// a [`Rule::cones`] cosine) has a kink, with whether it is a square-root kink.
/// `sqrt_kink`: whether the kink on the cone is a square-root one (the critical angle) or
/// plain.
fn cone_phi_breaks(c: f64, mu: f64, sin_v: f64, sqrt_kink: bool) -> Vec<(f64, bool)> {
    let mut out = Vec::new();
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
    // (iii) the critical cone meets the equator: with a square-root kink on the cone, the
    // inner integral's part near the equator goes like |φ − φ₃|^(3/2) there, which the
    // panel beside it converges on only algebraically and with estimates that can fall
    // below its error (on Cycles' glass_inv_E grid at tolerance 1e-7: 6 of 4,096 texels,
    // errors up to 9.4e-8 against estimates of 2–3e-8, η = 0.965, α ≥ 0.75;
    // examples/glass_probe.rs), so it is a square-root end (none over their estimates)
    if c < sin_v {
        push((c / sin_v).acos(), sqrt_kink);
    }
    out
}

/// tan θh of the micro-normals at azimuth φ (`cos_phi`) on the cone v·h = `c` about a view
/// with n·v = `mu` (θh in (0, π/2)): θh = ψ ± arccos(c/A), tan ψ = sin θv cos φ/μ,
/// A = √(μ² + sin²θv cos²φ) (h = (sin θh cos φ, sin θh sin φ, cos θh) has
/// v·h = A cos(θh − ψ)).
fn cone_tan_theta_h(c: f64, mu: f64, sin_v: f64, cos_phi: f64) -> [Option<f64>; 2] {
    let a = (mu * mu + sin_v * sin_v * cos_phi * cos_phi).sqrt();
    if c >= a {
        return [None, None];
    }
    let psi = (sin_v * cos_phi).atan2(mu);
    let d = (c / a).acos();
    [psi - d, psi + d].map(|th| (th > 0.0 && th < FRAC_PI_2).then(|| th.tan()))
}

/// The end of the warped inner variable u = asinh(tan θh/α) where the range is not cut by
/// v·h = 0: [`U_CAP`], or further where a grazing view or a tight tolerance needs it. Every
/// integrand of this module is bounded by the visible-normal measure
/// D G1(v) c/(n·v) dω_h ≤ D dω_h/(n·v). For GGX with x = tan θh, D dω_h =
/// 2α² x √(1 + x²)/(α² + x²)² dx over the azimuth, and with √(1 + x²) ≤ 1 + x the part
/// beyond x = T = α sinh u is at most α²/(α² + T²) + 2α atan(α/T) = 1/cosh²u +
/// 2α atan(1/sinh u) ≤ (4 + 4.01 α) e^(−u) for u ≥ 4. So the part left out is below
/// 1e-3·`tol` once u ≥ ln((4 + 4.01 α)/(1e-3·tol·n·v)). (For the default tolerances, α ≤ 1
/// and views ≥ 1e-3 that is below 30, which stays the end: those tables keep their bits.)
fn u_cap(alpha: f64, mu: f64, tol: f64) -> f64 {
    let need = ((4.0 + 4.01 * alpha) / (1e-3 * tol * mu)).ln();
    if need.is_finite() {
        U_CAP.max(need)
    } else {
        U_CAP
    }
}

/// −cos φ of the azimuth beyond π/2 where the end of the inner range, v·h = 0 at
/// tan θh = n·v/(sin θv (−cos φ)), reaches the lobe's scale tan θh = α: x = n·v/(α sin θv),
/// if below 1 (module docs). Between π/2 (end at the equator) and there the end falls from
/// the equator to the lobe within Δφ ≈ x, a layer the panel from π/2 does not resolve when x
/// is small: at n·v = 1e-4 (Cycles' clamp) and height-correlated masking its rule erred by up
/// to 5.4e-7 with estimates of 4.3e-7 (`examples/glass_probe.rs`).
fn layer_cosine(alpha: f64, mu: f64, sin_v: f64) -> Option<f64> {
    let x = mu / (alpha * sin_v);
    (x > 0.0 && x < 1.0).then_some(x)
}

/// tan θh where the lobe variable u hands over to θh itself ([`ThetaTail`]): θh = 45°.
const TAIL_TAN: f64 = 1.0;

/// The inner variable of an integral without a critical angle: the lobe warp
/// u = asinh(tan θh/α) up to θh = 45° (tan θh = [`TAIL_TAN`], u = `s`), and beyond it θh
/// itself, θh = 45° + k (σ − s), up to the equator (σ = s + (π/4)/k). Beyond the lobe's
/// scale the integrand is smooth in θh (D sin θh → α²/(π sin³θh) for tan θh ≫ α) but
/// decays like e^(−u) in u, over the long panel from u ≈ ln(2/α) to 30 that took 33 to 65
/// nodes; in θh it takes 9 to 17 (`examples/schlick_probe.rs`: 28% fewer nodes on EEVEE's
/// `btdf_ggx` grid), and the range ends at the equator itself, so nothing is cut off.
/// k = dθh/du at the hand-over, α cosh s/(1 + tan²) = √(1 + α²)/2, makes the Jacobian
/// continuous there, so the node at σ = s has the same value for both panels beside it.
#[derive(Clone, Copy, Debug)]
struct ThetaTail {
    alpha: f64,
    /// u at the hand-over
    s: f64,
    /// dθh/dσ beyond it
    k: f64,
}

impl ThetaTail {
    fn new(alpha: f64) -> ThetaTail {
        ThetaTail {
            alpha,
            s: (TAIL_TAN / alpha).asinh(),
            k: alpha * (1.0 + (TAIL_TAN / alpha).powi(2)).sqrt() / (1.0 + TAIL_TAN * TAIL_TAN),
        }
    }

    /// σ at the equator.
    fn end(self) -> f64 {
        self.s + (FRAC_PI_2 - TAIL_TAN.atan()) / self.k
    }

    /// σ at x = tan θh (∞ at the equator).
    fn of(self, x: f64) -> f64 {
        if x <= TAIL_TAN {
            (x / self.alpha).asinh()
        } else {
            self.s + (x.atan() - TAIL_TAN.atan()) / self.k
        }
    }

    /// `(cos θh, sin θh, sin θh dθh/dσ)` at σ > s (θh at most π/2, where cos θh = 6e-17 > 0
    /// keeps D at its limit α²/π).
    fn at(self, sigma: f64) -> (f64, f64, f64) {
        let th = (TAIL_TAN.atan() + self.k * (sigma - self.s)).min(FRAC_PI_2);
        let (sin_h, cos_h) = th.sin_cos();
        (cos_h, sin_h, sin_h * self.k)
    }
}

/// What [`integrate_micro_normals`] puts panel boundaries at, and how its panels estimate
/// their error.
#[derive(Clone, Copy, Debug)]
pub struct Rule<'a> {
    /// The relative indices whose kinks (η < 1: the critical angle, the transmitted
    /// direction's horizon) the integrand has (at most [`MAX_ETAS`]).
    pub etas: &'a [f64],
    /// Cosines c where the integrand has a (plain) kink on the cone v·h = c about the view
    /// (at most [`MAX_ETAS`] − `etas.len()`): the clamp of the normalized dielectric weight
    /// at F(c; η) = F0 for η ≳ 3.7 (`schlick-weight-*`).
    pub cones: &'a [f64],
    /// Whether the integrand has a non-analytic factor of 1 − v·h (panel ends where v·h
    /// peaks along each azimuth).
    pub view_peak: bool,
    /// The error estimate of every panel's nested Clenshaw–Curtis rule.
    pub estimator: Estimator,
    /// The roughnesses of an integrand that carries several lobes (a fibre along the
    /// roughness axis; empty: the NDF's own). The rule's variable is the warp of the NDF
    /// passed, which should be the narrowest; the lobes' grazing-view layers get panel
    /// breaks (`layer_cosine`: the widest lobe's, then each where x has doubled), and the
    /// range ends at the equator by the θ-tail (`ThetaTail`, also with a critical angle:
    /// beyond the narrow lobe's scale the wide lobes are smooth in θh, not in its u).
    pub alphas: &'a [f64],
}

impl<'a> Rule<'a> {
    /// The kinks of `etas`, no view peak, the standard estimate (`dielectric-btdf`).
    pub fn standard(etas: &'a [f64]) -> Rule<'a> {
        Rule {
            etas,
            cones: &[],
            view_peak: false,
            estimator: Estimator::Standard,
            alphas: &[],
        }
    }
}

/// `∫ g(h) dω_h` over the micro-normals h of the upper hemisphere with v·h > 0, for a view
/// with n·v = `mu`, to absolute tolerance `tol` per channel: the nested rule of the module
/// docs. `g` is the integrand per unit solid angle of h (given n·h, sin²θh and v·h); it may
/// have kinks only where this rule puts panel boundaries: the reflected direction's horizon
/// and, for every relative index in `etas` below 1, the critical angle and the transmitted
/// direction's horizon (indices ≥ 1 add none). With `view_peak`, also where v·h peaks along
/// each line of azimuth (θh = ψ, tan ψ = tan θv cos φ, for cos φ > 0), as a square-root end
/// (the panels beside it are integrated in t, u = end ± (b − a) t²): for integrands with a
/// non-analytic factor of 1 − v·h, such as the generalized Schlick weight (1 − v·h)^e of a
/// non-integer e, whose singular point h = v lies on the line φ = 0. `evals` counts the
/// inner nodes.
pub fn integrate_micro_normals<const N: usize, G: Fn(&MicroNormal) -> [f64; N]>(
    ndf: &Ndf,
    rule: Rule,
    mu: f64,
    tol: f64,
    g: G,
) -> Estimate<N> {
    integrate_micro_normals_into(ndf, rule, mu, tol, |h: &MicroNormal, y: &mut [f64; N]| {
        *y = g(h)
    })
}

/// [`integrate_micro_normals`] whose integrand writes its values into the slot it is given
/// (zeroed), so that many channels (a roughness fibre's) are not copied on the way to the
/// rule ([`crate::quadrature::cc1d::nested_cc_into`]); the same arithmetic, the same bits.
pub fn integrate_micro_normals_into<const N: usize, G: Fn(&MicroNormal, &mut [f64; N])>(
    ndf: &Ndf,
    rule: Rule,
    mu: f64,
    tol: f64,
    g: G,
) -> Estimate<N> {
    let Rule {
        etas,
        cones,
        view_peak,
        estimator,
        alphas,
    } = rule;
    assert!(
        etas.len() + cones.len() <= MAX_ETAS,
        "{} indices and {} cones",
        etas.len(),
        cones.len()
    );
    let mu = mu.min(1.0);
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let tan_v = sin_v / mu;
    let alpha = ndf.alpha();
    let cap = u_cap(alpha, mu, tol);
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
    // (only with a critical angle: the other integrals keep their bits)
    let critical = etas.iter().any(|&eta| eta < 1.0);
    let reach = if critical { NEAR_REACH } else { 0.0 };
    // without a critical angle or with several lobes, beyond θh = 45° in the θ-tail
    // variable ([`ThetaTail`])
    let tail = (!critical || !alphas.is_empty()).then(|| ThetaTail::new(alpha));
    let cap = tail.map_or(cap, ThetaTail::end);
    let to_u = |x: f64| match tail {
        Some(t) => t.of(x),
        None => (x / alpha).asinh().min(cap),
    };
    let phi_integrand = |phi: f64| -> [f64; N] {
        let (sp, cp) = phi.sin_cos();
        let u_end = if cp < 0.0 && sin_v > 0.0 {
            to_u(mu / (sin_v * -cp))
        } else {
            cap
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
        if let Some(t) = tail {
            inside(t.s, false);
        }
        if view_peak && cp > 0.0 {
            inside(to_u(tan_v * cp), true);
        }
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
        for &c in cones {
            for t in cone_tan_theta_h(c, mu, sin_v, cp).into_iter().flatten() {
                inside(to_u(t), false);
            }
        }
        let e = panels_reaching(
            |u: f64, y: &mut [f64; N]| {
                let (cos_h, sin_h, jac) = match tail {
                    Some(t) if u > t.s => t.at(u),
                    _ => {
                        // sinh u and cosh u from e = eᵘ − 1 (u ≥ 0; no cancellation: sinh u =
                        // (e + e/(1 + e))/2); below u = 1 by exp_m1, above it by exp, where
                        // the subtraction loses at most one bit of e ≥ 1.7 and glibc's exp
                        // costs less than half its exp_m1 (`perf` of eevee-bsdf-ggx: exp_m1
                        // 13% of the time before, exp 5% and exp_m1 2% after)
                        let e = if u < 1.0 { u.exp_m1() } else { u.exp() - 1.0 };
                        let inv = 1.0 / (1.0 + e);
                        let (sinh_u, cosh_u) = (0.5 * (e + e * inv), 0.5 * (1.0 + e + inv));
                        let t = alpha * sinh_u;
                        let c2 = 1.0 / (1.0 + t * t);
                        let cos_h = c2.sqrt();
                        let sin_h = t * cos_h;
                        // dω_h = sin θh dθh dφ, dθh/du = α cosh u cos²θh
                        (cos_h, sin_h, sin_h * alpha * cosh_u * c2)
                    }
                };
                let h = MicroNormal {
                    n_dot_h: cos_h,
                    sin2_h: sin_h * sin_h,
                    v_dot_h: sin_v * sin_h * cp + mu * cos_h,
                };
                g(&h, y);
                for v in y.iter_mut() {
                    *v *= jac;
                }
            },
            breaks,
            inner_tol,
            INNER_LEVEL,
            estimator,
            reach,
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
    // the boundary layer beyond π/2 at a view grazing on the lobe's scale (module docs)
    // (a fibre's lobes: the widest lobe's, then only where x has doubled since the last
    // break, a layer that the panel beside the last break resolves as well as its own)
    let mut xs: Vec<f64> = std::iter::once(alpha)
        .chain(alphas.iter().copied())
        .filter_map(|a| layer_cosine(a, mu, sin_v))
        .collect();
    xs.sort_by(f64::total_cmp);
    let mut last = 0.0;
    for x in xs {
        if x > 2.0 * last {
            breaks.push(PI - x.acos(), false);
            last = x;
        }
    }
    for &eta in etas {
        // (π/2, every index's first break, once)
        for (x, singular) in phi_breaks(eta, mu).into_iter().skip(1) {
            breaks.push(x, singular);
        }
    }
    for &c in cones {
        for (x, singular) in cone_phi_breaks(c, mu, sin_v, false) {
            breaks.push(x, singular);
        }
    }
    let e = panels_reaching(
        |phi, y: &mut [f64; N]| *y = phi_integrand(phi),
        breaks,
        outer_tol,
        OUTER_LEVEL,
        estimator,
        reach,
    );
    let inner_err = inner_err.get();
    Estimate {
        value: e.value.map(|v| 2.0 * v),
        // inner errors integrate over φ ∈ [0, π], doubled
        error: std::array::from_fn(|c| 2.0 * e.error[c] + 2.0 * PI * inner_err[c]),
        evals: inner_evals.get(),
    }
}
