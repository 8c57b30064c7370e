//! `brdfbake bake`: presets → textures.

use super::CliError;
use crate::pipeline::{bake_preset_until, write_files, BakedTable, Files};
use crate::preset::{self, Format, LoadError, Preset};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct BakeArgs {
    /// Preset names (from presets/ or built in) or preset file paths. Default: every preset.
    pub presets: Vec<String>,
    /// Also bake every preset of these engines (comma-separated, e.g. `godot`, `threejs`,
    /// `blender`; `brdfbake list` names them): the tables in the engine's own layouts and
    /// formats.
    #[arg(long, value_name = "NAME", value_delimiter = ',')]
    pub engine: Vec<String>,
    /// Output directory.
    #[arg(long, default_value = DEFAULT_OUT)]
    pub out: PathBuf,
    /// Worker threads (default: all cores). Outputs are identical for any count.
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// Output formats for every table, overriding the presets' (comma-separated:
    /// exr, ktx2, ktx2-zstd, dds, png, png-data, h, rs, glsl, hlsl, wgsl, npy, npz, bin). The
    /// JSON sidecar is always written.
    #[arg(long, value_name = "LIST")]
    pub format: Option<String>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
    /// Write nothing; exit 1 and list the outputs that are missing or stale (their sidecar's
    /// input hash differs from the preset's, e.g. after a preset edit or a brdfbake upgrade),
    /// exit 0 if all are up to date.
    #[arg(long)]
    pub check: bool,
    /// Print one JSON document (what was baked or checked) on stdout instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

/// One output that `--check` found missing or stale.
struct Stale {
    preset: String,
    table: String,
    file: PathBuf,
    reason: String,
}

/// The sidecar `files` keys a table's formats produce.
fn expected_keys(t: &crate::preset::PresetTable, formats: &[Format]) -> Vec<String> {
    let mut keys = Vec::new();
    for f in formats {
        if *f == Format::Png {
            let ch = t.stored_channels();
            for c in &ch {
                keys.push(format!("preview-{}.png", c.name));
            }
            keys.push(format!("preview-{}-colour.png", ch[0].name));
        } else if *f == Format::PngData || *f == Format::PngRgbd {
            // (png-data is TABLE.png; the previews are TABLE.preview-*.png)
            keys.push("png".to_string());
        } else if f.is_ktx2() {
            // (ktx2-zstd is TABLE.ktx2 too; the sidecar says which)
            keys.push("ktx2".to_string());
        } else {
            keys.push(f.name().to_string());
        }
    }
    keys
}

fn check(a: &BakeArgs, presets: &[Preset], formats: Option<&[Format]>) -> Result<(), CliError> {
    let mut stale = Vec::new();
    let mut checked = 0usize;
    for p in presets {
        let dir = crate::pipeline::table_dir(&a.out, &p.name);
        for t in &p.tables {
            checked += 1;
            let mut bad = |file: PathBuf, reason: String| {
                stale.push(Stale {
                    preset: p.name.clone(),
                    table: t.spec.name.clone(),
                    file,
                    reason,
                })
            };
            let jpath = dir.join(format!("{}.json", t.spec.name));
            let read = |p: &Path| -> Result<Option<Vec<u8>>, CliError> {
                match crate::readback::read_bytes(p) {
                    Ok(b) => Ok(Some(b)),
                    Err(crate::readback::ReadError::Input(_)) if !p.exists() => Ok(None),
                    Err(crate::readback::ReadError::Input(m)) => Err(CliError::input(m)),
                    Err(crate::readback::ReadError::Io(m)) => Err(CliError::env(m)),
                }
            };
            let Some(bytes) = read(&jpath)? else {
                bad(jpath, "missing".into());
                continue;
            };
            // the sidecar first: byte for byte what a bake wrote (crate::digest)
            if let Err(e) = crate::digest::check_seal(&bytes) {
                bad(jpath, format!("damaged: {e}"));
                continue;
            }
            let sidecar: serde_json::Value = match serde_json::from_slice(&bytes) {
                Ok(v) => v,
                Err(e) => {
                    bad(jpath, format!("not valid JSON ({e})"));
                    continue;
                }
            };
            let want = crate::meta::input_hash(t);
            let have = sidecar
                .get("input_hash")
                .and_then(|h| h.as_str())
                .unwrap_or("(none)");
            if have != want {
                bad(
                    jpath.clone(),
                    format!("stale: input hash {have} differs from the preset's {want} (preset changed or brdfbake version differs)"),
                );
            }
            // and it still describes what its hash says (a sealed sidecar no bake wrote)
            if have == want {
                match crate::readback::table_from_sidecar(&sidecar) {
                    Ok(t2) if crate::meta::input_hash(&t2) == want => {}
                    _ => bad(
                        jpath.clone(),
                        "the sidecar no longer describes its input hash: it was edited after the bake".into(),
                    ),
                }
            }
            let files = sidecar.get("files");
            let wanted = formats.unwrap_or(&t.formats);
            // a KTX2 file supercompressed as asked (the input hash does not hold the formats)
            let zstd = sidecar
                .pointer("/storage/ktx2/supercompression")
                .and_then(|v| v.as_str())
                == Some("zstd");
            let ktx2 = dir.join(format!("{}.ktx2", t.spec.name));
            if wanted.contains(&Format::Ktx2Zstd) && !zstd {
                bad(
                    ktx2.clone(),
                    "written as plain ktx2, ktx2-zstd asked for".into(),
                );
            } else if wanted.contains(&Format::Ktx2) && zstd {
                bad(
                    ktx2.clone(),
                    "written as ktx2-zstd, plain ktx2 asked for".into(),
                );
            }
            for key in expected_keys(t, wanted) {
                let name = format!("{}.{key}", t.spec.name);
                let path = dir.join(&name);
                if files.and_then(|f| f.get(&key)).is_none() {
                    let why = if path.is_file() {
                        "not listed in its sidecar (written by another bake)"
                    } else {
                        "missing"
                    };
                    bad(path, why.into());
                    continue;
                }
                let Some(bytes) = read(&path)? else {
                    bad(path, "missing".into());
                    continue;
                };
                if let Err(e) = crate::digest::check_file(&sidecar, &name, &bytes) {
                    bad(path, format!("damaged or stale: {e}"));
                }
            }
            // a `fit`: its sidecar names the table's input hash, and its functions exist
            if let Some(req) = &t.fit {
                let fpath = dir.join(format!("{}.fit.json", t.spec.name));
                let Some(bytes) = read(&fpath)? else {
                    bad(fpath, "missing (the preset asks for a fit)".into());
                    continue;
                };
                let doc: Option<serde_json::Value> = serde_json::from_slice(&bytes).ok();
                let have = doc
                    .as_ref()
                    .and_then(|d| d.get("input_hash"))
                    .and_then(|h| h.as_str())
                    .unwrap_or("(none)");
                if have != want {
                    bad(
                        fpath,
                        format!("stale: input hash {have} differs from the preset's {want}"),
                    );
                    continue;
                }
                for l in &req.emit {
                    if let Some(d) = crate::encode::function::dialect(l) {
                        let p = dir.join(format!("{}.fit.{}", t.spec.name, d.extension()));
                        if !p.is_file() {
                            bad(p, "missing".into());
                        }
                    }
                }
            }
        }
    }
    if a.json {
        let doc = serde_json::json!({
            "up_to_date": stale.is_empty(),
            "tables_checked": checked,
            "stale": stale.iter().map(|s| serde_json::json!({
                "preset": s.preset, "table": s.table,
                "file": s.file.display().to_string(), "reason": s.reason,
            })).collect::<Vec<_>>(),
        });
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
    } else if !a.quiet {
        for s in &stale {
            outln!(
                "{}/{}: {}: {}",
                s.preset,
                s.table,
                s.file.display(),
                s.reason
            );
        }
        if stale.is_empty() {
            outln!("{checked} table(s) up to date in {}", a.out.display());
        }
    }
    if stale.is_empty() {
        Ok(())
    } else {
        Err(CliError {
            code: super::EXIT_FAILURE,
            msg: format!(
                "{} output(s) missing or stale in {}; to update them, run: {}",
                stale.len(),
                a.out.display(),
                rebake_command(a)
            ),
        })
    }
}

/// Where `bake` writes unless told (`--out`).
const DEFAULT_OUT: &str = "out";

/// The `brdfbake bake` that rewrites what `bake --check` found stale: the user's own presets,
/// `--out` and `--format`, quoted for a POSIX shell where needed.
fn rebake_command(a: &BakeArgs) -> String {
    let quote = |s: &str| {
        if !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_./=,:+@".contains(c))
        {
            s.to_string()
        } else {
            format!("'{}'", s.replace('\'', "'\\''"))
        }
    };
    let mut cmd = vec!["brdfbake".to_string(), "bake".to_string()];
    cmd.extend(a.presets.iter().map(|p| quote(p)));
    if !a.engine.is_empty() {
        cmd.push("--engine".into());
        cmd.push(quote(&a.engine.join(",")));
    }
    if a.out != std::path::Path::new(DEFAULT_OUT) {
        cmd.push("--out".into());
        cmd.push(quote(&a.out.display().to_string()));
    }
    if let Some(f) = &a.format {
        cmd.push("--format".into());
        cmd.push(quote(f));
    }
    cmd.join(" ")
}

/// `--format`, parsed.
fn formats_of(a: &BakeArgs) -> Result<Option<Vec<Format>>, CliError> {
    a.format
        .as_deref()
        .map(|s| Format::parse_list(s).map_err(|e| CliError::input(format!("--format: {e}"))))
        .transpose()
}

/// The checks before any work: formats a table's storage cannot be written in (`--format exr`
/// for a unorm table, …) and the memory the bake needs (`--max-memory`).
fn admit(a: &BakeArgs, presets: &[Preset], formats: Option<&[Format]>) -> Result<(), CliError> {
    for p in presets {
        for t in &p.tables {
            t.check_formats(formats.unwrap_or(&t.formats))
                .map_err(|e| {
                    let flag = if formats.is_some() { "--format: " } else { "" };
                    CliError::input(format!("{flag}preset {}: {e}", p.name))
                })?;
        }
    }
    // (--check reads what a bake would write, one file at a time: bounded by the same)
    let estimate = crate::resources::estimate(presets, formats);
    crate::resources::check(&estimate, a.guards.max_memory).map_err(CliError::input)
}

/// What does not work in the tables' engines (preset field `engine`): (preset, table,
/// engine, warning).
fn engine_warnings(
    presets: &[Preset],
    formats: Option<&[Format]>,
) -> Vec<(String, String, &'static str, String)> {
    let mut warnings = Vec::new();
    for p in presets {
        for t in &p.tables {
            let written = crate::preset::PresetTable {
                formats: formats.map_or_else(|| t.formats.clone(), <[Format]>::to_vec),
                ..t.clone()
            };
            let engine = t.engine.map_or("", |e| e.name());
            for w in crate::engine::warnings(&written) {
                warnings.push((p.name.clone(), t.spec.name.clone(), engine, w));
            }
        }
    }
    warnings
}

/// Bakes every preset in memory on `--threads` threads within `--max-time`: the tables and
/// the files to write. Nothing is written.
fn bake_all(
    a: &BakeArgs,
    presets: &[Preset],
    formats: Option<&[Format]>,
    progress: &indicatif::ProgressBar,
) -> Result<(Vec<BakedTable>, Files), CliError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads.map_or(0, usize::from))
        .build()
        .map_err(|e| CliError::env(format!("cannot start worker threads: {e}")))?;
    let time = crate::resources::estimate_time(presets);
    crate::resources::check_time(&time, pool.current_num_threads(), a.guards.max_time)
        .map_err(CliError::input)?;
    let deadline = crate::deadline::Deadline::after(a.guards.max_time);
    let mut all_baked = Vec::new();
    let mut all_files = Vec::new();
    for p in presets {
        progress.set_message(format!("baking {}", p.name));
        let (baked, files) = pool
            .install(|| bake_preset_until(p, &a.out, formats, Some(&deadline)))
            .map_err(|e| {
                progress.finish_and_clear();
                CliError::from(e)
            })?;
        progress.inc(p.tables.len() as u64);
        all_baked.extend(baked);
        all_files.extend(files);
    }
    progress.finish_and_clear();
    Ok((all_baked, all_files))
}

/// What [`bake_in_memory`] baked: the tables and the files `bake` would write (paths under
/// `--out`), with the engine warnings `bake` prints.
#[derive(Debug)]
pub struct InMemory {
    pub tables: Vec<BakedTable>,
    pub files: Files,
    /// `PRESET/TABLE (engine ENGINE): WARNING`, as `bake` prints them.
    pub warnings: Vec<String>,
    /// (preset, table, warning) of the same, for [`summary_json`].
    pub table_warnings: Vec<(String, String, String)>,
}

/// Bakes `presets` as `bake` does with the flags of `a` — the same checks, guards
/// (`--max-memory`, `--max-time`), threads, formats and errors — and returns the tables and
/// the files instead of writing them (`a.presets`, `--check`, `--json` and `--quiet` are not
/// read). For embedders: the Python module, whose presets may not be files.
pub fn bake_in_memory(a: &BakeArgs, presets: &[Preset]) -> Result<InMemory, CliError> {
    let formats = formats_of(a)?;
    admit(a, presets, formats.as_deref())?;
    let warnings = engine_warnings(presets, formats.as_deref());
    let (tables, files) = bake_all(
        a,
        presets,
        formats.as_deref(),
        &indicatif::ProgressBar::hidden(),
    )?;
    Ok(InMemory {
        tables,
        files,
        warnings: warnings
            .iter()
            .map(|(p, t, e, w)| format!("{p}/{t} (engine {e}): {w}"))
            .collect(),
        table_warnings: warnings.into_iter().map(|(p, t, _, w)| (p, t, w)).collect(),
    })
}

/// The document `bake --json` prints: what was baked into `out`, in `seconds`, with each
/// table's warnings ((preset, table, warning)).
pub fn summary_json(
    out: &Path,
    seconds: f64,
    baked: &[BakedTable],
    warnings: &[(String, String, String)],
) -> serde_json::Value {
    let tables: Vec<serde_json::Value> = baked
        .iter()
        .map(|b| {
            let err: serde_json::Map<String, serde_json::Value> = b
                .lut
                .channels
                .iter()
                .zip(&b.lut.error_estimate)
                .map(|(c, e)| (c.name.clone(), serde_json::json!(e)))
                .collect();
            let w: Vec<&str> = warnings
                .iter()
                .filter(|(p, t, _)| *p == b.preset && *t == b.table)
                .map(|(_, _, w)| w.as_str())
                .collect();
            serde_json::json!({
                "preset": b.preset,
                "table": b.table,
                "warnings": w,
                "size": b.lut.axes.iter().map(|x| x.size).collect::<Vec<_>>(),
                "axes": b.lut.axes.iter().map(|x| x.name.clone()).collect::<Vec<_>>(),
                "channels": b.lut.channels.iter().map(|c| c.name.clone()).collect::<Vec<_>>(),
                "seconds": b.elapsed.as_secs_f64(),
                "evaluations": b.lut.evaluations,
                "estimated_max_error": err,
                "ltc_fit_lit_error": b.fit_lit_max.map(|(median, max)| serde_json::json!({"median": median, "max": max})),
                "files": b.files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>(),
            })
        })
        .collect();
    serde_json::json!({
        "generator": {"name": "brdfbake", "version": crate::meta::VERSION},
        "out": out.display().to_string(),
        "seconds": seconds,
        "tables": tables,
    })
}

pub fn run(a: BakeArgs) -> Result<(), CliError> {
    let formats = formats_of(&a)?;
    let presets = resolve(&with_engines(&a.presets, &a.engine)?)?;
    admit(&a, &presets, formats.as_deref())?;
    if a.check {
        return check(&a, &presets, formats.as_deref());
    }
    let warnings = engine_warnings(&presets, formats.as_deref());
    if !a.quiet && !a.json {
        for (p, t, engine, w) in &warnings {
            let line = format!("{p}/{t} (engine {engine}): {w}");
            eprintln!("warning: {}", super::error::terminal_safe(&line));
        }
    }
    let started = Instant::now();
    // Bake everything in memory first, then write all presets' files in one atomic set:
    // a failure anywhere leaves every previous output as it was.
    let progress = progress_bar(&a, &presets);
    let (all_baked, all_files) = bake_all(&a, &presets, formats.as_deref(), &progress)?;
    write_files(&all_files).map_err(CliError::from)?;
    if a.json {
        let warnings: Vec<(String, String, String)> =
            warnings.into_iter().map(|(p, t, _, w)| (p, t, w)).collect();
        let doc = summary_json(
            &a.out,
            started.elapsed().as_secs_f64(),
            &all_baked,
            &warnings,
        );
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
        return Ok(());
    }
    if !a.quiet {
        for b in all_baked {
            let dims: Vec<String> = b.lut.axes.iter().map(|x| x.size.to_string()).collect();
            let err = b.lut.error_estimate.iter().cloned().fold(0.0, f64::max);
            let channels: Vec<&str> = b.lut.channels.iter().map(|c| c.name.as_str()).collect();
            let files: Vec<String> = b.files.iter().map(|f| f.display().to_string()).collect();
            // an LTC fit's matrix is no integral (its estimate is 0): what the fit makes of the
            // light is its error
            let fit = b.fit_lit_max.map(|(median, max)| {
                format!(
                    "LTC fit: the worst probe light's relative lit error per texel, median {median:.1e}, max {max:.1e} (ltc.fit_error in the sidecar)"
                )
            });
            let error = match fit {
                Some(fit) if err == 0.0 => fit,
                Some(fit) => format!("est. max error {err:.1e}; {fit}"),
                None => format!("est. max error {err:.1e}"),
            };
            outln!(
                "{}/{}: {} {} in {:.2} s, {error} -> {}",
                b.preset,
                b.table,
                dims.join("x"),
                channels.join(","),
                b.elapsed.as_secs_f64(),
                files.join(", ")
            );
        }
    }
    Ok(())
}

/// A progress bar over the tables on stderr, shown only on a terminal and when neither
/// `--quiet` nor `--json` is given (pipelines see nothing of it).
fn progress_bar(a: &BakeArgs, presets: &[Preset]) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    let n: usize = presets.iter().map(|p| p.tables.len()).sum();
    if a.quiet || a.json || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let pb = indicatif::ProgressBar::new(n as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{spinner} [{elapsed}] {bar:30} {pos}/{len} tables  {msg}",
    ) {
        pb.set_style(style);
    }
    pb.enable_steady_tick(std::time::Duration::from_millis(120));
    pb
}

/// The preset names given, followed by the presets of the `--engine` names (each name once,
/// in order).
fn with_engines(presets: &[String], engines: &[String]) -> Result<Vec<String>, CliError> {
    let mut names = presets.to_vec();
    for e in engines {
        for p in crate::engines::select::presets_of(e).map_err(CliError::input)? {
            if !names.contains(&p) {
                names.push(p);
            }
        }
    }
    Ok(names)
}

/// The presets directory searched first for preset names.
pub const PRESET_DIR: &str = "presets";
/// The engine presets' folder inside [`PRESET_DIR`]: baked by name, not by a bare `bake`.
pub const ENGINE_PRESET_DIR: &str = "engines";

fn load(path: &Path) -> Result<Preset, CliError> {
    preset::load(path).map_err(|e| match e {
        LoadError::Input(m) => CliError::input(m),
        LoadError::Unreadable(m) => CliError::env(m),
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
            let engine = Path::new(PRESET_DIR)
                .join(ENGINE_PRESET_DIR)
                .join(format!("{a}.json"));
            if local.is_file() {
                load(&local)?
            } else if engine.is_file() {
                load(&engine)?
            } else if let Some((n, t)) = crate::presets::BUILTIN
                .iter()
                .chain(crate::presets::ENGINES)
                .find(|(n, _)| n == a)
            {
                preset::parse(t, &format!("built-in preset {n}"), n)
                    .map_err(|e| CliError::input(e.to_string()))?
            } else {
                let sorted = |l: &[(&str, &str)]| {
                    let mut v: Vec<&str> = l.iter().map(|(n, _)| *n).collect();
                    v.sort_unstable();
                    v.join(", ")
                };
                let known = crate::presets::BUILTIN
                    .iter()
                    .chain(crate::presets::ENGINES)
                    .map(|(n, _)| *n);
                let hint = crate::names::did_you_mean(a, known)
                    .map(|n| format!(" Did you mean `{n}`?"))
                    .unwrap_or_default();
                return Err(CliError::input(format!(
                    "unknown preset {a:?}: not a file, not in {PRESET_DIR}/ or {PRESET_DIR}/{ENGINE_PRESET_DIR}/, not built in.{hint} Built-in presets: {}; engine presets: {}",
                    sorted(crate::presets::BUILTIN),
                    sorted(crate::presets::ENGINES)
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
