//! `brdfbake measured FILE --out DIR`: the measured directional albedo as a table, written
//! like `bake` writes its tables — `DIR/<stem>-albedo.exr` (f32, channels R, G, B over one
//! `cos_theta_v` axis at texel centres) and its sidecar `DIR/<stem>-albedo.json` (schema
//! `brdfbake.lut/1`, kind `measured-albedo`), both written atomically after everything is
//! computed. The sidecar records the source file, the unmeasured entries and the fits; it
//! cannot be rebuilt into a preset table (there is no preset for a measured file), so
//! `inspect` and `probe` read it and `verify`/`bake --check` do not apply.

use crate::encode::exr::ExrEncoder;
use crate::encode::Encoder;
use crate::lut::{Axis, Channel, Convention, Lut, Quantity};
use crate::merl::{AlbedoRow, Fit, Merl};
use crate::table::Storage;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

use crate::meta::MEASURED_TABLE_KIND as KIND;

/// The texture and sidecar (path, bytes) for the albedo rows of `m` read from `file`.
pub fn files(
    file: &Path,
    m: &Merl,
    rows: &[AlbedoRow],
    tol: f64,
    fits: &[(&str, Vec<Option<Fit>>)],
    out: &Path,
) -> Result<Vec<(PathBuf, Vec<u8>)>, String> {
    // the file's stem in the characters a file name can always hold; a stem that needed
    // changing gets the first 8 hex digits of its own SHA-256, so that different stems
    // ("a b", "a_b", "a\u{202e}b") never write the same files
    let original = file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "measured".into());
    let mut stem = original
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect::<String>();
    let raw = file
        .file_stem()
        .map(|s| s.as_encoded_bytes())
        .unwrap_or(b"measured");
    if stem.as_bytes() != raw {
        let digest = crate::digest::sha256(raw);
        let hex = digest.rsplit(':').next().unwrap_or(&digest);
        stem = format!("{stem}-{}", &hex[..8]);
    }
    let name = format!("{stem}-albedo");
    let axis = Axis {
        name: "cos_theta_v".into(),
        quantity: Quantity::Cosine,
        size: rows.len(),
        range: [0.0, 1.0],
        convention: Convention::Centers,
        warp: Default::default(),
        clamp: None,
    };
    let names = ["R", "G", "B"];
    let channels: Vec<Channel> = names
        .iter()
        .map(|n| Channel {
            name: (*n).into(),
            meaning: format!(
                "E(mu) = int f_{n}(l, v) (n.l) dw_l of the measured {n} channel (MERL scale applied), interpolated data"
            ),
        })
        .collect();
    let mut data = Vec::with_capacity(rows.len() * 3);
    let mut err = vec![0.0f64; 3];
    for r in rows {
        for c in 0..3 {
            if !r.albedo[c].is_finite() {
                return Err(format!(
                    "{}: the albedo at mu = {} is not finite in channel {}",
                    file.display(),
                    r.mu,
                    names[c]
                ));
            }
            data.push(r.albedo[c] as f32);
            err[c] = err[c].max(r.error[c]);
        }
    }
    let lut = Lut {
        axes: vec![axis],
        channels,
        data,
        error_estimate: err.clone(),
        evaluations: 0,
    };
    let attrs = vec![
        ("schema".to_string(), crate::meta::SCHEMA.to_string()),
        ("version".to_string(), crate::meta::VERSION.to_string()),
        ("table".to_string(), name.clone()),
        ("kind".to_string(), KIND.to_string()),
        ("source".to_string(), file.display().to_string()),
        (
            "axis0".to_string(),
            format!("cos_theta_v cosine centers [0, 1] {} texels", rows.len()),
        ),
    ];
    let exr = ExrEncoder {
        storage: Storage::F32,
        table_name: name.clone(),
    }
    .encode(&lut, &attrs)
    .map_err(|e| e.to_string())?;
    let exr_name = format!("{name}.exr");
    let sidecar: Value = json!({
        "schema": crate::meta::SCHEMA,
        "generator": {"name": "brdfbake", "version": crate::meta::VERSION},
        "table": {
            "name": name,
            "kind": KIND,
            "description": "directional albedo E(cos theta_v) per channel of a measured BRDF (MERL binary file)",
            "dimensions": 1,
            "size": [rows.len()],
        },
        "model": {
            "form": "measured: the MERL table, multilinearly interpolated in Rusinkiewicz half/difference angles",
            "measured": {
                "file": file.display().to_string(),
                "format": "MERL BRDF (Matusik et al. 2003): int32 90 90 180, R G B f64, scales 1/1500 1.15/1500 1.66/1500",
                "unmeasured": m.unmeasured,
                "unmeasured_above_horizon": m.unmeasured_above_horizon,
                "unmeasured_policy": "interpolation corners that are unmeasured are left out and the weights renormalized; where all are unmeasured f = 0 (the albedo is then a lower bound)",
            },
            "fits": fits.iter().map(|(ndf, f)| json!({
                "ndf": ndf,
                "model": "kd/pi + D(alpha) G2_smith_height_correlated F_schlick(f0) / (4 cos_i cos_o)",
                "channels": f.iter().zip(names).map(|(f, n)| json!({"channel": n, "fit": f})).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        },
        "axes": [crate::meta::axis_json(0, &lut.axes[0])],
        "channels": lut.channels.iter().enumerate().map(|(i, c)| json!({"index": i, "name": c.name, "meaning": c.meaning})).collect::<Vec<_>>(),
        "reconstruction": "E(mu) per colour channel: the fraction of uniform white light the measured material reflects towards a view at cos theta_v = mu",
        "storage": {
            "texel_type": "f32",
            "rounding": "round to nearest f32: relative 2^-24 (6e-8 for values <= 1)",
            "layout": "channels interleaved per texel; x (axis 0, u) fastest",
            "row_order": "one row",
            "sampling": "linear filtering, clamp-to-edge; coordinates as in axes[0].shader_texture_coordinate",
            "scale": 1.0,
            "scale_meaning": "stored texel = value * scale",
        },
        "quadrature": {
            "method": "the energy-law integrator (brdfbake laws) on the interpolated data: nested adaptive Gauss-Kronrod (G7/K15) over the half vector, exact horizon; tolerance raised to the measured floor 1e-3",
            "tolerance": tol.max(crate::merl::MEASURED_TOLERANCE_FLOOR),
            "estimated_max_error": names.iter().zip(&err).map(|(n, e)| (n.to_string(), json!(e))).collect::<serde_json::Map<_, _>>(),
            "evaluations": 0,
        },
        "files": {"exr": exr_name},
    });
    let sealed = crate::digest::seal(sidecar, &[(&exr_name, &exr)]);
    Ok(vec![
        (out.join(&exr_name), exr),
        (out.join(format!("{name}.json")), sealed),
    ])
}
