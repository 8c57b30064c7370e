//! LTC texture layouts and their documented lookups, and readers for the published tables.
//!
//! **Heitz's layout** (selfshadow/ltc_code, `fit/fitLTC.cpp` and the shaders of its WebGL
//! demos, `webgl/shaders/ltc/ltc_quad.fs`; three.js `RectAreaLight` reads the same
//! textures, `lights_physical_pars_fragment.glsl.js`, `LTC_Uv`), for an `n × n` table
//! (`n = 64` published):
//! * texel `(a, t)` sits at index `a + t·n` (`a` the column, u; `t` the row, v), RGBA;
//! * u: perceptual roughness `r = a/(n − 1)` with `α = max(r², 10⁻⁵)` (`MIN_ALPHA` there);
//! * v: `x = t/(n − 1) = √(1 − cos θ)`, i.e. `cos θ = 1 − x²`, with θ clamped to at most
//!   1.57 rad (`min(1.57, acos(ct))` there), so the last row is fitted at cos θ ≈ 7.96e-4;
//! * both axes have their end points on texel centres: a shader looks up
//!   `uv = (r, √(1 − cos θ))·(n − 1)/n + 0.5/n` with bilinear filtering;
//! * `ltc_1 = (m00, m20, m02, m22)` of `M⁻¹/m11` (`invM /= invM[1][1]`, [`Ltc::heitz_texel`]),
//!   rebuilt as `mat3(vec3(t.x, 0, t.y), vec3(0, 1, 0), vec3(t.z, 0, t.w))`;
//! * `ltc_2 = (norm, fresnel, 0, sphere)`: `norm = ∫ f cos`, `fresnel = ∫ (1 − v·h)⁵ f cos`
//!   (a shader's specular is `F0·norm + (F90 − F0)·fresnel`), and, in the 4th channel, the
//!   horizon-clipped sphere table over the same texel grid read as `(z·0.5 + 0.5, len)`
//!   ([`clipped_sphere_table`]).
//!
//! three.js' `ltc_1`/`ltc_2` (`examples/jsm/lights/RectAreaLightTexturesLib.js`,
//! `LTC_MAT_1`/`LTC_MAT_2`, up to r187 at least) are `fit/results/ltc.js` of ltc_code, number
//! for number, uploaded as `DataTexture(…, 64, 64, RGBAFormat, FloatType)` (f32) or as
//! half floats: the same layout.
//!
//! Heitz's `fit/results/ltc.inc` holds the same fit for C: `tabMinv` (M⁻¹ unnormalized,
//! nine entries per texel in glm's column-major order, `%.6f`) and `tabMagnitude` (the norm),
//! texels in the same `a + t·n` order.

use crate::engines::shipped::{text_array, ShippedValues};
use crate::kernels::ltc_fit::LtcGrid;
use crate::kernels::ltc_polygon::clipped_sphere_table;
use crate::model::ltc::{Ltc, LtcError};

/// Heitz's table size.
pub const HEITZ_SIZE: usize = 64;
/// The smallest α of Heitz's layout (`MIN_ALPHA` in `fit/fitLTC.cpp`).
pub const HEITZ_MIN_ALPHA: f64 = 1e-5;
/// The largest view angle fitted (the last row), radians.
pub const HEITZ_MAX_THETA: f64 = 1.57;

/// The view cosine of row `t` of an `n`-row Heitz table.
pub fn heitz_row_mu(t: usize, n: usize) -> f64 {
    let x = t as f64 / (n.max(2) - 1) as f64;
    let ct = 1.0 - x * x;
    ct.max(HEITZ_MAX_THETA.cos())
}

/// The perceptual roughness of column `a` of an `n`-column Heitz table.
pub fn heitz_column_roughness(a: usize, n: usize) -> f64 {
    a as f64 / (n.max(2) - 1) as f64
}

/// α of a perceptual roughness in Heitz's layout: `max(r², 10⁻⁵)`.
pub fn heitz_alpha(r: f64) -> f64 {
    (r * r).max(HEITZ_MIN_ALPHA)
}

/// The texel grid of an `n × n` Heitz table: `(row view cosines, column α)`.
pub fn heitz_axes(n: usize) -> (Vec<f64>, Vec<f64>) {
    (
        (0..n).map(|t| heitz_row_mu(t, n)).collect(),
        (0..n)
            .map(|a| heitz_alpha(heitz_column_roughness(a, n)))
            .collect(),
    )
}

/// An LTC table in Heitz's layout: `ltc_1`, `ltc_2` texels at `a + t·n`.
#[derive(Clone, Debug, PartialEq)]
pub struct HeitzTable {
    pub n: usize,
    pub ltc_1: Vec<[f64; 4]>,
    pub ltc_2: Vec<[f64; 4]>,
}

/// How a table's texels are stored on the GPU (what a lookup sees).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexelStorage {
    F64,
    F32,
    F16,
}

impl TexelStorage {
    fn round(self, x: f64) -> f64 {
        match self {
            TexelStorage::F64 => x,
            TexelStorage::F32 => x as f32 as f64,
            TexelStorage::F16 => half::f16::from_f64(x).to_f64(),
        }
    }
}

impl HeitzTable {
    /// The table of a fitted grid whose axes are [`heitz_axes`]`(n)` (`grid.mus` the rows,
    /// `grid.alphas` the columns), the sphere table in `ltc_2.w`.
    pub fn from_grid(grid: &LtcGrid) -> Result<HeitzTable, LtcError> {
        let n = grid.alphas.len();
        if grid.mus.len() != n || n < 2 {
            return Err(LtcError::Domain(format!(
                "Heitz's layout is square: {} views x {} roughnesses",
                grid.mus.len(),
                n
            )));
        }
        let mut ltc_1 = Vec::with_capacity(n * n);
        let mut ltc_2 = Vec::with_capacity(n * n);
        for t in 0..n {
            for a in 0..n {
                let tx = grid.get(t, a).expect("in range");
                ltc_1.push(tx.ltc.heitz_texel());
                ltc_2.push([tx.norm, tx.fresnel, 0.0, sphere_texel(a, t, n)?]);
            }
        }
        Ok(HeitzTable { n, ltc_1, ltc_2 })
    }

    /// The texel values as a GPU holding them in `storage` would.
    pub fn stored(&self, storage: TexelStorage) -> HeitzTable {
        let r = |v: &[f64; 4]| v.map(|x| storage.round(x));
        HeitzTable {
            n: self.n,
            ltc_1: self.ltc_1.iter().map(r).collect(),
            ltc_2: self.ltc_2.iter().map(r).collect(),
        }
    }

    /// The documented lookup at view cosine `mu` and perceptual roughness `r`: texture
    /// coordinates `(r, √(1 − μ))·(n − 1)/n + 0.5/n`, bilinear between the four nearest
    /// texels (clamped to the edge), as a GPU filters them (exactly, without the 8-bit
    /// weight rounding of hardware filtering). Returns `(ltc_1, ltc_2)`.
    pub fn lookup(&self, mu: f64, r: f64) -> Result<([f64; 4], [f64; 4]), LtcError> {
        if !(mu.is_finite() && r.is_finite()) {
            return Err(LtcError::NotFinite {
                what: "a lookup coordinate",
            });
        }
        let n = self.n;
        if n < 2 || self.ltc_1.len() != n * n || self.ltc_2.len() != n * n {
            return Err(LtcError::Domain(format!(
                "an LTC table of side {n} needs side >= 2 and {} texels a texture, has {} and {}",
                n * n,
                self.ltc_1.len(),
                self.ltc_2.len()
            )));
        }
        let s = (1.0 - mu.clamp(0.0, 1.0)).sqrt();
        let uv = [r.clamp(0.0, 1.0), s];
        // continuous texel coordinates: u·n − 0.5 with u = x(n − 1)/n + 0.5/n is x(n − 1)
        let fx = uv[0] * (n - 1) as f64;
        let fy = uv[1] * (n - 1) as f64;
        let (x0, y0) = (
            fx.floor().min((n - 2) as f64),
            fy.floor().min((n - 2) as f64),
        );
        let (tx, ty) = (fx - x0, fy - y0);
        let (x0, y0) = (x0 as usize, y0 as usize);
        let at = |v: &Vec<[f64; 4]>, x: usize, y: usize| v[x + y * n];
        let bl = |v: &Vec<[f64; 4]>| {
            let mut o = [0.0; 4];
            for (k, ok) in o.iter_mut().enumerate() {
                let top = at(v, x0, y0)[k] * (1.0 - tx) + at(v, x0 + 1, y0)[k] * tx;
                let bot = at(v, x0, y0 + 1)[k] * (1.0 - tx) + at(v, x0 + 1, y0 + 1)[k] * tx;
                *ok = top * (1.0 - ty) + bot * ty;
            }
            o
        };
        Ok((bl(&self.ltc_1), bl(&self.ltc_2)))
    }

    /// The LTC and `(norm, fresnel)` a shader gets at `(mu, r)`.
    pub fn ltc_at(&self, mu: f64, r: f64) -> Result<(Ltc, f64, f64), LtcError> {
        let (t1, t2) = self.lookup(mu, r)?;
        Ok((Ltc::from_heitz_texel(t1)?, t2[0], t2[1]))
    }

    /// Reads a table from the text of ltc_code's `fit/results/ltc.js` (`g_ltc_1`,
    /// `g_ltc_2`) or three.js' `RectAreaLightTexturesLib.js` (`LTC_MAT_1`, `LTC_MAT_2`):
    /// JavaScript arrays of `4·n²` numbers.
    pub fn from_js(text: &str) -> Result<HeitzTable, LtcError> {
        let (a, b) = match (parse_array(text, "g_ltc_1"), parse_array(text, "g_ltc_2")) {
            (Ok(a), Ok(b)) => (a, b),
            _ => (
                parse_array(text, "LTC_MAT_1")?,
                parse_array(text, "LTC_MAT_2")?,
            ),
        };
        HeitzTable::from_flat(&a, &b)
    }

    /// Reads a table from the text of ltc_code's `fit/results/ltc.inc` (`tabMinv`, nine
    /// column-major entries a texel, and `tabMagnitude`); its Fresnel and sphere channels
    /// are not in that file and read 0.
    pub fn from_inc(text: &str) -> Result<HeitzTable, LtcError> {
        let m = parse_array(text, "tabMinv")?;
        let mag = parse_array(text, "tabMagnitude")?;
        if m.len() != 9 * mag.len() {
            return Err(LtcError::Domain(format!(
                "ltc.inc: {} tabMinv entries for {} magnitudes",
                m.len(),
                mag.len()
            )));
        }
        let n = square_side(mag.len())?;
        let mut ltc_1 = Vec::with_capacity(n * n);
        let mut ltc_2 = Vec::with_capacity(n * n);
        for (i, &g) in mag.iter().enumerate() {
            let e = &m[9 * i..9 * i + 9];
            // glm: e[col*3 + row]; rows of M⁻¹: [[e0, e3, e6], [e1, e4, e7], [e2, e5, e8]]
            let mid = e[4];
            if mid.is_nan() || mid <= 0.0 {
                return Err(LtcError::Domain(format!(
                    "ltc.inc: texel {i} has M^-1[1][1] = {mid}"
                )));
            }
            ltc_1.push([e[0] / mid, e[2] / mid, e[6] / mid, e[8] / mid]);
            ltc_2.push([g, 0.0, 0.0, 0.0]);
        }
        Ok(HeitzTable { n, ltc_1, ltc_2 })
    }

    fn from_flat(a: &[f64], b: &[f64]) -> Result<HeitzTable, LtcError> {
        if a.len() != b.len() || !a.len().is_multiple_of(4) {
            return Err(LtcError::Domain(format!(
                "LTC arrays of {} and {} numbers (need 4 n^2 each)",
                a.len(),
                b.len()
            )));
        }
        let n = square_side(a.len() / 4)?;
        let four = |v: &[f64]| v.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
        Ok(HeitzTable {
            n,
            ltc_1: four(a),
            ltc_2: four(b),
        })
    }
}

fn square_side(texels: usize) -> Result<usize, LtcError> {
    let n = (texels as f64).sqrt().round() as usize;
    if n < 2 || n * n != texels {
        return Err(LtcError::Domain(format!(
            "{texels} texels is not a square table"
        )));
    }
    Ok(n)
}

/// The sphere table's value at texel `(a, t)` of an `n × n` table: `z = 2a/(n − 1) − 1`,
/// `len = t/(n − 1)` (`genSphereTab` in `fit/fitLTC.cpp`), [`clipped_sphere_table`].
pub fn sphere_texel(a: usize, t: usize, n: usize) -> Result<f64, LtcError> {
    let d = (n.max(2) - 1) as f64;
    let z = 2.0 * a as f64 / d - 1.0;
    let len = t as f64 / d;
    clipped_sphere_table(z.clamp(-1.0, 1.0), len.clamp(0.0, 1.0))
}

/// The numbers of the array `name` in `text`, read by the one reader of numbers in text
/// ([`text_array`]: `compare`'s shipped tables use it too), which accepts the forms the
/// published files use: `-1.2e-07`, `- 1.2e-07` (three.js' spacing), `0.5f` (C suffix),
/// nested braces (`ltc.inc`'s matrices).
pub fn parse_array(text: &str, name: &str) -> Result<Vec<f64>, LtcError> {
    text_array(text, Some(name), ShippedValues::Float, "the LTC table text")
        .map_err(LtcError::Domain)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_published_forms() {
        let js = "var g_ltc_1 = [\n1, 0, - 4.5e-07, 2e-05, \n];";
        assert_eq!(
            parse_array(js, "g_ltc_1").unwrap(),
            vec![1.0, 0.0, -4.5e-7, 2e-5]
        );
        let inc = "// tabMagnitude: the norm\nstatic const float tabMagnitude[size*size] = {\n1.000000f, \n0.5f\n};";
        assert_eq!(parse_array(inc, "tabMagnitude").unwrap(), vec![1.0, 0.5]);
        let nested = "tabMinv[size*size] = {\n{1, 2, 3}, \n{4, 5, 6}\n};";
        assert_eq!(parse_array(nested, "tabMinv").unwrap().len(), 6);
        assert!(parse_array("x = [1, zz]", "x").is_err());
        assert!(parse_array("x = [1, 2", "x").is_err());
    }

    #[test]
    fn malformed_tables_are_errors() {
        let t = HeitzTable {
            n: 1,
            ltc_1: vec![[1.0, 0.0, 0.0, 1.0]],
            ltc_2: vec![[1.0, 0.0, 0.0, 0.0]],
        };
        assert!(t.lookup(0.5, 0.5).is_err());
        let t = HeitzTable {
            n: 2,
            ltc_1: vec![[1.0, 0.0, 0.0, 1.0]; 3],
            ltc_2: vec![[1.0, 0.0, 0.0, 0.0]; 4],
        };
        assert!(t.ltc_at(0.5, 0.5).is_err());
    }

    #[test]
    fn axes_follow_fitltc() {
        let (mus, alphas) = heitz_axes(64);
        assert_eq!(mus[0], 1.0);
        assert!((mus[63] - 1.57f64.cos()).abs() < 1e-15);
        assert_eq!(alphas[0], 1e-5);
        assert_eq!(alphas[63], 1.0);
    }
}
