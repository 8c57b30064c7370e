//! Byte-for-byte determinism of every output format across runs and thread counts. (The
//! GGX dfg table's 40-texel rows are long enough to be interpolated: src/quadrature/interp1d.rs;
//! the dielectric tables share rules between their eta >= 1 slices and columns, and karis-f82
//! goes column by column.)

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

const PRESET: &str = r#"{
  "schema": "brdfbake.preset/1",
  "tables": [
    {"name": "dfg", "kind": "dfg", "layout": "filament", "cloth": true,
     "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
     "axes": {"cos_theta_v": {"size": 40}, "roughness": {"size": 6, "quantity": "perceptual"}}},
    {"name": "dfg16", "kind": "dfg", "layout": "karis", "storage": "f16",
     "model": {"ndf": "beckmann", "masking": "smith-separable"},
     "axes": {"cos_theta_v": {"size": 5}, "roughness": {"size": 7, "range": [0.1, 1], "convention": "endpoints", "quantity": "alpha"}}},
    {"name": "g2", "kind": "g2", "layout_3d": "array",
     "model": {"ndf": "gaussian", "masking": "smith-height-correlated"},
     "axes": {"cos_theta_v": {"size": 4}, "cos_theta_l": {"size": 4}, "roughness": {"size": 3, "quantity": "cook-torrance-m"}}},
    {"name": "eavg", "kind": "albedo-avg",
     "model": {"ndf": "blinn-phong", "masking": "v-groove", "fresnel": {"type": "schlick", "f0": 0.04}},
     "axes": {"roughness": {"size": 3, "range": [2, 100], "quantity": "blinn-phong-exponent"}}},
    {"name": "glass", "kind": "dielectric-albedo",
     "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
     "axes": {"cos_theta_v": {"size": 6}, "roughness": {"size": 5, "quantity": "perceptual"}, "fresnel": {"size": 5, "quantity": "eta-reflectance", "range": [-0.5, 0.5], "convention": "endpoints"}}},
    {"name": "glass_avg", "kind": "dielectric-albedo-avg",
     "model": {"ndf": "ggx", "masking": "smith-separable"},
     "axes": {"roughness": {"size": 5, "quantity": "perceptual"}, "fresnel": {"size": 4, "quantity": "inverse-eta-reflectance", "range": [-0.5, 0.5], "convention": "endpoints"}}},
    {"name": "f82", "kind": "dfg", "layout": "karis-f82",
     "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
     "axes": {"cos_theta_v": {"size": 40}, "roughness": {"size": 6, "quantity": "perceptual"}}}
  ]
}"#;

fn bake(dir: &Path, threads: &str) -> BTreeMap<String, Vec<u8>> {
    let preset = dir.join("det.json");
    std::fs::write(&preset, PRESET).unwrap();
    let out = dir.join(format!("out-{threads}"));
    let st = Command::new(env!("CARGO_BIN_EXE_brdfbake"))
        .args([
            "bake",
            "--quiet",
            "--format",
            "exr,ktx2,png,h,rs,glsl,hlsl,wgsl",
            "--threads",
            threads,
            "--out",
        ])
        .arg(&out)
        .arg(&preset)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let mut files = BTreeMap::new();
    for e in std::fs::read_dir(out.join("det")).unwrap() {
        let p = e.unwrap().path();
        files.insert(
            p.file_name().unwrap().to_string_lossy().into_owned(),
            std::fs::read(&p).unwrap(),
        );
    }
    files
}

#[test]
fn every_format_is_byte_identical_across_runs_and_thread_counts() {
    let dir = tempfile::tempdir().unwrap();
    let one = bake(dir.path(), "1");
    // every format of every table is there: 4 tables × (exr, ktx2, h, rs, 3 shaders, json)
    // plus the PNG previews
    for t in ["dfg", "dfg16", "g2", "eavg"] {
        for ext in ["exr", "ktx2", "h", "rs", "glsl", "hlsl", "wgsl", "json"] {
            assert!(
                one.contains_key(&format!("{t}.{ext}")),
                "missing {t}.{ext}: {:?}",
                one.keys()
            );
        }
        assert!(one
            .keys()
            .any(|k| k.starts_with(&format!("{t}.preview")) && k.ends_with(".png")));
    }
    for threads in ["2", "8", "1"] {
        let other = bake(dir.path(), threads);
        assert_eq!(
            one.keys().collect::<Vec<_>>(),
            other.keys().collect::<Vec<_>>()
        );
        for (k, v) in &one {
            assert!(
                v == &other[k],
                "{k} differs between 1 and {threads} threads"
            );
        }
    }
}
