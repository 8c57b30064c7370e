//! MaterialX's directional-albedo table (issue 23; engine preset `materialx-albedo-table`):
//! R, G = Karis' A, B of GGX with height-correlated Smith at α = y, B = clamp(E, 0, 1) of the
//! "Imageworks" sheen (Charlie D with parameter max(y, 0.005), V = 1/(4(n·l + n·v − n·l n·v))),
//! 128², texel centres (MaterialX `mx_generate_albedo_table.glsl`, commit 4177b2c, Apache-2.0;
//! no table is shipped: MaterialXView renders it at start-up).
//!
//! **What MaterialX's estimator converges to.** Its GGX channels draw H from the visible
//! normals (Dupuy & Benyoub 2023), whose light density is p(l) = G1(v) D(h) (v·h)/(4 (n·v)(v·h))
//! = G1(v) D/(4 n·v); f·(n·l)/p = G2 F/G1(v), so the mean of G2·(1 − Fc, Fc)/G1(v) is
//! ∫(1 − Fc, Fc) f cos dω_l over the lights above the horizon: Karis' A, B (F = 1). Lights
//! below the horizon are not rejected but have n·l clamped to 1e-8, where G2 ≤ 2e-8/α: a leak
//! of at most 2e-8/(α G1(v)) per sample, added to the bounds below. Its sheen channel
//! samples l uniformly (density 1/(2π)): the mean of 2π f (n·l) is ∫ f cos dω_l. So the table
//! MaterialX approximates is exactly the `dfg` kind's A, B and cloth channel at α = y, the
//! cloth's α floored at 0.005 (`cloth_alpha_min`) and clamped to [0, 1] (`clamp01-sheen`).
//!
//! Tests: (a) the baked preset against the independent reference (tests/common/reference.rs)
//! at a spread of texels; (b) against MaterialX's own 64-point generator, written here again
//! from the shader, texel by texel, within that generator's error.

#[path = "common/reference.rs"]
mod reference;

#[path = "common/docs.rs"]
mod docs;

use brdfbake::lut::Lut;
use brdfbake::model::{Masking, NdfKind};
use brdfbake::preset::PresetTable;
use rayon::prelude::*;
use reference::RefModel;
use std::f64::consts::PI;

const REQ: f64 = 1e-6;
const REF_TOL: f64 = 1e-10;
const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;
/// MaterialX's sheen roughness floor (`mx_imageworks_sheen_brdf`: 1/max(r, 0.005)).
const SHEEN_MIN: f64 = 0.005;
const N: usize = 128;

fn preset_text() -> &'static str {
    brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == "materialx-albedo-table")
        .expect("engine preset materialx-albedo-table")
        .1
}

fn table(text: &str) -> PresetTable {
    let p = brdfbake::preset::parse(text, "materialx-albedo-table", "test").unwrap();
    p.tables.into_iter().next().unwrap()
}

/// The table as stored (R, G, B) and the table with the kind's channels (A, B, sheen).
fn bake(t: &PresetTable) -> Lut {
    t.stored(brdfbake::table::bake(&t.spec).unwrap())
}

/// Six indices spread over `0..n`, both ends included, and row/column 1.
fn spread(n: usize) -> Vec<usize> {
    let mut v: Vec<usize> = (0..6).map(|k| k * (n - 1) / 5).collect();
    v.push(1);
    v.sort();
    v.dedup();
    v
}

/// (A, B, clamp(E_sheen, 0, 1)) at (μ, α) by the independent reference, with its estimates:
/// the split sum in l-space polar coordinates (adaptive Gauss–Legendre), the sheen by the
/// reference for α ≥ 0.01 (its validated range, tests/accuracy.rs) and below by the library's
/// adaptive Gauss–Kronrod in half-vector coordinates (a different parameterization, rule and
/// estimate from the cloth kernels that bake the table), as tests/cloth_azimuth.rs does.
fn exact_ref(mu: f64, alpha: f64, sheen_alpha: f64) -> ([f64; 3], [f64; 3]) {
    assert!(
        alpha >= 1e-3,
        "the reference's validated range (tests/accuracy.rs)"
    );
    let m = RefModel::new(NdfKind::Ggx, alpha, Masking::SmithHeightCorrelated);
    let ab = reference::split_sum(&m, mu, REF_TOL);
    let (s, se) = if sheen_alpha >= 0.01 {
        let m = RefModel::new(NdfKind::Charlie, sheen_alpha, Masking::Ashikhmin);
        let r = reference::albedo(&m, mu, REF_TOL);
        (r.value[0], r.error)
    } else {
        let (v, e, _) = brdfbake::table::dfg::sheen_albedo_adaptive(sheen_alpha, mu, 1e-9);
        (v, e)
    };
    (
        [ab.value[0], ab.value[1], s.clamp(0.0, 1.0)],
        [ab.error, ab.error, se],
    )
}

/// Texel (i, j) of the stored table against [`exact_ref`] at (μ, α) given: |stored − reference|
/// within the table's estimate + the reference's + the f32 rounding of the stored value (both
/// estimates claim to bound their errors; the clamp is 1-Lipschitz, so it keeps the bound),
/// and within REQ.
fn check_texel(lut: &Lut, i: usize, j: usize, alpha: f64, sheen_alpha: f64) -> Vec<String> {
    let mu = lut.axes[0].coord(i);
    let (r, re) = exact_ref(mu, alpha, sheen_alpha);
    let mut f = Vec::new();
    for c in 0..3 {
        let got = lut.texel([i, j, 0], c) as f64;
        let d = (got - r[c]).abs();
        let bound = lut.error_estimate[c] + re[c] + F32_REL * r[c].abs();
        if d > REQ || d > bound {
            f.push(format!(
                "texel ({i},{j}) mu={mu} alpha={alpha} ch{c}: table {got}, reference {} diff {d:e} bound {bound:e}",
                r[c]
            ));
        }
    }
    f
}

/// (a) The preset's axes are MaterialX's (u = n·v, v = α, both (k + 0.5)/128), and its
/// values are the stated integrals: 7 × 7 texels (corners, row and column 1 — row 0 is the
/// only one below the sheen floor: α = 1/256 < 0.005 < 3/256) against the reference (the
/// split sum at 1e-10; the sheen at 1e-10, or by the library's adaptive integrator at 1e-9
/// below α = 0.01). Negative controls, which must fail the same check: the reference at
/// perceptual roughness (α = y²), and the sheen without the floor (α = 1/256 in row 0).
#[test]
fn materialx_table_matches_the_reference() {
    let t = table(preset_text());
    let lut = bake(&t);
    assert_eq!(lut.channels.len(), 3);
    for (k, a) in lut.axes.iter().enumerate() {
        assert_eq!(a.size, N, "axis {k}");
        for i in 0..N {
            let want = (i as f64 + 0.5) / N as f64;
            assert!((a.coord(i) - want).abs() < 1e-15, "axis {k} texel {i}");
        }
    }
    for j in 0..N {
        // the roughness coordinate is α itself
        assert!((lut.axes[1].alpha(j).unwrap() - (j as f64 + 0.5) / N as f64).abs() < 1e-15);
    }
    let idx = spread(N);
    let pairs: Vec<(usize, usize)> = idx
        .iter()
        .flat_map(|&i| idx.iter().map(move |&j| (i, j)))
        .collect();
    let failures: Vec<String> = pairs
        .par_iter()
        .flat_map(|&(i, j)| {
            let a = lut.axes[1].alpha(j).unwrap();
            check_texel(&lut, i, j, a, a.max(SHEEN_MIN))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));

    // negative control 1: perceptual roughness (α = y²) must not pass (rows from 25 on:
    // y² ≥ 0.04, inside the reference's range)
    let wrong: usize = pairs
        .par_iter()
        .filter(|&&(_, j)| j >= 25)
        .map(|&(i, j)| {
            let y = lut.axes[1].coord(j);
            check_texel(&lut, i, j, y * y, (y * y).max(SHEEN_MIN)).len()
        })
        .sum();
    assert!(wrong > 10, "perceptual roughness passed: {wrong} failures");
    // negative control 2: no sheen floor, row 0 (its sheen, not clamped to 1 away from grazing)
    let unfloored: usize = idx
        .par_iter()
        .map(|&i| {
            let a = lut.axes[1].alpha(0).unwrap();
            check_texel(&lut, i, 0, a, a).len()
        })
        .sum();
    assert!(unfloored >= 2, "the unfloored sheen passed row 0");
}

// ---------------------------------------------------------------------------------------
// MaterialX's generator, from the shader (mx_generate_albedo_table.glsl,
// mx_microfacet_specular.glsl, mx_microfacet_sheen.glsl, mx_microfacet.glsl), in f64.

/// `mx_spherical_fibonacci(i, n)`: ξ = ((i + 0.5)/n, fract((i + 1)·φ)), φ the golden ratio;
/// kept as (cos 2πξ₁, sin 2πξ₁, ξ₂), what both estimators take of it.
fn fibonacci(n: usize) -> Vec<[f64; 3]> {
    const GOLDEN: f64 = 1.618_033_988_749_895;
    (0..n)
        .map(|i| {
            let y = (i as f64 + 1.0) * GOLDEN;
            let phi = 2.0 * PI * (i as f64 + 0.5) / n as f64;
            [phi.cos(), phi.sin(), y - y.floor()]
        })
        .collect()
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

const EPS: f64 = 1e-8; // M_FLOAT_EPS

/// `mx_ggx_smith_G2`: height-correlated Smith of GGX.
fn g2(nl: f64, nv: f64, a: f64) -> f64 {
    let a2 = a * a;
    let ll = (a2 + (1.0 - a2) * nl * nl).sqrt();
    let lv = (a2 + (1.0 - a2) * nv * nv).sqrt();
    2.0 * nl * nv / (ll * nv + lv * nl)
}

/// `mx_ggx_smith_G1`: 2/(1 + √(1 + α² tan²θ)).
fn g1(nv: f64, a: f64) -> f64 {
    let c2 = nv * nv;
    let t2 = (1.0 - c2) / c2;
    2.0 / (1.0 + (1.0 + a * a * t2).sqrt())
}

/// `mx_ggx_dir_albedo_monte_carlo(NdotV, alpha, F0 = (1,0,0), F90 = (0,1,0)).xy` with the
/// point set `xi`: VNDF samples (Dupuy & Benyoub's spherical cap), no rejection below the
/// horizon, (Σ G2 (1 − Fc, Fc))/(G1(v) n).
fn mx_ggx(xi: &[[f64; 3]], nv: f64, a: f64) -> [f64; 2] {
    let nv = nv.clamp(EPS, 1.0);
    let v = [(1.0 - nv * nv).sqrt(), 0.0, nv];
    let vh = normalize([a * v[0], a * v[1], v[2]]);
    let (mut sa, mut sb) = (0.0, 0.0);
    for x in xi {
        let z = (1.0 - x[2]) * (1.0 + vh[2]) - vh[2];
        let st = (1.0 - z * z).clamp(0.0, 1.0).sqrt();
        let c = [st * x[0], st * x[1], z];
        let h = [c[0] + vh[0], c[1] + vh[1], c[2] + vh[2]];
        let h = normalize([a * h[0], a * h[1], h[2].max(0.0)]);
        let vdh = dot(v, h);
        let l = [
            2.0 * vdh * h[0] - v[0],
            2.0 * vdh * h[1] - v[1],
            2.0 * vdh * h[2] - v[2],
        ];
        let nl = l[2].clamp(EPS, 1.0);
        let vdh = vdh.clamp(EPS, 1.0);
        let fc = (1.0 - vdh).powi(5);
        let g = g2(nl, nv, a);
        sa += g * (1.0 - fc);
        sb += g * fc;
    }
    let k = g1(nv, a) * xi.len() as f64;
    [sa / k, sb / k]
}

/// `mx_imageworks_sheen_dir_albedo` by Monte Carlo with the point set `xi`: l uniform on the
/// hemisphere (cos θ = 1 − ξ₂), 2π f (n·l) averaged, clamped to [0, 1].
fn mx_sheen(xi: &[[f64; 3]], nv: f64, r: f64) -> f64 {
    let nv = nv.clamp(EPS, 1.0);
    let v = [(1.0 - nv * nv).sqrt(), 0.0, nv];
    let inv = 1.0 / r.max(SHEEN_MIN);
    let mut s = 0.0;
    for x in xi {
        let ct = 1.0 - x[2];
        let st = (1.0 - ct * ct).max(0.0).sqrt();
        let l = [x[0] * st, x[1] * st, ct];
        let h = normalize([l[0] + v[0], l[1] + v[1], l[2] + v[2]]);
        let nl = l[2].clamp(EPS, 1.0);
        let nh = h[2].clamp(EPS, 1.0);
        let sin2 = 1.0 - nh * nh;
        let d = (2.0 + inv) * sin2.powf(0.5 * inv) / (2.0 * PI);
        s += d / (4.0 * (nl + nv - nl * nv)) * nl * 2.0 * PI;
    }
    (s / xi.len() as f64).clamp(0.0, 1.0)
}

/// The generator's three channels at (x, y) with point set `xi`.
fn mx_texel(xi: &[[f64; 3]], x: f64, y: f64) -> [f64; 3] {
    let [a, b] = mx_ggx(xi, x, y);
    [a, b, mx_sheen(xi, x, y)]
}

/// The generator on the whole N² grid (texel (i, j) at ((i + 0.5)/N, (j + 0.5)/N), or at
/// (i/(N − 1), j/(N − 1)) with `endpoints`), n points per texel; axis 0 fastest.
fn mx_table(n: usize, endpoints: bool) -> Vec<[f64; 3]> {
    let xi = fibonacci(n);
    let c = |i: usize| {
        if endpoints {
            i as f64 / (N - 1) as f64
        } else {
            (i as f64 + 0.5) / N as f64
        }
    };
    (0..N * N)
        .into_par_iter()
        .map(|t| mx_texel(&xi, c(t % N), c(t / N)))
        .collect()
}

/// The 4096-point rule's largest error, allowed at every texel: 1e-3, about 3× the largest
/// |Q₄₀₉₆ − Q₆₅₅₃₆| found over a 35 × 35 spread of texels (every 4th and rows, columns 1, 2,
/// 127: 3.1e-4, 3.5e-4, 3.5e-4 for A, B and sheen, near grazing and small α), and checked
/// by the test at a spread of its own (where the 65536-point rule is within ~2e-5 of the
/// table: measured the same way).
const E_4096: f64 = 1e-3;

/// (b) brdfbake's table against MaterialX's generator (64 points, as MaterialXView runs it),
/// texel by texel over all 128², within that generator's error.
///
/// **The 64-point rule's error** per texel and channel is estimated from the same estimator
/// with 4096 points of the same family: |Q₆₄ − Q₄₀₉₆| + [`E_4096`] (the 4096-point rule's own
/// error, checked here at 19 × 19 texels against 65536 points: ≤ E_4096/2). Added: the
/// below-horizon leak (module doc; GGX channels), REQ (the table's accuracy; its estimates
/// are ≤ 1e-7) and the f32 rounding of the table's value. So |table − Q₆₄| ≤ bound is a
/// claim that could fail: it says that the table is where MaterialX's estimator converges,
/// at MaterialX's texel coordinates.
///
/// Negative controls (must fail the same bound): the generator on an α axis read as
/// perceptual roughness (the table baked with `quantity: perceptual`), and on endpoints
/// instead of centres (the table baked with `convention: endpoints` on both axes, from 0.001:
/// cosine 0 is no valid dfg texel, α = 0 no Charlie lobe).
///
/// Also reported: MaterialX's own table (Q₆₄) against brdfbake's (exact to ~1e-7, test (a)):
/// max and mean per channel — what brdfbake fixes in it.
#[test]
fn materialx_generator_converges_to_the_table() {
    let t = table(preset_text());
    let lut = bake(&t);
    let q64 = mx_table(64, false);
    let q4k = mx_table(4096, false);
    // the 4096-point rule's error at a spread (every 8th texel, rows and columns 1 and 2)
    let mut idx: Vec<usize> = (0..N).step_by(8).collect();
    idx.extend([1, 2, N - 1]);
    let spread: Vec<(usize, usize)> = idx
        .iter()
        .flat_map(|&i| idx.iter().map(move |&j| (i, j)))
        .collect();
    let fine = fibonacci(65536);
    let worst = spread
        .par_iter()
        .map(|&(i, j)| {
            let x = (i as f64 + 0.5) / N as f64;
            let y = (j as f64 + 0.5) / N as f64;
            let q = mx_texel(&fine, x, y);
            (0..3)
                .map(|c| (q4k[j * N + i][c] - q[c]).abs())
                .fold(0.0, f64::max)
        })
        .reduce(|| 0.0, f64::max);
    eprintln!(
        "the 4096-point rule vs 65536 points, largest difference at {} texels: {worst:.3e}",
        spread.len()
    );
    assert!(worst <= E_4096 / 2.0, "{worst}");
    let bound = |i: usize, j: usize, c: usize| -> f64 {
        let k = j * N + i;
        let x = (i as f64 + 0.5) / N as f64;
        let y = (j as f64 + 0.5) / N as f64;
        let leak = if c < 2 { 2e-8 / (y * g1(x, y)) } else { 0.0 };
        (q64[k][c] - q4k[k][c]).abs() + E_4096 + leak + REQ
    };
    let check = |l: &Lut| -> (usize, String) {
        let mut n = 0;
        let mut first = String::new();
        for j in 0..N {
            for i in 0..N {
                for (c, &want) in q64[j * N + i].iter().enumerate() {
                    let got = l.texel([i, j, 0], c) as f64;
                    let d = (got - want).abs();
                    let b = bound(i, j, c) + F32_REL * got.abs();
                    if d > b {
                        if n == 0 {
                            first = format!(
                                "texel ({i},{j}) ch{c}: table {got}, MaterialX {want}, diff {d:e} > bound {b:e}"
                            );
                        }
                        n += 1;
                    }
                }
            }
        }
        (n, first)
    };
    let (n, first) = check(&lut);
    assert_eq!(
        n, 0,
        "{n} texel channels outside the generator's error; first: {first}"
    );

    // MaterialX's own table against brdfbake's (= exact to the table's tolerance)
    let names = ["A", "B", "sheen"];
    let mut maxes = [0.0; 3];
    for c in 0..3 {
        let (mut max, mut sum, mut at) = (0.0f64, 0.0, (0, 0));
        let mut est_max = 0.0f64;
        for j in 0..N {
            for i in 0..N {
                let d = (q64[j * N + i][c] - lut.texel([i, j, 0], c) as f64).abs();
                sum += d;
                if d > max {
                    (max, at) = (d, (i, j));
                }
                est_max = est_max.max(bound(i, j, c));
            }
        }
        eprintln!(
            "MaterialX 64-point table, {}: error vs exact max {max:.3e} at texel {at:?}, mean {:.3e}; largest error bound {est_max:.3e}",
            names[c],
            sum / (N * N) as f64
        );
        maxes[c] = max;
    }
    docs::assert_says(
        "docs/engines.md",
        &format!(
            "that table is off by up to {} (A), {} (B) and {} (sheen)",
            brdfbake::numfmt::fig(maxes[0]),
            brdfbake::numfmt::fig(maxes[1]),
            brdfbake::numfmt::fig(maxes[2])
        ),
    );

    // negative controls
    let perceptual =
        table(&preset_text().replace(r#""quantity": "alpha""#, r#""quantity": "perceptual""#));
    let (n, _) = check(&bake(&perceptual));
    eprintln!("perceptual-roughness axis: {n} texel channels outside the bound");
    assert!(
        n > 1000,
        "a perceptual-roughness table passed ({n} failures)"
    );
    let endpoints = table(
        &preset_text()
            .replace(
                r#""cos_theta_v": { "size": 128 }"#,
                r#""cos_theta_v": { "size": 128, "convention": "endpoints", "range": [0.001, 1] }"#,
            )
            .replace(
                r#""quantity": "alpha" }"#,
                r#""quantity": "alpha", "convention": "endpoints", "range": [0.001, 1] }"#,
            ),
    );
    assert_eq!(endpoints.spec.axes[0].coord(127), 1.0);
    let (n, _) = check(&bake(&endpoints));
    eprintln!("endpoints axes: {n} texel channels outside the bound");
    assert!(n > 100, "an endpoints table passed ({n} failures)");
}
