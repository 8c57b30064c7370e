//! The Charlie sheen albedo with any masking term of the two cosines,
//! `E(μv) = ∫ D_Charlie(h) G(μv, μl) / (4 μv) dω_l`, as a one-dimensional integral over the
//! light's cosine with the azimuthal integral of D done by a trapezoid rule that converges
//! geometrically. For Conty–Kulla's fitted Λ (and any G(μv, μl) ≤ 1, smooth for μl > 0).
//!
//! **Reduction.** In light coordinates (μl = cos θl, azimuth φ relative to the view,
//! `dω_l = dμl dφ`) the masking depends on μl alone, so
//!
//! `E = (1/(4μv)) ∫₀¹ G(μv, μl) J(μl) dμl`, `J = ∫_{−π}^{π} D dφ`.
//!
//! Charlie's `D = norm·(sin²θh)^p`, `p = 1/(2α)`, `norm = (2 + 1/α)/(2π)` (Estevez & Kulla
//! 2017, eq. 2). With `h ∝ v + l`, `sin²θh = |v_t + l_t|²/|v + l|² = (A + B cos φ)/(C + B cos φ)`,
//! `A = sin²θv + sin²θl`, `B = 2 sin θv sin θl`, `C = 2 + 2μv μl`; w = sin²θh runs from
//! `w_min = sin²(Δ/2)` at φ = π to `w_max = sin²(Σ/2)` at φ = 0 (Δ = θv − θl, Σ = θv + θl),
//! and changing the variable from φ to w (`dφ/dw` from `cos φ = (z − C)/B`, `z = (μv + μl)²/(1 − w)`
//! and `√((1 − w_min)(1 − w_max)) = (μv + μl)/2`) gives
//!
//! `J = norm (μv + μl) ∫_{w_min}^{w_max} w^p dw / ((1 − w)√((w − w_min)(w_max − w)))`.
//!
//! The rule is taken in `u = √w` (so that the branch point of w^p at w = 0 lies at a
//! distance ∝ u_min, not u_min², from the interval; the same device as the GGX kernel's s,
//! [`ggx_polar`](super::ggx_polar)): with `u = u_min + h(1 + cos ϑ)`, `h = (u_max − u_min)/2`,
//!
//! `J = norm (μv + μl) ∫₀^π 2u^{2p+1} / ((1 − u²)√((u + u_min)(u + u_max))) dϑ`,
//!
//! an even periodic integrand, analytic in a strip about the real ϑ axis: its singularities
//! are the pole at u = 1 (near ϑ = 0 when both directions are near grazing, u_max → 1), and
//! the branch points at u = 0, −u_min, −u_max (near ϑ = π when θl → θv). The trapezoid rule
//! therefore converges geometrically (Trefethen & Weideman 2014, "The exponentially
//! convergent trapezoidal rule", thm. 3.2). Narrow lobes (large p) make `u^{2p}` a peak at
//! ϑ = 0 of width `σ ≈ √(u_max/(2ph))`, and the pole near grazing has width ∝ `√(1 − u_max)`:
//! there the rule is taken in τ, `tan(ϑ/2) = ε tan(τ/2)` (a Möbius map of the period onto
//! itself that gathers the nodes at ϑ = 0), with ε from the narrower of the two (module
//! constants). The angles are formed from `β = asin μ` (the elevation above the horizon) so
//! that `u_max = cos((βv + βl)/2)`, `1 − u_max = 2 sin²((βv + βl)/4)` and
//! `u_min = |sin((βl − βv)/2)|` keep their digits at grazing.
//!
//! **Rule.** Trapezoid sums with 1, 2, 4, …, 256 intervals (nested), `T_N` accepted from
//! N = 4 on when `|T_N − T_{N/2}|` (the error of the coarser sum, an over-estimate of
//! T_N's) is within the line's share — at N = 4 also `|T_2 − T_1|²/max|f|` (QUADPACK's
//! guard against a chance agreement, Piessens et al. 1983, §2.2.1); where no level is, the
//! adaptive Gauss–Kronrod rule on ϑ ∈ [0, π] ([`integrate`]). The outer integral is taken in
//! `x = ln μl` (Conty–Kulla's Λ depends on μl through `μl^c`, c ≈ 0.17–0.2, analytic in x),
//! on panels split at `x = ln μv` (where J has its branch point, θl = θv) and growing
//! geometrically below it, each by nested Clenshaw–Curtis (9 … 129 nodes, [`nested_cc`]:
//! its estimate `max(|Q_k − Q_{k−1}|, |Q_{k−1} − Q_{k−2}|²/|Q_k|)`), bisected where that does
//! not converge.
//!
//! **Cuts and error.** With G ≤ 1 and `u^{2p}/(1 − u²)` increasing in u, `J ≤ 2π norm (μv + μl)
//! u_max^{2p}/(1 − u_max²)`, with `1 − u_max² = sin²((βv + βl)/2)`: the domain is cut at
//! `μ_lo` below (where that bound times μ_lo is `tol/1000`) and, for narrow lobes (α <
//! [`CUT_BELOW_ALPHA`]), at `μ_hi` above (the smallest μl whose bound on the rest is
//! `tol/1000`: `u_max^{2p}` decays there like `exp(−p tan((βv + βl)/2) δβl)`), each bound
//! added to the estimate. An inner error δ on the line of weight k moves the result by
//! `∫ k δ dx ≤ X·max(k δ)` over the panels' length X: each line is asked for
//! `δ ≤ tol/(4 X k)` and the bound from the δ reached is added. The outer rules share tol/2.
//! A texel whose total does not reach `tol` returns `Err` (the caller falls back).
//!
//! Deterministic: fixed nodes and summation order, a pure function of its arguments.

// Level loops index the node tables and values together.
#![allow(clippy::needless_range_loop)]

use crate::quadrature::adaptive::{integrate, Estimate, Tolerance};
use crate::quadrature::cc1d::{nested_cc, nested_cc_indexed, FIRST_LEVEL};
use crate::quadrature::clenshaw_curtis::MAX_LEVEL;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// What this kernel does, for the sidecar's `quadrature.method`.
pub const METHOD: &str = "Charlie sheen with a masking G(n.v, n.l) as a 1D integral over the light's cosine (src/kernels/sheen_polar.rs): the azimuthal integral of D in u = sin(theta_h) by the trapezoid rule (nested 1 to 256 intervals, Moebius-mapped towards narrow peaks and the grazing pole; adaptive Gauss-Kronrod where it does not converge), the outer integral in ln(n.l) by nested Clenshaw-Curtis (9 to 129 nodes) on panels split at n.l = n.v, bisected where needed; the domain cut where a bound on the rest is under tol/1000";

/// Lobes narrower than this (α < 1/16) have the domain cut above `μ_hi` (module doc): their
/// albedo lives in a layer near grazing light.
pub const CUT_BELOW_ALPHA: f64 = 1.0 / 16.0;

/// Finest trapezoid level: 2^8 intervals on [0, π].
const MAX_LOG2: usize = 8;
const NTRAP: usize = 1 << MAX_LOG2;

/// The Möbius map is used where the ε it would take is below this: above, its gain does
/// not pay for its arithmetic.
const MOBIUS_BELOW: f64 = 0.5;

/// Where each level's nodes start in [`NodeTables`]' order: level 0 is the two ends (N = 1),
/// level l ≥ 1 the 2^(l−1) midpoints that N = 2^l adds.
const LEVEL_START: [usize; MAX_LOG2 + 2] = crate::quadrature::trapezoid::level_starts();

/// The trapezoid nodes τ = kπ/256 in the order of their levels (k = 0, 256; 128; 64, 192;
/// …), as `1 − cos τ = 2 sin²(τ/2)` and `1 + cos τ = 2 cos²(τ/2)` (each accurate where it
/// is small).
struct NodeTables {
    omc: [f64; NTRAP + 1],
    opc: [f64; NTRAP + 1],
}

fn node_tables() -> &'static NodeTables {
    static T: OnceLock<NodeTables> = OnceLock::new();
    T.get_or_init(|| {
        let mut t = NodeTables {
            omc: [0.0; NTRAP + 1],
            opc: [0.0; NTRAP + 1],
        };
        let mut i = 0;
        let mut put = |k: usize| {
            let (s, c) = (k as f64 * PI / (2 * NTRAP) as f64).sin_cos();
            t.omc[i] = 2.0 * s * s;
            t.opc[i] = 2.0 * c * c;
            i += 1;
        };
        for k in crate::quadrature::trapezoid::level_order(MAX_LOG2) {
            put(k);
        }
        t
    })
}

/// One light cosine's azimuthal integral `∫₀^π q dϑ` (module doc), set up: everything
/// but the lobe's exponent, so that the lobes of one column share it.
struct Line {
    u_min: f64,
    u_max: f64,
    /// `δ = 1 − u_max`, without cancellation.
    delta: f64,
    h: f64,
    /// The Möbius map's ε and ε² (ε = 1: none), and whether it gathers the nodes at ϑ = π
    /// (else at ϑ = 0).
    eps: f64,
    e2: f64,
    to_pi: bool,
    /// Whether the pole at u = 1 is subtracted: then `phi0` = Φ(u = 1) and `pole` its
    /// integral `Φ(1)·π/√(δ(δ + 2h))`.
    subtract: bool,
    phi0: f64,
    pole: f64,
    /// Straight to the adaptive rule (the branch point at u = 0 on the interval's end).
    adaptive_only: bool,
}

/// The pole at u = 1 is subtracted where `tanh(b/2)` of its distance b from the real axis
/// is below this (y = δ/h < ~0.19).
const SUBTRACT_BELOW: f64 = 0.3;

/// Lobes up to this exponent p = 1/(2α) (α ≥ 1/16) map towards ϑ = π for the branch point
/// at u = 0; narrower ones are negligible there (u_min^{2p} against u_max^{2p}). For them
/// the peak at ϑ = 0 never asks for the map either (σ = √(u_max/(2ph)) ≥ √(1/p) ≥ 0.35,
/// h ≤ u_max/2, so 2σ ≥ [`MOBIUS_BELOW`]): a line's setup is the same for every such lobe.
const WIDE_P: f64 = 8.0;

/// A trapezoid node's data (module doc), from which the integrand at any exponent p2 = 2p + 1
/// is `w·expm1(p2·a − c)` (pole subtracted) or `w·exp(p2·a)`: `a = ln(1 − ν)`, ν = 1 − u
/// (−∞ where u ≤ 0), `c = ln(1 − ν/2) + ½(ln(1 − ν/(1 + u_min)) + ln(1 − ν/(1 + u_max)))`, and
/// `w` the rest with the map's Jacobian.
#[derive(Clone, Copy, Default)]
struct NodeData {
    a: f64,
    c: f64,
    w: f64,
}

impl NodeData {
    #[inline]
    fn value(&self, p2: f64, subtract: bool) -> f64 {
        if subtract {
            self.w * (p2 * self.a - self.c).exp_m1()
        } else {
            self.w * (p2 * self.a).exp()
        }
    }
}

impl Line {
    fn new(p: f64, beta_v: f64, beta_l: f64) -> Line {
        let s = 0.5 * (beta_v + beta_l);
        let u_max = s.cos();
        let sq = (0.5 * s).sin();
        let delta = 2.0 * sq * sq;
        let u_min = (0.5 * (beta_l - beta_v)).sin().abs();
        let h = (0.5 * (u_max - u_min)).max(0.0);
        let tanh_half = |y: f64| (y / (2.0 + y)).sqrt();
        // the pole at u = 1 sits at ϑ = i·b, tanh(b/2) = √(y/(2 + y)), y = δ/h; where it is
        // near, q = (Φ(ν) − Φ(0))/ν + Φ(0)/ν with ν = 1 − u, the second part in closed form
        // (∫₀^π dϑ/(δ + h(1 − cos ϑ)) = π/√(δ(δ + 2h))), the first without the pole
        let subtract = h > 0.0 && tanh_half(delta / h) < SUBTRACT_BELOW;
        let phi0 = 1.0 / ((1.0 + u_min) * (1.0 + u_max)).sqrt();
        let pole = if subtract {
            phi0 * PI / (delta * (delta + 2.0 * h)).sqrt()
        } else {
            0.0
        };
        // the map: towards ϑ = 0 for the peak of u^{2p} there (width σ = √(u_max/(2ph)) in
        // ϑ; the map makes it σ/ε in τ, which 8–16 nodes resolve from σ/ε ≈ 1/2 on), and for
        // the pole where it is not subtracted (ε = √tanh(b/2) puts it and the map's image of
        // the far end at the same distance, as in the GGX kernel); towards ϑ = π for the
        // branch point of u^{2p+1} at u = 0, at tanh(b/2) = √(y/(2 + y)), y = u_min/h, where
        // it matters: for wide lobes, whose u^{2p} is not negligible there
        let (mut e0, mut epi) = (1.0f64, 1.0f64);
        if h > 0.0 {
            e0 = e0.min(2.0 * (u_max / (2.0 * p * h)).sqrt());
            if !subtract {
                e0 = e0.min(tanh_half(delta / h).sqrt());
            }
            if p <= WIDE_P {
                epi = tanh_half(u_min / h).sqrt();
            }
        }
        let (eps, to_pi) = if epi < e0 { (epi, true) } else { (e0, false) };
        let eps = if eps < MOBIUS_BELOW {
            eps.max(1e-8)
        } else {
            1.0
        };
        Line {
            u_min,
            u_max,
            delta,
            h,
            eps,
            e2: eps * eps,
            to_pi,
            subtract,
            phi0,
            pole,
            // with the branch point at u = 0 on (or within 1e-10·h of) the interval's end —
            // the light at the view's elevation, which the outer panels have as an end — the
            // trapezoid sums converge only algebraically
            adaptive_only: h > 0.0 && u_min < 1e-10 * h,
        }
    }

    /// The node data at ϑ given `1 ∓ cos ϑ` (`omc`, `opc`) and the Jacobian `jac`:
    /// the integrand `Φ(ν)/ν`, or without the pole `(Φ(ν) − Φ(0))/ν`, with
    /// `ν = 1 − u = δ + h(1 − cos ϑ)` and `Φ = 2u^{2p+1}/((1 + u)√((u + u_min)(u + u_max)))`
    /// (0 where u ≤ 0); `Φ(ν)/Φ(0) = (1 − ν)^{2p+1}/((1 − ν/2)√((1 − ν/(1 + u_min))(1 − ν/(1 + u_max))))`,
    /// so `Φ(ν) − Φ(0) = Φ(0)·expm1(…)` without cancellation.
    #[inline]
    fn node(&self, omc: f64, opc: f64, jac: f64) -> NodeData {
        // u from the nearer end, so that it keeps its digits at both
        let u = if omc <= 1.0 {
            self.u_max - self.h * omc
        } else {
            self.u_min + self.h * opc
        };
        let nu = self.delta + self.h * omc;
        // ln u = ln(1 − ν), accurate near u = 1 where p may be ~10⁶
        let a = if u <= 0.0 {
            f64::NEG_INFINITY
        } else {
            (-nu).ln_1p()
        };
        if self.subtract {
            let c = (-0.5 * nu).ln_1p()
                + 0.5 * ((-nu / (1.0 + self.u_min)).ln_1p() + (-nu / (1.0 + self.u_max)).ln_1p());
            NodeData {
                a,
                c: if u <= 0.0 { 0.0 } else { c },
                w: jac * self.phi0 / nu,
            }
        } else {
            let w = if u <= 0.0 {
                0.0
            } else {
                jac * 2.0 / (nu * (2.0 - nu) * ((u + self.u_min) * (u + self.u_max)).sqrt())
            };
            NodeData { a, c: 0.0, w }
        }
    }

    /// The node data of trapezoid node τ (`omc`, `opc` = 1 ∓ cos τ), through the Möbius
    /// map where it applies. Towards 0, `tan(ϑ/2) = ε tan(τ/2)`: with cw = cos²(τ/2) =
    /// opc/2, sw = sin²(τ/2) = omc/2 and den = 1/(cw + ε² sw), `1 − cos ϑ = 2ε² sw·den`,
    /// `1 + cos ϑ = 2 cw·den`, `dϑ/dτ = ε·den`; towards π the same with ϑ → π − ϑ.
    #[inline]
    fn at(&self, omc: f64, opc: f64) -> NodeData {
        if self.eps == 1.0 {
            return self.node(omc, opc, 1.0);
        }
        let (cw, sw) = (0.5 * opc, 0.5 * omc);
        let den = 1.0 / (cw + self.e2 * sw);
        let (near, far) = (2.0 * self.e2 * sw * den, 2.0 * cw * den);
        let jac = self.eps * den;
        if self.to_pi {
            self.node(far, near, jac)
        } else {
            self.node(near, far, jac)
        }
    }

    /// `∫₀^π q dϑ` (the pole's closed form added) at exponent `p2` = 2p + 1 to absolute
    /// tolerance `tol`: (value, its estimate, evaluations). `nodes` holds the trapezoid
    /// nodes' data computed so far, in level order (the first `nodes.len()`), and gets the
    /// ones this call computes: a line shared by several lobes computes each once.
    fn integral(&self, p2: f64, tol: f64, nodes: &mut Vec<NodeData>) -> (f64, f64, u64) {
        if self.adaptive_only {
            return self.adaptive(p2, tol, 0);
        }
        let t = node_tables();
        let mut f = |i: usize| {
            if i >= nodes.len() {
                nodes.push(self.at(t.omc[i], t.opc[i]));
            }
            nodes[i].value(p2, self.subtract)
        };
        let (a, b) = (f(0), f(1));
        let mut sum = 0.5 * (a + b);
        let mut fmax = a.abs().max(b.abs());
        let mut evals = 2u64;
        let mut prev = [0.0, sum];
        for level in 1..=MAX_LOG2 {
            for i in LEVEL_START[level]..LEVEL_START[level + 1] {
                let v = f(i);
                sum += v;
                if level <= 2 {
                    fmax = fmax.max(v.abs());
                }
                evals += 1;
            }
            let cur = sum / (1u64 << level) as f64;
            // (T_N/N as a mean over [0, π]: the integral is π times it)
            let mut d = PI * (cur - prev[1]).abs();
            if level == 2 {
                let d2 = PI * (prev[1] - prev[0]).abs();
                d = d.max(d2 * d2 / (PI * fmax).max(tol));
            }
            if level >= 2 && d <= tol && cur.is_finite() {
                return (PI * cur + self.pole, d, evals);
            }
            prev = [prev[1], cur];
        }
        self.adaptive(p2, tol, evals)
    }

    /// [`Line::integral`] by the adaptive Gauss–Kronrod rule in ϑ itself (`spent`: the
    /// evaluations of an abandoned attempt, counted in).
    fn adaptive(&self, p2: f64, tol: f64, spent: u64) -> (f64, f64, u64) {
        let tol_gk = Tolerance {
            abs: tol.max(f64::MIN_POSITIVE),
            initial_panels: 4,
            max_depth: 30,
            noise_floor: 0.0,
            max_evals: 1 << 16,
        };
        let e = integrate(
            |th: f64| {
                let (sh, ch) = (0.5 * th).sin_cos();
                [self
                    .node(2.0 * sh * sh, 2.0 * ch * ch, 1.0)
                    .value(p2, self.subtract)]
            },
            0.0,
            PI,
            tol_gk,
        );
        (e.value[0] + self.pole, e.error[0], spent + e.evals)
    }
}

/// The lowest tolerance whose cut the shared panels of wide lobes satisfy (the smallest a
/// table accepts, [`crate::table::spec::MIN_TOLERANCE`]).
const SHARED_TOL_FLOOR: f64 = 1e-12;

/// What the wide lobes (α ≥ [`CUT_BELOW_ALPHA`]) of one view share: the outer panels, which
/// then depend on the view alone (cut with G ≤ 1, the largest normalization of such a lobe
/// and the tolerance floor), and for each of their Clenshaw–Curtis nodes the line's setup
/// and the trapezoid nodes' data computed so far (`NodeData`: the lobe enters only
/// through its exponent). A texel gets the same bits from a filled cache as from an empty
/// one: every entry is a pure function of the view and its node.
#[derive(Default)]
pub struct PolarCache {
    mu_v: f64,
    panels: Vec<SharedPanel>,
}

struct SharedPanel {
    var: Var,
    a: f64,
    b: f64,
    /// Per Clenshaw–Curtis node index (finest level): the line and its node data.
    lines: Vec<Option<Box<CachedLine>>>,
}

/// A cached inner line and its node data.
type CachedLine = (Line, Vec<NodeData>);

impl PolarCache {
    /// The shared panels for view `mu_v` (built if they were for another view).
    fn for_view(&mut self, mu_v: f64, beta_v: f64) -> &mut Vec<SharedPanel> {
        if self.panels.is_empty() || self.mu_v.to_bits() != mu_v.to_bits() {
            self.mu_v = mu_v;
            // the lower cut of the module doc with G ≤ 1, norm ≤ (2 + 16)/(2π) and the
            // tolerance floor: valid for every wide lobe and tolerance
            let norm_max = (2.0 + 1.0 / CUT_BELOW_ALPHA) / (2.0 * PI);
            let c0 = norm_max / (4.0 * mu_v) * 4.0 * PI * mu_v / (0.5 * beta_v).sin().powi(2);
            let mu_lo = mu_v.min(1e-3 * SHARED_TOL_FLOOR / c0);
            self.panels = panels(mu_v, beta_v, mu_lo.ln(), 0.0)
                .into_iter()
                .map(|(var, a, b)| SharedPanel {
                    var,
                    a,
                    b,
                    lines: (0..NCC).map(|_| None).collect(),
                })
                .collect();
        }
        &mut self.panels
    }
}

/// Clenshaw–Curtis nodes of the finest level.
const NCC: usize = (1 << MAX_LEVEL) + 1;

/// The albedo `∫ D_Charlie(α) G (n·l) / (4 μv) ... dω_l` at view cosine `mu_v` ∈ (0, 1] and
/// Charlie α > 0, with `g(μl)` = G(μv, μl), which must lie in [0, 1] and not decrease with
/// μl (every masking term's light side falls towards grazing; the cuts' bounds rely on it),
/// to absolute tolerance `tol` (estimated, module doc); `Err(evaluations spent)` where it
/// does not get there. A pure function of its arguments.
pub fn charlie_albedo_polar(
    mu_v: f64,
    alpha: f64,
    g: &dyn Fn(f64) -> f64,
    tol: f64,
) -> Result<Estimate<1>, u64> {
    charlie_albedo_polar_shared(mu_v, alpha, g, tol, &mut PolarCache::default())
}

/// [`charlie_albedo_polar`] with the view's shared data (wide lobes) kept in `cache` for the
/// next texel of the same view: the same bits as without. Evaluations count the integrand's
/// values at the trapezoid nodes, whether their data were computed or found in the cache.
pub fn charlie_albedo_polar_shared(
    mu_v: f64,
    alpha: f64,
    g: &dyn Fn(f64) -> f64,
    tol: f64,
    cache: &mut PolarCache,
) -> Result<Estimate<1>, u64> {
    if !(mu_v > 0.0 && mu_v <= 1.0 && alpha > 0.0 && alpha.is_finite() && tol > 0.0) {
        return Err(0);
    }
    let p = 0.5 / alpha;
    let p2 = 2.0 * p + 1.0;
    let norm = (2.0 + 1.0 / alpha) / (2.0 * PI);
    let beta_v = mu_v.asin();
    // E = pre ∫ G (μv + μl) I dμl, I the ϑ integral
    let pre = norm / (4.0 * mu_v);
    let cut = 1e-3 * tol;
    // below μ_lo ≤ μv: G ≤ G(μ_lo) (G does not decrease with μl), (μv + μl) ≤ 2μv,
    // u_max ≤ 1, sin²((βv + βl)/2) ≥ sin²(βv/2): the rest is at most μ_lo·G(μ_lo)·c0
    let sv2 = (0.5 * beta_v).sin().powi(2);
    let c0 = pre * 4.0 * PI * mu_v / sv2;
    let shared = alpha >= CUT_BELOW_ALPHA && tol >= SHARED_TOL_FLOOR;
    let mut cut_err = cut;
    let mut own_panels: Vec<SharedPanel>;
    let panels: &mut [SharedPanel] = if shared {
        let panels = cache.for_view(mu_v, beta_v);
        // (the shared panels' lower end: the bound there at this lobe and G ≤ 1)
        let mu_lo = panels
            .first()
            .map_or(mu_v, |p| match p.var {
                Var::LnMu => p.a.exp(),
                Var::Beta => p.a.sin(),
            })
            .min(mu_v);
        cut_err = mu_lo * c0;
        panels
    } else {
        let below = |mu: f64| mu * g(mu) * c0;
        let mut mu_lo = mu_v.min(cut / c0);
        if below(mu_v) <= cut {
            mu_lo = mu_v;
        } else if g(mu_lo) < 0.5 {
            // the largest μ_lo (in x = ln μ, by bisection) whose bound is within `cut`:
            // where G is small near the horizon (Conty–Kulla's Λ(0) = e^{a + e} ~ 1e7)
            // this removes decades of x that hold nothing
            let (mut lo, mut hi) = (mu_lo.ln(), mu_v.ln());
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if below(mid.exp()) <= cut {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            mu_lo = lo.exp();
        }
        // the rest above μ_h: (1 − μ_h)·pre·2π(μv + 1)·u_max(μ_h)^{2p}/sin²(s_h)
        let tail = |mu_h: f64| {
            let s = 0.5 * (beta_v + mu_h.asin());
            (1.0 - mu_h) * pre * 2.0 * PI * (mu_v + 1.0) * (2.0 * p * s.cos().ln()).exp()
                / s.sin().powi(2)
        };
        let (x_lo, mut x_hi) = (mu_lo.ln(), 0.0f64);
        if alpha < CUT_BELOW_ALPHA {
            if tail(mu_lo) <= cut {
                return Ok(Estimate {
                    value: [0.0],
                    error: [2.0 * cut],
                    evals: 0,
                });
            }
            // bisection in x = ln μ_h for the smallest μ_h whose tail is within `cut` (the
            // tail decreases with μ_h: each factor does)
            let (mut lo, mut hi) = (x_lo, 0.0f64);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if tail(mid.exp()) <= cut {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            x_hi = hi;
            if x_hi < 0.0 {
                cut_err += cut;
            }
        }
        // (lines of its own are not kept: `lines` empty)
        own_panels = panels(mu_v, beta_v, x_lo, x_hi)
            .into_iter()
            .map(|(var, a, b)| SharedPanel {
                var,
                a,
                b,
                lines: Vec::new(),
            })
            .collect::<Vec<_>>();
        &mut own_panels
    };
    // (a shared line is set up as for the widest exponent it serves: its setup is the same
    // for every p ≤ WIDE_P, see there, so it does not matter which lobe built it)
    let p_line = if shared { WIDE_P } else { p };
    let n_panels = panels.len() as f64;
    let mut scratch = Vec::with_capacity(NTRAP + 1);
    let mut inner_err = 0.0f64;
    let mut evals = 0u64;
    let mut total = Estimate::<1>::zero();
    for sp in panels.iter_mut() {
        // each panel: its outer rule within tol/(2n), its lines' errors within tol/(4n)
        // (a line of weight k asked for δ ≤ tol/(4n·len·k): the panel's rule moves by at
        // most len·max(k δ))
        let (var, a, b) = (sp.var, sp.a, sp.b);
        let len = b - a;
        let tol_k = 0.25 * tol / (n_panels * len);
        let mut panel_inner = 0.0f64;
        let lines = &mut sp.lines;
        let mut f = |i: Option<usize>, x: f64| {
            let (mu_l, beta_l, jac) = match var {
                Var::LnMu => {
                    let mu_l = x.exp().min(1.0);
                    (mu_l, mu_l.asin(), mu_l)
                }
                Var::Beta => {
                    let (s, c) = x.sin_cos();
                    (s, x, c)
                }
            };
            let k = pre * jac * g(mu_l) * (mu_v + mu_l);
            if k == 0.0 {
                return [0.0];
            }
            let fresh = || {
                Box::new((
                    Line::new(p_line, beta_v, beta_l),
                    Vec::with_capacity(NTRAP + 1),
                ))
            };
            let (v, e, n) = match i.filter(|_| !lines.is_empty()) {
                Some(i) => {
                    let (line, nodes) = &mut **lines[i].get_or_insert_with(fresh);
                    line.integral(p2, tol_k / k, nodes)
                }
                None => {
                    scratch.clear();
                    Line::new(p_line, beta_v, beta_l).integral(p2, tol_k / k, &mut scratch)
                }
            };
            panel_inner = panel_inner.max(k * e);
            evals += n;
            [k * v]
        };
        if !panel(&mut f, a, b, 0.5 * tol / n_panels, 5, true, &mut total) {
            return Err(evals);
        }
        inner_err += len * panel_inner;
    }
    total.error[0] += inner_err + cut_err;
    total.evals = evals;
    if !(total.value[0].is_finite() && total.error[0] <= tol) {
        return Err(total.evals);
    }
    Ok(total)
}

/// The outer integral's variable on a panel.
#[derive(Clone, Copy, Debug)]
enum Var {
    /// x = ln μl (below μl = 1/2, where Conty–Kulla's Λ is analytic in x).
    LnMu,
    /// β = asin μl (above μl = 1/2: μl = sin β, the light's polar angle is analytic in it,
    /// while it has a square-root branch point at μl = 1 in x).
    Beta,
}

/// The panels of the outer integral over μl ∈ [e^{x_lo}, e^{x_hi}] (module doc): in x = ln μl
/// below 1/2, growing geometrically (lengths 2, 4, 8, …) away from x = ln μv, and in
/// β = asin μl above, split at βv.
fn panels(mu_v: f64, beta_v: f64, x_lo: f64, x_hi: f64) -> Vec<(Var, f64, f64)> {
    let x_half = 0.5f64.ln();
    let x_v = mu_v.ln();
    let top = x_hi.min(x_half);
    let mut out = Vec::new();
    // below min(x_v, top), from the top down
    let mut below = Vec::new();
    let (mut b, mut len) = (x_v.min(top), 2.0);
    while b > x_lo {
        let a = if b - len <= x_lo + 0.5 * len {
            x_lo
        } else {
            b - len
        };
        below.push((Var::LnMu, a, b));
        b = a;
        len *= 2.0;
    }
    below.reverse();
    out.extend(below);
    // from x_v up to the top
    let (mut a, mut len) = (x_v.max(x_lo), 2.0);
    while a < top {
        let b = if a + len >= top - 0.5 * len {
            top
        } else {
            a + len
        };
        out.push((Var::LnMu, a, b));
        a = b;
        len *= 2.0;
    }
    // above μl = 1/2, in β
    if x_hi > x_half {
        let (lo, hi) = (
            std::f64::consts::FRAC_PI_6.max(x_lo.exp().asin()),
            x_hi.exp().min(1.0).asin(),
        );
        if beta_v > lo && beta_v < hi {
            out.push((Var::Beta, lo, beta_v));
            out.push((Var::Beta, beta_v, hi));
        } else if hi > lo {
            out.push((Var::Beta, lo, hi));
        }
    }
    out
}

/// ∫ₐᵇ f by nested Clenshaw–Curtis, bisected up to `depth` times where it does not reach
/// `tol` (shared by length), added into `out`; false where even that fails. `f` is told the
/// node's index in the finest level on the panel itself (`top`), `None` on its halves.
fn panel(
    f: &mut dyn FnMut(Option<usize>, f64) -> [f64; 1],
    a: f64,
    b: f64,
    tol: f64,
    depth: u32,
    top: bool,
    out: &mut Estimate<1>,
) -> bool {
    let r = if top {
        nested_cc_indexed(&mut |i, x| f(Some(i), x), a, b, tol, FIRST_LEVEL, MAX_LEVEL)
    } else {
        nested_cc(&mut |x| f(None, x), a, b, tol, MAX_LEVEL)
    };
    match r {
        Ok(e) => {
            out.value[0] += e.value[0];
            out.error[0] += e.error[0];
            true
        }
        Err(_) if depth == 0 => false,
        Err(_) => {
            let m = 0.5 * (a + b);
            panel(f, a, m, 0.5 * tol, depth - 1, false, out)
                && panel(f, m, b, 0.5 * tol, depth - 1, false, out)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::masking::ContyKullaLambda;

    /// Conty–Kulla's G(μv, ·) at Charlie α.
    fn ck(mu_v: f64, alpha: f64) -> impl Fn(f64) -> f64 {
        let cl = ContyKullaLambda::new(alpha);
        let lv = cl.lambda(mu_v);
        move |mu_l| 1.0 / (1.0 + lv + cl.lambda(mu_l))
    }

    /// A texel's value, estimate and evaluations are the same bits whether the view's shared
    /// data come from a cache filled by other lobes (in any order, at other tolerances) or
    /// are computed afresh; a cache left by another view is not used.
    #[test]
    fn shared_lines_give_the_same_bits() {
        let alphas = [1.0, 0.07, 0.3, 0.0625, 0.01, 0.5, 0.0625, 0.2, 1e-4];
        for mu in [0.004, 0.3, 0.5, 0.9, 1.0] {
            let mut cache = PolarCache::default();
            for (k, &alpha) in alphas.iter().enumerate() {
                let tol = if k % 2 == 0 { 1e-7 } else { 3e-9 };
                let g = ck(mu, alpha);
                let a = charlie_albedo_polar_shared(mu, alpha, &g, tol, &mut cache).unwrap();
                let b = charlie_albedo_polar(mu, alpha, &g, tol).unwrap();
                assert_eq!(
                    a.value[0].to_bits(),
                    b.value[0].to_bits(),
                    "mu {mu} alpha {alpha}"
                );
                assert_eq!(
                    a.error[0].to_bits(),
                    b.error[0].to_bits(),
                    "mu {mu} alpha {alpha}"
                );
                assert_eq!(a.evals, b.evals, "mu {mu} alpha {alpha}");
            }
            let g = ck(0.45, 0.3);
            let a = charlie_albedo_polar_shared(0.45, 0.3, &g, 1e-7, &mut cache).unwrap();
            let b = charlie_albedo_polar(0.45, 0.3, &g, 1e-7).unwrap();
            assert_eq!(a.value[0].to_bits(), b.value[0].to_bits());
        }
    }

    /// Out-of-domain inputs are refused (the caller falls back), never answered.
    #[test]
    fn refuses_what_it_does_not_cover() {
        let g = |_: f64| 1.0;
        for (mu, alpha, tol) in [
            (0.0, 0.5, 1e-7),
            (1.5, 0.5, 1e-7),
            (0.5, 0.0, 1e-7),
            (f64::NAN, 0.5, 1e-7),
            (0.5, f64::INFINITY, 1e-7),
            (0.5, 0.5, 0.0),
        ] {
            assert!(
                charlie_albedo_polar(mu, alpha, &g, tol).is_err(),
                "{mu} {alpha} {tol}"
            );
        }
    }

    /// The ϑ form of J equals a brute-force azimuthal integral of Charlie's D at fixed
    /// (μv, μl): the substitutions are identities, so only the brute-force rule's error
    /// (composite Simpson, 2·10⁵ panels, on a D resolved to ≥ 50 nodes per feature: relative
    /// ~1e-11) remains. Views and lights from grazing to normal, θl = θv included, α from
    /// 0.02 to 1.
    #[test]
    fn azimuthal_integral_matches_brute_force() {
        for &alpha in &[1.0, 0.3, 0.1, 0.02] {
            let p = 0.5 / alpha;
            let norm = (2.0 + 1.0 / alpha) / (2.0 * PI);
            for &mu_v in &[0.02f64, 0.3, 0.8, 1.0] {
                for &mu_l in &[0.001f64, 0.05, 0.3, 0.8, 0.999] {
                    let (sv, sl) = ((1.0 - mu_v * mu_v).sqrt(), (1.0 - mu_l * mu_l).sqrt());
                    let n = 200_000;
                    let mut brute = 0.0;
                    for i in 0..=n {
                        let phi = PI * i as f64 / n as f64;
                        let w = if i == 0 || i == n {
                            1.0
                        } else if i % 2 == 1 {
                            4.0
                        } else {
                            2.0
                        };
                        let (a, b) = (sv * sv + sl * sl, 2.0 * sv * sl);
                        let c = 2.0 + 2.0 * mu_v * mu_l;
                        let s2 = (a + b * phi.cos()) / (c + b * phi.cos());
                        brute += w * norm * s2.max(0.0).powf(p);
                    }
                    brute *= 2.0 * PI / n as f64 / 3.0; // both halves of the circle
                    let line = Line::new(p, mu_v.asin(), mu_l.asin());
                    let (i, e, _) = line.integral(2.0 * p + 1.0, 1e-13, &mut Vec::new());
                    let j = norm * (mu_v + mu_l) * i;
                    assert!(
                        (j - brute).abs() <= 1e-9 * brute.max(1e-3) + e,
                        "alpha {alpha} mu_v {mu_v} mu_l {mu_l}: {j} vs {brute}"
                    );
                }
            }
        }
    }
}
