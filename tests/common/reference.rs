//! An independent high-precision reference for the accuracy tests.
//!
//! Nothing here uses `brdfbake::integrate`. The method is deliberately different from the
//! library's (half-vector parameterization, asinh lobe warp, exact horizon in θh, adaptive
//! Gauss–Kronrod K15/G7):
//!
//! * 1D rule: Gauss–Legendre of order [`GL_ORDER`] with nodes computed here by Newton's
//!   method on the Legendre recurrence; a panel is accepted when the rule on the whole
//!   panel and the sum of the rule on its two halves agree to the panel's share of the
//!   tolerance (share ∝ width), otherwise both halves are refined recursively. For an
//!   analytic integrand the two-halves sum is ~2^(−2n) more accurate than the whole-panel
//!   value, so the difference is a (very) conservative estimate of the kept value's error.
//! * Hemisphere of reflected directions: **l-space** polar coordinates about the normal,
//!   `l = (sin θ cos φ, sin θ sin φ, cos θ)`, `dω_l = sin θ dθ dφ`, θ ∈ [0, π/2] (outer),
//!   φ ∈ [0, π] (inner, doubled by the mirror symmetry of an isotropic BRDF about the plane
//!   of incidence). The horizon n·l = 0 is a coordinate line, so no clipping is needed;
//!   the lobe is resolved by fixed breakpoints placed geometrically around the mirror
//!   direction (θ = θv, φ = π) and the grazing corner (θ = π/2), down to a scale below
//!   the lobe's width in l-space (≈ 2α in θ, ≈ 2α·(n·v) in φ at grazing views).
//! * Micro-normal hemisphere (weak furnace, projected area): polar coordinates of h about
//!   the normal with the v·h = 0 limit in closed form (tan θh = n·v / (sin θv (−cos φ)))
//!   and breakpoints at multiples of α — no warp.
//!
//! The BRDF terms are re-implemented here from their textbook formulas (GGX/Beckmann D and
//! Λ, Gaussian normalization computed by this file's own quadrature, Blinn-Phong, Charlie,
//! V-groove, Ashikhmin, Schlick-GGX, Conty–Kulla's fitted Λ, Schlick weight). The one exception is the Smith G1 of the Gaussian
//! and Blinn-Phong NDFs, which has no closed form: it is taken from the library
//! (`Ndf::g1`) and checked independently by the weak white furnace test, which is exactly
//! the projected-area identity that defines it.

#![allow(dead_code)]

use brdfbake::model::{Masking, Ndf, NdfKind};
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

/// Order of the Gauss–Legendre rule.
pub const GL_ORDER: usize = 12;

/// Nodes and weights of Gauss–Legendre on [−1, 1].
pub struct Rule {
    pub x: Vec<f64>,
    pub w: Vec<f64>,
}

impl Rule {
    /// Gauss–Legendre of order n: Newton iteration on P_n from Chebyshev-like initial
    /// guesses, P_n and P_n' from the three-term recurrence.
    pub fn gauss_legendre(n: usize) -> Rule {
        let mut x = vec![0.0; n];
        let mut w = vec![0.0; n];
        let nf = n as f64;
        for i in 0..n.div_ceil(2) {
            let mut z = (PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
            let mut dp;
            let mut iter = 0;
            loop {
                let (mut p0, mut p1) = (1.0, z);
                for k in 2..=n {
                    let kf = k as f64;
                    let p2 = ((2.0 * kf - 1.0) * z * p1 - (kf - 1.0) * p0) / kf;
                    p0 = p1;
                    p1 = p2;
                }
                dp = nf * (z * p1 - p0) / (z * z - 1.0);
                let dz = p1 / dp;
                z -= dz;
                iter += 1;
                if dz.abs() <= 1e-16 || iter > 100 {
                    break;
                }
            }
            x[i] = -z;
            x[n - 1 - i] = z;
            let wi = 2.0 / ((1.0 - z * z) * dp * dp);
            w[i] = wi;
            w[n - 1 - i] = wi;
        }
        Rule { x, w }
    }

    /// The rule on [a, b]: value per channel and Σ|w·f| (for a rounding floor).
    #[inline]
    fn apply<const N: usize, F: FnMut(f64) -> [f64; N]>(
        &self,
        f: &mut F,
        a: f64,
        b: f64,
    ) -> ([f64; N], f64) {
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = [0.0; N];
        let mut sabs = 0.0;
        for (x, w) in self.x.iter().zip(&self.w) {
            let y = f(c + h * x);
            for k in 0..N {
                s[k] += w * y[k];
                sabs += (w * y[k]).abs();
            }
        }
        for v in s.iter_mut() {
            *v *= h;
        }
        (s, sabs * h.abs())
    }
}

fn rule() -> &'static Rule {
    static R: OnceLock<Rule> = OnceLock::new();
    R.get_or_init(|| Rule::gauss_legendre(GL_ORDER))
}

/// A reference result: value per channel, estimated absolute error (max over channels),
/// and the number of integrand evaluations.
#[derive(Clone, Copy, Debug)]
pub struct Est<const N: usize> {
    pub value: [f64; N],
    pub error: f64,
    pub evals: u64,
}

const MAX_DEPTH: u32 = 45;

#[allow(clippy::too_many_arguments)]
fn refine<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: &mut F,
    a: f64,
    b: f64,
    whole: [f64; N],
    tol: f64,
    noise: f64,
    depth: u32,
    out: &mut Est<N>,
) {
    let r = rule();
    let m = 0.5 * (a + b);
    let (l, la) = r.apply(f, a, m);
    let (rr, ra) = r.apply(f, m, b);
    out.evals += 2 * GL_ORDER as u64;
    let mut fine = [0.0; N];
    let mut err: f64 = 0.0;
    for k in 0..N {
        fine[k] = l[k] + rr[k];
        err = err.max((fine[k] - whole[k]).abs());
    }
    // Rounding floor: 1e-12 of Σ|w f|. Near grazing views the integrand reaches ~10²–10³
    // and its own rounding (through D's steep dependence on h) is ~1e-13 relative; without
    // a relative floor the bisection would chase that noise. It adds at most
    // 1e-12·∫|f| to the result's error, far below the 1e-9 target.
    let floor = 1e-12 * (la + ra);
    if err <= tol
        || err <= floor
        || err <= noise * (b - a)
        || depth >= MAX_DEPTH
        || !(m > a && m < b)
    {
        for (o, v) in out.value.iter_mut().zip(fine) {
            *o += v;
        }
        out.error += err;
        return;
    }
    refine(f, a, m, l, 0.5 * tol, noise, depth + 1, out);
    refine(f, m, b, rr, 0.5 * tol, noise, depth + 1, out);
}

/// Adaptive Gauss–Legendre over the panels given by the sorted breakpoints `breaks`
/// (first and last = the interval), to absolute tolerance `tol` (shared ∝ width).
pub fn adaptive<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: F,
    breaks: &[f64],
    tol: f64,
) -> Est<N> {
    adaptive_noisy(f, breaks, tol, 0.0)
}

/// As [`adaptive`] for an integrand known only to ±`noise` (an inner integral of a nested
/// quadrature): a panel is also accepted once its estimate is below `2·noise·width`, the
/// most by which the two rules can differ on noise alone — bisecting further would chase
/// the noise. The result's extra error is then at most `2·noise·(hi − lo)`, which the
/// callers budget for.
pub fn adaptive_noisy<const N: usize, F: FnMut(f64) -> [f64; N]>(
    mut f: F,
    breaks: &[f64],
    tol: f64,
    noise: f64,
) -> Est<N> {
    let mut out = Est {
        value: [0.0; N],
        error: 0.0,
        evals: 0,
    };
    let (lo, hi) = (breaks[0], breaks[breaks.len() - 1]);
    if hi <= lo {
        return out;
    }
    for p in breaks.windows(2) {
        let (a, b) = (p[0], p[1]);
        if b <= a {
            continue;
        }
        let (whole, _) = rule().apply(&mut f, a, b);
        out.evals += GL_ORDER as u64;
        refine(
            &mut f,
            a,
            b,
            whole,
            tol * (b - a) / (hi - lo),
            2.0 * noise,
            0,
            &mut out,
        );
    }
    out
}

/// Breakpoints `c ± big·2^(−k)` for k = 0, 1, … while `big·2^(−k) ≥ small`, plus `c`,
/// clipped to (lo, hi); `lo` and `hi` included. Sorted, duplicates removed.
pub fn geometric(c: f64, lo: f64, hi: f64, big: f64, small: f64) -> Vec<f64> {
    let mut v = vec![lo, hi];
    if c > lo && c < hi {
        v.push(c);
    }
    let mut s = big;
    while s >= small {
        for x in [c - s, c + s] {
            if x > lo && x < hi {
                v.push(x);
            }
        }
        s *= 0.5;
    }
    normalize_breaks(v)
}

/// Sorts, removes near-duplicates (closer than 1e-13).
pub fn normalize_breaks(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut out: Vec<f64> = Vec::with_capacity(v.len());
    for x in v {
        if !out.last().is_some_and(|&p| x - p <= 1e-13) {
            out.push(x);
        }
    }
    out
}

/// Union of breakpoint sets.
pub fn union(sets: &[Vec<f64>]) -> Vec<f64> {
    normalize_breaks(sets.iter().flatten().copied().collect())
}

/// The view direction with n·v = μ in the xz-plane.
pub fn view(mu: f64) -> [f64; 3] {
    [(1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu]
}

#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A reflected direction l and, computed without cancellation, s = v + l (|s| = 2 v·h).
#[derive(Clone, Copy, Debug)]
pub struct Dir {
    pub l: [f64; 3],
    pub s: [f64; 3],
}

/// ∫ g(l) dω_l over the upper hemisphere for a view with n·v = μ, where g is symmetric
/// under l_y → −l_y. `lobe` is the angular scale of the features of g in l-space around
/// the mirror direction (≈ 2α for a specular lobe); `tol` the absolute target.
pub fn over_l<const N: usize, G: Fn(&Dir) -> [f64; N]>(
    mu: f64,
    lobe: f64,
    tol: f64,
    g: G,
) -> Est<N> {
    over_l_kinked(mu, lobe, tol, g, |_, _| None)
}

/// As [`over_l`] for an integrand with a kink at a known azimuth for each θ:
/// `kink(cos θ, sin θ)` returns it as ψ = π − φ (or `None`), and it becomes an inner
/// breakpoint, so that each inner panel sees an analytic integrand.
///
/// The inner variable is ψ = π − φ, the azimuth measured from the mirror side, so that
/// the mirror lobe sits at ψ = 0 where ψ is represented to full relative precision; and
/// s = v + l is formed as `s_x = (sin θv − sin θ) + 2 sin θ sin²(ψ/2)` with
/// `sin θv − sin θ = (cos θ − μ)(cos θ + μ)/(sin θv + sin θ)`, which for grazing views
/// (l ≈ −v near the mirror direction) keeps h = s/|s| accurate to rounding instead of
/// losing digits to the cancellation of v_x + l_x.
pub fn over_l_kinked<const N: usize, G: Fn(&Dir) -> [f64; N], K: Fn(f64, f64) -> Option<f64>>(
    mu: f64,
    lobe: f64,
    tol: f64,
    g: G,
    kink: K,
) -> Est<N> {
    let mu = mu.min(1.0);
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let theta_v = mu.acos();
    // features of the lobe: ~lobe in θ around θv; ~lobe·(μ + cos θ) in ψ around 0 (the
    // l-space image of a micro-normal cone of width α, see the module comment)
    let small = (0.125 * lobe * mu).max(1e-5);
    let theta_breaks = union(&[
        geometric(theta_v, 0.0, FRAC_PI_2, 0.5, small),
        geometric(FRAC_PI_2, 0.0, FRAC_PI_2, 0.5, small),
        geometric(0.0, 0.0, FRAC_PI_2, 0.5, (0.125 * lobe).min(0.05)),
    ]);
    let psi_breaks = union(&[
        geometric(0.0, 0.0, PI, 1.0, small),
        vec![0.0, FRAC_PI_2, PI],
    ]);
    // Budget: the outer rule gets tol/2 plus, through its noise floor, up to
    // 2·(2ε)·(π/2) = 2πε where ε is the inner tolerance (its integrand 2 sin θ·I(θ) is known
    // to ±2ε); the inner errors themselves enter as ∫ 2 sin θ ε dθ ≤ 2ε. With ε = tol/40 the
    // total is ≤ tol/2 + (2π + 2)/40·tol < tol.
    let inner_tol = tol / 40.0;
    let inner_err = std::cell::Cell::new(0.0f64);
    let evals = std::cell::Cell::new(0u64);
    let outer = adaptive_noisy(
        |theta: f64| {
            let (st, ct) = theta.sin_cos();
            let sv_minus_st = (ct - mu) * (ct + mu) / (sin_v + st).max(f64::MIN_POSITIVE);
            let kinked;
            let breaks = match kink(ct, st) {
                Some(k) if k > 0.0 && k < PI => {
                    kinked = union(&[psi_breaks.clone(), vec![k]]);
                    &kinked
                }
                _ => &psi_breaks,
            };
            let e = adaptive(
                |psi: f64| {
                    let (sp, cp) = psi.sin_cos();
                    let half = (0.5 * psi).sin();
                    let d = Dir {
                        l: [-st * cp, st * sp, ct],
                        s: [sv_minus_st + 2.0 * st * half * half, st * sp, mu + ct],
                    };
                    g(&d)
                },
                breaks,
                inner_tol,
            );
            inner_err.set(inner_err.get().max(e.error));
            evals.set(evals.get() + e.evals);
            let mut y = e.value;
            for v in y.iter_mut() {
                *v *= 2.0 * st;
            }
            y
        },
        &theta_breaks,
        0.5 * tol,
        2.0 * inner_tol,
    );
    Est {
        value: outer.value,
        error: outer.error + 2.0 * inner_err.get(),
        evals: evals.get(),
    }
}

/// ∫ g(h) dω_h over the micro-normals of the upper hemisphere with v·h > 0, for a view
/// with n·v = μ (g symmetric under h_y → −h_y and vanishing at v·h = 0 or continuous
/// there). `alpha`: the NDF width, breakpoints in θh at multiples of it.
pub fn over_h_front<const N: usize, G: Fn([f64; 3]) -> [f64; N]>(
    mu: f64,
    alpha: f64,
    tol: f64,
    g: G,
) -> Est<N> {
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let mut base: Vec<f64> = vec![0.0, FRAC_PI_2];
    for k in -4..=4 {
        base.push(alpha.min(0.5) * 2f64.powi(k));
    }
    let phi_breaks = union(&[
        vec![0.0, 0.25 * PI, FRAC_PI_2, 0.75 * PI, PI],
        geometric(FRAC_PI_2, 0.0, PI, 0.25, 1e-3 * mu.max(1e-3)),
    ]);
    // Budget as in `over_l`: tol/2 for the outer rule, 2π·ε through its noise floor and
    // π·ε propagated, ε = tol/40: total ≤ 0.74·tol.
    let inner_tol = tol / 40.0;
    let inner_err = std::cell::Cell::new(0.0f64);
    let evals = std::cell::Cell::new(0u64);
    let outer = adaptive_noisy(
        |phi: f64| {
            let (sp, cp) = phi.sin_cos();
            // v·h = sinθv sinθh cosφ + μ cosθh > 0  ⇔  θh < θmax(φ)
            let th_max = if cp >= 0.0 {
                FRAC_PI_2
            } else {
                mu.atan2(sin_v * (-cp)).min(FRAC_PI_2)
            };
            let mut br: Vec<f64> = base.iter().copied().filter(|&t| t < th_max).collect();
            br.push(th_max);
            let br = normalize_breaks(br);
            let e = adaptive(
                |th: f64| {
                    let (s, c) = th.sin_cos();
                    let mut y = g([s * cp, s * sp, c]);
                    for v in y.iter_mut() {
                        *v *= 2.0 * s;
                    }
                    y
                },
                &br,
                inner_tol,
            );
            inner_err.set(inner_err.get().max(e.error));
            evals.set(evals.get() + e.evals);
            e.value
        },
        &phi_breaks,
        0.5 * tol,
        inner_tol,
    );
    Est {
        value: outer.value,
        error: outer.error + PI * inner_err.get(),
        evals: evals.get(),
    }
}

// ---------------------------------------------------------------------------------------
// The BRDF terms, from their formulas.
// ---------------------------------------------------------------------------------------

/// c(m) with ∫ c·exp(−(θ/m)²) cos θ dω = 1, by this file's quadrature (breakpoints at
/// multiples of m; the integrand is analytic).
pub fn gaussian_norm(m: f64) -> f64 {
    let mut br = vec![0.0, FRAC_PI_2];
    for k in 1..=12 {
        let x = 0.5 * m * k as f64;
        if x < FRAC_PI_2 {
            br.push(x);
        }
    }
    let e = adaptive(
        |t: f64| [2.0 * PI * (-(t / m) * (t / m)).exp() * t.cos() * t.sin()],
        &normalize_breaks(br),
        1e-16,
    );
    1.0 / e.value[0]
}

/// A specular model re-implemented from its formulas.
pub struct RefModel {
    pub kind: NdfKind,
    pub alpha: f64,
    pub masking: Masking,
    norm: f64,
    /// The library NDF, used only for the numeric Smith G1 of Gaussian and Blinn-Phong.
    lib: Ndf,
}

impl RefModel {
    pub fn new(kind: NdfKind, alpha: f64, masking: Masking) -> RefModel {
        let norm = match kind {
            NdfKind::Ggx | NdfKind::Beckmann => 1.0 / (PI * alpha * alpha),
            NdfKind::Gaussian => gaussian_norm(alpha),
            NdfKind::BlinnPhong => (2.0 / (alpha * alpha)) / (2.0 * PI), // (s + 2)/(2π)
            NdfKind::Charlie => (2.0 + 1.0 / alpha) / (2.0 * PI),
        };
        RefModel {
            kind,
            alpha,
            masking,
            norm,
            lib: Ndf::new(kind, alpha).unwrap(),
        }
    }

    /// D from cos θh and sin²θh (both > 0 computed from the vector's components).
    pub fn d(&self, cos_h: f64, sin2_h: f64) -> f64 {
        if cos_h <= 0.0 {
            return 0.0;
        }
        let a = self.alpha;
        match self.kind {
            NdfKind::Ggx => {
                // α² / (π (cos²θ (α² − 1) + 1)²) with cos²(α²−1)+1 = α² cos² + sin²
                let den = a * a * cos_h * cos_h + sin2_h;
                self.norm * a * a * a * a / (den * den)
            }
            NdfKind::Beckmann => {
                let c2 = cos_h * cos_h;
                self.norm * (-sin2_h / (c2 * a * a)).exp() / (c2 * c2)
            }
            NdfKind::Gaussian => {
                let th = sin2_h.sqrt().atan2(cos_h);
                self.norm * (-(th / a) * (th / a)).exp()
            }
            NdfKind::BlinnPhong => {
                let s = 2.0 / (a * a) - 2.0;
                self.norm * cos_h.powf(s)
            }
            NdfKind::Charlie => self.norm * sin2_h.powf(0.5 / a),
        }
    }

    /// D at a unit micro-normal.
    pub fn d_vec(&self, h: [f64; 3]) -> f64 {
        self.d(h[2], h[0] * h[0] + h[1] * h[1])
    }

    /// Smith Λ(μ).
    pub fn lambda(&self, mu: f64) -> f64 {
        if mu >= 1.0 {
            return 0.0;
        }
        let a = self.alpha;
        let s = (1.0 - mu * mu).sqrt();
        match self.kind {
            // Heitz 2014 eq. 86: Λ = (−1 + √(1 + α² tan²θ))/2
            NdfKind::Ggx => 0.5 * ((mu * mu + a * a * s * s).sqrt() - mu) / mu,
            // Heitz 2014 eq. 72: Λ = (erf(ν) − 1)/2 + e^{−ν²}/(2ν√π), ν = 1/(α tan θ)
            NdfKind::Beckmann => {
                let nu = mu / (a * s);
                0.5 * ((-nu * nu).exp() / (nu * PI.sqrt()) - libm::erfc(nu))
            }
            _ => 1.0 / self.lib.g1(mu) - 1.0,
        }
    }

    pub fn g1(&self, mu: f64) -> f64 {
        if mu <= 0.0 {
            return 0.0;
        }
        1.0 / (1.0 + self.lambda(mu))
    }

    /// G(v, l, h) for the model's masking term.
    pub fn g(&self, nv: f64, nl: f64, nh: f64, vh: f64) -> f64 {
        match self.masking {
            Masking::None => 1.0,
            Masking::SmithSeparable => self.g1(nv) * self.g1(nl),
            Masking::SmithHeightCorrelated => 1.0 / (1.0 + self.lambda(nv) + self.lambda(nl)),
            Masking::VGroove => {
                let x = 2.0 * nh * nv.min(nl) / vh;
                x.min(1.0)
            }
            Masking::Ashikhmin => nl * nv / (nl + nv - nl * nv),
            // Schlick 1994, eq. 19, G1 = 1/((1 − k) + k/μ), with Karis' (2013) k = α/2
            // (image-based lighting) or k = (r + 1)²/8, r = √α (analytic lights)
            Masking::SchlickGgx | Masking::SchlickGgxDirect => {
                let k = if self.masking == Masking::SchlickGgx {
                    self.alpha / 2.0
                } else {
                    (self.alpha.sqrt() + 1.0).powi(2) / 8.0
                };
                let g1 = |mu: f64| {
                    if mu <= 0.0 {
                        0.0
                    } else {
                        1.0 / ((1.0 - k) + k / mu)
                    }
                };
                g1(nv) * g1(nl)
            }
            Masking::ContyKulla | Masking::ContyKullaSoftened => {
                if nv <= 0.0 || nl <= 0.0 {
                    return 0.0;
                }
                let light = if self.masking == Masking::ContyKullaSoftened {
                    // BSDL's terminator softening, light side only: Λ^(1 + 2(1 − μ)⁸)
                    self.ck_lambda(nl).powf(1.0 + 2.0 * (1.0 - nl).powi(8))
                } else {
                    self.ck_lambda(nl)
                };
                1.0 / (1.0 + self.ck_lambda(nv) + light)
            }
        }
    }

    /// Conty Estevez & Kulla's fitted sheen Λ in the form KHR_materials_sheen writes it:
    /// `l(x) = a/(1 + b x^c) + d x + e` with (a, b, c, d, e) = mix(fit at α = 1, fit at
    /// α = 0, (1 − α)²), `Λ(μ) = exp(l(μ))` for μ < 0.5, `exp(2 l(0.5) − l(1 − μ))` above.
    pub fn ck_lambda(&self, mu: f64) -> f64 {
        let one = [21.5473, 3.82987, 0.19823, -1.97760, -4.32054];
        let zero = [25.3245, 3.32435, 0.16801, -1.27393, -4.85967];
        let w = (1.0 - self.alpha) * (1.0 - self.alpha);
        let p: Vec<f64> = one.iter().zip(zero).map(|(x, y)| x + (y - x) * w).collect();
        let l = |x: f64| p[0] / (1.0 + p[1] * x.powf(p[2])) + p[3] * x + p[4];
        let mu = mu.min(1.0);
        if mu < 0.5 {
            l(mu).exp()
        } else {
            (2.0 * l(0.5) - l(1.0 - mu)).exp()
        }
    }

    /// The azimuth ψ = π − φ of the V-groove kink for a view with n·v = μ at polar angle θ of l (cos θ,
    /// sin θ): with h the half vector, n·h = (n·v + n·l)/|v + l| and v·h = |v + l|/2, so
    /// 2(n·h)·m/(v·h) = 1 (m = min(n·v, n·l)) ⇔ |v + l|² = 4m(n·v + n·l) ⇔
    /// v·l = 2m(n·v + n·l) − 1, and v·l = sin θv sin θ cos φ + n·v cos θ.
    /// (The other kink, n·l = n·v, is the line θ = θv: an outer breakpoint already.)
    pub fn phi_kink(&self, mu: f64, ct: f64, st: f64) -> Option<f64> {
        if self.masking != Masking::VGroove {
            return None;
        }
        let sv = (1.0 - mu * mu).max(0.0).sqrt();
        if sv * st <= 0.0 {
            return None;
        }
        let m = mu.min(ct);
        let c = (2.0 * m * (mu + ct) - 1.0 - mu * ct) / (sv * st);
        if c.abs() < 1.0 {
            Some((-c).acos()) // ψ = π − φ
        } else {
            None
        }
    }

    /// `f(v, l)·(n·l)` with F = 1, and v·h, for a view with n·v = μ; `None` when l is
    /// below the horizon. With s = v + l: h = s/|s|, v·h = |s|/2.
    pub fn f_cos(&self, mu: f64, d: &Dir) -> Option<(f64, f64)> {
        let nl = d.l[2];
        if mu <= 0.0 || nl <= 0.0 {
            return None;
        }
        let s = d.s;
        let len2 = dot(s, s);
        let len = len2.sqrt();
        let vh = 0.5 * len;
        let nh = s[2] / len;
        let sin2_h = (s[0] * s[0] + s[1] * s[1]) / len2;
        let dd = self.d(nh, sin2_h);
        if dd == 0.0 {
            return Some((0.0, vh));
        }
        let g = self.g(mu, nl, nh, vh);
        // f·nl = D G /(4 nv nl) · nl
        Some((dd * g / (4.0 * mu), vh))
    }

    /// As [`RefModel::f_cos`] for plain unit vectors (h formed directly).
    pub fn f_cos_vec(&self, v: [f64; 3], l: [f64; 3]) -> Option<(f64, f64)> {
        if v[2] <= 0.0 {
            return None;
        }
        let d = Dir {
            l,
            s: [v[0] + l[0], v[1] + l[1], v[2] + l[2]],
        };
        self.f_cos(v[2], &d)
    }
}

/// Unpolarized Fresnel reflectance of a dielectric (relative index η, incidence from the
/// outside) from the s/p amplitudes: with cos θt = √(1 − sin²θi/η²),
/// r_s = (cos θi − η cos θt)/(cos θi + η cos θt), r_p = (η cos θi − cos θt)/(η cos θi + cos θt),
/// F = (r_s² + r_p²)/2 (1 under total internal reflection).
pub fn fresnel_dielectric(c: f64, eta: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    let st2 = (1.0 - c * c) / (eta * eta);
    if st2 >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - st2).sqrt();
    let rs = (c - eta * ct) / (c + eta * ct);
    let rp = (eta * c - ct) / (eta * c + ct);
    0.5 * (rs * rs + rp * rp)
}

/// Unpolarized Fresnel reflectance of a conductor with complex index η + ik, in the real
/// arithmetic of Lagarde, "Memo on Fresnel equations" (2013):
/// a² + b² = √((η² − k² − sin²θ)² + 4η²k²), a = √((a² + b² + η² − k² − sin²θ)/2),
/// R_s = (a² + b² + cos²θ − 2a cos θ)/(a² + b² + cos²θ + 2a cos θ),
/// R_p = R_s (cos²θ (a² + b²) + sin⁴θ − 2a cos θ sin²θ)/(cos²θ (a² + b²) + sin⁴θ + 2a cos θ sin²θ).
pub fn fresnel_conductor(c: f64, eta: f64, k: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let t1 = a2b2 + c2;
    let t2 = 2.0 * a * c;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = c2 * a2b2 + s2 * s2;
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    0.5 * (rs + rp)
}

/// Schlick's weight (1 − c)⁵.
pub fn fc(c: f64) -> f64 {
    (1.0 - c).powi(5)
}

/// Reference split-sum at (μ): [A = ∫(1 − Fc) f cos, B = ∫ Fc f cos] with F = 1.
pub fn split_sum(m: &RefModel, mu: f64, tol: f64) -> Est<2> {
    let lobe = lobe_scale(m);
    over_l_kinked(
        mu,
        lobe,
        tol,
        |d| match m.f_cos(mu, d) {
            Some((f, vh)) => {
                let w = fc(vh);
                [f * (1.0 - w), f * w]
            }
            None => [0.0, 0.0],
        },
        |ct, st| m.phi_kink(mu, ct, st),
    )
}

/// The angular scale of a model's lobe in l-space.
pub fn lobe_scale(m: &RefModel) -> f64 {
    match m.kind {
        NdfKind::Charlie => 0.5,
        _ => (2.0 * m.alpha).min(1.0),
    }
}

/// Reference directional albedo with F = 1 (and a Lambertian lobe of weight `wd/π`).
pub fn albedo(m: &RefModel, mu: f64, tol: f64) -> Est<1> {
    over_l_kinked(
        mu,
        lobe_scale(m),
        tol,
        |d| [m.f_cos(mu, d).map_or(0.0, |(f, _)| f)],
        |ct, st| m.phi_kink(mu, ct, st),
    )
}

/// Reference E_avg = 2∫₀¹ E(μ) μ dμ, nested over the reference albedo. Substituting
/// μ = t² (dμ = 2t dt) removes the √μ-type behaviour of E near grazing views.
pub fn average_albedo(m: &RefModel, tol: f64) -> Est<1> {
    let inner_err = std::cell::Cell::new(0.0f64);
    let evals = std::cell::Cell::new(0u64);
    let br = [0.0, 0.1, 0.3, 0.6, 1.0];
    // Budget: outer rule tol/2, its noise floor 2·(4ε)·1, propagation ∫4t³ε dt ≤ ε, with
    // ε = tol/40: total ≤ tol/2 + 9/40·tol < tol.
    let inner_tol = tol / 40.0;
    let outer = adaptive_noisy(
        |t: f64| {
            let mu = t * t;
            let e = albedo(m, mu, inner_tol);
            inner_err.set(inner_err.get().max(e.error));
            evals.set(evals.get() + e.evals);
            [4.0 * t * t * t * e.value[0]]
        },
        &br,
        0.5 * tol,
        4.0 * inner_tol,
    );
    Est {
        value: outer.value,
        error: outer.error + inner_err.get(),
        evals: evals.get(),
    }
}

/// Reference directional albedo with a Fresnel factor `fr(v·h)` (the exact or Schlick forms
/// above): ∫ f(v, l)·F(v·h)·(n·l) dω_l, F = 1 inside `f_cos`.
pub fn albedo_fresnel<Fr: Fn(f64) -> f64>(m: &RefModel, mu: f64, tol: f64, fr: Fr) -> Est<1> {
    over_l_kinked(
        mu,
        lobe_scale(m),
        tol,
        |d| [m.f_cos(mu, d).map_or(0.0, |(f, vh)| f * fr(vh))],
        |ct, st| m.phi_kink(mu, ct, st),
    )
}

/// Reference reflection and transmission albedo [R, T] of a rough dielectric interface
/// (GGX, separable Smith, relative index η, view on the outer side) in **l-space**, with
/// Walter et al.'s (2007) BRDF (eq. 20) and BTDF (eq. 21) written out from the paper:
/// f_t(v, l) = |v·h_t||l·h_t|/(|n·v||n·l|) · η² (1 − F(v·h_t)) G D(h_t) / (v·h_t + η l·h_t)²,
/// h_t = −(v + η l)/|v + η l| oriented towards n (eq. 16), non-zero only where v·h_t > 0
/// and l·h_t < 0; T integrates f_t |n·l| over the lower hemisphere, parameterized by the
/// mirror image l' = (l_x, l_y, −l_z) of l so that [`over_l`] applies.
pub fn dielectric_rt(alpha: f64, eta: f64, mu: f64, tol: f64) -> Est<2> {
    let m = RefModel::new(NdfKind::Ggx, alpha, Masking::SmithSeparable);
    let v = view(mu);
    // η < 1: total internal reflection for v·h < c = √(1 − η²), i.e. (v·h = |v + l|/2)
    // inside the cone v·l < 2c² − 1 about v: a square-root kink of F, given to the inner
    // rule as a breakpoint ψ = π − φ with cos φ = (2c² − 1 − μ cos θ)/(sin θv sin θ)
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let r = over_l_kinked(
        mu,
        lobe_scale(&m),
        0.5 * tol,
        |d| {
            [m.f_cos(mu, d)
                .map_or(0.0, |(f, vh)| f * fresnel_dielectric(vh, eta))]
        },
        |ct, st| {
            if eta >= 1.0 || sin_v * st <= 0.0 {
                return None;
            }
            let cc = 1.0 - eta * eta;
            let cphi = (2.0 * cc - 1.0 - mu * ct) / (sin_v * st);
            (cphi.abs() < 1.0).then(|| (-cphi).acos())
        },
    );
    let t = over_l(mu, 1.0, 0.5 * tol, |d| {
        let l = [d.l[0], d.l[1], -d.l[2]];
        let s = [v[0] + eta * l[0], v[1] + eta * l[1], v[2] + eta * l[2]];
        let len = dot(s, s).sqrt();
        if len == 0.0 {
            return [0.0];
        }
        let mut h = [-s[0] / len, -s[1] / len, -s[2] / len];
        if h[2] < 0.0 {
            h = [-h[0], -h[1], -h[2]];
        }
        let (vh, lh) = (dot(v, h), dot(l, h));
        if vh <= 0.0 || lh >= 0.0 || h[2] <= 0.0 {
            return [0.0];
        }
        let nl = -l[2];
        let g = m.g1(mu) * m.g1(nl);
        let den = vh + eta * lh;
        let ft = vh * (-lh) / (mu * nl)
            * eta
            * eta
            * (1.0 - fresnel_dielectric(vh, eta))
            * g
            * m.d_vec(h)
            / (den * den);
        [ft * nl]
    });
    Est {
        value: [r.value[0], t.value[0]],
        error: r.error + t.error,
        evals: r.evals + t.evals,
    }
}
