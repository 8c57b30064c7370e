//! `brdfbake inspect FILE`: what a texture (and its sidecar) holds.

use super::CliError;
use crate::readback::{self, ReadError, Readback};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct InspectArgs {
    /// A .exr, .ktx2 or .dds texture brdfbake wrote (its .json sidecar is read from next to it),
    /// or the .json sidecar itself.
    pub file: PathBuf,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

/// The bytes a read-back of `path` reads at most: the file, its sidecar (for a texture) and
/// the largest texture it may point to (for a sidecar), from their sizes on disk (0 for what
/// is not there: reading it fails first).
pub(super) fn file_bytes(path: &Path) -> u64 {
    let size = |p: &Path| std::fs::metadata(p).map_or(0, |m| m.len());
    let side = size(&path.with_extension("json"));
    let textures = size(&path.with_extension("exr"))
        .max(size(&path.with_extension("ktx2")))
        .max(size(&path.with_extension("dds")))
        .max(png_decoded_bytes(&path.with_extension("png")));
    size(path).max(textures) + side
}

/// What a png-data file decodes to at most, from its header (width × height × 4 components
/// × 2 bytes: its compressed size says little), capped at what readback decodes; 0 for what is
/// not a PNG.
fn png_decoded_bytes(p: &Path) -> u64 {
    let Some(head) = crate::input::read_head(p, 24) else {
        return 0;
    };
    if head.len() < 24 || !head.starts_with(b"\x89PNG\r\n\x1a\n") {
        return 0;
    }
    let be = |o: usize| u32::from_be_bytes([head[o], head[o + 1], head[o + 2], head[o + 3]]) as u64;
    (be(16) * be(20) * 8).min(crate::readback::MAX_PNG_DECODED_BYTES as u64)
}

/// The guards of a command that reads a file back: its bytes, the texels decoded as f32
/// and their statistics take ~3 times the files (reading is quick; the time limit still
/// holds for what follows).
pub(super) fn admit_read(
    guards: &super::guards::Guards,
    what: &str,
    path: &Path,
) -> Result<crate::deadline::Deadline, CliError> {
    let bytes = file_bytes(path);
    guards.admit(&super::guards::Work {
        what,
        memory: 3 * bytes + (1 << 20),
        memory_detail: format!("{bytes} bytes of files read and decoded"),
        time: Default::default(),
        threads: 1,
        smaller: "read a smaller table",
    })
}

/// Reads a file back, mapping errors to exit codes (2: not ours / bad path, 1: unreadable).
pub(super) fn read(path: &Path) -> Result<Readback, CliError> {
    readback::read(path).map_err(|e| match e {
        ReadError::Input(m) => CliError::input(m),
        ReadError::Io(m) => CliError::env(m),
    })
}

fn axis_line(a: &crate::lut::Axis) -> String {
    let q = match a.quantity {
        crate::lut::Quantity::Cosine => "cosine".to_string(),
        crate::lut::Quantity::Roughness(q) => format!("roughness ({}: {})", q.name(), q.mapping()),
        crate::lut::Quantity::Fresnel(q) => format!("fresnel ({}: {})", q.name(), q.mapping()),
        crate::lut::Quantity::Anisotropy => {
            format!("anisotropy ({})", crate::table::classic::ANISOTROPY_MAPPING)
        }
        crate::lut::Quantity::FormFactor => {
            "form factor (the z of its direction, or its length)".to_string()
        }
    };
    format!(
        "{} — {q}, {} texels over [{}, {}], {}{}",
        a.name,
        a.size,
        a.range[0],
        a.range[1],
        a.convention.name(),
        a.spacing_note()
    )
}

pub fn run(a: InspectArgs) -> Result<(), CliError> {
    admit_read(&a.guards, "this inspect", &a.file)?;
    let rb = read(&a.file)?;
    let sc = rb.sidecar.as_ref();
    let s = |path: &[&str]| -> Option<Value> {
        let mut x = sc?;
        for p in path {
            x = x.get(*p)?;
        }
        Some(x.clone())
    };
    let stats = rb.lut.as_ref().map(readback::stats);
    let notes = notes(&rb);
    if a.json {
        let doc = json!({
            "texture": rb.texture.as_ref().map(|p| p.display().to_string()),
            "texture_format": rb.texture_format,
            "sidecar": rb.sidecar_path.as_ref().map(|p| p.display().to_string()),
            "preset": rb.preset,
            "table": s(&["table"]),
            "model": rb.table.as_ref().map(|t| crate::meta::model_summary(&t.spec)),
            "axes": rb.lut.as_ref().map(|l| l.axes.iter().map(|x| json!({
                "name": x.name, "size": x.size, "range": x.range, "convention": x.convention.name(),
                "warp": x.warp.name(), "clamp": x.clamp,
            })).collect::<Vec<_>>()),
            "channels": s(&["channels"]),
            "reconstruction": s(&["reconstruction"]),
            "storage": s(&["storage", "texel_type"]),
            "scale": rb.scale,
            "estimated_max_error": s(&["quadrature", "estimated_max_error"]),
            "input_hash": s(&["input_hash"]),
            "input_hash_consistent": rb.hash_matches,
            "file_attributes": rb.file_facts.iter().map(|(k, v)| (k.clone(), json!(v))).collect::<serde_json::Map<_, _>>(),
            "stats": stats,
            "notes": notes,
        });
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
        return Ok(());
    }
    if let Some(t) = &rb.texture {
        outln!(
            "texture:   {} ({})",
            t.display(),
            rb.texture_format.unwrap_or("")
        );
    }
    match &rb.sidecar_path {
        Some(p) => outln!("sidecar:   {}", p.display()),
        None => outln!("sidecar:   none found (showing what the texture itself tells)"),
    }
    if let Some(p) = &rb.preset {
        outln!("preset:    {p}");
    }
    if let Some(t) = &rb.table {
        outln!(
            "table:     {} ({}: {})",
            t.spec.name,
            t.spec.kind.name(),
            t.spec.kind.description()
        );
        outln!("model:     {}", crate::meta::model_summary(&t.spec));
        outln!("storage:   {}, scale {}", t.spec.storage.name(), t.scale);
    }
    if rb.table.is_none() {
        for (k, v) in &rb.file_facts {
            outln!("{k:<10} {v}");
        }
    }
    if let Some(l) = &rb.lut {
        outln!("axes (u, v, w):");
        for x in &l.axes {
            outln!("  {}", axis_line(x));
        }
    }
    if let Some(Value::Array(ch)) = s(&["channels"]) {
        outln!("channels:");
        for c in ch {
            outln!(
                "  {} — {}",
                c["name"].as_str().unwrap_or(""),
                c["meaning"].as_str().unwrap_or("")
            );
        }
    }
    if let Some(Value::String(r)) = s(&["reconstruction"]) {
        outln!("shader:    {r}");
    }
    if let Some(Value::Object(e)) = s(&["quadrature", "estimated_max_error"]) {
        let parts: Vec<String> = e.iter().map(|(k, v)| format!("{k} {v}")).collect();
        outln!(
            "estimated bake error (max abs per channel): {}",
            parts.join(", ")
        );
    }
    if let Some(st) = &stats {
        outln!("texels (stored values):");
        outln!(
            "  {:<12} {:>14} {:>14} {:>14} {:>5} {:>5}",
            "channel",
            "min",
            "max",
            "mean",
            "NaN",
            "Inf"
        );
        for c in st {
            outln!(
                "  {:<12} {:>14.8} {:>14.8} {:>14.8} {:>5} {:>5}",
                c.name,
                c.min,
                c.max,
                c.mean,
                c.nan,
                c.inf
            );
        }
    }
    for n in &notes {
        outln!("note: {n}");
    }
    Ok(())
}

fn notes(rb: &Readback) -> Vec<String> {
    let mut v = Vec::new();
    if rb.sidecar.is_none() {
        v.push("no JSON sidecar next to the texture: axes, channel meanings and the bake error are unknown beyond the file's own header".into());
    }
    if rb.texture.is_none() {
        v.push(
            "no texture found for this sidecar (looked for its files.exr / files.ktx2 / files.dds)"
                .into(),
        );
    }
    if rb.hash_matches == Some(false) {
        let same_version = rb
            .sidecar
            .as_ref()
            .and_then(|s| s.pointer("/generator/version"))
            .and_then(Value::as_str)
            == Some(crate::meta::VERSION);
        v.push(if same_version {
            "the sidecar's input_hash does not match the table it describes: it was edited by hand"
                .into()
        } else {
            "written by another brdfbake version: its input_hash differs from this version's".into()
        });
    }
    if rb.scale != 1.0 {
        v.push(format!(
            "texels are stored as value x {}; divide by it",
            rb.scale
        ));
    }
    if let Some(st) = rb.lut.as_ref().map(readback::stats) {
        for c in st {
            if c.nan + c.inf > 0 {
                v.push(format!(
                    "channel {}: {} NaN, {} Inf texels",
                    c.name, c.nan, c.inf
                ));
            }
        }
    }
    v
}
