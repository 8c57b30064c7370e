//! Linearly transformed cosines (LTC): the distribution that area-light tables store.
//!
//! Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
//! Transformed Cosines" (ACM TOG 35(4), §3): take the clamped cosine
//! `D_o(ω_o) = max(0, z_o)/π` (which integrates to 1 over the sphere) and push it through a
//! linear map `M`, `ω = Mω_o/|Mω_o|`. The density of ω is (their eq. 1, with the Jacobian of
//! their eq. 18)
//!
//! `D(ω) = D_o(M⁻¹ω/|M⁻¹ω|) · |det M⁻¹| / |M⁻¹ω|³`,
//!
//! which, since `D_o` is homogeneous, is `max(0, (M⁻¹ω)_z)·|det M⁻¹| / (π |M⁻¹ω|⁴)`: a
//! function of `M⁻¹` that is invariant under scaling `M⁻¹`. Its integral over any region
//! `P` is the cosine's integral over `M⁻¹P` (their eq. 2–3), which is why a table stores
//! `M⁻¹` and a shader transforms the polygon by it.
//!
//! **The isotropic case.** For an isotropic BRDF with the view `v = (sin θv, 0, cos θv)` in
//! the xz-plane, the lobe is symmetric under `y ↦ −y`, so `M` (and `M⁻¹`) has the form
//! `[[a, 0, b], [0, c, 0], [d, 0, e]]` (their §4, "Fitting", and the tables of their code,
//! selfshadow/ltc_code `fit/fitLTC.cpp`, which zero the other four entries). Up to scale
//! that is four numbers; [`Ltc`] fixes `e = 1` in `M⁻¹`.
//!
//! Everything here is a pure function of f64; the polygon integrals are in
//! [`crate::kernels::ltc_polygon`], the fit in [`crate::kernels::ltc_fit`].

use std::f64::consts::PI;

/// Why an LTC could not be built or used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LtcError {
    /// An entry of M⁻¹ (or an input vector) is NaN or infinite.
    #[error("LTC: {what} is not finite")]
    NotFinite { what: &'static str },
    /// M⁻¹ is singular or reverses orientation (det M⁻¹ ≤ 0): not a distribution.
    #[error("LTC: M^-1 = [[{a}, 0, {b}], [0, {c}, 0], [{d}, 0, 1]] has det <= 0 (need c > 0 and a - b*d > 0)")]
    NotInvertible { a: f64, b: f64, c: f64, d: f64 },
    /// A direction of length 0.
    #[error("LTC: {what} has length 0")]
    ZeroVector { what: &'static str },
    /// Arguments outside a function's domain.
    #[error("LTC: {0}")]
    Domain(String),
}

/// An isotropic LTC, stored by its inverse matrix
/// `M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]]` (rows), in the frame where the normal is +z and
/// the view lies in the xz-plane at positive x.
///
/// The (2, 2) entry is fixed to 1: `D` does not change when `M⁻¹` is scaled (see the module
/// doc), and the fitted lobes all have a positive (2, 2) entry. Layouts that store another
/// normalization (Heitz's textures divide by the middle entry `c`) convert with
/// [`Ltc::heitz_texel`] and [`Ltc::from_heitz_texel`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ltc {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
}

impl Ltc {
    /// The clamped cosine itself (`M = I`): the exact LTC of a Lambertian BRDF.
    pub const IDENTITY: Ltc = Ltc {
        a: 1.0,
        b: 0.0,
        c: 1.0,
        d: 0.0,
    };

    /// Builds an LTC from the four free entries of `M⁻¹`; refuses non-finite entries and
    /// matrices with `det M⁻¹ = c·(a − b·d) ≤ 0` (a singular map has no density; a negative
    /// determinant would mirror the polygon and flip the sign of its integral).
    pub fn new(a: f64, b: f64, c: f64, d: f64) -> Result<Ltc, LtcError> {
        if ![a, b, c, d].iter().all(|x| x.is_finite()) {
            return Err(LtcError::NotFinite {
                what: "an entry of M^-1",
            });
        }
        let k = a - b * d;
        if !(c > 0.0 && k > 0.0 && (c * k).is_finite() && c * k > 0.0) {
            return Err(LtcError::NotInvertible { a, b, c, d });
        }
        Ok(Ltc { a, b, c, d })
    }

    /// Builds an LTC from any 3×3 `M⁻¹` of the isotropic form `[[a, 0, b], [0, c, 0],
    /// [d, 0, e]]` (rows) with `e > 0`, dividing by `e`. The four zero entries must be 0.
    pub fn from_inverse_matrix(m: [[f64; 3]; 3]) -> Result<Ltc, LtcError> {
        if !m.iter().flatten().all(|x| x.is_finite()) {
            return Err(LtcError::NotFinite {
                what: "an entry of M^-1",
            });
        }
        if m[0][1] != 0.0 || m[1][0] != 0.0 || m[1][2] != 0.0 || m[2][1] != 0.0 {
            return Err(LtcError::Domain(
                "M^-1 is not of the isotropic form [[a,0,b],[0,c,0],[d,0,e]]".into(),
            ));
        }
        let e = m[2][2];
        if e.is_nan() || e <= 0.0 {
            return Err(LtcError::Domain(format!(
                "M^-1's (2,2) entry must be > 0, got {e}"
            )));
        }
        Ltc::new(m[0][0] / e, m[0][2] / e, m[1][1] / e, m[2][0] / e)
    }

    /// `M⁻¹` as rows.
    pub fn inverse_matrix(&self) -> [[f64; 3]; 3] {
        [
            [self.a, 0.0, self.b],
            [0.0, self.c, 0.0],
            [self.d, 0.0, 1.0],
        ]
    }

    /// `M` as rows: the xz block `[[a, b], [d, 1]]` inverts to
    /// `[[1, −b], [−d, a]]/(a − bd)`, the y entry to `1/c`.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        let k = self.a - self.b * self.d;
        [
            [1.0 / k, 0.0, -self.b / k],
            [0.0, 1.0 / self.c, 0.0],
            [-self.d / k, 0.0, self.a / k],
        ]
    }

    /// `det M⁻¹ = c·(a − b·d)` (> 0 for every [`Ltc`]).
    #[inline]
    pub fn det_inverse(&self) -> f64 {
        self.c * (self.a - self.b * self.d)
    }

    /// `M⁻¹ω`.
    #[inline]
    pub fn apply_inverse(&self, w: [f64; 3]) -> [f64; 3] {
        [
            self.a * w[0] + self.b * w[2],
            self.c * w[1],
            self.d * w[0] + w[2],
        ]
    }

    /// The density `D(ω) = max(0, q_z)·det M⁻¹/(π|q|⁴)`, `q = M⁻¹ω`, at a unit direction ω
    /// (Heitz et al. 2016, eq. 1 with `D_o = max(0, z)/π`; derivation in the module doc).
    /// Per steradian; integrates to 1 over the sphere.
    #[inline]
    pub fn eval(&self, w: [f64; 3]) -> f64 {
        let q = self.apply_inverse(w);
        if q[2] <= 0.0 {
            return 0.0;
        }
        let l2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
        q[2] * self.det_inverse() / (PI * l2 * l2)
    }

    /// A direction distributed by `D` from two uniform numbers in [0, 1): a cosine-weighted
    /// direction (Malley's method: a uniform point of the unit disk lifted to the
    /// hemisphere) mapped by `M` and normalized (Heitz et al. 2016, §3.2, "Importance
    /// sampling").
    pub fn sample(&self, u1: f64, u2: f64) -> [f64; 3] {
        let r = u1.clamp(0.0, 1.0).sqrt();
        let (s, c) = (2.0 * PI * u2).sin_cos();
        let o = [r * c, r * s, (1.0 - r * r).max(0.0).sqrt()];
        let m = self.matrix();
        let w = [
            m[0][0] * o[0] + m[0][2] * o[2],
            m[1][1] * o[1],
            m[2][0] * o[0] + m[2][2] * o[2],
        ];
        let l = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        [w[0] / l, w[1] / l, w[2] / l]
    }

    /// The direction of the lobe's maximum: the image `M·ẑ` of the cosine's peak,
    /// normalized (a linear map moves the maximum of `D_o` along with it only up to the
    /// Jacobian, so this is the lobe's *axis*, not always its exact arg max).
    pub fn axis(&self) -> [f64; 3] {
        let m = self.matrix();
        let w = [m[0][2], 0.0, m[2][2]];
        let l = (w[0] * w[0] + w[2] * w[2]).sqrt();
        [w[0] / l, 0.0, w[2] / l]
    }

    /// The part of the distribution above the horizon, `∫_{z>0} D dω`, in closed form.
    ///
    /// The upper hemisphere `{ω : ω_z > 0}` maps under `M⁻¹` to the hemisphere
    /// `{ω_o : n'·ω_o > 0}` with `n' = Mᵀẑ` (the third row of `M`, `(−d, 0, a)/(a − bd)`),
    /// and the clamped cosine's integral over a hemisphere whose pole makes the angle γ with
    /// ẑ is `(1 + cos γ)/2` (the projected solid angle of a half-space, clipped to the
    /// horizon: Lambert's edge formula over the great circle gives `π(1 + cos γ)/2`, divided
    /// by `π`). Here `cos γ = a/√(a² + d²)`.
    pub fn upper_hemisphere_mass(&self) -> f64 {
        let h = self.a.hypot(self.d);
        0.5 * (1.0 + self.a / h)
    }

    /// The singular values of `M⁻¹`, largest first: `c` and those of the xz block
    /// `[[a, b], [d, 1]]` (closed form for 2×2: with `E = (p + s)/2`, `F = (p − s)/2`,
    /// `G = (r + q)/2`, `H = (r − q)/2` of `[[p, q], [r, s]]`, they are `√(E² + H²) ±
    /// √(F² + G²)`; Blinn 1996, "Consider the lowly 2×2 matrix").
    pub fn singular_values(&self) -> [f64; 3] {
        let (p, q, r, s) = (self.a, self.b, self.d, 1.0);
        let e = 0.5 * (p + s);
        let f = 0.5 * (p - s);
        let g = 0.5 * (r + q);
        let h = 0.5 * (r - q);
        let big = e.hypot(h);
        let small = f.hypot(g);
        let mut sv = [big + small, (big - small).abs(), self.c];
        sv.sort_by(|x, y| y.total_cmp(x));
        sv
    }

    /// The 2-norm condition number of `M⁻¹` (of `M` too): largest over smallest singular
    /// value. A lobe of width α needs about 1/α (the map squeezes the cosine by α in x and
    /// y), so "well-conditioned" for a table means `cond·α` bounded, not `cond` small.
    pub fn condition_number(&self) -> f64 {
        let sv = self.singular_values();
        sv[0] / sv[2]
    }

    /// The four stored entries of Heitz's texture `ltc_1` (and three.js' `ltc_1`): `M⁻¹`
    /// divided by its middle entry `c`, as `(m00, m20, m02, m22)` = `(a, d, b, 1)/c` — in
    /// GLSL, `mat3(vec3(t.x, 0, t.y), vec3(0, 1, 0), vec3(t.z, 0, t.w))` (column-major)
    /// rebuilds `M⁻¹/c`. (selfshadow/ltc_code `fit/fitLTC.cpp`, `packTab`: `invM /=
    /// invM[1][1]`, then `invM[0][0], invM[0][2], invM[2][0], invM[2][2]` in glm's
    /// `[column][row]` indexing.)
    pub fn heitz_texel(&self) -> [f64; 4] {
        let c = self.c;
        [self.a / c, self.d / c, self.b / c, 1.0 / c]
    }

    /// The inverse of [`Ltc::heitz_texel`].
    pub fn from_heitz_texel(t: [f64; 4]) -> Result<Ltc, LtcError> {
        Ltc::from_inverse_matrix([[t[0], 0.0, t[2]], [0.0, 1.0, 0.0], [t[1], 0.0, t[3]]])
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    #[test]
    fn identity_is_the_clamped_cosine() {
        let l = Ltc::IDENTITY;
        let w = [0.6, 0.0, 0.8];
        assert!((l.eval(w) - 0.8 / PI).abs() < 1e-15);
        assert_eq!(l.eval([0.6, 0.0, -0.8]), 0.0);
        assert!((l.upper_hemisphere_mass() - 1.0).abs() < 1e-15);
        assert!((l.condition_number() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn matrix_inverts() {
        let l = Ltc::new(3.0, 0.7, 2.5, -0.4).unwrap();
        let (m, mi) = (l.matrix(), l.inverse_matrix());
        for i in 0..3 {
            for j in 0..3 {
                let p: f64 = (0..3).map(|k| m[i][k] * mi[k][j]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((p - want).abs() < 1e-14, "{i}{j}: {p}");
            }
        }
        let t = l.heitz_texel();
        let back = Ltc::from_heitz_texel(t).unwrap();
        for (x, y) in [(l.a, back.a), (l.b, back.b), (l.c, back.c), (l.d, back.d)] {
            assert!((x - y).abs() < 1e-14 * x.abs().max(1.0));
        }
    }

    #[test]
    fn refuses_bad_matrices() {
        assert!(Ltc::new(f64::NAN, 0.0, 1.0, 0.0).is_err());
        assert!(Ltc::new(1.0, 0.0, 0.0, 0.0).is_err());
        assert!(Ltc::new(1.0, 2.0, 1.0, 0.5).is_err()); // a − bd = 0
        assert!(Ltc::new(1.0, 0.0, -1.0, 0.0).is_err());
        assert!(Ltc::from_heitz_texel([1.0, 0.0, 0.0, 0.0]).is_err());
        assert!(Ltc::from_heitz_texel([1.0, 0.0, 0.0, f64::INFINITY]).is_err());
    }

    #[test]
    fn singular_values_of_a_shear() {
        // [[1, 1], [0, 1]]: singular values (1 ± √5)/2 in magnitude, golden ratio
        let l = Ltc::new(1.0, 1.0, 1.0, 0.0).unwrap();
        let sv = l.singular_values();
        let phi = 0.5 * (1.0 + 5f64.sqrt());
        assert!((sv[0] - phi).abs() < 1e-14 && (sv[2] - 1.0 / phi).abs() < 1e-14);
    }
}
