//! The cloth albedo `∫ D_Charlie(α) V_Ashikhmin (n·l) dω_l` of **wide** sheen lobes
//! (1/16 ≤ α ≤ 1) in light-direction coordinates: the sibling of [`sheen_l`](super::sheen_l)
//! (narrow lobes), whose module docs derive the integrand. With `ψ = π − φ` (φ the azimuth of
//! l relative to v), `y = sin²(ψ/2)`, `sv = sin θv`, `sl = sin θl`:
//!
//! `sin²θh = N/D`, `N = (sv − sl)² + B y`, `D = (sv − sl)² + (μv + μl)² + B y`,
//! `B = 4 sv sl`
//!
//! (from `cos²θh = (μv + μl)²/(2 + 2 v·l)`, `v·l = μv μl + sv sl cos φ`), so
//! `B_cloth(μv) = ∫₀¹ dμl norm·μl·V(μl)·J(μl)`, `J = 2∫₀^π (N/D)^k dψ`, with Charlie's
//! `k = 1/(2α)`, `norm = (2 + 1/α)/(2π)` (Estevez & Kulla 2017, "Production Friendly
//! Microfacet Sheen BRDF", eq. 2) and Ashikhmin's `V = 1/(4(μl + μv − μl μv))` (Neubelt &
//! Pettineo 2013, as Filament uses it).
//!
//! **Why wide lobes need their own rules.** For k ∈ [½, 8] `(N/D)^k` is not analytic where N
//! vanishes, `sl = sv` and ψ = 0 (h = n). As a function of y, `(N/D)^k =
//! ((c_N² + y)/(c_D² + y))^k` with `c_N² = (sv − sl)²/B`, `c_D² = c_N² + (μv + μl)²/B`
//! is analytic except on the cut `y ∈ [−c_D², −c_N²]`, i.e. at `ψ ≈ ±2i·asinh(c_N)` and
//! `±2i·asinh(c_D)`: two features at ψ = 0 of widths `c_N ≈ |sl − sv|/(2√(sv sl))` (→ 0 at
//! the breakpoint θl = θv) and `c_D` (small at grazing views), on top of the O(1)-wide lobe
//! around ψ = π. One Möbius-mapped periodic trapezoid rule (the narrow path's) cannot take
//! both scales: with its ρ at c_N the O(1) part is squeezed into a few nodes, with ρ at
//! c_D the c_N feature is unresolved and, for k = ½ (a kink), the rule converges only
//! algebraically. And the outer integrand behaves like `analytic + c·|θl − θv|^{2k+1}`
//! (the integral of the feature's non-analytic part scales as c_N^{2k+1}), which one rule
//! across θv resolves only algebraically.
//!
//! **Outer rule.** In `ε = π/2 − θl` (μl = sin ε, so that at normal view the integrand
//! `sin^{2k}(θl/2) sin θl` has no square root at θl = 0), `ε = ε_v sinh z`, `ε_v = π/2 − θv`:
//! the visibility layer `μl/(μl + μv)` of width ~μv at the horizon and the features of J,
//! which scale with μl + μv at grazing views, are O(1)-wide in z, and the breakpoint θl = θv
//! is the fixed point `z_b = asinh 1`. Two panels, `z ∈ [0, z_b]` and `[z_b, asinh((π/2)/ε_v)]`,
//! each with nested Clenshaw–Curtis levels (17 … 129 nodes; the estimate of 9 nodes against 5
//! was once barely above the error) and the estimate of
//! [`tensor`](super::tensor) (`max(|Q_k − Q_{k−1}|, |Q_{k−1} − Q_{k−2}|²/max(|Q_k|, tol))`),
//! plus the inner rules' error bounds summed with the outer weights; each panel gets half the
//! tolerance. The breakpoint is an end of both panels, where the non-analytic term is an
//! endpoint singularity of order 2k + 1 ≥ 2.
//!
//! **Inner rule (ψ).** Split at ψ = π/2. On `[π/2, π]` the integrand is analytic within
//! O(1) of the interval and even about ψ = π: Clenshaw–Curtis in `ψ = π − (π/2)x`,
//! x ∈ [−1, 1] (each node and its mirror once). On `[0, π/2]`, `ψ = a sinh s`, `a = 2c_N`
//! (clamped to `[3·10⁻⁷ c_D, π/2]`), s ∈ [0, S], `S = asinh((π/2)/a)`: in s the
//! singularities of both scales lie at distance ~π/2 from the real axis (a sinh map turns
//! each scale between a and π/2 into an O(1) feature: Trefethen & Weideman 2014, "The
//! exponentially convergent trapezoidal rule", SIAM Review 56, §14 on such maps). The
//! integrand is even in s: Clenshaw–Curtis on `[−s₁, s₁]`, s₁ = min(S, 8) (each node and its
//! mirror once), and on equal sub-panels of length ≤ 8 up to S (only near the breakpoint,
//! where S reaches ~25). Every piece runs nested levels (5 … 129 nodes) until
//! `|T_m − T_{m/2}|` times the node's outer factor is below its share of the tolerance (or
//! below 1e-14 of T_m, rounding); that difference plus 1e-15 of the value is the node's
//! error bound. Where the lower clamp of a is active (at and next to the breakpoint), the
//! part ψ < a that the map does not resolve holds at most `2a·((c_N² + a²/4)/c_D²)^k`
//! (≤ 2·10⁻¹³ c_D), added to the bound. `Err(evaluations)` if a piece does not converge
//! within 129 nodes, a panel within 129 nodes, or the texel within [`EVAL_CAP`] evaluations.
//!
//! **Shared across a table column.** Every node (outer z, inner ψ) and `ln(N/D)` there
//! depends on μv alone, not on α: [`WideCache`] keeps them for the view (filled as texels
//! ask for them), and a texel then costs one `exp(k ln(N/D))` per evaluation, as the
//! half-vector kernel's [`SheenCache`](super::dfg_kernel::SheenCache) does. Over the wide
//! rows of a 128² `filament-dfg` table (`cargo run --release --example cloth_cost`, one
//! thread, tol 1e-7): 1,363 evaluations per texel against the half-vector kernel's 1,761,
//! every texel converged, ~1.8× less CPU time. Without the sharing this path takes ~3× the
//! kernel's time (~58 ns per evaluation: node, N/D, a logarithm and an exponential).
//!
//! Determinism: fixed nodes and summation order; a cache entry is a pure function of μv and
//! the node, so the value is a pure function of (μv, α, tol), with or without the cache.

// Node loops index several same-length arrays at once.
#![allow(clippy::needless_range_loop)]

use super::adaptive::Estimate;
use super::dfg_kernel::{exp_poly, ln_poly};
use super::tensor::{rules as cc_rules, MAX_LEVEL};
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

const NMAX: usize = (1 << MAX_LEVEL) + 1;
/// Index of x = 0 in the finest Clenshaw–Curtis level.
const MID: usize = NMAX / 2;
/// Lobes this path takes: α ∈ [`MIN_ALPHA`, `MAX_ALPHA`] (narrower ones: [`sheen_l`](super::sheen_l)).
pub const MIN_ALPHA: f64 = super::sheen_l::MAX_ALPHA;
/// The widest Charlie lobe (α = 1, k = ½).
pub const MAX_ALPHA: f64 = 1.0;
/// Evaluations after which a texel gives up (the half-vector kernel takes over).
pub const EVAL_CAP: u64 = 6000;
/// Lower clamp of the near map's scale a, relative to c_D: where it is active the part
/// ψ < a holds at most `2a·(a/(2c_D))^{2k} ≤ A_FLOOR²·c_D` (k ≥ ½), ≤ 1e-13·c_D.
const A_FLOOR: f64 = 3e-7;
/// Longest sub-panel in s of the near piece (the symmetric first one: [−S_PANEL, S_PANEL]);
/// measured over a 128² table: 3 → 1,727 evaluations per texel, 6 → 1,519, 8 → 1,478,
/// 12 → 1,472 (at inner share 0.05).
const S_PANEL: f64 = 8.0;
/// Share of a panel's tolerance that one outer node's inner error (times its outer factor)
/// may use (outer weights sum to 2, so the inner errors use at most 30%; 0.05 → 0.15 took
/// a 128² table's wide rows from 1,478 to 1,351 evaluations per texel; the outer panels'
/// estimate from level 4 on, not 3, then 1,363).
const INNER_SHARE: f64 = 0.15;

/// What this path does, for documentation and the benchmarks.
pub const METHOD: &str = "wide cloth lobes (1/16 <= alpha <= 1) in light-direction coordinates (src/integrate/sheen_wide.rs): outer nested Clenshaw-Curtis in pi/2 - theta_l = (pi/2 - theta_v) sinh z on two panels split at theta_l = theta_v (where h = n makes (sin theta_h)^(1/alpha) non-analytic); inner azimuthal integral split at psi = pi - phi = pi/2, nested Clenshaw-Curtis in psi on [pi/2, pi] and in psi = a sinh(s) on [0, pi/2] (a = |sin theta_l - sin theta_v|/sqrt(sin theta_l sin theta_v), the width of the h = n feature; s in panels of length <= 8); the roughness-independent node data shared by a table column; estimate from the nested levels plus the inner bounds";

/// The cloth albedo at view cosine `mu_v` ∈ (0, 1] and Charlie α ∈ [1/16, 1], to absolute
/// tolerance `tol` (estimated, see the module docs); `Err(evaluations spent)` where the
/// rules do not reach it (`Err(0)`: arguments outside that range). A pure function of its
/// arguments.
pub fn charlie_sheen_wide(mu_v: f64, alpha: f64, tol: f64) -> Result<Estimate<1>, u64> {
    charlie_sheen_wide_shared(mu_v, alpha, tol, &mut WideCache::default())
}

/// [`charlie_sheen_wide`] with the roughness-independent node data of the view `mu_v`
/// kept in `cache` for the next call (a table column): the same result, bit for bit (every
/// entry is a pure function of μv and the node; a cache holding another μv is cleared).
pub fn charlie_sheen_wide_shared(
    mu_v: f64,
    alpha: f64,
    tol: f64,
    cache: &mut WideCache,
) -> Result<Estimate<1>, u64> {
    if !(mu_v > 0.0
        && mu_v <= 1.0
        && (MIN_ALPHA..=MAX_ALPHA).contains(&alpha)
        && tol > 0.0
        && tol.is_finite())
    {
        return Err(0);
    }
    cache.select(mu_v);
    let view = View {
        mu_v,
        sv: ((1.0 - mu_v) * (1.0 + mu_v)).max(0.0).sqrt(),
        eps_v: mu_v.asin(),
    };
    let k = 0.5 / alpha;
    let norm = (2.0 + 1.0 / alpha) / (2.0 * PI);
    let z_b = 1f64.asinh();
    let z_t = (FRAC_PI_2 / view.eps_v).asinh();
    let panels = [(0.0, z_b), (z_b, z_t)];
    let n_panels = if z_t > z_b { 2 } else { 1 };
    let tol_p = tol / n_panels as f64;
    let (mut value, mut error, mut evals) = (0.0, 0.0, 0u64);
    for (p, &(z0, z1)) in panels[..n_panels].iter().enumerate() {
        let nodes = &mut cache.nodes[p * NMAX..(p + 1) * NMAX];
        let (v, e) = panel(&view, nodes, z0, z1, k, norm, tol_p, &mut evals)?;
        value += v;
        error += e;
    }
    if !(value.is_finite() && error.is_finite()) {
        return Err(evals);
    }
    Ok(Estimate {
        value: [value],
        error: [error],
        evals,
    })
}

/// The roughness-independent data of one view μv (a table column): per outer node, its
/// outer factor and, per inner piece and node, `ln(N/D)` and dψ/dx, filled as texels ask
/// for them.
#[derive(Default)]
pub struct WideCache {
    /// bits of the μv the entries belong to (meaningful only when `nodes` is non-empty)
    mu_bits: u64,
    /// per panel (2) and outer node of the finest level
    nodes: Vec<Option<Box<OuterNode>>>,
}

impl WideCache {
    fn select(&mut self, mu_v: f64) {
        if self.nodes.is_empty() || self.mu_bits != mu_v.to_bits() {
            self.mu_bits = mu_v.to_bits();
            self.nodes.clear();
            self.nodes.resize_with(2 * NMAX, || None);
        }
    }
}

/// The view's constants.
struct View {
    mu_v: f64,
    sv: f64,
    /// π/2 − θv
    eps_v: f64,
}

/// One outer panel `z ∈ [z0, z1]` (ε = ε_v sinh z): (value, error bound) to `tol`.
#[allow(clippy::too_many_arguments)]
fn panel(
    view: &View,
    nodes: &mut [Option<Box<OuterNode>>],
    z0: f64,
    z1: f64,
    k: f64,
    norm: f64,
    tol: f64,
    evals: &mut u64,
) -> Result<(f64, f64), u64> {
    let r = cc_rules();
    let mut done = [false; NMAX];
    let mut val = [0.0; NMAX];
    let mut err = [0.0; NMAX];
    let mut q = [0.0; MAX_LEVEL + 1];
    // the inner rules' values of one piece (each piece reads only what it wrote)
    let mut scratch = [0.0; NMAX];
    let half = 0.5 * (z1 - z0);
    let budget = INNER_SHARE * tol;
    for lev in 1..=MAX_LEVEL {
        let stride = 1usize << (MAX_LEVEL - lev);
        let (mut s, mut se) = (0.0, 0.0);
        for (jj, &w) in r.w[lev].iter().enumerate() {
            let i = jj * stride;
            if !done[i] {
                let node = nodes[i].get_or_insert_with(|| {
                    let z = z0 + half * (1.0 + r.x[i]);
                    let eps = view.eps_v * z.sinh();
                    let deps = view.eps_v * z.cosh() * half;
                    Box::new(if eps >= FRAC_PI_2 {
                        OuterNode::new(view, 1.0, 0.0)
                    } else {
                        let (sn, cs) = eps.sin_cos();
                        OuterNode::new(view, sn, cs * deps)
                    })
                });
                let (v, e) = node.eval(k, norm, budget, &mut scratch, evals)?;
                val[i] = v;
                err[i] = e;
                done[i] = true;
                if *evals > EVAL_CAP {
                    return Err(*evals);
                }
            }
            s += w * val[i];
            se += w * err[i];
        }
        q[lev] = s;
        if lev >= 4 {
            let e_out = super::tensor::nested_error(q[lev], q[lev - 1], q[lev - 2], tol);
            let e = e_out + se;
            if !e.is_finite() || !s.is_finite() {
                return Err(*evals);
            }
            if e <= tol {
                return Ok((s, e));
            }
        }
    }
    Err(*evals)
}

/// The inner rules' nodes in level order: position p of a piece's arrays holds the node
/// `idx[p]` of the finest level, the nodes of level 2 first, then each level's new nodes,
/// so that a level's new values are one contiguous slice (loops that vectorize); with each
/// level's weights in the same order. Symmetric pieces keep the nodes x ≥ 0 (i ≤ MID) and
/// fold the mirror half and the ½ of "half of [−1, 1]" into the weights.
struct Order {
    idx: [usize; NMAX],
    /// positions filled after level k: count[k]
    count: [usize; MAX_LEVEL + 1],
    /// w[k][p]: level k's weight of position p
    w: [[f64; NMAX]; MAX_LEVEL + 1],
}

impl Order {
    fn new(sym: bool) -> Order {
        let r = cc_rules();
        let last = if sym { MID } else { NMAX - 1 };
        let mut o = Order {
            idx: [0; NMAX],
            count: [0; MAX_LEVEL + 1],
            w: [[0.0; NMAX]; MAX_LEVEL + 1],
        };
        let mut n = 0;
        for lev in 2..=MAX_LEVEL {
            let stride = 1usize << (MAX_LEVEL - lev);
            let mut i = 0;
            while i <= last {
                // new at this level: level 2 takes all, later levels the odd multiples
                if lev == 2 || (i / stride) % 2 == 1 {
                    o.idx[n] = i;
                    n += 1;
                }
                i += stride;
            }
            o.count[lev] = n;
            for p in 0..n {
                let i = o.idx[p];
                let w = r.w[lev][i / stride];
                // symmetric: i < MID stands for i and its mirror, and the piece is half of
                // the rule on [−1, 1]: w for i < MID, w/2 for x = 0
                o.w[lev][p] = if sym && i == MID { 0.5 * w } else { w };
            }
        }
        o
    }
}

/// The level orders (symmetric, general) and y = sin²(ψ/2) at the far piece's nodes
/// ψ = π − (π/2)x in the symmetric order, the same for every texel.
struct Tables {
    sym: Order,
    gen: Order,
    far_y: [f64; NMAX],
}

fn tables() -> &'static Tables {
    static T: OnceLock<Tables> = OnceLock::new();
    T.get_or_init(|| {
        let r = cc_rules();
        let sym = Order::new(true);
        let mut far_y = [0.0; NMAX];
        for p in 0..sym.count[MAX_LEVEL] {
            // sin(π/2 − πx/4) = cos(πx/4)
            let c = (0.25 * PI * r.x[sym.idx[p]]).cos();
            far_y[p] = c * c;
        }
        Tables {
            sym,
            gen: Order::new(false),
            far_y,
        }
    })
}

/// sin²(t) for t ∈ [0, π/4] with full relative accuracy at small t:
/// `t²·(sin t / t)²`, sin t/t by its Taylor series to t¹⁶ (truncation `(π/4)¹⁸/19! < 1e-19`),
/// plain arithmetic for vectorized loops.
#[inline(always)]
fn sin2_small(t: f64) -> f64 {
    let z = t * t;
    let mut p = 1.0 / 355_687_428_096_000.0; // 1/17!
    p = p * (-z) + 1.0 / 1_307_674_368_000.0; // 1/15!
    p = p * (-z) + 1.0 / 6_227_020_800.0; // 1/13!
    p = p * (-z) + 1.0 / 39_916_800.0; // 1/11!
    p = p * (-z) + 1.0 / 362_880.0; // 1/9!
    p = p * (-z) + 1.0 / 5_040.0; // 1/7!
    p = p * (-z) + 1.0 / 120.0; // 1/5!
    p = p * (-z) + 1.0 / 6.0; // 1/3!
    p = 1.0 - z * p;
    z * p * p
}

/// One outer node's roughness-independent data.
struct OuterNode {
    /// μl·V·dμl/dx (the outer factor without Charlie's norm); 0: the node contributes 0
    g0: f64,
    /// (2a, ln((n0 + B a²/4)/e0)) where the clamp of a is active: the part ψ < a holds at
    /// most `2a·exp(k·ln(…))`
    unresolved: Option<(f64, f64)>,
    /// the far piece first, then the near piece's sub-panels
    pieces: Vec<Piece>,
}

impl OuterNode {
    /// The node at μl = `ml` with dμl/dx = `dml`.
    fn new(view: &View, ml: f64, dml: f64) -> OuterNode {
        let mu_v = view.mu_v;
        if ml <= 0.0 || dml == 0.0 {
            return OuterNode {
                g0: 0.0,
                unresolved: None,
                pieces: Vec::new(),
            };
        }
        let ml = ml.min(1.0);
        let sl = ((1.0 - ml) * (1.0 + ml)).max(0.0).sqrt();
        let b = 4.0 * view.sv * sl;
        // sv − sl = (μl − μv)(μl + μv)/(sv + sl), without cancellation near the breakpoint
        let c = mu_v + ml;
        let ssum = view.sv + sl;
        let dn = if ssum > 0.0 {
            (ml - mu_v) * c / ssum
        } else {
            0.0
        };
        let n0 = dn * dn;
        let e0 = n0 + c * c;
        let g0 = ml / (4.0 * (ml + mu_v - ml * mu_v)) * dml;
        let c_d = if b > 0.0 {
            (e0 / b).sqrt()
        } else {
            f64::INFINITY
        };
        let c_n = if b > 0.0 {
            (n0 / b).sqrt()
        } else {
            f64::INFINITY
        };
        let floor = A_FLOOR * c_d;
        let a = (2.0 * c_n).max(floor).min(FRAC_PI_2);
        let unresolved = (2.0 * c_n < floor && floor < FRAC_PI_2).then(|| {
            // ψ < a: N/D ≤ (n0 + B a²/4)/e0 there
            (2.0 * a, (((n0 + 0.25 * b * a * a) / e0).max(1e-300)).ln())
        });
        let consts = Consts { n0, e0, b };
        let mut pieces = vec![Piece::new(consts, Map::Far)];
        let big_s = (FRAC_PI_2 / a).asinh();
        let s1 = big_s.min(S_PANEL);
        pieces.push(Piece::new(consts, Map::SinhSym { a, s1 }));
        let n_more = ((big_s - s1) / S_PANEL).ceil() as usize;
        for j in 0..n_more {
            let lo = s1 + (big_s - s1) * j as f64 / n_more as f64;
            let hi = s1 + (big_s - s1) * (j + 1) as f64 / n_more as f64;
            pieces.push(Piece::new(consts, Map::Sinh { a, s0: lo, s1: hi }));
        }
        OuterNode {
            g0,
            unresolved,
            pieces,
        }
    }

    /// The outer integrand (times dμl/dx) for Charlie exponent `k` and normalization `norm`,
    /// and its error bound (the inner rules' bounds times the outer factor); `budget` is what
    /// that bound may reach. `Err` if an inner piece does not converge within 129 nodes.
    fn eval(
        &mut self,
        k: f64,
        norm: f64,
        budget: f64,
        scratch: &mut [f64; NMAX],
        evals: &mut u64,
    ) -> Result<(f64, f64), u64> {
        if self.g0 == 0.0 {
            return Ok((0.0, 0.0));
        }
        let g = norm * self.g0;
        // J = 2·Σ pieces: each piece may use an equal part of half the budget
        let share = 0.5 * budget / (g.abs().max(1e-300) * self.pieces.len() as f64);
        let (mut j, mut ej) = (0.0, 0.0);
        for p in self.pieces.iter_mut() {
            let (t, e) = p.run(k, share, scratch, evals)?;
            j += t;
            ej += e;
        }
        let j = 2.0 * j;
        let unresolved = self
            .unresolved
            .map_or(0.0, |(two_a, ln_u)| two_a * (k * ln_u).exp());
        let ej = 2.0 * ej + unresolved + 1e-15 * j;
        Ok((g * j, g * ej))
    }
}

/// The inner integrand's constants: `(N/D)^k` with `N = n0 + B y`, `D = e0 + B y`.
#[derive(Clone, Copy)]
struct Consts {
    n0: f64,
    e0: f64,
    b: f64,
}

/// An inner piece's variable: `[π/2, π]` as ψ = π − (π/2)x (symmetric about x = 0); on
/// `[0, π/2]`, ψ = a sinh(s) with s = s1·x (symmetric) or s ∈ [s0, s1].
#[derive(Clone, Copy)]
enum Map {
    Far,
    SinhSym { a: f64, s1: f64 },
    Sinh { a: f64, s0: f64, s1: f64 },
}

impl Map {
    /// Whether the integrand is even in x (nodes i ≤ MID stand for their mirrors too).
    fn symmetric(self) -> bool {
        !matches!(self, Map::Sinh { .. })
    }
}

/// One inner piece of one outer node: `ln(N/D)` (`l`) and the weight factor dψ/dx (`w`, 0
/// where N/D underflows) at its nodes in level order ([`Order`]), the first `have` filled.
struct Piece {
    consts: Consts,
    map: Map,
    have: usize,
    l: [f64; NMAX],
    w: [f64; NMAX],
}

impl Piece {
    fn new(consts: Consts, map: Map) -> Piece {
        Piece {
            consts,
            map,
            have: 0,
            l: [0.0; NMAX],
            w: [0.0; NMAX],
        }
    }

    fn order(&self) -> &'static Order {
        let t = tables();
        if self.map.symmetric() {
            &t.sym
        } else {
            &t.gen
        }
    }

    /// Makes sure the nodes of level `lev` are filled.
    fn ensure(&mut self, lev: usize) {
        let o = self.order();
        let n = o.count[lev];
        if self.have >= n {
            return;
        }
        let r = cc_rules();
        let t = tables();
        let Consts { n0, e0, b } = self.consts;
        for p in self.have..n {
            let x = r.x[o.idx[p]];
            let (y, jac) = match self.map {
                Map::Far => (t.far_y[p], FRAC_PI_2),
                Map::SinhSym { a, s1 } => sinh_node(a, s1 * x, s1),
                Map::Sinh { a, s0, s1 } => {
                    let h = 0.5 * (s1 - s0);
                    sinh_node(a, s0 + h * (1.0 + x), h)
                }
            };
            let ratio = (n0 + b * y) / (e0 + b * y);
            let keep = if ratio > 1e-300 { 1.0 } else { 0.0 };
            self.l[p] = ln_poly(ratio.max(1e-300));
            self.w[p] = keep * jac;
        }
        self.have = n;
    }

    /// ∫ (N/D)^k dψ over the piece and its error bound, nested levels 2…7 until the level
    /// difference is within `share` (or 1e-14 of the value: rounding).
    fn run(
        &mut self,
        k: f64,
        share: f64,
        vals: &mut [f64; NMAX],
        evals: &mut u64,
    ) -> Result<(f64, f64), u64> {
        let o = self.order();
        let mut done = 0usize;
        let mut prev = f64::NAN;
        for lev in 2..=MAX_LEVEL {
            self.ensure(lev);
            let n = o.count[lev];
            for p in done..n {
                vals[p] = exp_poly((k * self.l[p]).max(-700.0)) * self.w[p];
            }
            *evals += (n - done) as u64;
            done = n;
            let w = &o.w[lev];
            let mut t = 0.0;
            for p in 0..n {
                t += w[p] * vals[p];
            }
            if lev >= 3 {
                let e = (t - prev).abs();
                if e <= share || e <= 1e-14 * t.abs() {
                    return Ok((t, e));
                }
            }
            prev = t;
        }
        Err(*evals)
    }
}

/// y = sin²(ψ/2) and dψ/dx at s (ψ = a sinh s, ds/dx = `ds_dx`).
#[inline(always)]
fn sinh_node(a: f64, s: f64, ds_dx: f64) -> (f64, f64) {
    let e = exp_poly(s);
    let ei = 1.0 / e;
    let psi = a * 0.5 * (e - ei);
    (sin2_small(0.5 * psi), a * 0.5 * (e + ei) * ds_dx)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At normal view the albedo is a Beta integral
    /// ([`sheen_l::normal_view_albedo`](crate::integrate::sheen_l::normal_view_albedo)); the
    /// path must agree within its estimate plus rounding (1e-13 relative) and meet the
    /// tolerance.
    #[test]
    fn normal_view_matches_closed_form() {
        for &alpha in &[MIN_ALPHA, 0.1, 0.25, 0.5, 0.75, 1.0] {
            let exact = crate::integrate::sheen_l::normal_view_albedo(alpha);
            for tol in [1e-7, 1e-10] {
                let e = charlie_sheen_wide(1.0, alpha, tol).expect("converges at normal view");
                let d = (e.value[0] - exact).abs();
                assert!(
                    e.error[0] <= tol && d <= e.error[0] + 1e-13 * exact,
                    "alpha={alpha} tol={tol}: {e:?} vs {exact}"
                );
            }
        }
    }

    /// `sin2_small` against `sin(t)²` over its range, to 4 ulp relative.
    #[test]
    fn sin2_small_is_accurate() {
        for i in 0..=1000 {
            let t = std::f64::consts::FRAC_PI_4 * (i as f64 / 1000.0).powi(3);
            let (a, b) = (sin2_small(t), t.sin().powi(2));
            assert!((a - b).abs() <= 4.0 * f64::EPSILON * b, "{t}: {a} vs {b}");
        }
    }

    /// The inner rule's two pieces against a brute-force composite midpoint rule in ψ
    /// (refined geometrically towards ψ = 0) near the breakpoint, where the h = n feature is
    /// narrow: agreement within the returned bound plus the brute force's own error
    /// (estimated by halving its step).
    #[test]
    fn inner_rule_resolves_the_breakpoint_feature() {
        for &(mu_v, ml, k) in &[
            (0.5, 0.5, 0.5),
            (0.5, 0.499, 0.5),
            (0.5, 0.4999, 2.0),
            (0.01, 0.011, 0.5),
            (0.9, 0.2, 8.0),
        ] {
            let sv = ((1.0f64 - mu_v) * (1.0 + mu_v)).sqrt();
            let view = View {
                mu_v,
                sv,
                eps_v: mu_v.asin(),
            };
            let mut node = OuterNode::new(&view, ml, 1.0);
            // g = ml/(4(ml + mu_v − ml mu_v)) with norm = dml = 1
            let g = ml / (4.0 * (ml + mu_v - ml * mu_v));
            let mut n = 0;
            let (v, e) = node
                .eval(k, 1.0, 1e-11, &mut [0.0; NMAX], &mut n)
                .unwrap_or_else(|_| panic!("{mu_v} {ml} {k}: no convergence"));
            let sl = ((1.0f64 - ml) * (1.0 + ml)).sqrt();
            let f = |psi: f64| {
                let x = (psi / 2.0).sin().powi(2);
                let num = (sv - sl).powi(2) + 4.0 * sv * sl * x;
                (num / (num + (mu_v + ml).powi(2))).powf(k)
            };
            let brute = |m: usize| {
                // panels [π·4^{-(j+1)}, π·4^{-j}], j < 20, plus [0, π·4^-20], m midpoints each
                let mut s = 0.0;
                for j in 0..=20 {
                    let (lo, hi) = if j == 20 {
                        (0.0, PI * 0.25f64.powi(20))
                    } else {
                        (PI * 0.25f64.powi(j + 1), PI * 0.25f64.powi(j))
                    };
                    let h = (hi - lo) / m as f64;
                    for i in 0..m {
                        s += h * f(lo + h * (i as f64 + 0.5));
                    }
                }
                2.0 * s * g
            };
            let (b1, b2) = (brute(2000), brute(4000));
            let d = (v - b2).abs();
            assert!(
                d <= e + (b1 - b2).abs() + 1e-14 * b2,
                "{mu_v} {ml} {k}: {v} (bound {e:e}) vs {b2} (±{:e})",
                (b1 - b2).abs()
            );
        }
    }
}
