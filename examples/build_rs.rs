//! How a `build.rs` bakes a lookup table with the brdfbake library — no binary needed — and
//! writes it with the encoders.
//!
//! In a real crate, put `brdfbake` under `[build-dependencies]` and this `main` in `build.rs`;
//! the files land in `OUT_DIR`, and the crate embeds them, e.g.
//! `include!(concat!(env!("OUT_DIR"), "/dfg.rs"))` or `include_bytes!(... "/dfg.ktx2")`.
//! Run it here with `cargo run --release --example build_rs` (it writes to `OUT_DIR` if set,
//! else to `target/build_rs_example/`).
//!
//! Two ways are shown:
//! 1. a preset (the same JSON the CLI reads) through the pipeline: every format of the preset
//!    plus the JSON sidecar, written atomically;
//! 2. a [`TableSpec`] built in code, baked with [`brdfbake::bake`], and encoded one format at a
//!    time with the encoders ([`Ktx2Encoder`], [`RustSource`]), with its sidecar from [`meta`].

use brdfbake::encode::ktx2::Ktx2Encoder;
use brdfbake::encode::source::RustSource;
use brdfbake::encode::Encoder;
use brdfbake::lut::{Axis, Convention, Quantity};
use brdfbake::meta;
use brdfbake::model::{Fresnel, Masking, NdfKind, RoughnessQuantity};
use brdfbake::preset::{Layout3d, PresetTable};
use brdfbake::table::{DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
use std::path::PathBuf;

/// A small split-sum table, as a preset (the CLI's format; see docs/presets.md).
const PRESET: &str = r#"{
  "schema": "brdfbake.preset/1",
  "tables": [{
    "name": "envbrdf", "kind": "dfg", "layout": "karis",
    "model": { "ndf": "ggx", "masking": "smith-height-correlated" },
    "axes": { "cos_theta_v": { "size": 32 }, "roughness": { "size": 32, "quantity": "perceptual" } },
    "formats": ["exr", "rs"]
  }]
}"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::var_os("OUT_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/build_rs_example"));
    // a build script reruns only when its inputs change
    println!("cargo:rerun-if-changed=build.rs");

    // 1. A preset through the pipeline: out/<preset>/<table>.{exr,rs,json}.
    let preset = brdfbake::preset::parse(PRESET, "build.rs preset", "luts")?;
    for baked in brdfbake::pipeline::bake_and_write(&preset, &out, None)? {
        let err = baked.lut.error_estimate.iter().cloned().fold(0.0, f64::max);
        println!(
            "cargo:warning=baked {}/{} (est. error {err:.1e}) -> {:?}",
            baked.preset, baked.table, baked.files
        );
    }

    // 2. A table spec in code, baked and encoded by hand.
    let spec = TableSpec {
        name: "dfg".into(),
        kind: TableKind::Dfg,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes: vec![
            Axis {
                name: "cos_theta_v".into(),
                quantity: Quantity::Cosine,
                size: 32,
                range: [0.0, 1.0],
                convention: Convention::Centers,
                warp: Default::default(),
                clamp: None,
            },
            Axis {
                name: "roughness".into(),
                quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
                size: 32,
                range: [0.0, 1.0],
                convention: Convention::Centers,
                warp: Default::default(),
                clamp: None,
            },
        ],
        dfg_layout: Some(DfgLayout::Filament),
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F16,
        tolerance: 1e-7,
    };
    let lut = brdfbake::bake(&spec)?;
    // what a shader would read at n.v = 0.5, r = 0.5: E = mix(R, G, F0)
    let rg = lut.lookup(&[0.5, 0.5]);
    println!(
        "cargo:warning=dfg at (0.5, 0.5): R = {:.5}, G = {:.5}",
        rg[0], rg[1]
    );

    let table = PresetTable {
        spec,
        formats: vec![],
        scale: 1.0,
        layout_3d: Layout3d::Volume,
        accept_error_estimate: None,
        engine: None,
        axis_order: None,
        shipped: None,
        channels: None,
        fit: None,
    };
    let attrs = meta::header_attributes("build", &table, &lut);
    let dir = out.join("build");
    std::fs::create_dir_all(&dir)?;
    let encoders: Vec<Box<dyn Encoder>> = vec![
        Box::new(Ktx2Encoder {
            storage: Storage::F16,
            table_name: "dfg".into(),
            array_3d: false,
            supercompression: Default::default(),
        }),
        Box::new(RustSource {
            table_name: "dfg".into(),
            storage: Storage::F16,
        }),
    ];
    let mut files = Vec::new();
    for enc in &encoders {
        let name = format!("dfg.{}", enc.extension());
        std::fs::write(dir.join(&name), enc.encode(&lut, &attrs)?)?;
        files.push((enc.extension().to_string(), name));
    }
    let sidecar = meta::metadata("build", &table, &lut, &files);
    std::fs::write(
        dir.join("dfg.json"),
        serde_json::to_string_pretty(&sidecar)? + "\n",
    )?;
    println!("cargo:warning=wrote {}", dir.display());
    Ok(())
}
