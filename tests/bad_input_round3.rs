//! Reliability, round three: inputs that used to be accepted and now are refused with a
//! message naming what was wrong, exit 2 and nothing written. Every input is made here.

use std::fs;
use std::path::Path;

#[path = "common/cli.rs"]
mod cli;
use cli::{assert_fails, run, INPUT};

/// An 8-bit RGB PNG of `w` × `h` pixels.
fn png(w: u32, h: u32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut wr = enc.write_header().unwrap();
    let data: Vec<u8> = (0..w * h * 3).map(|i| (i * 37 % 251) as u8).collect();
    wr.write_image_data(&data).unwrap();
    wr.finish().unwrap();
    out
}

/// glTF's lut_ggx preset at `n` × `n`.
fn gltf_ggx(n: usize) -> String {
    let text = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/presets/engines/gltf-lut-ggx.json"
    ))
    .unwrap();
    text.replace("\"size\": 1024", &format!("\"size\": {n}"))
}

/// A shipped file of another size than the preset's table is refused, naming both sizes:
/// a PNG of the same pixel count in another shape, a PNG one row and column larger or
/// smaller, a text table with numbers appended or missing.
#[test]
fn compare_refuses_a_file_of_another_size() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("ggx8.json"), gltf_ggx(8)).unwrap();
    for (w, h, expect) in [
        (16, 4, "16 × 4 pixels"),
        (9, 9, "9 × 9 pixels"),
        (7, 7, "7 × 7 pixels"),
    ] {
        fs::write(d.join("lut.png"), png(w, h)).unwrap();
        let o = run(d, &["compare", "ggx8.json", "lut.png"]);
        assert_fails(&o, INPUT, &[expect, "8 × 8 texels"], &format!("{w}x{h}"));
    }
    fs::write(d.join("lut.png"), png(8, 8)).unwrap();
    let o = run(d, &["compare", "ggx8.json", "lut.png"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));

    // BSDL's 16 × 16 text table, with two numbers appended and with one missing
    let bsdl = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/engines/bsdl/MiniMicrofacetGGX.txt"
    ))
    .unwrap();
    let cases = [
        (
            format!("{bsdl}\n0.5 0.25\n"),
            "258 values where the table needs 256",
        ),
        (
            bsdl.trim_end()
                .rsplit_once(char::is_whitespace)
                .unwrap()
                .0
                .to_string(),
            "255 values where the table needs 256",
        ),
    ];
    for (text, expect) in cases {
        fs::write(d.join("bsdl.txt"), text).unwrap();
        let o = run(d, &["compare", "bsdl-ggx-energy", "bsdl.txt"]);
        assert_fails(&o, INPUT, &[expect], expect);
    }
    assert_no_outputs(d);
}

/// compare writes nothing: only the inputs made here are in the folder.
fn assert_no_outputs(d: &Path) {
    for e in fs::read_dir(d).unwrap() {
        let n = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(
            n.ends_with(".json") || n.ends_with(".png") || n.ends_with(".txt"),
            "{n}"
        );
    }
}
