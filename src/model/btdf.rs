//! A rough dielectric interface: GGX microfacets with Smith masking-shadowing, reflecting
//! with the exact unpolarized Fresnel F and transmitting 1 − F (Walter, Marschner, Li &
//! Torrance 2007, "Microfacet Models for Refraction through Rough Surfaces").
//!
//! The view v lies on the side of the normal n, in the medium of index η_o; the other side
//! has index η_i and η = η_i/η_o is the relative index (η > 1: entering glass from air,
//! η < 1: leaving it, with total internal reflection where sin θ > η).
//!
//! **Reflection and transmission albedo in micro-normal space.** For a micro-normal h with
//! c = v·h > 0 the reflected direction is l_r = 2c h − v (dω_l = 4c dω_h, Walter eq. 14) and
//! the refracted one l_t = (c/η − cos θt) h − v/η with cos θt = √(1 − (1 − c²)/η²) (Walter
//! eq. 40). Walter's scattering function of a microfacet surface (§4),
//! f(v, l) = |v·h|/(|n·v||n·l|) · {F, 1 − F} · G · D · |∂ω_h/∂ω_l|, of which the BRDF
//! (eq. 20) and the BTDF (eq. 21) are the two cases with their Jacobians (eq. 14, eq. 17),
//! gives f |n·l| dω_l = c {F, 1 − F} G D/(n·v) dω_h for both. So
//!
//! `R = ∫ D(h) G(v, l_r) F(c) c/(n·v) dω_h` over h with n·l_r > 0,
//! `T = ∫ D(h) G(v, l_t) (1 − F(c)) c/(n·v) dω_h` over h without total internal reflection
//! and with n·l_t < 0.
//!
//! With G = G1(v) alone the two integrands sum to D G1(v) c/(n·v), whose integral over
//! c > 0 is 1 (the normalization of the visible normals that defines Smith G1, Heitz 2014): so R + T ≤ 1, with
//! the defect the energy lost by single scattering, and R + T → 1 as α → 0.
//!
//! Masking ([`SmithForm`]): separable Smith G = G1(n·v) G1(|n·l|) (Walter et al. 2007,
//! eq. 23), both sides with the same Λ since the microsurface is the same; or the
//! height-correlated form G = 1/(1 + Λ(n·v) + Λ(|n·l|)) on both sides, as Cycles evaluates
//! its refraction closures (`bsdf_G` in `kernel/closure/bsdf_microfacet.h`, the masking of
//! its `ggx_glass` tables) and pbrt-v4 its dielectric BSDF. (Heitz 2014 derives, from the
//! same height-correlation assumption, the transmission form `B(1 + Λ(v), 1 + Λ(l))` with
//! B the Beta function: the view sees a height h with probability C(h)^Λ(v), the
//! transmitted direction, which looks at the microsurface from below, (1 − C(h))^Λ(l),
//! and ∫₀¹ C^a (1 − C)^b dC = B(1 + a, 1 + b). It equals 1/(1 + Λ(v) + Λ(l)) only where
//! one of the Λ vanishes; no engine table we compare with uses it, and the Cycles data
//! rule it out: `tests/cycles_tables.rs`.) With either form the two integrands below are
//! bounded by D G1(v) c/(n·v) (1/(1/a + 1/b − 1) ≤ min(a, b)), so R + T ≤ 1 still holds.

use super::fresnel::dielectric;
use super::masking::Masking;
use super::ndf::Ndf;

/// The Smith masking–shadowing form of a rough dielectric interface, on both sides.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SmithForm {
    /// `G = G1(n·v) G1(|n·l|)` (Walter et al. 2007, eq. 23).
    Separable,
    /// `G = 1/(1 + Λ(n·v) + Λ(|n·l|))` = `1/(1/G1(v) + 1/G1(l) − 1)` (Heitz 2014, eq. 99,
    /// taken for transmission as Cycles and pbrt-v4 do).
    HeightCorrelated,
}

impl SmithForm {
    /// The form of a preset's masking term, if it is a Smith one.
    pub fn of(m: Masking) -> Option<SmithForm> {
        match m {
            Masking::SmithSeparable => Some(SmithForm::Separable),
            Masking::SmithHeightCorrelated => Some(SmithForm::HeightCorrelated),
            _ => None,
        }
    }

    /// G of GGX with α² = `a2` for a view and a direction whose cosines to the
    /// macro-surface are `nv` and `nl` (clamped to 1; 0 if either is ≤ 0), in one division:
    /// with G1(x) = 2x/(x + r(x)), r(x) = √(α² + (1 − α²)x²) (`Ndf::g1`), the separable form
    /// is 4 nv nl/((nv + r_v)(nl + r_l)) and the height-correlated G1v G1l/(G1v + G1l −
    /// G1v G1l) = 2 nv nl/(nv r_l + nl r_v), a sum of positive terms (no cancellation).
    /// [`SmithForm::g`] of two `Ndf::g1` to a few roundings (tested), for the inner
    /// integrals of `dielectric-albedo-avg`, where the three divisions of that composition
    /// were a fifth of the time.
    #[inline]
    pub fn ggx(self, a2: f64, nv: f64, nl: f64) -> f64 {
        if nv <= 0.0 || nl <= 0.0 {
            return 0.0;
        }
        let (nv, nl) = (nv.min(1.0), nl.min(1.0));
        let r = |x: f64| (a2 + (1.0 - a2) * x * x).sqrt();
        let (rv, rl) = (r(nv), r(nl));
        match self {
            SmithForm::Separable => 4.0 * nv * nl / ((nv + rv) * (nl + rl)),
            SmithForm::HeightCorrelated => 2.0 * nv * nl / (nv * rl + nl * rv),
        }
    }

    /// G of a view with `G1(n·v) = g1v` and a direction with `G1(|n·l|) = g1l`.
    #[inline]
    pub fn g(self, g1v: f64, g1l: f64) -> f64 {
        match self {
            SmithForm::Separable => g1v * g1l,
            SmithForm::HeightCorrelated => {
                // 1/(1/a + 1/b − 1) = ab/(a + b − ab); a + b − ab ≥ max(a, b) for a, b in [0, 1]
                let p = g1v * g1l;
                if p <= 0.0 {
                    0.0
                } else {
                    p / (g1v + g1l - p)
                }
            }
        }
    }
}

/// A rough dielectric interface of relative index `eta` with a GGX (or any) NDF.
#[derive(Clone, Debug)]
pub struct RoughDielectric {
    pub ndf: Ndf,
    pub eta: f64,
}

/// Everything about one micro-normal h for a view with n·v = `n_dot_v`.
#[derive(Clone, Copy, Debug)]
pub struct MicroNormal {
    pub n_dot_h: f64,
    /// sin²θh (computed directly, see `hemisphere::Node::sin2_h`).
    pub sin2_h: f64,
    /// c = v·h > 0.
    pub v_dot_h: f64,
}

impl RoughDielectric {
    /// `[R, T]` integrands per unit solid angle of h (see the module doc), 0 where the
    /// corresponding direction does not exist or lies on the wrong side.
    #[inline]
    pub fn integrands(&self, n_dot_v: f64, m: &MicroNormal) -> [f64; 2] {
        self.integrands_with(n_dot_v, self.ndf.g1(n_dot_v), m)
    }

    /// [`Self::integrands`] with the view's `G1(n·v)` = `g1v` given (it is the same for every
    /// micro-normal of one view: a caller integrating over h computes it once).
    #[inline]
    pub fn integrands_with(&self, n_dot_v: f64, g1v: f64, m: &MicroNormal) -> [f64; 2] {
        integrands_many(
            &self.ndf,
            SmithForm::Separable,
            &[self.eta],
            n_dot_v,
            g1v,
            m,
        )
    }

    /// n·l_t of the refracted direction, `None` under total internal reflection.
    #[inline]
    pub fn n_dot_lt(&self, n_dot_v: f64, m: &MicroNormal) -> Option<f64> {
        n_dot_lt(self.eta, n_dot_v, m)
    }
}

/// n·l_t of the direction refracted at micro-normal `m` into relative index `eta`
/// (Walter et al. 2007, eq. 40: l_t = (c/η − cos θt) h − v/η), `None` under total internal
/// reflection.
#[inline]
pub fn n_dot_lt(eta: f64, n_dot_v: f64, m: &MicroNormal) -> Option<f64> {
    let c = m.v_dot_h;
    let s2t = (1.0 - c * c) / (eta * eta);
    if s2t >= 1.0 {
        return None;
    }
    let ct = (1.0 - s2t).sqrt();
    Some((c / eta - ct) * m.n_dot_h - n_dot_v / eta)
}

/// The `[R, T]` integrands of [`RoughDielectric::integrands_with`] for several relative
/// indices at once, channels `2k` (R) and `2k + 1` (T) for `etas[k]`; channels beyond
/// `2·etas.len()` are 0. What does not depend on η — D(h), G1(n·v), the Jacobian-free weight
/// w = D G1(v) c/(n·v), the reflected direction and its G1 — is computed once per
/// micro-normal; per η only F(c, η) (exact dielectric), the refracted direction and its G1
/// (Walter et al. 2007, eqs. 20–23, 40; module docs). `smith` chooses the masking form; the
/// height-correlated one replaces G1(v)·G1(l) by [`SmithForm::g`].
#[inline]
pub fn integrands_many<const N: usize>(
    ndf: &Ndf,
    smith: SmithForm,
    etas: &[f64],
    n_dot_v: f64,
    g1v: f64,
    m: &MicroNormal,
) -> [f64; N] {
    debug_assert!(2 * etas.len() <= N);
    let mut out = [0.0; N];
    let c = m.v_dot_h;
    if c <= 0.0 || n_dot_v <= 0.0 {
        return out;
    }
    let d = ndf.d_cs(m.n_dot_h, m.sin2_h);
    if d == 0.0 {
        return out;
    }
    let n_dot_lr = 2.0 * c * m.n_dot_h - n_dot_v;
    let g1r = if n_dot_lr > 0.0 {
        ndf.g1(n_dot_lr.min(1.0))
    } else {
        0.0
    };
    match smith {
        SmithForm::Separable => {
            let w = d * g1v * c / n_dot_v;
            for (k, &eta) in etas.iter().enumerate() {
                let f = dielectric(c, eta);
                out[2 * k] = w * f * g1r;
                if let Some(nlt) = n_dot_lt(eta, n_dot_v, m) {
                    if nlt < 0.0 {
                        out[2 * k + 1] = w * (1.0 - f) * ndf.g1((-nlt).min(1.0));
                    }
                }
            }
        }
        SmithForm::HeightCorrelated => {
            let w = d * c / n_dot_v;
            let gr = smith.g(g1v, g1r);
            for (k, &eta) in etas.iter().enumerate() {
                let f = dielectric(c, eta);
                out[2 * k] = w * f * gr;
                if let Some(nlt) = n_dot_lt(eta, n_dot_v, m) {
                    if nlt < 0.0 {
                        out[2 * k + 1] = w * (1.0 - f) * smith.g(g1v, ndf.g1((-nlt).min(1.0)));
                    }
                }
            }
        }
    }
    out
}

/// What the integrands of one micro-normal share across relative indices: `c = v·h`, the
/// weight `w = D(h) c/(n·v)` of the visible-normal measure without its masking, and `gr`, the
/// masking–shadowing G of the reflected direction (0 below the horizon). `None` where the
/// micro-normal is not visible (v·h ≤ 0) or D vanishes.
#[derive(Clone, Copy, Debug)]
pub struct Facet {
    pub c: f64,
    pub w: f64,
    pub gr: f64,
}

impl Facet {
    /// The shared terms of micro-normal `m` for a view with n·v = `n_dot_v` and
    /// G1(n·v) = `g1v`.
    #[inline]
    pub fn new(
        ndf: &Ndf,
        smith: SmithForm,
        n_dot_v: f64,
        g1v: f64,
        m: &MicroNormal,
    ) -> Option<Facet> {
        let c = m.v_dot_h;
        if c <= 0.0 || n_dot_v <= 0.0 {
            return None;
        }
        let d = ndf.d_cs(m.n_dot_h, m.sin2_h);
        if d == 0.0 {
            return None;
        }
        let n_dot_lr = 2.0 * c * m.n_dot_h - n_dot_v;
        let gr = if n_dot_lr > 0.0 {
            smith.g(g1v, ndf.g1(n_dot_lr.min(1.0)))
        } else {
            0.0
        };
        Some(Facet {
            c,
            w: d * c / n_dot_v,
            gr,
        })
    }

    /// The refraction into relative index `eta`: `(G of the refracted direction, cos θt =
    /// |h·l_t|)`, or `None` under total internal reflection or where the refracted
    /// direction does not leave below the surface (n·l_t ≥ 0).
    #[inline]
    pub fn refraction(
        &self,
        ndf: &Ndf,
        smith: SmithForm,
        g1v: f64,
        eta: f64,
        n_dot_v: f64,
        m: &MicroNormal,
    ) -> Option<(f64, f64)> {
        let s2t = (1.0 - self.c * self.c) / (eta * eta);
        if s2t >= 1.0 {
            return None;
        }
        let ct = (1.0 - s2t).sqrt();
        let nlt = (self.c / eta - ct) * m.n_dot_h - n_dot_v / eta;
        (nlt < 0.0).then(|| (smith.g(g1v, ndf.g1((-nlt).min(1.0))), ct))
    }
}

/// The refraction G of [`Facet::refraction`] into up to `L` relative indices at once (0 where
/// it is `None`), for GGX: the rule's constants, and per micro-normal one loop over the
/// indices with the same operations in the same order as `refraction` and its branches
/// turned into selections, so that it vectorizes; on x86-64 with AVX2 it is compiled for it
/// (only correctly rounded operations, none fused: the same bits as the portable build and as
/// `refraction`, tested). Used by the η fibres of `dielectric-schlick`, where the refractions
/// one at a time were half of the time.
#[derive(Clone, Copy, Debug)]
pub struct GgxRefractions<const L: usize> {
    /// α² as `Ndf::g1` forms it (α·α)
    a2: f64,
    height_correlated: bool,
    g1v: f64,
    n_dot_v: f64,
    /// every lane an index (lanes beyond the indices given repeat the last one)
    etas: [f64; L],
}

impl<const L: usize> GgxRefractions<L> {
    /// For the GGX lobe `ndf`, masking `smith`, a view with n·v = `n_dot_v` and
    /// G1(n·v) = `g1v`, and the indices `etas` (1 to `L` of them).
    pub fn new(ndf: &Ndf, smith: SmithForm, g1v: f64, n_dot_v: f64, etas: &[f64]) -> Self {
        assert!(
            ndf.kind() == super::NdfKind::Ggx && !etas.is_empty() && etas.len() <= L,
            "GGX, 1 to {L} indices"
        );
        GgxRefractions {
            a2: ndf.alpha() * ndf.alpha(),
            height_correlated: smith == SmithForm::HeightCorrelated,
            g1v,
            n_dot_v,
            etas: std::array::from_fn(|k| etas[k.min(etas.len() - 1)]),
        }
    }

    /// Per lane, the G of the facet `f` of micro-normal `m`'s refraction into that lane's
    /// index.
    #[inline]
    pub fn g(&self, f: &Facet, m: &MicroNormal) -> [f64; L] {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked above), all that `g_avx2` requires.
            return unsafe { self.g_avx2(f, m) };
        }
        self.g_portable(f, m)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn g_avx2(&self, f: &Facet, m: &MicroNormal) -> [f64; L] {
        self.g_portable(f, m)
    }

    #[inline(always)]
    fn g_portable(&self, f: &Facet, m: &MicroNormal) -> [f64; L] {
        let mut out = [0.0; L];
        let (a2, g1v, c) = (self.a2, self.g1v, f.c);
        for (o, &eta) in out.iter_mut().zip(&self.etas) {
            let s2t = (1.0 - c * c) / (eta * eta);
            // (where s2t ≥ 1, total internal reflection: computed at s2t = 1, then dropped)
            let ct = (1.0 - s2t.min(1.0)).sqrt();
            let nlt = (c / eta - ct) * m.n_dot_h - self.n_dot_v / eta;
            // Ndf::g1 of GGX at x = min(−n·l_t, 1): 1 at x = 1
            let x = (-nlt).min(1.0);
            let g1 = 2.0 * x / (x + (a2 + (1.0 - a2) * x * x).sqrt());
            let g1 = if x >= 1.0 { 1.0 } else { g1 };
            // SmithForm::g
            let p = g1v * g1;
            let g = if self.height_correlated {
                let q = p / (g1v + g1 - p);
                if p <= 0.0 {
                    0.0
                } else {
                    q
                }
            } else {
                p
            };
            *o = if s2t < 1.0 && nlt < 0.0 { g } else { 0.0 };
        }
        out
    }
}

/// The directional albedo integrand E = R + T of [`integrands_many`] per relative index:
/// channel k is `w (F(c, η_k) G_r + (1 − F(c, η_k)) G_t)` for `etas[k]`; channels beyond
/// `etas.len()` are 0.
#[inline]
pub fn albedo_integrands<const N: usize>(
    ndf: &Ndf,
    smith: SmithForm,
    etas: &[f64],
    n_dot_v: f64,
    g1v: f64,
    m: &MicroNormal,
) -> [f64; N] {
    debug_assert!(etas.len() <= N);
    let mut out = [0.0; N];
    let Some(f) = Facet::new(ndf, smith, n_dot_v, g1v, m) else {
        return out;
    };
    for (o, &eta) in out.iter_mut().zip(etas) {
        let fr = dielectric(f.c, eta);
        let gt = f
            .refraction(ndf, smith, g1v, eta, n_dot_v, m)
            .map_or(0.0, |(g, _)| g);
        *o = f.w * (fr * f.gr + (1.0 - fr) * gt);
    }
    out
}

/// The `[R, T]` integrands of [`integrands_many`] for one relative index η < 1, with what
/// depends only on η and the view computed once per integral (1/η, η² − 1, 1/(n·v)) and one
/// square root shared by the Fresnel factor and the refraction: with
/// g = √(η² − 1 + c²) (Cook & Torrance 1982, eq. 10), cos θt = √(1 − (1 − c²)/η²) = g/η, so
/// n·l_t = (c/η − cos θt) n·h − n·v/η = ((c − g) n·h − n·v)/η (Walter et al. 2007, eq. 40),
/// and F = ½(g − c)²(d² + n²)/((g + c)² d²) with n = c(g + c) − 1, d = c(g − c) + 1 =
/// 1 − c² + cg > 0 ([`super::fresnel::dielectric_one_division`], whose form holds here
/// too). Total internal reflection where η² − 1 + c² < 0: F = 1, no T. Equal to
/// [`integrands_many`] to rounding (unit test below); for the η < 1 texels, each integrated
/// alone ([`crate::table::dielectric`]).
#[derive(Clone, Copy, Debug)]
pub struct BelowOne {
    inv_eta: f64,
    eta2_m1: f64,
    n_dot_v: f64,
    inv_n_dot_v: f64,
    g1v: f64,
}

impl BelowOne {
    /// The per-integral constants of relative index `eta` (< 1) for a view with
    /// n·v = `n_dot_v` (> 0) and G1(n·v) = `g1v`.
    pub fn new(eta: f64, n_dot_v: f64, g1v: f64) -> BelowOne {
        debug_assert!(eta < 1.0 && n_dot_v > 0.0);
        BelowOne {
            inv_eta: 1.0 / eta,
            eta2_m1: (eta - 1.0) * (eta + 1.0),
            n_dot_v,
            inv_n_dot_v: 1.0 / n_dot_v,
            g1v,
        }
    }

    /// `[R, T]` per unit solid angle of h at micro-normal `m` (as [`integrands_many`]).
    #[inline]
    pub fn integrands(&self, ndf: &Ndf, smith: SmithForm, m: &MicroNormal) -> [f64; 2] {
        let c = m.v_dot_h;
        if c <= 0.0 {
            return [0.0; 2];
        }
        let d = ndf.d_cs(m.n_dot_h, m.sin2_h);
        if d == 0.0 {
            return [0.0; 2];
        }
        let n_dot_lr = 2.0 * c * m.n_dot_h - self.n_dot_v;
        let g1r = if n_dot_lr > 0.0 {
            ndf.g1(n_dot_lr.min(1.0))
        } else {
            0.0
        };
        let w = d * c * self.inv_n_dot_v;
        let (w, gr) = match smith {
            SmithForm::Separable => (w * self.g1v, g1r),
            SmithForm::HeightCorrelated => (w, smith.g(self.g1v, g1r)),
        };
        let g2 = self.eta2_m1 + c * c;
        if g2 < 0.0 {
            return [w * gr, 0.0];
        }
        let g = g2.sqrt();
        let (p, q) = (g + c, g - c);
        let (nn, dd) = (c * p - 1.0, c * q + 1.0);
        let f = 0.5 * q * q * (dd * dd + nn * nn) / (p * p * dd * dd);
        let nlt = (-q * m.n_dot_h - self.n_dot_v) * self.inv_eta;
        let t = if nlt < 0.0 {
            let g1t = ndf.g1((-nlt).min(1.0));
            let gt = match smith {
                SmithForm::Separable => g1t,
                SmithForm::HeightCorrelated => smith.g(self.g1v, g1t),
            };
            w * (1.0 - f) * gt
        } else {
            0.0
        };
        [w * f * gr, t]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::NdfKind;

    /// [`GgxRefractions`] against [`Facet::refraction`] one index at a time, bit
    /// for bit (the same operations; the branches became selections), over micro-normals,
    /// views, indices on both sides of 1 (total internal reflection included), roughnesses
    /// and both masking forms, with the AVX2 build where the CPU has it.
    #[test]
    fn ggx_refractions_are_refraction_bit_for_bit() {
        let etas = [1.0001, 1.1, 1.33, 1.5, 2.4, 3.0, 0.7, 0.95];
        // (both outcomes must occur often: a refraction, and none)
        let (mut some, mut none) = (0, 0);
        for alpha in [1e-4, 0.05, 0.3, 0.8, 1.0] {
            let ndf = Ndf::new(NdfKind::Ggx, alpha).unwrap();
            for smith in [SmithForm::Separable, SmithForm::HeightCorrelated] {
                for mu in [1e-4f64, 0.2, 0.6, 0.9999, 1.0] {
                    let sin_v = (1.0 - mu * mu).sqrt();
                    let g1v = ndf.g1(mu);
                    for i in 0..40 {
                        for j in 0..24 {
                            let th = (i as f64 + 0.5) / 40.0 * std::f64::consts::FRAC_PI_2;
                            let ph = j as f64 / 23.0 * std::f64::consts::PI;
                            let m = MicroNormal {
                                n_dot_h: th.cos(),
                                sin2_h: th.sin() * th.sin(),
                                v_dot_h: sin_v * th.sin() * ph.cos() + mu * th.cos(),
                            };
                            let Some(f) = Facet::new(&ndf, smith, mu, g1v, &m) else {
                                continue;
                            };
                            let got =
                                GgxRefractions::<8>::new(&ndf, smith, g1v, mu, &etas).g(&f, &m);
                            for (k, &eta) in etas.iter().enumerate() {
                                let want = f
                                    .refraction(&ndf, smith, g1v, eta, mu, &m)
                                    .map_or(0.0, |(g, _)| g);
                                assert_eq!(
                                    got[k].to_bits(),
                                    want.to_bits(),
                                    "alpha {alpha} {smith:?} mu {mu} eta {eta} {m:?}"
                                );
                                if want > 0.0 {
                                    some += 1;
                                } else {
                                    none += 1;
                                }
                            }
                        }
                    }
                }
            }
        }
        assert!(
            some > 10_000 && none > 10_000,
            "{some} refractions, {none} none"
        );
    }

    /// [`SmithForm::ggx`] against [`SmithForm::g`] of two `Ndf::g1` over roughnesses from
    /// Cycles' clamp (α = 1e-8) to 1, cosines from 1e-9 to beyond 1, both forms: the same
    /// quantity rearranged, so equal to a few roundings (1e-14 relative; every term is
    /// positive, so no cancellation amplifies them), and exactly 0 where a cosine is ≤ 0.
    #[test]
    fn ggx_masking_in_one_division_is_the_composed_form() {
        let xs: [f64; 11] = [
            -0.5, 0.0, 1e-9, 1e-4, 0.01, 0.2, 0.5, 0.9, 0.999_999, 1.0, 1.2,
        ];
        for alpha in [1e-8, 1e-3, 0.1, 0.5, 0.9, 1.0] {
            let ndf = Ndf::new(NdfKind::Ggx, alpha).unwrap();
            for form in [SmithForm::Separable, SmithForm::HeightCorrelated] {
                for &nv in &xs {
                    for &nl in &xs {
                        let want = form.g(ndf.g1(nv.min(1.0)), ndf.g1(nl.min(1.0)));
                        let got = form.ggx(alpha * alpha, nv, nl);
                        assert!(
                            (got - want).abs() <= 1e-14 * want,
                            "{form:?} alpha {alpha} nv {nv} nl {nl}: {got} vs {want}"
                        );
                    }
                }
            }
        }
    }

    /// [`BelowOne`] against [`integrands_many`] and [`albedo_integrands`] over a grid of
    /// micro-normals, views, indices below 1, roughnesses and both masking forms. They are
    /// the same formulas rearranged (a shared square root, products by inverses, one
    /// division for F), so they may differ by a few roundings of values ≤ D·c/(n·v): the
    /// bound is 1e-12 relative to that scale.
    #[test]
    fn below_one_matches_integrands_many() {
        for &alpha in &[1e-3, 0.1, 0.5, 1.0] {
            let ndf = Ndf::new(NdfKind::Ggx, alpha).unwrap();
            for smith in [SmithForm::Separable, SmithForm::HeightCorrelated] {
                for &eta in &[1e-4, 0.3, 0.667, 0.95, 0.9999] {
                    for iv in 1..8 {
                        let mu = iv as f64 / 8.0;
                        let sin_v = (1.0 - mu * mu).sqrt();
                        let g1v = ndf.g1(mu);
                        let b = BelowOne::new(eta, mu, g1v);
                        for ih in 0..24 {
                            let th = ih as f64 / 24.0 * 1.5;
                            for ip in 0..12 {
                                let cp = (ip as f64 / 11.0 * std::f64::consts::PI).cos();
                                let m = MicroNormal {
                                    n_dot_h: th.cos(),
                                    sin2_h: th.sin() * th.sin(),
                                    v_dot_h: sin_v * th.sin() * cp + mu * th.cos(),
                                };
                                let old = integrands_many::<2>(&ndf, smith, &[eta], mu, g1v, &m);
                                let alb = albedo_integrands::<1>(&ndf, smith, &[eta], mu, g1v, &m);
                                let new = b.integrands(&ndf, smith, &m);
                                let scale = ndf.d_cs(m.n_dot_h, m.sin2_h) * m.v_dot_h.abs() / mu;
                                for (x, y) in [
                                    (old[0], new[0]),
                                    (old[1], new[1]),
                                    (alb[0], new[0] + new[1]),
                                ] {
                                    let e = (x - y).abs() / scale.max(1e-300);
                                    assert!(
                                        e <= 1e-12,
                                        "{alpha} {smith:?} {eta} {mu} {th} {cp}: {x} vs {y}"
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }
}
