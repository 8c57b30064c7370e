//! Roughness parameterizations and their mappings to the NDF's own parameter.
//!
//! Engines disagree silently on what "roughness" means; every table axis in brdfbake
//! names one of these quantities and the metadata lists the α of every texel.

use super::ndf::{alpha_from_exponent, NdfKind};

/// The quantity a roughness axis is expressed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RoughnessQuantity {
    /// α, the NDF's own width parameter (for the Gaussian, its m; for Blinn-Phong, the
    /// Beckmann-equivalent α of its exponent).
    Alpha,
    /// Perceptual roughness r with α = r² (Burley 2012; Karis 2013; Filament, Unreal,
    /// glTF's `roughnessFactor`).
    Perceptual,
    /// Cook–Torrance's m: the RMS slope of Beckmann, the angular width (radians) of the
    /// Gaussian. Only for those two NDFs, where it *is* their parameter (α = m).
    CookTorranceM,
    /// Blinn-Phong exponent s, α = √(2/(s + 2)) (Walter et al. 2007, §5.2). Only for the
    /// Blinn-Phong NDF.
    BlinnPhongExponent,
    /// The lobe exponent of a classic model (Phong n, Blinn-Phong s, Ashikhmin–Shirley n,
    /// Lafortune n) taken as is by `classic-albedo` tables; the α listed for it is the
    /// Beckmann-equivalent width √(2/(n + 2)) (Walter et al. 2007, §5.2), for information.
    /// No NDF takes it.
    Exponent,
}

impl RoughnessQuantity {
    pub const ALL: [RoughnessQuantity; 5] = [
        RoughnessQuantity::Alpha,
        RoughnessQuantity::Perceptual,
        RoughnessQuantity::CookTorranceM,
        RoughnessQuantity::BlinnPhongExponent,
        RoughnessQuantity::Exponent,
    ];

    pub fn name(self) -> &'static str {
        match self {
            RoughnessQuantity::Alpha => "alpha",
            RoughnessQuantity::Perceptual => "perceptual",
            RoughnessQuantity::CookTorranceM => "cook-torrance-m",
            RoughnessQuantity::BlinnPhongExponent => "blinn-phong-exponent",
            RoughnessQuantity::Exponent => "exponent",
        }
    }

    pub fn mapping(self) -> &'static str {
        match self {
            RoughnessQuantity::Alpha => "alpha = coordinate",
            RoughnessQuantity::Perceptual => "alpha = coordinate^2",
            RoughnessQuantity::CookTorranceM => "alpha = m = coordinate",
            RoughnessQuantity::BlinnPhongExponent => "alpha = sqrt(2/(coordinate + 2))",
            RoughnessQuantity::Exponent => {
                "exponent = coordinate (a classic model's lobe exponent); alpha = sqrt(2/(coordinate + 2)) is its Beckmann-equivalent width, for information"
            }
        }
    }

    /// Whether this quantity is meaningful for the NDF.
    pub fn applies_to(self, ndf: NdfKind) -> bool {
        match self {
            RoughnessQuantity::Alpha | RoughnessQuantity::Perceptual => true,
            RoughnessQuantity::CookTorranceM => {
                matches!(ndf, NdfKind::Beckmann | NdfKind::Gaussian)
            }
            RoughnessQuantity::BlinnPhongExponent => ndf == NdfKind::BlinnPhong,
            RoughnessQuantity::Exponent => false,
        }
    }

    /// α for a coordinate value (no validation of α's range beyond finiteness).
    pub fn to_alpha(self, value: f64) -> f64 {
        match self {
            RoughnessQuantity::Alpha | RoughnessQuantity::CookTorranceM => value,
            RoughnessQuantity::Perceptual => value * value,
            RoughnessQuantity::BlinnPhongExponent | RoughnessQuantity::Exponent => {
                alpha_from_exponent(value)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ndf::blinn_phong_exponent;

    #[test]
    fn mappings_round_trip() {
        assert_eq!(RoughnessQuantity::Perceptual.to_alpha(0.5), 0.25);
        let s = 37.0;
        let a = RoughnessQuantity::BlinnPhongExponent.to_alpha(s);
        assert!((blinn_phong_exponent(a) - s).abs() < 1e-12);
        assert!(!RoughnessQuantity::CookTorranceM.applies_to(NdfKind::Ggx));
        assert!(!RoughnessQuantity::BlinnPhongExponent.applies_to(NdfKind::Beckmann));
    }
}
