//! `npz`: the texels and the header attributes as a NumPy `.npz` archive, which
//! `numpy.load` reads without brdfbake: a ZIP archive (stored, uncompressed, as
//! `numpy.savez` writes) of `.npy` files ([`super::npy`]):
//!
//! - `TABLE.npy` (key `TABLE`, the table's name): the texels, the array of [`super::bin`];
//! - `brdfbake.attributes.npy` (key `brdfbake.attributes`, which no table name can be: table
//!   names have no dots): the header attributes the EXR and KTX2 files carry (schema,
//!   version, input hash, preset, table, kind, model, scale, one line per axis) as one JSON
//!   object in a 0-d unicode array: `json.loads(str(npz["brdfbake.attributes"]))`.
//!
//! Determinism: entries in that order, every timestamp 1980-01-01 00:00 (the earliest a ZIP
//! holds), no extra fields, so the same table gives the same bytes. The archive format is
//! PKWARE's APPNOTE.TXT (local file headers, central directory, end of central directory
//! record; no ZIP64: an archive stays below 4 GiB).

use super::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::table::Storage;

/// Encodes a table as a `.npz` archive (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Npz {
    pub storage: Storage,
    /// The table's name: the texels' key, and used in error messages.
    pub table_name: String,
}

/// What a `.npz` file is, for the sidecar.
pub const FILE_NOTE: &str = "TABLE.npz: a NumPy .npz archive (numpy.load(path)) of the array under the table's name and of the header attributes as a JSON object under brdfbake.attributes";

/// The key of the header attributes.
pub const ATTRIBUTES_KEY: &str = "brdfbake.attributes";

impl Encoder for Npz {
    fn extension(&self) -> &'static str {
        "npz"
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        let shape = |reason: String| EncodeError::Shape {
            table: self.table_name.clone(),
            reason,
        };
        let texels = super::bin::texels(&self.table_name, lut, self.storage)?;
        let texels = super::npy::npy(
            super::bin::dtype(self.storage),
            &super::bin::shape(lut),
            &texels,
        )
        .map_err(shape)?;
        let attrs: serde_json::Map<String, serde_json::Value> = attributes
            .iter()
            .map(|(k, v)| (k.clone(), serde_json::Value::String(v.clone())))
            .collect();
        let text = serde_json::to_string(&attrs).expect("serializable");
        // a 0-d numpy unicode array: UTF-32LE code points, dtype '<U{number of code points}'
        let utf32: Vec<u8> = text
            .chars()
            .flat_map(|c| (c as u32).to_le_bytes())
            .collect();
        let attrs =
            super::npy::npy(&format!("<U{}", text.chars().count()), &[], &utf32).map_err(shape)?;
        zip_stored(&[
            (format!("{}.npy", self.table_name), texels),
            (format!("{ATTRIBUTES_KEY}.npy"), attrs),
        ])
        .map_err(shape)
    }
}

/// MS-DOS date of 1980-01-01 (day 1, month 1, year 1980 + 0); the time is 00:00:00.
const DOS_DATE_1980: u16 = (1 << 5) | 1;
/// Version needed to extract (and made by, MS-DOS attributes): 2.0, as for stored entries.
const ZIP_VERSION: u16 = 20;

/// A ZIP archive of `entries` (name, bytes), stored without compression.
fn zip_stored(entries: &[(String, Vec<u8>)]) -> Result<Vec<u8>, String> {
    let u32_of = |n: usize, what: &str| {
        u32::try_from(n).map_err(|_| format!("the .npz archive is too large ({what} over 4 GiB)"))
    };
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, bytes) in entries {
        let offset = u32_of(out.len(), "an offset")?;
        let size = u32_of(bytes.len(), "an entry")?;
        let crc = crc32fast::hash(bytes);
        let name_len = u16::try_from(name.len()).map_err(|_| "an entry name is too long")?;
        // local file header
        for field in [
            &0x0403_4b50u32.to_le_bytes()[..],
            &ZIP_VERSION.to_le_bytes(),
            &0u16.to_le_bytes(), // flags
            &0u16.to_le_bytes(), // stored
            &0u16.to_le_bytes(), // time 00:00:00
            &DOS_DATE_1980.to_le_bytes(),
            &crc.to_le_bytes(),
            &size.to_le_bytes(), // compressed
            &size.to_le_bytes(), // uncompressed
            &name_len.to_le_bytes(),
            &0u16.to_le_bytes(), // extra field length
            name.as_bytes(),
        ] {
            out.extend_from_slice(field);
        }
        out.extend_from_slice(bytes);
        // its central directory header
        for field in [
            &0x0201_4b50u32.to_le_bytes()[..],
            &ZIP_VERSION.to_le_bytes(), // made by
            &ZIP_VERSION.to_le_bytes(), // needed
            &0u16.to_le_bytes(),
            &0u16.to_le_bytes(),
            &0u16.to_le_bytes(),
            &DOS_DATE_1980.to_le_bytes(),
            &crc.to_le_bytes(),
            &size.to_le_bytes(),
            &size.to_le_bytes(),
            &name_len.to_le_bytes(),
            &0u16.to_le_bytes(), // extra field length
            &0u16.to_le_bytes(), // comment length
            &0u16.to_le_bytes(), // disk number
            &0u16.to_le_bytes(), // internal attributes
            &0u32.to_le_bytes(), // external attributes
            &offset.to_le_bytes(),
            name.as_bytes(),
        ] {
            central.extend_from_slice(field);
        }
    }
    let count = u16::try_from(entries.len()).map_err(|_| "too many entries")?;
    let cd_offset = u32_of(out.len(), "an offset")?;
    let cd_size = u32_of(central.len(), "the directory")?;
    out.extend_from_slice(&central);
    // end of central directory record
    for field in [
        &0x0605_4b50u32.to_le_bytes()[..],
        &0u16.to_le_bytes(), // this disk
        &0u16.to_le_bytes(), // the directory's disk
        &count.to_le_bytes(),
        &count.to_le_bytes(),
        &cd_size.to_le_bytes(),
        &cd_offset.to_le_bytes(),
        &0u16.to_le_bytes(), // comment length
    ] {
        out.extend_from_slice(field);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The structure of a two-entry archive: each entry's local header and stored bytes where
    /// the central directory says, the CRC-32 of the bytes (the check value of "123456789"
    /// is 0xCBF43926), and the end record pointing at the directory.
    #[test]
    fn stored_archive_structure() {
        let entries = vec![
            ("a.npy".to_string(), b"123456789".to_vec()),
            ("b.npy".to_string(), Vec::new()),
        ];
        let z = zip_stored(&entries).unwrap();
        let u16_at = |o: usize| u16::from_le_bytes([z[o], z[o + 1]]) as usize;
        let u32_at = |o: usize| u32::from_le_bytes(z[o..o + 4].try_into().unwrap()) as usize;
        let end = z.len() - 22;
        assert_eq!(u32_at(end), 0x0605_4b50);
        assert_eq!(u16_at(end + 10), 2);
        let mut cd = u32_at(end + 16);
        assert_eq!(cd + u32_at(end + 12), end);
        for (name, bytes) in &entries {
            assert_eq!(u32_at(cd), 0x0201_4b50);
            let (crc, size, n) = (u32_at(cd + 16), u32_at(cd + 24), u16_at(cd + 28));
            assert_eq!(&z[cd + 46..cd + 46 + n], name.as_bytes());
            assert_eq!(crc as u32, crc32fast::hash(bytes));
            let local = u32_at(cd + 42);
            assert_eq!(u32_at(local), 0x0403_4b50);
            let data = local + 30 + u16_at(local + 26);
            assert_eq!(&z[data..data + size], &bytes[..]);
            cd += 46 + n;
        }
        assert_eq!(crc32fast::hash(b"123456789"), 0xCBF4_3926);
    }
}
