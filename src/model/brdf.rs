//! BRDF composition: a microfacet specular lobe plus an optional diffuse lobe,
//! `f = w_s·D·G·F/(4 (n·l)(n·v)) + (w_d/π)·k` — the modern form, with `k` = 1 (Lambert) or
//! Burley's factor ([`DiffuseLobe`]). The lecture's Cook–Torrance
//! `k_d/π + k_s·(1/π)·F·D_CT·G/((n·l)(n·v))` is the same BRDF with D = (4/π)·D_CT.

use super::diffuse::DiffuseLobe;
use super::fresnel::Fresnel;
use super::masking::Masking;
use super::ndf::Ndf;
use crate::hemisphere::{LobeWarp, Node};
use std::f64::consts::PI;

/// A microfacet specular lobe.
#[derive(Clone, Debug)]
pub struct Specular {
    pub ndf: Ndf,
    pub masking: Masking,
    pub fresnel: Fresnel,
}

impl Specular {
    /// The warp the hemisphere quadrature should use for this lobe: the NDF's, with the
    /// θh range split at the V-groove term's kinks when that is the masking term.
    pub fn warp(&self) -> LobeWarp {
        match (self.masking, self.ndf.warp()) {
            (Masking::VGroove, LobeWarp::TanOverScale(s)) => LobeWarp::TanOverScaleVGroove(s),
            (_, w) => w,
        }
    }

    /// Builds now whatever the masking term will build lazily (the numeric Smith G1 of an
    /// NDF without a closed-form Λ), so that a table driver can do it once per roughness,
    /// in parallel, before the texel loop. Maskings that do not use Smith G1 (V-groove,
    /// Ashikhmin, none) build nothing: sheen's Charlie NDF has no use for its Λ, whose
    /// numeric derivation is slow for near-delta lobes.
    pub fn prepare(&self) {
        if matches!(
            self.masking,
            Masking::SmithSeparable | Masking::SmithHeightCorrelated
        ) {
            self.ndf.g1(0.5);
        }
    }

    /// `f(v, l)·(n·l)` at a half-vector node: `D·G·F/(4 n·v)` (the n·l cancels, which keeps
    /// the integrand finite at the horizon).
    #[inline]
    pub fn cosine_weighted(&self, n: &Node) -> f64 {
        self.cosine_weighted_with(n, self.fresnel.eval(n.v_dot_h))
    }

    /// As [`Specular::cosine_weighted`] with the Fresnel factor supplied by the caller (the
    /// split-sum tables weight F = 1 by Schlick's (1 − v·h)⁵ themselves).
    #[inline]
    pub fn cosine_weighted_with(&self, n: &Node, f: f64) -> f64 {
        let d = self.ndf.d_cs(n.n_dot_h, n.sin2_h);
        if d == 0.0 {
            return 0.0;
        }
        let g = self
            .masking
            .g(&self.ndf, n.n_dot_v, n.n_dot_l, n.n_dot_h, n.v_dot_h);
        d * g * f / (4.0 * n.n_dot_v)
    }

    /// The BRDF value for unit vectors v and l (normal = +z); 0 below the horizon.
    pub fn eval(&self, v: [f64; 3], l: [f64; 3]) -> f64 {
        let (nv, nl) = (v[2], l[2]);
        if nv <= 0.0 || nl <= 0.0 {
            return 0.0;
        }
        let hs = [v[0] + l[0], v[1] + l[1], v[2] + l[2]];
        let len = (hs[0] * hs[0] + hs[1] * hs[1] + hs[2] * hs[2]).sqrt();
        if len == 0.0 {
            return 0.0;
        }
        let h = [hs[0] / len, hs[1] / len, hs[2] / len];
        let vh = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
        let node = Node {
            n_dot_v: nv,
            n_dot_l: nl,
            n_dot_h: h[2],
            v_dot_h: vh,
            sin2_h: h[0] * h[0] + h[1] * h[1],
        };
        self.cosine_weighted(&node) / nl
    }
}

/// A complete BRDF.
#[derive(Clone, Debug)]
pub struct Brdf {
    pub specular: Option<Specular>,
    /// Weight `w_d` of the diffuse lobe `(w_d/π)·k` (0: none).
    pub diffuse_weight: f64,
    /// The diffuse lobe's shape `k`: Lambert (1) or Burley's.
    pub diffuse: DiffuseLobe,
}

impl Brdf {
    pub fn eval(&self, v: [f64; 3], l: [f64; 3]) -> f64 {
        if v[2] <= 0.0 || l[2] <= 0.0 {
            return 0.0;
        }
        let s = self.specular.as_ref().map_or(0.0, |s| s.eval(v, l));
        match self.diffuse {
            DiffuseLobe::Lambert => s + self.diffuse_weight / PI,
            d => {
                // v·h with h = (v + l)/|v + l|: v·h = √((1 + v·l)/2)
                let vl = v[0] * l[0] + v[1] * l[1] + v[2] * l[2];
                let vh = (0.5 * (1.0 + vl)).max(0.0).sqrt();
                s + self.diffuse_weight / PI * d.factor(v[2], l[2], vh)
            }
        }
    }

    /// The diffuse lobe's `f_d·(n·l)` at a half-vector node: `(w_d/π)·(n·l)` for Lambert
    /// (this expression, so that the integrands keep their bits), times Burley's factor.
    #[inline]
    pub fn diffuse_cosine_weighted(&self, n: &Node) -> f64 {
        let wd = self.diffuse_weight / PI;
        match self.diffuse {
            DiffuseLobe::Lambert => wd * n.n_dot_l,
            d => wd * n.n_dot_l * d.factor(n.n_dot_v, n.n_dot_l, n.v_dot_h),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ndf::NdfKind;

    fn dir(theta: f64, phi: f64) -> [f64; 3] {
        [
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ]
    }

    /// Helmholtz reciprocity f(v, l) = f(l, v) for every NDF × reciprocal masking × Fresnel, at a
    /// spread of direction pairs (all terms are symmetric in v and l analytically, so the
    /// only difference is rounding: relative 1e-12).
    #[test]
    fn every_combination_is_reciprocal() {
        let fresnels = [
            Fresnel::None,
            Fresnel::Schlick { f0: 0.04 },
            Fresnel::Dielectric { eta: 1.5 },
            Fresnel::Conductor { eta: 0.2, k: 3.0 },
        ];
        for kind in NdfKind::ALL {
            let ndf = Ndf::new(kind, 0.35).unwrap();
            // (the softened Conty–Kulla term is not reciprocal, on purpose)
            for masking in Masking::ALL.into_iter().filter(|m| m.is_reciprocal()) {
                for fresnel in fresnels {
                    let brdf = Brdf {
                        specular: Some(Specular {
                            ndf: ndf.clone(),
                            masking,
                            fresnel,
                        }),
                        diffuse_weight: 0.3,
                        diffuse: crate::model::DiffuseLobe::Lambert,
                    };
                    for &(tv, pv, tl, pl) in &[
                        (0.3, 0.0, 1.1, 2.0),
                        (1.4, 0.5, 0.2, 3.0),
                        (0.9, 1.0, 0.9, -1.0),
                    ] {
                        let (v, l) = (dir(tv, pv), dir(tl, pl));
                        let (a, b) = (brdf.eval(v, l), brdf.eval(l, v));
                        assert!(
                            (a - b).abs() <= 1e-12 * a.abs().max(1.0),
                            "{kind:?} {masking:?} {fresnel:?}: {a} {b}"
                        );
                    }
                }
            }
        }
    }
}
