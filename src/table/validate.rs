//! Validation of a [`TableSpec`]: everything that can be checked before baking, with errors
//! that name the field and what is accepted. Each kind's own rules live with the kind
//! ([`super::energy::validate`], [`super::classic::validate`]); this file walks the axes and
//! the model and hands over.

use super::spec::{
    DfgLayout, TableKind, TableSpec, MAX_AXIS_SIZE, MAX_TEXELS, MAX_TOLERANCE, MIN_COSINE,
    MIN_TOLERANCE,
};
use crate::lut::{Convention, Quantity, Warp};
use crate::model::ndf::MIN_ALPHA;
use crate::model::{Fresnel, Masking, Ndf, NdfKind, RoughnessQuantity};

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
            // warps apply to cosines and to Fresnel coordinates (Cycles' sqrt of
            // (eta - 1)/(eta + 1)), and the reversal one-minus also to roughness (Godot's DFG
            // rows run from roughness 1 down); every one is strictly monotone on its
            // coordinate domain
            let warp_ok = matches!(
                (ax.warp, ax.quantity),
                (Warp::Linear, _)
                    | (_, Quantity::Cosine | Quantity::Fresnel(_))
                    | (Warp::OneMinus, Quantity::Roughness(_))
            );
            if !warp_ok {
                return Err(format!(
                    "{f}.warp {:?} applies to cosine and fresnel axes only (a roughness axis takes \"one-minus\" alone); this axis is linear in its quantity",
                    ax.warp.name()
                ));
            }
            // the critical-angle remap places a view cosine about the critical angle of the
            // fresnel axis' relative index: only a dielectric table's view axis has both
            let coupled_kinds = [
                TableKind::DielectricBtdf,
                TableKind::DielectricAlbedo,
                TableKind::DielectricSchlick,
            ];
            if ax.warp.is_coupled() && !(coupled_kinds.contains(&kind) && ax.name == "cos_theta_v")
            {
                return Err(format!(
                    "{f}.warp \"critical-angle\" applies to the cos_theta_v axis of a {} table only (it places the \
                     view cosines about the critical angle of the fresnel axis' relative index eta)",
                    coupled_kinds.map(|k| k.name()).join(" or ")
                ));
            }
            if ax.warp != Warp::Linear && ax.quantity != Quantity::Cosine {
                let [dlo, dhi] = ax.warp.parameter_domain().unwrap_or([lo, hi]);
                if lo < dlo || hi > dhi {
                    return Err(format!(
                        "{f}.range must lie within [{}, {}] (the range of the warp's parameter {}), got [{}, {}]",
                        crate::numfmt::num(dlo),
                        crate::numfmt::num(dhi),
                        ax.warp.formula(),
                        crate::numfmt::num(lo),
                        crate::numfmt::num(hi)
                    ));
                }
            }
            if let Some([c0, c1]) = ax.clamp {
                if !(c0.is_finite() && c1.is_finite() && c0 <= c1) {
                    return Err(format!(
                        "{f}.clamp must be two finite numbers [lo, hi] with lo <= hi, got [{}, {}]",
                        crate::numfmt::num(c0),
                        crate::numfmt::num(c1)
                    ));
                }
                if ax.quantity == Quantity::Cosine && (c0 < 0.0 || c1 > 1.0) {
                    return Err(format!(
                        "{f}.clamp must lie within [0, 1] (a cosine), got [{}, {}]",
                        crate::numfmt::num(c0),
                        crate::numfmt::num(c1)
                    ));
                }
            }
            // the smallest coordinate of a texel, where it is evaluated (warped axes may
            // run from 1 down)
            let first = if ax.warp.is_coupled() {
                // in every slice (each has its own critical cosine)
                crate::lut::critical_cosines(&self.axes)
                    .into_iter()
                    .flat_map(|c| (0..ax.size).map(move |i| ax.coord_at(i, c)))
                    .fold(f64::INFINITY, f64::min)
            } else {
                (0..ax.size)
                    .map(|i| ax.coord(i))
                    .fold(f64::INFINITY, f64::min)
            };
            match ax.quantity {
                Quantity::Cosine => {
                    let [dlo, dhi] = ax.warp.parameter_domain().unwrap_or([0.0, 1.0]);
                    if lo < dlo || hi > dhi {
                        let what = match ax.warp {
                            Warp::Linear => "a cosine".to_string(),
                            w => format!("the range of the warp's parameter {}", w.formula()),
                        };
                        return Err(format!(
                            "{f}.range must lie within [{}, {}] ({what}), got [{lo}, {hi}]",
                            crate::numfmt::num(dlo),
                            crate::numfmt::num(dhi),
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
                            | (TableKind::DielectricBtdf, _)
                            | (TableKind::DielectricAlbedo, _)
                            | (TableKind::DielectricSchlick, _)
                            | (TableKind::SchlickWeightVndf, _)
                            | (TableKind::SchlickWeightAlbedo, _)
                            | (TableKind::Vgroove, "n_dot_h") // (an ltc table's views: table::ltc::validate, which says why and how to clamp)
                    ) || kind == TableKind::Ltc;
                    if !zero_ok && first <= 0.0 {
                        return Err(format!(
                            "{f}: a texel at cosine 0 is not allowed for a {} table (the quantity is undefined at 0: \
                             it divides by {}); use the centers convention or a range starting above 0",
                            kind.name(),
                            if ax.name == "n_dot_h" { "n.h" } else { "n.v" }
                        ));
                    }
                    if !zero_ok && first < MIN_COSINE {
                        return Err(format!(
                            "{f}: a texel is at cosine {}, below the smallest accepted {} for {} tables (they divide by {}: \
                             closer to grazing its angle's tangent passes 1e12, and in f64 the integrand overflows near 1e-154); \
                             start the range at {} or above (or clamp the axis' values)",
                            crate::numfmt::num(first),
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
                Quantity::FormFactor => {
                    if kind != TableKind::LtcSphere {
                        return Err(format!(
                            "{f}: only an ltc-sphere table's axes are form-factor coordinates"
                        ));
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
                    // every roughness coordinate is 0 or more (a negative perceptual r would
                    // square to a positive alpha: a mirrored table), and alpha at most 1, the
                    // domain the engines' tables span and the accuracy tests cover (beyond it
                    // a table fails its tolerance instead of being refused)
                    let max = match q {
                        RoughnessQuantity::Alpha
                        | RoughnessQuantity::Perceptual
                        | RoughnessQuantity::CookTorranceM => 1.0,
                        RoughnessQuantity::BlinnPhongExponent | RoughnessQuantity::Exponent => {
                            f64::INFINITY
                        }
                    };
                    if lo < 0.0 || hi > max {
                        return Err(format!(
                            "{f}.range must lie within [0, {}] ({} roughness{}{}), got [{}, {}]",
                            if max.is_finite() {
                                "1".to_string()
                            } else {
                                "inf".to_string()
                            },
                            q.name(),
                            self.model
                                .ndf
                                .map_or(String::new(), |n| format!(" of the {} NDF", n.name())),
                            if max.is_finite() {
                                ": alpha from 0 to 1, the domain whose tables are verified"
                            } else {
                                " exponent"
                            },
                            crate::numfmt::num(lo),
                            crate::numfmt::num(hi)
                        ));
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
                    // α = 0 (the smooth limit, table::smooth) only as one run of texels at
                    // an end of the axis, for the kinds and models that have the limit
                    let zeros: Vec<usize> = (0..ax.size)
                        .filter(|&i| q.to_alpha(ax.coord(i)) == 0.0)
                        .collect();
                    if let (Some(&z0), Some(&z1)) = (zeros.first(), zeros.last()) {
                        super::smooth::supported(self).map_err(|e| {
                            format!(
                                "{f}: texel {z0} is at alpha = 0, but {e}: use the centers convention or a range starting above 0"
                            )
                        })?;
                        if z1 - z0 + 1 != zeros.len() || (z0 != 0 && z1 != ax.size - 1) {
                            return Err(format!(
                                "{f}: the texels at alpha = 0 ({}) must be one run at an end of the axis",
                                zeros.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(", ")
                            ));
                        }
                    }
                    for i in 0..ax.size {
                        let x = ax.coord(i);
                        let a = q.to_alpha(x);
                        if a == 0.0 {
                            continue;
                        }
                        if !(a.is_finite() && a > 0.0) {
                            return Err(format!(
                                "{f}: texel {i} is at {} {x:e} (alpha {a:e}); every texel needs alpha >= 0 \
                                 (use the centers convention or a range starting at 0 or above)",
                                q.name()
                            ));
                        }
                        if let Some(n) = ndf {
                            Ndf::new(n, a).map_err(|e| format!("{f}: texel {i}: {e}"))?;
                        }
                        if a > 1.0
                            && matches!(
                                self.model.masking,
                                Masking::ContyKulla | Masking::ContyKullaSoftened
                            )
                        {
                            return Err(format!(
                                "{f}: texel {i} is at alpha {}, but the conty-kulla Lambda is fitted for alpha in (0, 1] \
                                 (its coefficients interpolate in t = (1 - alpha)^2 between alpha = 0 and 1)",
                                crate::numfmt::num(a)
                            ));
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
        let dm = self.model.diffuse_model;
        if dm != crate::model::DiffuseModel::Lambert {
            // (the other kinds' diffuse paths — smooth limits, energy, fast paths — know
            // Lambert's lobe only)
            if kind != TableKind::Ltc {
                return Err(format!(
                    "model.diffuse_model {:?} applies to ltc tables only; a {} table takes \"lambert\" (the default)",
                    dm.name(),
                    kind.name()
                ));
            }
            if w == 0.0 {
                return Err(format!(
                    "model.diffuse_model {:?} needs model.diffuse > 0 (the lobe's weight)",
                    dm.name()
                ));
            }
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
            && !matches!(
                m.masking,
                Masking::Ashikhmin | Masking::ContyKulla | Masking::ContyKullaSoftened
            )
        {
            let what = if m.masking.is_smith() {
                "smith".to_string()
            } else {
                format!("{:?}", m.masking.name())
            };
            return Err(format!(
                "{what} masking of the charlie NDF is not supported: use masking ashikhmin, conty-kulla or \
                 conty-kulla-softened (charlie is a sheen distribution, defined with these visibilities)"
            ));
        }
        // Schlick-GGX's k is fitted to GGX's Smith G1 (Karis 2013), Conty–Kulla's Λ to the
        // Charlie NDF (Estevez & Kulla 2017): with another NDF they approximate nothing
        if let Some(only) = m.masking.only_for() {
            if kind != TableKind::Ndf && m.ndf != Some(only) {
                return Err(format!(
                    "model.masking {:?} is defined for the {} NDF only ({}), got {}",
                    m.masking.name(),
                    only.name(),
                    if only == NdfKind::Ggx {
                        "its k is fitted to the Smith G1 of GGX"
                    } else {
                        "its Lambda is fitted to the charlie sheen NDF"
                    },
                    m.ndf
                        .map_or("no ndf".to_string(), |n| format!("ndf {}", n.name()))
                ));
            }
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
                if !m.masking.of_cosines_alone() || m.masking == Masking::None {
                    return Err(format!(
                        "model.masking {:?} is not a function of (cos theta_v, cos theta_l) alone; a g2 table accepts \
                         smith-separable, smith-height-correlated, ashikhmin, schlick-ggx, schlick-ggx-direct, conty-kulla \
                         or conty-kulla-softened (for the V-groove term use the vgroove kind)",
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
                if let Some(a) = self.cloth_alpha_min {
                    if !self.cloth {
                        return Err("cloth_alpha_min needs \"cloth\": true (it floors the cloth channel's alpha)".into());
                    }
                    if !(MIN_ALPHA..=1.0).contains(&a) {
                        return Err(format!(
                            "cloth_alpha_min must be in [{MIN_ALPHA:e}, 1] (the cloth channel's Charlie alpha is max(alpha, cloth_alpha_min)), got {a}"
                        ));
                    }
                }
                if self.dfg_layout == Some(DfgLayout::KarisF82)
                    && !(m.ndf == Some(NdfKind::Ggx) && m.masking.is_smith())
                {
                    return Err(format!(
                        "layout \"karis-f82\" needs model.ndf ggx with smith-separable or smith-height-correlated \
                         masking (its F82 channel is integrated over GGX micro-normals), got {:?} with {:?}",
                        m.ndf.map_or("none", |n| n.name()),
                        m.masking.name()
                    ));
                }
            }
            TableKind::KullaConty | TableKind::AlbedoFresnel | TableKind::DielectricBtdf => {
                super::energy::validate(self)?;
            }
            TableKind::DielectricAlbedo
            | TableKind::DielectricAlbedoAvg
            | TableKind::DielectricSchlick => super::dielectric::validate(self)?,
            TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => {
                super::schlick_weight::validate(self)?
            }
            TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => {
                unreachable!("validated above")
            }
            TableKind::Ltc | TableKind::LtcSphere => super::ltc::validate(self)?,
        }
        if kind != TableKind::Ltc && self.ltc_channels.is_some() && kind != TableKind::LtcSphere {
            return Err(format!(
                "ltc.channels applies to ltc tables only, not {}",
                kind.name()
            ));
        }
        if kind != TableKind::Dfg && self.cloth_alpha_min.is_some() {
            return Err(format!(
                "cloth_alpha_min applies to dfg tables with cloth only, not {}",
                kind.name()
            ));
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
