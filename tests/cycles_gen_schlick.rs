//! The engine presets `cycles-ggx-gen-schlick-s` and `cycles-ggx-gen-schlick-ior-s` bake
//! Cycles' shipped `table_ggx_gen_schlick_s` and `table_ggx_gen_schlick_ior_s`
//! (tests/data/engines/cycles/shader.tables, blender/cycles 97dbe6f, Apache-2.0) in Cycles'
//! own layout (index z·256 + y·16 + x, x = roughness, y = μ).
//!
//! Cycles' generator (`app/cycles_precompute.cpp`, `precompute_ggx_gen_schlick_s`) averages
//! `saturate(eval.x/eval.y)` = s(v·h) over 2²⁰ Owen-scrambled Sobol samples of its GGX
//! visible-normal sampler, 0 where the mirror direction leaves below the horizon: the
//! `schlick-weight-vndf` kind's S_vndf. Every sample lies in [0, 1], so its variance is at
//! most 1/4 and σ ≤ 0.5/√2²⁰ = 4.88e-4. Away from α = 0 the bound is the printed half-unit
//! 5e-7, plus 5σ, plus the preset's tolerance 1e-6 and f32 rounding of the stored value
//! (6e-8).
//!
//! At x = 0 (rough = 1e-4, α² = 1e-8) Cycles' closure is a perfect mirror (h = n, no
//! noise): the texel holds s(μ) of its f32 inputs, which the presets reproduce with α = 0 (the
//! smooth limit, S = s(μ)). There the bound is deterministic: 5e-7 + 1e-6 + f32 rounding of
//! Cycles' own arithmetic. For the exponent table that is e·s·δ with δ ≤ 2⁻²⁵ the rounding of
//! 1 − μ (s = (1 − μ)^e, ∂s/∂μ = −e s/(1 − μ)): at most 5·10⁴ · 0.0068 · 3e-8 = 1.0e-5 (slice 0,
//! e = 5·10⁴) and ≤ 70·3e-8 = 2.1e-6 elsewhere; for the η table a few f32 ulps of F and F0
//! divided by 1 − F0 ≥ 0.039: ≤ 8 · 6e-8/0.039 = 1.2e-5.
//!
//! Excluded from the η table and asserted separately: slice 0, where ior = ior_from_F0(1e-16)
//! rounds to 1.0f, F = F0 = 0 and Cycles stores 0 everywhere (ours is η = 1 + 2e-8, whose
//! weight reaches 1 at grazing v·h: 0.146 at the α = 0, μ = 1e-4 texel).
//!
//! Negative controls: the albedo-weighted mean (`schlick-weight-albedo`, the other definition)
//! and a transposed layout miss Cycles' tables by far more than the bound.

#[path = "common/cycles.rs"]
mod cycles_tables;
use cycles_tables::table as cycles;

/// The built-in engine preset's one table (its kind optionally replaced), baked, in its
/// stored order.
fn stored(name: &str, kind: Option<&str>) -> Vec<f64> {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no engine preset {name}"));
    let text = match kind {
        Some(k) => text
            .replace("\"schlick-weight-vndf\"", &format!("\"{k}\""))
            .replace("[\"S_vndf\"]", "[\"S_albedo\"]"),
        None => text.to_string(),
    };
    let t = brdfbake::preset::parse(&text, name, name)
        .unwrap()
        .tables
        .remove(0);
    let lut = t.stored(brdfbake::table::bake(&t.spec).unwrap());
    assert_eq!(lut.channels.len(), 1);
    assert!(
        lut.error_estimate[0] <= 1e-6,
        "{name}: {:?}",
        lut.error_estimate
    );
    lut.data.iter().map(|&v| v as f64).collect()
}

const SIGMA: f64 = 4.88e-4;
const BOUND: f64 = 5e-7 + 5.0 * SIGMA + 1e-6 + 6e-8;

fn worst(c: &[f64], ours: &[f64], texels: impl Iterator<Item = usize>) -> (f64, usize) {
    texels
        .map(|i| ((c[i] - ours[i]).abs(), i))
        .fold((0.0, 0), |m, d| if d.0 > m.0 { d } else { m })
}

fn check(preset: &str, table: &str, first_slice: usize, mirror_bound: impl Fn(usize) -> f64) {
    let c = cycles(table);
    let ours = stored(preset, None);
    assert_eq!(c.len(), 4096);
    assert_eq!(ours.len(), 4096);
    let rough = |i: usize| !i.is_multiple_of(16);
    let (d, i) = worst(&c, &ours, (first_slice * 256..4096).filter(|&i| rough(i)));
    eprintln!("{preset}: max |ours - Cycles| (alpha > 0) = {d:.3e} at {i} (bound {BOUND:.3e})");
    assert!(
        d <= BOUND,
        "{preset} texel {i}: {} vs Cycles {}",
        ours[i],
        c[i]
    );
    // the mirror column x = 0: deterministic on both sides
    for i in (first_slice * 256..4096).filter(|&i| !rough(i)) {
        let b = 5e-7 + 1e-6 + mirror_bound(i);
        assert!(
            (c[i] - ours[i]).abs() <= b,
            "{preset} mirror texel {i}: {} vs Cycles {} (bound {b:.2e})",
            ours[i],
            c[i]
        );
    }
    let (dm, im) = worst(&c, &ours, (first_slice * 256..4096).filter(|&i| !rough(i)));
    eprintln!("{preset}: max |ours - Cycles| (alpha = 0) = {dm:.3e} at {im}");
    // negative controls: transposed, and the albedo-weighted definition
    let swapped = (first_slice * 256..4096)
        .map(|i| {
            let (x, y, z) = (i % 16, (i / 16) % 16, i / 256);
            (c[i] - ours[z * 256 + x * 16 + y]).abs()
        })
        .fold(0.0, f64::max);
    eprintln!("{preset}: transposed max |diff| = {swapped:.3e}");
    assert!(
        swapped > 10.0 * BOUND,
        "{preset}: transposed within {swapped}"
    );
    let albedo = stored(preset, Some("schlick-weight-albedo"));
    let (da, ia) = worst(&c, &albedo, (first_slice * 256..4096).filter(|&i| rough(i)));
    eprintln!("{preset}: albedo-weighted max |diff| = {da:.3e} at {ia}");
    // (it must fail the check above, with margin: 5x)
    assert!(
        da > 5.0 * BOUND,
        "{preset}: the albedo-weighted mean within {da}"
    );
}

#[test]
fn generalized_schlick_exponent_table_matches_cycles() {
    check("cycles-ggx-gen-schlick-s", "ggx_gen_schlick_s", 0, |i| {
        // e·s·2^-25 (module doc): slice 0 is e = 5e4 with s <= 0.0068, the others
        // e <= 70 with s <= 1
        if i / 256 == 0 {
            5e4 * 0.0068 * 3e-8
        } else {
            70.0 * 3e-8
        }
    });
}

#[test]
fn generalized_schlick_ior_table_matches_cycles() {
    let c = cycles("ggx_gen_schlick_ior_s");
    assert!(
        c[..256].iter().all(|&v| v == 0.0),
        "slice 0: Cycles' ior is 1.0f, s = 0"
    );
    check(
        "cycles-ggx-gen-schlick-ior-s",
        "ggx_gen_schlick_ior_s",
        1,
        |_| 1.2e-5,
    );
}
