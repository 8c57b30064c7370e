//! OpenEXR encoding: a single-part, uncompressed, scanline image with one FLOAT or HALF
//! channel per table channel.
//!
//! Layout: width = nx; height = ny for 2D tables, 1 for 1D tables, ny·nz for 3D tables, whose
//! slices are stacked vertically (slice z occupies rows `[z·ny, (z+1)·ny)`). The first
//! scanline in the file (the top row, data window y = 0) holds table row y = 0. Channels
//! carry the table's channel names; EXR stores them sorted alphabetically.
//!
//! Header attributes are written as EXR `string` attributes (UTF-8) after the standard ones,
//! in the order given, each key prefixed with `brdfbake:` unless it already contains a colon.
//!
//! The file is written here, byte by byte (OpenEXR file layout: magic number, version
//! field, header attributes, offset table, one chunk per scanline; each chunk its y and
//! byte count, then the row of each channel in the channels' order). The standard
//! attributes are the ones, in the order, that the `exr` crate writes for such an image
//! (files are byte-identical to those it wrote for brdfbake until 2026-11-30); the crate
//! still reads files ([`decode_exr`]). Writing here takes 3–4 ms for a 512² RGB f32 table
//! (much of it the page faults of the fresh 3 MB buffer), where the crate's writer with
//! its per-channel copies took 7–10 ms, serial after the bake.
//!
//! Determinism: pixel data are stored uncompressed, so the bytes depend only on the table
//! and the attributes — not on a deflate implementation.

use super::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::table::spec::Storage;
use ::exr::image::FlatSamples;
use ::exr::meta::attribute::Compression;
use ::exr::meta::header::standard_names;
use ::exr::prelude::traits::{read, ReadChannels, ReadLayers};
use half::f16;
use rayon::prelude::*;
use std::io::Cursor;

/// Encodes a table as an OpenEXR image (see the module documentation for the layout).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExrEncoder {
    /// Sample precision: FLOAT (f32) or HALF (f16, rounded to nearest, ties to even).
    pub storage: Storage,
    /// The table's name, used in error messages.
    pub table_name: String,
}

/// What [`decode_exr`] returns: width, height, the channels (name and row-major samples,
/// top row first, in file order — alphabetical), and the non-standard string attributes
/// (name as stored, value) in file order.
pub type DecodedExr = (usize, usize, Vec<(String, Vec<f32>)>, Vec<(String, String)>);

/// The prefix given to attribute keys that carry no namespace of their own.
pub const ATTRIBUTE_PREFIX: &str = "brdfbake:";

const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];
const LONG_NAMES_BIT: u32 = 1 << 10;
const DEEP_BIT: u32 = 1 << 11;
const MULTIPART_BIT: u32 = 1 << 12;
/// Attribute and channel names up to this length need no "long names" flag.
const SHORT_NAME_MAX: usize = 31;
/// The longest attribute or channel name EXR allows.
const LONG_NAME_MAX: usize = 255;

impl Encoder for ExrEncoder {
    fn extension(&self) -> &'static str {
        "exr"
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        let (width, height) = self.image_size(lut)?;
        let attributes = header_attributes(attributes)?;
        let mut channels = self.channels(lut)?;
        // EXR lists channels sorted by name (bytes)
        channels.sort_by(|a, b| a.name.as_bytes().cmp(b.name.as_bytes()));
        Ok(write_file(lut, (width, height), &channels, &attributes))
    }
}

/// EXR pixel types.
const HALF: i32 = 1;
const FLOAT: i32 = 2;

/// One channel as stored: its name, its index among the table's channels, EXR pixel type
/// ([`HALF`] or [`FLOAT`]) and bytes per sample.
struct ChannelOut {
    name: String,
    index: usize,
    pixel_type: i32,
    bytes_per_sample: usize,
}

/// The whole file: header (the standard attributes as the `exr` crate writes them, then the
/// string attributes), offset table and scanline chunks.
fn write_file(
    lut: &Lut,
    (width, height): (usize, usize),
    channels: &[ChannelOut],
    attributes: &[(Vec<u8>, Vec<u8>)],
) -> Vec<u8> {
    fn attribute(out: &mut Vec<u8>, name: &[u8], kind: &[u8], value: &[u8]) {
        out.extend_from_slice(name);
        out.push(0);
        out.extend_from_slice(kind);
        out.push(0);
        out.extend_from_slice(&(value.len() as i32).to_le_bytes());
        out.extend_from_slice(value);
    }
    let i32s = |v: &[i32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let window = i32s(&[0, 0, width as i32 - 1, height as i32 - 1]);
    let mut chlist = Vec::new();
    for c in channels {
        chlist.extend_from_slice(c.name.as_bytes());
        chlist.push(0);
        chlist.extend_from_slice(&c.pixel_type.to_le_bytes());
        // pLinear 0, three reserved bytes, x and y sampling 1
        chlist.extend_from_slice(&[0, 0, 0, 0]);
        chlist.extend_from_slice(&i32s(&[1, 1]));
    }
    chlist.push(0);
    let row_bytes: usize = channels.iter().map(|c| c.bytes_per_sample * width).sum();

    let mut header = Vec::new();
    header.extend_from_slice(&MAGIC);
    let long = channels.iter().any(|c| c.name.len() > SHORT_NAME_MAX)
        || attributes.iter().any(|(n, _)| n.len() > SHORT_NAME_MAX);
    let flags = 2u32 | if long { LONG_NAMES_BIT } else { 0 };
    header.extend_from_slice(&flags.to_le_bytes());
    attribute(
        &mut header,
        b"chunkCount",
        b"int",
        &(height as i32).to_le_bytes(),
    );
    attribute(&mut header, b"channels", b"chlist", &chlist);
    attribute(&mut header, b"compression", b"compression", &[0]);
    attribute(&mut header, b"lineOrder", b"lineOrder", &[0]);
    attribute(&mut header, b"displayWindow", b"box2i", &window);
    attribute(
        &mut header,
        b"pixelAspectRatio",
        b"float",
        &1.0f32.to_le_bytes(),
    );
    attribute(&mut header, b"screenWindowCenter", b"v2f", &[0; 8]);
    attribute(
        &mut header,
        b"screenWindowWidth",
        b"float",
        &1.0f32.to_le_bytes(),
    );
    attribute(&mut header, b"dataWindow", b"box2i", &window);
    attribute(&mut header, b"type", b"string", b"scanlineimage");
    for (name, value) in attributes {
        attribute(&mut header, name, b"string", value);
    }
    header.push(0);

    let chunk = 8 + row_bytes;
    let data_start = header.len() + 8 * height;
    // zeroed by the allocator (fresh pages from the OS, not written here), so the page faults
    // (~0.5 ms per MB on this machine) happen in the parallel writes below, not in a serial
    // fill
    let mut out = vec![0u8; data_start + height * chunk];
    out[..header.len()].copy_from_slice(&header);
    for (y, entry) in out[header.len()..data_start]
        .chunks_exact_mut(8)
        .enumerate()
    {
        entry.copy_from_slice(&((data_start + y * chunk) as u64).to_le_bytes());
    }
    // image row y holds texels y·width .. (y + 1)·width (3D slices stacked), channels
    // interleaved in the table's data; straight from there into the file, without a copy
    // per channel; rows in parallel (the same bytes however they are split)
    let nc = lut.channels.len();
    let rows = lut.data.par_chunks_exact(width * nc);
    let dst = out[data_start..].par_chunks_exact_mut(chunk);
    rows.zip(dst).enumerate().for_each(|(y, (row, dst))| {
        let (head, mut rest) = dst.split_at_mut(8);
        head[..4].copy_from_slice(&(y as i32).to_le_bytes());
        head[4..].copy_from_slice(&(row_bytes as i32).to_le_bytes());
        for c in channels {
            let (line, tail) = rest.split_at_mut(c.bytes_per_sample * width);
            let samples = row[c.index..].iter().step_by(nc);
            match c.pixel_type {
                FLOAT => line
                    .chunks_exact_mut(4)
                    .zip(samples)
                    .for_each(|(d, v)| d.copy_from_slice(&v.to_le_bytes())),
                _ => line
                    .chunks_exact_mut(2)
                    .zip(samples)
                    .for_each(|(d, &v)| d.copy_from_slice(&f16::from_f32(v).to_le_bytes())),
            }
            rest = tail;
        }
    });
    out
}

impl ExrEncoder {
    fn shape_error(&self, reason: impl Into<String>) -> EncodeError {
        EncodeError::Shape {
            table: self.table_name.clone(),
            reason: reason.into(),
        }
    }

    /// Image width and height, after checking that axes, channels and data agree.
    fn image_size(&self, lut: &Lut) -> Result<(usize, usize), EncodeError> {
        if lut.axes.is_empty() || lut.axes.len() > 3 {
            return Err(self.shape_error(format!(
                "an EXR table has 1 to 3 axes, this one has {}",
                lut.axes.len()
            )));
        }
        if let Some(a) = lut.axes.iter().find(|a| a.size == 0) {
            return Err(self.shape_error(format!("axis `{}` has no texels", a.name)));
        }
        if lut.channels.is_empty() {
            return Err(self.shape_error("the table has no channels"));
        }
        let too_large = || self.shape_error("the table is too large for an EXR image");
        let width = lut.dim(0);
        let height = lut.dim(1).checked_mul(lut.dim(2)).ok_or_else(too_large)?;
        if i32::try_from(width).is_err() || i32::try_from(height).is_err() {
            return Err(too_large());
        }
        let samples = width
            .checked_mul(height)
            .and_then(|n| n.checked_mul(lut.channels.len()))
            .ok_or_else(too_large)?;
        if lut.data.len() != samples {
            return Err(self.shape_error(format!(
                "{} samples expected ({width}×{height} texels × {} channels), the data has {}",
                samples,
                lut.channels.len(),
                lut.data.len()
            )));
        }
        Ok((width, height))
    }

    /// One EXR channel per table channel, in table order, samples converted and checked.
    fn channels(&self, lut: &Lut) -> Result<Vec<ChannelOut>, EncodeError> {
        let nc = lut.channels.len();
        let (nx, ny) = (lut.dim(0), lut.dim(1));
        let mut out: Vec<ChannelOut> = Vec::with_capacity(nc);
        let (pixel_type, bytes_per_sample) = match self.storage {
            Storage::F32 => (FLOAT, 4),
            Storage::F16 => (HALF, 2),
            Storage::Unorm8 | Storage::Unorm16 => {
                return Err(self.shape_error(format!(
                    "EXR has no normalized-integer sample type, so a {} table has no EXR file \
                     (formats that store it: ktx2, png-data, h, rs)",
                    self.storage.name()
                )))
            }
        };
        // one pass over all samples first (the per-channel scans below, strided, cost ~1 ms
        // at 512², and only find which channel and texel failed): f16 rounds |v| < 65520 to
        // at most 65504, and |v| ≥ 65520 to infinity
        let all_storable = match self.storage {
            Storage::F16 => lut.data.iter().all(|v| v.abs() < 65520.0),
            _ => lut.data.iter().all(|v| v.is_finite()),
        };
        for (c, channel) in lut.channels.iter().enumerate() {
            let name_error = |reason| EncodeError::ChannelName {
                table: self.table_name.clone(),
                channel: channel.name.clone(),
                reason,
            };
            let name = &channel.name;
            if name.is_empty() {
                return Err(name_error("it is empty"));
            }
            if !name.bytes().all(|b| b.is_ascii_graphic() || b == b' ') {
                return Err(name_error("only printable ASCII characters are allowed"));
            }
            if name.len() > LONG_NAME_MAX {
                return Err(name_error("it is longer than 255 bytes"));
            }
            if lut.channels[..c].iter().any(|other| other.name == *name) {
                return Err(name_error("another channel has the same name"));
            }

            if all_storable {
                out.push(ChannelOut {
                    name: name.clone(),
                    index: c,
                    pixel_type,
                    bytes_per_sample,
                });
                continue;
            }
            let values = || lut.data.iter().skip(c).step_by(nc).copied();
            if let Some((i, v)) = values().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(EncodeError::NonFinite {
                    table: self.table_name.clone(),
                    channel: name.clone(),
                    texel: [i % nx, (i / nx) % ny, i / (nx * ny)],
                    value: v as f64,
                });
            }
            match self.storage {
                Storage::F32 | Storage::Unorm8 | Storage::Unorm16 => {}
                Storage::F16 => {
                    if values().any(|v| f16::from_f32(v).is_infinite()) {
                        let largest =
                            values().fold(0.0f32, |m, v| if v.abs() > m.abs() { v } else { m });
                        return Err(EncodeError::Unrepresentable {
                            table: self.table_name.clone(),
                            channel: name.clone(),
                            value: largest as f64,
                            format: "f16 (EXR HALF, largest finite value 65504)",
                        });
                    }
                }
            }
            out.push(ChannelOut {
                name: name.clone(),
                index: c,
                pixel_type,
                bytes_per_sample,
            });
        }
        Ok(out)
    }
}

/// Header attributes as stored: (EXR name, value) byte strings.
type RawStrings = Vec<(Vec<u8>, Vec<u8>)>;

/// The attributes as (EXR name, value) byte strings, checked.
fn header_attributes(attributes: &[(String, String)]) -> Result<RawStrings, EncodeError> {
    let mut out: RawStrings = Vec::with_capacity(attributes.len());
    for (key, value) in attributes {
        let error = |reason: &str| EncodeError::Attribute {
            key: key.clone(),
            reason: reason.to_string(),
        };
        if key.is_empty() {
            return Err(error("the key is empty"));
        }
        let name = if key.contains(':') {
            key.clone()
        } else {
            format!("{ATTRIBUTE_PREFIX}{key}")
        };
        if name.contains('\0') {
            return Err(error("the key contains a NUL character"));
        }
        if name.len() > LONG_NAME_MAX {
            return Err(error(&format!(
                "the EXR attribute name `{name}` is longer than {LONG_NAME_MAX} bytes"
            )));
        }
        if i32::try_from(value.len()).is_err() {
            return Err(error("the value is too long"));
        }
        if out.iter().any(|(n, _)| n == name.as_bytes()) {
            return Err(error(&format!(
                "another attribute is also written as `{name}`"
            )));
        }
        out.push((name.into_bytes(), value.as_bytes().to_vec()));
    }
    Ok(out)
}

/// One attribute of a header, as stored.
struct RawAttribute<'a> {
    name: &'a [u8],
    kind: &'a [u8],
    value: &'a [u8],
}

/// The header of a single-part EXR file, as stored.
struct RawHeader<'a> {
    attributes: Vec<RawAttribute<'a>>,
}

/// Walks the header of a single-part, non-deep EXR file.
fn scan_header(bytes: &[u8]) -> Result<RawHeader<'_>, String> {
    fn take<'a>(bytes: &'a [u8], at: &mut usize, n: usize) -> Result<&'a [u8], String> {
        let s = at
            .checked_add(n)
            .and_then(|end| bytes.get(*at..end))
            .ok_or("the EXR header is truncated")?;
        *at += n;
        Ok(s)
    }
    fn cstr<'a>(bytes: &'a [u8], at: &mut usize) -> Result<&'a [u8], String> {
        let rest = bytes.get(*at..).unwrap_or(&[]);
        let n = rest
            .iter()
            .position(|&b| b == 0)
            .ok_or("the EXR header is truncated")?;
        *at += n + 1;
        Ok(&rest[..n])
    }

    if bytes.get(..4) != Some(&MAGIC[..]) {
        return Err("not an OpenEXR file (bad magic number)".into());
    }
    let mut at = 4;
    let version_flags = u32::from_le_bytes(take(bytes, &mut at, 4)?.try_into().unwrap());
    if version_flags & 0xff != 2 {
        return Err(format!("unsupported EXR version {}", version_flags & 0xff));
    }
    if version_flags & (DEEP_BIT | MULTIPART_BIT) != 0 {
        return Err("multi-part and deep EXR files are not supported".into());
    }
    let mut attributes = Vec::new();
    loop {
        let name = cstr(bytes, &mut at)?;
        if name.is_empty() {
            return Ok(RawHeader { attributes });
        }
        let kind = cstr(bytes, &mut at)?;
        let size = i32::from_le_bytes(take(bytes, &mut at, 4)?.try_into().unwrap());
        let size = usize::try_from(size).map_err(|_| "negative EXR attribute size")?;
        let value = take(bytes, &mut at, size)?;
        attributes.push(RawAttribute { name, kind, value });
    }
}

/// Reads an EXR file (any single-layer flat image, not only ours) with the `exr` crate, for
/// tests and inspection. String attributes are read from the header in file order; the
/// standard ones (e.g. `type`, `name`) are left out.
pub fn decode_exr(bytes: &[u8]) -> Result<DecodedExr, String> {
    let header = scan_header(bytes)?;
    let attributes = header
        .attributes
        .iter()
        .filter(|a| a.kind == b"string" && !standard_names::ALL.contains(&a.name))
        .map(|a| {
            (
                String::from_utf8_lossy(a.name).into_owned(),
                String::from_utf8_lossy(a.value).into_owned(),
            )
        })
        .collect();

    // Refuse a header that declares more pixels than the file holds before the decoder
    // allocates for them: brdfbake writes uncompressed files, whose pixel data is in the file,
    // and a hostile data window would otherwise ask for terabytes (found by the readback_exr
    // fuzz target, docs/fuzzing.md).
    let meta = ::exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), true)
        .map_err(|e| format!("reading EXR: {e}"))?;
    for h in meta.headers.iter() {
        if h.compression != Compression::Uncompressed {
            return Err(format!(
                "{:?} compression; brdfbake writes uncompressed EXR",
                h.compression
            ));
        }
        let (w, ht) = (h.layer_size.0, h.layer_size.1);
        let need = (w as u128) * (ht as u128) * (h.channels.bytes_per_pixel as u128);
        if need > bytes.len() as u128 {
            return Err(format!(
                "the header declares {w} x {ht} pixels ({need} bytes of samples), more than the file's {} bytes hold",
                bytes.len()
            ));
        }
    }
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .pedantic()
        .non_parallel()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| format!("reading EXR: {e}"))?;
    let [layer] = &image.layer_data[..] else {
        return Err(format!(
            "expected one layer, the file has {}",
            image.layer_data.len()
        ));
    };
    let channels = layer
        .channel_data
        .list
        .iter()
        .map(|c| {
            let values = match &c.sample_data {
                FlatSamples::F16(v) => v.iter().map(|h| h.to_f32()).collect(),
                FlatSamples::F32(v) => v.clone(),
                FlatSamples::U32(v) => v.iter().map(|&u| u as f32).collect(),
            };
            (String::from(c.name.clone()), values)
        })
        .collect();
    Ok((layer.size.0, layer.size.1, channels, attributes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::{Axis, Channel, Convention, Quantity};

    fn axis(name: &str, size: usize) -> Axis {
        Axis {
            name: name.into(),
            quantity: Quantity::Cosine,
            size,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        }
    }

    fn lut(sizes: &[usize], names: &[&str], f: impl Fn(usize, usize) -> f32) -> Lut {
        let axes: Vec<Axis> = sizes
            .iter()
            .enumerate()
            .map(|(k, &n)| axis(&format!("axis{k}"), n))
            .collect();
        let texels: usize = sizes.iter().product();
        let data = (0..texels)
            .flat_map(|t| (0..names.len()).map(move |c| (t, c)))
            .map(|(t, c)| f(t, c))
            .collect();
        Lut {
            axes,
            channels: names
                .iter()
                .map(|n| Channel {
                    name: n.to_string(),
                    meaning: format!("test {n}"),
                })
                .collect(),
            data,
            error_estimate: vec![0.0; names.len()],
            evaluations: 0,
        }
    }

    fn encoder(storage: Storage) -> ExrEncoder {
        ExrEncoder {
            storage,
            table_name: "test".into(),
        }
    }

    fn attrs(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect()
    }

    /// Channel `name` of a decoded file.
    fn plane<'a>(decoded: &'a DecodedExr, name: &str) -> &'a [f32] {
        &decoded.2.iter().find(|(n, _)| n == name).unwrap().1
    }

    #[test]
    fn f32_round_trip_layout_and_attributes() {
        let t = lut(&[5, 3], &["B", "A"], |t, c| {
            (t as f32 * 0.37 - 1.5) * if c == 0 { 1.0 } else { -1e-30 }
        });
        let a = attrs(&[
            ("zeta", "last key first"),
            ("alpha", "E(μ) = ∫ f cos θ dω"),
            ("other:ns", "kept as is"),
            ("a_rather_long_attribute_key_name", "long names flag"),
            ("empty", ""),
        ]);
        let bytes = encoder(Storage::F32).encode(&t, &a).unwrap();
        let d = decode_exr(&bytes).unwrap();
        assert_eq!((d.0, d.1), (5, 3));
        let names: Vec<&str> = d.2.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["A", "B"]);
        for (c, name) in ["B", "A"].iter().enumerate() {
            let expected: Vec<f32> = t.data.iter().skip(c).step_by(2).copied().collect();
            assert_eq!(plane(&d, name), &expected[..]);
        }
        let expected_attrs = attrs(&[
            ("brdfbake:zeta", "last key first"),
            ("brdfbake:alpha", "E(μ) = ∫ f cos θ dω"),
            ("other:ns", "kept as is"),
            (
                "brdfbake:a_rather_long_attribute_key_name",
                "long names flag",
            ),
            ("brdfbake:empty", ""),
        ]);
        assert_eq!(d.3, expected_attrs);
    }

    #[test]
    fn same_bytes_as_the_exr_crates_writer() {
        // brdfbake's files were written by the `exr` crate until 2026-11-30; the hand-written
        // writer keeps them byte-identical (without custom attributes, which the crate would
        // write in a random order): F32 and F16, 1D, 2D and 3D, channels given unsorted
        use ::exr::image::{AnyChannel, AnyChannels, Blocks, Encoding, Image, Layer};
        use ::exr::math::Vec2;
        use ::exr::meta::attribute::{LineOrder, Text};
        use ::exr::meta::header::LayerAttributes;
        use ::exr::prelude::traits::WritableImage;
        for sizes in [&[5][..], &[6, 4], &[4, 3, 2]] {
            let t = lut(sizes, &["z", "B", "a"], |t, c| {
                (t * 3 + c) as f32 / 7.0 - 1.0
            });
            for storage in [Storage::F32, Storage::F16] {
                let (w, h) = (t.dim(0), t.dim(1) * t.dim(2));
                let channels: Vec<AnyChannel<FlatSamples>> = t
                    .channels
                    .iter()
                    .enumerate()
                    .map(|(c, ch)| {
                        let v: Vec<f32> = t.data.iter().skip(c).step_by(3).copied().collect();
                        AnyChannel {
                            name: Text::new_or_none(&ch.name).unwrap(),
                            sample_data: match storage {
                                Storage::F16 => {
                                    FlatSamples::F16(v.iter().map(|&x| f16::from_f32(x)).collect())
                                }
                                _ => FlatSamples::F32(v),
                            },
                            quantize_linearly: false,
                            sampling: Vec2(1, 1),
                        }
                    })
                    .collect();
                let layer = Layer::new(
                    Vec2(w, h),
                    LayerAttributes::default(),
                    Encoding {
                        compression: Compression::Uncompressed,
                        blocks: Blocks::ScanLines,
                        line_order: LineOrder::Increasing,
                    },
                    AnyChannels::sort(channels.into()),
                );
                let mut crate_bytes = Vec::new();
                Image::from_layer(layer)
                    .write()
                    .non_parallel()
                    .to_buffered(Cursor::new(&mut crate_bytes))
                    .unwrap();
                let ours = encoder(storage).encode(&t, &[]).unwrap();
                assert!(ours == crate_bytes, "{sizes:?} {storage:?}");
            }
        }
    }

    #[test]
    fn encoding_is_deterministic() {
        let t = lut(&[7, 4, 3], &["x", "y", "z"], |t, c| {
            (t * 3 + c) as f32 / 7.0
        });
        let a: Vec<(String, String)> = (0..24)
            .map(|i| (format!("key{i}"), format!("value {i}")))
            .collect();
        for storage in [Storage::F32, Storage::F16] {
            let first = encoder(storage).encode(&t, &a).unwrap();
            for _ in 0..16 {
                assert_eq!(encoder(storage).encode(&t, &a).unwrap(), first);
            }
            let from_thread = std::thread::scope(|s| {
                s.spawn(|| encoder(storage).encode(&t, &a).unwrap())
                    .join()
                    .unwrap()
            });
            assert_eq!(from_thread, first);
        }
    }

    #[test]
    fn slices_stack_vertically_and_1d_is_one_row() {
        let t = lut(&[4, 3, 2], &["v"], |t, _| t as f32);
        let d = decode_exr(&encoder(Storage::F32).encode(&t, &[]).unwrap()).unwrap();
        assert_eq!((d.0, d.1), (4, 6));
        // image row r = z·ny + y; pixel (x, r) holds texel [x, y, z]
        for z in 0..2 {
            for y in 0..3 {
                for x in 0..4 {
                    assert_eq!(plane(&d, "v")[(z * 3 + y) * 4 + x], t.texel([x, y, z], 0));
                }
            }
        }
        let t = lut(&[9], &["E"], |t, _| t as f32 * 0.5);
        let d = decode_exr(&encoder(Storage::F16).encode(&t, &[]).unwrap()).unwrap();
        assert_eq!((d.0, d.1), (9, 1));
        assert_eq!(plane(&d, "E"), &t.data[..]);
    }

    /// Ties round to the even neighbour: 1 + 2⁻¹¹ lies halfway between 1 (even mantissa) and
    /// 1 + 2⁻¹⁰ (odd), 1 + 3·2⁻¹¹ halfway between 1 + 2⁻¹⁰ (odd) and 1 + 2⁻⁹ (even).
    #[test]
    fn f16_rounds_to_nearest_even() {
        let tie_down = 1.0 + 2f32.powi(-11);
        let tie_up = 1.0 + 3.0 * 2f32.powi(-11);
        let above_tie = f32::from_bits(tie_down.to_bits() + 1);
        let values = [tie_down, tie_up, above_tie, -tie_down, 65519.0, 1e-8];
        let t = lut(&[values.len()], &["v"], |t, _| values[t]);
        let d = decode_exr(&encoder(Storage::F16).encode(&t, &[]).unwrap()).unwrap();
        let expected = [
            1.0,
            1.0 + 2f32.powi(-9),
            1.0 + 2f32.powi(-10),
            -1.0,
            65504.0,
            f16::from_f32(1e-8).to_f32(),
        ];
        assert_eq!(plane(&d, "v"), &expected[..]);
        for (v, e) in values.iter().zip(expected) {
            assert_eq!(f16::from_f32(*v).to_f32(), e);
        }
    }

    #[test]
    fn f16_overflow_is_an_error_naming_the_largest_value() {
        for (bad, largest) in [(65520.0f32, 65520.0), (-7e4, -1e5)] {
            let t = lut(&[4], &["ok", "big"], |t, c| match (t, c) {
                (_, 0) => 1.0,
                (1, _) => bad,
                (2, _) if largest != bad => largest,
                _ => 2.0,
            });
            let err = encoder(Storage::F16).encode(&t, &[]).unwrap_err();
            match &err {
                EncodeError::Unrepresentable {
                    table,
                    channel,
                    value,
                    ..
                } => {
                    assert_eq!((table.as_str(), channel.as_str()), ("test", "big"));
                    assert_eq!(*value, largest as f64);
                }
                other => panic!("unexpected error {other:?}"),
            }
            assert!(err.to_string().contains("`big`"), "{err}");
            // f32 storage holds it
            assert!(encoder(Storage::F32).encode(&t, &[]).is_ok());
        }
    }

    #[test]
    fn non_finite_values_shape_and_names_are_errors() {
        let t = lut(&[3, 2], &["v"], |t, _| if t == 4 { f32::NAN } else { 0.0 });
        for storage in [Storage::F32, Storage::F16] {
            match encoder(storage).encode(&t, &[]).unwrap_err() {
                EncodeError::NonFinite { texel, .. } => assert_eq!(texel, [1, 1, 0]),
                other => panic!("unexpected error {other:?}"),
            }
        }
        let mut t = lut(&[3, 2], &["v"], |_, _| 0.0);
        t.data.pop();
        assert!(matches!(
            encoder(Storage::F32).encode(&t, &[]),
            Err(EncodeError::Shape { .. })
        ));
        let t = lut(&[3], &["v", "v"], |_, _| 0.0);
        assert!(matches!(
            encoder(Storage::F32).encode(&t, &[]),
            Err(EncodeError::ChannelName { .. })
        ));
        let t = lut(&[3], &["v"], |_, _| 0.0);
        for bad in [
            attrs(&[("a", "1"), ("brdfbake:a", "2")]),
            attrs(&[("", "x")]),
            attrs(&[("nul\0", "x")]),
            vec![("k".repeat(256), String::new())],
        ] {
            assert!(
                matches!(
                    encoder(Storage::F32).encode(&t, &bad),
                    Err(EncodeError::Attribute { .. })
                ),
                "{bad:?}"
            );
        }
    }
}
