//! `png-rgbd`: a three-channel table as Babylon.js' RGBD-encoded 8-bit RGBA PNG, the
//! encoding of its environment BRDF lookup table (`brdfTextureTools.ts`,
//! `correlatedMSBRDF_RGBD.png`), which Babylon decodes with `fromRGBD`:
//! `value = toLinearSpace(rgb) / a = (c/255)^2.2 / (a/255)` (its default `toLinearSpace`
//! is the power 2.2, `helperFunctions.fx`).
//!
//! Encoding, as Babylon's `toRGBD` does it: per texel, with m the largest of R, G, B,
//! `D = min(floor(max(255/m, 1))/255, 1)` (so D = 1 while m ≤ 1: values in [0, 1] are plain
//! gamma-2.2 codes), each colour code `round(255 (v·D)^(1/2.2))` and the alpha code
//! `round(255 D)`. It holds values in [0, 255]; a negative value or one above 255 is an
//! error. Decoded, a value is off by at most half a code through the power curve, divided by
//! D: `((c + ½)/255)^2.2 − (c/255)^2.2` over `a/255` — 4.3e-3 at values near 1, far more
//! where D < 1 ([`max_rounding`], stated in the sidecar's `storage.rgbd`).
//!
//! Layout as `png-data`: width = nx, height = ny (slices of a 3D table stacked downward),
//! the top row is table row y = 0 (Babylon uploads it with `invertY = false`: row 0 at
//! v = 0), no colour-space chunk.

use super::png::write_png;
use super::{EncodeError, Encoder};
use crate::lut::Lut;
use ::png::{BitDepth, ColorType};

/// The exponent of Babylon's default `toLinearSpace`.
pub const GAMMA: f64 = 2.2;

/// The note every RGBD PNG carries (readback tells it from png-data by it).
pub const NOTE: &str =
    "RGBD: value = (c/255)^2.2 / (a/255) (Babylon.js fromRGBD), not UNORM texels";

/// Encodes a three-channel table as an RGBD PNG (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PngRgbd {
    /// The table's name: used in titles and error messages.
    pub table_name: String,
}

/// The RGBA codes of one texel's (R, G, B), or why they cannot be encoded.
pub fn encode_texel(rgb: [f64; 3]) -> Result<[u8; 4], String> {
    if let Some(v) = rgb
        .iter()
        .find(|v| !(v.is_finite() && (0.0..=255.0).contains(*v)))
    {
        return Err(format!("RGBD holds values in [0, 255], the table has {v}"));
    }
    let m = rgb.iter().cloned().fold(0.0, f64::max);
    let d = if m > 0.0 {
        ((255.0 / m).max(1.0).floor() / 255.0).min(1.0)
    } else {
        1.0
    };
    let code = |x: f64| (255.0 * x.clamp(0.0, 1.0)).round() as u8;
    Ok([
        code((rgb[0] * d).powf(1.0 / GAMMA)),
        code((rgb[1] * d).powf(1.0 / GAMMA)),
        code((rgb[2] * d).powf(1.0 / GAMMA)),
        code(d),
    ])
}

/// Babylon's decoding of one RGBA texel: (R, G, B) values (alpha 0: not a valid RGBD
/// texel, `None`).
pub fn decode_texel(c: [u8; 4]) -> Option<[f64; 3]> {
    if c[3] == 0 {
        return None;
    }
    let d = c[3] as f64 / 255.0;
    let v = |k: usize| (c[k] as f64 / 255.0).powf(GAMMA) / d;
    Some([v(0), v(1), v(2)])
}

/// The most a decoded value of colour code `c` and alpha code `a` can differ from the value
/// it was encoded from: half a code either way through the power curve, over D.
pub fn rounding(c: u8, a: u8) -> f64 {
    let x = c as f64 / 255.0;
    let h = 0.5 / 255.0;
    let up = ((x + h).min(1.0)).powf(GAMMA) - x.powf(GAMMA);
    let down = x.powf(GAMMA) - (x - h).max(0.0).powf(GAMMA);
    up.max(down) / (a.max(1) as f64 / 255.0)
}

/// Per channel, the largest [`rounding`] over the texels of `lut` as encoded.
pub fn max_rounding(lut: &Lut) -> Vec<f64> {
    let mut worst = vec![0.0f64; 3];
    for t in lut.data.chunks_exact(3) {
        let rgb = [t[0] as f64, t[1] as f64, t[2] as f64];
        if let Ok(c) = encode_texel(rgb) {
            for k in 0..3 {
                worst[k] = worst[k].max(rounding(c[k], c[3]));
            }
        }
    }
    worst
}

impl Encoder for PngRgbd {
    fn extension(&self) -> &'static str {
        "png"
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        super::source::check_table(&self.table_name, lut)?;
        let shape = |reason: String| EncodeError::Shape {
            table: self.table_name.clone(),
            reason,
        };
        let nc = lut.channels.len();
        if nc != 3 {
            return Err(shape(format!(
                "png-rgbd stores three channels (R, G, B; D goes in alpha), the table has {nc}"
            )));
        }
        let (w, h) = (lut.dim(0), lut.dim(1) * lut.dim(2));
        if w > u32::MAX as usize / 2 || h > u32::MAX as usize / 2 {
            return Err(shape("the table is too large for a PNG image".into()));
        }
        let mut data = Vec::with_capacity(w * h * 4);
        for (i, t) in lut.data.chunks_exact(3).enumerate() {
            let c = encode_texel([t[0] as f64, t[1] as f64, t[2] as f64])
                .map_err(|m| shape(format!("texel {i}: {m}")))?;
            data.extend_from_slice(&c);
        }
        let names: Vec<&str> = lut.channels.iter().map(|c| c.name.as_str()).collect();
        let mut text = vec![
            (
                "Title".to_string(),
                format!("brdfbake table {} (png-rgbd)", self.table_name),
            ),
            (
                "Description".to_string(),
                format!(
                    "the texels of brdfbake table {} RGBD-encoded as Babylon.js decodes them: \
                     value = (c/255)^2.2 / (a/255); linear data, not an image to colour-manage",
                    self.table_name
                ),
            ),
            ("Software".to_string(), "brdfbake".to_string()),
            ("note".to_string(), NOTE.to_string()),
            (
                "layout".to_string(),
                format!(
                    "R = {}, G = {}, B = {}, A = D; the top row is y = 0 (the first coordinate of axis 1), x = 0 the left column",
                    names[0], names[1], names[2]
                ),
            ),
        ];
        text.extend(attributes.iter().cloned());
        write_png(
            (w as u32, h as u32),
            ColorType::Rgba,
            BitDepth::Eight,
            &text,
            &data,
            &|e| shape(format!("PNG encoding failed: {e}")),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Texels of Babylon's shipped table (tests/data/engines/babylon): encoding their decoded
    /// values gives their codes back (not at every texel: a decoded maximum of exactly
    /// 255/a sits on the edge of `floor`, where f64 may fall either side), and every value in
    /// [0, 255] decodes within the stated rounding.
    #[test]
    fn round_trip_within_the_stated_rounding() {
        for c in [[46u8, 46, 238, 6], [0, 255, 3, 255], [45, 238, 131, 255]] {
            let v = decode_texel(c).unwrap();
            assert_eq!(encode_texel(v).unwrap(), c, "{v:?}");
        }
        let mut x = 0.0f64;
        while x <= 255.0 {
            for rgb in [[x, x / 3.0, 0.0], [0.0, x, 1e-4 * x]] {
                let c = encode_texel(rgb).unwrap();
                let back = decode_texel(c).unwrap();
                for k in 0..3 {
                    let r = rounding(c[k], c[3]);
                    assert!(
                        (back[k] - rgb[k]).abs() <= r * (1.0 + 1e-12),
                        "{rgb:?} -> {c:?} -> {back:?}: channel {k} off by more than {r}"
                    );
                }
            }
            x = if x < 2.0 { x + 0.01 } else { x * 1.07 };
        }
        // docs/engines.md: half a code at values near 1 (D = 1) is 4.3e-3 after decoding
        assert_eq!(format!("{:.1e}", rounding(255, 255)), "4.3e-3");
        assert!(encode_texel([256.0, 0.0, 0.0]).is_err());
        assert!(encode_texel([-1e-9, 0.0, 0.0]).is_err());
        assert!(encode_texel([f64::NAN, 0.0, 0.0]).is_err());
        assert_eq!(decode_texel([1, 2, 3, 0]), None);
    }
}
