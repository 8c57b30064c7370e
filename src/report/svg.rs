//! Inline SVG charts: line plots with round-numbered ticks and a legend, the colour map, and
//! the number formats the charts print. Heatmaps are in [`super::heatmap`]; where text goes,
//! in [`super::layout`].

use super::layout::{text_width, wrap, Anchor, Canvas, Label, FONT, LINE};
use std::fmt::Write;

pub use super::layout::esc;

/// A line of a plot.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub colour: String,
    pub dashed: bool,
}

/// Viridis, sampled at 9 points; linear interpolation between them.
const VIRIDIS: [[f64; 3]; 9] = [
    [68.0, 1.0, 84.0],
    [71.0, 44.0, 122.0],
    [59.0, 81.0, 139.0],
    [44.0, 113.0, 142.0],
    [33.0, 144.0, 141.0],
    [39.0, 173.0, 129.0],
    [92.0, 200.0, 99.0],
    [170.0, 220.0, 50.0],
    [253.0, 231.0, 37.0],
];

/// The colour of `t` in [0, 1] (a non-finite `t` gets the lowest colour), 8-bit RGB.
pub fn colour_rgb(t: f64) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * 8.0;
    let i = (x.floor() as usize).min(7);
    let f = x - i as f64;
    let mut c = [0u8; 3];
    for (k, v) in c.iter_mut().enumerate() {
        *v = (VIRIDIS[i][k] * (1.0 - f) + VIRIDIS[i + 1][k] * f).round() as u8;
    }
    c
}

/// A coordinate for a label: at most 4 decimals, or 3 significant digits in scientific
/// notation when tiny or huge.
pub fn fmt_num(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-3 {
        format!("{v:.2e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

/// Ticks of an axis: its drawn range (the data's, widened to whole steps) and labelled
/// values.
pub struct Ticks {
    pub lo: f64,
    pub hi: f64,
    pub at: Vec<(f64, String)>,
}

/// A round step (1, 2 or 5 × 10^k) of at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * mag)
}

/// The label of tick `v` of an axis whose ticks are `step` apart: as many decimals as the
/// step needs, scientific when the step is below 1e-4 or the value 1e5 and above.
fn tick_label(v: f64, step: f64) -> String {
    if v.abs() < step * 1e-6 {
        return "0".into();
    }
    let es = step.log10().floor() as i32;
    if v.abs() < 1e5 && es >= -4 {
        let d = (-es).max(0) as usize;
        format!("{v:.d$}")
    } else {
        let ev = v.abs().log10().floor() as i32;
        let d = (ev - es).max(0) as usize;
        format!("{v:.d$e}")
    }
}

/// Linear ticks over [lo, hi] at a round step giving at most `intervals` intervals; the
/// range widens to whole steps.
pub fn linear_ticks(lo: f64, hi: f64, intervals: usize) -> Ticks {
    let step = nice_step((hi - lo) / intervals.max(1) as f64);
    let k0 = (lo / step + 1e-9).floor() as i64;
    let k1 = (hi / step - 1e-9).ceil() as i64;
    let at = (k0..=k1)
        .map(|k| {
            let v = k as f64 * step;
            (v, tick_label(v, step))
        })
        .collect();
    Ticks {
        lo: k0 as f64 * step,
        hi: k1 as f64 * step,
        at,
    }
}

/// Ticks of a log axis whose coordinates are log₁₀ values: whole decades, labelled 1e{k},
/// at most ~8 labelled.
fn decade_ticks(lo: f64, hi: f64) -> Ticks {
    let (lo, hi) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
    let step = ((hi - lo) / 8.0).ceil().max(1.0) as usize;
    Ticks {
        lo,
        hi,
        at: (lo as i64..=hi as i64)
            .step_by(step)
            .map(|k| (k as f64, format!("1e{k}")))
            .collect(),
    }
}

/// How a plot's coordinates are read.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// As they are.
    Linear,
    /// Both coordinates are log₁₀ of the quantity: decade ticks labelled 10^k, a marker on
    /// every point (a method whose cost does not change is a single spot).
    LogLog,
}

/// Width and height of a plot's frame, px.
const PLOT_W: f64 = 300.0;
const PLOT_H: f64 = 200.0;

/// A line plot with ticks, axis labels and a legend.
pub fn line_plot(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    plot(title, xlabel, ylabel, series, Scale::Linear)
}

/// A plot of `series` on `scale`.
pub fn plot(title: &str, xlabel: &str, ylabel: &str, series: &[Series], scale: Scale) -> String {
    let pts = || {
        series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|p| p.0.is_finite() && p.1.is_finite())
    };
    let range = |f: fn((f64, f64)) -> f64| {
        pts()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            })
    };
    let (mut x0, mut x1) = range(|p| p.0);
    let (mut y0, mut y1) = range(|p| p.1);
    if !x0.is_finite() {
        (x0, x1) = (0.0, 1.0);
    }
    if !y0.is_finite() {
        (y0, y1) = (0.0, 1.0);
    }
    if scale == Scale::Linear {
        y0 = y0.min(0.0);
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    if y1 <= y0 {
        y1 = y0 + 1.0;
    }
    let ticks = |lo: f64, hi: f64, n: usize| match scale {
        Scale::Linear => linear_ticks(lo, hi, n),
        Scale::LogLog => decade_ticks(lo, hi),
    };
    let yt = ticks(y0, y1, 6);
    // as many x ticks as their labels leave room for
    let mut xt = ticks(x0, x1, 5);
    for n in (1..5).rev() {
        let widths: f64 = xt
            .at
            .iter()
            .map(|(_, l)| text_width(l, FONT, false) + 8.0)
            .sum();
        if widths <= PLOT_W {
            break;
        }
        xt = ticks(x0, x1, n);
    }
    let yw = yt
        .at
        .iter()
        .map(|(_, l)| text_width(l, FONT, false))
        .fold(0.0, f64::max);
    let ylabel_x = 4.0 + 0.95 * FONT;
    let ml = ylabel_x + 0.25 * FONT + 6.0 + yw + 5.0;
    let lines = wrap(title, ml + PLOT_W + 12.0, FONT, true);
    let mut c = Canvas::new();
    for (i, l) in lines.iter().enumerate() {
        c.label(&Label::new(4.0, 16.0 + LINE * i as f64, Anchor::Start, l.as_str()).bold());
    }
    let mt = 16.0 + LINE * (lines.len() as f64 - 1.0) + 16.0;
    let (pw, ph) = (PLOT_W, PLOT_H);
    let sx = |x: f64| ml + (x - xt.lo) / (xt.hi - xt.lo) * pw;
    let sy = |y: f64| mt + ph - (y - yt.lo) / (yt.hi - yt.lo) * ph;
    c.shape(
        &format!("<rect x=\"{ml:.1}\" y=\"{mt:.1}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#222\"/>"),
        ml + pw,
        mt + ph,
    );
    for (v, l) in &xt.at {
        let x = sx(*v);
        c.shape(
            &format!(
                "<line x1=\"{x:.1}\" y1=\"{mt:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#ddd\"/>",
                mt + ph
            ),
            x,
            mt + ph,
        );
        c.label(&Label::new(x, mt + ph + 18.0, Anchor::Middle, l.as_str()));
    }
    for (v, l) in &yt.at {
        let y = sy(*v);
        c.shape(
            &format!(
                "<line x1=\"{ml:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#ddd\"/>",
                ml + pw
            ),
            ml + pw,
            y,
        );
        c.label(&Label::new(ml - 5.0, y + 4.0, Anchor::End, l.as_str()));
    }
    c.label(&Label::new(
        ml + pw / 2.0,
        mt + ph + 34.0,
        Anchor::Middle,
        xlabel,
    ));
    c.label(&Label::new(ylabel_x, mt + ph / 2.0, Anchor::Middle, ylabel).vertical());
    for (k, se) in series.iter().enumerate() {
        let dash = if se.dashed {
            " stroke-dasharray=\"5 3\""
        } else {
            ""
        };
        let on: Vec<(f64, f64)> = se
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| (sx(x), sy(y)))
            .collect();
        if !on.is_empty() {
            let mut d = String::new();
            for (x, y) in &on {
                let _ = write!(d, "{x:.2},{y:.2} ");
            }
            c.shape(
                &format!(
                    "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.6\"{dash} points=\"{}\"/>",
                    se.colour,
                    d.trim_end()
                ),
                ml + pw,
                mt + ph,
            );
        }
        if scale == Scale::LogLog {
            for (x, y) in &on {
                c.shape(
                    &format!(
                        "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"2.5\" fill=\"{}\"/>",
                        se.colour
                    ),
                    x + 2.5,
                    y + 2.5,
                );
            }
        }
        let ly = mt + ph + 52.0 + LINE * k as f64;
        c.shape(
            &format!(
                "<line x1=\"{ml:.1}\" y1=\"{a:.1}\" x2=\"{b:.1}\" y2=\"{a:.1}\" stroke=\"{}\" stroke-width=\"2\"{dash}/>",
                se.colour,
                a = ly - 4.0,
                b = ml + 24.0
            ),
            ml + 24.0,
            ly,
        );
        c.label(&Label::new(ml + 30.0, ly, Anchor::Start, se.label.as_str()));
    }
    c.finish(title, "")
}

#[cfg(test)]
mod tests {
    use super::super::layout::layout_problems;
    use super::*;

    #[test]
    fn numbers_for_labels() {
        let t = linear_ticks(-0.0342, 1.0, 6);
        let labels: Vec<&str> = t.at.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["-0.2", "0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        assert_eq!((t.lo, t.hi), (-0.2, 1.0));
        let t = linear_ticks(0.0, 21.79, 5);
        assert_eq!(t.at.last().unwrap().1, "25");
        let t = linear_ticks(0.0, 3e-6, 3);
        assert_eq!(t.at[1].1, "1e-6");
        assert_eq!(decade_ticks(-16.2, 4.3).at[0].1, "1e-17");
    }

    /// Long titles wrap, wide tick labels push the frame right, long legend entries widen
    /// the chart: no text leaves the viewBox or overlaps other text.
    #[test]
    fn plots_keep_their_text_inside_and_apart() {
        let s = |label: &str, pts: Vec<(f64, f64)>| Series {
            label: label.into(),
            points: pts,
            colour: "#000".into(),
            dashed: false,
        };
        let plots = [
            line_plot(
                "E_avg = 2∫E(μ)μ dμ from a-table-with-a-long-name (midpoint rule over the table)",
                "roughness (perceptual)",
                "E_avg",
                &[s("E_avg", vec![(0.0039, 1.0), (0.9961, 0.41)])],
            ),
            line_plot(
                "A",
                "cos θv = μ",
                "A",
                &[
                    s("A table, r = 0.004", vec![(0.0, -0.0342), (1.0, 1.0)]),
                    s(&"a very long legend entry ".repeat(4), vec![(0.0, 0.5)]),
                ],
            ),
            line_plot(
                "tiny",
                "x",
                "y",
                &[s("y", vec![(1e-7, -3e-9), (2e-7, 4.2e-9)])],
            ),
            line_plot("huge", "x", "y", &[s("y", vec![(0.0, 1e7), (1e6, 3e7)])]),
            plot(
                "convergence",
                "integrand evaluations",
                "|error|",
                &[s("brdfbake", vec![(1.2, -16.9), (4.3, -1.0)])],
                Scale::LogLog,
            ),
        ];
        for p in &plots {
            assert_eq!(layout_problems(p), Vec::<String>::new(), "{p}");
        }
        assert!(
            plots[0].matches("font-weight=\"bold\"").count() >= 2,
            "wrapped"
        );
    }
}
