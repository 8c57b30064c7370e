//! Tables as engines ship them. An engine preset (`presets/engines/`) bakes a shipped table
//! on the engine's own grid — axes, texel positions, clamps, axis order, channels, storage —
//! and says where the original lives (`source`) and how its file holds it (`shipped`,
//! [`shipped::Shipped`]). `brdfbake compare` reads the shipped file ([`shipped`]) and compares
//! it, and brdfbake's own table, with exact values at every texel ([`compare`]).

pub mod compare;
pub mod figures;
pub mod select;
pub mod shipped;

use crate::lut::Lut;
use crate::preset::PresetTable;
use crate::table::{BakeError, BakeOptions, Storage};
use serde::Serialize;
pub use shipped::Source;

/// The comparison of one preset table with its shipped file.
#[derive(Clone, Debug, Serialize)]
pub struct Comparison {
    pub preset: String,
    pub table: String,
    /// The engine's table as the preset's `source` names it (`Cycles (Blender) table_ggx_E`),
    /// or the preset's table name.
    pub source_table: String,
    pub file: String,
    /// Stored axis sizes.
    pub dims: Vec<usize>,
    /// The tolerance the exact reference was baked at (100× the table's, or the table's own
    /// where the tighter one cannot be reached), and its largest error estimate.
    pub reference_tolerance: f64,
    pub exact_error_estimate: f64,
    /// Why the reference is baked at the table's own tolerance, where it is (an `ltc` table's
    /// fit, or a tighter rule that does not converge at every texel): it is then the same
    /// computation as brdfbake's table, whose error against it is 0 by construction, and
    /// brdfbake's true error is bounded by the error estimate alone.
    pub reference_is_own_bake: Option<&'static str>,
    /// What brdfbake's computed texels are held to: max |error| / max(1, |exact|) ≤ this
    /// (1e-6, or the table's tolerance plus f32 rounding when coarser).
    pub brdfbake_bound: f64,
    /// What the file stores, and, for a quotes file, how many texels it quotes.
    pub storage: String,
    /// The degenerate slices the preset names, left out of each channel's verdict.
    pub excluded: Vec<compare::ExcludedSlice>,
    pub channels: Vec<compare::ChannelComparison>,
    /// The shipped table's error per texel (shipped − exact) of each compared channel, in
    /// the stored layout: for the report's heatmaps.
    #[serde(skip)]
    pub errors: Lut,
}

/// Why a comparison could not be made.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// The preset or the file cannot be compared (exit 2).
    #[error("{0}")]
    Input(String),
    /// The bake failed: the time limit, or a tolerance miss (exit 1).
    #[error(transparent)]
    Bake(#[from] BakeError),
}

/// The tolerance of the exact reference: 100× tighter than the table's own, at most 1e-9,
/// at least the tightest the rules accept.
fn reference_tolerance(tol: f64) -> f64 {
    (tol / 100.0).clamp(crate::table::spec::MIN_TOLERANCE, 1e-9)
}

/// `v` as the table's storage holds it (f16 rounds to nearest even; UNORM to its code, read
/// back; f32 as is). A value a UNORM storage cannot hold stays as it is (the bake refuses it).
fn stored_value(storage: Storage, v: f32) -> f32 {
    match storage {
        Storage::F16 => half::f16::from_f32(v).to_f32(),
        Storage::F32 => v,
        Storage::Unorm8 | Storage::Unorm16 => {
            let max = storage.unorm_max().expect("a UNORM storage");
            crate::encode::unorm::code(v, max)
                .map_or(v, |c| crate::encode::unorm::value(c, max) as f32)
        }
    }
}

/// Compares table `t` of preset `preset` (whose `source` is `source`) with `bytes`, the engine's shipped file (`file`
/// names it in messages). Bakes the table twice: as the preset says, and as the exact
/// reference.
pub fn compare_table(
    preset: &str,
    source: Option<&Source>,
    t: &PresetTable,
    bytes: &[u8],
    file: &str,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Comparison, CompareError> {
    let shipped = t.shipped.as_ref().ok_or_else(|| {
        CompareError::Input(format!(
            "preset {preset}: table {} has no `shipped` description (how the engine's file holds it), so there is nothing to compare with",
            t.spec.name
        ))
    })?;
    let stored_axes = t.stored_axes();
    let dims = [0, 1, 2].map(|k| stored_axes.get(k).map_or(1, |a| a.size));
    let table = shipped.read(bytes, dims, file).map_err(|e| {
        CompareError::Input(format!(
            "{e}\n  {preset} reads {}; {file} looks like {}",
            shipped.expects(None),
            shipped::looks_like(bytes)
        ))
    })?;
    let ours = crate::table::bake_with(
        &t.spec,
        &BakeOptions {
            deadline,
            accept_error_estimate: t.accept_error_estimate,
        },
    )?;
    let mut ref_spec = t.spec.clone();
    // An `ltc` table's matrix channels are the fit's result: they have no exact value beyond
    // the fit itself, and a refit on integrals of another tolerance may settle in another
    // minimum where the fit is ill-conditioned (grazing views at small alpha) with the same
    // lit error. Its reference is the fit at the preset's own tolerance, so the matrix
    // channels compare the shipped fit with brdfbake's; the lit error, which is what matters,
    // is tests/ltc_table.rs'.
    let fits_matrix = t.spec.kind == crate::table::TableKind::Ltc
        && crate::table::ltc::ltc_channels(&t.spec)
            .iter()
            .any(|c| c.is_matrix());
    ref_spec.tolerance = if fits_matrix {
        t.spec.tolerance
    } else {
        reference_tolerance(t.spec.tolerance)
    };
    let reference = |spec: &crate::table::TableSpec| {
        crate::table::bake_with(
            spec,
            &BakeOptions {
                deadline,
                // (where the reference's rule cannot reach its tighter tolerance it keeps what
                // it reached, at most what the preset accepts)
                accept_error_estimate: Some(t.accept_error_estimate.unwrap_or(t.spec.tolerance)),
            },
        )
    };
    // a texel whose tighter rule does not converge (a near-singular lobe at a grazing view)
    // leaves the reference at the preset's own tolerance, which the preset's bake met
    let ours = t.stored(ours);
    let (exact, reference_tolerance) = match &table.present {
        // a quotes file: the reference at the quoted texels only (the rest keeps brdfbake's
        // values, which nothing compares)
        Some(present) => (
            quoted_reference(t, &ours, present, ref_spec.tolerance, deadline)?,
            ref_spec.tolerance,
        ),
        None => {
            let (l, tol) = match reference(&ref_spec) {
                Ok(l) => (l, ref_spec.tolerance),
                Err(BakeError::ToleranceMissed { .. }) => (reference(&t.spec)?, t.spec.tolerance),
                Err(e) => return Err(e.into()),
            };
            (t.stored(l), tol)
        }
    };
    let stored = (t.spec.storage != Storage::F32).then(|| {
        let mut s = ours.clone();
        for v in s.data.iter_mut() {
            // (the storage holds value × scale)
            let scale = t.scale as f32;
            *v = stored_value(t.spec.storage, *v * scale) / scale;
        }
        s
    });
    let exact_error = exact.error_estimate.iter().fold(0.0, |m: f64, e| m.max(*e));
    let (excluded, _) =
        compare::judged_texels(&exact, table.present.as_deref(), &shipped.degenerate);
    let channels = compare::compare(&compare::Inputs {
        shipped: &table,
        ours: &ours,
        stored: stored.as_ref(),
        exact: &exact,
        exact_error,
        degenerate: &shipped.degenerate,
        names: &shipped.spelled,
    });
    // the shipped table's errors, for the report
    let mut errors = exact.clone();
    errors.channels = channels
        .iter()
        .map(|c| crate::lut::Channel {
            name: c.channel.clone(),
            meaning: format!("shipped {} - exact", c.channel),
        })
        .collect();
    let nce = exact.channels.len();
    let ncf = table.channels.len();
    errors.data = (0..exact.texel_count())
        .flat_map(|i| {
            let table = &table;
            let exact = &exact;
            channels.iter().map(move |c| {
                let e = exact
                    .channels
                    .iter()
                    .position(|x| x.name == c.channel)
                    .expect("compared");
                let f = table
                    .channels
                    .iter()
                    .position(|x| x == &c.channel)
                    .expect("compared");
                if table.present.as_ref().is_some_and(|p| !p[i]) {
                    // (a texel the quotes file does not hold)
                    return 0.0;
                }
                (table.values[i * ncf + f] - exact.data[i * nce + e] as f64) as f32
            })
        })
        .collect();
    // each left-out slice's largest error, from the errors just computed
    let mut excluded = excluded;
    for e in excluded.iter_mut() {
        let k = errors.axes.iter().position(|a| a.name == e.axis);
        let nc = errors.channels.len().max(1);
        let (nx, ny) = (errors.dim(0), errors.dim(1));
        e.max_abs = errors
            .data
            .chunks(nc)
            .enumerate()
            .filter(|(t, _)| {
                k.is_some_and(|k| [t % nx, (t / nx) % ny, t / (nx * ny)][k] == e.index)
            })
            .flat_map(|(_, c)| c.iter())
            .fold(0.0f64, |m, v| m.max(v.abs() as f64));
    }
    // (the computed texels are f32: 2^-24 relative, well below 1e-6 for values up to ~16)
    let largest = exact.data.iter().fold(0.0f64, |m, v| m.max(v.abs() as f64));
    let rounding = largest * 2f64.powi(-24) + t.spec.tolerance;
    Ok(Comparison {
        preset: preset.to_string(),
        table: t.spec.name.clone(),
        // (the names without their parenthetical notes: `Cycles (Blender)` is Cycles)
        source_table: source.map_or_else(
            || t.spec.name.clone(),
            |s| {
                let short = |x: &str| x.split(" (").next().unwrap_or(x).to_string();
                format!("{} `{}`", short(&s.engine), short(&s.table))
            },
        ),
        file: file.to_string(),
        dims: stored_axes.iter().map(|a| a.size).collect(),
        reference_tolerance,
        reference_is_own_bake: (reference_tolerance >= t.spec.tolerance).then_some(
            if fits_matrix {
                "the table is an LTC fit, whose matrix has no exact value beyond the fit"
            } else {
                "a 100x tighter reference does not converge at every texel"
            },
        ),
        exact_error_estimate: exact_error,
        brdfbake_bound: 1e-6f64.max(rounding),
        storage: table.storage.clone(),
        excluded,
        channels,
        errors,
    })
}

/// brdfbake's stored table `ours` with the texels `present` replaced by their exact values
/// at tolerance `tol` (each a one-point bake), their error estimates its estimate.
fn quoted_reference(
    t: &PresetTable,
    ours: &Lut,
    present: &[bool],
    tol: f64,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Lut, CompareError> {
    use rayon::prelude::*;
    let texels: Vec<usize> = (0..present.len()).filter(|t| present[*t]).collect();
    let (nx, ny) = (ours.dim(0), ours.dim(1));
    let values: Vec<Result<(Vec<f64>, f64), String>> = texels
        .par_iter()
        .map(|&i| {
            if deadline.is_some_and(|d| d.passed()) {
                return Err("the time limit passed".into());
            }
            let idx = [i % nx, (i / nx) % ny, i / (nx * ny)];
            let x = crate::lut::texel_nominal_coordinates(&ours.axes, &idx[..ours.axes.len()]);
            let (v, e) = crate::readback::exact_at(&t.spec, &t.to_kind_order(&x), tol)?;
            Ok((
                t.stored_values(&v),
                e.iter().fold(0.0, |m: f64, x| m.max(*x)),
            ))
        })
        .collect();
    let mut exact = ours.clone();
    let nc = exact.channels.len();
    let mut err = 0.0f64;
    for (i, v) in texels.iter().zip(values) {
        let (v, e) = v.map_err(|m| match deadline.filter(|d| d.passed()) {
            Some(d) => CompareError::Bake(BakeError::TimeLimit {
                name: t.spec.name.clone(),
                seconds: d.seconds,
                texels: texels.len(),
            }),
            None => CompareError::Input(m),
        })?;
        for (d, x) in exact.data[i * nc..(i + 1) * nc].iter_mut().zip(&v) {
            *d = *x as f32;
        }
        err = err.max(e);
    }
    exact.error_estimate = vec![err; nc];
    Ok(exact)
}

impl Comparison {
    /// Whether brdfbake's table meets [`Comparison::brdfbake_bound`] in every channel.
    pub fn brdfbake_within_bound(&self) -> bool {
        self.channels
            .iter()
            .all(|c| c.brdfbake.max_rel <= self.brdfbake_bound)
    }
}
