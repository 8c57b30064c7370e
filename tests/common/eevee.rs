//! What the EEVEE tests share: GLSL's `refract` as EEVEE's generators call it, and the bound
//! on the error of EEVEE's own Monte Carlo tables (tests/eevee_btdf.rs, tests/eevee_bsdf_ggx.rs).

#![allow(dead_code)]

/// GLSL `refract(I, N, r)`: `None` where k = 1 − r²(1 − (N·I)²) < 0.
pub fn refract(i: [f64; 3], n: [f64; 3], r: f64) -> Option<[f64; 3]> {
    let d = n[0] * i[0] + n[1] * i[1] + n[2] * i[2];
    let k = 1.0 - r * r * (1.0 - d * d);
    if k < 0.0 {
        return None;
    }
    let s = r * d + k.sqrt();
    Some([
        r * i[0] - s * n[0],
        r * i[1] - s * n[1],
        r * i[2] - s * n[2],
    ])
}

/// EEVEE's own error in a quoted texel of a table its LUT shader computes (512² Hammersley
/// samples in [0, 1] summed in float32, printed with 6 decimals). The float32 running sum
/// S_k stays ≤ k·m̄ and its k-th addition rounds by at most 2⁻²⁴ S_k, so the mean is off by at
/// most Σ 2⁻²⁴ k m̄/N ≤ 2⁻²⁴·N/2·m̄ = 2⁻⁷·m̄ ≤ 2⁻⁷ (7.8e-3; tests/engines.rs argues the same
/// for `bsdf_split_sum_ggx`; visible in `btdf_ggx`'s α = 0 layer, where every sample is the
/// same value: 0.744800 at y = 55 against the exact 1 − (1 − μ)⁵ = 0.742829). Its sampling
/// error: a sample's variance is at most 1/4, so independent samples give σ ≤ 0.5/512 ≈
/// 9.8e-4 (Hammersley points do better), taken at 3σ. Plus the quotes' 6 decimals (5e-7):
/// B = 2⁻⁷ + 3·0.5/512 + 5e-7 ≈ 1.07e-2.
pub const EEVEE_ERROR: f64 = 0.0078125 + 3.0 * 0.5 / 512.0 + 5e-7;
