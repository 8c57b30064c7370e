//! The `godot-dfg` preset against Godot's own generator, written here again from its source:
//! Godot 4 ships no DFG table — the Forward+ renderer computes it at start-up on the GPU
//! (godotengine/godot `servers/rendering/renderer_rd/shaders/forward_clustered/integrate_dfg.glsl`
//! at e8387d695efee663e2f427bd427792a6f0c633f0, MIT), so the generator is the engine's table.
//!
//! The generator, per texel (x, y) of 128²: μ = (x + 0.5)/128, r = (y + 0.5)/128, the result
//! stored in row 127 − y (the shader samples `vec2(NoV, 1.0 - roughness)`); V = (√(1 − μ²), 0, μ);
//! for the 1024 Hammersley points ξ:
//! * GGX half vectors (a = r², cos θh = √((1 − ξ₂)/(1 + (a² − 1)ξ₂)), φ = 2πξ₁), turned into
//!   the frame its `importance_sample_ggx` builds for N = +z (tangent (0, −1, 0), bitangent
//!   (1, 0, 0): H = (sin θ sin φ, −sin θ cos φ, cos θ)); L = normalize(2(V·H)H − V); where
//!   n·l > 0: G = G1(v) G1(l), Schlick-GGX G1(μ) = μ/(μ(1 − k) + k), k = r²/2 = α/2;
//!   w = G (v·h)/((n·h)(n·v)), R += (1 − v·h)⁵ w, G += w — f cos/p of the GGX light density
//!   D (n·h)/(4 v·h), so (R, G)/1024 converges to Filament's ∫Fc f cos, ∫f cos with
//!   Schlick-GGX masking, k = α/2;
//! * half vectors uniform on the hemisphere (cos θh = 1 − ξ₂, φ = 2πξ₁, density 1/(2π) in h,
//!   1/(8π v·h) in l); where n·l > 0: B += D_Charlie(n·h; r²) V_Ashikhmin(n·v, n·l) (n·l)(v·h),
//!   times 8π/1024 — f cos/p of the cloth lobe, converging to ∫ D_Charlie V_Ashikhmin cos.
//!
//! The test compares the baked preset with the 1024-point generator texel by texel, within
//! that generator's error (estimated per texel, see [`generator`]), reports that error (the
//! table Godot renders with, against the exact one), and runs two negative controls that must
//! fail: the table with height-correlated Smith masking (Filament's), and the generator of
//! Godot's previous version (row y computed at roughness (128.5 − y)/128, one texel above
//! where the shader samples it).

#[path = "common/docs.rs"]
mod docs;
#[path = "common/hammersley.rs"]
mod hammersley;
use hammersley::hammersley;

use brdfbake::lut::Lut;
use brdfbake::numfmt::fig;
use brdfbake::preset::PresetTable;
use rayon::prelude::*;
use std::f64::consts::PI;

const N: usize = 128;
const REQ: f64 = 1e-6;
const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;

fn godot_table(edit: &dyn Fn(&str) -> String) -> PresetTable {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == "godot-dfg")
        .expect("no engine preset godot-dfg");
    let p = brdfbake::preset::parse(&edit(text), "godot-dfg", "test").unwrap();
    p.tables.into_iter().next().unwrap()
}

/// Godot's `integrate_brdfs(n_dot_v, roughness)` with the point set `xi` (module doc):
/// [R, G, B].
fn integrate_brdfs(xi: &[[f64; 3]], mu: f64, r: f64) -> [f64; 3] {
    let a = r * r;
    let k = a / 2.0;
    let g1 = |m: f64| m / (m * (1.0 - k) + k);
    let v = [(1.0 - mu * mu).sqrt(), 0.0, mu];
    let reflect = |h: [f64; 3]| {
        let vh = v[0] * h[0] + v[2] * h[2];
        let l = [
            2.0 * vh * h[0] - v[0],
            2.0 * vh * h[1],
            2.0 * vh * h[2] - v[2],
        ];
        let len = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
        // (n·l, n·h, v·h), saturated as the shader does
        (
            (l[2] / len).clamp(0.0, 1.0),
            h[2].clamp(0.0, 1.0),
            vh.clamp(0.0, 1.0),
        )
    };
    let (mut sr, mut sg, mut sb) = (0.0, 0.0, 0.0);
    for x in xi {
        let (cp, sp, x2) = (x[0], x[1], x[2]);
        // GGX, in the tangent frame of importance_sample_ggx
        let ct = ((1.0 - x2) / (1.0 + (a * a - 1.0) * x2)).sqrt();
        let st = (1.0 - ct * ct).max(0.0).sqrt();
        let (nl, nh, vh) = reflect([st * sp, -st * cp, ct]);
        if nl > 0.0 {
            let w = g1(mu) * g1(nl) * vh / (nh * mu);
            sr += (1.0 - vh).powi(5) * w;
            sg += w;
        }
        // cloth: uniform half vectors
        let ct = 1.0 - x2;
        let st = (1.0 - ct * ct).max(0.0).sqrt();
        let (nl, nh, vh) = reflect([st * cp, st * sp, ct]);
        if nl > 0.0 {
            let d = (2.0 + 1.0 / a) * (1.0 - nh * nh).powf(0.5 / a) / (2.0 * PI);
            let vis = 1.0 / (4.0 * (nl + mu - nl * mu));
            sb += vis * d * nl * vh;
        }
    }
    let n = xi.len() as f64;
    [sr / n, sg / n, sb * 8.0 * PI / n]
}

/// The generator's (n·v, roughness) for texel (i, j) of the table (row j = 127 − y),
/// `shift` texels up in roughness (1: Godot's previous version).
fn at(i: usize, j: usize, shift: f64) -> (f64, f64) {
    let y = (N - 1 - j) as f64;
    ((i as f64 + 0.5) / N as f64, (y + 0.5 + shift) / N as f64)
}

/// Every texel (i, j), row by row.
fn texels() -> Vec<(usize, usize)> {
    (0..N).flat_map(|j| (0..N).map(move |i| (i, j))).collect()
}

type Est = ([f64; 3], [f64; 3]);

/// The generator's 1024-point values at every texel (roughness shifted by `shift` texels),
/// and each one's error bound.
///
/// **The 1024-point rule's error** per texel and channel is estimated from the same
/// estimator with 16384 Hammersley points: |Q₁₀₂₄ − Q₁₆₃₈₄| + [`e16k`], the 16384-point
/// rule's own error, checked in the test at a spread of texels against 262144 points
/// (≤ e16k/2 there).
fn generator(shift: f64) -> Vec<Est> {
    let (x1, x16) = (hammersley(1024), hammersley(16384));
    texels()
        .par_iter()
        .map(|&(i, j)| {
            let (mu, r) = at(i, j, shift);
            let (q1, q16) = (integrate_brdfs(&x1, mu, r), integrate_brdfs(&x16, mu, r));
            (
                q1,
                std::array::from_fn(|c| (q1[c] - q16[c]).abs() + e16k(i)[c]),
            )
        })
        .collect()
}

/// Columns with n·v below 1/16 (x < 8), where the weight's 1/(n·v) makes both rules
/// noisy, get their own bound.
const GRAZING: usize = 8;

/// The 16384-point rule's error bound for texel column `i`, channel `c`: about 3× the
/// largest |Q₁₆₃₈₄ − Q₂₆₂₁₄₄| [`fine_rule_error`] finds in the column's class.
fn e16k(i: usize) -> [f64; 3] {
    if i < GRAZING {
        [1.5e-3, 2.5e-2, 0.4]
    } else {
        [2e-4, 7e-3, 2e-3]
    }
}

/// The largest |Q₁₆₃₈₄ − Q₂₆₂₁₄₄| per channel over every 8th texel on both axes (and the
/// first two and the last rows and columns), in the grazing columns and in the others.
fn fine_rule_error() -> [[f64; 3]; 2] {
    let (x16, x256) = (hammersley(16384), hammersley(262144));
    let mut idx: Vec<usize> = (0..N).step_by(8).collect();
    idx.extend([1, N - 1]);
    idx.sort();
    idx.dedup();
    let picked: Vec<(usize, usize)> = idx
        .iter()
        .flat_map(|&j| idx.iter().map(move |&i| (i, j)))
        .collect();
    let max = |a: [f64; 3], b: [f64; 3]| std::array::from_fn(|c| a[c].max(b[c]));
    picked
        .par_iter()
        .map(|&(i, j)| {
            let (mu, r) = at(i, j, 0.0);
            let (p, q) = (integrate_brdfs(&x16, mu, r), integrate_brdfs(&x256, mu, r));
            let d = std::array::from_fn(|c| (p[c] - q[c]).abs());
            if i < GRAZING {
                [d, [0.0; 3]]
            } else {
                [[0.0; 3], d]
            }
        })
        .reduce(|| [[0.0; 3]; 2], |a, b| [max(a[0], b[0]), max(a[1], b[1])])
}

/// The number of texel channels where |table − generator| exceeds the bound (+ REQ + f32
/// rounding), and the first such one.
fn outside(lut: &Lut, gen: &[Est], bounds: &[Est]) -> (usize, String) {
    let mut n = 0;
    let mut first = String::new();
    for (k, &(i, j)) in texels().iter().enumerate() {
        for c in 0..3 {
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

/// The 1024-point generator's largest error against the table (exact to ~1e-7) per channel,
/// printed with its mean and place.
fn report(lut: &Lut, gen: &[Est]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (c, ch) in ["R", "G", "B"].iter().enumerate() {
        let (mut max, mut sum, mut place) = (0.0f64, 0.0, (0, 0));
        for (k, &(i, j)) in texels().iter().enumerate() {
            let d = (gen[k].0[c] - lut.texel([i, j, 0], c) as f64).abs();
            sum += d;
            if d > max {
                (max, place) = (d, (i, j));
            }
        }
        eprintln!(
            "godot-dfg: the 1024-point generator's {ch} vs exact: max {max:.3e} at texel {place:?}, mean {:.3e}",
            sum / (N * N) as f64
        );
        out[c] = max;
    }
    out
}

#[test]
fn godot_dfg_is_its_generator_converged() {
    let t = godot_table(&|s| s.to_string());
    // the layout: u = n·v at centres, row j at roughness 1 − (j + 0.5)/128
    for k in 0..N {
        let (mu, r) = at(k, k, 0.0);
        assert!((t.spec.axes[0].coord(k) - mu).abs() < 1e-15);
        assert!((t.spec.axes[1].alpha(k).unwrap() - r * r).abs() < 1e-15);
        // and a lookup at Godot's v = 1 − r lands on that texel's centre
        assert!((t.spec.axes[1].texture_coordinate(r) - (k as f64 + 0.5) / N as f64).abs() < 1e-12);
    }
    let lut = brdfbake::table::bake(&t.spec).unwrap();

    let fine = fine_rule_error();
    eprintln!(
        "godot-dfg: the 16384-point rule vs 262144 points, largest difference (R, G, B): n.v < 1/16 {:?}, above {:?}",
        fine[0], fine[1]
    );
    for (k, i) in [0, GRAZING].into_iter().enumerate() {
        for c in 0..3 {
            assert!(
                fine[k][c] <= e16k(i)[c] / 2.0,
                "class {k} channel {c}: {fine:?}"
            );
        }
    }
    let gen = generator(0.0);
    let worst = report(&lut, &gen);
    let (n, first) = outside(&lut, &gen, &gen);
    assert_eq!(
        n, 0,
        "{n} texel channels outside the generator's error; first: {first}"
    );

    // negative control 1: Filament's height-correlated Smith masking
    let hc = godot_table(&|s| s.replace(r#""schlick-ggx""#, r#""smith-height-correlated""#));
    let (n, first) = outside(&brdfbake::table::bake(&hc.spec).unwrap(), &gen, &gen);
    eprintln!("godot-dfg, height-correlated Smith: {n} texel channels outside the bound ({first})");
    assert!(n > N * N / 4, "the height-correlated table passed ({n})");
    // negative control 2: Godot's previous generator, one texel above the lookup
    let old = generator(1.0);
    let (n, first) = outside(&lut, &old, &gen);
    eprintln!(
        "godot-dfg, one texel up in roughness: {n} texel channels outside the bound ({first})"
    );
    assert!(n > N * N / 4, "the shifted generator passed ({n})");

    docs::assert_says(
        "docs/engines.md",
        &format!(
            "Godot's R off by up to {}, G by {}, B (cloth) by {}",
            fig(worst[0]),
            fig(worst[1]),
            fig(worst[2])
        ),
    );
}
