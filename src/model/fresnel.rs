//! Fresnel reflectance F(v·h).

/// A Fresnel term.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Fresnel {
    /// F = 1: tables that factor the Fresnel term out, or white-furnace tests.
    None,
    /// Schlick (1994): `F = F0 + (1 − F0)(1 − v·h)⁵`.
    Schlick { f0: f64 },
    /// Exact unpolarized Fresnel for a dielectric with relative index η (Cook & Torrance
    /// 1982, eq. 10; Walter et al. 2007, eq. 22). Total internal reflection gives 1.
    Dielectric { eta: f64 },
    /// Exact unpolarized Fresnel for a conductor with complex index η + i·k (e.g. pbrt-v4,
    /// `FrComplex`).
    Conductor { eta: f64, k: f64 },
}

impl Fresnel {
    pub fn name(&self) -> &'static str {
        match self {
            Fresnel::None => "none",
            Fresnel::Schlick { .. } => "schlick",
            Fresnel::Dielectric { .. } => "dielectric",
            Fresnel::Conductor { .. } => "conductor",
        }
    }

    pub fn formula(&self) -> &'static str {
        match self {
            Fresnel::None => "F = 1",
            Fresnel::Schlick { .. } => "F = F0 + (1 - F0)(1 - v.h)^5",
            Fresnel::Dielectric { .. } => {
                "F = 1/2 (g-c)^2/(g+c)^2 (1 + ((c(g+c)-1)/(c(g-c)+1))^2), c = v.h, g = sqrt(eta^2 - 1 + c^2); F = 1 under total internal reflection"
            }
            Fresnel::Conductor { .. } => "F = (|r_s|^2 + |r_p|^2)/2 with complex eta + i k",
        }
    }

    /// Checks the parameters; the message names the field and the accepted range.
    pub fn validate(&self) -> Result<(), String> {
        match *self {
            Fresnel::None => Ok(()),
            Fresnel::Schlick { f0 } => {
                if f0.is_finite() && (0.0..=1.0).contains(&f0) {
                    Ok(())
                } else {
                    Err(format!(
                        "fresnel.f0 must be in [0, 1], got {f0}",
                        f0 = crate::numfmt::num(f0)
                    ))
                }
            }
            Fresnel::Dielectric { eta } => {
                if eta.is_finite() && eta > 0.0 && eta <= 100.0 {
                    Ok(())
                } else {
                    Err(format!(
                        "fresnel.eta must be in (0, 100], got {eta}",
                        eta = crate::numfmt::num(eta)
                    ))
                }
            }
            Fresnel::Conductor { eta, k } => {
                if !(eta.is_finite() && eta > 0.0 && eta <= 100.0) {
                    Err(format!(
                        "fresnel.eta must be in (0, 100], got {eta}",
                        eta = crate::numfmt::num(eta)
                    ))
                } else if !(k.is_finite() && (0.0..=100.0).contains(&k)) {
                    Err(format!(
                        "fresnel.k must be in [0, 100], got {k}",
                        k = crate::numfmt::num(k)
                    ))
                } else {
                    Ok(())
                }
            }
        }
    }

    #[inline]
    pub fn eval(&self, v_dot_h: f64) -> f64 {
        let c = v_dot_h.clamp(0.0, 1.0);
        match *self {
            Fresnel::None => 1.0,
            Fresnel::Schlick { f0 } => f0 + (1.0 - f0) * schlick_weight(c),
            Fresnel::Dielectric { eta } => dielectric(c, eta),
            Fresnel::Conductor { eta, k } => conductor(c, eta, k),
        }
    }
}

/// Schlick's weight Fc = (1 − c)⁵.
#[inline]
pub fn schlick_weight(c: f64) -> f64 {
    let m = 1.0 - c;
    let m2 = m * m;
    m2 * m2 * m
}

/// The F82-tint weight `c (1 − c)⁶` (Hoffman 2023, "Generalization of Adobe's Fresnel
/// Model"; Kutz, Hasan & Edmondson 2021): F = F_Schlick(c) − b·c(1 − c)⁶, whose peak at
/// c = 1/7 (θ ≈ 82°) sets the tint.
#[inline]
pub fn f82_tint_weight(c: f64) -> f64 {
    let m = (1.0 - c).clamp(0.0, 1.0);
    let m3 = m * m * m;
    c * m3 * m3
}

/// Unpolarized dielectric Fresnel reflectance.
#[inline]
pub fn dielectric(c: f64, eta: f64) -> f64 {
    let g2 = eta * eta - 1.0 + c * c;
    if g2 < 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// [`dielectric`] for η ≥ 1 (no total internal reflection) and `c` ∈ [0, 1], with one
/// division instead of three: with `g = √(η² − 1 + c²)`, `a = (g − c)/(g + c)` and
/// `b = (c(g + c) − 1)/(c(g − c) + 1)` (Cook & Torrance 1982, eq. 10),
/// `F = ½a²(1 + b²) = ½(g − c)²(d² + n²)/((g + c)² d²)` with `n`, `d` the numerator and
/// denominator of b (`d ≥ 1`, `g + c > 0` there). Equal to [`dielectric`] to rounding (unit
/// test below); for the hot loops of the V-groove albedo kernel.
#[inline]
pub fn dielectric_one_division(c: f64, eta: f64) -> f64 {
    let g = (eta * eta - 1.0 + c * c).sqrt();
    let (p, m) = (g + c, g - c);
    let (n, d) = (c * p - 1.0, c * m + 1.0);
    0.5 * m * m * (d * d + n * n) / (p * p * d * d)
}

/// Unpolarized conductor Fresnel reflectance for complex index η + ik.
pub fn conductor(c: f64, eta: f64, k: f64) -> f64 {
    // complex arithmetic on (re, im) pairs
    let mul = |a: (f64, f64), b: (f64, f64)| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let div = |a: (f64, f64), b: (f64, f64)| {
        let d = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    let sqrt = |a: (f64, f64)| {
        let r = (a.0 * a.0 + a.1 * a.1).sqrt();
        let re = ((r + a.0) * 0.5).max(0.0).sqrt();
        let im = ((r - a.0) * 0.5).max(0.0).sqrt().copysign(a.1);
        (re, im)
    };
    let n = (eta, k);
    let sin2 = 1.0 - c * c;
    let n2 = mul(n, n);
    let sin2_t = div((sin2, 0.0), n2);
    let cos_t = sqrt((1.0 - sin2_t.0, -sin2_t.1));
    let ci = (c, 0.0);
    let nci = mul(n, ci);
    let nct = mul(n, cos_t);
    let r_parl = div(
        (nci.0 - cos_t.0, nci.1 - cos_t.1),
        (nci.0 + cos_t.0, nci.1 + cos_t.1),
    );
    let r_perp = div((ci.0 - nct.0, ci.1 - nct.1), (ci.0 + nct.0, ci.1 + nct.1));
    let norm = |a: (f64, f64)| a.0 * a.0 + a.1 * a.1;
    0.5 * (norm(r_parl) + norm(r_perp))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At normal incidence both exact forms reduce to ((η−1)² + k²)/((η+1)² + k²); a
    /// conductor with k = 0 is a dielectric. Rounding-level tolerances.
    #[test]
    fn exact_forms_agree() {
        for &eta in &[1.1f64, 1.5, 2.4] {
            let r0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((dielectric(1.0, eta) - r0).abs() < 1e-15);
            for i in 1..=10 {
                let c = i as f64 / 10.0;
                assert!(
                    (dielectric(c, eta) - conductor(c, eta, 0.0)).abs() < 1e-14,
                    "{eta} {c}"
                );
            }
        }
        let (eta, k) = (0.2f64, 3.0f64);
        let r0 = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        assert!((conductor(1.0, eta, k) - r0).abs() < 1e-14);
        assert!((dielectric(1e-9, 1.5) - 1.0).abs() < 1e-6); // grazing → 1
        assert_eq!(dielectric(0.1, 1.0 / 1.5), 1.0); // total internal reflection
    }

    /// The one-division form equals the three-division one to rounding (a few operations
    /// on numbers ≤ ~η²: 1e-15 relative) over c ∈ [0, 1] and η ∈ [1, 4], ends included
    /// (except c = 0 at η = 1, where g = c = 0 makes both forms 0/0: no interface, and a
    /// grazing direction the kernels never evaluate there).
    #[test]
    fn one_division_dielectric_matches() {
        for &eta in &[1.0f64, 1.0001, 1.33, 1.5, 2.4, 4.0] {
            for i in (eta == 1.0) as usize..=1000 {
                let c = i as f64 / 1000.0;
                let (a, b) = (dielectric(c, eta), dielectric_one_division(c, eta));
                assert!(
                    (a - b).abs() <= 1e-15 * a.max(1e-300),
                    "eta {eta} c {c}: {a} {b}"
                );
            }
        }
    }
}
