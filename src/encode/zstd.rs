//! Zstandard frames for KTX2 supercompression, by the pure-Rust `ruzstd` encoder at its
//! `Fastest` level (about zstd's level 1): no threads, no dictionary, no timestamps, so the
//! same texels always give the same bytes. Inflation (for `inspect`, `probe`, `verify`) is
//! bounded by the size the KTX2 level index states, so a hostile file cannot make it allocate
//! more than the texture it claims to be.

use std::io::Read;

/// One Zstandard frame holding `data`.
pub fn compress(data: &[u8]) -> Vec<u8> {
    ruzstd::encoding::compress_to_vec(data, ruzstd::encoding::CompressionLevel::Fastest)
}

/// The bytes of the Zstandard frame(s) in `frame`, which must inflate to exactly `expected`
/// bytes: more or fewer is an error, as is a malformed frame.
pub fn decompress(frame: &[u8], expected: usize) -> Result<Vec<u8>, String> {
    let mut decoder = ruzstd::decoding::StreamingDecoder::new(frame)
        .map_err(|e| format!("not a Zstandard frame ({e})"))?;
    let mut out = Vec::new();
    out.try_reserve_exact(expected)
        .map_err(|_| format!("cannot allocate the {expected} bytes the level index states"))?;
    // one byte past what is expected shows a frame that inflates to more
    let limit = expected as u64 + 1;
    (&mut decoder)
        .take(limit)
        .read_to_end(&mut out)
        .map_err(|e| format!("a malformed Zstandard frame ({e})"))?;
    if out.len() != expected {
        return Err(format!(
            "the Zstandard frame inflates to {}{} bytes, the level index states {expected}",
            out.len().min(expected + 1),
            if out.len() > expected { " or more" } else { "" }
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_size_checks() {
        let data: Vec<u8> = (0..10_000u32).flat_map(|i| (i / 7).to_le_bytes()).collect();
        let frame = compress(&data);
        assert!(frame.len() < data.len() / 2, "{} bytes", frame.len());
        assert_eq!(compress(&data), frame, "deterministic");
        assert_eq!(decompress(&frame, data.len()).unwrap(), data);
        assert!(decompress(&frame, data.len() - 1)
            .unwrap_err()
            .contains("or more"));
        assert!(decompress(&frame, data.len() + 1).is_err());
        assert!(decompress(&data[..64], 64).is_err());
    }
}
