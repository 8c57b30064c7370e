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
