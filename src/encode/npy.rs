//! `npy`: the texels as a NumPy `.npy` file (format version 1.0), which `numpy.load` reads
//! without brdfbake: the array of [`super::bin`] (dimensions the axes in reverse, then the
//! channels; element type the table's storage) behind the format's header.
//!
//! The header is the one `numpy.save` writes for that array, byte for byte: the magic
//! `\x93NUMPY`, version 1.0, the header length, then the Python literal
//! `{'descr': '<f4', 'fortran_order': False, 'shape': (256, 256, 2), }` followed by the spaces
//! numpy leaves to grow the first dimension in place and the padding that aligns the data to
//! 64 bytes, ending in a newline (the format's specification: numpy's
//! `numpy/lib/format.py`, "NPY format version 1.0"). The `.npy` format has no room for other
//! keys: the sidecar beside the file says what the axes and channels are.

use super::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::table::Storage;

/// Encodes a table's texels as a `.npy` file (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Npy {
    pub storage: Storage,
    /// The table's name, for error messages.
    pub table_name: String,
}

/// What a `.npy` file is, for the sidecar.
pub const FILE_NOTE: &str =
    "TABLE.npy: the array with a NumPy .npy (version 1.0) header: numpy.load(path)";

/// numpy's `GROWTH_AXIS_MAX_DIGITS`: the header leaves room for a first dimension this long.
const GROWTH_AXIS_MAX_DIGITS: usize = 21;
/// The data starts at a multiple of this (numpy's `ARRAY_ALIGN`).
const ARRAY_ALIGN: usize = 64;
/// `\x93NUMPY`, version 1.0.
const MAGIC: &[u8; 8] = b"\x93NUMPY\x01\x00";

impl Encoder for Npy {
    fn extension(&self) -> &'static str {
        "npy"
    }

    /// The file; `attributes` are not stored (the format has no place for them).
    fn encode(&self, lut: &Lut, _attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        let data = super::bin::texels(&self.table_name, lut, self.storage)?;
        npy(
            super::bin::dtype(self.storage),
            &super::bin::shape(lut),
            &data,
        )
        .map_err(|reason| EncodeError::Shape {
            table: self.table_name.clone(),
            reason,
        })
    }
}

/// A `.npy` file of the C-ordered array `data` (its bytes, as `descr` says) of `shape`, as
/// `numpy.save` writes it. Fails only for a header longer than version 1.0 holds (64 KiB).
pub fn npy(descr: &str, shape: &[usize], data: &[u8]) -> Result<Vec<u8>, String> {
    // the tuple as Python's repr writes it: `()`, `(5,)`, `(2, 3)`
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let tuple = match dims.as_slice() {
        [one] => format!("({one},)"),
        _ => format!("({})", dims.join(", ")),
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {tuple}, }}");
    if let Some(first) = dims.first() {
        header.push_str(&" ".repeat(GROWTH_AXIS_MAX_DIGITS.saturating_sub(first.len())));
    }
    // padding so that the data starts at a multiple of 64: 1 to 64 spaces, then '\n'
    let unpadded = MAGIC.len() + 2 + header.len() + 1;
    let pad = ARRAY_ALIGN - unpadded % ARRAY_ALIGN;
    let len = u16::try_from(header.len() + pad + 1)
        .map_err(|_| format!("the .npy header of shape {tuple} is too long"))?;
    let mut out = Vec::with_capacity(unpadded + pad + data.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&len.to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend(std::iter::repeat_n(b' ', pad));
    out.push(b'\n');
    out.extend_from_slice(data);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The headers `numpy.save` (numpy 2.4.6) writes for `np.zeros((2, 3), '<f4')`,
    /// `np.array('abc')` and `np.zeros(256, 'u1')`: each 118 bytes after the length, the
    /// dictionary, the growth spaces (none for a 0-d array) and the alignment to 128.
    #[test]
    fn headers_as_numpy_writes_them() {
        for (descr, shape, dict, data) in [
            (
                "<f4",
                &[2usize, 3][..],
                "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }",
                24,
            ),
            (
                "<U3",
                &[][..],
                "{'descr': '<U3', 'fortran_order': False, 'shape': (), }",
                12,
            ),
            (
                "|u1",
                &[256][..],
                "{'descr': '|u1', 'fortran_order': False, 'shape': (256,), }",
                256,
            ),
        ] {
            let f = npy(descr, shape, &vec![7; data]).unwrap();
            assert_eq!(&f[..10], b"\x93NUMPY\x01\x00\x76\x00", "{dict}");
            let header = std::str::from_utf8(&f[10..128]).unwrap();
            assert_eq!(header, format!("{dict:<117}\n"));
            assert_eq!(f.len(), 128 + data);
            assert!(f[128..].iter().all(|&b| b == 7));
        }
    }
}
