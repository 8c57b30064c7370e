//! The texels of a table as a GPU texture stores them, shared by the texture containers (KTX2,
//! DDS): texels in x order, rows in y order, slices (or layers) in z order, the channels of a
//! texel interleaved, little-endian; f16/f32 floats or the UNORM codes of [`super::unorm`], a
//! 3-channel table padded to 4 components with a 4th component of 1.0 (the largest code for
//! UNORM). Every value is checked before a byte is produced: a NaN or an infinity, or an f16
//! that would overflow, is an error naming the texel or the channel.

use super::EncodeError;
use crate::lut::Lut;
use crate::table::spec::Storage;
use half::f16;

/// The texture components a table of `channels` channels is stored in (3 padded to 4).
pub fn components(channels: usize) -> usize {
    if channels == 3 {
        4
    } else {
        channels
    }
}

/// The interleaved texel bytes of `lut` in `storage` with `components` components per texel
/// (the table's channels, then padding of 1.0). `f16_format` names the container's 16-bit
/// float format in the overflow error.
pub fn interleaved(
    table_name: &str,
    lut: &Lut,
    storage: Storage,
    components: usize,
    f16_format: &'static str,
) -> Result<Vec<u8>, EncodeError> {
    let nc = lut.channels.len();
    let (nx, ny) = (lut.dim(0), lut.dim(1));
    for (c, channel) in lut.channels.iter().enumerate() {
        let values = || lut.data.iter().skip(c).step_by(nc).copied();
        if let Some((i, v)) = values().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(EncodeError::NonFinite {
                table: table_name.to_string(),
                channel: channel.name.clone(),
                texel: [i % nx, (i / nx) % ny, i / (nx * ny)],
                value: v as f64,
            });
        }
        if storage == Storage::F16 && values().any(|v| f16::from_f32(v).is_infinite()) {
            let largest = values().fold(0.0f32, |m, v| if v.abs() > m.abs() { v } else { m });
            return Err(EncodeError::Unrepresentable {
                table: table_name.to_string(),
                channel: channel.name.clone(),
                value: largest as f64,
                format: f16_format,
            });
        }
    }

    let texels = lut.data.len() / nc.max(1);
    let mut out = Vec::with_capacity(texels * components * storage.bytes());
    if let Some(max) = storage.unorm_max() {
        let codes = super::unorm::codes(table_name, lut, storage)?;
        let mut push = |c: u16| match storage {
            Storage::Unorm8 => out.push(c as u8),
            _ => out.extend_from_slice(&c.to_le_bytes()),
        };
        for texel in codes.chunks_exact(nc) {
            for &c in texel {
                push(c);
            }
            // the alpha padding of a 3-channel table: 1.0
            for _ in nc..components {
                push(max as u16);
            }
        }
        return Ok(out);
    }
    let mut push = |v: f32| match storage {
        Storage::F16 => out.extend_from_slice(&f16::from_f32(v).to_le_bytes()),
        _ => out.extend_from_slice(&v.to_le_bytes()),
    };
    for texel in lut.data.chunks_exact(nc) {
        for &v in texel {
            push(v);
        }
        // the alpha padding of a 3-channel table
        for _ in nc..components {
            push(1.0);
        }
    }
    Ok(out)
}
