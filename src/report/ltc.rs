//! The report's section on an `ltc` table's fit: a heatmap per channel of the per-texel fit
//! error (the numbers the sidecar's `ltc.fit_error` records, [`crate::table::ltc::fit_channels`]),
//! on a log₁₀ scale (the errors span decades: tiny on rough lobes, large at grazing views and
//! small α), with their median, 99th percentile and maximum, and a sentence on what each
//! measures.

use super::heatmap::heatmap;
use super::page::{Page, TABLE_ATTRS};
use super::svg::esc;
use crate::lut::Lut;
use std::fmt::Write;

/// What each fit-error channel measures, for a reader of the report.
fn plain_meaning(name: &str) -> &'static str {
    match name {
        "objective" => "what the fit minimized: a weighted mean of the squared relative errors of the LTC at a fixed rule's nodes and of the probe lights' lit values (its square root is an rms relative error). It ranks texels by how hard they were to fit.",
        "l3" => "Heitz et al. 2016's error, ∫|f cos − norm·D|³ over ∫(f cos)³ on the fit's rule: the lobe's shape near its peak, where the cube weighs the bright directions; blind to dim lights in the tails.",
        "lit_rms" => "the relative error of the lit value of the probe lights (a fixed tiling of the hemisphere into quads, and bands across the horizon), rms weighted by solid angle: what a user sees, over lights everywhere, dim tails included.",
        "lit_max" => "the largest relative error of a probe light holding at least 1% of the brightest probe's light: the worst error of a light that matters.",
        _ => "",
    }
}

/// The per-texel values of channel `c` of `fit`.
fn channel_values(fit: &Lut, c: usize) -> Vec<f64> {
    let nc = fit.channels.len().max(1);
    fit.data
        .iter()
        .skip(c)
        .step_by(nc)
        .map(|&v| v as f64)
        .collect()
}

/// `(median, p99, max)` as the sidecar's `ltc.fit_error` states them (the value at index
/// `round((n − 1)·p)` of the sorted values); NaN for no values.
fn quantiles(mut v: Vec<f64>) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    let q = |p: f64| {
        v.get(((v.len() as f64 - 1.0) * p).round() as usize)
            .copied()
            .unwrap_or(f64::NAN)
    };
    (q(0.5), q(0.99), q(1.0))
}

/// The smallest value shown on the log scale: below, a texel is drawn as 10⁻⁹ (a texel with
/// nothing to fit, e.g. a Lambertian lobe's identity, has error 0).
const LOG_FLOOR: f64 = 1e-9;

/// The section for table `name`'s fit error `fit` (texels as the table's, 4 channels).
pub fn section(name: &str, fit: &Lut, out: &mut Page) {
    out.heading(&format!("Fit error of the LTC — {name}"));
    let _ = writeln!(
        out,
        "<p>Per texel, the error of the fitted LTC against \
         the BRDF that the sidecar records in <code>ltc.fit_error</code> (<code>brdfbake verify</code> \
         checks it against a refit), on a log<sub>10</sub> scale; <code>brdfbake probe FILE --at … \
         --polygon …</code> shows the lit value of any polygon light against the exact one.</p>"
    );
    out.table(&format!("{name}: fit error quantiles"), TABLE_ATTRS);
    let _ = writeln!(
        out,
        "<tr><th>error</th><th>median</th><th>99th percentile</th><th>max</th><th>what it measures</th></tr>"
    );
    for (c, ch) in fit.channels.iter().enumerate() {
        let (m, p, x) = quantiles(channel_values(fit, c));
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{m:.3e}</td><td>{p:.3e}</td><td>{x:.3e}</td><td>{}</td></tr>",
            esc(&ch.name),
            esc(plain_meaning(&ch.name))
        );
    }
    let _ = writeln!(out, "</table><div class=\"row\">");
    let mut log = fit.clone();
    for v in log.data.iter_mut() {
        let x = (*v as f64).max(LOG_FLOOR);
        *v = if x.is_finite() {
            x.log10() as f32
        } else {
            f32::NAN
        };
    }
    for (c, ch) in fit.channels.iter().enumerate() {
        out.push_str(&heatmap(
            &log,
            c,
            &format!("{name} — log10 {} (fit error)", ch.name),
        ));
    }
    let _ = writeln!(out, "</div>");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_as_the_sidecar_states_them() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        // round(99 * 0.5) = 50 (half away from zero), round(99 * 0.99) = 98
        assert_eq!(quantiles(v), (51.0, 99.0, 100.0));
        assert!(quantiles(Vec::new()).0.is_nan());
    }
}
