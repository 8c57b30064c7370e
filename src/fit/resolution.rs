//! The other way to meet an error: a texture of the smallest resolution whose filtered
//! lookups stay within it. For each square size the table is baked as its preset says (its
//! axes at that many texels, its storage) and its lookup error bounded as the sidecar's
//! `lookup_error` bounds it (`meta::lookup_error`): with exact bilinear weights and with the
//! 8-bit weights of hardware filtering.

use crate::meta::lookup_error;
use crate::preset::{Preset, PresetTable};

/// The sizes tried, texels per axis.
pub const SIZES: [usize; 7] = [4, 8, 16, 32, 64, 128, 256];

/// One size's worst lookup error over the channels, with exact and with 8-bit weights.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolution {
    pub size: usize,
    pub ideal: f64,
    pub hardware: f64,
    /// The typical error where the table is smooth at that size (the sidecar's
    /// `interpolation_estimate`, plus the texel error): what a lookup is usually off by.
    pub estimate: f64,
}

/// The table `table` of `preset` baked at every size of [`SIZES`] (every axis of more than
/// one texel at that size), in order, until `stop` says stop.
pub fn resolutions(
    preset: &Preset,
    table: &PresetTable,
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Vec<Resolution>, String> {
    let mut out = Vec::new();
    for &n in &SIZES {
        let mut t = table.clone();
        for a in &mut t.spec.axes {
            if a.size > 1 {
                a.size = n;
            }
        }
        let p = Preset {
            tables: vec![t.clone()],
            ..preset.clone()
        };
        let (baked, _) =
            crate::pipeline::bake_preset_until(&p, std::path::Path::new("."), Some(&[]), deadline)
                .map_err(|e| e.to_string())?;
        let e = lookup_error(&t, &baked[0].lut);
        let worst = |key: &str| {
            e[key].as_object().map_or(f64::NAN, |m| {
                m.values().filter_map(|v| v.as_f64()).fold(0.0, f64::max)
            })
        };
        out.push(Resolution {
            size: n,
            ideal: worst("ideal_filtering"),
            hardware: worst("hardware_filtering"),
            estimate: {
                let est = e["interpolation_estimate"]
                    .as_object()
                    .cloned()
                    .unwrap_or_default();
                let tex = e["texel_error"].as_object().cloned().unwrap_or_default();
                est.iter()
                    .map(|(k, v)| {
                        v.as_f64().unwrap_or(f64::NAN) + tex[k].as_f64().unwrap_or(f64::NAN)
                    })
                    .fold(0.0, f64::max)
            },
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// More texels help (the bounds and the estimate at 256 well below those at 4), and the
    /// hardware bound adds the weights' rounding to the ideal one, never less.
    #[test]
    fn bounds_fall_with_resolution() {
        let (_, text) = crate::presets::BUILTIN
            .iter()
            .find(|(n, _)| *n == "karis-envbrdf")
            .unwrap();
        let p = crate::preset::parse(text, "karis-envbrdf", "karis-envbrdf").unwrap();
        let r = resolutions(&p, &p.tables[0], None).unwrap();
        assert_eq!(r.len(), SIZES.len());
        let (first, last) = (&r[0], &r[r.len() - 1]);
        assert!(
            last.ideal < first.ideal / 4.0 && last.estimate < first.estimate / 4.0,
            "{r:?}"
        );
        assert!(
            r.iter()
                .all(|x| x.hardware >= x.ideal && x.ideal.is_finite()),
            "{r:?}"
        );
    }
}
