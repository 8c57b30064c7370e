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
    let f32 = spec.storage == Storage::F32;
    let mut w = Vec::new();
    match engine {
        Engine::Threejs => {
            if dims == 3 && table.layout_3d == Layout3d::Array && has(Format::Ktx2) {
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
            if !has(Format::Exr) {
                w.push(
                    "Unreal imports no KTX2 files: add \"exr\" to the formats (docs/engines.md)"
                        .to_string(),
                );
            }
        }
        Engine::Unity => {
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
            if dims == 3 && has(Format::Ktx2) {
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
        Engine::Filament => {}
        Engine::Blender => {
            if dims == 3 {
                w.push(
                    "Blender's Image Texture node samples 2D images only: a 3D table cannot be \
                     sampled in Blender's shader nodes (bake 2D tables)"
                        .to_string(),
                );
            }
            if !has(Format::Exr) {
                w.push(
                    "Blender reads no KTX2 files: add \"exr\" to the formats (docs/engines.md)"
                        .to_string(),
                );
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
