//! Fixed quadrature rules: Gauss–Kronrod G7/K15 and Gauss–Legendre of any order.
//!
//! The G7/K15 pair is the one QUADPACK's `qk15` uses (Piessens et al., *QUADPACK*, 1983);
//! the node and weight values below are the published ones (Kronrod 1965, to 33 digits),
//! kept verbatim so they can be checked against the source (f64 rounds them on parsing).
#![allow(clippy::excessive_precision)]

/// Kronrod nodes on [-1, 1] (non-negative half; the rule is symmetric). Odd indices are
/// the 7-point Gauss nodes.
pub const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];

/// Kronrod weights matching [`XGK`].
pub const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];

/// 7-point Gauss weights for the nodes `XGK[1], XGK[3], XGK[5], XGK[7]`.
pub const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// The 15 Kronrod abscissae mapped to `[a, b]`, in a fixed order (left to right).
#[inline]
pub fn k15_nodes(a: f64, b: f64) -> [f64; 15] {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let mut x = [0.0; 15];
    for j in 0..7 {
        x[j] = c - h * XGK[j];
        x[14 - j] = c + h * XGK[j];
    }
    x[7] = c;
    x
}

/// Gauss–Legendre nodes and weights on [-1, 1] of order `n`, computed by Newton's
/// iteration on the three-term recurrence (Golub–Welsch would do as well; Newton from
/// Tricomi's initial guess converges to full f64 precision in a few steps).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1);
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let m = n.div_ceil(2);
    for i in 0..m {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre_and_derivative(n, z);
            dp = d;
            let dz = p / d;
            z -= dz;
            if dz.abs() <= 1e-16 {
                let (_, d) = legendre_and_derivative(n, z);
                dp = d;
                break;
            }
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

fn legendre_and_derivative(n: usize, z: f64) -> (f64, f64) {
    let mut p0 = 1.0;
    let mut p1 = z;
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * z * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    if n == 1 {
        return (z, 1.0);
    }
    let d = n as f64 * (z * p1 - p0) / (z * z - 1.0);
    (p1, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// K15 integrates polynomials up to degree 22 exactly and G7 up to degree 13, so the
    /// only error is f64 rounding of ~15 terms of size O(1): a few ulps, bounded by 1e-14.
    #[test]
    fn kronrod_and_gauss_are_exact_on_polynomials() {
        for deg in 0..=22u32 {
            let exact = if deg % 2 == 0 {
                2.0 / (deg as f64 + 1.0)
            } else {
                0.0
            };
            let xs = k15_nodes(-1.0, 1.0);
            let mut k = 0.0;
            for (j, x) in xs.iter().enumerate() {
                let wj = if j < 8 { WGK[j] } else { WGK[14 - j] };
                k += wj * x.powi(deg as i32);
            }
            assert!(
                (k - exact).abs() < 1e-14,
                "K15 degree {deg}: {k} vs {exact}"
            );
            if deg <= 13 {
                let mut g = 0.0;
                for (j, wg) in WG.iter().enumerate() {
                    let xn = XGK[2 * j + 1];
                    g += wg * xn.powi(deg as i32);
                    if j < 3 {
                        g += wg * (-xn).powi(deg as i32);
                    }
                }
                assert!((g - exact).abs() < 1e-14, "G7 degree {deg}: {g} vs {exact}");
            }
        }
    }

    /// An n-point Gauss–Legendre rule is exact to degree 2n−1 (rounding bound as above,
    /// growing mildly with n: 1e-13 for n ≤ 64).
    #[test]
    fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
        for n in [1usize, 2, 3, 7, 16, 33, 64] {
            let (x, w) = gauss_legendre(n);
            for deg in 0..(2 * n) as i32 {
                let exact = if deg % 2 == 0 {
                    2.0 / (deg as f64 + 1.0)
                } else {
                    0.0
                };
                let s: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(deg)).sum();
                assert!((s - exact).abs() < 1e-13, "n={n} deg={deg}: {s}");
            }
        }
    }
}
