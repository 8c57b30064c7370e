//! `cargo bench`: criterion benchmarks of brdfbake's public API.
//!
//! * `table/<kind>`: `brdfbake::bake` of one small table per kind (ndf, g1, g2, vgroove,
//!   albedo, albedo-avg, dfg Karis (8-texel rows, texel by texel; 256-texel rows,
//!   interpolated in √μ), dfg Filament + cloth), described as a preset so the
//!   benchmark goes through the same validation as the CLI;
//! * `method/<integral>`: one integral at one point by each public entry point —
//!   brdfbake's adaptive Gauss–Kronrod (`table::albedo`, `table::dfg`, the hemisphere
//!   integrator itself) at the presets' default tolerance 1e-7, and importance-sampled Monte
//!   Carlo on 4096 Hammersley points (`integrate::monte_carlo`) for comparison; the
//!   classic-albedo 1D fast path against the laws integrator.
//!
//! `cargo test` does not run these (only `cargo bench` or `cargo test --benches` does).
//! Whole-process timings against the issue's targets: `scripts/bench.sh`.

use brdfbake::hemisphere::integrate_over_l;
use brdfbake::hemisphere::monte_carlo::{estimate_over_l, Sampling};
use brdfbake::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
use brdfbake::table::albedo::{average_albedo, directional_albedo};
use brdfbake::table::classic::{fast_albedo, view_albedo, ClassicModel};
use brdfbake::table::dfg::{sheen_albedo, split_sum};
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::time::Duration;

/// One small table of every kind (axis names and models as in presets/).
const SMALL: &str = r#"{
  "schema": "brdfbake.preset/1",
  "description": "benchmark tables",
  "tables": [
    { "name": "ndf", "kind": "ndf", "model": { "ndf": "ggx" },
      "axes": { "cos_theta_h": { "size": 32 }, "roughness": { "size": 32, "quantity": "alpha" } } },
    { "name": "g1", "kind": "g1", "model": { "ndf": "ggx" },
      "axes": { "cos_theta": { "size": 32 }, "roughness": { "size": 32, "quantity": "alpha" } } },
    { "name": "g1-gaussian-numeric", "kind": "g1", "model": { "ndf": "gaussian" },
      "axes": { "cos_theta": { "size": 16 }, "roughness": { "size": 4, "range": [0.05, 1], "convention": "endpoints", "quantity": "cook-torrance-m" } } },
    { "name": "g2", "kind": "g2", "model": { "ndf": "ggx", "masking": "smith-height-correlated" },
      "axes": { "cos_theta_v": { "size": 16 }, "cos_theta_l": { "size": 16 }, "roughness": { "size": 8, "quantity": "alpha" } } },
    { "name": "vgroove", "kind": "vgroove",
      "axes": { "n_dot_l": { "size": 16, "range": [0, 1], "convention": "endpoints" }, "n_dot_h": { "size": 16 }, "n_dot_v": { "size": 16, "range": [0, 1], "convention": "endpoints" } } },
    { "name": "albedo", "kind": "albedo", "model": { "ndf": "ggx", "masking": "smith-height-correlated", "fresnel": { "type": "none" } },
      "axes": { "cos_theta_v": { "size": 8 }, "roughness": { "size": 8, "quantity": "perceptual" } } },
    { "name": "albedo-avg", "kind": "albedo-avg", "model": { "ndf": "ggx", "masking": "smith-height-correlated", "fresnel": { "type": "none" } },
      "axes": { "roughness": { "size": 4, "quantity": "perceptual" } } },
    { "name": "dfg-karis", "kind": "dfg", "layout": "karis", "model": { "ndf": "ggx", "masking": "smith-height-correlated" },
      "axes": { "cos_theta_v": { "size": 8 }, "roughness": { "size": 8, "quantity": "perceptual" } } },
    { "name": "dfg-karis-rows", "kind": "dfg", "layout": "karis", "model": { "ndf": "ggx", "masking": "smith-height-correlated" },
      "axes": { "cos_theta_v": { "size": 256 }, "roughness": { "size": 4, "quantity": "perceptual" } } },
    { "name": "dfg-filament-cloth", "kind": "dfg", "layout": "filament", "cloth": true,
      "model": { "ndf": "ggx", "masking": "smith-height-correlated", "fresnel": { "type": "none" } },
      "axes": { "cos_theta_v": { "size": 8, "range": [0, 1], "convention": "centers" },
                "roughness": { "size": 8, "range": [0, 1], "convention": "centers", "quantity": "perceptual" } } }
  ]
}"#;

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
}

fn tables(c: &mut Criterion) {
    let preset = brdfbake::preset::parse(SMALL, "benches/bake.rs", "bench").expect("valid preset");
    let mut g = c.benchmark_group("table");
    for t in &preset.tables {
        let dims: Vec<String> = t.spec.axes.iter().map(|a| a.size.to_string()).collect();
        g.bench_function(format!("{} {}", t.spec.name, dims.join("x")), |b| {
            b.iter(|| brdfbake::bake(black_box(&t.spec)).expect("bakes"))
        });
    }
    g.finish();
}

fn methods(c: &mut Criterion) {
    const TOL: f64 = 1e-7;
    const MU: f64 = 0.5;
    const ALPHA: f64 = 0.25;
    let ggx = Specular {
        ndf: Ndf::new(NdfKind::Ggx, ALPHA).expect("alpha"),
        masking: Masking::SmithHeightCorrelated,
        fresnel: Fresnel::None,
    };
    let brdf = Brdf {
        specular: Some(ggx.clone()),
        diffuse_weight: 0.0,
        diffuse: brdfbake::model::DiffuseLobe::Lambert,
    };
    let mut g = c.benchmark_group("method");
    g.bench_function("albedo E: adaptive G7/K15 (table::albedo)", |b| {
        b.iter(|| directional_albedo(black_box(&brdf), black_box(MU), TOL))
    });
    g.bench_function(
        "albedo E: adaptive G7/K15 (hemisphere::integrate_over_l)",
        |b| {
            b.iter(|| {
                integrate_over_l(black_box(MU), ggx.ndf.warp(), TOL, |n| {
                    [ggx.cosine_weighted(n)]
                })
            })
        },
    );
    g.bench_function("albedo E: Monte Carlo, 4096 Hammersley points", |b| {
        b.iter(|| {
            estimate_over_l(
                black_box(MU),
                Sampling::Ndf(NdfKind::Ggx, ALPHA),
                4096,
                |n| [ggx.cosine_weighted(n)],
            )
        })
    });
    g.bench_function("DFG A,B: adaptive G7/K15 (table::dfg::split_sum)", |b| {
        b.iter(|| split_sum(black_box(&ggx), black_box(MU), TOL))
    });
    g.bench_function("cloth: adaptive G7/K15 (table::dfg::sheen_albedo)", |b| {
        b.iter(|| sheen_albedo(black_box(ALPHA), black_box(MU), TOL))
    });
    g.bench_function(
        "E_avg: nested adaptive G7/K15 (table::albedo::average_albedo)",
        |b| b.iter(|| average_albedo(black_box(&brdf), TOL)),
    );
    g.bench_function("G1 Gaussian: numeric (Ndf::g1_numeric)", |b| {
        let n = Ndf::new(NdfKind::Gaussian, 0.3).expect("m");
        b.iter(|| n.g1_numeric(black_box(0.3)))
    });
    // the classic-albedo texels: the 1D fast path (integrate::classic_lobes) against the
    // laws integrator it is tried before
    for (c, p) in [
        (ClassicModel::BlinnPhong { ks: 1.0 }, 48.0),
        (ClassicModel::ModifiedPhong { kd: 0.0, ks: 1.0 }, 48.0),
        (
            ClassicModel::WardGmd {
                rho_d: 0.0,
                rho_s: 1.0,
            },
            0.25,
        ),
    ] {
        g.bench_function(format!("classic E {}: 1D fast path", c.name()), |b| {
            b.iter(|| fast_albedo(black_box(&c), black_box(MU), p, TOL))
        });
        g.bench_function(format!("classic E {}: laws G7/K15", c.name()), |b| {
            b.iter(|| view_albedo(c.reflectance(p, 1.0), black_box(MU), 0.0, TOL))
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = tables, methods
}
criterion_main!(benches);
