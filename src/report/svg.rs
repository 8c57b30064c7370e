//! Inline SVG charts: heatmaps with axes and a colour bar, line plots with a legend.

use crate::lut::Lut;
use std::fmt::Write;

/// Escapes text for HTML.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

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

/// The colour of `t` in [0, 1].
pub fn colour(t: f64) -> String {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * 8.0;
    let i = (x.floor() as usize).min(7);
    let f = x - i as f64;
    let c: Vec<u8> = (0..3)
        .map(|k| (VIRIDIS[i][k] * (1.0 - f) + VIRIDIS[i + 1][k] * f).round() as u8)
        .collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

fn fmt_num(v: f64) -> String {
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

/// A heatmap of channel `c` over axes 0 (right) and 1 (up); a 3D table shows its middle
/// slice, a 1D table one row. At most 64×64 cells (finer tables are sampled at cell centres
/// by the GPU-equivalent lookup).
pub fn heatmap(lut: &Lut, c: usize, title: &str) -> String {
    let nd = lut.axes.len();
    let nx = lut.dim(0).min(64);
    let ny = if nd >= 2 { lut.dim(1).min(64) } else { 1 };
    let mut vals = vec![0.0f64; nx * ny];
    let ax = &lut.axes[0];
    let coord = |a: &crate::lut::Axis, i: usize, n: usize| {
        if a.size == n {
            a.coord(i)
        } else {
            a.coord(0) + (a.coord(a.size - 1) - a.coord(0)) * (i as f64 + 0.5) / n as f64
        }
    };
    for j in 0..ny {
        for i in 0..nx {
            let mut x = vec![coord(ax, i, nx)];
            if nd >= 2 {
                x.push(coord(&lut.axes[1], j, ny));
            }
            if nd == 3 {
                let az = &lut.axes[2];
                x.push(az.coord(az.size / 2));
            }
            vals[j * nx + i] = lut.lookup(&x)[c];
        }
    }
    let lo = vals
        .iter()
        .cloned()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    let hi = vals
        .iter()
        .cloned()
        .filter(|v| v.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    let span = if hi > lo { hi - lo } else { 1.0 };
    let (pw, ph) = (256.0, if ny == 1 { 32.0 } else { 256.0 });
    let (ml, mt) = (56.0, 28.0);
    let (w, h) = (ml + pw + 90.0, mt + ph + 48.0);
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" role=\"img\"><title>{t}</title>\
         <text x=\"{ml}\" y=\"16\" font-weight=\"bold\">{t}</text>",
        t = esc(title)
    );
    let (cw, chh) = (pw / nx as f64, ph / ny as f64);
    for j in 0..ny {
        for i in 0..nx {
            let v = vals[j * nx + i];
            // axis 1 upwards: row j drawn from the bottom
            let _ = write!(
                s,
                "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                ml + i as f64 * cw,
                mt + ph - (j + 1) as f64 * chh,
                cw + 0.3,
                chh + 0.3,
                colour((v - lo) / span)
            );
        }
    }
    let _ = write!(s, "<rect x=\"{ml}\" y=\"{mt}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#222\"/>");
    // axis 0 ticks and label
    let r0 = [ax.coord(0), ax.coord(ax.size - 1)];
    for (k, v) in r0.iter().enumerate() {
        let x = ml + if k == 0 { cw / 2.0 } else { pw - cw / 2.0 };
        let _ = write!(s, "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\" stroke=\"#222\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">{}</text>", mt + ph, mt + ph + 4.0, mt + ph + 16.0, fmt_num(*v));
    }
    let _ = write!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{} →</text>",
        ml + pw / 2.0,
        mt + ph + 34.0,
        esc(&ax.name)
    );
    if nd >= 2 {
        let ay = &lut.axes[1];
        for (k, v) in [ay.coord(0), ay.coord(ay.size - 1)].iter().enumerate() {
            let y = mt + if k == 0 { ph - chh / 2.0 } else { chh / 2.0 };
            let _ = write!(s, "<line x1=\"{}\" y1=\"{y}\" x2=\"{ml}\" y2=\"{y}\" stroke=\"#222\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>", ml - 4.0, ml - 6.0, y + 4.0, fmt_num(*v));
        }
        let _ = write!(
            s,
            "<text transform=\"translate(14 {}) rotate(-90)\" text-anchor=\"middle\">{} →</text>",
            mt + ph / 2.0,
            esc(&ay.name)
        );
    }
    if nd == 3 {
        let az = &lut.axes[2];
        let _ = write!(
            s,
            "<text x=\"{ml}\" y=\"{}\">slice {} = {}</text>",
            h - 2.0,
            esc(&az.name),
            fmt_num(az.coord(az.size / 2))
        );
    }
    // colour bar
    let bx = ml + pw + 16.0;
    for k in 0..32 {
        let t = k as f64 / 31.0;
        let _ = write!(
            s,
            "<rect x=\"{bx}\" y=\"{:.2}\" width=\"14\" height=\"{:.2}\" fill=\"{}\"/>",
            mt + ph - (k + 1) as f64 * ph / 32.0,
            ph / 32.0 + 0.3,
            colour(t)
        );
    }
    let _ = write!(
        s,
        "<rect x=\"{bx}\" y=\"{mt}\" width=\"14\" height=\"{ph}\" fill=\"none\" stroke=\"#222\"/>"
    );
    for (y, v) in [(mt + ph, lo), (mt + ph / 2.0, 0.5 * (lo + hi)), (mt, hi)] {
        let _ = write!(
            s,
            "<text x=\"{}\" y=\"{}\">{}</text>",
            bx + 18.0,
            y + 4.0,
            fmt_num(v)
        );
    }
    s.push_str("</svg>\n");
    s
}

/// A line plot with ticks, axis labels and a legend.
pub fn line_plot(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    let pts = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() || !x1.is_finite() {
        (x0, x1) = (0.0, 1.0);
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    if !y0.is_finite() || !y1.is_finite() {
        (y0, y1) = (0.0, 1.0);
    }
    y0 = y0.min(0.0);
    if y1 <= y0 {
        y1 = y0 + 1.0;
    }
    let (ml, mt, pw, ph) = (56.0, 28.0, 300.0, 200.0);
    let legend_h = 14.0 * series.len() as f64;
    let (w, h) = (ml + pw + 20.0, mt + ph + 44.0 + legend_h);
    let sx = |x: f64| ml + (x - x0) / (x1 - x0) * pw;
    let sy = |y: f64| mt + ph - (y - y0) / (y1 - y0) * ph;
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" role=\"img\"><title>{t}</title>\
         <text x=\"4\" y=\"16\" font-weight=\"bold\">{t}</text>\
         <rect x=\"{ml}\" y=\"{mt}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#222\"/>",
        t = esc(title)
    );
    for k in 0..=4 {
        let f = k as f64 / 4.0;
        let (x, y) = (x0 + f * (x1 - x0), y0 + f * (y1 - y0));
        let _ = write!(
            s,
            "<line x1=\"{X}\" y1=\"{mt}\" x2=\"{X}\" y2=\"{B}\" stroke=\"#ddd\"/><text x=\"{X}\" y=\"{T}\" text-anchor=\"middle\">{xl}</text>\
             <line x1=\"{ml}\" y1=\"{Y}\" x2=\"{R}\" y2=\"{Y}\" stroke=\"#ddd\"/><text x=\"{L}\" y=\"{Y4}\" text-anchor=\"end\">{yl}</text>",
            X = sx(x),
            B = mt + ph,
            T = mt + ph + 14.0,
            xl = fmt_num(x),
            Y = sy(y),
            R = ml + pw,
            L = ml - 4.0,
            Y4 = sy(y) + 4.0,
            yl = fmt_num(y)
        );
    }
    let _ = write!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
        ml + pw / 2.0,
        mt + ph + 30.0,
        esc(xlabel)
    );
    let _ = write!(
        s,
        "<text transform=\"translate(12 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
        mt + ph / 2.0,
        esc(ylabel)
    );
    for (k, se) in series.iter().enumerate() {
        let d: Vec<String> = se
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| format!("{:.2},{:.2}", sx(x), sy(y)))
            .collect();
        let dash = if se.dashed {
            " stroke-dasharray=\"5 3\""
        } else {
            ""
        };
        if !d.is_empty() {
            let _ = write!(
                s,
                "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.6\"{dash} points=\"{}\"/>",
                se.colour,
                d.join(" ")
            );
        }
        let ly = mt + ph + 44.0 + 14.0 * k as f64;
        let _ = write!(
            s,
            "<line x1=\"{ml}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"2\"{dash}/><text x=\"{}\" y=\"{ly}\">{}</text>",
            ly - 4.0,
            ml + 24.0,
            ly - 4.0,
            se.colour,
            ml + 30.0,
            esc(&se.label)
        );
    }
    s.push_str("</svg>\n");
    s
}
