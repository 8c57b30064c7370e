//! Bevy's DFG table (`bevy-dfg`): the files Bevy loads, and Bevy's own `dfg.ktx2`
//! (tests/data/engines/bevy, MIT OR Apache-2.0) judged against the exact table.
//!
//! * The KTX2 is what `bevy_image` reads: vkFormat R16G16_SFLOAT (wgpu `Rg16Float`), 64 × 64,
//!   one level, Zstandard-supercompressed (the `ktx2` crate parses it here; libktx reads every
//!   ktx2-zstd file brdfbake writes in tests/ktx2_libktx.rs), and its inflated level is byte
//!   for byte the `.bin` file — the raw texels an `include_bytes!` hands to `Image::new` with
//!   `TextureFormat::Rg16Float`, no ktx2 or zstd feature needed — which holds the exact table
//!   rounded to f16 (x = n·v fastest, row 0 at roughness 0).
//! * Bevy's shipped table agrees with this layout (A, B at texel centres of n·v and
//!   perceptual roughness, height-correlated Smith) within its f16 rounding and Monte Carlo
//!   noise from n·v ≥ 0.13; below, its A is biased (up to 6.3e-3). Read with the axes swapped
//!   or one texel off, it does not agree.

#[path = "common/cli.rs"]
mod cli;

use std::path::Path;

const N: usize = 64;

fn table() -> brdfbake::preset::PresetTable {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == "bevy-dfg")
        .unwrap();
    brdfbake::preset::parse(text, "bevy-dfg", "bevy-dfg")
        .unwrap()
        .tables
        .remove(0)
}

/// The exact table (A, B per texel, x = n·v fastest), f32 as baked.
fn exact(t: &brdfbake::preset::PresetTable) -> Vec<f32> {
    t.stored(brdfbake::table::bake(&t.spec).unwrap()).data
}

#[test]
fn the_ktx2_and_the_raw_file_hold_the_exact_table_in_f16() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = cli::run(d, &["bake", "--engine", "bevy", "--out", "out", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let ktx = std::fs::read(d.join("out/bevy-dfg/dfg.ktx2")).unwrap();
    let raw = std::fs::read(d.join("out/bevy-dfg/dfg.bin")).unwrap();
    let r = ktx2::Reader::new(&ktx[..]).unwrap();
    let h = r.header();
    assert_eq!(h.format, Some(ktx2::Format::R16G16_SFLOAT));
    assert_eq!((h.pixel_width, h.pixel_height), (N as u32, N as u32));
    assert_eq!((h.level_count, h.layer_count, h.face_count), (1, 0, 1));
    assert_eq!(
        h.supercompression_scheme,
        Some(ktx2::SupercompressionScheme::Zstandard)
    );
    let level = r.levels().next().unwrap();
    let inflated = ruzstd::decoding::StreamingDecoder::new(level.data)
        .map(|mut s| {
            let mut v = Vec::new();
            std::io::Read::read_to_end(&mut s, &mut v).unwrap();
            v
        })
        .unwrap();
    assert_eq!(inflated, raw, "the KTX2's texels are the .bin's");
    assert_eq!(raw.len(), N * N * 2 * 2, "64 x 64 RG16F");
    let t = table();
    let exact = exact(&t);
    for (k, b) in raw.chunks_exact(2).enumerate() {
        let stored = half::f16::from_le_bytes([b[0], b[1]]);
        assert_eq!(
            stored,
            half::f16::from_f32(exact[k]),
            "texel {} channel {}",
            k / 2,
            k % 2
        );
    }
    // `bake --engine bevy` warns about nothing Bevy cannot load
    assert!(cli::stderr(&o).is_empty(), "{}", cli::stderr(&o));
}

#[test]
fn bevys_shipped_table_is_this_layout() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/engines/bevy/dfg.ktx2");
    let bytes = std::fs::read(&file).unwrap();
    let t = table();
    let shipped = t
        .shipped
        .as_ref()
        .unwrap()
        .read(&bytes, [N, N, 1], "dfg.ktx2")
        .unwrap();
    assert_eq!(shipped.storage, "f16");
    let exact = exact(&t);
    // the largest |shipped − exact| over columns from `first` on, the shipped table's texel
    // (i, j) compared with the exact one at `at(i, j)`
    let worst = |first: usize, at: &dyn Fn(usize, usize) -> (usize, usize)| -> [f64; 2] {
        let mut w = [0.0f64; 2];
        for j in 0..N {
            for i in first..N {
                let (ei, ej) = at(i, j);
                for c in 0..2 {
                    let s = shipped.values[(j * N + i) * 2 + c];
                    let e = exact[(ej * N + ei) * 2 + c] as f64;
                    w[c] = w[c].max((s - e).abs());
                }
            }
        }
        w
    };
    // its A is biased at grazing views, falling with n·v (6.3e-3 in column 0, 2.1e-3 from
    // column 4, 9e-4 from column 8): from n·v ≥ 0.13 (column 8) within 1.5e-3 for A and
    // 5e-4 for B — f16's half-ulp near 1 (2.4e-4) plus five of its Monte Carlo noise's
    // sigma (1.9e-4 for A, 3.5e-5 for B: brdfbake compare's estimate)
    let w = worst(8, &|i, j| (i, j));
    assert!(w[0] < 1.5e-3 && w[1] < 5e-4, "A, B worst {w:?}");
    let grazing = worst(0, &|i, j| (i, j));
    assert!(
        grazing[0] > 3.0 * w[0],
        "A's grazing bias: {grazing:?} vs {w:?}"
    );
    // negative controls: the axes swapped (roughness along u), or the table one texel off
    let swapped = worst(8, &|i, j| (j, i));
    assert!(swapped[0] > 0.1, "swapped axes fit: {swapped:?}");
    let shifted = worst(8, &|i, j| (i, (j + 1).min(N - 1)));
    assert!(
        shifted[0] > 4.0 * w[0] || shifted[1] > 4.0 * w[1],
        "a one-texel shift fits: {shifted:?} vs {w:?}"
    );
}
