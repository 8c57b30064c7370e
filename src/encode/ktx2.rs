//! KTX 2.0 encoding: an uncompressed, single-level texture in a signed-float or unsigned
//! normalized Vulkan format, ready to upload as-is (Vulkan, WebGPU, or OpenGL through libktx).
//!
//! Formats (`vkFormat`), by channel count and [`Storage`]:
//!
//! | channels | f16                   | f32                   | unorm8           | unorm16               |
//! |----------|-----------------------|-----------------------|------------------|-----------------------|
//! | 1        | `R16_SFLOAT`          | `R32_SFLOAT`          | `R8_UNORM`       | `R16_UNORM`           |
//! | 2        | `R16G16_SFLOAT`       | `R32G32_SFLOAT`       | `R8G8_UNORM`     | `R16G16_UNORM`        |
//! | 3, 4     | `R16G16B16A16_SFLOAT` | `R32G32B32A32_SFLOAT` | `R8G8B8A8_UNORM` | `R16G16B16A16_UNORM`  |
//!
//! Table channel `c` is texture component `c` (R, G, B, A, in table order). A 3-channel table
//! is stored as RGBA with a 4th (A) channel of 1.0 (the largest code for UNORM) in every
//! texel, because three-component formats are rarely sampleable on GPUs; the JSON sidecar
//! lists the real channels. UNORM components hold the codes of [`super::unorm`]
//! (`round(v·(2ⁿ − 1))`; a value outside [0, 1] is an error).
//!
//! Shape: texture x = table axis 0, y = axis 1, z = axis 2.
//! - A 1D table becomes a 2D texture of height 1 (not a 1D texture, which many engines and
//!   loaders do not handle, and WebGPU samples differently).
//! - A 2D table becomes a 2D texture.
//! - A 3D table becomes a 3D texture (`pixelDepth` = nz) or, with
//!   [`Ktx2Encoder::array_3d`], a 2D array texture (`layerCount` = nz, `pixelDepth` 0) whose
//!   layer z is table slice z (no filtering across slices).
//!
//! The first row of the image data is table row y = 0, and `KTXorientation` says so: `rd`
//! (x to the right, rows going down, so the first row is at texture coordinate v = 0) for 2D
//! and array textures, `rdi` for 3D textures (slice z = 0 first, depth going "in"). The KTX
//! specification counts no array dimension in the orientation, so arrays get two characters.
//!
//! Header layout, per the KTX 2.0 specification: 80-byte header, one level index entry, the
//! Data Format Descriptor (the Basic DFD the Khronos tools derive from the `vkFormat`: RGBSDA
//! model, BT.709 primaries, linear transfer, straight alpha, one sample per component: for
//! the float formats `FLOAT|SIGNED` with sampleLower −1.0 and sampleUpper 1.0, for the UNORM
//! formats no qualifier bits with sampleLower 0 and sampleUpper 2ⁿ − 1), the key/value data (`KTXorientation`
//! and `KTXwriter`, sorted by key bytes, each entry padded to 4 bytes), no supercompression
//! global data (offset and length 0), zero padding to `lcm(texel size, 4)`, then the level's
//! texels: slices (or layers) in z order, rows in y order, texels in x order, channels
//! interleaved, little-endian. The file ends with the level: the specification puts `mipPadding`
//! before levels only. `levelCount` is 1 (0 would ask the loader to generate mips).
//!
//! Header attributes are NOT written: the `attributes` argument of [`Encoder::encode`] is
//! ignored. KTX validators warn about unknown keys, and the metadata lives in the JSON sidecar.
//!
//! Determinism: every byte is a function of the table and the crate version (`KTXwriter`).

use super::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::table::spec::Storage;
use ::ktx2::dfd::{Basic, Block, ChannelTypeQualifiers, DataFormatFlags, SampleInformation};
use ::ktx2::{ColorModel, ColorPrimaries, Format, Header, Index, LevelIndex, TransferFunction};
use std::num::NonZeroU8;

/// Encodes a table as a KTX 2.0 texture (see the module documentation for the layout).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ktx2Encoder {
    /// Component precision: `*_SFLOAT` with 32 or 16 bits (f16: rounded to nearest, ties to
    /// even; a value that would become infinite is an error), or `*_UNORM` with 8 or 16 bits
    /// (codes rounded to nearest; a value outside [0, 1] is an error).
    pub storage: Storage,
    /// The table's name, used in error messages.
    pub table_name: String,
    /// 3D tables only: write a 2D array texture (one layer per slice) instead of a 3D texture.
    pub array_3d: bool,
    /// The level's supercompression (`supercompressionScheme`).
    pub supercompression: Supercompression,
}

/// A KTX2 level's supercompression.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Supercompression {
    /// The texels as they are uploaded (`supercompressionScheme` 0).
    #[default]
    None,
    /// Zstandard (`supercompressionScheme` 2): one frame holding the level's texels, inflated
    /// by the loader before upload (libktx, three.js' KTX2Loader with its zstd decoder).
    Zstd,
}

impl Supercompression {
    /// The name the sidecar gives it (`storage.ktx2.supercompression`).
    pub fn name(self) -> &'static str {
        match self {
            Supercompression::None => "none",
            Supercompression::Zstd => "zstd",
        }
    }
}

/// The value of the `KTXwriter` key.
pub const WRITER: &str = concat!("brdfbake ", env!("CARGO_PKG_VERSION"));

/// DFD channel ids of the RGBSDA colour model, by component.
const CHANNEL_IDS: [u8; 4] = [0, 1, 2, 15];

/// The texture a table becomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Shape {
    width: u32,
    height: u32,
    /// `pixelDepth`: 0 unless a 3D texture.
    depth: u32,
    /// `layerCount`: 0 unless an array texture.
    layers: u32,
    /// Table channels.
    channels: usize,
    /// Texture components (channels, 3 padded to 4).
    components: usize,
    /// The `KTXorientation` value.
    orientation: &'static str,
}

impl Encoder for Ktx2Encoder {
    fn extension(&self) -> &'static str {
        "ktx2"
    }

    /// Encodes `lut`; `attributes` are ignored (see the module documentation).
    fn encode(&self, lut: &Lut, _attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        let shape = self.shape(lut)?;
        let (format, component_bytes) = vk_format(shape.components, self.storage);
        let texel_bytes = component_bytes * shape.components;
        let level = super::texels::interleaved(
            &self.table_name,
            lut,
            self.storage,
            shape.components,
            "KTX2 *_SFLOAT with 16 bits",
        )?;
        let stored_length = level.len();
        let level = match self.supercompression {
            Supercompression::None => level,
            Supercompression::Zstd => super::zstd::compress(&level),
        };

        let dfd = data_format_descriptor(shape.components, self.storage);
        let kvd = key_value_data(&[("KTXorientation", shape.orientation), ("KTXwriter", WRITER)]);

        // Offsets: header, level index (one level), DFD, KVD, no SGD, padding, level data.
        let dfd_offset = Header::LENGTH + LevelIndex::LENGTH;
        let kvd_offset = dfd_offset + dfd.len();
        let kvd_end = kvd_offset + kvd.len();
        // the level's alignment: lcm(texel size, 4), or 1 for supercompressed data (KTX 2.0,
        // section 3.9.7 mipPadding)
        let align = match self.supercompression {
            Supercompression::None => lcm(texel_bytes, 4),
            Supercompression::Zstd => 1,
        };
        let level_offset = kvd_end.next_multiple_of(align);
        let too_large = || self.shape_error("the table is too large for a KTX2 file");
        let header = Header {
            format: Some(format),
            type_size: component_bytes as u32,
            pixel_width: shape.width,
            pixel_height: shape.height,
            pixel_depth: shape.depth,
            layer_count: shape.layers,
            face_count: 1,
            level_count: 1,
            supercompression_scheme: match self.supercompression {
                Supercompression::None => None,
                Supercompression::Zstd => Some(::ktx2::SupercompressionScheme::Zstandard),
            },
            index: Index {
                dfd_byte_offset: dfd_offset as u32,
                dfd_byte_length: dfd.len() as u32,
                kvd_byte_offset: kvd_offset as u32,
                kvd_byte_length: kvd.len() as u32,
                sgd_byte_offset: 0,
                sgd_byte_length: 0,
            },
        };
        let level_length = u64::try_from(level.len()).map_err(|_| too_large())?;
        let level_index = LevelIndex {
            byte_offset: level_offset as u64,
            byte_length: level_length,
            uncompressed_byte_length: u64::try_from(stored_length).map_err(|_| too_large())?,
        };

        let total = level_offset
            .checked_add(level.len())
            .ok_or_else(too_large)?;
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(&header.as_bytes());
        out.extend_from_slice(&level_index.as_bytes());
        out.extend_from_slice(&dfd);
        out.extend_from_slice(&kvd);
        out.resize(level_offset, 0);
        out.extend_from_slice(&level);
        debug_assert_eq!(out.len(), total);
        Ok(out)
    }
}

impl Ktx2Encoder {
    fn shape_error(&self, reason: impl Into<String>) -> EncodeError {
        EncodeError::Shape {
            table: self.table_name.clone(),
            reason: reason.into(),
        }
    }

    /// The texture's shape, after checking that axes, channels and data agree.
    fn shape(&self, lut: &Lut) -> Result<Shape, EncodeError> {
        let dims = lut.axes.len();
        if dims == 0 || dims > 3 {
            return Err(
                self.shape_error(format!("a KTX2 table has 1 to 3 axes, this one has {dims}"))
            );
        }
        if let Some(a) = lut.axes.iter().find(|a| a.size == 0) {
            return Err(self.shape_error(format!("axis `{}` has no texels", a.name)));
        }
        let channels = lut.channels.len();
        if channels == 0 || channels > 4 {
            return Err(self.shape_error(format!(
                "a KTX2 texture holds 1 to 4 channels, the table has {channels}"
            )));
        }
        let too_large = || self.shape_error("the table is too large for a KTX2 texture");
        let size = |k: usize| u32::try_from(lut.dim(k)).map_err(|_| too_large());
        let (width, height, nz) = (size(0)?, size(1)?, size(2)?);
        let samples = lut
            .dim(0)
            .checked_mul(lut.dim(1))
            .and_then(|n| n.checked_mul(lut.dim(2)))
            .and_then(|n| n.checked_mul(channels))
            .ok_or_else(too_large)?;
        if lut.data.len() != samples {
            return Err(self.shape_error(format!(
                "{samples} samples expected ({}×{}×{} texels × {channels} channels), the data \
                 has {}",
                lut.dim(0),
                lut.dim(1),
                lut.dim(2),
                lut.data.len()
            )));
        }
        let (depth, layers, orientation) = match (dims, self.array_3d) {
            (3, false) => (nz, 0, "rdi"),
            (3, true) => (0, nz, "rd"),
            _ => (0, 0, "rd"),
        };
        Ok(Shape {
            width,
            height,
            depth,
            layers,
            channels,
            components: if channels == 3 { 4 } else { channels },
            orientation,
        })
    }
}

/// The `vkFormat` for `components` components, and the bytes of one component.
fn vk_format(components: usize, storage: Storage) -> (Format, usize) {
    match (components, storage) {
        (1, Storage::F16) => (Format::R16_SFLOAT, 2),
        (2, Storage::F16) => (Format::R16G16_SFLOAT, 2),
        (_, Storage::F16) => (Format::R16G16B16A16_SFLOAT, 2),
        (1, Storage::F32) => (Format::R32_SFLOAT, 4),
        (2, Storage::F32) => (Format::R32G32_SFLOAT, 4),
        (_, Storage::F32) => (Format::R32G32B32A32_SFLOAT, 4),
        (1, Storage::Unorm8) => (Format::R8_UNORM, 1),
        (2, Storage::Unorm8) => (Format::R8G8_UNORM, 1),
        (_, Storage::Unorm8) => (Format::R8G8B8A8_UNORM, 1),
        (1, Storage::Unorm16) => (Format::R16_UNORM, 2),
        (2, Storage::Unorm16) => (Format::R16G16_UNORM, 2),
        (_, Storage::Unorm16) => (Format::R16G16B16A16_UNORM, 2),
    }
}

/// The storage and component count a `vkFormat` holds, where it is one this encoder writes
/// (R, RG or RGBA in 16- or 32-bit float or 8- or 16-bit UNORM): for readers of KTX2 files.
pub fn storage_of(format: Format) -> Option<(Storage, usize)> {
    Storage::ALL
        .into_iter()
        .flat_map(|s| [1, 2, 4].map(|c| (s, c)))
        .find(|&(s, c)| vk_format(c, s).0 == format)
}

/// The Data Format Descriptor of the format of `components` components in `storage`
/// (`*_SFLOAT` or `*_UNORM`): `dfdTotalSize` followed by one Basic descriptor block.
fn data_format_descriptor(components: usize, storage: Storage) -> Vec<u8> {
    let component_bytes = storage.bytes();
    let bits = (component_bytes * 8) as u8;
    // UNORM samples are unsigned integers 0..=2ⁿ − 1 (no qualifiers), the float ones signed
    // floats whose -1.0 and 1.0 are the sample range (Khronos Data Format 1.3, 5.18-5.20)
    let (qualifiers, lower, upper) = match storage.unorm_max() {
        Some(max) => (ChannelTypeQualifiers::empty(), 0, max),
        None => (
            ChannelTypeQualifiers::FLOAT | ChannelTypeQualifiers::SIGNED,
            (-1.0f32).to_bits(),
            1.0f32.to_bits(),
        ),
    };
    let basic = Basic {
        color_model: Some(ColorModel::RGBSDA),
        color_primaries: Some(ColorPrimaries::BT709),
        transfer_function: Some(TransferFunction::Linear),
        flags: DataFormatFlags::STRAIGHT_ALPHA,
        // stored as dimension − 1: a 1×1×1×1 texel block
        texel_block_dimensions: [NonZeroU8::MIN; 4],
        bytes_planes: [(components * component_bytes) as u8, 0, 0, 0, 0, 0, 0, 0],
        sample_information: CHANNEL_IDS[..components]
            .iter()
            .enumerate()
            .map(|(i, &channel_type)| SampleInformation {
                bit_offset: i as u16 * u16::from(bits),
                bit_length: NonZeroU8::new(bits).expect("8, 16 or 32 bits"),
                channel_type,
                channel_type_qualifiers: qualifiers,
                sample_positions: [0; 4],
                lower,
                upper,
            })
            .collect(),
    };
    let block = Block::Basic(basic).to_vec();
    let mut dfd = Vec::with_capacity(4 + block.len());
    dfd.extend_from_slice(&(4 + block.len() as u32).to_le_bytes());
    dfd.extend_from_slice(&block);
    dfd
}

/// Key/value data: for each pair, sorted by the key's bytes, `keyAndValueByteLength` (u32),
/// the key, NUL, the value, NUL, then zero padding to a multiple of 4 bytes.
fn key_value_data(pairs: &[(&str, &str)]) -> Vec<u8> {
    let mut pairs = pairs.to_vec();
    pairs.sort_by(|a, b| a.0.as_bytes().cmp(b.0.as_bytes()));
    let mut out = Vec::new();
    for (key, value) in pairs {
        let length = key.len() + 1 + value.len() + 1;
        out.extend_from_slice(&(length as u32).to_le_bytes());
        out.extend_from_slice(key.as_bytes());
        out.push(0);
        out.extend_from_slice(value.as_bytes());
        out.push(0);
        out.resize(out.len().next_multiple_of(4), 0);
    }
    out
}

fn lcm(a: usize, b: usize) -> usize {
    fn gcd(a: usize, b: usize) -> usize {
        if b == 0 {
            a
        } else {
            gcd(b, a % b)
        }
    }
    a / gcd(a, b) * b
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Our DFDs equal the ones the `ktx2` crate derives from the same `vkFormat` (its port of
    /// the Khronos `vk2dfd` tables), and the type sizes agree.
    #[test]
    fn dfd_matches_the_ktx2_crate() {
        for storage in Storage::ALL {
            for components in [1, 2, 4] {
                let (format, component_bytes) = vk_format(components, storage);
                let (basic, type_size) = Basic::from_format(format).unwrap();
                assert_eq!(type_size as usize, component_bytes, "{format:?}");
                let ours = data_format_descriptor(components, storage);
                assert_eq!(&ours[4..], &Block::Basic(basic).to_vec()[..], "{format:?}");
                assert_eq!(
                    u32::from_le_bytes(ours[..4].try_into().unwrap()) as usize,
                    ours.len()
                );
            }
        }
    }

    #[test]
    fn key_value_data_is_sorted_nul_terminated_and_padded() {
        let kvd = key_value_data(&[("KTXwriter", "w 1"), ("KTXorientation", "rd")]);
        let mut want = Vec::new();
        want.extend_from_slice(&18u32.to_le_bytes());
        want.extend_from_slice(b"KTXorientation\0rd\0\0\0");
        want.extend_from_slice(&14u32.to_le_bytes());
        want.extend_from_slice(b"KTXwriter\0w 1\0\0\0");
        assert_eq!(kvd, want);
    }

    #[test]
    fn lcm_of_texel_sizes() {
        assert_eq!(lcm(2, 4), 4);
        assert_eq!(lcm(4, 4), 4);
        assert_eq!(lcm(8, 4), 8);
        assert_eq!(lcm(16, 4), 16);
        assert_eq!(lcm(6, 4), 12);
    }
}
