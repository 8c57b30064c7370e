//! BENCHMARKS.md's held-out LTC figures: brdfbake's 64² GGX table (Heitz's layout, the fit
//! `heitz-ltc` bakes) against Heitz's published `ltc.inc`, judged by the relative error of
//! the lit value on draws of the light distributions of
//! [`ltc_lights`](crate::kernels::ltc_lights): the stated one's fit draw and held-out draw,
//! `ltc_check`'s fixed set, and held-out draws of the variants that change one thing.
//!
//! `cargo run --release --example ltc_heldout -- --write` puts the table into BENCHMARKS.md;
//! `tests/ltc_heldout.rs` recomputes it and fails when the file and the command disagree.

use crate::kernels::ltc_check::{test_lights, test_roughnesses, test_views};
use crate::kernels::ltc_fit::{fit_grid, LtcFitOptions};
use crate::kernels::ltc_lights::{
    draw_cases, ground_truth, judge, Judged, LightCase, LightDistribution, CASES, FIT_SEED,
    HELD_OUT_SEED,
};
use crate::model::ltc::LtcError;
use crate::model::{Brdf, DiffuseLobe, Fresnel, Masking, Ndf, NdfKind, Specular};
use crate::table::ltc_layout::{heitz_axes, HeitzTable, HEITZ_SIZE};

/// The markers of the generated block in BENCHMARKS.md.
pub const BEGIN: &str = "<!-- begin ltc-heldout (generated: do not edit) -->";
pub const END: &str = "<!-- end ltc-heldout -->";

/// GGX with height-correlated Smith masking and no Fresnel: the BRDF the tables fit.
pub fn ggx(alpha: f64) -> Result<Brdf, String> {
    Ok(Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha)?,
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
        diffuse: DiffuseLobe::Lambert,
    })
}

/// One judged light set: its name, and the two tables' errors on it.
#[derive(Clone, Debug)]
pub struct HeldOutRow {
    pub set: String,
    pub ours: Judged,
    pub heitz: Judged,
}

/// `ltc_check`'s fixed set as cases: 200 lights × 10 views × 10 roughnesses.
pub fn fixed_cases() -> Vec<LightCase> {
    let mut v = Vec::new();
    for light in &test_lights() {
        for &mu in &test_views() {
            for &r in &test_roughnesses() {
                v.push(LightCase {
                    light: light.clone(),
                    mu,
                    r,
                });
            }
        }
    }
    v
}

/// Fits brdfbake's table with `opts` and judges it and Heitz's (`heitz_inc`: the text of
/// his `ltc.inc`) on every light set (module doc), in the order printed.
pub fn held_out_rows(heitz_inc: &str, opts: &LtcFitOptions) -> Result<Vec<HeldOutRow>, LtcError> {
    let (mus, alphas) = heitz_axes(HEITZ_SIZE);
    let grid = fit_grid(&ggx, &mus, &alphas, opts)?;
    let ours = HeitzTable::from_grid(&grid)?;
    let heitz = HeitzTable::from_inc(heitz_inc)?;
    let stated = LightDistribution::STATED;
    let mut sets = vec![
        (
            format!("{}, fit draw (seed {FIT_SEED})", stated.name),
            draw_cases(&stated, FIT_SEED, CASES),
        ),
        (
            format!("{}, held-out draw (seed {HELD_OUT_SEED})", stated.name),
            draw_cases(&stated, HELD_OUT_SEED, CASES),
        ),
        ("`ltc_check` set".to_string(), fixed_cases()),
    ];
    for d in &LightDistribution::ALL[1..] {
        sets.push((
            format!("{}, held-out draw", d.name),
            draw_cases(d, HELD_OUT_SEED, CASES),
        ));
    }
    let mut rows = Vec::new();
    for (set, cases) in sets {
        let truth = ground_truth(&cases, &ggx)?;
        let judged = |t: &HeitzTable| {
            judge(&cases, &truth, &|mu, r| {
                let (l, n, _) = t.ltc_at(mu, r)?;
                Ok((l, n))
            })
        };
        rows.push(HeldOutRow {
            set,
            ours: judged(&ours)?,
            heitz: judged(&heitz)?,
        });
    }
    Ok(rows)
}

/// The rows as BENCHMARKS.md's table, between [`BEGIN`] and [`END`].
pub fn markdown(rows: &[HeldOutRow]) -> String {
    let mut s = format!("{BEGIN}\n| light set | table | median | p90 | p99 | max | zeros | mirror cases | mirror median | mirror p99 | mirror max |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for r in rows {
        for (name, j) in [("brdfbake", &r.ours), ("Heitz `ltc.inc`", &r.heitz)] {
            s += &format!(
                "| {} | {name} | {:.4} | {:.4} | {:.3} | {:.3e} | {:.1}% | {} | {:.4} | {:.3} | {:.3} |\n",
                r.set,
                j.all.median,
                j.all.p90,
                j.all.p99,
                j.all.max,
                100.0 * j.all.zeros,
                j.mirror.count,
                j.mirror.median,
                j.mirror.p99,
                j.mirror.max
            );
        }
    }
    s + END
}
