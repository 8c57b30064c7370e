//! DDS encoding (DirectDraw Surface with the DX10 header extension): an uncompressed,
//! single-level texture in a DXGI format, as Direct3D, Godot, OGRE and Babylon.js load it.
//!
//! Formats (`dxgiFormat`), by channel count and [`Storage`] (the same components as KTX2):
//!
//! | channels | f16                              | f32                              | unorm8                         | unorm16                         |
//! |----------|----------------------------------|----------------------------------|--------------------------------|---------------------------------|
//! | 1        | `R16_FLOAT` (54)                 | `R32_FLOAT` (41)                 | `R8_UNORM` (61)                | `R16_UNORM` (56)                |
//! | 2        | `R16G16_FLOAT` (34)              | `R32G32_FLOAT` (16)              | `R8G8_UNORM` (49)              | `R16G16_UNORM` (35)             |
//! | 3, 4     | `R16G16B16A16_FLOAT` (10)        | `R32G32B32A32_FLOAT` (2)         | `R8G8B8A8_UNORM` (28)          | `R16G16B16A16_UNORM` (11)       |
//!
//! A 3-channel table is stored as 4 components with a 4th of 1.0 (the largest code for
//! UNORM), as in KTX2. Shape: texture x = table axis 0, y = axis 1; a 1D table is a 2D
//! texture of height 1; a 3D table a volume texture (`resourceDimension` TEXTURE3D,
//! `DDSD_DEPTH`, `DDSCAPS2_VOLUME`) or, with [`DdsEncoder::array_3d`], a 2D array
//! (`arraySize` = slices). DDS's first row is the top of the image, which Direct3D, Vulkan
//! and Metal put at texture coordinate v = 0: the first row is table row y = 0, no y-flip
//! (OpenGL loaders that flip DDS images on upload must not flip these).
//!
//! Layout (Microsoft's "DDS" programming guide: `DDS_HEADER`, `DDS_PIXELFORMAT`,
//! `DDS_HEADER_DXT10`): the magic `"DDS "`, a 124-byte header (flags CAPS, HEIGHT, WIDTH,
//! PITCH, PIXELFORMAT, MIPMAPCOUNT, and DEPTH for a volume; pitch = width × texel bytes;
//! mipMapCount 1), a pixel format of FourCC `DX10`, the 20-byte DX10 header (alpha mode
//! unknown: the data is not colour), then the texels (rows in y order, slices or layers in
//! z order, channels interleaved, little-endian). DDS has no place for the header
//! attributes: they are in the JSON sidecar, as for KTX2.
//!
//! Determinism: every byte is a function of the table (no writer string, no time).

use super::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::table::spec::Storage;

/// Encodes a table as a DDS texture (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DdsEncoder {
    /// Component precision, as for [`super::ktx2::Ktx2Encoder::storage`].
    pub storage: Storage,
    /// The table's name, used in error messages.
    pub table_name: String,
    /// 3D tables only: a 2D array texture (one layer per slice) instead of a volume.
    pub array_3d: bool,
}

const MAGIC: &[u8; 4] = b"DDS ";
const DDSD_CAPS: u32 = 0x1;
const DDSD_HEIGHT: u32 = 0x2;
const DDSD_WIDTH: u32 = 0x4;
const DDSD_PITCH: u32 = 0x8;
const DDSD_PIXELFORMAT: u32 = 0x1000;
const DDSD_MIPMAPCOUNT: u32 = 0x2_0000;
const DDSD_DEPTH: u32 = 0x80_0000;
const DDPF_FOURCC: u32 = 0x4;
const DDSCAPS_TEXTURE: u32 = 0x1000;
const DDSCAPS2_VOLUME: u32 = 0x20_0000;
const D3D10_RESOURCE_DIMENSION_TEXTURE2D: u32 = 3;
const D3D10_RESOURCE_DIMENSION_TEXTURE3D: u32 = 4;

/// The DXGI format of `components` components in `storage`, with its name.
pub fn dxgi_format(components: usize, storage: Storage) -> (u32, &'static str) {
    match (components, storage) {
        (1, Storage::F16) => (54, "R16_FLOAT"),
        (2, Storage::F16) => (34, "R16G16_FLOAT"),
        (_, Storage::F16) => (10, "R16G16B16A16_FLOAT"),
        (1, Storage::F32) => (41, "R32_FLOAT"),
        (2, Storage::F32) => (16, "R32G32_FLOAT"),
        (_, Storage::F32) => (2, "R32G32B32A32_FLOAT"),
        (1, Storage::Unorm8) => (61, "R8_UNORM"),
        (2, Storage::Unorm8) => (49, "R8G8_UNORM"),
        (_, Storage::Unorm8) => (28, "R8G8B8A8_UNORM"),
        (1, Storage::Unorm16) => (56, "R16_UNORM"),
        (2, Storage::Unorm16) => (35, "R16G16_UNORM"),
        (_, Storage::Unorm16) => (11, "R16G16B16A16_UNORM"),
    }
}

/// The texture a table becomes: (width, height, depth or 1, array size or 1, volume).
fn shape(name: &str, lut: &Lut, array_3d: bool) -> Result<(u32, u32, u32, u32, bool), EncodeError> {
    let err = |reason: String| EncodeError::Shape {
        table: name.to_string(),
        reason,
    };
    let dims = lut.axes.len();
    if dims == 0 || dims > 3 {
        return Err(err(format!(
            "a DDS table has 1 to 3 axes, this one has {dims}"
        )));
    }
    if let Some(a) = lut.axes.iter().find(|a| a.size == 0) {
        return Err(err(format!("axis `{}` has no texels", a.name)));
    }
    let nc = lut.channels.len();
    if nc == 0 || nc > 4 {
        return Err(err(format!(
            "a DDS texture holds 1 to 4 channels, the table has {nc}"
        )));
    }
    let too_large = || err("the table is too large for a DDS texture".into());
    let size = |k: usize| u32::try_from(lut.dim(k)).map_err(|_| too_large());
    let (w, h, z) = (size(0)?, size(1)?, size(2)?);
    let samples = [lut.dim(0), lut.dim(1), lut.dim(2), nc]
        .iter()
        .try_fold(1usize, |n, &k| n.checked_mul(k))
        .ok_or_else(too_large)?;
    if lut.data.len() != samples {
        return Err(err(format!(
            "{samples} samples expected, the data has {}",
            lut.data.len()
        )));
    }
    Ok(match (dims, array_3d) {
        (3, false) => (w, h, z, 1, true),
        (3, true) => (w, h, 1, z, false),
        _ => (w, h, 1, 1, false),
    })
}

impl Encoder for DdsEncoder {
    fn extension(&self) -> &'static str {
        "dds"
    }

    /// Encodes `lut`; `attributes` are ignored (DDS has no place for them).
    fn encode(&self, lut: &Lut, _attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        let (width, height, depth, array_size, volume) =
            shape(&self.table_name, lut, self.array_3d)?;
        let components = super::texels::components(lut.channels.len());
        let (dxgi, _) = dxgi_format(components, self.storage);
        let texel_bytes = components * self.storage.bytes();
        let pitch =
            u32::try_from(width as usize * texel_bytes).map_err(|_| EncodeError::Shape {
                table: self.table_name.clone(),
                reason: "a row is too large for a DDS pitch".into(),
            })?;
        let texels = super::texels::interleaved(
            &self.table_name,
            lut,
            self.storage,
            components,
            "DDS R16*_FLOAT",
        )?;

        let mut flags =
            DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PITCH | DDSD_PIXELFORMAT | DDSD_MIPMAPCOUNT;
        let mut caps2 = 0;
        if volume {
            flags |= DDSD_DEPTH;
            caps2 |= DDSCAPS2_VOLUME;
        }
        let mut out = Vec::with_capacity(4 + 124 + 20 + texels.len());
        let mut put = |v: u32| out.extend_from_slice(&v.to_le_bytes());
        // DDS_HEADER
        put(124); // dwSize
        put(flags);
        put(height);
        put(width);
        put(pitch); // dwPitchOrLinearSize
        put(if volume { depth } else { 0 });
        put(1); // dwMipMapCount
        for _ in 0..11 {
            put(0); // dwReserved1
        }
        // DDS_PIXELFORMAT
        put(32);
        put(DDPF_FOURCC);
        put(u32::from_le_bytes(*b"DX10"));
        for _ in 0..5 {
            put(0); // RGB bit count and masks: unused with a FourCC
        }
        put(DDSCAPS_TEXTURE);
        put(caps2);
        put(0); // dwCaps3
        put(0); // dwCaps4
        put(0); // dwReserved2
                // DDS_HEADER_DXT10
        put(dxgi);
        put(if volume {
            D3D10_RESOURCE_DIMENSION_TEXTURE3D
        } else {
            D3D10_RESOURCE_DIMENSION_TEXTURE2D
        });
        put(0); // miscFlag: not a cube map
        put(array_size);
        put(0); // miscFlags2: DDS_ALPHA_MODE_UNKNOWN
        let mut file = Vec::with_capacity(4 + out.len() + texels.len());
        file.extend_from_slice(MAGIC);
        file.extend_from_slice(&out);
        file.extend_from_slice(&texels);
        Ok(file)
    }
}

/// What [`read`] found in a DDS file brdfbake wrote.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DdsImage {
    pub width: u32,
    pub height: u32,
    /// Slices of a volume texture (1 otherwise).
    pub depth: u32,
    /// Layers of an array texture (1 otherwise).
    pub array_size: u32,
    pub volume: bool,
    pub dxgi_format: u32,
    /// The texture components per texel (1, 2 or 4) and their storage that `dxgi_format` is.
    pub components: usize,
    pub storage: Storage,
    /// The texel bytes after the headers.
    pub data_offset: usize,
}

/// Parses the headers of a DDS file as [`DdsEncoder`] writes them, refusing any field that
/// differs from what it would write (a texture of another shape, format, mip count or with
/// bytes after the texels is not one of ours).
pub fn read(bytes: &[u8]) -> Result<DdsImage, String> {
    if bytes.len() < 4 + 124 + 20 {
        return Err(format!(
            "{} bytes: shorter than the DDS and DX10 headers (148 bytes)",
            bytes.len()
        ));
    }
    if &bytes[..4] != MAGIC {
        return Err("no DDS magic (\"DDS \")".into());
    }
    let u = |i: usize| u32::from_le_bytes(bytes[4 + 4 * i..8 + 4 * i].try_into().expect("4"));
    let field = |name: &str, got: u32, want: u32| {
        if got == want {
            Ok(())
        } else {
            Err(format!("{name} is {got:#x}, brdfbake writes {want:#x}"))
        }
    };
    field("dwSize", u(0), 124)?;
    let flags = u(1);
    let volume = flags & DDSD_DEPTH != 0;
    let base =
        DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PITCH | DDSD_PIXELFORMAT | DDSD_MIPMAPCOUNT;
    field("dwFlags", flags, base | if volume { DDSD_DEPTH } else { 0 })?;
    let (height, width, pitch, depth) = (u(2), u(3), u(4), u(5));
    if !volume {
        field("dwDepth", depth, 0)?;
    }
    field("dwMipMapCount", u(6), 1)?;
    field("ddspf.dwSize", u(18), 32)?;
    field("ddspf.dwFlags", u(19), DDPF_FOURCC)?;
    field("ddspf.dwFourCC", u(20), u32::from_le_bytes(*b"DX10"))?;
    field("dwCaps", u(26), DDSCAPS_TEXTURE)?;
    field("dwCaps2", u(27), if volume { DDSCAPS2_VOLUME } else { 0 })?;
    let dxgi = u(31);
    let dim = u(32);
    field(
        "resourceDimension",
        dim,
        if volume {
            D3D10_RESOURCE_DIMENSION_TEXTURE3D
        } else {
            D3D10_RESOURCE_DIMENSION_TEXTURE2D
        },
    )?;
    field("miscFlag", u(33), 0)?;
    let array_size = u(34);
    if volume {
        field("arraySize", array_size, 1)?;
    }
    if width == 0 || height == 0 || array_size == 0 || (volume && depth == 0) {
        return Err(format!(
            "a zero size (width {width}, height {height}, depth {depth}, arraySize {array_size})"
        ));
    }
    let (components, storage) = [1usize, 2, 4]
        .into_iter()
        .flat_map(|c| Storage::ALL.into_iter().map(move |s| (c, s)))
        .find(|&(c, s)| dxgi_format(c, s).0 == dxgi)
        .ok_or_else(|| format!("dxgiFormat {dxgi} is not one brdfbake writes"))?;
    let texel_bytes = components * storage.bytes();
    field(
        "dwPitchOrLinearSize",
        pitch,
        (width as u64 * texel_bytes as u64).min(u32::MAX as u64) as u32,
    )?;
    let need = [
        height as u128,
        if volume { depth } else { 1 } as u128,
        array_size as u128,
    ]
    .iter()
    .fold(pitch as u128, |n, &k| n * k);
    let data_offset = 4 + 124 + 20;
    if (bytes.len() - data_offset) as u128 != need {
        return Err(format!(
            "{} bytes of texels after the headers; the headers (width {width}, height {height}, \
             depth {depth}, arraySize {array_size}, dxgiFormat {dxgi}) describe {need}",
            bytes.len() - data_offset
        ));
    }
    Ok(DdsImage {
        width,
        height,
        depth: if volume { depth } else { 1 },
        array_size,
        volume,
        dxgi_format: dxgi,
        components,
        storage,
        data_offset,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table whose texels ramp from 0 (every value distinct).
    fn table(sizes: &[usize], nc: usize) -> Lut {
        let n: usize = sizes.iter().product();
        let data = (0..n * nc).map(|i| i as f32 / (n * nc) as f32).collect();
        crate::lut::test_table(sizes, nc, data)
    }

    /// `read` accepts what the encoder writes, with the shape it was given, and every single
    /// changed byte of a field it knows (all but the reserved ones and the unused pixel-format
    /// masks) is refused without a panic; so is every truncation.
    #[test]
    fn read_round_trips_and_refuses_changed_fields() {
        for (sizes, nc, array_3d) in [
            (&[7][..], 1, false),
            (&[5, 3][..], 2, false),
            (&[4, 3, 2][..], 3, false),
            (&[4, 3, 2][..], 4, true),
        ] {
            for storage in Storage::ALL {
                let enc = DdsEncoder {
                    storage,
                    table_name: "t".into(),
                    array_3d,
                };
                let bytes = enc.encode(&table(sizes, nc), &[]).unwrap();
                let im = read(&bytes).unwrap();
                let z = sizes.get(2).copied().unwrap_or(1) as u32;
                assert_eq!(
                    (im.width, im.height),
                    (sizes[0] as u32, sizes.get(1).copied().unwrap_or(1) as u32)
                );
                assert_eq!(
                    (im.depth, im.array_size, im.volume),
                    if sizes.len() == 3 && !array_3d {
                        (z, 1, true)
                    } else {
                        (1, z, false)
                    }
                );
                // u32 fields (after the magic) that read() does not check
                let unchecked: Vec<usize> =
                    (7..18).chain(21..26).chain(28..31).chain([35]).collect();
                for i in 0..148 {
                    if i >= 4 && unchecked.contains(&((i - 4) / 4)) {
                        continue;
                    }
                    let mut b = bytes.clone();
                    b[i] ^= 0x10;
                    assert!(read(&b).is_err(), "byte {i} changed was accepted");
                }
                for n in [0, 100, 147, 148, bytes.len() - 1] {
                    assert!(read(&bytes[..n]).is_err());
                }
                let mut longer = bytes.clone();
                longer.push(0);
                assert!(read(&longer).is_err());
            }
        }
    }
}
