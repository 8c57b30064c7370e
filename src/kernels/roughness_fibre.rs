//! The integrals of a rough dielectric interface seen from the denser side (relative index
//! η < 1) at one view and several roughnesses, by one nested rule: a fibre along the
//! roughness axis (`dielectric-schlick`, `dielectric-btdf`, `dielectric-albedo`).
//!
//! **Why it can be shared.** Every panel boundary of an η < 1 integral over micro-normals
//! ([`crate::kernels::micro_normals`]) is a property of the geometry alone: the critical
//! cone v·h = √(1 − η²), the reflected and transmitted directions' horizons, and in φ where
//! those meet. None depends on α. So for up to [`ROUGHNESS_FIBRE`] GGX lobes the integrands
//! are the channels of one rule whose nodes compute v·h, the Fresnel or Schlick factor and
//! the refraction once, and only D and the masking per lobe (`Lobes::weights`, branch-free
//! so that it vectorizes). The rule's variable is the narrowest lobe's warp
//! u = asinh(tan θh/α) up to θh = 45° and θh itself beyond (`Rule::alphas`); every lobe
//! whose view is grazing on its own scale brings its own layer break in φ. A panel is refined
//! until every channel meets its share of the tolerance, and each texel keeps its own
//! channels' estimates.
//!
//! **Cost.** On EEVEE's `bsdf_ggx` grid (15 roughness layers, every 4th η and view texel;
//! `examples/schlick_probe.rs fibre 4`): 858 nodes per texel (a rule of 15 lobes takes ~2.4×
//! the nodes of one lobe's) against 6,028 per texel alone, each node ~3× the texel rule's,
//! 2.4× less time; the bake of `eevee-bsdf-ggx` took 5.3 s instead of 12.1 s (2 threads,
//! 2026-12-03).

use super::micro_normals::{integrate_micro_normals_into, Rule};
use crate::model::btdf::{MicroNormal, SmithForm};
use crate::model::{Ndf, NdfKind};
use crate::quadrature::Estimate;

/// Most roughnesses one rule serves. Measured on `eevee-bsdf-ggx` (15 layers, 2 threads):
/// 5 per rule 6.3 s, 8 per rule 6.3 s, 15 per rule 5.4 s (the nodes per rule grow with the
/// spread of α, but the shared part of each node is paid once for more lobes).
pub const ROUGHNESS_FIBRE: usize = 15;

/// Lanes of [`Lobes`]' arrays: [`ROUGHNESS_FIBRE`] rounded up to a multiple of 4 (AVX2).
const LANES: usize = ROUGHNESS_FIBRE.div_ceil(4) * 4;

/// Widest spread of α within one rule of [`roughness_fibre_with`]: the rule's variable is
/// the narrowest lobe's warp, in which a lobe s times wider grows like (s sinh u)² up to
/// the θ-tail, so a lobe far wider than the narrowest makes every panel before θh = 45°
/// take the finest levels. EEVEE's 15 layers, α = (k/15)², span 225 and go in one rule;
/// Cycles' roughness axes clamped at r = 1e-4 (α = 1e-8) put that texel in a rule of its
/// own.
pub const ROUGHNESS_SPREAD: f64 = 256.0;

/// [`roughness_rule`] for any number of GGX lobes `ndfs`: in runs of at most
/// [`ROUGHNESS_FIBRE`] lobes, in order of α (ties by position), whose α spans at most
/// [`ROUGHNESS_SPREAD`], one rule each. Returns each lobe's `K` channels in the order of
/// `ndfs`, with evaluations counted at each run's first (narrowest) lobe.
pub fn roughness_fibre_with<const N: usize, const K: usize>(
    ndfs: &[Ndf],
    smith: SmithForm,
    eta: f64,
    mu: f64,
    tol: f64,
    coef: impl Fn(f64) -> [[f64; 2]; K] + Copy,
) -> Vec<Estimate<K>> {
    let mut order: Vec<usize> = (0..ndfs.len()).collect();
    order.sort_by(|&a, &b| ndfs[a].alpha().total_cmp(&ndfs[b].alpha()).then(a.cmp(&b)));
    let mut out = vec![Estimate::<K>::zero(); ndfs.len()];
    let mut start = 0;
    while start < order.len() {
        let first = ndfs[order[start]].alpha();
        let len = order[start..]
            .iter()
            .take(ROUGHNESS_FIBRE)
            .take_while(|&&j| ndfs[j].alpha() <= ROUGHNESS_SPREAD * first)
            .count();
        let run = &order[start..start + len];
        let group: Vec<Ndf> = run.iter().map(|&j| ndfs[j].clone()).collect();
        let e = roughness_rule::<N, K>(&group, smith, eta, mu, tol, coef);
        for (k, &j) in run.iter().enumerate() {
            out[j] = Estimate {
                value: std::array::from_fn(|c| e.value[K * k + c]),
                error: std::array::from_fn(|c| e.error[K * k + c]),
                evals: if k == 0 { e.evals } else { 0 },
            };
        }
        start += len;
    }
    out
}

/// The integrals `∫ (a_j(c) w_r + b_j(c) w_t) dω_h`, j < `K`, of every lobe in `ndfs`
/// (GGX, at most [`ROUGHNESS_FIBRE`], any order) at one relative index `eta` < 1 and view
/// cosine `mu`, where `w_r = D c G(v, l_r)/(n·v)` and `w_t = D c G(v, l_t)/(n·v)` are each
/// lobe's weights of the reflected and the refracted direction (0 where that direction does
/// not leave on its side, or under total internal reflection) and `coef(c)` gives the
/// coefficients `[a_j, b_j]` at c = v·h: channel `K·k + j` is lobe k's j-th integral,
/// to absolute tolerance `tol` each (module docs). `evals` counts the inner nodes.
pub fn roughness_rule<const N: usize, const K: usize>(
    ndfs: &[Ndf],
    smith: SmithForm,
    eta: f64,
    mu: f64,
    tol: f64,
    coef: impl Fn(f64) -> [[f64; 2]; K],
) -> Estimate<N> {
    assert!(
        !ndfs.is_empty() && ndfs.len() <= ROUGHNESS_FIBRE && ndfs.len() * K <= N,
        "{} lobes of {K} channels in {N}",
        ndfs.len()
    );
    assert!(
        ndfs.iter()
            .all(|n| n.kind() == NdfKind::Ggx && n.alpha() > 0.0)
            && eta < 1.0,
        "GGX lobes, eta < 1"
    );
    let mu1 = mu.min(1.0);
    let lobes = Lobes::new(ndfs, smith, mu1);
    let alphas: Vec<f64> = ndfs.iter().map(Ndf::alpha).collect();
    // the narrowest lobe's warp
    let narrowest = ndfs
        .iter()
        .min_by(|a, b| a.alpha().total_cmp(&b.alpha()))
        .expect("a lobe");
    let etas = [eta];
    let rule = Rule {
        alphas: &alphas,
        ..Rule::standard(&etas)
    };
    integrate_micro_normals_into(
        narrowest,
        rule,
        mu,
        tol,
        |h: &MicroNormal, y: &mut [f64; N]| {
            // (y is zeroed: channels beyond the lobes' stay 0)
            let c = h.v_dot_h;
            if c <= 0.0 || mu1 <= 0.0 {
                return;
            }
            // the cosines of the reflected and refracted directions to the macro-surface, 0
            // where a direction does not leave on its own side (its masking vanishes there);
            // refraction l_t = (c/η − cos θt) h − v/η (Walter et al. 2007, eq. 40)
            let x_r = (2.0 * c * h.n_dot_h - mu1).clamp(0.0, 1.0);
            let s2t = (1.0 - c * c) / (eta * eta);
            let x_t = if s2t < 1.0 {
                (mu1 / eta - (c / eta - (1.0 - s2t).sqrt()) * h.n_dot_h).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut w = [[0.0; LANES]; 2];
            lobes.weights(h, c, [x_r, x_t], &mut w);
            let [wr, wt] = w;
            let ab = coef(c);
            for (k, y) in y.chunks_exact_mut(K).take(ndfs.len()).enumerate() {
                for (y, &[a, b]) in y.iter_mut().zip(&ab) {
                    *y = a * wr[k] + b * wt[k];
                }
            }
        },
    )
}

/// The per-roughness constants of [`roughness_rule`]'s GGX lobes, in fixed-size arrays
/// (unused lanes repeat the last lobe), so that the loop over them has no branch and
/// vectorizes.
struct Lobes {
    a2: [f64; LANES],
    one_minus_a2: [f64; LANES],
    /// G1(v) of each lobe
    g1v: [f64; LANES],
    /// 2 α² G1(v)/(π n·v): D c G/(n·v) = scale·c·x/(d² q) ([`Lobes::weights`])
    scale: [f64; LANES],
    height_correlated: bool,
}

impl Lobes {
    fn new(ndfs: &[Ndf], smith: SmithForm, mu: f64) -> Lobes {
        let mut l = Lobes {
            a2: [0.0; LANES],
            one_minus_a2: [0.0; LANES],
            g1v: [0.0; LANES],
            scale: [0.0; LANES],
            height_correlated: smith == SmithForm::HeightCorrelated,
        };
        for k in 0..LANES {
            let ndf = &ndfs[k.min(ndfs.len() - 1)];
            let a2 = ndf.alpha() * ndf.alpha();
            l.a2[k] = a2;
            l.one_minus_a2[k] = 1.0 - a2;
            l.g1v[k] = ndf.g1(mu);
            l.scale[k] = 2.0 * a2 * l.g1v[k] / (std::f64::consts::PI * mu);
        }
        l
    }

    /// Per lobe, `D c G(v, l)/(n·v)` per unit solid angle of h for the reflected and the
    /// refracted direction, whose cosines to the macro-surface are `x = [x_r, x_t]` (0:
    /// masked), into `w = [w_r, w_t]`. GGX: D = α²/(π d²) with d = sin²θh + α² cos²θh,
    /// G1(x) = 2x/(x + √(α² + (1 − α²)x²)) (`Ndf::d_cs`, `Ndf::g1`); G = G1(v) G1(l)
    /// (separable) or G1(v) G1(l)/(G1(v) + G1(l) − G1(v) G1(l)) (height-correlated), both
    /// 2x G1(v)/q with q = x + √(…) or G1(v)(x + √(…)) + 2x(1 − G1(v)); one division for both
    /// directions. On x86-64 with AVX2 the same code is compiled for it (four lobes per
    /// instruction): only correctly rounded additions, multiplications, divisions and square
    /// roots, none fused, in the same order, so both give the same bits.
    #[inline]
    fn weights(&self, h: &MicroNormal, c: f64, x: [f64; 2], w: &mut [[f64; LANES]; 2]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked above), all that `weights_avx2` requires.
            unsafe { self.weights_avx2(h, c, x, w) };
            return;
        }
        self.weights_portable(h, c, x, w);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn weights_avx2(&self, h: &MicroNormal, c: f64, x: [f64; 2], w: &mut [[f64; LANES]; 2]) {
        self.weights_portable(h, c, x, w);
    }

    #[inline(always)]
    fn weights_portable(&self, h: &MicroNormal, c: f64, x: [f64; 2], w: &mut [[f64; LANES]; 2]) {
        let c2 = h.n_dot_h * h.n_dot_h;
        let [x_r, x_t] = x;
        let (xr2, xt2) = (x_r * x_r, x_t * x_t);
        let [wr, wt] = w;
        if self.height_correlated {
            for k in 0..LANES {
                let d = h.sin2_h + self.a2[k] * c2;
                let g = self.g1v[k];
                let qr = g * (x_r + (self.a2[k] + self.one_minus_a2[k] * xr2).sqrt())
                    + 2.0 * x_r * (1.0 - g);
                let qt = g * (x_t + (self.a2[k] + self.one_minus_a2[k] * xt2).sqrt())
                    + 2.0 * x_t * (1.0 - g);
                let inv = self.scale[k] * c / (d * d * qr * qt);
                wr[k] = x_r * qt * inv;
                wt[k] = x_t * qr * inv;
            }
        } else {
            for k in 0..LANES {
                let d = h.sin2_h + self.a2[k] * c2;
                let qr = x_r + (self.a2[k] + self.one_minus_a2[k] * xr2).sqrt();
                let qt = x_t + (self.a2[k] + self.one_minus_a2[k] * xt2).sqrt();
                let inv = self.scale[k] * c / (d * d * qr * qt);
                wr[k] = x_r * qt * inv;
                wt[k] = x_t * qr * inv;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`Lobes::weights`] against the model's own D, G1 and masking forms (`Ndf::d_cs`,
    /// `Ndf::g1`, `SmithForm::g`) on a grid of micro-normals, cosines, views and both forms:
    /// the same formulas rearranged (one division for both directions), so equal to a few
    /// roundings: 1e-12 relative. Masked directions (x = 0) give exactly 0. And the AVX2
    /// build of the loop gives the same bits as the portable one.
    #[test]
    fn lobe_weights_are_the_models_d_and_masking() {
        let ndfs: Vec<Ndf> = [1e-4, 0.01, 0.2, 0.5, 1.0]
            .iter()
            .map(|&a| Ndf::new(NdfKind::Ggx, a).unwrap())
            .collect();
        for smith in [SmithForm::Separable, SmithForm::HeightCorrelated] {
            for mu in [1e-4, 0.3, 0.999] {
                let lobes = Lobes::new(&ndfs, smith, mu);
                for th in [1e-6, 0.3, 1.2, 1.57] {
                    let (s, c) = f64::sin_cos(th);
                    let h = MicroNormal {
                        n_dot_h: c,
                        sin2_h: s * s,
                        v_dot_h: 0.7,
                    };
                    for x in [[0.0, 0.4], [0.2, 0.0], [1e-3, 1.0], [0.8, 0.05]] {
                        let mut w = [[0.0; LANES]; 2];
                        lobes.weights(&h, h.v_dot_h, x, &mut w);
                        let mut p = [[0.0; LANES]; 2];
                        lobes.weights_portable(&h, h.v_dot_h, x, &mut p);
                        assert_eq!(w, p, "avx2 and portable builds differ");
                        for (k, ndf) in ndfs.iter().enumerate() {
                            let base = ndf.d_cs(h.n_dot_h, h.sin2_h) * h.v_dot_h / mu;
                            for d in 0..2 {
                                let want = base * smith.g(ndf.g1(mu), ndf.g1(x[d]));
                                let got = w[d][k];
                                if x[d] == 0.0 {
                                    assert_eq!(got, 0.0);
                                }
                                assert!(
                                    (got - want).abs() <= 1e-12 * want.abs(),
                                    "{smith:?} mu {mu} theta {th} x {x:?} alpha {}: {got} vs {want}",
                                    ndf.alpha()
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// Runs of [`roughness_fibre_with`]: at most [`ROUGHNESS_FIBRE`] lobes, α spanning at
    /// most [`ROUGHNESS_SPREAD`], in order of α whatever the input order, evaluations at each
    /// run's first lobe; a lobe 1e4 times narrower than the next goes alone.
    #[test]
    fn runs_respect_size_and_spread() {
        let mut alphas: Vec<f64> = (1..=16).map(|k| (k as f64 / 16.0).powi(2)).collect();
        alphas.push(1e-8);
        alphas.reverse();
        let ndfs: Vec<Ndf> = alphas
            .iter()
            .map(|&a| Ndf::new(NdfKind::Ggx, a).unwrap())
            .collect();
        let got = roughness_fibre_with::<ROUGHNESS_FIBRE, 1>(
            &ndfs,
            SmithForm::Separable,
            0.8,
            0.5,
            1e-5,
            |_| [[1.0, 0.0]],
        );
        // sorted by α: 1e-8 alone, then (1/16)² … (15/16)² (spread 225), then 1
        // (input order: 1e-8, then 1 down to (1/16)²)
        let counted: Vec<f64> = alphas
            .iter()
            .zip(&got)
            .filter(|(_, e)| e.evals > 0)
            .map(|(&a, _)| a)
            .collect();
        assert_eq!(counted, vec![1e-8, 1.0, (1.0f64 / 16.0).powi(2)]);
    }
}
