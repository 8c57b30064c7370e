//! `png-data`: the texels of a UNORM8 or UNORM16 table themselves as a PNG image of that bit
//! depth — a texture to upload or import as data, unlike the previews of [`super::png`].
//!
//! Layout, as the EXR's: width = nx, height = ny (1 for a 1D table, ny·nz for a 3D table,
//! whose slices are stacked downward: slice z occupies rows `[z·ny, (z+1)·ny)`); the first
//! (top) image row is table row y = 0, the first coordinate of axis 1 — uploaded as the first
//! row in memory it is v = 0, as everywhere in brdfbake. Each sample is the table value's
//! normalized-integer code ([`super::unorm`]: `round(v·(2ⁿ − 1))`, ties to even; a value
//! outside [0, 1] is an error), 8 or 16 bits as the storage says (16-bit samples big-endian,
//! as PNG stores them).
//!
//! Channels: 1 → greyscale; 2 → RGB with B = 0 (PNG has no two-channel colour type: its
//! grey+alpha would put the second channel in alpha, which importers premultiply or drop);
//! 3 → RGB; 4 → RGBA (straight, unassociated alpha as PNG defines it).
//!
//! No colour-space chunk (`sRGB`, `gAMA`, `cHRM`, `iCCP`): the samples are data. Importers
//! that assume sRGB for untagged PNGs must be told the image is linear/non-colour
//! (docs/engines.md). Text chunks: `Software`, `Title`, `Description`, `brdfbake:note`
//! ("texels, not a preview"), `brdfbake:layout`, then the caller's attributes (keys prefixed
//! with `brdfbake:` unless they contain a colon, as in the previews).
//!
//! Determinism: fixed deflate level and filter choice, as the previews.

use super::png::write_png;
use super::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::table::Storage;
use ::png::{BitDepth, ColorType};

/// Encodes a UNORM table's texels as a PNG image (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PngData {
    /// `Unorm8` (8-bit PNG) or `Unorm16` (16-bit PNG); a float storage is an error.
    pub storage: Storage,
    /// The table's name: used in titles and error messages.
    pub table_name: String,
}

/// The note every png-data file carries (the previews carry [`super::png::NOTE`]).
pub const NOTE: &str = "texels, not a preview";

/// The PNG colour type and the number of image channels for a table of `channels` channels.
pub fn colour_type(channels: usize) -> Option<(ColorType, usize)> {
    match channels {
        1 => Some((ColorType::Grayscale, 1)),
        2 | 3 => Some((ColorType::Rgb, 3)),
        4 => Some((ColorType::Rgba, 4)),
        _ => None,
    }
}

impl Encoder for PngData {
    fn extension(&self) -> &'static str {
        "png"
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        super::source::check_table(&self.table_name, lut)?;
        let shape = |reason: String| EncodeError::Shape {
            table: self.table_name.clone(),
            reason,
        };
        let (depth, max) = match self.storage {
            Storage::Unorm8 => (BitDepth::Eight, 255),
            Storage::Unorm16 => (BitDepth::Sixteen, 65535),
            s => {
                return Err(shape(format!(
                    "png-data stores normalized integers (unorm8 or unorm16), not {}",
                    s.name()
                )))
            }
        };
        let nc = lut.channels.len();
        let (color, components) = colour_type(nc).ok_or_else(|| {
            shape(format!(
                "a PNG image holds 1 to 4 channels, the table has {nc}"
            ))
        })?;
        let (w, h) = (lut.dim(0), lut.dim(1) * lut.dim(2));
        if w > u32::MAX as usize / 2 || h > u32::MAX as usize / 2 {
            return Err(shape("the table is too large for a PNG image".into()));
        }
        let codes = super::unorm::codes(&self.table_name, lut, self.storage)?;
        let bytes_per_sample = self.storage.bytes();
        let mut data = Vec::with_capacity(w * h * components * bytes_per_sample);
        for texel in codes.chunks_exact(nc) {
            for k in 0..components {
                // (a 2-channel table's B is 0)
                let c = texel.get(k).copied().unwrap_or(0);
                match depth {
                    BitDepth::Eight => data.push(c as u8),
                    _ => data.extend_from_slice(&c.to_be_bytes()),
                }
            }
        }
        let channel_map = ["R", "G", "B", "A"][..components]
            .iter()
            .enumerate()
            .map(|(k, comp)| match lut.channels.get(k) {
                Some(ch) if nc > 1 => format!("{comp} = {}", ch.name),
                Some(ch) => format!("grey = {}", ch.name),
                None => format!("{comp} = 0 (padding: PNG has no two-channel colour type)"),
            })
            .collect::<Vec<_>>()
            .join(", ");
        let mut text = vec![
            (
                "Title".to_string(),
                format!("brdfbake table {} (png-data)", self.table_name),
            ),
            (
                "Description".to_string(),
                format!(
                    "the texels of brdfbake table {} as {}-bit normalized integers: value = sample / {max}; \
                     linear data, not an image to colour-manage",
                    self.table_name,
                    bytes_per_sample * 8
                ),
            ),
            ("Software".to_string(), "brdfbake".to_string()),
            ("note".to_string(), NOTE.to_string()),
            (
                "layout".to_string(),
                format!(
                    "{channel_map}; the top row is y = 0 (the first coordinate of axis 1), x = 0 the left column{}",
                    if lut.axes.len() == 3 {
                        format!(
                            "; the {} slices are stacked downward: slice z is rows [z*{ny}, (z+1)*{ny})",
                            lut.dim(2),
                            ny = lut.dim(1)
                        )
                    } else {
                        String::new()
                    }
                ),
            ),
        ];
        text.extend(attributes.iter().cloned());

        write_png((w as u32, h as u32), color, depth, &text, &data, &|e| {
            shape(format!("PNG encoding failed: {e}"))
        })
    }
}
