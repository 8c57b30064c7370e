//! Content digests that make every output checkable: the sidecar lists the SHA-256 of each
//! file it describes (`digests`) and seals itself (`sidecar_digest`: the SHA-256 of its own
//! bytes with that value written as 64 zeros). A reader that checks both knows the texture
//! is byte for byte what the bake wrote beside this sidecar, and the sidecar byte for byte
//! what the bake wrote: any flipped byte, an edited field, a file copied over from another
//! table, or a set left half old and half new by an interrupted bake is found and named.

use serde_json::{Map, Value};
use sha2::{Digest, Sha256};

/// The sidecar field holding the sidecar's own digest.
pub const SEAL_FIELD: &str = "sidecar_digest";
/// The sidecar field mapping each file name to its digest.
pub const DIGESTS_FIELD: &str = "digests";

const PREFIX: &str = "sha256:";
const ZEROS: &str = "0000000000000000000000000000000000000000000000000000000000000000";

/// `sha256:<hex>` of `bytes`.
pub fn sha256(bytes: &[u8]) -> String {
    let d = Sha256::digest(bytes);
    let mut s = String::with_capacity(PREFIX.len() + 64);
    s.push_str(PREFIX);
    for b in d {
        s.push_str(&format!("{b:02x}"));
    }
    s
}

/// The text the seal is searched by: `"sidecar_digest": "sha256:`, as pretty-printed JSON
/// writes it.
fn seal_key() -> String {
    format!("\"{SEAL_FIELD}\": \"{PREFIX}")
}

/// Serializes a sidecar (pretty JSON and a final newline) with `digests` (file name →
/// bytes' digest) added, then sealed. Any earlier `digests`/seal fields are replaced.
pub fn seal(mut sidecar: Value, files: &[(&str, &[u8])]) -> Vec<u8> {
    let obj = sidecar.as_object_mut().expect("a sidecar is a JSON object");
    obj.remove(DIGESTS_FIELD);
    obj.remove(SEAL_FIELD);
    let digests: Map<String, Value> = files
        .iter()
        .map(|(name, bytes)| (name.to_string(), Value::String(sha256(bytes))))
        .collect();
    obj.insert(DIGESTS_FIELD.into(), Value::Object(digests));
    obj.insert(SEAL_FIELD.into(), Value::String(format!("{PREFIX}{ZEROS}")));
    let mut text = serde_json::to_string_pretty(&sidecar).expect("a sidecar serializes");
    text.push('\n');
    let digest = sha256(text.as_bytes());
    let placeholder = format!("{}{ZEROS}", seal_key());
    debug_assert_eq!(text.matches(&placeholder).count(), 1);
    text.replacen(
        &placeholder,
        &format!("{}{}", seal_key(), &digest[PREFIX.len()..]),
        1,
    )
    .into_bytes()
}

/// Why a sidecar or a file does not match.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Mismatch {
    #[error("it has no {SEAL_FIELD} (written by an older brdfbake, or damaged): bake it again")]
    Unsealed,
    #[error("it holds {SEAL_FIELD} more than once: it was edited")]
    SealedTwice,
    #[error("its bytes do not match its {SEAL_FIELD}: it was edited or damaged after the bake")]
    SealBroken,
    #[error("its sidecar lists no digest for it (written by another bake): bake it again")]
    NotListed,
    #[error(
        "its bytes do not match the digest in its sidecar: it was replaced, damaged, or left from \
         another bake (an interrupted one?): bake it again"
    )]
    FileChanged,
}

/// Checks a sidecar's bytes against its seal.
pub fn check_seal(bytes: &[u8]) -> Result<(), Mismatch> {
    let key = seal_key();
    let key = key.as_bytes();
    let found: Vec<usize> = bytes
        .windows(key.len())
        .enumerate()
        .filter(|(_, w)| *w == key)
        .map(|(i, _)| i + key.len())
        .collect();
    let at = match found.as_slice() {
        // the field is there but not as the bake wrote it: reformatted or edited
        [] if contains(bytes, format!("\"{SEAL_FIELD}\"").as_bytes()) => {
            return Err(Mismatch::SealBroken)
        }
        [] => return Err(Mismatch::Unsealed),
        [at] => *at,
        _ => return Err(Mismatch::SealedTwice),
    };
    let Some(hex) = bytes.get(at..at + 64) else {
        return Err(Mismatch::SealBroken);
    };
    let mut zeroed = bytes.to_vec();
    zeroed[at..at + 64].copy_from_slice(ZEROS.as_bytes());
    let want = sha256(&zeroed);
    if want.as_bytes()[PREFIX.len()..] == *hex {
        Ok(())
    } else {
        Err(Mismatch::SealBroken)
    }
}

fn contains(hay: &[u8], needle: &[u8]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

/// Checks a file's bytes against the digest its (sealed) sidecar lists for `name`.
pub fn check_file(sidecar: &Value, name: &str, bytes: &[u8]) -> Result<(), Mismatch> {
    let listed = sidecar
        .get(DIGESTS_FIELD)
        .and_then(|d| d.get(name))
        .and_then(Value::as_str)
        .ok_or(Mismatch::NotListed)?;
    if listed == sha256(bytes) {
        Ok(())
    } else {
        Err(Mismatch::FileChanged)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn sealed() -> (Vec<u8>, Vec<u8>) {
        let tex = b"texture bytes".to_vec();
        let v = json!({"schema": "brdfbake.lut/1", "files": {"exr": "t.exr"}, "x": [1.5, 2]});
        (seal(v, &[("t.exr", &tex)]), tex)
    }

    #[test]
    fn sealed_sidecar_and_file_check() {
        let (bytes, tex) = sealed();
        assert_eq!(check_seal(&bytes), Ok(()));
        let v: Value = serde_json::from_slice(&bytes).unwrap();
        assert_eq!(check_file(&v, "t.exr", &tex), Ok(()));
        assert_eq!(
            check_file(&v, "t.exr", b"other bytes"),
            Err(Mismatch::FileChanged)
        );
        assert_eq!(check_file(&v, "u.exr", &tex), Err(Mismatch::NotListed));
        // sealing is deterministic and idempotent
        assert_eq!(seal(v, &[("t.exr", &tex)]), bytes);
    }

    /// Every single-byte change of a sealed sidecar is found (by the seal, or because the
    /// seal can no longer be found or read).
    #[test]
    fn every_flipped_byte_breaks_the_seal() {
        let (bytes, _) = sealed();
        for i in 0..bytes.len() {
            for x in [0x01u8, 0x20, 0x80, 0xff] {
                let mut b = bytes.clone();
                b[i] ^= x;
                assert!(check_seal(&b).is_err(), "byte {i} ^ {x:#x} went unnoticed");
            }
        }
    }

    #[test]
    fn unsealed_and_doubly_sealed() {
        assert_eq!(check_seal(b"{}"), Err(Mismatch::Unsealed));
        let (bytes, _) = sealed();
        let mut twice = bytes.clone();
        twice.extend_from_slice(&bytes);
        assert_eq!(check_seal(&twice), Err(Mismatch::SealedTwice));
    }
}
