//! The report's section on the classic-model tables (`classic-albedo`,
//! `classic-albedo-aniso`): E(μ) of every classic table at the middle texel of its parameter
//! axis, one curve per model, and a laws summary per model — Helmholtz reciprocity measured
//! by [`crate::laws::reciprocity`] at that parameter (≈ 15k BRDF evaluations, cheap), and
//! where the table itself says the model reflects more than it receives (E > 1).

use super::page::{Page, PALETTE, TABLE_ATTRS};
use super::svg::{esc, line_plot, Series};
use crate::laws::reciprocity;
use crate::table::TableKind;
use std::fmt::Write;

/// Appends the section if any table is a classic one (nothing otherwise).
pub fn section(tables: &[super::ReportTable], out: &mut Page) {
    let classic: Vec<&super::ReportTable> =
        tables.iter().filter(|t| t.spec.kind.is_classic()).collect();
    if classic.is_empty() {
        return;
    }
    out.section("Classic models: albedo and the two laws");
    let _ = writeln!(
        out,
        "<p>E(μ) = ∫ f(l, v)(n·l) dω_l of each classic table at the middle texel of its parameter \
         axis (anisotropic tables, dashed: the view-azimuth average E_avg at the largest anisotropy \
         of the table). Reciprocity: the largest relative \
         |f(ωi,ωo) − f(ωo,ωi)| over the fixed direction set of <code>brdfbake laws</code>. \
         Energy: the largest E in the table; E &gt; 1 means the model reflects more than it \
         receives there.</p><div class=\"row\">"
    );
    let mut curves = Vec::new();
    let mut rows = String::new();
    for (k, t) in classic.iter().enumerate() {
        let lut = &t.lut;
        let c = t.spec.model.classic.expect("a classic table");
        let pa = &lut.axes[1];
        let j = pa.size / 2;
        let z = if lut.axes.len() == 3 {
            lut.axes[2].size - 1
        } else {
            0
        };
        let mu = &lut.axes[0];
        let pts: Vec<(f64, f64)> = (0..mu.size)
            .map(|i| (mu.coord(i), lut.texel([i, j, z], 0) as f64))
            .collect();
        curves.push(Series {
            label: format!(
                "{} ({} = {:.3})",
                t.spec.name,
                c.parameter_quantity().name(),
                pa.coord(j)
            ),
            points: pts,
            colour: PALETTE[k % PALETTE.len()].into(),
            dashed: t.spec.kind == TableKind::ClassicAlbedoAniso,
        });
        let r = reciprocity(c.reflectance(pa.coord(j), 1.0).as_ref());
        let nc = lut.channels.len();
        let (mut emax, mut at) = (f64::NEG_INFINITY, 0usize);
        for (i, v) in lut.data.iter().enumerate().step_by(nc) {
            if (*v as f64) > emax {
                emax = *v as f64;
                at = i / nc;
            }
        }
        let (nx, ny) = (lut.dim(0), lut.dim(1));
        let (ix, iy) = (at % nx, (at / nx) % ny);
        let _ = write!(
            rows,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.2e}</td><td>{:.6} at μ = {:.4}, {} = {:.4}{}</td></tr>",
            esc(&t.spec.name),
            esc(c.name()),
            if r.holds { "holds" } else { "fails" },
            r.max_rel,
            emax,
            lut.axes[0].coord(ix),
            c.parameter_quantity().name(),
            lut.axes[1].coord(iy),
            if emax > 1.0 + lut.error_estimate[0] { " (E > 1: not energy conserving there)" } else { "" },
        );
    }
    out.push_str(&line_plot(
        "E(μ) of the classic models",
        "cos θv = μ",
        "E",
        &curves,
    ));
    let _ = writeln!(out, "</div>");
    out.table("Classic models: reciprocity and energy", TABLE_ATTRS);
    let _ = writeln!(
        out,
        "<tr><th>table</th><th>model</th><th>reciprocity</th><th>max relative violation</th>\
         <th>largest E in the table</th></tr>{rows}</table>"
    );
    out.end_section();
}
