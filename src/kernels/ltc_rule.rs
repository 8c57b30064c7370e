//! The fixed quadrature rule over the outgoing hemisphere on which an LTC fit compares the
//! BRDF with the LTC: nodes, solid-angle weights, directions and the half-vector [`Node`]s
//! that a BRDF is evaluated at (once per texel).
//!
//! It is the hemisphere integrator's parameterization (see [`crate::hemisphere`]) with fixed
//! Gauss–Legendre rules instead of adaptive ones: the half vector `h = (θh, φ)`, `φ ∈ [0, π]`
//! (the `y < 0` half mirrors it: weights doubled), `θh` up to the exact horizon limit
//! `θmax(φ)`, and `dω_l = 4(v·h) sin θh dθh dφ` (Walter et al. 2007, eq. 14).
//! * φ: `φ = π/2 + c·sinh s` with `c = min(cot θv, 1)` (the fast path's warp,
//!   `hemisphere::tensor`), which gathers nodes where the horizon limit swings at
//!   grazing views.
//! * θh: the lobe's warp ([`LobeWarp`]): `u = asinh(tan θh / s)` for lobes at the normal,
//!   which spaces the nodes about evenly in `ln θh` from `θh ~ s` out to the horizon — the
//!   peak *and* the tails, each scale of angular distance getting its share, which is what
//!   a relative error measure over lights of every size and place needs; θh itself for wide
//!   sheen; `θh = θmax − w·sinh u` for narrow sheen, whose lobe leans on the horizon.
//!
//! A fixed rule makes the objective a smooth, deterministic function of the LTC's
//! parameters (an adaptive rule would move its nodes as they change).

use crate::hemisphere::tensor::PhiWarp;
use crate::hemisphere::{tan_theta_h_max, LobeWarp, Node};
use crate::quadrature::gauss::gauss_legendre;

/// Gauss–Legendre tables for a rule of `n_phi × n_u` nodes, built once and shared by every
/// texel of a table.
#[derive(Clone, Debug)]
pub struct RuleShape {
    phi: (Vec<f64>, Vec<f64>),
    u: (Vec<f64>, Vec<f64>),
}

impl RuleShape {
    /// `n_phi` nodes in φ over [0, π], `n_u` in the inner variable (both ≥ 2).
    pub fn new(n_phi: usize, n_u: usize) -> RuleShape {
        RuleShape {
            phi: gauss_legendre(n_phi.max(2)),
            u: gauss_legendre(n_u.max(2)),
        }
    }

    /// Nodes per rule.
    pub fn len(&self) -> usize {
        self.phi.0.len() * self.u.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The nodes of one texel's rule (view cosine μ, lobe warp).
#[derive(Clone, Debug, Default)]
pub struct HemisphereRule {
    /// Outgoing directions `l` (unit; normal +z, view in the xz-plane at positive x).
    pub dirs: Vec<[f64; 3]>,
    /// Solid-angle weights (for the whole hemisphere: the mirrored half included).
    pub weights: Vec<f64>,
    /// The half-vector nodes, for BRDFs written as functions of [`Node`].
    pub nodes: Vec<Node>,
}

impl HemisphereRule {
    /// The rule for view cosine `mu` ∈ (0, 1] and lobe warp `warp`. Nodes whose `l` would
    /// fall on or below the horizon (rounding at the limit) are left out.
    pub fn new(shape: &RuleShape, mu: f64, warp: LobeWarp) -> HemisphereRule {
        let pw = PhiWarp::new(mu);
        let (mu_v, sin_v) = (pw.mu_v, pw.sin_v);
        let v = [sin_v, 0.0, mu_v];
        let mut r = HemisphereRule::default();
        let n = shape.len();
        r.dirs.reserve(n);
        r.weights.reserve(n);
        r.nodes.reserve(n);
        let (xs, ws) = (&shape.phi.0, &shape.phi.1);
        let (xu, wu) = (&shape.u.0, &shape.u.1);
        for (&x, &wx) in xs.iter().zip(ws) {
            // s ∈ [−S, S]
            let s = pw.big_s * x;
            let phi = std::f64::consts::FRAC_PI_2 + pw.c * s.sinh();
            let dphi = pw.c * s.cosh() * pw.big_s * wx;
            let (sp, cp) = phi.sin_cos();
            let tmax = tan_theta_h_max(pw.tan_v, cp);
            let thmax = tmax.atan();
            for (&y, &wy) in xu.iter().zip(wu) {
                let t01 = 0.5 * (y + 1.0);
                // (sin θh, cos θh, dθh per unit of the [0, 1] variable)
                let (sin_h, cos_h, dth) = match warp {
                    LobeWarp::TanOverScale(sc) | LobeWarp::TanOverScaleVGroove(sc) => {
                        let umax = (tmax / sc).asinh();
                        let u = umax * t01;
                        let t = sc * u.sinh();
                        let c2 = 1.0 / (1.0 + t * t);
                        let ch = c2.sqrt();
                        (t * ch, ch, sc * u.cosh() * c2 * umax)
                    }
                    LobeWarp::SheenFlank(alpha) => {
                        let w = (alpha * tmax).min(alpha.sqrt());
                        let umax = (thmax / w).asinh();
                        let u = umax * t01;
                        let th = (thmax - w * u.sinh()).max(0.0);
                        let (sh, ch) = th.sin_cos();
                        (sh, ch, w * u.cosh() * umax)
                    }
                    LobeWarp::Linear => {
                        let th = thmax * t01;
                        let (sh, ch) = th.sin_cos();
                        (sh, ch, thmax)
                    }
                };
                let node = Node::at(mu_v, sin_v, cp, sin_h, cos_h);
                if node.n_dot_l <= 0.0 || node.v_dot_h <= 0.0 {
                    continue;
                }
                let h = [sin_h * cp, sin_h * sp, cos_h];
                let k = 2.0 * node.v_dot_h;
                let l = [k * h[0] - v[0], k * h[1] - v[1], k * h[2] - v[2]];
                // renormalize (|l| = 1 up to rounding) and take n·l from the node, which
                // computes it without cancellation near the horizon
                let len = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
                let l = [l[0] / len, l[1] / len, node.n_dot_l];
                // 0.5·wy: the [0, 1] variable's Gauss weight; ×2 for the mirrored half
                let w = 2.0 * dphi * 0.5 * wy * dth * 4.0 * node.v_dot_h * sin_h;
                r.dirs.push(l);
                r.weights.push(w);
                r.nodes.push(node);
            }
        }
        r
    }

    pub fn len(&self) -> usize {
        self.dirs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.dirs.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The weights add up to the hemisphere's solid angle 2π, and Σ w·n·l to π, at every
    /// view and warp (Gauss rules on smooth integrands; 32 × 48 nodes: relative 1e-6).
    #[test]
    fn weights_integrate_the_hemisphere() {
        let shape = RuleShape::new(32, 48);
        for mu in [1.0, 0.7, 0.2, 0.01] {
            for warp in [
                LobeWarp::TanOverScale(0.3),
                LobeWarp::TanOverScale(1.0),
                LobeWarp::Linear,
            ] {
                let r = HemisphereRule::new(&shape, mu, warp);
                let sa: f64 = r.weights.iter().sum();
                let proj: f64 = r.weights.iter().zip(&r.dirs).map(|(w, l)| w * l[2]).sum();
                let tp = 2.0 * std::f64::consts::PI;
                assert!((sa / tp - 1.0).abs() < 1e-4, "{mu} {warp:?}: {sa}");
                assert!(
                    (proj / std::f64::consts::PI - 1.0).abs() < 1e-4,
                    "{mu} {warp:?}: {proj}"
                );
            }
        }
    }
}
