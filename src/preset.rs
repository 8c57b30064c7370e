//! Presets: JSON files that name one or more tables to bake (schema `brdfbake.preset/1`,
//! documented in `docs/presets.md`). Parsing is strict — unknown fields, duplicate keys and
//! wrong types are errors that name the field's path, and every value is checked against
//! what is accepted before anything is baked.

use crate::lut::{Axis, Channel, Convention, Lut, Quantity};
use crate::model::{Fresnel, FresnelQuantity, Masking, NdfKind, RoughnessQuantity};
use crate::table::{DfgLayout, ModelSpec, Storage, TableKind, TableSpec};
use serde::Deserialize;
use std::path::Path;

/// The preset schema identifier.
pub const SCHEMA: &str = "brdfbake.preset/1";
/// Default per-texel quadrature tolerance (estimated absolute error).
pub const DEFAULT_TOLERANCE: f64 = 1e-7;
/// Largest preset file accepted.
pub const MAX_PRESET_BYTES: u64 = 1 << 20;

/// Output formats a table can be written in (the JSON sidecar is always written).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Deserialize, serde::Serialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// OpenEXR, f32 or f16 per `storage` (EXR has no normalized-integer type: not for
    /// unorm8/unorm16 tables).
    Exr,
    /// KTX 2.0, R/RG/RGBA 16- or 32-bit float or 8- or 16-bit UNORM per `storage` (3
    /// channels padded to 4).
    Ktx2,
    /// The KTX 2.0 texture of `ktx2` with its level supercompressed by Zstandard
    /// (`supercompressionScheme` 2): the same `TABLE.ktx2` name, smaller, inflated by the
    /// loader (libktx, three.js' `KTX2Loader`, Bevy with its `zstd` feature).
    Ktx2Zstd,
    /// DDS with the DX10 header: the same components as KTX2 in a DXGI format
    /// ([`crate::encode::dds`]), for Direct3D, Godot, OGRE and Babylon.js.
    Dds,
    /// 16-bit PNG previews for people (one greyscale image per channel and a false-colour
    /// image with a legend), never a texture to sample.
    Png,
    /// The texels of a unorm8/unorm16 table as an 8- or 16-bit PNG (`TABLE.png`): data to
    /// upload, not a preview ([`crate::encode::png_data`]).
    PngData,
    /// A three-channel f32/f16 table as Babylon.js' RGBD-encoded 8-bit RGBA PNG
    /// (`TABLE.png`, [`crate::encode::rgbd`]): value = (c/255)^2.2 / (a/255).
    PngRgbd,
    /// C/C++ header with the texels as a `float` (or half-bit `uint16_t`) array.
    H,
    /// Rust source with the texels as a `static` array.
    Rs,
    /// GLSL lookup function with the exact coordinate transform.
    Glsl,
    /// HLSL lookup function.
    Hlsl,
    /// WGSL lookup function.
    Wgsl,
    /// The texels as a NumPy `.npy` array ([`crate::encode::npy`]).
    Npy,
    /// The texels and header attributes as a NumPy `.npz` archive ([`crate::encode::npz`]).
    Npz,
    /// The texels as raw little-endian numbers, the layout in the sidecar
    /// ([`crate::encode::bin`]).
    Bin,
}

impl Format {
    pub const ALL: [Format; 15] = [
        Format::Exr,
        Format::Ktx2,
        Format::Ktx2Zstd,
        Format::Dds,
        Format::Png,
        Format::PngData,
        Format::PngRgbd,
        Format::H,
        Format::Rs,
        Format::Glsl,
        Format::Hlsl,
        Format::Wgsl,
        Format::Npy,
        Format::Npz,
        Format::Bin,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Format::Exr => "exr",
            Format::Ktx2 => "ktx2",
            Format::Ktx2Zstd => "ktx2-zstd",
            Format::Dds => "dds",
            Format::Png => "png",
            Format::PngData => "png-data",
            Format::PngRgbd => "png-rgbd",
            Format::H => "h",
            Format::Rs => "rs",
            Format::Glsl => "glsl",
            Format::Hlsl => "hlsl",
            Format::Wgsl => "wgsl",
            Format::Npy => "npy",
            Format::Npz => "npz",
            Format::Bin => "bin",
        }
    }

    /// Parses a comma-separated list such as `exr,ktx2,png` (for `--format`).
    pub fn parse_list(s: &str) -> Result<Vec<Format>, String> {
        let mut out = Vec::new();
        for part in s.split(',').map(str::trim) {
            let f = Format::ALL
                .iter()
                .find(|f| f.name() == part)
                .ok_or_else(|| {
                    format!(
                        "unknown format {part:?} (accepted: {})",
                        Format::ALL.map(|f| f.name()).join(", ")
                    )
                })?;
            if out.contains(f) {
                return Err(format!(
                    "{part:?} is listed twice; list each format once (accepted: {})",
                    Format::ALL.map(|f| f.name()).join(", ")
                ));
            }
            out.push(*f);
        }
        Format::check_combination(&out)?;
        Ok(out)
    }

    /// Formats that cannot be written together: `ktx2` and `ktx2-zstd` both write
    /// `TABLE.ktx2`.
    pub fn check_combination(formats: &[Format]) -> Result<(), String> {
        if formats.contains(&Format::Ktx2) && formats.contains(&Format::Ktx2Zstd) {
            return Err(
                "\"ktx2\" and \"ktx2-zstd\" both write TABLE.ktx2: list one of them (ktx2-zstd is the same texture with its level supercompressed by Zstandard)".into(),
            );
        }
        if formats.contains(&Format::PngData) && formats.contains(&Format::PngRgbd) {
            return Err(
                "\"png-data\" and \"png-rgbd\" both write TABLE.png: list one of them (png-data holds UNORM codes, png-rgbd Babylon.js' RGBD encoding of f32/f16 values)".into(),
            );
        }
        Ok(())
    }

    /// Whether this format writes the KTX2 texture (plain or supercompressed).
    pub fn is_ktx2(self) -> bool {
        matches!(self, Format::Ktx2 | Format::Ktx2Zstd)
    }
}

/// Whether `storage` can be written as `format`: `None` when it can, else why not and what
/// works instead. EXR has no normalized-integer sample type; `png-data` stores only
/// normalized integers.
pub fn format_refusal(storage: Storage, format: Format) -> Option<String> {
    match (format, storage.is_unorm()) {
        (Format::Exr, true) => Some(format!(
            "EXR has no normalized-integer sample type, so a {} table cannot be written as exr: \
             use ktx2, png-data, h or rs (or \"storage\": \"f16\" or \"f32\" for an EXR file)",
            storage.name()
        )),
        (Format::PngData, false) => Some(format!(
            "png-data holds normalized integers (an 8- or 16-bit PNG of the texels): it needs \
             \"storage\": \"unorm8\" or \"unorm16\"; a {} table is written as exr, ktx2, h or rs \
             (\"png\" gives previews for people)",
            storage.name()
        )),
        (Format::PngRgbd, true) => Some(format!(
            "png-rgbd encodes the table's values (Babylon.js' RGBD, 8 bits with a shared \
             divisor): it needs \"storage\": \"f32\" or \"f16\", not {}",
            storage.name()
        )),
        _ => None,
    }
}

/// An engine or API a table is baked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Engine {
    /// three.js (WebGL2), loading the KTX2 with `KTX2Loader`.
    Threejs,
    /// WebGPU (browsers; the raw API).
    Webgpu,
    /// Bevy (wgpu), loading the KTX2 with its image loader.
    Bevy,
    /// Unreal Engine (imports the EXR).
    Unreal,
    /// Unity (imports the EXR, or loads the KTX2 texels in a script).
    Unity,
    /// Godot 4 (loads the KTX2 with its `ktx` module).
    Godot,
    /// Filament (uploads the texels with `Texture::setImage`).
    Filament,
    /// Blender (Image Texture node, EXR).
    Blender,
}

impl Engine {
    pub const ALL: [Engine; 8] = [
        Engine::Threejs,
        Engine::Webgpu,
        Engine::Bevy,
        Engine::Unreal,
        Engine::Unity,
        Engine::Godot,
        Engine::Filament,
        Engine::Blender,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Engine::Threejs => "threejs",
            Engine::Webgpu => "webgpu",
            Engine::Bevy => "bevy",
            Engine::Unreal => "unreal",
            Engine::Unity => "unity",
            Engine::Godot => "godot",
            Engine::Filament => "filament",
            Engine::Blender => "blender",
        }
    }
}

/// How a 3D table is stored in a KTX2 file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Layout3d {
    /// A 3D texture (trilinear filtering across slices in hardware).
    Volume,
    /// A 2D array texture, one layer per slice (the shader interpolates between layers).
    Array,
}

/// A parsed, validated preset.
#[derive(Clone, Debug)]
pub struct Preset {
    pub name: String,
    pub description: String,
    /// Where the table an engine preset reproduces lives (`source`).
    pub source: Option<crate::engines::shipped::Source>,
    pub tables: Vec<PresetTable>,
}

/// One table of a preset.
#[derive(Clone, Debug)]
pub struct PresetTable {
    pub spec: TableSpec,
    pub formats: Vec<Format>,
    /// Stored value = computed value × scale (so that e.g. large D values fit f16); the
    /// metadata tells the shader to divide by it.
    pub scale: f64,
    pub layout_3d: Layout3d,
    /// The largest per-texel quadrature error estimate the preset accepts, when it accepts
    /// more than its tolerance (`accept_error_estimate`; recorded in the sidecar). `None`:
    /// a texel whose estimate exceeds the tolerance fails the bake.
    pub accept_error_estimate: Option<f64>,
    /// The engine the table is baked for (`engine`; recorded in the sidecar and, when set,
    /// the input hash): `bake` warns about what does not work there ([`crate::engine`]).
    pub engine: Option<Engine>,
    /// The order the axes are stored in (`axis_order`), as indices into the kind's axes
    /// ([`crate::table::TableKind::axis_names`]): stored axis k (texture u, v, w) is the
    /// kind's axis `order[k]`. `None`: the kind's order. Engines differ (Cycles and three.js
    /// put roughness along u, Filament n·v).
    pub axis_order: Option<Vec<usize>>,
    /// How the engine's own file holds this table (`shipped`), for `brdfbake compare`; no
    /// effect on the bake.
    pub shipped: Option<crate::engines::shipped::Shipped>,
    /// The channels stored (`channels`), in texture component order (R, G, B, A), each a
    /// function of the kind's computed channels ([`crate::table::channels`]). `None`: the
    /// kind's channels as computed. Engines differ (the glTF Sample Viewer's Charlie LUT
    /// holds its value in B, BSDL stores 1 − E).
    pub channels: Option<Vec<StoredChannel>>,
    /// A fit of the table's exact function to emit beside it (`fit`: `{"max_error": E}` or
    /// `{"max_ops": N}`, [`crate::fit::emit`]): `bake` writes `TABLE.fit.{glsl,…}` and the
    /// fit's sidecar `TABLE.fit.json`, and fails when no fit meets the request.
    pub fit: Option<crate::fit::request::Request>,
}

/// One stored channel of a table whose preset sets `channels`: what texture component k
/// holds, in terms of the kind's computed channels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StoredChannel {
    /// The kind's channel `i` as computed (`"E"`).
    Computed(usize),
    /// One minus the kind's channel `i` (`"1-E"`).
    OneMinus(usize),
    /// The kind's channel `i` clamped to [0, 1] (`"clamp01-E"`), as an engine that clamps
    /// what its generator writes (MaterialX's sheen albedo) stores it.
    Clamp01(usize),
    /// The constant 0 (`"0"`).
    Zero,
    /// The constant 1 (`"1"`).
    One,
}

impl StoredChannel {
    /// The stored value, from the computed channels' values.
    pub fn apply(self, computed: &[f64]) -> f64 {
        match self {
            StoredChannel::Computed(i) => computed[i],
            StoredChannel::OneMinus(i) => 1.0 - computed[i],
            StoredChannel::Clamp01(i) => computed[i].clamp(0.0, 1.0),
            StoredChannel::Zero => 0.0,
            StoredChannel::One => 1.0,
        }
    }

    /// [`Self::apply`] in f32, as the stored texels are computed from the baked f32 values
    /// (1 − v is rounded once, to the nearest f32).
    pub fn apply_f32(self, computed: &[f32]) -> f32 {
        match self {
            StoredChannel::Computed(i) => computed[i],
            StoredChannel::OneMinus(i) => (1.0 - computed[i] as f64) as f32,
            StoredChannel::Clamp01(i) => computed[i].clamp(0.0, 1.0),
            StoredChannel::Zero => 0.0,
            StoredChannel::One => 1.0,
        }
    }

    /// The computed channel it is made from, if any.
    pub fn source(self) -> Option<usize> {
        match self {
            StoredChannel::Computed(i) | StoredChannel::OneMinus(i) | StoredChannel::Clamp01(i) => {
                Some(i)
            }
            StoredChannel::Zero | StoredChannel::One => None,
        }
    }

    /// The preset's spelling (`"E"`, `"1-E"`, `"0"`, `"1"`), given the kind's channels.
    pub fn text(self, kind_channels: &[Channel]) -> String {
        match self {
            StoredChannel::Computed(i) => kind_channels[i].name.clone(),
            StoredChannel::OneMinus(i) => format!("1-{}", kind_channels[i].name),
            StoredChannel::Clamp01(i) => format!("clamp01-{}", kind_channels[i].name),
            StoredChannel::Zero => "0".into(),
            StoredChannel::One => "1".into(),
        }
    }

    /// The transform's name in the sidecar.
    pub fn transform(self) -> &'static str {
        match self {
            StoredChannel::Computed(_) => "identity",
            StoredChannel::OneMinus(_) => "one minus",
            StoredChannel::Clamp01(_) => "clamped to [0, 1]",
            StoredChannel::Zero => "constant 0",
            StoredChannel::One => "constant 1",
        }
    }

    /// Parses a preset entry against the kind's channels: `None` when it names none.
    pub fn parse(entry: &str, kind_channels: &[Channel]) -> Option<StoredChannel> {
        let find = |n: &str| kind_channels.iter().position(|c| c.name == n);
        match entry {
            "0" => Some(StoredChannel::Zero),
            "1" => Some(StoredChannel::One),
            _ => {
                if let Some(n) = entry.strip_prefix("1-") {
                    find(n).map(StoredChannel::OneMinus)
                } else if let Some(n) = entry.strip_prefix("clamp01-") {
                    find(n).map(StoredChannel::Clamp01)
                } else {
                    find(entry).map(StoredChannel::Computed)
                }
            }
        }
    }
}

/// The names of stored channels when a preset sets `channels`: the texture components.
pub const COMPONENT_NAMES: [&str; 4] = ["R", "G", "B", "A"];

impl PresetTable {
    /// Checks that the table can be written in `formats` (the preset's, or `bake --format`'s
    /// in their place): the first refusal of [`format_refusal`], naming the table.
    pub fn check_formats(&self, formats: &[Format]) -> Result<(), String> {
        Format::check_combination(formats)
            .map_err(|e| format!("table `{}`: {e}", self.spec.name))?;
        for f in formats {
            if let Some(why) = format_refusal(self.spec.storage, *f) {
                return Err(format!("table `{}`: {why}", self.spec.name));
            }
        }
        let nc = self.stored_channels().len();
        if formats.contains(&Format::PngRgbd) && nc != 3 {
            return Err(format!(
                "table `{}`: png-rgbd stores three channels (R, G, B; the shared divisor D goes in alpha), the table stores {nc}",
                self.spec.name
            ));
        }
        Ok(())
    }

    /// The baked table (the kind's channels, in the kind's axis order) as stored: its stored
    /// channels (`channels`) in its stored axis order (`axis_order`).
    pub fn stored(&self, lut: Lut) -> Lut {
        let lut = self.stored_channels_of(lut);
        match &self.axis_order {
            Some(order) => lut.permuted(order),
            None => lut,
        }
    }

    /// The baked table's stored channels (`channels`): every texel's stored values computed
    /// from its computed ones, the error estimates carried along (0 for the constants).
    fn stored_channels_of(&self, lut: Lut) -> Lut {
        let Some(stored) = &self.channels else {
            return lut;
        };
        let nc = lut.channels.len().max(1);
        let mut data = Vec::with_capacity(lut.data.len() / nc * stored.len());
        for texel in lut.data.chunks_exact(nc) {
            data.extend(stored.iter().map(|s| s.apply_f32(texel)));
        }
        Lut {
            channels: self.stored_channels(),
            data,
            error_estimate: stored
                .iter()
                .map(|s| s.source().map_or(0.0, |i| lut.error_estimate[i]))
                .collect(),
            ..lut
        }
    }

    /// The channels as stored: the kind's ([`crate::table::channels`]), or with `channels`
    /// set, the texture components R, G, B, A, each saying what it holds.
    pub fn stored_channels(&self) -> Vec<Channel> {
        let kind = crate::table::channels(&self.spec);
        let Some(stored) = &self.channels else {
            return kind;
        };
        stored
            .iter()
            .zip(COMPONENT_NAMES)
            .map(|(s, name)| Channel {
                name: name.to_string(),
                meaning: match *s {
                    StoredChannel::Computed(i) => {
                        format!("{}: {}", kind[i].name, kind[i].meaning)
                    }
                    StoredChannel::OneMinus(i) => format!(
                        "1 - {n}, one minus {n} = {}",
                        kind[i].meaning,
                        n = kind[i].name
                    ),
                    StoredChannel::Clamp01(i) => format!(
                        "clamp({n}, 0, 1), where {n} = {}",
                        kind[i].meaning,
                        n = kind[i].name
                    ),
                    StoredChannel::Zero => "the constant 0".into(),
                    StoredChannel::One => "the constant 1".into(),
                },
            })
            .collect()
    }

    /// The stored channels' values from the computed ones (e.g. exact values, for `verify`
    /// and `probe` to compare with the stored texels).
    pub fn stored_values(&self, computed: &[f64]) -> Vec<f64> {
        match &self.channels {
            Some(stored) => stored.iter().map(|s| s.apply(computed)).collect(),
            None => computed.to_vec(),
        }
    }

    /// The kind's `n` computed channels recovered from stored values (the inverse of
    /// [`Self::stored_values`]): `None` for a computed channel no stored channel holds.
    pub fn computed_from_stored(&self, stored: &[f64], n: usize) -> Vec<Option<f64>> {
        let Some(chans) = &self.channels else {
            return (0..n).map(|i| stored.get(i).copied()).collect();
        };
        let mut out = vec![None; n];
        for (s, &v) in chans.iter().zip(stored) {
            match *s {
                StoredChannel::Computed(i) if i < n => out[i] = Some(v),
                StoredChannel::OneMinus(i) if i < n => out[i] = Some(1.0 - v),
                _ => {}
            }
        }
        out
    }

    /// Error estimates of computed values carried to the stored channels (0 for constants).
    pub fn stored_errors(&self, computed: &[f64]) -> Vec<f64> {
        match &self.channels {
            Some(stored) => stored
                .iter()
                .map(|s| s.source().map_or(0.0, |i| computed[i]))
                .collect(),
            None => computed.to_vec(),
        }
    }

    /// The axes in their stored order.
    pub fn stored_axes(&self) -> Vec<Axis> {
        match &self.axis_order {
            Some(order) => order.iter().map(|&o| self.spec.axes[o].clone()).collect(),
            None => self.spec.axes.clone(),
        }
    }

    /// Physical coordinates given in the stored axis order (`x[k]` on stored axis k), in the
    /// kind's order, as [`crate::readback::exact_at`] takes them.
    pub fn to_kind_order(&self, x: &[f64]) -> Vec<f64> {
        match &self.axis_order {
            Some(order) => {
                let mut out = vec![0.0; x.len()];
                for (k, &o) in order.iter().enumerate() {
                    out[o] = x[k];
                }
                out
            }
            None => x.to_vec(),
        }
    }

    /// Texel indices given in the stored axis order, in the kind's order.
    pub fn texel_to_kind_order(&self, idx: [usize; 3]) -> [usize; 3] {
        match &self.axis_order {
            Some(order) => {
                let mut out = [0; 3];
                for (k, &o) in order.iter().enumerate() {
                    out[o] = idx[k];
                }
                out
            }
            None => idx,
        }
    }

    /// How many of the table's axes (the first ones) a texture unit filters: all of them,
    /// but the slices of a 3D table stored as a 2D array, which its shader blends itself.
    pub fn hardware_filtered_axes(&self) -> usize {
        let n = self.spec.axes.len();
        if n == 3 && self.layout_3d == Layout3d::Array {
            2
        } else {
            n
        }
    }
}

/// Why a preset was rejected.
#[derive(Debug, thiserror::Error)]
pub enum PresetError {
    #[error("{source_name}: invalid JSON at line {line}, column {column}: {msg}")]
    Syntax {
        source_name: String,
        line: usize,
        column: usize,
        msg: String,
    },
    #[error("{source_name}: {path}: {msg}")]
    Field {
        source_name: String,
        path: String,
        msg: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPreset {
    schema: String,
    #[serde(default)]
    description: String,
    #[serde(default)]
    source: Option<crate::engines::shipped::Source>,
    tables: Vec<RawTable>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTable {
    name: String,
    kind: TableKind,
    #[serde(default)]
    model: Option<RawModel>,
    axes: RawAxes,
    #[serde(default)]
    layout: Option<DfgLayout>,
    #[serde(default)]
    cloth: Option<bool>,
    #[serde(default)]
    cloth_alpha_min: Option<f64>,
    #[serde(default)]
    storage: Option<Storage>,
    #[serde(default)]
    tolerance: Option<f64>,
    #[serde(default)]
    formats: Option<Vec<Format>>,
    #[serde(default)]
    scale: Option<f64>,
    #[serde(default)]
    layout_3d: Option<Layout3d>,
    #[serde(default)]
    accept_error_estimate: Option<f64>,
    #[serde(default)]
    engine: Option<Engine>,
    #[serde(default)]
    axis_order: Option<Vec<String>>,
    #[serde(default)]
    shipped: Option<crate::engines::shipped::Shipped>,
    channels: Option<Vec<String>>,
    #[serde(default)]
    ltc: Option<RawLtc>,
    #[serde(default)]
    fit: Option<crate::fit::request::RawRequest>,
}

/// The `ltc` object of an `ltc` table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLtc {
    #[serde(default)]
    channels: Option<Vec<crate::table::LtcChannel>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawModel {
    #[serde(default)]
    ndf: Option<NdfKind>,
    #[serde(default)]
    masking: Option<Masking>,
    #[serde(default)]
    fresnel: Option<Fresnel>,
    #[serde(default)]
    diffuse: Option<f64>,
    #[serde(default)]
    diffuse_model: Option<crate::model::DiffuseModel>,
    #[serde(default)]
    classic: Option<crate::table::classic::ClassicModel>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawAxes {
    cos_theta: Option<RawAxis>,
    cos_theta_v: Option<RawAxis>,
    cos_theta_l: Option<RawAxis>,
    cos_theta_h: Option<RawAxis>,
    n_dot_l: Option<RawAxis>,
    n_dot_h: Option<RawAxis>,
    n_dot_v: Option<RawAxis>,
    roughness: Option<RawAxis>,
    fresnel: Option<RawAxis>,
    anisotropy: Option<RawAxis>,
    form_factor_z: Option<RawAxis>,
    form_factor_length: Option<RawAxis>,
}

impl RawAxes {
    fn take(&mut self, name: &str) -> Option<RawAxis> {
        match name {
            "cos_theta" => self.cos_theta.take(),
            "cos_theta_v" => self.cos_theta_v.take(),
            "cos_theta_l" => self.cos_theta_l.take(),
            "cos_theta_h" => self.cos_theta_h.take(),
            "n_dot_l" => self.n_dot_l.take(),
            "n_dot_h" => self.n_dot_h.take(),
            "n_dot_v" => self.n_dot_v.take(),
            "roughness" => self.roughness.take(),
            "fresnel" => self.fresnel.take(),
            "anisotropy" => self.anisotropy.take(),
            "form_factor_z" => self.form_factor_z.take(),
            "form_factor_length" => self.form_factor_length.take(),
            _ => None,
        }
    }

    fn remaining(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        let all = [
            ("cos_theta", &self.cos_theta),
            ("cos_theta_v", &self.cos_theta_v),
            ("cos_theta_l", &self.cos_theta_l),
            ("cos_theta_h", &self.cos_theta_h),
            ("n_dot_l", &self.n_dot_l),
            ("n_dot_h", &self.n_dot_h),
            ("n_dot_v", &self.n_dot_v),
            ("roughness", &self.roughness),
            ("fresnel", &self.fresnel),
            ("anisotropy", &self.anisotropy),
            ("form_factor_z", &self.form_factor_z),
            ("form_factor_length", &self.form_factor_length),
        ];
        for (n, a) in all {
            if a.is_some() {
                v.push(n);
            }
        }
        v
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxis {
    size: usize,
    #[serde(default)]
    range: Option<Vec<f64>>,
    #[serde(default)]
    convention: Option<Convention>,
    #[serde(default)]
    quantity: Option<RawQuantity>,
    #[serde(default)]
    warp: Option<crate::lut::Warp>,
    #[serde(default)]
    clamp: Option<Vec<f64>>,
}

/// An axis quantity as written in a preset: a roughness quantity or a Fresnel quantity.
#[derive(Clone, Copy, Debug)]
enum RawQuantity {
    Roughness(RoughnessQuantity),
    Fresnel(FresnelQuantity),
}

impl<'de> Deserialize<'de> for RawQuantity {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        if let Some(q) = RoughnessQuantity::ALL.into_iter().find(|q| q.name() == s) {
            return Ok(RawQuantity::Roughness(q));
        }
        if let Some(q) = FresnelQuantity::from_name(&s) {
            return Ok(RawQuantity::Fresnel(q));
        }
        Err(serde::de::Error::custom(format!(
            "unknown quantity {s:?} (roughness axes accept {}; fresnel axes accept {})",
            RoughnessQuantity::ALL.map(|q| q.name()).join(", "),
            FresnelQuantity::ALL.map(|q| q.name()).join(", ")
        )))
    }
}

/// Parses a preset from JSON text. `source_name` is used in messages (a path or a name),
/// `name` is the preset's name (its file stem).
pub fn parse(text: &str, source_name: &str, name: &str) -> Result<Preset, PresetError> {
    // serde's derived structs also accept JSON arrays in place of objects; a preset is
    // objects all the way down, so check the shape first (this also reports syntax errors).
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| PresetError::Syntax {
        source_name: source_name.into(),
        line: e.line(),
        column: e.column(),
        msg: strip_position(&e.to_string()),
    })?;
    check_objects(&value).map_err(|(path, msg)| PresetError::Field {
        source_name: source_name.into(),
        path,
        msg,
    })?;
    check_no_null(&value, "").map_err(|(path, msg)| PresetError::Field {
        source_name: source_name.into(),
        path,
        msg,
    })?;
    let de = &mut serde_json::Deserializer::from_str(text);
    let raw: RawPreset = serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        // the text parsed as JSON above: a "syntax" error here is serde_json's report of a
        // value of the wrong type where a name is expected (`"layout_3d": 1`)
        if inner.is_syntax() && path != "." {
            return PresetError::Field {
                source_name: source_name.into(),
                msg: format!(
                    "must be one of the accepted names (a string, see docs/presets.md), got {} (line {}, column {})",
                    value_at(&value, &path).map_or("another type", kind_of),
                    inner.line(),
                    inner.column()
                ),
                path,
            };
        }
        if inner.is_syntax() || inner.is_eof() || path == "." {
            PresetError::Syntax {
                source_name: source_name.into(),
                line: inner.line(),
                column: inner.column(),
                msg: strip_position(&inner.to_string()),
            }
        } else {
            PresetError::Field {
                source_name: source_name.into(),
                path,
                msg: format!(
                    "{} (line {}, column {})",
                    strip_position(&inner.to_string()),
                    inner.line(),
                    inner.column()
                ),
            }
        }
    })?;
    let field = |path: String, msg: String| PresetError::Field {
        source_name: source_name.into(),
        path,
        msg,
    };
    if raw.schema != SCHEMA {
        return Err(field(
            "schema".into(),
            format!("expected {SCHEMA:?}, got {:?}", raw.schema),
        ));
    }
    if raw.tables.is_empty() {
        return Err(field(
            "tables".into(),
            "a preset needs at least one table".into(),
        ));
    }
    if raw.tables.len() > 64 {
        return Err(field(
            "tables".into(),
            format!("at most 64 tables per preset, got {}", raw.tables.len()),
        ));
    }
    let mut tables = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    for (i, t) in raw.tables.into_iter().enumerate() {
        let at = |f: &str| format!("tables[{i}].{f}");
        if !valid_name(&t.name) {
            return Err(field(
                at("name"),
                format!(
                    "{:?} is not a valid file stem: use 1-64 characters from a-z, A-Z, 0-9, '-', '_', not starting with '-'",
                    t.name
                ),
            ));
        }
        if !seen.insert(t.name.clone()) {
            return Err(field(
                at("name"),
                format!("{:?} is used by two tables of this preset", t.name),
            ));
        }
        let spec = table_spec(
            t.name.clone(),
            t.kind,
            t.model,
            t.axes,
            t.layout,
            t.cloth,
            t.cloth_alpha_min,
            t.storage,
            t.tolerance,
            t.ltc,
        )
        .map_err(|(p, m)| field(at(&p), m))?;
        spec.validate()
            .map_err(|m| field(format!("tables[{i}]"), m))?;
        // (EXR cannot hold normalized integers: a UNORM table's default file is the KTX2)
        let formats = t.formats.unwrap_or_else(|| {
            vec![if spec.storage.is_unorm() {
                Format::Ktx2
            } else {
                Format::Exr
            }]
        });
        if formats.is_empty() {
            return Err(field(
                at("formats"),
                format!(
                    "list at least one format (accepted: {})",
                    Format::ALL.map(|f| f.name()).join(", ")
                ),
            ));
        }
        for (k, f) in formats.iter().enumerate() {
            if formats[..k].contains(f) {
                return Err(field(
                    at(&format!("formats[{k}]")),
                    format!("{:?} is listed twice; list each format once", f.name()),
                ));
            }
            if let Some(why) = format_refusal(spec.storage, *f) {
                return Err(field(
                    at(&format!("formats[{k}]")),
                    format!(
                        "{:?} with \"storage\": {:?}: {why}",
                        f.name(),
                        spec.storage.name()
                    ),
                ));
            }
        }
        if let Some(a) = t.accept_error_estimate {
            if !(a.is_finite() && a >= spec.tolerance && a <= 1.0) {
                return Err(field(
                    at("accept_error_estimate"),
                    format!(
                        "must be a number in [tolerance, 1] = [{:e}, 1] (the largest per-texel error estimate accepted), got {a:e}",
                        spec.tolerance
                    ),
                ));
            }
        }
        let scale = t.scale.unwrap_or(1.0);
        if !(scale.is_finite() && scale > 0.0 && scale <= 1e30) {
            return Err(field(
                at("scale"),
                format!(
                    "must be a number in (0, 1e30], got {scale}",
                    scale = crate::numfmt::num(scale)
                ),
            ));
        }
        if t.layout_3d.is_some() && spec.axes.len() != 3 {
            return Err(field(at("layout_3d"), "applies to 3D tables only".into()));
        }
        let axis_order = match &t.axis_order {
            None => None,
            Some(names) => {
                let kind_axes = spec.kind.axis_names();
                let mut order = Vec::new();
                for (k, n) in names.iter().enumerate() {
                    let Some(o) = kind_axes.iter().position(|a| a == n) else {
                        return Err(field(
                            at(&format!("axis_order[{k}]")),
                            format!(
                                "{n:?} is not an axis of a {} table (its axes: {})",
                                spec.kind.name(),
                                kind_axes.join(", ")
                            ),
                        ));
                    };
                    if order.contains(&o) {
                        return Err(field(
                            at(&format!("axis_order[{k}]")),
                            format!("{n:?} is listed twice; list each axis once"),
                        ));
                    }
                    order.push(o);
                }
                if order.len() != kind_axes.len() {
                    return Err(field(
                        at("axis_order"),
                        format!(
                            "must list every axis of a {} table once, in the order stored (texture u first): {}",
                            spec.kind.name(),
                            kind_axes.join(", ")
                        ),
                    ));
                }
                // (the kind's own order is no reordering: the same table, the same hash)
                (order.iter().enumerate().any(|(k, &o)| k != o)).then_some(order)
            }
        };
        let channels = match &t.channels {
            None => None,
            Some(entries) => {
                let kind = crate::table::channels(&spec);
                let names: Vec<&str> = kind.iter().map(|c| c.name.as_str()).collect();
                let accepted = format!(
                    "a channel of the {} table ({}), \"1-NAME\" for one minus it (\"1-{}\"), \"clamp01-NAME\" for it clamped to [0, 1], or the constants \"0\" and \"1\"",
                    spec.kind.name(),
                    names.join(", "),
                    names[0]
                );
                if entries.is_empty() || entries.len() > 4 {
                    return Err(field(
                        at("channels"),
                        format!(
                            "lists {} entries: a texture stores 1 to 4 channels (R, G, B, A), each {accepted}",
                            entries.len()
                        ),
                    ));
                }
                let mut stored = Vec::new();
                for (k, e) in entries.iter().enumerate() {
                    let s = StoredChannel::parse(e, &kind).ok_or_else(|| {
                        field(
                            at(&format!("channels[{k}]")),
                            format!("{e:?} is not a stored channel: give {accepted}"),
                        )
                    })?;
                    stored.push(s);
                }
                if stored.iter().all(|s| s.source().is_none()) {
                    return Err(field(
                        at("channels"),
                        format!(
                            "stores only constants: store at least one of the table's channels ({})",
                            names.join(", ")
                        ),
                    ));
                }
                // (the kind's own channels in order are no change: the same table, the same
                // hash, the same files)
                let identity = stored.len() == kind.len()
                    && stored
                        .iter()
                        .enumerate()
                        .all(|(k, s)| *s == StoredChannel::Computed(k));
                (!identity).then_some(stored)
            }
        };
        let mut table = PresetTable {
            spec,
            formats,
            scale,
            layout_3d: t.layout_3d.unwrap_or(Layout3d::Volume),
            accept_error_estimate: t.accept_error_estimate,
            engine: t.engine,
            axis_order,
            shipped: None,
            channels,
            fit: None,
        };
        if let Some(mut sh) = t.shipped {
            // the file's channels name stored channels: by their names (R, G, … when the
            // table sets `channels`) or as the preset spells them ("1-E")
            let kind = crate::table::channels(&table.spec);
            let stored = table.stored_channels();
            let spelled: Vec<String> = match &table.channels {
                Some(c) => c.iter().map(|s| s.text(&kind)).collect(),
                None => stored.iter().map(|c| c.name.clone()).collect(),
            };
            // (a spelling first: with `"channels": ["A", "B", "0"]` the file's "B" is the
            // split sum's B, stored in component G, not component B)
            sh.spelled = sh.channels.clone();
            for c in sh.channels.iter_mut() {
                if let Some(k) = spelled.iter().position(|x| x == c) {
                    *c = stored[k].name.clone();
                }
            }
            let names: Vec<String> = stored.into_iter().map(|c| c.name).collect();
            sh.validate(&names).map_err(|m| field(at("shipped"), m))?;
            let axes: Vec<(String, usize)> = table
                .stored_axes()
                .iter()
                .map(|a| (a.name.clone(), a.size))
                .collect();
            sh.validate_degenerate(&axes)
                .map_err(|m| field(at("shipped"), m))?;
            table.shipped = Some(sh);
        }
        if let Some(f) = &t.fit {
            let req = f.check().map_err(|m| field(at("fit"), m))?;
            crate::fit::grid::points(&table.spec)
                .map_err(|m| field(at("fit"), format!("this table cannot be fitted: {m}")))?;
            table.fit = Some(req);
        }
        tables.push(table);
    }
    Ok(Preset {
        name: name.into(),
        description: raw.description,
        source: raw.source,
        tables,
    })
}

/// Reads and parses a preset file (at most [`MAX_PRESET_BYTES`]).
pub fn load(path: &Path) -> Result<Preset, LoadError> {
    if !path.exists() {
        return Err(LoadError::Input(format!(
            "{}: no such preset file",
            path.display()
        )));
    }
    let bytes =
        crate::input::read_regular(path, MAX_PRESET_BYTES, "a preset .json file").map_err(|e| {
            match e {
                crate::input::InputError::Input(m) => LoadError::Input(m),
                crate::input::InputError::Io(m) => LoadError::Unreadable(m),
            }
        })?;
    if bytes.starts_with(b"\xef\xbb\xbf") {
        return Err(LoadError::Input(format!(
            "{}: starts with a UTF-8 byte order mark (EF BB BF); save the preset as UTF-8 without BOM",
            path.display()
        )));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        LoadError::Input(format!(
            "{}: not UTF-8 text (invalid byte at offset {})",
            path.display(),
            e.utf8_error().valid_up_to()
        ))
    })?;
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("")
        .to_string();
    if !valid_name(&name) {
        return Err(LoadError::Input(format!(
            "{}: the file stem {name:?} is the preset's name and output folder; use 1-64 characters \
             from a-z, A-Z, 0-9, '-', '_', not starting with '-'",
            path.display()
        )));
    }
    parse(&text, &path.display().to_string(), &name).map_err(|e| LoadError::Input(e.to_string()))
}

/// Why a preset could not be loaded: bad input (exit 2) or the environment (exit 1).
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error("{0}")]
    Input(String),
    /// The file exists but could not be read (exit 1).
    #[error("{0}")]
    Unreadable(String),
}

/// Every place of the schema that holds an object must hold one (not an array).
/// One rule for every field: `null` is never a value in a preset (an optional field is left
/// out for its default; `null` used to mean that for some fields and be refused for others).
fn check_no_null(v: &serde_json::Value, path: &str) -> Result<(), (String, String)> {
    use serde_json::Value;
    match v {
        Value::Null => Err((
            if path.is_empty() { "(top level)".into() } else { path.to_string() },
            "is null: a preset takes no null anywhere; leave an optional field out for its default (docs/presets.md)".into(),
        )),
        Value::Object(m) => m.iter().try_for_each(|(k, x)| {
            check_no_null(x, &if path.is_empty() { k.clone() } else { format!("{path}.{k}") })
        }),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .try_for_each(|(i, x)| check_no_null(x, &format!("{path}[{i}]"))),
        _ => Ok(()),
    }
}

fn check_objects(v: &serde_json::Value) -> Result<(), (String, String)> {
    use serde_json::Value;
    let need = |v: &Value, path: &str| -> Result<(), (String, String)> {
        match v {
            Value::Object(_) => Ok(()),
            Value::Null => check_no_null(v, path),
            other => Err((
                path.to_string(),
                format!("must be a JSON object {{...}}, got {}", kind_of(other)),
            )),
        }
    };
    need(v, "(top level)")?;
    if let Some(Value::Array(tables)) = v.get("tables") {
        for (i, t) in tables.iter().enumerate() {
            need(t, &format!("tables[{i}]"))?;
            for key in ["model", "axes", "ltc"] {
                if let Some(x) = t.get(key) {
                    need(x, &format!("tables[{i}].{key}"))?;
                }
            }
            if let Some(Value::Object(axes)) = t.get("axes") {
                for (k, a) in axes {
                    need(a, &format!("tables[{i}].axes.{k}"))?;
                }
            }
            if let Some(f) = t.get("model").and_then(|m| m.get("fresnel")) {
                need(f, &format!("tables[{i}].model.fresnel"))?;
            }
            if let Some(c) = t.get("model").and_then(|m| m.get("classic")) {
                need(c, &format!("tables[{i}].model.classic"))?;
            }
        }
    }
    Ok(())
}

/// The value at a path such as `tables[0].engine` (serde_path_to_error's form).
fn value_at<'a>(v: &'a serde_json::Value, path: &str) -> Option<&'a serde_json::Value> {
    let mut v = v;
    for part in path.split('.') {
        let (key, index) = match part.split_once('[') {
            Some((k, i)) => (k, Some(i.trim_end_matches(']').parse::<usize>().ok()?)),
            None => (part, None),
        };
        if !key.is_empty() {
            v = v.get(key)?;
        }
        if let Some(i) = index {
            v = v.get(i)?;
        }
    }
    Some(v)
}

fn kind_of(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "a boolean",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Array(_) => "an array",
        serde_json::Value::Object(_) => "an object",
    }
}

/// Whether `s` is a valid preset or table name (a file stem and output folder): 1-64
/// characters from a-z, A-Z, 0-9, '-', '_', not starting with '-'.
pub fn valid_name(s: &str) -> bool {
    !s.is_empty()
        && s.len() <= 64
        && !s.starts_with('-')
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
}

/// serde_json appends " at line L column C"; we report the position ourselves.
fn strip_position(s: &str) -> String {
    match s.rfind(" at line ") {
        Some(i) => s[..i].to_string(),
        None => s.to_string(),
    }
}

#[allow(clippy::too_many_arguments)]
fn table_spec(
    name: String,
    kind: TableKind,
    model: Option<RawModel>,
    mut axes: RawAxes,
    layout: Option<DfgLayout>,
    cloth: Option<bool>,
    cloth_alpha_min: Option<f64>,
    storage: Option<Storage>,
    tolerance: Option<f64>,
    ltc: Option<RawLtc>,
) -> Result<TableSpec, (String, String)> {
    let masking_list = Masking::ALL
        .iter()
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ");
    let model = match model {
        Some(m) => m,
        None if kind == TableKind::Vgroove => RawModel {
            ndf: None,
            masking: Some(Masking::VGroove),
            fresnel: None,
            diffuse: None,
            diffuse_model: None,
            classic: None,
        },
        // (a closed form of geometry: no BRDF)
        None if kind == TableKind::LtcSphere => RawModel {
            ndf: None,
            masking: Some(Masking::None),
            fresnel: None,
            diffuse: None,
            diffuse_model: None,
            classic: None,
        },
        None => {
            return Err((
                "model".into(),
                format!("a {} table needs a model object", kind.name()),
            ))
        }
    };
    // a V-groove table is the V-groove masking alone: any other model field would be ignored
    if kind == TableKind::Vgroove {
        let given: Vec<&str> = [
            ("ndf", model.ndf.is_some()),
            // (the values that change nothing, as a sidecar writes them, are accepted)
            (
                "fresnel",
                model.fresnel.is_some_and(|f| !matches!(f, Fresnel::None)),
            ),
            ("diffuse", model.diffuse.is_some_and(|w| w != 0.0)),
            (
                "diffuse_model",
                model
                    .diffuse_model
                    .is_some_and(|m| m != crate::model::DiffuseModel::Lambert),
            ),
            ("classic", model.classic.is_some()),
            (
                "masking",
                model.masking.is_some_and(|m| m != Masking::VGroove),
            ),
        ]
        .into_iter()
        .filter_map(|(n, set)| set.then_some(n))
        .collect();
        if let Some(first) = given.first() {
            return Err((
                format!("model.{first}"),
                format!(
                    "a vgroove table is the V-groove masking alone (Cook & Torrance 1982); it takes no {} (leave the model out, or give {{\"masking\": \"v-groove\"}})",
                    given.join(", ")
                ),
            ));
        }
    }
    let masking = match (model.masking, kind) {
        (Some(m), _) => m,
        (None, TableKind::Ndf) => Masking::None,
        (None, TableKind::G1) => Masking::SmithSeparable,
        (None, TableKind::Vgroove) => Masking::VGroove,
        (None, k) if k.is_classic() => Masking::None,
        (None, TableKind::LtcSphere) => Masking::None,
        // (a Lambertian lobe has no masking)
        (None, TableKind::Ltc) if model.ndf.is_none() => Masking::None,
        (None, _) => {
            return Err((
                "model.masking".into(),
                format!(
                    "is required for a {} table (accepted: {masking_list})",
                    kind.name()
                ),
            ))
        }
    };
    if kind == TableKind::G1 && !masking.is_smith() {
        return Err((
            "model.masking".into(),
            "a g1 table is Smith's G1 by definition: omit masking or use smith-separable / smith-height-correlated".into(),
        ));
    }
    let model = ModelSpec {
        ndf: model.ndf,
        masking,
        fresnel: model.fresnel.unwrap_or(Fresnel::None),
        diffuse_weight: model.diffuse.unwrap_or(0.0),
        diffuse_model: model.diffuse_model.unwrap_or_default(),
        classic: model.classic,
    };
    let mut out_axes = Vec::new();
    for &an in kind.axis_names() {
        let raw = axes.take(an).ok_or_else(|| {
            (
                format!("axes.{an}"),
                format!(
                    "is required for a {} table (its axes: {})",
                    kind.name(),
                    kind.axis_names().join(", ")
                ),
            )
        })?;
        let is_rough = an == "roughness";
        let quantity = match (an, raw.quantity) {
            ("anisotropy", None) => Quantity::Anisotropy,
            ("form_factor_z" | "form_factor_length", None) => Quantity::FormFactor,
            ("form_factor_z" | "form_factor_length", Some(_)) => {
                return Err((
                    format!("axes.{an}.quantity"),
                    "a form-factor axis takes no quantity: its coordinate is the z of the vector form factor's direction ([-1, 1]) or its length ([0, 1])".into(),
                ))
            }
            ("anisotropy", Some(_)) => {
                return Err((
                    format!("axes.{an}.quantity"),
                    format!(
                        "the anisotropy axis takes no quantity: its coordinate is the anisotropy a in [0, 1] ({})",
                        crate::table::classic::ANISOTROPY_MAPPING
                    ),
                ))
            }
            ("roughness", Some(RawQuantity::Roughness(q))) => Quantity::Roughness(q),
            ("fresnel", Some(RawQuantity::Fresnel(q))) => Quantity::Fresnel(q),
            ("fresnel", _) => {
                return Err((
                    format!("axes.{an}.quantity"),
                    format!(
                        "is required: say what the fresnel axis means (accepted: {})",
                        FresnelQuantity::ALL.map(|q| q.name()).join(", ")
                    ),
                ))
            }
            (_, q) if is_rough && !matches!(q, Some(RawQuantity::Fresnel(_))) => {
                return Err((
                    format!("axes.{an}.quantity"),
                    format!(
                        "is required: say what the roughness axis means (accepted: {})",
                        RoughnessQuantity::ALL
                            .iter()
                            .map(|q| q.name())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ))
            }
            (_, Some(RawQuantity::Fresnel(q))) if is_rough => {
                return Err((
                    format!("axes.{an}.quantity"),
                    format!(
                        "{:?} is a Fresnel quantity; the roughness axis accepts {}",
                        q.name(),
                        RoughnessQuantity::ALL.map(|q| q.name()).join(", ")
                    ),
                ))
            }
            (_, Some(_)) => {
                return Err((
                    format!("axes.{an}.quantity"),
                    "only the roughness axis (or a fresnel axis) takes a quantity (this axis is a cosine)"
                        .into(),
                ))
            }
            (_, None) => Quantity::Cosine,
        };
        let range = match raw.range.as_deref() {
            None => [0.0, 1.0],
            Some(&[lo, hi]) => [lo, hi],
            Some(r) => {
                return Err((
                    format!("axes.{an}.range"),
                    format!("must be two numbers [lo, hi], got {} numbers", r.len()),
                ))
            }
        };
        let clamp = match raw.clamp.as_deref() {
            None => None,
            Some(&[lo, hi]) => Some([lo, hi]),
            Some(r) => {
                return Err((
                    format!("axes.{an}.clamp"),
                    format!("must be two numbers [lo, hi], got {} numbers", r.len()),
                ))
            }
        };
        out_axes.push(Axis {
            name: an.to_string(),
            quantity,
            size: raw.size,
            range,
            convention: raw.convention.unwrap_or(Convention::Centers),
            warp: raw.warp.unwrap_or_default(),
            clamp,
        });
    }
    let extra = axes.remaining();
    if !extra.is_empty() {
        return Err((
            format!("axes.{}", extra[0]),
            format!(
                "is not an axis of a {} table (its axes: {})",
                kind.name(),
                kind.axis_names().join(", ")
            ),
        ));
    }
    let ltc_channels = match (kind, ltc) {
        (TableKind::Ltc, l) => Some(
            l.and_then(|l| l.channels)
                .unwrap_or_else(|| crate::table::LtcChannel::DEFAULT.to_vec()),
        ),
        (_, None) => None,
        (_, Some(_)) => {
            return Err((
                "ltc".into(),
                format!("applies to ltc tables only, not {}", kind.name()),
            ))
        }
    };
    Ok(TableSpec {
        name,
        kind,
        model,
        axes: out_axes,
        dfg_layout: layout,
        cloth: cloth.unwrap_or(false),
        cloth_alpha_min,
        ltc_channels,
        storage: storage.unwrap_or(Storage::F32),
        tolerance: tolerance.unwrap_or(DEFAULT_TOLERANCE),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"{
      "schema": "brdfbake.preset/1",
      "tables": [{
        "name": "dfg", "kind": "dfg", "layout": "karis",
        "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
        "axes": {"cos_theta_v": {"size": 8}, "roughness": {"size": 8, "quantity": "perceptual"}}
      }]
    }"#;

    #[test]
    fn parses_a_good_preset() {
        let p = parse(GOOD, "t", "t").unwrap();
        assert_eq!(p.tables.len(), 1);
        assert_eq!(
            p.tables[0].spec.axes[1].quantity,
            Quantity::Roughness(RoughnessQuantity::Perceptual)
        );
    }

    fn err(text: &str) -> String {
        parse(text, "t", "t").unwrap_err().to_string()
    }

    #[test]
    fn errors_name_the_field() {
        let e = err(&GOOD.replace("\"ggx\"", "\"ggxx\""));
        assert!(
            e.contains("tables[0].model.ndf") && e.contains("beckmann"),
            "{e}"
        );
        let e = err(&GOOD.replace("\"size\": 8}, \"roughness\"", "\"size\": 0}, \"roughness\""));
        assert!(e.contains("axes.cos_theta_v.size"), "{e}");
        let e = err(&GOOD.replace(", \"quantity\": \"perceptual\"", ""));
        assert!(
            e.contains("tables[0].axes.roughness.quantity") && e.contains("perceptual"),
            "{e}"
        );
        let e = err(&GOOD.replace(
            "\"layout\": \"karis\",",
            "\"layout\": \"karis\", \"layout\": \"filament\",",
        ));
        assert!(e.contains("duplicate field"), "{e}");
        let e = err(&GOOD.replace("\"kind\": \"dfg\",", "\"kind\": \"dfg\", \"colour\": 1,"));
        assert!(e.contains("tables[0]") && e.contains("colour"), "{e}");
        let e = err("{\"schema\": ");
        assert!(e.contains("line 1"), "{e}");
        let e = err(&GOOD.replace("\"masking\": \"smith-height-correlated\"", "\"masking\": \"smith-height-correlated\", \"fresnel\": {\"type\": \"schlick\", \"f0\": 0.04}"));
        assert!(e.contains("fresnel must be none"), "{e}");
    }
}
