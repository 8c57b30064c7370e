//! Importance-sampled Monte Carlo with Hammersley points: the method other LUT bakers use,
//! kept here only as the baseline of the convergence study (`brdfbake report`,
//! `cargo run --release --example convergence`). brdfbake never bakes a table with it.
//!
//! **Points.** The N-point Hammersley set `x_i = (i/N, Φ₂(i))`, Φ₂ the base-2 radical
//! inverse (Hammersley & Handscomb, *Monte Carlo Methods*, 1964, §3.5; in the form Karis
//! uses for his split-sum table, "Real Shading in Unreal Engine 4", 2013, p. 4). For three
//! dimensions the third coordinate is the base-3 radical inverse Φ₃(i).
//!
//! **Sampling the half vector.** h is drawn with density `p(h) = D(h)(n·h)` (w.r.t. dω_h),
//! φ = 2πξ₁ and, inverting the CDF of θh: GGX `tan²θh = α² ξ₂/(1 − ξ₂)`, Beckmann
//! `tan²θh = −α² ln(1 − ξ₂)` (Walter et al. 2007, eqs. 28, 35). The reflected direction
//! l = 2(v·h)h − v then has density `p(l) = D(h)(n·h)/(4 v·h)` (Walter et al. 2007, eq. 14),
//! and the estimator of `I = ∫ g(l) dω_l` is `(1/N) Σ g(l_i)/p(l_i)`, where samples with
//! l below the horizon (or v·h ≤ 0) contribute **0** but still count in N: that is the
//! unbiased estimator. Dividing by the number of *valid* samples instead — a common slip —
//! is biased: it over-estimates I by the factor 1/P(n·l > 0), which does not vanish as N
//! grows (at grazing views and high roughness a large share of the reflected directions
//! fall below the horizon). Both are returned so the bias can be shown.
//!
//! **Uniform sampling.** For lobes not concentrated at the normal (the Charlie sheen NDF,
//! as Filament's `cmgen` does for its cloth channel), l is drawn uniformly over the
//! hemisphere: cos θl = ξ₂, φ = 2πξ₁, `p(l) = 1/(2π)`.

use crate::hemisphere::Node;
use crate::model::{Ndf, NdfKind};
use std::f64::consts::PI;

/// The base-b radical inverse of i: its base-b digits mirrored about the radix point.
pub fn radical_inverse(mut i: u64, base: u64) -> f64 {
    let inv = 1.0 / base as f64;
    let mut f = inv;
    let mut r = 0.0;
    while i > 0 {
        r += (i % base) as f64 * f;
        i /= base;
        f *= inv;
    }
    r
}

/// The i-th point of the N-point 2D Hammersley set: (i/N, Φ₂(i)).
pub fn hammersley(i: u64, n: u64) -> (f64, f64) {
    (i as f64 / n as f64, radical_inverse(i, 2))
}

/// How directions are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sampling {
    /// h with density D(h)(n·h) of this NDF (GGX or Beckmann, which have closed-form
    /// inverse CDFs), l reflected about h.
    Ndf(NdfKind, f64),
    /// l uniform over the hemisphere.
    Uniform,
}

/// A Monte Carlo estimate: the unbiased value (÷ N), the biased one (÷ valid samples),
/// the number of samples N (= integrand evaluations) and how many were valid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct McEstimate<const N: usize> {
    pub unbiased: [f64; N],
    pub biased: [f64; N],
    pub samples: u64,
    pub valid: u64,
}

/// The half-vector node for a view with n·v = `mu` (v in the xz-plane) and a micro-normal
/// at (sin θh, cos θh, φ); `None` when l is below the horizon or v·h ≤ 0.
fn node_from_h(mu: f64, sin_v: f64, sin_h: f64, cos_h: f64, cos_phi: f64) -> Option<Node> {
    let v_dot_h = sin_v * sin_h * cos_phi + mu * cos_h;
    let n_dot_l = 2.0 * v_dot_h * cos_h - mu;
    if v_dot_h <= 0.0 || n_dot_l <= 0.0 {
        return None;
    }
    Some(Node {
        n_dot_v: mu,
        n_dot_l,
        n_dot_h: cos_h,
        v_dot_h,
        sin2_h: sin_h * sin_h,
    })
}

/// Draws one direction from `(xi1, xi2)`; returns the node and the density p(l), or `None`
/// for an invalid sample (below the horizon).
pub fn sample(sampling: Sampling, mu: f64, xi1: f64, xi2: f64) -> Option<(Node, f64)> {
    let mu = mu.clamp(1e-12, 1.0);
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let cos_phi = (2.0 * PI * xi1).cos();
    match sampling {
        Sampling::Ndf(kind, alpha) => {
            let tan2 = match kind {
                NdfKind::Beckmann => -alpha * alpha * (1.0 - xi2).ln(),
                _ => alpha * alpha * xi2 / (1.0 - xi2).max(f64::MIN_POSITIVE),
            };
            let c2 = 1.0 / (1.0 + tan2);
            let cos_h = c2.sqrt();
            let sin_h = (tan2 * c2).sqrt();
            let n = node_from_h(mu, sin_v, sin_h, cos_h, cos_phi)?;
            let d = Ndf::new(kind, alpha).ok()?.d_cs(cos_h, n.sin2_h);
            let pdf = d * cos_h / (4.0 * n.v_dot_h);
            (pdf > 0.0 && pdf.is_finite()).then_some((n, pdf))
        }
        Sampling::Uniform => {
            let cos_l = xi2;
            let sin_l = (1.0 - cos_l * cos_l).max(0.0).sqrt();
            if cos_l <= 0.0 {
                return None;
            }
            // h = (v + l)/|v + l| with v = (sin_v, 0, mu), l = (sin_l cos φ, sin_l sin φ, cos_l)
            let sin_phi = (2.0 * PI * xi1).sin();
            let s = [sin_v + sin_l * cos_phi, sin_l * sin_phi, mu + cos_l];
            let len = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            if len <= 0.0 {
                return None;
            }
            let n = Node {
                n_dot_v: mu,
                n_dot_l: cos_l,
                n_dot_h: s[2] / len,
                v_dot_h: 0.5 * len,
                sin2_h: (s[0] * s[0] + s[1] * s[1]) / (len * len),
            };
            Some((n, 1.0 / (2.0 * PI)))
        }
    }
}

/// Estimates `∫ g dω_l` (g as for [`crate::hemisphere::integrate_over_l`]) for a view with
/// n·v = `mu` from the `n`-point Hammersley set.
pub fn estimate_over_l<const N: usize, F: Fn(&Node) -> [f64; N]>(
    mu: f64,
    sampling: Sampling,
    n: u64,
    g: F,
) -> McEstimate<N> {
    let mut sum = [0.0; N];
    let mut valid = 0u64;
    for i in 0..n {
        let (x1, x2) = hammersley(i, n);
        if let Some((node, pdf)) = sample(sampling, mu, x1, x2) {
            let y = g(&node);
            for c in 0..N {
                sum[c] += y[c] / pdf;
            }
            valid += 1;
        }
    }
    finish(sum, n, valid)
}

fn finish<const N: usize>(sum: [f64; N], n: u64, valid: u64) -> McEstimate<N> {
    let mut unbiased = [0.0; N];
    let mut biased = [0.0; N];
    for c in 0..N {
        unbiased[c] = sum[c] / n.max(1) as f64;
        biased[c] = sum[c] / valid.max(1) as f64;
    }
    McEstimate {
        unbiased,
        biased,
        samples: n,
        valid,
    }
}

/// Estimates `E_avg = 2∫₀¹ E(μ) μ dμ = ∫∫ g_μ dω_l p(μ) dμ` with μ drawn with density 2μ
/// (μ = √ξ₃, ξ₃ = Φ₃(i), the third Hammersley coordinate) and l as in [`estimate_over_l`]:
/// one integrand evaluation per point.
pub fn estimate_average<F: Fn(&Node) -> f64>(sampling: Sampling, n: u64, g: F) -> McEstimate<1> {
    let mut sum = 0.0;
    let mut valid = 0u64;
    for i in 0..n {
        let (x1, x2) = hammersley(i, n);
        let mu = radical_inverse(i, 3).sqrt();
        if mu <= 0.0 {
            continue;
        }
        if let Some((node, pdf)) = sample(sampling, mu, x1, x2) {
            sum += g(&node) / pdf;
            valid += 1;
        }
    }
    finish([sum], n, valid)
}

/// Estimates the projected area `∫ (v·h)⁺ D(h) dω_h = μ(1 + Λ(μ))` of `ndf` for a view with
/// n·v = μ (Heitz 2014, eq. 2), h drawn from the `proposal` NDF (density D_p(h)(n·h)):
/// `(1/N) Σ (v·h)⁺ D(h) / (D_p(h)(n·h))`. Smith G1 is then μ / estimate. Used for NDFs without a
/// closed-form Λ (the Gaussian), with a GGX proposal of the same α, whose polynomial tail
/// keeps the weight D/D_p bounded.
pub fn estimate_projected_area(ndf: &Ndf, proposal: &Ndf, mu: f64, n: u64) -> McEstimate<1> {
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let alpha = proposal.alpha();
    let mut sum = 0.0;
    let mut valid = 0u64;
    for i in 0..n {
        let (x1, x2) = hammersley(i, n);
        let tan2 = match proposal.kind() {
            NdfKind::Beckmann => -alpha * alpha * (1.0 - x2).ln(),
            _ => alpha * alpha * x2 / (1.0 - x2).max(f64::MIN_POSITIVE),
        };
        let c2 = 1.0 / (1.0 + tan2);
        let (cos_h, sin_h) = (c2.sqrt(), (tan2 * c2).sqrt());
        let v_dot_h = sin_v * sin_h * (2.0 * PI * x1).cos() + mu * cos_h;
        let dp = proposal.d_cs(cos_h, sin_h * sin_h);
        if dp > 0.0 && dp.is_finite() {
            valid += 1;
            if v_dot_h > 0.0 {
                sum += v_dot_h * ndf.d_cs(cos_h, sin_h * sin_h) / (dp * cos_h);
            }
        }
    }
    finish([sum], n, valid)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Φ₂ and Φ₃ of small integers, by hand: 1 → 1/2, 2 → 1/4, 3 → 3/4, 6 → 1/8 + 1/4;
    /// base 3: 1 → 1/3, 5 = 12₃ → 2/3 + 1/9.
    #[test]
    fn radical_inverse_digits() {
        for (i, want) in [(1u64, 0.5), (2, 0.25), (3, 0.75), (6, 0.375)] {
            assert_eq!(radical_inverse(i, 2), want);
        }
        assert!((radical_inverse(1, 3) - 1.0 / 3.0).abs() < 1e-15);
        assert!((radical_inverse(5, 3) - (2.0 / 3.0 + 1.0 / 9.0)).abs() < 1e-15);
    }

    /// ∫ (n·l) dω_l = π with uniform sampling: on the 2^k-point Hammersley set cos θ runs
    /// over {j/N}, so the estimate is 2π·(N − 1)/(2N) = π(1 − 1/N): error exactly π/N.
    /// D-sampling (GGX α = 0.8, grazing view μ = 0.2) with g = p(l) itself: every valid
    /// sample contributes exactly 1, so the unbiased estimate is the fraction of valid
    /// samples and the biased one is 1 — the bias made explicit (rounding: 1e-12).
    #[test]
    fn estimators_on_known_integrals() {
        let n = 4096;
        let e = estimate_over_l(0.7, Sampling::Uniform, n, |nd| [nd.n_dot_l]);
        assert!(
            (e.unbiased[0] - PI).abs() <= PI / n as f64 * (1.0 + 1e-12),
            "{e:?}"
        );
        let s = Sampling::Ndf(NdfKind::Ggx, 0.8);
        let e = estimate_over_l(0.2, s, n, |nd| {
            let d = Ndf::new(NdfKind::Ggx, 0.8)
                .unwrap()
                .d_cs(nd.n_dot_h, nd.sin2_h);
            [d * nd.n_dot_h / (4.0 * nd.v_dot_h)]
        });
        let frac = e.valid as f64 / n as f64;
        assert!(
            frac < 0.95,
            "grazing view, rough: some samples fall below the horizon"
        );
        assert!((e.unbiased[0] - frac).abs() < 1e-12, "{e:?}");
        assert!((e.biased[0] - 1.0).abs() < 1e-12, "{e:?}");
    }
}
