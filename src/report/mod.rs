//! A self-contained HTML report of baked tables: inline SVG only (no scripts, no network),
//! a table of contents linking every section, heading and table. Per table: a heatmap of
//! every texel per channel (labelled axes, a colour bar from the true minimum to the true
//! maximum), and where they apply E(μ) curves for several roughness values, the energy loss
//! 1 − E, E_avg against roughness and the comparison with Karis' mobile `EnvBRDFApprox`
//! (2014).

pub mod classic;
pub mod convergence;
pub mod engines;
pub mod filament;
mod heatmap;
pub mod layout;
pub mod ltc;
mod page;
mod svg;

use crate::lut::{Lut, Quantity};
use crate::model::NdfKind;
use crate::table::{DfgLayout, TableKind, TableSpec};
pub use heatmap::heatmap;
pub use layout::layout_problems;
pub use page::Page;
use page::{PALETTE, TABLE_ATTRS};
use std::fmt::Write;
pub use svg::{esc, line_plot, Series};

/// One baked table to show.
pub struct ReportTable {
    pub preset: String,
    pub spec: TableSpec,
    /// The table's values (unscaled).
    pub lut: Lut,
    /// An `ltc` table's per-texel fit error ([`crate::table::ltc::fit_channels`], the
    /// sidecar's `ltc.fit_error`), texels as `lut`'s; `None` for other tables.
    pub fit: Option<Lut>,
}

/// Karis' analytic fit of the split-sum A, B for GGX ("Physically Based Shading on Mobile",
/// 2014), at perceptual roughness `r` and `n_dot_v`.
pub fn env_brdf_approx(r: f64, n_dot_v: f64) -> (f64, f64) {
    let c0 = [-1.0, -0.0275, -0.572, 0.022];
    let c1 = [1.0, 0.0425, 1.04, -0.04];
    let v: Vec<f64> = (0..4).map(|i| r * c0[i] + c1[i]).collect();
    let a004 = (v[0] * v[0]).min((-9.28 * n_dot_v).exp2()) * v[0] + v[1];
    (-1.04 * a004 + v[2], 1.04 * a004 + v[3])
}

/// The directional albedo E at (μ, roughness coordinate) a table holds, if it holds one.
fn albedo_of(t: &ReportTable, mu: f64, r: f64) -> Option<f64> {
    let v = t.lut.lookup(&[mu, r]);
    match (t.spec.kind, t.spec.dfg_layout) {
        (TableKind::Albedo, _) | (TableKind::KullaConty, _) | (TableKind::ClassicAlbedo, _) => {
            Some(v[0])
        }
        (TableKind::Dfg, Some(DfgLayout::Karis | DfgLayout::KarisF82)) => Some(v[0] + v[1]),
        (TableKind::Dfg, _) => Some(v[1]),
        _ => None,
    }
}

fn roughness_label(spec: &TableSpec) -> String {
    match spec.axes.last().map(|a| a.quantity) {
        Some(Quantity::Roughness(q)) => format!("roughness ({})", q.name()),
        _ => "roughness".into(),
    }
}

/// Five roughness coordinates spread over the axis' texel centres.
fn roughness_picks(spec: &TableSpec) -> Vec<f64> {
    let a = spec.axes.last().expect("axis");
    let (lo, hi) = (a.coord(0), a.coord(a.size - 1));
    (0..5).map(|i| lo + (hi - lo) * i as f64 / 4.0).collect()
}

fn table_section(t: &ReportTable, out: &mut Page) {
    let spec = &t.spec;
    let lut = &t.lut;
    out.section(&format!("{} / {}", t.preset, spec.name));
    let _ = writeln!(
        out,
        "<p><b>{}</b>: {}<br>model: {}<br>axes: {}<br>storage: {}{}</p>",
        spec.kind.name(),
        esc(spec.kind.description()),
        esc(&crate::meta::model_summary(spec)),
        esc(&lut
            .axes
            .iter()
            .map(|a| format!(
                "{} ({} texels, [{}, {}], {}{})",
                a.name,
                a.size,
                a.range[0],
                a.range[1],
                a.convention.name(),
                a.spacing_note()
            ))
            .collect::<Vec<_>>()
            .join("; ")),
        spec.storage.name(),
        if spec.storage == crate::table::Storage::F32 {
            ""
        } else {
            " (the heatmaps show the computed f32 texels; the file rounds them to this)"
        }
    );
    let _ = writeln!(out, "<div class=\"row\">");
    for (c, ch) in lut.channels.iter().enumerate() {
        out.push_str(&heatmap(lut, c, &format!("{} — {}", spec.name, ch.name)));
    }
    let _ = writeln!(out, "</div>");
    if let Some(fit) = &t.fit {
        ltc::section(&spec.name, fit, out);
    }
    let is_e = matches!(
        spec.kind,
        TableKind::Albedo | TableKind::Dfg | TableKind::KullaConty | TableKind::ClassicAlbedo
    );
    if is_e {
        let picks = roughness_picks(spec);
        let mu_axis = &lut.axes[0];
        let n = 64;
        let mus: Vec<f64> = (0..=n)
            .map(|i| {
                let [lo, hi] = mu_axis.coordinate_span();
                lo + (hi - lo) * i as f64 / n as f64
            })
            .collect();
        let rl = roughness_label(spec);
        let mut curves = Vec::new();
        let mut losses = Vec::new();
        for (k, r) in picks.iter().enumerate() {
            let pts: Vec<(f64, f64)> = mus
                .iter()
                .filter_map(|&m| albedo_of(t, m, *r).map(|e| (m, e)))
                .collect();
            let label = format!("{rl} = {r:.3}");
            losses.push(Series {
                label: label.clone(),
                points: pts.iter().map(|(m, e)| (*m, 1.0 - e)).collect(),
                colour: PALETTE[k % PALETTE.len()].into(),
                dashed: false,
            });
            curves.push(Series {
                label,
                points: pts,
                colour: PALETTE[k % PALETTE.len()].into(),
                dashed: false,
            });
        }
        let what = if spec.kind == TableKind::Dfg {
            " (F0 = 1: E = A + B = G)"
        } else {
            ""
        };
        let _ = writeln!(out, "<div class=\"row\">");
        out.push_str(&line_plot(
            &format!("E(μ) of {}{what}", spec.name),
            "cos θv = μ",
            "E",
            &curves,
        ));
        out.push_str(&line_plot(
            &format!("energy loss 1 − E(μ) of {}", spec.name),
            "cos θv = μ",
            "1 − E",
            &losses,
        ));
        // E_avg = 2 ∫ E μ dμ from the table (trapezoid over lookups, μ in the axis range)
        let ra = lut.axes.last().expect("axis");
        let rs: Vec<f64> = (0..=48)
            .map(|i| ra.coord(0) + (ra.coord(ra.size - 1) - ra.coord(0)) * i as f64 / 48.0)
            .collect();
        let m = 256;
        let avg: Vec<(f64, f64)> = rs
            .iter()
            .filter_map(|&r| {
                let f = |i: usize| {
                    let mu = (i as f64 + 0.5) / m as f64;
                    albedo_of(t, mu, r).map(|e| 2.0 * e * mu / m as f64)
                };
                (0..m).map(f).sum::<Option<f64>>().map(|s| (r, s))
            })
            .collect();
        out.push_str(&line_plot(
            &format!(
                "E_avg = 2∫E(μ)μ dμ from {} (midpoint rule over the table)",
                spec.name
            ),
            &rl,
            "E_avg",
            &[Series {
                label: "E_avg".into(),
                points: avg,
                colour: PALETTE[1].into(),
                dashed: false,
            }],
        ));
        let _ = writeln!(out, "</div>");
    }
    if spec.kind == TableKind::AlbedoAvg {
        let a = &lut.axes[0];
        let pts: Vec<(f64, f64)> = (0..a.size)
            .map(|i| (a.coord(i), lut.data[i * lut.channels.len()] as f64))
            .collect();
        out.push_str(&line_plot(
            &format!("E_avg vs roughness ({})", spec.name),
            &roughness_label(spec),
            "E_avg",
            &[Series {
                label: "E_avg (texels)".into(),
                points: pts,
                colour: PALETTE[1].into(),
                dashed: false,
            }],
        ));
    }
    if spec.kind == TableKind::Dfg && spec.model.ndf == Some(NdfKind::Ggx) {
        karis_section(t, out);
    }
    out.end_section();
}

fn karis_section(t: &ReportTable, out: &mut Page) {
    let spec = &t.spec;
    let lut = &t.lut;
    let ra = lut.axes.last().expect("axis");
    let perceptual = |coord: f64| match ra.quantity {
        Quantity::Roughness(q) => q.to_alpha(coord).sqrt(),
        Quantity::Cosine | Quantity::Fresnel(_) | Quantity::Anisotropy | Quantity::FormFactor => {
            coord
        }
    };
    let ab = |mu: f64, r: f64| {
        let v = lut.lookup(&[mu, r]);
        match spec.dfg_layout {
            Some(DfgLayout::Karis | DfgLayout::KarisF82) => (v[0], v[1]),
            _ => (v[1] - v[0], v[0]),
        }
    };
    let mut series = Vec::new();
    let mut max_a: f64 = 0.0;
    let mut max_b: f64 = 0.0;
    let mu_axis = &lut.axes[0];
    for (k, r) in roughness_picks(spec)
        .iter()
        .enumerate()
        .filter(|(k, _)| k % 2 == 0)
    {
        let mut ta = Vec::new();
        let mut tb = Vec::new();
        let mut ka = Vec::new();
        let mut kb = Vec::new();
        for i in 0..=64 {
            let [lo, hi] = mu_axis.coordinate_span();
            let mu = lo + (hi - lo) * i as f64 / 64.0;
            let (a, b) = ab(mu, *r);
            let (xa, xb) = env_brdf_approx(perceptual(*r), mu);
            max_a = max_a.max((a - xa).abs());
            max_b = max_b.max((b - xb).abs());
            ta.push((mu, a));
            tb.push((mu, b));
            ka.push((mu, xa));
            kb.push((mu, xb));
        }
        let col = PALETTE[k % PALETTE.len()].to_string();
        let lab = format!("r = {:.3}", perceptual(*r));
        series.push((
            Series {
                label: format!("A table, {lab}"),
                points: ta,
                colour: col.clone(),
                dashed: false,
            },
            Series {
                label: format!("A approx, {lab}"),
                points: ka,
                colour: col.clone(),
                dashed: true,
            },
            Series {
                label: format!("B table, {lab}"),
                points: tb,
                colour: col.clone(),
                dashed: false,
            },
            Series {
                label: format!("B approx, {lab}"),
                points: kb,
                colour: col,
                dashed: true,
            },
        ));
    }
    let (a_s, b_s): (Vec<Series>, Vec<Series>) = series
        .into_iter()
        .flat_map(|(a, b, c, d)| [(a, c), (b, d)])
        .unzip();
    out.heading(&format!(
        "{}: comparison with Karis' EnvBRDFApprox (mobile, 2014)",
        spec.name
    ));
    let _ = writeln!(
        out,
        "<p>Solid: this table; dashed: the analytic fit. Max |difference| over the plotted curves: \
         A {max_a:.4}, B {max_b:.4}. The fit was made to Unreal's table (Schlick-Smith G with \
         k = alpha/2, perceptual roughness); where this table's model differs, so do the curves.</p>\
         <div class=\"row\">"
    );
    out.push_str(&line_plot("A = ∫(1 − Fc) f cos", "cos θv = μ", "A", &a_s));
    out.push_str(&line_plot("B = ∫ Fc f cos", "cos θv = μ", "B", &b_s));
    let _ = writeln!(out, "</div>");
}

/// The section comparing a shipped Filament DFG table (`label`: the file's name).
fn filament_section(label: &str, c: &filament::Comparison, out: &mut Page) {
    let names = ["R = ∫Fc f cos", "G = ∫ f cos", "B = cloth ∫ D V cos"];
    out.section("Comparison with Filament's shipped DFG table");
    let _ = writeln!(
        out,
        "<p>File <code>{}</code>: {n}×{n}, {} channels, f16. Exact values: GGX, \
         height-correlated Smith, F = 1 (and Charlie/Ashikhmin cloth), computed by brdfbake at \
         tolerance 1e-7. <b>As sampled</b>: each texel against the exact value where Filament's \
         shader reads it (n·v = (x + 0.5)/N, perceptual roughness = (y + 0.5)/N) — what a \
         renderer gets. <b>As computed</b>: against the exact value where cmgen computed the \
         row (roughness min((y + 1.5)/N, 1): its row formula saturate((N − y + 0.5)/N) with \
         the flip to GL order puts every row one texel up) — cmgen's integration error alone. \
         f16 rounding alone accounts for up to the last column.</p>",
        esc(label),
        c.channels,
        n = c.size
    );
    out.table(
        &format!("{label}: shipped − exact per channel"),
        TABLE_ATTRS,
    );
    let _ = writeln!(
        out,
        "<tr><th>channel</th><th>max |Δ| as sampled</th><th>at (n·v, r)</th>\
         <th>mean |Δ| as sampled</th><th>max |Δ| as computed</th><th>at (n·v, r)</th>\
         <th>mean |Δ| as computed</th><th>f16 rounding</th></tr>"
    );
    for (ch, name) in names.iter().enumerate().take(c.channels) {
        let (a, b) = (&c.as_sampled[ch], &c.as_computed[ch]);
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{:.2e}</td><td>({:.4}, {:.4})</td><td>{:.2e}</td>\
             <td>{:.2e}</td><td>({:.4}, {:.4})</td><td>{:.2e}</td><td>{:.1e}</td></tr>",
            name,
            a.max_abs,
            a.at.0,
            a.at.1,
            a.mean_abs,
            b.max_abs,
            b.at.0,
            b.at.1,
            b.mean_abs,
            c.f16_floor[ch]
        );
    }
    let _ = writeln!(out, "</table><div class=\"row\">");
    for (k, ch) in c.diff.channels.iter().enumerate() {
        out.push_str(&heatmap(
            &c.diff,
            k,
            &format!("shipped − exact, as sampled — {}", ch.name),
        ));
    }
    let _ = writeln!(out, "</div>");
    out.end_section();
}

/// The whole page; `filament`: a shipped Filament DFG table's name and its comparison;
/// `engines`: the comparisons of `--compare`.
pub fn html(
    tables: &[ReportTable],
    filament: Option<(&str, &filament::Comparison)>,
    engines: &[engines::EngineComparison],
) -> String {
    let head = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\">\
         <title>brdfbake report</title><style>\
         body{{font-family:sans-serif;margin:1.5em;color:#222;background:#fff}}\
         section{{border-top:1px solid #ccc;margin-top:1.5em}}\
         .row{{display:flex;flex-wrap:wrap;gap:1em;align-items:flex-start}}\
         caption{{text-align:left;font-weight:bold;padding:0.3em 0}}\
         td{{vertical-align:top}} td:not(:last-child){{white-space:nowrap}}\
         svg{{background:#fff;flex:none}} svg text{{font-family:sans-serif;fill:#222}}\
         </style></head><body>\n<h1>brdfbake report</h1>\n<p>brdfbake {} — {} table(s). \
         Heatmaps draw every texel of a channel, one image pixel per texel (zoom in to see \
         each), over the table's axes: axis 0 to the right, axis 1 upwards, a 3D table one \
         panel per slice. Their colour bar runs from the channel's minimum to its maximum over \
         the whole table, both printed. A table too large to draw whole says on its chart \
         which texels are drawn. Values are the baked texels (f32, before a file's storage \
         rounds them).</p>\n",
        crate::meta::VERSION,
        tables.len()
    );
    let mut out = Page::new();
    if let Some((label, c)) = filament {
        filament_section(label, c, &mut out);
    }
    engines::section(engines, &mut out);
    for t in tables {
        table_section(t, &mut out);
    }
    classic::section(tables, &mut out);
    convergence::section(&mut out);
    out.push_str("</body></html>\n");
    out.finish(&head)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Karis' fit, against the formula evaluated by hand: smooth at normal incidence A + B ≈ 1;
    /// fully rough, B slightly negative (a property of the fit).
    #[test]
    fn env_brdf_approx_is_karis_fit() {
        let (a, b) = env_brdf_approx(0.0, 1.0);
        let a004 = 2f64.powf(-9.28) + 0.0425;
        assert!(
            (a - (1.04 - 1.04 * a004)).abs() < 1e-15 && (b - (1.04 * a004 - 0.04)).abs() < 1e-15
        );
        assert!((a + b - 1.0).abs() < 1e-12, "{a} {b}");
        let (a, b) = env_brdf_approx(1.0, 0.5);
        assert!(
            (a - 0.4524).abs() < 1e-12 && (b + 0.0024).abs() < 1e-12,
            "{a} {b}"
        );
    }
}
