//! What to bake: a validated table specification. Built from a preset (see `preset.rs`) or
//! directly by library users; every field is explicit, nothing is guessed.

use crate::lut::{Axis, Convention, Quantity};
use crate::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, RoughnessQuantity, Specular};
use serde::{Deserialize, Serialize};

/// The kinds of table brdfbake bakes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TableKind {
    /// D(cos θh; roughness), 2D.
    Ndf,
    /// Smith G1(cos θ; roughness), 2D.
    G1,
    /// G2(cos θv, cos θl; roughness), 3D.
    G2,
    /// Cook–Torrance's V-groove G(n·l, n·h, n·v), 3D (roughness-independent).
    Vgroove,
    /// Directional albedo E(cos θv; roughness), 2D.
    Albedo,
    /// Average albedo E_avg(roughness) = 2∫E(μ)μ dμ, 1D.
    AlbedoAvg,
    /// Split-sum DFG table, 2D.
    Dfg,
    /// Kulla–Conty inputs in one texture: E(cos θv; roughness) and E_avg(roughness), 2D.
    KullaConty,
    /// Fresnel-resolved directional albedo E(cos θv; roughness; F0 or η), 3D.
    AlbedoFresnel,
    /// Rough dielectric interface (GGX, Walter et al. 2007): reflection and transmission
    /// albedo R, T over (cos θv; roughness; η), 3D.
    DielectricBtdf,
    /// Directional albedo of a classic analytic model (Phong, Blinn-Phong, Ward,
    /// Ashikhmin–Shirley, Lafortune): E(cos θv; exponent or α), 2D (`table::classic`).
    ClassicAlbedo,
    /// Directional albedo of an anisotropic classic model (Ward, Ashikhmin–Shirley) over
    /// (cos θv; exponent or α; anisotropy), 3D, per view azimuth and azimuth-averaged.
    ClassicAlbedoAniso,
}

impl TableKind {
    pub const ALL: [TableKind; 10] = [
        TableKind::Ndf,
        TableKind::G1,
        TableKind::G2,
        TableKind::Vgroove,
        TableKind::Albedo,
        TableKind::AlbedoAvg,
        TableKind::Dfg,
        TableKind::KullaConty,
        TableKind::AlbedoFresnel,
        TableKind::DielectricBtdf,
    ];

    /// The kinds of the classic analytic models (`table::classic`); not in [`Self::ALL`],
    /// which lists the microfacet kinds a [`ModelSpec`] without `classic` bakes.
    pub const CLASSIC: [TableKind; 2] = [TableKind::ClassicAlbedo, TableKind::ClassicAlbedoAniso];

    /// Whether this is one of [`Self::CLASSIC`].
    pub fn is_classic(self) -> bool {
        Self::CLASSIC.contains(&self)
    }

    pub fn name(self) -> &'static str {
        match self {
            TableKind::Ndf => "ndf",
            TableKind::G1 => "g1",
            TableKind::G2 => "g2",
            TableKind::Vgroove => "vgroove",
            TableKind::Albedo => "albedo",
            TableKind::AlbedoAvg => "albedo-avg",
            TableKind::Dfg => "dfg",
            TableKind::KullaConty => "kulla-conty",
            TableKind::AlbedoFresnel => "albedo-fresnel",
            TableKind::DielectricBtdf => "dielectric-btdf",
            TableKind::ClassicAlbedo => "classic-albedo",
            TableKind::ClassicAlbedoAniso => "classic-albedo-aniso",
        }
    }

    /// The axes this kind has, fastest first: (name, is a roughness axis).
    pub fn axis_names(self) -> &'static [&'static str] {
        match self {
            TableKind::Ndf => &["cos_theta_h", "roughness"],
            TableKind::G1 => &["cos_theta", "roughness"],
            TableKind::G2 => &["cos_theta_v", "cos_theta_l", "roughness"],
            TableKind::Vgroove => &["n_dot_l", "n_dot_h", "n_dot_v"],
            TableKind::Albedo | TableKind::Dfg => &["cos_theta_v", "roughness"],
            TableKind::AlbedoAvg => &["roughness"],
            TableKind::KullaConty => &["cos_theta_v", "roughness"],
            TableKind::AlbedoFresnel | TableKind::DielectricBtdf => {
                &["cos_theta_v", "roughness", "fresnel"]
            }
            TableKind::ClassicAlbedo => &["cos_theta_v", "roughness"],
            TableKind::ClassicAlbedoAniso => &["cos_theta_v", "roughness", "anisotropy"],
        }
    }

    pub fn description(self) -> &'static str {
        match self {
            TableKind::Ndf => "normal distribution D(n.h; roughness)",
            TableKind::G1 => "Smith masking G1(cos theta; roughness) = 1/(1 + Lambda)",
            TableKind::G2 => "masking-shadowing G2(cos theta_v, cos theta_l; roughness)",
            TableKind::Vgroove => "Cook-Torrance V-groove G(n.l, n.h, n.v)",
            TableKind::Albedo => {
                "directional albedo E(cos theta_v; roughness) = int f(v,l) (n.l) dl"
            }
            TableKind::AlbedoAvg => "average albedo E_avg(roughness) = 2 int_0^1 E(mu) mu dmu",
            TableKind::Dfg => "split-sum DFG (Karis A/B or Filament multiscatter R/G[/cloth])",
            TableKind::KullaConty => {
                "Kulla-Conty energy compensation: E(cos theta_v; roughness) and E_avg(roughness) at F = 1"
            }
            TableKind::AlbedoFresnel => {
                "Fresnel-resolved directional albedo E(cos theta_v; roughness; F0 or eta)"
            }
            TableKind::DielectricBtdf => {
                "rough dielectric interface: reflection and transmission albedo R, T(cos theta_v; roughness; eta)"
            }
            TableKind::ClassicAlbedo => {
                "directional albedo E(cos theta_v; exponent or alpha) of a classic model (phong, blinn-phong, ward, ashikhmin-shirley, lafortune)"
            }
            TableKind::ClassicAlbedoAniso => {
                "directional albedo E(cos theta_v; exponent or alpha; anisotropy) of ward or ashikhmin-shirley: view azimuth average, at 0 and at 90 degrees"
            }
        }
    }
}

/// Channel layout of a `dfg` table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DfgLayout {
    /// Karis 2013: A = ∫(1 − Fc) f cos, B = ∫ Fc f cos; E = F0·A + B.
    Karis,
    /// Filament (Lagarde & de Rousiers 2014 / Filament's multiscatter): R = ∫ Fc f cos,
    /// G = ∫ f cos; E = mix(R, G, F0); optional cloth B = ∫ D_Charlie·V_Ashikhmin·cos.
    Filament,
}

/// Storage precision of the written textures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Storage {
    F32,
    F16,
}

/// The BRDF model of a table, before a roughness is chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelSpec {
    /// The specular lobe's NDF; `None` for a purely diffuse model.
    pub ndf: Option<NdfKind>,
    pub masking: Masking,
    pub fresnel: Fresnel,
    /// Weight of the Lambertian lobe w_d/π (0 = none).
    pub diffuse_weight: f64,
    /// The classic analytic model of a `classic-albedo` / `classic-albedo-aniso` table
    /// (then `ndf` is `None`, `masking` none, `fresnel` none, `diffuse_weight` 0: the
    /// classic model carries its own weights); `None` for every other kind.
    pub classic: Option<super::classic::ClassicModel>,
}

impl ModelSpec {
    /// The BRDF at NDF parameter α.
    pub fn brdf(&self, alpha: f64) -> Result<Brdf, String> {
        let specular = match self.ndf {
            Some(kind) => Some(Specular {
                ndf: Ndf::new(kind, alpha)?,
                masking: self.masking,
                fresnel: self.fresnel,
            }),
            None => None,
        };
        Ok(Brdf {
            specular,
            diffuse_weight: self.diffuse_weight,
        })
    }
}

/// A validated table specification.
#[derive(Clone, Debug, PartialEq)]
pub struct TableSpec {
    /// File stem of the outputs.
    pub name: String,
    pub kind: TableKind,
    pub model: ModelSpec,
    /// Axes in the order of [`TableKind::axis_names`].
    pub axes: Vec<Axis>,
    pub dfg_layout: Option<DfgLayout>,
    /// Filament layout only: add the cloth channel.
    pub cloth: bool,
    pub storage: Storage,
    /// Target max absolute error of the quadrature per texel.
    pub tolerance: f64,
}

/// The smallest cosine accepted on an axis whose kind divides by it (albedo, dfg, …; see
/// [`TableSpec::validate`]): these integrals reach their grazing limit long before (E at
/// μ = 1e-12 equals its limit to 1e-12), while below ~1e-154 μ² underflows and the
/// integrand is not finite.
pub const MIN_COSINE: f64 = 1e-12;

/// The tightest accepted quadrature tolerance: f64 sums of ~10⁴ terms of size ~1 carry
/// rounding errors of ~1e-13, so a tighter estimate would be noise (and the rules would
/// refine until their budgets run out).
pub const MIN_TOLERANCE: f64 = 1e-12;
/// The loosest accepted tolerance.
pub const MAX_TOLERANCE: f64 = 1e-2;

/// Limits on sizes, so a typo cannot ask for a terabyte.
pub const MAX_AXIS_SIZE: usize = 4096;
pub const MAX_TEXELS: usize = 1 << 24;

impl TableSpec {
    /// Checks everything that can be checked before baking: model/kind compatibility and
    /// every texel's coordinate. Errors name the field (`tables[i].…` is prefixed by the
    /// caller) and what is accepted.
    pub fn validate(&self) -> Result<(), String> {
        let kind = self.kind;
        let names = kind.axis_names();
        if self.axes.len() != names.len() {
            return Err(format!("a {} table has axes {:?}", kind.name(), names));
        }
        let mut texels: usize = 1;
        for (ax, want) in self.axes.iter().zip(names) {
            if ax.name != *want {
                return Err(format!(
                    "axis {:?} should be {want:?} for a {} table",
                    ax.name,
                    kind.name()
                ));
            }
            let f = format!("axes.{}", ax.name);
            if ax.size == 0 || ax.size > MAX_AXIS_SIZE {
                return Err(format!(
                    "{f}.size must be in 1..={MAX_AXIS_SIZE}, got {}",
                    ax.size
                ));
            }
            texels = texels.saturating_mul(ax.size);
            let [lo, hi] = ax.range;
            if !(lo.is_finite() && hi.is_finite()) || lo > hi || (lo == hi && ax.size > 1) {
                return Err(format!(
                    "{f}.range must be two finite numbers [lo, hi] with lo < hi, got [{lo}, {hi}]",
                    lo = crate::numfmt::num(lo),
                    hi = crate::numfmt::num(hi)
                ));
            }
            if ax.convention == Convention::Endpoints && ax.size < 2 {
                return Err(format!("{f}: the endpoints convention needs size >= 2"));
            }
            match ax.quantity {
                Quantity::Cosine => {
                    if lo < 0.0 || hi > 1.0 {
                        return Err(format!(
                            "{f}.range must lie within [0, 1] (a cosine), got [{lo}, {hi}]",
                            lo = crate::numfmt::num(lo),
                            hi = crate::numfmt::num(hi)
                        ));
                    }
                    let zero_ok = !matches!(
                        (kind, ax.name.as_str()),
                        (TableKind::Albedo, _)
                            | (TableKind::Dfg, _)
                            | (TableKind::KullaConty, _)
                            | (TableKind::AlbedoFresnel, _)
                            | (TableKind::ClassicAlbedo, _)
                            | (TableKind::ClassicAlbedoAniso, _)
                            | (TableKind::Vgroove, "n_dot_h")
                    );
                    if !zero_ok && ax.coord(0) <= 0.0 {
                        return Err(format!(
                            "{f}: a texel at cosine 0 is not allowed for a {} table (the quantity is undefined at 0: \
                             it divides by {}); use the centers convention or a range starting above 0",
                            kind.name(),
                            if ax.name == "n_dot_h" { "n.h" } else { "n.v" }
                        ));
                    }
                    if !zero_ok && ax.coord(0) < MIN_COSINE {
                        return Err(format!(
                            "{f}: texel 0 is at cosine {}, below the smallest accepted {} for {} tables (they divide by {}: \
                             closer to grazing its angle's tangent passes 1e12, and in f64 the integrand overflows near 1e-154); \
                             start the range at {} or above",
                            crate::numfmt::num(ax.coord(0)),
                            crate::numfmt::num(MIN_COSINE),
                            kind.name(),
                            if ax.name == "n_dot_h" { "n.h" } else { "n.v" },
                            crate::numfmt::num(MIN_COSINE),
                        ));
                    }
                }
                Quantity::Fresnel(q) => {
                    if ax.name != "fresnel" {
                        return Err(format!(
                            "{f}: only the fresnel axis takes a Fresnel quantity"
                        ));
                    }
                    for i in 0..ax.size {
                        q.check(ax.coord(i))
                            .map_err(|e| format!("{f}: texel {i}: {e}"))?;
                    }
                }
                Quantity::Anisotropy => {
                    if ax.name != "anisotropy" || lo < 0.0 || hi > 1.0 {
                        return Err(format!(
                            "{f}.range must lie within [0, 1] (an anisotropy: 0 isotropic, 1 alpha_x/alpha_y = 10), got [{lo}, {hi}]", lo = crate::numfmt::num(lo), hi = crate::numfmt::num(hi)));
                    }
                }
                Quantity::Roughness(q) => {
                    if let Some(c) = &self.model.classic {
                        super::classic::check_parameter_axis(c, q, ax, &f)?;
                        continue;
                    }
                    let ndf = self.model.ndf;
                    if let Some(n) = ndf {
                        if !q.applies_to(n) {
                            return Err(format!(
                                "{f}.quantity {:?} does not apply to the {} NDF (accepted: {})",
                                q.name(),
                                n.name(),
                                RoughnessQuantity::ALL
                                    .iter()
                                    .filter(|r| r.applies_to(n))
                                    .map(|r| r.name())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ));
                        }
                    }
                    for i in 0..ax.size {
                        let x = ax.coord(i);
                        let a = q.to_alpha(x);
                        if !(a.is_finite() && a > 0.0) {
                            return Err(format!(
                                "{f}: texel {i} is at {} {x:e} (alpha {a:e}); every texel needs alpha > 0 \
                                 (use the centers convention or a range starting above 0)",
                                q.name()
                            ));
                        }
                        if let Some(n) = ndf {
                            Ndf::new(n, a).map_err(|e| format!("{f}: texel {i}: {e}"))?;
                        }
                    }
                }
            }
        }
        if texels > MAX_TEXELS {
            return Err(format!(
                "the table has {texels} texels; at most {MAX_TEXELS} are accepted"
            ));
        }
        self.model
            .fresnel
            .validate()
            .map_err(|e| format!("model.{e}"))?;
        let w = self.model.diffuse_weight;
        if !(w.is_finite() && (0.0..=1.0).contains(&w)) {
            return Err(format!(
                "model.diffuse must be a weight in [0, 1], got {w}",
                w = crate::numfmt::num(w)
            ));
        }
        if !(self.tolerance.is_finite()
            && self.tolerance >= MIN_TOLERANCE
            && self.tolerance <= MAX_TOLERANCE)
        {
            return Err(format!(
                "tolerance must be in [1e-12, 1e-2], got {}",
                crate::numfmt::num(self.tolerance)
            ));
        }
        let m = &self.model;
        if kind.is_classic() {
            return super::classic::validate(self);
        }
        if m.classic.is_some() {
            return Err(format!(
                "model.classic applies to classic-albedo and classic-albedo-aniso tables only, not {}",
                kind.name()
            ));
        }
        let need_ndf = |what: &str| -> Result<NdfKind, String> {
            m.ndf
                .ok_or_else(|| format!("model.ndf is required for a {} table{what}", kind.name()))
        };
        let only_spec = |why: &str| -> Result<(), String> {
            if m.diffuse_weight != 0.0 {
                return Err(format!(
                    "model.diffuse must be 0 for a {} table ({why})",
                    kind.name()
                ));
            }
            Ok(())
        };
        // Charlie is a sheen distribution, paired with the Ashikhmin visibility (Estevez &
        // Kulla 2017; Neubelt & Pettineo 2013): it has no closed-form Smith Λ, and without
        // masking its D/(4 n·v) albedo grows without bound at grazing views for narrow lobes
        // (α = 1e-9, cos θv = 1e-6: ~10⁴), which no absolute tolerance reaches in bounded time
        if m.ndf == Some(NdfKind::Charlie)
            && !matches!(kind, TableKind::Ndf | TableKind::G1)
            && m.masking != Masking::Ashikhmin
        {
            let what = if m.masking.is_smith() {
                "smith".to_string()
            } else {
                format!("{:?}", m.masking.name())
            };
            return Err(format!(
                "{what} masking of the charlie NDF is not supported: use masking ashikhmin (charlie is a sheen \
                 distribution, defined with the ashikhmin visibility)"
            ));
        }
        match kind {
            TableKind::Ndf => {
                need_ndf("")?;
            }
            TableKind::G1 => {
                let n = need_ndf("")?;
                if n == NdfKind::Charlie {
                    return Err("a g1 table of the charlie NDF is not supported: sheen uses the ashikhmin visibility, not Smith masking".into());
                }
            }
            TableKind::G2 => {
                let n = need_ndf("")?;
                if !(m.masking.is_smith() || m.masking == Masking::Ashikhmin) {
                    return Err(format!(
                        "model.masking {:?} is not a function of (cos theta_v, cos theta_l) alone; a g2 table accepts \
                         smith-separable, smith-height-correlated or ashikhmin (for the V-groove term use the vgroove kind)",
                        m.masking.name()
                    ));
                }
                if m.masking.is_smith() && n == NdfKind::Charlie {
                    return Err(
                        "smith masking of the charlie NDF is not supported: use masking ashikhmin"
                            .into(),
                    );
                }
            }
            TableKind::Vgroove => {
                if m.masking != Masking::VGroove {
                    return Err("a vgroove table needs model.masking \"v-groove\"".into());
                }
            }
            TableKind::Albedo | TableKind::AlbedoAvg => {
                if m.ndf.is_none() && m.diffuse_weight == 0.0 {
                    return Err(format!(
                        "a {} table needs a specular lobe (model.ndf) or a diffuse weight",
                        kind.name()
                    ));
                }
                if m.ndf == Some(NdfKind::Charlie) && m.masking.is_smith() {
                    return Err(
                        "smith masking of the charlie NDF is not supported: use masking ashikhmin"
                            .into(),
                    );
                }
            }
            TableKind::Dfg => {
                need_ndf("")?;
                only_spec("the split sum weights the specular lobe only")?;
                if m.fresnel != Fresnel::None {
                    return Err(format!(
                        "model.fresnel must be none for a dfg table: the split sum factors Schlick's Fresnel out \
                         (E = F0*A + B), got {:?}",
                        m.fresnel.name()
                    ));
                }
                if self.dfg_layout.is_none() {
                    return Err("a dfg table needs layout \"karis\" or \"filament\"".into());
                }
                if self.cloth && self.dfg_layout != Some(DfgLayout::Filament) {
                    return Err("cloth is only available with layout \"filament\"".into());
                }
            }
            TableKind::KullaConty | TableKind::AlbedoFresnel | TableKind::DielectricBtdf => {
                super::energy::validate(self)?;
            }
            TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => {
                unreachable!("validated above")
            }
        }
        if kind != TableKind::Dfg && (self.dfg_layout.is_some() || self.cloth) {
            return Err(format!(
                "layout and cloth apply to dfg tables only, not {}",
                kind.name()
            ));
        }
        Ok(())
    }
}
