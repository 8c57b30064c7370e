//! Preset → files: bake every table of a preset, encode each in its formats plus the JSON
//! sidecar, and hand the bytes to [`crate::write`] — the only code that touches the disk.
//! Nothing is written until every table of the preset has baked and encoded, and then all
//! files are replaced atomically, so a failure never leaves a partial or mixed set.

use crate::encode::exr::ExrEncoder;
use crate::encode::Encoder;
use crate::lut::Lut;
use crate::meta;
use crate::preset::{Format, Preset};
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
}

/// The files a preset's table goes to: `<out>/<preset>/<table>.<ext>`.
pub fn table_dir(out: &Path, preset: &str) -> PathBuf {
    out.join(preset)
}

/// Files to write: (path, bytes).
pub type Files = Vec<(PathBuf, Vec<u8>)>;

/// Bakes and encodes every table of `preset` in memory. Returns the tables and the files
/// to write.
pub fn bake_preset(preset: &Preset, out: &Path) -> Result<(Vec<BakedTable>, Files), PipelineError> {
    let dir = table_dir(out, &preset.name);
    let mut baked = Vec::new();
    let mut files = Vec::new();
    for t in &preset.tables {
        let start = Instant::now();
        let lut = crate::table::bake(&t.spec)
            .map_err(|e| PipelineError::Input(format!("preset {}: {e}", preset.name)))?;
        let elapsed = start.elapsed();
        let attrs = meta::header_attributes(&preset.name, &t.spec, &lut);
        let mut names = Vec::new();
        let mut paths = Vec::new();
        for f in &t.formats {
            let (name, bytes) = match f {
                Format::Exr => {
                    let enc = ExrEncoder {
                        storage: t.spec.storage,
                        table_name: t.spec.name.clone(),
                    };
                    let bytes = enc.encode(&lut, &attrs).map_err(|e| {
                        PipelineError::Input(format!("preset {}: {e}", preset.name))
                    })?;
                    ("exr", bytes)
                }
            };
            let file = format!("{}.{}", t.spec.name, name);
            let path = dir.join(&file);
            names.push((name, file));
            paths.push(path.clone());
            files.push((path, bytes));
        }
        let json = meta::metadata(&preset.name, &t.spec, &lut, &names);
        let mut text = serde_json::to_string_pretty(&json).expect("metadata serializes");
        text.push('\n');
        let jpath = dir.join(format!("{}.json", t.spec.name));
        paths.push(jpath.clone());
        files.push((jpath, text.into_bytes()));
        baked.push(BakedTable {
            preset: preset.name.clone(),
            table: t.spec.name.clone(),
            lut,
            files: paths,
            elapsed,
        });
    }
    Ok((baked, files))
}

/// Bakes a preset and writes its files atomically under `out`.
pub fn bake_and_write(preset: &Preset, out: &Path) -> Result<Vec<BakedTable>, PipelineError> {
    let (baked, files) = bake_preset(preset, out)?;
    let dir = table_dir(out, &preset.name);
    std::fs::create_dir_all(&dir).map_err(|e| {
        PipelineError::Environment(format!(
            "cannot create output directory {}: {e}",
            dir.display()
        ))
    })?;
    crate::write::write_all_atomic(&files)
        .map_err(|e| PipelineError::Environment(e.to_string()))?;
    Ok(baked)
}
