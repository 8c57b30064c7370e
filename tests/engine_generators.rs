//! Unreal's PreIntegratedGF and LearnOpenGL's BRDF LUT (issue 23) against their engines'
//! own generators, written here again from the published listings: no table of either is
//! public (Unreal's ships under the UE EULA; LearnOpenGL renders its LUT at start-up), so the
//! generator is the engine's table.
//!
//! The generator (Karis 2013, "Real Shading in Unreal Engine 4", `IntegrateBRDF`; LearnOpenGL
//! `2.2.1.brdf.fs` is the same algorithm): V = (√(1 − μ²), 0, μ); for the 1024 Hammersley
//! points ξ = (i/1024, radical inverse of i), H from the GGX NDF (a = r², cos θh =
//! √((1 − ξ₂)/(1 + (a² − 1)ξ₂)), φ = 2πξ₁), L = 2(V·H)H − V; where n·l > 0:
//! G = G1(l)G1(v), Schlick-GGX G1(μ) = μ/(μ(1 − k) + k), k = a/2; w = G (v·h)/((n·h)(n·v)),
//! Fc = (1 − v·h)⁵, A += (1 − Fc) w, B += Fc w; (A, B)/1024. Its light density is
//! D (n·h)/(4 v·h), so w·(1 − Fc, Fc) is f cos/p with F = (1 − Fc, Fc): the estimator
//! converges to Karis' A, B with Schlick-GGX masking, k = α/2 — what the presets bake.
//!
//! Each test compares the baked preset with the 1024-point generator texel by texel, within
//! that generator's error (estimated per texel, see [`generator`]), and runs two negative
//! controls that must fail: the table with Karis' analytic-light k = (r + 1)²/8, and the
//! generator half a texel off (at (k + 1)/N instead of (k + 0.5)/N on both axes).

#[path = "common/docs.rs"]
mod docs;

use brdfbake::lut::Lut;
use brdfbake::numfmt::fig;
use brdfbake::preset::PresetTable;
use rayon::prelude::*;
use std::f64::consts::PI;

const REQ: f64 = 1e-6;
const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;

fn engine_table(name: &str, edit: &dyn Fn(&str) -> String) -> PresetTable {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no engine preset {name}"));
    let p = brdfbake::preset::parse(&edit(text), name, "test").unwrap();
    p.tables.into_iter().next().unwrap()
}

/// The table's computed values (A, B), before storage rounding (f32).
fn bake(t: &PresetTable) -> Lut {
    brdfbake::table::bake(&t.spec).unwrap()
}

/// `Hammersley(i, n)`: ξ = (i/n, the base-2 radical inverse of i, as `reversebits(i)·2⁻³²`),
/// kept as (cos 2πξ₁, sin 2πξ₁, ξ₂).
fn hammersley(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let r = (i as u32).reverse_bits() as f64 / 4_294_967_296.0;
            let phi = 2.0 * PI * i as f64 / n as f64;
            [phi.cos(), phi.sin(), r]
        })
        .collect()
}

/// `IntegrateBRDF(Roughness, NoV)` with the point set `xi` (module doc).
fn integrate_brdf(xi: &[[f64; 3]], roughness: f64, nv: f64) -> [f64; 2] {
    let a = roughness * roughness;
    let k = a / 2.0;
    let g1 = |m: f64| m / (m * (1.0 - k) + k);
    let v = [(1.0 - nv * nv).sqrt(), 0.0, nv];
    let (mut sa, mut sb) = (0.0, 0.0);
    for x in xi {
        let ct = ((1.0 - x[2]) / (1.0 + (a * a - 1.0) * x[2])).sqrt();
        let st = (1.0 - ct * ct).max(0.0).sqrt();
        let h = [st * x[0], st * x[1], ct];
        let vh = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
        let nl = (2.0 * vh * h[2] - v[2]).clamp(0.0, 1.0);
        let nh = h[2].clamp(0.0, 1.0);
        let vh = vh.clamp(0.0, 1.0);
        if nl > 0.0 {
            let g = g1(nv) * g1(nl);
            let w = g * vh / (nh * nv);
            let fc = (1.0 - vh).powi(5);
            sa += (1.0 - fc) * w;
            sb += fc * w;
        }
    }
    let n = xi.len() as f64;
    [sa / n, sb / n]
}

/// The engine table's texels compared: (i, j) of an nx × ny table (u = n·v, v = perceptual
/// roughness, centres).
struct Grid {
    nx: usize,
    ny: usize,
    texels: Vec<(usize, usize)>,
}

impl Grid {
    /// Texel (i, j)'s (n·v, roughness), shifted by `shift` texels on both axes.
    fn at(&self, i: usize, j: usize, shift: f64) -> (f64, f64) {
        (
            (i as f64 + 0.5 + shift) / self.nx as f64,
            (j as f64 + 0.5 + shift) / self.ny as f64,
        )
    }
}

/// The generator's 1024-point values at the grid's texels, shifted by `shift` texels, and each
/// one's error bound.
///
/// **The 1024-point rule's error** per texel and channel is estimated from the same
/// estimator with 16384 Hammersley points: |Q₁₀₂₄ − Q₁₆₃₈₄| + `e16k`, the 16384-point
/// rule's own error, checked in [`run`] at a spread of texels against 262144 points
/// (≤ e16k/2 there). e16k is about 3× the largest |Q₁₆₃₈₄ − Q₂₆₂₁₄₄| found at that spread
/// (Unreal's grid 9.8e-4, LearnOpenGL's 2.1e-3: at the most grazing column, where the
/// weight's 1/(n·v), n·v = 1/256 or 1/1024, makes D-sampling noisy). Added per texel ([`compare`]): REQ (the table's accuracy; its
/// estimates are ≤ 1e-7) and the f32 rounding of the table's value.
fn generator(g: &Grid, shift: f64, e16k: f64) -> Vec<([f64; 2], [f64; 2])> {
    let (x1, x16) = (hammersley(1024), hammersley(16384));
    g.texels
        .par_iter()
        .map(|&(i, j)| {
            let (mu, r) = g.at(i, j, shift);
            let (q1, q16) = (integrate_brdf(&x1, r, mu), integrate_brdf(&x16, r, mu));
            let e = |c: usize| (q1[c] - q16[c]).abs() + e16k;
            (q1, [e(0), e(1)])
        })
        .collect()
}

/// The largest |Q₁₆₃₈₄ − Q₂₆₂₁₄₄| over every `step`-th texel of the grid (and its first two
/// and last rows and columns), both channels.
fn fine_rule_error(g: &Grid, step: usize) -> f64 {
    let (x16, x256) = (hammersley(16384), hammersley(262144));
    let pick = |n: usize| {
        let mut v: Vec<usize> = (0..n).step_by(step).collect();
        v.extend([1, n - 1]);
        v.sort();
        v.dedup();
        v
    };
    let (is, js) = (pick(g.nx), pick(g.ny));
    let texels: Vec<(usize, usize)> = js
        .iter()
        .flat_map(|&j| is.iter().map(move |&i| (i, j)))
        .collect();
    texels
        .par_iter()
        .map(|&(i, j)| {
            let (mu, r) = g.at(i, j, 0.0);
            let (p, q) = (integrate_brdf(&x16, r, mu), integrate_brdf(&x256, r, mu));
            (p[0] - q[0]).abs().max((p[1] - q[1]).abs())
        })
        .reduce(|| 0.0, f64::max)
}

/// The number of texel channels where |table − generator| exceeds the generator's error
/// bound (+ REQ + f32 rounding), and the first such one.
fn compare(
    lut: &Lut,
    g: &Grid,
    gen: &[([f64; 2], [f64; 2])],
    bounds: &[([f64; 2], [f64; 2])],
) -> (usize, String) {
    let mut n = 0;
    let mut first = String::new();
    for (k, &(i, j)) in g.texels.iter().enumerate() {
        for c in 0..2 {
            let got = lut.texel([i, j, 0], c) as f64;
            let want = gen[k].0[c];
            let d = (got - want).abs();
            let b = bounds[k].1[c] + REQ + F32_REL * got.abs();
            if d > b {
                if n == 0 {
                    first = format!(
                        "texel ({i},{j}) ch{c}: table {got}, generator {want}, diff {d:e} > bound {b:e}"
                    );
                }
                n += 1;
            }
        }
    }
    (n, first)
}

/// Prints the 1024-point generator's error against the table (exact to ~1e-7): max, mean;
/// returns the max of A and B.
fn report(name: &str, lut: &Lut, g: &Grid, gen: &[([f64; 2], [f64; 2])]) -> [f64; 2] {
    let mut out = [0.0; 2];
    for (c, ch) in ["A", "B"].iter().enumerate() {
        let (mut max, mut sum, mut at, mut bmax) = (0.0f64, 0.0, (0, 0), 0.0f64);
        for (k, &(i, j)) in g.texels.iter().enumerate() {
            let d = (gen[k].0[c] - lut.texel([i, j, 0], c) as f64).abs();
            sum += d;
            if d > max {
                (max, at) = (d, (i, j));
            }
            bmax = bmax.max(gen[k].1[c]);
        }
        eprintln!(
            "{name}: the 1024-point generator's {ch} vs exact: max {max:.3e} at texel {at:?}, mean {:.3e} over {} texels; largest error bound {bmax:.3e}",
            sum / g.texels.len() as f64,
            g.texels.len()
        );
        out[c] = max;
    }
    out
}

/// Runs the checks; returns the 1024-point generator's largest error in A and B.
fn run(name: &str, g: &Grid, e16k: f64) -> [f64; 2] {
    let t = engine_table(name, &|s| s.to_string());
    assert_eq!(
        (t.spec.axes[0].size, t.spec.axes[1].size),
        (g.nx, g.ny),
        "{name}"
    );
    for &(i, j) in &g.texels {
        let (mu, r) = g.at(i, j, 0.0);
        assert!((t.spec.axes[0].coord(i) - mu).abs() < 1e-15);
        assert!((t.spec.axes[1].alpha(j).unwrap() - r * r).abs() < 1e-15);
    }
    let lut = bake(&t);
    let fine = fine_rule_error(g, 8);
    eprintln!("{name}: the 16384-point rule vs 262144 points, largest difference: {fine:.3e}");
    assert!(fine <= e16k / 2.0, "{name}: {fine}");
    let gen = generator(g, 0.0, e16k);
    let worst = report(name, &lut, g, &gen);
    let (n, first) = compare(&lut, g, &gen, &gen);
    assert_eq!(
        n, 0,
        "{name}: {n} texel channels outside the generator's error; first: {first}"
    );

    // negative control 1: k = (r + 1)²/8 (Karis' analytic-light remap)
    let direct = engine_table(name, &|s| {
        s.replace(r#""schlick-ggx""#, r#""schlick-ggx-direct""#)
    });
    let (n, first) = compare(&bake(&direct), g, &gen, &gen);
    eprintln!("{name}, k = (r + 1)^2/8: {n} texel channels outside the bound ({first})");
    assert!(
        n > g.texels.len() / 4,
        "{name}: the k = (r+1)^2/8 table passed ({n})"
    );
    // negative control 2: the generator half a texel off, with the centred texels' bounds
    let shifted = generator(g, 0.5, e16k);
    let (n, first) = compare(&lut, g, &shifted, &gen);
    eprintln!("{name}, half-texel shift: {n} texel channels outside the bound ({first})");
    // (half a texel is 1/1024 in n·v on LearnOpenGL's 512²: only the most grazing columns,
    // where A and B change fastest, tell it apart — 29 texel channels; on Unreal's 128 × 32,
    // 3990 of 8192)
    assert!(n >= 10, "{name}: the shifted generator passed ({n})");
    worst
}

/// Unreal's PreIntegratedGF (128 × 32, every texel; the computed values, before the
/// preset's UNORM16 rounding, which the sidecar states).
#[test]
fn unreal_preintegrated_gf_is_its_generator_converged() {
    let (nx, ny) = (128, 32);
    let texels = (0..ny).flat_map(|j| (0..nx).map(move |i| (i, j))).collect();
    let [a, b] = run("unreal-preintegrated-gf", &Grid { nx, ny, texels }, 3e-3);
    docs::assert_says(
        "docs/engines.md",
        &format!(
            "Unreal's A off by up to {}, B by {} at all 4,096 texels",
            fig(a),
            fig(b)
        ),
    );
}

/// LearnOpenGL's BRDF LUT (512², RG16F): every 8th texel on both axes and the last row and
/// column (65 × 65 texels; the generator at 16384 points on all 512² would cost ~64× more).
/// The computed values, before the preset's f16 rounding.
#[test]
fn learnopengl_brdf_lut_is_its_generator_converged() {
    let n = 512;
    let mut idx: Vec<usize> = (0..n).step_by(8).collect();
    idx.push(n - 1);
    let texels = idx
        .iter()
        .flat_map(|&j| idx.iter().map(move |&i| (i, j)))
        .collect();
    let count = texels_len(&idx);
    let [a, b] = run(
        "learnopengl-brdf-lut",
        &Grid {
            nx: n,
            ny: n,
            texels,
        },
        6e-3,
    );
    docs::assert_says(
        "docs/engines.md",
        &format!(
            "LearnOpenGL's A by {}, B by {} at {count} of its texels",
            fig(a),
            fig(b)
        ),
    );
}

/// The number of texels of the grid `idx` × `idx`, as the docs write it (`4,225`).
fn texels_len(idx: &[usize]) -> String {
    let n = idx.len() * idx.len();
    format!("{},{:03}", n / 1000, n % 1000)
}
