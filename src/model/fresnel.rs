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

/// The generalized Schlick weight `(1 − c)^e` of F = F0 + (F90 − F0)(1 − c)^e (Cycles'
/// generalized Schlick Fresnel with a non-negative exponent; e = 5 is Schlick 1994; 1 at
/// e = 0).
#[inline]
pub fn generalized_schlick_weight(c: f64, e: f64) -> f64 {
    (1.0 - c).clamp(0.0, 1.0).powf(e)
}

/// The exact dielectric Fresnel reflectance normalized to Schlick's form,
/// `saturate((F(c; η) − F0)/(1 − F0))` with F0 = ((η − 1)/(η + 1))², so that
/// F0 + (1 − F0)·w = F(c; η) (Cycles' generalized Schlick Fresnel with a negative exponent
/// remaps the real Fresnel this way, `bsdf_microfacet.h`, and its `gen_schlick_ior_s` table
/// averages w). 0 at η = 1 for c > 0, 1 under total internal reflection.
#[inline]
pub fn normalized_dielectric_weight(c: f64, eta: f64) -> f64 {
    let r = (eta - 1.0) / (eta + 1.0);
    let f0 = r * r;
    ((dielectric(c, eta) - f0) / (1.0 - f0)).clamp(0.0, 1.0)
}

/// Where [`normalized_dielectric_weight`] has a kink inside (0, 1): the cosine c* at which
/// F(c; η) falls below F0 (for η above ≈ 3.7 the unpolarized F dips below its normal value
/// between c* and 1, around Brewster's angle, and the weight is clamped to 0 there), or
/// `None` (η < 1: total internal reflection keeps F ≥ F0; η ≤ 3.7: F ≥ F0 throughout). Found
/// by scanning c geometrically from 1e-9 to 1 − 1e-6 for the first c with
/// F − F0 < −1e-12 (below that a dip is rounding; the kink it would make is below any
/// tolerance) and bisecting the bracket to rounding.
pub fn normalized_dielectric_kink(eta: f64) -> Option<f64> {
    if eta <= 1.0 {
        return None;
    }
    let r = (eta - 1.0) / (eta + 1.0);
    let f0 = r * r;
    let g = |c: f64| dielectric(c, eta) - f0;
    const STEPS: usize = 2000;
    let (lo_exp, hi) = (-9.0f64, 1.0 - 1e-6);
    let mut prev = 0.0;
    for k in 0..=STEPS {
        let c = (10f64.powf(lo_exp * (1.0 - k as f64 / STEPS as f64))).min(hi);
        if g(c) < -1e-12 {
            let (mut a, mut b) = (prev, c);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if m <= a || m >= b {
                    break;
                }
                if g(m) < 0.0 {
                    b = m;
                } else {
                    a = m;
                }
            }
            return Some(0.5 * (a + b));
        }
        prev = c;
    }
    None
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

    /// The kink of the normalized dielectric weight: F(c*) = F0 to rounding, F > F0 just
    /// below c* and F < F0 just above (so the weight is clamped to 0 there); none at or
    /// below η = 3.3 (F ≥ F0 throughout, checked on a grid), one from η = 4.6 on.
    #[test]
    fn normalized_dielectric_kink_is_where_f_falls_below_f0() {
        let f0 = |eta: f64| ((eta - 1.0) / (eta + 1.0)).powi(2);
        for eta in [0.5, 1.0, 1.5, 2.6, 3.3] {
            assert_eq!(normalized_dielectric_kink(eta), None, "eta {eta}");
            if eta > 1.0 {
                assert!((1..1000).all(|i| dielectric(i as f64 / 1000.0, eta) >= f0(eta) - 1e-12));
            }
        }
        for eta in [4.556, 7.036, 14.52, 99.5] {
            let c = normalized_dielectric_kink(eta).expect("a kink");
            assert!(
                (dielectric(c, eta) - f0(eta)).abs() < 1e-12,
                "eta {eta}: c* = {c}"
            );
            assert!(dielectric(c * (1.0 - 1e-3), eta) > f0(eta), "eta {eta}");
            assert!(dielectric(c * (1.0 + 1e-3), eta) < f0(eta), "eta {eta}");
            assert_eq!(normalized_dielectric_weight(c * (1.0 + 1e-3), eta), 0.0);
        }
    }

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
