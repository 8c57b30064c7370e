//! Preset → files: bake every table of a preset, encode each in its formats plus the JSON
//! sidecar, and hand the bytes to [`crate::write`] — the only code that touches the disk.
//! Nothing is written until every table of the preset has baked and encoded, and then all
//! files are replaced atomically, so a failure never leaves a partial or mixed set.

use crate::encode::bin::RawBin;
use crate::encode::dds::DdsEncoder;
use crate::encode::exr::ExrEncoder;
use crate::encode::ktx2::{Ktx2Encoder, Supercompression};
use crate::encode::npy::Npy;
use crate::encode::npz::Npz;
use crate::encode::png::PngPreview;
use crate::encode::png_data::PngData;
use crate::encode::shader::{ShaderLang, ShaderSnippet};
use crate::encode::source::{CHeader, RustSource};
use crate::encode::{EncodeError, Encoder};
use crate::lut::Lut;
use crate::meta;
use crate::preset::{Format, Layout3d, Preset, PresetTable};
use crate::table::Storage;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// What one baked table produced.
#[derive(Debug)]
pub struct BakedTable {
    pub preset: String,
    pub table: String,
    pub lut: Lut,
    pub files: Vec<PathBuf>,
    pub elapsed: Duration,
    /// An `ltc` table's fit: the worst probe light's relative lit error per texel, its
    /// median and largest over the texels (the sidecar's `ltc.fit_error.lit_max`); `None`
    /// for other tables.
    pub fit_lit_max: Option<(f64, f64)>,
}

/// Why baking a preset failed, with the exit code class it maps to.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    /// The inputs cannot be baked (exit code 2).
    #[error("{0}")]
    Input(String),
    /// The environment failed: disk, permissions (exit code 1).
    #[error("{0}")]
    Environment(String),
    /// The bake ran but its result cannot be trusted or was not finished: an error estimate
    /// over the tolerance, the time limit (exit code 1).
    #[error("{0}")]
    Failed(String),
}

/// The files a preset's table goes to: `<out>/<preset>/<table>.<ext>`.
pub fn table_dir(out: &Path, preset: &str) -> PathBuf {
    out.join(preset)
}

/// Files to write: (path, bytes).
pub type Files = Vec<(PathBuf, Vec<u8>)>;

/// Encodes one table in one format: (file name suffix after `<table>.`, bytes) pairs.
pub fn encode(
    format: Format,
    table: &PresetTable,
    lut: &Lut,
    attrs: &[(String, String)],
) -> Result<Vec<(String, Vec<u8>)>, EncodeError> {
    let name = table.spec.name.clone();
    let storage = table.spec.storage;
    let one = |enc: &dyn Encoder| -> Result<Vec<(String, Vec<u8>)>, EncodeError> {
        Ok(vec![(enc.extension().to_string(), enc.encode(lut, attrs)?)])
    };
    match format {
        Format::Exr => one(&ExrEncoder {
            storage: table.spec.storage,
            table_name: name,
        }),
        Format::Ktx2 | Format::Ktx2Zstd => one(&Ktx2Encoder {
            storage: table.spec.storage,
            table_name: name,
            array_3d: table.layout_3d == Layout3d::Array,
            supercompression: if format == Format::Ktx2Zstd {
                Supercompression::Zstd
            } else {
                Supercompression::None
            },
        }),
        Format::Dds => one(&DdsEncoder {
            storage: table.spec.storage,
            table_name: name,
            array_3d: table.layout_3d == Layout3d::Array,
        }),
        Format::Png => PngPreview { table_name: name }.encode_all_with_attributes(lut, attrs),
        Format::PngData => one(&PngData {
            storage,
            table_name: name,
        }),
        Format::PngRgbd => one(&crate::encode::rgbd::PngRgbd { table_name: name }),
        Format::H => one(&CHeader {
            table_name: name,
            storage,
        }),
        Format::Rs => one(&RustSource {
            table_name: name,
            storage,
        }),
        Format::Glsl | Format::Hlsl | Format::Wgsl => one(&ShaderSnippet {
            lang: match format {
                Format::Glsl => ShaderLang::Glsl,
                Format::Hlsl => ShaderLang::Hlsl,
                _ => ShaderLang::Wgsl,
            },
            table_name: name,
        }),
        Format::Npy => one(&Npy {
            storage,
            table_name: name,
        }),
        Format::Npz => one(&Npz {
            storage,
            table_name: name,
        }),
        Format::Bin => one(&RawBin {
            storage,
            table_name: name,
        }),
    }
}

/// Bakes and encodes every table of `preset` in memory. `formats` overrides the preset's
/// formats when given. Returns the tables and the files to write.
pub fn bake_preset(
    preset: &Preset,
    out: &Path,
    formats: Option<&[Format]>,
) -> Result<(Vec<BakedTable>, Files), PipelineError> {
    bake_preset_until(preset, out, formats, None)
}

/// [`bake_preset`] that gives up once `deadline` has passed (`bake --max-time`): an
/// environment error (the machine was slower than the estimate), nothing to write.
pub fn bake_preset_until(
    preset: &Preset,
    out: &Path,
    formats: Option<&[Format]>,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<(Vec<BakedTable>, Files), PipelineError> {
    let dir = table_dir(out, &preset.name);
    // formats the tables' storage cannot be written in, before any work
    for t in &preset.tables {
        t.check_formats(formats.unwrap_or(&t.formats))
            .map_err(|e| PipelineError::Input(format!("preset {}: {e}", preset.name)))?;
    }
    let mut baked = Vec::new();
    let mut files = Vec::new();
    for t in &preset.tables {
        let start = Instant::now();
        let opts = crate::table::BakeOptions {
            deadline,
            accept_error_estimate: t.accept_error_estimate,
        };
        let (lut, fit) = crate::table::bake_with_fit(&t.spec, &opts).map_err(|e| match e {
            crate::table::BakeError::TimeLimit { .. }
            | crate::table::BakeError::ToleranceMissed { .. }
            | crate::table::BakeError::FitFailed { .. } => {
                PipelineError::Failed(format!("preset {}: {e}", preset.name))
            }
            _ => PipelineError::Input(format!("preset {}: {e}", preset.name)),
        })?;
        let elapsed = start.elapsed();
        // the engine's channels (`channels`: values, before the scale) in its axis order
        // (`axis_order`), where the preset gives them
        let mut lut = t.stored(lut);
        // (the fit error keeps its own channels; only the axis order is the table's)
        let fit = fit.map(|f| match &t.axis_order {
            Some(order) => f.permuted(order),
            None => f,
        });
        check_underflow(t, &lut).map_err(|m| {
            PipelineError::Input(format!(
                "preset {}: table {}: {m}",
                preset.name, t.spec.name
            ))
        })?;
        if t.scale != 1.0 {
            for v in lut.data.iter_mut() {
                *v = (*v as f64 * t.scale) as f32;
            }
            if let Some(i) = lut.data.iter().position(|v| !v.is_finite()) {
                return Err(PipelineError::Input(format!(
                    "preset {}: table {}: scale {} makes texel {} overflow f32",
                    preset.name,
                    t.spec.name,
                    t.scale,
                    i / lut.channels.len()
                )));
            }
        }
        check_unorm_range(t, &lut).map_err(|m| {
            PipelineError::Input(format!(
                "preset {}: table `{}`: {m}",
                preset.name, t.spec.name
            ))
        })?;
        let attrs = meta::header_attributes(&preset.name, t, &lut);
        let mut names = Vec::new();
        let mut encoded_files = Vec::new();
        // the table as written: with `bake --format`'s formats (the sidecar's engine warnings
        // speak of those)
        let written = PresetTable {
            formats: formats.unwrap_or(&t.formats).to_vec(),
            ..t.clone()
        };
        for f in &written.formats {
            let encoded = encode(*f, t, &lut, &attrs).map_err(|e| {
                PipelineError::Input(format!(
                    "preset {}: {e}{}",
                    preset.name,
                    if t.spec.kind == crate::table::TableKind::Ltc && lut.channels.len() > 4 {
                        " (an ltc table's channels go into textures of at most 4: list them in ltc.channels, \
                         e.g. Heitz's layout as two tables, [m00, m20, m02, m22] and [norm, fresnel, zero, sphere]: \
                         presets/engines/heitz-ltc.json)"
                    } else {
                        ""
                    }
                ))
            })?;
            for (suffix, bytes) in encoded {
                let file = format!("{}.{}", t.spec.name, suffix);
                names.push((suffix, file.clone()));
                encoded_files.push((file, bytes));
            }
        }
        let json = meta::metadata_with_fit(&preset.name, &written, &lut, &names, fit.as_ref());
        // the sidecar lists every file's digest and seals itself (crate::digest)
        let listed: Vec<(&str, &[u8])> = encoded_files
            .iter()
            .map(|(n, b)| (n.as_str(), b.as_slice()))
            .collect();
        let sidecar = crate::digest::seal(json, &listed);
        let mut paths = Vec::new();
        for (file, bytes) in encoded_files {
            let path = dir.join(&file);
            paths.push(path.clone());
            files.push((path, bytes));
        }
        let jpath = dir.join(format!("{}.json", t.spec.name));
        paths.push(jpath.clone());
        files.push((jpath, sidecar));
        if let Some(req) = &t.fit {
            for (path, bytes) in fit_files(&preset.name, t, req, &dir, deadline)? {
                paths.push(path.clone());
                files.push((path, bytes));
            }
        }
        let fit_lit_max = fit.as_ref().and_then(|f| {
            let c = f.channels.iter().position(|c| c.name == "lit_max")?;
            let nc = f.channels.len();
            let mut v: Vec<f64> = f
                .data
                .iter()
                .skip(c)
                .step_by(nc)
                .map(|&x| x as f64)
                .collect();
            v.sort_by(f64::total_cmp);
            Some((*v.get(v.len() / 2)?, *v.last()?))
        });
        baked.push(BakedTable {
            preset: preset.name.clone(),
            table: t.spec.name.clone(),
            lut,
            files: paths,
            elapsed,
            fit_lit_max,
        });
    }
    Ok((baked, files))
}

/// The files of a table's `fit` (`TABLE.fit.{glsl,…}` and the sidecar `TABLE.fit.json`,
/// which carries the table's input hash for `bake --check`): the fit of its exact function
/// that the request asks for, or the error that none does (exit 1, as a table that misses
/// its tolerance).
fn fit_files(
    preset: &str,
    t: &PresetTable,
    req: &crate::fit::emit::Request,
    dir: &Path,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Files, PipelineError> {
    let what = format!("preset {preset}: table {}: fit", t.spec.name);
    let (tg, front) = crate::fit::emit::front(&t.spec, req.weight, deadline)
        .map_err(|m| PipelineError::Input(format!("{what}: {m}")))?
        .ok_or_else(|| PipelineError::Failed(format!("{what}: stopped at the time limit")))?;
    let c = crate::fit::emit::choose(&front, req.goal, &format!("{preset}/{}", t.spec.name))
        .map_err(|m| PipelineError::Failed(format!("preset {preset}: {m}")))?;
    let mut extra = serde_json::Map::new();
    extra.insert(
        "input_hash".into(),
        serde_json::Value::String(meta::input_hash(t)),
    );
    Ok(crate::fit::emit::files(
        preset,
        &t.spec.name,
        &tg,
        req.weight,
        c,
        &req.emit,
        dir,
        &format!("{}.fit", t.spec.name),
        extra,
    ))
}

/// Refuses a table whose stored values (value × scale, rounded to the storage type) lose
/// more than the storage's own rounding plus the tolerance: a scale so small that texels
/// underflow to zero or to a few subnormal bits (`"scale": 5e-324`, or f16 with 1e-8) would
/// otherwise write a table of zeros. Overflow (f16 above 65504) is the encoders' error.
///
/// Bound per texel: |stored/scale − value| ≤ ε·|value| + tolerance, with ε the storage's
/// relative rounding (2^-11 for f16, 2^-24 for f32; the value is already f32) and 2^-20
/// of slack for the division by the scale. Without a scale it always holds for f32 (the
/// texels are stored as they are); f16 rounds its subnormal range (below 6.1e-5) to at most
/// 2^-25 ≈ 3e-8 absolute, which only a table of tolerance below that can notice.
fn check_underflow(t: &PresetTable, lut: &Lut) -> Result<(), String> {
    if t.scale == 1.0 && t.spec.storage == Storage::F32 {
        return Ok(()); // f32 stores the texels as they are
    }
    let (eps, name) = match t.spec.storage {
        Storage::F16 => (2f64.powi(-11), "f16"),
        Storage::F32 => (2f64.powi(-24), "f32"),
        // UNORM rounds absolutely, by up to half a step (÷ scale in values), which the
        // sidecar states; values it cannot hold are check_unorm_range's
        Storage::Unorm8 | Storage::Unorm16 => return Ok(()),
    };
    let nc = lut.channels.len().max(1);
    for (k, &v) in lut.data.iter().enumerate() {
        let v = v as f64;
        let scaled = (v * t.scale) as f32;
        let stored = match t.spec.storage {
            Storage::F16 => half::f16::from_f32(scaled).to_f32(),
            _ => scaled,
        };
        if !stored.is_finite() {
            continue; // overflow: reported by the encoders (f16) or below (f32)
        }
        let back = stored as f64 / t.scale;
        let err = (back - v).abs();
        let allowed = (eps * (1.0 + 2f64.powi(-20))) * v.abs() + t.spec.tolerance;
        if err > allowed {
            let t0 = k / nc;
            let (nx, ny) = (lut.dim(0), lut.dim(1));
            let texel = [t0 % nx, (t0 / nx) % ny, t0 / (nx * ny)];
            let texel = &texel[..lut.axes.len()];
            let n = crate::numfmt::num;
            return Err(format!(
                "scale {} makes texel {texel:?} (channel {}, value {}) underflow {name}: it is stored as {} and reads back as {}, off by {} (more than {name} rounding plus the tolerance, {}); raise \"scale\"{}",
                n(t.scale),
                lut.channels[k % nc].name,
                n(v),
                n(stored as f64),
                n(back),
                n(err),
                n(allowed),
                if t.spec.storage == Storage::F16 { " or use \"storage\": \"f32\"" } else { "" },
            ));
        }
    }
    Ok(())
}

/// Refuses a UNORM table (`lut`: values × scale) with a value whose nearest code lies outside
/// 0..=2ⁿ − 1, i.e. more than half a step outside [0, 1] (crate::encode::unorm): naming the
/// channel, the texel, the value and what to do. Never a clamp.
fn check_unorm_range(t: &PresetTable, lut: &Lut) -> Result<(), String> {
    use crate::encode::unorm;
    let Some((c, texel, v)) = unorm::first_unstorable(lut, t.spec.storage) else {
        return Ok(());
    };
    let n = crate::numfmt::num;
    let texel = &texel[..lut.axes.len()];
    let scaled = if t.scale == 1.0 {
        String::new()
    } else {
        format!(" ({} x scale {})", n(v as f64 / t.scale), n(t.scale))
    };
    Err(format!(
        "channel `{}`, texel {texel:?}: the stored value {}{scaled} lies outside [0, 1], which \"storage\": {:?} holds (code = round(value x {}); nothing is clamped); {}",
        lut.channels[c].name,
        n(v as f64),
        t.spec.storage.name(),
        t.spec.storage.unorm_max().unwrap_or(0),
        unorm::advice(
            v as f64,
            unorm::channel_extreme(lut, c),
            t.scale,
            t.spec.storage.quantization_step().unwrap_or(0.0) / 2.0
        )
    ))
}

/// Writes a set of encoded files atomically: every file is written to a temporary file
/// first, and only when all are written are they renamed into place.
pub fn write_files(files: &Files) -> Result<(), PipelineError> {
    let mut dirs: Vec<&Path> = files.iter().filter_map(|(p, _)| p.parent()).collect();
    dirs.sort();
    dirs.dedup();
    for dir in dirs {
        std::fs::create_dir_all(dir).map_err(|e| {
            PipelineError::Environment(format!(
                "cannot create output directory {}: {e}",
                dir.display()
            ))
        })?;
    }
    // sidecars last: every reader checks a texture against its sidecar's digest, so a set
    // interrupted between renames is found (new textures beside old sidecars), and a
    // sidecar is never newer than the files it lists
    let is_sidecar = |p: &Path| p.extension().is_some_and(|e| e == "json");
    let (sidecars, mut ordered): (Vec<_>, Vec<_>) = files
        .iter()
        .map(|(p, b)| (p.as_path(), b.as_slice()))
        .partition(|(p, _)| is_sidecar(p));
    ordered.extend(sidecars);
    crate::write::write_all_atomic(&ordered).map_err(|e| PipelineError::Environment(e.to_string()))
}

/// Bakes a preset and writes its files atomically under `out`.
pub fn bake_and_write(
    preset: &Preset,
    out: &Path,
    formats: Option<&[Format]>,
) -> Result<Vec<BakedTable>, PipelineError> {
    let (baked, files) = bake_preset(preset, out, formats)?;
    write_files(&files)?;
    Ok(baked)
}
