//! Storage engines upload and the channels they store: the `unorm8`/`unorm16` storages, the
//! `png-data` format and the `channels` preset field, end to end through the binary.
//!
//! - png-data files decoded by the `png` crate (an independent decoder; readback uses it too,
//!   but here nothing of brdfbake's decodes): colour type, bit depth, size, every sample equal
//!   to the code computed here (nearest integer to value × (2ⁿ − 1), ties to even), B = 0 for
//!   two channels, the first row y = 0, and no colour-space chunk;
//! - the sidecar states the step, the bound and the measured rounding, and the measured
//!   rounding is what the files hold;
//! - verify, probe, inspect and bake --check read UNORM KTX2 and png-data files;
//! - the `channels` field transforms the stored channels exactly, is in the input hash only
//!   when set, and verify/probe compare the transformed exact values;
//! - every bad input is a named error, exit 2, with nothing written;
//! - bytes are identical for any thread count.

#[path = "common/cli.rs"]
mod cli;
#[path = "common/luts.rs"]
mod luts;

use brdfbake::encode::png_data::PngData;
use brdfbake::encode::Encoder;
use brdfbake::table::Storage;
use serde_json::Value;
use std::fs;
use std::path::Path;

/// The UNORM code of `v` computed here, independently of the encoders: the nearest integer
/// to v·max, a tie going to the even one.
fn unorm_code(v: f32, max: u32) -> u16 {
    let x = v as f64 * max as f64;
    let f = x.floor();
    let c = if x - f > 0.5 || (x - f == 0.5 && f % 2.0 == 1.0) {
        f + 1.0
    } else {
        f
    };
    assert!((0.0..=max as f64).contains(&c), "{v} is not storable");
    c as u16
}

/// A decoded PNG: (colour type, bit depth, width, height, samples as u16, chunk types).
type Decoded = (
    png::ColorType,
    png::BitDepth,
    usize,
    usize,
    Vec<u16>,
    Vec<String>,
);

/// Decodes a PNG with the `png` crate, samples as stored (no transformations).
fn decode(bytes: &[u8]) -> Decoded {
    let mut d = png::Decoder::new(std::io::Cursor::new(bytes));
    d.set_transformations(png::Transformations::IDENTITY);
    let mut r = d.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let frame = r.next_frame(&mut buf).unwrap();
    let buf = &buf[..frame.buffer_size()];
    let samples = match frame.bit_depth {
        png::BitDepth::Eight => buf.iter().map(|&b| b as u16).collect(),
        _ => buf
            .chunks_exact(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect(),
    };
    // chunk types, walking the file: 8-byte signature, then length, type, data, CRC
    let mut chunks = Vec::new();
    let mut at = 8;
    while at + 8 <= bytes.len() {
        let len = u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        chunks.push(String::from_utf8_lossy(&bytes[at + 4..at + 8]).into_owned());
        at += 12 + len;
    }
    (
        frame.color_type,
        frame.bit_depth,
        frame.width as usize,
        frame.height as usize,
        samples,
        chunks,
    )
}

/// Values in [0, 1] with the rounding cases: ends, an exact tie, values within half a step
/// outside [0, 1].
fn unit_value(t: [usize; 3], c: usize) -> f32 {
    const SPECIAL: [f32; 6] = [0.0, 1.0, 0.5, 1.0 + 1e-6, -1e-6, 0.999_999];
    let i = (t[2] * 7 + t[1]) * 13 + t[0];
    if (i + c).is_multiple_of(5) {
        SPECIAL[(i / 5 + c) % SPECIAL.len()]
    } else {
        0.5 + 0.5 * (i as f32 * 0.41 + c as f32 * 1.7).sin()
    }
}

/// png-data through the `png` crate: every channel count, both depths, 1D, 2D and 3D.
#[test]
fn png_data_round_trips_through_the_png_crate() {
    for storage in [Storage::Unorm8, Storage::Unorm16] {
        let max = storage.unorm_max().unwrap();
        for sizes in [&[7][..], &[5, 3], &[4, 3, 2]] {
            for nc in 1..=4 {
                let t = luts::lut(sizes, &["E", "A", "B", "C"][..nc], unit_value);
                let enc = PngData {
                    storage,
                    table_name: "t".into(),
                };
                let attrs = vec![
                    ("schema".to_string(), brdfbake::meta::SCHEMA.to_string()),
                    ("preset".to_string(), "unit".to_string()),
                ];
                let bytes = enc.encode(&t, &attrs).unwrap();
                assert_eq!(enc.encode(&t, &attrs).unwrap(), bytes, "deterministic");
                let (color, depth, w, h, samples, chunks) = decode(&bytes);
                let what = format!("{storage:?} {sizes:?} {nc} channels");
                let (want_color, comps) = match nc {
                    1 => (png::ColorType::Grayscale, 1),
                    2 | 3 => (png::ColorType::Rgb, 3),
                    _ => (png::ColorType::Rgba, 4),
                };
                assert_eq!(color, want_color, "{what}");
                let want_depth = if max == 255 {
                    png::BitDepth::Eight
                } else {
                    png::BitDepth::Sixteen
                };
                assert_eq!(depth, want_depth, "{what}");
                // width nx, height ny·nz: the slices stacked downward
                assert_eq!((w, h), (t.dim(0), t.dim(1) * t.dim(2)), "{what}");
                for z in 0..t.dim(2) {
                    for y in 0..t.dim(1) {
                        for x in 0..t.dim(0) {
                            // image row z·ny + y from the top
                            let px = ((z * t.dim(1) + y) * w + x) * comps;
                            for k in 0..comps {
                                let want = if k < nc {
                                    unorm_code(t.texel([x, y, z], k), max)
                                } else {
                                    0 // the B of a two-channel table
                                };
                                assert_eq!(samples[px + k], want, "{what} [{x},{y},{z}] {k}");
                            }
                        }
                    }
                }
                for colour in ["sRGB", "gAMA", "cHRM", "iCCP", "cICP"] {
                    assert!(!chunks.iter().any(|c| c == colour), "{what}: {chunks:?}");
                }
                assert!(chunks.iter().any(|c| c == "tEXt"), "{what}: {chunks:?}");
                // brdfbake reads back what a sampler reads: code / max
                let (back, facts) =
                    brdfbake::readback::read_png_data_bytes(Path::new("t.png"), &bytes, None)
                        .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert!(facts.iter().any(|(k, v)| k == "preset" && v == "unit"));
                // (without a sidecar: the image's components)
                assert_eq!(back.channels.len(), comps, "{what}");
                for (i, v) in t.data.iter().enumerate() {
                    let (texel, c) = (i / nc, i % nc);
                    let got = back.data[texel * back.channels.len() + c] as f64;
                    let want = unorm_code(*v, max) as f64 / max as f64;
                    assert!((got - want).abs() <= 1e-7, "{what}: {got} vs {want}");
                }
            }
        }
    }
    // float storage is refused
    let t = luts::lut(&[3], &["E"], unit_value);
    let e = PngData {
        storage: Storage::F32,
        table_name: "t".into(),
    }
    .encode(&t, &[])
    .unwrap_err()
    .to_string();
    assert!(e.contains("png-data stores normalized integers"), "{e}");
}

const MODEL: &str = r#""model": {"ndf": "ggx", "masking": "smith-height-correlated"}"#;

fn preset(tables: &[String]) -> String {
    format!(
        r#"{{"schema": "brdfbake.preset/1", "tables": [{}]}}"#,
        tables.join(",\n")
    )
}

fn dfg(name: &str, extra: &str, nx: usize, ny: usize) -> String {
    format!(
        r#"{{"name": "{name}", "kind": "dfg", "layout": "karis", {MODEL}{extra},
            "axes": {{"cos_theta_v": {{"size": {nx}}}, "roughness": {{"size": {ny}, "quantity": "perceptual"}}}}}}"#
    )
}

fn json(path: &Path) -> Value {
    serde_json::from_slice(&fs::read(path).unwrap()).unwrap()
}

/// The UNORM storages bake, state their rounding (bound and measured) and read back through
/// every command; the measured rounding is what the files hold.
#[test]
fn unorm_tables_state_their_rounding_and_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let formats = r#", "formats": ["ktx2", "png-data", "h", "rs", "glsl", "wgsl"]"#;
    let text = preset(&[
        dfg(
            "u16",
            &format!(r#", "storage": "unorm16"{formats}"#),
            64,
            64,
        ),
        dfg("u8", &format!(r#", "storage": "unorm8"{formats}"#), 64, 64),
        dfg("f32", r#", "formats": ["ktx2"]"#, 64, 64),
        dfg("u16s", r#", "storage": "unorm16", "scale": 0.5"#, 16, 8),
    ]);
    fs::write(d.join("u.json"), &text).unwrap();
    let o = cli::run(d, &["bake", "u.json", "--out", "out", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    // a unorm table's default format is the KTX2
    assert!(d.join("out/u/u16s.ktx2").is_file());
    assert!(!d.join("out/u/u16s.exr").exists());
    let f32_side = json(&d.join("out/u/f32.json"));
    for (name, max) in [("u16", 65535u32), ("u8", 255)] {
        let side = json(&d.join(format!("out/u/{name}.json")));
        let st = &side["storage"];
        let step = 1.0 / max as f64;
        assert_eq!(
            st["texel_type"],
            if max == 255 { "unorm8" } else { "unorm16" }
        );
        assert_eq!(st["quantization_step"].as_f64().unwrap(), step);
        assert_eq!(st["rounding_error_bound"].as_f64().unwrap(), step / 2.0);
        // the codes in the png-data file against the f32 table's texels (same inputs but
        // the storage: the same baked values)
        let (_, _, w, h, samples, _) =
            decode(&fs::read(d.join(format!("out/u/{name}.png"))).unwrap());
        let f32_lut = brdfbake::readback::read(&d.join("out/u/f32.ktx2"))
            .unwrap()
            .lut
            .unwrap();
        assert_eq!((w, h), (64, 64));
        for (c, ch) in ["A", "B"].iter().enumerate() {
            let mut measured = 0.0f64;
            for y in 0..64 {
                for x in 0..64 {
                    let v = f32_lut.texel([x, y, 0], c);
                    let code = samples[(y * 64 + x) * 3 + c];
                    assert_eq!(code, unorm_code(v, max), "{name} {ch} [{x}, {y}]");
                    measured = measured.max((code as f64 / max as f64 - v as f64).abs());
                }
            }
            let stated = st["measured_max_rounding_error"][ch].as_f64().unwrap();
            assert_eq!(stated, measured, "{name} {ch}");
            // at most half a step; and 4096 smooth-table texels' fractional parts cover it:
            // all within 0.9 of the half step has chance ~0.9^4096
            assert!(measured <= step / 2.0, "{name} {ch}: {measured}");
            assert!(measured > 0.9 * step / 2.0, "{name} {ch}: {measured}");
            eprintln!(
                "{name} {ch}: measured rounding {measured:.4e} (bound {:.4e})",
                step / 2.0
            );
            // texel_error = the f32 table's + the bound
            let te = side["lookup_error"]["texel_error"][ch].as_f64().unwrap();
            let te32 = f32_side["lookup_error"]["texel_error"][ch]
                .as_f64()
                .unwrap();
            assert!(
                (te - te32 - step / 2.0).abs() <= 1e-15,
                "{name} {ch}: {te} vs {te32}"
            );
        }
        // the same codes in the KTX2 (through readback) and the sources
        let ktx = brdfbake::readback::read(&d.join(format!("out/u/{name}.ktx2"))).unwrap();
        assert_eq!(ktx.texture_format, Some("ktx2"));
        let png = brdfbake::readback::read(&d.join(format!("out/u/{name}.png"))).unwrap();
        assert_eq!(png.texture_format, Some("png-data"));
        assert_eq!(
            ktx.lut.as_ref().unwrap().data,
            png.lut.as_ref().unwrap().data
        );
        let h_text = fs::read_to_string(d.join(format!("out/u/{name}.h"))).unwrap();
        let element = if max == 255 { "uint8_t" } else { "uint16_t" };
        assert!(
            h_text.contains(&format!("static const {element} ")),
            "{name}"
        );
        let glsl = fs::read_to_string(d.join(format!("out/u/{name}.glsl"))).unwrap();
        assert!(glsl.contains(&format!("storage unorm{}", if max == 255 { 8 } else { 16 })));
        // verify: within the tolerance plus half a step, and it says so
        for f in ["ktx2", "png"] {
            let o = cli::run(d, &["verify", &format!("out/u/{name}.{f}"), "--json"]);
            assert!(o.status.success(), "{name}.{f}: {}", cli::stderr(&o));
            let v: Value = serde_json::from_slice(&o.stdout).unwrap();
            let t = &v["tables"][0];
            assert_eq!(t["storage_rounding_bound"].as_f64().unwrap(), step / 2.0);
            assert_eq!(t["threshold"].as_f64().unwrap(), 1e-6 + step / 2.0);
            for c in t["channels"].as_array().unwrap() {
                assert!(c["max_error"].as_f64().unwrap() <= 1e-6 + step / 2.0);
            }
            let o = cli::run(d, &["verify", &format!("out/u/{name}.{f}")]);
            assert!(
                String::from_utf8_lossy(&o.stdout).contains("storage's rounding, half a step"),
                "{}",
                String::from_utf8_lossy(&o.stdout)
            );
        }
        // inspect and probe read them
        let o = cli::run(d, &["inspect", &format!("out/u/{name}.png"), "--json"]);
        assert!(o.status.success(), "{}", cli::stderr(&o));
        let v: Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(v["texture_format"], "png-data");
        assert_eq!(v["storage"], if max == 255 { "unorm8" } else { "unorm16" });
        let o = cli::run(
            d,
            &[
                "probe",
                &format!("out/u/{name}.ktx2"),
                "--at",
                "cos_theta_v=0.5,roughness=0.5",
                "--json",
            ],
        );
        assert!(o.status.success(), "{}", cli::stderr(&o));
    }
    // the scale: stored = value × scale, rounded; measured and stated in values
    let side = json(&d.join("out/u/u16s.json"));
    let measured = side["storage"]["measured_max_rounding_error"]["A"]
        .as_f64()
        .unwrap();
    assert!(measured <= 0.5 / 65535.0 / 0.5, "{measured}");
    let o = cli::run(d, &["verify", "out/u/u16s.ktx2", "--json"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        v["tables"][0]["storage_rounding_bound"].as_f64().unwrap(),
        0.5 / 65535.0 / 0.5
    );
    // bake --check knows the files; a preview is not read back as data
    let o = cli::run(d, &["bake", "u.json", "--out", "out", "--check"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let o = cli::run(
        d,
        &[
            "bake", "u.json", "--out", "out", "-q", "--format", "png,ktx2",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    cli::assert_fails(
        &cli::run(d, &["verify", "out/u/u8.preview-A.png"]),
        cli::INPUT,
        &["preview for people"],
        "a preview",
    );
    // a code changed in a png-data file, the sidecar sealed over it (as no bake writes):
    // verify finds the texel off by more than the rounding
    let o = cli::run(d, &["bake", "u.json", "--out", "out2", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let path = d.join("out2/u/u8.png");
    let rb = brdfbake::readback::read(&path).unwrap();
    let table = rb.table.unwrap();
    let mut lut = rb.lut.unwrap();
    // the first texel's A, which verify always checks (a corner), 3 codes off: 3/255 is
    // more than the tolerance plus half a step, 1e-6 + 1/510
    let code = (lut.data[0] as f64 * 255.0).round();
    let moved = if code <= 252.0 {
        code + 3.0
    } else {
        code - 3.0
    };
    lut.data[0] = (moved / 255.0) as f32;
    let attrs = brdfbake::meta::header_attributes("u", &table, &lut);
    let bytes = PngData {
        storage: Storage::Unorm8,
        table_name: "u8".into(),
    }
    .encode(&lut, &attrs)
    .unwrap();
    fs::write(&path, &bytes).unwrap();
    let side = json(&d.join("out2/u/u8.json"));
    let ktx = fs::read(d.join("out2/u/u8.ktx2")).unwrap();
    fs::write(
        d.join("out2/u/u8.json"),
        brdfbake::digest::seal(side, &[("u8.ktx2", &ktx), ("u8.png", &bytes)]),
    )
    .unwrap();
    cli::assert_fails(
        &cli::run(d, &["verify", "out2/u/u8.png"]),
        cli::ENV,
        &["over the tolerance"],
        "a changed code",
    );
}

/// The `channels` field: engines' arrangements stored exactly, described in the sidecar,
/// verified against the transformed exact values; in the hash only when set.
#[test]
fn channels_store_the_engines_arrangement() {
    use brdfbake::preset::{parse, StoredChannel};
    let one = |extra: &str| {
        parse(&preset(&[dfg("t", extra, 8, 8)]), "t", "t")
            .unwrap()
            .tables
            .remove(0)
    };
    let plain = one("");
    let identity = one(r#", "channels": ["A", "B"]"#);
    assert!(
        identity.channels.is_none(),
        "the kind's own channels are no change"
    );
    let h = brdfbake::meta::input_hash;
    assert_eq!(h(&plain), h(&identity));
    assert!(brdfbake::meta::inputs(&plain).get("channels").is_none());
    let gltf = one(r#", "channels": ["A", "B", "0"]"#);
    assert_eq!(
        gltf.channels,
        Some(vec![
            StoredChannel::Computed(0),
            StoredChannel::Computed(1),
            StoredChannel::Zero
        ])
    );
    assert_ne!(h(&plain), h(&gltf));
    assert_eq!(
        brdfbake::meta::inputs(&gltf)["channels"],
        serde_json::json!(["A", "B", "0"])
    );
    let reordered = one(r#", "channels": ["B", "A"]"#);
    assert_ne!(h(&reordered), h(&plain));

    // baked: the stored texels are the transform of the computed ones, exactly in f32
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = preset(&[
        dfg("plain", r#", "formats": ["exr", "ktx2"]"#, 12, 10),
        dfg(
            "mixed",
            r#", "formats": ["exr", "ktx2"], "channels": ["1-A", "B", "0", "1"]"#,
            12,
            10,
        ),
        dfg(
            "charlie",
            r#", "storage": "unorm16", "formats": ["png-data", "ktx2"], "channels": ["0", "0", "A"], "axis_order": ["roughness", "cos_theta_v"]"#,
            12,
            10,
        ),
        format!(
            r#"{{"name": "bsdl", "kind": "albedo", {MODEL}, "channels": ["1-E"], "storage": "unorm16",
                "axes": {{"cos_theta_v": {{"size": 9}}, "roughness": {{"size": 7, "quantity": "alpha", "range": [0.05, 1], "convention": "endpoints"}}}}}}"#
        ),
    ]);
    fs::write(d.join("c.json"), &text).unwrap();
    let o = cli::run(d, &["bake", "c.json", "--out", "out", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let read = |f: &str| brdfbake::readback::read(&d.join("out/c").join(f)).unwrap();
    let plain = read("plain.exr").lut.unwrap();
    let mixed = read("mixed.exr").lut.unwrap();
    let names: Vec<&str> = mixed.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["R", "G", "B", "A"], "the texture components");
    for (p, m) in plain.data.chunks(2).zip(mixed.data.chunks(4)) {
        assert_eq!(m[0], (1.0 - p[0] as f64) as f32);
        assert_eq!(m[1], p[1]);
        assert_eq!((m[2], m[3]), (0.0, 1.0));
    }
    let side = json(&d.join("out/c/mixed.json"));
    let ch = side["channels"].as_array().unwrap();
    assert_eq!(ch[0]["stores"], "1-A");
    assert_eq!(ch[0]["source"], "A");
    assert_eq!(ch[0]["transform"], "one minus");
    assert_eq!(ch[2]["stores"], "0");
    assert!(ch[2]["source"].is_null());
    assert_eq!(ch[3]["transform"], "constant 1");
    assert!(ch[0]["meaning"].as_str().unwrap().starts_with("1 - A"));
    // the charlie arrangement with the roughness along u: B holds A at [roughness, mu]
    let charlie = read("charlie.png").lut.unwrap();
    assert_eq!(charlie.axes[0].name, "roughness");
    for y in 0..12 {
        for x in 0..10 {
            let want = plain.texel([y, x, 0], 0) as f64;
            let got = charlie.texel([x, y, 0], 2) as f64;
            assert!((got - want).abs() <= 0.5 / 65535.0 + 1e-7, "[{x}, {y}]");
            assert_eq!(charlie.texel([x, y, 0], 0), 0.0);
        }
    }
    // verify and probe compare the stored channels with the transformed exact values
    for f in [
        "mixed.exr",
        "mixed.ktx2",
        "charlie.png",
        "charlie.ktx2",
        "bsdl.ktx2",
    ] {
        let o = cli::run(d, &["verify", &format!("out/c/{f}"), "--all", "--json"]);
        assert!(o.status.success(), "{f}: {}", cli::stderr(&o));
    }
    let o = cli::run(d, &["verify", "c.json"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let o = cli::run(
        d,
        &[
            "probe",
            "out/c/mixed.exr",
            "--at",
            "cos_theta_v=0.3,roughness=0.6",
            "--json",
        ],
    );
    let p: Value = serde_json::from_slice(&o.stdout).unwrap();
    let o = cli::run(
        d,
        &[
            "probe",
            "out/c/plain.exr",
            "--at",
            "cos_theta_v=0.3,roughness=0.6",
            "--json",
        ],
    );
    let q: Value = serde_json::from_slice(&o.stdout).unwrap();
    let exact = |v: &Value, c: usize| v["channels"][c]["exact"].as_f64().unwrap();
    assert_eq!(exact(&p, 0), 1.0 - exact(&q, 0));
    assert_eq!(exact(&p, 1), exact(&q, 1));
    assert_eq!((exact(&p, 2), exact(&p, 3)), (0.0, 1.0));
    // the sidecar rebuilds the table: bake --check and the input hash
    let o = cli::run(d, &["bake", "c.json", "--out", "out", "--check"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    // the EXR's channels are R, G, B, A: what importers map
    let exr = read("mixed.exr");
    assert!(exr
        .file_facts
        .iter()
        .any(|(k, v)| k == "channels" && v == "R = 1-A, G = B, B = 0, A = 1"));
}

/// Bad input: a named error, exit 2, nothing written.
#[test]
fn bad_storage_formats_and_channels_are_named_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ndf = |extra: &str| {
        format!(
            r#"{{"name": "d", "kind": "ndf", "model": {{"ndf": "ggx"}}{extra},
                "axes": {{"cos_theta_h": {{"size": 8, "convention": "endpoints"}}, "roughness": {{"size": 4, "range": [0.3, 1], "quantity": "perceptual"}}}}}}"#
        )
    };
    let cases: Vec<(String, Vec<&str>, Vec<&str>)> = vec![
        (
            preset(&[dfg(
                "t",
                r#", "storage": "unorm8", "formats": ["exr"]"#,
                8,
                8,
            )]),
            vec![],
            vec![
                "tables[0].formats[0]",
                "EXR has no normalized-integer",
                "ktx2, png-data",
            ],
        ),
        (
            preset(&[dfg("t", r#", "formats": ["ktx2", "png-data"]"#, 8, 8)]),
            vec![],
            vec!["tables[0].formats[1]", "png-data", "unorm8", "\"f32\""],
        ),
        (
            preset(&[dfg("t", r#", "storage": "unorm16""#, 8, 8)]),
            vec!["--format", "exr,ktx2"],
            vec!["--format", "table `t`", "EXR has no normalized-integer"],
        ),
        (
            preset(&[dfg("t", r#", "storage": "unorm12""#, 8, 8)]),
            vec![],
            vec!["tables[0].storage", "unorm12", "unorm16"],
        ),
        // D reaches 14.1 at n.h = 1: outside [0, 1], never clamped
        (
            preset(&[ndf(r#", "storage": "unorm16""#)]),
            vec![],
            vec![
                "table `d`",
                "channel `D`",
                "texel [7, 0]",
                "14.1177",
                "outside [0, 1]",
                "\"scale\" to 0.0708332 or less",
            ],
        ),
        // 1 - D is negative there
        (
            preset(&[ndf(
                r#", "storage": "unorm8", "channels": ["1-D"], "scale": 0.01"#,
            )]),
            vec![],
            vec![
                "channel `R`",
                "outside [0, 1]",
                "holds [0, 1] only",
                "\"f16\"",
            ],
        ),
        // the cloth channel of Filament's table exceeds 1 at grazing angles
        (
            preset(&[format!(
                r#"{{"name": "dfg", "kind": "dfg", "layout": "filament", "cloth": true, "storage": "unorm16", {MODEL},
                    "axes": {{"cos_theta_v": {{"size": 16}}, "roughness": {{"size": 16, "quantity": "perceptual"}}}}}}"#
            )]),
            vec![],
            vec!["channel `B`", "outside [0, 1]", "scale"],
        ),
        (
            preset(&[dfg("t", r#", "channels": ["A", "X"]"#, 8, 8)]),
            vec![],
            vec![
                "tables[0].channels[1]",
                "\"X\"",
                "(A, B)",
                "\"1-A\"",
                "\"0\"",
            ],
        ),
        (
            preset(&[dfg("t", r#", "channels": ["1 - A"]"#, 8, 8)]),
            vec![],
            vec!["tables[0].channels[0]", "\"1 - A\""],
        ),
        (
            preset(&[dfg("t", r#", "channels": []"#, 8, 8)]),
            vec![],
            vec!["tables[0].channels", "1 to 4"],
        ),
        (
            preset(&[dfg("t", r#", "channels": ["A", "B", "A", "B", "0"]"#, 8, 8)]),
            vec![],
            vec!["tables[0].channels", "lists 5 entries"],
        ),
        (
            preset(&[dfg("t", r#", "channels": ["0", "1"]"#, 8, 8)]),
            vec![],
            vec!["tables[0].channels", "only constants"],
        ),
        (
            preset(&[dfg("t", r#", "channels": "A""#, 8, 8)]),
            vec![],
            vec!["tables[0].channels"],
        ),
    ];
    for (i, (text, args, expect)) in cases.iter().enumerate() {
        let p = d.join(format!("bad{i}.json"));
        fs::write(&p, text).unwrap();
        let mut a = vec![
            "bake".to_string(),
            p.display().to_string(),
            "--out".into(),
            "out".into(),
        ];
        a.extend(args.iter().map(|s| s.to_string()));
        let o = cli::run(d, &a);
        cli::assert_fails(&o, cli::INPUT, expect, &format!("case {i}"));
        assert!(!d.join("out").exists(), "case {i} wrote something");
    }
}

/// The same bytes for any thread count, in every format a UNORM table takes.
#[test]
fn unorm_outputs_are_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = preset(&[
        dfg(
            "u16",
            r#", "storage": "unorm16", "channels": ["A", "B", "0"], "formats": ["ktx2", "png-data", "png", "h", "rs", "glsl", "hlsl", "wgsl"]"#,
            33,
            17,
        ),
        format!(
            r#"{{"name": "g2", "kind": "g2", "storage": "unorm8", {MODEL}, "formats": ["ktx2", "png-data", "h"],
                "axes": {{"cos_theta_v": {{"size": 5}}, "cos_theta_l": {{"size": 6}}, "roughness": {{"size": 7, "quantity": "alpha", "range": [0.1, 1]}}}}}}"#
        ),
    ]);
    fs::write(d.join("u.json"), &text).unwrap();
    for (out, threads) in [("a", "1"), ("b", "2"), ("c", "2")] {
        let o = cli::run(
            d,
            &["bake", "u.json", "--out", out, "-q", "--threads", threads],
        );
        assert!(o.status.success(), "{}", cli::stderr(&o));
    }
    let a = cli::snapshot(&d.join("a"));
    assert_eq!(a.len(), 16, "{:?}", a.keys());
    assert_eq!(a, cli::snapshot(&d.join("b")));
    assert_eq!(a, cli::snapshot(&d.join("c")));
}

/// CRC-32 (ISO-HDLC) of a PNG chunk's type and data.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 == 1 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A PNG of just a header (IHDR: `w` × `h`, 16-bit RGBA) and IEND.
fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let chunk = |out: &mut Vec<u8>, kind: &[u8], data: &[u8]| {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let mut typed = kind.to_vec();
        typed.extend_from_slice(data);
        out.extend_from_slice(&typed);
        out.extend_from_slice(&crc32(&typed).to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[16, 6, 0, 0, 0]); // 16-bit RGBA, deflate, adaptive, no interlace
    chunk(&mut out, b"IHDR", &ihdr);
    chunk(&mut out, b"IEND", &[]);
    out
}

/// Hostile PNGs: a header claiming 2^31 − 1 squared pixels is refused before anything is
/// allocated for it (no abort: exit 2, at once), a PNG that is not brdfbake's is named as such.
#[test]
fn hostile_pngs_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // the CRC is right: the png crate accepts this header
    let huge = png_header_only(0x7fff_ffff, 0x7fff_ffff);
    fs::write(d.join("huge.png"), &huge).unwrap();
    let o = cli::run_within(
        d,
        &["inspect", "huge.png"],
        std::time::Duration::from_secs(60),
    );
    cli::assert_fails(
        &o,
        cli::INPUT,
        // (the decoder's limit, the largest table's decoded size, or readback's own check)
        &["huge.png", "not a png-data file brdfbake wrote"],
        "huge",
    );
    let small = png_header_only(4, 4);
    fs::write(d.join("small.png"), &small).unwrap();
    for cmd in ["inspect", "verify"] {
        let o = cli::run_within(d, &[cmd, "small.png"], std::time::Duration::from_secs(60));
        cli::assert_fails(
            &o,
            cli::INPUT,
            &["small.png", "not a png-data file brdfbake wrote"],
            cmd,
        );
    }
}
