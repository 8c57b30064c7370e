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
//! **Gradient.** The edge term `T(p, q) = θ·u_z/s` (`u = p × q`, `s = |u|`,
//! `θ = atan2(s, p·q)`) is differentiated with the clipping in forward mode (dual numbers).

use crate::hemisphere::Node;
use crate::model::ltc::Ltc;
use crate::quadrature::gauss::gauss_legendre;
use std::f64::consts::PI;

use crate::numerics::vec3::{cross, dot};

fn dir(el_deg: f64, az_deg: f64) -> [f64; 3] {
    let (e, a) = (el_deg.to_radians(), az_deg.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// Elevation band edges of the probes, degrees.
const BANDS: [f64; 9] = [0.0, 3.0, 8.0, 15.0, 25.0, 40.0, 60.0, 80.0, 90.0];
/// Bands that straddle the horizon, degrees: lights partly below it, whose lit value is
/// their upper part's while an LTC with `d ≠ 0` also counts its mass below.
const STRADDLING: [[f64; 2]; 2] = [[-4.0, 4.0], [-12.0, 12.0]];
/// Azimuth sectors over [0°, 180°].
const SECTORS: usize = 6;

/// The probe quads (vertices counterclockwise about the outward direction).
pub fn probe_quads() -> Vec<[[f64; 3]; 4]> {
    let mut out = Vec::new();
    let bands = BANDS.windows(2).map(|b| [b[0], b[1]]).chain(STRADDLING);
    for b in bands {
        for s in 0..SECTORS {
            let a0 = 180.0 * s as f64 / SECTORS as f64;
            let a1 = 180.0 * (s + 1) as f64 / SECTORS as f64;
            out.push([dir(b[0], a0), dir(b[0], a1), dir(b[1], a1), dir(b[1], a0)]);
        }
    }
    out
}

/// One probe with its target: the BRDF's lit value `Y` (of `y = f cos/norm`) and the solid
/// angle `Ω` above the horizon, both for the probe and its mirror image together.
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    pub verts: [[f64; 3]; 4],
    pub y: f64,
    pub omega: f64,
}

/// Gauss–Legendre orders per side of the two rules on a probe (the lower one checks the
/// higher one).
const ORDER: usize = 4;
const CHECK_ORDER: usize = 3;

/// One node of a probe's rule: its unit direction `d` and its solid-angle weight.
type ProbeNode = ([f64; 3], f64);

/// A probe quad with the nodes of its `ORDER²` and `CHECK_ORDER²` rules.
type ProbeRules = ([[f64; 3]; 4], Vec<ProbeNode>, Vec<ProbeNode>);

/// The nodes of the `order²` Gauss rule on the quad `q`'s bilinear patch projected to the
/// sphere (`ω(s, t) = P/|P|`, `dω = |(P_s × P_t)·P|/|P|³ ds dt`). They depend only on the
/// quad, not on the texel: [`probe_rules`] computes them once.
fn quad_nodes(q: &[[f64; 3]; 4], order: usize) -> Vec<ProbeNode> {
    let (gx, gw) = gauss_legendre(order);
    let mut out = Vec::with_capacity(order * order);
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
            let w = 0.25 * ws * wt * dot(cross(ps, pt), p).abs() / (l2 * l);
            out.push(([p[0] / l, p[1] / l, p[2] / l], w));
        }
    }
    out
}

/// Each probe quad with the nodes of its `ORDER²` and `CHECK_ORDER²` rules, built once per
/// process (the same for every texel of every table).
fn probe_rules() -> &'static [ProbeRules] {
    static RULES: std::sync::OnceLock<Vec<ProbeRules>> = std::sync::OnceLock::new();
    RULES.get_or_init(|| {
        probe_quads()
            .into_iter()
            .map(|q| (q, quad_nodes(&q, ORDER), quad_nodes(&q, CHECK_ORDER)))
            .collect()
    })
}

/// `(∫ y dω, ∫ dω above the horizon)` over a quad (and its mirror image) by its rule's
/// nodes ([`quad_nodes`]).
fn quad_rule(
    nodes: &[ProbeNode],
    v: [f64; 3],
    fcos: &dyn Fn(&Node) -> f64,
    norm: f64,
) -> (f64, f64) {
    let (mut y, mut om) = (0.0, 0.0);
    for &(d, w) in nodes {
        if d[2] > 0.0 {
            om += w;
        }
        if let Some(n) = node_of(v, d) {
            let val = fcos(&n) / norm;
            if val.is_finite() && val > 0.0 {
                y += w * val;
            }
        }
    }
    (2.0 * y, 2.0 * om)
}

/// The probes of one texel whose BRDF value can be trusted: `Y` by the `ORDER²` rule on
/// each quad (`quad_rule`), kept where the `CHECK_ORDER²` rule agrees to 10% (of
/// `Y + floor·Ω`) and the quad does not hold `peak` (the BRDF's largest value on the
/// fit's rule): a lobe narrower than a probe is a spike that 16 nodes miss or hit by
/// chance, and the fit's nodes, not the probes, are there to see it.
pub fn probes(
    v: [f64; 3],
    fcos: &dyn Fn(&Node) -> f64,
    norm: f64,
    peak: Option<[f64; 3]>,
    floor: f64,
) -> Vec<Probe> {
    probe_rules()
        .iter()
        .filter(|(q, _, _)| {
            peak.is_none_or(|pk| !(0..4).all(|i| dot(cross(q[i], q[(i + 1) % 4]), pk) >= 0.0))
        })
        .filter_map(|(q, high, check)| {
            let (y, omega) = quad_rule(high, v, fcos, norm);
            let (y3, _) = quad_rule(check, v, fcos, norm);
            let ok = (y - y3).abs() <= 0.1 * (y + floor * omega) && omega > 0.0;
            ok.then_some(Probe {
                verts: *q,
                y,
                omega,
            })
        })
        .collect()
}

/// The BRDF evaluations [`probes`] spends on one texel: both rules on every probe quad.
pub fn brdf_evaluations() -> usize {
    probe_quads().len() * (ORDER * ORDER + CHECK_ORDER * CHECK_ORDER)
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

/// A number with its gradient in the four fit parameters (forward-mode differentiation).
#[derive(Clone, Copy, Debug)]
struct Dual {
    v: f64,
    g: [f64; 4],
}

impl Dual {
    fn c(v: f64) -> Dual {
        Dual { v, g: [0.0; 4] }
    }
    fn add(self, o: Dual) -> Dual {
        Dual {
            v: self.v + o.v,
            g: std::array::from_fn(|k| self.g[k] + o.g[k]),
        }
    }
    fn sub(self, o: Dual) -> Dual {
        Dual {
            v: self.v - o.v,
            g: std::array::from_fn(|k| self.g[k] - o.g[k]),
        }
    }
    fn mul(self, o: Dual) -> Dual {
        Dual {
            v: self.v * o.v,
            g: std::array::from_fn(|k| self.g[k] * o.v + self.v * o.g[k]),
        }
    }
    fn div(self, o: Dual) -> Dual {
        let inv = 1.0 / o.v;
        let q = self.v * inv;
        Dual {
            v: q,
            g: std::array::from_fn(|k| (self.g[k] - q * o.g[k]) * inv),
        }
    }
    fn sqrt(self) -> Dual {
        let r = self.v.sqrt();
        let h = 0.5 / r;
        Dual {
            v: r,
            g: self.g.map(|x| x * h),
        }
    }
    /// `atan2(self, x)`: `d = (x·dy − y·dx)/(x² + y²)`.
    fn atan2(self, x: Dual) -> Dual {
        let den = self.v * self.v + x.v * x.v;
        Dual {
            v: self.v.atan2(x.v),
            g: std::array::from_fn(|k| (x.v * self.g[k] - self.v * x.g[k]) / den),
        }
    }
}

type DVec = [Dual; 3];

fn dcross(p: &DVec, q: &DVec) -> DVec {
    [
        p[1].mul(q[2]).sub(p[2].mul(q[1])),
        p[2].mul(q[0]).sub(p[0].mul(q[2])),
        p[0].mul(q[1]).sub(p[1].mul(q[0])),
    ]
}

fn ddot(p: &DVec, q: &DVec) -> Dual {
    p[0].mul(q[0]).add(p[1].mul(q[1])).add(p[2].mul(q[2]))
}

/// The edge term `θ·u_z/s` (module doc) in duals; zero for a degenerate edge.
fn dedge(p: &DVec, q: &DVec) -> Dual {
    let u = dcross(p, q);
    let s2 = ddot(&u, &u);
    if s2.v.is_nan() || s2.v <= 0.0 {
        return Dual::c(0.0);
    }
    let s = s2.sqrt();
    let th = s.atan2(ddot(p, q));
    th.mul(u[2]).div(s)
}

/// [`ltc_probe`] for a polygon entirely inside the LTC's support, with the edge terms'
/// gradients in closed form: for `T(p, q) = θ·u_z/s` (`u = p × q`, `s = |u|`, `c = p·q`,
/// `θ = atan2(s, c)`), `∂s/∂p = (q × u)/s`, `∂s/∂q = (u × p)/s`, `∂c/∂p = q`, `∂c/∂q = p`,
/// `∂u_z/∂p = (q_y, −q_x, 0)`, `∂u_z/∂q = (−p_y, p_x, 0)`, `∂θ = (c∂s − s∂c)/(s² + c²)` and
/// `∂T = (u_z/s)∂θ + θ(∂u_z − u_z∂s/s)/s`; each vertex's gradient then meets the
/// parameters through `∂p/∂θ` (see [`ltc_probe`]). The same numbers as the dual path, four
/// times cheaper.
fn unclipped(ltc: &Ltc, verts: &[[f64; 3]], p: &[[f64; 3]]) -> (f64, [f64; 4]) {
    let n = p.len();
    let mut gv = [[0.0; 3]; 8];
    let mut t = 0.0;
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b) = (p[i], p[j]);
        let u = cross(a, b);
        let s2 = dot(u, u);
        if s2.is_nan() || s2 <= 0.0 {
            continue;
        }
        let s = s2.sqrt();
        let c = dot(a, b);
        let th = s.atan2(c);
        t += th * u[2] / s;
        let k = 1.0 / (s2 + c * c);
        let (uz_s, th_s) = (u[2] / s, th / s);
        let qu = cross(b, u);
        let up = cross(u, a);
        for m in 0..3 {
            // ∂/∂a_m and ∂/∂b_m
            let ds_a = qu[m] / s;
            let ds_b = up[m] / s;
            let dth_a = (c * ds_a - s * b[m]) * k;
            let dth_b = (c * ds_b - s * a[m]) * k;
            let duz_a = [b[1], -b[0], 0.0][m];
            let duz_b = [-a[1], a[0], 0.0][m];
            gv[i][m] += uz_s * dth_a + th_s * (duz_a - u[2] * ds_a / s);
            gv[j][m] += uz_s * dth_b + th_s * (duz_b - u[2] * ds_b / s);
        }
    }
    let mut g = [0.0; 4];
    for i in 0..n {
        g[0] += gv[i][0] * p[i][0];
        g[1] += gv[i][0] * ltc.a * verts[i][2];
        g[2] += gv[i][1] * p[i][1];
        g[3] += gv[i][2] * verts[i][0];
    }
    (t / PI, g.map(|x| x / PI))
}

/// `∫_P D` for the polygon `verts` (directions, counterclockwise about the outward
/// direction) and its mirror image `y ↦ −y`, for the LTC `M⁻¹ = [[a, 0, b], [0, c, 0],
/// [d, 0, 1]]`, with its gradient in `θ = (ln a, b/a, ln c, d)`: the vertices are mapped by
/// `M⁻¹` (`∂q/∂ln a = (q_x, 0, 0)`, `∂q/∂(b/a) = (a v_z, 0, 0)`, `∂q/∂ln c = (0, q_y, 0)`,
/// `∂q/∂d = (0, 0, v_x)`), clipped to `q_z > 0` (the LTC's support, where a shader clips)
/// and summed by Lambert's formula ([`super::ltc_polygon`]), every step in duals. Only the
/// first `p` gradient entries are used by a fit with `p` parameters.
pub fn ltc_probe(ltc: &Ltc, verts: &[[f64; 3]]) -> (f64, [f64; 4]) {
    let n = verts.len();
    if (3..=8).contains(&n) {
        // the common case, every vertex inside the support: the gradient in closed form
        let mut p = [[0.0; 3]; 8];
        let mut inside = true;
        for (i, &v) in verts.iter().enumerate() {
            p[i] = ltc.apply_inverse(v);
            inside &= p[i][2] > 0.0;
        }
        if inside {
            return unclipped(ltc, verts, &p[..n]);
        }
    }
    let map = |v: [f64; 3]| -> DVec {
        let q = ltc.apply_inverse(v);
        [
            Dual {
                v: q[0],
                g: [q[0], ltc.a * v[2], 0.0, 0.0],
            },
            Dual {
                v: q[1],
                g: [0.0, 0.0, q[1], 0.0],
            },
            Dual {
                v: q[2],
                g: [0.0, 0.0, 0.0, v[0]],
            },
        ]
    };
    let mut first: Option<DVec> = None;
    let mut prev: Option<DVec> = None;
    let mut sum = Dual::c(0.0);
    let mut emit = |x: DVec, sum: &mut Dual| {
        match prev {
            None => first = Some(x),
            Some(pv) => *sum = sum.add(dedge(&pv, &x)),
        }
        prev = Some(x);
    };
    if n >= 3 {
        let mut p = map(verts[n - 1]);
        for &vq in verts {
            let q = map(vq);
            let (pin, qin) = (p[2].v > 0.0, q[2].v > 0.0);
            if pin != qin {
                let t = p[2].div(p[2].sub(q[2]));
                let x = [
                    p[0].add(t.mul(q[0].sub(p[0]))),
                    p[1].add(t.mul(q[1].sub(p[1]))),
                    Dual::c(0.0),
                ];
                emit(x, &mut sum);
            }
            if qin {
                emit(q, &mut sum);
            }
            p = q;
        }
    }
    if let (Some(f), Some(pv)) = (first, prev) {
        sum = sum.add(dedge(&pv, &f));
    }
    // × 2 for the mirror image, / 2π for the formula
    (sum.v / PI, sum.g.map(|x| x / PI))
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
        let ps = probes(v, &|n: &Node| n.n_dot_l / PI, 1.0, None, 0.0);
        let tiles = (BANDS.len() - 1) * SECTORS;
        let om: f64 = ps[..tiles].iter().map(|p| p.omega).sum();
        let e: f64 = ps[..tiles].iter().map(|p| p.y).sum();
        assert!((om / (2.0 * PI) - 1.0).abs() < 1e-6, "{om}");
        assert!((e - 1.0).abs() < 1e-6, "{e}");
        let x: f64 = probe_quads()[..tiles]
            .iter()
            .map(|q| ltc_probe(&Ltc::IDENTITY, q).0)
            .sum();
        assert!((x - 1.0).abs() < 1e-12, "{x}");
    }

    /// The gradient against central differences, and the value against the polygon kernel,
    /// with and without clipping (d ≠ 0 moves the support's edge through the probes).
    #[test]
    fn gradient_matches_differences() {
        for l in [
            Ltc::new(3.0, 2.0, 5.0, 0.0).unwrap(),
            Ltc::new(3.0, 2.0, 5.0, -0.8).unwrap(),
            Ltc::new(2.0, 1.0, 4.0, 0.5).unwrap(),
        ] {
            let theta = [l.a.ln(), l.b / l.a, l.c.ln(), l.d];
            let at = |t: [f64; 4]| {
                let a = t[0].exp();
                Ltc::new(a, t[1] * a, t[2].exp(), t[3]).unwrap()
            };
            for q in probe_quads().iter().step_by(3) {
                let (x, g) = ltc_probe(&l, q);
                let want = 2.0 * ltc_polygon_integral(&l, q).unwrap();
                assert!((x - want).abs() < 1e-14, "{x} {want}");
                for k in 0..4 {
                    let h = 1e-6;
                    let (mut tp, mut tm) = (theta, theta);
                    tp[k] += h;
                    tm[k] -= h;
                    let fd = (ltc_probe(&at(tp), q).0 - ltc_probe(&at(tm), q).0) / (2.0 * h);
                    assert!(
                        (fd - g[k]).abs() < 1e-6 * (1.0 + fd.abs()),
                        "{l:?} {k}: {fd} {}",
                        g[k]
                    );
                }
            }
        }
    }
}
