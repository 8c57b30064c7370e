//! Masking–shadowing terms G(v, l, h).
//!
//! All are expressed as the G of `f = D·G·F / (4 (n·l)(n·v))`, so a visibility term
//! `V = G / (4 (n·l)(n·v))` (as sheen models and real-time engines write it) is converted.

use super::ndf::Ndf;

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
}

impl Masking {
    pub const ALL: [Masking; 5] = [
        Masking::None,
        Masking::VGroove,
        Masking::SmithSeparable,
        Masking::SmithHeightCorrelated,
        Masking::Ashikhmin,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Masking::None => "none",
            Masking::VGroove => "v-groove",
            Masking::SmithSeparable => "smith-separable",
            Masking::SmithHeightCorrelated => "smith-height-correlated",
            Masking::Ashikhmin => "ashikhmin",
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
        }
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
    use crate::model::ndf::NdfKind;

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

    /// G is symmetric in v and l for every term (needed for reciprocity).
    #[test]
    fn masking_is_symmetric() {
        let ndf = Ndf::new(NdfKind::Ggx, 0.4).unwrap();
        for m in Masking::ALL {
            let a = m.g(&ndf, 0.3, 0.8, 0.9, 0.7);
            let b = m.g(&ndf, 0.8, 0.3, 0.9, 0.7);
            assert!((a - b).abs() < 1e-15, "{m:?}");
            assert!((0.0..=1.0).contains(&a), "{m:?} {a}");
        }
    }
}
