//! Specialised kernels for the split-sum tables: the GGX split sum (Smith height-correlated
//! or separable masking, F = 1, Schlick weight) and the Charlie/Ashikhmin cloth albedo.
//!
//! They compute the same integrals, in the same coordinates and with the same nested
//! Clenshaw–Curtis tensor rule and error estimate, as the generic fast path
//! ([`tensor`](super::tensor)), but with the integrand written out for the one model instead
//! of assembled from [`Node`](super::hemisphere::Node), NDF, masking and Fresnel enums, and with
//! everything that depends on the view alone shared by all roughnesses of a table column
//! ([`Column`]). A texel whose estimate does not reach the tolerance returns `Err`; the
//! caller then uses the generic path (which may itself fall back to the adaptive
//! integrator), so every result keeps an over-estimating error estimate.
//!
//! **GGX in the lobe warp.** With `tan θh = α sinh u` (the warp of
//! [`hemisphere`](super::hemisphere)), the GGX measure is closed-form:
//! `D(h)(n·h) dω_h = sinh u / (π cosh³u) du dφ` (GGX: Walter et al. 2007, eq. 33; the
//! substitution is ours: `α² + tan²θh = α² cosh²u`, `dθh = cos²θh α cosh u du`), so D
//! itself is never evaluated. With `v = (sin θv, 0, μ)`, `r = √(1 + tan²θh)` and
//! `q = μ + sin θv cos φ tan θh = (v·h)/cos θh`:
//! `v·h = q/r`, `n·l = 2q/r² − μ`, and the integrand of `∫ f (n·l) dω_l` with
//! `dω_l = 4(v·h) dω_h` (Walter et al. 2007, eq. 14) is
//!
//! `f (n·l) dω_l = D G (v·h)/μ dω_h = sinh u/(π cosh³u) · q · G/μ du dφ`,
//!
//! where, with `a_v = √(μ²(1 − α²) + α²)` and `b_l = √((n·l)²(1 − α²) + α²)`
//! (Heitz 2014, "Understanding the Masking-Shadowing Function", eqs. 86, 98, 99, written in
//! cosines as in Filament's documentation, "Geometric shadowing"):
//! * height-correlated: `G/μ = 2 (n·l) / ((n·l) a_v + μ b_l)`,
//! * separable: `G/μ = 2/(μ + a_v) · 2 (n·l)/((n·l) + b_l)`,
//!
//! both finite as μ → 0. Schlick's weight is `Fc = (1 − v·h)⁵` (Schlick 1994).
//!
//! **Cloth.** Charlie `D = (2 + 1/α) sin^{1/α}θh / (2π)` (Estevez & Kulla 2017) with
//! Ashikhmin's visibility `V = 1/(4(n·l + n·v − (n·l)(n·v)))` (Neubelt & Pettineo 2013):
//! `f (n·l) dω_l = D (n·l)(v·h)/(n·l + μ − (n·l)μ) dω_h`, in the generic path's two sheen
//! warps (`cos θh = √α sinh y` for α < 1/16, `θh = θmax w²` with a horizon layer beyond).
//!
//! Determinism: fixed nodes, fixed summation order, per-thread scratch whose every entry
//! read was written in the same call.

// Channel loops index several same-length arrays at once; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

use super::adaptive::Estimate;
use super::hemisphere::tan_theta_h_max;
use super::tensor::{rules as cc_rules, PhiWarp, MAX_LEVEL};
use std::cell::{OnceCell, RefCell};
use std::f64::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4};

const NMAX: usize = (1 << MAX_LEVEL) + 1;

/// fdlibm's split of ln 2 (e_exp.c: ln2HI, ln2LO): the high part has trailing zero bits, so
/// n·LN2_HI is exact for the |n| < 2^11 used here.
const LN2_HI: f64 = 6.931_471_803_691_238e-1;
const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;

/// What the kernels do, for the sidecar's `quadrature.method`.
pub const METHOD: &str = "specialised kernels for the GGX split sum (Smith height-correlated or separable masking) and the Charlie/Ashikhmin cloth channel (src/integrate/dfg_kernel.rs): the nested Clenshaw-Curtis tensor rule of the generic fast path (same coordinates, warps, levels and error estimate) with the integrand in closed form (GGX: D (n.h) dw_h = sinh u/(pi cosh^3 u) du dphi, tan theta_h = alpha sinh u) and the per-view setup shared by a table column; a texel whose estimate does not reach the tolerance goes to the generic path";

/// One view's data for the kernels that share it along a table column — the φ-node setup
/// ([`Column`]), the half-vector cloth kernel's node data ([`SheenCache`]), the wide
/// cloth lobes' ([`WideCache`](super::sheen_wide::WideCache)) and the θh cloth kernel's
/// ([`AzimuthCache`](super::sheen_azimuth::AzimuthCache)) — built on first use and then
/// shared by every texel at that view. The kernels tried first (the polar split sum, the
/// θh cloth kernel) need no column and no
/// half-vector cache, and building them would cost more than some of those texels (that
/// cache alone zeroes 266 KB: at 512², one per column was ~1% of the bake in page faults).
/// The results are the same bits with or without them.
pub struct View {
    /// The view cosine, at most 1 (as [`Column::mu`] has it).
    mu: f64,
    col: OnceCell<Column>,
    cache: OnceCell<RefCell<SheenCache>>,
    wide: RefCell<super::sheen_wide::WideCache>,
    azimuth: RefCell<super::sheen_azimuth::AzimuthCache>,
}

impl View {
    /// For view cosine `mu` (values above 1 are taken as 1).
    pub fn new(mu: f64) -> View {
        View {
            mu: mu.min(1.0),
            col: OnceCell::new(),
            cache: OnceCell::new(),
            wide: RefCell::default(),
            azimuth: RefCell::default(),
        }
    }

    /// The view cosine (at most 1).
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The view's [`Column`], built on the first call.
    pub fn column(&self) -> &Column {
        self.col.get_or_init(|| Column::new(self.mu))
    }

    /// The half-vector cloth kernel's node data for this view, created (empty) on the first
    /// call.
    pub fn cache(&self) -> &RefCell<SheenCache> {
        self.cache.get_or_init(Default::default)
    }

    /// The wide cloth lobes' node data for this view (filled as texels ask for it).
    pub fn wide(&self) -> &RefCell<super::sheen_wide::WideCache> {
        &self.wide
    }

    /// The θh cloth kernel's node data for this view (filled as texels ask for it).
    pub fn azimuth(&self) -> &RefCell<super::sheen_azimuth::AzimuthCache> {
        &self.azimuth
    }
}

/// Everything that depends on the view μ alone, at the finest φ level: shared by every
/// roughness of a table column.
#[derive(Clone, Debug)]
pub struct Column {
    mu: f64,
    sin_v: f64,
    /// cos φ at each φ node (φ = π/2 + c sinh(S x_i), c = min(cot θv, 1)).
    cos_phi: Vec<f64>,
    /// dφ/dx at each node, doubled for the mirror half φ ∈ [π, 2π].
    dphi: Vec<f64>,
    /// tan θmax(φ), the exact horizon.
    tmax: Vec<f64>,
}

impl Column {
    /// The φ nodes of [`tensor`](super::tensor)'s fast path for view cosine `mu` ∈ (0, 1].
    pub fn new(mu: f64) -> Column {
        let r = cc_rules();
        let PhiWarp {
            mu_v,
            sin_v,
            tan_v,
            c,
            big_s,
        } = PhiWarp::new(mu);
        let mut cos_phi = vec![0.0; NMAX];
        let mut dphi = vec![0.0; NMAX];
        let mut tmax = vec![0.0; NMAX];
        for i in 0..NMAX {
            let s = big_s * r.x[i];
            let phi = FRAC_PI_2 + c * s.sinh();
            cos_phi[i] = phi.cos();
            dphi[i] = 2.0 * c * s.cosh() * big_s;
            tmax[i] = tan_theta_h_max(tan_v, cos_phi[i]);
        }
        Column {
            mu: mu_v,
            sin_v,
            cos_phi,
            dphi,
            tmax,
        }
    }

    /// The view cosine.
    pub fn mu(&self) -> f64 {
        self.mu
    }
}

/// Which Smith masking term the GGX kernel uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Smith {
    HeightCorrelated,
    Separable,
}

/// Fills the integrand values of one φ node for the new u nodes of a level (indices
/// `j = 0, stride, 2·stride, …` that are not multiples of `old_stride`; `old_stride = 0`:
/// all), `N` channels interleaved in `out`; returns the node's inner half-length × dφ/dx.
trait Fill<const N: usize> {
    fn fill(
        &self,
        i: usize,
        stride: usize,
        old_stride: usize,
        out: &mut [f64],
        tmp: &mut Tmp,
    ) -> f64;
}

/// Per-call work arrays of a fill (one set per texel, so that no fill initializes or
/// copies arrays of its own).
struct Tmp {
    xs: [f64; NMAX],
    js: [usize; NMAX],
    v0: [f64; NMAX],
    v1: [f64; NMAX],
}

struct GgxFill<'a> {
    col: &'a Column,
    alpha: f64,
    a_v: f64,
    /// 1/(μ + a_v) for the separable form.
    inv_g1v: f64,
    one_m_a2: f64,
    smith: Smith,
}

impl GgxFill<'_> {
    /// The two channels at inner nodes `xs` (rule abscissae in [−1, 1]) of one φ node:
    /// straight-line arithmetic on fixed-size arrays (no calls, no branches) so that the
    /// compiler can vectorize it.
    #[inline(always)]
    fn batch<const HC: bool>(
        &self,
        svcp: f64,
        half: f64,
        xs: &[f64; NMAX],
        m: usize,
        v0: &mut [f64; NMAX],
        v1: &mut [f64; NMAX],
    ) {
        let (mu, alpha, a2c, a_v, inv_g1v) = (
            self.col.mu,
            self.alpha,
            self.one_m_a2,
            self.a_v,
            self.inv_g1v,
        );
        let a2 = alpha * alpha;
        for k in 0..m {
            // Everything below is the formula of the module docs multiplied through by
            // powers of e = e^u (so that 1/e is never formed): with E = e² − 1,
            // T = αE = 2e·tan θh, R = 4e² + T² = 4e²r², Q = 2eμ + sin θv cos φ·T = 2e·q and
            // M = 4eQ − μR = 4e²r²·(n·l): v·h = Q/√R, and
            // sinh u·q/cosh³u = 2eEQ/(e² + 1)³; in G/μ the factors 4e²r² cancel, with
            // B = √(M²(1 − α²) + α²R²) = 4e²r²·b_l.
            let u = half * (1.0 - xs[k]);
            let e = exp_poly(u);
            let e2 = e * e;
            let big_e = e2 - 1.0;
            let t = alpha * big_e;
            let big_r = 4.0 * e2 + t * t;
            let q = 2.0 * e * mu + svcp * t;
            let nl = (4.0 * e * q - mu * big_r).max(0.0);
            let vh = q / big_r.sqrt();
            let b_l = (nl * nl * a2c + a2 * big_r * big_r).sqrt();
            let p = e2 + 1.0;
            let w = 2.0 * FRAC_1_PI * e * big_e * q;
            let f = if HC {
                2.0 * w * nl / (p * p * p * (nl * a_v + mu * b_l))
            } else {
                4.0 * w * nl * inv_g1v / (p * p * p * (nl + b_l))
            };
            let x = (1.0 - vh).max(0.0);
            let x2 = x * x;
            let fc = x2 * x2 * x;
            v0[k] = f - f * fc;
            v1[k] = f * fc;
        }
    }
}

impl Fill<2> for GgxFill<'_> {
    #[inline]
    fn fill(
        &self,
        i: usize,
        stride: usize,
        old_stride: usize,
        out: &mut [f64],
        tmp: &mut Tmp,
    ) -> f64 {
        let r = cc_rules();
        let col = self.col;
        let svcp = col.sin_v * col.cos_phi[i];
        let umax = (col.tmax[i] / self.alpha).asinh();
        let half = 0.5 * umax;
        let m = new_nodes(&r.x, stride, old_stride, tmp);
        let Tmp { xs, js, v0, v1 } = tmp;
        match self.smith {
            Smith::HeightCorrelated => self.batch::<true>(svcp, half, xs, m, v0, v1),
            Smith::Separable => self.batch::<false>(svcp, half, xs, m, v0, v1),
        }
        for k in 0..m {
            out[js[k] * 2] = v0[k];
            out[js[k] * 2 + 1] = v1[k];
        }
        half * col.dphi[i]
    }
}

/// The inner nodes a fill must compute: indices `0, stride, 2·stride, …` that are not
/// multiples of `old_stride` (0: all), with their abscissae; (abscissae, indices, count).
#[inline(always)]
fn new_nodes(x: &[f64; NMAX], stride: usize, old_stride: usize, tmp: &mut Tmp) -> usize {
    let (xs, js) = (&mut tmp.xs, &mut tmp.js);
    let mut m = 0;
    // strides are powers of two
    let mask = old_stride.wrapping_sub(1);
    let mut j = 0;
    while j < NMAX {
        if old_stride == 0 || j & mask != 0 {
            xs[m] = x[j];
            js[m] = j;
            m += 1;
        }
        j += stride;
    }
    m
}

/// e^x for |x| ≤ 700 by Cody–Waite reduction `x = n ln 2 + r`, |r| ≤ ln2/2, and the
/// degree-12 Taylor polynomial of e^r (Estrin's scheme) (truncation `|r|^13/13! < 2e-16` relative), scaled by
/// 2^n through the exponent bits: plain arithmetic, so loops that call it vectorize (libm's
/// exp is a call). Within a few ulp of `f64::exp` (unit test below). The reduction
/// constants are fdlibm's split of ln 2 (high part with trailing zero bits, so `n·LN2_HI`
/// is exact).
#[inline(always)]
pub fn exp_poly(x: f64) -> f64 {
    const LOG2E: f64 = std::f64::consts::LOG2_E;
    // round-to-nearest by the 1.5·2^52 trick: the low mantissa bits of `big` hold n
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let big = x * LOG2E + SHIFT;
    let n = big - SHIFT;
    let r = (x - n * LN2_HI) - n * LN2_LO;
    // Σ r^k/k!, k = 0..12, by Estrin's scheme (short dependency chains)
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let a01 = 1.0 + r;
    let a23 = 0.5 + r * (1.0 / 6.0);
    let a45 = 1.0 / 24.0 + r * (1.0 / 120.0);
    let a67 = 1.0 / 720.0 + r * (1.0 / 5_040.0);
    let a89 = 1.0 / 40_320.0 + r * (1.0 / 362_880.0);
    let a1011 = 1.0 / 3_628_800.0 + r * (1.0 / 39_916_800.0);
    let a12 = 1.0 / 479_001_600.0;
    let b0 = a01 + r2 * a23;
    let b1 = a45 + r2 * a67;
    let b2 = a89 + r2 * a1011;
    let p = (b0 + r4 * b1) + r8 * (b2 + r4 * a12);
    // 2^n: (n + 1023) << 52, with n from big's low bits (two's complement, |n| < 1023)
    let scale = f64::from_bits((big.to_bits() << 52).wrapping_add(1023u64 << 52));
    p * scale
}

/// The GGX split sum `[∫(1 − Fc) f cos, ∫ Fc f cos]` (F = 1) at the column's view and
/// roughness `alpha`, to absolute tolerance `tol` per channel (estimated); `Err(evaluations
/// spent)` where the nested rules do not reach it within the generic fast path's node budget (the estimate
/// is that path's: see [`tensor`](super::tensor)).
pub fn ggx_split_sum(col: &Column, alpha: f64, smith: Smith, tol: f64) -> Result<Estimate<2>, u64> {
    if !(col.mu > 0.0 && alpha > 0.0) {
        return Err(0);
    }
    // the products of powers of e^u in the kernel (up to ~e^{9u} α³) must stay finite:
    // u ≤ asinh(tmax/α) ≤ 60 (α = 1e-6 at μ = 1e-4 needs u ≈ 24)
    if (col.tmax.iter().cloned().fold(0.0, f64::max) / alpha).asinh() > 60.0 {
        return Err(0);
    }
    let mu = col.mu;
    let a2 = alpha * alpha;
    let a_v = (mu * mu * (1.0 - a2) + a2).sqrt();
    let k = GgxFill {
        col,
        alpha,
        a_v,
        inv_g1v: 1.0 / (mu + a_v),
        one_m_a2: 1.0 - a2,
        smith,
    };
    SCRATCH.with(|s| run::<2, _>(&mut s.borrow_mut(), &k, tol))
}

/// The inner warp of the cloth kernel (as [`InnerWarp`](super::tensor::InnerWarp) for
/// Charlie).
#[derive(Clone, Copy)]
enum SheenWarp {
    /// `cos θh = β sinh y`, β = √α (α < 1/16).
    Cos(f64),
    /// `θh = θmax w²`, with the horizon layer `w = 1 − d sinh z`.
    Sqrt,
}

struct SheenFill<'a> {
    col: &'a Column,
    /// the α-independent node data of the wide-lobe warp, shared by a column's texels
    cache: Option<&'a RefCell<SheenCache>>,
    norm: f64,
    /// 1/(2α): D = norm · (sin²θh)^k.
    k: f64,
    warp: SheenWarp,
}

impl SheenFill<'_> {
    /// `D (n·l)(v·h)/(n·l + μ − (n·l)μ)` for a half vector at (θh, φ) given by sin θh,
    /// cos θh and sin²θh; 0 beyond the horizon (n·l ≤ 0, which includes v·h ≤ 0 since
    /// n·l = 2(v·h)cos θh − μ). Branch-free, for vectorized batches.
    #[inline(always)]
    fn value(&self, mu: f64, svcp: f64, sin_h: f64, cos_h: f64, sin2_h: f64) -> f64 {
        let vh = svcp * sin_h + mu * cos_h;
        let nl = (2.0 * vh * cos_h - mu).max(0.0);
        // D = norm·(sin²θh)^k; e^x below −700 is 0 to f64 precision for our purposes
        // (< 1e-304) and keeps exp_poly in range
        let d = self.norm * exp_poly((self.k * ln_poly(sin2_h)).max(-700.0));
        d * nl * vh / (nl + mu - nl * mu)
    }
}

impl Fill<1> for SheenFill<'_> {
    #[inline]
    fn fill(
        &self,
        i: usize,
        stride: usize,
        old_stride: usize,
        out: &mut [f64],
        tmp: &mut Tmp,
    ) -> f64 {
        let r = cc_rules();
        let col = self.col;
        let mu = col.mu;
        let svcp = col.sin_v * col.cos_phi[i];
        let tmax = col.tmax[i];
        let m = new_nodes(&r.x, stride, old_stride, tmp);
        let Tmp { xs, js, v0: v, .. } = tmp;
        let scale = match self.warp {
            SheenWarp::Cos(beta) => {
                let cmin = 1.0 / (1.0 + tmax * tmax).sqrt();
                let (y0, y1) = ((cmin / beta).asinh(), (1.0 / beta).asinh());
                let half = 0.5 * (y1 - y0);
                for k in 0..m {
                    let y = y0 + half * (1.0 - xs[k]);
                    let e = exp_poly(y);
                    let ei = 1.0 / e;
                    let cos_h = (beta * 0.5 * (e - ei)).min(1.0);
                    let sin2_h = (1.0 - cos_h) * (1.0 + cos_h);
                    // sin θh dθh = β cosh y dy
                    v[k] = self.value(mu, svcp, sin2_h.sqrt(), cos_h, sin2_h)
                        * (beta * 0.5 * (e + ei));
                }
                half * col.dphi[i]
            }
            SheenWarp::Sqrt => {
                let (norm, kk) = (self.norm, self.k);
                match self.cache {
                    Some(cache) => {
                        let mut c = cache.borrow_mut();
                        c.ensure(col, i, stride);
                        let base = i * NMAX;
                        for q in 0..m {
                            let at = base + js[q];
                            v[q] = norm * exp_poly((kk * c.ln_sin2[at]).max(-700.0)) * c.rest[at];
                        }
                        c.scale[i]
                    }
                    None => {
                        let g = SqrtWarpPhi::new(col, i);
                        for q in 0..m {
                            let (l, p) = g.node(xs[q]);
                            v[q] = norm * exp_poly((kk * l).max(-700.0)) * p;
                        }
                        g.scale
                    }
                }
            }
        };
        for k in 0..m {
            out[js[k]] = v[k];
        }
        scale
    }
}

/// The wide-lobe sheen warp at one φ node: `θh = θmax w²`, with `w = 1 − d sinh z` where the
/// Ashikhmin visibility's horizon layer is narrow. Nothing here depends on α, so a table
/// column can share it ([`SheenCache`]).
struct SqrtWarpPhi {
    mu: f64,
    svcp: f64,
    thmax: f64,
    d: f64,
    zmax: f64,
    /// the node's inner half-length × dφ/dx
    scale: f64,
}

impl SqrtWarpPhi {
    fn new(col: &Column, i: usize) -> SqrtWarpPhi {
        let mu = col.mu;
        let cp = col.cos_phi[i];
        let thmax = col.tmax[i].atan();
        // Near the horizon n·l ≈ 2A(θmax − θh), A = √(cos²θv + sin²θv cos²φ), and the
        // visibility turns over at n·l ~ n·v: a layer of width ℓ = n·v/(2A) in θh; where it
        // is narrow (d = ℓ/(2θmax) < 1/4), w = 1 − d sinh z puts nodes into it (as tensor.rs)
        let amp = (mu * mu + col.sin_v * col.sin_v * cp * cp).sqrt();
        let d = mu / (2.0 * amp) / (2.0 * thmax);
        let zmax = if d < 0.25 { (1.0 / d).asinh() } else { 0.0 };
        SqrtWarpPhi {
            mu,
            svcp: col.sin_v * cp,
            thmax,
            d,
            zmax,
            scale: 0.5 * col.dphi[i] * if zmax > 0.0 { zmax } else { 1.0 },
        }
    }

    /// At rule abscissa x: (ln sin²θh, the integrand without D: (n·l)(v·h)/(n·l + μ −
    /// (n·l)μ) · sin θh |dθh/dx'|), so that the value is `norm·exp(k·ln sin²θh)·rest`.
    #[inline(always)]
    fn node(&self, x: f64) -> (f64, f64) {
        let (w, dw) = if self.zmax > 0.0 {
            let z = self.zmax * 0.5 * (1.0 - x);
            let e = exp_poly(z);
            let ei = 1.0 / e;
            (
                (1.0 - self.d * 0.5 * (e - ei)).max(0.0),
                self.d * 0.5 * (e + ei),
            )
        } else {
            (0.5 * (1.0 - x), 1.0)
        };
        let th = self.thmax * w * w;
        let (sin_h, cos_h) = sin_cos_poly(th);
        let mu = self.mu;
        let vh = self.svcp * sin_h + mu * cos_h;
        let nl = (2.0 * vh * cos_h - mu).max(0.0);
        // dω_h = sin θh dθh dφ, |dθh/dw| = 2 θmax w
        let rest = nl * vh / (nl + mu - nl * mu) * (sin_h * 2.0 * self.thmax * w * dw);
        (ln_poly(sin_h * sin_h), rest)
    }
}

/// The cloth kernel's α-independent data for one table column (one view μ), wide-lobe
/// warp: per φ node and inner node, ln sin²θh and the integrand without D, filled level by
/// level as texels ask for them. Each entry is a pure function of (μ, node), so sharing it
/// changes no value: a texel computes the same bits with or without it.
pub struct SheenCache {
    level_stride: Vec<usize>,
    scale: Vec<f64>,
    ln_sin2: Vec<f64>,
    rest: Vec<f64>,
}

impl Default for SheenCache {
    fn default() -> Self {
        SheenCache {
            level_stride: vec![0; NMAX],
            scale: vec![0.0; NMAX],
            ln_sin2: vec![0.0; NMAX * NMAX],
            rest: vec![0.0; NMAX * NMAX],
        }
    }
}

impl SheenCache {
    /// Makes sure φ node i has every inner node of stride `stride`.
    fn ensure(&mut self, col: &Column, i: usize, stride: usize) {
        let have = self.level_stride[i];
        if have != 0 && have <= stride {
            return;
        }
        let r = cc_rules();
        let g = SqrtWarpPhi::new(col, i);
        let mask = have.wrapping_sub(1);
        let mut j = 0;
        while j < NMAX {
            if have == 0 || j & mask != 0 {
                let (l, p) = g.node(r.x[j]);
                self.ln_sin2[i * NMAX + j] = l;
                self.rest[i * NMAX + j] = p;
            }
            j += stride;
        }
        self.scale[i] = g.scale;
        self.level_stride[i] = stride;
    }
}

/// ln x for finite x > 0 (subnormals excepted): x = 2^n·m with m ∈ [√½, √2) from the bits,
/// ln m = 2 atanh(s) = 2(s + s³/3 + … + s²¹/21), s = (m − 1)/(m + 1), |s| ≤ 0.1716
/// (truncation < 1e-19 relative); plain arithmetic so that loops calling it vectorize. Within
/// a few ulp of `f64::ln` (unit test below).
#[inline(always)]
pub fn ln_poly(x: f64) -> f64 {
    let bits = x.to_bits();
    // biased exponent as a float: its bits under 2^52, minus 2^52
    let eb = f64::from_bits((bits >> 52) | 0x4330_0000_0000_0000) - 4_503_599_627_370_496.0;
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let big = m > std::f64::consts::SQRT_2;
    let m = if big { 0.5 * m } else { m };
    let n = eb - 1023.0 + if big { 1.0 } else { 0.0 };
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let mut p = 1.0 / 21.0;
    p = p * s2 + 1.0 / 19.0;
    p = p * s2 + 1.0 / 17.0;
    p = p * s2 + 1.0 / 15.0;
    p = p * s2 + 1.0 / 13.0;
    p = p * s2 + 1.0 / 11.0;
    p = p * s2 + 1.0 / 9.0;
    p = p * s2 + 1.0 / 7.0;
    p = p * s2 + 1.0 / 5.0;
    p = p * s2 + 1.0 / 3.0;
    let lnm = 2.0 * s + 2.0 * s * s2 * p;
    n * LN2_HI + (n * LN2_LO + lnm)
}

/// (sin x, cos x) for x ∈ [0, π/2]: with d = x − π/4 (|d| ≤ π/4),
/// sin x = (sin d + cos d)/√2 and cos x = (cos d − sin d)/√2, sin d and cos d by
/// [`sin_cos_taylor`]; plain arithmetic, for vectorized loops. Absolute error a few 1e-16
/// (unit test below).
#[inline(always)]
pub fn sin_cos_poly(x: f64) -> (f64, f64) {
    let (sd, cd) = sin_cos_taylor(x - std::f64::consts::FRAC_PI_4);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    ((sd + cd) * h, (cd - sd) * h)
}

/// (sin d, cos d) for |d| ≤ π/4 by their Taylor series to degrees 17 and 18 (truncation
/// < 1e-16), evaluated by Estrin's scheme in d² (a short dependency chain); sin d as d times
/// its series, so relatively accurate down to d → 0 (unit test below; the polar kernel's
/// lines take their half-angle sine and cosine from it).
#[inline(always)]
pub fn sin_cos_taylor(d: f64) -> (f64, f64) {
    let z = d * d;
    let z2 = z * z;
    let z4 = z2 * z2;
    let z8 = z4 * z4;
    let c = &SIN_C;
    let sd = d
        * (((c[0] + z * c[1]) + z2 * (c[2] + z * c[3]))
            + z4 * ((c[4] + z * c[5]) + z2 * (c[6] + z * c[7]))
            + z8 * c[8]);
    let c = &COS_C;
    let cd = ((c[0] + z * c[1]) + z2 * (c[2] + z * c[3]))
        + z4 * ((c[4] + z * c[5]) + z2 * (c[6] + z * c[7]))
        + z8 * (c[8] + z * c[9]);
    (sd, cd)
}

/// (−1)^k/(2k+1)!, k = 0..11.
const SIN_C: [f64; 12] = [
    1.0,
    -1.0 / 6.0,
    1.0 / 120.0,
    -1.0 / 5_040.0,
    1.0 / 362_880.0,
    -1.0 / 39_916_800.0,
    1.0 / 6_227_020_800.0,
    -1.0 / 1_307_674_368_000.0,
    1.0 / 355_687_428_096_000.0,
    -1.0 / 121_645_100_408_832_000.0,
    1.0 / 51_090_942_171_709_440_000.0,
    -1.0 / 25_852_016_738_884_976_640_000.0,
];

/// (−1)^k/(2k)!, k = 0..12.
const COS_C: [f64; 13] = [
    1.0,
    -1.0 / 2.0,
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40_320.0,
    -1.0 / 3_628_800.0,
    1.0 / 479_001_600.0,
    -1.0 / 87_178_291_200.0,
    1.0 / 20_922_789_888_000.0,
    -1.0 / 6_402_373_705_728_000.0,
    1.0 / 2_432_902_008_176_640_000.0,
    -1.0 / 1_124_000_727_777_607_680_000.0,
    1.0 / 620_448_401_733_239_439_360_000.0,
];

/// The cloth albedo `∫ D_Charlie(α) V_Ashikhmin (n·l) dω_l` at the column's view, to
/// absolute tolerance `tol` (estimated); `Err(evaluations spent)` where the nested rules do
/// not reach it, and
/// for the very narrow lobes pressed against the horizon that the generic path sends to the
/// adaptive integrator directly (α < 1e-4 with D > 1e-12 D_max at the lowest horizon point;
/// see [`integrate_over_l_smooth`](super::tensor::integrate_over_l_smooth)).
pub fn charlie_sheen(col: &Column, alpha: f64, tol: f64) -> Result<Estimate<1>, u64> {
    charlie_sheen_shared(col, None, alpha, tol)
}

/// [`charlie_sheen`] with the column's α-independent node data shared through `cache`
/// (which must only ever be used with this `col`): the same result, bit for bit.
pub fn charlie_sheen_shared(
    col: &Column,
    cache: Option<&RefCell<SheenCache>>,
    alpha: f64,
    tol: f64,
) -> Result<Estimate<1>, u64> {
    if !(col.mu > 0.0 && alpha > 0.0) {
        return Err(0);
    }
    let warp = if alpha < 1.0 / 16.0 {
        let theta_v = col.mu.clamp(0.0, 1.0).acos();
        let cmin = (FRAC_PI_4 - 0.5 * theta_v).sin();
        let d_rel = ((1.0 - cmin * cmin).ln() / (2.0 * alpha)).exp();
        if alpha < 1e-4 && d_rel > 1e-12 {
            return Err(0);
        }
        SheenWarp::Cos(alpha.sqrt())
    } else {
        SheenWarp::Sqrt
    };
    let k = SheenFill {
        col,
        cache,
        norm: (2.0 + 1.0 / alpha) / (2.0 * std::f64::consts::PI),
        k: 0.5 / alpha,
        warp,
    };
    SCRATCH.with(|s| run::<1, _>(&mut s.borrow_mut(), &k, tol))
}

/// Per-thread scratch, as in [`tensor`](super::tensor).
#[derive(Default)]
struct Scratch {
    vals: Vec<f64>,
    level: Vec<usize>,
    scale: Vec<f64>,
    /// per φ index: its three inner sums (levels ku, ku − 1, ku − 2), and that ku
    inner: Vec<f64>,
    inner_level: Vec<usize>,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// The nested Clenshaw–Curtis tensor rule of [`tensor`](super::tensor) — its level driver
/// [`refine`](super::tensor::refine) itself — over a specialised [`Fill`], with the inner sums
/// cached per φ node.
fn run<const N: usize, K: Fill<N>>(sc: &mut Scratch, k: &K, tol: f64) -> Result<Estimate<N>, u64> {
    sc.vals.resize(NMAX * NMAX * N, 0.0);
    sc.level.clear();
    sc.level.resize(NMAX, usize::MAX);
    sc.scale.resize(NMAX, 0.0);
    sc.inner.resize(NMAX * 3 * N, 0.0);
    sc.inner_level.clear();
    sc.inner_level.resize(NMAX, usize::MAX);
    let mut tmp = Tmp {
        xs: [0.0; NMAX],
        js: [0; NMAX],
        v0: [0.0; NMAX],
        v1: [0.0; NMAX],
    };
    let fill = |sc: &mut Scratch, evals: &mut u64, i: usize, ku: usize| {
        let tmp = &mut tmp;
        let have = sc.level[i];
        if have != usize::MAX && have >= ku {
            return;
        }
        let stride = 1usize << (MAX_LEVEL - ku);
        let old_stride = if have == usize::MAX {
            0
        } else {
            1usize << (MAX_LEVEL - have)
        };
        let base = i * NMAX * N;
        sc.scale[i] = k.fill(
            i,
            stride,
            old_stride,
            &mut sc.vals[base..base + NMAX * N],
            tmp,
        );
        let new = (1usize << ku) + 1;
        let old = if have == usize::MAX {
            0
        } else {
            (1usize << have) + 1
        };
        *evals += (new - old) as u64;
        sc.level[i] = ku;
    };
    // The inner sums of φ node i at u levels ku, ku − 1, ku − 2 (times the node's scale),
    // kept until the node's u level changes.
    let inner = |sc: &mut Scratch, i: usize, ku: usize| -> [[f64; N]; 3] {
        let cache = i * 3 * N;
        let mut out = [[0.0; N]; 3];
        if sc.inner_level[i] == ku {
            for m in 0..3 {
                for c in 0..N {
                    out[m][c] = sc.inner[cache + m * N + c];
                }
            }
            return out;
        }
        let out: [[f64; N]; 3] =
            super::tensor::inner_sums(&sc.vals[i * NMAX * N..(i + 1) * NMAX * N], sc.scale[i], ku);
        for m in 0..3 {
            for c in 0..N {
                sc.inner[cache + m * N + c] = out[m][c];
            }
        }
        sc.inner_level[i] = ku;
        out
    };
    super::tensor::refine(sc, tol, fill, inner)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// exp_poly against the platform's exp over the range the kernels use (and beyond):
    /// relative difference ≤ 8 ulp (≈ 1.8e-15): reduction rounding (≤ 1 ulp of r, which
    /// is |r| ≤ 0.35), 13 Estrin terms and the final product, each ≤ 1 ulp, plus the
    /// reference's own ≤ 1 ulp.
    #[test]
    fn exp_poly_matches_exp() {
        let mut x = -700.0;
        while x <= 700.0 {
            let (a, b) = (exp_poly(x), x.exp());
            assert!((a - b).abs() <= 8.0 * f64::EPSILON * b, "x={x}: {a} vs {b}");
            x += 0.013_7;
        }
        assert_eq!(exp_poly(0.0), 1.0);
    }

    /// ln_poly against ln on (0, 1] and beyond: absolute difference ≤ 4 ulp of max(1, |ln x|)
    /// (the sum n·ln2 + ln m rounds at that scale; ln m ≤ 0.35 in magnitude is accurate to a
    /// few ulp of itself).
    #[test]
    fn ln_poly_matches_ln() {
        let mut x = 1e-300f64;
        while x < 1e6 {
            let (a, b) = (ln_poly(x), x.ln());
            assert!(
                (a - b).abs() <= 4.0 * f64::EPSILON * b.abs().max(1.0),
                "x={x}: {a} vs {b}"
            );
            x *= 1.013;
        }
        assert_eq!(ln_poly(1.0), 0.0);
    }

    /// `f` against libm's `sin_cos` at n + 1 equally spaced points of [0, `hi`]: both
    /// absolute differences within `abs`; `sine` checks each (x, f's sine, libm's) further.
    fn check_sin_cos(
        f: impl Fn(f64) -> (f64, f64),
        hi: f64,
        n: usize,
        abs: f64,
        sine: impl Fn(f64, f64, f64),
    ) {
        for i in 0..=n {
            let x = hi * i as f64 / n as f64;
            let (s, c) = f(x);
            let (s0, c0) = x.sin_cos();
            assert!(
                (s - s0).abs() <= abs && (c - c0).abs() <= abs,
                "x={x}: {s} {c} vs {s0} {c0}"
            );
            sine(x, s, s0);
        }
    }

    /// sin_cos_poly against sin_cos on [0, π/2]: absolute difference ≤ 4e-16 (ten terms of
    /// magnitude ≤ 0.8 in each series, summed in a fixed order, and the final rotation).
    #[test]
    fn sin_cos_poly_matches_sin_cos() {
        check_sin_cos(
            sin_cos_poly,
            std::f64::consts::FRAC_PI_2,
            10_000,
            4e-16,
            |_, _, _| {},
        );
    }

    /// `sin_cos_taylor`, which gives the polar kernel's lines their half-angle sine and
    /// cosine, against libm on [0, π/4]: within 3e-16 absolute (both are within ~2 ulp of
    /// the true values, which are at most 1) and 4e-16 relative for the sine, down to 1e-300
    /// (the lines near θl = 0 of a narrow lobe at the normal view need it relatively
    /// accurate).
    #[test]
    fn sin_cos_taylor_matches_libm() {
        check_sin_cos(
            sin_cos_taylor,
            std::f64::consts::FRAC_PI_4,
            100_000,
            3e-16,
            |x, s, s0| assert!((s - s0).abs() <= 4e-16 * s0, "x {x}: {s} vs {s0}"),
        );
        for x in [1e-300, 1e-20, 1e-8, 1e-3] {
            let (s, c) = sin_cos_taylor(x);
            assert!(
                (s - x.sin()).abs() <= 2e-16 * x && (c - x.cos()).abs() <= 2e-16,
                "x {x}"
            );
        }
    }
}
