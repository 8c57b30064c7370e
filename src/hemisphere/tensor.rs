//! The fast path for smooth hemisphere integrals: a nested Clenshaw–Curtis tensor rule over
//! the half vector, refined one dimension at a time, with an error estimate from the nested
//! lower-order rules (no extra evaluations).
//!
//! **Coordinates.** The same as [`integrate_over_l`](crate::hemisphere::integrate_over_l):
//! the half vector `h = (θh, φ)`, `dω_l = 4 (v·h) dω_h`, θh up to the exact horizon
//! `θmax(φ) = π/4 + ψ/2` (`tan ψ = tan θv cos φ`), the lobe warp `u = asinh(tan θh / α)` for
//! lobes peaked at the normal. Two further warps make every integrand an O(1)-wide smooth
//! function of the rule's variables so that a *fixed* high-order rule converges fast:
//!
//! * φ over the whole `[0, π]` as `φ = π/2 + c·sinh s`, `s ∈ [−S, S]`, `S = asinh(π/(2c))`,
//!   with `c = min(cot θv, 1)`: at grazing views ψ swings from +θv to −θv within
//!   `|φ − π/2| ≲ cot θv` (`tan ψ = tan θv cos φ` crosses ±1 there), and the sinh map puts
//!   as many nodes into that band as outside it.
//! * for sheen lobes (Charlie, `D ∝ sin^{1/α} θh`, concentrated at grazing micro-normals on
//!   a scale `cos θh ~ √α`), the inner variable is `y = asinh(cos θh / β)`, `β = min(√α, 1)`,
//!   with `sin θh dθh = −d cos θh = −β cosh y dy`.
//!
//! **Rule and estimate.** Clenshaw–Curtis on `2^k + 1` points (Chebyshev extrema; weights
//! by Waldvogel's formula, 2006, or Trefethen, *Is Gauss quadrature better than
//! Clenshaw–Curtis?*, SIAM Review 50, 2008, which also shows its convergence matches
//! Gauss–Legendre's on functions that are not entire). Level k's nodes contain level k−1's,
//! so the tensor rule `Q(kφ, ku)` comes with `Q(kφ−1, ku)` and `Q(kφ, ku−1)` for free. The
//! error estimate per channel is `|Q(kφ,ku) − Q(kφ−1,ku)| + |Q(kφ,ku) − Q(kφ,ku−1)|`: each
//! term is (to first order) the error of the *coarser* rule in that dimension, and with
//! geometric convergence the finer rule we keep is far more accurate, so the estimate is an
//! over-estimate, as |K15 − G7| is for the adaptive integrator. The dimension whose
//! difference is larger is refined until the estimate is below the tolerance; if that
//! needs more than [`MAX_LEVEL`] in a dimension, the caller is told to use the adaptive
//! integrator instead (`None`). The starting levels are [`MIN_LEVEL`](crate::quadrature::clenshaw_curtis::MIN_LEVEL) (9 × 9 nodes) so
//! that an O(1)-wide feature cannot fall between all nodes of both compared rules.
//!
//! Determinism: the sums run in a fixed order over fixed nodes; scratch memory is per
//! thread but every entry read was written in the same call.

// Channel loops index several same-length arrays at once; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

use crate::hemisphere::{tan_theta_h_max, LobeWarp, Node};
use crate::model::{Ndf, NdfKind};
use crate::quadrature::adaptive::Estimate;
use crate::quadrature::clenshaw_curtis::{inner_sums, refine, rules, MAX_LEVEL, NMAX};
use std::cell::RefCell;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// What the fast path does, as the sidecar's `quadrature.method` states it.
pub const METHOD: &str = "nested Clenshaw-Curtis tensor rule over the half vector (2^k+1 nodes per dimension, k = 3..7, at most 65x65 nodes), refined one dimension at a time: phi in [0, pi] (doubled by symmetry) as phi = pi/2 + c sinh(s), c = min(cot theta_v, 1); theta_h up to the exact horizon pi/4 + psi/2 (tan psi = tan theta_v cos phi) in the lobe warp u = asinh(tan theta_h / alpha) (sheen: cos theta_h = sqrt(alpha) sinh(y) for alpha < 1/16, theta_h = theta_max w^2 otherwise); error estimate per channel and dimension max(|Q_k - Q_k-1|, |Q_k-1 - Q_k-2|^2 / max(|Q_k|, tol)) from the nested lower-order rules, summed over the two dimensions; a texel whose estimate does not reach the tolerance within 65x65 nodes, or whose very narrow sheen lobe (alpha < 1e-4) has D > 1e-12 D_max at the horizon, is integrated by nested adaptive Gauss-Kronrod (G7/K15) instead (phi split at pi/2, same horizon and warp, estimate |K15 - G7| summed over panels); f64 accumulation";

/// The inner (θh) variable of the fast path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InnerWarp {
    /// `u = asinh(tan θh / scale)`: lobes of width `scale` about the normal.
    TanOverScale(f64),
    /// `y = asinh(cos θh / scale)`: lobes concentrated at grazing micro-normals within
    /// `cos θh ~ scale` (narrow sheen).
    CosOverScale(f64),
    /// `θh = θmax·w²`, w ∈ [0, 1]: wide lobes with a non-analytic factor `θh^p` at the normal
    /// (Charlie's `sin^{1/α} θh` for α not 1/integer): in w it becomes `w^{2p+3}`, smooth
    /// enough for the rule's algebraic convergence rate (error ~ n^{−2(2p+4)}) to be fast.
    SquareRoot,
}

impl InnerWarp {
    /// The warp for an NDF's lobe: the hemisphere integrator's `TanOverScale(α)` for lobes
    /// peaked at the normal. For Charlie, `sin^{1/α} θh = (1 − cos²θh)^{1/(2α)} ≈
    /// exp(−cos²θh/(2α))` has width √α in cos θh: `CosOverScale(√α)` while that is narrow
    /// (α < 1/16, where the factor is also flat to all orders at the normal), `SquareRoot`
    /// beyond.
    pub fn for_ndf(ndf: &Ndf) -> InnerWarp {
        match (ndf.kind(), ndf.warp()) {
            (NdfKind::Charlie, _) | (_, LobeWarp::Linear | LobeWarp::SheenFlank(_)) => {
                if ndf.alpha() < 1.0 / 16.0 {
                    InnerWarp::CosOverScale(ndf.alpha().sqrt())
                } else {
                    InnerWarp::SquareRoot
                }
            }
            // (an NDF's own warp is never the V-groove one, which `Specular::warp` adds and
            // which the fast path does not take)
            (_, LobeWarp::TanOverScale(s) | LobeWarp::TanOverScaleVGroove(s)) => {
                InnerWarp::TanOverScale(s)
            }
        }
    }
}

/// The view data and φ warp of the fast paths (this file's, the specialised kernels' and the
/// V-groove path's): `φ = π/2 + c sinh s`, `s ∈ [−S, S]`, `c = min(cot θv, 1)`,
/// `S = asinh(π/(2c))`, which clusters φ nodes at π/2 for grazing views.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PhiWarp {
    pub(crate) mu_v: f64,
    pub(crate) sin_v: f64,
    pub(crate) tan_v: f64,
    pub(crate) c: f64,
    pub(crate) big_s: f64,
}

impl PhiWarp {
    /// For view cosine `n_dot_v` ∈ (0, 1] (values above 1 are taken as 1).
    pub(crate) fn new(n_dot_v: f64) -> PhiWarp {
        let mu_v = n_dot_v.min(1.0);
        let sin_v = (1.0 - mu_v * mu_v).max(0.0).sqrt();
        let c = if sin_v > 0.0 {
            (mu_v / sin_v).min(1.0)
        } else {
            1.0
        };
        PhiWarp {
            mu_v,
            sin_v,
            tan_v: sin_v / mu_v,
            c,
            big_s: (FRAC_PI_2 / c).asinh(),
        }
    }
}

/// Per-thread scratch: integrand values on the finest grid (channel-interleaved) and, per
/// φ node, its setup and the finest u level computed so far (also the V-groove path's).
#[derive(Default)]
pub(crate) struct Scratch {
    pub(crate) vals: Vec<f64>,
    /// per φ index: u level computed (usize::MAX = none)
    pub(crate) level: Vec<usize>,
    /// per φ index: inner half-length × outer Jacobian dφ/ds (the product every inner sum
    /// is multiplied by)
    pub(crate) scale: Vec<f64>,
}

impl Scratch {
    /// Sized for the finest grid with `n` channels, every φ node marked as not computed.
    pub(crate) fn reset(&mut self, n: usize) {
        self.vals.resize(NMAX * NMAX * n, 0.0);
        self.level.clear();
        self.level.resize(NMAX, usize::MAX);
        self.scale.resize(NMAX, 0.0);
    }
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Fast-path version of [`integrate_over_l`](crate::hemisphere::integrate_over_l): returns
/// `None` if the nested rules do not reach `tol_abs` (estimated) within [`MAX_LEVEL`].
/// `g` is as there: `f(v, l)·(n·l)` per channel at a half-vector node.
pub fn integrate_over_l_cc<const N: usize, F: Fn(&Node) -> [f64; N]>(
    n_dot_v: f64,
    warp: InnerWarp,
    tol_abs: f64,
    g: F,
) -> Option<Estimate<N>> {
    SCRATCH
        .with(|s| run(&mut s.borrow_mut(), n_dot_v, warp, tol_abs, &g))
        .ok()
}

/// [`integrate_over_l_cc`] that also says what an abandoned attempt cost: `Err(evaluations)`
/// where the nested rules do not reach `tol_abs`.
pub fn integrate_over_l_cc_counted<const N: usize, F: Fn(&Node) -> [f64; N]>(
    n_dot_v: f64,
    warp: InnerWarp,
    tol_abs: f64,
    g: F,
) -> Result<Estimate<N>, u64> {
    SCRATCH.with(|s| run(&mut s.borrow_mut(), n_dot_v, warp, tol_abs, &g))
}

fn run<const N: usize, F: Fn(&Node) -> [f64; N]>(
    sc: &mut Scratch,
    n_dot_v: f64,
    warp: InnerWarp,
    tol: f64,
    g: &F,
) -> Result<Estimate<N>, u64> {
    let r = rules();
    sc.reset(N);
    let PhiWarp {
        mu_v,
        sin_v,
        tan_v,
        c,
        big_s,
    } = PhiWarp::new(n_dot_v);
    // Fills the values of φ index i up to u level ku.
    let fill = |sc: &mut Scratch, evals: &mut u64, i: usize, ku: usize| {
        let have = sc.level[i];
        if have != usize::MAX && have >= ku {
            return;
        }
        let s = big_s * r.x[i];
        let phi = FRAC_PI_2 + c * s.sinh();
        let cp = phi.cos();
        // dφ/dx = c cosh(s)·S; ×2: φ ∈ [0, π] covers half the plane (mirror symmetry)
        let dphi_ds = 2.0 * c * s.cosh() * big_s;
        let tmax = tan_theta_h_max(tan_v, cp);
        let node_at = |sin_h: f64, cos_h: f64| Node::at(mu_v, sin_v, cp, sin_h, cos_h);
        let stride = 1usize << (MAX_LEVEL - ku);
        let old_stride = if have == usize::MAX {
            0
        } else {
            1usize << (MAX_LEVEL - have)
        };
        let base = i * NMAX * N;
        match warp {
            InnerWarp::TanOverScale(scale) => {
                let umax = (tmax / scale).asinh();
                let half = 0.5 * umax;
                sc.scale[i] = half * dphi_ds;
                let mut j = 0;
                while j < NMAX {
                    if old_stride == 0 || j % old_stride != 0 {
                        let u = half * (1.0 - r.x[j]);
                        let t = scale * u.sinh();
                        let c2 = 1.0 / (1.0 + t * t);
                        let cos_h = c2.sqrt();
                        let sin_h = t * cos_h;
                        let n = node_at(sin_h, cos_h);
                        let out = &mut sc.vals[base + j * N..base + j * N + N];
                        if n.n_dot_l <= 0.0 || n.v_dot_h <= 0.0 {
                            out.fill(0.0);
                        } else {
                            let jac = 4.0 * n.v_dot_h * sin_h * scale * u.cosh() * c2;
                            let y = g(&n);
                            for k in 0..N {
                                out[k] = y[k] * jac;
                            }
                        }
                        *evals += 1;
                    }
                    j += stride;
                }
            }
            InnerWarp::SquareRoot => {
                let thmax = tmax.atan();
                // Near the horizon n·l ≈ 2A(θmax − θh), A = √(cos²θv + sin²θv cos²φ)
                // (module docs of `hemisphere`), and the Ashikhmin visibility
                // n·l/(n·l + n·v − (n·l)(n·v)) turns over at n·l ~ n·v: a layer of width
                // ℓ = n·v/(2A) in θh. Where it is narrow, w = 1 − d·sinh z (d = ℓ/(2θmax))
                // puts nodes into it; θh = θmax·w² still vanishes quadratically at the normal.
                let amp = (mu_v * mu_v + sin_v * sin_v * cp * cp).sqrt();
                let d = mu_v / (2.0 * amp) / (2.0 * thmax);
                let zmax = if d < 0.25 { (1.0 / d).asinh() } else { 0.0 };
                sc.scale[i] = 0.5 * dphi_ds * if zmax > 0.0 { zmax } else { 1.0 };
                let mut j = 0;
                while j < NMAX {
                    if old_stride == 0 || j % old_stride != 0 {
                        let x = 0.5 * (1.0 - r.x[j]);
                        // w and dw/dx
                        let (w, dw) = if zmax > 0.0 {
                            let z = zmax * x;
                            ((1.0 - d * z.sinh()).max(0.0), d * z.cosh())
                        } else {
                            (x, 1.0)
                        };
                        let th = thmax * w * w;
                        let (sin_h, cos_h) = th.sin_cos();
                        let n = node_at(sin_h, cos_h);
                        let out = &mut sc.vals[base + j * N..base + j * N + N];
                        if n.n_dot_l <= 0.0 || n.v_dot_h <= 0.0 {
                            out.fill(0.0);
                        } else {
                            // dω_h = sin θh dθh dφ, |dθh/dw| = 2 θmax w
                            let jac = 4.0 * n.v_dot_h * sin_h * 2.0 * thmax * w * dw;
                            let y = g(&n);
                            for k in 0..N {
                                out[k] = y[k] * jac;
                            }
                        }
                        *evals += 1;
                    }
                    j += stride;
                }
            }
            InnerWarp::CosOverScale(beta) => {
                // cos θh = β sinh y, y from the horizon (cos θmax) up to the normal (1)
                let cmin = 1.0 / (1.0 + tmax * tmax).sqrt();
                let (y0, y1) = ((cmin / beta).asinh(), (1.0 / beta).asinh());
                let half = 0.5 * (y1 - y0);
                sc.scale[i] = half * dphi_ds;
                let mut j = 0;
                while j < NMAX {
                    if old_stride == 0 || j % old_stride != 0 {
                        let y = y0 + half * (1.0 - r.x[j]);
                        let cos_h = (beta * y.sinh()).min(1.0);
                        let sin2_h = (1.0 - cos_h) * (1.0 + cos_h);
                        let sin_h = sin2_h.sqrt();
                        let n = node_at(sin_h, cos_h);
                        let out = &mut sc.vals[base + j * N..base + j * N + N];
                        if n.n_dot_l <= 0.0 || n.v_dot_h <= 0.0 {
                            out.fill(0.0);
                        } else {
                            // sin θh dθh = d(cos θh) = β cosh y dy
                            let jac = 4.0 * n.v_dot_h * beta * y.cosh();
                            let y = g(&n);
                            for k in 0..N {
                                out[k] = y[k] * jac;
                            }
                        }
                        *evals += 1;
                    }
                    j += stride;
                }
            }
        }
        sc.level[i] = ku;
    };

    let inner = |sc: &mut Scratch, i: usize, ku: usize| -> [[f64; N]; 3] {
        inner_sums(&sc.vals[i * NMAX * N..(i + 1) * NMAX * N], sc.scale[i], ku)
    };
    refine(sc, tol, fill, inner)
}

/// The hemisphere integral of a smooth integrand: the fast path, or — where its nested
/// estimate does not reach `tol_abs` within [`MAX_NODES`](crate::quadrature::clenshaw_curtis::MAX_NODES) — the adaptive integrator
/// ([`integrate_over_l`](crate::hemisphere::integrate_over_l)) from scratch; the
/// evaluations of the abandoned attempt are counted too. For integrands with kinks (the
/// V-groove term) call the adaptive integrator directly.
pub fn integrate_over_l_smooth<const N: usize, F: Fn(&Node) -> [f64; N]>(
    n_dot_v: f64,
    ndf: Option<&Ndf>,
    tol_abs: f64,
    g: F,
) -> Estimate<N> {
    let (inner, lobe) = match ndf {
        Some(n) => (InnerWarp::for_ndf(n), n.warp()),
        None => (InnerWarp::TanOverScale(1.0), LobeWarp::TanOverScale(1.0)),
    };
    if let InnerWarp::CosOverScale(beta) = inner {
        // A very narrow sheen lobe (α = β² < 1e-4: D ∝ (1 − cos²θh)^{1/(2α)}) that still
        // has weight at the horizon, whose lowest point is cos θmax(φ = 0) = sin(π/4 − θv/2),
        // is a spike of width ~α/cos θmax pressed against the n·l = 0 edge: nested fixed
        // rules can agree on it falsely (seen at μ = 0.01, α = 1e-6), so such texels go to
        // the adaptive integrator directly.
        let alpha = beta * beta;
        let theta_v = n_dot_v.clamp(0.0, 1.0).acos();
        let cmin = (FRAC_PI_4 - 0.5 * theta_v).sin();
        let d_rel = ((1.0 - cmin * cmin).ln() / (2.0 * alpha)).exp();
        if alpha < 1e-4 && d_rel > 1e-12 {
            return crate::hemisphere::integrate_over_l(n_dot_v, lobe, tol_abs, g);
        }
    }
    match SCRATCH.with(|s| run(&mut s.borrow_mut(), n_dot_v, inner, tol_abs, &g)) {
        Ok(e) => e,
        Err(spent) => {
            let mut e = crate::hemisphere::integrate_over_l(n_dot_v, lobe, tol_abs, g);
            e.evals += spent;
            e
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// ∫ n·l dω_l = π for every view: checks the φ map, the horizon limit and the
    /// Jacobians of the tan and square-root warps (asked for 1e-11; the nested estimate must hold and
    /// the value be within 1e-10, rounding of ~10³ terms included).
    #[test]
    fn projected_solid_angle_is_pi() {
        for &mu in &[1.0, 0.7, 0.2, 0.01, 1e-4] {
            for warp in [
                // (not a narrow TanOverScale: n·l is not a lobe at the normal, and in that
                // warp its weight sits at the far end of the u range, where the rule does
                // not converge to 1e-11 within 65² nodes and the caller falls back)
                InnerWarp::TanOverScale(0.3),
                // (nor CosOverScale: n·l keeps a √(1 − cos²θh) factor at the normal that
                // only a narrow sheen D flattens; that warp is checked on sheen albedos in
                // tests/fast_path.rs and tests/accuracy.rs)
                InnerWarp::TanOverScale(1.0),
                InnerWarp::SquareRoot,
            ] {
                // at grazing views 1e-11 may need more than 65² nodes: then the caller
                // falls back (None), which is allowed there and only there
                let Some(e) = integrate_over_l_cc(mu, warp, 1e-11, |n| [n.n_dot_l]) else {
                    assert!(mu < 0.1, "mu={mu} {warp:?}: no convergence");
                    continue;
                };
                let d = (e.value[0] - PI).abs();
                assert!(
                    d < 1e-10 && d <= e.error[0] + 1e-13,
                    "mu={mu} {warp:?}: {e:?}"
                );
            }
        }
    }
}
