//! A baked lookup table: its axes (with every texel's coordinate), its channels, its f32
//! texels, and what the bake measured. Also the lookup a GPU performs on it.

use crate::model::{FresnelQuantity, RoughnessQuantity};
use serde::Serialize;

/// Where texel coordinates sit on an axis of `size` texels spanning `[lo, hi]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Convention {
    /// Texel i holds the value at `lo + (hi − lo)(i + 0.5)/size` — the texel centre, where a
    /// GPU with normalized coordinate `s = (x − lo)/(hi − lo)` samples it exactly. No shader
    /// remap needed; values at the range ends are clamped-to-edge extrapolations.
    Centers,
    /// Texel i holds the value at `lo + (hi − lo)·i/(size − 1)` — the range ends are exact
    /// texels. A shader must remap `s = (0.5 + t·(size − 1))/size` with `t = (x − lo)/(hi − lo)`.
    Endpoints,
}

impl Convention {
    pub fn name(self) -> &'static str {
        match self {
            Convention::Centers => "centers",
            Convention::Endpoints => "endpoints",
        }
    }
}

/// What an axis measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// A cosine with respect to the surface normal (n·v, n·l, n·h).
    Cosine,
    /// A roughness in the named parameterization.
    Roughness(RoughnessQuantity),
    /// A Fresnel parameter (F0 or the relative index η) in the named parameterization.
    Fresnel(FresnelQuantity),
    /// The anisotropy a ∈ [0, 1] of a `classic-albedo-aniso` table: aspect = √(1 − 0.9 a),
    /// α_x = α/aspect, α_y = α·aspect (see `table::classic`).
    Anisotropy,
}

/// One axis of a table.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The axis' name, which also says what it measures: `cos_theta_v`, `n_dot_h`, `roughness`, …
    pub name: String,
    pub quantity: Quantity,
    pub size: usize,
    pub range: [f64; 2],
    pub convention: Convention,
}

impl Axis {
    /// The coordinate of texel `i` in the axis' own quantity.
    pub fn coord(&self, i: usize) -> f64 {
        let [lo, hi] = self.range;
        let t = match self.convention {
            Convention::Centers => (i as f64 + 0.5) / self.size as f64,
            Convention::Endpoints => {
                if self.size == 1 {
                    0.0
                } else {
                    i as f64 / (self.size - 1) as f64
                }
            }
        };
        lo + (hi - lo) * t
    }

    /// Every texel coordinate, in texel order.
    pub fn coords(&self) -> Vec<f64> {
        (0..self.size).map(|i| self.coord(i)).collect()
    }

    /// The NDF parameter α of texel `i` (roughness axes only).
    pub fn alpha(&self, i: usize) -> Option<f64> {
        match self.quantity {
            Quantity::Roughness(q) => Some(q.to_alpha(self.coord(i))),
            Quantity::Cosine | Quantity::Fresnel(_) | Quantity::Anisotropy => None,
        }
    }

    /// The Fresnel parameter (F0 or η) of texel `i` (Fresnel axes only).
    pub fn fresnel_parameter(&self, i: usize) -> Option<f64> {
        match self.quantity {
            Quantity::Fresnel(q) => Some(q.to_parameter(self.coord(i))),
            _ => None,
        }
    }

    /// The continuous texel-space position of coordinate `x` (texel i at position i),
    /// clamped to `[0, size − 1]` as clamp-to-edge sampling does.
    pub fn texel_position(&self, x: f64) -> f64 {
        let [lo, hi] = self.range;
        let t = if hi != lo { (x - lo) / (hi - lo) } else { 0.0 };
        let p = match self.convention {
            Convention::Centers => t * self.size as f64 - 0.5,
            Convention::Endpoints => t * (self.size as f64 - 1.0),
        };
        p.clamp(0.0, (self.size - 1) as f64)
    }

    /// The normalized texture coordinate a GPU must sample for coordinate `x`.
    pub fn texture_coordinate(&self, x: f64) -> f64 {
        (self.texel_position(x) + 0.5) / self.size as f64
    }
}

/// One channel of a table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Channel {
    /// Short name, used as the EXR channel name (`E`, `A`, `B`, `DFG_R`, …).
    pub name: String,
    /// What the channel holds, as a formula.
    pub meaning: String,
}

/// A baked table.
#[derive(Clone, Debug, PartialEq)]
pub struct Lut {
    /// Axes, fastest-varying first: axis 0 is x (texture u), axis 1 is y (texture v, the row),
    /// axis 2 is z (the slice of a 3D table).
    pub axes: Vec<Axis>,
    pub channels: Vec<Channel>,
    /// Texels, channels interleaved: index `((z·ny + y)·nx + x)·nc + c`.
    pub data: Vec<f32>,
    /// Estimated max absolute quadrature error per channel, over all texels (before f32 rounding).
    pub error_estimate: Vec<f64>,
    /// Number of integrand evaluations the bake spent.
    pub evaluations: u64,
}

impl Lut {
    /// Texel count (without channels).
    pub fn texel_count(&self) -> usize {
        self.axes.iter().map(|a| a.size).product()
    }

    /// Size along axis `k`, 1 if the table has fewer axes.
    pub fn dim(&self, k: usize) -> usize {
        self.axes.get(k).map_or(1, |a| a.size)
    }

    /// The stored value at integer texel indices (missing axes = 0).
    pub fn texel(&self, idx: [usize; 3], c: usize) -> f32 {
        let (nx, ny) = (self.dim(0), self.dim(1));
        self.data[((idx[2] * ny + idx[1]) * nx + idx[0]) * self.channels.len() + c]
    }

    /// What a GPU returns when sampling with linear filtering and clamp-to-edge at the
    /// physical coordinates `x` (one per axis, in each axis' own quantity), computed in f64
    /// from the stored f32 texels.
    pub fn lookup(&self, x: &[f64]) -> Vec<f64> {
        assert_eq!(x.len(), self.axes.len(), "one coordinate per axis");
        let mut lo = [0usize; 3];
        let mut hi = [0usize; 3];
        let mut fr = [0.0f64; 3];
        for (k, a) in self.axes.iter().enumerate() {
            let p = a.texel_position(x[k]);
            let i0 = p.floor() as usize;
            let i1 = (i0 + 1).min(a.size - 1);
            lo[k] = i0;
            hi[k] = i1;
            fr[k] = p - i0 as f64;
        }
        let nc = self.channels.len();
        let mut out = vec![0.0; nc];
        for corner in 0..8usize {
            let mut w = 1.0;
            let mut idx = [0usize; 3];
            for k in 0..3 {
                let bit = (corner >> k) & 1;
                if k >= self.axes.len() {
                    if bit == 1 {
                        w = 0.0;
                    }
                    continue;
                }
                idx[k] = if bit == 1 { hi[k] } else { lo[k] };
                w *= if bit == 1 { fr[k] } else { 1.0 - fr[k] };
            }
            if w == 0.0 {
                continue;
            }
            for (c, o) in out.iter_mut().enumerate() {
                *o += w * self.texel(idx, c) as f64;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(size: usize, conv: Convention) -> Axis {
        Axis {
            name: "cos_theta_v".into(),
            quantity: Quantity::Cosine,
            size,
            range: [0.0, 1.0],
            convention: conv,
        }
    }

    /// A table of a linear function is reproduced exactly by the lookup between texels, and
    /// a lookup at a texel's own coordinate returns that texel (both conventions).
    #[test]
    fn lookup_is_exact_at_texels_and_on_linear_data() {
        for conv in [Convention::Centers, Convention::Endpoints] {
            let ax = axis(8, conv);
            let ay = Axis {
                name: "roughness".into(),
                quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
                ..axis(5, conv)
            };
            let f = |x: f64, y: f64| 0.25 + 0.5 * x - 0.125 * y;
            let mut data = Vec::new();
            for j in 0..5 {
                for i in 0..8 {
                    data.push(f(ax.coord(i), ay.coord(j)) as f32);
                }
            }
            let lut = Lut {
                axes: vec![ax.clone(), ay.clone()],
                channels: vec![Channel {
                    name: "v".into(),
                    meaning: "test".into(),
                }],
                data,
                error_estimate: vec![0.0],
                evaluations: 0,
            };
            assert_eq!(
                lut.lookup(&[ax.coord(3), ay.coord(2)])[0],
                lut.texel([3, 2, 0], 0) as f64
            );
            // inside the texel-centre hull linear data interpolates exactly (f32 storage: 6e-8)
            let (x, y) = (
                0.5 * (ax.coord(2) + ax.coord(3)),
                0.3 * ay.coord(1) + 0.7 * ay.coord(2),
            );
            assert!((lut.lookup(&[x, y])[0] - f(x, y)).abs() < 1e-7);
        }
    }
}
