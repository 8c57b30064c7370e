//! Table kinds: each turns a [`TableSpec`] into a [`Lut`] through the model and the
//! quadrature. One file per kind; this file holds the shared texel loop.
//!
//! Determinism: every texel is computed independently from its own coordinates with a
//! fixed-order quadrature, and rayon only decides *which thread* computes it, so the
//! output is bit-identical for any thread count.

pub mod albedo;
pub mod classic;
pub mod classic_model;
pub mod dfg;
pub mod dfg_lines;
pub mod dielectric;
pub mod dielectric_average;
pub mod dielectric_schlick;
pub mod energy;
pub mod local;
pub mod ltc;
pub mod methods;
pub mod schlick_weight;
mod smooth;
pub mod spec;
pub mod texel;
mod validate;

pub use spec::{DfgLayout, LtcChannel, ModelSpec, Storage, TableKind, TableSpec};
pub use texel::MISSES_SHOWN;
pub(crate) use texel::{FibreFn, Misses, RoughnessFibres, TexelResult};

use crate::lut::{Channel, Lut};
use crate::numfmt::num;
use crate::quadrature::budget::{with_budget, INTEGRAL_EVAL_BUDGET};
use rayon::prelude::*;

/// Why a bake failed.
#[derive(Debug, thiserror::Error)]
pub enum BakeError {
    #[error("invalid table spec {name:?}: {msg}")]
    Invalid { name: String, msg: String },
    #[error(
        "table {name:?}: stopped at the time limit of {} (--max-time) before all {texels} texels were baked; \
         nothing was written: raise the limit, use more threads, or bake a smaller table",
        crate::numfmt::human_seconds(*seconds)
    )]
    TimeLimit {
        name: String,
        seconds: f64,
        texels: usize,
    },
    #[error("{}", tolerance_message(name, *limit, *tolerance, *count, *texels, worst))]
    ToleranceMissed {
        name: String,
        /// The largest accepted estimate (the tolerance, or the preset's
        /// `accept_error_estimate`).
        limit: f64,
        tolerance: f64,
        /// Texel channels whose estimate exceeds `limit`.
        count: usize,
        texels: usize,
        /// The largest of them, largest first (at most [`MISSES_SHOWN`]).
        worst: Vec<Miss>,
    },
    /// The LTC fit found no LTC at a texel (an `ltc` table).
    #[error("table {name:?}: the LTC fit failed at texel {:?} ({}): {msg}; nothing was written", &texel[..at.len()], at.iter().map(|(a, x)| format!("{a}={}", num(*x))).collect::<Vec<_>>().join(", "))]
    FitFailed {
        name: String,
        texel: [usize; 3],
        at: Vec<(String, f64)>,
        msg: String,
    },
    #[error(
        "table {name:?}: channel {channel} of texel {:?} ({}) is not finite ({value}{}): the model is undefined or \
         overflows there; move the axis range away from that point{}",
        &texel[..at.len()],
        at.iter().map(|(a, x)| format!("{a}={}", num(*x))).collect::<Vec<_>>().join(", "),
        if value.is_finite() { ", beyond f32" } else { "" },
        if value.is_finite() { " or lower the values with a \"scale\"" } else { "" }
    )]
    NonFinite {
        name: String,
        texel: [usize; 3],
        /// Each axis' name and the texel's coordinate on it.
        at: Vec<(String, f64)>,
        channel: String,
        value: f64,
    },
}

/// A texel channel whose quadrature error estimate exceeds what the table accepts.
#[derive(Clone, Debug, PartialEq)]
pub struct Miss {
    pub texel: [usize; 3],
    /// Each axis' name and the texel's coordinate on it.
    pub at: Vec<(String, f64)>,
    pub channel: String,
    pub estimate: f64,
}

fn tolerance_message(
    name: &str,
    limit: f64,
    tolerance: f64,
    count: usize,
    texels: usize,
    worst: &[Miss],
) -> String {
    let shown: Vec<String> = worst
        .iter()
        .map(|m| {
            let at: Vec<String> =
                m.at.iter()
                    .map(|(a, x)| format!("{a}={}", num(*x)))
                    .collect();
            format!(
                "{} at texel {:?} ({}): {}",
                m.channel,
                &m.texel[..m.at.len()],
                at.join(", "),
                num(m.estimate)
            )
        })
        .collect();
    let bound = if limit > tolerance {
        format!(
            "the accepted estimate {} (accept_error_estimate; tolerance {})",
            num(limit),
            num(tolerance)
        )
    } else {
        format!("its tolerance {}", num(tolerance))
    };
    format!(
        "table {name:?}: the quadrature's error estimate exceeds {bound} in {count} texel channel(s) of \
         {texels} texels; largest: {}. Nothing was written. The integrand cannot be resolved to that \
         accuracy there: move the axis range away from it (cosines near 0, roughness near its limits), \
         raise \"tolerance\", or accept the estimate explicitly with \"accept_error_estimate\" (recorded \
         in the sidecar)",
        shown.join("; ")
    )
}

/// What a bake may do besides the spec itself.
#[derive(Clone, Copy, Debug, Default)]
pub struct BakeOptions<'a> {
    /// Stop with [`BakeError::TimeLimit`] once this has passed (`bake --max-time`).
    pub deadline: Option<&'a crate::deadline::Deadline>,
    /// The largest per-texel error estimate accepted (default: the spec's tolerance); a
    /// table with a larger one fails with [`BakeError::ToleranceMissed`].
    pub accept_error_estimate: Option<f64>,
}

/// Bakes a table. Validates the spec first; never returns a table with NaN or Inf, nor one
/// whose quadrature error estimate exceeds the spec's tolerance at any texel.
pub fn bake(spec: &TableSpec) -> Result<Lut, BakeError> {
    bake_with(spec, &BakeOptions::default())
}

/// [`bake`] with a deadline.
pub fn bake_until(
    spec: &TableSpec,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Lut, BakeError> {
    bake_with(
        spec,
        &BakeOptions {
            deadline,
            ..Default::default()
        },
    )
}

/// [`bake`] with options: gives up with [`BakeError::TimeLimit`] once the deadline has passed (checked
/// before every texel — every column of a dfg table, every fibre of a table with a fibre
/// path —, so a bake overruns it by at most one texel, column or fibre per thread; every
/// texel's integrals together are bounded by
/// [`INTEGRAL_EVAL_BUDGET`] evaluations, see [`crate::quadrature::budget`]).
pub fn bake_with(spec: &TableSpec, opts: &BakeOptions) -> Result<Lut, BakeError> {
    let mut lut = bake_unclamped(spec, opts)?;
    clamp_nonnegative(spec, &mut lut);
    Ok(lut)
}

/// Which channels of a table hold a quantity that cannot be negative: every integral of a
/// non-negative integrand (albedos, split-sum terms, sheen, R and T, D, G, norms), every one
/// but the off-diagonal entries of an LTC matrix.
pub fn nonnegative_channels(spec: &TableSpec) -> Vec<bool> {
    match spec.kind {
        TableKind::Ltc => ltc::ltc_channels(spec)
            .iter()
            .map(|c| !matches!(c, LtcChannel::M20 | LtcChannel::M02))
            .collect(),
        _ => vec![true; channels(spec).len()],
    }
}

/// Stores a computed value below 0 of a channel that cannot be negative
/// ([`nonnegative_channels`]) as 0 (and −0 as +0). Such a value is a quadrature sum's
/// rounding near a zero (filament-dfg's cloth channel at n·v → 1, α → 0: −5e-9), within its
/// error estimate of the true value, which is ≥ 0: 0 is nearer to it, so the estimate still
/// bounds the stored texel's error.
fn clamp_nonnegative(spec: &TableSpec, lut: &mut Lut) {
    let keep = nonnegative_channels(spec);
    let nc = lut.channels.len().max(1);
    for texel in lut.data.chunks_mut(nc) {
        for (v, nonneg) in texel.iter_mut().zip(&keep) {
            if *nonneg && v.is_sign_negative() {
                *v = 0.0;
            }
        }
    }
}

/// [`bake_with`] before [`clamp_nonnegative`].
fn bake_unclamped(spec: &TableSpec, opts: &BakeOptions) -> Result<Lut, BakeError> {
    let deadline = opts.deadline;
    spec.validate().map_err(|msg| BakeError::Invalid {
        name: spec.name.clone(),
        msg,
    })?;
    if spec.kind.is_ltc() {
        return bake_ltc(spec, opts).map(|(lut, _)| lut);
    }
    if let Some((k, zero, rest)) = smooth_texels(spec) {
        return bake_with_smooth(spec, opts, k, zero, rest);
    }
    let limit = opts
        .accept_error_estimate
        .unwrap_or(spec.tolerance)
        .max(spec.tolerance);
    let channels = channels(spec);
    let dims = [
        spec.axes.first().map_or(1, |a| a.size),
        spec.axes.get(1).map_or(1, |a| a.size),
        spec.axes.get(2).map_or(1, |a| a.size),
    ];
    let n = dims[0] * dims[1] * dims[2];
    // `--max-time`: checked before every texel (every column of a dfg table, every fibre);
    // once passed, the remaining work is skipped and the bake fails with nothing to write
    let stopped = std::sync::atomic::AtomicBool::new(false);
    let out_of_time = || {
        use std::sync::atomic::Ordering::Relaxed;
        let Some(d) = deadline else { return false };
        if stopped.load(Relaxed) || d.passed() {
            stopped.store(true, Relaxed);
            return true;
        }
        false
    };
    // The texel results in blocks: one block per column (axis-0 index) for dfg tables, which
    // are computed a column (one view μ, all roughnesses) per task so that the column's view
    // data is built once (dfg::column_fn); one block in texel order otherwise.
    // (GGX dfg tables go by lines instead, interpolated along rows and columns: dfg_lines, whose
    // dense result needs no per-texel allocation)
    // (and large Charlie albedo tables: methods::albedo_by_lines)
    let dense = if matches!(spec.kind, TableKind::Dfg | TableKind::Albedo) {
        dfg_lines::bake(spec, &out_of_time, limit)
    } else {
        None
    };
    // (the other cloth albedo tables too: albedo::by_column; and dielectric-albedo-avg, whose
    // column is one roughness with every eta)
    let albedo_columns = dense.is_none() && albedo::by_column(spec);
    // (a column shares rules among its η ≥ 1 texels; where every texel is η < 1, each is
    // integrated alone anyway, so the table goes texel by texel: its 16 columns of
    // `cycles-glass-inv-eavg` differ 3× in cost and left a thread idle at the end)
    let average_columns = spec.kind == TableKind::DielectricAlbedoAvg
        && (0..spec.axes[1].size).any(|z| dielectric::eta_of_slice(spec, z) >= 1.0);
    let by_column =
        (spec.kind == TableKind::Dfg && dense.is_none()) || albedo_columns || average_columns;
    // tables with a fibre path go one fibre (all slices of one (i, j)) per task: block
    // i + j·nx holds the fibre's texels in slice order
    let fibre = if by_column || dense.is_some() {
        None
    } else {
        energy::fibre_fn(spec)
    };
    // and the slices that go by roughness fibres instead
    let rough = fibre.as_ref().and_then(|_| energy::roughness_fibres(spec));
    let blocks: Vec<Vec<TexelResult>> = if dense.is_some() {
        Vec::new()
    } else if let Some(fibre) = &fibre {
        vec![by_fibres(fibre, rough.as_ref(), dims, &out_of_time)]
    } else if by_column {
        let column = if albedo_columns {
            albedo::column_fn(spec)
        } else if average_columns {
            dielectric_average::column_fn(spec)
        } else {
            dfg::column_fn(spec)
        };
        (0..dims[0])
            .into_par_iter()
            .with_min_len(1)
            .map(|i| {
                if out_of_time() {
                    return Vec::new();
                }
                with_budget(INTEGRAL_EVAL_BUDGET.saturating_mul(dims[1] as u64), || {
                    column(i)
                })
            })
            .collect()
    } else {
        let per_row: Box<dyn Fn([usize; 3]) -> TexelResult + Sync> = match spec.kind {
            TableKind::Ndf | TableKind::G1 | TableKind::G2 | TableKind::Vgroove => {
                local::texel_fn(spec)
            }
            TableKind::Albedo | TableKind::AlbedoAvg => albedo::texel_fn(spec),
            TableKind::Dfg => unreachable!("dfg tables are baked per column above"),
            TableKind::KullaConty | TableKind::AlbedoFresnel | TableKind::DielectricBtdf => {
                energy::texel_fn(spec)
            }
            TableKind::DielectricAlbedo => dielectric::texel_fn(spec),
            TableKind::DielectricAlbedoAvg => dielectric_average::texel_fn(spec),
            TableKind::DielectricSchlick => dielectric_schlick::texel_fn(spec),
            TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => {
                schlick_weight::texel_fn(spec)
            }
            TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => classic::texel_fn(spec),
            TableKind::Ltc | TableKind::LtcSphere => unreachable!("baked by bake_ltc above"),
        };
        vec![(0..n)
            .into_par_iter()
            .with_min_len(1)
            .map(|i| {
                if out_of_time() {
                    return TexelResult::exact(Vec::new());
                }
                let idx = [
                    i % dims[0],
                    (i / dims[0]) % dims[1],
                    i / (dims[0] * dims[1]),
                ];
                with_budget(INTEGRAL_EVAL_BUDGET, || per_row(idx))
            })
            .collect()]
    };
    if stopped.into_inner() {
        return Err(BakeError::TimeLimit {
            name: spec.name.clone(),
            seconds: deadline.map_or(0.0, |d| d.seconds),
            texels: n,
        });
    }
    // texel i (axis 0 fastest)
    let nc = channels.len();
    // the error for channel c of texel i, whose value is not finite in f64 or f32
    let texel_of = |i: usize| {
        [
            i % dims[0],
            (i / dims[0]) % dims[1],
            i / (dims[0] * dims[1]),
        ]
    };
    let coords_of = |texel: [usize; 3]| -> Vec<(String, f64)> {
        spec.axes
            .iter()
            .enumerate()
            .map(|(k, a)| (a.name.clone(), a.coord(texel[k])))
            .collect()
    };
    let non_finite = |i: usize, c: usize, value: f64| BakeError::NonFinite {
        name: spec.name.clone(),
        texel: texel_of(i),
        at: coords_of(texel_of(i)),
        channel: channels[c].name.clone(),
        value,
    };
    let missed = |m: Misses| -> Result<(), BakeError> {
        if m.count == 0 {
            return Ok(());
        }
        let mut m = m;
        m.trim();
        let worst = m
            .worst
            .iter()
            .map(|&(estimate, i, c)| Miss {
                texel: texel_of(i),
                at: coords_of(texel_of(i)),
                channel: channels[c].name.clone(),
                estimate,
            })
            .collect();
        Err(BakeError::ToleranceMissed {
            name: spec.name.clone(),
            limit,
            tolerance: spec.tolerance,
            count: m.count,
            texels: n,
            worst,
        })
    };
    if let Some(d) = dense {
        if let Some((i, c, value)) = d.non_finite {
            return Err(non_finite(i, c, value));
        }
        missed(d.misses)?;
        return Ok(Lut {
            axes: spec.axes.clone(),
            channels,
            data: d.data,
            error_estimate: d.max_error,
            evaluations: d.evals,
        });
    }
    // texel i's values, error estimates and evaluations
    let result = |i: usize| -> (&[f64], &[f64], u64) {
        let r = if by_column {
            &blocks[i % dims[0]][i / dims[0]]
        } else {
            &blocks[0][i]
        };
        (&r.value, &r.error, r.evals)
    };
    let mut data = Vec::with_capacity(n * nc);
    let mut err = vec![0.0f64; nc];
    let mut evals = 0;
    let mut misses = Misses::default();
    for i in 0..n {
        let (value, error, texel_evals) = result(i);
        for c in 0..nc {
            let v = value[c];
            if !v.is_finite() || !(v as f32).is_finite() {
                return Err(non_finite(i, c, v));
            }
            data.push(v as f32);
            err[c] = err[c].max(error[c]);
            misses.check(limit, i, c, error[c]);
        }
        evals += texel_evals;
    }
    missed(misses)?;
    Ok(Lut {
        axes: spec.axes.clone(),
        channels,
        data,
        error_estimate: err,
        evaluations: evals,
    })
}

/// The texel results of a table with a fibre path, in texel order (axis 0 fastest): one task
/// per fibre along axis 2 (all slices of one (i, j)), and where the kind has roughness fibres
/// one per fibre along axis 1 (all roughnesses of one (i, z)) for the slices they take, which
/// the axis-2 fibres leave out. Every integral of a fibre shares one bounded budget
/// (budget.rs); a task started after the deadline returns nothing (the caller then fails).
fn by_fibres(
    fibre: &FibreFn,
    rough: Option<&RoughnessFibres>,
    dims: [usize; 3],
    out_of_time: &(dyn Fn() -> bool + Sync),
) -> Vec<TexelResult> {
    #[derive(Clone, Copy)]
    enum Task {
        Slices(usize, usize),
        Roughnesses(usize, usize),
    }
    let [nx, ny, nz] = dims;
    let by_roughness = |z: usize| rough.is_some_and(|r| r.slices[z]);
    let mut tasks = Vec::new();
    if (0..nz).any(|z| !by_roughness(z)) {
        tasks.extend((0..nx * ny).map(|ij| Task::Slices(ij % nx, ij / nx)));
    }
    if let Some(r) = rough {
        for z in (0..nz).filter(|&z| r.slices[z]) {
            tasks.extend((0..nx).map(|i| Task::Roughnesses(i, z)));
        }
    }
    let done: Vec<Vec<TexelResult>> = tasks
        .par_iter()
        .with_min_len(1)
        .map(|&t| {
            if out_of_time() {
                return Vec::new();
            }
            match t {
                Task::Slices(i, j) => {
                    with_budget(INTEGRAL_EVAL_BUDGET.saturating_mul(nz as u64), || {
                        fibre(i, j)
                    })
                }
                Task::Roughnesses(i, z) => {
                    let r = rough.expect("roughness fibres");
                    with_budget(INTEGRAL_EVAL_BUDGET.saturating_mul(ny as u64), || {
                        (r.run)(i, z)
                    })
                }
            }
        })
        .collect();
    let mut out = vec![TexelResult::exact(Vec::new()); nx * ny * nz];
    for (t, results) in tasks.into_iter().zip(done) {
        for (k, r) in results.into_iter().enumerate() {
            match t {
                Task::Slices(i, j) if !by_roughness(k) => out[i + nx * (j + ny * k)] = r,
                Task::Slices(..) => {}
                Task::Roughnesses(i, z) => out[i + nx * (k + ny * z)] = r,
            }
        }
    }
    out
}

/// [`bake_with`], and for an `ltc` table with matrix channels the per-texel fit error
/// ([`ltc::fit_channels`]) as a table of the same axes.
pub fn bake_with_fit(
    spec: &TableSpec,
    opts: &BakeOptions,
) -> Result<(Lut, Option<Lut>), BakeError> {
    if spec.kind.is_ltc() {
        spec.validate().map_err(|msg| BakeError::Invalid {
            name: spec.name.clone(),
            msg,
        })?;
        let (mut lut, fit) = bake_ltc(spec, opts)?;
        clamp_nonnegative(spec, &mut lut);
        return Ok((lut, fit));
    }
    Ok((bake_with(spec, opts)?, None))
}

/// The `ltc` and `ltc-sphere` kinds ([`ltc`]): a validated spec.
fn bake_ltc(spec: &TableSpec, opts: &BakeOptions) -> Result<(Lut, Option<Lut>), BakeError> {
    let limit = opts
        .accept_error_estimate
        .unwrap_or(spec.tolerance)
        .max(spec.tolerance);
    let stop = || opts.deadline.is_some_and(|d| d.passed());
    let b = ltc::bake(spec, &stop, limit);
    let n: usize = spec.axes.iter().map(|a| a.size).product();
    let nx = spec.axes[0].size;
    let texel_of = |t: usize| [t % nx, t / nx, 0];
    let at = |t: usize| -> Vec<(String, f64)> {
        let idx = texel_of(t);
        spec.axes
            .iter()
            .enumerate()
            .map(|(k, a)| (a.name.clone(), a.coord(idx[k])))
            .collect()
    };
    if b.stopped {
        return Err(BakeError::TimeLimit {
            name: spec.name.clone(),
            seconds: opts.deadline.map_or(0.0, |d| d.seconds),
            texels: n,
        });
    }
    if let Some((t, msg)) = b.failed {
        return Err(BakeError::FitFailed {
            name: spec.name.clone(),
            texel: texel_of(t),
            at: at(t),
            msg,
        });
    }
    let channels = channels(spec);
    if let Some((t, c, value)) = b.non_finite {
        return Err(BakeError::NonFinite {
            name: spec.name.clone(),
            texel: texel_of(t),
            at: at(t),
            channel: channels[c].name.clone(),
            value,
        });
    }
    if b.misses.count > 0 {
        let mut m = b.misses;
        m.trim();
        return Err(BakeError::ToleranceMissed {
            name: spec.name.clone(),
            limit,
            tolerance: spec.tolerance,
            count: m.count,
            texels: n,
            worst: m
                .worst
                .iter()
                .map(|&(estimate, t, c)| Miss {
                    texel: texel_of(t),
                    at: at(t),
                    channel: channels[c].name.clone(),
                    estimate,
                })
                .collect(),
        });
    }
    let fit = b.fit.map(|v| Lut {
        axes: spec.axes.clone(),
        channels: ltc::fit_channels(),
        data: v.iter().map(|&x| x as f32).collect(),
        error_estimate: vec![0.0; 4],
        evaluations: 0,
    });
    Ok((
        Lut {
            axes: spec.axes.clone(),
            channels,
            data: b.data,
            error_estimate: b.max_error,
            evaluations: b.evals,
        },
        fit,
    ))
}

/// The values and error estimates of texel `idx` if it lies at α = 0, where the table holds
/// the smooth-surface limit in closed form (`smooth.rs`); `None` for any other texel.
pub fn smooth_limit_at(spec: &TableSpec, idx: [usize; 3]) -> Option<(Vec<f64>, Vec<f64>)> {
    let (k, zero, _) = smooth_texels(spec)?;
    zero.contains(&idx[k]).then(|| {
        let t = smooth::texel(spec, idx);
        (t.value, t.error)
    })
}

/// The roughness texels at α = 0 (the smooth limit, [`smooth`]), if any: the roughness
/// axis' index, the range of those texels and the range of the others (validation has
/// made them one run at an end of the axis).
fn smooth_texels(
    spec: &TableSpec,
) -> Option<(usize, std::ops::Range<usize>, std::ops::Range<usize>)> {
    let k = spec
        .axes
        .iter()
        .position(|a| matches!(a.quantity, crate::lut::Quantity::Roughness(_)))?;
    let a = &spec.axes[k];
    let zero = |i: usize| a.alpha(i) == Some(0.0);
    let n = a.size;
    let head = (0..n).take_while(|&i| zero(i)).count();
    if head > 0 {
        return Some((k, 0..head, head..n));
    }
    let tail = (0..n).rev().take_while(|&i| zero(i)).count();
    (tail > 0).then(|| (k, n - tail..n, 0..n - tail))
}

/// The texels `window` of axis `a` as an axis of their own: the same parameters (up to
/// rounding in the last place), warp and clamp.
fn window_axis(a: &crate::lut::Axis, window: std::ops::Range<usize>) -> crate::lut::Axis {
    use crate::lut::Convention;
    let mut b = a.clone();
    let (s, e) = (window.start, window.end);
    b.size = e - s;
    if b.size == 1 {
        let p = a.parameter(s);
        b.range = [p, p];
        b.convention = Convention::Centers;
        return b;
    }
    b.range = match a.convention {
        Convention::Endpoints => [a.parameter(s), a.parameter(e - 1)],
        Convention::Centers => {
            let [lo, hi] = a.range;
            let n = a.size as f64;
            [lo + (hi - lo) * s as f64 / n, lo + (hi - lo) * e as f64 / n]
        }
    };
    b
}

/// [`bake_with`] of a table whose roughness axis `k` has texels `zero` at α = 0: the others
/// (`rest`) are baked as a table of their own, the α = 0 texels take the smooth limit's
/// closed form ([`smooth::texel`]).
fn bake_with_smooth(
    spec: &TableSpec,
    opts: &BakeOptions,
    k: usize,
    zero: std::ops::Range<usize>,
    rest: std::ops::Range<usize>,
) -> Result<Lut, BakeError> {
    let channels = channels(spec);
    let nc = channels.len();
    let dims = [
        spec.axes.first().map_or(1, |a| a.size),
        spec.axes.get(1).map_or(1, |a| a.size),
        spec.axes.get(2).map_or(1, |a| a.size),
    ];
    let sub = if rest.is_empty() {
        None
    } else {
        let mut s = spec.clone();
        s.axes[k] = window_axis(&spec.axes[k], rest.clone());
        Some(bake_with(&s, opts)?)
    };
    let mut data = Vec::with_capacity(dims.iter().product::<usize>() * nc);
    let mut err = sub
        .as_ref()
        .map_or(vec![0.0; nc], |l| l.error_estimate.clone());
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                let mut idx = [x, y, z];
                if zero.contains(&idx[k]) {
                    let t = smooth::texel(spec, idx);
                    for c in 0..nc {
                        let v = t.value[c];
                        if !v.is_finite() || !(v as f32).is_finite() {
                            return Err(BakeError::NonFinite {
                                name: spec.name.clone(),
                                texel: idx,
                                at: spec
                                    .axes
                                    .iter()
                                    .enumerate()
                                    .map(|(j, a)| (a.name.clone(), a.coord(idx[j])))
                                    .collect(),
                                channel: channels[c].name.clone(),
                                value: v,
                            });
                        }
                        data.push(v as f32);
                        err[c] = err[c].max(t.error[c]);
                    }
                } else {
                    let l = sub.as_ref().expect("texels beside the smooth ones");
                    idx[k] -= rest.start;
                    for c in 0..nc {
                        data.push(l.texel(idx, c));
                    }
                }
            }
        }
    }
    Ok(Lut {
        axes: spec.axes.clone(),
        channels,
        data,
        error_estimate: err,
        evaluations: sub.map_or(0, |l| l.evaluations),
    })
}

fn ch(name: &str, meaning: &str) -> Channel {
    Channel {
        name: name.into(),
        meaning: meaning.into(),
    }
}

/// The cloth channel of a dfg table (`cloth`; its α floored by `cloth_alpha_min` if set).
const SHEEN_MEANING: &str = "int D_Charlie(alpha) V_Ashikhmin (n.l) dw_l: the sheen (cloth) directional albedo, may exceed 1 at grazing angles";

/// The channels of a table, with their meaning.
pub fn channels(spec: &TableSpec) -> Vec<Channel> {
    match spec.kind {
        TableKind::Ndf => vec![ch("D", "D(n.h; alpha), normalized: int D (n.h) dw = 1")],
        TableKind::G1 => vec![ch("G1", "Smith G1(cos theta; alpha) = 1/(1 + Lambda(cos theta))")],
        TableKind::G2 => vec![ch("G2", "G2(cos theta_v, cos theta_l; alpha)")],
        TableKind::Vgroove => vec![
            ch("G", "min(1, 2(n.h)(n.v)/(v.h), 2(n.h)(n.l)/(v.h)) with v.h = (n.l + n.v)/(2 n.h)"),
            ch(
                "realizable",
                "1 where some pair of unit vectors l, v has these three cosines, 0 where the triple is geometrically impossible (G is still the formula's value there)",
            ),
        ],
        TableKind::Albedo => vec![ch("E", "E(mu) = int f(v,l) (n.l) dw_l over the hemisphere")],
        TableKind::AlbedoAvg => vec![ch("E_avg", "E_avg = 2 int_0^1 E(mu) mu dmu")],
        TableKind::Dfg => match spec.dfg_layout {
            Some(l @ (DfgLayout::Karis | DfgLayout::KarisF82)) => {
                let mut v = vec![
                    ch("A", "A = int (1 - Fc) f cos dw_l, Fc = (1 - v.h)^5, f with F = 1; E = F0*A + B"),
                    ch("B", "B = int Fc f cos dw_l"),
                ];
                if l == DfgLayout::KarisF82 {
                    v.push(ch("F82", "F82 = int (v.h)(1 - v.h)^6 f cos dw_l: the F82-tint term; E = F0*A + B - b*F82"));
                }
                if spec.cloth {
                    v.push(ch("sheen", SHEEN_MEANING));
                }
                v
            }
            _ => {
                let mut v = vec![
                    ch("R", "int Fc f cos dw_l, Fc = (1 - v.h)^5, f with F = 1; E = mix(R, G, F0) = (1 - F0) R + F0 G"),
                    ch("G", "int f cos dw_l (F = 1): the single-scattering albedo; multiscatter compensation 1 + F0 (1/G - 1)"),
                ];
                if spec.cloth {
                    v.push(ch("B", SHEEN_MEANING));
                }
                v
            }
        },
        TableKind::KullaConty | TableKind::AlbedoFresnel | TableKind::DielectricBtdf => {
            energy::channels(spec)
        }
        TableKind::DielectricAlbedo | TableKind::DielectricAlbedoAvg => {
            dielectric::channels(spec)
        }
        TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => schlick_weight::channels(spec),
        TableKind::DielectricSchlick => dielectric_schlick::channels(spec),
        TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => classic::channels(spec),
        TableKind::Ltc | TableKind::LtcSphere => ltc::channels(spec),
    }
}
pub mod ltc_heldout;
pub mod ltc_layout;
