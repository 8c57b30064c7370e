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
    /// Slices of the shipped table that hold something other than the preset's physics by
    /// the engine's own construction (Cycles' η slice whose ior rounds to 1.0f, where its
    /// sampler takes the smooth branch): `compare` names each, says why, and reports the
    /// shipped table's error both with and without them.
    #[serde(default)]
    pub degenerate: Vec<Degenerate>,
    /// The file's channels as the preset spells them: the engine's own names (`A`, `1-E`),
    /// before [`Shipped::channels`] is mapped to the stored channels (`R`, `G`, …). Set by the
    /// preset parser; empty when the two are the same.
    #[serde(skip)]
    pub spelled: Vec<String>,
}

/// One degenerate slice of a shipped table ([`Shipped::degenerate`]).
#[derive(Clone, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Degenerate {
    /// A stored axis' name (`fresnel`).
    pub axis: String,
    /// The texel index along it.
    pub index: usize,
    /// Why the engine's values there are not comparable with the physical value, for people.
    pub why: String,
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
    /// A KTX 2.0 texture of one level, R/RG/RGBA in 16- or 32-bit float or 8- or 16-bit
    /// UNORM, plain or Zstandard-supercompressed (Bevy's `dfg.ktx2`), any writer; a 2D
    /// array's layers or a volume's slices stacked as rows.
    Ktx2,
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
    /// Babylon.js' RGBD ([`crate::encode::rgbd`]): an 8-bit RGBA PNG whose channels R, G, B
    /// decode as `(c/255)^2.2 / (a/255)`; the file's fourth channel (D) is listed as `-`.
    Rgbd,
}

/// A shipped table read into the stored layout: `values[(texel)·nc + c]` for the file's
/// channels `c`, texel index `(z·ny + y)·nx + x`.
#[derive(Clone, Debug, PartialEq)]
pub struct ShippedTable {
    /// The file's channels (as [`Shipped::channels`] names them).
    pub channels: Vec<String>,
    pub values: Vec<f64>,
    /// The quantization step of the stored numbers where they are integers (1/255, 1/65535),
    /// or the half-float spacing near 1 (2⁻¹¹), or 0 for printed decimals.
    pub step: f64,
    /// Per value (indexed as `values`): the most by which the file's number can differ from
    /// the value it was made from through its storage alone — half the spacing of the
    /// numbers the storage can hold at that value (half a UNORM code, decoded; half an f16
    /// or f32 ulp; half a unit in the last printed decimal).
    pub rounding: Vec<f64>,
    /// What the file stores, for people: `6 decimals`, `f16`, `8-bit UNORM`.
    pub storage: String,
    /// The texels the file holds, where it holds only some (a quotes file: `true` at each
    /// quoted texel); `None`: every texel.
    pub present: Option<Vec<bool>>,
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
                // (named as the preset writes it: `channels` may hold the stored names the
                // preset's spellings were translated to)
                let written = self.spelled.get(k).unwrap_or(c);
                return Err(format!("channels[{k}]: {written:?} is listed twice"));
            }
        }
        if self.decode == Some(Decode::Rgbd)
            && (self.format != ShippedFormat::Png
                || self.channels.len() != 4
                || self.channels[3] != "-")
        {
            return Err(
                "decode rgbd reads an RGBA PNG whose alpha is the divisor D: give \"format\": \"png\" and four channels, the last \"-\" (e.g. [\"R\", \"G\", \"B\", \"-\"])".into(),
            );
        }
        if self.channels.iter().all(|c| c == "-") {
            return Err("channels: at least one channel must be compared (all are \"-\")".into());
        }
        if self.symbol.as_deref().is_some_and(|s| s.trim().is_empty()) {
            return Err(
                "symbol is empty: give the name of the array in the file (or leave symbol out to read every number)".into(),
            );
        }
        if self.format != ShippedFormat::Text && (self.symbol.is_some() || self.values.is_some()) {
            return Err(format!(
                "symbol and values apply to the text format only, not {:?}",
                self.format
            ));
        }
        Ok(())
    }

    /// Checks the degenerate slices against the stored axes (name, size).
    pub fn validate_degenerate(&self, axes: &[(String, usize)]) -> Result<(), String> {
        for (k, d) in self.degenerate.iter().enumerate() {
            let Some((_, size)) = axes.iter().find(|(n, _)| *n == d.axis) else {
                return Err(format!(
                    "degenerate[{k}].axis: {:?} is not an axis of the table (its axes: {})",
                    d.axis,
                    axes.iter()
                        .map(|(n, _)| n.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            };
            if d.index >= *size {
                return Err(format!(
                    "degenerate[{k}].index: {} is not a texel of axis {} (0 to {})",
                    d.index,
                    d.axis,
                    size - 1
                ));
            }
            if d.why.trim().is_empty() {
                return Err(format!(
                    "degenerate[{k}].why: say why the engine's values there are not comparable"
                ));
            }
        }
        Ok(())
    }

    /// Decodes `bytes` (the shipped file) into `texels` texels of the table whose stored axis
    /// sizes are `dims` (x fastest). `name` names the file in messages. A text file that
    /// declares itself a quotes file (a line `# brdfbake-quotes: z y x T R`, see
    /// [`QUOTES_MARKER`]) is read as the quoted texels of the table, whatever the format.
    pub fn read(&self, bytes: &[u8], dims: [usize; 3], name: &str) -> Result<ShippedTable, String> {
        if let Some(columns) = quotes_columns(bytes) {
            return self.read_quotes(bytes, &columns, dims, name);
        }
        let nc = self.channels.len();
        let texels = dims[0] * dims[1] * dims[2];
        // an image's width and height must be the table's: the same count of values in
        // another shape would be read with the wrong stride
        let mut image = None;
        let (raw, kinds) = match self.format {
            ShippedFormat::Text => {
                let text = std::str::from_utf8(bytes).map_err(|_| {
                    format!("{name}: not a text file (format text expects numbers in text, e.g. a C array)")
                })?;
                let values = self.values.unwrap_or(ShippedValues::Float);
                let (raw, decimals) =
                    text_array_with_decimals(text, self.symbol.as_deref(), values, name)?;
                (raw, vec![values.number_kind(decimals); nc])
            }
            ShippedFormat::Png | ShippedFormat::Exr | ShippedFormat::Ktx2 => {
                let (raw, kinds, size) = match self.format {
                    ShippedFormat::Png => png_values(bytes, nc, name)?,
                    ShippedFormat::Exr => exr_values(bytes, nc, name)?,
                    _ => ktx2_values(bytes, nc, name)?,
                };
                image = Some(size);
                (raw, kinds)
            }
            ShippedFormat::Bin => (bin_values(bytes, name)?, vec![NumberKind::F32; nc]),
        };
        if let Some([w, h]) = image {
            let (nx, rows) = (dims[0], dims[1] * dims[2]);
            if self.offset == 0 && (w != nx || h != rows) {
                return Err(format!(
                    "{name}: the image is {w} × {h} pixels, the preset's table is {nx} × {rows} texels{}: the file's table and the preset's axes differ",
                    if dims[2] > 1 { format!(" ({} slices of {} rows)", dims[2], dims[1]) } else { String::new() }
                ));
            }
        }
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
        if raw.len() != want {
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
        let mut rounding = vec![0.0; texels * nc];
        for t in 0..texels {
            let (x, y, z) = (t % nx, (t / nx) % ny, t / (nx * ny));
            // where texel (x, y, z) sits in the file
            let fy = if self.flip_y { ny - 1 - y } else { y };
            let ft = (z * ny + fy) * nx + x;
            let index = |k: usize| match self.interleave.unwrap_or(Interleave::Texel) {
                Interleave::Texel => ft * nc + k,
                Interleave::Plane => k * texels + ft,
            };
            // an RGBD texel decodes as a whole (validated: an 8-bit RGBA PNG, D the fourth
            // channel)
            let rgbd = if self.decode == Some(Decode::Rgbd) {
                let code = |k: usize| (raw[index(k)] * 255.0).round().clamp(0.0, 255.0) as u8;
                let px = [code(0), code(1), code(2), code(3)];
                let rgb = crate::encode::rgbd::decode_texel(px).ok_or_else(|| {
                    format!("{name}: texel [{x}, {y}, {z}] has D = 0: not an RGBD texel")
                })?;
                Some((rgb, px))
            } else {
                None
            };
            for c in 0..nc {
                let i = index(c);
                let v = raw[i];
                if !v.is_finite() {
                    return Err(format!(
                        "{name}: value {} (texel [{x}, {y}, {z}], channel {c}) is {v}: a shipped table holds finite values",
                        i + self.offset
                    ));
                }
                let (value, r) = match rgbd {
                    Some((rgb, px)) if c < 3 => {
                        (rgb[c], crate::encode::rgbd::rounding(px[c], px[3]))
                    }
                    Some(_) => (0.0, 0.0), // D itself: listed as "-", not compared
                    None => self.decoded(v, kinds[c]),
                };
                values[t * nc + c] = value;
                rounding[t * nc + c] = r;
            }
        }
        Ok(ShippedTable {
            channels: self.channels.clone(),
            values,
            step: kinds.iter().map(|k| k.step()).fold(0.0, f64::max),
            rounding,
            storage: if self.decode == Some(Decode::Rgbd) {
                "8-bit RGBD".into()
            } else {
                storage_text(&kinds, self.decode == Some(Decode::Srgb))
            },
            present: None,
        })
    }

    /// A stored number `v` decoded (sRGB or linear), and the decoded value's rounding by the
    /// storage `kind`.
    fn decoded(&self, v: f64, kind: NumberKind) -> (f64, f64) {
        match self.decode.unwrap_or(Decode::Linear) {
            // (RGBD decodes a whole texel, in read)
            Decode::Linear | Decode::Rgbd => (v, kind.rounding(v)),
            Decode::Srgb => {
                // half a step of the stored number either way, through the transfer function
                let h = kind.rounding(v);
                let value = srgb_to_linear(v);
                let up = srgb_to_linear((v + h).min(1.0)) - value;
                let down = value - srgb_to_linear((v - h).max(0.0));
                (value, up.max(down))
            }
        }
    }

    /// The quoted texels of a quotes file whose marker line lists `columns`: index columns
    /// `x`, `y`, `z` (the file's array indices: `y` counts the file's rows, which `flip_y`
    /// maps to the table's) and one value column per compared channel, named as the preset
    /// spells the file's channels.
    fn read_quotes(
        &self,
        bytes: &[u8],
        columns: &[String],
        dims: [usize; 3],
        name: &str,
    ) -> Result<ShippedTable, String> {
        let text = std::str::from_utf8(bytes)
            .map_err(|_| format!("{name}: a quotes file is text; this one is not UTF-8"))?;
        let nc = self.channels.len();
        let spelled = if self.spelled.is_empty() {
            &self.channels
        } else {
            &self.spelled
        };
        // what each column is: an axis index (0, 1, 2 for x, y, z) or a file channel
        enum Col {
            Index(usize),
            Channel(usize),
        }
        let mut cols = Vec::new();
        for c in columns {
            let col = match c.as_str() {
                "x" => Col::Index(0),
                "y" => Col::Index(1),
                "z" => Col::Index(2),
                _ => Col::Channel(spelled.iter().position(|s| s == c).ok_or_else(|| {
                    format!(
                        "{name}: the quotes' column {c:?} is neither an index (x, y, z) nor a channel of the table as the preset names them ({})",
                        spelled.join(", ")
                    )
                })?),
            };
            cols.push(col);
        }
        for (k, d) in dims.iter().enumerate() {
            if *d > 1 && !cols.iter().any(|c| matches!(c, Col::Index(i) if *i == k)) {
                return Err(format!(
                    "{name}: the quotes' columns ({}) lack the index {} of an axis of {d} texels",
                    columns.join(" "),
                    ["x", "y", "z"][k]
                ));
            }
        }
        let quoted: Vec<usize> = cols
            .iter()
            .filter_map(|c| match c {
                Col::Channel(i) => Some(*i),
                Col::Index(_) => None,
            })
            .collect();
        for (c, ch) in self.channels.iter().enumerate() {
            if ch != "-" && !quoted.contains(&c) {
                return Err(format!(
                    "{name}: the quotes have no column for the table's channel {:?}",
                    spelled[c]
                ));
            }
        }
        let texels = dims[0] * dims[1] * dims[2];
        let mut values = vec![0.0; texels * nc];
        let mut rounding = vec![0.0; texels * nc];
        let mut present = vec![false; texels];
        let mut decimals = 0u32;
        let mut count = 0usize;
        for (ln, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let toks: Vec<&str> = line.split_whitespace().collect();
            if toks.len() != cols.len() {
                return Err(format!(
                    "{name}, line {}: {} numbers where the quotes' columns ({}) are {}",
                    ln + 1,
                    toks.len(),
                    columns.join(" "),
                    cols.len()
                ));
            }
            let mut idx = [0usize; 3];
            let mut row = vec![0.0; nc];
            let mut row_decimals = vec![0u32; nc];
            for (tok, col) in toks.iter().zip(&cols) {
                match col {
                    Col::Index(k) => {
                        idx[*k] = tok.parse::<usize>().ok().filter(|i| *i < dims[*k]).ok_or_else(|| {
                            format!(
                                "{name}, line {}: index {} = {tok:?} is not a texel index of the table (0 to {})",
                                ln + 1,
                                ["x", "y", "z"][*k],
                                dims[*k] - 1
                            )
                        })?;
                    }
                    Col::Channel(c) => {
                        row[*c] = parse_number(tok, ShippedValues::Float).ok_or_else(|| {
                            format!("{name}, line {}: {tok:?} is not a decimal number", ln + 1)
                        })?;
                        row_decimals[*c] = printed_decimals(tok);
                    }
                }
            }
            if self.flip_y {
                idx[1] = dims[1] - 1 - idx[1];
            }
            let t = (idx[2] * dims[1] + idx[1]) * dims[0] + idx[0];
            if present[t] {
                return Err(format!(
                    "{name}, line {}: texel x = {}, y = {}, z = {} is quoted twice",
                    ln + 1,
                    idx[0],
                    idx[1],
                    idx[2]
                ));
            }
            present[t] = true;
            count += 1;
            for c in 0..nc {
                values[t * nc + c] = row[c];
                decimals = decimals.max(row_decimals[c]);
            }
        }
        if count == 0 {
            return Err(format!("{name}: a quotes file without a quoted texel"));
        }
        let kind = NumberKind::Printed(decimals);
        for t in (0..texels).filter(|t| present[*t]) {
            for c in 0..nc {
                rounding[t * nc + c] = kind.rounding(values[t * nc + c]);
            }
        }
        Ok(ShippedTable {
            channels: self.channels.clone(),
            values,
            step: 0.0,
            rounding,
            storage: format!("{}, {count} of {texels} texels quoted", kind.text()),
            present: Some(present),
        })
    }

    /// What the preset reads, for messages about a file that is not it: `a text file holding
    /// the array table_ggx_E of decimal numbers (Cycles' intern/cycles/scene/shader.tables)`.
    pub fn expects(&self, engine: Option<&str>) -> String {
        let what = match self.format {
            ShippedFormat::Text => {
                let numbers = match self.values.unwrap_or(ShippedValues::Float) {
                    ShippedValues::Float => "decimal numbers",
                    ShippedValues::HalfBits => "half-float bit patterns",
                    ShippedValues::Unorm8 => "8-bit integers",
                    ShippedValues::Unorm16 => "16-bit integers",
                };
                match &self.symbol {
                    Some(s) => format!("a text file holding the array {s} of {numbers}"),
                    None => format!("a text file of {numbers}"),
                }
            }
            ShippedFormat::Png => format!("a {}-channel PNG", self.channels.len()),
            ShippedFormat::Exr => format!("an OpenEXR file of {} channels", self.channels.len()),
            ShippedFormat::Ktx2 => format!("a KTX2 texture of {} components", self.channels.len()),
            ShippedFormat::Bin => format!(
                "a raw little-endian float32 file of {} channels",
                self.channels.len()
            ),
        };
        match (&self.file, engine) {
            (Some(f), Some(e)) => format!("{what} ({e}'s {f}, or a brdfbake quotes file of it)"),
            (Some(f), None) => format!("{what} ({f}, or a brdfbake quotes file of it)"),
            (None, _) => what,
        }
    }
}

/// The marker line of a quotes file: `# brdfbake-quotes: z y x T R` names the columns of
/// every line that follows (texel indices x, y, z as the engine's array counts them, then
/// the channels' values as the preset names them). Such a file quotes some texels of a table
/// whose licence keeps the whole out of the repository (EEVEE's, GPL); `compare` judges the
/// quoted texels.
pub const QUOTES_MARKER: &str = "# brdfbake-quotes:";

/// The columns a quotes file's marker line names, or `None` for any other file.
fn quotes_columns(bytes: &[u8]) -> Option<Vec<String>> {
    // (the marker sits in the comment header, within the first lines)
    let head = &bytes[..bytes.len().min(1 << 16)];
    let text = std::str::from_utf8(head).ok().or_else(|| {
        // a multi-byte character cut at the end of the head
        std::str::from_utf8(&head[..head.len().saturating_sub(3)]).ok()
    })?;
    text.lines()
        .find_map(|l| l.trim().strip_prefix(QUOTES_MARKER))
        .map(|cols| cols.split_whitespace().map(String::from).collect())
}

/// How a shipped file stores its numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
enum NumberKind {
    /// Decimal numbers printed with at most this many decimals (`%f`: 6), read as f32.
    Printed(u32),
    Half,
    F32,
    /// Normalized integers, value = n / max.
    Unorm(f64),
}

impl NumberKind {
    /// Half the spacing of the numbers this storage holds, at `v` (in stored units: the
    /// code's value n / max for UNORM).
    fn rounding(self, v: f64) -> f64 {
        match self {
            NumberKind::Printed(d) => (0.5 * 10f64.powi(-(d as i32))).max(half_ulp(v, 24, -126)),
            NumberKind::Half => half_ulp(v, 11, -14),
            NumberKind::F32 => half_ulp(v, 24, -126),
            NumberKind::Unorm(max) => 0.5 / max,
        }
    }

    fn step(self) -> f64 {
        match self {
            NumberKind::Printed(_) | NumberKind::F32 => 0.0,
            NumberKind::Half => 2f64.powi(-11),
            NumberKind::Unorm(max) => 1.0 / max,
        }
    }

    fn text(self) -> String {
        match self {
            NumberKind::Printed(d) if d >= 9 => "f32 printed in full".into(),
            NumberKind::Printed(d) => format!("{d} decimals"),
            NumberKind::Half => "f16".into(),
            NumberKind::F32 => "f32".into(),
            NumberKind::Unorm(max) => format!("{}-bit UNORM", (max + 1.0).log2().round()),
        }
    }
}

/// Half the spacing of binary floating-point numbers of `p` significant bits (24: f32, 11:
/// f16) at `v`, whose normal range starts at 2^`emin`.
fn half_ulp(v: f64, p: i32, emin: i32) -> f64 {
    let a = v.abs();
    let e = if a > 0.0 {
        a.log2().floor() as i32
    } else {
        emin
    }
    .max(emin);
    2f64.powi(e - p)
}

/// The storage of a file whose channels are stored as `kinds`, for people.
fn storage_text(kinds: &[NumberKind], srgb: bool) -> String {
    let mut k: Vec<String> = kinds.iter().map(|k| k.text()).collect();
    k.dedup();
    let mut s = k.join(" and ");
    if srgb {
        s.push_str(", sRGB-encoded");
    }
    s
}

/// How many decimals a printed number carries (`0.500624f`: 6; `2.5e-3`: 4; `1`: 0).
fn printed_decimals(tok: &str) -> u32 {
    let t = tok.trim_end_matches(['f', 'F']);
    let (m, e) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i32>().unwrap_or(0)),
        None => (t, 0),
    };
    let frac = m.split_once('.').map_or(0, |(_, f)| f.len() as i32);
    (frac - e).max(0) as u32
}

/// The file's kind, for a message about a file that is not what a preset reads: `a PNG
/// image`, `Cycles' shader.tables`, `a brdfbake sidecar`.
pub fn looks_like(bytes: &[u8]) -> String {
    const MAGIC: [(&[u8], &str); 5] = [
        (b"\x89PNG\r\n\x1a\n", "a PNG image"),
        (b"\x76\x2f\x31\x01", "an OpenEXR image"),
        (b"\xabKTX 20\xbb", "a KTX2 texture"),
        (b"\xabKTX 11\xbb", "a KTX 1 texture"),
        (b"DDS ", "a DDS texture"),
    ];
    for (m, what) in MAGIC {
        if bytes.starts_with(m) {
            return what.into();
        }
    }
    let Ok(text) = std::str::from_utf8(&bytes[..bytes.len().min(1 << 20)]) else {
        return format!("a binary file of {} bytes", bytes.len());
    };
    const TEXTS: [(&str, &str); 9] = [
        (QUOTES_MARKER, "a brdfbake quotes file"),
        ("brdfbake.lut/", "a brdfbake sidecar (JSON)"),
        ("brdfbake.preset/", "a brdfbake preset (JSON)"),
        ("table_ggx_E", "Cycles' shader.tables"),
        ("DFGLUTData", "three.js' DFGLUTData.js"),
        ("btdf_split_sum_ggx", "Blender EEVEE's eevee_lut.cc"),
        (
            "g_ltc_1",
            "Heitz's LTC tables (ltc_code's ltc.js or ltc.inc)",
        ),
        ("MiniMicrofacetGGX", "BSDL's GGX energy table"),
        ("ContyKullaSheen", "BSDL's sheen energy table"),
    ];
    for (needle, what) in TEXTS {
        if text.contains(needle) {
            return what.into();
        }
    }
    format!("a text file of {} bytes", bytes.len())
}

impl ShippedValues {
    /// How numbers written this way are stored (printed decimals: `decimals` of them).
    fn number_kind(self, decimals: u32) -> NumberKind {
        match self {
            ShippedValues::Float => NumberKind::Printed(decimals),
            ShippedValues::HalfBits => NumberKind::Half,
            ShippedValues::Unorm8 => NumberKind::Unorm(255.0),
            ShippedValues::Unorm16 => NumberKind::Unorm(65535.0),
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
    text_array_with_decimals(text, symbol, values, name).map(|(v, _)| v)
}

/// [`text_array`], and the most decimals any of its numbers is printed with.
fn text_array_with_decimals(
    text: &str,
    symbol: Option<&str>,
    values: ShippedValues,
    name: &str,
) -> Result<(Vec<f64>, u32), String> {
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
    let mut decimals = 0;
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
        if values == ShippedValues::Float {
            decimals = decimals.max(printed_decimals(tok));
        }
        out.push(v);
    }
    Ok((out, decimals))
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
/// An image's pixels (rows from the top, channels interleaved), their storage kinds per
/// channel, and its (width, height).
type ImageValues = (Vec<f64>, Vec<NumberKind>, [usize; 2]);

/// The pixels of a PNG file (see [`ImageValues`]).
fn png_values(bytes: &[u8], nc: usize, name: &str) -> Result<ImageValues, String> {
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
    let (values, max) = if depth == 8 {
        (buf.iter().map(|&b| b as f64 / 255.0).collect(), 255.0)
    } else {
        (
            buf.chunks_exact(2)
                .map(|b| u16::from_be_bytes([b[0], b[1]]) as f64 / 65535.0)
                .collect(),
            65535.0,
        )
    };
    Ok((
        values,
        vec![NumberKind::Unorm(max); nc],
        [w as usize, h as usize],
    ))
}

/// The largest level a shipped KTX2 file may inflate to (a 1024³ RGBA f32 table is 16 GiB;
/// engines ship tables of a few MiB).
const MAX_KTX2_BYTES: u64 = 1 << 30;

/// The texels of a KTX2 file's only level, components in order, rows from its first (a 2D
/// array's layers and a volume's slices stacked as rows, layer/slice 0 first).
fn ktx2_values(bytes: &[u8], nc: usize, name: &str) -> Result<ImageValues, String> {
    let r = std::panic::catch_unwind(|| ktx2::Reader::new(bytes))
        .map_err(|_| format!("{name}: malformed KTX2 (the parser failed on it)"))?
        .map_err(|e| format!("{name}: not a KTX2 file brdfbake can read: {e}"))?;
    let hd = r.header();
    let Some((storage, components)) = hd.format.and_then(crate::encode::ktx2::storage_of) else {
        return Err(format!(
            "{name}: vkFormat {:?}; a shipped KTX2 table is R, RG or RGBA in 16- or 32-bit float or 8- or 16-bit UNORM",
            hd.format
        ));
    };
    let kind = match storage.unorm_max() {
        Some(max) => NumberKind::Unorm(max as f64),
        None if storage == crate::table::Storage::F16 => NumberKind::Half,
        None => NumberKind::F32,
    };
    let bytes_per = storage.bytes();
    if components != nc {
        return Err(format!(
            "{name}: the KTX2 texels have {components} components, the preset's shipped.channels lists {nc}"
        ));
    }
    if hd.level_count > 1 {
        return Err(format!(
            "{name}: {} mip levels; a shipped table has one",
            hd.level_count
        ));
    }
    let level = r
        .levels()
        .next()
        .ok_or_else(|| format!("{name}: no level"))?;
    let (w, h) = (hd.pixel_width as usize, hd.pixel_height.max(1) as usize);
    let d =
        hd.pixel_depth.max(1) as u64 * hd.layer_count.max(1) as u64 * hd.face_count.max(1) as u64;
    let need = w as u64 * h as u64 * d * (components * bytes_per) as u64;
    if need > MAX_KTX2_BYTES {
        return Err(format!(
            "{name}: {need} bytes of texels, more than a shipped table can be"
        ));
    }
    let data: std::borrow::Cow<[u8]> = match hd.supercompression_scheme {
        None => level.data.into(),
        Some(ktx2::SupercompressionScheme::Zstandard) => {
            crate::encode::zstd::decompress(level.data, level.uncompressed_byte_length as usize)
                .map_err(|e| format!("{name}: its level: {e}"))?
                .into()
        }
        Some(s) => {
            return Err(format!(
                "{name}: supercompressionScheme {s:?}; a shipped table is plain or Zstandard"
            ))
        }
    };
    if data.len() as u64 != need {
        return Err(format!(
            "{name}: the level holds {} bytes, its header's {w} × {h} × {d} texels need {need}",
            data.len()
        ));
    }
    let values = data
        .chunks_exact(bytes_per)
        .map(|b| match (kind, bytes_per) {
            (NumberKind::Half, _) => half::f16::from_le_bytes([b[0], b[1]]).to_f64(),
            (NumberKind::F32, _) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            (NumberKind::Unorm(max), 1) => b[0] as f64 / max,
            (NumberKind::Unorm(max), _) => u16::from_le_bytes([b[0], b[1]]) as f64 / max,
            _ => f64::NAN,
        })
        .collect();
    Ok((values, vec![kind; nc], [w, h * d as usize]))
}

/// The values of a file of raw little-endian 32-bit floats.
fn bin_values(bytes: &[u8], name: &str) -> Result<Vec<f64>, String> {
    if !bytes.len().is_multiple_of(4) {
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
fn exr_values(bytes: &[u8], nc: usize, name: &str) -> Result<ImageValues, String> {
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
    let mut kinds = Vec::with_capacity(nc);
    for (c, ch) in list.iter().enumerate() {
        let samples: Vec<f64> = match &ch.sample_data {
            FlatSamples::F16(v) => {
                kinds.push(NumberKind::Half);
                v.iter().map(|x| x.to_f64()).collect()
            }
            FlatSamples::F32(v) => {
                kinds.push(NumberKind::F32);
                v.iter().map(|&x| x as f64).collect()
            }
            FlatSamples::U32(v) => {
                kinds.push(NumberKind::Unorm(1.0));
                v.iter().map(|&x| x as f64).collect()
            }
        };
        for (i, s) in samples.into_iter().enumerate() {
            out[i * nc + c] = s;
        }
    }
    Ok((out, kinds, [size.width(), size.height()]))
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

    /// The rounding of each storage, a quotes file read by its marker whatever the format,
    /// and files of another kind named.
    #[test]
    fn storage_rounding_quotes_and_file_kinds() {
        assert_eq!(printed_decimals("0.500624f"), 6);
        assert_eq!(printed_decimals("2.5e-3"), 4);
        assert_eq!(printed_decimals("1"), 0);
        let s = shipped(r#"{"format": "text", "symbol": "b", "channels": ["E"]}"#);
        let t = s
            .read(b"float b[2] = {0.500000f, 0.25f};", [2, 1, 1], "t")
            .unwrap();
        assert_eq!(t.rounding, [5e-7, 5e-7]);
        assert_eq!(t.storage, "6 decimals");
        let s = shipped(r#"{"format": "text", "values": "half-bits", "channels": ["E"]}"#);
        let t = s.read(b"0x3c00 0x3800", [2, 1, 1], "t").unwrap();
        // half an f16 ulp: 2^-11 at 1, 2^-12 at 0.5
        assert_eq!(t.rounding, [2f64.powi(-11), 2f64.powi(-12)]);
        let s = shipped(
            r#"{"format": "text", "values": "unorm8", "channels": ["E"], "decode": "srgb"}"#,
        );
        let t = s.read(b"255 0", [2, 1, 1], "t").unwrap();
        // sRGB: half a code near 1 is ~2.2x larger in linear; near 0 it is 1/12.92 of it
        assert!(
            (t.rounding[0] - 0.5 / 255.0 * 2.2).abs() < 2e-4,
            "{:?}",
            t.rounding
        );
        assert!((t.rounding[1] - 0.5 / 255.0 / 12.92).abs() < 1e-9);

        let mut s =
            shipped(r#"{"format": "text", "symbol": "t", "channels": ["R", "G"], "flip_y": true}"#);
        s.spelled = vec!["T".into(), "R".into()];
        let q = "# quoted\n# brdfbake-quotes: y x T R\n0 1 0.250000 0.5\n1 0 0.125 1.0\n";
        let t = s.read(q.as_bytes(), [2, 2, 1], "q").unwrap();
        // file row 0 is the table's last row (flip_y)
        assert_eq!(t.present, Some(vec![true, false, false, true]));
        assert_eq!(&t.values[6..8], [0.25, 0.5]);
        assert_eq!(&t.values[0..2], [0.125, 1.0]);
        assert_eq!(t.storage, "6 decimals, 2 of 4 texels quoted");
        let e = s
            .read(b"# brdfbake-quotes: y x T\n0 0 1\n", [2, 2, 1], "q")
            .unwrap_err();
        assert!(e.contains("no column for the table's channel \"R\""), "{e}");
        let e = s
            .read(b"# brdfbake-quotes: y x T R\n0 2 1 1\n", [2, 2, 1], "q")
            .unwrap_err();
        assert!(e.contains("line 2") && e.contains("0 to 1"), "{e}");

        assert_eq!(looks_like(b"\x89PNG\r\n\x1a\nrest"), "a PNG image");
        assert_eq!(
            looks_like(b"static const float table_ggx_E[1024] = {"),
            "Cycles' shader.tables"
        );
        assert_eq!(looks_like(&[0xff, 0xfe, 0x00]), "a binary file of 3 bytes");
    }
}
