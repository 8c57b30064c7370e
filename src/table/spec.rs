//! What to bake: a validated table specification. Built from a preset (see `preset.rs`) or
//! directly by library users; every field is explicit, nothing is guessed.

use crate::lut::Axis;
use crate::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
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
    /// Directional albedo E = R + T of a rough dielectric interface (GGX, exact Fresnel):
    /// the light reflected or transmitted by single scattering, over (cos θv; roughness; η),
    /// 3D (Cycles' `glass_E`, `glass_inv_E`).
    DielectricAlbedo,
    /// Average albedo E_avg = 2∫E(μ)μ dμ of a rough dielectric interface over (roughness; η),
    /// 2D (Cycles' `glass_Eavg`, `glass_inv_Eavg`).
    DielectricAlbedoAvg,
    /// The mean of the generalized-Schlick blend weight s(v·h) (F = F0 + (F90 − F0) s) over
    /// the GGX visible normals, over (cos θv; roughness; exponent or η), 3D (Cycles'
    /// `gen_schlick_s`, `gen_schlick_ior_s`; `table::schlick_weight`).
    SchlickWeightVndf,
    /// The albedo-weighted mean of the generalized-Schlick blend weight, over (cos θv;
    /// roughness; exponent or η), 3D (`table::schlick_weight`).
    SchlickWeightAlbedo,
    /// The Schlick split sum of a rough dielectric interface (GGX): A, B, T with reflectance
    /// F0·A + F90·B and transmittance (1 − F0)·T, Schlick's weight on the less dense side,
    /// over (cos θv; roughness; η), 3D (EEVEE's `bsdf_ggx`, `btdf_ggx`;
    /// `table::dielectric_schlick`).
    DielectricSchlick,
    /// Directional albedo of a classic analytic model (Phong, Blinn-Phong, Ward,
    /// Ashikhmin–Shirley, Lafortune): E(cos θv; exponent or α), 2D (`table::classic`).
    ClassicAlbedo,
    /// Directional albedo of an anisotropic classic model (Ward, Ashikhmin–Shirley) over
    /// (cos θv; exponent or α; anisotropy), 3D, per view azimuth and azimuth-averaged.
    ClassicAlbedoAniso,
    /// Linearly transformed cosines for area lights (Heitz et al. 2016) over (cos θv;
    /// roughness), 2D: the fitted M⁻¹ in Heitz's normalization, the norm, the Fresnel term,
    /// the horizon-clipped sphere table, as the preset's `ltc.channels` choose
    /// (`table::ltc`).
    Ltc,
    /// The horizon-clipped sphere table of Heitz & Hill 2017 (EEVEE's `ltc_disk_integral`)
    /// over (z, length) of a vector form factor, 2D (`table::ltc`).
    LtcSphere,
}

impl TableKind {
    pub const ALL: [TableKind; 15] = [
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
        TableKind::DielectricAlbedo,
        TableKind::DielectricAlbedoAvg,
        TableKind::SchlickWeightVndf,
        TableKind::SchlickWeightAlbedo,
        TableKind::DielectricSchlick,
    ];

    /// The kinds of the classic analytic models (`table::classic`); not in [`Self::ALL`],
    /// which lists the microfacet kinds a [`ModelSpec`] without `classic` bakes.
    pub const CLASSIC: [TableKind; 2] = [TableKind::ClassicAlbedo, TableKind::ClassicAlbedoAniso];

    /// The rough dielectric kinds (GGX interface, exact Fresnel of the fresnel axis' η,
    /// integrated over micro-normals by [`crate::kernels::micro_normals`]).
    pub fn is_dielectric(self) -> bool {
        matches!(
            self,
            TableKind::DielectricBtdf
                | TableKind::DielectricAlbedo
                | TableKind::DielectricAlbedoAvg
        )
    }

    /// Whether this is one of [`Self::CLASSIC`].
    pub fn is_classic(self) -> bool {
        Self::CLASSIC.contains(&self)
    }

    /// The area-light kinds (`table::ltc`); not in [`Self::ALL`].
    pub const LTC: [TableKind; 2] = [TableKind::Ltc, TableKind::LtcSphere];

    /// Whether this is one of [`Self::LTC`].
    pub fn is_ltc(self) -> bool {
        Self::LTC.contains(&self)
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
            TableKind::DielectricAlbedo => "dielectric-albedo",
            TableKind::DielectricAlbedoAvg => "dielectric-albedo-avg",
            TableKind::SchlickWeightVndf => "schlick-weight-vndf",
            TableKind::SchlickWeightAlbedo => "schlick-weight-albedo",
            TableKind::DielectricSchlick => "dielectric-schlick",
            TableKind::ClassicAlbedo => "classic-albedo",
            TableKind::ClassicAlbedoAniso => "classic-albedo-aniso",
            TableKind::Ltc => "ltc",
            TableKind::LtcSphere => "ltc-sphere",
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
            TableKind::AlbedoFresnel
            | TableKind::DielectricBtdf
            | TableKind::DielectricAlbedo
            | TableKind::SchlickWeightVndf
            | TableKind::SchlickWeightAlbedo
            | TableKind::DielectricSchlick => &["cos_theta_v", "roughness", "fresnel"],
            TableKind::DielectricAlbedoAvg => &["roughness", "fresnel"],
            TableKind::ClassicAlbedo => &["cos_theta_v", "roughness"],
            TableKind::ClassicAlbedoAniso => &["cos_theta_v", "roughness", "anisotropy"],
            TableKind::Ltc => &["cos_theta_v", "roughness"],
            TableKind::LtcSphere => &["form_factor_z", "form_factor_length"],
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
            TableKind::DielectricAlbedo => {
                "rough dielectric interface: directional albedo E = R + T(cos theta_v; roughness; eta)"
            }
            TableKind::SchlickWeightVndf => {
                "generalized-Schlick blend weight s(v.h) = (1 - v.h)^e or the normalized exact dielectric Fresnel, averaged over the GGX visible normals: S_vndf(cos theta_v; roughness; exponent or eta) (Cycles' gen_schlick tables)"
            }
            TableKind::SchlickWeightAlbedo => {
                "generalized-Schlick blend weight s(v.h) = (1 - v.h)^e or the normalized exact dielectric Fresnel, albedo-weighted: S_albedo = int s f cos / int f cos (cos theta_v; roughness; exponent or eta)"
            }
            TableKind::DielectricSchlick => {
                "Schlick split sum of a rough dielectric interface: A, B, T(cos theta_v; roughness; eta), reflectance F0 A + F90 B, transmittance (1 - F0) T, Schlick's weight on the less dense side (EEVEE's bsdf_ggx, btdf_ggx)"
            }
            TableKind::DielectricAlbedoAvg => {
                "rough dielectric interface: average albedo E_avg = 2 int_0^1 (R + T)(mu) mu dmu (roughness; eta)"
            }
            TableKind::ClassicAlbedo => {
                "directional albedo E(cos theta_v; exponent or alpha) of a classic model (phong, blinn-phong, ward, ashikhmin-shirley, lafortune)"
            }
            TableKind::ClassicAlbedoAniso => {
                "directional albedo E(cos theta_v; exponent or alpha; anisotropy) of ward or ashikhmin-shirley: view azimuth average, at 0 and at 90 degrees"
            }
            TableKind::Ltc => {
                "linearly transformed cosine (area lights) over (cos theta_v; roughness): the fitted M^-1, the norm int f cos, the Fresnel term int (1 - v.h)^5 f cos, the horizon-clipped sphere table"
            }
            TableKind::LtcSphere => {
                "horizon-clipped sphere table (area lights): the clamped cosine's integral over a sphere whose vector form factor has length len and direction z, divided by len"
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
    /// Karis' A, B and the F82-tint channel `F82 = ∫ (v·h)(1 − v·h)⁶ f cos` (EEVEE's
    /// `brdf_ggx[64][64][3]` "metal_bias"): the albedo of the F82-tint Fresnel
    /// F = F_Schlick − b (v·h)(1 − v·h)⁶ (Hoffman 2023, "Generalization of Adobe's Fresnel
    /// Model"; Kutz et al. 2021) is `F0 A + B − b F82`.
    KarisF82,
    /// Filament (Lagarde & de Rousiers 2014 / Filament's multiscatter): R = ∫ Fc f cos,
    /// G = ∫ f cos; E = mix(R, G, F0); optional cloth B = ∫ D_Charlie·V_Ashikhmin·cos.
    Filament,
}

/// One channel of an `ltc` table (the preset's `ltc.channels`; `table::ltc` says what each
/// holds).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LtcChannel {
    /// Entries of the fitted `M⁻¹` divided by its middle entry `m11` (Heitz's
    /// normalization): row 0 column 0, row 2 column 0, row 0 column 2, row 2 column 2.
    M00,
    M20,
    M02,
    M22,
    /// `∫ f cos`: the BRDF's directional albedo (F = 1).
    Norm,
    /// `∫ (1 − v·h)⁵ f cos`: the Schlick-weighted part.
    Fresnel,
    /// The horizon-clipped sphere table at the texel's position in the texture.
    Sphere,
    /// 0 (padding).
    Zero,
}

impl LtcChannel {
    pub const ALL: [LtcChannel; 8] = [
        LtcChannel::M00,
        LtcChannel::M20,
        LtcChannel::M02,
        LtcChannel::M22,
        LtcChannel::Norm,
        LtcChannel::Fresnel,
        LtcChannel::Sphere,
        LtcChannel::Zero,
    ];

    /// The channels of an `ltc` table whose preset does not list them: the matrix, the norm
    /// and the Fresnel term (an EXR; a texture holds 4, so engines split them over two
    /// tables: `presets/engines/heitz-ltc.json`).
    pub const DEFAULT: [LtcChannel; 6] = [
        LtcChannel::M00,
        LtcChannel::M20,
        LtcChannel::M02,
        LtcChannel::M22,
        LtcChannel::Norm,
        LtcChannel::Fresnel,
    ];

    pub fn name(self) -> &'static str {
        match self {
            LtcChannel::M00 => "m00",
            LtcChannel::M20 => "m20",
            LtcChannel::M02 => "m02",
            LtcChannel::M22 => "m22",
            LtcChannel::Norm => "norm",
            LtcChannel::Fresnel => "fresnel",
            LtcChannel::Sphere => "sphere",
            LtcChannel::Zero => "zero",
        }
    }

    /// Whether the channel is an entry of the fitted matrix.
    pub fn is_matrix(self) -> bool {
        matches!(
            self,
            LtcChannel::M00 | LtcChannel::M20 | LtcChannel::M02 | LtcChannel::M22
        )
    }
}

/// Storage precision of the written textures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Storage {
    /// IEEE 754 binary32.
    F32,
    /// IEEE 754 binary16, rounded to nearest (ties to even).
    F16,
    /// 8-bit unsigned normalized: code = round(v·255), read back as code/255 ∈ [0, 1].
    Unorm8,
    /// 16-bit unsigned normalized: code = round(v·65535), read back as code/65535 ∈ [0, 1].
    Unorm16,
}

impl Storage {
    pub const ALL: [Storage; 4] = [
        Storage::F32,
        Storage::F16,
        Storage::Unorm8,
        Storage::Unorm16,
    ];

    /// The name a preset and the sidecar use (`f32`, `f16`, `unorm8`, `unorm16`).
    pub fn name(self) -> &'static str {
        match self {
            Storage::F32 => "f32",
            Storage::F16 => "f16",
            Storage::Unorm8 => "unorm8",
            Storage::Unorm16 => "unorm16",
        }
    }

    /// Bytes of one stored component.
    pub fn bytes(self) -> usize {
        match self {
            Storage::F32 => 4,
            Storage::F16 | Storage::Unorm16 => 2,
            Storage::Unorm8 => 1,
        }
    }

    /// Whether this is a normalized-integer storage (values in [0, 1] as codes).
    pub fn is_unorm(self) -> bool {
        matches!(self, Storage::Unorm8 | Storage::Unorm16)
    }

    /// The largest code of a normalized-integer storage, 2ⁿ − 1 (255, 65535); `None` for
    /// the float storages.
    pub fn unorm_max(self) -> Option<u32> {
        match self {
            Storage::Unorm8 => Some(255),
            Storage::Unorm16 => Some(65535),
            Storage::F32 | Storage::F16 => None,
        }
    }

    /// The quantization step of a normalized-integer storage, 1/(2ⁿ − 1), in stored units
    /// (a rounded value is off by at most half of it); `None` for the float storages.
    pub fn quantization_step(self) -> Option<f64> {
        self.unorm_max().map(|m| 1.0 / m as f64)
    }
}

/// The BRDF model of a table, before a roughness is chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelSpec {
    /// The specular lobe's NDF; `None` for a purely diffuse model.
    pub ndf: Option<NdfKind>,
    pub masking: Masking,
    pub fresnel: Fresnel,
    /// Weight w_d of the diffuse lobe (0 = none).
    pub diffuse_weight: f64,
    /// The diffuse lobe's model (the preset's `model.diffuse_model`; Lambert by default).
    pub diffuse_model: crate::model::DiffuseModel,
    /// The classic analytic model of a `classic-albedo` / `classic-albedo-aniso` table
    /// (then `ndf` is `None`, `masking` none, `fresnel` none, `diffuse_weight` 0: the
    /// classic model carries its own weights); `None` for every other kind.
    pub classic: Option<super::classic_model::ClassicModel>,
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
            diffuse: self.diffuse_model.lobe(alpha),
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
    /// Add the cloth channel (dfg tables): ∫ D_Charlie(α)·V_Ashikhmin·cos.
    pub cloth: bool,
    /// The cloth channel's Charlie parameter is `max(α, cloth_alpha_min)` (MaterialX's
    /// `max(r, 0.005)`); the split-sum channels keep α. `None`: α itself.
    pub cloth_alpha_min: Option<f64>,
    /// The channels of an `ltc` table (the preset's `ltc.channels`, or
    /// [`LtcChannel::DEFAULT`]); `None` for every other kind.
    pub ltc_channels: Option<Vec<LtcChannel>>,
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
