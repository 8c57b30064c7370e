//! Masking–shadowing terms G(v, l, h).
//!
//! All are expressed as the G of `f = D·G·F / (4 (n·l)(n·v))`, so a visibility term
//! `V = G / (4 (n·l)(n·v))` (as sheen models and real-time engines write it) is converted.

use super::ndf::{Ndf, NdfKind};

/// Which masking–shadowing term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Masking {
    /// No masking, G = 1.
    None,
    /// Cook & Torrance (1982), eq. 6: the V-groove term
    /// `G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h))` (Torrance & Sparrow 1967).
    VGroove,
    /// Smith, separable: `G2 = G1(v)·G1(l)` (Heitz 2014, eq. 98).
    SmithSeparable,
    /// Smith, height-correlated: `G2 = 1/(1 + Λ(v) + Λ(l))` (Heitz 2014, eq. 99).
    SmithHeightCorrelated,
    /// Ashikhmin's sheen visibility in the simplified form of Neubelt & Pettineo (2013):
    /// `V = 1/(4(n·l + n·v − (n·l)(n·v)))`, i.e. `G = (n·l)(n·v)/(n·l + n·v − (n·l)(n·v))`.
    Ashikhmin,
    /// Schlick's approximation of Smith's G1 for GGX, separable, with `k = α/2`
    /// ([`SchlickGgx::ibl`]): Karis 2013 for image-based lighting, Unreal's
    /// PreIntegratedGF, LearnOpenGL's BRDF LUT. GGX only.
    SchlickGgx,
    /// The same with `k = (r + 1)²/8`, `r = √α` ([`SchlickGgx::direct`]): Karis' remap
    /// for analytic lights. GGX only.
    SchlickGgxDirect,
    /// Conty Estevez & Kulla's sheen shadowing `G2 = 1/(1 + Λ(n·v) + Λ(n·l))` with their
    /// fitted Λ ([`ContyKullaLambda`]), as KHR_materials_sheen and the glTF Sample Viewer
    /// use it. Charlie only.
    ContyKulla,
    /// The same with BSDL's terminator softening on the light side,
    /// `G2 = 1/(1 + Λ(n·v) + Λ(n·l)^{1 + 2(1 − n·l)⁸})` ([`ContyKullaLambda::softened`]):
    /// not reciprocal (on purpose). Charlie only.
    ContyKullaSoftened,
}

impl Masking {
    pub const ALL: [Masking; 9] = [
        Masking::None,
        Masking::VGroove,
        Masking::SmithSeparable,
        Masking::SmithHeightCorrelated,
        Masking::Ashikhmin,
        Masking::SchlickGgx,
        Masking::SchlickGgxDirect,
        Masking::ContyKulla,
        Masking::ContyKullaSoftened,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Masking::None => "none",
            Masking::VGroove => "v-groove",
            Masking::SmithSeparable => "smith-separable",
            Masking::SmithHeightCorrelated => "smith-height-correlated",
            Masking::Ashikhmin => "ashikhmin",
            Masking::SchlickGgx => "schlick-ggx",
            Masking::SchlickGgxDirect => "schlick-ggx-direct",
            Masking::ContyKulla => "conty-kulla",
            Masking::ContyKullaSoftened => "conty-kulla-softened",
        }
    }

    pub fn formula(self) -> &'static str {
        match self {
            Masking::None => "G = 1",
            Masking::VGroove => "G = min(1, 2(n.h)(n.v)/(v.h), 2(n.h)(n.l)/(v.h))",
            Masking::SmithSeparable => "G = G1(v) G1(l), G1 = 1/(1 + Lambda)",
            Masking::SmithHeightCorrelated => "G = 1/(1 + Lambda(v) + Lambda(l))",
            Masking::Ashikhmin => {
                "G = (n.l)(n.v)/(n.l + n.v - (n.l)(n.v))  [V = 1/(4(n.l + n.v - (n.l)(n.v)))]"
            }
            Masking::SchlickGgx => "G = G1(n.v) G1(n.l), G1(mu) = mu/(mu (1 - k) + k), k = alpha/2",
            Masking::SchlickGgxDirect => {
                "G = G1(n.v) G1(n.l), G1(mu) = mu/(mu (1 - k) + k), k = (sqrt(alpha) + 1)^2/8"
            }
            Masking::ContyKulla => CONTY_KULLA_FORMULA,
            Masking::ContyKullaSoftened => CONTY_KULLA_SOFTENED_FORMULA,
        }
    }

    pub fn source(self) -> &'static str {
        match self {
            Masking::None => "-",
            Masking::VGroove => "Torrance & Sparrow 1967; Cook & Torrance 1982, eq. 6",
            Masking::SmithSeparable => {
                "Smith 1967; Heitz 2014, 'Understanding the Masking-Shadowing Function', eq. 98"
            }
            Masking::SmithHeightCorrelated => {
                "Heitz 2014, 'Understanding the Masking-Shadowing Function', eq. 99"
            }
            Masking::Ashikhmin => "Ashikhmin et al. 2000; Neubelt & Pettineo 2013",
            Masking::SchlickGgx => {
                "Schlick 1994; k = alpha/2: Karis 2013, 'Real Shading in Unreal Engine 4' (image-based lighting; Unreal's PreIntegratedGF, LearnOpenGL's BRDF LUT)"
            }
            Masking::SchlickGgxDirect => {
                "Schlick 1994; k = (r + 1)^2/8: Karis 2013, 'Real Shading in Unreal Engine 4' (analytic lights, Disney's roughness remap)"
            }
            Masking::ContyKulla => {
                "Estevez & Kulla 2017, 'Production Friendly Microfacet Sheen BRDF' (fitted Lambda); coefficients as in KHR_materials_sheen and BSDL's ContyKullaSheen"
            }
            Masking::ContyKullaSoftened => {
                "Estevez & Kulla 2017 (fitted Lambda) with the terminator softening of BSDL's ContyKullaSheen (OpenShadingLanguage src/libbsdl)"
            }
        }
    }

    /// The NDF this term is defined for, if only one: Schlick-GGX's k fits Smith's G1 of
    /// GGX (Karis 2013), Conty–Kulla's Λ is fitted to the Charlie sheen NDF.
    pub fn only_for(self) -> Option<NdfKind> {
        match self {
            Masking::SchlickGgx | Masking::SchlickGgxDirect => Some(NdfKind::Ggx),
            Masking::ContyKulla | Masking::ContyKullaSoftened => Some(NdfKind::Charlie),
            _ => None,
        }
    }

    /// Whether G is a function of (n·v, n·l) alone (every term but the V-groove one).
    pub fn of_cosines_alone(self) -> bool {
        self != Masking::VGroove
    }

    /// Whether `G(v, l) = G(l, v)` (every term but the softened Conty–Kulla one).
    pub fn is_reciprocal(self) -> bool {
        self != Masking::ContyKullaSoftened
    }

    /// The term's separable Schlick-GGX G1 at NDF parameter α, for the Schlick-GGX terms.
    pub fn schlick(self, alpha: f64) -> Option<SchlickGgx> {
        match self {
            Masking::SchlickGgx => Some(SchlickGgx::ibl(alpha)),
            Masking::SchlickGgxDirect => Some(SchlickGgx::direct(alpha)),
            _ => None,
        }
    }

    /// Whether the term uses the NDF's Smith Λ.
    pub fn is_smith(self) -> bool {
        matches!(
            self,
            Masking::SmithSeparable | Masking::SmithHeightCorrelated
        )
    }

    /// G for the given cosines (all assumed > 0 except where stated).
    #[inline]
    pub fn g(self, ndf: &Ndf, n_dot_v: f64, n_dot_l: f64, n_dot_h: f64, v_dot_h: f64) -> f64 {
        match self {
            Masking::None => 1.0,
            Masking::VGroove => vgroove(n_dot_v, n_dot_l, n_dot_h, v_dot_h),
            Masking::SmithSeparable => ndf.g1(n_dot_v) * ndf.g1(n_dot_l),
            Masking::SmithHeightCorrelated => {
                if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
                    return 0.0;
                }
                1.0 / (1.0 + ndf.lambda(n_dot_v) + ndf.lambda(n_dot_l))
            }
            Masking::Ashikhmin => {
                let d = n_dot_l + n_dot_v - n_dot_l * n_dot_v;
                if d <= 0.0 {
                    0.0
                } else {
                    n_dot_l * n_dot_v / d
                }
            }
            Masking::SchlickGgx | Masking::SchlickGgxDirect => {
                let s = self.schlick(ndf.alpha()).expect("a Schlick-GGX term");
                s.g1(n_dot_v) * s.g1(n_dot_l)
            }
            Masking::ContyKulla | Masking::ContyKullaSoftened => {
                if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
                    return 0.0;
                }
                let cl = ContyKullaLambda::new(ndf.alpha());
                let light = if self == Masking::ContyKullaSoftened {
                    cl.softened(n_dot_l)
                } else {
                    cl.lambda(n_dot_l)
                };
                1.0 / (1.0 + cl.lambda(n_dot_v) + light)
            }
        }
    }
}

/// Schlick's approximation of Smith's G1 (Schlick 1994, "An Inexpensive BRDF Model for
/// Physically-based Rendering", eq. 19): `G1(μ) = μ/(μ(1 − k) + k)`, used separably,
/// `G = G1(n·v) G1(n·l)`. Karis (2013, "Real Shading in Unreal Engine 4", p. 3) fits
/// k to Smith's G1 of GGX: `k = α/2` ("with this modification, the Schlick model exactly
/// matches Smith for α = 1"), and for analytic lights remaps the roughness first,
/// `α' = ((r + 1)/2)²`, i.e. `k = (r + 1)²/8` ("only used for analytic light sources").
/// LearnOpenGL's IBL tutorial writes `k = r²/2` with r the perceptual roughness (= α/2)
/// for its BRDF LUT and `k = (r + 1)²/8` for direct light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchlickGgx {
    pub k: f64,
}

impl SchlickGgx {
    /// `k = α/2`: image-based lighting (Karis 2013).
    pub fn ibl(alpha: f64) -> SchlickGgx {
        SchlickGgx { k: 0.5 * alpha }
    }

    /// `k = (√α + 1)²/8`: analytic lights (Karis 2013).
    pub fn direct(alpha: f64) -> SchlickGgx {
        let r1 = alpha.max(0.0).sqrt() + 1.0;
        SchlickGgx { k: 0.125 * r1 * r1 }
    }

    /// `G1(μ) = μ/(μ(1 − k) + k)`; 0 for μ ≤ 0 (and 1 for μ > 0 when k = 0, the α = 0
    /// limit of the image-based form).
    #[inline]
    pub fn g1(self, mu: f64) -> f64 {
        if mu <= 0.0 {
            return 0.0;
        }
        mu / (mu * (1.0 - self.k) + self.k)
    }
}

const CONTY_KULLA_FORMULA: &str = "G = 1/(1 + Lambda(n.v) + Lambda(n.l)); Lambda(mu) = exp(L(mu)) for mu < 0.5, exp(2 L(0.5) - L(1 - mu)) otherwise; L(x) = a/(1 + b x^c) + d x + e, (a, b, c, d, e) = (1 - t)(21.5473, 3.82987, 0.19823, -1.97760, -4.32054) + t (25.3245, 3.32435, 0.16801, -1.27393, -4.85967), t = (1 - alpha)^2";
const CONTY_KULLA_SOFTENED_FORMULA: &str = "G = 1/(1 + Lambda(n.v) + Lambda(n.l)^(1 + 2 (1 - n.l)^8)) (light side softened, not reciprocal); Lambda(mu) = exp(L(mu)) for mu < 0.5, exp(2 L(0.5) - L(1 - mu)) otherwise; L(x) = a/(1 + b x^c) + d x + e, (a, b, c, d, e) = (1 - t)(21.5473, 3.82987, 0.19823, -1.97760, -4.32054) + t (25.3245, 3.32435, 0.16801, -1.27393, -4.85967), t = (1 - alpha)^2";

/// Conty Estevez & Kulla's fitted Smith Λ of the Charlie sheen NDF (Estevez & Kulla 2017,
/// "Production Friendly Microfacet Sheen BRDF", §3.2 and table 1): with
/// `L(x) = a/(1 + b·x^c) + d·x + e`,
/// `Λ(μ) = exp(L(μ))` for μ < 1/2 and `exp(2 L(1/2) − L(1 − μ))` above (symmetric about
/// μ = 1/2 in log space), the coefficients interpolated linearly in `t = (1 − α)²` between
/// their fits at α = 1 (t = 0) and α = 0 (t = 1), α the Charlie NDF's own parameter.
/// The same numbers are in KHR_materials_sheen ("Visibility: Charlie") and BSDL's
/// `ContyKullaSheen` (OpenShadingLanguage, `bsdf_sheen_impl.h`); BSDL's `softened` light
/// side is [`ContyKullaLambda::softened`]. Defined for α ∈ (0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContyKullaLambda {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    e: f64,
}

/// The fit at α = 1 (t = 0) and at α = 0 (t = 1).
const CK_AT_1: [f64; 5] = [21.5473, 3.82987, 0.19823, -1.97760, -4.32054];
const CK_AT_0: [f64; 5] = [25.3245, 3.32435, 0.16801, -1.27393, -4.85967];

impl ContyKullaLambda {
    /// The coefficients at Charlie parameter α (t = (1 − α)², clamped to [0, 1]).
    pub fn new(alpha: f64) -> ContyKullaLambda {
        let t = ((1.0 - alpha) * (1.0 - alpha)).clamp(0.0, 1.0);
        let k = |i: usize| (1.0 - t) * CK_AT_1[i] + t * CK_AT_0[i];
        ContyKullaLambda {
            a: k(0),
            b: k(1),
            c: k(2),
            d: k(3),
            e: k(4),
        }
    }

    /// `L(x) = a/(1 + b x^c) + d x + e`.
    #[inline]
    fn l(&self, x: f64) -> f64 {
        self.a / (1.0 + self.b * x.powf(self.c)) + self.d * x + self.e
    }

    /// Λ(μ) for μ ∈ [0, 1] (values above 1 are taken as 1; Λ(0) = e^{a + e} is finite).
    #[inline]
    pub fn lambda(&self, mu: f64) -> f64 {
        let mu = mu.clamp(0.0, 1.0);
        if mu < 0.5 {
            self.l(mu).exp()
        } else {
            (2.0 * self.l(0.5) - self.l(1.0 - mu)).exp()
        }
    }

    /// BSDL's terminator softening of the light side, `Λ(μ)^{1 + 2(1 − μ)⁸}`.
    #[inline]
    pub fn softened(&self, mu: f64) -> f64 {
        let mu = mu.clamp(0.0, 1.0);
        let w = (1.0 - mu).powi(8);
        self.lambda(mu).powf(1.0 + 2.0 * w)
    }

    /// `G1(μ) = 1/(1 + Λ(μ))`.
    pub fn g1(&self, mu: f64) -> f64 {
        1.0 / (1.0 + self.lambda(mu))
    }
}

/// Cook–Torrance's V-groove G, as the lecture writes it: a function of n·l, n·h, n·v and
/// v·h (= l·h).
#[inline]
pub fn vgroove(n_dot_v: f64, n_dot_l: f64, n_dot_h: f64, v_dot_h: f64) -> f64 {
    if v_dot_h <= 0.0 {
        return 0.0;
    }
    let gv = 2.0 * n_dot_h * n_dot_v / v_dot_h;
    let gl = 2.0 * n_dot_h * n_dot_l / v_dot_h;
    1.0f64.min(gv).min(gl).max(0.0)
}

/// The V-groove G from the three cosines of the lecture's signature G(n·l, n·h, n·v):
/// with h the half vector, |l + v| = 2(v·h) and n·h = (n·l + n·v)/|l + v|, so
/// `v·h = (n·l + n·v)/(2 n·h)`. Returns `(G, realizable)`, where `realizable` says whether
/// some pair of unit vectors l, v has these cosines (v·h ≤ 1 and l·v = 2(v·h)² − 1 within
/// [cos(θl + θv), cos(θl − θv)]).
pub fn vgroove_from_cosines(n_dot_l: f64, n_dot_h: f64, n_dot_v: f64) -> (f64, bool) {
    let v_dot_h = (n_dot_l + n_dot_v) / (2.0 * n_dot_h);
    let g = vgroove(n_dot_v, n_dot_l, n_dot_h, v_dot_h);
    let l_dot_v = 2.0 * v_dot_h * v_dot_h - 1.0;
    let (sl, sv) = (
        (1.0 - n_dot_l * n_dot_l).max(0.0).sqrt(),
        (1.0 - n_dot_v * n_dot_v).max(0.0).sqrt(),
    );
    let lo = n_dot_l * n_dot_v - sl * sv; // cos(θl + θv)
    let hi = n_dot_l * n_dot_v + sl * sv; // cos(θl − θv)
    let eps = 1e-12;
    let ok = v_dot_h <= 1.0 + eps && l_dot_v >= lo - eps && l_dot_v <= hi + eps;
    (g, ok)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From explicit vectors: the cosine-only form equals the vector form.
    #[test]
    fn vgroove_from_cosines_matches_vectors() {
        let v = [0.6f64, 0.0, 0.8];
        for &(lx, ly) in &[(-0.3f64, 0.2f64), (0.1, -0.7), (-0.9, 0.1)] {
            let lz = (1.0 - lx * lx - ly * ly).sqrt();
            let l = [lx, ly, lz];
            let hs = [v[0] + l[0], v[1] + l[1], v[2] + l[2]];
            let len = (hs[0] * hs[0] + hs[1] * hs[1] + hs[2] * hs[2]).sqrt();
            let h = [hs[0] / len, hs[1] / len, hs[2] / len];
            let vh = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
            let g = vgroove(v[2], l[2], h[2], vh);
            let (g2, ok) = vgroove_from_cosines(l[2], h[2], v[2]);
            assert!(ok);
            assert!((g - g2).abs() < 1e-14);
        }
        // an impossible triple: n·h smaller than both n·l and n·v allow
        let (_, ok) = vgroove_from_cosines(0.9, 0.1, 0.9);
        assert!(!ok);
    }

    /// G is symmetric in v and l for every term but the softened Conty–Kulla one (needed
    /// for reciprocity), which is not: it softens the light side only.
    #[test]
    fn masking_is_symmetric() {
        for kind in [NdfKind::Ggx, NdfKind::Charlie] {
            let ndf = Ndf::new(kind, 0.4).unwrap();
            for m in Masking::ALL {
                let a = m.g(&ndf, 0.3, 0.8, 0.9, 0.7);
                let b = m.g(&ndf, 0.8, 0.3, 0.9, 0.7);
                assert!((0.0..=1.0).contains(&a), "{m:?} {a}");
                if m.is_reciprocal() {
                    assert!((a - b).abs() < 1e-15, "{m:?}");
                } else {
                    assert!((a - b).abs() > 1e-3, "{m:?}: {a} {b}");
                }
            }
        }
    }

    /// Karis 2013: with k = α/2 "the Schlick model exactly matches Smith for α = 1":
    /// 2μ/(1 + μ) both (the Smith G1 of GGX is 2μ/(μ + √(α² + (1 − α²)μ²))); elsewhere
    /// they differ (by up to ~0.05 at α = 0.5, grazing), and the direct form's k is
    /// (√α + 1)²/8: 1/8 at α = 0, 1/2 at α = 1 (where both forms agree).
    #[test]
    fn schlick_ggx_matches_smith_at_alpha_one() {
        let smith = Ndf::new(NdfKind::Ggx, 1.0).unwrap();
        for i in 0..=100 {
            let mu = i as f64 / 100.0;
            let s = SchlickGgx::ibl(1.0).g1(mu);
            assert!((s - smith.g1(mu)).abs() < 1e-15, "mu {mu}: {s}");
            assert!((s - 2.0 * mu / (1.0 + mu)).abs() < 1e-15);
            assert_eq!(SchlickGgx::direct(1.0).g1(mu).to_bits(), s.to_bits());
        }
        assert_eq!(SchlickGgx::direct(0.0).k, 0.125);
        assert_eq!(SchlickGgx::direct(0.25).k, 0.28125); // (0.5 + 1)²/8
        let half = Ndf::new(NdfKind::Ggx, 0.5).unwrap();
        let gap = (1..100)
            .map(|i| {
                let mu = i as f64 / 100.0;
                (SchlickGgx::ibl(0.5).g1(mu) - half.g1(mu)).abs()
            })
            .fold(0.0, f64::max);
        assert!(gap > 1e-2 && gap < 0.1, "{gap}");
        // the α = 0 limit of the image-based form: G1 = 1 above the horizon, 0 on it
        assert_eq!(SchlickGgx::ibl(0.0).g1(1e-300), 1.0);
        assert_eq!(SchlickGgx::ibl(0.0).g1(0.0), 0.0);
    }

    /// The fitted Λ: its two branches meet at μ = 1/2 (the second is the first reflected
    /// in log space, so they agree there by construction: a typo in either would show),
    /// it falls monotonically from e^{a + e} at μ = 0 to e^{2L(1/2) − a − e} at μ = 1,
    /// and the coefficients are the published ones at α = 1 and α → 0 (t = 0, 1).
    #[test]
    fn conty_kulla_lambda_is_continuous_and_decreasing() {
        for alpha in [1e-6, 0.06, 0.3, 0.7, 1.0] {
            let cl = ContyKullaLambda::new(alpha);
            let below = cl.lambda(0.5 - 1e-12);
            let above = cl.lambda(0.5);
            assert!(
                (below - above).abs() <= 1e-9 * above,
                "{alpha}: {below} {above}"
            );
            let mut last = f64::INFINITY;
            for i in 0..=1000 {
                let l = cl.lambda(i as f64 / 1000.0);
                assert!(l.is_finite() && l > 0.0 && l < last, "{alpha} {i}: {l}");
                last = l;
            }
            assert!((cl.lambda(0.0) - (cl.a + cl.e).exp()).abs() <= 1e-12 * cl.lambda(0.0));
            // softening: Λ^(1 + 2(1 − μ)^8), the same at μ = 1, Λ³ at μ = 0
            assert_eq!(cl.softened(1.0), cl.lambda(1.0));
            let l0 = cl.lambda(0.0);
            assert!((cl.softened(0.0) - l0 * l0 * l0).abs() <= 1e-12 * l0 * l0 * l0);
        }
        assert_eq!(
            [ContyKullaLambda::new(1.0).a, ContyKullaLambda::new(1.0).e],
            [21.5473, -4.32054]
        );
        let c0 = ContyKullaLambda::new(1e-300);
        assert_eq!([c0.a, c0.b, c0.c, c0.d, c0.e], CK_AT_0);
    }
}
