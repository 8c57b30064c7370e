//! The stated light distribution that LTC tables are judged on: lights, views and
//! roughnesses drawn at random from a seed, so that a fit can be tuned on one draw and judged
//! on another it never saw (a held-out draw).
//!
//! The fixed set of [`super::ltc_check`] (200 lights on a 10 × 10 grid of views and
//! roughnesses) puts many of its lights just above or across the horizon, where a lobe that
//! leaks is punished; a table tuned on it can win there and lose on lights placed otherwise.
//! This distribution is meant as a user's scene: lights anywhere above the horizon, a part
//! of them at or across it, every size from a spot to a wall, on the viewer's side too.
//!
//! **One case** ([`draw_cases`]), every number from a 64-bit LCG seeded by the caller:
//! * the view: `cos θv` uniform in [0.02, 1] (azimuth 0: the view is in the xz-plane);
//! * the roughness: perceptual `r` uniform in [0.02, 1] (α = r²);
//! * the light's centre direction: azimuth uniform in [0, 2π) (the viewer's side included);
//!   elevation with probability 0.7 uniform in solid angle above the horizon
//!   (`sin e` uniform in [0, 1]), else uniform in [−15°, 15°] (lights at the horizon,
//!   partly below it);
//! * its angular half-extent `σ` log-uniform in [0.01, 1] rad (0.6° to 57°);
//! * its plane tilted from facing the shading point by up to 75°, spun in itself uniformly;
//! * its shape: a rectangle (aspect ratio uniform in [0.25, 1]) or a triangle, even odds
//!   ([`place_light`](super::ltc_check) draws the shape and orientation);
//! * a light with nothing above the horizon is drawn again (its case keeps its view and
//!   roughness).
//!
//! The ground truth of a case is [`super::ltc_check::lit_reference`] (the light clipped to
//! the horizon, adaptive quadrature to relative 1e-7), the LTC's lit value
//! [`super::ltc_check::lit_ltc`] of the whole light, as a shader does.

use super::ltc_check::{
    contains, error_stats, lit_ltc, lit_reference, mirror, place_light, ErrorStats, Lcg,
    PolygonLight, Shape,
};
use crate::model::ltc::{Ltc, LtcError};
use crate::model::Brdf;
use rayon::prelude::*;
use std::f64::consts::PI;

/// One judged case: a light, a view cosine and a perceptual roughness.
#[derive(Clone, Debug, PartialEq)]
pub struct LightCase {
    pub light: PolygonLight,
    /// `cos θv`.
    pub mu: f64,
    /// Perceptual roughness (α = r²).
    pub r: f64,
}

/// A light distribution (module doc): the stated one is [`LightDistribution::STATED`]; the
/// others change one thing to see how far a verdict depends on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightDistribution {
    /// What the figures call it.
    pub name: &'static str,
    /// The share of lights centred in [−15°, 15°] of elevation (the rest uniform in solid
    /// angle above the horizon).
    pub horizon_share: f64,
    /// `true`: azimuths only on the viewer's side (within 90° of the view's), where an LTC
    /// that leaks overestimates and a published table with exact zeros cannot.
    pub viewer_side_only: bool,
    /// The range of the angular half-extent σ, radians (log-uniform).
    pub sigma: [f64; 2],
}

impl LightDistribution {
    /// The distribution the fit is judged on (module doc).
    pub const STATED: LightDistribution = LightDistribution {
        name: "stated",
        horizon_share: 0.3,
        viewer_side_only: false,
        sigma: [0.01, 1.0],
    };
    /// No light centred near the horizon.
    pub const ABOVE_HORIZON: LightDistribution = LightDistribution {
        name: "above the horizon",
        horizon_share: 0.0,
        viewer_side_only: false,
        sigma: [0.01, 1.0],
    };
    /// Lights on the viewer's side only, none centred near the horizon.
    pub const VIEWER_SIDE: LightDistribution = LightDistribution {
        name: "viewer's side",
        horizon_share: 0.0,
        viewer_side_only: true,
        sigma: [0.01, 1.0],
    };
    /// Small lights only (σ from 0.1° to 17°), none centred near the horizon.
    pub const SMALL: LightDistribution = LightDistribution {
        name: "small lights",
        horizon_share: 0.0,
        viewer_side_only: false,
        sigma: [0.002, 0.3],
    };
    /// Every distribution the figures report, the stated one first.
    pub const ALL: [LightDistribution; 4] = [
        Self::STATED,
        Self::ABOVE_HORIZON,
        Self::VIEWER_SIDE,
        Self::SMALL,
    ];
}

/// The seed of the draw the fit is tuned on.
pub const FIT_SEED: u64 = 1;
/// The seed of the held-out draw: never seen while tuning.
pub const HELD_OUT_SEED: u64 = 2;
/// Cases per draw.
pub const CASES: usize = 20_000;

/// `n` cases of the distribution `dist` (module doc) drawn from `seed`: the same on every
/// machine.
pub fn draw_cases(dist: &LightDistribution, seed: u64, n: usize) -> Vec<LightCase> {
    // a scrambled seed: nearby seeds start far apart in the LCG's sequence
    let mut rng = Lcg(seed
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(0xD1B5_4A32_D192_ED03));
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let mu = 0.02 + 0.98 * rng.next();
        let r = 0.02 + 0.98 * rng.next();
        let light = loop {
            let phi = if dist.viewer_side_only {
                PI * (rng.next() - 0.5)
            } else {
                2.0 * PI * rng.next()
            };
            let elevation = if rng.next() >= dist.horizon_share {
                rng.next().asin()
            } else {
                (-15.0 + 30.0 * rng.next()).to_radians()
            };
            let (se, ce) = elevation.sin_cos();
            let c = [ce * phi.cos(), ce * phi.sin(), se];
            let [lo, hi] = dist.sigma;
            let sigma = (lo.ln() + rng.next() * (hi / lo).ln()).exp();
            let shape = if rng.next() < 0.5 {
                Shape::Rectangle
            } else {
                Shape::Triangle
            };
            if let Some(l) = place_light(&mut rng, c, sigma, 75f64.to_radians(), shape) {
                break l;
            }
        };
        out.push(LightCase { light, mu, r });
    }
    out
}

/// The relative tolerance of the ground truth (its own error estimate is checked against
/// it case by case: [`ground_truth`] fails a case that misses it).
pub const TRUTH_TOL: f64 = 1e-7;

/// The ground truth of every case: the lit value of the light clipped to the horizon under
/// `brdf(α)` ([`lit_reference`]), to relative [`TRUTH_TOL`]. Cases are independent (the
/// result does not depend on the thread count).
pub fn ground_truth(
    cases: &[LightCase],
    brdf: &(dyn Fn(f64) -> Result<Brdf, String> + Sync),
) -> Result<Vec<f64>, LtcError> {
    cases
        .par_iter()
        .map(|c| {
            let alpha = c.r * c.r;
            let b = brdf(alpha).map_err(LtcError::Domain)?;
            let e = lit_reference(&b, alpha, c.mu, &c.light, TRUTH_TOL)?;
            if !(e.value > 0.0 && e.error <= 10.0 * TRUTH_TOL * e.value) {
                return Err(LtcError::Domain(format!(
                    "ground truth of a case (cos θv = {}, r = {}): {} ± {} misses relative {TRUTH_TOL:e}",
                    c.mu, c.r, e.value, e.error
                )));
            }
            Ok(e.value)
        })
        .collect()
}

/// A table's errors on a draw: over every case, and over the cases whose light holds the
/// mirror direction of the view (the highlight).
#[derive(Clone, Copy, Debug)]
pub struct Judged {
    pub all: ErrorStats,
    pub mirror: ErrorStats,
}

/// The relative error `|LTC − truth|/truth` of the lit value of every case, for a table
/// looked up by `ltc_at(cos θv, r) → (LTC, norm)` (between texels as the table's filter does).
pub fn judge(
    cases: &[LightCase],
    truth: &[f64],
    ltc_at: &(dyn Fn(f64, f64) -> Result<(Ltc, f64), LtcError> + Sync),
) -> Result<Judged, LtcError> {
    let res: Vec<(f64, f64, bool)> = cases
        .par_iter()
        .zip(truth)
        .map(|(c, &t)| {
            let (ltc, norm) = ltc_at(c.mu, c.r)?;
            let v = lit_ltc(&ltc, norm, &c.light)?;
            Ok(((v - t).abs() / t, v, contains(&c.light.verts, mirror(c.mu))))
        })
        .collect::<Result<_, LtcError>>()?;
    let all: Vec<(f64, f64)> = res.iter().map(|x| (x.0, x.1)).collect();
    let inside: Vec<(f64, f64)> = res.iter().filter(|x| x.2).map(|x| (x.0, x.1)).collect();
    Ok(Judged {
        all: error_stats(&all),
        mirror: error_stats(&inside),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::ltc_check::{contains, mirror};

    #[test]
    fn draws_are_fixed_distinct_and_cover_the_stated_places() {
        let a = draw_cases(&LightDistribution::STATED, FIT_SEED, 2000);
        assert_eq!(a, draw_cases(&LightDistribution::STATED, FIT_SEED, 2000));
        let b = draw_cases(&LightDistribution::STATED, HELD_OUT_SEED, 2000);
        assert!(
            a.iter().zip(&b).all(|(x, y)| x != y),
            "seeds give distinct draws"
        );
        for c in &a {
            assert!((0.02..=1.0).contains(&c.mu) && (0.02..=1.0).contains(&c.r));
            assert!(c.light.verts.iter().any(|p| p[2] > 0.0));
        }
        // the stated parts are all there: across the horizon, on the viewer's side, holding
        // the mirror direction (fractions from the distribution: 0.3·P(|e| < σ-ish) etc.,
        // loose bounds that a wrong draw — e.g. no below-horizon part — fails)
        let frac = |f: &dyn Fn(&LightCase) -> bool| {
            a.iter().filter(|c| f(c)).count() as f64 / a.len() as f64
        };
        let crossing = frac(&|c| c.light.crosses_horizon);
        let viewer_side = frac(&|c| {
            let m = c.light.verts.iter().fold(0.0, |s, p| s + p[0]);
            m > 0.0
        });
        let mirror_in = frac(&|c| contains(&c.light.verts, mirror(c.mu)));
        assert!((0.1..0.4).contains(&crossing), "{crossing}");
        assert!((0.4..0.6).contains(&viewer_side), "{viewer_side}");
        assert!((0.005..0.1).contains(&mirror_in), "{mirror_in}");
    }
}
