//! Reading a table as an engine ships it: the `shipped` description of an engine preset's
//! table (what file format, which array, which channels, which row order) and the decoders of
//! those formats. Pure functions of the file's bytes; the file is read by
//! [`crate::input::read_regular`].
//!
//! The shipped texels are read into the preset table's *stored* layout (its `axis_order`):
//! texel `(x, y, z)` with x fastest, as brdfbake writes the table, so that a shipped value and
//! brdfbake's value at the same index mean the same thing.

use serde::Deserialize;

/// Where a shipped table comes from (an engine preset's `source`): what a reader needs to
/// find the original and its licence.
#[derive(Clone, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Source {
    /// The engine or library (`Cycles`, `Blender EEVEE`, `three.js`).
    pub engine: String,
    /// The table's name there (`table_ggx_E`).
    pub table: String,
    /// Repository, path in it, and the commit or release the facts were read at.
    pub repository: String,
    pub path: String,
    pub commit: String,
    pub licence: String,
    /// The generator and its estimator, as far as it is known.
    #[serde(default)]
    pub generator: Option<String>,
    /// How the engine samples the table (its lookup).
    #[serde(default)]
    pub lookup: Option<String>,
    #[serde(default)]
    pub notes: Option<String>,
}

/// How an engine's file holds the table (the preset table's `shipped` field).
#[derive(Clone, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Shipped {
    /// The file in the engine's source tree, for messages and the report
    /// (`intern/cycles/scene/shader.tables`).
    #[serde(default)]
    pub file: Option<String>,
    pub format: ShippedFormat,
    /// `text`: the name of the array to read when the file holds several (`table_ggx_E`);
    /// the values are those between the first bracket after the name and its match.
    /// Without it every number of the file is read.
    #[serde(default)]
    pub symbol: Option<String>,
    /// `text`: how the numbers are written (default `float`).
    #[serde(default)]
    pub values: Option<ShippedValues>,
    /// What each channel of the file holds: a stored channel's name, or `-` for one that is
    /// not compared (glTF's `lut_ggx.png` has R = A, G = B and an unused B).
    pub channels: Vec<String>,
    /// `texel` (default): channels interleaved per texel; `plane`: all texels of channel 0,
    /// then of channel 1, … (Cycles' `table_sheen_ltc`).
    #[serde(default)]
    pub interleave: Option<Interleave>,
    /// The file's first row is the table's last (axis-1 texel N − 1 first: an image stored
    /// top-down whose texture coordinate v = 0 is its bottom row).
    #[serde(default)]
    pub flip_y: bool,
    /// How the stored numbers map to values: `linear` (default), or `srgb`: the values were
    /// written through the sRGB transfer function and are decoded with its inverse.
    #[serde(default)]
    pub decode: Option<Decode>,
    /// Leading values of the array to skip (an array holding several tables in a row).
    #[serde(default)]
    pub offset: usize,
}

/// The file formats `compare` reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShippedFormat {
    /// Numbers in text: a C/C++/GLSL/JS array (`static const float t[] = {1.0f, …};`,
    /// `new Uint16Array([0x3c00, …])`) or plain text; `//`, `/* */` and `#`-line comments
    /// are skipped.
    Text,
    /// A PNG of 8 or 16 bits per channel, grey, grey + alpha, RGB or RGBA; values / (2ⁿ − 1).
    Png,
    /// An OpenEXR file of half or float channels, read in the channel order the file lists.
    Exr,
    /// Raw little-endian 32-bit floats and nothing else (nvdiffrec's `bsdf_256_256.bin`):
    /// exactly the table's values (after `offset` skipped ones), no more.
    Bin,
}

/// How the numbers of a `text` file encode values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShippedValues {
    /// Decimal numbers (`0.25`, `1.0f`, `2.5e-3`).
    Float,
    /// IEEE half-float bit patterns (`0x3c00` or decimal).
    HalfBits,
    /// 8-bit normalized integers: value = n / 255.
    Unorm8,
    /// 16-bit normalized integers: value = n / 65535.
    Unorm16,
}

/// How channels are laid out in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Interleave {
    Texel,
    Plane,
}

/// The transfer function the shipped values went through.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Decode {
    Linear,
    Srgb,
}

/// A shipped table read into the stored layout: `values[(texel)·nc + c]` for the file's
/// channels `c`, texel index `(z·ny + y)·nx + x`.
#[derive(Clone, Debug, PartialEq)]
pub struct ShippedTable {
    /// The file's channels (as [`Shipped::channels`] names them).
    pub channels: Vec<String>,
    pub values: Vec<f64>,
    /// The quantization step of the stored numbers where they are integers (1/255, 1/65535),
    /// or the half-float spacing near 1 (2⁻¹¹), or 0 for printed decimals (whose printed
    /// precision the caller states).
    pub step: f64,
}

impl Shipped {
    /// Checks the description against the stored table: channel names, and that the format
    /// takes the given fields.
    pub fn validate(&self, stored_channels: &[String]) -> Result<(), String> {
        if self.channels.is_empty() {
            return Err("channels: list what each channel of the file holds (a channel of the table, or \"-\")".into());
        }
        for (k, c) in self.channels.iter().enumerate() {
            if c != "-" && !stored_channels.contains(c) {
                return Err(format!(
                    "channels[{k}]: {c:?} is not a channel of the table (its channels: {}; \"-\" skips a file channel)",
                    stored_channels.join(", ")
                ));
            }
            if c != "-" && self.channels[..k].contains(c) {
                return Err(format!("channels[{k}]: {c:?} is listed twice"));
            }
        }
        if self.channels.iter().all(|c| c == "-") {
            return Err("channels: at least one channel must be compared (all are \"-\")".into());
        }
        if self.format != ShippedFormat::Text && (self.symbol.is_some() || self.values.is_some()) {
            return Err(format!(
                "symbol and values apply to the text format only, not {:?}",
                self.format
            ));
        }
        Ok(())
    }

    /// Decodes `bytes` (the shipped file) into `texels` texels of the table whose stored axis
    /// sizes are `dims` (x fastest). `name` names the file in messages.
    pub fn read(&self, bytes: &[u8], dims: [usize; 3], name: &str) -> Result<ShippedTable, String> {
        let nc = self.channels.len();
        let texels = dims[0] * dims[1] * dims[2];
        let (raw, step) = match self.format {
            ShippedFormat::Text => {
                let text = std::str::from_utf8(bytes).map_err(|_| {
                    format!("{name}: not a text file (format text expects numbers in text, e.g. a C array)")
                })?;
                let values = self.values.unwrap_or(ShippedValues::Float);
                (
                    text_array(text, self.symbol.as_deref(), values, name)?,
                    values.step(),
                )
            }
            ShippedFormat::Png => png_values(bytes, nc, name)?,
            ShippedFormat::Exr => exr_values(bytes, nc, name)?,
            ShippedFormat::Bin => (bin_values(bytes, name)?, 0.0),
        };
        let want = self.offset + texels * nc;
        if self.format == ShippedFormat::Bin && raw.len() != want {
            return Err(format!(
                "{name}: {} bytes hold {} float32 values, the table needs {want} ({texels} texels × {nc} channels{}): the file's table and the preset's axes differ",
                bytes.len(),
                raw.len(),
                if self.offset > 0 { format!(" after {} skipped", self.offset) } else { String::new() }
            ));
        }
        if self.format == ShippedFormat::Text && self.symbol.is_some() && raw.len() != want {
            return Err(format!(
                "{name}: the array {} holds {} values, the table needs {} ({texels} texels × {nc} channels{})",
                self.symbol.as_deref().unwrap_or(""),
                raw.len(),
                want,
                if self.offset > 0 { format!(" after {} skipped", self.offset) } else { String::new() }
            ));
        }
        if raw.len() < want {
            return Err(format!(
                "{name}: {} values where the table needs {} ({} texels × {nc} channels{}): the file's table and the preset's axes differ",
                raw.len().saturating_sub(self.offset),
                texels * nc,
                texels,
                if self.offset > 0 { format!(", after the {} skipped", self.offset) } else { String::new() }
            ));
        }
        let raw = &raw[self.offset..want];
        let (nx, ny) = (dims[0], dims[1]);
        let mut values = vec![0.0; texels * nc];
        for t in 0..texels {
            let (x, y, z) = (t % nx, (t / nx) % ny, t / (nx * ny));
            // where texel (x, y, z) sits in the file
            let fy = if self.flip_y { ny - 1 - y } else { y };
            let ft = (z * ny + fy) * nx + x;
            for c in 0..nc {
                let i = match self.interleave.unwrap_or(Interleave::Texel) {
                    Interleave::Texel => ft * nc + c,
                    Interleave::Plane => c * texels + ft,
                };
                let v = raw[i];
                if !v.is_finite() {
                    return Err(format!(
                        "{name}: value {} (texel [{x}, {y}, {z}], channel {c}) is {v}: a shipped table holds finite values",
                        i + self.offset
                    ));
                }
                values[t * nc + c] = match self.decode.unwrap_or(Decode::Linear) {
                    Decode::Linear => v,
                    Decode::Srgb => srgb_to_linear(v),
                };
            }
        }
        Ok(ShippedTable {
            channels: self.channels.clone(),
            values,
            step,
        })
    }
}

impl ShippedValues {
    fn step(self) -> f64 {
        match self {
            ShippedValues::Float => 0.0,
            ShippedValues::HalfBits => 2f64.powi(-11),
            ShippedValues::Unorm8 => 1.0 / 255.0,
            ShippedValues::Unorm16 => 1.0 / 65535.0,
        }
    }
}

/// The sRGB electro-optical transfer function (IEC 61966-2-1): stored value → linear.
pub fn srgb_to_linear(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The text with comments replaced by spaces: `//` to the end of the line, `/* … */`, and
/// lines whose first non-blank character is `#` (preprocessor lines, and the headers of
/// brdfbake's test data).
fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut line_start = true;
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if let Some(r) = rest.strip_prefix("//") {
            rest = r.find('\n').map_or("", |i| &r[i..]);
            continue;
        }
        if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |i| &r[i + 2..]);
            out.push(' ');
            continue;
        }
        if line_start && c == '#' {
            rest = rest.find('\n').map_or("", |i| &rest[i..]);
            continue;
        }
        if c == '\n' {
            line_start = true;
        } else if !c.is_whitespace() {
            line_start = false;
        }
        out.push(c);
        rest = &rest[c.len_utf8()..];
    }
    out
}

/// The numbers of a text file, or of the array `symbol` in it (the values between the first
/// bracket after the symbol's declaration and its match, nested brackets flattened), as
/// `values` encodes them. Comments (`//`, `/* */`, `#` lines) are skipped; a sign written
/// apart from its number (`- 4.5e-07`, as three.js' `RectAreaLightTexturesLib.js` spaces
/// them) belongs to it. `name` names the file in messages. The one reader of numbers in text:
/// `compare`'s shipped tables and the published LTC tables (`table::ltc_layout`).
pub fn text_array(
    text: &str,
    symbol: Option<&str>,
    values: ShippedValues,
    name: &str,
) -> Result<Vec<f64>, String> {
    let body = strip_comments(text);
    let body: &str = match symbol {
        None => &body,
        Some(s) => {
            let at = find_symbol(&body, s).ok_or_else(|| {
                format!("{name}: no array named {s:?} (the preset's shipped.symbol)")
            })?;
            let mut rest = &body[at + s.len()..];
            // a C declarator `t[1024] = {…}` or a JS `DATA = new Uint16Array([…])`: the values
            // follow the '=' that comes before the first '{' and ';'
            let stop = rest.find(['{', ';']).unwrap_or(rest.len());
            if let Some(eq) = rest[..stop].find('=') {
                rest = &rest[eq + 1..];
            }
            let open = rest.find(['{', '[']).ok_or_else(|| {
                format!("{name}: no '{{' or '[' after {s:?}: cannot find the array's values")
            })?;
            let inner = &rest[open + 1..];
            let close = matching_close(inner)
                .ok_or_else(|| format!("{name}: the array {s:?} is not closed"))?;
            &inner[..close]
        }
    };
    let mut tokens: Vec<String> = Vec::new();
    let mut sign: Option<&str> = None;
    for t in body
        .split(|c: char| c == ',' || c.is_whitespace() || "{}[]();=".contains(c))
        .filter(|t| !t.is_empty())
    {
        match (sign.take(), t) {
            (None, "-" | "+") => sign = Some(t),
            (Some(s), _) => tokens.push(format!("{s}{t}")),
            (None, _) => tokens.push(t.to_string()),
        }
    }
    if let Some(s) = sign {
        tokens.push(s.to_string());
    }
    let mut out = Vec::new();
    for (k, tok) in tokens.iter().map(String::as_str).enumerate() {
        let v = parse_number(tok, values).ok_or_else(|| {
            format!(
                "{name}: value {} ({tok:?}) is not {} (shipped.values)",
                k + 1,
                match values {
                    ShippedValues::Float => "a decimal number",
                    ShippedValues::HalfBits => "a 16-bit half-float bit pattern such as 0x3c00",
                    ShippedValues::Unorm8 => "an integer in 0..=255",
                    ShippedValues::Unorm16 => "an integer in 0..=65535",
                }
            )
        })?;
        out.push(v);
    }
    Ok(out)
}

/// The byte offset of `symbol` as a whole word in `text`.
fn find_symbol(text: &str, symbol: &str) -> Option<usize> {
    let word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut from = 0;
    while let Some(i) = text[from..].find(symbol) {
        let at = from + i;
        let before = text[..at].chars().next_back();
        let after = text[at + symbol.len()..].chars().next();
        if !before.is_some_and(word) && !after.is_some_and(word) {
            return Some(at);
        }
        from = at + symbol.len();
    }
    None
}

/// The offset of the bracket closing the one just before `s`.
fn matching_close(s: &str) -> Option<usize> {
    let mut depth = 1usize;
    for (i, c) in s.char_indices() {
        match c {
            '{' | '[' => depth += 1,
            '}' | ']' => {
                depth -= 1;
                if depth == 0 {
                    return Some(i);
                }
            }
            _ => {}
        }
    }
    None
}

fn parse_number(tok: &str, values: ShippedValues) -> Option<f64> {
    let int = || -> Option<u64> {
        match tok.strip_prefix("0x").or_else(|| tok.strip_prefix("0X")) {
            Some(h) => u64::from_str_radix(h.trim_end_matches(['u', 'U']), 16).ok(),
            None => tok.trim_end_matches(['u', 'U']).parse::<u64>().ok(),
        }
    };
    match values {
        ShippedValues::Float => tok
            .trim_end_matches(['f', 'F'])
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite()),
        ShippedValues::HalfBits => {
            let b = u16::try_from(int()?).ok()?;
            Some(half::f16::from_bits(b).to_f64())
        }
        ShippedValues::Unorm8 => {
            let n = int()?;
            (n <= 255).then(|| n as f64 / 255.0)
        }
        ShippedValues::Unorm16 => {
            let n = int()?;
            (n <= 65535).then(|| n as f64 / 65535.0)
        }
    }
}

/// Largest PNG side accepted (the pixels are decoded into memory).
const MAX_PNG_SIDE: u32 = 16384;

/// The pixels of a PNG as values in [0, 1], channels interleaved, rows as stored (row 0
/// first); `nc` must be its channel count.
fn png_values(bytes: &[u8], nc: usize, name: &str) -> Result<(Vec<f64>, f64), String> {
    let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
    // (the glTF Sample Viewer's lut_sheen_E.png carries an iCCP chunk whose CRC is wrong;
    // the pixels are intact, and the chunk does not change what they mean here)
    dec.ignore_checksums(true);
    dec.set_transformations(png::Transformations::IDENTITY);
    let mut reader = dec
        .read_info()
        .map_err(|e| format!("{name}: not a PNG file brdfbake can read: {e}"))?;
    let info = reader.info();
    let (w, h) = (info.width, info.height);
    if w > MAX_PNG_SIDE || h > MAX_PNG_SIDE {
        return Err(format!(
            "{name}: {w} × {h} pixels, larger than a shipped table can be (at most {MAX_PNG_SIDE} a side)"
        ));
    }
    let channels = match info.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => {
            return Err(format!(
                "{name}: a palette PNG; a shipped table is grey, RGB or RGBA"
            ))
        }
    };
    let depth = match info.bit_depth {
        png::BitDepth::Eight => 8,
        png::BitDepth::Sixteen => 16,
        d => {
            return Err(format!(
                "{name}: {d:?} bits per channel; a shipped table has 8 or 16"
            ))
        }
    };
    if channels != nc {
        return Err(format!(
            "{name}: the PNG has {channels} channels, the preset's shipped.channels lists {nc}"
        ));
    }
    let mut buf = vec![
        0u8;
        reader
            .output_buffer_size()
            .ok_or_else(|| format!("{name}: too large"))?
    ];
    let frame = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("{name}: damaged PNG pixel data: {e}"))?;
    let buf = &buf[..frame.buffer_size()];
    let (values, step) = if depth == 8 {
        (buf.iter().map(|&b| b as f64 / 255.0).collect(), 1.0 / 255.0)
    } else {
        (
            buf.chunks_exact(2)
                .map(|b| u16::from_be_bytes([b[0], b[1]]) as f64 / 65535.0)
                .collect(),
            1.0 / 65535.0,
        )
    };
    Ok((values, step))
}

/// The values of a file of raw little-endian 32-bit floats.
fn bin_values(bytes: &[u8], name: &str) -> Result<Vec<f64>, String> {
    if bytes.len() % 4 != 0 {
        return Err(format!(
            "{name}: {} bytes is not a whole number of float32 values (format bin: raw little-endian 32-bit floats)",
            bytes.len()
        ));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64)
        .collect())
}

/// The pixels of an EXR file's first layer, channels in the file's order, rows from the top
/// of its data window (row 0 first).
fn exr_values(bytes: &[u8], nc: usize, name: &str) -> Result<(Vec<f64>, f64), String> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| format!("{name}: not an EXR file brdfbake can read: {e}"))?;
    let layer = &image.layer_data;
    let list = &layer.channel_data.list;
    if list.len() != nc {
        return Err(format!(
            "{name}: the EXR has {} channels ({}), the preset's shipped.channels lists {nc}",
            list.len(),
            list.iter()
                .map(|c| c.name.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let size = layer.size;
    let n = size.width() * size.height();
    let mut out = vec![0.0; n * nc];
    let mut step: f64 = 0.0;
    for (c, ch) in list.iter().enumerate() {
        let samples: Vec<f64> = match &ch.sample_data {
            FlatSamples::F16(v) => {
                step = step.max(2f64.powi(-11));
                v.iter().map(|x| x.to_f64()).collect()
            }
            FlatSamples::F32(v) => v.iter().map(|&x| x as f64).collect(),
            FlatSamples::U32(v) => v.iter().map(|&x| x as f64).collect(),
        };
        for (i, s) in samples.into_iter().enumerate() {
            out[i * nc + c] = s;
        }
    }
    Ok((out, step))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shipped(json: &str) -> Shipped {
        serde_json::from_str(json).unwrap()
    }

    #[test]
    fn text_arrays_by_symbol_and_comments() {
        let text = "/* header */\n#include <x>\nstatic const float a[3] = {1.0f, 2.0f, 3.0f};\n\
                    // table b\nstatic const float b[4] = {\n  0.5f, 0.25f, // row 0\n  0.125f, 1e-3f,\n};\n";
        let s = shipped(r#"{"format": "text", "symbol": "b", "channels": ["E"]}"#);
        let t = s.read(text.as_bytes(), [2, 2, 1], "t").unwrap();
        assert_eq!(t.values, [0.5, 0.25, 0.125, 1e-3]);
        // flip_y: the file's first row is the last texel row
        let s = shipped(r#"{"format": "text", "symbol": "b", "channels": ["E"], "flip_y": true}"#);
        let t = s.read(text.as_bytes(), [2, 2, 1], "t").unwrap();
        assert_eq!(t.values, [0.125, 1e-3, 0.5, 0.25]);
        // a wrong size is named
        let e = shipped(r#"{"format": "text", "symbol": "a", "channels": ["E"]}"#)
            .read(text.as_bytes(), [2, 2, 1], "t")
            .unwrap_err();
        assert!(e.contains("holds 3 values") && e.contains("needs 4"), "{e}");
        let e = shipped(r#"{"format": "text", "symbol": "c", "channels": ["E"]}"#)
            .read(text.as_bytes(), [2, 2, 1], "t")
            .unwrap_err();
        assert!(e.contains("no array named \"c\""), "{e}");
    }

    /// A sign spaced apart from its number (three.js' LTC arrays) belongs to it; a lone
    /// trailing sign is an error, not a silent zero.
    #[test]
    fn spaced_signs_join_their_numbers() {
        let t = text_array(
            "a = [1, - 4.5e-07, + 2, -3]",
            Some("a"),
            ShippedValues::Float,
            "t",
        )
        .unwrap();
        assert_eq!(t, [1.0, -4.5e-7, 2.0, -3.0]);
        let e = text_array("a = [1, -]", Some("a"), ShippedValues::Float, "t").unwrap_err();
        assert!(e.contains("\"-\""), "{e}");
    }

    #[test]
    fn half_bits_planes_and_srgb() {
        let text = "new Uint16Array([0x3c00, 0x3800, 0x0000, 0x3400])";
        let s = shipped(
            r#"{"format": "text", "symbol": "Uint16Array", "values": "half-bits", "channels": ["A", "B"], "interleave": "plane"}"#,
        );
        let t = s.read(text.as_bytes(), [2, 1, 1], "t").unwrap();
        // planes: A = (1, 0.5), B = (0, 0.25), read back interleaved
        assert_eq!(t.values, [1.0, 0.0, 0.5, 0.25]);
        let s = shipped(
            r#"{"format": "text", "values": "unorm8", "channels": ["E"], "decode": "srgb"}"#,
        );
        let t = s.read(b"255 0", [2, 1, 1], "t").unwrap();
        assert_eq!(t.values, [1.0, 0.0]);
        let e = s.read(b"256 0", [2, 1, 1], "t").unwrap_err();
        assert!(e.contains("0..=255"), "{e}");
        assert!((srgb_to_linear(0.5) - 0.214041).abs() < 1e-6);
    }

    /// Raw float32: the values in order, exactly as many as the table has; another size or a
    /// non-finite value is named.
    #[test]
    fn raw_float32_files() {
        let s = shipped(r#"{"format": "bin", "channels": ["A", "B"]}"#);
        let bytes: Vec<u8> = [0.25f32, 1.0, -2.5, 3e-9]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let t = s.read(&bytes, [2, 1, 1], "t.bin").unwrap();
        assert_eq!(t.values, [0.25, 1.0, -2.5, 3e-9f32 as f64]);
        let e = s.read(&bytes, [1, 1, 1], "t.bin").unwrap_err();
        assert!(
            e.contains("16 bytes hold 4 float32 values") && e.contains("needs 2"),
            "{e}"
        );
        let e = s.read(&bytes[..15], [2, 1, 1], "t.bin").unwrap_err();
        assert!(e.contains("15 bytes is not a whole number"), "{e}");
        let nan: Vec<u8> = [0.0f32, f32::NAN]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let e = shipped(r#"{"format": "bin", "channels": ["E"]}"#)
            .read(&nan, [2, 1, 1], "t.bin")
            .unwrap_err();
        assert!(e.contains("finite"), "{e}");
    }

    #[test]
    fn channel_names_are_checked() {
        let s = shipped(r#"{"format": "png", "channels": ["A", "Q", "-"]}"#);
        let e = s.validate(&["A".into(), "B".into()]).unwrap_err();
        assert!(e.contains("channels[1]") && e.contains("\"Q\""), "{e}");
        let s = shipped(r#"{"format": "png", "symbol": "x", "channels": ["A"]}"#);
        assert!(s
            .validate(&["A".into()])
            .unwrap_err()
            .contains("text format only"));
    }
}
