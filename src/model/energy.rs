//! Energy compensation of single-scattering microfacet BRDFs.
//!
//! **Kulla & Conty 2017** ("Revisiting Physically Based Shading at Imageworks", SIGGRAPH
//! course *Physically Based Shading in Theory and Practice*, the energy compensation part): with E(μ) the
//! directional albedo of the lobe at F = 1 and E_avg = 2∫₀¹ E(μ) μ dμ its cosine-weighted
//! average, the multiple-scattering lobe
//!
//! `f_ms(μo, μi) = (1 − E(μo))(1 − E(μi)) / (π (1 − E_avg))`
//!
//! has directional albedo exactly 1 − E(μo) (because 2π∫₀¹(1 − E(μi)) μi dμi = π(1 − E_avg)),
//! so f + f_ms passes the white furnace test. With a Fresnel term, f_ms is scaled by
//!
//! `F_avg² E_avg / (1 − F_avg (1 − E_avg))`, `F_avg = 2∫₀¹ F(μ) μ dμ`,
//!
//! the sum over k ≥ 1 bounces of F_avg^(k+1) E_avg (1 − E_avg)^k divided by f_ms's own
//! average albedo 1 − E_avg (their Fresnel extension).
//!
//! **Turquin 2019** ("Practical multiple scattering compensation for microfacet models",
//! Industrial Light & Magic technical report): scale the single-scattering lobe by
//! `1 + F0 (1 − E(μo))/E(μo)` with E the F = 1 albedo (the `G` channel of a Filament `dfg`
//! table); at F0 = 1 the compensated albedo E·(1 + (1 − E)/E) is exactly 1.

use super::fresnel::Fresnel;
use crate::quadrature::{integrate, Tolerance};
use std::f64::consts::PI;

/// F_avg of Schlick's Fresnel in closed form: 2∫₀¹ (F0 + (1 − F0)(1 − μ)⁵) μ dμ
/// = F0 + (1 − F0)·2·B(2, 6) = F0 + (1 − F0)/21 = (20 F0 + 1)/21 (the value Kulla & Conty 2017 give).
pub fn f_avg_schlick(f0: f64) -> f64 {
    (20.0 * f0 + 1.0) / 21.0
}

/// F_avg = 2∫₀¹ F(μ) μ dμ of any Fresnel term, by adaptive Gauss–Kronrod to absolute
/// tolerance `tol` (the exact forms are smooth in μ except at the critical angle of a
/// dielectric seen from inside, η < 1, which is a panel boundary here). Returns (value, error).
pub fn f_avg(fresnel: &Fresnel, tol: f64) -> (f64, f64) {
    let mut breaks = vec![0.0, 1.0];
    if let Fresnel::Dielectric { eta } = *fresnel {
        if eta < 1.0 {
            // total internal reflection for μ < μc = √(1 − η²)
            breaks.insert(1, (1.0 - eta * eta).sqrt());
        }
    }
    let mut v = 0.0;
    let mut e = 0.0;
    for w in breaks.windows(2) {
        let r = integrate(
            |mu: f64| [2.0 * fresnel.eval(mu) * mu],
            w[0],
            w[1],
            Tolerance {
                abs: 0.5 * tol,
                initial_panels: 4,
                max_depth: 40,
                ..Default::default()
            },
        );
        v += r.value[0];
        e += r.error[0];
    }
    (v, e)
}

/// Kulla–Conty's Fresnel factor of the multiple-scattering lobe:
/// `F_avg² E_avg / (1 − F_avg (1 − E_avg))` (1 when F_avg = 1).
pub fn kulla_conty_fresnel_factor(f_avg: f64, e_avg: f64) -> f64 {
    f_avg * f_avg * e_avg / (1.0 - f_avg * (1.0 - e_avg))
}

/// Kulla–Conty's multiple-scattering lobe `(1 − E(μo))(1 − E(μi)) / (π (1 − E_avg))` at F = 1
/// from the two directional albedos and the average; 0 when E_avg = 1 (no energy is lost).
pub fn kulla_conty_f_ms(e_o: f64, e_i: f64, e_avg: f64) -> f64 {
    if e_avg >= 1.0 {
        return 0.0;
    }
    (1.0 - e_o) * (1.0 - e_i) / (PI * (1.0 - e_avg))
}

/// Turquin's compensation factor `1 + F0 (1 − E)/E` for the single-scattering lobe, with E
/// the F = 1 directional albedo (Turquin 2019).
pub fn turquin_factor(f0: f64, e: f64) -> f64 {
    1.0 + f0 * (1.0 - e) / e
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form agrees with the quadrature of the same Schlick term (tolerance 1e-12
    /// requested, the integrand is a polynomial of degree 6: K15 is exact to rounding).
    #[test]
    fn schlick_f_avg_closed_form() {
        for f0 in [0.0, 0.04, 0.5, 1.0] {
            let (v, _) = f_avg(&Fresnel::Schlick { f0 }, 1e-12);
            assert!((v - f_avg_schlick(f0)).abs() < 1e-13, "{f0}: {v}");
        }
    }

    /// The Fresnel factor is the geometric series of the bounces divided by f_ms's albedo
    /// 1 − E_avg, summed here explicitly (terms decay like (F_avg (1 − E_avg))^k ≤ 0.9^k:
    /// 400 terms leave < 1e-18).
    #[test]
    fn fresnel_factor_is_the_bounce_series() {
        for (fa, ea) in [(1.0, 0.4), (0.9, 0.5), (0.3, 0.9), (0.05, 0.7)] {
            let mut sum = 0.0;
            for k in 1..400 {
                sum += f64::powi(fa, k + 1) * ea * f64::powi(1.0 - ea, k);
            }
            let want = sum / (1.0 - ea);
            assert!((kulla_conty_fresnel_factor(fa, ea) - want).abs() < 1e-14);
        }
        assert!((kulla_conty_fresnel_factor(1.0, 0.37) - 1.0).abs() < 1e-15);
    }
}
