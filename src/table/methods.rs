//! Which methods each table kind tries for a texel, in order, and when it falls back: the
//! one place that says so (the kinds' files call these choosers, and the sidecar's
//! `quadrature.method` is [`describe`]'s text). Every chain ends in a method that always
//! answers; a texel whose final estimate still exceeds its tolerance fails the bake.
//!
//! * `ndf`, `vgroove`, `g1`/`g2` with a closed-form Λ: closed forms. `g1`/`g2` of the
//!   Gaussian NDF: Λ derived numerically from D (adaptive Gauss–Kronrod, piecewise
//!   Chebyshev; `model/ndf.rs`).
//! * `dfg` split-sum channels, GGX with Smith masking ([`split_sum_uses_kernel`]): on tables
//!   of at least 128 columns by lines (`dfg_lines.rs`: interpolated in √μ and ln α from
//!   quadrature nodes), each node or direct texel by the polar kernel
//!   ([`crate::kernels::ggx_polar`]), where its estimate fails the generic path below. Other
//!   models: the generic path.
//! * `dfg` cloth channel, and `albedo` of Charlie + Ashikhmin ([`albedo_uses_kernel`]): the θh
//!   kernel (`charlie_kernels`, [`crate::kernels::sheen_azimuth`]; it declines views within
//!   1e-3 of the normal), then the generic path.
//! * `albedo` (and the E of `albedo-avg`, `kulla-conty`) of GGX + Smith, F = 1: the polar
//!   kernel's albedo; with Schlick's Fresnel, E = F0·A + B from the polar split sum; then the
//!   generic path. V-groove masking: the branch-split rule (`vgroove_fast_path`,
//!   [`crate::kernels::vgroove`]; Beckmann alone in closed-form pieces), then adaptive.
//! * `albedo-fresnel` with exact Fresnel, `dielectric-btdf`: the Fresnel fibres (every slice
//!   of one (μ, α) as the channels of one rule, `energy.rs`, `dielectric.rs`), texel by
//!   texel where a fibre fails; `dielectric-btdf` by nested Clenshaw–Curtis panels between
//!   its kinks, adaptive per panel where those fail. The η < 1 slices of the 3D dielectric
//!   kinds by roughness fibres instead (every roughness of one (μ, η) as the channels of
//!   shared rules, [`crate::kernels::roughness_fibre`]).
//! * `classic-albedo`: the 1D lobe kernels ([`crate::kernels::classic_lobes`]) for
//!   Blinn-Phong, (modified) Phong and Ward–GMD, else the energy-law integrator.
//! * The generic path of every smooth hemisphere integral: the tensor rule
//!   ([`crate::hemisphere::tensor`]), then the adaptive integrator
//!   ([`crate::hemisphere::integrate_over_l`]) where its estimate fails.

use super::spec::{TableKind, TableSpec};
use crate::kernels::ggx_polar::Smith;
use crate::kernels::sheen_azimuth::{self, View};
use crate::kernels::vgroove::TailCut;
use crate::lut::Quantity;
use crate::model::{Masking, NdfKind, Specular};

/// The Smith form the specialised GGX kernels (2D and polar) handle for this lobe, if they
/// do (GGX with Smith masking; the split sums ignore the lobe's own Fresnel).
pub(crate) fn kernel_smith(s: &Specular) -> Option<Smith> {
    match (s.ndf.kind(), s.masking) {
        (NdfKind::Ggx, Masking::SmithHeightCorrelated) => Some(Smith::HeightCorrelated),
        (NdfKind::Ggx, Masking::SmithSeparable) => Some(Smith::Separable),
        (NdfKind::Ggx, m @ (Masking::SchlickGgx | Masking::SchlickGgxDirect)) => {
            m.schlick(s.ndf.alpha()).map(|g| Smith::Schlick { k: g.k })
        }
        _ => None,
    }
}

/// Whether a dfg table with this model uses the specialised kernels of
/// [`crate::kernels::ggx_polar`] (first) for its split-sum channels: GGX with Smith's
/// masking or Schlick's approximation of it (smooth functions of (n·v, n·l) alone).
pub fn split_sum_uses_kernel(ndf: Option<NdfKind>, masking: Masking) -> bool {
    ndf == Some(NdfKind::Ggx) && kernel_masking(masking)
}

/// The masking terms the GGX polar kernel takes.
fn kernel_masking(masking: Masking) -> bool {
    matches!(
        masking,
        Masking::SmithHeightCorrelated
            | Masking::SmithSeparable
            | Masking::SchlickGgx
            | Masking::SchlickGgxDirect
    )
}

/// The cloth albedo `∫ D_Charlie V_Ashikhmin (n·l) dω_l` (F = 1) at view `view.mu()` by the
/// cloth kernel, as the `filament-dfg` cloth channel computes it: [`sheen_azimuth`] (a 1D
/// integral over θh with the azimuthal integral in closed form; it shares its node data for
/// wide lobes along the view's column, and declines views within 1e-3 of the normal);
/// `Err(evaluations spent)` where it declines or does not reach `tol` (the caller falls back
/// to the generic path). The same bits whether `view` is shared by a column or the texel's
/// own.
pub(crate) fn charlie_kernels(
    view: &View,
    alpha: f64,
    tol: f64,
) -> Result<crate::quadrature::Estimate<1>, u64> {
    sheen_azimuth::charlie_sheen_azimuth_shared(
        view.mu(),
        alpha,
        tol,
        &mut view.azimuth().borrow_mut(),
    )
}

/// The Charlie sheen albedo with a masking term of the two cosines other than Ashikhmin's
/// (Conty–Kulla's, plain or softened) by the light-cosine kernel
/// ([`crate::kernels::sheen_polar`]); `None` for lobes it does not take, `Err(evaluations
/// spent)` where it does not reach `tol` (the caller falls back to the generic path).
pub(crate) fn charlie_polar(
    s: &Specular,
    view: &View,
    tol: f64,
) -> Option<Result<crate::quadrature::Estimate<1>, u64>> {
    let mu = view.mu();
    use crate::model::masking::ContyKullaLambda;
    if s.ndf.kind() != NdfKind::Charlie {
        return None;
    }
    let softened = match s.masking {
        Masking::ContyKulla => false,
        Masking::ContyKullaSoftened => true,
        _ => return None,
    };
    let cl = ContyKullaLambda::new(s.ndf.alpha());
    let lv = cl.lambda(mu);
    let g = |mu_l: f64| {
        let ll = if softened {
            cl.softened(mu_l)
        } else {
            cl.lambda(mu_l)
        };
        1.0 / (1.0 + lv + ll)
    };
    Some(crate::kernels::sheen_polar::charlie_albedo_polar_shared(
        mu,
        s.ndf.alpha(),
        &g,
        tol,
        &mut view.polar().borrow_mut(),
    ))
}

/// Whether the V-groove fast path ([`integrate_over_l_kinked`]) may take this lobe, and the
/// tail it may leave out. Not where the Fresnel factor has a kink of its own: a dielectric
/// with η < 1 switches to total internal reflection at v·h = √(1 − η²), a curve the branch
/// split does not follow (`None`: the adaptive integrator, which bisects towards it). The
/// tail cut only for a Beckmann lobe alone (no diffuse lobe, whose n·l does not decay with
/// θh; every Fresnel factor is ≤ 1), leaving out at most 10⁻⁴ of the tolerance.
pub(crate) fn vgroove_fast_path(
    s: &crate::model::Specular,
    diffuse_weight: f64,
    tol: f64,
) -> Option<TailCut> {
    use crate::model::{Fresnel, NdfKind};
    if matches!(s.fresnel, Fresnel::Dielectric { eta } if eta < 1.0) {
        return None;
    }
    Some(
        if s.ndf.kind() == NdfKind::Beckmann && diffuse_weight == 0.0 {
            TailCut::beckmann_vgroove(1e-4 * tol)
        } else {
            TailCut::NONE
        },
    )
}

/// Whether [`directional_albedo`](super::albedo::directional_albedo) tries the specialised kernels for this model.
pub fn albedo_uses_kernel(model: &super::ModelSpec) -> bool {
    use crate::model::NdfKind;
    model.diffuse_weight == 0.0
        && model.fresnel == crate::model::Fresnel::None
        && match model.ndf {
            Some(NdfKind::Ggx) => kernel_masking(model.masking),
            Some(NdfKind::Charlie) => matches!(
                model.masking,
                Masking::Ashikhmin | Masking::ContyKulla | Masking::ContyKullaSoftened
            ),
            _ => false,
        }
}

/// `dfg_lines.rs` lays grids only on tables of at least this many texel columns: a grid's
/// x-line needs ~36–68 columns (measured on filament-dfg: 9.9 M evaluations with grids
/// against 10.0 M without at 96², 11.8 M against 14.6 M at 128², 8.1 M against 3.0 M at
/// 32²). Below it the pair goes by rows and the wide cloth lobes by columns alone.
pub(crate) const GRID_MIN_COLUMNS: usize = 128;

/// Whether `dfg_lines.rs` bakes this table by lines: 2D dfg tables whose split-sum channels go through the
/// GGX kernels (analytic in √μ along a row, in ln α along a column), with view cosines
/// increasing and positive. Lines too short to pay are computed texel by texel inside
/// [`crate::quadrature::interp1d`].
pub fn split_sum_by_lines(spec: &TableSpec) -> bool {
    let [x, _] = match spec.axes.as_slice() {
        [x, y] => [x, y],
        _ => return false,
    };
    spec.kind == TableKind::Dfg
        // (karis-f82's third channel goes texel by texel: column by column)
        && spec.dfg_layout != Some(super::DfgLayout::KarisF82)
        && split_sum_uses_kernel(spec.model.ndf, spec.model.masking)
        && spec.model.diffuse_weight == 0.0
        && x.size >= 2
        && x.coord(0) > 0.0
        && (1..x.size).all(|i| x.coord(i) > x.coord(i - 1))
}

/// Whether `dfg_lines.rs` bakes this `albedo` table by lines: the Charlie sheen albedo
/// (any of its maskings, F = 1, no diffuse lobe) on tables of at least
/// `GRID_MIN_COLUMNS` (128) columns whose view cosines
/// increase and are positive — the plan of the `dfg` table's cloth channel, its kernel the
/// model's (`dfg::cloth_texel`). Smaller tables go column by column,
/// texel by texel.
pub fn albedo_by_lines(spec: &TableSpec) -> bool {
    let [x, _] = match spec.axes.as_slice() {
        [x, y] => [x, y],
        _ => return false,
    };
    spec.kind == TableKind::Albedo
        && spec.model.ndf == Some(NdfKind::Charlie)
        && albedo_uses_kernel(&spec.model)
        && x.size >= GRID_MIN_COLUMNS
        && x.coord(0) > 0.0
        && (1..x.size).all(|i| x.coord(i) > x.coord(i - 1))
}

/// Whether an `albedo-fresnel` table goes by fibres: an exact (dielectric or conductor)
/// Fresnel axis — Schlick slices are E = F0·A + B from the polar split sum already —, not
/// V-groove masking (its kinked path, per texel) and a lobe the tensor rule takes in the warp
/// u = asinh(tan θh/α), i.e. every NDF but Charlie (whose sheen warps have special cases).
pub(crate) fn uses_fresnel_fibre(spec: &TableSpec) -> bool {
    spec.kind == TableKind::AlbedoFresnel
        && matches!(spec.axes.get(2).map(|a| a.quantity), Some(Quantity::Fresnel(q)) if !q.is_f0())
        && spec.model.masking != Masking::VGroove
        && spec.model.diffuse_weight == 0.0
        && spec.model.ndf.is_some_and(|k| k != NdfKind::Charlie)
}

/// The nested rule over micro-normals of every `dielectric-btdf`, `dielectric-albedo` and `schlick-weight` texel
/// ([`crate::kernels::micro_normals`]), as the sidecar's `quadrature.method` states it.
pub const MICRO_NORMALS_METHOD: &str = "nested quadrature over the micro-normal h: phi in [0, pi] (doubled by symmetry), u = asinh(tan theta_h / alpha) from 0 to v.h = 0 or the equator (without a critical angle: u up to theta_h = 45 degrees, theta_h itself beyond it, to the equator; with one: u up to 30, further where a grazing view or a tight tolerance needs it: the tail beyond is below 1e-3 of the tolerance); panel boundaries at every kink, in closed form: in u the reflected and (eta < 1) transmitted directions' horizons and the critical angle, in phi pi/2, at a view grazing on the lobe's scale (x = n.v/(alpha sin theta_v) < 1) where -cos phi = x, and (eta < 1) where the critical cone touches the azimuth line (a square-root kink), meets the reflected horizon and meets the equator (a 3/2-power one) (square-root kinks integrated in t, x = end +- (b - a) t^2; with eta < 1, a panel whose nearest square-root kink lies outside it within half its length, in t about that point, x = s +- (b - s) t^2); each panel by nested Clenshaw-Curtis (9 to 129 nodes in u, 65 in phi; estimate max(|Q_k - Q_k-1|, |Q_k-1 - Q_k-2|^2 / max(|Q_k|, tol))), else adaptive Gauss-Kronrod (G7/K15, estimate |K15 - G7|); estimates summed over panels; f64 accumulation.";

/// What the fibre path of an `albedo-fresnel` table does, as the sidecar's
/// `quadrature.method` states it (followed by the per-texel method).
pub const FRESNEL_FIBRE_METHOD: &str = "Fibres: the texels of one (mu, roughness) differ only in the Fresnel factor F(v.h), so up to 8 slices are integrated together as the channels of one nested Clenshaw-Curtis tensor rule (as below: nodes, D and G computed once, times each slice's exact Fresnel factor), refined until every channel's own estimate meets the tolerance; each texel keeps its own channel's estimate. Evaluations count the nodes, once however many slices they serve.";

/// The sidecar's `quadrature.method` of a table: every method its texels may take, in the
/// order tried.
pub fn describe(spec: &TableSpec) -> String {
    let method = match spec.kind {
        TableKind::Ndf | TableKind::Vgroove => "closed form, evaluated in f64".to_string(),
        TableKind::G1 | TableKind::G2 => match spec.model.ndf {
            Some(n) if n.closed_form_lambda() => "closed form Smith Lambda, evaluated in f64".into(),
            _ => "Smith Lambda derived numerically from D: adaptive Gauss-Kronrod (G7/K15) of the slope-space integral, interpolated piecewise-Chebyshev".into(),
        },
        TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => {
            crate::table::classic::method(spec)
        }
        TableKind::DielectricBtdf => format!("{MICRO_NORMALS_METHOD} Fibres: the eta >= 1 texels of one (mu, roughness), whose breakpoints are the same, are integrated together, up to 4, as the channels (R, T of each) of one such rule: nodes, D, G1(v) and the reflected direction computed once, each eta's Fresnel factor and refracted direction per node; a panel is refined until every channel's own estimate meets its share, and each texel keeps its own channels' estimates; eta < 1 texels by roughness fibres: every roughness of one (mu, eta) as the channels of shared rules (up to 15 roughnesses whose alpha spans at most 256, src/kernels/roughness_fibre.rs; every breakpoint of an eta < 1 integral is a property of the geometry alone), in the narrowest lobe's u up to theta_h = 45 degrees and theta_h beyond, D and masking per lobe, each texel keeping its own channels' estimates. Evaluations count the u nodes, once however many texels they serve"),
        TableKind::DielectricAlbedo => format!("{MICRO_NORMALS_METHOD} Fibres: the eta >= 1 texels of one (mu, roughness) with the same view cosine, whose breakpoints are the same, are integrated together as the channels of one such rule (up to 8 of them), each texel keeping its own channels' estimates; eta < 1 texels by roughness fibres: every roughness of one (mu, eta) as the channels of shared rules (up to 15 roughnesses whose alpha spans at most 256, src/kernels/roughness_fibre.rs; every breakpoint of an eta < 1 integral is a property of the geometry alone), in the narrowest lobe's u up to theta_h = 45 degrees and theta_h beyond, D and masking per lobe, each texel keeping its own channels' estimates. Evaluations count the u nodes, once however many texels they serve"),
        TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => format!("{MICRO_NORMALS_METHOD} With an exponent axis, also a square-root panel end where v.h peaks along each azimuth (the weight (1 - v.h)^e is not analytic at v.h = 1). S_albedo = the ratio of two integrals of the same rule (run at tolerance/2, and again at tolerance times the denominator/2 where that leaves the ratio's estimate (d_num + S d_den)/den above the tolerance). Fibres: all exponents, or the eta >= 1 slices, of one (mu, roughness) three at a time as the channels of one rule (the shared denominator and two numerators each); eta < 1 slices alone. Evaluations count the u nodes"),
        TableKind::DielectricSchlick => format!("{MICRO_NORMALS_METHOD} The eta < 1 texels with dielectric-btdf's breakpoints (Schlick's weight on the less dense side has the same square-root end at the critical angle as the exact Fresnel term), by roughness fibres: every roughness of one (mu, eta) as the channels (A, B, T of each) of shared rules (up to 15 roughnesses whose alpha spans at most 256, src/kernels/roughness_fibre.rs), in the narrowest lobe's u up to theta_h = 45 degrees and theta_h beyond, D and masking per lobe, each texel keeping its own channels' estimates. The eta >= 1 texels of one roughness and view cosine share one rule, up to 8 slices as its channels A, B, T_1..T_8 (A and B do not depend on eta there; each texel keeps its own channels' estimates). Evaluations count the u nodes, once however many texels they serve"),
        TableKind::DielectricAlbedoAvg => "E_avg = (1/pi) int D(h) Phi(theta_h) dw_h with Phi = int c [F(c) G(v, l_r) + (1 - F(c)) G(v, l_t)] dw_v in coordinates of v about h (c = v.h, azimuth psi), the order of the v- and h-integrals exchanged (src/kernels/dielectric_average.rs): outer u = asinh(tan theta_h / alpha) with a square-root panel end at theta_h = acos eta (eta < 1), middle c in [0, 1] with square-root panel ends at sin theta_h, the critical cosine and sqrt(1 - eta^2 cos^2 theta_h), inner psi over its closed-form range; each panel by nested Clenshaw-Curtis (9 to 65 nodes; 33 in psi; error estimated from the coarser levels' differences in u, by their geometric tail in c and psi), else adaptive Gauss-Kronrod (G7/K15); the eta >= 1 texels of one roughness as the channels of one rule, up to 8, sharing the reflected part; eta < 1 texels alone; f64 accumulation. Evaluations count the psi nodes".into(),
        TableKind::Albedo
        | TableKind::AlbedoAvg
        | TableKind::Dfg
        | TableKind::KullaConty
        | TableKind::AlbedoFresnel
            if spec.model.masking != Masking::VGroove || spec.model.ndf.is_none() =>
        {
            let outer = if spec.kind == TableKind::AlbedoAvg {
                "E_avg: adaptive Gauss-Kronrod (G7/K15) over mu of E(mu), each E(mu) as follows. "
            } else if spec.kind == TableKind::KullaConty {
                "E_avg channel: adaptive Gauss-Kronrod (G7/K15) over mu of E(mu); E(mu), there and in the E channel, as follows. "
            } else {
                ""
            };
            format!("{outer}{}", crate::hemisphere::tensor::METHOD)
        }
        // V-groove masking with an NDF: the branch-split tensor rule
        _ => {
            let outer = match spec.kind {
                TableKind::AlbedoAvg => "E_avg: adaptive Gauss-Kronrod (G7/K15) over mu of E(mu), each E(mu) as follows. ",
                TableKind::KullaConty => "E_avg channel: adaptive Gauss-Kronrod (G7/K15) over mu of E(mu); E(mu), there and in the E channel, as follows. ",
                _ => "",
            };
            format!("{outer}{}", crate::kernels::vgroove::METHOD)
        }
    };
    let method =
        if spec.kind == TableKind::Dfg && spec.cloth && spec.model.masking == Masking::VGroove {
            format!(
                "{method}. Cloth channel B: {}",
                crate::hemisphere::tensor::METHOD
            )
        } else {
            method
        };
    let kernel = match spec.kind {
        TableKind::Dfg => spec.cloth || split_sum_uses_kernel(spec.model.ndf, spec.model.masking),
        TableKind::Albedo | TableKind::AlbedoAvg | TableKind::KullaConty => {
            albedo_uses_kernel(&spec.model)
        }
        // Schlick slices of GGX + Smith: E = F0·A + B from the polar split sum
        TableKind::AlbedoFresnel => {
            matches!(spec.axes[2].quantity, Quantity::Fresnel(q) if q.is_f0())
                && spec.model.diffuse_weight == 0.0
                && split_sum_uses_kernel(spec.model.ndf, spec.model.masking)
        }
        _ => false,
    };
    let charlie_albedo = matches!(
        spec.kind,
        TableKind::Albedo | TableKind::AlbedoAvg | TableKind::KullaConty
    ) && spec.model.ndf == Some(crate::model::NdfKind::Charlie);
    let method = if kernel && charlie_albedo && spec.model.masking != Masking::Ashikhmin {
        // Charlie + Conty-Kulla, F = 1: the light-cosine kernel
        format!(
            "{}; where that fails, the generic path: {method}",
            crate::kernels::sheen_polar::METHOD,
        )
    } else if kernel && charlie_albedo {
        // Charlie + Ashikhmin, F = 1: the cloth kernels of the filament-dfg cloth channel
        // (src/table/albedo.rs `charlie_kernels`)
        format!(
            "Charlie/Ashikhmin cloth kernel: {}; where that declines (views within 1e-3 of the normal) or fails, the generic path: {method}",
            crate::kernels::sheen_azimuth::METHOD,
        )
    } else if kernel {
        format!(
            "{} (GGX with Smith masking); where its estimate fails, the generic path: {method}",
            crate::kernels::ggx_polar::METHOD,
        )
    } else {
        method
    };
    let method = if uses_fresnel_fibre(spec) {
        format!(
            "{} Where that fails, texel by texel: {method}",
            FRESNEL_FIBRE_METHOD
        )
    } else {
        method
    };
    let method = if spec.kind == TableKind::Dfg && split_sum_by_lines(spec) {
        format!(
            "Split-sum channels by lines (src/table/dfg_lines.rs): on tables of at least 128 columns, the rows with alpha >= 1/64, and those of [1/256, 1/64) where that band holds at least 24 rows, on grids: interpolated across the table in x = sqrt(mu) from whole columns (at tolerance/8), each column interpolated along the roughness axis in y = ln(alpha) (nodes at tolerance/4 of the column's); every other row along the row in x = sqrt(mu), cut at mu = 0.073 too. Lines across the table are first cut at mu = 0.01 (texels closer to grazing: usually computed directly, a column at a time on grids). Interpolation: {} Each quadrature: {method}",
            crate::quadrature::interp1d::METHOD
        )
    } else {
        method
    };
    let method = if albedo_by_lines(spec) {
        format!(
            "By lines (src/table/dfg_lines.rs), the plan of the dfg table's cloth channel: wide lobes (1/16 <= alpha <= 1) on a grid (columns in y = sqrt(alpha), nodes at tolerance/4 of the column's), narrow lobes along each row in x = sqrt(mu) (nodes at tolerance/8), texel by texel near grazing views; each node or direct texel: {method}"
        )
    } else {
        method
    };
    let method = if spec.kind == TableKind::Dfg && spec.cloth {
        let interpolated = if split_sum_by_lines(spec) {
            "interpolated by the same rule: wide lobes (1/16 <= alpha <= 1) on a grid as above (columns in y = sqrt(alpha), their nodes at tolerance/4 of the column's) on tables of at least 128 columns, else along each column in y = sqrt(alpha) (nodes at tolerance/4); narrow lobes (alpha < 1/16) along each row in x = sqrt(mu) above mu = 0.04 (nodes at tolerance/8) and below it texel by texel; or, from 64 narrow rows on, below mu = 0.01 along each texel column in y = ln(alpha) and above it on a grid for alpha >= 1/1024 (columns in y = sqrt(alpha)), by rows below (nodes at tolerance/8); each node or direct texel: "
        } else {
            ""
        };
        format!(
            "{method}. Cloth channel B {interpolated}first {}; where that declines or fails, the generic path above",
            crate::kernels::sheen_azimuth::METHOD,
        )
    } else {
        method
    };
    method
}
