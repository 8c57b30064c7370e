//! EXR files written by brdfbake, read back by the official OpenEXR library (its Python
//! bindings, through tests/support/read_exr.py): dimensions, channel names and types, every
//! sample's bits, and the header attributes. Needs `python3 -m pip install openexr numpy`, which
//! `scripts/test` provisions (and then requires: tests/common/judges.rs).

use brdfbake::encode::{decode_exr, Encoder, ExrEncoder};
use brdfbake::lut::Lut;
use brdfbake::table::Storage;
use half::f16;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

#[path = "common/judges.rs"]
mod judges;
#[path = "common/luts.rs"]
mod luts;
use luts::lut;

const READER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/support/read_exr.py");

fn attributes() -> Vec<(String, String)> {
    [
        ("preset", "unit-test"),
        ("table", "dfg"),
        ("formula", "E(μ) = ∫ f(v,l) cos θ_l dω_l"),
        ("axis.x", "cos_theta_v, centers, [0, 1]"),
        ("vendor:key", "kept without prefix"),
        ("a_key_long_enough_to_need_the_long_names_flag", "long"),
        ("empty", ""),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), v.to_string()))
    .collect()
}

/// What OpenEXR reads from `path`; `None` when the bindings are missing outside
/// `scripts/test` (which requires them).
fn read_with_openexr(path: &Path) -> Option<Value> {
    if !judges::openexr() {
        return None;
    }
    let out = Command::new("python3")
        .arg(READER)
        .arg(path)
        .output()
        .expect("running python3");
    assert!(
        out.status.success(),
        "{READER} {} failed: {}",
        path.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    Some(serde_json::from_slice(&out.stdout).expect("read_exr.py prints JSON"))
}

/// Encodes `lut` (twice, checking determinism), writes it, reads it with OpenEXR and checks
/// everything against the table.
fn check(name: &str, lut: &Lut, storage: Storage) {
    let encoder = ExrEncoder {
        storage,
        table_name: name.into(),
    };
    let attrs = attributes();
    let bytes = encoder.encode(lut, &attrs).unwrap();
    assert_eq!(
        encoder.encode(lut, &attrs).unwrap(),
        bytes,
        "{name}: encoding twice gave different bytes"
    );

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("{name}.{}", encoder.extension()));
    brdfbake::write::write_atomic(&path, &bytes).unwrap();
    let Some(exr) = read_with_openexr(&path) else {
        return;
    };

    let (nx, ny, nz) = (lut.dim(0), lut.dim(1), lut.dim(2));
    assert_eq!(exr["parts"], 1, "{name}");
    assert_eq!(exr["width"], nx, "{name}");
    assert_eq!(exr["height"], ny * nz, "{name}");
    assert_eq!(exr["data_window"][0], serde_json::json!([0, 0]), "{name}");
    assert_eq!(exr["compression"], "NO_COMPRESSION", "{name}");
    assert_eq!(exr["line_order"], "INCREASING_Y", "{name}");
    assert_eq!(exr["storage"], "scanlineimage", "{name}");

    // channels: the table's names, in EXR's (byte-wise alphabetical) order
    let channels = exr["channels"].as_array().unwrap();
    let mut expected_names: Vec<&str> = lut.channels.iter().map(|c| c.name.as_str()).collect();
    expected_names.sort_unstable();
    let names: Vec<&str> = channels
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, expected_names, "{name}");

    let decoded = decode_exr(&bytes).unwrap();
    assert_eq!((decoded.0, decoded.1), (nx, ny * nz), "{name}");

    for channel in channels {
        let cname = channel["name"].as_str().unwrap();
        let c = lut.channels.iter().position(|ch| ch.name == cname).unwrap();
        let expected_type = match storage {
            Storage::F32 => "FLOAT",
            Storage::F16 => "HALF",
            s => unreachable!("EXR has no {s:?}"),
        };
        assert_eq!(channel["type"], expected_type, "{name}/{cname}");
        assert_eq!(channel["x_sampling"], 1, "{name}/{cname}");
        assert_eq!(channel["y_sampling"], 1, "{name}/{cname}");

        // image pixel (x, row z·ny + y), rows top to bottom, holds texel [x, y, z]
        let mut expected_bits = Vec::new();
        let mut expected_values = Vec::new();
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    let v = lut.texel([x, y, z], c);
                    let (bits, stored) = match storage {
                        Storage::F32 => (v.to_bits() as u64, v),
                        Storage::F16 => {
                            let h = f16::from_f32(v);
                            (h.to_bits() as u64, h.to_f32())
                        }
                        s => unreachable!("EXR has no {s:?}"),
                    };
                    expected_bits.push(bits);
                    expected_values.push(stored);
                }
            }
        }
        let bits: Vec<u64> = channel["bits"]
            .as_array()
            .unwrap()
            .iter()
            .map(|b| b.as_u64().unwrap())
            .collect();
        assert_eq!(bits.len(), expected_bits.len(), "{name}/{cname}");
        for (i, (got, want)) in bits.iter().zip(&expected_bits).enumerate() {
            assert_eq!(
                got,
                want,
                "{name}/{cname}: sample {i} (x {}, row {}) has bits {got:#x}, expected {want:#x} ({})",
                i % nx,
                i / nx,
                expected_values[i]
            );
        }
        // the exr crate's reader agrees
        let (_, ours) = decoded.2.iter().find(|(n, _)| n == cname).unwrap();
        let ours: Vec<u32> = ours.iter().map(|v| v.to_bits()).collect();
        let want: Vec<u32> = expected_values.iter().map(|v| v.to_bits()).collect();
        assert_eq!(ours, want, "{name}/{cname}: decode_exr");
    }

    // header attributes: every one, prefixed unless namespaced, and nothing else
    let in_order: Vec<(String, String)> = attrs
        .iter()
        .map(|(k, v)| {
            let key = if k.contains(':') {
                k.clone()
            } else {
                format!("brdfbake:{k}")
            };
            (key, v.clone())
        })
        .collect();
    let expected: BTreeMap<String, String> = in_order.iter().cloned().collect();
    let got: BTreeMap<String, String> = exr["string_attributes"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| (k.clone(), v.as_str().unwrap().to_string()))
        .collect();
    assert_eq!(got, expected, "{name}: attributes as OpenEXR reads them");
    assert_eq!(decoded.3, in_order, "{name}: attributes in file order");
}

/// Values spanning what a table may hold: tiny (f16 subnormal and underflow), large,
/// negative, zero and negative zero.
fn mixed(idx: [usize; 3], c: usize) -> f32 {
    const SPECIAL: [f32; 10] = [
        0.0,
        -0.0,
        1e-7,
        3.0e-5,
        -2.5,
        0.1,
        1.0 / 3.0,
        60000.0,
        -65504.0,
        1e-30,
    ];
    let i = idx[0] + 7 * idx[1] + 31 * idx[2] + 3 * c;
    if i.is_multiple_of(3) {
        SPECIAL[(i / 3) % SPECIAL.len()]
    } else {
        (i as f32 * 0.731).sin() * 10f32.powi((i % 9) as i32 - 4)
    }
}

#[test]
fn two_channel_2d_f16() {
    check("dfg", &lut(&[6, 4], &["B", "A"], mixed), Storage::F16);
}

#[test]
fn two_channel_2d_f32() {
    check("dfg32", &lut(&[6, 4], &["A", "B"], mixed), Storage::F32);
}

#[test]
fn three_channel_2d_f32_with_extreme_values() {
    let extreme = |idx: [usize; 3], c: usize| match (idx[0] + idx[1] + c) % 4 {
        0 => 3.0e38,
        1 => -1.0e-38,
        2 => f32::from_bits(1), // the smallest subnormal
        _ => mixed(idx, c),
    };
    check(
        "multiscatter",
        &lut(&[5, 3], &["R", "G", "cloth"], extreme),
        Storage::F32,
    );
    check(
        "multiscatter16",
        &lut(&[5, 3], &["R", "G", "cloth"], mixed),
        Storage::F16,
    );
}

#[test]
fn one_d() {
    let t = lut(&[17], &["E_avg"], mixed);
    check("albedo-avg", &t, Storage::F16);
    check("albedo-avg32", &t, Storage::F32);
}

#[test]
fn three_d_slices_stack_vertically() {
    let t = lut(&[4, 3, 5], &["G2"], mixed);
    check("g2", &t, Storage::F32);
    check("g2-16", &t, Storage::F16);
}

/// f16 storage rounds ties to even, as OpenEXR reads it back.
#[test]
fn f16_ties_round_to_even() {
    let ties = [
        1.0 + 2f32.powi(-11),       // → 1
        1.0 + 3.0 * 2f32.powi(-11), // → 1 + 2⁻⁹
        -(1.0 + 2f32.powi(-11)),    // → −1
        2f32.powi(-25),             // halfway between 0 and the smallest subnormal → 0
        3.0 * 2f32.powi(-25),       // → 2⁻²³ (even subnormal)
    ];
    let t = lut(&[ties.len()], &["v"], |idx, _| ties[idx[0]]);
    check("ties", &t, Storage::F16);
    let expected = [1.0, 1.0 + 2f32.powi(-9), -1.0, 0.0, 2f32.powi(-23)];
    for (v, e) in ties.iter().zip(expected) {
        assert_eq!(f16::from_f32(*v).to_f32(), e, "{v}");
    }
}
