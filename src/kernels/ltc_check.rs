//! The measurement of an LTC table as a user sees it: the relative error of the lit value of
//! polygonal lights, against a quadrature ground truth.
//!
//! **The test set** ([`test_lights`]): 200 planar lights, 120 quads (rectangles) and 80
//! triangles, around a shading point at the origin with normal +z. Light `i` is drawn from a
//! fixed 64-bit LCG (Knuth's MMIX constants) seeded with 25, so the set is the same on every
//! machine:
//! * centre direction: azimuth uniform in [0, 2π) (the view is at azimuth 0), polar angle
//!   `θc = acos(1 − 1.2u)`, so `cos θc` is uniform in [−0.2, 1]: centres above the horizon
//!   and up to 11.5° below it;
//! * angular size: half-extent σ log-uniform in [0.02, 0.8] rad (1° to 46°), the plane at
//!   distance 1 along the centre, tilted from facing the origin by up to 60° about a random
//!   axis in it, rotated in its plane by a uniform angle; rectangles with aspect ratio
//!   uniform in [0.25, 1], triangles with vertices at 120° ± 20° apart and radii 0.6σ…σ;
//! * lights with nothing above the horizon are skipped (drawing the next), so all 200 have
//!   a positive lit value; lights that cross the horizon are clipped to it for the ground
//!   truth (a surface is not lit from below) and handed to the LTC whole, as a shader does
//!   (the LTC's own support does the clipping).
//!
//! **Views and roughnesses** ([`test_views`], [`test_roughnesses`]): `cos θv ∈ {0.05, 0.15,
//! …, 0.95}` and perceptual `r ∈ {0.05, 0.15, …, 0.95}` (α = r²): 10 × 10, between the
//! texels of a 64² table, so a lookup interpolates, as it does for a user.
//!
//! **The ground truth**: `∫_P f(v, l)(n·l) dω_l` over the clipped polygon by the adaptive
//! polar quadrature of [`polygon_integral`] about the mirror direction, to relative 1e-7.

use super::ltc_polygon::ltc_polygon_integral;
use super::ltc_reference::{clip_to_halfspace, polygon_integral, Reference};
use crate::model::ltc::{Ltc, LtcError};
use crate::model::Brdf;
use std::f64::consts::PI;

/// One planar light: vertex positions relative to the shading point (counterclockwise about
/// the direction away from the origin, so the cosine integral is positive).
#[derive(Clone, Debug, PartialEq)]
pub struct PolygonLight {
    pub verts: Vec<[f64; 3]>,
    /// Crosses the horizon (some vertex below it).
    pub crosses_horizon: bool,
}

/// Knuth's MMIX LCG, the top 53 bits as a uniform number in [0, 1).
pub(crate) struct Lcg(pub(crate) u64);

impl Lcg {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

use crate::numerics::vec3::{cross, dot};

fn unit(p: [f64; 3]) -> [f64; 3] {
    let l = dot(p, p).sqrt();
    [p[0] / l, p[1] / l, p[2] / l]
}

/// Rotates `p` about the unit axis `k` by `ang` (Rodrigues).
fn rotate(p: [f64; 3], k: [f64; 3], ang: f64) -> [f64; 3] {
    let (s, c) = ang.sin_cos();
    let kx = cross(k, p);
    let kd = dot(k, p) * (1.0 - c);
    [
        p[0] * c + kx[0] * s + k[0] * kd,
        p[1] * c + kx[1] * s + k[1] * kd,
        p[2] * c + kx[2] * s + k[2] * kd,
    ]
}

/// The shape of a light in its plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A rectangle of half-width `tan σ` and aspect ratio uniform in [0.25, 1].
    Rectangle,
    /// A triangle, vertices 120° ± 20° apart at radii `0.6…1 · tan σ`.
    Triangle,
}

/// A light of half-extent `σ` (radians, seen from the origin) centred on the unit direction
/// `c` at distance 1: its plane tilted from facing the origin by up to `max_tilt` about a
/// random axis in it and spun in itself by a uniform angle, its shape drawn from `rng`.
/// `None` when nothing of it is above the horizon. The draws from `rng` are in a fixed
/// order, so a seed gives the same light on every machine.
pub(crate) fn place_light(
    rng: &mut Lcg,
    c: [f64; 3],
    sigma: f64,
    max_tilt: f64,
    shape: Shape,
) -> Option<PolygonLight> {
    // the plane's frame: normal n (towards the origin is −c), tilted
    let (e1, e2) = {
        let a = if c[2].abs() < 0.9 {
            [0.0, 0.0, 1.0]
        } else {
            [1.0, 0.0, 0.0]
        };
        let e1 = unit(cross(a, c));
        (e1, cross(c, e1))
    };
    let tilt = max_tilt * rng.next();
    let tilt_axis_ang = 2.0 * PI * rng.next();
    let axis = unit([
        tilt_axis_ang.cos() * e1[0] + tilt_axis_ang.sin() * e2[0],
        tilt_axis_ang.cos() * e1[1] + tilt_axis_ang.sin() * e2[1],
        tilt_axis_ang.cos() * e1[2] + tilt_axis_ang.sin() * e2[2],
    ]);
    let spin = 2.0 * PI * rng.next();
    let (u, v) = (
        rotate(rotate(e1, c, spin), axis, tilt),
        rotate(rotate(e2, c, spin), axis, tilt),
    );
    // in-plane 2D shape, half-extent tan σ at distance 1
    let h = sigma.tan();
    let shape: Vec<(f64, f64)> = if shape == Shape::Rectangle {
        let aspect = 0.25 + 0.75 * rng.next();
        let (w, hh) = (h, h * aspect);
        vec![(-w, -hh), (w, -hh), (w, hh), (-w, hh)]
    } else {
        let base = 2.0 * PI * rng.next();
        (0..3)
            .map(|k| {
                let ang = base
                    + 2.0 * PI * k as f64 / 3.0
                    + (rng.next() - 0.5) * 2.0 * (20f64).to_radians();
                let rad = h * (0.6 + 0.4 * rng.next());
                (rad * ang.cos(), rad * ang.sin())
            })
            .collect()
    };
    let mut verts: Vec<[f64; 3]> = shape
        .iter()
        .map(|&(x, y)| {
            [
                c[0] + x * u[0] + y * v[0],
                c[1] + x * u[1] + y * v[1],
                c[2] + x * u[2] + y * v[2],
            ]
        })
        .collect();
    // counterclockwise about the outward direction
    let n = cross(
        [
            verts[1][0] - verts[0][0],
            verts[1][1] - verts[0][1],
            verts[1][2] - verts[0][2],
        ],
        [
            verts[2][0] - verts[0][0],
            verts[2][1] - verts[0][1],
            verts[2][2] - verts[0][2],
        ],
    );
    if dot(n, verts[0]) < 0.0 {
        verts.reverse();
    }
    if verts.iter().all(|p| p[2] <= 0.0) {
        return None;
    }
    let crosses_horizon = verts.iter().any(|p| p[2] <= 0.0);
    Some(PolygonLight {
        verts,
        crosses_horizon,
    })
}

/// The 200 lights of the test set (module doc).
pub fn test_lights() -> Vec<PolygonLight> {
    let mut rng = Lcg(25);
    let mut out = Vec::with_capacity(200);
    while out.len() < 200 {
        let quad = out.len() % 5 < 3;
        let phi = 2.0 * PI * rng.next();
        let cz = 1.0 - 1.2 * rng.next();
        let sz = (1.0 - cz * cz).max(0.0).sqrt();
        let c = [sz * phi.cos(), sz * phi.sin(), cz];
        let sigma = (0.02f64.ln() + rng.next() * (0.8f64 / 0.02).ln()).exp();
        let shape = if quad {
            Shape::Rectangle
        } else {
            Shape::Triangle
        };
        if let Some(light) = place_light(&mut rng, c, sigma, 60f64.to_radians(), shape) {
            out.push(light);
        }
    }
    out
}

/// The test views, `cos θv`.
pub fn test_views() -> Vec<f64> {
    (0..10).map(|k| 0.05 + 0.1 * k as f64).collect()
}

/// The test roughnesses (perceptual, α = r²).
pub fn test_roughnesses() -> Vec<f64> {
    (0..10).map(|k| 0.05 + 0.1 * k as f64).collect()
}

/// The view vector of cosine `mu` (in the xz-plane at positive x).
pub fn view_vector(mu: f64) -> [f64; 3] {
    [(1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu]
}

/// The mirror direction of the view `mu` about +z.
pub fn mirror(mu: f64) -> [f64; 3] {
    let v = view_vector(mu);
    [-v[0], 0.0, v[2]]
}

/// Whether the direction `w` is inside the (convex) polygon `verts` as seen from the origin.
pub fn contains(verts: &[[f64; 3]], w: [f64; 3]) -> bool {
    let n = verts.len();
    (0..n).all(|i| dot(cross(verts[i], verts[(i + 1) % n]), w) >= 0.0)
}

/// The ground truth `∫_P f(v, l)(n·l) dω_l` over the light clipped to the upper hemisphere,
/// for view cosine `mu`, by [`polygon_integral`] about the mirror direction (lifted to at
/// least 1e-3 above the horizon) with radial scale `2α + 10⁻⁴`, to relative `rel_tol`.
pub fn lit_reference(
    brdf: &Brdf,
    alpha: f64,
    mu: f64,
    light: &PolygonLight,
    rel_tol: f64,
) -> Result<Reference, LtcError> {
    lit_reference_about(brdf, mu, light, mirror(mu), 2.0 * alpha + 1e-4, rel_tol)
}

/// [`lit_reference`] about another centre and scale (the harness checks the ground truth
/// with a second one).
pub fn lit_reference_about(
    brdf: &Brdf,
    mu: f64,
    light: &PolygonLight,
    center: [f64; 3],
    scale: f64,
    rel_tol: f64,
) -> Result<Reference, LtcError> {
    let v = view_vector(mu);
    let clipped = clip_to_halfspace(&light.verts, [0.0, 0.0, 1.0]);
    let c = unit([center[0], center[1], center[2].max(1e-3)]);
    let g = |l: [f64; 3]| {
        if l[2] <= 0.0 {
            0.0
        } else {
            brdf.eval(v, l) * l[2]
        }
    };
    polygon_integral(&g, &clipped, c, scale, rel_tol)
}

/// [`lit_reference`] with Schlick's Fresnel `F0 + (1 − F0)(1 − v·h)⁵` (F90 = 1) weighting the
/// BRDF (`f0 = None`: F = 1, [`lit_reference`] itself): the exact value that a table's
/// `F0·norm + (1 − F0)·fresnel` times `∫_P D` approximates.
pub fn lit_reference_schlick(
    brdf: &Brdf,
    alpha: f64,
    mu: f64,
    light: &PolygonLight,
    f0: Option<f64>,
    rel_tol: f64,
) -> Result<Reference, LtcError> {
    let Some(f0) = f0 else {
        return lit_reference(brdf, alpha, mu, light, rel_tol);
    };
    let v = view_vector(mu);
    let clipped = clip_to_halfspace(&light.verts, [0.0, 0.0, 1.0]);
    let m = mirror(mu);
    let c = unit([m[0], m[1], m[2].max(1e-3)]);
    let g = |l: [f64; 3]| {
        if l[2] <= 0.0 {
            return 0.0;
        }
        let hs = [v[0] + l[0], v[1] + l[1], v[2] + l[2]];
        let len = dot(hs, hs).sqrt();
        let vh = if len > 0.0 { dot(v, hs) / len } else { 0.0 };
        let f = f0 + (1.0 - f0) * crate::model::fresnel::schlick_weight(vh);
        brdf.eval(v, l) * l[2] * f
    };
    polygon_integral(&g, &clipped, c, 2.0 * alpha + 1e-4, rel_tol)
}

/// The most vertices [`polygon_light`] accepts (a light's polygon; clipping to the horizon
/// adds at most one).
pub const MAX_POLYGON_VERTICES: usize = 8;

/// A user's polygonal light (vertex positions relative to the shading point, in the frame
/// with the normal +z and the view in the xz-plane at positive x), checked: 3 to
/// [`MAX_POLYGON_VERTICES`] finite vertices, none at the shading point, convex as seen from
/// it with no two vertices in the same direction and no three on one great circle (else the
/// polygon is degenerate, or not the convex light the reference quadrature integrates), and
/// something of it above the horizon. Either winding is accepted (the light is taken as
/// two-sided): a clockwise polygon is returned reversed, counterclockwise about the
/// direction away from the shading point, the winding whose integrals are positive.
/// Returns the light and whether it was reversed; the error says what is wrong.
pub fn polygon_light(verts: &[[f64; 3]]) -> Result<(PolygonLight, bool), String> {
    let n = verts.len();
    if !(3..=MAX_POLYGON_VERTICES).contains(&n) {
        return Err(format!(
            "{n} vertices: a polygon light has 3 to {MAX_POLYGON_VERTICES}"
        ));
    }
    let mut u = Vec::with_capacity(n);
    for (i, p) in verts.iter().enumerate() {
        if !p.iter().all(|x| x.is_finite()) {
            return Err(format!("vertex {} is not finite", i + 1));
        }
        let l = dot(*p, *p).sqrt();
        if !(l > 0.0 && l.is_finite()) {
            return Err(format!(
                "vertex {} is at the shading point (0, 0, 0) or out of range: vertices are positions relative to it",
                i + 1
            ));
        }
        u.push([p[0] / l, p[1] / l, p[2] / l]);
    }
    // every other vertex strictly on one side of every edge's great circle
    let mut sign = 0.0;
    for i in 0..n {
        let j = (i + 1) % n;
        let e = cross(u[i], u[j]);
        let s = dot(e, e).sqrt();
        if s < 1e-9 {
            return Err(format!(
                "vertices {} and {} are in the same or opposite directions from the shading point: the polygon is degenerate",
                i + 1,
                j + 1
            ));
        }
        for (k, &w) in u.iter().enumerate() {
            if k == i || k == j {
                continue;
            }
            let t = dot(e, w) / s;
            if t.abs() < 1e-9 || (sign != 0.0 && t.signum() != sign) {
                return Err(format!(
                    "the polygon is not convex as seen from the shading point (vertex {} is {} the great circle through vertices {} and {}): give a convex polygon with no three vertices in line",
                    k + 1,
                    if t.abs() < 1e-9 { "on" } else { "on the wrong side of" },
                    i + 1,
                    j + 1
                ));
            }
            sign = t.signum();
        }
    }
    let mut v = verts.to_vec();
    let reversed = sign < 0.0;
    if reversed {
        v.reverse();
    }
    let e = super::ltc_polygon::clamped_cosine_integral(&v).map_err(|e| e.to_string())?;
    if e.is_nan() || e <= 0.0 {
        return Err(
            "the polygon lies at or below the horizon (z <= 0 in the shading frame): it lights nothing".into(),
        );
    }
    let crosses_horizon = v.iter().any(|p| p[2] <= 0.0);
    Ok((
        PolygonLight {
            verts: v,
            crosses_horizon,
        },
        reversed,
    ))
}

/// The default test light of `probe`: a square of side 1 at distance 2 facing the shading
/// point, centred on the mirror direction of the view `mu` (lifted to 10° above the horizon
/// at grazing views, so that most of it lights), edges along y and the direction
/// perpendicular to both: the light a specular lobe sees best (half-angle atan(1/4) ≈ 14°).
pub fn default_test_quad(mu: f64) -> Vec<[f64; 3]> {
    let m = mirror(mu.clamp(0.0, 1.0));
    let lift = 10f64.to_radians().sin();
    let c = if m[2] < lift {
        [-(1.0 - lift * lift).sqrt(), 0.0, lift]
    } else {
        m
    };
    // e1 ⟂ c in the xz-plane (towards +z), e2 = y: (e1, e2, c) right-handed
    let e1 = [c[2], 0.0, -c[0]];
    let e2 = [0.0, 1.0, 0.0];
    let at = |s: f64, t: f64| {
        [
            2.0 * c[0] + 0.5 * (s * e1[0] + t * e2[0]),
            2.0 * c[1] + 0.5 * (s * e1[1] + t * e2[1]),
            2.0 * c[2] + 0.5 * (s * e1[2] + t * e2[2]),
        ]
    };
    vec![at(-1.0, -1.0), at(1.0, -1.0), at(1.0, 1.0), at(-1.0, 1.0)]
}

/// The lit value of a light through an LTC: `norm·∫_P D` ([`ltc_polygon_integral`], the
/// whole polygon, as a shader does).
pub fn lit_ltc(ltc: &Ltc, norm: f64, light: &PolygonLight) -> Result<f64, LtcError> {
    Ok(norm * ltc_polygon_integral(ltc, &light.verts)?)
}

/// Summary statistics of relative errors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorStats {
    pub count: usize,
    pub median: f64,
    pub p90: f64,
    pub p99: f64,
    pub max: f64,
    pub mean: f64,
    /// Fraction of cases whose LTC value is exactly 0 (the light is outside its support).
    pub zeros: f64,
}

/// The statistics of `(relative error, ltc value)` pairs; percentiles by the nearest rank
/// (`⌈p·n⌉`-th smallest).
pub fn error_stats(cases: &[(f64, f64)]) -> ErrorStats {
    let mut e: Vec<f64> = cases.iter().map(|c| c.0).collect();
    e.sort_by(f64::total_cmp);
    let n = e.len();
    let rank = |p: f64| -> f64 {
        if n == 0 {
            return f64::NAN;
        }
        let k = ((p * n as f64).ceil() as usize).clamp(1, n);
        e[k - 1]
    };
    let zeros = cases.iter().filter(|c| c.1 == 0.0).count();
    ErrorStats {
        count: n,
        median: rank(0.5),
        p90: rank(0.9),
        p99: rank(0.99),
        max: e.last().copied().unwrap_or(f64::NAN),
        mean: if n == 0 {
            f64::NAN
        } else {
            e.iter().sum::<f64>() / n as f64
        },
        zeros: if n == 0 { 0.0 } else { zeros as f64 / n as f64 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_lights_are_checked() {
        let sq = [
            [-0.5, -0.5, 1.0],
            [0.5, -0.5, 1.0],
            [0.5, 0.5, 1.0],
            [-0.5, 0.5, 1.0],
        ];
        let (l, rev) = polygon_light(&sq).unwrap();
        assert!(!rev && !l.crosses_horizon);
        let mut cw = sq;
        cw.reverse();
        let (l2, rev) = polygon_light(&cw).unwrap();
        assert!(rev);
        assert_eq!(l2.verts, cw.iter().rev().copied().collect::<Vec<_>>());
        // too few, non-finite, at the origin, repeated, three in line, non-convex, below
        assert!(polygon_light(&sq[..2]).is_err());
        assert!(polygon_light(&[[f64::NAN, 0.0, 1.0], sq[1], sq[2]]).is_err());
        assert!(polygon_light(&[[0.0; 3], sq[1], sq[2]]).is_err());
        assert!(polygon_light(&[sq[0], sq[0], sq[1], sq[2]]).is_err());
        assert!(polygon_light(&[sq[0], [0.0, -0.5, 1.0], sq[1], sq[2]]).is_err());
        assert!(polygon_light(&[sq[0], sq[2], sq[1], sq[3]]).is_err());
        let below = sq.map(|p| [p[0], p[1], -p[2]]);
        assert!(polygon_light(&below).is_err());
        // the default quad: valid, counterclockwise, holding the mirror direction
        for mu in [0.0, 0.05, 0.5, 1.0] {
            let q = default_test_quad(mu);
            let (l, rev) = polygon_light(&q).unwrap();
            assert!(!rev, "{mu}");
            if mu >= 0.2 {
                assert!(contains(&l.verts, mirror(mu)), "{mu}");
            }
        }
    }

    #[test]
    fn the_test_set_is_fixed_and_valid() {
        let l = test_lights();
        assert_eq!(l.len(), 200);
        assert_eq!(l, test_lights());
        let crossing = l.iter().filter(|x| x.crosses_horizon).count();
        assert!(crossing > 10, "{crossing}");
        for x in &l {
            let e = crate::kernels::ltc_polygon::clamped_cosine_integral(&x.verts).unwrap();
            assert!(e > 0.0);
        }
    }
}
