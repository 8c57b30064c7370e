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

use super::shipped::ShippedTable;
use crate::lut::Lut;
use serde::Serialize;

/// Error statistics of one table channel against the exact values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stats {
    /// Largest |value − exact|.
    pub max_abs: f64,
    /// Largest |value − exact| / max(1, |exact|).
    pub max_rel: f64,
    pub mean_abs: f64,
    pub rms: f64,
    /// Mean of value − exact (the bias).
    pub mean_signed: f64,
    /// The texel (stored order) of the largest |error|, its coordinates, value and exact value.
    pub worst_texel: [usize; 3],
    pub worst_at: Vec<(String, f64)>,
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

/// The comparison of one channel.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChannelComparison {
    pub channel: String,
    pub shipped: Stats,
    /// brdfbake's texels as computed (f32), before its storage rounds them.
    pub brdfbake: Stats,
    /// brdfbake's texels as its storage holds them, where that is not f32.
    pub brdfbake_stored: Option<Stats>,
    pub findings: Vec<Finding>,
}

/// How much worse than the median line a line must be to be named, and the floor (in units
/// of the stored step) below which no line is named.
const LINE_FACTOR: f64 = 5.0;
/// A shift is named when it lowers the mean error at least this much.
const SHIFT_FACTOR: f64 = 4.0;

/// Compares every compared channel of `shipped` (in the stored layout of `ours`) with `exact`.
/// `ours` is brdfbake's table as computed (f32), `stored` the same as its storage holds it
/// (f16, UNORM: rounded; scale removed) where that differs, `exact` the reference; all in the
/// stored axis order, with the stored channel names.
pub fn compare(
    shipped: &ShippedTable,
    ours: &Lut,
    stored: Option<&Lut>,
    exact: &Lut,
) -> Vec<ChannelComparison> {
    let nc_file = shipped.channels.len();
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
        let exact_v: Vec<f64> = (0..n)
            .map(|t| exact.data[t * exact.channels.len() + c] as f64)
            .collect();
        let of = |l: &Lut| -> Vec<f64> {
            (0..n)
                .map(|t| l.data[t * l.channels.len() + c] as f64)
                .collect()
        };
        let ours_v = of(ours);
        let s = stats(exact, &shipped_v, &exact_v);
        let mut findings = Vec::new();
        findings.extend(shifts(exact, &shipped_v, &exact_v, s.mean_abs));
        findings.extend(lines(exact, &shipped_v, &exact_v, shipped.step));
        findings.extend(saturation(&shipped_v, &exact_v, shipped.step));
        findings.push(noise(exact, &shipped_v, &exact_v));
        out.push(ChannelComparison {
            channel: name.clone(),
            shipped: s,
            brdfbake: stats(exact, &ours_v, &exact_v),
            brdfbake_stored: stored.map(|l| stats(exact, &of(l), &exact_v)),
            findings,
        });
    }
    out
}

fn texel_of(l: &Lut, t: usize) -> [usize; 3] {
    let (nx, ny) = (l.dim(0), l.dim(1));
    [t % nx, (t / nx) % ny, t / (nx * ny)]
}

fn coords_of(l: &Lut, idx: [usize; 3]) -> Vec<(String, f64)> {
    let x = crate::lut::texel_coordinates(&l.axes, &idx[..l.axes.len()]);
    l.axes.iter().map(|a| a.name.clone()).zip(x).collect()
}

fn stats(l: &Lut, v: &[f64], exact: &[f64]) -> Stats {
    let n = v.len().max(1) as f64;
    let (mut max_abs, mut max_rel, mut sum, mut sum2, mut signed) = (0.0f64, 0.0f64, 0.0, 0.0, 0.0);
    let mut worst = 0;
    for (t, (a, e)) in v.iter().zip(exact).enumerate() {
        let d = a - e;
        if d.abs() > max_abs {
            max_abs = d.abs();
            worst = t;
        }
        max_rel = max_rel.max(d.abs() / e.abs().max(1.0));
        sum += d.abs();
        sum2 += d * d;
        signed += d;
    }
    let idx = texel_of(l, worst);
    Stats {
        max_abs,
        max_rel,
        mean_abs: sum / n,
        rms: (sum2 / n).sqrt(),
        mean_signed: signed / n,
        worst_texel: idx,
        worst_at: coords_of(l, idx),
        worst_value: v.get(worst).copied().unwrap_or(0.0),
        worst_exact: exact.get(worst).copied().unwrap_or(0.0),
    }
}

/// Moves the exact grid by ±1 texel along each axis of at least 3 texels.
fn shifts(l: &Lut, v: &[f64], exact: &[f64], mean_abs: f64) -> Vec<Finding> {
    let mut out = Vec::new();
    for (k, a) in l.axes.iter().enumerate() {
        if a.size < 3 {
            continue;
        }
        let mut best: Option<(i64, f64)> = None;
        for by in [-1i64, 1] {
            let (mut sum, mut n) = (0.0, 0usize);
            for (t, vt) in v.iter().enumerate() {
                let mut idx = texel_of(l, t);
                let j = idx[k] as i64 + by;
                if j < 0 || j >= a.size as i64 {
                    continue;
                }
                idx[k] = j as usize;
                let u = (idx[2] * l.dim(1) + idx[1]) * l.dim(0) + idx[0];
                sum += (vt - exact[u]).abs();
                n += 1;
            }
            let m = sum / n.max(1) as f64;
            if best.is_none_or(|(_, b)| m < b) {
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
fn lines(l: &Lut, v: &[f64], exact: &[f64], step: f64) -> Vec<Finding> {
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
        for t in 0..v.len() {
            let i = texel_of(l, t)[k];
            let d = (v[t] - exact[t]).abs();
            sum[i] += d;
            max[i] = max[i].max(d);
            cnt[i] += 1;
        }
        let means: Vec<f64> = sum
            .iter()
            .zip(&cnt)
            .map(|(s, &c)| s / c.max(1) as f64)
            .collect();
        let mut sorted = means.clone();
        sorted.sort_by(|a, b| a.total_cmp(b));
        let median = sorted[sorted.len() / 2];
        for (i, &m) in means.iter().enumerate() {
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

fn saturation(v: &[f64], exact: &[f64], step: f64) -> Vec<Finding> {
    let min_difference = (2.0 * step).max(1e-6);
    [0.0, 1.0]
        .into_iter()
        .filter_map(|s| {
            let count = v
                .iter()
                .zip(exact)
                .filter(|(a, e)| **a == s && (*a - *e).abs() > min_difference)
                .count();
            (count > 0).then_some(Finding::Saturated {
                value: s,
                count,
                min_difference,
            })
        })
        .collect()
}

fn noise(l: &Lut, v: &[f64], exact: &[f64]) -> Finding {
    let nx = l.dim(0);
    let (mut sum2, mut n) = (0.0, 0usize);
    for t in 0..v.len() {
        let x = t % nx;
        if x == 0 || x + 1 >= nx {
            continue;
        }
        let e = |u: usize| v[u] - exact[u];
        let d2 = e(t - 1) - 2.0 * e(t) + e(t + 1);
        sum2 += d2 * d2;
        n += 1;
    }
    let bias = v.iter().zip(exact).map(|(a, e)| a - e).sum::<f64>() / v.len().max(1) as f64;
    Finding::Noise {
        sigma: if n > 0 {
            (sum2 / n as f64 / 6.0).sqrt()
        } else {
            0.0
        },
        bias,
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
        ShippedTable {
            channels: vec!["E".into()],
            values,
            step: 0.0,
        }
    }

    fn exact_fn(x: usize, y: usize) -> f64 {
        ((x * x) as f64 * 0.01 + y as f64 * 0.1).sin()
    }

    #[test]
    fn a_shifted_grid_is_found() {
        let exact = lut(|x, y| exact_fn(x, y) as f32);
        // the shipped row y holds the exact row y + 1 (the last row repeats)
        let s = shipped(|x, y| exact_fn(x, (y + 1).min(7)));
        let c = &compare(&s, &exact, None, &exact)[0];
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
        let c = &compare(&s, &exact, None, &exact)[0];
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
}
