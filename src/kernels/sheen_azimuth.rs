//! The cloth albedo `∫ D_Charlie(α) V_Ashikhmin (n·l) dω_l` as a 1D integral over the
//! half-vector's polar angle θh, the integral over its azimuth being in closed form.
//!
//! **Reduction.** In half-vector coordinates (`dω_l = 4 (v·h) dω_h`, `dω_h = sin θh dθh dφ`,
//! Walter et al. 2007, "Microfacet Models for Refraction", eq. 14) Charlie's D depends on θh
//! alone (Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF", eq. 2:
//! `D = norm·sin^{1/α}θh`, `norm = (2 + 1/α)/(2π)`) and Ashikhmin's visibility
//! `V = 1/(4(μl + μv − μl μv))` (Neubelt & Pettineo 2013, as used by Filament) on the
//! light's cosine alone, so
//!
//! `E(μv) = ∫₀^{θ0} D(θh) sin θh K(θh) dθh`, `K(θh) = ∫ μl (v·h) / (μl + μv − μl μv) dφ`
//!
//! over the azimuths where `μl > 0`. With `v = (sv, 0, μv)`, the reflected direction's cosine
//! is `m = μl = m0 + m1 cos φ`, `m0 = μv cos 2θh`, `m1 = sv sin 2θh`, and `v·h = (m + μv)/(2u)`
//! (`u = cos θh`), so the integrand is the rational function
//! `g(m)/(2u)`, `g(m) = m(m + μv)/(c m + μv)`, `c = 1 − μv`:
//!
//! `g = m/c − μv²/c² + μv³/(c²(c m + μv))`,
//!
//! whose terms integrate in closed form over the arc `|φ| ≤ φ1`, `cos φ1 = −m0/m1`: with
//! `τ = tan(φ/2)`, `∫ dφ/(a + b cos φ) = ∫ 2 dτ/((a + b) + (a − b) τ²)`, an arctangent for
//! a > b and an inverse hyperbolic tangent for a < b (computed from the exact value
//! `a + b cos φ1 = μv` where it would cancel), with a series where `a ≈ b`. The
//! arc is the whole circle for `θh ≤ θ1 = (π/2 − θv)/2` and empty beyond
//! `θ0 = (π/2 + θv)/2` (where `m` at φ = 0 and φ = π changes sign: `cos(2θh ∓ θv) = 0`).
//!
//! **Rule.** At `θ1` and `θ0` the arc's ends meet and K behaves like `|θh − θ1|^{3/2}` and
//! `(θ0 − θh)^{3/2}`: on `[θ1, θ0]` two panels with `θh = θ1 + w²` and `θh = θ0 − w²` (split
//! at the midpoint) make the integrand smooth in w; on `[0, θ1]`, where K is analytic,
//! `θh = θ1 w²` for the factor `sin^{1/α}θh`, not analytic at 0 unless 1/α is an even integer.
//! Each panel is integrated by nested Clenshaw–Curtis ([`cc1d`](crate::quadrature::cc1d): 9 … 129 nodes,
//! its estimate) to a third of the tolerance. Narrow lobes (α < [`CUT_BELOW_ALPHA`])
//! concentrate in a layer below θ0 (or at θh = π/2 for grazing views): everything below
//! `θ_lo`, where `norm·sin^{1/α+1}θh·2π` times the interval is below `tol/1000` (`K ≤ 2π`:
//! `μl/(μl + μv − μl μv) ≤ 1`, `v·h ≤ 1`), is cut and that bound added to the estimate.
//! Wider lobes take the whole panels, whose nodes then depend on the view alone: a table
//! column (one view, every roughness) computes each node's K once ([`AzimuthCache`]) and
//! each texel costs an `exp` per node.
//!
//! **Cost** (examples/cloth_azimuth_cost.rs and filament-dfg, 2026-11-30): ~110 ns per node where K is
//! computed (`atan`, a `sin_cos`, a `ln`, an `exp`, three square roots), ~60 nodes per texel
//! over a 128² table; the cloth channel of filament-dfg at 128² takes ~15 ms of one core's
//! time. Against the adaptive
//! half-vector integrator at tol/100 over every texel of a 128² table: at most 3e-9 apart,
//! no texel declined.
//!
//! The closed form divides by `c²`: it declines (`Err(0)`) for `μv > 0.999`, where it would
//! lose more than ~1e-10 to rounding, and leaves those views to the generic path.
//!
//! Determinism: fixed nodes and summation order; what a column shares is a pure function of
//! the view and the panel, so a texel gets the same bits alone or in its column.

use crate::quadrature::adaptive::Estimate;
use crate::quadrature::cc1d::{nested_cc_indexed, FIRST_LEVEL};
use crate::quadrature::clenshaw_curtis::MAX_LEVEL;
use std::f64::consts::{FRAC_PI_2, PI};

/// What a table column (one view μ, every roughness) shares: the view cosine, the θh
/// kernel's node data ([`AzimuthCache`]) and the light-cosine kernel's
/// ([`PolarCache`](super::sheen_polar::PolarCache)), filled as its texels ask for them. Each texel's result
/// is the same bits with or without it.
pub struct View {
    /// The view cosine, at most 1.
    mu: f64,
    azimuth: std::cell::RefCell<AzimuthCache>,
    polar: std::cell::RefCell<super::sheen_polar::PolarCache>,
}

impl View {
    /// For view cosine `mu` (values above 1 are taken as 1).
    pub fn new(mu: f64) -> View {
        View {
            mu: mu.min(1.0),
            azimuth: Default::default(),
            polar: Default::default(),
        }
    }

    /// The view cosine (at most 1).
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The θh cloth kernel's node data for this view.
    pub fn azimuth(&self) -> &std::cell::RefCell<AzimuthCache> {
        &self.azimuth
    }

    /// The light-cosine sheen kernel's shared data for this view
    /// ([`sheen_polar`](super::sheen_polar)).
    pub fn polar(&self) -> &std::cell::RefCell<super::sheen_polar::PolarCache> {
        &self.polar
    }
}

/// Views closer to the normal than this (`1 − μv`) are declined: the partial fractions
/// cancel to ~`ε/c²`.
const MIN_C: f64 = 1e-3;

/// What this path does, for documentation and the benchmarks.
pub const METHOD: &str = "cloth as a 1D integral over theta_h (src/kernels/sheen_azimuth.rs): the azimuthal integral of V mu_l (v.h) in closed form (partial fractions), nested Clenshaw-Curtis on three panels with square-root warps at the arc's end points, cut below where the lobe is under tol/1000";

/// The view's constants for K(θh) (not [`View`], the column-shared view data of the table
/// code).
struct Azimuth {
    mu_v: f64,
    sv: f64,
    c: f64,
}

impl Azimuth {
    /// `K(θh)` of the module doc, `(1/u) ∫₀^{φ1} g(m(φ)) dφ`, from `sin θh` and `u = cos θh`.
    fn azimuthal(&self, sin_h: f64, u: f64) -> f64 {
        let (mu_v, c) = (self.mu_v, self.c);
        let m0 = mu_v * (u - sin_h) * (u + sin_h);
        let m1 = self.sv * 2.0 * sin_h * u;
        let sp = m1 + m0;
        if sp <= 0.0 {
            return 0.0;
        }
        let a = c * m0 + mu_v;
        let b = c * m1;
        let (phi1, int_m, int_inv) = if m0 >= m1 {
            // the whole circle: a − b = c·m(π) + μv > 0
            (PI, PI * m0, PI / ((a - b) * (a + b)).sqrt())
        } else {
            let sm = m1 - m0;
            let root = (sp * sm).sqrt(); // m1 sin φ1
            let tau2 = sp / sm; // tan²(φ1/2)
            let tau = tau2.sqrt();
            let phi1 = 2.0 * tau.atan();
            let y = (a - b) / (a + b) * tau2;
            let pre = 2.0 * tau / (a + b);
            // ∫₀^{φ1} dφ/(a + b cos φ) = pre·S(y), S(y) = atan(√y)/√y (atanh(√−y)/√−y)
            let s = if y.abs() < 1e-3 {
                1.0 - y
                    * (1.0 / 3.0 - y * (1.0 / 5.0 - y * (1.0 / 7.0 - y * (1.0 / 9.0 - y / 11.0))))
            } else if y > 0.0 {
                let r = y.sqrt();
                r.atan() / r
            } else {
                // x < 1: a + b cos φ ≥ a + b cos φ1 = μv > 0 on the arc
                let x = (-y).sqrt();
                let atanh = if x <= 0.5 {
                    0.5 * (2.0 * x / (1.0 - x)).ln_1p()
                } else {
                    // (1 + x)/(1 − x) = (P + Qτ)²(1 + cos φ1)/(2μv), exact where 1 − x cancels
                    let (p, q) = ((a + b).sqrt(), (b - a).sqrt());
                    let t = p + q * tau;
                    0.5 * (t * t * sm / (2.0 * mu_v * m1)).ln()
                };
                atanh / x
            };
            (phi1, m0 * phi1 + root, pre * s)
        };
        let g = (int_m - mu_v * mu_v / c * phi1 + mu_v * mu_v * mu_v / c * int_inv) / c;
        g / u
    }
}

/// Lobes narrower than this (α < 1/16) are cut below `θ_lo` (module doc): their integrand
/// lives in a layer much thinner than the panel. Wider lobes are integrated over whole
/// panels, whose nodes then depend on the view alone and are shared along a column
/// ([`AzimuthCache`]).
pub const CUT_BELOW_ALPHA: f64 = 1.0 / 16.0;

const NMAX: usize = (1 << MAX_LEVEL) + 1;

/// One panel's per-node data, valid for the panel `key` (its bounds in its variable):
/// `ln sin θh` and `(dθh/dw)·K(θh)` at the Clenshaw–Curtis nodes computed so far.
struct PanelNodes {
    key: (f64, f64),
    filled: [bool; NMAX],
    ln_sin: [f64; NMAX],
    jk: [f64; NMAX],
}

/// What the texels of one view share: the panels' node data (which depend on the view and
/// the panel's bounds, not on α). A texel's value is the same, bit for bit, whether its
/// nodes come from here or are computed afresh.
#[derive(Default)]
pub struct AzimuthCache {
    mu_v: f64,
    panels: Option<Box<[PanelNodes; 3]>>,
}

impl AzimuthCache {
    /// The panels for view `mu_v`, emptied if they were for another view.
    fn for_view(&mut self, mu_v: f64) -> &mut [PanelNodes; 3] {
        let mut same = self.mu_v.to_bits() == mu_v.to_bits();
        self.mu_v = mu_v;
        let panels = self.panels.get_or_insert_with(|| {
            // a dropped cache's storage if this thread has one (emptied below), else fresh
            same = false;
            SPARE.with(|s| s.borrow_mut().pop()).unwrap_or_else(|| {
                let fresh = || PanelNodes {
                    key: (f64::NAN, f64::NAN),
                    filled: [false; NMAX],
                    ln_sin: [0.0; NMAX],
                    jk: [0.0; NMAX],
                };
                Box::new([fresh(), fresh(), fresh()])
            })
        });
        if !same {
            for p in panels.iter_mut() {
                p.key = (f64::NAN, f64::NAN);
            }
        }
        panels
    }
}

thread_local! {
    /// Panel storage of this thread's dropped caches, for its next ones: a table's rows
    /// make a cache per texel, and allocating and zeroing 6.6 KB for each was ~2% of a
    /// 128² filament-dfg bake's instructions. A reused one is emptied (its keys reset), so
    /// a texel's bits do not depend on it.
    static SPARE: std::cell::RefCell<Vec<Box<[PanelNodes; 3]>>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// Most panel sets a thread keeps for reuse.
const SPARE_MAX: usize = 4;

impl Drop for AzimuthCache {
    fn drop(&mut self) {
        if let Some(p) = self.panels.take() {
            // (during thread teardown the pool may be gone: then the storage is just freed)
            let _ = SPARE.try_with(|s| {
                if let Ok(mut s) = s.try_borrow_mut() {
                    if s.len() < SPARE_MAX {
                        s.push(p);
                    }
                }
            });
        }
    }
}

/// How a panel's variable w maps to θh.
#[derive(Clone, Copy)]
enum Warp {
    /// θh = s·w² (from 0)
    Square(f64),
    /// θh = w
    Linear,
    /// θh = θ1 + w²
    From(f64),
    /// θh = θ0 − w²
    To(f64),
}

impl Warp {
    /// θh and dθh/dw at w.
    fn at(self, w: f64) -> (f64, f64) {
        match self {
            Warp::Square(s) => (s * w * w, 2.0 * s * w),
            Warp::Linear => (w, 1.0),
            Warp::From(t) => (t + w * w, 2.0 * w),
            Warp::To(t) => (t - w * w, 2.0 * w),
        }
    }
}

/// The cloth albedo at view cosine `mu_v` ∈ (0, 0.999] and Charlie α > 0 to absolute
/// tolerance `tol` (estimated, module docs); `Err(evaluations spent)` where a panel does
/// not converge within 129 nodes, or for views it declines. A pure function of its
/// arguments.
pub fn charlie_sheen_azimuth(mu_v: f64, alpha: f64, tol: f64) -> Result<Estimate<1>, u64> {
    charlie_sheen_azimuth_shared(mu_v, alpha, tol, &mut AzimuthCache::default())
}

/// [`charlie_sheen_azimuth`] with the view's node data kept in `cache` for the next texel
/// of the same view (the same bits as without). Evaluations count the integrand's values at
/// the nodes, whether their azimuthal integral was computed or found in the cache (a found
/// one costs an `exp` and two products instead of ~100 ns).
pub fn charlie_sheen_azimuth_shared(
    mu_v: f64,
    alpha: f64,
    tol: f64,
    cache: &mut AzimuthCache,
) -> Result<Estimate<1>, u64> {
    let c = 1.0 - mu_v;
    if !(mu_v > 0.0 && c >= MIN_C && alpha > 0.0 && alpha.is_finite() && tol > 0.0) {
        return Err(0);
    }
    let view = Azimuth {
        mu_v,
        sv: ((1.0 - mu_v) * (1.0 + mu_v)).sqrt(),
        c,
    };
    let theta_v = mu_v.acos();
    let theta0 = 0.5 * (FRAC_PI_2 + theta_v);
    let theta1 = 0.5 * (FRAC_PI_2 - theta_v);
    let norm = (2.0 + 1.0 / alpha) / (2.0 * PI);
    let power = 1.0 / alpha + 1.0; // sin^{1/α}θh·sin θh
                                   // θ_lo: ∫₀^{θ_lo} ≤ (π/2)·2π·norm·sin^{power}θ_lo = eps_t
    let eps_t = 1e-3 * tol;
    let ln_s_lo = (eps_t / (PI * PI * norm)).ln() / power;
    let (mut theta_lo, mut tail) = (0.0, 0.0);
    if alpha < CUT_BELOW_ALPHA && ln_s_lo < 0.0 {
        let s_lo = ln_s_lo.exp();
        if s_lo >= theta0.sin() {
            return Ok(Estimate {
                value: [0.0],
                error: [eps_t],
                evals: 0,
            });
        }
        theta_lo = s_lo.asin();
        tail = eps_t;
    }
    let theta_m = 0.5 * (theta0 + theta1);
    // the panels: [0, θ1] (the whole circle), [θ1, θm] in θ = θ1 + w², [θm, θ0] in
    // θ = θ0 − w², each cut at θ_lo
    let mut panels: [Option<(f64, f64, Warp)>; 3] = [None; 3];
    if theta1 > theta_lo {
        panels[0] = Some(if theta_lo == 0.0 {
            (0.0, 1.0, Warp::Square(theta1))
        } else {
            (theta_lo, theta1, Warp::Linear)
        });
    }
    if theta_m > theta_lo {
        let w0 = (theta_lo - theta1).max(0.0).sqrt();
        panels[1] = Some((w0, (theta_m - theta1).sqrt(), Warp::From(theta1)));
    }
    let w1 = (theta0 - theta_m.max(theta_lo)).sqrt();
    panels[2] = Some((0.0, w1, Warp::To(theta0)));

    let share = (tol - tail) / 3.0;
    let mut total = Estimate {
        value: [0.0],
        error: [tail],
        evals: 0,
    };
    let nodes = cache.for_view(mu_v);
    for (p, panel) in nodes.iter_mut().zip(panels) {
        let Some((lo, hi, warp)) = panel else {
            continue;
        };
        if p.key.0.to_bits() != lo.to_bits() || p.key.1.to_bits() != hi.to_bits() {
            p.key = (lo, hi);
            p.filled = [false; NMAX];
        }
        let mut g = |i: usize, w: f64| {
            if !p.filled[i] {
                let (theta, jac) = warp.at(w);
                let (sin_h, u) = theta.sin_cos();
                p.ln_sin[i] = sin_h.ln();
                p.jk[i] = jac * view.azimuthal(sin_h, u);
                p.filled[i] = true;
            }
            [norm * (power * p.ln_sin[i]).exp() * p.jk[i]]
        };
        match nested_cc_indexed(&mut g, lo, hi, share, FIRST_LEVEL, MAX_LEVEL) {
            Ok(e) => {
                total.value[0] += e.value[0];
                total.error[0] += e.error[0];
                total.evals += e.evals;
            }
            Err(n) => return Err(total.evals + n),
        }
    }
    if !(total.value[0].is_finite() && total.error[0] <= tol) {
        return Err(total.evals);
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A texel's value and estimate are the same bits whether the view's node data come from
    /// a cache filled by other roughnesses (in any order) or are computed afresh.
    #[test]
    fn shared_nodes_give_the_same_bits() {
        let alphas = [1.0, 0.07, 0.3, 0.0625, 0.01, 1e-4, 0.5, 0.0625, 0.2];
        for mu in [0.004, 0.3, 0.9] {
            let mut cache = AzimuthCache::default();
            for &alpha in &alphas {
                let a = charlie_sheen_azimuth_shared(mu, alpha, 1e-7, &mut cache).unwrap();
                let b = charlie_sheen_azimuth(mu, alpha, 1e-7).unwrap();
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
            }
            // a cache left by another view is not used for this one
            let b = charlie_sheen_azimuth(0.5, 0.3, 1e-7).unwrap();
            let a = charlie_sheen_azimuth_shared(0.5, 0.3, 1e-7, &mut cache).unwrap();
            assert_eq!(a.value[0].to_bits(), b.value[0].to_bits());
        }
    }

    /// A cache whose storage a dropped one left on this thread gives the same bits as one
    /// built fresh (each texel computed alone on a new thread, whose pool is empty).
    #[test]
    fn reused_storage_gives_the_same_bits() {
        let texels = [
            (0.004, 0.3),
            (0.3, 0.07),
            (0.3, 1e-4),
            (0.9, 1.0),
            (0.5, 0.0625),
        ];
        for _ in 0..3 {
            for &(mu, alpha) in &texels {
                let here = charlie_sheen_azimuth(mu, alpha, 1e-7).unwrap();
                let fresh = std::thread::spawn(move || {
                    assert!(SPARE.with(|s| s.borrow().is_empty()));
                    charlie_sheen_azimuth(mu, alpha, 1e-7).unwrap()
                })
                .join()
                .unwrap();
                assert_eq!(here.value[0].to_bits(), fresh.value[0].to_bits());
                assert_eq!(here.error[0].to_bits(), fresh.error[0].to_bits());
            }
        }
        assert!(SPARE.with(|s| !s.borrow().is_empty()), "storage was reused");
    }

    /// K(θh) against a brute-force azimuthal integral (composite Gauss–Legendre over the
    /// arc, split at φ1, of the integrand `μl (v·h)/(μl + μv − μl μv)` written directly):
    /// the closed form's terms are O(μv²/c²) ≤ 1e6 at the largest view tried, so rounding
    /// leaves ~1e-10 of K's scale (≤ 2π).
    #[test]
    fn azimuthal_integral_matches_quadrature() {
        let (gx, gw) = crate::quadrature::gauss::gauss_legendre(40);
        for &mu_v in &[0.001, 0.004, 0.03, 0.2, 0.5, 0.77, 0.95, 0.999] {
            let view = Azimuth {
                mu_v,
                sv: ((1.0 - mu_v) * (1.0 + mu_v)).sqrt(),
                c: 1.0 - mu_v,
            };
            for i in 1..200 {
                let theta = FRAC_PI_2 * i as f64 / 200.0;
                let (st, u) = theta.sin_cos();
                let integrand = |phi: f64| {
                    let w = view.sv * st * phi.cos() + mu_v * u;
                    let ml = 2.0 * w * u - mu_v;
                    if ml <= 0.0 {
                        0.0
                    } else {
                        ml * w / (ml + mu_v - ml * mu_v)
                    }
                };
                // the arc's end, where the integrand's derivative jumps
                let (m0, m1) = (mu_v * (2.0 * theta).cos(), view.sv * (2.0 * theta).sin());
                let phi1 = if m0 >= m1 {
                    PI
                } else if m0 + m1 <= 0.0 {
                    0.0
                } else {
                    (-m0 / m1).acos()
                };
                let mut brute = 0.0;
                for (lo, hi) in [(0.0, phi1), (phi1, PI)] {
                    let panels = 64;
                    let h = (hi - lo) / panels as f64;
                    for p in 0..panels {
                        for (x, w) in gx.iter().zip(&gw) {
                            let phi = lo + h * (p as f64 + 0.5 * (1.0 + x));
                            brute += 0.5 * h * w * integrand(phi);
                        }
                    }
                }
                brute *= 2.0;
                let k = view.azimuthal(st, u);
                assert!(
                    (k - brute).abs() <= 1e-9 * (1.0 + brute),
                    "mu_v {mu_v} theta {theta}: closed {k} brute {brute}"
                );
            }
        }
    }
}
