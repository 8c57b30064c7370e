//! `dielectric-albedo-avg`: the average albedo E_avg = 2∫₀¹ (R + T)(μ) μ dμ of a rough
//! dielectric interface over (roughness; η), 2D (Cycles' `glass_Eavg`, `glass_inv_Eavg`), by
//! the three-dimensional micro-normal integral of
//! [`crate::kernels::dielectric_average`]. A column of the table (one roughness, every η)
//! is one task: its η ≥ 1 texels share rules, up to [`GROUP`] at a time.

use super::{TableSpec, TexelResult};
use crate::kernels::dielectric_average::average_albedo;
use crate::model::{Ndf, NdfKind};

/// Most η ≥ 1 texels of one column integrated as the channels of one rule.
pub const GROUP: usize = 8;

/// The texels of column `i` (roughness texel i, every η in slice order): the η ≥ 1 ones in
/// groups of up to [`GROUP`] consecutive texels, each η < 1 alone; evaluations counted at
/// each group's first texel.
fn column(ndf: &Ndf, spec: &TableSpec, etas: &[f64]) -> Vec<TexelResult> {
    let smith = super::dielectric::smith_of(spec);
    let tol = spec.tolerance;
    let groups = super::dielectric::fibre_groups_of(etas, &vec![0.0; etas.len()], GROUP);
    let mut out = vec![TexelResult::exact(vec![0.0]); etas.len()];
    for g in groups {
        if let [z] = g[..] {
            // (alone, as every eta < 1 texel: one channel, not GROUP of which all but one
            // would be summed as zeros at every node: 25% of `cycles-glass-inv-eavg`)
            let e = average_albedo::<1>(ndf, smith, &[etas[z]], tol);
            out[z] = TexelResult {
                value: e.value.to_vec(),
                error: e.error.to_vec(),
                evals: e.evals,
            };
            continue;
        }
        let group: Vec<f64> = g.iter().map(|&z| etas[z]).collect();
        let e = average_albedo::<GROUP>(ndf, smith, &group, tol);
        for (j, &z) in g.iter().enumerate() {
            out[z] = TexelResult {
                value: vec![e.value[j]],
                error: vec![e.error[j]],
                evals: if j == 0 { e.evals } else { 0 },
            };
        }
    }
    out
}

fn setup(spec: &TableSpec) -> (Vec<Ndf>, Vec<f64>) {
    let kind = spec.model.ndf.unwrap_or(NdfKind::Ggx);
    let ndfs = (0..spec.axes[0].size)
        .map(|i| Ndf::new(kind, spec.axes[0].alpha(i).expect("roughness axis")).expect("validated"))
        .collect();
    let etas = (0..spec.axes[1].size)
        .map(|z| super::dielectric::eta_of_slice(spec, z))
        .collect();
    (ndfs, etas)
}

/// One texel alone (`readback`'s exact values).
pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let (ndfs, etas) = setup(spec);
    let spec = spec.clone();
    Box::new(move |idx| {
        column(&ndfs[idx[0]], &spec, &[etas[idx[1]]])
            .pop()
            .expect("one texel")
    })
}

/// The column path (`table::bake_with`): every η of one roughness.
pub(crate) fn column_fn(spec: &TableSpec) -> Box<dyn Fn(usize) -> Vec<TexelResult> + Sync> {
    let (ndfs, etas) = setup(spec);
    let spec = spec.clone();
    Box::new(move |i| column(&ndfs[i], &spec, &etas))
}
