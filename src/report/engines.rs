//! The report's section of engine comparisons (`brdfbake report --compare PRESET=FILE`):
//! per shipped table, where it comes from, its error and brdfbake's against exact values per
//! channel, what the comparison found, and a heatmap of the shipped table's error.

use super::heatmap::heatmap;
use super::page::{Page, TABLE_ATTRS};
use super::svg::esc;
use crate::engines::Comparison;
use crate::numfmt::num;
use std::fmt::Write;

/// One comparison: the engine preset's source (where the original lives) and the result.
pub struct EngineComparison {
    pub source: Option<crate::engines::Source>,
    pub comparison: Comparison,
}

/// Appends the section (nothing when there is no comparison).
pub fn section(items: &[EngineComparison], out: &mut Page) {
    if items.is_empty() {
        return;
    }
    out.section("Engine tables");
    let _ = writeln!(
        out,
        "<p>Each shipped table against exact values at its own \
         texels (brdfbake's bake of the engine preset at a 100× tighter tolerance), next to \
         brdfbake's table of the same preset. The heatmaps show the shipped table's error \
         (shipped − exact) per channel over its stored axes.</p>"
    );
    for e in items {
        let c = &e.comparison;
        out.heading(&format!("{} / {}", c.preset, c.table));
        if let Some(s) = &e.source {
            let _ = writeln!(
                out,
                "<p>{} <code>{}</code>: {} <code>{}</code> at {} ({}). {}</p>",
                esc(&s.engine),
                esc(&s.table),
                esc(&s.repository),
                esc(&s.path),
                esc(&s.commit),
                esc(&s.licence),
                s.generator.as_deref().map(esc).unwrap_or_default()
            );
        }
        let _ = writeln!(
            out,
            "<p>File <code>{}</code>, {} texels.</p>",
            esc(&c.file),
            c.dims
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(" × ")
        );
        out.table(
            &format!("{} / {}: errors per channel", c.preset, c.table),
            TABLE_ATTRS,
        );
        let _ = writeln!(
            out,
            "<tr><th>channel</th><th>shipped max |Δ|</th><th>at</th><th>shipped mean |Δ|</th>\
             <th>brdfbake max |Δ|</th><th>brdfbake as stored max |Δ|</th></tr>"
        );
        for ch in &c.channels {
            let at = ch
                .shipped
                .worst_at
                .iter()
                .map(|(n, x)| format!("{n} = {}", num(*x)))
                .collect::<Vec<_>>()
                .join(", ");
            let _ = writeln!(
                out,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                esc(&ch.channel),
                num(ch.shipped.max_abs),
                esc(&at),
                num(ch.shipped.mean_abs),
                num(ch.brdfbake.max_abs),
                ch.brdfbake_stored
                    .as_ref()
                    .map_or("–".to_string(), |s| num(s.max_abs))
            );
        }
        let _ = writeln!(out, "</table><ul>");
        for ch in &c.channels {
            for f in &ch.findings {
                let _ = writeln!(out, "<li>{}: {}</li>", esc(&ch.channel), esc(&f.describe()));
            }
        }
        let _ = writeln!(out, "</ul><div class=\"row\">");
        for (k, ch) in c.errors.channels.iter().enumerate() {
            out.push_str(&heatmap(
                &c.errors,
                k,
                &format!("{}: shipped − exact, {}", c.table, ch.name),
            ));
        }
        let _ = writeln!(out, "</div>");
    }
    out.end_section();
}
