//! `brdfbake bake`: presets → textures.

use super::CliError;
use crate::pipeline::{bake_preset, write_files, PipelineError};
use crate::preset::{self, LoadError, Preset};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct BakeArgs {
    /// Preset names (from presets/ or built in) or preset file paths. Default: every preset.
    pub presets: Vec<String>,
    /// Output directory.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Worker threads (default: all cores). Outputs are identical for any count.
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// Output formats for every table, overriding the presets' (comma-separated:
    /// exr, ktx2, png, h, rs, glsl, hlsl, wgsl). The JSON sidecar is always written.
    #[arg(long, value_name = "LIST")]
    pub format: Option<String>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

pub fn run(a: BakeArgs) -> Result<(), CliError> {
    let formats = match &a.format {
        Some(s) => Some(
            crate::preset::Format::parse_list(s)
                .map_err(|e| CliError::input(format!("--format: {e}")))?,
        ),
        None => None,
    };
    let presets = resolve(&a.presets)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads.map_or(0, usize::from))
        .build()
        .map_err(|e| CliError::env(format!("cannot start worker threads: {e}")))?;
    // Bake everything in memory first, then write all presets' files in one atomic set:
    // a failure anywhere leaves every previous output as it was.
    let to_err = |e: PipelineError| match e {
        PipelineError::Input(m) => CliError::input(m),
        PipelineError::Environment(m) => CliError::env(m),
    };
    let mut all_baked = Vec::new();
    let mut all_files = Vec::new();
    for p in &presets {
        let (baked, files) = pool
            .install(|| bake_preset(p, &a.out, formats.as_deref()))
            .map_err(to_err)?;
        all_baked.extend(baked);
        all_files.extend(files);
    }
    write_files(&all_files).map_err(to_err)?;
    if !a.quiet {
        for b in all_baked {
            let dims: Vec<String> = b.lut.axes.iter().map(|x| x.size.to_string()).collect();
            let err = b.lut.error_estimate.iter().cloned().fold(0.0, f64::max);
            let channels: Vec<&str> = b.lut.channels.iter().map(|c| c.name.as_str()).collect();
            let files: Vec<String> = b.files.iter().map(|f| f.display().to_string()).collect();
            println!(
                "{}/{}: {} {} in {:.2} s, est. max error {:.1e} -> {}",
                b.preset,
                b.table,
                dims.join("x"),
                channels.join(","),
                b.elapsed.as_secs_f64(),
                err,
                files.join(", ")
            );
        }
    }
    Ok(())
}

/// The presets directory searched first for preset names.
pub const PRESET_DIR: &str = "presets";

fn load(path: &Path) -> Result<Preset, CliError> {
    preset::load(path).map_err(|e| match e {
        LoadError::Input(m) => CliError::input(m),
        LoadError::Io(p, e) if e.kind() == std::io::ErrorKind::NotFound => {
            CliError::input(format!("{p}: no such preset file"))
        }
        e @ LoadError::Io(..) => CliError::env(e.to_string()),
    })
}

/// Turns the command-line arguments into presets: a path to a file, or a name looked up
/// in `presets/` and then among the built-in presets.
pub fn resolve(args: &[String]) -> Result<Vec<Preset>, CliError> {
    if args.is_empty() {
        let dir = Path::new(PRESET_DIR);
        if dir.is_dir() {
            let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
                .map_err(|e| CliError::env(format!("cannot read {}: {e}", dir.display())))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect();
            files.sort();
            if files.is_empty() {
                return Err(CliError::input(format!(
                    "{} holds no *.json presets",
                    dir.display()
                )));
            }
            return files.iter().map(|f| load(f)).collect();
        }
        return crate::presets::BUILTIN
            .iter()
            .map(|(n, t)| {
                preset::parse(t, &format!("built-in preset {n}"), n)
                    .map_err(|e| CliError::input(e.to_string()))
            })
            .collect();
    }
    let mut out = Vec::new();
    let mut names = std::collections::BTreeSet::new();
    for a in args {
        let p = Path::new(a);
        let preset = if p.exists() || a.contains('/') || a.ends_with(".json") {
            load(p)?
        } else {
            let local = Path::new(PRESET_DIR).join(format!("{a}.json"));
            if local.is_file() {
                load(&local)?
            } else if let Some((n, t)) = crate::presets::BUILTIN.iter().find(|(n, _)| n == a) {
                preset::parse(t, &format!("built-in preset {n}"), n)
                    .map_err(|e| CliError::input(e.to_string()))?
            } else {
                return Err(CliError::input(format!(
                    "unknown preset {a:?}: not a file, not in {PRESET_DIR}/, not built in (built-in presets: {})",
                    crate::presets::BUILTIN.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
                )));
            }
        };
        if !names.insert(preset.name.clone()) {
            return Err(CliError::input(format!(
                "preset {:?} is named twice",
                preset.name
            )));
        }
        out.push(preset);
    }
    Ok(out)
}
