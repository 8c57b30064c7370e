//! DDS files written by brdfbake, read back by an independent DDS parser: the `ddsfile` crate
//! (crates.io, MIT/Apache-2.0; not used by brdfbake itself). For every storage (f16, f32,
//! unorm8, unorm16), channel count (1 to 4) and shape (1D, 2D, 3D as a volume and as an
//! array), `ddsfile` reports the DXGI format, width, height, depth, array size and mip count a
//! loader needs, and the texel bytes it locates (its own offsets and sizes) hold exactly the
//! table's values: f32 bit for bit, f16 as `half::f16::from_f32`, UNORM as the code computed
//! here (round to nearest, ties to even), a 3-channel table's padding 1.0 or the largest code.
//! Then a bake through the CLI (`--format dds`): `inspect` and `verify` read it back, and
//! the texels equal the EXR of the same bake.

use brdfbake::encode::dds::DdsEncoder;
use brdfbake::encode::Encoder;
use brdfbake::lut::Lut;
use brdfbake::table::Storage;
use ddsfile::{D3D10ResourceDimension, Dds};
use half::f16;

#[path = "common/luts.rs"]
mod luts;
use luts::{unorm_code, values_for};

#[path = "common/cli.rs"]
mod cli;

fn lut(sizes: &[usize], channels: usize, storage: Storage) -> Lut {
    luts::lut(
        sizes,
        &["E", "A", "B", "cloth"][..channels],
        values_for(storage),
    )
}

/// The DXGI format name `ddsfile` gives the format a table of `components` components in
/// `storage` must have (Microsoft's DXGI_FORMAT names, as the crate spells them).
fn expected_format(components: usize, storage: Storage) -> &'static str {
    match (components, storage) {
        (1, Storage::F16) => "R16_Float",
        (2, Storage::F16) => "R16G16_Float",
        (4, Storage::F16) => "R16G16B16A16_Float",
        (1, Storage::F32) => "R32_Float",
        (2, Storage::F32) => "R32G32_Float",
        (4, Storage::F32) => "R32G32B32A32_Float",
        (1, Storage::Unorm8) => "R8_UNorm",
        (2, Storage::Unorm8) => "R8G8_UNorm",
        (4, Storage::Unorm8) => "R8G8B8A8_UNorm",
        (1, Storage::Unorm16) => "R16_UNorm",
        (2, Storage::Unorm16) => "R16G16_UNorm",
        (4, Storage::Unorm16) => "R16G16B16A16_UNorm",
        _ => unreachable!(),
    }
}

/// The bytes texel component `v` must have in `storage`.
fn component_bytes(v: f32, storage: Storage) -> Vec<u8> {
    match storage {
        Storage::F32 => v.to_le_bytes().to_vec(),
        Storage::F16 => f16::from_f32(v).to_le_bytes().to_vec(),
        Storage::Unorm8 => vec![unorm_code(v, 255) as u8],
        Storage::Unorm16 => unorm_code(v, 65535).to_le_bytes().to_vec(),
    }
}

fn check(t: &Lut, storage: Storage, array_3d: bool) {
    let what = format!(
        "{:?}, {} channels, {storage:?}, array {array_3d}",
        t.axes.iter().map(|a| a.size).collect::<Vec<_>>(),
        t.channels.len()
    );
    let enc = DdsEncoder {
        storage,
        table_name: "t".into(),
        array_3d,
    };
    let bytes = enc.encode(t, &[]).unwrap();
    assert_eq!(bytes, enc.encode(t, &[]).unwrap(), "{what}: deterministic");
    let dds = Dds::read(&bytes[..]).unwrap_or_else(|e| panic!("{what}: ddsfile: {e}"));
    let nc = t.channels.len();
    let components = if nc == 3 { 4 } else { nc };
    let (nx, ny, nz) = (t.dim(0), t.dim(1), t.dim(2));
    let volume = t.axes.len() == 3 && !array_3d;
    let format = dds.get_dxgi_format().expect("a DX10 header");
    assert_eq!(
        format!("{format:?}"),
        expected_format(components, storage),
        "{what}"
    );
    let h10 = dds.header10.as_ref().expect("DX10 header");
    assert_eq!(
        h10.resource_dimension,
        if volume {
            D3D10ResourceDimension::Texture3D
        } else {
            D3D10ResourceDimension::Texture2D
        },
        "{what}"
    );
    assert_eq!(
        (dds.get_width(), dds.get_height()),
        (nx as u32, ny as u32),
        "{what}"
    );
    assert_eq!(
        dds.get_depth(),
        if volume { nz as u32 } else { 1 },
        "{what}"
    );
    let layers = if t.axes.len() == 3 && array_3d { nz } else { 1 };
    assert_eq!(dds.get_num_array_layers(), layers as u32, "{what}");
    assert_eq!(dds.get_num_mipmap_levels(), 1, "{what}");
    let cb = storage.bytes();
    assert_eq!(
        dds.get_pitch(),
        Some((nx * components * cb) as u32),
        "{what}"
    );

    // every texel, where ddsfile puts the layers
    // (the padding: 1.0, stored as the largest code for UNORM)
    let padding = 1.0;
    for layer in 0..layers {
        let data = dds.get_data(layer as u32).unwrap();
        let slices = if volume { nz } else { 1 };
        assert_eq!(data.len(), nx * ny * slices * components * cb, "{what}");
        let mut want = Vec::new();
        for s in 0..slices {
            let z = if volume { s } else { layer };
            for y in 0..ny {
                for x in 0..nx {
                    let i = ((z * ny + y) * nx + x) * nc;
                    for c in 0..components {
                        let v = if c < nc { t.data[i + c] } else { padding };
                        want.extend(component_bytes(v, storage));
                    }
                }
            }
        }
        assert!(data == &want[..], "{what}: layer {layer}'s texels differ");
    }
}

#[test]
fn every_storage_channel_count_and_shape_reads_back_in_ddsfile() {
    for storage in Storage::ALL {
        for nc in 1..=4 {
            // odd, non-square sizes: rows of every length modulo 4 bytes
            check(&lut(&[5 + nc, 3], nc, storage), storage, false);
        }
        check(&lut(&[9], 2, storage), storage, false);
        for array_3d in [false, true] {
            for nc in [1, 3] {
                check(&lut(&[4, 3, 5], nc, storage), storage, array_3d);
            }
        }
    }
}

#[test]
fn bad_tables_are_errors() {
    let enc = |storage| DdsEncoder {
        storage,
        table_name: "t".into(),
        array_3d: false,
    };
    let mut t = lut(&[4, 4], 2, Storage::F16);
    t.data[5] = f32::NAN;
    let e = enc(Storage::F16).encode(&t, &[]).unwrap_err().to_string();
    assert!(e.contains("not a finite number"), "{e}");
    let mut t = lut(&[4, 4], 2, Storage::F16);
    t.data[3] = 1e6;
    let e = enc(Storage::F16).encode(&t, &[]).unwrap_err().to_string();
    assert!(e.contains("cannot be stored") && e.contains("DDS"), "{e}");
    let t = lut(&[4, 4], 2, Storage::F32);
    let mut t5 = t.clone();
    t5.channels
        .extend(t.channels.iter().cloned().chain(t.channels.iter().cloned()));
    let e = enc(Storage::F32).encode(&t5, &[]).unwrap_err().to_string();
    assert!(e.contains("1 to 4 channels"), "{e}");
}

/// `bake --format dds,exr`: the DDS holds the EXR's texels (f16 both), the sidecar says how to
/// read it, `inspect` and `verify` read it back, `bake --check` sees it; a damaged header is
/// refused by name.
#[test]
fn baked_dds_matches_the_exr_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = cli::run(
        d,
        &[
            "bake",
            "filament-dfg",
            "--format",
            "dds,exr",
            "--out",
            "out",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let bytes = std::fs::read(d.join("out/filament-dfg/dfg.dds")).unwrap();
    let dds = Dds::read(&bytes[..]).unwrap();
    let side: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("out/filament-dfg/dfg.json")).unwrap())
            .unwrap();
    let st = &side["storage"];
    assert_eq!(
        st["dds"]["dxgi_format"].as_u64(),
        Some(dds.get_dxgi_format().unwrap() as u64)
    );
    assert_eq!(side["files"]["dds"], "dfg.dds");
    // the texels equal the EXR's (the OpenEXR judge reads the EXR in tests/exr_openexr.rs;
    // here brdfbake's EXR reader, which that test validates, gives the reference)
    let exr =
        brdfbake::encode::decode_exr(&std::fs::read(d.join("out/filament-dfg/dfg.exr")).unwrap())
            .unwrap();
    let data = dds.get_data(0).unwrap();
    let nc = side["channels"].as_array().unwrap().len();
    let comps = if nc == 3 { 4 } else { nc };
    let cb = match st["texel_type"].as_str().unwrap() {
        "f16" => 2,
        _ => 4,
    };
    let texels = data.len() / (comps * cb);
    assert_eq!(texels, 128 * 128);
    let names: Vec<&str> = side["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    for (c, name) in names.iter().enumerate() {
        let plane = &exr.2.iter().find(|(n, _)| n == name).unwrap().1;
        assert_eq!(plane.len(), texels);
        for (i, want) in plane.iter().enumerate() {
            let at = (i * comps + c) * cb;
            let v = if cb == 2 {
                f16::from_le_bytes([data[at], data[at + 1]]).to_f32()
            } else {
                f32::from_le_bytes(data[at..at + 4].try_into().unwrap())
            };
            assert_eq!(v.to_bits(), want.to_bits(), "channel {name} texel {i}");
        }
    }
    for cmd in [
        &["inspect", "out/filament-dfg/dfg.dds"][..],
        &["verify", "out/filament-dfg/dfg.dds"],
        &[
            "bake",
            "--check",
            "filament-dfg",
            "--format",
            "dds,exr",
            "--out",
            "out",
        ],
    ] {
        let o = cli::run(d, cmd);
        assert!(o.status.success(), "{cmd:?}: {}", cli::stderr(&o));
    }
    // a header field changed (dwMipMapCount 1 -> 2) with the sidecar's digest recomputed is
    // still refused, naming the field
    std::fs::create_dir(d.join("bad")).unwrap();
    for (offset, value, field) in [(28, 2u8, "dwMipMapCount"), (4 + 124 + 12, 2, "arraySize")] {
        let mut bad = bytes.clone();
        bad[offset] = value;
        std::fs::write(d.join("bad/dfg.dds"), &bad).unwrap();
        std::fs::write(
            d.join("bad/dfg.json"),
            brdfbake::digest::seal(side.clone(), &[("dfg.dds", bad.as_slice())]),
        )
        .unwrap();
        for cmd in ["inspect", "verify"] {
            let o = cli::run(d, &[cmd, "bad/dfg.dds"]);
            let err = cli::stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{cmd} {field}: {err}");
            assert!(err.contains(field), "{cmd} {field}: {err}");
        }
    }
}
