//! The source and preview encoders, checked by their consumers: generated C headers are
//! compiled with the machine's C (and C++) compiler, generated Rust sources with rustc, and
//! the programs print every stored value's bits, which must equal the baked table's (f32),
//! its round-to-nearest-even f16 conversion (half) or its UNORM8/UNORM16 code (computed here
//! independently: round half to even of value × (2ⁿ − 1)). PNG previews are decoded with the
//! `image` and `png` crates. Requires `cc`, `c++` and `rustc` on the PATH (`$RUSTC` if set); without
//! them these tests fail rather than skip.

use brdfbake::encode::png::{PngPreview, NOTE};
use brdfbake::encode::source::{constant_identifier, CHeader, RustSource};
use brdfbake::encode::{EncodeError, Encoder};
use brdfbake::lut::{Axis, Channel, Convention, Lut, Quantity};
use brdfbake::model::{Fresnel, Masking, NdfKind, RoughnessQuantity};
use brdfbake::preset::{Format, Layout3d, PresetTable};
use brdfbake::table::{bake, DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
use half::f16;
use std::io::Cursor;
use std::process::Command;
use std::sync::OnceLock;

fn cosine(name: &str, size: usize, convention: Convention) -> Axis {
    Axis {
        name: name.into(),
        quantity: Quantity::Cosine,
        size,
        range: [0.0, 1.0],
        convention,
        warp: Default::default(),
        clamp: None,
    }
}

fn roughness(size: usize, convention: Convention) -> Axis {
    Axis {
        name: "roughness".into(),
        quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
        size,
        range: [
            if convention == Convention::Endpoints {
                0.05
            } else {
                0.0
            },
            1.0,
        ],
        convention,
        warp: Default::default(),
        clamp: None,
    }
}

fn spec(name: &str, kind: TableKind, axes: Vec<Axis>) -> TableSpec {
    TableSpec {
        name: name.into(),
        kind,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes,
        dfg_layout: None,
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-6,
    }
}

/// The baked test tables, with their specs: a 2-channel Karis DFG 8×8 (roughness at the
/// endpoints), a 1-channel 3D G2 4×4×4, a 3-channel Filament DFG with cloth 8×6.
fn tables() -> &'static [(TableSpec, Lut)] {
    static TABLES: OnceLock<Vec<(TableSpec, Lut)>> = OnceLock::new();
    TABLES.get_or_init(|| {
        let mut karis = spec(
            "dfg-karis",
            TableKind::Dfg,
            vec![
                cosine("cos_theta_v", 8, Convention::Centers),
                roughness(8, Convention::Endpoints),
            ],
        );
        karis.dfg_layout = Some(DfgLayout::Karis);
        let g2 = spec(
            "g2",
            TableKind::G2,
            vec![
                cosine("cos_theta_v", 4, Convention::Centers),
                cosine("cos_theta_l", 4, Convention::Centers),
                roughness(4, Convention::Centers),
            ],
        );
        let mut cloth = spec(
            "3d-cloth",
            TableKind::Dfg,
            vec![
                cosine("cos_theta_v", 8, Convention::Centers),
                roughness(6, Convention::Centers),
            ],
        );
        cloth.dfg_layout = Some(DfgLayout::Filament);
        cloth.cloth = true;
        [karis, g2, cloth]
            .into_iter()
            .map(|s| {
                let lut = bake(&s).unwrap();
                (s, lut)
            })
            .collect()
    })
}

fn attributes(spec: &TableSpec, lut: &Lut) -> Vec<(String, String)> {
    let table = PresetTable {
        spec: spec.clone(),
        formats: vec![Format::H, Format::Rs, Format::Png],
        scale: 1.0,
        layout_3d: Layout3d::Volume,
        accept_error_estimate: None,
        engine: None,
        axis_order: None,
        shipped: None,
        channels: None,
        fit: None,
    };
    let mut a = brdfbake::meta::header_attributes("unit-test", &table, lut);
    a.push((
        "hostile".into(),
        "ends a comment */ opens one /* and goes on\r\non a new line \\".into(),
    ));
    a.push(("formula".into(), "E(μ) = ∫ f cos θ dω".into()));
    a
}

/// A table of values that are hard to print exactly (for UNORM: hard to round: ties, the ends
/// and values within half a step outside [0, 1]).
fn tricky_lut(storage: Storage) -> Lut {
    let half = storage == Storage::F16;
    let mut values: Vec<f32> = vec![
        1.0,
        -0.0,
        0.0,
        0.1,
        1.0 / 3.0,
        1e-8,
        65504.0,
        -2.5,
        6e-8,
        f32::from_bits(0x3f80_0001),
        -65519.0,
    ];
    if let Some(max) = storage.unorm_max() {
        let m = max as f32;
        values = vec![
            0.0,
            1.0,
            0.5,
            1.0 / 3.0,
            2.0 / 3.0,
            0.1,
            1e-8,
            0.999_999,
            // near ties: k + 1/2 steps, rounded to f32 (0.5 above is an exact tie)
            2.5 / m,
            3.5 / m,
            // within half a step outside [0, 1]: the end codes
            -0.4 / m,
            1.0 + 0.4 / m,
        ];
    } else if !half {
        values.extend([
            f32::from_bits(1),
            f32::MIN_POSITIVE,
            f32::MAX,
            f32::MIN,
            1e-40,
            1e30,
            16777216.0,
            123456.79,
        ]);
    }
    while !values.len().is_multiple_of(3) {
        values.push(0.5);
    }
    Lut {
        axes: vec![cosine("cos_theta", values.len() / 3, Convention::Centers)],
        channels: ["R", "G\"?", "B"]
            .iter()
            .map(|n| Channel {
                name: n.to_string(),
                meaning: format!("test {n}"),
            })
            .collect(),
        data: values,
        error_estimate: vec![0.0; 3],
        evaluations: 0,
    }
}

/// The UNORM code of `v` computed here, independently of the encoders: the nearest integer
/// to v·max, a tie going to the even one.
fn unorm_code(v: f32, max: u32) -> u32 {
    let x = v as f64 * max as f64;
    let f = x.floor();
    let c = match (x - f).partial_cmp(&0.5).unwrap() {
        std::cmp::Ordering::Less => f,
        std::cmp::Ordering::Greater => f + 1.0,
        std::cmp::Ordering::Equal if f % 2.0 == 0.0 => f,
        std::cmp::Ordering::Equal => f + 1.0,
    };
    assert!((0.0..=max as f64).contains(&c), "{v} is not storable");
    c as u32
}

/// The bits a program must print for each stored value.
fn expected_bits(lut: &Lut, storage: Storage) -> Vec<String> {
    lut.data
        .iter()
        .map(|&v| match storage {
            Storage::F16 => format!("{:04x}", f16::from_f32(v).to_bits()),
            Storage::F32 => format!("{:08x}", v.to_bits()),
            Storage::Unorm8 => format!("{:02x}", unorm_code(v, 255)),
            Storage::Unorm16 => format!("{:04x}", unorm_code(v, 65535)),
        })
        .collect()
}

/// Whether every value of `lut` fits `storage` (UNORM holds [0, 1]).
fn fits(lut: &Lut, storage: Storage) -> bool {
    !storage.is_unorm() || lut.data.iter().all(|v| (0.0..=1.0).contains(v))
}

/// The first lines every test program prints: the size constants and the channel names.
fn expected_header(lut: &Lut) -> Vec<String> {
    vec![
        format!(
            "{} {} {} {}",
            lut.dim(0),
            lut.dim(1),
            lut.dim(2),
            lut.channels.len()
        ),
        lut.channels
            .iter()
            .map(|c| c.name.as_str())
            .collect::<Vec<_>>()
            .join(","),
    ]
}

fn run(cmd: &mut Command, what: &str) -> String {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot run {cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{what} failed ({cmd:?}):\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Compiles the header of `lut` into a C and a C++ program that print the sizes, the channel
/// names and every value's bits, runs them and compares with the table.
fn check_c(name: &str, lut: &Lut, storage: Storage, attrs: &[(String, String)]) {
    let dir = tempfile::tempdir().unwrap();
    let encoder = CHeader {
        table_name: name.into(),
        storage,
    };
    assert_eq!(encoder.extension(), "h");
    let header = encoder.encode(lut, attrs).unwrap();
    assert_eq!(encoder.encode(lut, attrs).unwrap(), header, "deterministic");
    std::fs::write(dir.path().join("table.h"), &header).unwrap();
    let id = constant_identifier(name);
    let (ty, fmt) = match storage {
        Storage::F16 | Storage::Unorm16 => ("uint16_t", "%04x"),
        Storage::Unorm8 => ("uint8_t", "%02x"),
        Storage::F32 => ("uint32_t", "%08x"),
    };
    let program = format!(
        r#"#include <stdio.h>
#include <string.h>
#include <stdint.h>
#include "table.h"
#include "table.h" /* the include guard makes a second inclusion harmless */
int main(void) {{
    size_t i;
    printf("%d %d %d %d\n", (int){id}_WIDTH, (int){id}_HEIGHT, (int){id}_DEPTH, (int){id}_CHANNELS);
    for (i = 0; i < {id}_CHANNELS; i++) printf("%s%s", i ? "," : "", {id}_CHANNEL_NAMES[i]);
    printf("\n");
    if (sizeof({id}) / sizeof({id}[0]) != (size_t){id}_WIDTH * {id}_HEIGHT * {id}_DEPTH * {id}_CHANNELS) return 3;
    for (i = 0; i < sizeof({id}) / sizeof({id}[0]); i++) {{
        {ty} bits;
        memcpy(&bits, &{id}[i], sizeof bits);
        printf("{fmt}\n", (unsigned)bits);
    }}
    return 0;
}}
"#
    );
    let src = dir.path().join("main.c");
    std::fs::write(&src, program).unwrap();
    let mut expected = expected_header(lut);
    expected.extend(expected_bits(lut, storage));
    for (compiler, flags) in [
        ("cc", &["-std=c99", "-pedantic"][..]),
        ("c++", &["-x", "c++", "-std=c++11"][..]),
    ] {
        let exe = dir.path().join(format!("main-{compiler}"));
        run(
            Command::new(compiler)
                .args(flags)
                .args(["-Wall", "-Wextra", "-Werror", "-o"])
                .arg(&exe)
                .arg(&src)
                .current_dir(dir.path()),
            &format!("compiling the header of {name} with {compiler}"),
        );
        let out = run(&mut Command::new(&exe), "running the C program");
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines, expected, "{name} ({storage:?}) via {compiler}");
    }
}

/// Compiles the Rust source of `lut` as a module of a program that prints the sizes, the
/// channel names and every value's bits, runs it and compares with the table; with `include`,
/// the file is pulled in with `include!` instead.
fn check_rust(name: &str, lut: &Lut, storage: Storage, attrs: &[(String, String)], include: bool) {
    let dir = tempfile::tempdir().unwrap();
    let encoder = RustSource {
        table_name: name.into(),
        storage,
    };
    assert_eq!(encoder.extension(), "rs");
    let source = encoder.encode(lut, attrs).unwrap();
    assert_eq!(encoder.encode(lut, attrs).unwrap(), source, "deterministic");
    std::fs::write(dir.path().join("table.rs"), &source).unwrap();
    let id = constant_identifier(name);
    let print = match storage {
        Storage::F16 | Storage::Unorm16 => "println!(\"{v:04x}\")",
        Storage::Unorm8 => "println!(\"{v:02x}\")",
        Storage::F32 => "println!(\"{:08x}\", v.to_bits())",
    };
    let module = if include {
        "mod table {\n    include!(\"table.rs\");\n}"
    } else {
        "mod table;"
    };
    let program = format!(
        r#"{module}
fn main() {{
    println!("{{}} {{}} {{}} {{}}", table::{id}_WIDTH, table::{id}_HEIGHT, table::{id}_DEPTH, table::{id}_CHANNELS);
    println!("{{}}", table::{id}_CHANNEL_NAMES.join(","));
    for v in table::{id}.iter() {{
        {print};
    }}
}}
"#
    );
    let src = dir.path().join("main.rs");
    std::fs::write(&src, program).unwrap();
    let exe = dir.path().join("main");
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    run(
        Command::new(rustc)
            .args([
                "--edition",
                "2021",
                "-D",
                "warnings",
                "-C",
                "opt-level=0",
                "-o",
            ])
            .arg(&exe)
            .arg(&src),
        &format!("compiling the Rust source of {name}"),
    );
    let out = run(&mut Command::new(&exe), "running the Rust program");
    let lines: Vec<&str> = out.lines().collect();
    let mut expected = expected_header(lut);
    expected.extend(expected_bits(lut, storage));
    assert_eq!(lines, expected, "{name} ({storage:?})");
}

#[test]
fn c_headers_compile_and_hold_the_exact_values() {
    let mut unorm = 0;
    for (spec, lut) in tables() {
        let attrs = attributes(spec, lut);
        for storage in Storage::ALL {
            if fits(lut, storage) {
                unorm += usize::from(storage.is_unorm());
                check_c(&spec.name, lut, storage, &attrs);
            }
        }
    }
    assert!(unorm >= 2, "a baked table in each UNORM storage");
    for storage in Storage::ALL {
        check_c("tricky", &tricky_lut(storage), storage, &[]);
    }
}

#[test]
fn rust_sources_compile_and_hold_the_exact_values() {
    for (spec, lut) in tables() {
        let attrs = attributes(spec, lut);
        for storage in Storage::ALL {
            if fits(lut, storage) {
                check_rust(&spec.name, lut, storage, &attrs, false);
            }
        }
    }
    for storage in Storage::ALL {
        check_rust(
            "tricky",
            &tricky_lut(storage),
            storage,
            &[],
            storage == Storage::F16,
        );
    }
}

/// A value more than half a step outside [0, 1] is an error naming the channel, the texel and
/// the value, in every UNORM encoder; nothing is clamped.
#[test]
fn unorm_sources_reject_values_outside_the_unit_interval() {
    for storage in [Storage::Unorm8, Storage::Unorm16] {
        let max = storage.unorm_max().unwrap() as f32;
        for (bad, at) in [(1.0 + 0.6 / max, 4), (-0.6 / max, 7)] {
            let mut lut = tricky_lut(storage);
            lut.data[at] = bad;
            for encoder in [
                &CHeader {
                    table_name: "t".into(),
                    storage,
                } as &dyn Encoder,
                &RustSource {
                    table_name: "t".into(),
                    storage,
                },
            ] {
                match encoder.encode(&lut, &[]) {
                    Err(EncodeError::OutOfUnitRange {
                        channel,
                        texel,
                        value,
                        ..
                    }) => {
                        assert_eq!(channel, lut.channels[at % 3].name);
                        assert_eq!(texel, vec![at / 3]);
                        assert_eq!(value, bad as f64);
                    }
                    other => panic!("{storage:?} {bad}: {other:?}"),
                }
            }
        }
    }
}

#[test]
fn sources_document_the_table() {
    let (spec, lut) = &tables()[0];
    let attrs = attributes(spec, lut);
    for (text, c) in [
        (
            CHeader {
                table_name: spec.name.clone(),
                storage: Storage::F32,
            }
            .encode(lut, &attrs)
            .unwrap(),
            true,
        ),
        (
            RustSource {
                table_name: spec.name.clone(),
                storage: Storage::F16,
            }
            .encode(lut, &attrs)
            .unwrap(),
            false,
        ),
    ] {
        let text = String::from_utf8(text).unwrap();
        for (k, v) in &attrs {
            let mut first = v.lines().next().unwrap_or("").trim_end().to_string();
            if c {
                // a C block comment cannot hold `*/` (nor, warning-free, `/*`)
                first = first.replace("*/", "* /").replace("/*", "/ *");
            }
            assert!(text.contains(&format!("{k}: {first}")), "{k}\n{text}");
        }
        for needle in [
            "cos_theta_v = cosine, range [0, 1], 8 texels, convention centers",
            "roughness = roughness:perceptual (alpha = coordinate^2), range [0.05, 1], 8 texels, convention endpoints",
            "texel i holds roughness = 0.05 + (1 - 0.05) * i / (8 - 1)",
            "sample at (0.5 + t * (8 - 1)) / 8",
            "0 A: A = int (1 - Fc) f cos",
            "DFG_KARIS_WIDTH",
            "DFG_KARIS_CHANNEL_NAMES",
            "no y-flip",
        ] {
            assert!(text.contains(needle), "{needle}\n{text}");
        }
    }
}

#[test]
fn half_sources_reject_values_beyond_f16() {
    let mut lut = tricky_lut(Storage::F32);
    let big = lut.data.iter().position(|&v| v == f32::MAX).unwrap();
    assert!(CHeader {
        table_name: "t".into(),
        storage: Storage::F32
    }
    .encode(&lut, &[])
    .is_ok());
    for encoder in [
        &CHeader {
            table_name: "t".into(),
            storage: Storage::F16,
        } as &dyn Encoder,
        &RustSource {
            table_name: "t".into(),
            storage: Storage::F16,
        },
    ] {
        match encoder.encode(&lut, &[]) {
            Err(EncodeError::Unrepresentable { channel, value, .. }) => {
                assert_eq!(channel, lut.channels[big % 3].name);
                assert_eq!(value.abs(), f32::MAX as f64);
            }
            other => panic!("{other:?}"),
        }
    }
    lut.data[0] = f32::INFINITY;
    assert!(matches!(
        RustSource {
            table_name: "t".into(),
            storage: Storage::F32
        }
        .encode(&lut, &[]),
        Err(EncodeError::NonFinite { .. })
    ));
}

/// A decoded PNG: dimensions, 16-bit samples (row-major, top row first) and text chunks.
struct Decoded {
    width: usize,
    height: usize,
    samples: Vec<u16>,
    channels: usize,
    text: Vec<(String, String)>,
}

fn decode(bytes: &[u8]) -> Decoded {
    let image = image::load_from_memory_with_format(bytes, image::ImageFormat::Png).unwrap();
    let (width, height) = (image.width() as usize, image.height() as usize);
    let (samples, channels) = match image {
        image::DynamicImage::ImageLuma16(b) => (b.into_raw(), 1),
        image::DynamicImage::ImageRgb16(b) => (b.into_raw(), 3),
        other => panic!("not a 16-bit grey or RGB image: {:?}", other.color()),
    };
    let reader = png::Decoder::new(Cursor::new(bytes)).read_info().unwrap();
    let info = reader.info();
    assert_eq!(info.bit_depth, png::BitDepth::Sixteen);
    let mut text: Vec<(String, String)> = info
        .uncompressed_latin1_text
        .iter()
        .map(|t| (t.keyword.clone(), t.text.clone()))
        .collect();
    for t in &info.utf8_text {
        text.push((t.keyword.clone(), t.get_text().unwrap()));
    }
    Decoded {
        width,
        height,
        samples,
        channels,
        text,
    }
}

impl Decoded {
    fn text(&self, key: &str) -> &str {
        &self
            .text
            .iter()
            .find(|(k, _)| k == key)
            .unwrap_or_else(|| panic!("no text chunk {key}: {:?}", self.text))
            .1
    }

    fn pixel(&self, x: usize, y: usize) -> &[u16] {
        let i = (y * self.width + x) * self.channels;
        &self.samples[i..i + self.channels]
    }
}

#[test]
fn png_previews_map_min_and_max_to_the_full_16_bit_range() {
    for (spec, lut) in tables() {
        let preview = PngPreview {
            table_name: spec.name.clone(),
        };
        let files = preview.encode_all(lut).unwrap();
        let nc = lut.channels.len();
        let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
        let mut expected: Vec<String> = lut
            .channels
            .iter()
            .map(|c| format!("preview-{}.png", c.name))
            .collect();
        expected.push(format!("preview-{}-colour.png", lut.channels[0].name));
        assert_eq!(names, expected);
        let (nx, ny, nz) = (lut.dim(0), lut.dim(1), lut.dim(2));
        let height = ny * nz;
        for (c, (_, bytes)) in files[..nc].iter().enumerate() {
            let d = decode(bytes);
            assert_eq!((d.width, d.height, d.channels), (nx, height, 1));
            let values: Vec<f32> = lut.data.iter().skip(c).step_by(nc).copied().collect();
            let min = values.iter().copied().fold(f32::INFINITY, f32::min);
            let max = values.iter().copied().fold(f32::NEG_INFINITY, f32::max);
            assert!(max > min);
            assert_eq!(d.text("brdfbake:min").parse::<f32>().unwrap(), min);
            assert_eq!(d.text("brdfbake:max").parse::<f32>().unwrap(), max);
            assert_eq!(d.text("brdfbake:note"), NOTE);
            assert!(d.text("brdfbake:orientation").starts_with("y axis up"));
            assert!(d.text("Description").contains(NOTE));
            // y axis up: table row z·ny + y is image row height − 1 − (z·ny + y)
            for z in 0..nz {
                for y in 0..ny {
                    for x in 0..nx {
                        let v = lut.texel([x, y, z], c) as f64;
                        let want = ((v - min as f64) / (max as f64 - min as f64) * 65535.0).round();
                        let got = d.pixel(x, height - 1 - (z * ny + y))[0];
                        assert_eq!(got as f64, want, "texel {x} {y} {z}");
                    }
                }
            }
            assert!(d.samples.contains(&0) && d.samples.contains(&65535));
        }
        // the false-colour image: min and max texels have the bar's bottom and top colours
        let d = decode(&files[nc].1);
        assert_eq!(d.channels, 3);
        assert!(d.width > nx && d.height >= height);
        assert!(d.text("brdfbake:legend").contains("tick marks"));
        assert_eq!(d.text("brdfbake:note"), NOTE);
        let (kx, ky) = (
            256usize.div_ceil(nx).clamp(1, 32),
            256usize.div_ceil(height).clamp(1, 32),
        );
        assert_eq!(d.height, height * ky);
        let bar_x = nx * kx + 8;
        let values: Vec<f32> = lut.data.iter().step_by(nc).copied().collect();
        let at = |i: usize| (i % nx, height - 1 - i / nx);
        let min_i = (0..values.len())
            .min_by(|&a, &b| values[a].total_cmp(&values[b]))
            .unwrap();
        let max_i = (0..values.len())
            .max_by(|&a, &b| values[a].total_cmp(&values[b]))
            .unwrap();
        let (x, y) = at(min_i);
        assert_eq!(
            d.pixel(x * kx + kx / 2, y * ky + ky / 2),
            d.pixel(bar_x + 1, d.height - 1)
        );
        let (x, y) = at(max_i);
        assert_eq!(d.pixel(x * kx, y * ky), d.pixel(bar_x + 1, 0));
        // the tick marks right of the bar are white at the ends and the middle
        let row = |f: f64| d.height - 1 - ((d.height - 1) as f64 * f).round() as usize;
        for f in [0.0, 0.5, 1.0] {
            assert_eq!(d.pixel(bar_x + 16 + 2, row(f)), [65535; 3]);
        }
        assert_ne!(d.pixel(bar_x + 16 + 2, row(0.125)), [65535; 3]);
    }
}

#[test]
fn png_previews_are_deterministic_and_carry_the_attributes() {
    let (spec, lut) = &tables()[1];
    let attrs = attributes(spec, lut);
    let preview = PngPreview {
        table_name: spec.name.clone(),
    };
    let first = preview.encode_all_with_attributes(lut, &attrs).unwrap();
    for _ in 0..3 {
        assert_eq!(
            preview.encode_all_with_attributes(lut, &attrs).unwrap(),
            first
        );
    }
    let from_thread = std::thread::scope(|s| {
        s.spawn(|| preview.encode_all_with_attributes(lut, &attrs).unwrap())
            .join()
            .unwrap()
    });
    assert_eq!(from_thread, first);
    // the single-file encoder is the false-colour image
    assert_eq!(preview.extension(), "png");
    assert_eq!(
        preview.encode(lut, &attrs).unwrap(),
        first.last().unwrap().1
    );
    let d = decode(&first[0].1);
    assert_eq!(d.text("brdfbake:formula"), "E(μ) = ∫ f cos θ dω");
    assert_eq!(d.text("brdfbake:table"), "g2");
    assert!(d.text("brdfbake:axis2").contains("roughness"));
    assert!(d.text("brdfbake:image-z").contains("roughness"));
    assert!(d.text("brdfbake:hostile").contains("*/"));
}

#[test]
fn png_preview_of_a_constant_1d_table() {
    let mut lut = tricky_lut(Storage::F32);
    lut.data.iter_mut().for_each(|v| *v = 0.25);
    let files = PngPreview {
        table_name: "flat".into(),
    }
    .encode_all(&lut)
    .unwrap();
    assert_eq!(files.len(), 4);
    assert_eq!(files[1].0, "preview-G__.png");
    let d = decode(&files[0].1);
    assert_eq!((d.width, d.height), (lut.dim(0), 1));
    assert!(d.samples.iter().all(|&s| s == 0));
    assert_eq!(d.text("brdfbake:min"), "0.25");
}
