//! The GGX split sum as a one-dimensional integral over the light's polar angle θl, with the
//! azimuthal integral done in closed form (single-scattering albedo) or by a rule that
//! converges geometrically after the lobe's pole is subtracted (Schlick-weighted part).
//!
//! **Why it works.** In light coordinates (θl, relative azimuth φ), Smith's masking depends
//! on μl = cos θl and μv alone — height-correlated `G2 = 1/(1 + Λ(μv) + Λ(μl))` and separable
//! `G1(μv) G1(μl)` alike (Heitz 2014, "Understanding the Masking-Shadowing Function",
//! eqs. 43, 98, 99) — so with `f (n·l) = D G2 F/(4 μv)`
//!
//! `∫ f (n·l) dω_l = ∫₀^{π/2} sin θl · G2/(2 μv) · [∫₀^π D F dφ] dθl`.
//!
//! With `c = v·l = μv μl + sv sl cos φ`, `z = 2 + 2c = 4 (v·h)²` and `(n·h)² = m/z`,
//! `m = (μv + μl)²`, GGX's `D = α²/(π ((n·h)²(α² − 1) + 1)²)` (Walter et al. 2007, eq. 33)
//! becomes `D = (α²/π) z²/y²` with `y = z − M`, `M = m (1 − α²)`: a rational function of
//! cos φ. Writing `y = S + Q cos φ` (`Q = 2 sv sl`), `S − Q = α² m + (sv − sl)²` and
//! `S + Q = α² m + (sv + sl)²` (both exact, without cancellation), `r = √((S − Q)(S + Q))`
//! and the classical `∫₀^π dφ/(S + Q cos φ) = π/r`, `∫₀^π dφ/(S + Q cos φ)² = π S/r³`
//! (Gradshteyn & Ryzhik 3.613.2 and its derivative in S):
//!
//! `I₀ = ∫₀^π D dφ = α² (1 + 2M/r + M² S/r³)`   (F = 1, exact, every term positive).
//!
//! **Schlick's weight** `Fc = (1 − v·h)⁵` (Schlick 1994) is `Fc = (1 − s/2)⁵` with `s = √z`,
//! so `D Fc = (α²/π) g(z)/y²` with `g(z) = z² Fc`, a polynomial `G(s) = s⁴ (1 − s/2)⁵` in s.
//! The lobe is the double pole y = 0 (z = M, s = s₀ = √M); subtracting it,
//!
//! `I₅ = ∫₀^π D Fc dφ = α² (g(M) S/r³ + g'(M)/r + (1/π) ∫₀^π R dφ)`,
//! `R = (g(z) − g(M) − g'(M)(z − M))/(z − M)² = P₂(s)/(s + s₀)²`,
//!
//! where `P₂` is G divided twice by (s − s₀) (synthetic division, exact up to rounding, so R
//! is evaluated without the cancellation of the first form). R is bounded, but as a function
//! of φ it is singular where z = 0, just outside [0, π] when both directions are near
//! grazing (z_min = P − Q = 4 cos²((θv + θl)/2)). The rule is therefore taken in s itself:
//! with `s = s_min + h (1 + cos ϑ)` (`s_min = √(P − Q)`, `s_max = √(P + Q)`,
//! `h = (s_max − s_min)/2`), `dφ = 2s dϑ/√((s + s_min)(s + s_max))`, so
//!
//! `∫₀^π R dφ = ∫₀^π R(s) 2s/√((s + s_min)(s + s_max)) dϑ`,
//!
//! whose integrand is analytic in ϑ except at s = −s_min, −s_max, −s₀, at a distance
//! proportional to s_min rather than s_min² from the interval. The trapezoid rule on this
//! even periodic integrand converges geometrically (Trefethen & Weideman 2014, "The
//! exponentially convergent trapezoidal rule", thm. 3.2), at a rate set by the distance of
//! the nearest singularity from the real axis. All of them lie on one line: with u = π − ϑ,
//! s = −σ (σ ∈ {s₀, s_min, s_max}) at u = ±i b_σ, `tanh(b_σ/2) = √(y/(2 + y))`,
//! `y = (s_min + σ)/h`; near grazing b_{s₀} is small. There the rule is taken in w,
//! `tan(u/2) = ε tan(w/2)` (a Möbius map of the period onto itself: nodes gather at s_min),
//! with `ε = √tanh(b_{s₀}/2)`. The map sends a singularity at u = i b to distance
//! `2 atanh(min(t/ε, ε/t))` from the real w axis, t = tanh(b/2), and the integrand has one
//! more: u → i∞ (s → ∞, where it grows like s⁵) is t = 1, w = π + 2i atanh(ε), a pole of
//! the integrand in w. This ε puts the nearest (s₀) and that farthest one at the same
//! distance `2 atanh(√tanh(b_{s₀}/2))`, wider than b_{s₀} (Trefethen & Weideman 2014, §3, on
//! conformal maps that widen the strip). (Until 2026-11-30 ε balanced s₀ against s_max and
//! left the pole from u → i∞ nearer than both: 3% more nodes.) The rule is applied with 1, 2,
//! 4, …, 64 intervals (nested) and T_N accepted from N = 4 on when |T_N − T_{N/2}| (the error of the
//! coarser rule, an over-estimate of T_N's) is within the inner tolerance — at N = 4 also
//! `|T_2 − T_1|²/max|R|`, which guards against T_4 and T_2 agreeing by chance before the
//! geometric regime (the guard of QUADPACK's estimates, Piessens et al. 1983, §2.2.1); where they do not
//! (both directions within a few degrees of grazing), the φ integral of D Fc is done by the
//! adaptive Gauss–Kronrod rule in ψ, `tan(φ/2) = √((S+Q)/(S−Q)) tan(ψ/2)`, which makes
//! `dφ/y = dψ/r` and the integrand `(α²/π) z² Fc (S − Q cos ψ)/r³` bounded.
//!
//! **The outer integral** over θl is split at θv (where the lobe peaks: near θl = θv,
//! `S − Q ≈ μv² ((θl − θv)² + 4α²)`) and warped there, `θl = θv ± w sinh t`, and, where the
//! horizon is far from θv, again near the horizon, where the masking turns over at
//! μl ≈ μv α/a_v (see `run`). In t the integrand is analytic in a strip |Im t| < ~π/2 (the
//! lobe's poles sit at sinh t = ±i·(lobe width)/w), so each panel is integrated whole by
//! nested Clenshaw–Curtis rules of 9, 17, 33, 65 nodes in t (Trefethen 2008, "Is Gauss
//! quadrature better than Clenshaw–Curtis?"), both channels at once, bisected only where
//! 65 nodes do not reach the tolerance. (Panels at most 1.5 long in t, wide lobes, went to
//! the adaptive G7/K15 rule until the outer estimate below replaced the interpolation bound:
//! since then Clenshaw–Curtis needs fewer lines there too.)
//!
//! **Error.** The outer rule's estimate plus a bound on the inner rules'. Clenshaw–Curtis
//! with n + 1 nodes integrates a Chebyshev polynomial T_m of degree m > n as its alias
//! T_{m'} (m' = m reflected into [0, n] modulo 2n: the two agree at the nodes), so on
//! [a, b] its error is exactly `((b − a)/2)·Σ_{m>n} a_m (I(T_m) − I(T_{m'}))`, a_m the
//! Chebyshev coefficients of f, `I(T_j) = 2/(1 − j²)` for even j and 0 for odd j (Trefethen
//! 2008, §5). The weights are small just above n (`8nj/(((n+j)² − 1)((n−j)² − 1))` at
//! m = n + j, j even; 0 for j odd) and reach ~2 only near m = 2n, where the alias is T_0:
//! the quadrature error is far below the interpolant's, `(b − a)·2Σ_{m>n}|a_m|` (Trefethen,
//! *Approximation Theory and Approximation Practice*, 2013, thm. 4.2). The tail is modelled
//! as `|a_{n+j}| ≤ Ĉ ρ^{−j}`: Ĉ the largest of the interpolant's top four computed
//! coefficients (the tail test of Chebfun's chopping, ATAP ch. 3), ρ their decay per degree
//! from the previous level's top four, `(Ĉ_{n/2}/Ĉ_n)^{2/n}`, but at most 2 — so the model's
//! tail is never lighter than `Σ_{m>n}|a_m| ≤ Ĉ`, the assumption of the interpolation bound
//! `(b − a)·2Ĉ`; that bound caps the estimate, and is the estimate where the coefficients do
//! not decay (ρ ≤ 1). The model's error is multiplied by `TAIL_SAFETY` = 10: the decay
//! need not stay geometric beyond n (near normal views it slows), and on a dense sample the
//! bare model came within 1.1× of the true error. (Until 2026-11-30 the estimate was the
//! interpolation bound itself, at n = 32 500–1,800 times this one for ρ = 1.5–2: most
//! panels stopped at 65 nodes instead of 33. |Q_n − Q_{n/2}| would be the error of the
//! coarser rule: it would need twice the nodes.) The estimate presumes accurate values: noise in them is no tail of
//! decaying coefficients, which is why the lines' values are computed without cancellation
//! (see `sin_half`). The inner rules':
//! an inner error δ(θl) on `(1/π)∫R dφ` moves the Schlick channel by
//! `∫ k α² δ dθl` with the line's weight `k = sin θl G2/(2μv)`, at most `(π/2) max(k α² δ)`;
//! each line is asked for `δ ≤ tol/(2π α² k)` (so lines near the horizon, where G2 → 0, are
//! cheap) and the bound from the δ actually reached is added to the estimate. A texel whose
//! total does not reach the tolerance returns `Err` and the caller falls back.

// Channel loops index several same-length arrays at once.
#![allow(clippy::needless_range_loop)]

use crate::numerics::sin_cos_taylor;
use crate::quadrature::adaptive::{integrate, Estimate, Tolerance};
use crate::quadrature::clenshaw_curtis::{rules, MAX_LEVEL};
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

/// Which masking term the GGX kernel uses: Smith's, or Schlick's approximation of it.
/// Each is a smooth function of (μv, μl) alone, which is all the reduction needs (the
/// module doc); the kernel takes it through the line weight `G2/(2μv)` and the scale of its
/// layer at the horizon (`Texel::g_fac`, `Texel::horizon_scale`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Smith {
    HeightCorrelated,
    Separable,
    /// Schlick's separable approximation `G1(μ) = μ/(μ(1 − k) + k)` (Schlick 1994, eq. 19;
    /// k = α/2 or (√α + 1)²/8 in Karis 2013), any k in (0, 1]: `G2/(2μv) = μl/(2 b(μv) b(μl))`
    /// with `b(μ) = μ(1 − k) + k`, finite as μv → 0.
    Schlick {
        k: f64,
    },
}

/// What this kernel does, for the sidecar's `quadrature.method`.
pub const METHOD: &str = "GGX split sum as a 1D integral over the light's polar angle (src/kernels/ggx_polar.rs): the azimuthal integral of D in closed form, that of D*Fc by the trapezoid rule after subtracting the lobe's double pole (adaptive Gauss-Kronrod in the pole-flattening variable where that does not converge), the polar integral by nested Clenshaw-Curtis (9 to 65 nodes, error from the Chebyshev coefficient tail integrated with the rule's aliasing, bisected where needed) on sinh-warped panels from theta_v; a texel whose estimate does not reach the tolerance goes to the 2D kernels";

/// The Möbius map of the azimuthal rule is used where the nearest singularity has
/// `tanh(b₀/2)` below this (b₀ ≲ 0.4: lines near grazing); elsewhere its gain did not pay
/// for its arithmetic (measured with examples/polar_cost.rs).
const MOBIUS_BELOW: f64 = 0.2;

/// Finest trapezoid level: 2^6 intervals on [0, π].
const MAX_LOG2: usize = 6;
const NTRAP: usize = 1 << MAX_LOG2;

/// `2^−l` for the levels l = 0 ..= [`MAX_LOG2`].
const INV_POW2: [f64; MAX_LOG2 + 1] = {
    let mut t = [1.0; MAX_LOG2 + 1];
    let mut l = 1;
    while l <= MAX_LOG2 {
        t[l] = 0.5 * t[l - 1];
        l += 1;
    }
    t
};

/// Where each level's new trapezoid nodes start in [`NodeTables`]' order: level 0 is the
/// two ends (N = 1), level l ≥ 1 the 2^(l−1) midpoints that N = 2^l adds.
const LEVEL_START: [usize; MAX_LOG2 + 2] = crate::quadrature::trapezoid::level_starts();

/// The trapezoid nodes ϑ = kπ/64 (k = 0..=64) in the order of their levels — k = 0, 64;
/// 32; 16, 48; 8, 24, 40, 56; … (increasing within a level, the order in which the sums
/// add them) — as `1 + cos(kπ/64) = 2 cos²(kπ/128)` (accurate near φ = π) and the same at
/// 64 − k, so that each level's nodes lie contiguous for [`Nodes::eval`].
struct NodeTables {
    opc: [f64; NTRAP + 1],
    opc_rev: [f64; NTRAP + 1],
}

fn node_tables() -> &'static NodeTables {
    static T: OnceLock<NodeTables> = OnceLock::new();
    T.get_or_init(|| {
        let one_plus_cos = |k: usize| {
            let c = (k as f64 * PI / (2 * NTRAP) as f64).cos();
            2.0 * c * c
        };
        let mut t = NodeTables {
            opc: [0.0; NTRAP + 1],
            opc_rev: [0.0; NTRAP + 1],
        };
        let mut i = 0;
        let mut put = |k: usize| {
            t.opc[i] = one_plus_cos(k);
            t.opc_rev[i] = one_plus_cos(NTRAP - k);
            i += 1;
        };
        for k in crate::quadrature::trapezoid::level_order(MAX_LOG2) {
            put(k);
        }
        t
    })
}

/// The integrand of one line's azimuthal rule, `R(s) ds/dϑ` at the trapezoid nodes
/// (times the Möbius map's Jacobian where it applies): see the module doc and
/// [`Texel::line`].
struct Nodes {
    /// `P₂` as coefficients of s⁰..s⁷.
    p2: [f64; 8],
    s0: f64,
    s_min: f64,
    s_max: f64,
    /// `(s_max − s_min)/2`.
    h: f64,
    /// The Möbius map's ε and ε² (ε = 1: no map).
    eps: f64,
    e2: f64,
}

impl Nodes {
    /// The values at the nodes `range` of [`NodeTables`]' order, into `out[range]`, with
    /// the Möbius map or without. On x86-64 with AVX2 the same code is compiled for it
    /// (four nodes per instruction): only additions, multiplications, divisions and square
    /// roots, each correctly rounded and none fused, in the same order, so both give the
    /// same bits.
    fn eval(&self, mobius: bool, range: std::ops::Range<usize>, out: &mut [f64; NTRAP + 1]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked above), all that `eval_avx2` requires.
            unsafe { self.eval_avx2(mobius, range, out) };
            return;
        }
        self.eval_portable(mobius, range, out);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn eval_avx2(
        &self,
        mobius: bool,
        range: std::ops::Range<usize>,
        out: &mut [f64; NTRAP + 1],
    ) {
        self.eval_portable(mobius, range, out);
    }

    #[inline(always)]
    fn eval_portable(
        &self,
        mobius: bool,
        range: std::ops::Range<usize>,
        out: &mut [f64; NTRAP + 1],
    ) {
        let t = node_tables();
        let out = &mut out[range.clone()];
        if mobius {
            let (opc, opc_rev) = (&t.opc[range.clone()], &t.opc_rev[range]);
            for ((o, &a), &b) in out.iter_mut().zip(opc).zip(opc_rev) {
                *o = self.at_mobius(a, b);
            }
        } else {
            for (o, &a) in out.iter_mut().zip(&t.opc[range]) {
                *o = self.at(a);
            }
        }
    }

    /// At ϑ with `opc` = 1 + cos ϑ: u = w, 1 − cos u = 1 + cos ϑ.
    #[inline(always)]
    fn at(&self, opc: f64) -> f64 {
        self.value(self.s_min + self.h * opc, 1.0)
    }

    /// At w with `opc` = 1 + cos w and `opc_rev` = 1 + cos(π − w): cos²(w/2) = opc/2,
    /// sin²(w/2) = opc_rev/2, and with den = cos²(w/2) + ε² sin²(w/2),
    /// 1 − cos u = 2ε² sin²(w/2)/den and du/dw = ε/den.
    #[inline(always)]
    fn at_mobius(&self, opc: f64, opc_rev: f64) -> f64 {
        let (cw, sw) = (0.5 * opc, 0.5 * opc_rev);
        let den = 1.0 / (cw + self.e2 * sw);
        self.value(
            self.s_min + self.h * 2.0 * self.e2 * sw * den,
            self.eps * den,
        )
    }

    /// `jac · R(s) · 2s/√((s + s_min)(s + s_max))`, R = P₂(s)/(s + s₀)².
    #[inline(always)]
    fn value(&self, sq: f64, jac: f64) -> f64 {
        let p2 = &self.p2;
        let mut p = p2[7];
        for c in (0..7).rev() {
            p = p * sq + p2[c];
        }
        let d = sq + self.s0;
        jac * p * 2.0 * sq / (d * d * ((sq + self.s_min) * (sq + self.s_max)).sqrt())
    }
}

/// `G(s) = s⁴ (1 − s/2)⁵ = z² Fc` as coefficients of s⁰..s⁹.
const G_COEF: [f64; 10] = [0.0, 0.0, 0.0, 0.0, 1.0, -2.5, 2.5, -1.25, 0.3125, -0.03125];

/// The view and roughness data of one texel.
struct Texel {
    mu_v: f64,
    sin_v: f64,
    theta_v: f64,
    a2: f64,
    /// `√(μv²(1 − α²) + α²)` (Λ(μv) = (a_v − μv)/(2μv)).
    a_v: f64,
    smith: Smith,
    /// Schlick's `b(μv) = μv(1 − k) + k` (unused by the Smith forms).
    b_v: f64,
    /// sin and cos of θv/2, and √(1 − α²): so that a line needs one sin_cos.
    half_v: (f64, f64),
    sqrt_1ma2: f64,
}

/// The azimuthal integrals at one θl: `[I₀, I₅]`, the inner error bound on (1/π)∫R dφ and
/// the evaluations spent.
struct Line {
    /// The line's weight in the θl integral, `sin θl G2/(2μv)`.
    k: f64,
    i0: f64,
    i5: f64,
    err: f64,
    evals: u64,
}

impl Texel {
    fn new(mu: f64, alpha: f64, smith: Smith) -> Texel {
        let a2 = alpha * alpha;
        let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
        let theta_v = sin_v.atan2(mu);
        Texel {
            mu_v: mu,
            sin_v,
            theta_v,
            a2,
            a_v: (mu * mu * (1.0 - a2) + a2).sqrt(),
            smith,
            b_v: match smith {
                Smith::Schlick { k } => mu * (1.0 - k) + k,
                _ => 0.0,
            },
            half_v: (0.5 * theta_v).sin_cos(),
            sqrt_1ma2: (1.0 - a2).sqrt(),
        }
    }

    /// `G2/(2μv)` at μl (every form; finite as μv → 0).
    fn g_fac(&self, mu_l: f64) -> f64 {
        match self.smith {
            // G2 = 2 μv μl/(μl a_v + μv a_l)
            Smith::HeightCorrelated => {
                let a_l = (mu_l * mu_l * (1.0 - self.a2) + self.a2).sqrt();
                mu_l / (mu_l * self.a_v + self.mu_v * a_l)
            }
            // G1(μ) = 2μ/(μ + a(μ))
            Smith::Separable => {
                let a_l = (mu_l * mu_l * (1.0 - self.a2) + self.a2).sqrt();
                2.0 * mu_l / ((self.mu_v + self.a_v) * (mu_l + a_l))
            }
            // G1(μv) G1(μl)/(2μv) = μl/(2 b(μv) b(μl)), b(μ) = μ(1 − k) + k
            Smith::Schlick { k } => mu_l / (2.0 * self.b_v * (mu_l * (1.0 - k) + k)),
        }
    }

    /// Where the line weight `G2/(2μv)` turns over near the horizon, in μl (see `run`):
    /// Smith's `λ = μv α/a_v` (≈ min(μv, α)); Schlick's `k/(1 − k)`, where
    /// `μl(1 − k) = k` (it does not depend on the view).
    fn horizon_scale(&self, alpha: f64) -> f64 {
        match self.smith {
            Smith::HeightCorrelated | Smith::Separable => self.mu_v * alpha / self.a_v,
            Smith::Schlick { k } => k / (1.0 - k),
        }
    }

    /// The azimuthal integrals at `theta_l` = θv + `delta` (both given: near the lobe's
    /// peak the offset carries digits that θl has lost); `tol_k` is the inner tolerance
    /// times the line's weight k (the inner rules are asked for `tol_k / k`).
    /// `vals` is scratch space for the azimuthal rule's node values.
    fn line(
        &self,
        theta_l: f64,
        delta: f64,
        tol_k: f64,
        with_fc: bool,
        vals: &mut [f64; NTRAP + 1],
    ) -> Line {
        self.setup(theta_l, delta, tol_k, with_fc).run(vals)
    }

    /// [`Texel::line`] at two points `(θl, δ)` at once, with scratch space for each: the
    /// same operations on each line, so the same bits, but the two lines' trapezoid levels
    /// run in lockstep. A line is a chain of dependent operations ending in a branch the
    /// CPU cannot predict (the level at which the rule stops): one line at a time left most
    /// of the core idle, two at a time let the chains overlap. Measured on filament-dfg at
    /// 128² (one thread, 21 interleaved runs, 2026-11-30): CPU time 34.8 → 32.2 ms (median),
    /// with 4% more instructions; four lines at a time were no faster than two.
    fn line_pair(
        &self,
        a: (f64, f64),
        b: (f64, f64),
        tol_k: f64,
        with_fc: bool,
        va: &mut [f64; NTRAP + 1],
        vb: &mut [f64; NTRAP + 1],
    ) -> [Line; 2] {
        let sa = self.setup(a.0, a.1, tol_k, with_fc);
        let sb = self.setup(b.0, b.1, tol_k, with_fc);
        // (by reference: a Setup is ~30 words, and moving two into a tuple showed in profiles)
        let (Setup::Trap(ta), Setup::Trap(tb)) = (&sa, &sb) else {
            return [sa.run(va), sb.run(vb)];
        };
        let mut sta = ta.start(va);
        let mut stb = tb.start(vb);
        let (mut ra, mut rb) = (None, None);
        for level in 1..=MAX_LOG2 {
            if ra.is_none() {
                ra = ta.step(&mut sta, level, va);
            }
            if rb.is_none() {
                rb = tb.step(&mut stb, level, vb);
            }
            if ra.is_some() && rb.is_some() {
                break;
            }
        }
        [
            ra.unwrap_or_else(|| ta.finish(&sta)),
            rb.unwrap_or_else(|| tb.finish(&stb)),
        ]
    }

    /// A line's closed forms, and its azimuthal rule set up where the Schlick-weighted
    /// part is asked for (`with_fc`).
    #[inline(always)]
    fn setup(&self, theta_l: f64, delta: f64, tol_k: f64, with_fc: bool) -> Setup {
        // (θl/2 ≤ π/4: a series, inlined; libm's call was ~7% of a bake's instructions)
        let (hs, hc) = sin_cos_taylor(0.5 * theta_l);
        let sin_l = 2.0 * hs * hc;
        let mu_l = (hc - hs) * (hc + hs);
        let k = self.g_fac(mu_l) * sin_l;
        let inner_tol = tol_k / k;
        let (mu_v, sin_v, a2) = (self.mu_v, self.sin_v, self.a2);
        // s_min = √(P − Q) = 2 cos((θv + θl)/2), s_max = √(P + Q) = 2 cos((θv − θl)/2)
        let (hsv, hcv) = self.half_v;
        let s_min = (2.0 * (hcv * hc - hsv * hs)).max(0.0);
        let s_max = 2.0 * (hcv * hc + hsv * hs);
        let m = (mu_v + mu_l) * (mu_v + mu_l);
        let big_m = m * (1.0 - a2);
        // S − Q = α²m + (sin θv − sin θl)², and sin θv − sin θl = −s_min sin(δ/2): as a
        // difference of sines it would carry an absolute rounding error ~1e-16, which near
        // the peak (|δ| ~ α) of a narrow lobe is relative noise ~1e-16/α in S − Q (1e-10 at
        // α = 1e-6), enough to stall the outer rule's convergence there
        let dsin = -s_min * sin_half(delta, hs, hc, self.half_v);
        let dm = a2 * m + dsin * dsin;
        let dp = a2 * m + (sin_v + sin_l) * (sin_v + sin_l);
        let s = 0.5 * (dm + dp);
        let q = 2.0 * sin_v * sin_l;
        let r = (dm * dp).sqrt();
        let j1 = 1.0 / r;
        let j2 = s / (r * r * r);
        let i0 = a2 * (1.0 + 2.0 * big_m * j1 + big_m * big_m * j2);
        if !with_fc {
            return Setup::Done(Line {
                k,
                i0,
                i5: 0.0,
                err: 0.0,
                evals: 1,
            });
        }

        // g(M), g'(M) and P₂ = G ÷ (s − s₀) ÷ (s − s₀) after removing g'(M)(s + s₀)
        let s0 = (mu_v + mu_l) * self.sqrt_1ma2;
        let u0 = 1.0 - 0.5 * s0;
        let u04 = u0 * u0 * u0 * u0;
        let g_m = big_m * big_m * u04 * u0;
        let dg_m = 0.5 * big_m * u04 * (4.0 - 4.5 * s0);
        let mut q1 = [0.0; 9];
        q1[8] = G_COEF[9];
        for k in (0..8).rev() {
            q1[k] = G_COEF[k + 1] + s0 * q1[k + 1];
        }
        q1[0] -= dg_m * s0;
        q1[1] -= dg_m;
        let mut p2 = [0.0; 8];
        p2[7] = q1[8];
        for k in (0..7).rev() {
            p2[k] = q1[k + 1] + s0 * p2[k + 1];
        }
        // in s = √z = 2 v·h ∈ [s_min, s_max] (see the module doc), s = s_min + h (1 + cos ϑ)
        let h = 0.5 * (s_max - s_min).max(0.0);
        // Möbius map of the period, u = π − ϑ, tan(u/2) = ε tan(w/2) (trapezoid nodes in w):
        // every singularity sits on the imaginary u axis, at u = i b_σ with
        // tanh(b_σ/2) = √(y_σ/(2 + y_σ)), y_σ = (s_min + σ)/h, σ ∈ {s₀, s_min, s_max}; the map
        // sends those with tanh(b/2) < ε to distance 2 atanh(tanh(b/2)/ε) from the real w axis
        // and the others to 2 atanh(ε/tanh(b/2)); u → i∞ (tanh = 1) is a pole in w, so
        // ε = √tanh(b₀/2) gives the nearest (s₀) and that farthest one the same distance —
        // the widest strip, hence the fastest geometric rate (Trefethen & Weideman 2014, §3) —
        // and ε = 1 is the identity.
        // tanh(b₀/2) < MOBIUS_BELOW ⟺ y₀/(2 + y₀) < MOBIUS_BELOW², tested without a division
        let b2 = MOBIUS_BELOW * MOBIUS_BELOW;
        let eps = if h > 0.0 && (1.0 - b2) * (s_min + s0) < 2.0 * b2 * h {
            let y0 = (s_min + s0) / h;
            (y0 / (2.0 + y0)).sqrt().sqrt().clamp(1e-6, 1.0)
        } else {
            1.0
        };
        let e2 = eps * eps;
        let nodes = Nodes {
            p2,
            s0,
            s_min,
            s_max,
            h,
            eps,
            e2,
        };
        let mobius = eps < 1.0;
        Setup::Trap(Trap {
            k,
            i0,
            inner_tol,
            a2,
            g_m,
            dg_m,
            j1,
            j2,
            dm,
            q,
            r,
            s_min,
            nodes,
            mobius,
        })
    }
}

/// A line after [`Texel::setup`]: finished (no Schlick-weighted part asked for), or its
/// azimuthal rule ready to run.
enum Setup {
    Done(Line),
    Trap(Trap),
}

impl Setup {
    #[inline(always)]
    fn run(self, vals: &mut [f64; NTRAP + 1]) -> Line {
        match self {
            Setup::Done(l) => l,
            Setup::Trap(t) => t.run(vals),
        }
    }
}

/// One line's azimuthal rule for `I₅`: the nodes, the line's closed-form parts, and what
/// the fallback rule in ψ needs.
struct Trap {
    k: f64,
    i0: f64,
    inner_tol: f64,
    a2: f64,
    g_m: f64,
    dg_m: f64,
    j1: f64,
    j2: f64,
    dm: f64,
    q: f64,
    r: f64,
    s_min: f64,
    nodes: Nodes,
    mobius: bool,
}

/// The trapezoid sums of a [`Trap`] so far: the running sum, max|R| over T_4's nodes (for
/// the guard), the nodes spent, and T_{N/4}, T_{N/2}.
struct TrapState {
    sum: f64,
    fmax: f64,
    evals: u64,
    t_prev: [f64; 2],
}

impl Trap {
    /// Trapezoid sums T_N on [0, π] (as means, T_N/π), nested by doubling from N = 1; T_N
    /// is accepted from N = 4 on with the estimate |T_N − T_{N/2}| (the error of the
    /// coarser rule), at N = 4 guarded against a chance agreement by |T_2 − T_1|²/max|R|;
    /// where no level is accepted, the rule in ψ ([`i5_psi`]).
    #[inline(always)]
    fn run(&self, vals: &mut [f64; NTRAP + 1]) -> Line {
        let mut st = self.start(vals);
        for level in 1..=MAX_LOG2 {
            if let Some(l) = self.step(&mut st, level, vals) {
                return l;
            }
        }
        self.finish(&st)
    }

    /// The nodes of levels 0–2 (the nodes in the order of their levels, `node_tables`,
    /// each level's computed at once) and T_1.
    #[inline(always)]
    fn start(&self, vals: &mut [f64; NTRAP + 1]) -> TrapState {
        self.nodes.eval(self.mobius, 0..LEVEL_START[3], vals);
        let sum = 0.5 * (vals[0] + vals[1]);
        let mut fmax = vals[0].abs().max(vals[1].abs());
        for v in &vals[2..LEVEL_START[3]] {
            fmax = fmax.max(v.abs());
        }
        TrapState {
            sum,
            fmax,
            evals: 2,
            t_prev: [0.0, sum],
        }
    }

    /// Level `level` (T_N, N = 2^level): the line if it is accepted there.
    #[inline(always)]
    fn step(&self, st: &mut TrapState, level: usize, vals: &mut [f64; NTRAP + 1]) -> Option<Line> {
        let new = LEVEL_START[level]..LEVEL_START[level + 1];
        if level > 2 {
            self.nodes.eval(self.mobius, new.clone(), vals);
        }
        for v in &vals[new.clone()] {
            st.sum += v;
        }
        st.evals += new.len() as u64;
        // (T_N/N: a multiplication by 2^−level, exactly the division's result, off the
        // exit test's critical path)
        let cur = st.sum * INV_POW2[level];
        let mut d = (cur - st.t_prev[1]).abs();
        if level == 2 {
            let d2 = (st.t_prev[1] - st.t_prev[0]).abs();
            d = d.max(d2 * d2 / st.fmax.max(self.inner_tol));
        }
        if level >= 2 && d <= self.inner_tol && cur.is_finite() {
            let i5 = self.a2 * (self.g_m * self.j2 + self.dg_m * self.j1 + cur);
            return Some(Line {
                k: self.k,
                i0: self.i0,
                i5,
                err: d,
                evals: st.evals,
            });
        }
        st.t_prev = [st.t_prev[1], cur];
        None
    }

    /// The fallback where no trapezoid level is accepted.
    fn finish(&self, st: &TrapState) -> Line {
        let p_m_q = self.s_min * self.s_min;
        let (i5, err, n) = i5_psi(self.dm, self.q, self.r, p_m_q, self.a2, self.inner_tol);
        Line {
            k: self.k,
            i0: self.i0,
            i5,
            err,
            evals: st.evals + n,
        }
    }
}

/// `sin(δ/2)` for δ = θl − θv, given the half angles' sines and cosines: from δ itself
/// where |δ/2| < 0.05 (its Taylor series to x⁹; the first term left out, x¹¹/11!, is below
/// 2e-22 relative), else as `sin(θl/2 − θv/2)` from the half angles (absolute error ~2e-16,
/// below 5e-15 relative there).
fn sin_half(delta: f64, hs: f64, hc: f64, (hsv, hcv): (f64, f64)) -> f64 {
    let x = 0.5 * delta;
    if x.abs() < 0.05 {
        let x2 = x * x;
        x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))))
    } else {
        hs * hcv - hc * hsv
    }
}

/// `I₅ = ∫₀^π D Fc dφ` by the adaptive Gauss–Kronrod rule in ψ, `tan(φ/2) = √((S+Q)/(S−Q))
/// tan(ψ/2)`: then `dφ/(S + Q cos φ) = dψ/r`, `S + Q cos φ = r²/(S − Q cos ψ)` and
/// `1 + cos φ = (S − Q)(1 + cos ψ)/(S − Q cos ψ)`, so `D Fc dφ = (α²/π) z² Fc (S − Q cos ψ)/r³ dψ`
/// is bounded (`dm` = S − Q, `q` = Q, `p_m_q` = P − Q). Returns the value, its error on
/// `(1/π)∫R dφ` (I₅'s error divided by α², the unit of `inner_tol`) and the evaluations.
fn i5_psi(dm: f64, q: f64, r: f64, p_m_q: f64, a2: f64, inner_tol: f64) -> (f64, f64, u64) {
    let scale = a2 / (PI * r * r * r);
    let tol = Tolerance {
        abs: (inner_tol * a2).max(f64::MIN_POSITIVE),
        initial_panels: 2,
        max_depth: 20,
        noise_floor: 0.0,
        max_evals: 1 << 14,
    };
    let e = integrate(
        |psi: f64| {
            let (sh, chh) = (0.5 * psi).sin_cos();
            let den = dm + q * 2.0 * sh * sh; // S − Q cos ψ
            let z = p_m_q + q * dm * 2.0 * chh * chh / den;
            let u = 1.0 - 0.5 * z.sqrt();
            let u2 = u * u;
            [scale * z * z * u2 * u2 * u * den]
        },
        0.0,
        PI,
        tol,
    );
    (e.value[0], e.error[0] / a2, e.evals)
}

/// Number of top Chebyshev coefficients whose largest bounds the outer rule's error.
const TAIL: usize = 4;

/// `(2/n)·w_j·cos(π j m/n)` (w_j = ½ at the ends, else 1) for the top [`TAIL`] degrees `m = n − TAIL + 1 ..= n` of every level
/// `n = 2^k` (k = 0..=MAX_LEVEL, rows of `TAIL·(n + 1)`; empty below n = TAIL), taken from the
/// Clenshaw–Curtis nodes `cos(iπ/2^MAX_LEVEL)` so that they are exact to the same bits.
fn tail_cos() -> &'static Vec<Vec<f64>> {
    static T: OnceLock<Vec<Vec<f64>>> = OnceLock::new();
    T.get_or_init(|| {
        let r = rules();
        (0..=MAX_LEVEL)
            .map(|k| {
                let n = 1usize << k;
                let stride = 1usize << (MAX_LEVEL - k);
                let mut v = Vec::new();
                if n >= TAIL {
                    for m in (n + 1 - TAIL)..=n {
                        for j in 0..=n {
                            let p = (j * m) % (2 * n);
                            let i = if p <= n { p } else { 2 * n - p };
                            let w = if j == 0 || j == n { 1.0 } else { 2.0 };
                            v.push(w / n as f64 * r.x[i * stride]);
                        }
                    }
                }
                v
            })
            .collect()
    })
}

/// The factor on the outer estimate's tail model (module doc, "Error"). Measured with
/// examples/polar_check.rs and on a 100 × 100 grid of (√μ, √α) plus μ = 1 at tolerances
/// 1e-7 … 1e-9 against the kernel at 1e-13: without it the largest true error / estimate
/// was 1.12 (μ = 1, α = 0.19, where the coefficients' decay slows beyond n), with it 0.16.
const TAIL_SAFETY: f64 = 10.0;
/// The fastest decay per degree the outer estimate's tail model assumes (module doc,
/// "Error"): at 2, `Σ_{j≥1} Ĉ 2^{−j} = Ĉ`, the tail sum the interpolation bound assumed.
const TAIL_MAX_DECAY: f64 = 2.0;
// (`cc_tail` skips the power for ratios from 2^{n/2} on: the cap must be 2)
const _: () = assert!(TAIL_MAX_DECAY == 2.0);

/// `Σ_{j≥1} ρ^{−j} |I(T_{n+j}) − I(T_{m'})|`, m' the alias of n + j under the
/// Clenshaw–Curtis rule with n + 1 nodes (module doc, "Error"): the quadrature error of a
/// tail `|a_{n+j}| = ρ^{−j}` on [−1, 1]. Summed until the rest, whose terms are each at most
/// 4 (|I(T_j)| ≤ 2), is below 1e-3 of the sum (or from m = 32n on, for ρ near 1), and
/// that rest's bound added; `rho` > 1, n a power of two from 2^[`OUTER_MIN_LEVEL`] to
/// 2^[`OUTER_MAX_LEVEL`]. Returns early, with the partial sum, once that reaches `enough`
/// (where the caller's estimate is capped anyway: for ρ near 1 the full sum takes 31n
/// terms). The differences come from [`alias_diffs`]: this runs once per panel, level and
/// channel.
fn alias_weight(n: usize, rho: f64, enough: f64) -> f64 {
    // the most common ρ (the decay model's cap) from a table: the same sum, so the same
    // bits, wherever the early return would not have cut it short
    if rho == TAIL_MAX_DECAY {
        static AT_MAX: OnceLock<Vec<f64>> = OnceLock::new();
        let at_max = AT_MAX.get_or_init(|| {
            (OUTER_MIN_LEVEL..=OUTER_MAX_LEVEL)
                .map(|k| alias_weight_sum(1 << k, TAIL_MAX_DECAY, f64::INFINITY))
                .collect()
        });
        let w = at_max[n.trailing_zeros() as usize - OUTER_MIN_LEVEL];
        if w < enough {
            return w;
        }
    }
    alias_weight_sum(n, rho, enough)
}

fn alias_weight_sum(n: usize, rho: f64, enough: f64) -> f64 {
    let q = 1.0 / rho;
    let rest = |f: f64| 4.0 * f * q / (1.0 - q);
    let (mut f, mut w) = (1.0, 0.0);
    for (j, &diff) in alias_diffs(n).iter().enumerate() {
        let m = n + 1 + j;
        f *= q;
        w += f * diff;
        if w >= enough {
            return w;
        }
        if m > 2 * n && rest(f) <= 1e-3 * w {
            break;
        }
    }
    w + rest(f)
}

/// `|I(T_m) − I(T_{m'})|` for m = n + 1 ..= 32n (m' the alias of m under n + 1 nodes,
/// `I(T_j) = 2/(1 − j²)` for even j, 0 for odd), for n = 2^k, k = [`OUTER_MIN_LEVEL`]
/// ..= [`OUTER_MAX_LEVEL`].
fn alias_diffs(n: usize) -> &'static [f64] {
    static T: OnceLock<Vec<Vec<f64>>> = OnceLock::new();
    let t = T.get_or_init(|| {
        let integral = |j: usize| {
            if j % 2 == 1 {
                0.0
            } else {
                2.0 / (1.0 - (j * j) as f64)
            }
        };
        (OUTER_MIN_LEVEL..=OUTER_MAX_LEVEL)
            .map(|k| {
                let n = 1usize << k;
                (n + 1..=32 * n)
                    .map(|m| {
                        let r = m % (2 * n);
                        let alias = if r <= n { r } else { 2 * n - r };
                        (integral(m) - integral(alias)).abs()
                    })
                    .collect()
            })
            .collect()
    });
    &t[n.trailing_zeros() as usize - OUTER_MIN_LEVEL]
}

/// First and last Clenshaw–Curtis level of the outer rule: 2^3 + 1 = 9 to 2^6 + 1 = 65 nodes.
const OUTER_MIN_LEVEL: usize = 3;
const OUTER_MAX_LEVEL: usize = 6;
/// Most θl lines one panel may spend (bisections included): a pathological integrand costs
/// bounded time and reports the error it reached.
const OUTER_MAX_LINES: u64 = 1 << 12;

/// ∫ₐᵇ f (both channels) by nested Clenshaw–Curtis levels [`OUTER_MIN_LEVEL`]`..=`
/// [`OUTER_MAX_LEVEL`], stopping at the first whose estimate (the module doc's "Error") is at
/// most `tol` in both channels, else bisected (to `depth` levels, within `lines` of
/// [`OUTER_MAX_LINES`]). Adds value and error to `out`, the lines used to `lines`. `f(x, None)`
/// is f at x (in its first entry), `f(x, Some(y))` f at x and at y (so that it can compute two
/// lines at once, [`Texel::line_pair`]).
fn cc_tail<F: FnMut(f64, Option<f64>) -> [[f64; 2]; 2]>(
    f: &mut F,
    (a, b): (f64, f64),
    tol: f64,
    depth: u32,
    out: &mut Estimate<2>,
    lines: &mut u64,
) {
    // values at the nodes of the finest outer level, local index l ↔ node cos(lπ/2^6)
    // (the rules' global index l·G)
    const NV: usize = (1 << OUTER_MAX_LEVEL) + 1;
    const G: usize = 1 << (MAX_LEVEL - OUTER_MAX_LEVEL);
    let r = rules();
    let tc = tail_cos();
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let mut vals = [[0.0f64; 2]; NV];
    let mut last = Estimate::<2>::zero();
    // Ĉ of the previous level, per channel (the decay rate's reference)
    let mut prev_top = [0.0f64; 2];
    for k in 1..=OUTER_MAX_LEVEL {
        let ls = 1usize << (OUTER_MAX_LEVEL - k);
        // the new nodes of level k: all three at k = 1, else the odd multiples of ls
        let (mut l, step) = if k == 1 { (0, ls) } else { (ls, 2 * ls) };
        // (two at a time where there are two: `f` then runs both lines in lockstep)
        while l < NV {
            let x = mid + half * r.x[l * G];
            if l + step < NV {
                let [va, vb] = f(x, Some(mid + half * r.x[(l + step) * G]));
                vals[l] = va;
                vals[l + step] = vb;
                *lines += 2;
                l += 2 * step;
            } else {
                vals[l] = f(x, None)[0];
                *lines += 1;
                l += step;
            }
        }
        if k + 1 < OUTER_MIN_LEVEL {
            continue;
        }
        // Ĉ: the largest of the interpolant's top TAIL coefficients
        // c_m = (2/n) Σ'' v_j cos(π j m/n)
        let n = 1usize << k;
        // (node by node, each coefficient's sum in the order of the nodes: eight independent
        // sums rather than two at a time)
        let rows = &tc[k];
        let mut cm = [[0.0f64; 2]; TAIL];
        if !rows.is_empty() {
            for j in 0..=n {
                let v = vals[j * ls];
                for (m, c) in cm.iter_mut().enumerate() {
                    let t = rows[m * (n + 1) + j];
                    c[0] += t * v[0];
                    c[1] += t * v[1];
                }
            }
        }
        let mut top = [0.0f64; 2];
        for c in &cm {
            for ch in 0..2 {
                top[ch] = top[ch].max(c[ch].abs());
            }
        }
        if k < OUTER_MIN_LEVEL {
            prev_top = top;
            continue;
        }
        let mut q = [0.0f64; 2];
        for (j, &w) in r.w[k].iter().enumerate() {
            for c in 0..2 {
                q[c] += w * vals[j * ls][c];
            }
        }
        let mut err = [0.0f64; 2];
        for c in 0..2 {
            // the interpolation bound (b − a)·2Ĉ, and the model's tail (module doc, "Error")
            let bound = 4.0 * half * top[c];
            // ρ = (Ĉ_{n/2}/Ĉ_n)^{2/n} capped at TAIL_MAX_DECAY = 2, with the power only where
            // it matters (pow was ~2% of a bake's time): a ratio from 2^{n/2} on is the cap, as
            // is NaN (0/0, which `min` sent there too), and one ≤ 1 means no decay either way
            let ratio = prev_top[c] / top[c];
            let rho = if ratio.is_nan() || ratio >= (1u64 << (n / 2)) as f64 {
                TAIL_MAX_DECAY
            } else if ratio > 1.0 {
                ratio.powf(2.0 / n as f64).min(TAIL_MAX_DECAY)
            } else {
                ratio
            };
            // (a weight ≥ 1.025·4/TAIL_SAFETY puts the model above the bound)
            err[c] = if rho > 1.0 {
                let w = alias_weight(n, rho, 4.1 / TAIL_SAFETY);
                bound.min(TAIL_SAFETY * half * top[c] * w)
            } else {
                bound
            };
        }
        prev_top = top;
        last = Estimate {
            value: [q[0] * half, q[1] * half],
            error: err,
            evals: 0,
        };
        if err.iter().all(|&e| e <= tol) && last.value.iter().all(|v| v.is_finite()) {
            break;
        }
    }
    let done = last.error.iter().all(|&e| e <= tol);
    if done || depth == 0 || *lines >= OUTER_MAX_LINES || !last.error.iter().all(|e| e.is_finite())
    {
        for c in 0..2 {
            out.value[c] += last.value[c];
            out.error[c] += last.error[c];
        }
        return;
    }
    cc_tail(f, (a, mid), 0.5 * tol, depth - 1, out, lines);
    cc_tail(f, (mid, b), 0.5 * tol, depth - 1, out, lines);
}

/// The GGX split sum `[∫(1 − Fc) f cos, ∫ Fc f cos]` (F = 1) at view cosine `mu` and
/// roughness `alpha` ∈ (0, 1], to absolute tolerance `tol` per channel (estimated);
/// `Err(evaluations spent)` where the estimate does not reach it. Evaluations count the
/// outer nodes and the inner (azimuthal) nodes alike.
pub fn ggx_split_sum(mu: f64, alpha: f64, smith: Smith, tol: f64) -> Result<Estimate<2>, u64> {
    run(mu, alpha, smith, tol, true)
}

/// The GGX single-scattering albedo `∫ f cos` (F = 1) alone: the same integral as the sum of
/// [`ggx_split_sum`]'s channels, with the azimuthal integral in closed form everywhere (one
/// evaluation per θl node), to absolute tolerance `tol` (estimated).
pub fn ggx_albedo(mu: f64, alpha: f64, smith: Smith, tol: f64) -> Result<Estimate<1>, u64> {
    let e = run(mu, alpha, smith, tol, false)?;
    // channel 1 (the Schlick-weighted part) was not integrated: it is 0, its error too
    Ok(Estimate {
        value: [e.value[0]],
        error: [e.error[0]],
        evals: e.evals,
    })
}

/// The sinh warp from θv has scale `w = min(2α, WARP_LAMBDA·λ)` (λ = μv α/a_v, see `run`).
/// As λ ≤ α, at factor 1 (until 2026-11-30) w was λ alone. A wider w shortens each panel in
/// t (its length is asinh(panel/w)) and moves the lobe's poles, at sinh t = ±i·2α/w, toward
/// the panel's end at t = 0, where Clenshaw–Curtis gathers its nodes; past ~3λ the shorter
/// panels stop paying. Measured (outer lines, filament-dfg 128² / 512², 2026-11-30): factor 1
/// 127.7k / 322.6k, 2 115.1k / 254.4k, 2.5 114.7k / 253.0k, 3 114.4k / 252.1k, 4 114.4k /
/// 252.2k; 3 on the lower panel with 1.5 or 2 on the upper cost 1.9% and 0.1% more; the cap
/// at 0.7·2α or 1.2·2α, 1–2% more. Instructions (cachegrind, one thread) 262 → 242 M at 128².
/// The estimates still bound the errors: `examples/polar_check.rs 100 100` (10,000 points,
/// two tolerances, both channels) finds none outside, largest error/estimate 0.28 (0.81 at
/// factor 1, at a point whose estimate is ~5e-12).
const WARP_LAMBDA: f64 = 3.0;

fn run(mu: f64, alpha: f64, smith: Smith, tol: f64, with_fc: bool) -> Result<Estimate<2>, u64> {
    if !(mu > 0.0 && mu <= 1.0 && alpha > 0.0 && alpha <= 1.0 && tol > 0.0) {
        return Err(0);
    }
    if let Smith::Schlick { k } = smith {
        if !(k > 0.0 && k < 1.0) {
            return Err(0);
        }
    }
    let t = Texel::new(mu, alpha, smith);
    let a2 = t.a2;
    let theta_v = t.theta_v;
    // Scales of the integrand's features in θl: the lobe, S − Q ≈ μv²((θl − θv)² + 4α²),
    // and the masking layer at the horizon, where G2/(2μv) = μl/(μl a_v + μv a_l) turns
    // over at μl ≈ λ = μv α/a_v (≈ min(μv, α); Schlick's form at k/(1 − k):
    // `Texel::horizon_scale`). Panels: [0, θv] and [θv, π/2] warped from
    // θv at w = min(2α, [`WARP_LAMBDA`]·λ); where the horizon is far from θv compared with
    // λ, the upper one ends at θb = π/2 − √(dλ) and [θb, π/2] is warped from the horizon.
    let lambda = t.horizon_scale(alpha);
    let w = (2.0 * alpha).min(WARP_LAMBDA * lambda);
    let d_h = FRAC_PI_2 - theta_v;
    let split = d_h > 16.0 * lambda;
    let hz = if split { (d_h * lambda).sqrt() } else { 0.0 };
    // (origin, direction, scale, length, whether the origin is θv)
    let panels = [
        (theta_v, -1.0, w, theta_v, true),
        (theta_v, 1.0, w, d_h - hz, true),
        (FRAC_PI_2, -1.0, lambda, hz, false),
    ];
    let mut inner_err = 0.0f64;
    let mut evals = 0u64;
    let mut scratch = [[0.0f64; NTRAP + 1]; 2];
    let mut total = Estimate::<2>::zero();
    // each panel's outer rule within tol/8 per channel (three panels, two channels summed
    // into channel 0, and the inner rules' tol/4: at most tol in all)
    let outer_tol = 0.125 * tol;
    for (origin, sign, scale, len, from_v) in panels {
        if len <= 0.0 {
            continue;
        }
        let t_max = (len / scale).asinh();
        let node = |x: f64| {
            // sinh and cosh from one expm1: with e = e^x − 1, sinh x = e(e + 2)/(2(e + 1))
            // (no cancellation near 0) and cosh x = sinh x + 1/(e + 1)
            let e = x.exp_m1();
            let inv = 1.0 / (e + 1.0);
            let sh = 0.5 * e * (e + 2.0) * inv;
            let off = sign * scale * sh;
            let theta_l = (origin + off).clamp(0.0, FRAC_PI_2);
            // θl − θv: exact from the offset on the panels from θv
            let delta = if from_v {
                off.clamp(-theta_v, FRAC_PI_2 - theta_v)
            } else {
                theta_l - theta_v
            };
            (theta_l, delta, scale * (sh + inv))
        };
        // an inner error δ on the line of weight k moves the result by k·α²·δ per unit θl:
        // δ ≤ tol/(2π α² k) keeps the sum ≤ tol/4
        let tol_k = tol / (2.0 * PI * a2);
        let mut f = |x: f64, y: Option<f64>| {
            let (ta, da, ja) = node(x);
            let mut put = |l: &Line, jac: f64| {
                inner_err = inner_err.max(l.k * a2 * l.err);
                evals += l.evals;
                [l.k * jac * l.i0, l.k * jac * l.i5]
            };
            match y {
                None => {
                    let l = t.line(ta, da, tol_k, with_fc, &mut scratch[0]);
                    [put(&l, ja), [0.0; 2]]
                }
                Some(y) => {
                    let (tb, db, jb) = node(y);
                    let [sa, sb] = &mut scratch;
                    let [la, lb] = t.line_pair((ta, da), (tb, db), tol_k, with_fc, sa, sb);
                    [put(&la, ja), put(&lb, jb)]
                }
            }
        };
        let mut e = Estimate::<2>::zero();
        let mut lines = 0u64;
        cc_tail(&mut f, (0.0, t_max), outer_tol, 12, &mut e, &mut lines);
        for c in 0..2 {
            total.value[c] += e.value[c];
            total.error[c] += e.error[c];
        }
    }
    total.evals = evals;
    let inner = FRAC_PI_2 * inner_err;
    let [e_all, e_fc] = total.value;
    let [err_all, err_fc] = total.error;
    let out = Estimate {
        value: [e_all - e_fc, e_fc],
        error: [err_all + err_fc + inner, err_fc + inner],
        evals,
    };
    let ok = out.value.iter().all(|v| v.is_finite())
        && out.error.iter().all(|e| e.is_finite() && *e <= tol);
    if ok {
        Ok(out)
    } else {
        Err(evals)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sin_half` against libm's `sin(δ/2)` on both sides of its branch (|δ/2| = 0.05) and
    /// down to δ = 1e-12: within 4e-15 relative (the series is exact to ~1e-22 below the
    /// branch, the half-angle products have absolute error ~2e-16 above it, where
    /// |sin(δ/2)| ≥ 0.05; libm's own error ≤ 1 ulp).
    #[test]
    fn sin_half_is_accurate_on_both_branches() {
        let theta_v: f64 = 0.9;
        let mut deltas = vec![
            1e-12, 1e-9, 1e-6, 1e-3, 0.0999, 0.1, 0.1001, 0.3, -0.5, -0.0999,
        ];
        deltas.extend((1..=40).map(|i| 0.005 * i as f64 * if i % 2 == 0 { 1.0 } else { -1.0 }));
        for delta in deltas {
            let theta_l = theta_v + delta;
            let got = sin_half(
                delta,
                (0.5 * theta_l).sin(),
                (0.5 * theta_l).cos(),
                (0.5 * theta_v).sin_cos(),
            );
            let want = (0.5 * delta).sin();
            assert!(
                (got - want).abs() <= 4e-15 * want.abs(),
                "delta {delta}: {got} vs {want}"
            );
        }
    }

    /// The azimuthal rule's node values are the same bits through the AVX2 path as through
    /// the portable one (each operation correctly rounded and none fused), with and without
    /// the Möbius map, on the lines of several texels; and the nodes in level order are the
    /// nodes kπ/64, each once.
    #[test]
    fn node_values_are_the_same_bits_on_every_path() {
        let t = node_tables();
        let mut ks: Vec<usize> = (0..=NTRAP)
            .map(|i| {
                let k = (t.opc[i] / 2.0).sqrt().acos() * (2 * NTRAP) as f64 / PI;
                k.round() as usize
            })
            .collect();
        ks.sort_unstable();
        assert_eq!(ks, (0..=NTRAP).collect::<Vec<_>>());
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            let mut checked = 0;
            for &(mu, alpha) in &[(0.7, 0.3), (0.02, 0.05), (0.95, 0.6), (0.05, 0.9)] {
                for &eps in &[1.0, 0.3, 0.01] {
                    let s0 = 1.3 * mu + 0.1 * alpha;
                    let nodes = Nodes {
                        p2: [0.7, -1.1, 0.3, 2.0 * mu, -alpha, 0.02, -0.31, 0.03125],
                        s0,
                        s_min: 0.05 * mu,
                        s_max: 1.9 - alpha,
                        h: 0.5 * (1.9 - alpha - 0.05 * mu),
                        eps,
                        e2: eps * eps,
                    };
                    let (mut a, mut b) = ([0.0; NTRAP + 1], [0.0; NTRAP + 1]);
                    nodes.eval_portable(eps < 1.0, 0..NTRAP + 1, &mut a);
                    // SAFETY: the CPU has AVX2 (checked above).
                    unsafe { nodes.eval_avx2(eps < 1.0, 0..NTRAP + 1, &mut b) };
                    for i in 0..=NTRAP {
                        assert_eq!(a[i].to_bits(), b[i].to_bits(), "node {i}");
                        assert!(a[i].is_finite());
                    }
                    checked += 1;
                }
            }
            assert_eq!(checked, 12);
        }
    }

    /// Two lines at once ([`Texel::line_pair`]) are the same bits as each alone
    /// ([`Texel::line`]): k, I₀, I₅, error and evaluations, with and without the
    /// Schlick-weighted part, on lines that stop at every trapezoid level, use the Möbius map,
    /// or fall back to the rule in ψ (both directions within a degree of grazing).
    #[test]
    fn line_pairs_are_the_lines_alone() {
        let same = |a: &Line, b: &Line| {
            a.k.to_bits() == b.k.to_bits()
                && a.i0.to_bits() == b.i0.to_bits()
                && a.i5.to_bits() == b.i5.to_bits()
                && a.err.to_bits() == b.err.to_bits()
                && a.evals == b.evals
        };
        let (mut fallbacks, mut mobius, mut checked) = (0, 0, 0);
        let mut levels = std::collections::BTreeSet::new();
        for &(mu, alpha) in &[
            (0.9, 0.5),
            (0.5, 0.05),
            (0.02, 0.3),
            (0.01, 1e-3),
            (1e-4, 0.1),
        ] {
            let t = Texel::new(mu, alpha, Smith::HeightCorrelated);
            let thetas: Vec<f64> = (0..24)
                .map(|i| {
                    // spread over [0, π/2], denser at the horizon (with the view within
                    // 0.006° of it, the lines within 0.2° fall back) and around θv
                    let u = (i as f64 + 0.5) / 24.0;
                    if i % 3 == 0 {
                        FRAC_PI_2 - 0.004 * u
                    } else if i % 3 == 1 {
                        (t.theta_v + 0.3 * (u - 0.5) * alpha).clamp(0.0, FRAC_PI_2)
                    } else {
                        FRAC_PI_2 * u
                    }
                })
                .collect();
            for with_fc in [true, false] {
                for w in thetas.windows(2) {
                    let (ta, tb) = (w[0], w[1]);
                    let tol_k = 1e-9 / (2.0 * PI * t.a2);
                    let mut v = [[0.0; NTRAP + 1]; 3];
                    let la = t.line(ta, ta - t.theta_v, tol_k, with_fc, &mut v[0]);
                    let lb = t.line(tb, tb - t.theta_v, tol_k, with_fc, &mut v[0]);
                    let [v1, v2] = &mut [v[1], v[2]];
                    let [pa, pb] = t.line_pair(
                        (ta, ta - t.theta_v),
                        (tb, tb - t.theta_v),
                        tol_k,
                        with_fc,
                        v1,
                        v2,
                    );
                    assert!(
                        same(&la, &pa) && same(&lb, &pb),
                        "θl {ta}, {tb} at μ {mu}, α {alpha}"
                    );
                    checked += 1;
                    if let Setup::Trap(tr) = t.setup(ta, ta - t.theta_v, tol_k, with_fc) {
                        mobius += usize::from(tr.mobius);
                    }
                    if la.evals > NTRAP as u64 + 1 {
                        fallbacks += 1;
                    } else if with_fc {
                        levels.insert(la.evals);
                    }
                }
            }
        }
        assert_eq!(checked, 5 * 2 * 23);
        assert!(fallbacks > 0, "no line fell back to the rule in ψ");
        assert!(mobius > 0, "no line used the Möbius map");
        assert!(levels.len() >= 3, "lines stopped at levels {levels:?} only");
    }

    /// The closed-form I₀ equals a brute-force φ integral of GGX's D, and I₅ (subtracted
    /// trapezoid, and the fallback rule in ψ) equals one of D·Fc: the rational form of D,
    /// the pole subtraction and the substitutions are exact identities, so only the brute-force rule's error (composite Simpson with 2e5
    /// panels on a peak resolved to ≥ 50 nodes: relative ~1e-12) remains.
    #[test]
    fn azimuthal_integrals_match_brute_force() {
        for &(mu_v, alpha) in &[
            (0.7, 0.3),
            (0.2, 0.05),
            (0.95, 0.6),
            (0.4, 1.0),
            (0.05, 0.2),
        ] {
            let sin_v = (1.0f64 - mu_v * mu_v).sqrt();
            let a2: f64 = alpha * alpha;
            let t = Texel::new(mu_v, alpha, Smith::HeightCorrelated);
            for &theta_l in &[0.1, 0.5, t.theta_v, 1.2, 1.5] {
                let (sl, ml): (f64, f64) = theta_l.sin_cos();
                let n = 200_000;
                let (mut s0, mut s5) = (0.0, 0.0);
                for i in 0..=n {
                    let phi = PI * i as f64 / n as f64;
                    let w = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    let c = mu_v * ml + sin_v * sl * phi.cos();
                    let nh2 = (mu_v + ml) * (mu_v + ml) / (2.0 + 2.0 * c);
                    let den = nh2 * (a2 - 1.0) + 1.0;
                    let d = a2 / (PI * den * den);
                    let vh = ((1.0 + c) / 2.0).max(0.0).sqrt();
                    s0 += w * d;
                    s5 += w * d * (1.0 - vh).powi(5);
                }
                let h = PI / n as f64 / 3.0;
                let l = t.line(
                    theta_l,
                    theta_l - t.theta_v,
                    1e-13 * t.g_fac(ml) * sl,
                    true,
                    &mut [0.0; NTRAP + 1],
                );
                let (b0, b5) = (s0 * h, s5 * h);
                assert!((l.i0 - b0).abs() <= 1e-10 * b0, "I0 {} vs {b0}", l.i0);
                assert!((l.i5 - b5).abs() <= 1e-10 * b0, "I5 {} vs {b5}", l.i5);
                // the fallback rule in ψ on its own
                let m = (mu_v + ml) * (mu_v + ml);
                let dm = a2 * m + (sin_v - sl) * (sin_v - sl);
                let dp = a2 * m + (sin_v + sl) * (sin_v + sl);
                let ch = (0.5 * (t.theta_v + theta_l)).cos();
                let q = 2.0 * sin_v * sl;
                let (p5, _, _) = i5_psi(dm, q, (dm * dp).sqrt(), 4.0 * ch * ch, a2, 1e-13);
                assert!((p5 - b5).abs() <= 1e-10 * b0, "I5 (psi) {p5} vs {b5}");
            }
        }
    }
}
