//! The `sheen-charlie` preset's `sheen-e` table (Charlie + Ashikhmin albedo, F = 1,
//! perceptual r ∈ [0.1, 1]) through the cloth kernel it shares with the `filament-dfg`
//! cloth channel (src/table/albedo.rs `charlie_kernels`: the θh kernel, the generic path as
//! fallback), baked column by column with shared node data.
//!
//! Tolerances:
//! * `tol = 1e-7`, the preset's (default) per-texel tolerance.
//! * against the independent reference (`tests/common/reference.rs`: l-space polar
//!   coordinates, adaptive Gauss–Legendre, Charlie and Ashikhmin re-implemented; nothing in
//!   it uses `brdfbake::integrate`) at 1e-9 (100× tighter): the f64 value must lie within its
//!   own estimate plus the reference's estimate (+1e-15 for exact ties): both claim to bound
//!   their errors, so their sum bounds the difference; the stored f32 value within that plus
//!   its rounding (2⁻²⁴ relative).

#[path = "common/reference.rs"]
mod reference;

use brdfbake::table::albedo::directional_albedo;
use brdfbake::table::{bake, TableSpec};
use rayon::prelude::*;
use reference::RefModel;

const REF_TOL: f64 = 1e-9;
const F32_REL: f64 = 1.0 / (1u64 << 24) as f64;

fn preset_table() -> TableSpec {
    let p = brdfbake::preset::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/sheen-charlie.json"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    p.tables[0].spec.clone()
}

/// Every texel of the table baked column by column (shared node data) is, bit for bit, the
/// texel computed alone by `directional_albedo` (a pure function of (μ, α, tol)); at a 6×6
/// subset — the grazing and normal columns, the narrowest (α = 0.01) and widest (α = 1)
/// rows and the rows on both sides of α = 1/16 included — the value is
/// within its estimate of the reference and within the tolerance.
#[test]
fn sheen_preset_matches_reference_and_texels_alone() {
    let spec = preset_table();
    let (nx, ny) = (spec.axes[0].size, spec.axes[1].size);
    assert_eq!((nx, ny), (32, 32));
    let lut = bake(&spec).unwrap();
    let alone: Vec<(usize, usize, f64, f64)> = (0..nx * ny)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k % nx, k / nx);
            let brdf = spec.model.brdf(spec.axes[1].alpha(j).unwrap()).unwrap();
            let (v, e, _) = directional_albedo(&brdf, spec.axes[0].coord(i), spec.tolerance);
            (i, j, v[0], e[0])
        })
        .collect();
    let mut failures = Vec::new();
    for &(i, j, v, e) in &alone {
        let t = lut.texel([i, j, 0], 0);
        if t != v as f32 || e > spec.tolerance {
            failures.push(format!("texel ({i},{j}): table {t}, alone {v} ± {e:e}"));
        }
    }
    // r = 0.1 + 0.9 j/31: α = r² < 1/16 for j ≤ 4 (r = 0.245), ≥ 1/16 from j = 5 (r = 0.274)
    let subset_j = [0usize, 4, 5, 12, 24, 31];
    let subset_i = [0usize, 1, 8, 16, 27, 31];
    failures.extend(
        subset_j
            .iter()
            .flat_map(|&j| subset_i.map(|i| (i, j)))
            .collect::<Vec<_>>()
            .par_iter()
            .filter_map(|&(i, j)| {
                let (_, _, v, est) = alone[j * nx + i];
                let (mu, alpha) = (spec.axes[0].coord(i), spec.axes[1].alpha(j).unwrap());
                let m = RefModel::new(
                    brdfbake::model::NdfKind::Charlie,
                    alpha,
                    brdfbake::model::Masking::Ashikhmin,
                );
                let r = reference::albedo(&m, mu, REF_TOL);
                let d = (v - r.value[0]).abs();
                let stored = (lut.texel([i, j, 0], 0) as f64 - r.value[0]).abs();
                let bound = est + r.error + 1e-15;
                (d > bound || d > spec.tolerance || stored > bound + F32_REL * v.abs()).then(
                    || {
                        format!(
                            "mu={mu} alpha={alpha}: {v} vs reference {} ± {:e}: |error| {d:e}, estimate {est:e}",
                            r.value[0], r.error
                        )
                    },
                )
            })
            .collect::<Vec<_>>(),
    );
    assert!(
        failures.is_empty(),
        "{} failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}
