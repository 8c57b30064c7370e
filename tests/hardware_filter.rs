//! Hardware filtering: `probe --filter hardware` reads what a GPU with 8-bit sub-texel weights
//! reads (checked against a bilinear/trilinear fetch written here from the KTX2 texels), never
//! further from the ideal lookup than the table's weight-rounding bound, which the sidecar
//! states (`lookup_error`, recomputed here from the texels) with the interpolation estimate;
//! `verify` measures the lookup error at cell middles, as `probe` computes it.

#[path = "common/cli.rs"]
mod cli;

use brdfbake::lut::{Filter, Lut};
use serde_json::Value;
use std::path::Path;

const PRESET: &str = r#"{
  "schema": "brdfbake.preset/1",
  "tables": [
    {"name": "dfg", "kind": "dfg", "layout": "karis",
     "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
     "axes": {"cos_theta_v": {"size": 16},
              "roughness": {"size": 12, "quantity": "perceptual", "range": [0.1, 1], "convention": "endpoints"}},
     "formats": ["ktx2"]},
    {"name": "g2", "kind": "g2", "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
     "axes": {"cos_theta_v": {"size": 8}, "cos_theta_l": {"size": 8},
              "roughness": {"size": 6, "quantity": "alpha", "range": [0.1, 1]}},
     "formats": ["ktx2"], "layout_3d": "array"},
    {"name": "g2v", "kind": "g2", "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
     "axes": {"cos_theta_v": {"size": 8}, "cos_theta_l": {"size": 8},
              "roughness": {"size": 6, "quantity": "alpha", "range": [0.1, 1]}},
     "formats": ["ktx2"]}
  ]
}"#;

fn baked() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("hw.json"), PRESET).unwrap();
    let o = cli::run(dir.path(), &["bake", "hw.json", "--out", "out", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    dir
}

fn json(o: &std::process::Output) -> Value {
    assert!(o.status.success(), "{}", cli::stderr(o));
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

fn probe(dir: &Path, file: &str, at: &str, filter: &str) -> Value {
    json(&cli::run(
        dir,
        &["probe", file, "--at", at, "--json", "--filter", filter],
    ))
}

fn lut_of(dir: &Path, file: &str) -> Lut {
    brdfbake::readback::read(&dir.join(file))
        .unwrap()
        .lut
        .expect("a texture")
}

/// A fetch with weights rounded to 1/256 on the first `hw_axes` axes, written from the KTX2
/// texels without the library's lookup: texel-space position p = t·N − ½ (centers) or
/// t·(N − 1) (endpoints), clamped to [0, N − 1].
fn fetch_8bit(lut: &Lut, x: &[f64], hw_axes: usize) -> Vec<f64> {
    let taps: Vec<(usize, usize, f64)> = (0..3)
        .map(|k| {
            let Some(a) = lut.axes.get(k) else {
                return (0, 0, 0.0);
            };
            let [lo, hi] = a.range;
            let t = (x[k] - lo) / (hi - lo);
            let n = a.size as f64;
            let p = match a.convention {
                brdfbake::lut::Convention::Centers => t * n - 0.5,
                brdfbake::lut::Convention::Endpoints => t * (n - 1.0),
            }
            .clamp(0.0, n - 1.0);
            let i = p.floor();
            let mut f = p - i;
            if k < hw_axes {
                f = (f * 256.0).round() / 256.0;
            }
            (i as usize, (i as usize + 1).min(a.size - 1), f)
        })
        .collect();
    (0..lut.channels.len())
        .map(|c| {
            let mut v = 0.0;
            for corner in 0..8 {
                let mut w = 1.0;
                let mut idx = [0; 3];
                for (k, &(i0, i1, f)) in taps.iter().enumerate() {
                    let up = (corner >> k) & 1 == 1;
                    idx[k] = if up { i1 } else { i0 };
                    w *= if up { f } else { 1.0 - f };
                }
                if w != 0.0 {
                    v += w * lut.texel(idx, c) as f64;
                }
            }
            v
        })
        .collect()
}

/// Σ over the first `axes` axes of the largest neighbour step / 512, from the texels.
fn bound_of(lut: &Lut, axes: usize) -> Vec<f64> {
    let dims = [lut.dim(0), lut.dim(1), lut.dim(2)];
    (0..lut.channels.len())
        .map(|c| {
            let mut sum = 0.0;
            for k in 0..axes {
                let mut m = 0.0f64;
                for z in 0..dims[2] {
                    for y in 0..dims[1] {
                        for x in 0..dims[0] {
                            let mut n = [x, y, z];
                            n[k] += 1;
                            if n[k] < dims[k] {
                                let d = lut.texel(n, c) as f64 - lut.texel([x, y, z], c) as f64;
                                m = m.max(d.abs());
                            }
                        }
                    }
                }
                sum += m / 512.0;
            }
            sum
        })
        .collect()
}

#[test]
fn probe_reads_what_8_bit_weights_read() {
    let dir = baked();
    let d = dir.path();
    let lut = lut_of(d, "out/hw/dfg.ktx2");
    let side: Value =
        serde_json::from_slice(&std::fs::read(d.join("out/hw/dfg.json")).unwrap()).unwrap();
    let bound = bound_of(&lut, 2);
    // a texel centre and a cell middle: weights 0 and 1/2 are exact in 8 bits (up to the
    // f64 rounding of the coordinates: a weight of 0.5 - 1e-16 rounds to 0.5)
    for (x, y) in [(lut.axes[0].coord(3), lut.axes[1].coord(5)), (0.5, 0.55)] {
        let at = format!("cos_theta_v={x},roughness={y}");
        let p = probe(d, "out/hw/dfg.ktx2", &at, "hardware");
        for ch in p["channels"].as_array().unwrap() {
            let w = ch["weight_rounding"].as_f64().unwrap();
            assert!(w.abs() <= 1e-15, "{at}: {ch}");
        }
    }
    // points off the 1/256 grid: the 8-bit fetch, within the bound of the ideal one
    let mut largest = [0.0f64; 2];
    for i in 0..40 {
        let x = 0.013 + 0.0247 * i as f64;
        let y = 0.1 + (0.9 * ((i * 7) % 40) as f64 + 0.37) / 40.0;
        let at = format!("cos_theta_v={x},roughness={y}");
        let p = probe(d, "out/hw/dfg.ktx2", &at, "hardware");
        assert_eq!(p["filter"], "hardware");
        assert_eq!(
            p["hardware_filtered_axes"],
            serde_json::json!(["cos_theta_v", "roughness"])
        );
        let want = fetch_8bit(&lut, &[x, y], 2);
        let ideal = probe(d, "out/hw/dfg.ktx2", &at, "ideal");
        for (c, ch) in p["channels"].as_array().unwrap().iter().enumerate() {
            let gpu = ch["gpu"].as_f64().unwrap();
            assert!((gpu - want[c]).abs() <= 1e-12, "{at}: {gpu} vs {}", want[c]);
            let ideal_gpu = ideal["channels"][c]["gpu"].as_f64().unwrap();
            assert_eq!(ch["gpu_ideal"].as_f64().unwrap(), ideal_gpu);
            let d = (gpu - ideal_gpu).abs();
            assert!(d <= bound[c] * (1.0 + 1e-9), "{at}: {d} > {}", bound[c]);
            assert_eq!(ch["weight_rounding_bound"].as_f64().unwrap(), bound[c]);
            largest[c] = largest[c].max(d);
        }
    }
    // the rounding shows: a lookup moves by a sizable part of the bound somewhere
    for c in 0..2 {
        assert!(largest[c] > 0.05 * bound[c], "{largest:?} vs {bound:?}");
    }
    // the sidecar states the same bound, and the hardware error as ideal + bound
    let le = &side["lookup_error"];
    for (c, name) in ["A", "B"].iter().enumerate() {
        assert_eq!(
            le["weight_rounding_bound"][name].as_f64().unwrap(),
            bound[c]
        );
        let sum = le["ideal_filtering"][name].as_f64().unwrap() + bound[c];
        let hw = le["hardware_filtering"][name].as_f64().unwrap();
        assert!((hw - sum).abs() <= 1e-15 * hw, "{hw} vs {sum}");
        let interp = le["interpolation_estimate"][name].as_f64().unwrap();
        assert_eq!(
            interp,
            lut.interpolation_error_estimate()[c],
            "the sidecar's estimate is the texels' own"
        );
        let ideal = le["ideal_filtering"][name].as_f64().unwrap();
        let texel = le["texel_error"][name].as_f64().unwrap();
        assert_eq!(ideal, lut.interpolation_bound()[c] + texel);
        // the bound is the largest corner range of a cell: at most the sum of the axes'
        // largest steps, and at least the largest step
        let steps: Vec<f64> = (0..2).map(|k| lut.max_steps(k)[c]).collect();
        let b = lut.interpolation_bound()[c];
        assert!(
            b <= steps[0] + steps[1] && b >= steps[0].max(steps[1]),
            "{b} {steps:?}"
        );
    }
}

/// A 3D table: a 3D texture rounds the weights on all three axes, the 2D-array layout (its
/// shader blends the slices) on u and v only; the sidecars say so.
#[test]
fn arrays_round_the_weights_of_two_axes() {
    let dir = baked();
    let d = dir.path();
    for (file, axes) in [("out/hw/g2v.ktx2", 3), ("out/hw/g2.ktx2", 2)] {
        let lut = lut_of(d, file);
        let bound = bound_of(&lut, axes);
        let side: Value =
            serde_json::from_slice(&std::fs::read(d.join(file.replace(".ktx2", ".json"))).unwrap())
                .unwrap();
        let le = &side["lookup_error"];
        assert_eq!(le["hardware_filtered_axes"].as_array().unwrap().len(), axes);
        assert_eq!(
            le["weight_rounding_bound"]["G2"].as_f64().unwrap(),
            bound[0]
        );
        for i in 0..12 {
            let x = [
                0.03 + 0.077 * i as f64,
                0.97 - 0.061 * i as f64,
                0.1 + 0.9 * ((i * 5 % 12) as f64 + 0.29) / 12.0,
            ];
            let at = format!(
                "cos_theta_v={},cos_theta_l={},roughness={}",
                x[0], x[1], x[2]
            );
            let p = probe(d, file, &at, "hardware");
            let gpu = p["channels"][0]["gpu"].as_f64().unwrap();
            assert!(
                (gpu - fetch_8bit(&lut, &x, axes)[0]).abs() <= 1e-12,
                "{file} {at}"
            );
            let ideal = lut.lookup(&x)[0];
            assert!((gpu - ideal).abs() <= bound[0] * (1.0 + 1e-9));
            assert_eq!(
                lut.lookup_filtered(&x, Filter::Hardware { axes })[0],
                gpu,
                "the library's fetch"
            );
        }
    }
}

/// Beyond the range (a cosine of 1.3), where no exact value exists, probe gives the exact
/// value where the GPU reads: at the edge texels.
#[test]
fn probe_beyond_the_range_compares_with_the_edge_texels() {
    let dir = baked();
    let d = dir.path();
    let p = probe(
        d,
        "out/hw/dfg.ktx2",
        "cos_theta_v=1.3,roughness=0.05",
        "ideal",
    );
    let lut = lut_of(d, "out/hw/dfg.ktx2");
    let edge = [lut.axes[0].coord(15), lut.axes[1].coord(0)];
    assert_eq!(p["exact_at"]["cos_theta_v"].as_f64().unwrap(), edge[0]);
    assert_eq!(p["exact_at"]["roughness"].as_f64().unwrap(), edge[1]);
    let notes = p["notes"].to_string();
    assert!(notes.contains("at the edge texels' coordinates"), "{notes}");
    for (c, ch) in p["channels"].as_array().unwrap().iter().enumerate() {
        assert_eq!(ch["gpu"].as_f64().unwrap(), lut.texel([15, 0, 0], c) as f64);
        // the edge texel is within its quadrature tolerance of the exact value there
        assert!(ch["difference"].as_f64().unwrap().abs() < 1e-6, "{ch}");
    }
    // within the domain (roughness 0.05 < the range's 0.1) the exact value is at the point
    let p = probe(
        d,
        "out/hw/dfg.ktx2",
        "cos_theta_v=0.5,roughness=0.05",
        "ideal",
    );
    assert!(p.get("exact_at").is_none(), "{p}");
}

/// verify measures the lookup error at cell middles: its largest is probe's difference at
/// that point, and its hardware figure adds the sidecar's weight-rounding bound.
#[test]
fn verify_measures_lookups_between_texels() {
    let dir = baked();
    let d = dir.path();
    let v = json(&cli::run(d, &["verify", "out/hw/dfg.ktx2", "--json"]));
    let t = &v["tables"][0];
    let lookups = &t["lookups"];
    assert!(
        lookups["cell_middles_checked"].as_u64().unwrap() > 20,
        "{lookups}"
    );
    let side: Value =
        serde_json::from_slice(&std::fs::read(d.join("out/hw/dfg.json")).unwrap()).unwrap();
    for ch in lookups["channels"].as_array().unwrap() {
        let name = ch["channel"].as_str().unwrap();
        let at = ch["at"].as_array().unwrap();
        let at = format!(
            "cos_theta_v={},roughness={}",
            at[0].as_f64().unwrap(),
            at[1].as_f64().unwrap()
        );
        let p = probe(d, "out/hw/dfg.ktx2", &at, "ideal");
        let pc = p["channels"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["channel"] == name)
            .unwrap();
        let e = ch["ideal_filtering_max_error"].as_f64().unwrap();
        assert!(e > 0.0);
        // both recompute the exact value to 1e-10
        assert!(
            (pc["difference"].as_f64().unwrap().abs() - e).abs() < 1e-9,
            "{pc} {ch}"
        );
        let bound = side["lookup_error"]["weight_rounding_bound"][name]
            .as_f64()
            .unwrap();
        assert_eq!(ch["weight_rounding_bound"].as_f64().unwrap(), bound);
        assert_eq!(
            ch["hardware_filtering_max_error"].as_f64().unwrap(),
            e + bound
        );
        // a smooth, monotone table: the measured error is within the sidecar's worst case
        assert_eq!(ch["within_sidecar_worst_case"], true, "{ch}");
    }
    let text = cli::run(d, &["verify", "out/hw/dfg.ktx2"]);
    let out = String::from_utf8_lossy(&text.stdout);
    assert!(out.contains("lookups between texels"), "{out}");
    assert!(out.contains("hardware up to"), "{out}");
}
