//! The Fresnel parameter of a table axis (Fresnel-resolved albedo, dielectric BTDF tables):
//! which quantity the axis coordinate is, and how it maps to F0 or to the relative index η.
//!
//! `(η − 1)/(η + 1)` is the signed amplitude reflectance at normal incidence (its square is
//! F0 = ((η − 1)/(η + 1))², Cook & Torrance 1982, eq. 9): it maps η ∈ (0, ∞) onto (−1, 1)
//! with η = 1 at 0, η = 1/x at the mirror point −t of η = x, so one axis covers the inside
//! (η < 1) and outside (η > 1) of an interface with texels spread evenly in reflectance.
//! Its mirror image, `inverse-eta-reflectance` x = (1 − η)/(1 + η), is the same axis seen
//! from the other side: x ≥ 0 is η ≤ 1 (Cycles' `glass_inv_*` tables, which are indexed by
//! the reflectance of 1/η).
//!
//! The generalized Schlick Fresnel F = F0 + (F90 − F0)(1 − v·h)^e (Cycles) has a third kind of
//! parameter, its exponent e: `schlick-exponent` (x = e) and `schlick-exponent-ratio`
//! (x = 5/(5 + e), Cycles' axis: x = 1/2 is Schlick's 5, x = 1 is e = 0); only the
//! `schlick-weight` kind takes them.

/// The smallest relative index a Fresnel axis accepts (Cycles' `glass_inv_*` tables reach
/// η = 1/99.5).
pub const MIN_ETA: f64 = 1e-4;
/// The largest relative index a Fresnel axis accepts.
pub const MAX_ETA: f64 = 100.0;
/// The largest generalized Schlick exponent a Fresnel axis accepts (Cycles' table reaches
/// 5(1 − 1e-4)/1e-4 ≈ 5·10⁴).
pub const MAX_EXPONENT: f64 = 1e6;

/// What a `fresnel` axis coordinate is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FresnelQuantity {
    /// Schlick's F0 itself (Schlick Fresnel F = F0 + (1 − F0)(1 − v·h)⁵).
    F0,
    /// √F0: texels denser at small F0, where dielectrics are (F0 = coordinate²); Schlick.
    SqrtF0,
    /// The relative index of refraction η = η_inside/η_outside itself (exact Fresnel).
    Eta,
    /// t = (η − 1)/(η + 1) ∈ (−1, 1), η = (1 + t)/(1 − t) (exact Fresnel).
    EtaReflectance,
    /// t = (1 − η)/(1 + η) ∈ (−1, 1), η = (1 − t)/(1 + t): the reflectance of 1/η (exact
    /// Fresnel; t ≥ 0 is η ≤ 1, the view inside the denser medium).
    InverseEtaReflectance,
    /// The exponent e ≥ 0 of the generalized Schlick weight (1 − v·h)^e.
    SchlickExponent,
    /// x = 5/(5 + e) ∈ (0, 1], e = 5(1 − x)/x: the generalized Schlick exponent as Cycles
    /// spaces it (x = 1/2: e = 5).
    SchlickExponentRatio,
}

impl FresnelQuantity {
    pub const ALL: [FresnelQuantity; 7] = [
        FresnelQuantity::F0,
        FresnelQuantity::SqrtF0,
        FresnelQuantity::Eta,
        FresnelQuantity::EtaReflectance,
        FresnelQuantity::InverseEtaReflectance,
        FresnelQuantity::SchlickExponent,
        FresnelQuantity::SchlickExponentRatio,
    ];

    pub fn name(self) -> &'static str {
        match self {
            FresnelQuantity::F0 => "f0",
            FresnelQuantity::SqrtF0 => "sqrt-f0",
            FresnelQuantity::Eta => "eta",
            FresnelQuantity::EtaReflectance => "eta-reflectance",
            FresnelQuantity::InverseEtaReflectance => "inverse-eta-reflectance",
            FresnelQuantity::SchlickExponent => "schlick-exponent",
            FresnelQuantity::SchlickExponentRatio => "schlick-exponent-ratio",
        }
    }

    /// Parses a name as written in a preset.
    pub fn from_name(s: &str) -> Option<FresnelQuantity> {
        Self::ALL.into_iter().find(|q| q.name() == s)
    }

    /// Whether the coordinate gives Schlick's F0.
    pub fn is_f0(self) -> bool {
        matches!(self, FresnelQuantity::F0 | FresnelQuantity::SqrtF0)
    }

    /// Whether the coordinate gives the relative index η of the exact Fresnel.
    pub fn is_eta(self) -> bool {
        matches!(
            self,
            FresnelQuantity::Eta
                | FresnelQuantity::EtaReflectance
                | FresnelQuantity::InverseEtaReflectance
        )
    }

    /// Whether the coordinate gives the exponent of the generalized Schlick weight.
    pub fn is_exponent(self) -> bool {
        matches!(
            self,
            FresnelQuantity::SchlickExponent | FresnelQuantity::SchlickExponentRatio
        )
    }

    /// What the coordinate gives: `F0`, `eta` or `exponent`.
    pub fn parameter_name(self) -> &'static str {
        if self.is_f0() {
            "F0"
        } else if self.is_eta() {
            "eta"
        } else {
            "exponent"
        }
    }

    pub fn mapping(self) -> &'static str {
        match self {
            FresnelQuantity::F0 => "F0 = coordinate (Schlick)",
            FresnelQuantity::SqrtF0 => "F0 = coordinate^2 (Schlick)",
            FresnelQuantity::Eta => "eta = coordinate (the relative index of refraction)",
            FresnelQuantity::EtaReflectance => {
                "eta = (1 + coordinate)/(1 - coordinate), i.e. coordinate = (eta - 1)/(eta + 1) (the relative index of refraction)"
            }
            FresnelQuantity::InverseEtaReflectance => {
                "eta = (1 - coordinate)/(1 + coordinate), i.e. coordinate = (1 - eta)/(1 + eta) = (1/eta - 1)/(1/eta + 1) (the relative index of refraction)"
            }
            FresnelQuantity::SchlickExponent => {
                "exponent e = coordinate of the generalized Schlick weight (1 - v.h)^e"
            }
            FresnelQuantity::SchlickExponentRatio => {
                "exponent e = 5 (1 - coordinate)/coordinate, i.e. coordinate = 5/(5 + e) (0.5: e = 5), of the generalized Schlick weight (1 - v.h)^e"
            }
        }
    }

    /// The parameter (F0, η or exponent) at a coordinate; NaN/∞ outside the domain (validation
    /// rejects those texels).
    pub fn to_parameter(self, x: f64) -> f64 {
        match self {
            FresnelQuantity::F0 | FresnelQuantity::Eta => x,
            FresnelQuantity::SqrtF0 => x * x,
            FresnelQuantity::EtaReflectance => (1.0 + x) / (1.0 - x),
            FresnelQuantity::InverseEtaReflectance => (1.0 - x) / (1.0 + x),
            FresnelQuantity::SchlickExponent => x,
            FresnelQuantity::SchlickExponentRatio => 5.0 * (1.0 - x) / x,
        }
    }

    /// Checks one texel's parameter; the message says what is accepted.
    pub fn check(self, x: f64) -> Result<f64, String> {
        let p = self.to_parameter(x);
        if self.is_f0() {
            if x.is_finite() && x >= 0.0 && p <= 1.0 {
                return Ok(p);
            }
            return Err(format!(
                "{} coordinate {x} gives F0 = {p}; F0 must be in [0, 1]",
                self.name()
            ));
        }
        if self.is_exponent() {
            if x.is_finite() && p.is_finite() && (0.0..=MAX_EXPONENT).contains(&p) {
                return Ok(p);
            }
            return Err(format!(
                "{} coordinate {x} gives exponent e = {p}; e must be in [0, {MAX_EXPONENT:e}]",
                self.name()
            ));
        }
        if p.is_finite() && (MIN_ETA..=MAX_ETA).contains(&p) {
            return Ok(p);
        }
        Err(format!(
            "{} coordinate {x} gives eta = {p}; eta must be in [{MIN_ETA:e}, {MAX_ETA}]",
            self.name()
        ))
    }
}
