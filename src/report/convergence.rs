//! Convergence study: error against the number of integrand evaluations, for each kind of
//! integral brdfbake bakes, comparing
//!
//! * brdfbake's method — the nested adaptive Gauss–Kronrod (G7/K15) quadrature the tables
//!   use ([`crate::table::albedo`], [`crate::table::dfg`]), over a sweep of tolerances — with
//! * importance-sampled Monte Carlo on Hammersley points ([`crate::hemisphere::monte_carlo`]),
//!   the method of the usual bakers, unbiased (÷ N) and in the biased variant (÷ valid
//!   samples) that some implementations use.
//!
//! Each kind is studied at one representative point (fixed below). The reference value is
//! supplied by the caller: `brdfbake report` uses brdfbake's own quadrature at tolerance
//! [`LIBRARY_REFERENCE_TOL`] (fast, but not independent: its curve then measures
//! self-convergence); `cargo run --release --example convergence` uses the test suite's
//! independent l-space integrator (`tests/common/reference.rs`) and prints the tables of
//! BENCHMARKS.md.

use super::svg::Series;
use crate::hemisphere::monte_carlo::{self as mc, Sampling};
use crate::model::fresnel::schlick_weight;
use crate::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
use crate::quadrature::{integrate1, Tolerance};
use crate::table::albedo::{average_albedo, directional_albedo};
use crate::table::dfg::{sheen_albedo, split_sum};
use std::f64::consts::FRAC_PI_2;
use std::fmt::Write;

/// The tolerance at which brdfbake's own quadrature serves as the report's reference
/// (E_avg, a nested integral: [`LIBRARY_REFERENCE_TOL_AVG`]).
pub const LIBRARY_REFERENCE_TOL: f64 = 1e-13;
/// The report's reference tolerance for E_avg: at 1e-9 the nested quadrature already costs
/// 1.7 million evaluations (its measured error there is ~2e-14).
pub const LIBRARY_REFERENCE_TOL_AVG: f64 = 1e-9;

/// The report's reference tolerance for `kind`.
pub fn library_reference_tol(kind: Kind) -> f64 {
    if kind == Kind::AlbedoAvg {
        LIBRARY_REFERENCE_TOL_AVG
    } else {
        LIBRARY_REFERENCE_TOL
    }
}

/// The integral kinds of the study.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Directional albedo E(μ) of GGX + height-correlated Smith, F = 1.
    Albedo,
    /// The split-sum pair (A, B) of the same model (Karis layout; Filament's R, G are B and
    /// A + B).
    SplitSum,
    /// The cloth (sheen) albedo ∫ D_Charlie V_Ashikhmin (n·l) dω_l.
    Cloth,
    /// E_avg = 2∫ E(μ) μ dμ of GGX + height-correlated Smith.
    AlbedoAvg,
    /// Smith G1 of the Gaussian NDF, which has no closed-form Λ.
    G1Numeric,
}

/// Every kind, in report order.
pub const KINDS: [Kind; 5] = [
    Kind::Albedo,
    Kind::SplitSum,
    Kind::Cloth,
    Kind::AlbedoAvg,
    Kind::G1Numeric,
];

/// α of the study's GGX / Charlie lobes (perceptual roughness ≈ 0.71).
pub const ALPHA: f64 = 0.5;
/// n·v of the study's view.
pub const MU: f64 = 0.3;
/// Cook–Torrance m of the Gaussian NDF for the G1 study.
pub const GAUSS_M: f64 = 0.3;

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::Albedo => "albedo E",
            Kind::SplitSum => "DFG A, B",
            Kind::Cloth => "cloth (sheen) albedo",
            Kind::AlbedoAvg => "albedo-avg E_avg",
            Kind::G1Numeric => "G1 numeric (Gaussian NDF)",
        }
    }

    /// The integral and its point, in words.
    pub fn description(self) -> String {
        match self {
            Kind::Albedo => format!("E(μ) = ∫ f (n·l) dω_l, GGX + height-correlated Smith, F = 1, α = {ALPHA}, μ = {MU}; MC samples h ∝ D(h)(n·h)"),
            Kind::SplitSum => "A = ∫ (1 − Fc) f cos, B = ∫ Fc f cos (max error of the two), same model and point; MC samples h ∝ D(h)(n·h)".to_string(),
            Kind::Cloth => format!("∫ D_Charlie V_Ashikhmin (n·l) dω_l, α = {ALPHA}, μ = {MU}; MC samples l uniformly (as cmgen does for cloth)"),
            Kind::AlbedoAvg => format!("E_avg = 2∫ E(μ) μ dμ, GGX + height-correlated Smith, α = {ALPHA}; MC: 3D Hammersley, μ ∝ 2μ, h ∝ D(h)(n·h)"),
            Kind::G1Numeric => format!("G1(μ) of the Gaussian NDF (m = {GAUSS_M}), μ = {MU}; brdfbake: adaptive Gauss–Kronrod of the slope-space Λ integral; MC: μ / ∫(v·h)⁺ D dω_h with h from GGX(α = m)"),
        }
    }

    /// Number of channels of the kind's value.
    pub fn channels(self) -> usize {
        if self == Kind::SplitSum {
            2
        } else {
            1
        }
    }
}

fn ggx() -> Specular {
    Specular {
        ndf: Ndf::new(NdfKind::Ggx, ALPHA).expect("valid alpha"),
        masking: Masking::SmithHeightCorrelated,
        fresnel: Fresnel::None,
    }
}

fn sheen() -> Specular {
    Specular {
        ndf: Ndf::new(NdfKind::Charlie, ALPHA).expect("valid alpha"),
        masking: Masking::Ashikhmin,
        fresnel: Fresnel::None,
    }
}

fn gaussian() -> Ndf {
    Ndf::new(NdfKind::Gaussian, GAUSS_M).expect("valid m")
}

/// Smith G1 of `ndf` by brdfbake's formula (the slope-space integral of [`Ndf::g1_numeric`],
/// Heitz 2014 eq. 72, with the substitution θm = θ0 + (π/2 − θ0)w²) integrated by adaptive
/// G7/K15 at absolute tolerance `tol` on μ̃Λ. Returns (G1, evaluations).
pub fn g1_by_quadrature(ndf: &Ndf, mu: f64, tol: f64) -> (f64, u64) {
    let cot = mu / (1.0 - mu * mu).sqrt();
    let th0 = cot.atan();
    let span = FRAC_PI_2 - th0;
    let evals = std::cell::Cell::new(0u64);
    let (mu_lambda, _) = integrate1(
        |w| {
            evals.set(evals.get() + 1);
            let th = th0 + span * w * w;
            let (s, c) = th.sin_cos();
            let d = ndf.d_cs(c.max(0.0), s * s);
            if c <= 0.0 {
                return 2.0 * d * s * s * 2.0 * span * w;
            }
            let r = s / c;
            let bracket = (r * r - cot * cot).max(0.0).sqrt() - cot * (cot / r).min(1.0).acos();
            2.0 * d * c * s * bracket * 2.0 * span * w
        },
        0.0,
        1.0,
        Tolerance {
            abs: tol,
            initial_panels: 8,
            max_depth: 40,
            ..Default::default()
        },
    );
    (cot / (cot + mu_lambda.max(0.0)), evals.get())
}

/// brdfbake's method at tolerance `tol`: (value per channel, evaluations).
pub fn adaptive(kind: Kind, tol: f64) -> (Vec<f64>, u64) {
    match kind {
        Kind::Albedo => {
            let b = Brdf {
                specular: Some(ggx()),
                diffuse_weight: 0.0,
                diffuse: crate::model::DiffuseLobe::Lambert,
            };
            let (v, _, n) = directional_albedo(&b, MU, tol);
            (v.to_vec(), n)
        }
        Kind::SplitSum => {
            let (v, _, n) = split_sum(&ggx(), MU, tol);
            (v.to_vec(), n)
        }
        Kind::Cloth => {
            let (v, _, n) = sheen_albedo(ALPHA, MU, tol);
            (vec![v], n)
        }
        Kind::AlbedoAvg => {
            let b = Brdf {
                specular: Some(ggx()),
                diffuse_weight: 0.0,
                diffuse: crate::model::DiffuseLobe::Lambert,
            };
            let (v, _, n) = average_albedo(&b, tol);
            (vec![v], n)
        }
        Kind::G1Numeric => {
            let (g, n) = g1_by_quadrature(&gaussian(), MU, tol);
            (vec![g], n)
        }
    }
}

/// Monte Carlo on the `n`-point Hammersley set: (unbiased values, biased values,
/// evaluations).
pub fn monte_carlo(kind: Kind, n: u64) -> (Vec<f64>, Vec<f64>, u64) {
    let gs = Sampling::Ndf(NdfKind::Ggx, ALPHA);
    match kind {
        Kind::Albedo => {
            let s = ggx();
            let e = mc::estimate_over_l(MU, gs, n, |nd| [s.cosine_weighted(nd)]);
            (e.unbiased.to_vec(), e.biased.to_vec(), e.samples)
        }
        Kind::SplitSum => {
            let s = ggx();
            let e = mc::estimate_over_l(MU, gs, n, |nd| {
                let f = s.cosine_weighted_with(nd, 1.0);
                let fc = schlick_weight(nd.v_dot_h);
                [f * (1.0 - fc), f * fc]
            });
            (e.unbiased.to_vec(), e.biased.to_vec(), e.samples)
        }
        Kind::Cloth => {
            let s = sheen();
            let e = mc::estimate_over_l(MU, Sampling::Uniform, n, |nd| [s.cosine_weighted(nd)]);
            (e.unbiased.to_vec(), e.biased.to_vec(), e.samples)
        }
        Kind::AlbedoAvg => {
            let s = ggx();
            // the integrand of E_avg per (μ, l) sample is f cos (the density 2μ of μ
            // carries the weight 2μ of the definition)
            let e = mc::estimate_average(gs, n, |nd| s.cosine_weighted(nd));
            (e.unbiased.to_vec(), e.biased.to_vec(), e.samples)
        }
        Kind::G1Numeric => {
            let g = gaussian();
            let p = Ndf::new(NdfKind::Ggx, GAUSS_M).expect("valid alpha");
            let e = mc::estimate_projected_area(&g, &p, MU, n);
            let to_g1 = |a: f64| MU / a.max(f64::MIN_POSITIVE);
            (
                vec![to_g1(e.unbiased[0])],
                vec![to_g1(e.biased[0])],
                e.samples,
            )
        }
    }
}

/// One point of a convergence curve.
#[derive(Clone, Debug)]
pub struct Row {
    /// "brdfbake", "MC Hammersley (÷ N)" or "MC Hammersley (÷ valid, biased)".
    pub method: &'static str,
    /// The tolerance or the sample count.
    pub setting: String,
    pub evals: u64,
    /// max over channels of |value − reference|.
    pub error: f64,
}

/// brdfbake's own methods for the integral (the table path: kernels, the tensor rule, the
/// adaptive integrator, as `table::methods` orders them).
pub const ADAPTIVE: &str = "brdfbake";
pub const MC_UNBIASED: &str = "MC Hammersley (÷ N)";
pub const MC_BIASED: &str = "MC Hammersley (÷ valid, biased)";

fn max_err(v: &[f64], r: &[f64]) -> f64 {
    v.iter()
        .zip(r)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// The study of one kind: brdfbake at each tolerance of `tols`, Monte Carlo at each count
/// of `counts`, errors against `reference` (one value per channel).
pub fn study(kind: Kind, reference: &[f64], tols: &[f64], counts: &[u64]) -> Vec<Row> {
    let mut rows = Vec::new();
    for &t in tols {
        let (v, n) = adaptive(kind, t);
        rows.push(Row {
            method: ADAPTIVE,
            setting: format!("tol {t:.0e}"),
            evals: n,
            error: max_err(&v, reference),
        });
    }
    let mut biased = Vec::new();
    for &n in counts {
        let (u, b, e) = monte_carlo(kind, n);
        rows.push(Row {
            method: MC_UNBIASED,
            setting: format!("N = {n}"),
            evals: e,
            error: max_err(&u, reference),
        });
        biased.push(Row {
            method: MC_BIASED,
            setting: format!("N = {n}"),
            evals: e,
            error: max_err(&b, reference),
        });
    }
    rows.extend(biased);
    rows
}

/// The report's reference: brdfbake at [`library_reference_tol`].
pub fn library_reference(kind: Kind) -> Vec<f64> {
    adaptive(kind, library_reference_tol(kind)).0
}

/// The markdown table of one kind's study.
pub fn markdown(kind: Kind, reference: &[f64], rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "#### {}\n\n{}.\n", kind.name(), kind.description());
    let refs: Vec<String> = reference.iter().map(|v| format!("{v:.15}")).collect();
    let _ = writeln!(s, "Reference value: {}\n", refs.join(", "));
    let _ = writeln!(s, "| method | setting | evaluations | max abs error |");
    let _ = writeln!(s, "|---|---|---:|---:|");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2e} |",
            r.method, r.setting, r.evals, r.error
        );
    }
    s
}

/// Errors below this are drawn at it (log scale; a zero error has no logarithm).
const ERROR_FLOOR: f64 = 1e-17;

/// A log-log plot (integrand evaluations against |error|) of one kind's study.
pub fn plot(kind: Kind, rows: &[Row]) -> String {
    let series = [
        (ADAPTIVE, "#1f77b4", false),
        (MC_UNBIASED, "#d62728", false),
        (MC_BIASED, "#ff7f0e", true),
    ]
    .iter()
    .map(|&(m, colour, dashed)| Series {
        label: m.to_string(),
        points: rows
            .iter()
            .filter(|r| r.method == m && r.evals > 0)
            .map(|r| ((r.evals as f64).log10(), r.error.max(ERROR_FLOOR).log10()))
            .collect(),
        colour: colour.to_string(),
        dashed,
    })
    .collect::<Vec<_>>();
    // (log₁₀ x, log₁₀ y) points: whole decades on both axes, a marker at every point
    super::svg::plot(
        &format!("convergence: {}", kind.name()),
        "integrand evaluations",
        "|error|",
        &series,
        super::svg::Scale::LogLog,
    )
}

/// Tolerances and sample counts the report uses (kept small: the report is rendered in
/// the test suite). E_avg stops at 1e-6 ([`report_tols`]): below, its nested quadrature
/// costs 10⁵–10⁷ evaluations, too slow for a page rendered in the tests.
pub const REPORT_TOLS: [f64; 6] = [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12];

/// The tolerances the report sweeps for `kind`.
pub fn report_tols(kind: Kind) -> &'static [f64] {
    if kind == Kind::AlbedoAvg {
        &REPORT_TOLS[..3]
    } else {
        &REPORT_TOLS
    }
}
pub const REPORT_COUNTS: [u64; 6] = [16, 64, 256, 1024, 4096, 16384];

/// The report's convergence section: one log-log plot per kind.
pub fn section(out: &mut super::Page) {
    out.section("Convergence: brdfbake's quadrature vs Monte Carlo");
    let _ = writeln!(
        out,
        "<p>Error against integrand evaluations for each integral kind, at one point each: \
         brdfbake's quadrature (the methods its tables use) over a sweep of tolerances ({}), and \
         importance-sampled Monte Carlo on Hammersley points ({} samples), unbiased (÷ N) and \
         in the biased variant that divides by the number of valid samples (its error stops \
         falling). Errors below 1e-17 (or exactly 0) are drawn at 1e-17. Reference: brdfbake at tolerance {:.0e} (E_avg: {:.0e}, and its sweep stops at \
         1e-6; self-convergence; \
         <code>cargo run --release --example convergence</code> measures against the \
         independent reference integrator of the test suite).</p><ul>",
        REPORT_TOLS
            .iter()
            .map(|t| format!("{t:.0e}"))
            .collect::<Vec<_>>()
            .join(", "),
        REPORT_COUNTS
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        LIBRARY_REFERENCE_TOL,
        LIBRARY_REFERENCE_TOL_AVG
    );
    for k in KINDS {
        let _ = writeln!(
            out,
            "<li>{}: {}</li>",
            super::esc(k.name()),
            super::esc(&k.description())
        );
    }
    let _ = writeln!(out, "</ul><div class=\"row\">");
    for k in KINDS {
        let r = library_reference(k);
        let rows = study(k, &r, report_tols(k), &REPORT_COUNTS);
        out.push_str(&plot(k, &rows));
    }
    let _ = writeln!(out, "</div>");
    out.end_section();
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The study's claims, checked on its own numbers: for every kind brdfbake's quadrature
    /// at tolerance 1e-8 is within 1e-8 of the library reference (its error estimate is an
    /// upper bound) plus the reference's own tolerance, and Monte Carlo with at least as many evaluations (the next power of
    /// two) has a larger error; Monte Carlo converges (its error at that count is below its
    /// error at 16 samples).
    #[test]
    fn quadrature_beats_monte_carlo() {
        for k in KINDS {
            let r = library_reference(k);
            let ad = study(k, &r, &[1e-8], &[]).remove(0);
            let n = ad.evals.next_power_of_two();
            let rows = study(k, &r, &[], &[16, n]);
            let (mc16, mc_big) = (&rows[0], &rows[1]);
            assert!(ad.error <= 1e-8 + library_reference_tol(k), "{k:?}: {ad:?}");
            assert!(mc_big.error > ad.error, "{k:?}: {ad:?} {mc_big:?}");
            assert!(mc_big.error < mc16.error, "{k:?}: {mc16:?} {mc_big:?}");
        }
    }
}
