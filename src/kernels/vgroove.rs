//! The fast path for hemisphere integrals with Cook–Torrance's V-groove masking term
//! `G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h))` (Cook & Torrance 1982, eq. 6, after
//! Torrance & Sparrow 1967): the nested Clenshaw–Curtis tensor rule of
//! [`tensor`](crate::hemisphere::tensor) on pieces of the half-vector domain inside which G is one
//! smooth branch, so that no rule ever sees a kink.
//!
//! **Which branch where.** Same coordinates as [`integrate_over_l`]: view
//! `v = (sin θv, 0, cos θv)`, half vector at (θh, φ), `tan ψ = tan θv cos φ`, horizon
//! `θmax = π/4 + ψ/2`. Writing `t = tan θh`, `s = tan ψ`, one has
//! `v·h = cos θh cos θv (1 + t s)`, hence
//!
//! * `gv = 2(n·h)(n·v)/(v·h) = 2/(1 + t s)`, and
//! * `gl = 2(n·h)(n·l)/(v·h) = 4 cos²θh − gv` (from `n·l = 2(v·h)(n·h) − n·v`),
//!
//! so `gl = gv` ⇔ `t = s` (θh = ψ), `gv = 1` ⇔ `θh = π/2 − ψ`, and `gl = 1` ⇔
//! `θh = (ψ + π/2)/3` (see [`vgroove_kinks`](crate::hemisphere::vgroove_kinks), which lists
//! all three candidates). Of these, only some are branch switches of the min (derived
//! here): both ratios are 2 at θh = 0, gl decreases through 1 once in `[0, θmax]`, and
//! gl < gv exactly for θh > ψ. Hence
//!
//! * `ψ ≤ π/4`: `G = 1` on `[0, (ψ + π/2)/3]`, `G = gl` on `[(ψ + π/2)/3, θmax]` (for
//!   0 < ψ ≤ π/4 the crossing at θh = ψ has `gv = gl = 2cos²ψ ≥ 1`, and `gv = 1` lies
//!   where gl < 1 already);
//! * `ψ > π/4`: `G = 1` on `[0, π/2 − ψ]`, `G = gv` on `[π/2 − ψ, ψ]`, `G = gl` on
//!   `[ψ, θmax]`.
//!
//! All three switches coincide at ψ = π/4 (θh = π/4), the only place where the inner
//! integral is not smooth in φ: the φ range is split there, at `cos φ = 1/tan θv` (views
//! beyond 45°). Each (φ panel, θh piece) is then a smooth 2D integral whose θh ends are
//! smooth functions of φ, integrated by the nested tensor rule and driver of
//! [`tensor::refine`](crate::hemisphere::tensor) (its error estimate from the nested lower-order
//! rules, each piece to its share of the tolerance, the estimates summed).
//!
//! **Warps.** φ = π/2 + c·sinh s with `c = min(cot θv, 1)` as in the smooth fast path (the
//! panels are intervals of s); the inner variable of a piece is the lobe warp
//! `u = asinh(tan θh / α)` mapped linearly from the piece's ends in u.
//!
//! **Tail cut.** A narrow lobe seen at a grazing angle makes the pieces long in u (the
//! middle one reaches u ≈ 7.5 for α = 0.05, μ = 1/64) while the integrand lives in the
//! first ~2 units of it: the nested rule then spends its nodes on zeros and may not
//! converge within 65×65 nodes. Where the caller can bound the integrand's tail (a
//! [`TailCut`], e.g. [`TailCut::beckmann_vgroove`]), u stops at the cut and the bound is
//! added to the error estimate.

// Channel loops index several same-length arrays at once; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

use crate::hemisphere::tensor::{PhiWarp, Scratch};
use crate::hemisphere::{integrate_over_l, tan_theta_h_max, LobeWarp, Node};
use crate::numerics::exp_poly;
use crate::quadrature::adaptive::Estimate;
use crate::quadrature::clenshaw_curtis::{inner_sums, refine, rules, MAX_LEVEL};
use std::cell::RefCell;
use std::f64::consts::FRAC_PI_2;

/// What the fast path does, as the sidecar's `quadrature.method` states it.
pub const METHOD: &str = "V-groove masking split into its smooth branches (G = 1, 2(n.h)(n.v)/(v.h), 2(n.h)(n.l)/(v.h)) in closed form: theta_h split at (psi + pi/2)/3 (tan psi = tan theta_v cos phi <= 1), or at pi/2 - psi and psi (tan psi > 1), phi split where tan psi = 1; on each piece a nested Clenshaw-Curtis tensor rule (2^k+1 nodes per dimension, k = 3..7, at most 65x65 nodes) over phi = pi/2 + c sinh(s), c = min(cot theta_v, 1), and the lobe warp u = asinh(tan theta_h / alpha) up to the exact horizon pi/4 + psi/2, refined one dimension at a time; error estimate per piece and dimension max(|Q_k - Q_k-1|, |Q_k-1 - Q_k-2|^2 / max(|Q_k|, tol)), summed over dimensions and pieces (tolerance shared among the pieces in order: each may use what the pieces before left unspent, divided by the pieces still to come); Beckmann lobes without a diffuse lobe: u cut where the integrand's tail beyond is provably <= 1e-4 of the tolerance (added to the estimate), and the integrand in closed form per piece (D sin(theta_h) dtheta_h = exp(-sinh^2 u) sinh u cosh u / (pi cos theta_h) du, G (v.h) = v.h, 2(n.h)(n.v) or 2(n.h)(n.l) by piece); a texel any of whose pieces does not reach its share within 65x65 nodes, and every texel of a sheen lobe or under a dielectric Fresnel with eta < 1 (whose total-internal-reflection kink the split does not follow), is integrated by nested adaptive Gauss-Kronrod (G7/K15) instead (phi split at pi/2 and at the kinks' meeting points, theta_h split at the kinks, estimate |K15 - G7| summed over panels); f64 accumulation";

const NMAX: usize = (1 << MAX_LEVEL) + 1;

/// The θh piece of a φ node, as its ends in the lobe variable u.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Piece {
    /// `[0, u(θa)]`, G = 1.
    Flat,
    /// Between the first switch and the second (gv branch, ψ > π/4 only).
    Middle,
    /// From the last switch to the horizon (gl branch).
    Outer,
}

/// The θh values (as tangents) at which G switches branch for a view with `tan ψ = s`,
/// in increasing order, none beyond `tan_max`, and how many: one switch for `s ≤ 1`, two
/// for `s > 1` (module docs).
#[inline]
fn switches(s: f64, tan_max: f64) -> ([f64; 2], usize) {
    if s <= 1.0 {
        // tan((ψ + π/2)/3)
        let th = (s.atan() + FRAC_PI_2) / 3.0;
        ([th.tan().min(tan_max), 0.0], 1)
    } else {
        // tan(π/2 − ψ) = 1/s < 1 < s = tan ψ < tan θmax
        ([1.0 / s, s.min(tan_max)], 2)
    }
}

/// The ends `(u_lo, u_hi)` of piece `p` for `tan ψ = s`, lobe scale α and horizon `tan_max`,
/// none beyond `cap`.
#[cfg(test)]
fn piece_ends(p: Piece, s: f64, alpha: f64, tan_max: f64, cap: f64) -> (f64, f64) {
    let (t, n) = switches(s, tan_max);
    let u = |tan_th: f64| (tan_th / alpha).asinh();
    let umax = u(tan_max).min(cap);
    let u = |t: f64| u(t).min(cap);
    match p {
        Piece::Flat => (0.0, u(t[0]).min(umax)),
        Piece::Middle => {
            let lo = u(t[0]).min(umax);
            (lo, u(t[1]).clamp(lo, umax))
        }
        Piece::Outer => (u(t[n - 1]).min(umax), umax),
    }
}

/// The ends of every piece for `tan ψ = s` (indexed as [`Piece`]: Flat, Middle, Outer), the
/// same values as [`piece_ends`] gives one by one, with each asinh computed once.
#[inline]
fn all_piece_ends(s: f64, alpha: f64, tan_max: f64, cap: f64) -> [(f64, f64); 3] {
    let (t, n) = switches(s, tan_max);
    let u = |tan_th: f64| (tan_th / alpha).asinh();
    let umax = u(tan_max).min(cap);
    let u0 = u(t[0]).min(cap).min(umax);
    let u1 = if n == 2 { u(t[1]).min(cap) } else { u0 };
    [
        (0.0, u0),
        (u0, u1.clamp(u0, umax)),
        (if n == 2 { u1.min(umax) } else { u0 }, umax),
    ]
}

/// A φ node's data, shared by the pieces of its panel: cos φ, dφ/dx (×2 for the mirror
/// half) and every piece's u range.
#[derive(Clone, Copy)]
struct PhiNode {
    cp: f64,
    dphi_dx: f64,
    ends: [(f64, f64); 3],
}

/// Where a lobe's tail may be left out: over the half vectors with
/// `asinh(tan θh / α) > u` the integrand integrates to at most `mass` (absolute, every
/// channel), which the fast path adds to its error estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TailCut {
    pub u: f64,
    pub mass: f64,
}

impl TailCut {
    /// No cut.
    pub const NONE: TailCut = TailCut {
        u: f64::INFINITY,
        mass: 0.0,
    };

    /// The cut for a Beckmann lobe (width α) under the V-groove term with a Fresnel factor
    /// ≤ 1 and no other lobe, each channel's integrand at most `f·(n·l)` of that BRDF:
    /// per unit solid angle of h the integrand is `D·G·F·(v·h)/(n·v)` (with
    /// `dω_l = 4(v·h) dω_h`), and `G ≤ 2(n·h)(n·v)/(v·h)`, so it is at most `2·D·(n·h)`,
    /// whose integral over `tan θh > T` is `2·exp(−T²/α²)` (the Beckmann distribution of
    /// tan²θh is exponential: Walter et al. 2007, eq. 28). For a tail of at most `mass`,
    /// `T/α = sinh u = √ln(2/mass)`.
    pub fn beckmann_vgroove(mass: f64) -> TailCut {
        TailCut {
            u: (2.0 / mass).ln().max(0.0).sqrt().asinh(),
            mass,
        }
    }
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// The V-groove fast path: `∫ g dω_l` over the upper hemisphere of `l` for a view with
/// cosine `n_dot_v ∈ (0, 1]` and an NDF lobe of width `alpha` at the normal, `g` being
/// `f(v, l)·(n·l)` per channel at a half-vector node (as for
/// [`integrate_over_l`]), with G inside `f` the V-groove term; u beyond `tail.u` left out
/// (and `tail.mass` added to the estimate). `Err(evaluations spent)` if a piece's nested
/// rule does not reach its share of `tol_abs` within the tensor rule's limits.
pub fn integrate_over_l_vgroove_cc<const N: usize, F: Fn(&Node) -> [f64; N]>(
    n_dot_v: f64,
    alpha: f64,
    tail: TailCut,
    tol_abs: f64,
    g: F,
) -> Result<Estimate<N>, u64> {
    let w = PhiWarp::new(n_dot_v);
    let (mu_v, sin_v) = (w.mu_v, w.sin_v);
    // the integrand per du dφ at (cos φ, u): g times dω_l/(du dφ)
    let h1 = |cp: f64, u: f64| -> [f64; N] {
        let t = alpha * u.sinh();
        let c2 = 1.0 / (1.0 + t * t);
        let cos_h = c2.sqrt();
        let sin_h = t * cos_h;
        let n = Node::at(mu_v, sin_v, cp, sin_h, cos_h);
        if n.n_dot_l <= 0.0 || n.v_dot_h <= 0.0 {
            return [0.0; N];
        }
        // dω_h = sin θh dθh dφ, dθh/du = α cosh u cos²θh; dω_l = 4(v·h) dω_h
        let jac = 4.0 * n.v_dot_h * sin_h * alpha * u.cosh() * c2;
        let y = g(&n);
        let mut out = [0.0; N];
        for k in 0..N {
            out[k] = y[k] * jac;
        }
        out
    };
    let h = |_: Piece, cp: f64, us: &[f64], out: &mut [[f64; N]]| {
        for (o, &u) in out.iter_mut().zip(us) {
            *o = h1(cp, u);
        }
    };
    run_pieces(w, alpha, tail, tol_abs, &h)
}

/// The directional albedo `∫ f (n·l) dω_l` of a Beckmann lobe (width `alpha`) with the
/// V-groove term and the Fresnel factor `fresnel(v·h)` (≤ 1; no other lobe), by the V-groove
/// fast path with the integrand in closed form on each piece (the branch of G is known
/// there, so no min() is evaluated). With `tan θh = α sinh u`, Beckmann's
/// `D = exp(−tan²θh/α²)/(π α² cos⁴θh)` (Walter et al. 2007, eq. 25) and
/// `dθh/du = α cosh u cos²θh`,
///
/// `D sin θh dθh = exp(−sinh²u) sinh u cosh u/(π cos θh) du`,
///
/// and with `f (n·l) dω_l = D G F (v·h)/(n·v) dω_h` (from `dω_l = 4(v·h) dω_h`) the piece's
/// `G·(v·h)` is `v·h` (G = 1), `2(n·h)(n·v)` (the n·v branch) or `2(n·h)(n·l)` (the n·l
/// branch; Cook & Torrance 1982, eq. 6). One exponential gives sinh u and cosh u, one more
/// Beckmann's exp(−sinh²u): the same integral, nodes, pieces and estimate as
/// [`integrate_over_l_vgroove_cc`] with about half the work per node. `tail` as there.
pub fn beckmann_vgroove_albedo<Fr: Fn(f64) -> f64>(
    n_dot_v: f64,
    alpha: f64,
    tail: TailCut,
    tol_abs: f64,
    fresnel: Fr,
) -> Result<Estimate<1>, u64> {
    let w = PhiWarp::new(n_dot_v);
    let (mu_v, sin_v) = (w.mu_v, w.sin_v);
    let inv_pi_mu = 1.0 / (std::f64::consts::PI * mu_v);
    // A batch of u nodes at one φ node, written as plain arithmetic (no calls but the inlined
    // exp_poly and `fresnel`, no branches but selects) so that the loop vectorizes.
    let h = |piece: Piece, cp: f64, us: &[f64], out: &mut [[f64; 1]]| {
        // G·(v·h)/cos θh by piece: v·h/cos θh, 2(n·v), 2(n·l)/cos θh·cos θh (see below)
        let (kf, km, ko) = match piece {
            Piece::Flat => (1.0, 0.0, 0.0),
            Piece::Middle => (0.0, 1.0, 0.0),
            Piece::Outer => (0.0, 0.0, 1.0),
        };
        let st = sin_v * cp;
        for (o, &u) in out.iter_mut().zip(us) {
            // sinh u, cosh u from e^u (0 ≤ u ≤ the tail cut, a few units: for small u the
            // difference loses relative accuracy of sinh u but its absolute error stays
            // ~1e-16, and the integrand is proportional to it)
            let e = exp_poly(u);
            let inv_e = 1.0 / e;
            let sh = 0.5 * (e - inv_e);
            let ch = 0.5 * (e + inv_e);
            let t = alpha * sh;
            let c2 = 1.0 / (1.0 + t * t);
            let cos_h = c2.sqrt();
            // v·h = cos θh (n·v + sin θv tan θh cos φ) and n·l = 2(v·h)(n·h) − n·v
            let vh_over_cos = mu_v + st * t;
            let v_dot_h = cos_h * vh_over_cos;
            let n_dot_l = 2.0 * c2 * vh_over_cos - mu_v;
            let d = exp_poly((-sh * sh).max(-700.0));
            // D sin θh dθh/du · F/(n·v), then G·(v·h) of the piece
            let e = d * sh * ch * fresnel(v_dot_h.clamp(0.0, 1.0)) * inv_pi_mu;
            let g = kf * vh_over_cos + km * (2.0 * mu_v) + ko * (2.0 * n_dot_l);
            let visible = n_dot_l > 0.0 && v_dot_h > 0.0;
            o[0] = if visible { e * g } else { 0.0 };
        }
    };
    run_pieces(w, alpha, tail, tol_abs, &h)
}

/// The pieces of the V-groove fast path (module docs) for the view `w`, each by its nested
/// tensor rule over `h(piece, cos φ, us, out)`, the integrand per du dφ at a batch of u
/// nodes of one φ node; u beyond `tail.u` left out and `tail.mass` added to the estimate.
/// The tolerance left after the tail is shared among the pieces in order: each piece may
/// use what is left divided by the pieces still to come (an estimate below its share leaves
/// the rest to the later pieces; the sum stays within `tol_abs`). Per panel the G = 1 piece
/// comes last: it is the costliest (half the evaluations of `cook-torrance-1982`/albedo)
/// and the others, whose nested estimates usually land far below their shares, leave it
/// most of theirs (2.02 → 1.97 M evaluations for that table).
fn run_pieces<const N: usize, H: Fn(Piece, f64, &[f64], &mut [[f64; N]])>(
    w: PhiWarp,
    alpha: f64,
    tail: TailCut,
    tol_abs: f64,
    h: &H,
) -> Result<Estimate<N>, u64> {
    let PhiWarp {
        mu_v: _,
        sin_v: _,
        tan_v,
        c,
        big_s,
    } = w;
    // φ panels in s: split where tan ψ = 1 (cos φ = 1/tan θv), left of it ψ > π/4
    let mut panels: Vec<(f64, f64, &[Piece])> = Vec::with_capacity(2);
    const TWO: &[Piece] = &[Piece::Outer, Piece::Flat];
    const THREE: &[Piece] = &[Piece::Outer, Piece::Middle, Piece::Flat];
    if tan_v > 1.0 {
        let phi_star = (1.0 / tan_v).acos();
        let s_star = ((phi_star - FRAC_PI_2) / c).asinh();
        panels.push((-big_s, s_star, THREE));
        panels.push((s_star, big_s, TWO));
    } else {
        panels.push((-big_s, big_s, TWO));
    }
    let n_pieces: usize = panels.iter().map(|p| p.2.len()).sum();
    let tol_pieces = tol_abs - tail.mass;
    let mut total = Estimate::<N>::zero();
    total.error = [tail.mass; N];
    let mut spent = 0u64;
    // tolerance used so far (largest channel) and pieces done
    let (mut used, mut done) = (0.0f64, 0usize);
    for &(s0, s1, pieces) in &panels {
        // the φ nodes of this panel, filled as the pieces' rules ask for them
        let mut nodes: [Option<PhiNode>; NMAX] = [None; NMAX];
        for &piece in pieces {
            let tol_piece = (tol_pieces - used) / (n_pieces - done) as f64;
            let r = SCRATCH.with(|sc| {
                let sc = &mut *sc.borrow_mut();
                let at = (tan_v, c, (s0, s1), &mut nodes);
                piece_rule(sc, at, piece, (alpha, tail.u), tol_piece, h)
            });
            match r {
                Ok(e) => {
                    for k in 0..N {
                        total.value[k] += e.value[k];
                        total.error[k] += e.error[k];
                    }
                    used += e.error.iter().fold(0.0f64, |a, &b| a.max(b));
                    done += 1;
                    spent += e.evals;
                }
                Err(n) => return Err(spent + n),
            }
        }
    }
    total.evals = spent;
    Ok(total)
}

/// One piece's tensor rule over `s ∈ [s0, s1]` (φ = π/2 + c sinh s, doubled by mirror
/// symmetry) and the piece's u range, through [`refine`]; `h(piece, cos φ, u)` is the
/// integrand per du dφ.
#[allow(clippy::too_many_arguments)]
fn piece_rule<const N: usize, H: Fn(Piece, f64, &[f64], &mut [[f64; N]])>(
    sc: &mut Scratch,
    (tan_v, c, (s0, s1), nodes): (f64, f64, (f64, f64), &mut [Option<PhiNode>; NMAX]),
    piece: Piece,
    (alpha, cap): (f64, f64),
    tol: f64,
    h: &H,
) -> Result<Estimate<N>, u64> {
    let r = rules();
    sc.reset(N);
    let (s_mid, s_half) = (0.5 * (s0 + s1), 0.5 * (s1 - s0));
    let fill = |sc: &mut Scratch, evals: &mut u64, i: usize, ku: usize| {
        let have = sc.level[i];
        if have != usize::MAX && have >= ku {
            return;
        }
        let PhiNode { cp, dphi_dx, ends } = *nodes[i].get_or_insert_with(|| {
            let s = s_mid + s_half * r.x[i];
            let phi = FRAC_PI_2 + c * s.sinh();
            let cp = phi.cos();
            let tan_max = tan_theta_h_max(tan_v, cp);
            PhiNode {
                cp,
                // dφ/dx = c cosh(s)·s_half; ×2 for φ ∈ [0, π] standing for the whole circle
                dphi_dx: 2.0 * c * s.cosh() * s_half,
                ends: all_piece_ends(tan_v * cp, alpha, tan_max, cap),
            }
        });
        let (u0, u1) = ends[piece as usize];
        let half = 0.5 * (u1 - u0);
        sc.scale[i] = half * dphi_dx;
        let stride = 1usize << (MAX_LEVEL - ku);
        let old_stride = if have == usize::MAX {
            0
        } else {
            1usize << (MAX_LEVEL - have)
        };
        let base = i * NMAX * N;
        // the new nodes of this level, evaluated as one batch
        let (mut us, mut js, mut m) = ([0.0f64; NMAX], [0usize; NMAX], 0usize);
        let mut j = 0;
        while j < NMAX {
            if old_stride == 0 || j % old_stride != 0 {
                us[m] = u0 + half * (1.0 - r.x[j]);
                js[m] = j;
                m += 1;
            }
            j += stride;
        }
        let mut ys = [[0.0f64; N]; NMAX];
        if half > 0.0 {
            h(piece, cp, &us[..m], &mut ys[..m]);
            *evals += m as u64;
        }
        // (an empty piece, whose ends met at a panel end, is zero: nothing evaluated)
        for k in 0..m {
            sc.vals[base + js[k] * N..base + js[k] * N + N].copy_from_slice(&ys[k]);
        }
        sc.level[i] = ku;
    };
    let inner = |sc: &mut Scratch, i: usize, ku: usize| -> [[f64; N]; 3] {
        inner_sums(&sc.vals[i * NMAX * N..(i + 1) * NMAX * N], sc.scale[i], ku)
    };
    refine(sc, tol, fill, inner)
}

/// `∫ g dω_l` for an integrand with the V-groove term: the fast path above when the lobe
/// warp is `TanOverScaleVGroove(α)`, or — for other warps, or where a piece does not reach
/// its tolerance share — the adaptive integrator
/// ([`integrate_over_l`], kinks split there too), the abandoned attempt's evaluations
/// counted.
pub fn integrate_over_l_kinked<const N: usize, F: Fn(&Node) -> [f64; N]>(
    n_dot_v: f64,
    warp: LobeWarp,
    tail: TailCut,
    tol_abs: f64,
    g: F,
) -> Estimate<N> {
    let mut spent = 0;
    if let LobeWarp::TanOverScaleVGroove(alpha) = warp {
        match integrate_over_l_vgroove_cc(n_dot_v, alpha, tail, tol_abs, &g) {
            Ok(e) => return e,
            Err(n) => spent = n,
        }
    }
    let mut e = integrate_over_l(n_dot_v, warp, tol_abs, g);
    e.evals += spent;
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::masking::vgroove;
    use std::f64::consts::PI;

    /// Inside every piece G is one branch: at 200 points strictly inside each piece, for
    /// views and azimuths on both sides of ψ = π/4, G equals the piece's branch (1, gv or
    /// gl) to rounding (1e-13: a few operations on O(1) numbers), and the pieces tile
    /// [0, θmax] in order.
    #[test]
    fn each_piece_is_one_branch() {
        let alpha = 1.0; // u = asinh(tan θh): any positive α gives the same θh ends
        let mut seen = [0usize; 2];
        for &mu in &[1.0, 0.9, 0.6, 0.3, 0.05, 0.001] {
            let sin_v = (1.0f64 - mu * mu).sqrt();
            let tan_v = sin_v / mu;
            for k in 0..=64 {
                let phi = PI * k as f64 / 64.0;
                let cp = phi.cos();
                let s = tan_v * cp;
                let tan_max = tan_theta_h_max(tan_v, cp);
                let pieces: &[Piece] = if s > 1.0 {
                    &[Piece::Flat, Piece::Middle, Piece::Outer]
                } else {
                    &[Piece::Flat, Piece::Outer]
                };
                seen[(s > 1.0) as usize] += 1;
                assert_eq!(pieces.len(), switches(s, tan_max).1 + 1);
                let mut prev = 0.0;
                for &p in pieces {
                    let (u0, u1) = piece_ends(p, s, alpha, tan_max, f64::INFINITY);
                    // the shared form gives the same bits, with a cap inside or not
                    assert_eq!(
                        all_piece_ends(s, alpha, tan_max, f64::INFINITY)[p as usize],
                        (u0, u1)
                    );
                    for cap in [0.3, 1.0, 2.0] {
                        assert_eq!(
                            all_piece_ends(s, alpha, tan_max, cap)[p as usize],
                            piece_ends(p, s, alpha, tan_max, cap)
                        );
                    }
                    assert!(u0 == prev && u1 >= u0, "mu={mu} phi={phi} {p:?}");
                    prev = u1;
                    for m in 1..200 {
                        let u = u0 + (u1 - u0) * m as f64 / 200.0;
                        let t = alpha * u.sinh();
                        let cos_h = 1.0 / (1.0 + t * t).sqrt();
                        let sin_h = t * cos_h;
                        let n = Node::at(mu, sin_v, cp, sin_h, cos_h);
                        if n.n_dot_l <= 0.0 {
                            continue;
                        }
                        let gv = 2.0 * n.n_dot_h * n.n_dot_v / n.v_dot_h;
                        let gl = 2.0 * n.n_dot_h * n.n_dot_l / n.v_dot_h;
                        let branch = match p {
                            Piece::Flat => 1.0,
                            Piece::Middle => gv,
                            Piece::Outer => gl,
                        };
                        let gg = vgroove(n.n_dot_v, n.n_dot_l, n.n_dot_h, n.v_dot_h);
                        assert!(
                            (gg - branch).abs() <= 1e-13,
                            "mu={mu} phi={phi} {p:?} u={u}: G={gg}, branch {branch}"
                        );
                    }
                }
                assert_eq!(prev, (tan_max / alpha).asinh());
            }
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
    }
}
