//! Probe lights for the LTC fit: a fixed partition of the upper hemisphere into spherical
//! quads, the LTC's lit value of each in closed form with its gradient, and the BRDF's by a
//! fixed rule on each quad.
//!
//! Why: a rule of nodes sees the LTC only at its nodes, and a sheared LTC can put a narrow
//! ridge of mass where no node is (at grazing views, along the horizon on the viewer's side:
//! a ×10⁴ overestimate of the lights there that the nodes never saw). A probe's closed-form
//! integral sees every bit of mass inside it, however narrow, and is exactly what the user
//! measure is: the lit value of a polygonal light.
//!
//! **The probes** ([`probe_quads`]): elevation bands with edges at 0°, 3°, 8°, 15°, 25°, 40°,
//! 60°, 80° and 90° × 30° azimuth sectors over azimuths [0°, 180°] (the lobes are symmetric
//! in y, so the other half mirrors it); the top band's quads have two vertices at the pole,
//! a zero-length edge that the edge formula counts as 0.
//!
//! **Gradient.** The edge term `T(p, q) = θ·u_z/s` with `u = p × q`, `s = |u|`,
//! `c = p·q`, `θ = atan2(s, c)` has `dθ = (c·ds − s·dc)/(s² + c²)`, `ds = u·du/s`,
//! `du = dp × q + p × dq`, `dc = dp·q + p·dq`, so `dT = (u_z/s)·dθ + θ·(du_z − u_z·ds/s)/s`
//! (derived here).

use crate::hemisphere::Node;
use crate::model::ltc::Ltc;
use crate::quadrature::gauss::gauss_legendre;
use std::f64::consts::PI;

#[inline]
fn cross(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    [
        p[1] * q[2] - p[2] * q[1],
        p[2] * q[0] - p[0] * q[2],
        p[0] * q[1] - p[1] * q[0],
    ]
}

#[inline]
fn dot(p: [f64; 3], q: [f64; 3]) -> f64 {
    p[0] * q[0] + p[1] * q[1] + p[2] * q[2]
}

fn dir(el_deg: f64, az_deg: f64) -> [f64; 3] {
    let (e, a) = (el_deg.to_radians(), az_deg.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// Elevation band edges of the probes, degrees.
const BANDS: [f64; 9] = [0.0, 3.0, 8.0, 15.0, 25.0, 40.0, 60.0, 80.0, 90.0];
/// Azimuth sectors over [0°, 180°].
const SECTORS: usize = 6;

/// The probe quads (vertices counterclockwise about the outward direction).
pub fn probe_quads() -> Vec<[[f64; 3]; 4]> {
    let mut out = Vec::new();
    for b in BANDS.windows(2) {
        for s in 0..SECTORS {
            let a0 = 180.0 * s as f64 / SECTORS as f64;
            let a1 = 180.0 * (s + 1) as f64 / SECTORS as f64;
            out.push([dir(b[0], a0), dir(b[0], a1), dir(b[1], a1), dir(b[1], a0)]);
        }
    }
    out
}

/// One probe with its target: the BRDF's lit value `Y` (of `y = f cos/norm`) and solid
/// angle `Ω`, both for the probe and its mirror image together.
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    pub verts: [[f64; 3]; 4],
    pub y: f64,
    pub omega: f64,
}

/// Gauss–Legendre order per side of the rule on a probe.
const ORDER: usize = 4;

/// The probes of one texel: `Y` by an `ORDER²` Gauss rule on the bilinear patch of each quad
/// projected to the sphere (`ω(s, t) = P(s, t)/|P|`, `dω = |(P_s × P_t)·P|/|P|³ ds dt`).
pub fn probes(v: [f64; 3], fcos: &dyn Fn(&Node) -> f64, norm: f64) -> Vec<Probe> {
    let (gx, gw) = gauss_legendre(ORDER);
    probe_quads()
        .into_iter()
        .map(|q| {
            let (mut y, mut om) = (0.0, 0.0);
            for (&s, &ws) in gx.iter().zip(&gw) {
                for (&t, &wt) in gx.iter().zip(&gw) {
                    let (s, t) = (0.5 * (s + 1.0), 0.5 * (t + 1.0));
                    let mut p = [0.0; 3];
                    let mut ps = [0.0; 3];
                    let mut pt = [0.0; 3];
                    for k in 0..3 {
                        p[k] = (1.0 - s) * (1.0 - t) * q[0][k]
                            + s * (1.0 - t) * q[1][k]
                            + s * t * q[2][k]
                            + (1.0 - s) * t * q[3][k];
                        ps[k] = (1.0 - t) * (q[1][k] - q[0][k]) + t * (q[2][k] - q[3][k]);
                        pt[k] = (1.0 - s) * (q[3][k] - q[0][k]) + s * (q[2][k] - q[1][k]);
                    }
                    let l2 = dot(p, p);
                    let l = l2.sqrt();
                    let jac = dot(cross(ps, pt), p).abs() / (l2 * l);
                    let w = 0.25 * ws * wt * jac;
                    let d = [p[0] / l, p[1] / l, p[2] / l];
                    om += w;
                    if let Some(n) = node_of(v, d) {
                        let val = fcos(&n) / norm;
                        if val.is_finite() && val > 0.0 {
                            y += w * val;
                        }
                    }
                }
            }
            // the mirror image (y ↦ −y) has the same values
            Probe {
                verts: q,
                y: 2.0 * y,
                omega: 2.0 * om,
            }
        })
        .collect()
}

/// The half-vector node of unit directions `v`, `l` (normal +z); `None` at or below the
/// horizon.
pub fn node_of(v: [f64; 3], l: [f64; 3]) -> Option<Node> {
    if v[2] <= 0.0 || l[2] <= 0.0 {
        return None;
    }
    let hs = [v[0] + l[0], v[1] + l[1], v[2] + l[2]];
    let len = dot(hs, hs).sqrt();
    if len == 0.0 {
        return None;
    }
    let h = [hs[0] / len, hs[1] / len, hs[2] / len];
    Some(Node {
        n_dot_v: v[2],
        n_dot_l: l[2],
        n_dot_h: h[2],
        v_dot_h: dot(v, h),
        sin2_h: h[0] * h[0] + h[1] * h[1],
    })
}

/// `∫_quad D` (the probe and its mirror image) for an LTC with `d = 0` and its gradient in
/// `θ = (ln a, b/a, ln c)`: the quads lie above the horizon, and `M⁻¹` keeps z, so no
/// clipping is needed. With `p = M⁻¹v`: `∂p/∂ln a = (p_x, 0, 0)`, `∂p/∂(b/a) = (a v_z, 0, 0)`,
/// `∂p/∂ln c = (0, p_y, 0)`.
pub fn ltc_probe(ltc: &Ltc, verts: &[[f64; 3]; 4]) -> (f64, [f64; 3]) {
    let mut p = [[0.0; 3]; 4];
    let mut dp = [[[0.0; 3]; 3]; 4];
    for i in 0..4 {
        let v = verts[i];
        p[i] = ltc.apply_inverse(v);
        dp[i][0] = [p[i][0], 0.0, 0.0];
        dp[i][1] = [ltc.a * v[2], 0.0, 0.0];
        dp[i][2] = [0.0, p[i][1], 0.0];
    }
    let mut t = 0.0;
    let mut g = [0.0; 3];
    for i in 0..4 {
        let j = (i + 1) % 4;
        let (pa, pb) = (p[i], p[j]);
        let u = cross(pa, pb);
        let s = dot(u, u).sqrt();
        if s == 0.0 {
            continue;
        }
        let c = dot(pa, pb);
        let th = s.atan2(c);
        t += th * u[2] / s;
        for k in 0..3 {
            let (da, db) = (dp[i][k], dp[j][k]);
            let du = {
                let x = cross(da, pb);
                let y = cross(pa, db);
                [x[0] + y[0], x[1] + y[1], x[2] + y[2]]
            };
            let dc = dot(da, pb) + dot(pa, db);
            let ds = dot(u, du) / s;
            let dth = (c * ds - s * dc) / (s * s + c * c);
            g[k] += (u[2] / s) * dth + th * (du[2] - u[2] * ds / s) / s;
        }
    }
    // × 2 for the mirror image, / 2π for the formula
    (t / PI, g.map(|x| x / PI))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::ltc_polygon::ltc_polygon_integral;

    /// The probes tile the upper hemisphere: their cosine integrals (with the mirror images)
    /// add up to 1, and their solid angles to 2π (4×4 Gauss on each patch: 1e-6).
    #[test]
    fn probes_tile_the_hemisphere() {
        let v = [0.6, 0.0, 0.8];
        let ps = probes(v, &|n: &Node| n.n_dot_l / PI, 1.0);
        let om: f64 = ps.iter().map(|p| p.omega).sum();
        let e: f64 = ps.iter().map(|p| p.y).sum();
        assert!((om / (2.0 * PI) - 1.0).abs() < 1e-6, "{om}");
        assert!((e - 1.0).abs() < 1e-6, "{e}");
        let x: f64 = probe_quads()
            .iter()
            .map(|q| ltc_probe(&Ltc::IDENTITY, q).0)
            .sum();
        assert!((x - 1.0).abs() < 1e-12, "{x}");
    }

    /// The gradient against central differences, and the value against the polygon kernel.
    #[test]
    fn gradient_matches_differences() {
        let l = Ltc::new(3.0, 2.0, 5.0, 0.0).unwrap();
        let theta = [l.a.ln(), l.b / l.a, l.c.ln()];
        let at = |t: [f64; 3]| {
            let a = t[0].exp();
            Ltc::new(a, t[1] * a, t[2].exp(), 0.0).unwrap()
        };
        for q in probe_quads().iter().step_by(5) {
            let (x, g) = ltc_probe(&l, q);
            let want = 2.0 * ltc_polygon_integral(&l, q).unwrap();
            assert!((x - want).abs() < 1e-14, "{x} {want}");
            for k in 0..3 {
                let h = 1e-6;
                let (mut tp, mut tm) = (theta, theta);
                tp[k] += h;
                tm[k] -= h;
                let fd = (ltc_probe(&at(tp), q).0 - ltc_probe(&at(tm), q).0) / (2.0 * h);
                assert!((fd - g[k]).abs() < 1e-7 * (1.0 + fd.abs()), "{k}: {fd} {}", g[k]);
            }
        }
    }
}
