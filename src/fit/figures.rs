//! BENCHMARKS.md's comparison of fits with the published ones: for each preset a published
//! fit approximates, the published fit's max error over the whole domain, brdfbake's best fit
//! with no more operations, and the cheapest fits under 1e-3 and 1e-4 — every error measured
//! the same way (the exact integral on the validation grid; ours including their f32
//! rounding bound). `cargo run --release --example fit_figures -- --write` puts the table
//! into BENCHMARKS.md; `tests/fit_figures.rs` recomputes it and fails when they differ.

use super::reference::{self, Reference};
use super::search::{self, Candidate, Limits, Weight};
use super::target;

/// The markers of the generated block in BENCHMARKS.md.
pub const BEGIN: &str = "<!-- begin fit-table (generated: do not edit) -->";
pub const END: &str = "<!-- end fit-table -->";

/// The requested max errors whose cheapest fits the table gives.
pub const TARGETS: [f64; 2] = [1e-3, 1e-4];

/// One preset's row.
#[derive(Clone, Debug)]
pub struct FitRow {
    pub preset: String,
    pub table: String,
    pub published: Reference,
    /// The published fit's max |error| over every channel, and where (the coordinates).
    pub published_error: f64,
    pub published_at: Vec<f64>,
    pub published_ops: usize,
    /// brdfbake's best fit with at most the published fit's operations (by max error plus
    /// f32 bound), if any.
    pub ours_same_ops: Option<Candidate>,
    /// The cheapest fit under each of [`TARGETS`], if the search found one.
    pub cheapest: Vec<Option<Candidate>>,
    /// The most accurate fit found (its error and operations, when no target is met).
    pub best: Candidate,
}

/// The rows for every published fit's preset (the built-in presets' first table).
pub fn rows() -> Result<Vec<FitRow>, String> {
    let mut out = Vec::new();
    for r in reference::all() {
        let name = reference::preset_of(r.name).ok_or_else(|| format!("{}: no preset", r.name))?;
        let (_, text) = crate::presets::BUILTIN
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| format!("{name}: not a built-in preset"))?;
        let preset = crate::preset::parse(text, name, name).map_err(|e| e.to_string())?;
        let spec = &preset.tables[0].spec;
        let tg = target::build(spec, None)?;
        let front = search::search(
            &tg,
            Weight::Absolute,
            spec.model.ndf.is_some(),
            &Limits::default(),
            &|| false,
        );
        let m = reference::measure(&r.program, &tg);
        let (c, _) = m
            .error
            .iter()
            .enumerate()
            .fold((0, f64::MIN), |a, (i, &e)| if e > a.1 { (i, e) } else { a });
        let ops = m.counts.ops;
        let best = front
            .iter()
            .min_by(|a, b| a.max_total().total_cmp(&b.max_total()))
            .cloned()
            .ok_or_else(|| format!("{name}: the search found no fit"))?;
        out.push(FitRow {
            preset: name.to_string(),
            table: spec.name.clone(),
            published_error: m.max_error(),
            published_at: m.argmax[c].clone(),
            published_ops: ops,
            ours_same_ops: front
                .iter()
                .filter(|f| f.counts.ops <= ops)
                .min_by(|a, b| a.max_total().total_cmp(&b.max_total()))
                .cloned(),
            cheapest: TARGETS
                .iter()
                .map(|&e| front.iter().find(|f| f.max_total() <= e).cloned())
                .collect(),
            best,
            published: r,
        });
    }
    Ok(out)
}

fn g(x: f64) -> String {
    format!("{x:.3e}")
}

/// The rows as BENCHMARKS.md's table, between [`BEGIN`] and [`END`].
pub fn markdown(rows: &[FitRow]) -> String {
    let mut s = format!(
        "{BEGIN}\n| preset (table) | published fit: ops, max error, where (μ, r) | brdfbake at ≤ its ops: ops, max error (+ f32 bound), ratio | cheapest ≤ 1e-3 | cheapest ≤ 1e-4 |\n|---|---|---|---|---|\n"
    );
    for r in rows {
        let at: Vec<String> = r.published_at.iter().map(|x| format!("{x:.3}")).collect();
        let ours = r.ours_same_ops.as_ref().map_or("none".to_string(), |c| {
            format!(
                "{}, {} ({}), {:.1}× lower",
                c.counts.ops,
                g(c.max_total()),
                c.description,
                r.published_error / c.max_total()
            )
        });
        let cheap: Vec<String> = r
            .cheapest
            .iter()
            .map(|c| match c {
                Some(c) => format!(
                    "{} ops, {} ({})",
                    c.counts.ops,
                    g(c.max_total()),
                    c.description
                ),
                None => format!(
                    "none found (best {} at {} ops)",
                    g(r.best.max_total()),
                    r.best.counts.ops
                ),
            })
            .collect();
        s += &format!(
            "| `{}` ({}) | {}: {}, {}, at ({}) | {} | {} | {} |\n",
            r.preset,
            r.table,
            r.published.name,
            r.published_ops,
            g(r.published_error),
            at.join(", "),
            ours,
            cheap[0],
            cheap[1]
        );
    }
    s + END
}
