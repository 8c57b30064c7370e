//! Closed-form integrals of the clamped cosine over spherical polygons and caps: what an
//! LTC shader evaluates per light.
//!
//! **Polygons.** For a spherical polygon `P` with vertices `p₀ … p_{n−1}` (directions; any
//! positive lengths), Lambert's formula for the irradiance of a uniform polygonal source
//! (Lambert 1760; Arvo 1995, "Applications of Irradiance Tensors", eq. 5 and §5; Heitz et
//! al. 2016, eq. 11) gives the integral of the cosine about ẑ over `P`:
//!
//! `E(P) = (1/π) ∫_P ω_z dω = (1/2π) Σᵢ θᵢ · (pᵢ × pᵢ₊₁)_z / |pᵢ × pᵢ₊₁|`,
//! `θᵢ = ∠(pᵢ, pᵢ₊₁)`,
//!
//! exact for a polygon inside the upper hemisphere. The *clamped* cosine `max(0, ω_z)/π`
//! needs `P` clipped to `z ≥ 0` first (Heitz et al. 2016, §5.2 "Horizon clipping"): the
//! clip of a cone by the plane `z = 0` is another polygon, with at most one vertex more.
//! The angle is computed as `atan2(|p × q|, p·q)`, which keeps full precision for short
//! edges where `acos(p̂·q̂)` loses half the digits.
//!
//! **Sign.** `E` is positive when the vertices turn counterclockwise about the outward
//! direction (right-hand rule: `(p₁ − p₀) × (p₂ − p₀)` points away from the origin), and
//! negative for the opposite winding; one-sided lights keep the positive winding, two-sided
//! ones take `|E|`.
//!
//! **The LTC's integral** over `P` is the cosine's over `M⁻¹P` (Heitz et al. 2016, eq. 3):
//! transform the vertices, then clip and sum as above ([`ltc_polygon_integral`]). Linear
//! maps send great circles to great circles, so the transformed edges are the great arcs
//! between the transformed vertices.
//!
//! **Spheres and disks.** The cosine's integral over a spherical cap clipped to the horizon
//! ([`cap_clamped_cosine`]) is the closed form tabulated as `ltc_disk_integral` / the 4th
//! channel of Heitz's `ltc_2` ([`clipped_sphere_table`]).

use crate::model::ltc::{Ltc, LtcError};
use std::f64::consts::{FRAC_PI_2, PI};

use crate::numerics::vec3::{cross, dot};

/// One edge's term of the vector form factor, `θ·(p × q)/|p × q|` (not divided by 2π):
/// the integral of the (unclamped) direction vector ω over the sector spanned by the edge
/// and the origin's antipode, Arvo 1995, eq. 5. Zero for a degenerate edge.
#[inline]
pub fn edge_vector(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    let c = cross(p, q);
    let s = dot(c, c).sqrt();
    if s == 0.0 {
        return [0.0; 3];
    }
    let theta = s.atan2(dot(p, q));
    let k = theta / s;
    [k * c[0], k * c[1], k * c[2]]
}

/// The z term of [`edge_vector`] alone.
#[inline]
fn edge_z(p: [f64; 3], q: [f64; 3]) -> f64 {
    let c = cross(p, q);
    let s = dot(c, c).sqrt();
    if s == 0.0 {
        return 0.0;
    }
    s.atan2(dot(p, q)) * c[2] / s
}

/// The vector form factor `F = (1/2π) Σ θᵢ n̂ᵢ` of an unclipped polygon (Arvo 1995; Heitz &
/// Hill 2017 use its length and direction to look up the horizon-clipped sphere that has
/// the same `F`, [`clipped_sphere_table`]).
pub fn vector_form_factor(verts: &[[f64; 3]]) -> Result<[f64; 3], LtcError> {
    check_polygon(verts)?;
    let n = verts.len();
    let mut f = [0.0; 3];
    for i in 0..n {
        let e = edge_vector(verts[i], verts[(i + 1) % n]);
        for k in 0..3 {
            f[k] += e[k];
        }
    }
    Ok(f.map(|x| x / (2.0 * PI)))
}

fn check_polygon(verts: &[[f64; 3]]) -> Result<(), LtcError> {
    for p in verts {
        if !p.iter().all(|x| x.is_finite()) {
            return Err(LtcError::NotFinite {
                what: "a polygon vertex",
            });
        }
        if dot(*p, *p) == 0.0 {
            return Err(LtcError::ZeroVector {
                what: "a polygon vertex",
            });
        }
    }
    Ok(())
}

/// Streams the clipped polygon's vertices into the edge sum: Sutherland–Hodgman clipping
/// against `z ≥ 0` (Sutherland & Hodgman 1974) without a vertex buffer. A crossing edge
/// `p → q` (`p_z`, `q_z` of opposite signs) contributes the point `p + t(q − p)`,
/// `t = p_z/(p_z − q_z)`, on the horizon; any point of that chord lies on the same great
/// arc, so the vertices need no normalization.
struct ClipSum {
    first: Option<[f64; 3]>,
    prev: [f64; 3],
    sum: f64,
}

impl ClipSum {
    fn new() -> ClipSum {
        ClipSum {
            first: None,
            prev: [0.0; 3],
            sum: 0.0,
        }
    }

    #[inline]
    fn emit(&mut self, p: [f64; 3]) {
        match self.first {
            None => self.first = Some(p),
            Some(_) => self.sum += edge_z(self.prev, p),
        }
        self.prev = p;
    }

    fn finish(self) -> f64 {
        match self.first {
            Some(f) => (self.sum + edge_z(self.prev, f)) / (2.0 * PI),
            None => 0.0,
        }
    }
}

/// `∫_P max(0, ω_z) dω / π` for the spherical polygon with these vertex directions, with
/// the sign of its winding (module doc). Fewer than 3 vertices give 0.
pub fn clamped_cosine_integral(verts: &[[f64; 3]]) -> Result<f64, LtcError> {
    check_polygon(verts)?;
    Ok(clamped_cosine_unchecked(verts.iter().copied()))
}

/// [`clamped_cosine_integral`] over vertices already checked finite and non-zero.
fn clamped_cosine_unchecked<I: Iterator<Item = [f64; 3]> + Clone>(verts: I) -> f64 {
    let n = verts.clone().count();
    if n < 3 {
        return 0.0;
    }
    let last = verts.clone().last().expect("n >= 3");
    let mut acc = ClipSum::new();
    let mut p = last;
    for q in verts {
        let (pin, qin) = (p[2] > 0.0, q[2] > 0.0);
        if pin != qin {
            // the edge crosses the horizon: add its crossing point (exactly z = 0)
            let t = p[2] / (p[2] - q[2]);
            let x = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), 0.0];
            if dot(x, x) > 0.0 {
                acc.emit(x);
            }
        }
        if qin {
            acc.emit(q);
        }
        p = q;
    }
    acc.finish()
}

/// `∫_P D dω` for the LTC `ltc` over the polygon `P` (vertex directions in the LTC's frame:
/// normal +z, view in the xz-plane at positive x): the clamped cosine's integral over
/// `M⁻¹P` (Heitz et al. 2016, eq. 3 and §5), signed by winding as
/// [`clamped_cosine_integral`]. This is the shader's computation in f64.
pub fn ltc_polygon_integral(ltc: &Ltc, verts: &[[f64; 3]]) -> Result<f64, LtcError> {
    check_polygon(verts)?;
    Ok(clamped_cosine_unchecked(
        verts.iter().map(|&p| ltc.apply_inverse(p)),
    ))
}

/// The projected solid angle of a spherical cap clipped to the horizon, over π:
/// `(1/π) ∫_cap max(0, ω_z) dω` for a cap of angular radius σ ∈ [0, π/2] whose centre makes
/// the angle ω ∈ [0, π] with the normal.
///
/// Snyder 1996, "Area light sources for real-time graphics" (Microsoft Research
/// MSR-TR-96-11), the irradiance from a horizon-clipped spherical source; in the form that
/// Heitz & Hill 2017 ("Real-Time Line- and Disk-Light Shading with Linearly Transformed
/// Cosines", SIGGRAPH course; selfshadow/ltc_code `fit/fitLTC.cpp`, `ihemi`) tabulate:
/// with `γ = asin(cos σ / sin ω)`,
/// * `ω ≤ π/2 − σ` (the cap entirely above): `π cos ω sin²σ`;
/// * `π/2 − σ < ω < π/2`: `π cos ω sin²σ + G − H`;
/// * `π/2 ≤ ω < π/2 + σ`: `G + H`;
/// * beyond: 0;
///
/// where `G = −2 sin ω cos σ cos γ + π/2 − γ + sin γ cos γ` and
/// `H = cos ω (cos γ √(sin²σ − cos²γ) + sin²σ asin(cos γ / sin σ))`.
pub fn cap_clamped_cosine(omega: f64, sigma: f64) -> Result<f64, LtcError> {
    if !(omega.is_finite() && sigma.is_finite()) {
        return Err(LtcError::NotFinite {
            what: "a cap angle",
        });
    }
    if !((0.0..=PI).contains(&omega) && (0.0..=FRAC_PI_2).contains(&sigma)) {
        return Err(LtcError::Domain(format!(
            "cap angles need omega in [0, pi] and sigma in [0, pi/2], got {omega}, {sigma}"
        )));
    }
    let (sw, cw) = omega.sin_cos();
    let (ss, cs) = sigma.sin_cos();
    let s2 = ss * ss;
    if omega <= FRAC_PI_2 - sigma {
        return Ok(cw * s2);
    }
    if omega >= FRAC_PI_2 + sigma {
        return Ok(0.0);
    }
    // here sin ω ≥ cos σ > 0 … up to rounding: clamp the asin arguments
    let g = (cs / sw).clamp(-1.0, 1.0).asin();
    let (sg, cg) = g.sin_cos();
    let gg = -2.0 * sw * cs * cg + FRAC_PI_2 - g + sg * cg;
    let h = cw * (cg * (s2 - cg * cg).max(0.0).sqrt() + s2 * (cg / ss).clamp(-1.0, 1.0).asin());
    let v = if omega < FRAC_PI_2 {
        PI * cw * s2 + gg - h
    } else {
        gg + h
    };
    Ok((v / PI).clamp(0.0, 1.0))
}

/// The horizon-clipped sphere table of Heitz & Hill 2017 (the `ltc_disk_integral` of
/// EEVEE, the 4th channel of Heitz's `ltc_2`): for a vector form factor of length `len =
/// sin²σ` ∈ (0, 1] and direction cosine `z = cos ω` ∈ [−1, 1], the clipped cap's integral
/// divided by `len`, so that a shader's clipped result is `len · table(z, len)`; at
/// `len = 0`, the limit `max(z, 0)` (selfshadow/ltc_code `fit/fitLTC.cpp`, `genSphereTab`).
pub fn clipped_sphere_table(z: f64, len: f64) -> Result<f64, LtcError> {
    if !(z.is_finite() && len.is_finite()) {
        return Err(LtcError::NotFinite {
            what: "a sphere-table coordinate",
        });
    }
    if !((-1.0..=1.0).contains(&z) && (0.0..=1.0).contains(&len)) {
        return Err(LtcError::Domain(format!(
            "sphere table needs z in [-1, 1] and len in [0, 1], got {z}, {len}"
        )));
    }
    if len == 0.0 {
        return Ok(z.max(0.0));
    }
    let sigma = len.sqrt().asin();
    let omega = z.acos();
    Ok(cap_clamped_cosine(omega, sigma)? / len)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(center: [f64; 3], h: f64) -> Vec<[f64; 3]> {
        // a small square around `center` (assumed = +z here), CCW about +z
        vec![
            [center[0] - h, center[1] - h, center[2]],
            [center[0] + h, center[1] - h, center[2]],
            [center[0] + h, center[1] + h, center[2]],
            [center[0] - h, center[1] + h, center[2]],
        ]
    }

    #[test]
    fn upper_hemisphere_is_one() {
        // a square "polygon" whose cone is the whole upper half-space, clipped at z = 0:
        // its vertices on the horizon (z slightly negative clips exactly at z = 0)
        let v = vec![
            [1.0, 0.0, -1e-300],
            [0.0, 1.0, -1e-300],
            [-1.0, 0.0, -1e-300],
            [0.0, -1.0, -1e-300],
        ];
        // all below (z < 0): nothing left
        assert_eq!(clamped_cosine_integral(&v).unwrap(), 0.0);
        let v = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ];
        // on the horizon exactly, points count as outside (z > 0 is inside): 0 again
        assert_eq!(clamped_cosine_integral(&v).unwrap(), 0.0);
        let v = [
            [1.0, 0.0, 1e-9],
            [0.0, 1.0, 1e-9],
            [-1.0, 0.0, 1e-9],
            [0.0, -1.0, 1e-9],
        ];
        let e = clamped_cosine_integral(&v).unwrap();
        assert!((e - 1.0).abs() < 1e-8, "{e}");
    }

    #[test]
    fn small_square_is_cosine_times_solid_angle() {
        let h = 1e-4;
        let e = clamped_cosine_integral(&quad([0.0, 0.0, 1.0], h)).unwrap();
        let want = 4.0 * h * h / PI; // solid angle (2h)² at distance 1, cos = 1
        assert!((e / want - 1.0).abs() < 1e-7, "{e} {want}");
        // reversed winding: negative
        let mut q = quad([0.0, 0.0, 1.0], h);
        q.reverse();
        assert!((clamped_cosine_integral(&q).unwrap() + e).abs() < 1e-20);
    }

    #[test]
    fn identity_ltc_is_the_cosine() {
        let q = quad([0.0, 0.0, 1.0], 0.3);
        let a = clamped_cosine_integral(&q).unwrap();
        let b = ltc_polygon_integral(&Ltc::IDENTITY, &q).unwrap();
        assert_eq!(a, b);
    }

    #[test]
    fn cap_limits() {
        // whole cap above: π cos ω sin²σ / π
        let v = cap_clamped_cosine(0.3, 0.2).unwrap();
        assert!((v - 0.3f64.cos() * 0.2f64.sin().powi(2)).abs() < 1e-15);
        // whole upper hemisphere as a cap of radius π/2 at the pole
        assert!((cap_clamped_cosine(0.0, FRAC_PI_2).unwrap() - 1.0).abs() < 1e-15);
        // a hemisphere tilted by γ: (1 + cos γ)/2
        for g in [0.3, 1.0, 1.4, 2.0] {
            let v = cap_clamped_cosine(g, FRAC_PI_2).unwrap();
            assert!((v - 0.5 * (1.0 + f64::cos(g))).abs() < 1e-12, "{g}: {v}");
        }
        assert_eq!(cap_clamped_cosine(2.0, 0.3).unwrap(), 0.0);
        assert!(cap_clamped_cosine(f64::NAN, 0.3).is_err());
        assert!(clipped_sphere_table(2.0, 0.3).is_err());
        assert_eq!(clipped_sphere_table(0.5, 0.0).unwrap(), 0.5);
    }

    #[test]
    fn bad_vertices_are_errors() {
        assert!(clamped_cosine_integral(&[[0.0; 3], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]]).is_err());
        assert!(clamped_cosine_integral(&[[f64::NAN, 0.0, 1.0]]).is_err());
        assert_eq!(clamped_cosine_integral(&[[1.0, 0.0, 1.0]]).unwrap(), 0.0);
    }
}
