//! Comparing a shipped table with exact values at its own texels, and brdfbake's table with
//! the same values: per channel the largest and mean errors and where they are, and the
//! findings that say *how* a shipped table departs from its stated model — a grid one texel
//! off along an axis (Filament's `dfg.inc`), one row or column far worse than the rest
//! (EEVEE's α = 0 column, three.js' grazing rows), values saturated at 0 or 1, and how much of
//! the error is texel-to-texel noise (Monte Carlo) and how much a smooth bias.
//!
//! "Exact" is brdfbake's own bake of the preset's table at a tolerance 100× tighter than the
//! preset's (at most 1e-9), stored in f32: its error is far below what any shipped table
//! shows.

use super::shipped::{Degenerate, ShippedTable};
use crate::lut::Lut;
use crate::numfmt::{fig, num};
use serde::Serialize;

/// Error statistics of one table channel against the exact values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stats {
    /// How many texels the statistics cover.
    pub texels: usize,
    /// Largest |value − exact|.
    pub max_abs: f64,
    /// Largest |value − exact| / max(1, |exact|).
    pub max_rel: f64,
    pub mean_abs: f64,
    pub rms: f64,
    /// Mean of value − exact (the bias).
    pub mean_signed: f64,
    /// The texel (stored order, x fastest) of the largest |error|, its coordinates, value
    /// and exact value.
    pub worst_texel: [usize; 3],
    pub worst_at: Vec<(String, f64)>,
    /// The worst texel's coordinates as physical quantities (`r = 1 (α = 1), n·v = 1e-4`).
    pub worst_physical: String,
    pub worst_value: f64,
    pub worst_exact: f64,
}

/// How a shipped table departs from its stated model.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Finding {
    /// Texel i along `axis` holds the exact value of texel i + `by`: the mean error drops
    /// from `mean_abs` to `shifted_mean_abs` when the grid is moved.
    Shifted {
        axis: String,
        by: i64,
        mean_abs: f64,
        shifted_mean_abs: f64,
    },
    /// One line of texels (index `index` along `axis`, coordinate `at`) errs far more than the
    /// others: `mean_abs` against the median line's `median_abs`.
    Line {
        axis: String,
        index: usize,
        at: f64,
        mean_abs: f64,
        median_abs: f64,
        max_abs: f64,
    },
    /// `count` texels hold exactly `value` (0 or 1) where the exact value differs by more
    /// than `min_difference` (clamped estimators).
    Saturated {
        value: f64,
        count: usize,
        min_difference: f64,
    },
    /// The error split into texel-to-texel scatter (σ of white noise giving the observed
    /// second differences along axis 0: rms(Δ²e)/√6) and the mean signed error.
    Noise { sigma: f64, bias: f64 },
}

/// A degenerate slice of the shipped table ([`super::shipped::Degenerate`]) as `compare`
/// reports it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExcludedSlice {
    pub axis: String,
    pub index: usize,
    /// The slice's coordinate as a physical quantity (`η = 1 + 2e-8`).
    pub at: String,
    pub texels: usize,
    pub why: String,
    /// The shipped table's largest |error| in the slice, over the compared channels.
    pub max_abs: f64,
}

/// What is wrong with a shipped channel, beyond its storage's rounding.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Fault {
    /// The texels sit one texel off along `axis`: a half-texel or endpoint/centre mix-up.
    ShiftedGrid { axis: String, by: i64 },
    /// The file holds another quantity than the preset's: the median error is this fraction
    /// of the exact value.
    WrongQuantity { median_relative: f64 },
    /// `count` texels clamped at `value` where the exact value lies beyond.
    Clamped { value: f64, count: usize },
    /// Lines of texels far worse than the rest: index ranges `[first, last]` along `axis`,
    /// `text` naming them physically; `max_abs` the largest error on them.
    Lines {
        axis: String,
        ranges: Vec<[usize; 2]>,
        text: String,
        max_abs: f64,
    },
    /// A systematic offset: the mean signed error over the texels `text` names (all of
    /// them, or a range of lines along `axis`), significant against the texels' scatter.
    Bias {
        axis: Option<String>,
        /// The first and last line of the range along `axis`.
        range: Option<[usize; 2]>,
        text: String,
        mean_signed: f64,
        /// Whether the bias exceeds the storage's rounding (else it shows only on average).
        material: bool,
    },
    /// Texel-to-texel scatter (Monte Carlo noise) larger than the storage's rounding.
    Noise { sigma: f64 },
    /// Texels above their storage's rounding that no pattern above accounts for: how many
    /// are above 4× it, and the worst.
    Outliers {
        count: usize,
        worst_error: f64,
        worst_texel: [usize; 3],
        worst_physical: String,
    },
}

/// The verdict on one shipped channel: its error against what its own storage allows.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verdict {
    /// The file's storage (`6 decimals`, `f16`, `8-bit UNORM`).
    pub storage: String,
    /// The largest rounding the storage allows at the judged texels (half a step).
    pub storage_rounding: f64,
    /// The largest of |error| / allowance over the judged texels (every texel outside the
    /// degenerate slices), the allowance of a texel being its storage's rounding there plus
    /// the exact value's own error (its f32 rounding and the reference's estimate).
    pub ratio: f64,
    /// Where that ratio is largest (x fastest).
    pub ratio_texel: [usize; 3],
    /// `ratio` ≤ 1: the file is its exact values, rounded by its storage.
    pub within_storage: bool,
    /// `within-storage` (ratio ≤ 1); `near-storage` (ratio ≤ 4: a few roundings, nothing a
    /// shader would see); `noise` (above that, but scatter explains it: more samples would
    /// fix it); or `systematic` (a pattern a fix must address: bias, lines, clamping, a
    /// shifted grid, another quantity, outliers).
    pub grade: &'static str,
    pub faults: Vec<Fault>,
    /// The verdict in one line, for people.
    pub text: String,
}

/// The comparison of one channel.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChannelComparison {
    /// The stored channel's name (`R`, `E`).
    pub channel: String,
    /// The channel's name in the engine (`A` of glTF's `lut_ggx.png`, `1-E`): what the
    /// preset calls the file's channel.
    pub name: String,
    /// The shipped table at every compared texel.
    pub shipped: Stats,
    /// The shipped table without its degenerate slices, where the preset names any.
    pub shipped_regular: Option<Stats>,
    /// brdfbake's texels as computed (f32), before its storage rounds them.
    pub brdfbake: Stats,
    /// brdfbake's texels as its storage holds them, where that is not f32.
    pub brdfbake_stored: Option<Stats>,
    pub findings: Vec<Finding>,
    pub verdict: Verdict,
}

/// How much worse than the median line a line must be to be named, and the floor (in units
/// of the stored step) below which no line is named.
const LINE_FACTOR: f64 = 5.0;
/// A shift is named when it lowers the mean error at least this much.
const SHIFT_FACTOR: f64 = 4.0;
/// A median error above this fraction of the exact values: the file holds another quantity.
const WRONG_QUANTITY: f64 = 0.05;

/// What [`compare`] compares.
pub struct Inputs<'a> {
    pub shipped: &'a ShippedTable,
    /// brdfbake's table as computed (f32).
    pub ours: &'a Lut,
    /// The same as its storage holds it (f16, UNORM: rounded; scale removed) where that
    /// differs.
    pub stored: Option<&'a Lut>,
    /// The reference, and its largest error estimate.
    pub exact: &'a Lut,
    pub exact_error: f64,
    /// The preset's degenerate slices of the shipped table.
    pub degenerate: &'a [Degenerate],
    /// The file's channels as the engine names them (else the stored names).
    pub names: &'a [String],
}

/// The degenerate slices as reported, and the mask of the texels outside them (and, for a
/// quotes file, quoted).
pub fn judged_texels(
    exact: &Lut,
    present: Option<&[bool]>,
    degenerate: &[Degenerate],
) -> (Vec<ExcludedSlice>, Vec<bool>) {
    let n = exact.texel_count();
    let mut judged: Vec<bool> = present.map_or_else(|| vec![true; n], |p| p.to_vec());
    let mut out = Vec::new();
    for d in degenerate {
        let Some(k) = exact.axes.iter().position(|a| a.name == d.axis) else {
            continue;
        };
        let mut texels = 0;
        let mut at = String::new();
        for (t, j) in judged.iter_mut().enumerate() {
            let idx = texel_of(exact, t);
            if idx[k] == d.index {
                if present.is_none_or(|p| p[t]) {
                    texels += 1;
                }
                if at.is_empty() {
                    let x = crate::lut::texel_coordinates(&exact.axes, &idx[..exact.axes.len()]);
                    at = exact.axes[k].physical(x[k]);
                }
                *j = false;
            }
        }
        out.push(ExcludedSlice {
            axis: d.axis.clone(),
            index: d.index,
            at,
            texels,
            why: d.why.clone(),
            max_abs: 0.0,
        });
    }
    (out, judged)
}

/// Compares every compared channel of the shipped table (in the stored layout of `ours`)
/// with the exact values, and judges it against its storage. All tables in the stored axis
/// order, with the stored channel names.
pub fn compare(inp: &Inputs) -> Vec<ChannelComparison> {
    let (shipped, exact) = (inp.shipped, inp.exact);
    let nc_file = shipped.channels.len();
    let present = shipped.present.as_deref();
    let (_, judged) = judged_texels(exact, present, inp.degenerate);
    let all: Vec<bool> = present.map_or_else(|| vec![true; exact.texel_count()], |p| p.to_vec());
    let degenerate = !inp.degenerate.is_empty();
    let mut out = Vec::new();
    for (fc, name) in shipped.channels.iter().enumerate() {
        if name == "-" {
            continue;
        }
        let Some(c) = exact.channels.iter().position(|ch| &ch.name == name) else {
            continue;
        };
        let n = exact.texel_count();
        let shipped_v: Vec<f64> = (0..n).map(|t| shipped.values[t * nc_file + fc]).collect();
        let rounding: Vec<f64> = (0..n).map(|t| shipped.rounding[t * nc_file + fc]).collect();
        let exact_v: Vec<f64> = (0..n)
            .map(|t| exact.data[t * exact.channels.len() + c] as f64)
            .collect();
        let of = |l: &Lut| -> Vec<f64> {
            (0..n)
                .map(|t| l.data[t * l.channels.len() + c] as f64)
                .collect()
        };
        let ours_v = of(inp.ours);
        let s = stats(exact, &shipped_v, &exact_v, &all);
        let regular = degenerate.then(|| stats(exact, &shipped_v, &exact_v, &judged));
        let mut findings = Vec::new();
        // (the patterns need the whole grid; a quotes file has a few texels of it)
        let grid = present.is_none();
        let r = regular.as_ref().unwrap_or(&s);
        if grid {
            findings.extend(shifts(exact, &shipped_v, &exact_v, &judged, r.mean_abs));
            findings.extend(lines(exact, &shipped_v, &exact_v, &judged, shipped.step));
        }
        findings.extend(saturation(&shipped_v, &exact_v, &judged, shipped.step));
        if grid {
            findings.push(noise(exact, &shipped_v, &exact_v, &judged));
        }
        let verdict = verdict(
            exact,
            &shipped_v,
            &exact_v,
            &rounding,
            &judged,
            inp.exact_error,
            r,
            &findings,
            &shipped.storage,
        );
        out.push(ChannelComparison {
            channel: name.clone(),
            name: inp.names.get(fc).cloned().unwrap_or_else(|| name.clone()),
            shipped: s,
            shipped_regular: regular,
            brdfbake: stats(exact, &ours_v, &exact_v, &all),
            brdfbake_stored: inp.stored.map(|l| stats(exact, &of(l), &exact_v, &all)),
            findings,
            verdict,
        });
    }
    out
}

/// Half the spacing of f32 numbers at `v`: the exact values are stored in f32.
fn f32_rounding(v: f64) -> f64 {
    let a = v.abs();
    let e = if a > 0.0 {
        a.log2().floor() as i32
    } else {
        -126
    }
    .max(-126);
    2f64.powi(e - 24)
}

/// A ratio to the storage's rounding up to which a table is `near-storage`.
const NEAR_STORAGE: f64 = 4.0;

#[allow(clippy::too_many_arguments)]
fn verdict(
    l: &Lut,
    v: &[f64],
    exact: &[f64],
    rounding: &[f64],
    judged: &[bool],
    exact_error: f64,
    s: &Stats,
    findings: &[Finding],
    storage: &str,
) -> Verdict {
    let (mut ratio, mut at, mut storage_rounding) = (0.0f64, 0, 0.0f64);
    let mut rel = Vec::new();
    let allow = |t: usize| rounding[t] + f32_rounding(exact[t]) + exact_error;
    for t in (0..v.len()).filter(|t| judged[*t]) {
        let e = (v[t] - exact[t]).abs();
        storage_rounding = storage_rounding.max(rounding[t]);
        if e / allow(t) > ratio {
            ratio = e / allow(t);
            at = t;
        }
        rel.push(e / exact[t].abs().max(1e-3));
    }
    rel.sort_by(|a, b| a.total_cmp(b));
    let median_relative = rel.get(rel.len() / 2).copied().unwrap_or(0.0);
    let within = ratio <= 1.0;
    let mut faults = Vec::new();
    let sigma = findings.iter().find_map(|f| match f {
        Finding::Noise { sigma, .. } => Some(*sigma),
        _ => None,
    });
    if !within {
        for f in findings {
            if let Finding::Shifted { axis, by, .. } = f {
                faults.push(Fault::ShiftedGrid {
                    axis: axis.clone(),
                    by: *by,
                });
            }
        }
        if median_relative > WRONG_QUANTITY {
            faults.push(Fault::WrongQuantity { median_relative });
        }
        for f in findings {
            if let Finding::Saturated { value, count, .. } = f {
                faults.push(Fault::Clamped {
                    value: *value,
                    count: *count,
                });
            }
        }
        faults.extend(line_faults(l, findings));
        faults.extend(bias(l, v, exact, judged, storage_rounding));
        if let Some(sigma) = sigma.filter(|sg| *sg > storage_rounding) {
            faults.push(Fault::Noise { sigma });
        }
        let only_noise = faults.iter().all(|f| matches!(f, Fault::Noise { .. }));
        let explained_by_noise = noise_explains(s, sigma, storage_rounding);
        if only_noise && !explained_by_noise {
            // texels far above the rest that no pattern names
            let far: Vec<usize> = (0..v.len())
                .filter(|t| judged[*t] && (v[*t] - exact[*t]).abs() > NEAR_STORAGE * allow(*t))
                .collect();
            if !far.is_empty() {
                faults.push(Fault::Outliers {
                    count: far.len(),
                    worst_error: s.worst_value - s.worst_exact,
                    worst_texel: s.worst_texel,
                    worst_physical: s.worst_physical.clone(),
                });
            }
        }
    }
    let only_noise = faults.iter().all(|f| matches!(f, Fault::Noise { .. }));
    let grade = if within {
        "within-storage"
    } else if ratio <= NEAR_STORAGE {
        "near-storage"
    } else if only_noise && noise_explains(s, sigma, storage_rounding) {
        "noise"
    } else {
        "systematic"
    };
    let mut text = if within {
        format!(
            "within its storage rounding ({storage}: ±{} at most)",
            num(storage_rounding)
        )
    } else {
        format!(
            "{}× its storage rounding ({storage}: ±{} at most)",
            fig(ratio),
            num(storage_rounding)
        )
    };
    if !faults.is_empty() {
        let parts: Vec<String> = faults.iter().map(|f| f.describe()).collect();
        text.push_str(": ");
        text.push_str(&parts.join("; "));
    }
    Verdict {
        storage: storage.to_string(),
        storage_rounding,
        ratio,
        ratio_texel: texel_of(l, at),
        within_storage: within,
        grade,
        faults,
        text,
    }
}

/// Whether scatter of σ `sigma` explains the largest error: within the extreme of that many
/// Gaussian draws (√(2 ln N) σ, plus one σ) above the storage's rounding.
fn noise_explains(s: &Stats, sigma: Option<f64>, rounding: f64) -> bool {
    sigma.is_some_and(|sg| {
        let n = s.texels.max(2) as f64;
        s.max_abs <= rounding + ((2.0 * n.ln()).sqrt() + 1.0) * sg
    })
}

/// A significant and material mean signed error: over all judged texels, else over the
/// longest run of lines along one axis whose mean signed errors share a sign and are each
/// significant. Significant: more than 5 standard errors of the mean (the texels' own
/// scatter about it over √count); material: more than a tenth of the storage's rounding and
/// a quarter of the mean |error| there.
fn bias(l: &Lut, v: &[f64], exact: &[f64], judged: &[bool], rounding: f64) -> Option<Fault> {
    // mean signed, mean |e| and standard error of a set of texels
    let moments = |ts: &mut dyn Iterator<Item = usize>| -> (f64, f64, f64, usize) {
        let (mut s1, mut s2, mut sa, mut n) = (0.0, 0.0, 0.0, 0usize);
        for t in ts {
            let d = v[t] - exact[t];
            s1 += d;
            s2 += d * d;
            sa += d.abs();
            n += 1;
        }
        let m = n.max(1) as f64;
        let mean = s1 / m;
        let var = (s2 / m - mean * mean).max(0.0);
        (mean, sa / m, (var / m).sqrt(), n)
    };
    let material = |mean: f64, mean_abs: f64, se: f64| {
        mean.abs() > 5.0 * se && mean.abs() > 0.1 * rounding && mean.abs() >= 0.25 * mean_abs
    };
    let (mean, mean_abs, se, _) = moments(&mut (0..v.len()).filter(|t| judged[*t]));
    if material(mean, mean_abs, se) {
        return Some(Fault::Bias {
            axis: None,
            range: None,
            text: "every texel".into(),
            mean_signed: mean,
            material: mean.abs() > rounding,
        });
    }
    let mut best: Option<(usize, usize, usize, f64)> = None; // (axis, first, last, mean)
    for (k, a) in l.axes.iter().enumerate() {
        if a.size < 4 {
            continue;
        }
        let line: Vec<Option<f64>> = (0..a.size)
            .map(|i| {
                let (m, ma, se, n) =
                    moments(&mut (0..v.len()).filter(|t| judged[*t] && texel_of(l, *t)[k] == i));
                (n > 1 && material(m, ma, se)).then_some(m)
            })
            .collect();
        let mut i = 0;
        while i < a.size {
            let Some(m0) = line[i] else {
                i += 1;
                continue;
            };
            let mut j = i;
            while j + 1 < a.size && line[j + 1].is_some_and(|m| m.signum() == m0.signum()) {
                j += 1;
            }
            // a run of at least a tenth of the axis (and 2 lines): a region, not a line
            if j + 1 - i >= (a.size / 10).max(2) && best.is_none_or(|b| j - i > b.2 - b.1) {
                let (m, _, _, _) = moments(
                    &mut (0..v.len())
                        .filter(|t| judged[*t] && (i..=j).contains(&texel_of(l, *t)[k])),
                );
                best = Some((k, i, j, m));
            }
            i = j + 1;
        }
    }
    best.map(|(k, i, j, m)| {
        let a = &l.axes[k];
        Fault::Bias {
            axis: Some(a.name.clone()),
            range: Some([i, j]),
            text: a.physical_range(a.coord(i), a.coord(j)),
            mean_signed: m,
            material: m.abs() > rounding,
        }
    })
}

/// The line findings of each axis grouped into ranges of consecutive lines.
fn line_faults(l: &Lut, findings: &[Finding]) -> Vec<Fault> {
    let mut out = Vec::new();
    for a in &l.axes {
        let mut idx: Vec<(usize, f64)> = findings
            .iter()
            .filter_map(|f| match f {
                Finding::Line {
                    axis,
                    index,
                    max_abs,
                    ..
                } if axis == &a.name => Some((*index, *max_abs)),
                _ => None,
            })
            .collect();
        if idx.is_empty() {
            continue;
        }
        idx.sort_by_key(|x| x.0);
        let mut ranges: Vec<[usize; 2]> = Vec::new();
        for (i, _) in &idx {
            match ranges.last_mut() {
                Some(r) if r[1] + 1 == *i => r[1] = *i,
                _ => ranges.push([*i, *i]),
            }
        }
        let max_abs = idx.iter().fold(0.0f64, |m, x| m.max(x.1));
        let shown: Vec<String> = ranges
            .iter()
            .take(3)
            .map(|r| {
                if r[0] == r[1] {
                    format!("{} (texel {})", a.physical(a.coord(r[0])), r[0])
                } else {
                    format!(
                        "{} (texels {}-{})",
                        a.physical_range(a.coord(r[0]), a.coord(r[1])),
                        r[0],
                        r[1]
                    )
                }
            })
            .collect();
        let mut text = shown.join(", ");
        if ranges.len() > 3 {
            text.push_str(&format!(" and {} more ranges", ranges.len() - 3));
        }
        out.push(Fault::Lines {
            axis: a.name.clone(),
            ranges,
            text,
            max_abs,
        });
    }
    out
}

impl Fault {
    /// The fault for people.
    pub fn describe(&self) -> String {
        match self {
            Fault::ShiftedGrid { axis, by } => format!(
                "its grid is one texel off along {axis} (texel i holds the value of texel i{}): a half-texel or endpoints/centres mix-up",
                if *by > 0 { "+1" } else { "-1" }
            ),
            Fault::WrongQuantity { median_relative } => format!(
                "it holds another quantity (the median error is {}% of the exact value)",
                fig(100.0 * median_relative)
            ),
            Fault::Clamped { value, count } => format!(
                "{count} texel(s) clamped at {} where the exact value lies beyond",
                num(*value)
            ),
            Fault::Lines { text, max_abs, .. } => {
                format!("worst at {text}, up to {} there", fig(*max_abs))
            }
            Fault::Bias {
                text,
                mean_signed,
                material,
                ..
            } => format!(
                "biased {} by {} on average over {text} ({})",
                if *mean_signed < 0.0 { "low" } else { "high" },
                fig(mean_signed.abs()),
                if *material {
                    "a different estimator or model"
                } else {
                    "below its rounding, but systematic"
                }
            ),
            Fault::Noise { sigma } => {
                format!("Monte Carlo noise, sigma {} texel to texel", fig(*sigma))
            }
            Fault::Outliers {
                count,
                worst_error,
                worst_physical,
                ..
            } => format!(
                "{count} texel(s) above 4× that, the worst {} {} at {worst_physical}",
                fig(worst_error.abs()),
                if *worst_error < 0.0 { "low" } else { "high" }
            ),
        }
    }
}

fn texel_of(l: &Lut, t: usize) -> [usize; 3] {
    let (nx, ny) = (l.dim(0), l.dim(1));
    [t % nx, (t / nx) % ny, t / (nx * ny)]
}

fn coords_of(l: &Lut, idx: [usize; 3]) -> Vec<(String, f64)> {
    let x = crate::lut::texel_coordinates(&l.axes, &idx[..l.axes.len()]);
    l.axes.iter().map(|a| a.name.clone()).zip(x).collect()
}

fn stats(l: &Lut, v: &[f64], exact: &[f64], judged: &[bool]) -> Stats {
    let (mut max_abs, mut max_rel, mut sum, mut sum2, mut signed) = (0.0f64, 0.0f64, 0.0, 0.0, 0.0);
    let mut worst = None;
    let mut count = 0usize;
    for (t, (a, e)) in v.iter().zip(exact).enumerate() {
        if !judged[t] {
            continue;
        }
        count += 1;
        let d = a - e;
        if worst.is_none() || d.abs() > max_abs {
            max_abs = d.abs();
            worst = Some(t);
        }
        max_rel = max_rel.max(d.abs() / e.abs().max(1.0));
        sum += d.abs();
        sum2 += d * d;
        signed += d;
    }
    let n = count.max(1) as f64;
    let worst = worst.unwrap_or(0);
    let idx = texel_of(l, worst);
    Stats {
        texels: count,
        max_abs,
        max_rel,
        mean_abs: sum / n,
        rms: (sum2 / n).sqrt(),
        mean_signed: signed / n,
        worst_texel: idx,
        worst_at: coords_of(l, idx),
        worst_physical: crate::lut::texel_physical(&l.axes, &idx[..l.axes.len()]),
        worst_value: v.get(worst).copied().unwrap_or(0.0),
        worst_exact: exact.get(worst).copied().unwrap_or(0.0),
    }
}

/// Moves the exact grid by ±1 texel along each axis of at least 3 texels (judged texels only).
fn shifts(l: &Lut, v: &[f64], exact: &[f64], judged: &[bool], mean_abs: f64) -> Vec<Finding> {
    let mut out = Vec::new();
    for (k, a) in l.axes.iter().enumerate() {
        if a.size < 3 {
            continue;
        }
        let mut best: Option<(i64, f64)> = None;
        for by in [-1i64, 1] {
            let (mut sum, mut n) = (0.0, 0usize);
            for (t, vt) in v.iter().enumerate() {
                if !judged[t] {
                    continue;
                }
                let mut idx = texel_of(l, t);
                let j = idx[k] as i64 + by;
                if j < 0 || j >= a.size as i64 {
                    continue;
                }
                idx[k] = j as usize;
                let u = (idx[2] * l.dim(1) + idx[1]) * l.dim(0) + idx[0];
                if !judged[u] {
                    continue;
                }
                sum += (vt - exact[u]).abs();
                n += 1;
            }
            let m = sum / n.max(1) as f64;
            if n > 0 && best.is_none_or(|(_, b)| m < b) {
                best = Some((by, m));
            }
        }
        if let Some((by, m)) = best {
            if m * SHIFT_FACTOR < mean_abs {
                out.push(Finding::Shifted {
                    axis: a.name.clone(),
                    by,
                    mean_abs,
                    shifted_mean_abs: m,
                });
            }
        }
    }
    out
}

/// Lines of texels (fixed index along one axis) whose mean error stands out.
fn lines(l: &Lut, v: &[f64], exact: &[f64], judged: &[bool], step: f64) -> Vec<Finding> {
    let mut out = Vec::new();
    // errors below a few storage steps (or 1e-6 for printed decimals) are not worth naming
    let floor = (4.0 * step).max(1e-6);
    for (k, a) in l.axes.iter().enumerate() {
        if a.size < 4 {
            continue;
        }
        let mut sum = vec![0.0; a.size];
        let mut max = vec![0.0f64; a.size];
        let mut cnt = vec![0usize; a.size];
        for t in (0..v.len()).filter(|t| judged[*t]) {
            let i = texel_of(l, t)[k];
            let d = (v[t] - exact[t]).abs();
            sum[i] += d;
            max[i] = max[i].max(d);
            cnt[i] += 1;
        }
        let means: Vec<Option<f64>> = sum
            .iter()
            .zip(&cnt)
            .map(|(s, &c)| (c > 0).then(|| s / c as f64))
            .collect();
        let mut sorted: Vec<f64> = means.iter().flatten().copied().collect();
        if sorted.is_empty() {
            continue;
        }
        sorted.sort_by(|a, b| a.total_cmp(b));
        let median = sorted[sorted.len() / 2];
        for (i, m) in means.iter().enumerate() {
            let Some(m) = *m else { continue };
            if m > LINE_FACTOR * median && m > floor {
                out.push(Finding::Line {
                    axis: a.name.clone(),
                    index: i,
                    at: a.coord(i),
                    mean_abs: m,
                    median_abs: median,
                    max_abs: max[i],
                });
            }
        }
    }
    out
}

fn saturation(v: &[f64], exact: &[f64], judged: &[bool], step: f64) -> Vec<Finding> {
    let min_difference = (2.0 * step).max(1e-6);
    [0.0, 1.0]
        .into_iter()
        .filter_map(|s| {
            let count = v
                .iter()
                .zip(exact)
                .zip(judged)
                .filter(|((a, e), j)| **j && **a == s && (*a - *e).abs() > min_difference)
                .count();
            (count > 0).then_some(Finding::Saturated {
                value: s,
                count,
                min_difference,
            })
        })
        .collect()
}

fn noise(l: &Lut, v: &[f64], exact: &[f64], judged: &[bool]) -> Finding {
    let nx = l.dim(0);
    let (mut sum2, mut n) = (0.0, 0usize);
    for t in 0..v.len() {
        let x = t % nx;
        if x == 0 || x + 1 >= nx || !(judged[t - 1] && judged[t] && judged[t + 1]) {
            continue;
        }
        let e = |u: usize| v[u] - exact[u];
        let d2 = e(t - 1) - 2.0 * e(t) + e(t + 1);
        sum2 += d2 * d2;
        n += 1;
    }
    let (mut bias, mut m) = (0.0, 0usize);
    for t in (0..v.len()).filter(|t| judged[*t]) {
        bias += v[t] - exact[t];
        m += 1;
    }
    Finding::Noise {
        sigma: if n > 0 {
            (sum2 / n as f64 / 6.0).sqrt()
        } else {
            0.0
        },
        bias: bias / m.max(1) as f64,
    }
}

impl Finding {
    /// One line of text for people.
    pub fn describe(&self) -> String {
        use crate::numfmt::num;
        match self {
            Finding::Shifted {
                axis,
                by,
                mean_abs,
                shifted_mean_abs,
            } => format!(
                "the grid is one texel off along {axis}: texel i holds the exact value of texel i{} (mean error {} against the stated grid, {} shifted)",
                if *by > 0 { "+1" } else { "-1" },
                num(*mean_abs),
                num(*shifted_mean_abs)
            ),
            Finding::Line {
                axis,
                index,
                at,
                mean_abs,
                median_abs,
                max_abs,
            } => format!(
                "{axis} = {} (texel {index}) errs more than the rest: mean {}, {:.0}x the median line's {}, max {}",
                num(*at),
                num(*mean_abs),
                mean_abs / median_abs.max(f64::MIN_POSITIVE),
                num(*median_abs),
                num(*max_abs)
            ),
            Finding::Saturated {
                value,
                count,
                min_difference,
            } => format!(
                "{count} texel(s) hold exactly {} where the exact value differs by more than {} (a clamped estimate)",
                num(*value),
                num(*min_difference)
            ),
            Finding::Noise { sigma, bias } => format!(
                "texel-to-texel scatter sigma {} (white noise of that size gives the observed second differences along the first axis), mean signed error {}",
                num(*sigma),
                num(*bias)
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::{Axis, Channel, Convention, Quantity};

    fn lut(f: impl Fn(usize, usize) -> f32) -> Lut {
        let ax = |n: &str| Axis::new(n, Quantity::Cosine, 8, [0.0, 1.0], Convention::Centers);
        let mut data = Vec::new();
        for y in 0..8 {
            for x in 0..8 {
                data.push(f(x, y));
            }
        }
        Lut {
            axes: vec![ax("u"), ax("v")],
            channels: vec![Channel {
                name: "E".into(),
                meaning: String::new(),
            }],
            data,
            error_estimate: vec![0.0],
            evaluations: 0,
        }
    }

    fn shipped(f: impl Fn(usize, usize) -> f64) -> ShippedTable {
        let mut values = Vec::new();
        for y in 0..8 {
            for x in 0..8 {
                values.push(f(x, y));
            }
        }
        let n = values.len();
        ShippedTable {
            channels: vec!["E".into()],
            values,
            step: 0.0,
            // (6 printed decimals)
            rounding: vec![5e-7; n],
            storage: "6 decimals".into(),
            present: None,
        }
    }

    fn cmp(s: &ShippedTable, exact: &Lut) -> Vec<ChannelComparison> {
        compare(&Inputs {
            shipped: s,
            ours: exact,
            stored: None,
            exact,
            exact_error: 0.0,
            degenerate: &[],
            names: &[],
        })
    }

    fn exact_fn(x: usize, y: usize) -> f64 {
        ((x * x) as f64 * 0.01 + y as f64 * 0.1).sin()
    }

    #[test]
    fn a_shifted_grid_is_found() {
        let exact = lut(|x, y| exact_fn(x, y) as f32);
        // the shipped row y holds the exact row y + 1 (the last row repeats)
        let s = shipped(|x, y| exact_fn(x, (y + 1).min(7)));
        let c = &cmp(&s, &exact)[0];
        assert!(
            c.findings
                .iter()
                .any(|f| matches!(f, Finding::Shifted { axis, by: 1, .. } if axis == "v")),
            "{:?}",
            c.findings
        );
        assert!(c.brdfbake.max_abs == 0.0);
    }

    #[test]
    fn a_bad_column_and_saturation_are_found() {
        let exact = lut(|x, y| (0.5 + 0.01 * (x + y) as f64) as f32);
        let s = shipped(|x, y| {
            let e = 0.5 + 0.01 * (x + y) as f64;
            let noise = if (x * 7 + y * 3) % 2 == 0 {
                1e-5
            } else {
                -1e-5
            };
            if x == 0 {
                e + 3e-3
            } else if x == 7 && y == 7 {
                1.0
            } else {
                e + noise
            }
        });
        let c = &cmp(&s, &exact)[0];
        assert!(
            c.findings
                .iter()
                .any(|f| matches!(f, Finding::Line { axis, index: 0, .. } if axis == "u")),
            "{:?}",
            c.findings
        );
        assert!(
            c.findings
                .iter()
                .any(|f| matches!(f, Finding::Saturated { count: 1, .. })),
            "{:?}",
            c.findings
        );
        assert_eq!(c.shipped.worst_texel, [7, 7, 0]);
    }

    /// A deterministic pseudo-random value in [-0.5, 0.5) per texel.
    fn jitter(x: usize, y: usize) -> f64 {
        let h = ((x * 7919 + y * 104729) as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }

    /// The exact values printed with 6 decimals are within their storage; the same plus
    /// scatter of 20 roundings is noise; plus an offset of 10 roundings is biased; and a
    /// shifted copy is a shifted grid. Each verdict names what it found.
    #[test]
    fn verdicts_relate_errors_to_the_storage() {
        let exact = lut(|x, y| exact_fn(x, y) as f32);
        let printed = |x, y| (exact_fn(x, y) * 1e6).round() / 1e6;
        let c = &cmp(&shipped(printed), &exact)[0];
        assert!(c.verdict.within_storage, "{:?}", c.verdict);
        assert_eq!(c.verdict.grade, "within-storage");
        assert!(c.verdict.ratio <= 1.0 && c.verdict.faults.is_empty());

        let noisy = |x, y| printed(x, y) + 2e-5 * jitter(x, y);
        let c = &cmp(&shipped(noisy), &exact)[0];
        assert!(!c.verdict.within_storage);
        assert_eq!(c.verdict.grade, "noise", "{}", c.verdict.text);
        assert!(
            c.verdict.text.contains("Monte Carlo noise"),
            "{}",
            c.verdict.text
        );

        let biased = |x, y| printed(x, y) + 5e-6 + 1e-6 * jitter(x, y);
        let c = &cmp(&shipped(biased), &exact)[0];
        assert_eq!(c.verdict.grade, "systematic", "{}", c.verdict.text);
        assert!(
            c.verdict
                .faults
                .iter()
                .any(|f| matches!(f, Fault::Bias { mean_signed, .. } if *mean_signed > 0.0)),
            "{:?}",
            c.verdict.faults
        );
        assert!(c.verdict.text.contains("biased high"), "{}", c.verdict.text);

        let s = shipped(|x, y| exact_fn(x, (y + 1).min(7)));
        let c = &cmp(&s, &exact)[0];
        assert!(
            c.verdict.text.contains("one texel off along v"),
            "{}",
            c.verdict.text
        );
    }

    /// A degenerate slice is left out of the verdict and the regular statistics, and kept in
    /// the statistics of every texel; a quotes table is judged at its quoted texels only.
    #[test]
    fn degenerate_slices_and_quotes() {
        let exact = lut(|x, y| exact_fn(x, y) as f32);
        let s = shipped(|x, y| if y == 0 { 1.0 } else { exact_fn(x, y) });
        let deg = [Degenerate {
            axis: "v".into(),
            index: 0,
            why: "a test".into(),
        }];
        let c = &compare(&Inputs {
            shipped: &s,
            ours: &exact,
            stored: None,
            exact: &exact,
            exact_error: 0.0,
            degenerate: &deg,
            names: &[],
        })[0];
        assert!(c.shipped.max_abs > 0.5);
        let r = c.shipped_regular.as_ref().expect("regular statistics");
        assert!(r.max_abs < 1e-6 && r.texels == 56, "{r:?}");
        assert!(c.verdict.within_storage, "{}", c.verdict.text);
        let (ex, _) = judged_texels(&exact, None, &deg);
        assert_eq!(ex[0].texels, 8);
        assert_eq!(ex[0].at, "v = 0.0625");

        let mut q = shipped(|x, y| {
            if (x + y) % 3 == 0 {
                exact_fn(x, y) + 0.25
            } else {
                0.0
            }
        });
        q.present = Some((0..64).map(|t| (t % 8 + t / 8) % 3 == 0).collect());
        let c = &cmp(&q, &exact)[0];
        assert_eq!(c.shipped.texels, 21);
        assert!(
            (c.shipped.max_abs - 0.25).abs() < 1e-6 && (c.shipped.mean_signed - 0.25).abs() < 1e-6
        );
    }
}
