//! The engine presets `cycles-glass-e` and `cycles-glass-eavg` bake Cycles' shipped
//! `table_ggx_glass_E` and `table_ggx_glass_Eavg` (tests/data/engines/cycles/shader.tables,
//! blender/cycles 97dbe6f, Apache-2.0) in Cycles' own layout: the stored table, texel for
//! texel in the order Cycles prints it, agrees within the printed half-unit plus 5σ of
//! Cycles' sampling noise, outside the index-matched slice 0 (Cycles' ior rounds to 1.0f
//! there and its sampler takes its specular branch, E = 1). The argument for σ (every sample
//! of Cycles' estimator lies in [0, 1], resp. 2μ·[0, 1]) is in tests/dielectric_kinds.rs,
//! which checks the same kinds on the same grid from explicit specs; this test checks that
//! the shipped presets are that grid, with Cycles' axis order.

#[path = "common/cycles.rs"]
mod cycles_tables;
use cycles_tables::table as cycles;

/// The built-in engine preset's one table, baked and in its stored order.
fn stored(name: &str) -> Vec<f64> {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no engine preset {name}"));
    let t = brdfbake::preset::parse(text, name, name)
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

#[test]
fn cycles_glass_presets_reproduce_the_shipped_tables() {
    // printed half-unit + 5σ + the preset's tolerance 1e-6 + f32 rounding
    // (σ ≤ 0.5/√2²³ for glass_E, √(4/3)/√2²⁶ for glass_Eavg: tests/dielectric_kinds.rs)
    for (preset, table, slice, sigma) in [
        ("cycles-glass-e", "ggx_glass_E", 256, 1.73e-4),
        ("cycles-glass-eavg", "ggx_glass_Eavg", 16, 1.41e-4),
    ] {
        let c = cycles(table);
        let ours = stored(preset);
        assert_eq!(c.len(), ours.len(), "{preset}");
        assert!(
            c[..slice].iter().all(|&v| v >= 0.99998),
            "{table}: slice 0 is Cycles' specular branch"
        );
        let bound = 5e-7 + 5.0 * sigma + 1e-6 + 6e-8;
        let (d, i) = (slice..c.len())
            .map(|i| ((c[i] - ours[i]).abs(), i))
            .fold((0.0, 0), |m, d| if d.0 > m.0 { d } else { m });
        eprintln!(
            "{preset}: max |ours - Cycles| beyond slice 0 = {d:.3e} at {i} (bound {bound:.3e})"
        );
        assert!(
            d <= bound,
            "{preset} texel {i}: {} vs Cycles {}",
            ours[i],
            c[i]
        );
        // the layout matters: transposing u and v (or rows and slices) misses by far more
        let n = if slice == 256 { 16 } else { 1 };
        let swapped = (slice..c.len())
            .map(|i| {
                let (x, y, z) = (i % 16, (i / 16) % 16, i / 256);
                let j = if n == 16 {
                    z * 256 + x * 16 + y
                } else {
                    x * 16 + y
                };
                (c[i] - ours[j]).abs()
            })
            .fold(0.0, f64::max);
        assert!(
            swapped > 100.0 * bound,
            "{preset}: transposed within {swapped}"
        );
    }
}

/// `cycles-glass-inv-e` and `cycles-glass-inv-eavg` (η < 1: the view inside the denser
/// medium) bake the physical integral, which Cycles' `glass_inv_E`/`glass_inv_Eavg` are not:
/// Cycles' sampler keeps refracted directions that leave on the view's side (its
/// `dot(Ng, wo) < 0` check is commented out), terms ≥ 0 that Walter's model drops, so beyond
/// slice/row 0 (Cycles' specular branch, asserted to be 1 as for glass_E) ours ≤ Cycles + the
/// bound of `cycles_glass_presets_reproduce_the_shipped_tables` everywhere, with equality
/// within that bound in the last slice (η = 1/99.5: total internal reflection for all but
/// v·h > 0.99995, nothing refracted). How much Cycles adds is printed, and must exceed the
/// bound somewhere (else the tables would not be "stale" and this test would say nothing):
/// that is the negative control.
#[test]
fn cycles_glass_inv_presets_bound_the_shipped_tables() {
    for (preset, table, slice, sigma) in [
        ("cycles-glass-inv-e", "ggx_glass_inv_E", 256, 1.73e-4),
        ("cycles-glass-inv-eavg", "ggx_glass_inv_Eavg", 16, 1.41e-4),
    ] {
        let c = cycles(table);
        let ours = stored(preset);
        assert_eq!(c.len(), ours.len(), "{preset}");
        assert!(
            c[..slice].iter().all(|&v| v >= 0.99998),
            "{table}: slice 0 is Cycles' specular branch"
        );
        let bound = 5e-7 + 5.0 * sigma + 1e-6 + 6e-8;
        let (over, i) = (slice..c.len())
            .map(|i| (ours[i] - c[i], i))
            .fold((f64::NEG_INFINITY, 0), |m, d| if d.0 > m.0 { d } else { m });
        let (extra, j) = (slice..c.len())
            .map(|i| (c[i] - ours[i], i))
            .fold((f64::NEG_INFINITY, 0), |m, d| if d.0 > m.0 { d } else { m });
        let n = c.len() / slice;
        let mean_extra =
            (slice..c.len()).map(|i| c[i] - ours[i]).sum::<f64>() / (c.len() - slice) as f64;
        eprintln!(
            "{preset}: max (ours - Cycles) = {over:.3e} at {i}; Cycles adds up to {extra:.3e} (at {j}), {mean_extra:.3e} on average (bound {bound:.3e})"
        );
        assert!(
            over <= bound,
            "{preset} texel {i}: ours {} over Cycles {}",
            ours[i],
            c[i]
        );
        assert!(extra > 10.0 * bound, "{preset}: Cycles adds only {extra}");
        let last = (n - 1) * slice;
        let (d, k) = (last..c.len())
            .map(|i| ((c[i] - ours[i]).abs(), i))
            .fold((0.0, 0), |m, d| if d.0 > m.0 { d } else { m });
        eprintln!("{preset}: last slice max |diff| = {d:.3e} at {k}");
        assert!(
            d <= bound,
            "{preset} texel {k}: ours {} vs Cycles {}",
            ours[k],
            c[k]
        );
    }
}
