//! Source-code encodings: the table as a C header (`.h`) or a Rust source file (`.rs`), for
//! engines that embed their lookup tables in the binary instead of loading a texture.
//!
//! Both hold the texels exactly as baked, in the table's own order (channels interleaved,
//! `NAME[((z·HEIGHT + y)·WIDTH + x)·CHANNELS + c]`, x fastest), as the table's [`Storage`]
//! says: `float`/`f32` values printed so that they parse back to the same bits; for f16 the
//! bit patterns of IEEE 754 binary16 values (`uint16_t`/`u16`) rounded to nearest, ties to
//! even, from the baked f32 values (a value beyond the f16 range is an
//! [`EncodeError::Unrepresentable`] error, never an infinity); for unorm8 and unorm16 the
//! normalized-integer codes (`uint8_t`/`u8`, `uint16_t`/`u16`, value = code/(2ⁿ − 1), see
//! [`super::unorm`]; a value outside [0, 1] is an error).
//!
//! Identifiers come from the table name: every character that is not an ASCII letter, digit
//! or underscore becomes `_`, `LUT_` is prepended when the result does not start with a
//! letter, and constants are upper case: table `dfg-ms` gives `DFG_MS`, `DFG_MS_WIDTH`,
//! `DFG_MS_HEIGHT`, `DFG_MS_DEPTH`, `DFG_MS_CHANNELS`, `DFG_MS_CHANNEL_NAMES`. Missing axes
//! count as size 1 (a 2D table has depth 1, a 1D table height 1).
//!
//! A comment block at the top documents the axes (name, quantity, range, convention, the
//! coordinate every texel holds and the texture coordinate a shader samples), the channels
//! and every header attribute the caller passes, in order. Output is plain text, ASCII apart
//! from what the attributes and channel meanings contain, and depends only on the inputs.

use super::{EncodeError, Encoder};
use crate::lut::{Axis, Convention, Lut, Quantity, Warp};
use crate::table::Storage;
use half::f16;
use std::fmt::Write as _;

/// Encodes a table as a C header (C99 and C++ compatible).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CHeader {
    /// The table's name: the source of every identifier, and used in error messages.
    pub table_name: String,
    /// How the texels are stored: `float`, binary16 bit patterns (`uint16_t`) or UNORM codes
    /// (`uint8_t`, `uint16_t`).
    pub storage: Storage,
}

/// Encodes a table as a Rust source file, usable as a module (`mod dfg;`) or with
/// `include!`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RustSource {
    /// The table's name: the source of every identifier, and used in error messages.
    pub table_name: String,
    /// How the texels are stored: `f32`, binary16 bit patterns (`u16`) or UNORM codes (`u8`,
    /// `u16`).
    pub storage: Storage,
}

/// Values per line in the generated arrays (rounded down to whole texels).
const PER_LINE: usize = 8;

impl Encoder for CHeader {
    fn extension(&self) -> &'static str {
        "h"
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        check_table(&self.table_name, lut)?;
        let values = Values::new(&self.table_name, lut, self.storage)?;
        let id = constant_identifier(&self.table_name);
        let guard = format!("BRDFBAKE_{id}_H");
        let size_expr = format!("{id}_WIDTH * {id}_HEIGHT * {id}_DEPTH * {id}_CHANNELS");

        let mut out = String::new();
        let mut doc = description(&self.table_name, &id, lut, self.storage, Lang::C);
        doc.extend(scale_lines(attributes));
        doc.push(String::new());
        doc.push("Attributes:".into());
        doc.extend(attribute_lines(attributes));
        out.push_str("/*\n");
        for line in &doc {
            for l in comment_lines(line) {
                let l = l.replace("*/", "* /").replace("/*", "/ *");
                if l.is_empty() {
                    out.push_str(" *\n");
                } else {
                    let _ = writeln!(out, " * {l}");
                }
            }
        }
        out.push_str(" */\n");
        let _ = writeln!(out, "#ifndef {guard}\n#define {guard}\n");
        if self.storage != Storage::F32 {
            out.push_str("#include <stdint.h>\n\n");
        }
        for (suffix, value, what) in size_constants(lut) {
            let _ = writeln!(out, "/* {what} */\n#define {id}_{suffix} {value}");
        }
        let names: Vec<String> = lut.channels.iter().map(|c| c_string(&c.name)).collect();
        let _ = writeln!(
            out,
            "\n/* Channel names, in storage order. */\nstatic const char *const {id}_CHANNEL_NAMES[{id}_CHANNELS] = {{{}}};\n",
            names.join(", ")
        );
        let element = match self.storage {
            Storage::F32 => "float",
            Storage::Unorm8 => "uint8_t",
            Storage::F16 | Storage::Unorm16 => "uint16_t",
        };
        let _ = writeln!(
            out,
            "/* {id}[((z * {id}_HEIGHT + y) * {id}_WIDTH + x) * {id}_CHANNELS + c] */\nstatic const {element} {id}[{size_expr}] = {{"
        );
        values.write_rows(&mut out, lut, "    /* ", " */", &|v| match v {
            Value::F32(v) => c_float(v),
            Value::Half(h) => format!("0x{:04x}", h.to_bits()),
            Value::Code(c) => c.to_string(),
        });
        out.push_str("};\n\n");
        let _ = writeln!(out, "#endif /* {guard} */");
        Ok(out.into_bytes())
    }
}

impl Encoder for RustSource {
    fn extension(&self) -> &'static str {
        "rs"
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        check_table(&self.table_name, lut)?;
        let values = Values::new(&self.table_name, lut, self.storage)?;
        let id = constant_identifier(&self.table_name);

        let mut out = String::new();
        let mut doc = description(&self.table_name, &id, lut, self.storage, Lang::Rust);
        doc.extend(scale_lines(attributes));
        doc.push(String::new());
        doc.push("Attributes:".into());
        doc.extend(attribute_lines(attributes));
        for line in &doc {
            for l in comment_lines(line) {
                if l.is_empty() {
                    out.push_str("//\n");
                } else {
                    let _ = writeln!(out, "// {l}");
                }
            }
        }
        out.push('\n');
        for (suffix, value, what) in size_constants(lut) {
            let _ = writeln!(out, "/// {what}\npub const {id}_{suffix}: usize = {value};");
        }
        let names: Vec<String> = lut
            .channels
            .iter()
            .map(|c| format!("{:?}", c.name))
            .collect();
        let _ = writeln!(
            out,
            "/// Channel names, in storage order.\npub const {id}_CHANNEL_NAMES: [&str; {id}_CHANNELS] = [{}];\n",
            names.join(", ")
        );
        let (element, what) = match self.storage {
            Storage::F16 => (
                "u16",
                "IEEE 754 binary16 bit patterns (`half::f16::from_bits`), rounded to nearest even from the baked f32 values",
            ),
            Storage::Unorm8 => (
                "u8",
                "UNORM8 codes: value = code / 255, code = round(baked value * 255)",
            ),
            Storage::Unorm16 => (
                "u16",
                "UNORM16 codes: value = code / 65535, code = round(baked value * 65535)",
            ),
            Storage::F32 => ("f32", "the baked f32 values, exact"),
        };
        let _ = writeln!(
            out,
            "/// Table `{}`: {what}.\n///\n/// Index: `{id}[(({{z}} * {id}_HEIGHT + {{y}}) * {id}_WIDTH + {{x}}) * {id}_CHANNELS + {{c}}]`.\n\
             #[rustfmt::skip]\n\
             #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal)]\n\
             pub static {id}: [{element}; {id}_WIDTH * {id}_HEIGHT * {id}_DEPTH * {id}_CHANNELS] = [",
            rust_doc_text(&self.table_name),
        );
        values.write_rows(&mut out, lut, "    // ", "", &|v| match v {
            Value::F32(v) => format!("{v:?}"),
            Value::Half(h) => format!("0x{:04x}", h.to_bits()),
            Value::Code(c) => c.to_string(),
        });
        out.push_str("];\n");
        Ok(out.into_bytes())
    }
}

/// One stored value.
#[derive(Clone, Copy)]
enum Value {
    F32(f32),
    Half(f16),
    /// A UNORM8 or UNORM16 code.
    Code(u16),
}

/// The values to store, converted and checked.
struct Values(Vec<Value>);

impl Values {
    fn new(table: &str, lut: &Lut, storage: Storage) -> Result<Values, EncodeError> {
        match storage {
            Storage::F32 => return Ok(Values(lut.data.iter().map(|&v| Value::F32(v)).collect())),
            Storage::Unorm8 | Storage::Unorm16 => {
                let codes = super::unorm::codes(table, lut, storage)?;
                return Ok(Values(codes.into_iter().map(Value::Code).collect()));
            }
            Storage::F16 => {}
        }
        Ok(Values(
            f16_values(table, lut)?
                .into_iter()
                .map(Value::Half)
                .collect(),
        ))
    }

    /// Writes the values, one block per table row (x varying), each block preceded by a
    /// comment naming its y and z, `PER_LINE` values per line, every value followed by a comma.
    fn write_rows(
        &self,
        out: &mut String,
        lut: &Lut,
        comment_open: &str,
        comment_close: &str,
        format: &dyn Fn(Value) -> String,
    ) {
        let nc = lut.channels.len();
        let row_len = lut.dim(0) * nc;
        // whole texels per line
        let per_line = (PER_LINE / nc).max(1) * nc;
        for (r, row) in self.0.chunks(row_len).enumerate() {
            let (y, z) = (r % lut.dim(1), r / lut.dim(1));
            let mut label = String::new();
            for (k, i) in [(1usize, y), (2, z)] {
                if let Some(a) = lut.axes.get(k) {
                    if !label.is_empty() {
                        label.push_str(", ");
                    }
                    if a.warp.is_coupled() {
                        // (its coordinate differs along the fresnel axis: the parameter)
                        let _ = write!(
                            label,
                            "{} = {i}: {} at p = {}",
                            ["x", "y", "z"][k],
                            a.name,
                            a.parameter(i)
                        );
                        continue;
                    }
                    let _ = write!(
                        label,
                        "{} = {i}: {} = {}",
                        ["x", "y", "z"][k],
                        a.name,
                        a.coord(i)
                    );
                }
            }
            if !label.is_empty() {
                let label = label.replace("*/", "* /");
                let _ = writeln!(out, "{comment_open}{label}{comment_close}");
            }
            for line in row.chunks(per_line) {
                out.push_str("   ");
                for &v in line {
                    out.push(' ');
                    out.push_str(&format(v));
                    out.push(',');
                }
                out.push('\n');
            }
        }
    }
}

/// The note on a `scale` attribute other than 1.
fn scale_lines(attributes: &[(String, String)]) -> Vec<String> {
    match scale_attribute(attributes) {
        Some(s) => vec![
            String::new(),
            format!("Scale: the stored values are the computed values times {s} (attribute `scale`): divide by {s}."),
        ],
        None => Vec::new(),
    }
}

/// The comment dialect a description is written for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Lang {
    C,
    Rust,
}

/// (constant suffix, value, doc) of the size constants.
fn size_constants(lut: &Lut) -> Vec<(&'static str, usize, String)> {
    let along = |k: usize| match lut.axes.get(k) {
        Some(a) => format!(
            "Texels along {} (axis {k}, `{}`).",
            ["x", "y", "z"][k],
            a.name
        ),
        None => format!(
            "Texels along {} (1: the table has {} axes).",
            ["x", "y", "z"][k],
            lut.axes.len()
        ),
    };
    vec![
        ("WIDTH", lut.dim(0), along(0)),
        ("HEIGHT", lut.dim(1), along(1)),
        ("DEPTH", lut.dim(2), along(2)),
        (
            "CHANNELS",
            lut.channels.len(),
            "Channels per texel, interleaved.".to_string(),
        ),
    ]
}

/// The description comment of a generated source file (lines without comment markers).
fn description(table: &str, id: &str, lut: &Lut, storage: Storage, lang: Lang) -> Vec<String> {
    let mut d = vec![
        format!("brdfbake lookup table `{table}`: generated, do not edit."),
        String::new(),
    ];
    let storage = match (storage, lang) {
        (Storage::F16, Lang::C) => "uint16_t IEEE 754 binary16 bit patterns, rounded to nearest even from the baked f32 values",
        (Storage::F16, Lang::Rust) => "u16 IEEE 754 binary16 bit patterns (half::f16::from_bits), rounded to nearest even from the baked f32 values",
        (Storage::F32, Lang::C) => {
            "float, the baked f32 values exactly (every literal parses back to the same bits)"
        }
        (Storage::F32, Lang::Rust) => {
            "f32, the baked f32 values exactly (every literal parses back to the same bits)"
        }
        (Storage::Unorm8, Lang::C) => "uint8_t UNORM8 codes: value = code / 255, code = round(baked f32 value * 255), ties to even (upload as R8/RG8/RGBA8 UNORM: the sampler returns code / 255)",
        (Storage::Unorm8, Lang::Rust) => "u8 UNORM8 codes: value = code / 255, code = round(baked f32 value * 255), ties to even (upload as R8/RG8/RGBA8 UNORM: the sampler returns code / 255)",
        (Storage::Unorm16, Lang::C) => "uint16_t UNORM16 codes: value = code / 65535, code = round(baked f32 value * 65535), ties to even (upload as R16/RG16/RGBA16 UNORM: the sampler returns code / 65535)",
        (Storage::Unorm16, Lang::Rust) => "u16 UNORM16 codes: value = code / 65535, code = round(baked f32 value * 65535), ties to even (upload as R16/RG16/RGBA16 UNORM: the sampler returns code / 65535)",
    };
    d.push(format!(
        "{id}[((z * {id}_HEIGHT + y) * {id}_WIDTH + x) * {id}_CHANNELS + c]: {storage}."
    ));
    d.push(
        "x (axis 0) varies fastest and is the texture's u; y (axis 1) is v, one texture row per y; \
         z (axis 2) is the slice of a 3D table."
            .into(),
    );
    d.push(
        "Texture uploads: row y = 0 is the first row in memory, which every graphics API samples \
         at v = 0 (no y-flip)."
            .into(),
    );
    d.push(String::new());
    d.push("Axes:".into());
    for (k, a) in lut.axes.iter().enumerate() {
        d.extend(axis_lines(k, a));
    }
    d.push(String::new());
    d.push(format!(
        "Channels ({} per texel, interleaved):",
        lut.channels.len()
    ));
    for (c, ch) in lut.channels.iter().enumerate() {
        d.push(format!("  {c} {}: {}", ch.name, ch.meaning));
    }
    d
}

/// The quantity of an axis as the metadata names it (`cosine`, `roughness:perceptual`).
pub(crate) fn quantity_name(a: &Axis) -> String {
    match a.quantity {
        Quantity::Cosine => "cosine".into(),
        Quantity::Roughness(q) => format!("roughness:{} ({})", q.name(), q.mapping()),
        Quantity::Fresnel(q) => format!("fresnel:{} ({})", q.name(), q.mapping()),
        Quantity::Anisotropy => {
            format!("anisotropy ({})", crate::table::classic::ANISOTROPY_MAPPING)
        }
        Quantity::FormFactor => {
            "form-factor (of a vector form factor: the z of its direction, or its length)".into()
        }
    }
}

/// Description lines of axis `k`: name, quantity, range, convention, the coordinate each
/// texel holds and the texture coordinate to sample.
pub(crate) fn axis_lines(k: usize, a: &Axis) -> Vec<String> {
    let [lo, hi] = a.range;
    let n = a.size;
    let texture_axis = ["u", "v", "w (slice)"][k.min(2)];
    let letter = ["x", "y", "z"][k.min(2)];
    let linear = a.warp == Warp::Linear;
    let mut head = format!(
        "  {letter} (axis {k}, texture {texture_axis}): {} = {}, range [{lo}, {hi}], {n} texels, convention {}",
        a.name,
        quantity_name(a),
        a.convention.name()
    );
    if !linear {
        // (the range is the parameter's)
        head.push_str(&format!(
            ", warp {}: {} with x = {}, the range is p's",
            a.warp.name(),
            a.warp.formula(),
            a.name
        ));
    }
    if let Some([c0, c1]) = a.clamp {
        head.push_str(&format!(", values at {} clamped to [{c0}, {c1}]", a.name));
    }
    let mut v = vec![head];
    // the name of what is uniform in the texels: the coordinate, or the warp's parameter
    let p = if linear { a.name.as_str() } else { "p" };
    let (texel, remap) = if n == 1 {
        (
            format!("the single texel holds {} = {}", a.name, a.coord(0)),
            "sample at 0.5 (a single texel: the coordinate does not matter)".to_string(),
        )
    } else {
        match a.convention {
            Convention::Centers => (
                format!("texel i holds {p} = {lo} + ({hi} - {lo}) * (i + 0.5) / {n}"),
                "sample at t directly (texel centres hold the values)".to_string(),
            ),
            Convention::Endpoints => (
                format!("texel i holds {p} = {lo} + ({hi} - {lo}) * i / ({n} - 1)"),
                format!("sample at (0.5 + t * ({n} - 1)) / {n} (the range ends are texel centres)"),
            ),
        }
    };
    v.push(format!("      {texel}"));
    if !linear {
        v.push(format!(
            "      {} = {} (the inverse of the warp)",
            a.name,
            a.warp.inverse_formula().trim_start_matches("x = ")
        ));
        v.push(format!(
            "      p = {} with x = {} clamped to [0, 1]",
            a.warp.formula().trim_start_matches("p = "),
            a.name
        ));
    }
    v.push(format!(
        "      t = clamp(({p} - {lo}) / ({hi} - {lo}), 0, 1); {remap}"
    ));
    v
}

/// The `scale` attribute (stored texel = value × scale) when it is a number other than 1.
pub(crate) fn scale_attribute(attributes: &[(String, String)]) -> Option<f64> {
    let (_, v) = attributes.iter().find(|(k, _)| k == "scale")?;
    let s: f64 = v.trim().parse().ok()?;
    (s.is_finite() && s > 0.0 && s != 1.0).then_some(s)
}

/// `key: value` lines of the attributes, in order.
pub(crate) fn attribute_lines(attributes: &[(String, String)]) -> Vec<String> {
    if attributes.is_empty() {
        return vec!["  (none)".into()];
    }
    attributes
        .iter()
        .map(|(k, v)| format!("  {k}: {}", v.replace('\n', "\n      ")))
        .collect()
}

/// Splits text into lines that are safe inside a line comment: no line breaks, no other
/// control characters (they become spaces), no trailing whitespace, and no trailing
/// backslash (which would continue a `//` comment onto the next line in C-like languages).
pub(crate) fn comment_lines(text: &str) -> Vec<String> {
    text.split('\n')
        .map(|line| {
            let mut l: String = line
                .chars()
                .map(|c| if c.is_control() { ' ' } else { c })
                .collect();
            l.truncate(l.trim_end().len());
            if l.ends_with('\\') {
                l.push_str(" (end of line)");
            }
            l
        })
        .collect()
}

/// Text safe inside a one-line `///` doc comment.
fn rust_doc_text(s: &str) -> String {
    comment_lines(s).join(" ")
}

/// The upper-case identifier of a table: non-identifier characters become `_`, and `LUT_`
/// is prepended unless the result starts with an ASCII letter.
pub fn constant_identifier(table_name: &str) -> String {
    identifier(table_name).to_ascii_uppercase()
}

/// The identifier of a table, in the name's own case (see [`constant_identifier`]).
pub(crate) fn identifier(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
        s.insert_str(0, "LUT_");
    }
    s
}

/// A C `float` literal that parses to exactly `v` (finite): Rust's shortest round-trip
/// representation, with `.0` added when it has neither point nor exponent, and `f`.
fn c_float(v: f32) -> String {
    let mut s = format!("{v:?}");
    if !s.contains(['.', 'e', 'E']) {
        s.push_str(".0");
    }
    s.push('f');
    s
}

/// A C string literal of `s`: printable ASCII as is (with `"` and `\` escaped), every other
/// byte as a three-digit octal escape.
fn c_string(s: &str) -> String {
    let mut out = String::from("\"");
    for b in s.bytes() {
        match b {
            b'"' | b'\\' => {
                out.push('\\');
                out.push(b as char);
            }
            // `?` escaped too: no trigraphs
            b'?' => out.push_str("\\?"),
            0x20..=0x7e => out.push(b as char),
            _ => {
                let _ = write!(out, "\\{b:03o}");
            }
        }
    }
    out.push('"');
    out
}

/// Every value of `lut` as IEEE 754 binary16, rounded to nearest (ties to even), or the
/// error naming the channel whose largest value is beyond the f16 range (never an infinity).
pub(crate) fn f16_values(table: &str, lut: &Lut) -> Result<Vec<f16>, EncodeError> {
    let nc = lut.channels.len().max(1);
    let halves: Vec<f16> = lut.data.iter().map(|&v| f16::from_f32(v)).collect();
    if let Some(i) = halves.iter().position(|h| h.is_infinite()) {
        let c = i % nc;
        let largest =
            lut.data.iter().skip(c).step_by(nc).fold(
                0.0f32,
                |m, &v| {
                    if v.abs() > m.abs() {
                        v
                    } else {
                        m
                    }
                },
            );
        return Err(EncodeError::Unrepresentable {
            table: table.to_string(),
            channel: lut.channels[c].name.clone(),
            value: largest as f64,
            format: "f16 (IEEE 754 binary16, largest finite value 65504)",
        });
    }
    Ok(halves)
}

/// Checks what every encoder in this family needs: 1 to 3 axes of at least one texel, at
/// least one channel, data of the right length, and finite values.
pub(crate) fn check_table(table: &str, lut: &Lut) -> Result<(), EncodeError> {
    let shape = |reason: String| EncodeError::Shape {
        table: table.to_string(),
        reason,
    };
    if lut.axes.is_empty() || lut.axes.len() > 3 {
        return Err(shape(format!(
            "a table has 1 to 3 axes, this one has {}",
            lut.axes.len()
        )));
    }
    if let Some(a) = lut.axes.iter().find(|a| a.size == 0) {
        return Err(shape(format!("axis `{}` has no texels", a.name)));
    }
    if lut.channels.is_empty() {
        return Err(shape("the table has no channels".into()));
    }
    let samples = lut
        .axes
        .iter()
        .try_fold(lut.channels.len(), |n, a| n.checked_mul(a.size))
        .ok_or_else(|| shape("the table is too large".into()))?;
    if lut.data.len() != samples {
        return Err(shape(format!(
            "{samples} samples expected, the data has {}",
            lut.data.len()
        )));
    }
    let nc = lut.channels.len();
    if let Some(i) = lut.data.iter().position(|v| !v.is_finite()) {
        let t = i / nc;
        let (nx, ny) = (lut.dim(0), lut.dim(1));
        return Err(EncodeError::NonFinite {
            table: table.to_string(),
            channel: lut.channels[i % nc].name.clone(),
            texel: [t % nx, (t / nx) % ny, t / (nx * ny)],
            value: lut.data[i] as f64,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::Channel;

    fn lut(values: &[f32]) -> Lut {
        Lut {
            axes: vec![Axis {
                name: "cos_theta".into(),
                quantity: Quantity::Cosine,
                size: values.len(),
                range: [0.0, 1.0],
                convention: Convention::Centers,
                warp: Default::default(),
                clamp: None,
            }],
            channels: vec![Channel {
                name: "v".into(),
                meaning: "test".into(),
            }],
            data: values.to_vec(),
            error_estimate: vec![0.0],
            evaluations: 0,
        }
    }

    #[test]
    fn identifiers() {
        assert_eq!(constant_identifier("dfg-ms"), "DFG_MS");
        assert_eq!(constant_identifier("1d_table"), "LUT_1D_TABLE");
        assert_eq!(constant_identifier("_x"), "LUT__X");
        assert_eq!(constant_identifier("été"), "LUT__T_");
    }

    #[test]
    fn c_literals() {
        assert_eq!(c_float(1.0), "1.0f");
        assert_eq!(c_float(-0.0), "-0.0f");
        assert_eq!(c_float(1e-8), "1e-8f");
        assert_eq!(c_float(0.1), "0.1f");
        assert_eq!(c_string("a\"b\\c?\u{e9}"), "\"a\\\"b\\\\c\\?\\303\\251\"");
    }

    #[test]
    fn comments_cannot_be_escaped() {
        let attrs = vec![(
            "note".to_string(),
            "ends */ here\r\nnext line \\".to_string(),
        )];
        let h = CHeader {
            table_name: "t".into(),
            storage: Storage::F32,
        };
        let text = String::from_utf8(h.encode(&lut(&[1.0, 2.0]), &attrs).unwrap()).unwrap();
        let body = &text[..text.find("#ifndef").unwrap()];
        assert_eq!(body.matches("*/").count(), 1, "{body}");
        assert!(
            body.contains(" *       next line \\ (end of line)\n"),
            "{body}"
        );
    }

    #[test]
    fn half_overflow_and_non_finite_are_errors() {
        let h = CHeader {
            table_name: "t".into(),
            storage: Storage::F16,
        };
        match h.encode(&lut(&[1.0, 7e4, -1e5]), &[]).unwrap_err() {
            EncodeError::Unrepresentable { value, .. } => assert_eq!(value, -1e5),
            e => panic!("{e:?}"),
        }
        let r = RustSource {
            table_name: "t".into(),
            storage: Storage::F32,
        };
        assert!(matches!(
            r.encode(&lut(&[1.0, f32::NAN]), &[]),
            Err(EncodeError::NonFinite {
                texel: [1, 0, 0],
                ..
            })
        ));
    }
}
