//! Normalized-integer quantization, shared by the encoders that store UNORM8 or UNORM16
//! texels (KTX2, png-data, `h`, `rs`): a stored value v (already × scale) becomes the code
//! `round(v·(2ⁿ − 1))`, rounded to nearest with ties to even, which a sampler reads back as
//! `code/(2ⁿ − 1)`. The rounding error is at most half a step, `1/(2·(2ⁿ − 1))`.
//!
//! A value whose nearest code is not in `0..=2ⁿ − 1` — more than half a step below 0 or above
//! 1 — cannot be stored: that is an error ([`EncodeError::OutOfUnitRange`]), never a clamp. A
//! value within half a step of [0, 1] (quadrature's last bits above an exact 1, say) rounds to
//! the end code like any other value, within the same bound.

use super::EncodeError;
use crate::lut::Lut;
use crate::table::Storage;

/// The code of the stored value `v` in a storage with largest code `max` (255 or 65535):
/// `round(v·max)` (ties to even), or `None` when that is not a code (outside `0..=max`, or
/// `v` not finite).
pub fn code(v: f32, max: u32) -> Option<u16> {
    let c = (v as f64 * max as f64).round_ties_even();
    (c >= 0.0 && c <= max as f64).then_some(c as u16)
}

/// The value a sampler reads for `code`: `code / max`.
pub fn value(code: u16, max: u32) -> f64 {
    code as f64 / max as f64
}

/// The first texel of `lut` whose value `storage` (a UNORM storage) cannot hold: (channel,
/// texel indices `[x, y, z]`, value), in texel order.
pub fn first_unstorable(lut: &Lut, storage: Storage) -> Option<(usize, [usize; 3], f32)> {
    let max = storage.unorm_max()?;
    let nc = lut.channels.len().max(1);
    let (nx, ny) = (lut.dim(0), lut.dim(1));
    let i = lut.data.iter().position(|&v| code(v, max).is_none())?;
    let t = i / nc;
    Some((i % nc, [t % nx, (t / nx) % ny, t / (nx * ny)], lut.data[i]))
}

/// The codes of every stored value of `lut` (texel order, channels interleaved), or the error
/// naming the first value `storage` cannot hold. `storage` must be a UNORM storage.
pub fn codes(table: &str, lut: &Lut, storage: Storage) -> Result<Vec<u16>, EncodeError> {
    let Some(max) = storage.unorm_max() else {
        return Err(EncodeError::Shape {
            table: table.to_string(),
            reason: format!("{} is not a normalized-integer storage", storage.name()),
        });
    };
    if let Some((c, texel, v)) = first_unstorable(lut, storage) {
        let channel = lut
            .channels
            .get(c)
            .map_or(String::new(), |c| c.name.clone());
        if !v.is_finite() {
            return Err(EncodeError::NonFinite {
                table: table.to_string(),
                channel,
                texel,
                value: v as f64,
            });
        }
        return Err(EncodeError::OutOfUnitRange {
            table: table.to_string(),
            channel,
            texel: texel[..lut.axes.len().clamp(1, 3)].to_vec(),
            value: v as f64,
            storage: storage.name(),
            advice: advice(v as f64, channel_extreme(lut, c), 1.0, 0.5 / max as f64),
        });
    }
    Ok(lut
        .data
        .iter()
        .map(|&v| code(v, max).expect("checked"))
        .collect())
}

/// The channel's value farthest outside [0, 1] in the direction of `c`'s first bad value
/// (its largest value, or its smallest when that is negative).
pub(crate) fn channel_extreme(lut: &Lut, c: usize) -> (f64, f64) {
    let nc = lut.channels.len().max(1);
    lut.data
        .iter()
        .skip(c)
        .step_by(nc)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v as f64), hi.max(v as f64))
        })
}

/// What to do about a value `v` (stored units) that UNORM cannot hold, given the channel's
/// (smallest, largest) stored values, the table's current scale and the storage's half step
/// (values within it of [0, 1] round to the end codes).
pub(crate) fn advice(v: f64, (lo, hi): (f64, f64), scale: f64, half_step: f64) -> String {
    let n = crate::numfmt::num;
    let negative = format!(
        "a normalized-integer storage holds [0, 1] only and this channel reaches {}: store the \
         table as \"f16\" or \"f32\", or store a transform of the channel that stays in [0, 1] \
         (\"channels\")",
        n(lo)
    );
    if v < 0.0 {
        return negative;
    }
    let fit = format!(
        "the channel reaches {}: set the table's \"scale\" to {} or less (stored = value x \
         scale; the shader divides by it), or store it as \"f16\" or \"f32\"",
        n(hi),
        n(scale / hi)
    );
    if lo < -half_step {
        format!("{fit}; besides, {negative}")
    } else {
        fit
    }
}

/// `lut` with every value replaced by what a sampler reads back from its `storage` code
/// (`code/(2ⁿ − 1)` as f32): the table as stored. Float storages leave `lut` as it is.
pub fn quantized(table: &str, lut: &Lut, storage: Storage) -> Result<Lut, EncodeError> {
    let Some(max) = storage.unorm_max() else {
        return Ok(lut.clone());
    };
    let codes = codes(table, lut, storage)?;
    Ok(Lut {
        data: codes.iter().map(|&c| value(c, max) as f32).collect(),
        ..lut.clone()
    })
}

/// Per channel, the largest |code/(2ⁿ − 1) − v| over the texels of `lut` (stored units; 0
/// for the float storages and for values that cannot be stored).
pub fn max_rounding_error(lut: &Lut, storage: Storage) -> Vec<f64> {
    let nc = lut.channels.len();
    let mut out = vec![0.0f64; nc];
    let Some(max) = storage.unorm_max() else {
        return out;
    };
    for (i, &v) in lut.data.iter().enumerate() {
        if let Some(c) = code(v, max) {
            let e = (value(c, max) - v as f64).abs();
            out[i % nc] = out[i % nc].max(e);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_to_nearest_with_ties_to_even() {
        assert_eq!(code(0.0, 255), Some(0));
        assert_eq!(code(1.0, 255), Some(255));
        assert_eq!(code(0.5, 255), Some(128)); // 127.5: ties to even
        assert_eq!(code(0.5, 65535), Some(32768)); // 32767.5
        assert_eq!(code(-0.001, 255), Some(0)); // within half a step of 0
        assert_eq!(code(-0.003, 255), None); // -0.765: code -1
        assert_eq!(code(1.001, 255), Some(255)); // 255.255
        assert_eq!(code(1.003, 255), None); // 255.765
        assert_eq!(code(f32::NAN, 255), None);
        assert_eq!(code(f32::INFINITY, 65535), None);
        // every code is its own value's code
        for c in 0..=255u16 {
            assert_eq!(code(value(c, 255) as f32, 255), Some(c));
        }
        for c in (0..=65535u16).step_by(7) {
            assert_eq!(code(value(c, 65535) as f32, 65535), Some(c));
        }
    }
}
