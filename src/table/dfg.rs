//! `dfg`: the split-sum tables of the specular lobe with the Fresnel factored out.
//!
//! With Schlick's F = F0 + (1 − F0)·Fc, Fc = (1 − v·h)⁵, the directional albedo is linear in
//! F0: E = F0·∫(1 − Fc) f cos + ∫ Fc f cos (Karis 2013, "Real Shading in Unreal Engine 4",
//! eq. 8), with f the BRDF at F = 1. Filament stores the same information as
//! (∫ Fc f cos, ∫ f cos) so that the second channel is the single-scattering albedo used for
//! multiple-scattering compensation (Filament documentation, "Energy loss in specular
//! reflectance"), and optionally the cloth albedo ∫ D_Charlie·V_Ashikhmin·cos in the third.
//!
//! **How a table is baked.** GGX tables with Smith masking go row by row ([`by_rows`]): along
//! a row (one roughness) the split-sum pair is an analytic function of √μ, interpolated from
//! values at Chebyshev nodes ([`interp1d`]) with the interpolation's error in each texel's
//! estimate. The cloth channel is interpolated too: narrow lobes along rows in √μ, wide
//! ones along columns in √α, where their kernel shares node data between roughnesses.
//! Other models go column by column ([`column_fn`]), texel by texel.

use super::albedo::brdfs_per_roughness;
use super::{DfgLayout, TableSpec, TexelResult};
use crate::integrate::dfg_kernel::{self, Column, Smith, View};
use crate::integrate::ggx_polar;
use crate::integrate::hemisphere::{integrate_over_l, Node};
use crate::integrate::interp1d;
use crate::integrate::sheen_l;
use crate::integrate::tensor::integrate_over_l_smooth;
use crate::integrate::vgroove::{integrate_over_l_kinked, TailCut};
use crate::model::fresnel::schlick_weight;
use crate::model::{Fresnel, Masking, Ndf, NdfKind, Specular};

/// The split-sum pair at one (μ, α) with F = 1 inside `spec`: returns
/// `([∫(1−Fc) f cos, ∫ Fc f cos], errors, evaluations)`.
///
/// Smooth maskings use the fast tensor rule ([`integrate_over_l_smooth`], falling back to the
/// adaptive integrator per texel); the V-groove term, the tensor rule on its smooth branches
/// ([`integrate_over_l_kinked`], falling back to the adaptive integrator per texel).
pub fn split_sum(spec: &Specular, mu: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
    let g = |n: &Node| {
        let f = spec.cosine_weighted_with(n, 1.0);
        let fc = schlick_weight(n.v_dot_h);
        [f * (1.0 - fc), f * fc]
    };
    let e = if spec.masking == Masking::VGroove {
        // (F = 1 here, and both channels are at most f·(n·l): the tail cut holds for each)
        let tail = super::albedo::vgroove_fast_path(spec, 0.0, tol).unwrap_or(TailCut::NONE);
        integrate_over_l_kinked(mu, spec.warp(), tail, tol, g)
    } else {
        integrate_over_l_smooth(mu, Some(&spec.ndf), tol, g)
    };
    (e.value, e.error, e.evals)
}

/// [`split_sum`] by the adaptive integrator alone (the reference the fast path is tested
/// against).
pub fn split_sum_adaptive(spec: &Specular, mu: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
    let e = integrate_over_l(mu, spec.warp(), tol, |n| {
        let f = spec.cosine_weighted_with(n, 1.0);
        let fc = schlick_weight(n.v_dot_h);
        [f * (1.0 - fc), f * fc]
    });
    (e.value, e.error, e.evals)
}

/// The sheen albedo ∫ D_Charlie(α)·V_Ashikhmin·(n·l) dω_l at one (μ, α).
pub fn sheen_albedo(alpha: f64, mu: f64, tol: f64) -> (f64, f64, u64) {
    let sheen = Specular {
        ndf: Ndf::new(NdfKind::Charlie, alpha).expect("alpha validated > 0"),
        masking: Masking::Ashikhmin,
        fresnel: Fresnel::None,
    };
    let e = integrate_over_l_smooth(mu, Some(&sheen.ndf), tol, |n| [sheen.cosine_weighted(n)]);
    (e.value[0], e.error[0], e.evals)
}

/// [`sheen_albedo`] by the adaptive integrator alone.
pub fn sheen_albedo_adaptive(alpha: f64, mu: f64, tol: f64) -> (f64, f64, u64) {
    let sheen = Specular {
        ndf: Ndf::new(NdfKind::Charlie, alpha).expect("alpha validated > 0"),
        masking: Masking::Ashikhmin,
        fresnel: Fresnel::None,
    };
    let e = integrate_over_l(mu, sheen.ndf.warp(), tol, |n| [sheen.cosine_weighted(n)]);
    (e.value[0], e.error[0], e.evals)
}

/// The Smith form the specialised GGX kernels (2D and polar) handle for this lobe, if they
/// do (GGX with Smith masking; the split sums ignore the lobe's own Fresnel).
pub(crate) fn kernel_smith(s: &Specular) -> Option<Smith> {
    match (s.ndf.kind(), s.masking) {
        (NdfKind::Ggx, Masking::SmithHeightCorrelated) => Some(Smith::HeightCorrelated),
        (NdfKind::Ggx, Masking::SmithSeparable) => Some(Smith::Separable),
        _ => None,
    }
}

/// Whether a dfg table with this model uses the specialised kernels of
/// [`dfg_kernel`] (first) for its split-sum channels.
pub fn uses_kernel(ndf: Option<NdfKind>, masking: Masking) -> bool {
    ndf == Some(NdfKind::Ggx)
        && matches!(
            masking,
            Masking::SmithHeightCorrelated | Masking::SmithSeparable
        )
}

/// [`split_sum`] through the specialised GGX kernels where they apply — the 1D polar one
/// ([`ggx_polar`]) first, then the 2D one of [`dfg_kernel`] with the view setup of `col`
/// (whose μ must be `mu`) — and the generic path where they do not apply or their
/// estimates do not reach `tol` (the kernels' evaluations are counted either way).
pub fn split_sum_column(
    spec: &Specular,
    col: &Column,
    mu: f64,
    tol: f64,
) -> ([f64; 2], [f64; 2], u64) {
    split_sum_lazy(spec, mu, tol, || col)
}

/// [`split_sum_column`] with the view setup asked for only where the polar kernel gives up.
fn split_sum_lazy<'a>(
    spec: &Specular,
    mu: f64,
    tol: f64,
    col: impl FnOnce() -> &'a Column,
) -> ([f64; 2], [f64; 2], u64) {
    let mut spent = 0;
    if let Some(smith) = kernel_smith(spec) {
        match ggx_polar::ggx_split_sum(mu, spec.ndf.alpha(), smith, tol) {
            Ok(e) => return (e.value, e.error, e.evals),
            Err(n) => spent = n,
        }
        match dfg_kernel::ggx_split_sum(col(), spec.ndf.alpha(), smith, tol) {
            Ok(e) => return (e.value, e.error, e.evals + spent),
            Err(n) => spent += n,
        }
    }
    let (v, e, n) = split_sum(spec, mu, tol);
    (v, e, n + spent)
}

/// What every texel of a dfg table needs.
struct Ctx {
    brdfs: Vec<crate::model::Brdf>,
    axes: Vec<crate::lut::Axis>,
    tol: f64,
    layout: DfgLayout,
    cloth: bool,
}

impl Ctx {
    fn new(spec: &TableSpec) -> Ctx {
        Ctx {
            brdfs: brdfs_per_roughness(spec),
            axes: spec.axes.clone(),
            tol: spec.tolerance,
            layout: spec.dfg_layout.expect("validated"),
            cloth: spec.cloth,
        }
    }

    /// Texel (i0, j) with the view data of column i0.
    fn texel(&self, j: usize, view: &View) -> TexelResult {
        let mut r = self.pair(j, view, self.tol);
        if self.cloth {
            let alpha = self.axes[1].alpha(j).expect("roughness axis");
            let (v, e, n) = cloth_texel(view, alpha, self.tol);
            r.value.push(v);
            r.error.push(e);
            r.evals += n;
        }
        r
    }

    /// The split-sum channels of row j's lobe in the table's layout, at `view`.
    fn pair(&self, j: usize, view: &View, tol: f64) -> TexelResult {
        let s = self.brdfs[j]
            .specular
            .as_ref()
            .expect("validated: dfg has an NDF");
        // each channel of the pair below is a sum/difference of the two integrals, so its
        // error bound is the sum of theirs
        let ([a, b], [ea, eb], n) = split_sum_lazy(s, view.mu(), tol, || view.column());
        match self.layout {
            DfgLayout::Karis => TexelResult {
                value: vec![a, b],
                error: vec![ea, eb],
                evals: n,
            },
            DfgLayout::Filament => TexelResult {
                value: vec![b, a + b],
                error: vec![eb, ea + eb],
                evals: n,
            },
        }
    }
}

/// The cloth channel at one texel: the cloth kernels
/// ([`charlie_kernels`](super::albedo::charlie_kernels), with the view's shared node data),
/// then the generic path; the evaluations of abandoned attempts are counted. A pure function
/// of (μ, α, tol): the same bits whether the texel is computed alone or in its column.
fn cloth_texel(view: &View, alpha: f64, tol: f64) -> (f64, f64, u64) {
    match super::albedo::charlie_kernels(view, alpha, tol) {
        Ok(e) => (e.value[0], e.error[0], e.evals),
        Err(n) => {
            let (v, e, m) = sheen_albedo(alpha, view.mu(), tol);
            (v, e, m + n)
        }
    }
}

/// The texels of one table column (one view μ, every roughness, in axis-1 order): the view
/// setup ([`Column`]) and the cloth kernel's α-independent node data ([`SheenCache`]) are
/// built once for the column and shared by its texels; each texel's value is the same, bit
/// for bit, as computed alone ([`texel_fn`]).
pub(crate) fn column_fn(spec: &TableSpec) -> Box<dyn Fn(usize) -> Vec<TexelResult> + Sync> {
    let ctx = Ctx::new(spec);
    Box::new(move |i0| {
        let view = View::new(ctx.axes[0].coord(i0));
        (0..ctx.axes[1].size).map(|j| ctx.texel(j, &view)).collect()
    })
}

/// One texel on its own (for single-point evaluations such as `readback`'s exact values).
pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let ctx = Ctx::new(spec);
    Box::new(move |idx| ctx.texel(idx[1], &View::new(ctx.axes[0].coord(idx[0]))))
}

/// Where [`by_rows`] cuts every row first, in x = √μ: μ = 0.01 (θv ≈ 89.4°). Closer to
/// grazing the split sum of a narrow lobe changes on the scale of μ itself (the masking layer
/// at the horizon), which costs many nodes, and those nodes are the most expensive
/// quadratures of the row: the few texels there (one of a 128-texel row, five of 512) are
/// computed directly instead. Measured on karis-envbrdf: 10.3 → 6.5 M evaluations at 128²,
/// 79 → 42 M at 512² (cuts at μ = 0.0025 … 0.0625 tried; 0.01 is best at both sizes).
const GRAZING_BREAK: f64 = 0.1;

/// Whether [`by_rows`] bakes this table: 2D dfg tables whose split-sum channels go through
/// the GGX kernels (whose values are analytic in √μ along a row), with view cosines
/// increasing and positive (the rows are interpolated in √μ). Rows too short to pay are
/// computed texel by texel inside [`interp1d::line`].
pub fn rows_interpolated(spec: &TableSpec) -> bool {
    let [x, _] = match spec.axes.as_slice() {
        [x, y] => [x, y],
        _ => return false,
    };
    uses_kernel(spec.model.ndf, spec.model.masking)
        && spec.model.diffuse_weight == 0.0
        && x.size >= 2
        && x.coord(0) > 0.0
        && (1..x.size).all(|i| x.coord(i) > x.coord(i - 1))
}

fn as_sample(r: TexelResult) -> interp1d::Sample {
    interp1d::Sample {
        value: r.value,
        error: r.error,
        evals: r.evals,
    }
}

/// The whole table row by row, each row's split-sum pair interpolated in `x = √μ` from
/// values at Chebyshev nodes ([`interp1d`]); the cloth channel of narrow lobes row by row
/// ([`cloth_row`]), of wide ones column by column ([`cloth_column`]), both interpolated the
/// same way. `None` where [`rows_interpolated`] says no. Texels a row does not resolve
/// are computed as [`texel_fn`] computes them. Each interpolated texel's error estimate is
/// the interpolation's (truncation, plus the nodes' quadrature errors times the Lebesgue
/// constant). Results in texel order (μ fastest), without per-texel allocations (a 512²
/// table's results take 19 MB). `stop()` true makes every remaining sample
/// a cheap zero (the caller then discards the table).
pub(crate) fn by_rows(spec: &TableSpec, stop: &(dyn Fn() -> bool + Sync)) -> Option<Dense> {
    use rayon::prelude::*;
    if !rows_interpolated(spec) {
        return None;
    }
    let ctx = Ctx::new(spec);
    let (ax, ay) = (&ctx.axes[0], &ctx.axes[1]);
    let (nx, ny) = (ax.size, ay.size);
    let xs: Vec<f64> = (0..nx).map(|i| ax.coord(i).sqrt()).collect();
    let blank = || interp1d::Sample {
        value: vec![0.0; 2],
        error: vec![0.0; 2],
        evals: 0,
    };
    let pair_rows = || -> Vec<interp1d::LineValues> {
        (0..ny)
            .into_par_iter()
            .with_min_len(1)
            .map(|j| {
                interp1d::line(
                    &xs,
                    &[GRAZING_BREAK],
                    2,
                    ctx.tol,
                    |x, t| {
                        if stop() {
                            return blank();
                        }
                        as_sample(ctx.pair(j, &View::new(x * x), t))
                    },
                    |i, t| {
                        if stop() {
                            return blank();
                        }
                        as_sample(ctx.pair(j, &View::new(ax.coord(i)), t))
                    },
                )
            })
            .collect()
    };
    // the cloth channel: narrow lobes along rows, wide ones along columns (`cloth_rows`,
    // `cloth_column`)
    let narrow = |j: usize| ay.alpha(j).expect("roughness axis") < sheen_l::MAX_ALPHA;
    let narrow_rows = || -> Vec<Option<interp1d::LineValues>> {
        if !ctx.cloth {
            return Vec::new();
        }
        (0..ny)
            .into_par_iter()
            .with_min_len(1)
            .map(|j| narrow(j).then(|| cloth_row(&ctx, &xs, j, stop)))
            .collect()
    };
    let wide_columns = || -> Vec<interp1d::LineValues> {
        if !ctx.cloth {
            return Vec::new();
        }
        (0..nx)
            .into_par_iter()
            .with_min_len(1)
            .map(|i| cloth_column(&ctx, i, stop))
            .collect()
    };
    // the three sets of lines at once, so that one set's last lines overlap the others'
    // (each line is a pure function of its index: the same values in any schedule)
    let (rows, (cloth_rows, cloth_cols)) =
        rayon::join(pair_rows, || rayon::join(narrow_rows, wide_columns));
    let nc = if ctx.cloth { 3 } else { 2 };
    let mut out = Dense {
        channels: nc,
        value: Vec::with_capacity(nx * ny * nc),
        error: Vec::with_capacity(nx * ny * nc),
        evals: 0,
    };
    out.evals += cloth_rows.iter().flatten().map(|r| r.evals).sum::<u64>();
    out.evals += cloth_cols.iter().map(|c| c.evals).sum::<u64>();
    let cloth_at = |i: usize, j: usize| match &cloth_rows[j] {
        Some(r) => (r.value[i], r.error[i]),
        None => (cloth_cols[i].value[j], cloth_cols[i].error[j]),
    };
    for (j, row) in rows.iter().enumerate() {
        out.evals += row.evals;
        for i in 0..nx {
            out.value.extend_from_slice(&row.value[2 * i..2 * i + 2]);
            out.error.extend_from_slice(&row.error[2 * i..2 * i + 2]);
            if ctx.cloth {
                let (v, e) = cloth_at(i, j);
                out.value.push(v);
                out.error.push(e);
            }
        }
    }
    Some(out)
}

/// Below which, in x = √μ, [`cloth_row`] computes a narrow lobe's texels directly: μ = 0.04.
/// There the cloth albedo of a narrow lobe changes on the scale of μ and its quadratures
/// are the costliest of the row (the light-direction kernel often gives up there, and at
/// the nodes' tighter tolerance the half-vector kernel too, leaving the generic path: at
/// 512², interpolating down to the first texel spent 46 M of 138 M evaluations on such
/// nodes). Measured on filament-dfg's narrow rows at 128² (cut as an interpolation break,
/// nodes at tol/8): x = 0.1, 0.2 and 0.25 gave 937 (most rows direct: their nodes' estimates
/// near x = 0.13 use up the budget), 467 and 460 evaluations per texel (778 texel by texel).
const CLOTH_GRAZING_BREAK: f64 = 0.2;

/// The interpolation nodes of the cloth channel are computed at tol/8, not interp1d's tol/4:
/// the cloth kernels' estimates come close to what they are asked for, and at tol/4 the
/// nodes' own error times the Lebesgue constant (2.4 at degree 8) would exceed the half of
/// the tolerance beyond which an interval is computed directly — most narrow rows did.
const CLOTH_NODE_TOL_FRACTION: f64 = 1.0 / 8.0;

fn cloth_sample((v, e, n): (f64, f64, u64)) -> interp1d::Sample {
    interp1d::Sample {
        value: vec![v],
        error: vec![e],
        evals: n,
    }
}

/// The cloth channel of row j (a narrow lobe, α < [`sheen_l::MAX_ALPHA`]) interpolated in
/// x = √μ ([`interp1d`]) from [`cloth_texel`] values: narrow lobes go through
/// [`sheen_l`], which shares nothing along a column, so a row loses nothing by not being
/// computed column by column. Texels the row does not resolve are computed as
/// [`column_fn`] computes them.
fn cloth_row(
    ctx: &Ctx,
    xs: &[f64],
    j: usize,
    stop: &(dyn Fn() -> bool + Sync),
) -> interp1d::LineValues {
    let alpha = ctx.axes[1].alpha(j).expect("roughness axis");
    let at = |mu: f64, t: f64| {
        if stop() {
            return cloth_sample((0.0, 0.0, 0));
        }
        cloth_sample(cloth_texel(&View::new(mu), alpha, t))
    };
    // the texels below the break directly, the rest interpolated
    let k = xs.partition_point(|&x| x < CLOTH_GRAZING_BREAK);
    let mut out = interp1d::line_with_node_tol(
        &xs[k..],
        &[],
        1,
        ctx.tol,
        ctx.tol * CLOTH_NODE_TOL_FRACTION,
        |x, t| at(x * x, t),
        |i, t| at(ctx.axes[0].coord(k + i), t),
    );
    let mut value = Vec::with_capacity(xs.len());
    let mut error = Vec::with_capacity(xs.len());
    for i in 0..k {
        let s = at(ctx.axes[0].coord(i), ctx.tol);
        value.push(s.value[0]);
        error.push(s.error[0]);
        out.evals += s.evals;
        out.direct += 1;
    }
    value.extend_from_slice(&out.value);
    error.extend_from_slice(&out.error);
    out.value = value;
    out.error = error;
    out
}

/// The cloth channel of column i (one view μ): the wide lobes ([`sheen_wide`]'s range,
/// 1/16 ≤ α ≤ 1), if their α increases along the column, interpolated in x = √α
/// ([`interp1d`]; analytic there: Charlie's `sin^{1/α}` is analytic in 1/α) from
/// [`cloth_texel`] values, whose kernel shares its node data along the column
/// ([`SheenCache`]) at any α; every other texel computed as [`column_fn`] computes it (the
/// narrow lobes' values are left 0 here: [`cloth_row`] computes them).
///
/// [`sheen_wide`]: crate::integrate::sheen_wide
fn cloth_column(ctx: &Ctx, i: usize, stop: &(dyn Fn() -> bool + Sync)) -> interp1d::LineValues {
    use crate::integrate::sheen_wide;
    let ay = &ctx.axes[1];
    let ny = ay.size;
    let view = View::new(ctx.axes[0].coord(i));
    let at = |alpha: f64, t: f64| {
        if stop() {
            return (0.0, 0.0, 0);
        }
        cloth_texel(&view, alpha, t)
    };
    let alphas: Vec<f64> = (0..ny)
        .map(|j| ay.alpha(j).expect("roughness axis"))
        .collect();
    let wide = |a: f64| (sheen_l::MAX_ALPHA..=sheen_wide::MAX_ALPHA).contains(&a);
    let mut out = interp1d::LineValues {
        value: vec![0.0; ny],
        error: vec![0.0; ny],
        ..Default::default()
    };
    // the wide run: contiguous, α strictly increasing
    let j0 = alphas.iter().position(|&a| wide(a)).unwrap_or(ny);
    let j1 = j0 + alphas[j0..].iter().take_while(|&&a| wide(a)).count();
    let increasing = alphas[j0..j1].windows(2).all(|w| w[1] > w[0]);
    let (j0, j1) = if increasing { (j0, j1) } else { (0, 0) };
    if j1 > j0 {
        let xs: Vec<f64> = alphas[j0..j1].iter().map(|a| a.sqrt()).collect();
        let run = interp1d::line(
            &xs,
            &[],
            1,
            ctx.tol,
            |x, t| cloth_sample(at(x * x, t)),
            |k, t| cloth_sample(at(alphas[j0 + k], t)),
        );
        out.value[j0..j1].copy_from_slice(&run.value);
        out.error[j0..j1].copy_from_slice(&run.error);
        out.evals += run.evals;
    }
    for (j, &a) in alphas.iter().enumerate() {
        if (j0..j1).contains(&j) || a < sheen_l::MAX_ALPHA {
            continue;
        }
        let (v, e, n) = at(a, ctx.tol);
        out.value[j] = v;
        out.error[j] = e;
        out.evals += n;
    }
    out
}

/// A whole table's values without per-texel allocations: channel c of texel t (axis 0
/// fastest) at `value[t·channels + c]`, its error estimate at the same index of `error`.
pub(crate) struct Dense {
    pub channels: usize,
    pub value: Vec<f64>,
    pub error: Vec<f64>,
    pub evals: u64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::{Axis, Convention, Quantity};
    use crate::model::RoughnessQuantity;
    use crate::table::{ModelSpec, Storage, TableKind};

    fn spec(nx: usize, roughness: [f64; 2], ny: usize, cloth: bool, tol: f64) -> TableSpec {
        TableSpec {
            name: "t".into(),
            kind: TableKind::Dfg,
            model: ModelSpec {
                ndf: Some(NdfKind::Ggx),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
                diffuse_weight: 0.0,
                classic: None,
            },
            axes: vec![
                Axis {
                    name: "cos_theta_v".into(),
                    quantity: Quantity::Cosine,
                    size: nx,
                    range: [0.0, 1.0],
                    convention: Convention::Centers,
                },
                Axis {
                    name: "roughness".into(),
                    quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
                    size: ny,
                    range: roughness,
                    convention: Convention::Endpoints,
                },
            ],
            dfg_layout: Some(if cloth {
                DfgLayout::Filament
            } else {
                DfgLayout::Karis
            }),
            cloth,
            storage: Storage::F32,
            tolerance: tol,
        }
    }

    /// Every texel of rows interpolated in √μ (300 texels per row, roughness from a near-mirror
    /// 0.02 to 1) lies within its own estimate of the same split sum computed texel by texel
    /// at a 1000× tighter tolerance (whose estimate is added), each estimate is within the
    /// table's tolerance, and the rows cost fewer evaluations than the texels would.
    #[test]
    fn interpolated_rows_match_texel_values() {
        let tol = 1e-7;
        let s = spec(300, [0.02, 1.0], 5, false, tol);
        let rows = by_rows(&s, &|| false).expect("a GGX dfg table is interpolated");
        let ctx = Ctx::new(&s);
        let mut direct_evals = 0u64;
        let row_evals = rows.evals;
        for t in 0..300 * 5 {
            let (i, j) = (t % 300, t / 300);
            let view = View::new(ctx.axes[0].coord(i));
            let fine = ctx.pair(j, &view, tol * 1e-3);
            direct_evals += ctx.pair(j, &view, tol).evals;
            for c in 0..2 {
                let (v, e) = (rows.value[2 * t + c], rows.error[2 * t + c]);
                let d = (v - fine.value[c]).abs();
                assert!(
                    d <= e + fine.error[c],
                    "texel ({i}, {j}) channel {c}: {v} vs {} (estimates {e:e} + {:e})",
                    fine.value[c],
                    fine.error[c]
                );
                assert!(e <= tol, "estimate {e:e} over the tolerance");
            }
        }
        assert!(
            2 * row_evals < direct_evals,
            "{row_evals} evaluations by rows vs {direct_evals} texel by texel"
        );
    }

    /// Every channel agrees with the column path (texel by texel) within the two estimates;
    /// a table whose rows and columns are too short to pay is computed texel by texel, bit
    /// for bit as by columns.
    #[test]
    fn short_lines_are_the_column_values() {
        for (nx, short) in [(40, false), (8, true)] {
            let s = spec(nx, [0.1, 0.9], 3, true, 1e-7);
            let rows = by_rows(&s, &|| false).expect("interpolated");
            let column = column_fn(&s);
            for i in 0..nx {
                let col = column(i);
                for (j, c) in col.iter().enumerate() {
                    let t = 3 * (j * nx + i);
                    for k in 0..3 {
                        let (v, e) = (rows.value[t + k], rows.error[t + k]);
                        if short {
                            assert_eq!(v.to_bits(), c.value[k].to_bits());
                        } else {
                            assert!((v - c.value[k]).abs() <= e + c.error[k]);
                        }
                    }
                }
            }
        }
    }

    /// The interpolated cloth channel — narrow lobes along rows in √μ, wide ones along
    /// columns in √α — lies within its own estimate of the cloth albedo computed texel by
    /// texel at a 100× tighter tolerance (whose estimate is added), on three narrow rows
    /// (α = 0.0025 … 0.04, 150 texels each) and three columns (60 wide texels each, α = 1/16
    /// … 1), and every estimate is within the table's tolerance. Both lines must really be
    /// interpolated (fewer quadratures than texels).
    #[test]
    fn interpolated_cloth_matches_texel_values() {
        let tol = 1e-7;
        let s = spec(150, [0.05, 1.0], 77, true, tol);
        let ctx = Ctx::new(&s);
        let check = |i: usize, j: usize, v: f64, e: f64| {
            let alpha = ctx.axes[1].alpha(j).unwrap();
            let (r, re, _) = cloth_texel(&View::new(ctx.axes[0].coord(i)), alpha, tol * 1e-2);
            assert!(
                (v - r).abs() <= e + re,
                "texel ({i}, {j}), alpha {alpha}: {v} vs {r} (estimates {e:e} + {re:e})"
            );
            assert!(e <= tol, "estimate {e:e} over the tolerance");
        };
        let xs: Vec<f64> = (0..150).map(|i| ctx.axes[0].coord(i).sqrt()).collect();
        for j in [0, 6, 12] {
            assert!(ctx.axes[1].alpha(j).unwrap() < sheen_l::MAX_ALPHA);
            let row = cloth_row(&ctx, &xs, j, &|| false);
            assert!(row.nodes + row.direct < 150, "row {j} not interpolated");
            for i in 0..150 {
                check(i, j, row.value[i], row.error[i]);
            }
        }
        for i in [0, 70, 149] {
            let c = cloth_column(&ctx, i, &|| false);
            assert!(c.nodes + c.direct < 60, "column {i} not interpolated");
            for j in 17..77 {
                assert!(ctx.axes[1].alpha(j).unwrap() >= sheen_l::MAX_ALPHA);
                check(i, j, c.value[j], c.error[j]);
            }
        }
    }
}
