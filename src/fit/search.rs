//! The search over forms: for each set of variables, minimax polynomials of growing
//! supports (every downward-closed support of degree ≤ 3 at the cheap end, then total
//! degrees), piecewise polynomials on 2ⁿ…4ⁿ cells, and for cosine axes the exponential
//! warp 2^(kμ) with k chosen by golden section. Each candidate's error is the max over the
//! validation set of its f32-coefficient polynomial, its cost the operation count of its
//! program; [`pareto`] keeps the candidates no other beats in both.
//!
//! Deterministic: the candidates are tried in a fixed order, each by the sequential
//! exchange algorithm; rayon only decides which thread fits which (channel, support) pair,
//! and the results are collected in order.

use super::form::{ChannelPoly, Fitted, Form};
use super::target::Target;
use super::vars::{self, Var, VarSet, Warp};
use crate::approx::poly::Support;
use crate::approx::polyfit;
use crate::approx::program::OpCount;
use rayon::prelude::*;

pub use super::request::Weight;

/// The floor of the relative weight, as a fraction of the channel's largest |value|.
pub const RELATIVE_FLOOR: f64 = 1e-3;

/// One candidate fit with its measured error and cost.
#[derive(Clone, Debug)]
pub struct Candidate {
    pub fitted: Fitted,
    /// Per channel, the max weighted error over the validation set (f64 evaluation).
    pub error: Vec<f64>,
    /// Per channel, the f32 evaluation bound ([`Fitted::f32_bound`]).
    pub f32_bound: Vec<f64>,
    pub counts: OpCount,
    pub description: String,
}

impl Candidate {
    /// The largest channel error.
    pub fn max_error(&self) -> f64 {
        self.error.iter().cloned().fold(0.0, f64::max)
    }

    /// The largest channel error plus its f32 bound: what the code can be off by.
    pub fn max_total(&self) -> f64 {
        self.error
            .iter()
            .zip(&self.f32_bound)
            .map(|(e, b)| e + b)
            .fold(0.0, f64::max)
    }
}

/// How far the search goes.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Highest total degree of a global polynomial, by variable count (1, 2, 3).
    pub degree: [usize; 3],
    /// Largest cell count per variable of a piecewise fit.
    pub cells: usize,
    /// Skip supports whose error cannot matter: stop raising the degree of a channel once
    /// its error is below this.
    pub floor: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            degree: [16, 10, 5],
            cells: 4,
            floor: 1e-6,
        }
    }
}

/// The clamped coordinates of every validation point.
pub fn points(target: &Target) -> Vec<Vec<f64>> {
    (0..target.points())
        .map(|i| vars::clamp_inputs(&target.inputs, &target.point(i)))
        .collect()
}

/// Per channel, the weights of `weight` (`None`: absolute).
pub fn weights(target: &Target, weight: Weight) -> Vec<Option<Vec<f64>>> {
    target
        .values
        .iter()
        .map(|v| match weight {
            Weight::Absolute => None,
            Weight::Relative => {
                let big = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let floor = (RELATIVE_FLOOR * big).max(f64::MIN_POSITIVE);
                Some(v.iter().map(|x| x.abs().max(floor)).collect())
            }
        })
        .collect()
}

/// Every candidate worth comparing (see the module doc), then [`pareto`] of them.
pub fn search(
    target: &Target,
    weight: Weight,
    corner: bool,
    limits: &Limits,
    stop: &(dyn Fn() -> bool + Sync),
) -> Vec<Candidate> {
    let pts = points(target);
    let w = weights(target, weight);
    let nv = target.inputs.len();
    let mut sets = vars::candidates(&target.inputs, corner);
    // 2^(kμ) for the cosine axis, k by golden section on a cheap support
    if let Some(mu) = target
        .inputs
        .iter()
        .position(|i| i.quantity == crate::lut::Quantity::Cosine)
    {
        if let Some(rate) = best_rate(target, &pts, &w, mu) {
            let mut s: Vec<Var> = (0..nv)
                .map(|k| Var::Axis {
                    axis: k,
                    warp: Warp::Linear,
                })
                .collect();
            s[mu] = Var::Axis {
                axis: mu,
                warp: Warp::Exp2 { rate },
            };
            sets.push(s);
        }
    }
    let supports = supports(nv, limits);
    let mut out = Vec::new();
    // the cheapest forms: sparse, in the raw exponential variable and roughness
    if let Some(Var::Axis {
        axis: mu,
        warp: Warp::Exp2 { rate },
    }) = sets.last().and_then(|s| {
        s.iter()
            .find(|v| {
                matches!(
                    v,
                    Var::Axis {
                        warp: Warp::Exp2 { .. },
                        ..
                    }
                )
            })
            .copied()
    }) {
        let rough = (0..nv).find(|&k| k != mu);
        if let (2, Some(rough), false) = (nv, rough, stop()) {
            out.extend(sparse(target, &pts, &w, mu, rough, rate, stop));
        }
    }
    for vs in &sets {
        if stop() {
            break;
        }
        out.extend(polynomials(target, &pts, &w, vs, &supports, limits, stop));
    }
    // piecewise: on the last (richest) set of variables that is not the exponential one
    if nv <= 2 && !stop() {
        let vs = sets
            .iter()
            .rev()
            .find(|s| {
                !s.iter().any(|v| {
                    matches!(
                        v,
                        Var::Axis {
                            warp: Warp::Exp2 { .. },
                            ..
                        }
                    )
                })
            })
            .expect("the linear set");
        out.extend(piecewise(target, &pts, &w, vs, limits, stop));
    }
    pareto(out)
}

/// Most monomials besides the constant in a sparse support ([`sparse`]).
const SPARSE_TERMS: usize = 5;
/// Supports per channel and Horner cost kept from the coarse ranking for the full fit.
const SPARSE_KEEP: usize = 3;
/// Points of the coarse ranking (every n-th validation point).
const SPARSE_COARSE: usize = 4000;

/// Sparse polynomials in the raw variables e = 2^(kμ) and r (both in [0, 1]: no maps onto
/// [−1, 1], which cost an operation each) and, where a support uses it, s = r² computed once
/// for every channel — the forms whose terms a shader shares, the cheap end of the front
/// (A = c₀ + c₁r² + e(c₂ + c₃r + c₄r² + c₅e) and B = c₀ + e(c₁ + c₂r + c₃r²) cost 11
/// operations together with e and s). Supports: the constant and 1 to [`SPARSE_TERMS`]
/// monomials eⁱrʲsᵏ (i ≤ 2, j, k ≤ 1; [`Support::sparse`]), ranked per channel on every
/// n-th point ([`SPARSE_COARSE`] of them), the best [`SPARSE_KEEP`] per Horner cost fitted
/// on all points; every pair of the channels' fronts is a candidate.
fn sparse(
    target: &Target,
    pts: &[Vec<f64>],
    w: &[Option<Vec<f64>>],
    mu: usize,
    rough: usize,
    rate: f32,
    stop: &(dyn Fn() -> bool + Sync),
) -> Vec<Candidate> {
    let nc = target.values.len();
    if nc > 2 {
        return Vec::new();
    }
    let var3 = vec![
        Var::Axis {
            axis: mu,
            warp: Warp::Exp2 { rate },
        },
        Var::Axis {
            axis: rough,
            warp: Warp::Linear,
        },
        Var::Axis {
            axis: rough,
            warp: Warp::Square,
        },
    ];
    let vs3 = VarSet {
        vars: var3.clone(),
        maps: vec![(1.0, 0.0); 3],
    };
    let t: Vec<Vec<f64>> = pts.iter().map(|x| vs3.eval(x)).collect();
    // the supports, in a fixed order
    let monos: Vec<Vec<u8>> = (0..=2u8)
        .flat_map(|i| (0..=1u8).flat_map(move |j| (0..=1u8).map(move |k| vec![i, j, k])))
        .filter(|e| e.iter().any(|&x| x > 0))
        .collect();
    let mut supports: Vec<Support> = Vec::new();
    let mut pick: Vec<usize> = Vec::new();
    fn grow(monos: &[Vec<u8>], from: usize, pick: &mut Vec<usize>, out: &mut Vec<Support>) {
        if !pick.is_empty() {
            let mut e: Vec<Vec<u8>> = pick.iter().map(|&i| monos[i].clone()).collect();
            e.push(vec![0, 0, 0]);
            if let Some(s) = Support::sparse(3, e) {
                out.push(s);
            }
        }
        if pick.len() == SPARSE_TERMS {
            return;
        }
        for i in from..monos.len() {
            pick.push(i);
            grow(monos, i + 1, pick, out);
            pick.pop();
        }
    }
    grow(&monos, 0, &mut pick, &mut supports);
    let step = (t.len() / SPARSE_COARSE).max(1);
    let coarse: Vec<usize> = (0..t.len()).step_by(step).collect();
    let tc: Vec<Vec<f64>> = coarse.iter().map(|&i| t[i].clone()).collect();
    let per: Vec<Vec<polyfit::PolyFit>> = (0..nc)
        .map(|c| {
            let f = &target.values[c];
            let fc: Vec<f64> = coarse.iter().map(|&i| f[i]).collect();
            let wc: Option<Vec<f64>> = w[c]
                .as_ref()
                .map(|w| coarse.iter().map(|&i| w[i]).collect());
            let ranked: Vec<(usize, f64)> = supports
                .par_iter()
                .enumerate()
                .map(|(k, s)| {
                    if stop() {
                        return (k, f64::INFINITY);
                    }
                    let e = polyfit::fit(s, &tc, &fc, wc.as_deref())
                        .map_or(f64::INFINITY, |r| r.max_error);
                    (k, e)
                })
                .collect();
            // the best few per Horner cost, in a fixed order
            let mut by_cost: std::collections::BTreeMap<usize, Vec<(f64, usize)>> =
                Default::default();
            for (k, e) in ranked {
                if e.is_finite() {
                    by_cost
                        .entry(supports[k].horner_cost())
                        .or_default()
                        .push((e, k));
                }
            }
            let kept: Vec<usize> = by_cost
                .into_values()
                .flat_map(|mut v| {
                    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                    v.into_iter().take(SPARSE_KEEP).map(|(_, k)| k)
                })
                .collect();
            let mut fits: Vec<polyfit::PolyFit> = kept
                .par_iter()
                .filter_map(|&k| {
                    if stop() {
                        return None;
                    }
                    polyfit::fit(&supports[k], &t, f, w[c].as_deref()).ok()
                })
                .collect();
            fits.sort_by(|a, b| {
                a.support
                    .horner_cost()
                    .cmp(&b.support.horner_cost())
                    .then(a.max_error.total_cmp(&b.max_error))
            });
            let mut front: Vec<polyfit::PolyFit> = Vec::new();
            for f in fits {
                if front.last().is_none_or(|l| f.max_error < l.max_error) {
                    front.push(f);
                }
            }
            front
        })
        .collect();
    if stop() || per.iter().any(|p| p.is_empty()) {
        return Vec::new();
    }
    let combos: Vec<Vec<usize>> = if nc == 1 {
        (0..per[0].len()).map(|i| vec![i]).collect()
    } else {
        (0..per[0].len())
            .flat_map(|i| (0..per[1].len()).map(move |j| vec![i, j]))
            .collect()
    };
    let mut out = Vec::new();
    for combo in combos {
        let fits: Vec<&polyfit::PolyFit> =
            combo.iter().enumerate().map(|(c, &j)| &per[c][j]).collect();
        // without s in any channel: the two-variable set (no r² computed)
        let uses_s = fits
            .iter()
            .any(|f| f.support.exponents().iter().any(|e| e[2] > 0));
        let (vs, keep) = if uses_s {
            (vs3.clone(), 3)
        } else {
            (
                VarSet {
                    vars: var3[..2].to_vec(),
                    maps: vec![(1.0, 0.0); 2],
                },
                2,
            )
        };
        let polys: Vec<ChannelPoly> = fits
            .iter()
            .map(|f| ChannelPoly {
                exponents: f
                    .support
                    .exponents()
                    .iter()
                    .map(|e| e[..keep].to_vec())
                    .collect(),
                coef: f.coef.iter().map(|&v| v as f32).collect(),
            })
            .collect();
        let fitted = Fitted {
            vars: vs,
            form: Form::Polynomial { channels: polys },
        };
        let error = fits.iter().map(|f| f.max_error).collect();
        out.push(candidate(target, fitted, error, pts, w, &target.channels));
    }
    pareto(out)
}

/// The supports tried for `nv` variables: at the cheap end every downward-closed support of
/// degree ≤ 3 (two variables) costing at most 5 operations, then total degrees.
fn supports(nv: usize, limits: &Limits) -> Vec<Support> {
    let dmax = limits.degree[nv.clamp(1, 3) - 1];
    let mut v: Vec<Support> = if nv == 2 {
        Support::all_closed(2, 3, 5)
    } else {
        Vec::new()
    };
    for d in 1..=dmax {
        let s = Support::total_degree(nv, d);
        if !v.contains(&s) {
            v.push(s);
        }
    }
    v
}

/// The best rate k of 2^(kμ) ∈ [−24, −1] for a total-degree-2 polynomial (the cheapest
/// form where the warp matters), by golden section on every 4th point.
fn best_rate(target: &Target, pts: &[Vec<f64>], w: &[Option<Vec<f64>>], mu: usize) -> Option<f32> {
    let nv = target.inputs.len();
    let s = Support::total_degree(nv, 2);
    let sub: Vec<usize> = (0..pts.len()).step_by(4).collect();
    let sp: Vec<Vec<f64>> = sub.iter().map(|&i| pts[i].clone()).collect();
    let err = |k: f64| -> f64 {
        let mut vars: Vec<Var> = (0..nv)
            .map(|a| Var::Axis {
                axis: a,
                warp: Warp::Linear,
            })
            .collect();
        vars[mu] = Var::Axis {
            axis: mu,
            warp: Warp::Exp2 { rate: k as f32 },
        };
        let vs = VarSet::map_to(vars, &sp, -1.0, 1.0);
        let t: Vec<Vec<f64>> = sp.iter().map(|x| vs.eval(x)).collect();
        (0..target.values.len())
            .map(|c| {
                let f: Vec<f64> = sub.iter().map(|&i| target.values[c][i]).collect();
                let wc: Option<Vec<f64>> =
                    w[c].as_ref().map(|w| sub.iter().map(|&i| w[i]).collect());
                polyfit::fit(&s, &t, &f, wc.as_deref()).map_or(f64::INFINITY, |r| r.max_error)
            })
            .fold(0.0, f64::max)
    };
    let (k, e) = polyfit::golden_min(err, -24.0, -1.0, 0.05);
    e.is_finite().then_some((k * 100.0).round() as f32 / 100.0)
}

/// Per channel, the fits of every support; then every combination of per-channel
/// choices on the channels' own Pareto fronts.
fn polynomials(
    target: &Target,
    pts: &[Vec<f64>],
    w: &[Option<Vec<f64>>],
    vars: &[Var],
    supports: &[Support],
    limits: &Limits,
    stop: &(dyn Fn() -> bool + Sync),
) -> Vec<Candidate> {
    let vs = VarSet::map_to(vars.to_vec(), pts, -1.0, 1.0);
    let t: Vec<Vec<f64>> = pts.iter().map(|x| vs.eval(x)).collect();
    let nc = target.values.len();
    // per channel: (support index, fit); degrees stop rising once a channel is at the floor
    let per: Vec<Vec<(usize, polyfit::PolyFit)>> = (0..nc)
        .into_par_iter()
        .map(|c| {
            let mut fits: Vec<(usize, polyfit::PolyFit)> = Vec::new();
            let mut best = f64::INFINITY;
            for (k, s) in supports.iter().enumerate() {
                if stop() || best < limits.floor {
                    break;
                }
                if let Ok(r) = polyfit::fit(s, &t, &target.values[c], w[c].as_deref()) {
                    best = best.min(r.max_error);
                    fits.push((k, r));
                }
            }
            // this channel's own front: cost up, error down
            fits.sort_by_key(|(k, _)| (supports[*k].horner_cost(), *k));
            let mut front: Vec<(usize, polyfit::PolyFit)> = Vec::new();
            for f in fits {
                if front.last().is_none_or(|l| f.1.max_error < l.1.max_error) {
                    front.push(f);
                }
            }
            front
        })
        .collect();
    if per.iter().any(|p| p.is_empty()) {
        return Vec::new();
    }
    // combinations (for more than two channels: the same support index everywhere)
    let mut combos: Vec<Vec<usize>> = Vec::new();
    if nc <= 2 {
        let mut idx = vec![0usize; nc];
        loop {
            combos.push(idx.clone());
            let mut k = 0;
            loop {
                if k == nc {
                    break;
                }
                idx[k] += 1;
                if idx[k] < per[k].len() {
                    break;
                }
                idx[k] = 0;
                k += 1;
            }
            if k == nc {
                break;
            }
        }
    } else {
        for j in 0..per[0].len() {
            let k = per[0][j].0;
            let pos: Option<Vec<usize>> = per
                .iter()
                .map(|p| p.iter().position(|(s, _)| *s == k))
                .collect();
            if let Some(p) = pos {
                combos.push(p);
            }
        }
    }
    let channels = &target.channels;
    let mut out = Vec::new();
    for combo in combos {
        let polys: Vec<ChannelPoly> = combo
            .iter()
            .enumerate()
            .map(|(c, &j)| {
                let f = &per[c][j].1;
                ChannelPoly {
                    exponents: f.support.exponents().to_vec(),
                    coef: f.coef.iter().map(|&v| v as f32).collect(),
                }
            })
            .collect();
        let fitted = Fitted {
            vars: vs.clone(),
            form: Form::Polynomial { channels: polys },
        };
        let error = combo
            .iter()
            .enumerate()
            .map(|(c, &j)| per[c][j].1.max_error)
            .collect();
        out.push(candidate(target, fitted, error, pts, w, channels));
    }
    pareto(out)
}

/// One global polynomial of total degree `degree` per channel in the variables `vars`
/// (no search): the building block of [`search`], public for tests and callers that know
/// the form they want.
pub fn fit_polynomial(
    target: &Target,
    weight: Weight,
    vars: &[Var],
    degree: usize,
) -> Option<Candidate> {
    let pts = points(target);
    let w = weights(target, weight);
    let s = [Support::total_degree(vars.len(), degree)];
    let limits = Limits {
        floor: 0.0,
        ..Limits::default()
    };
    polynomials(target, &pts, &w, vars, &s, &limits, &|| false)
        .into_iter()
        .next()
}

fn candidate(
    target: &Target,
    fitted: Fitted,
    error: Vec<f64>,
    pts: &[Vec<f64>],
    w: &[Option<Vec<f64>>],
    channels: &[String],
) -> Candidate {
    // the error between the grid's points: the larger of the two sets' (weighted as on the
    // grid: a relative weight's floor is the grid's smallest weight)
    let program = fitted.program(&target.inputs, channels);
    let floors: Vec<Option<f64>> = w
        .iter()
        .map(|ws| {
            ws.as_ref()
                .map(|ws| ws.iter().copied().fold(f64::INFINITY, f64::min))
        })
        .collect();
    let mut error = error;
    for (x, exact) in target.check.iter().zip(&target.check_values) {
        let y = program.eval(&vars::clamp_inputs(&target.inputs, x));
        for (c, e) in error.iter_mut().enumerate() {
            let scale = floors[c].map_or(1.0, |f| exact[c].abs().max(f));
            let d = (y[c] - exact[c]).abs() / scale;
            *e = e.max(if d.is_nan() { f64::INFINITY } else { d });
        }
    }
    let counts = fitted.counts(&target.inputs, channels);
    let f32_bound = fitted.f32_bound(pts);
    let description = fitted.describe(&target.inputs);
    Candidate {
        fitted,
        error,
        f32_bound,
        counts,
        description,
    }
}

/// Piecewise polynomials on k × k cells (k = 2…limits.cells) of degrees 3 to 8.
fn piecewise(
    target: &Target,
    pts: &[Vec<f64>],
    w: &[Option<Vec<f64>>],
    vars: &[Var],
    limits: &Limits,
    stop: &(dyn Fn() -> bool + Sync),
) -> Vec<Candidate> {
    let nv = vars.len();
    let vs = VarSet::map_to(vars.to_vec(), pts, 0.0, 1.0);
    let mut x: Vec<Vec<f64>> = pts.iter().map(|p| vs.eval(p)).collect();
    // fitted on the check set too (absolute error): a cell's polynomial in the corner
    // variables can swing between the grid's points at grazing views, where the check set
    // has a quarter of its points; each is a point the fit must hold
    let absolute = w.iter().all(|w| w.is_none());
    let mut values: Vec<Vec<f64>> = target.values.clone();
    if absolute {
        for (p, exact) in target.check.iter().zip(&target.check_values) {
            x.push(vs.eval(&vars::clamp_inputs(&target.inputs, p)));
            for (c, v) in values.iter_mut().enumerate() {
                v.push(exact[c]);
            }
        }
    }
    // one grid step of the validation set, in [0, 1] units, as the cells' overlap
    let margin = 1.0 / (target.shape().iter().copied().max().unwrap_or(2) - 1).max(1) as f64;
    let mut jobs = Vec::new();
    for k in 2..=limits.cells {
        for d in [3, 4, 5, 6, 8] {
            jobs.push((vec![k; nv], d));
        }
    }
    let fits: Vec<Option<Candidate>> = jobs
        .par_iter()
        .map(|(cells, d)| {
            if stop() {
                return None;
            }
            let s = Support::total_degree(nv, *d);
            let mut coef = Vec::new();
            let mut error = Vec::new();
            for (c, vals) in values.iter().enumerate() {
                let r =
                    polyfit::fit_piecewise(&s, cells, &x, vals, w[c].as_deref(), margin).ok()?;
                error.push(r.max_error);
                coef.push(
                    r.coef
                        .iter()
                        .map(|cell| cell.iter().map(|&v| v as f32).collect())
                        .collect(),
                );
            }
            let fitted = Fitted {
                vars: vs.clone(),
                form: Form::Piecewise {
                    cells: cells.clone(),
                    exponents: s.exponents().to_vec(),
                    coef,
                },
            };
            Some(candidate(target, fitted, error, pts, w, &target.channels))
        })
        .collect();
    pareto(fits.into_iter().flatten().collect())
}

/// The candidates no other beats: fewer operations (then fewer special ones, then fewer
/// constants) and a lower max error. Sorted by operations.
pub fn pareto(mut v: Vec<Candidate>) -> Vec<Candidate> {
    v.sort_by(|a, b| {
        (a.counts.ops, a.counts.special, a.counts.constants)
            .cmp(&(b.counts.ops, b.counts.special, b.counts.constants))
            .then(a.max_error().total_cmp(&b.max_error()))
    });
    let mut out: Vec<Candidate> = Vec::new();
    for c in v {
        if out
            .last()
            .is_none_or(|l| c.max_error() < l.max_error() * (1.0 - 1e-9))
        {
            out.push(c);
        }
    }
    out
}
