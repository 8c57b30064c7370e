//! 16-bit PNG previews of a table, for people to look at — never the texture to sample (8- or
//! 16-bit normalized values are not the baked values; sample the EXR or KTX2 texture).
//!
//! [`PngPreview::encode_all`] gives one greyscale image per channel, `preview-<channel>.png`,
//! whose grey levels map the channel's values linearly from `[min, max]` to `0..=65535`
//! (`round((v − min)/(max − min)·65535)`; all 0 when `max = min`), one pixel per texel; and
//! one false-colour RGB image of the first channel, `preview-<channel>-colour.png`, with each
//! texel enlarged to a block of pixels and a colour bar (with tick marks at 0, ¼, ½, ¾ and 1
//! of the range, labelled with their values to 4 significant digits in a 5×7 pixel font;
//! the in-between labels only where they fit) to its right. Every file carries tEXt chunks: the channel's `min` and `max`
//! (shortest round-trip f32 decimals), the mapping, the orientation, the axes, the note
//! "preview, not a texture", and the caller's attributes (tEXt when ASCII, else iTXt).
//!
//! Orientation: **y axis up**, like a plot — the bottom image row is y = 0 (the first
//! coordinate of axis 1, usually roughness), so the y axis reads upward; x = 0 is the left
//! column. A 3D table's slices are stacked upward: slice z occupies the image rows
//! `[H − (z+1)·ny, H − z·ny)` counted from the top, H = ny·nz. This is the EXR layout
//! (whose first row is y = 0) flipped vertically; the tEXt chunk `orientation` says so.
//!
//! Channel names become file-name suffixes with every character other than ASCII letters,
//! digits, `-` and `_` replaced by `_`.
//!
//! Determinism: fixed deflate level (flate2 level 9) and fixed filter choice (adaptive, a
//! function of the pixels only), so identical tables give identical bytes with the locked
//! versions of the `png` crate and its deflate backend.

use super::source::check_table;
use super::{EncodeError, Encoder};
use crate::lut::Lut;
use ::png::{BitDepth, ColorType, DeflateCompression, Filter};

/// Writes PNG previews of a table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PngPreview {
    /// The table's name: used in titles and error messages.
    pub table_name: String,
}

/// The note every preview carries.
pub const NOTE: &str = "preview, not a texture";

/// The orientation every preview states.
pub const ORIENTATION: &str =
    "y axis up: the bottom image row is y = 0 (the first coordinate of axis 1), \
     x = 0 is the left column; the slices of a 3D table are stacked upward (slice 0 at the \
     bottom); the EXR image has y = 0 at the top instead";

/// Longest side of a false-colour image's data area that enlarging aims for.
const TARGET_SIDE: usize = 256;
/// Largest enlargement of a texel in the false-colour image.
const MAX_SCALE: usize = 32;
/// Colour bar geometry, in pixels: gap between data and bar, bar width, tick length, margin.
const GAP: usize = 8;
const BAR: usize = 16;
const TICK: usize = 6;
const MARGIN: usize = 4;
/// Background and tick colours (16-bit grey levels).
const BACKGROUND: u16 = 0x2000;
const TICK_COLOUR: u16 = 0xffff;
/// Gap between a tick mark and its label, in glyph cells (a tick mark right before a label
/// would read as a minus sign).
const LABEL_GAP: usize = 1;

/// A 5×7 pixel font for the bar's numbers: per glyph, 7 rows top first, bit 4 the left
/// column.
const GLYPHS: [(char, [u8; 7]); 14] = [
    ('0', [0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e]),
    ('1', [0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e]),
    ('2', [0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f]),
    ('3', [0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e]),
    ('4', [0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02]),
    ('5', [0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e]),
    ('6', [0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e]),
    ('7', [0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08]),
    ('8', [0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e]),
    ('9', [0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c]),
    ('.', [0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c]),
    ('-', [0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00]),
    ('e', [0x00, 0x00, 0x0e, 0x11, 0x1f, 0x10, 0x0e]),
    ('+', [0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00]),
];

/// The rows of `c` in [`GLYPHS`] (blank for a character it lacks).
fn glyph(c: char) -> [u8; 7] {
    GLYPHS
        .iter()
        .find(|(g, _)| *g == c)
        .map_or([0; 7], |(_, rows)| *rows)
}

/// Pixel size of a glyph cell (5 columns and a gap, 7 rows) at `scale`.
fn cell(scale: usize) -> (usize, usize) {
    (6 * scale, 7 * scale)
}

/// Viridis (matplotlib), sampled at 0, 1/8, …, 1; interpolated linearly in between.
const VIRIDIS: [[f64; 3]; 9] = [
    [0.267004, 0.004874, 0.329415],
    [0.282623, 0.140926, 0.457517],
    [0.229739, 0.322361, 0.545706],
    [0.172719, 0.448791, 0.557885],
    [0.127568, 0.566949, 0.550556],
    [0.157851, 0.683765, 0.501686],
    [0.369214, 0.788888, 0.382914],
    [0.678489, 0.863742, 0.189503],
    [0.993248, 0.906157, 0.143936],
];

/// One image to write: size, colour type, big-endian 16-bit samples and text chunks.
struct Image {
    width: usize,
    height: usize,
    color: ColorType,
    samples: Vec<u16>,
    text: Vec<(String, String)>,
}

impl PngPreview {
    /// The previews of every channel and the false-colour image of the first channel:
    /// (file-name suffix, PNG bytes), e.g. `("preview-A.png", …)`.
    pub fn encode_all(&self, lut: &Lut) -> Result<Vec<(String, Vec<u8>)>, EncodeError> {
        self.encode_all_with_attributes(lut, &[])
    }

    /// [`PngPreview::encode_all`], with the caller's attributes written as text chunks too.
    pub fn encode_all_with_attributes(
        &self,
        lut: &Lut,
        attributes: &[(String, String)],
    ) -> Result<Vec<(String, Vec<u8>)>, EncodeError> {
        check_table(&self.table_name, lut)?;
        let suffixes = self.suffixes(lut);
        let mut out = Vec::new();
        for (c, suffix) in suffixes.iter().enumerate() {
            let image = self.greyscale(lut, c, attributes)?;
            out.push((format!("preview-{suffix}.png"), self.write(&image)?));
        }
        let image = self.false_colour(lut, 0, attributes)?;
        out.push((
            format!("preview-{}-colour.png", suffixes[0]),
            self.write(&image)?,
        ));
        Ok(out)
    }

    fn error(&self, reason: String) -> EncodeError {
        EncodeError::Shape {
            table: self.table_name.clone(),
            reason,
        }
    }

    /// File-name-safe channel names, made unique by appending the channel index.
    fn suffixes(&self, lut: &Lut) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for (c, ch) in lut.channels.iter().enumerate() {
            let mut s: String = ch
                .name
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                        c
                    } else {
                        '_'
                    }
                })
                .collect();
            if s.is_empty() || out.contains(&s) || s.ends_with("-colour") {
                s = format!("{s}{c}");
            }
            out.push(s);
        }
        out
    }

    /// Width and height of the data area at one pixel per texel.
    fn size(&self, lut: &Lut) -> Result<(usize, usize), EncodeError> {
        let (w, h) = (lut.dim(0), lut.dim(1) * lut.dim(2));
        if w > u32::MAX as usize / 2 || h > u32::MAX as usize / 2 {
            return Err(self.error("the table is too large for a PNG image".into()));
        }
        Ok((w, h))
    }

    /// The channel's values in image order (top row first: y axis up), its min and max.
    fn plane(&self, lut: &Lut, c: usize) -> (Vec<f32>, f32, f32) {
        let nc = lut.channels.len();
        let w = lut.dim(0);
        let values: Vec<f32> = lut.data.iter().skip(c).step_by(nc).copied().collect();
        let mut plane = Vec::with_capacity(values.len());
        for row in values.chunks(w).rev() {
            plane.extend_from_slice(row);
        }
        let min = values.iter().copied().fold(f32::INFINITY, f32::min);
        let max = values.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        (plane, min, max)
    }

    /// Text chunks common to every preview of channel `c`.
    fn text(
        &self,
        lut: &Lut,
        c: usize,
        min: f32,
        max: f32,
        how: Vec<(String, String)>,
        attributes: &[(String, String)],
    ) -> Vec<(String, String)> {
        let ch = &lut.channels[c];
        let mut t = vec![
            (
                "Title".to_string(),
                format!(
                    "brdfbake preview of table {}, channel {}",
                    self.table_name, ch.name
                ),
            ),
            (
                "Description".to_string(),
                format!(
                    "{NOTE}: 16-bit values mapped linearly from [min, max] of the channel; \
                     sample the EXR or KTX2 texture, never this image. Channel {}: {}",
                    ch.name, ch.meaning
                ),
            ),
            ("Software".to_string(), "brdfbake".to_string()),
            ("note".to_string(), NOTE.to_string()),
            ("channel".to_string(), ch.name.clone()),
            ("min".to_string(), format!("{min:?}")),
            ("max".to_string(), format!("{max:?}")),
        ];
        t.extend(how);
        t.push(("orientation".to_string(), ORIENTATION.to_string()));
        for (k, a) in lut.axes.iter().enumerate() {
            t.push((
                format!("image-{}", ["x", "y", "z"][k]),
                format!(
                    "axis {k} {} ({}), range [{}, {}], {} texels, convention {}",
                    a.name,
                    [
                        "left to right",
                        "bottom to top",
                        "slices stacked bottom to top"
                    ][k],
                    a.range[0],
                    a.range[1],
                    a.size,
                    a.convention.name()
                ),
            ));
        }
        t.extend(attributes.iter().cloned());
        t
    }

    fn greyscale(
        &self,
        lut: &Lut,
        c: usize,
        attributes: &[(String, String)],
    ) -> Result<Image, EncodeError> {
        let (width, height) = self.size(lut)?;
        let (plane, min, max) = self.plane(lut, c);
        let samples = plane.iter().map(|&v| level(v, min, max)).collect();
        let how = vec![(
            "mapping".to_string(),
            "grey = round((value - min) / (max - min) * 65535), 0 everywhere when max = min; \
             one pixel per texel"
                .to_string(),
        )];
        let text = self.text(lut, c, min, max, how, attributes);
        Ok(Image {
            width,
            height,
            color: ColorType::Grayscale,
            samples,
            text,
        })
    }

    fn false_colour(
        &self,
        lut: &Lut,
        c: usize,
        attributes: &[(String, String)],
    ) -> Result<Image, EncodeError> {
        let (w, h) = self.size(lut)?;
        let (plane, min, max) = self.plane(lut, c);
        let scale = |n: usize| TARGET_SIDE.div_ceil(n).clamp(1, MAX_SCALE);
        let (kx, ky) = (scale(w), scale(h));
        let (dw, dh) = (w * kx, h * ky);
        let bar_x = dw + GAP;
        let ticks = [0.0, 0.25, 0.5, 0.75, 1.0];
        let tick_values: Vec<String> = ticks
            .iter()
            .map(|f| format!("{}", min as f64 + f * (max as f64 - min as f64)))
            .collect();
        // the labels: 4 significant digits, twice the font's size on a tall image
        let font = if dh >= 128 { 2 } else { 1 };
        let (gw, gh) = cell(font);
        let labels: Vec<String> = ticks
            .iter()
            .map(|f| crate::numfmt::sig4(min as f64 + f * (max as f64 - min as f64)))
            .collect();
        let label_x = bar_x + BAR + TICK + LABEL_GAP * gw;
        let label_w = labels.iter().map(|l| l.len() * gw).max().unwrap_or(0);
        let width = label_x + label_w + MARGIN;
        let height = dh;
        let mut samples = vec![BACKGROUND; width * height * 3];
        let mut put = |x: usize, y: usize, rgb: [u16; 3]| {
            let i = (y * width + x) * 3;
            samples[i..i + 3].copy_from_slice(&rgb);
        };
        for y in 0..dh {
            for x in 0..dw {
                let v = plane[(y / ky) * w + x / kx];
                put(x, y, colour(level(v, min, max) as f64 / 65535.0));
            }
        }
        // the bar: bottom row = min, top row = max
        for y in 0..dh {
            let f = if dh > 1 {
                (dh - 1 - y) as f64 / (dh - 1) as f64
            } else {
                0.0
            };
            for x in bar_x..bar_x + BAR {
                put(x, y, colour(f));
            }
        }
        let tick_row = |f: f64| dh - 1 - (f * (dh - 1) as f64).round() as usize;
        for f in ticks {
            let y = tick_row(f);
            for x in bar_x + BAR..bar_x + BAR + TICK {
                put(x, y, [TICK_COLOUR; 3]);
            }
        }
        // labels centred on their tick, kept inside the image; min and max always, the
        // others where they clear the labels drawn (max first, then min, then upwards)
        let mut taken: Vec<usize> = Vec::new();
        let mut labelled = Vec::new();
        for k in [4, 0, 1, 2, 3] {
            let top = (tick_row(ticks[k]) + 1)
                .saturating_sub(gh.div_ceil(2))
                .min(dh.saturating_sub(gh));
            if k != 4 && k != 0 && taken.iter().any(|t| top.abs_diff(*t) < gh + 2) {
                continue;
            }
            taken.push(top);
            labelled.push(k);
            for (n, ch) in labels[k].chars().enumerate() {
                let rows = glyph(ch);
                for (r, bits) in rows.iter().enumerate() {
                    for col in 0..5 {
                        if bits & (0x10 >> col) == 0 {
                            continue;
                        }
                        for dy in 0..font {
                            for dx in 0..font {
                                let (x, y) =
                                    (label_x + n * gw + col * font + dx, top + r * font + dy);
                                if y < dh {
                                    put(x, y, [TICK_COLOUR; 3]);
                                }
                            }
                        }
                    }
                }
            }
        }
        labelled.sort_unstable();
        let how = vec![
            (
                "mapping".to_string(),
                format!(
                    "false colour (viridis): colour(round((value - min) / (max - min) * 65535) / 65535), \
                     the lowest colour everywhere when max = min; each texel is {kx} x {ky} pixels \
                     (the data area is the left {dw} x {dh} pixels)"
                ),
            ),
            (
                "legend".to_string(),
                format!(
                    "colour bar right of the data (columns {bar_x} to {}): bottom = min, top = max, \
                     linear; tick marks at 0, 1/4, 1/2, 3/4 and 1 of the range, i.e. values {}; \
                     labelled (from column {label_x}, 4 significant digits): {}",
                    bar_x + BAR - 1,
                    tick_values.join(", "),
                    labelled
                        .iter()
                        .map(|&k| labels[k].as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ),
        ];
        let text = self.text(lut, c, min, max, how, attributes);
        Ok(Image {
            width,
            height,
            color: ColorType::Rgb,
            samples,
            text,
        })
    }

    fn write(&self, image: &Image) -> Result<Vec<u8>, EncodeError> {
        let data: Vec<u8> = image.samples.iter().flat_map(|s| s.to_be_bytes()).collect();
        let size = (image.width as u32, image.height as u32);
        write_png(
            size,
            image.color,
            BitDepth::Sixteen,
            &image.text,
            &data,
            &|e| self.error(format!("PNG encoding failed: {e}")),
        )
    }
}

/// A PNG as both PNG writers make it: `data` the rows in PNG byte order, deflate level 9,
/// adaptive filters, `text` as tEXt chunks (ASCII) or iTXt chunks, each keyword once (a
/// repeated one is an error naming it).
pub(crate) fn write_png(
    (width, height): (u32, u32),
    color: ColorType,
    depth: BitDepth,
    text: &[(String, String)],
    data: &[u8],
    png_error: &dyn Fn(::png::EncodingError) -> EncodeError,
) -> Result<Vec<u8>, EncodeError> {
    let mut bytes = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    encoder.set_deflate_compression(DeflateCompression::Level(9));
    encoder.set_filter(Filter::Adaptive);
    let mut keywords: Vec<String> = Vec::with_capacity(text.len());
    for (key, value) in text {
        let keyword = text_keyword(key)?;
        if keywords.contains(&keyword) {
            return Err(EncodeError::Attribute {
                key: key.clone(),
                reason: format!("the PNG text keyword `{keyword}` is used twice"),
            });
        }
        keywords.push(keyword.clone());
        if value.is_ascii() {
            encoder.add_text_chunk(keyword, value.clone())
        } else {
            encoder.add_itxt_chunk(keyword, value.clone())
        }
        .map_err(png_error)?;
    }
    let mut writer = encoder.write_header().map_err(png_error)?;
    writer.write_image_data(data).map_err(png_error)?;
    writer.finish().map_err(png_error)?;
    Ok(bytes)
}

/// The false-colour image of the first channel, with the attributes as text chunks.
impl Encoder for PngPreview {
    fn extension(&self) -> &'static str {
        "png"
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        check_table(&self.table_name, lut)?;
        let image = self.false_colour(lut, 0, attributes)?;
        self.write(&image)
    }
}

/// The 16-bit level of `v` in `[min, max]`.
fn level(v: f32, min: f32, max: f32) -> u16 {
    if max > min {
        let f = (v as f64 - min as f64) / (max as f64 - min as f64);
        (f * 65535.0).round().clamp(0.0, 65535.0) as u16
    } else {
        0
    }
}

/// Viridis at `f` in [0, 1], as 16-bit RGB.
fn colour(f: f64) -> [u16; 3] {
    let x = f.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f64;
    let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let w = x - i as f64;
    let mut rgb = [0u16; 3];
    for (k, out) in rgb.iter_mut().enumerate() {
        let v = VIRIDIS[i][k] * (1.0 - w) + VIRIDIS[i + 1][k] * w;
        *out = (v * 65535.0).round() as u16;
    }
    rgb
}

/// A PNG text keyword for an attribute key: standard keywords as they are, others prefixed
/// with `brdfbake:` unless they contain a colon; 1 to 79 printable Latin-1 characters without
/// leading, trailing or double spaces.
pub(crate) fn text_keyword(key: &str) -> Result<String, EncodeError> {
    const STANDARD: [&str; 4] = ["Title", "Description", "Software", "Comment"];
    let keyword = if STANDARD.contains(&key) || key.contains(':') {
        key.to_string()
    } else {
        format!("brdfbake:{key}")
    };
    let error = |reason: &str| EncodeError::Attribute {
        key: key.to_string(),
        reason: reason.to_string(),
    };
    if key.is_empty() {
        return Err(error("the key is empty"));
    }
    if keyword.chars().count() > 79 {
        return Err(error("a PNG text keyword has at most 79 characters"));
    }
    if !keyword
        .chars()
        .all(|c| (' '..='~').contains(&c) || ('\u{a1}'..='\u{ff}').contains(&c))
    {
        return Err(error(
            "a PNG text keyword holds only printable Latin-1 characters",
        ));
    }
    if keyword.starts_with(' ') || keyword.ends_with(' ') || keyword.contains("  ") {
        return Err(error(
            "a PNG text keyword has no leading, trailing or consecutive spaces",
        ));
    }
    Ok(keyword)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_and_colours() {
        assert_eq!(level(1.0, 1.0, 3.0), 0);
        assert_eq!(level(3.0, 1.0, 3.0), 65535);
        assert_eq!(level(2.0, 1.0, 3.0), 32768);
        assert_eq!(level(2.0, 2.0, 2.0), 0);
        assert_eq!(colour(0.0), [17498, 319, 21588]);
        assert_eq!(colour(1.0)[0], 65093);
    }

    /// Reads the text the 5×7 font drew at (x, top): glyph cells until a blank one.
    fn read_label(img: &Image, x: usize, top: usize, font: usize) -> String {
        let white = |x: usize, y: usize| {
            y < img.height && img.samples[(y * img.width + x) * 3] == TICK_COLOUR
        };
        let (gw, _) = cell(font);
        let mut out = String::new();
        for n in 0.. {
            let x0 = x + n * gw;
            if x0 + 5 * font > img.width {
                break;
            }
            let rows: [u8; 7] = std::array::from_fn(|r| {
                (0..5).fold(0u8, |b, col| {
                    b | if white(x0 + col * font, top + r * font) {
                        0x10 >> col
                    } else {
                        0
                    }
                })
            });
            if rows == [0; 7] {
                break;
            }
            let c = GLYPHS.iter().find(|(_, g)| *g == rows).expect("a glyph");
            out.push(c.0);
        }
        out
    }

    /// The false-colour image prints the bar's minimum and maximum beside its ends: read
    /// back from the pixels, they are the channel's min and max to 4 significant digits;
    /// on a 1D table's 32-pixel image too (smaller font, middle label only where it fits).
    #[test]
    fn colour_bar_numbers_read_back() {
        use crate::lut::{Axis, Channel, Convention, Quantity};
        let axis = |n: usize| Axis {
            name: "x".into(),
            quantity: Quantity::Cosine,
            size: n,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        };
        // (sizes, min, max, labels drawn)
        for (sizes, lo, hi, drawn) in [
            (vec![16, 16], -4.935_667e-9f32, 21.786_14f32, 5),
            (vec![8], 0.25, 0.75, 3),
        ] {
            let n: usize = sizes.iter().product();
            let lut = Lut {
                axes: sizes.iter().map(|&s| axis(s)).collect(),
                channels: vec![Channel {
                    name: "B".into(),
                    meaning: "test".into(),
                }],
                data: (0..n)
                    .map(|k| lo + (hi - lo) * k as f32 / (n - 1) as f32)
                    .collect(),
                error_estimate: vec![0.0],
                evaluations: 0,
            };
            let p = PngPreview {
                table_name: "t".into(),
            };
            let img = p.false_colour(&lut, 0, &[]).unwrap();
            let font = if img.height >= 128 { 2 } else { 1 };
            let (_, gh) = cell(font);
            let kx = TARGET_SIDE.div_ceil(lut.dim(0)).clamp(1, MAX_SCALE);
            let bar_x = lut.dim(0) * kx + GAP;
            let x = bar_x + BAR + TICK + LABEL_GAP * cell(font).0;
            let top = read_label(&img, x, 0, font);
            let bottom = read_label(&img, x, img.height - gh, font);
            for (read, want) in [(&top, hi), (&bottom, lo)] {
                let v: f64 = read.parse().unwrap();
                let want = f64::from(want);
                assert!((v - want).abs() <= 5e-4 * want.abs(), "{read} for {want}");
            }
            let legend = &img.text.iter().find(|(k, _)| k == "legend").unwrap().1;
            let (_, list) = legend
                .split_once(&format!(
                    "labelled (from column {x}, 4 significant digits): "
                ))
                .expect("the labels");
            assert_eq!(list.split(", ").count(), drawn, "{legend}");
        }
    }

    #[test]
    fn keywords() {
        assert_eq!(text_keyword("min").unwrap(), "brdfbake:min");
        assert_eq!(text_keyword("Title").unwrap(), "Title");
        assert_eq!(text_keyword("x:y").unwrap(), "x:y");
        assert!(text_keyword("").is_err());
        assert!(text_keyword("a  b").is_err());
        assert!(text_keyword(&"k".repeat(80)).is_err());
        assert!(text_keyword("μ").is_err());
    }
}
