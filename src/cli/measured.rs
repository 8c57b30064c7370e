//! `brdfbake measured FILE`: a measured BRDF (MERL binary format): what the file holds,
//! its directional albedo per channel, and GGX + Lambert and Beckmann + Lambert fits per
//! channel with their errors.

use super::CliError;
use crate::merl::{albedo_table_until, fit_model_lambert, Merl, FIT_MODELS};
use crate::model::{Masking, NdfKind};
use serde_json::json;
use std::sync::Arc;

#[derive(clap::Args, Debug)]
pub struct MeasuredArgs {
    /// A MERL .binary file (90x90x180 half/difference-angle table, R G B f64).
    pub file: std::path::PathBuf,
    /// Number of cos(theta_i) values of the albedo table (at texel centres).
    #[arg(long, default_value_t = 16)]
    pub albedo_size: usize,
    /// Quadrature tolerance of each albedo (estimated absolute error; at least 1e-3 is
    /// used on measured data, see `merl::MEASURED_TOLERANCE_FLOOR`).
    #[arg(long, default_value_t = 1e-3)]
    pub tolerance: f64,
    /// Skip the fits.
    #[arg(long)]
    pub no_fit: bool,
    /// The microfacet models to fit (each + Lambert, Schlick F0, per channel), comma-separated:
    /// ggx, beckmann (height-correlated Smith G2), cook-torrance (Beckmann, V-groove G).
    /// [default: ggx,beckmann]
    #[arg(long, conflicts_with = "no_fit")]
    pub fit: Option<String>,
    /// Also write the albedo as a table: DIR/<stem>-albedo.exr and its sidecar .json.
    #[arg(long, value_name = "DIR")]
    pub out: Option<std::path::PathBuf>,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

/// Typical integrand evaluations of one albedo of measured data at the measured floor
/// tolerance, for the time estimate (bounded by the integral budget in any case).
const EVALS_PER_ALBEDO: f64 = 2e5;

/// Evaluations of one fit: ~90 alpha values (a grid of 40, then golden-section steps), each
/// a linear least-squares solve over ~40k nodes.
const EVALS_PER_FIT: f64 = 90.0 * 40_000.0;

/// Node strides (theta_d, phi_d) of the fit: every theta_h node, every 3rd theta_d and
/// every 6th phi_d node (~40k nodes above the horizon).
pub const FIT_STRIDE: [usize; 2] = [3, 6];

pub fn run(a: MeasuredArgs) -> Result<(), CliError> {
    if !(1..=1024).contains(&a.albedo_size) {
        return Err(CliError::input(format!(
            "--albedo-size must be in [1, 1024], got {}",
            a.albedo_size
        )));
    }
    super::guards::check_tolerance(a.tolerance)?;
    let mut ndfs: Vec<(&str, NdfKind, Masking)> = Vec::new();
    for part in a
        .fit
        .as_deref()
        .unwrap_or("ggx,beckmann")
        .split(',')
        .map(str::trim)
    {
        let n = FIT_MODELS.iter().find(|n| n.0 == part).ok_or_else(|| {
            CliError::input(format!(
                "--fit: unknown model {part:?} (accepted: {})",
                FIT_MODELS.map(|n| n.0).join(", ")
            ))
        })?;
        if !ndfs.contains(n) {
            ndfs.push(*n);
        }
    }
    let fits = if a.no_fit { 0 } else { 3 * ndfs.len() };
    let deadline = a.guards.admit(&super::guards::Work {
        what: "this measured run",
        // the file read, its values, and the fit nodes
        memory: 2 * crate::merl::FILE_BYTES as u64 + (64 << 20),
        memory_detail: "a MERL file read and held, and the fit nodes".into(),
        time: crate::resources::time_of_evaluations(
            (3 * a.albedo_size) as f64 * EVALS_PER_ALBEDO + fits as f64 * EVALS_PER_FIT,
        ),
        threads: rayon::current_num_threads(),
        smaller: "a smaller --albedo-size, or fewer --fit models",
    })?;
    let m = Merl::read(&a.file).map_err(CliError::from)?;
    let m = Arc::new(m);
    let table = albedo_table_until(&m, a.albedo_size, a.tolerance, Some(&deadline))
        .ok_or_else(|| super::guards::stopped("this measured run", &deadline))?;
    // one list of per-channel fits per NDF, in the order asked
    let all_fits: Vec<(&str, Vec<_>)> = if a.no_fit {
        Vec::new()
    } else {
        ndfs.iter()
            .map(|&(name, n, mk)| {
                (
                    name,
                    (0..3)
                        .map(|c| fit_model_lambert(&m, c, FIT_STRIDE, n, mk))
                        .collect::<Vec<_>>(),
                )
            })
            .collect()
    };
    let fits_of = |n: &str| {
        all_fits
            .iter()
            .find(|(k, _)| *k == n)
            .map(|(_, f)| f.clone())
            .unwrap_or_default()
    };
    if let Some(dir) = &a.out {
        let named: Vec<(&str, Vec<_>)> = all_fits.iter().map(|(n, f)| (*n, f.clone())).collect();
        let files = super::measured_table::files(&a.file, &m, &table, a.tolerance, &named, dir)
            .map_err(CliError::input)?;
        std::fs::create_dir_all(dir).map_err(|e| {
            CliError::env(format!(
                "cannot create output directory {}: {e}",
                dir.display()
            ))
        })?;
        crate::write::write_all_atomic(&files).map_err(|e| CliError::env(e.to_string()))?;
        for (p, _) in &files {
            eprintln!("wrote {}", p.display());
        }
    }
    let fits = fits_of("ggx");
    let fits_beckmann = fits_of("beckmann");
    let fits_ct = fits_of("cook-torrance");
    let names = ["R", "G", "B"];
    if a.json {
        let doc = json!({
            "schema": "brdfbake.measured/1",
            "file": a.file.display().to_string(),
            "format": "MERL BRDF (Matusik et al. 2003): int32 90 90 180, R G B f64, scales 1/1500 1.15/1500 1.66/1500",
            "unmeasured": m.unmeasured,
            "unmeasured_above_horizon": m.unmeasured_above_horizon,
            "unmeasured_policy": "interpolation corners that are unmeasured are left out and the weights renormalized; where all are unmeasured f = 0",
            "albedo": {"mu": "texel centres (i + 0.5)/n", "tolerance": a.tolerance, "rows": table},
            "fit": {
                "model": "kd/pi + D_GGX(alpha) G2_smith_height_correlated F_schlick(f0) / (4 cos_i cos_o)",
                "weights": "cos_i cos_o, nodes above the horizon, measured only",
                "stride_theta_d_phi_d": FIT_STRIDE,
                "channels": fits.iter().zip(names).map(|(f, n)| json!({"channel": n, "fit": f})).collect::<Vec<_>>(),
            },
            "fit_beckmann": {
                "model": "kd/pi + D_Beckmann(alpha) G2_smith_height_correlated F_schlick(f0) / (4 cos_i cos_o), D = exp(-tan^2/alpha^2)/(pi alpha^2 cos^4)",
                "weights": "cos_i cos_o, nodes above the horizon, measured only",
                "stride_theta_d_phi_d": FIT_STRIDE,
                "channels": fits_beckmann.iter().zip(names).map(|(f, n)| json!({"channel": n, "fit": f})).collect::<Vec<_>>(),
            },
            "fit_cook_torrance": {
                "model": "kd/pi + D_Beckmann(alpha) G_V-groove F_schlick(f0) / (4 cos_i cos_o), G = min(1, 2(n.h)(n.v)/(v.h), 2(n.h)(n.l)/(v.h)) (Cook & Torrance 1982)",
                "weights": "cos_i cos_o, nodes above the horizon, measured only",
                "stride_theta_d_phi_d": FIT_STRIDE,
                "channels": fits_ct.iter().zip(names).map(|(f, n)| json!({"channel": n, "fit": f})).collect::<Vec<_>>(),
            },
        });
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).map_err(|e| CliError::env(e.to_string()))?
        );
        return Ok(());
    }
    outln!("{}", a.file.display());
    for (c, name) in names.iter().enumerate() {
        outln!(
            "  {name}: {} unmeasured entries ({} of them above the horizon)",
            m.unmeasured[c],
            m.unmeasured_above_horizon[c]
        );
    }
    outln!("  directional albedo E(mu), R G B (+- error):");
    for r in &table {
        outln!(
            "    mu {:.5}: {:.6} {:.6} {:.6}  (+- {:.1e})",
            r.mu,
            r.albedo[0],
            r.albedo[1],
            r.albedo[2],
            r.error.iter().cloned().fold(0.0, f64::max)
        );
    }
    for (f, n) in all_fits.iter().flat_map(|(_, fs)| fs.iter().zip(names)) {
        match f {
            Some(f) => outln!(
                "  fit {n}: {} + Lambert kd = {:.6}, f0 = {:.6}, alpha = {:.6}{}; rms {:.3e} (relative {:.3e}), max |error| {:.3e} over {} nodes",
                match (f.ndf, f.masking) {
                    ("ggx", _) => "GGX",
                    (_, "v-groove") => "Cook-Torrance (Beckmann, V-groove G)",
                    _ => "Beckmann",
                },
                f.kd,
                f.f0,
                f.alpha,
                if f.alpha_at_limit { " (at the end of the searched range)" } else { "" },
                f.rms,
                f.rel_rms,
                f.max_abs,
                f.nodes
            ),
            None => outln!("  fit {n}: no measured node"),
        }
    }
    Ok(())
}
