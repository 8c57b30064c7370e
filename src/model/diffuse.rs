//! The diffuse lobe of a [`Brdf`](super::Brdf): Lambert's constant `w_d/π`, or Burley's
//! ("Disney") diffuse with its retro-reflective grazing boost.
//!
//! Burley 2012, "Physically-Based Shading at Disney" (SIGGRAPH course notes, §5.3, "Diffuse"):
//! `f_d = (base/π)·(1 + (F_D90 − 1)(1 − n·l)⁵)·(1 + (F_D90 − 1)(1 − n·v)⁵)` with
//! `F_D90 = 0.5 + 2·r·(l·h)²`, where `r` is Burley's *perceptual* roughness (the slider
//! value; his specular lobe takes `α = r²`). brdfbake's models are parametrized by α, so
//! the lobe at α uses `r = √α`: a table whose roughness axis is perceptual gets the `r`
//! of its axis, one on α gets `√α`. `base` is the diffuse weight `w_d`. Since
//! `l·h = v·h`, the lobe is a function of (n·v, n·l, v·h), as every brdfbake integrand.

/// Which diffuse model a table's `model.diffuse` weighs (the preset's `model.diffuse_model`).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum DiffuseModel {
    /// `w_d/π`.
    #[default]
    Lambert,
    /// Burley 2012's diffuse (module doc).
    Burley,
}

impl DiffuseModel {
    pub const ALL: [DiffuseModel; 2] = [DiffuseModel::Lambert, DiffuseModel::Burley];

    pub fn name(self) -> &'static str {
        match self {
            DiffuseModel::Lambert => "lambert",
            DiffuseModel::Burley => "burley",
        }
    }

    pub fn formula(self) -> &'static str {
        match self {
            DiffuseModel::Lambert => "f_d = w_d / pi",
            DiffuseModel::Burley => {
                "f_d = (w_d / pi) (1 + (F_D90 - 1)(1 - n.l)^5) (1 + (F_D90 - 1)(1 - n.v)^5), F_D90 = 0.5 + 2 r (l.h)^2, r = sqrt(alpha) the perceptual roughness (Burley 2012, 'Physically-Based Shading at Disney', section 5.3)"
            }
        }
    }

    /// The lobe at NDF parameter α.
    pub fn lobe(self, alpha: f64) -> DiffuseLobe {
        match self {
            DiffuseModel::Lambert => DiffuseLobe::Lambert,
            DiffuseModel::Burley => DiffuseLobe::Burley {
                roughness: alpha.max(0.0).sqrt(),
            },
        }
    }
}

/// The diffuse lobe of one BRDF.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum DiffuseLobe {
    #[default]
    Lambert,
    /// Burley's diffuse at perceptual roughness `roughness`.
    Burley { roughness: f64 },
}

impl DiffuseLobe {
    /// The lobe's shape factor: `f_d = (w_d/π)·factor` (1 for Lambert; Burley's two
    /// Schlick-like factors, module doc) at cosines `n·v`, `n·l` and `v·h` (= `l·h`).
    #[inline]
    pub fn factor(self, n_dot_v: f64, n_dot_l: f64, v_dot_h: f64) -> f64 {
        match self {
            DiffuseLobe::Lambert => 1.0,
            DiffuseLobe::Burley { roughness } => {
                let fd90 = 0.5 + 2.0 * roughness * v_dot_h * v_dot_h;
                let p5 = |c: f64| {
                    let m = (1.0 - c).clamp(0.0, 1.0);
                    let m2 = m * m;
                    m2 * m2 * m
                };
                (1.0 + (fd90 - 1.0) * p5(n_dot_l)) * (1.0 + (fd90 - 1.0) * p5(n_dot_v))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Burley's limits: at normal incidence and exit both factors are 1 (f_d = w_d/π, as
    /// Lambert); at grazing exit and view (n·l = n·v = 0) the factor is F_D90², with
    /// F_D90 = 0.5 + 2r(l·h)²: 0.25 at r = 0 (the smooth darkening), 2.5² at r = 1, l·h = 1.
    #[test]
    fn burley_limits() {
        let b = |r: f64| DiffuseLobe::Burley { roughness: r };
        assert_eq!(b(0.7).factor(1.0, 1.0, 1.0), 1.0);
        assert_eq!(b(0.0).factor(0.0, 0.0, 0.3), 0.25);
        assert_eq!(b(1.0).factor(0.0, 0.0, 1.0), 6.25);
        assert_eq!(DiffuseLobe::Lambert.factor(0.1, 0.2, 0.3), 1.0);
        assert_eq!(DiffuseModel::Burley.lobe(0.25), b(0.5));
    }
}
