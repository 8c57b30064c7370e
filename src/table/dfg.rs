//! `dfg`: the split-sum tables of the specular lobe with the Fresnel factored out.
//!
//! With Schlick's F = F0 + (1 − F0)·Fc, Fc = (1 − v·h)⁵, the directional albedo is linear in
//! F0: E = F0·∫(1 − Fc) f cos + ∫ Fc f cos (Karis 2013, "Real Shading in Unreal Engine 4",
//! eq. 8), with f the BRDF at F = 1. Filament stores the same information as
//! (∫ Fc f cos, ∫ f cos) so that the second channel is the single-scattering albedo used for
//! multiple-scattering compensation (Filament documentation, "Energy loss in specular
//! reflectance"), and optionally the cloth albedo ∫ D_Charlie·V_Ashikhmin·cos in the third.
//!
//! **How a table is baked.** GGX tables with Smith masking go by lines of texels
//! interpolated from fewer quadratures: rows, grids across the table whose samples are whole
//! columns, and columns ([`dfg_lines`](super::dfg_lines), which holds the plan and its
//! measurements). Other models go column by column (`column_fn`), texel by texel; this
//! module holds the per-texel integrals both use.

use super::methods::{charlie_kernels, charlie_polar, kernel_smith};
use super::texel::brdfs_per_roughness;
use super::{DfgLayout, TableSpec, TexelResult};
use crate::hemisphere::tensor::integrate_over_l_smooth;
use crate::hemisphere::{integrate_over_l, Node};
use crate::kernels::ggx_polar;
use crate::kernels::sheen_azimuth::View;
use crate::kernels::vgroove::{integrate_over_l_kinked, TailCut};
use crate::model::fresnel::schlick_weight;
use crate::model::{Fresnel, Masking, Ndf, NdfKind, Specular};
use crate::quadrature::interp1d;

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
        let tail = super::methods::vgroove_fast_path(spec, 0.0, tol).unwrap_or(TailCut::NONE);
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
    sheen_albedo_with(Masking::Ashikhmin, alpha, mu, tol)
}

/// The sheen albedo ∫ D_Charlie(α)·G·(n·l)/(4 (n·l)(n·v)) dω_l with masking `masking` at one
/// (μ, α), by the generic path (the tensor rule, then the adaptive integrator).
pub fn sheen_albedo_with(masking: Masking, alpha: f64, mu: f64, tol: f64) -> (f64, f64, u64) {
    let sheen = Specular {
        ndf: Ndf::new(NdfKind::Charlie, alpha).expect("alpha validated > 0"),
        masking,
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

/// [`split_sum`] through the specialised GGX kernel where it applies — the 1D polar one
/// ([`ggx_polar`]) — and the generic path where it does not apply or its estimate does not
/// reach `tol` (the kernel's evaluations are counted either way).
pub fn split_sum_kernels(spec: &Specular, mu: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
    let mut spent = 0;
    if let Some(smith) = kernel_smith(spec) {
        match ggx_polar::ggx_split_sum(mu, spec.ndf.alpha(), smith, tol) {
            Ok(e) => return (e.value, e.error, e.evals),
            Err(n) => spent = n,
        }
    }
    let (v, e, n) = split_sum(spec, mu, tol);
    (v, e, n + spent)
}

/// What every texel of a dfg table needs (and of a Charlie albedo table baked by lines,
/// whose one channel is the dfg table's cloth channel with the table's own masking).
pub(super) struct Ctx {
    model: super::ModelSpec,
    brdfs: Vec<crate::model::Brdf>,
    pub(super) axes: Vec<crate::lut::Axis>,
    pub(super) tol: f64,
    layout: DfgLayout,
    /// Whether the table has the split-sum pair (dfg tables; not the albedo ones).
    pub(super) pair: bool,
    pub(super) cloth: bool,
    /// The cloth channel's masking: Ashikhmin's for a dfg table, the model's for a Charlie
    /// albedo table.
    pub(super) sheen: Masking,
    /// The cloth channel's floor on α (`cloth_alpha_min`).
    pub(super) cloth_alpha_min: Option<f64>,
}

impl Ctx {
    pub(super) fn new(spec: &TableSpec) -> Ctx {
        let pair = spec.kind == super::TableKind::Dfg;
        Ctx {
            model: spec.model.clone(),
            brdfs: brdfs_per_roughness(spec),
            axes: spec.axes.clone(),
            tol: spec.tolerance,
            layout: spec.dfg_layout.unwrap_or(DfgLayout::Karis),
            pair,
            cloth: spec.cloth || !pair,
            sheen: if pair {
                Masking::Ashikhmin
            } else {
                spec.model.masking
            },
            cloth_alpha_min: spec.cloth_alpha_min,
        }
    }

    /// The cloth channel's Charlie α at a texel of roughness α: `max(α, cloth_alpha_min)`.
    pub(super) fn cloth_alpha(&self, alpha: f64) -> f64 {
        match self.cloth_alpha_min {
            Some(m) => alpha.max(m),
            None => alpha,
        }
    }

    /// Texel (i0, j) with the view data of column i0.
    fn texel(&self, j: usize, view: &View) -> TexelResult {
        let mut r = if self.pair {
            self.pair(j, view, self.tol)
        } else {
            TexelResult::exact(Vec::new())
        };
        if self.layout == DfgLayout::KarisF82 {
            let s = self.brdfs[j]
                .specular
                .as_ref()
                .expect("validated: dfg has an NDF");
            let (v, e, n) = f82_channel(s, view.mu(), self.tol);
            r.value.push(v);
            r.error.push(e);
            r.evals += n;
        }
        if self.cloth {
            let alpha = self.cloth_alpha(self.axes[1].alpha(j).expect("roughness axis"));
            let (v, e, n) = cloth_texel(self.sheen, view, alpha, self.tol);
            r.value.push(v);
            r.error.push(e);
            r.evals += n;
        }
        r
    }

    /// The split-sum channels of row j's lobe in the table's layout, at `view`.
    pub(super) fn pair(&self, j: usize, view: &View, tol: f64) -> TexelResult {
        let s = self.brdfs[j]
            .specular
            .as_ref()
            .expect("validated: dfg has an NDF");
        self.pair_of(s, view, tol)
    }

    /// The split-sum channels of the table's lobe at any roughness α inside the axis's range
    /// (an interpolation node between rows).
    pub(super) fn pair_at(&self, alpha: f64, view: &View, tol: f64) -> TexelResult {
        let b = self
            .model
            .brdf(alpha)
            .expect("α inside the validated axis range");
        let s = b.specular.as_ref().expect("validated: dfg has an NDF");
        s.prepare();
        self.pair_of(s, view, tol)
    }

    /// The split-sum channels of lobe `s` in the table's layout, at `view`.
    fn pair_of(&self, s: &Specular, view: &View, tol: f64) -> TexelResult {
        // each channel of the pair below is a sum/difference of the two integrals, so its
        // error bound is the sum of theirs
        let ([a, b], [ea, eb], n) = split_sum_kernels(s, view.mu(), tol);
        match self.layout {
            DfgLayout::Karis | DfgLayout::KarisF82 => TexelResult {
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

/// The F82-tint channel `∫ (v·h)(1 − v·h)⁶ f cos dω_l` of a GGX lobe with Smith masking
/// (F = 1) at view μ: `∫ b(c) D G c/(n·v) dω_h` over the micro-normals whose reflection
/// leaves above the horizon, by the nested rule of [`crate::kernels::micro_normals`] (the
/// weight is a polynomial in c = v·h: no kink of its own).
pub(super) fn f82_channel(s: &Specular, mu: f64, tol: f64) -> (f64, f64, u64) {
    use crate::kernels::micro_normals::{integrate_micro_normals, Rule};
    use crate::model::btdf::{Facet, SmithForm};
    let smith = SmithForm::of(s.masking).unwrap_or(SmithForm::Separable);
    let mu1 = mu.min(1.0);
    let g1v = s.ndf.g1(mu1);
    let rule = Rule {
        etas: &[],
        cones: &[],
        view_peak: false,
        estimator: crate::quadrature::cc1d::Estimator::Tail,
        alphas: &[],
    };
    let e = integrate_micro_normals(&s.ndf, rule, mu, tol, |h| {
        Facet::new(&s.ndf, smith, mu1, g1v, h).map_or([0.0], |f| {
            [f.w * f.gr * crate::model::fresnel::f82_tint_weight(f.c)]
        })
    });
    (e.value[0], e.error[0], e.evals)
}

/// The cloth channel at one texel, Charlie with masking `masking`: for Ashikhmin's, the
/// cloth kernels ([`charlie_kernels`], with the view's shared node data), for the others the
/// light-cosine kernel ([`charlie_polar`]), then the generic path; the evaluations of
/// abandoned attempts are counted. A pure function of (μ, α, tol): the same bits whether
/// the texel is computed alone or in its column.
pub(super) fn cloth_texel(masking: Masking, view: &View, alpha: f64, tol: f64) -> (f64, f64, u64) {
    let r = if masking == Masking::Ashikhmin {
        charlie_kernels(view, alpha, tol)
    } else {
        let s = Specular {
            ndf: Ndf::new(NdfKind::Charlie, alpha).expect("alpha validated > 0"),
            masking,
            fresnel: Fresnel::None,
        };
        charlie_polar(&s, view, tol).unwrap_or(Err(0))
    };
    match r {
        Ok(e) => (e.value[0], e.error[0], e.evals),
        Err(n) => {
            let (v, e, m) = sheen_albedo_with(masking, alpha, view.mu(), tol);
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

pub(super) fn as_sample(r: TexelResult) -> interp1d::Sample {
    interp1d::Sample {
        value: r.value,
        error: r.error,
        evals: r.evals,
    }
}

pub(super) fn cloth_sample((v, e, n): (f64, f64, u64)) -> interp1d::Sample {
    interp1d::Sample {
        value: vec![v],
        error: vec![e],
        evals: n,
    }
}

/// A whole table as it is stored, without per-texel allocations: channel c of texel t
/// (axis 0 fastest) at `data[t·channels + c]` (f32), the largest error estimate of each
/// channel, and the first texel (lowest index t, then channel) whose value is not finite in
/// f64 or f32, with that value, and the texels that missed the accepted error estimate.
pub(crate) struct Dense {
    pub data: Vec<f32>,
    pub max_error: Vec<f64>,
    pub evals: u64,
    pub non_finite: Option<(usize, usize, f64)>,
    /// The texels whose estimate exceeds the accepted one (texel index t).
    pub misses: super::Misses,
}
