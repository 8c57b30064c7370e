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
    /// from the stored f32 texels, with exact weights ([`Filter::Ideal`]).
    pub fn lookup(&self, x: &[f64]) -> Vec<f64> {
        self.lookup_filtered(x, Filter::Ideal)
    }

    /// [`Lut::lookup`] with the weights `filter` gives the texels.
    pub fn lookup_filtered(&self, x: &[f64], filter: Filter) -> Vec<f64> {
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
            fr[k] = match filter {
                Filter::Hardware { axes } if k < axes => hardware_weight(p - i0 as f64),
                _ => p - i0 as f64,
            };
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

    /// Per channel: the most a lookup with [`Filter::Hardware`] weights on the first `axes`
    /// axes can differ from the ideal one, anywhere: Σ over those axes of the largest step
    /// between neighbouring texels along the axis, / 512.
    ///
    /// Derivation: within a cell the interpolant is affine in each weight `f_k`, with slope
    /// the step along axis k interpolated over the other axes, so at most the cell's largest
    /// step along k. Rounding `f_k` to the nearest multiple of 1/256 moves it by at most
    /// 1/512; changing the weights one axis at a time, the value moves by at most
    /// Σ_k max|step_k|/512.
    pub fn weight_rounding_bound(&self, axes: usize) -> Vec<f64> {
        let nc = self.channels.len();
        let mut out = vec![0.0; nc];
        for k in 0..axes.min(self.axes.len()) {
            let steps = self.max_steps(k);
            for (o, s) in out.iter_mut().zip(steps) {
                *o += s / 512.0;
            }
        }
        out
    }

    /// Per channel: a bound of the error of linear interpolation between texel centres: the
    /// largest difference between the largest and the smallest texel at the corners of one
    /// cell. It holds wherever the function is monotone along each axis inside each cell (no
    /// peak or dip strictly between texel centres): then along every axis the function lies
    /// between its values at the cell's faces, so inside the cell it lies within the range of
    /// the corner texels, and so does the interpolant (a convex combination of them).
    pub fn interpolation_bound(&self) -> Vec<f64> {
        let nc = self.channels.len();
        let dims = [self.dim(0), self.dim(1), self.dim(2)];
        let d = self.axes.len();
        let mut out = vec![0.0f64; nc];
        for idx in texel_indices(dims) {
            if (0..d).any(|k| dims[k] >= 2 && idx[k] + 1 >= dims[k]) {
                continue;
            }
            for (c, o) in out.iter_mut().enumerate() {
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for corner in 0..(1usize << d) {
                    let mut j = idx;
                    for (k, jk) in j.iter_mut().enumerate().take(d) {
                        if (corner >> k) & 1 == 1 && dims[k] >= 2 {
                            *jk += 1;
                        }
                    }
                    let v = self.texel(j, c) as f64;
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
                *o = o.max(hi - lo);
            }
        }
        out
    }

    /// Per channel: the largest |difference| between neighbouring texels along axis `k`.
    pub fn max_steps(&self, k: usize) -> Vec<f64> {
        let nc = self.channels.len();
        let mut out = vec![0.0f64; nc];
        let dims = [self.dim(0), self.dim(1), self.dim(2)];
        if dims[k] < 2 {
            return out;
        }
        for idx in texel_indices(dims) {
            if idx[k] + 1 >= dims[k] {
                continue;
            }
            let mut next = idx;
            next[k] += 1;
            for (c, o) in out.iter_mut().enumerate() {
                let d = (self.texel(next, c) as f64 - self.texel(idx, c) as f64).abs();
                *o = o.max(d);
            }
        }
        out
    }

    /// Per channel: an estimate of the largest error of linear interpolation between texel
    /// centres: the maximum over texels of Σ_k |second difference along k| / 8 (the
    /// remainder of linear interpolation at a cell's middle is h²|f''|/8 per axis, and a
    /// second difference of the texels is h²f'' at a point of the two cells around it; an
    /// axis of fewer than 3 texels contributes nothing; texels on an axis' edge use the
    /// second difference of their inner neighbour). Exact for data quadratic along each axis;
    /// an estimate, not a bound, where f'' changes fast between neighbouring cells.
    pub fn interpolation_error_estimate(&self) -> Vec<f64> {
        let nc = self.channels.len();
        let dims = [self.dim(0), self.dim(1), self.dim(2)];
        let mut out = vec![0.0f64; nc];
        let mut sum = vec![0.0f64; nc];
        for idx in texel_indices(dims) {
            sum.iter_mut().for_each(|s| *s = 0.0);
            for k in 0..self.axes.len() {
                if dims[k] < 3 {
                    continue;
                }
                let mut mid = idx;
                mid[k] = idx[k].clamp(1, dims[k] - 2);
                let (mut a, mut b) = (mid, mid);
                a[k] -= 1;
                b[k] += 1;
                for (c, s) in sum.iter_mut().enumerate() {
                    let d2 = self.texel(a, c) as f64 - 2.0 * self.texel(mid, c) as f64
                        + self.texel(b, c) as f64;
                    *s += d2.abs() / 8.0;
                }
            }
            for (o, s) in out.iter_mut().zip(&sum) {
                *o = o.max(*s);
            }
        }
        out
    }
}

/// Every texel index of a table of `dims`, x fastest.
fn texel_indices(dims: [usize; 3]) -> impl Iterator<Item = [usize; 3]> {
    (0..dims[2])
        .flat_map(move |z| (0..dims[1]).flat_map(move |y| (0..dims[0]).map(move |x| [x, y, z])))
}

/// How a texture unit weights the texels it blends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// Exact weights: the fraction of the texel-space position (what CPUs compute, and
    /// software rasterizers such as SwiftShader in f32).
    Ideal,
    /// Weights rounded to the nearest multiple of 1/256 on the first `axes` axes: what GPUs
    /// with 8 bits of sub-texel precision (the minimum Direct3D requires, and common in
    /// hardware) compute. The other axes keep exact weights: the 2D-array layout of a 3D
    /// table blends its slices in shader arithmetic, so it has `axes` = 2.
    Hardware { axes: usize },
}

/// Bits of sub-texel precision of [`Filter::Hardware`].
pub const HARDWARE_WEIGHT_BITS: u32 = 8;

/// A weight `f` in [0, 1] rounded to the nearest multiple of 2^-[`HARDWARE_WEIGHT_BITS`]
/// (halves away from zero).
pub fn hardware_weight(f: f64) -> f64 {
    let scale = (1u32 << HARDWARE_WEIGHT_BITS) as f64;
    (f * scale).round() / scale
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

    fn line(values: &[f32]) -> Lut {
        Lut {
            axes: vec![axis(values.len(), Convention::Endpoints)],
            channels: vec![Channel {
                name: "v".into(),
                meaning: "test".into(),
            }],
            data: values.to_vec(),
            error_estimate: vec![0.0],
            evaluations: 0,
        }
    }

    /// Hardware weights: equal to the ideal lookup where the fraction is a multiple of 1/256
    /// (texel centres, midpoints), and at most the bound away from it elsewhere; the bound
    /// is attained at a fraction of 1/512 (rounded up to 1/256).
    #[test]
    fn hardware_weights_stay_within_the_bound() {
        let lut = line(&[0.0, 1.0, 3.0, 2.5]);
        let hw = Filter::Hardware { axes: 1 };
        let bound = lut.weight_rounding_bound(1)[0];
        assert_eq!(bound, 2.0 / 512.0);
        for i in 0..=3000 {
            let x = i as f64 / 3000.0;
            let (a, b) = (lut.lookup(&[x])[0], lut.lookup_filtered(&[x], hw)[0]);
            assert!((a - b).abs() <= bound * (1.0 + 1e-12), "{x}: {a} {b}");
        }
        // texel 1 is at x = 1/3; the midpoint of cell [1, 2] at 1/2
        for x in [1.0 / 3.0, 0.5] {
            assert!((lut.lookup(&[x])[0] - lut.lookup_filtered(&[x], hw)[0]).abs() < 1e-12);
        }
        // in cell [1, 2] (step 2) at fraction 1/512: the weight becomes 1/256
        let x = (1.0 + 1.0 / 512.0) / 3.0;
        let d = lut.lookup_filtered(&[x], hw)[0] - lut.lookup(&[x])[0];
        assert!((d - bound).abs() < 1e-12, "{d}");
        assert_eq!(hardware_weight(0.5), 0.5);
        assert_eq!(hardware_weight(1.0 / 512.0), 1.0 / 256.0);
        assert_eq!(hardware_weight(0.999), 1.0);
    }

    /// The interpolation estimate is exact on a quadratic: f = x² at texel centres has
    /// f'' = 2, so the error at every cell's middle is h²/4.
    #[test]
    fn interpolation_estimate_is_exact_on_a_quadratic() {
        let n = 16;
        let ax = axis(n, Convention::Centers);
        let values: Vec<f32> = ax.coords().iter().map(|x| (x * x) as f32).collect();
        let mut lut = line(&values);
        lut.axes = vec![ax.clone()];
        let h = 1.0 / n as f64;
        let est = lut.interpolation_error_estimate()[0];
        assert!((est - h * h / 4.0).abs() < 1e-7, "{est}");
        let mid = 0.5 * (ax.coord(5) + ax.coord(6));
        let err = lut.lookup(&[mid])[0] - mid * mid;
        assert!((err - h * h / 4.0).abs() < 1e-7, "{err}");
    }
}
