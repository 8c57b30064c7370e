//! Babylon.js' environment BRDF table (`babylon-env-brdf`) and the `png-rgbd` format it is
//! stored in.
//!
//! * The baked RGBD PNG, read by the `png` crate (image-rs; brdfbake writes PNGs through it
//!   but the decoding below is Babylon's formula, written here from its `fromRGBD`), decodes
//!   to the exact table within half a code through the power curve per texel — the bound the
//!   sidecar states as `storage.rgbd.max_rounding`.
//! * Babylon's own shipped PNG (tests/data/engines/babylon, Apache-2.0), read as RGBD,
//!   agrees with the exact R and G within a few codes: the layout (n·v along u at centres,
//!   perceptual roughness along v at centres, row 0 at roughness 0) and the decoding are
//!   Babylon's. Negative controls: the same file read as linear 8-bit, or upside down,
//!   does not fit. Its B (sheen) is one texel off along roughness, which `compare` says.

#[path = "common/cli.rs"]
mod cli;

use serde_json::Value;
use std::path::Path;

const N: usize = 256;

/// Babylon's `fromRGBD` with its default `toLinearSpace` (pow 2.2): written here from
/// `helperFunctions.fx`, not taken from brdfbake.
fn from_rgbd(c: u8, a: u8) -> f64 {
    (c as f64 / 255.0).powf(2.2) / (a as f64 / 255.0)
}

/// Half a code of `c` either way through the power curve, over D.
fn half_code(c: u8, a: u8) -> f64 {
    let x = c as f64 / 255.0;
    let h = 0.5 / 255.0;
    let up = (x + h).min(1.0).powf(2.2) - x.powf(2.2);
    let down = x.powf(2.2) - (x - h).max(0.0).powf(2.2);
    up.max(down) / (a as f64 / 255.0)
}

/// The exact table (R, G, B per texel, x = n·v fastest), baked by the library.
fn exact() -> Vec<f64> {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == "babylon-env-brdf")
        .unwrap();
    let p = brdfbake::preset::parse(text, "babylon-env-brdf", "babylon-env-brdf").unwrap();
    let t = &p.tables[0];
    let lut = t.stored(brdfbake::table::bake(&t.spec).unwrap());
    assert_eq!(lut.channels.len(), 3);
    lut.data.iter().map(|&v| v as f64).collect()
}

/// (width, height, RGBA bytes, whether a colour-space chunk is present) of a PNG.
fn read_png(p: &Path) -> (usize, usize, Vec<u8>, bool) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(p).unwrap()));
    let mut r = dec.read_info().unwrap();
    let info = r.info();
    assert_eq!(info.color_type, png::ColorType::Rgba, "{}", p.display());
    assert_eq!(info.bit_depth, png::BitDepth::Eight, "{}", p.display());
    let colour = info.srgb.is_some() || info.gama_chunk.is_some() || info.icc_profile.is_some();
    let (w, h) = (info.width as usize, info.height as usize);
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let f = r.next_frame(&mut buf).unwrap();
    buf.truncate(f.buffer_size());
    (w, h, buf, colour)
}

#[test]
fn the_rgbd_png_decodes_to_the_exact_table() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = cli::run(d, &["bake", "babylon-env-brdf", "--out", "out", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let (w, h, px, colour) = read_png(&d.join("out/babylon-env-brdf/brdf.png"));
    assert_eq!((w, h), (N, N));
    assert!(!colour, "no colour-space chunk: the samples are data");
    let exact = exact();
    let side: Value =
        serde_json::from_slice(&std::fs::read(d.join("out/babylon-env-brdf/brdf.json")).unwrap())
            .unwrap();
    let stated: Vec<f64> = side["storage"]["rgbd"]["max_rounding"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let mut worst = [0.0f64; 3];
    let mut hdr = 0;
    for t in 0..N * N {
        let a = px[4 * t + 3];
        assert!(a > 0, "texel {t}: D = 0");
        if a < 255 {
            hdr += 1;
        }
        for c in 0..3 {
            let v = from_rgbd(px[4 * t + c], a);
            let e = exact[3 * t + c];
            // half a code through the curve, plus the f32 rounding of the exact value (the
            // table is within 1e-6 of it)
            let bound = half_code(px[4 * t + c], a) * (1.0 + 1e-9) + 1e-6 * e.max(1.0);
            let err = (v - e).abs();
            assert!(
                err <= bound,
                "texel ({}, {}) channel {c}: decoded {v}, exact {e}, bound {bound}",
                t % N,
                t / N
            );
            worst[c] = worst[c].max(err);
        }
    }
    // the sheen at grazing views of smooth cloth exceeds 1: some texels need D < 1
    assert!(hdr > 100, "{hdr} texels with D < 255");
    for c in 0..3 {
        assert!(
            worst[c] <= stated[c] + 1e-6,
            "channel {c}: {} over the stated {}",
            worst[c],
            stated[c]
        );
    }
    // brdfbake's readers refuse the RGBD image (its values are the sidecar's, rounded):
    // verify reads the EXR of the same bake
    cli::assert_fails(
        &cli::run(d, &["verify", "out/babylon-env-brdf/brdf.png"]),
        2,
        &["png-rgbd", "storage.rgbd", ".exr"],
        "verify of an RGBD PNG",
    );
    let o = cli::run(d, &["verify", "out/babylon-env-brdf/brdf.exr"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    // a table of other than three channels is refused before any work
    std::fs::write(
        d.join("two.json"),
        r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "t", "kind": "dfg", "layout": "karis",
            "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
            "axes": {"cos_theta_v": {"size": 8}, "roughness": {"size": 8, "quantity": "perceptual"}},
            "formats": ["png-rgbd"]}]}"#,
    )
    .unwrap();
    cli::assert_fails(
        &cli::run(d, &["bake", "two.json", "--out", "x"]),
        2,
        &["png-rgbd stores three channels", "stores 2"],
        "a two-channel RGBD table",
    );
    cli::assert_fails(
        &cli::run(
            d,
            &[
                "bake",
                "babylon-env-brdf",
                "--out",
                "x",
                "--format",
                "png-data,png-rgbd",
            ],
        ),
        2,
        &["both write TABLE.png"],
        "png-data with png-rgbd",
    );
}

#[test]
fn babylons_shipped_table_is_this_layout() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/engines/babylon/environmentBRDF.png");
    let (w, h, px, _) = read_png(&file);
    assert_eq!((w, h), (N, N));
    let exact = exact();
    // (largest error, mean |error| in codes' rounding) of R and G over the texels away from
    // the grazing columns (n·v ≥ 0.05), read as `decode` says and rows as `flip` says
    let fit = |decode: &dyn Fn(u8, u8) -> f64, flip: bool| -> (f64, f64) {
        let (mut worst, mut sum, mut n) = (0.0f64, 0.0, 0.0);
        for y in 0..N {
            let fy = if flip { N - 1 - y } else { y };
            for x in 13..N {
                let p = &px[4 * (fy * N + x)..4 * (fy * N + x) + 4];
                for c in 0..2 {
                    let err = (decode(p[c], p[3]) - exact[3 * (y * N + x) + c]).abs();
                    worst = worst.max(err);
                    sum += err / half_code(p[c], p[3]).max(1e-9);
                    n += 1.0;
                }
            }
        }
        (worst, sum / n)
    };
    let (worst, mean) = fit(&from_rgbd, false);
    // Babylon's R and G within a few codes (its generator is a Monte Carlo estimate: not
    // every texel within half a code) and on average within about one
    assert!(worst < 0.02, "R, G worst {worst}");
    assert!(mean < 1.5, "R, G mean error {mean} half-codes");
    // read as linear 8-bit, or upside down: another table
    let (w_lin, _) = fit(&|c, a| c as f64 / 255.0 * 255.0 / a as f64, false);
    assert!(w_lin > 0.1, "linear decoding fits too well: {w_lin}");
    let (w_flip, _) = fit(&from_rgbd, true);
    assert!(w_flip > 0.1, "a flipped table fits too well: {w_flip}");
    // compare: the sheen's grid is one texel off along roughness
    let dir = tempfile::tempdir().unwrap();
    let o = cli::run(
        dir.path(),
        &[
            "compare",
            "babylon-env-brdf",
            file.to_str().unwrap(),
            "--json",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    let b = doc["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["channel"] == "B")
        .unwrap();
    assert!(
        b["findings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|f| f["kind"] == "shifted" && f["axis"] == "roughness" && f["by"] == 1),
        "{b}"
    );
}
