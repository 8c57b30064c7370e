//! Resource guards: how much memory a bake will need, estimated from the requested sizes
//! before anything is allocated, and the check that refuses a bake over the limit
//! (`brdfbake bake --max-memory SIZE`) instead of letting it thrash or be killed.
//!
//! The estimate is deliberately an upper bound of what the pipeline holds at its peak: a
//! bake keeps every table's texels and every encoded file in memory until all are written
//! atomically ([`crate::pipeline`]), and while a table bakes it also holds one result per
//! texel (two small `Vec<f64>` of value and error estimate).

use crate::preset::{Format, Preset, PresetTable};
use crate::table::Storage;

/// The default `--max-memory`: 2 GiB.
pub const DEFAULT_MAX_MEMORY: u64 = 2 << 30;

/// Bytes per texel of the bake's per-texel results while a table bakes: two `Vec<f64>`
/// headers (2 × 24 bytes) and two heap blocks of at most 4 channels × 8 bytes each, which
/// the allocator rounds up with its own header (≤ 48 bytes each); 160 rounds that up.
const SCRATCH_PER_TEXEL: u64 = 160;

/// Bytes per value of the text formats (C header, Rust source): a value printed with its
/// separator takes at most ~16 characters (`-1.23456789e-12, ` style, or `0x3c00, ` for
/// half), and the `String` may have grown to twice its length while being built.
const TEXT_BYTES_PER_VALUE: u64 = 32;

/// Fixed allowance per table: sidecar JSON, headers, shader snippets, small vectors.
const PER_TABLE: u64 = 1 << 20;

/// The estimated peak memory of baking one table into `formats`, split into what stays
/// until the write (`kept`: texels and encoded files) and what is freed when the table is
/// done (`scratch`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Estimate {
    /// Texels of all tables.
    pub texels: u64,
    /// Bytes held until the files are written.
    pub kept: u64,
    /// Largest transient allocation of one table's bake.
    pub scratch: u64,
}

impl Estimate {
    /// Estimated peak bytes: everything kept plus the largest table's scratch.
    pub fn peak(&self) -> u64 {
        self.kept.saturating_add(self.scratch)
    }
}

/// Estimates one table (see [`Estimate`]); `formats` are the formats it is written in.
pub fn estimate_table(t: &PresetTable, formats: &[Format]) -> Estimate {
    let texels = t
        .spec
        .axes
        .iter()
        .fold(1u64, |n, a| n.saturating_mul(a.size as u64));
    let channels = crate::table::channels(&t.spec).len() as u64;
    let stored = match t.spec.storage {
        Storage::F32 => 4,
        Storage::F16 => 2,
    };
    // the Lut's f32 texels
    let mut per_texel: u64 = channels * 4;
    for f in formats {
        per_texel += match f {
            // encoder buffer + the encoded file (KTX2 pads 3 channels to 4)
            Format::Exr => 2 * channels * stored,
            Format::Ktx2 => 2 * channels.max(if channels == 3 { 4 } else { 1 }) * stored,
            // 16-bit grey image per channel + 16-bit RGB false colour, raw and compressed
            Format::Png => 2 * (channels * 2 + 6),
            Format::H | Format::Rs => channels * TEXT_BYTES_PER_VALUE,
            // a lookup function: no texels
            Format::Glsl | Format::Hlsl | Format::Wgsl => 0,
        };
    }
    Estimate {
        texels,
        kept: texels.saturating_mul(per_texel).saturating_add(PER_TABLE),
        scratch: texels.saturating_mul(SCRATCH_PER_TEXEL),
    }
}

/// Estimates a whole invocation: every table of every preset, each in `formats` when
/// given (the `--format` override) or in its own.
pub fn estimate(presets: &[Preset], formats: Option<&[Format]>) -> Estimate {
    let mut total = Estimate::default();
    for p in presets {
        for t in &p.tables {
            let e = estimate_table(t, formats.unwrap_or(&t.formats));
            total.texels = total.texels.saturating_add(e.texels);
            total.kept = total.kept.saturating_add(e.kept);
            total.scratch = total.scratch.max(e.scratch);
        }
    }
    total
}

/// `bytes` for people: `1.5 GiB`, `12.0 MiB`, `512 bytes`.
pub fn human(bytes: u64) -> String {
    const UNITS: [(&str, u64); 3] = [("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)];
    for (name, size) in UNITS {
        if bytes >= size {
            return format!("{:.1} {name}", bytes as f64 / size as f64);
        }
    }
    format!("{bytes} bytes")
}

/// Parses a memory size: a whole number of bytes with an optional unit `K`, `M`, `G`, `T`
/// (powers of 1024; `KiB`, `MiB`, ... and `KB`, `MB`, ... are read the same), e.g. `4GiB`,
/// `512M`, `1000000`. Zero is refused.
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t.find(|c: char| !c.is_ascii_digit()).unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let accepted = "a whole number of bytes with an optional unit K, M, G or T (powers of 1024), e.g. 4GiB or 512M";
    if num.is_empty() {
        return Err(format!("{s:?} is not a size: expected {accepted}"));
    }
    let n: u64 = num
        .parse()
        .map_err(|_| format!("{s:?} is too large a size (at most {} bytes)", u64::MAX))?;
    let shift = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 0,
        "k" | "kb" | "kib" => 10,
        "m" | "mb" | "mib" => 20,
        "g" | "gb" | "gib" => 30,
        "t" | "tb" | "tib" => 40,
        _ => return Err(format!("{s:?}: unknown unit {unit:?}; expected {accepted}")),
    };
    let bytes = n
        .checked_mul(1u64 << shift)
        .ok_or_else(|| format!("{s:?} is too large a size (at most {} bytes)", u64::MAX))?;
    if bytes == 0 {
        return Err(format!("{s:?}: the limit must be more than 0 bytes"));
    }
    Ok(bytes)
}

/// Refuses `est` over `limit` with a message giving the estimate and how to raise the limit.
pub fn check(est: &Estimate, limit: u64) -> Result<(), String> {
    if est.peak() <= limit {
        return Ok(());
    }
    Err(format!(
        "this bake needs an estimated {} of memory ({} texels in all; texels and encoded files are kept until \
         the atomic write), more than the limit of {}: raise it with --max-memory SIZE (e.g. --max-memory {}), \
         or bake fewer or smaller tables or fewer formats",
        human(est.peak()),
        est.texels,
        human(limit),
        suggest(est.peak())
    ))
}

/// A round `--max-memory` value at least `bytes`: whole GiB, or whole MiB below 1 GiB.
fn suggest(bytes: u64) -> String {
    if bytes >= 1 << 30 {
        format!("{}GiB", bytes.div_ceil(1 << 30))
    } else {
        format!("{}MiB", bytes.div_ceil(1 << 20).max(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_units() {
        assert_eq!(parse_size("1000").unwrap(), 1000);
        assert_eq!(parse_size("4GiB").unwrap(), 4 << 30);
        assert_eq!(parse_size("512M").unwrap(), 512 << 20);
        assert_eq!(parse_size("3 kb").unwrap(), 3 << 10);
        assert_eq!(parse_size("1T").unwrap(), 1 << 40);
        for bad in [
            "",
            "GiB",
            "-1",
            "1.5G",
            "12 parsecs",
            "0",
            "0M",
            "99999999999999999999",
        ] {
            assert!(parse_size(bad).is_err(), "{bad:?} accepted");
        }
        // overflow of the unit multiplication is refused, not wrapped
        assert!(parse_size("17179869184G").is_err());
    }

    #[test]
    fn human_sizes() {
        assert_eq!(human(512), "512 bytes");
        assert_eq!(human(3 << 20), "3.0 MiB");
        assert_eq!(human(3 << 29), "1.5 GiB");
    }

    #[test]
    fn suggestion_is_at_least_the_estimate() {
        for b in [1u64, 1 << 20, (1 << 20) + 1, 5 << 29, (3 << 30) + 7] {
            let s = suggest(b);
            assert!(parse_size(&s).unwrap() >= b, "{b}: {s}");
        }
    }
}
