//! `bin`: the texels as raw little-endian numbers and nothing else — the form research code
//! loads with `numpy.fromfile` (nvdiffrec's `bsdf_256_256.bin` is such a file) and engines
//! upload with one memcpy.
//!
//! The bytes are the texels of the EXR and KTX2 files in the same order: channels interleaved
//! per texel, x (axis 0, u) fastest, then y (axis 1, v), then z (axis 2); no padding channel.
//! Each value is stored as the table's storage says: f32 (IEEE 754 binary32), f16 (binary16,
//! rounded to nearest, ties to even; a value beyond its range is an error, never an
//! infinity), unorm8 or unorm16 (the codes of [`super::unorm`]), multi-byte values
//! little-endian. There is no header: the sidecar's `storage.array` section
//! ([`array_layout`]) gives the element type and the shape, so that
//! `numpy.fromfile(path, dtype).reshape(shape)` is the table.
//!
//! The array's dimensions are the axes in reverse, then the channels — (ny, nx, channels) for
//! a 2D table, as an image's rows: element `[y][x][c]` is texel (x, y)'s channel c, and a 3D
//! table is `[z][y][x][c]`. The same array is what [`super::npy`] and [`super::npz`] hold and
//! what the Python module returns.

use super::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::table::Storage;
use serde_json::{json, Value};

/// Encodes a table's texels as raw little-endian numbers (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RawBin {
    pub storage: Storage,
    /// The table's name, for error messages.
    pub table_name: String,
}

/// What a `.bin` file is, for the sidecar.
pub const FILE_NOTE: &str = "TABLE.bin: the array's bytes alone, no header: numpy.fromfile(path, dtype=dtype).reshape(shape)";

impl Encoder for RawBin {
    fn extension(&self) -> &'static str {
        "bin"
    }

    /// The texels; `attributes` are not stored (the file has no header).
    fn encode(&self, lut: &Lut, _attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        texels(&self.table_name, lut, self.storage)
    }
}

/// The texels of `lut` as stored in `storage`, little-endian, in texel order (the module
/// documentation), after the checks every encoder makes (shape, finite values, the storage's
/// range).
pub fn texels(table: &str, lut: &Lut, storage: Storage) -> Result<Vec<u8>, EncodeError> {
    super::source::check_table(table, lut)?;
    let mut out = Vec::with_capacity(lut.data.len() * storage.bytes());
    match storage {
        Storage::F32 => {
            for v in &lut.data {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
        Storage::F16 => {
            for h in super::source::f16_values(table, lut)? {
                out.extend_from_slice(&h.to_le_bytes());
            }
        }
        Storage::Unorm8 => {
            out.extend(
                super::unorm::codes(table, lut, storage)?
                    .into_iter()
                    .map(|c| c as u8),
            );
        }
        Storage::Unorm16 => {
            for c in super::unorm::codes(table, lut, storage)? {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    Ok(out)
}

/// numpy's name of the element type (`numpy.dtype(...)`): `<f4`, `<f2`, `|u1`, `<u2`.
pub fn dtype(storage: Storage) -> &'static str {
    match storage {
        Storage::F32 => "<f4",
        Storage::F16 => "<f2",
        Storage::Unorm8 => "|u1",
        Storage::Unorm16 => "<u2",
    }
}

/// The array's shape: the axes' sizes in reverse, then the channels.
pub fn shape(lut: &Lut) -> Vec<usize> {
    let mut s: Vec<usize> = lut.axes.iter().rev().map(|a| a.size).collect();
    s.push(lut.channels.len());
    s
}

/// The sidecar's `storage.array` section: how the `bin`, `npy` and `npz` files (and the
/// Python module's arrays) hold the texels.
pub fn array_layout(lut: &Lut, storage: Storage) -> Value {
    let element = match storage {
        Storage::F32 => "IEEE 754 binary32 (float32), little-endian",
        Storage::F16 => "IEEE 754 binary16 (float16), little-endian",
        Storage::Unorm8 => "8-bit unsigned normalized-integer codes (uint8): value = code / 255",
        Storage::Unorm16 => {
            "16-bit unsigned normalized-integer codes (uint16), little-endian: value = code / 65535"
        }
    };
    let mut dims: Vec<String> = lut
        .axes
        .iter()
        .enumerate()
        .rev()
        .map(|(k, a)| format!("{} (axis {k})", a.name))
        .collect();
    dims.push("channel (the channels list)".into());
    json!({
        "dtype": dtype(storage),
        "element": element,
        "shape": shape(lut),
        "dimensions": dims,
        "order": "row-major (C order): the last dimension varies fastest, so array[y][x][c] is texel (x, y)'s channel c (a 3D table: array[z][y][x][c]); the texels of the EXR and KTX2 files in the same order, without the KTX2's padding channel",
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::lut::test_table as table;

    #[test]
    fn texels_in_order_as_stored() {
        // 3 x 2 texels, 2 channels: value = 10 x + 100 y + c / 4 (exact in f16 too)
        let data: Vec<f32> = (0..2)
            .flat_map(|y| {
                (0..3).flat_map(move |x| {
                    (0..2).map(move |c| 10.0 * x as f32 + 100.0 * y as f32 + c as f32 / 4.0)
                })
            })
            .collect();
        let lut = table(&[3, 2], 2, data.clone());
        let b = texels("t", &lut, Storage::F32).unwrap();
        assert_eq!(b.len(), 12 * 4);
        let back: Vec<f32> = b
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(back, data);
        let h = texels("t", &lut, Storage::F16).unwrap();
        // texel (x 1, y 1), channel 1: 110.25 = 0x56E4 in binary16
        let i = ((3 + 1) * 2 + 1) * 2;
        assert_eq!(u16::from_le_bytes([h[i], h[i + 1]]), 0x56e4);
        assert_eq!(shape(&lut), [2, 3, 2]);
        assert_eq!(array_layout(&lut, Storage::F16)["dtype"], "<f2");
    }

    #[test]
    fn unorm_codes_and_refusals() {
        let lut = table(&[2], 1, vec![0.0, 1.0]);
        assert_eq!(texels("t", &lut, Storage::Unorm8).unwrap(), [0, 255]);
        assert_eq!(
            texels("t", &lut, Storage::Unorm16).unwrap(),
            [0, 0, 255, 255]
        );
        let out = table(&[2], 1, vec![0.5, 1.5]);
        assert!(matches!(
            texels("t", &out, Storage::Unorm8),
            Err(EncodeError::OutOfUnitRange { .. })
        ));
        let big = table(&[2], 1, vec![0.5, 1e5]);
        assert!(matches!(
            texels("t", &big, Storage::F16),
            Err(EncodeError::Unrepresentable { .. })
        ));
        let nan = table(&[2], 1, vec![0.5, f32::NAN]);
        assert!(matches!(
            texels("t", &nan, Storage::F32),
            Err(EncodeError::NonFinite { .. })
        ));
    }
}
