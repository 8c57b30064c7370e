//! Engine targets (a preset table's optional `engine` field): what cannot work, or needs a
//! step the user must know, when a table is used in a given engine. `bake` prints these as
//! warnings and the sidecar records them; docs/engines.md gives the details and sources.

pub use crate::preset::Engine;
use crate::preset::{Format, Layout3d, PresetTable};
use crate::table::Storage;

/// What does not work, or needs a step, for `table` in its engine (none without one), with
/// the table's formats as they are written (`bake --format` overrides the preset's).
pub fn warnings(table: &PresetTable) -> Vec<String> {
    let Some(engine) = table.engine else {
        return Vec::new();
    };
    let spec = &table.spec;
    let dims = spec.axes.len();
    let has = |f: Format| table.formats.contains(&f);
    let has_ktx2 = table.formats.iter().any(|f| f.is_ktx2());
    let f32 = spec.storage == Storage::F32;
    let unorm16 = spec.storage == Storage::Unorm16;
    let unorm = spec.storage.is_unorm();
    let nc = table.stored_channels().len();
    let mut w = Vec::new();
    match engine {
        Engine::Threejs => {
            if unorm16 {
                w.push(
                    "WebGL2 samples 16-bit normalized textures only with the EXT_texture_norm16 \
                     extension (three.js asks for it and otherwise leaves the texture incomplete); many \
                     browsers lack it, Chromium on SwiftShader among them (tests/gpu_path.rs): \
                     \"storage\": \"unorm8\" or \"f16\" samples everywhere"
                        .to_string(),
                );
                if has_ktx2 && nc <= 2 {
                    w.push(format!(
                        "three.js' KTX2Loader (r187) reads R16G16B16A16_UNORM only: this {nc}-channel \
                         table's {} file fails with \"Unsupported vkFormat\"; store 3 or 4 channels \
                         (e.g. \"channels\" padded with \"0\") or build a DataTexture from the .h/.rs \
                         codes (docs/engines.md)",
                        if nc == 1 { "R16_UNORM" } else { "R16G16_UNORM" }
                    ));
                }
            }
            if has(Format::PngData) {
                w.push(
                    "three.js loads a PNG through the browser's image decoder, as 8 bits per sample (a \
                     16-bit png-data table loses its low byte) and with Texture.flipY = true (the first \
                     row, y = 0, at v = 1): set flipY = false, or load the KTX2 (docs/engines.md)"
                        .to_string(),
                );
            }
            if dims == 3 && table.layout_3d == Layout3d::Array && has_ktx2 {
                w.push(
                    "three.js' KTX2Loader loads a 2D-array KTX2 as a 2D texture of its first layer \
                     (it ignores layerCount for uncompressed formats): use \"layout_3d\": \"volume\" \
                     (a Data3DTexture), or build a DataArrayTexture from the file yourself \
                     (docs/engines.md)"
                        .to_string(),
                );
            }
            if f32 {
                w.push(
                    "WebGL2 filters 32-bit float textures only with OES_texture_float_linear, which \
                     many mobile GPUs lack (the texture is then incomplete and samples as 0, 0, 0, 1): \
                     \"storage\": \"f16\" filters everywhere"
                        .to_string(),
                );
            }
        }
        Engine::Webgpu => {
            if unorm16 {
                w.push(
                    "WebGPU has r16unorm, rg16unorm and rgba16unorm only with the optional \
                     'texture-formats-tier1' feature, and even then not filterable \
                     ('unfilterable-float'): the linear sampler of the WGSL snippet cannot sample \
                     this table (tests/gpu_path.rs); \"storage\": \"unorm8\" or \"f16\" works on \
                     every device"
                        .to_string(),
                );
            }
            if f32 {
                w.push(
                    "WebGPU filters 32-bit float textures only on devices created with the optional \
                     'float32-filterable' feature (a bind group with a filtering sampler fails \
                     validation otherwise): \"storage\": \"f16\" works on every device"
                        .to_string(),
                );
            }
        }
        Engine::Bevy => {
            if unorm16 {
                w.push(
                    "wgpu has R16Unorm, Rg16Unorm and Rgba16Unorm only with \
                     Features::TEXTURE_FORMAT_16BIT_NORM, a native-only feature (not on the WebGPU or \
                     WebGL2 backends): \"storage\": \"unorm8\" or \"f16\" works everywhere"
                        .to_string(),
                );
            }
            if has(Format::PngData) {
                w.push(
                    "Bevy loads an 8-bit PNG as sRGB colour unless the loader settings say \
                     is_srgb: false: load the png-data file with ImageLoaderSettings { is_srgb: false, .. }, \
                     or load the KTX2 (docs/engines.md)"
                        .to_string(),
                );
            }
            if dims == 1 {
                w.push(
                    "Bevy's KTX2 loader makes a texture of height 1 a 1D texture, which the WGSL \
                     snippet's texture_2d cannot bind: set the loaded image's \
                     texture_descriptor.dimension to TextureDimension::D2 (docs/engines.md)"
                        .to_string(),
                );
            }
            if f32 {
                w.push(
                    "wgpu filters 32-bit float textures only with Features::FLOAT32_FILTERABLE (Bevy \
                     requests every feature the adapter has; WebGL2 and many WebGPU adapters lack it): \
                     \"storage\": \"f16\" works everywhere"
                        .to_string(),
                );
            }
        }
        Engine::Unreal => {
            if unorm && !has(Format::PngData) {
                w.push(
                    "Unreal imports no KTX2 files, and a normalized-integer table has no EXR: add \
                     \"png-data\" to the formats (Unreal imports 8- and 16-bit PNGs; docs/engines.md)"
                        .to_string(),
                );
            } else if !unorm && !has(Format::Exr) {
                w.push(
                    "Unreal imports no KTX2 files: add \"exr\" to the formats (docs/engines.md)"
                        .to_string(),
                );
            }
            if has(Format::PngData) {
                w.push(
                    "Unreal imports a PNG as an sRGB colour texture by default: turn sRGB off in the \
                     texture's settings, or it decodes the data as sRGB (docs/engines.md)"
                        .to_string(),
                );
            }
        }
        Engine::Unity => {
            if has(Format::PngData) {
                w.push(
                    "Unity's texture importer puts an image's top row (this table's first row, y = 0) \
                     at v = 1 and imports PNGs as sRGB colour textures: untick sRGB (Color Texture) and \
                     sample the imported png-data at 1 - v, or load the KTX2's texels with \
                     LoadRawTextureData, whose first row is v = 0 (docs/engines.md)"
                        .to_string(),
                );
            }
            if has(Format::Exr) {
                w.push(
                    "Unity's texture importer puts an image's top row (this table's first row, y = 0) \
                     at v = 1: sample the imported EXR at 1 - v, or load the KTX2's texels with \
                     LoadRawTextureData, whose first row is v = 0 (docs/engines.md)"
                        .to_string(),
                );
            }
        }
        Engine::Godot => {
            if spec.storage == Storage::Unorm8 && has_ktx2 && nc == 2 {
                w.push(
                    "Godot's KTX loader reads R8G8_UNORM as FORMAT_LA8 (luminance and alpha): a shader \
                     reads this table's second channel in .a, not .g (and its first in .r, .g and .b); \
                     read .ra, or store it as \"unorm16\" (FORMAT_RG16) or \"f16\""
                        .to_string(),
                );
            }
            if spec.storage == Storage::Unorm8 && has_ktx2 && nc >= 3 {
                w.push(
                    "Godot's KTX loader has no R8G8B8A8_UNORM (it reads R8G8B8A8_SRGB and _UINT) and \
                     refuses this file (\"Unsupported format 37\"): store it as \"unorm16\" \
                     (FORMAT_RGBA16) or \"f16\", or import the png-data file (docs/engines.md)"
                        .to_string(),
                );
            }
            if unorm16 && has(Format::PngData) {
                w.push(
                    "Godot's PNG loader converts 16-bit samples to 8 bits: the png-data file loses its \
                     low byte there; load the KTX2 (R16_UNORM → FORMAT_R16 and so on) instead"
                        .to_string(),
                );
            }
            if dims == 3 && has_ktx2 {
                w.push(
                    "Godot's KTX loader reads 2D textures only (it refuses 3D and array KTX2 files): \
                     build a Texture3D or Texture2DArray from the slices in a script \
                     (docs/engines.md)"
                        .to_string(),
                );
            }
            let channels = table.stored_channels();
            let rgba = channels
                .iter()
                .zip(["R", "G", "B", "A"])
                .all(|(c, n)| c.name == n);
            if has(Format::Exr) && !rgba {
                let names: Vec<&str> = channels.iter().map(|c| c.name.as_str()).collect();
                w.push(format!(
                    "Godot's EXR loader maps channels by the names R, G, B, A (and Y) and refuses a file \
                     without R; this table's EXR channels are named {}: load the KTX2 instead",
                    names.join(", ")
                ));
            }
        }
        Engine::Filament => {
            if unorm16 {
                w.push(
                    "Filament's Texture::InternalFormat has no 16-bit normalized format (R16F, R16UI \
                     and R16I only): \"storage\": \"unorm8\" (R8, RG8, RGBA8 with Type::UBYTE) or \
                     \"f16\""
                        .to_string(),
                );
            }
        }
        Engine::Blender => {
            if dims == 3 {
                w.push(
                    "Blender's Image Texture node samples 2D images only: a 3D table cannot be \
                     sampled in Blender's shader nodes (bake 2D tables)"
                        .to_string(),
                );
            }
            if !has(Format::Exr) && !has(Format::PngData) {
                w.push(if unorm {
                    "Blender reads no KTX2 files, and a normalized-integer table has no EXR: add \
                     \"png-data\" to the formats (docs/engines.md)"
                        .to_string()
                } else {
                    "Blender reads no KTX2 files: add \"exr\" to the formats (docs/engines.md)"
                        .to_string()
                });
            } else {
                w.push(
                    "Blender puts an image's top row (this table's first row, y = 0) at v = 1: map \
                     the v coordinate to 1 - v (docs/engines.md)"
                        .to_string(),
                );
            }
        }
    }
    w
}
