//! The `nvdiffrec-bsdf-256` engine preset against nvdiffrec's `bsdf_256_256.bin`: the layout
//! (axes, texel centres, perceptual roughness, masking, channel order, raw float32) is the
//! file's, a wrong one fails the same comparison, and `compare` reads a raw float32 file
//! (`shipped.format: bin`) at the texels it names. `bake --format bin` writes a drop-in file.
//!
//! nvdiffrec's licence (NVIDIA Source Code License, research and evaluation use only) does
//! not let the file be kept here: its values are quoted below, with attribution.

#[path = "common/cli.rs"]
mod cli;

use brdfbake::preset::PresetTable;
use serde_json::Value;

/// Quoted from NVlabs/nvdiffrec `data/irrmaps/bsdf_256_256.bin` at
/// a3e73909a01887c8a135235ff860dd23a045cc1b (NVIDIA Source Code License for nvdiffrec,
/// Copyright (c) 2020-2022 NVIDIA CORPORATION & AFFILIATES): the file read as
/// `numpy.fromfile(path, numpy.float32).reshape(256, 256, 2)`, (row y, column x, A = [y, x, 0],
/// B = [y, x, 1]), each the shortest decimal that parses back to the stored float32. Among
/// them the two texels `brdfbake compare` names as the file's worst, A at (37, 150) and B at
/// (13, 49), the corners, the grazing column and a spread.
const NVDIFFREC: &[(usize, usize, f32, f32)] = &[
    (0, 0, 0.009727465, 0.9902487),
    (0, 1, 0.028955435, 0.97101426),
    (0, 255, 1., 2.8419638e-14),
    (1, 0, 0.009740711, 0.99012196),
    (0, 128, 0.96930236, 0.03064513),
    (37, 0, 0.25913197, 0.72225153),
    (37, 150, 0.9871737, 0.0122889485),
    (13, 49, 0.65835345, 0.34159386),
    (128, 0, 0.8055832, 0.19020821),
    (64, 64, 0.76064575, 0.20047013),
    (128, 128, 0.8342644, 0.021933476),
    (100, 200, 0.95879626, 0.0015457575),
    (128, 255, 0.9143665, 3.0049076e-5),
    (255, 0, 0.941525, 0.046538267),
    (255, 1, 0.9255012, 0.04467809),
    (255, 32, 0.7030566, 0.020684853),
    (255, 128, 0.44855067, 0.0029803712),
    (255, 255, 0.30927664, 3.546864e-5),
    (200, 12, 0.8414034, 0.05883388),
    (16, 240, 0.99999994, 8.469213e-7),
    (9, 7, 0.13923472, 0.8596786),
    (220, 100, 0.5995511, 0.009197284),
    (60, 180, 0.99208987, 0.0029346824),
    (180, 60, 0.7368863, 0.03557227),
];

/// The file's own error, as `brdfbake compare nvdiffrec-bsdf-256 bsdf_256_256.bin` measures it
/// over all its 65536 texels: at most 3.93e-4 (A) and 3.45e-4 (B), A biased 1.0e-4 high, with
/// a texel-to-texel scatter of 9e-6 (its estimator's noise). Its quoted texels must agree
/// with brdfbake's (exact to 1e-6) within that; 4e-4 is the larger, rounded up.
const FILE_ERROR: f64 = 4e-4;

fn preset_table(edit: impl Fn(String) -> String) -> PresetTable {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == "nvdiffrec-bsdf-256")
        .expect("the nvdiffrec preset is built in");
    brdfbake::preset::parse(&edit(text.to_string()), "nvdiffrec", "nvdiffrec-bsdf-256")
        .unwrap()
        .tables
        .remove(0)
}

/// The largest difference between the quoted texels and `t`'s table.
fn worst(t: &PresetTable) -> f64 {
    let lut = t.stored(brdfbake::table::bake(&t.spec).unwrap());
    let mut worst: f64 = 0.0;
    for &(y, x, a, b) in NVDIFFREC {
        for (c, v) in [(0, a), (1, b)] {
            worst = worst.max((lut.texel([x, y, 0], c) as f64 - v as f64).abs());
        }
    }
    worst
}

/// nvdiffrec's texels are brdfbake's on its grid (within the file's own error); Karis'
/// Schlick-GGX masking (what its authors cite: off by 0.35), roughness at texel endpoints
/// (3.4e-3), α along the roughness axis or the axes swapped each miss by more than 5 times
/// that.
#[test]
fn the_quoted_texels_fit_this_layout_and_no_other() {
    let w = worst(&preset_table(|s| s));
    assert!(w <= FILE_ERROR, "nvdiffrec's texels differ by {w}");
    for (what, edit) in [
        (
            "Schlick-GGX masking",
            ("smith-height-correlated", "schlick-ggx"),
        ),
        (
            "roughness at texel endpoints",
            (
                "\"quantity\": \"perceptual\"",
                "\"quantity\": \"perceptual\", \"convention\": \"endpoints\"",
            ),
        ),
        (
            "alpha along v",
            ("\"quantity\": \"perceptual\"", "\"quantity\": \"alpha\""),
        ),
        (
            "n.v along v",
            (
                "\"storage\": \"f32\"",
                "\"axis_order\": [\"roughness\", \"cos_theta_v\"], \"storage\": \"f32\"",
            ),
        ),
    ] {
        let t = preset_table(|s| {
            assert!(s.contains(edit.0), "{what}");
            s.replace(edit.0, edit.1)
        });
        let w = worst(&t);
        assert!(w > 5.0 * FILE_ERROR, "{what} should not fit: {w}");
    }
}

/// `bake --format bin` writes nvdiffrec's layout: 256 × 256 × 2 float32, 524288 bytes like
/// the original, row y = roughness. `compare` reads such a file (format `bin`) texel by texel
/// at the positions it names: brdfbake's own file with the quoted texels put in agrees with
/// the exact values except at them, and its worst texels are the file's worst quoted ones.
#[test]
fn bin_files_bake_and_compare() {
    let dir = tempfile::tempdir().unwrap();
    let w = dir.path();
    let o = cli::run(
        w,
        &[
            "bake",
            "nvdiffrec-bsdf-256",
            "--out",
            "out",
            "--format",
            "bin",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let file = w.join("out/nvdiffrec-bsdf-256/bsdf_256_256.bin");
    let mut bytes = std::fs::read(&file).unwrap();
    assert_eq!(bytes.len(), 524_288);
    let sidecar: Value =
        serde_json::from_slice(&std::fs::read(file.with_extension("json")).unwrap()).unwrap();
    assert_eq!(sidecar["storage"]["array"]["dtype"], "<f4");
    assert_eq!(
        sidecar["storage"]["array"]["shape"],
        serde_json::json!([256, 256, 2])
    );
    for &(y, x, a, b) in NVDIFFREC {
        for (c, v) in [(0, a), (1, b)] {
            let at = ((y * 256 + x) * 2 + c) * 4;
            bytes[at..at + 4].copy_from_slice(&v.to_le_bytes());
        }
    }
    std::fs::write(w.join("patched.bin"), &bytes).unwrap();
    let o = cli::run(
        w,
        &["compare", "nvdiffrec-bsdf-256", "patched.bin", "--json"],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    let channel = |name: &str| {
        doc["channels"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["channel"] == name)
            .unwrap_or_else(|| panic!("no channel {name}: {doc}"))
            .clone()
    };
    for (name, texel, value) in [("A", [150, 37], 0.9871737f32), ("B", [49, 13], 0.34159386)] {
        let s = &channel(name)["shipped"];
        assert_eq!(s["worst_texel"][0], texel[0], "{name}: {s}");
        assert_eq!(s["worst_texel"][1], texel[1], "{name}: {s}");
        assert_eq!(s["worst_value"].as_f64().unwrap(), value as f64, "{s}");
        let max = s["max_abs"].as_f64().unwrap();
        assert!(max > 3e-4 && max <= FILE_ERROR, "{name}: {s}");
    }
    // a file of another size is named
    std::fs::write(w.join("short.bin"), &bytes[..524_284]).unwrap();
    let o = cli::run(w, &["compare", "nvdiffrec-bsdf-256", "short.bin"]);
    cli::assert_fails(
        &o,
        cli::INPUT,
        &["524284 bytes hold 131071 float32 values", "needs 131072"],
        "a short file",
    );
}
