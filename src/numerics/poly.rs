//! Polynomial forms of exp, sin and cos: plain arithmetic (no libm call), so that loops over
//! quadrature nodes that call them vectorize. Each is within a few ulp of libm, as its unit
//! test checks; the kernels use them where the same function is taken at thousands of nodes.

/// ln 2 split as fdlibm does: the high part has trailing zero bits, so `n·LN2_HI` is exact.
const LN2_HI: f64 = 6.931_471_803_691_238e-1;
const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;

/// e^x for |x| ≤ 700 by Cody–Waite reduction `x = n ln 2 + r`, |r| ≤ ln2/2, and the
/// degree-12 Taylor polynomial of e^r (Estrin's scheme) (truncation `|r|^13/13! < 2e-16` relative), scaled by
/// 2^n through the exponent bits: plain arithmetic, so loops that call it vectorize (libm's
/// exp is a call). Within a few ulp of `f64::exp` (unit test below). The reduction
/// constants are fdlibm's split of ln 2 (high part with trailing zero bits, so `n·LN2_HI`
/// is exact).
#[inline(always)]
pub fn exp_poly(x: f64) -> f64 {
    const LOG2E: f64 = std::f64::consts::LOG2_E;
    // round-to-nearest by the 1.5·2^52 trick: the low mantissa bits of `big` hold n
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let big = x * LOG2E + SHIFT;
    let n = big - SHIFT;
    let r = (x - n * LN2_HI) - n * LN2_LO;
    // Σ r^k/k!, k = 0..12, by Estrin's scheme (short dependency chains)
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let a01 = 1.0 + r;
    let a23 = 0.5 + r * (1.0 / 6.0);
    let a45 = 1.0 / 24.0 + r * (1.0 / 120.0);
    let a67 = 1.0 / 720.0 + r * (1.0 / 5_040.0);
    let a89 = 1.0 / 40_320.0 + r * (1.0 / 362_880.0);
    let a1011 = 1.0 / 3_628_800.0 + r * (1.0 / 39_916_800.0);
    let a12 = 1.0 / 479_001_600.0;
    let b0 = a01 + r2 * a23;
    let b1 = a45 + r2 * a67;
    let b2 = a89 + r2 * a1011;
    let p = (b0 + r4 * b1) + r8 * (b2 + r4 * a12);
    // 2^n: (n + 1023) << 52, with n from big's low bits (two's complement, |n| < 1023)
    let scale = f64::from_bits((big.to_bits() << 52).wrapping_add(1023u64 << 52));
    p * scale
}

/// (sin d, cos d) for |d| ≤ π/4 by their Taylor series to degrees 17 and 18 (truncation
/// < 1e-16), evaluated by Estrin's scheme in d² (a short dependency chain); sin d as d times
/// its series, so relatively accurate down to d → 0 (unit test below; the polar kernel's
/// lines take their half-angle sine and cosine from it).
#[inline(always)]
pub fn sin_cos_taylor(d: f64) -> (f64, f64) {
    let z = d * d;
    let z2 = z * z;
    let z4 = z2 * z2;
    let z8 = z4 * z4;
    let c = &SIN_C;
    let sd = d
        * (((c[0] + z * c[1]) + z2 * (c[2] + z * c[3]))
            + z4 * ((c[4] + z * c[5]) + z2 * (c[6] + z * c[7]))
            + z8 * c[8]);
    let c = &COS_C;
    let cd = ((c[0] + z * c[1]) + z2 * (c[2] + z * c[3]))
        + z4 * ((c[4] + z * c[5]) + z2 * (c[6] + z * c[7]))
        + z8 * (c[8] + z * c[9]);
    (sd, cd)
}

/// cos x for x ∈ [0, π] from [`sin_cos_taylor`] about 0, π/2 or π (|d| ≤ π/4), for
/// integrands taken at thousands of azimuths: glibc's `cos` was 19% of
/// `cycles-glass-inv-eavg` (`perf`). Absolute error a few 1e-16 (π/2 and π are rounded
/// to doubles: ≤ 1.3e-16 in d), as the unit test checks; outside [0, π] it is not cos.
#[inline(always)]
pub fn cos_0_pi(x: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
    if x <= FRAC_PI_4 {
        sin_cos_taylor(x).1
    } else if x < 3.0 * FRAC_PI_4 {
        // cos x = sin(π/2 − x)
        sin_cos_taylor(FRAC_PI_2 - x).0
    } else {
        // cos x = −cos(π − x)
        -sin_cos_taylor(PI - x).1
    }
}

/// (−1)^k/(2k+1)!, k = 0..11.
const SIN_C: [f64; 12] = [
    1.0,
    -1.0 / 6.0,
    1.0 / 120.0,
    -1.0 / 5_040.0,
    1.0 / 362_880.0,
    -1.0 / 39_916_800.0,
    1.0 / 6_227_020_800.0,
    -1.0 / 1_307_674_368_000.0,
    1.0 / 355_687_428_096_000.0,
    -1.0 / 121_645_100_408_832_000.0,
    1.0 / 51_090_942_171_709_440_000.0,
    -1.0 / 25_852_016_738_884_976_640_000.0,
];

/// (−1)^k/(2k)!, k = 0..12.
const COS_C: [f64; 13] = [
    1.0,
    -1.0 / 2.0,
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40_320.0,
    -1.0 / 3_628_800.0,
    1.0 / 479_001_600.0,
    -1.0 / 87_178_291_200.0,
    1.0 / 20_922_789_888_000.0,
    -1.0 / 6_402_373_705_728_000.0,
    1.0 / 2_432_902_008_176_640_000.0,
    -1.0 / 1_124_000_727_777_607_680_000.0,
    1.0 / 620_448_401_733_239_439_360_000.0,
];

#[cfg(test)]
mod tests {
    use super::*;

    /// exp_poly against the platform's exp over the range the kernels use (and beyond):
    /// relative difference ≤ 8 ulp (≈ 1.8e-15): reduction rounding (≤ 1 ulp of r, which
    /// is |r| ≤ 0.35), 13 Estrin terms and the final product, each ≤ 1 ulp, plus the
    /// reference's own ≤ 1 ulp.
    #[test]
    fn exp_poly_matches_exp() {
        let mut x = -700.0;
        while x <= 700.0 {
            let (a, b) = (exp_poly(x), x.exp());
            assert!((a - b).abs() <= 8.0 * f64::EPSILON * b, "x={x}: {a} vs {b}");
            x += 0.013_7;
        }
        assert_eq!(exp_poly(0.0), 1.0);
    }

    /// `f` against libm's `sin_cos` at n + 1 equally spaced points of [0, `hi`]: both
    /// absolute differences within `abs`; `sine` checks each (x, f's sine, libm's) further.
    fn check_sin_cos(
        f: impl Fn(f64) -> (f64, f64),
        hi: f64,
        n: usize,
        abs: f64,
        sine: impl Fn(f64, f64, f64),
    ) {
        for i in 0..=n {
            let x = hi * i as f64 / n as f64;
            let (s, c) = f(x);
            let (s0, c0) = x.sin_cos();
            assert!(
                (s - s0).abs() <= abs && (c - c0).abs() <= abs,
                "x={x}: {s} {c} vs {s0} {c0}"
            );
            sine(x, s, s0);
        }
    }

    /// `cos_0_pi` against libm's cos on [0, π] (every reduction branch and their seams):
    /// within 5e-16 absolute: the reduced argument's rounding (π/2, π as doubles, ≤ 1.3e-16,
    /// times |sin| ≤ 1), the series' ~2 ulp and libm's own ulp.
    #[test]
    fn cos_0_pi_matches_cos() {
        let n = 100_000;
        for i in 0..=n {
            let x = std::f64::consts::PI * i as f64 / n as f64;
            let (a, b) = (cos_0_pi(x), x.cos());
            assert!((a - b).abs() <= 5e-16, "x={x}: {a} vs {b}");
        }
        assert_eq!(cos_0_pi(0.0), 1.0);
    }

    /// `sin_cos_taylor`, which gives the polar kernel's lines their half-angle sine and
    /// cosine, against libm on [0, π/4]: within 3e-16 absolute (both are within ~2 ulp of
    /// the true values, which are at most 1) and 4e-16 relative for the sine, down to 1e-300
    /// (the lines near θl = 0 of a narrow lobe at the normal view need it relatively
    /// accurate).
    #[test]
    fn sin_cos_taylor_matches_libm() {
        check_sin_cos(
            sin_cos_taylor,
            std::f64::consts::FRAC_PI_4,
            100_000,
            3e-16,
            |x, s, s0| assert!((s - s0).abs() <= 4e-16 * s0, "x {x}: {s} vs {s0}"),
        );
        for x in [1e-300, 1e-20, 1e-8, 1e-3] {
            let (s, c) = sin_cos_taylor(x);
            assert!(
                (s - x.sin()).abs() <= 2e-16 * x && (c - x.cos()).abs() <= 2e-16,
                "x {x}"
            );
        }
    }
}
