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

/// The shape of a rule: composite Gauss–Legendre, `phi_panels` equal panels of
/// `phi_order` nodes in φ's variable and `u_panels` of `u_order` in the inner one, built
/// once and shared by every texel of a table. A cell is one φ panel × one inner panel.
#[derive(Clone, Debug)]
pub struct RuleShape {
    phi: (Vec<f64>, Vec<f64>),
    u: (Vec<f64>, Vec<f64>),
    phi_panels: usize,
    u_panels: usize,
}

impl RuleShape {
    /// A composite rule (each count at least 1, orders at least 2).
    pub fn new(phi_panels: usize, phi_order: usize, u_panels: usize, u_order: usize) -> RuleShape {
        RuleShape {
            phi: gauss_legendre(phi_order.max(2)),
            u: gauss_legendre(u_order.max(2)),
            phi_panels: phi_panels.max(1),
            u_panels: u_panels.max(1),
        }
    }

    /// Nodes per rule.
    pub fn len(&self) -> usize {
        self.phi.0.len() * self.u.0.len() * self.phi_panels * self.u_panels
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// `(φ panels, inner panels)`: the cells of the rule.
    pub fn cells(&self) -> (usize, usize) {
        (self.phi_panels, self.u_panels)
    }

    /// The composite rule's nodes on [0, 1] with weights, and the panel of each.
    fn composite(gl: &(Vec<f64>, Vec<f64>), panels: usize) -> Vec<(f64, f64, usize)> {
        let h = 1.0 / panels as f64;
        let mut out = Vec::with_capacity(gl.0.len() * panels);
        for p in 0..panels {
            for (&x, &w) in gl.0.iter().zip(&gl.1) {
                out.push((h * (p as f64 + 0.5 * (x + 1.0)), 0.5 * h * w, p));
            }
        }
        out
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
    /// The cell of each node, `φ panel × u_panels + inner panel`.
    pub cells: Vec<u32>,
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
        let phis = RuleShape::composite(&shape.phi, shape.phi_panels);
        let us = RuleShape::composite(&shape.u, shape.u_panels);
        for &(x01, wx, pp) in &phis {
            // s ∈ [−S, S]
            let s = pw.big_s * (2.0 * x01 - 1.0);
            let phi = std::f64::consts::FRAC_PI_2 + pw.c * s.sinh();
            let dphi = pw.c * s.cosh() * 2.0 * pw.big_s * wx;
            let (sp, cp) = phi.sin_cos();
            let tmax = tan_theta_h_max(pw.tan_v, cp);
            let thmax = tmax.atan();
            for &(t01, wy, pu) in &us {
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
                // wy: the [0, 1] variable's weight; ×2 for the mirrored half
                let w = 2.0 * dphi * wy * dth * 4.0 * node.v_dot_h * sin_h;
                r.dirs.push(l);
                r.weights.push(w);
                r.nodes.push(node);
                r.cells.push((pp * shape.u_panels + pu) as u32);
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
        let shape = RuleShape::new(4, 8, 4, 12);
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
