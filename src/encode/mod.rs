//! Encoders: pure functions from a baked [`Lut`] (plus header attributes) to the bytes of a
//! file. Encoders never touch the file system — writing is `crate::write`'s job — so the same
//! input always gives the same bytes, and an encoding error leaves no half-written output.

pub mod bin;
pub mod dds;
pub mod exr;
pub mod function;
pub mod ktx2;
pub mod npy;
pub mod npz;
pub mod png;
pub mod png_data;
pub mod rgbd;
pub mod shader;
pub mod shader_ltc;
pub mod source;
pub mod texels;
pub mod unorm;
pub mod zstd;

pub use self::exr::{decode_exr, DecodedExr, ExrEncoder};

use crate::lut::Lut;

/// An encoded file: its bytes and the file name extension (without the dot) it should get.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Encoded {
    pub extension: &'static str,
    pub bytes: Vec<u8>,
}

/// Why a table could not be encoded.
#[derive(Debug, thiserror::Error)]
pub enum EncodeError {
    /// A finite value is outside the range of the storage format (it would become ±inf).
    /// `value` is the channel's largest-magnitude value.
    #[error(
        "table `{table}`, channel `{channel}`: value {value} cannot be stored as {format} \
         (it would become infinite); store the table as f32 (\"storage\": \"f32\") or set its \"scale\" below 1"
    )]
    Unrepresentable {
        table: String,
        channel: String,
        value: f64,
        format: &'static str,
    },
    /// A value a normalized-integer storage (UNORM8, UNORM16) cannot hold: its nearest code
    /// lies outside 0..=2ⁿ − 1 (the value is more than half a step outside [0, 1]).
    #[error(
        "table `{table}`, channel `{channel}`: texel {texel:?} holds {value} (stored units, after \
         the scale), outside the [0, 1] that {storage} stores; {advice}"
    )]
    OutOfUnitRange {
        table: String,
        channel: String,
        /// Texel indices, one per axis.
        texel: Vec<usize>,
        value: f64,
        storage: &'static str,
        /// What to do.
        advice: String,
    },
    /// The table holds a NaN or an infinity, which no lookup table should contain.
    #[error(
        "table `{table}`, channel `{channel}`: texel {texel:?} is {value}, not a finite number"
    )]
    NonFinite {
        table: String,
        channel: String,
        /// Texel indices `[x, y, z]` (missing axes are 0).
        texel: [usize; 3],
        value: f64,
    },
    /// The table's axes, channels and data do not fit together or do not fit the format.
    #[error("table `{table}`: {reason}")]
    Shape { table: String, reason: String },
    /// A channel name the format cannot hold.
    #[error("table `{table}`: channel name `{channel}` is not usable: {reason}")]
    ChannelName {
        table: String,
        channel: String,
        reason: &'static str,
    },
    /// A header attribute the format cannot hold.
    #[error("header attribute `{key}` is not usable: {reason}")]
    Attribute { key: String, reason: String },
    /// The EXR library failed.
    #[error("EXR encoding failed: {0}")]
    Exr(String),
}

/// A pure encoder of lookup tables into one file format.
pub trait Encoder {
    /// The file name extension (without the dot) of the files this encoder produces.
    fn extension(&self) -> &'static str;

    /// Encodes `lut` with the header `attributes` (key/value pairs, written in this order
    /// where the format keeps an order). Identical arguments give identical bytes.
    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError>;

    /// [`Encoder::encode`], packaged with the extension.
    fn encode_file(
        &self,
        lut: &Lut,
        attributes: &[(String, String)],
    ) -> Result<Encoded, EncodeError> {
        Ok(Encoded {
            extension: self.extension(),
            bytes: self.encode(lut, attributes)?,
        })
    }
}
