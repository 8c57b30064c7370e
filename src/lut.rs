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
    /// A coordinate of a vector form factor (an `ltc-sphere` table): the z of its direction,
    /// in [−1, 1], or its length, in [0, 1].
    FormFactor,
}

/// How an axis spaces its texels: uniformly in a parameter `p = warp(x)` of its physical
/// coordinate `x` (a cosine, a roughness, …). The axis' `range` is a range of `p`. Engines
/// space their view axes in √(1 − cos θ) (EEVEE, the LTC tables), in θ itself (older LTC
/// tables) or in √cos θ (texels at (i/N)² in cos θ: BSDL), to put more texels where the
/// tabulated function changes fastest; their index axes in √((η − 1)/(η + 1)) (Cycles) or
/// in η² (EEVEE). Every warp is strictly monotone on its coordinate domain, so it has an
/// exact inverse there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Warp {
    /// `p = x`.
    #[default]
    Linear,
    /// `p = √(1 − x)`, `x = 1 − p²`; p in [0, 1] (cosine axes).
    SqrtOneMinus,
    /// `p = √x`, `x = p²`; p in [0, 1] (cosine and Fresnel axes: Cycles' √((η − 1)/(η + 1))).
    Sqrt,
    /// `p = acos x` in radians, `x = cos p`; p in [0, π/2] (cosine axes).
    Acos,
    /// `p = x²`, `x = √p`; p in [0, 1] (cosine and Fresnel axes: EEVEE's η² axis).
    Square,
    /// `p = 1 − x`, `x = 1 − p`; p in [0, 1] (any axis whose coordinate lies in [0, 1]): the
    /// axis runs backwards, its first texel at the largest coordinate — Godot's DFG table
    /// puts perceptual roughness 1 in its first row and samples it at `1 − roughness`.
    OneMinus,
    /// EEVEE's critical-angle remap of the view cosine `x = μ` of a table whose relative index
    /// η < 1 has the critical cosine `c = √(1 − η²)` (0 for η ≥ 1; η is the texel's own, from
    /// the table's fresnel axis): `p = μ/(2c)` for μ ≤ c, `p = 1/2 + (μ − c)/(2(1 − c))`
    /// above; inverse `t = 2p − 1`, `μ = c + t·c` for t ≤ 0, `μ = c + t·(1 − c)` above. The
    /// first half of the texels lies below the critical angle (total internal reflection of
    /// a smooth interface), the second half above it. p in [0, 1].
    CriticalAngle,
}

impl Warp {
    pub const ALL: [Warp; 7] = [
        Warp::Linear,
        Warp::SqrtOneMinus,
        Warp::Sqrt,
        Warp::Acos,
        Warp::Square,
        Warp::OneMinus,
        Warp::CriticalAngle,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Warp::Linear => "linear",
            Warp::SqrtOneMinus => "sqrt-one-minus",
            Warp::Sqrt => "sqrt",
            Warp::Acos => "acos",
            Warp::Square => "square",
            Warp::OneMinus => "one-minus",
            Warp::CriticalAngle => "critical-angle",
        }
    }

    /// The parameter as a formula of the coordinate `x`.
    pub fn formula(self) -> &'static str {
        match self {
            Warp::Linear => "p = x",
            Warp::SqrtOneMinus => "p = sqrt(1 - x)",
            Warp::Sqrt => "p = sqrt(x)",
            Warp::Acos => "p = acos(x) (radians)",
            Warp::Square => "p = x^2",
            Warp::OneMinus => "p = 1 - x",
            Warp::CriticalAngle => {
                "p = x/(2c) for x <= c, 0.5 + (x - c)/(2(1 - c)) for x > c, with c = sqrt(1 - eta^2) (0 for eta >= 1) of the texel's relative index eta (the fresnel axis)"
            }
        }
    }

    /// The coordinate as a formula of the parameter `p`.
    pub fn inverse_formula(self) -> &'static str {
        match self {
            Warp::Linear => "x = p",
            Warp::SqrtOneMinus => "x = 1 - p^2",
            Warp::Sqrt => "x = p^2",
            Warp::Acos => "x = cos(p)",
            Warp::Square => "x = sqrt(p)",
            Warp::OneMinus => "x = 1 - p",
            Warp::CriticalAngle => {
                "x = c + t*c for t <= 0, c + t*(1 - c) for t > 0, with t = 2p - 1 and c = sqrt(1 - eta^2) (0 for eta >= 1)"
            }
        }
    }

    /// Whether the warp depends on another axis of the table (the critical angle: on the
    /// relative index of the fresnel axis).
    pub fn is_coupled(self) -> bool {
        self == Warp::CriticalAngle
    }

    /// The parameters the warp is defined for (the accepted `range`); `None` for any finite
    /// number.
    pub fn parameter_domain(self) -> Option<[f64; 2]> {
        match self {
            Warp::Linear => None,
            Warp::SqrtOneMinus
            | Warp::Sqrt
            | Warp::Square
            | Warp::OneMinus
            | Warp::CriticalAngle => Some([0.0, 1.0]),
            Warp::Acos => Some([0.0, std::f64::consts::FRAC_PI_2]),
        }
    }

    /// The coordinates the warp is defined for; a coordinate outside is clamped into it
    /// first (as the shader snippets do).
    pub fn coordinate_domain(self) -> Option<[f64; 2]> {
        match self {
            Warp::Linear => None,
            Warp::SqrtOneMinus
            | Warp::Sqrt
            | Warp::Acos
            | Warp::Square
            | Warp::OneMinus
            | Warp::CriticalAngle => Some([0.0, 1.0]),
        }
    }

    /// `p` of coordinate `x` (clamped into the warp's domain); a coupled warp at the
    /// critical cosine c = 0 (an index η ≥ 1): use [`Warp::parameter_at`] with the texel's own.
    pub fn parameter(self, x: f64) -> f64 {
        self.parameter_at(x, 0.0)
    }

    /// `p` of coordinate `x` (clamped into the warp's domain), the critical-angle warp at
    /// the critical cosine `c` (ignored by the others).
    pub fn parameter_at(self, x: f64, c: f64) -> f64 {
        let x = match self.coordinate_domain() {
            Some([lo, hi]) => x.clamp(lo, hi),
            None => x,
        };
        match self {
            Warp::Linear => x,
            Warp::SqrtOneMinus => (1.0 - x).sqrt(),
            Warp::OneMinus => 1.0 - x,
            Warp::Sqrt => x.sqrt(),
            Warp::Acos => x.acos(),
            Warp::Square => x * x,
            // (as the shader snippets write it: at c = 0, x = 0 gives p = 0, and at c = 1
            // every x ≤ c; the texels of the empty half all hold the value at x = c)
            Warp::CriticalAngle => {
                if x <= c {
                    0.5 * x / c.max(1e-30)
                } else {
                    0.5 + 0.5 * (x - c) / (1.0 - c).max(1e-30)
                }
            }
        }
    }

    /// The coordinate `x` of parameter `p`; a coupled warp at c = 0 (see [`Warp::parameter`]).
    pub fn coordinate(self, p: f64) -> f64 {
        self.coordinate_at(p, 0.0)
    }

    /// The coordinate `x` of parameter `p`, the critical-angle warp at the critical cosine
    /// `c` (ignored by the others).
    pub fn coordinate_at(self, p: f64, c: f64) -> f64 {
        match self {
            Warp::Linear => p,
            Warp::SqrtOneMinus => 1.0 - p * p,
            Warp::OneMinus => 1.0 - p,
            Warp::Sqrt => p * p,
            Warp::Acos => p.cos(),
            Warp::Square => p.max(0.0).sqrt(),
            Warp::CriticalAngle => {
                let t = 2.0 * p - 1.0;
                if t > 0.0 {
                    c + t * (1.0 - c)
                } else {
                    c + t * c
                }
            }
        }
    }
}

/// The critical cosine `c = √(1 − η²)` of a relative index η (0 for η ≥ 1, where there is
/// no total internal reflection): the parameter of the critical-angle warp.
pub fn critical_cosine(eta: f64) -> f64 {
    if eta >= 1.0 {
        0.0
    } else {
        ((1.0 - eta) * (1.0 + eta)).max(0.0).sqrt()
    }
}

/// One axis of a table.
///
/// Texel `i` sits at the parameter `p_i` the `convention` gives within `range`, i.e. at the
/// coordinate `x_i = warp⁻¹(p_i)`, and holds the tabulated function's value at
/// `clamp(x_i, clamp[0], clamp[1])` (engines evaluate their end texels slightly inside the
/// domain, e.g. Cycles at cos θ ≥ 1e-4). A lookup of `x` samples at the texture coordinate
/// of `warp(x)`; the function the table represents is `x ↦ f(clamp(x))`.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The axis' name, which also says what it measures: `cos_theta_v`, `n_dot_h`, `roughness`, …
    pub name: String,
    pub quantity: Quantity,
    pub size: usize,
    /// The range of the parameter `p = warp(x)` (of `x` itself for a linear axis).
    pub range: [f64; 2],
    pub convention: Convention,
    /// How the texels are spaced in the coordinate (linear for most tables).
    pub warp: Warp,
    /// Where the texels' coordinates are clamped to before the function is evaluated.
    pub clamp: Option<[f64; 2]>,
}

impl Axis {
    /// A linear, unclamped axis.
    pub fn new(
        name: &str,
        quantity: Quantity,
        size: usize,
        range: [f64; 2],
        convention: Convention,
    ) -> Axis {
        Axis {
            name: name.into(),
            quantity,
            size,
            range,
            convention,
            warp: Warp::Linear,
            clamp: None,
        }
    }

    /// The parameter `p_i` of texel `i`: uniform in `range` by the convention.
    pub fn parameter(&self, i: usize) -> f64 {
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

    /// The coordinate `x_i = warp⁻¹(p_i)` of texel `i`, before the clamp (a coupled warp at
    /// c = 0: see [`Axis::nominal_coord_at`]).
    pub fn nominal_coord(&self, i: usize) -> f64 {
        self.warp.coordinate(self.parameter(i))
    }

    /// [`Axis::nominal_coord`] of a critical-angle axis in a slice whose critical cosine is
    /// `c` ([`critical_cosine`]; other warps ignore it).
    pub fn nominal_coord_at(&self, i: usize, c: f64) -> f64 {
        self.warp.coordinate_at(self.parameter(i), c)
    }

    /// The coordinate of texel `i` in the axis' own quantity, where its value is evaluated:
    /// `clamp(x_i)` (a coupled warp at c = 0: see [`Axis::coord_at`]).
    pub fn coord(&self, i: usize) -> f64 {
        self.clamped(self.nominal_coord(i))
    }

    /// [`Axis::coord`] of a critical-angle axis in a slice whose critical cosine is `c`.
    pub fn coord_at(&self, i: usize, c: f64) -> f64 {
        self.clamped(self.nominal_coord_at(i, c))
    }

    /// `x` clamped as the texels' coordinates are: the point whose value the table holds
    /// for a lookup at `x`.
    pub fn clamped(&self, x: f64) -> f64 {
        match self.clamp {
            Some([a, b]) => x.clamp(a, b),
            None => x,
        }
    }

    /// Every texel coordinate, in texel order.
    pub fn coords(&self) -> Vec<f64> {
        (0..self.size).map(|i| self.coord(i)).collect()
    }

    /// The smallest and largest coordinate the axis' texels cover (before the clamp): the
    /// range of `x` a lookup interpolates in. (A critical-angle axis spans [0, 1] whatever
    /// its critical cosine: both ends map to the range ends.)
    pub fn coordinate_span(&self) -> [f64; 2] {
        let [a, b] = self.range.map(|p| self.warp.coordinate(p));
        [a.min(b), a.max(b)]
    }

    /// `""` for a linear unclamped axis, else what the warp and the clamp do, for messages
    /// and summaries: `, warp sqrt-one-minus (p = sqrt(1 - x), range of p), values at x clamped to [a, b]`.
    pub fn spacing_note(&self) -> String {
        let mut s = String::new();
        if self.warp != Warp::Linear {
            s.push_str(&format!(
                ", warp {} ({}, the range is p's)",
                self.warp.name(),
                self.warp.formula()
            ));
        }
        if let Some([a, b]) = self.clamp {
            s.push_str(&format!(", values at x clamped to [{a}, {b}]"));
        }
        s
    }

    /// The coordinate `x` of this axis as the physical quantity it stands for, for people:
    /// `n·v = 0.5`, `r = 0.4 (α = 0.16)`, `η = 1.5`, `η = 1 + 2e-8`, `exponent e = 5`.
    pub fn physical(&self, x: f64) -> String {
        let (sym, value) = self.physical_parts(x, crate::numfmt::num);
        format!("{sym} = {value}")
    }

    /// [`Axis::physical`] with 3 significant digits and without the α of a perceptual
    /// roughness, for short texts: `n·v = 0.0317`, `r = 0.35`.
    pub fn physical_short(&self, x: f64) -> String {
        let (sym, value) = self.physical_parts(x, crate::numfmt::short);
        let value = value.split(" (α").next().unwrap_or(&value).to_string();
        format!("{sym} = {value}")
    }

    /// The symbol of [`Axis::physical`] (`n·v`, `r`, `η`).
    pub fn physical_symbol(&self) -> String {
        self.physical_parts(0.5, crate::numfmt::num).0
    }

    /// Coordinates `x0` to `x1` of this axis as a physical range: `n·v from 0.0005 to 0.29`.
    pub fn physical_range(&self, x0: f64, x1: f64) -> String {
        let (sym, a) = self.physical_parts(x0, crate::numfmt::num);
        let (_, b) = self.physical_parts(x1, crate::numfmt::num);
        format!("{sym} from {a} to {b}")
    }

    /// [`Axis::physical`] as its symbol and its value: (`r`, `0.4 (α = 0.16)`).
    fn physical_parts(&self, x: f64, num: fn(f64) -> String) -> (String, String) {
        use crate::numfmt::near_one;
        let (sym, val): (&str, String) = match self.quantity {
            Quantity::Cosine => {
                let sym = match self.name.as_str() {
                    "cos_theta_v" | "n_dot_v" => "n·v",
                    "cos_theta_l" | "n_dot_l" => "n·l",
                    "cos_theta_h" | "n_dot_h" => "n·h",
                    "cos_theta" => "cos θ",
                    other => other,
                };
                (sym, num(x))
            }
            Quantity::Roughness(q) => match q {
                RoughnessQuantity::Alpha => ("α", num(x)),
                RoughnessQuantity::Perceptual => {
                    ("r", format!("{} (α = {})", num(x), num(q.to_alpha(x))))
                }
                RoughnessQuantity::CookTorranceM => ("m", num(x)),
                RoughnessQuantity::BlinnPhongExponent => (
                    "exponent s",
                    format!("{} (α = {})", num(x), num(q.to_alpha(x))),
                ),
                RoughnessQuantity::Exponent => ("exponent n", num(x)),
            },
            Quantity::Fresnel(q) => {
                let p = q.to_parameter(x);
                if q.is_eta() {
                    let near = (p - 1.0).abs() < 1e-4 && p != 1.0;
                    ("η", if near { near_one(p) } else { num(p) })
                } else if q.is_f0() {
                    ("F0", num(p))
                } else {
                    ("exponent e", num(p))
                }
            }
            Quantity::Anisotropy => ("anisotropy", num(x)),
            Quantity::FormFactor => (self.name.as_str(), num(x)),
        };
        (sym.to_string(), val)
    }

    /// The NDF parameter α of texel `i` (roughness axes only).
    pub fn alpha(&self, i: usize) -> Option<f64> {
        match self.quantity {
            Quantity::Roughness(q) => Some(q.to_alpha(self.coord(i))),
            Quantity::Cosine
            | Quantity::Fresnel(_)
            | Quantity::Anisotropy
            | Quantity::FormFactor => None,
        }
    }

    /// The Fresnel parameter (F0 or η) of texel `i` (Fresnel axes only).
    pub fn fresnel_parameter(&self, i: usize) -> Option<f64> {
        match self.quantity {
            Quantity::Fresnel(q) => Some(q.to_parameter(self.coord(i))),
            _ => None,
        }
    }

    /// The normalized parameter `t = (warp(x) − lo)/(hi − lo)` of coordinate `x`, clamped
    /// to [0, 1]; 0 on an axis of one texel. (A coupled warp at c = 0: see
    /// [`Axis::normalized_at`].)
    pub fn normalized(&self, x: f64) -> f64 {
        self.normalized_at(x, 0.0)
    }

    /// [`Axis::normalized`] of a critical-angle axis at the critical cosine `c`.
    pub fn normalized_at(&self, x: f64, c: f64) -> f64 {
        let [lo, hi] = self.range;
        if hi == lo {
            return 0.0;
        }
        ((self.warp.parameter_at(x, c) - lo) / (hi - lo)).clamp(0.0, 1.0)
    }

    /// The continuous texel-space position of coordinate `x` (texel i at position i),
    /// clamped to `[0, size − 1]` as clamp-to-edge sampling does. (A coupled warp at c = 0:
    /// see [`Axis::texel_position_at`].)
    pub fn texel_position(&self, x: f64) -> f64 {
        self.texel_position_at(x, 0.0)
    }

    /// [`Axis::texel_position`] of a critical-angle axis at the critical cosine `c`.
    pub fn texel_position_at(&self, x: f64, c: f64) -> f64 {
        let [lo, hi] = self.range;
        let p = self.warp.parameter_at(x, c);
        let t = if hi != lo { (p - lo) / (hi - lo) } else { 0.0 };
        let pos = match self.convention {
            Convention::Centers => t * self.size as f64 - 0.5,
            Convention::Endpoints => t * (self.size as f64 - 1.0),
        };
        pos.clamp(0.0, (self.size - 1) as f64)
    }

    /// The normalized texture coordinate a GPU must sample for coordinate `x`.
    pub fn texture_coordinate(&self, x: f64) -> f64 {
        self.texture_coordinate_at(x, 0.0)
    }

    /// [`Axis::texture_coordinate`] of a critical-angle axis at the critical cosine `c`.
    pub fn texture_coordinate_at(&self, x: f64, c: f64) -> f64 {
        (self.texel_position_at(x, c) + 0.5) / self.size as f64
    }
}

/// The critical cosine of every texel of the axis named `fresnel` of `axes` (`[0.0]` where
/// there is none): the parameter a critical-angle axis takes in each slice.
pub fn critical_cosines(axes: &[Axis]) -> Vec<f64> {
    match axes.iter().find(|a| a.name == "fresnel") {
        Some(f) => (0..f.size)
            .map(|i| f.fresnel_parameter(i).map_or(0.0, critical_cosine))
            .collect(),
        None => vec![0.0],
    }
}

/// The critical cosine a coupled (critical-angle) axis of `axes` takes at texel `idx` (one
/// index per axis, in the same order): from the relative index of the axis named `fresnel`;
/// 0 where there is none or its index is ≥ 1.
pub fn critical_cosine_at_texel(axes: &[Axis], idx: &[usize]) -> f64 {
    axes.iter()
        .zip(idx)
        .find(|(a, _)| a.name == "fresnel")
        .and_then(|(a, &i)| a.fresnel_parameter(i))
        .map_or(0.0, critical_cosine)
}

/// The critical cosine a coupled axis of `axes` takes at the physical coordinates `x` (one
/// per axis): from the relative index of the fresnel axis' (clamped) coordinate.
pub fn critical_cosine_at(axes: &[Axis], x: &[f64]) -> f64 {
    axes.iter()
        .zip(x)
        .find(|(a, _)| a.name == "fresnel")
        .and_then(|(a, &v)| match a.quantity {
            Quantity::Fresnel(q) if q.is_eta() => Some(q.to_parameter(a.clamped(v))),
            _ => None,
        })
        .map_or(0.0, critical_cosine)
}

/// The coordinates of texel `idx` (one index per axis), each in its axis' own quantity and
/// clamped: [`Axis::coord`], a critical-angle axis at its texel's critical cosine.
pub fn texel_coordinates(axes: &[Axis], idx: &[usize]) -> Vec<f64> {
    let c = critical_cosine_at_texel(axes, idx);
    axes.iter()
        .zip(idx)
        .map(|(a, &i)| a.coord_at(i, c))
        .collect()
}

/// Texel `idx` described by its physical coordinates, for people: `r = 1 (α = 1), n·v =
/// 1e-4, η = 1 + 2e-8` ([`Axis::physical`] of each axis at [`texel_coordinates`]).
pub fn texel_physical(axes: &[Axis], idx: &[usize]) -> String {
    axes.iter()
        .zip(texel_coordinates(axes, idx))
        .map(|(a, x)| a.physical(x))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Texel `idx` by its indices in one order for every table, `x` the fastest axis of the
/// stored layout (as the file runs), for people: `x = 15, y = 0, z = 0`.
pub fn texel_indices(idx: &[usize]) -> String {
    idx.iter()
        .zip(["x", "y", "z"])
        .map(|(i, n)| format!("{n} = {i}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// [`texel_coordinates`] before the clamp: [`Axis::nominal_coord`] of every axis, a
/// critical-angle axis at its texel's critical cosine.
pub fn texel_nominal_coordinates(axes: &[Axis], idx: &[usize]) -> Vec<f64> {
    let c = critical_cosine_at_texel(axes, idx);
    axes.iter()
        .zip(idx)
        .map(|(a, &i)| a.nominal_coord_at(i, c))
        .collect()
}

/// One channel of a table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Channel {
    /// Short name, used as the EXR channel name (`E`, `A`, `B`, `DFG_R`, …).
    pub name: String,
    /// What the channel holds, as a formula.
    pub meaning: String,
}

/// A table of test data for encoders' tests: axes `a0, a1, …` of cosines over [0, 1] at texel
/// centres, channels `c0, c1, …`, the texels `data` (channels fastest).
#[cfg(test)]
pub(crate) fn test_table(sizes: &[usize], nc: usize, data: Vec<f32>) -> Lut {
    Lut {
        axes: sizes
            .iter()
            .enumerate()
            .map(|(k, &n)| Axis {
                name: format!("a{k}"),
                quantity: Quantity::Cosine,
                size: n,
                range: [0.0, 1.0],
                convention: Convention::Centers,
                warp: Default::default(),
                clamp: None,
            })
            .collect(),
        channels: (0..nc)
            .map(|c| Channel {
                name: format!("c{c}"),
                meaning: String::new(),
            })
            .collect(),
        data,
        error_estimate: vec![0.0; nc],
        evaluations: 0,
    }
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

    /// The same table with its axes reordered: axis k of the result is axis `order[k]` of
    /// this one (a permutation of `0..axes.len()`).
    pub fn permuted(&self, order: &[usize]) -> Lut {
        assert_eq!(order.len(), self.axes.len(), "one index per axis");
        let axes: Vec<Axis> = order.iter().map(|&o| self.axes[o].clone()).collect();
        let nc = self.channels.len();
        let dim = |k: usize| axes.get(k).map_or(1, |a| a.size);
        let mut data = Vec::with_capacity(self.data.len());
        for z in 0..dim(2) {
            for y in 0..dim(1) {
                for x in 0..dim(0) {
                    let mut old = [0usize; 3];
                    for (k, i) in [x, y, z].into_iter().enumerate().take(order.len()) {
                        old[order[k]] = i;
                    }
                    for c in 0..nc {
                        data.push(self.texel(old, c));
                    }
                }
            }
        }
        Lut {
            axes,
            channels: self.channels.clone(),
            data,
            error_estimate: self.error_estimate.clone(),
            evaluations: self.evaluations,
        }
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
        let c = critical_cosine_at(&self.axes, x);
        for (k, a) in self.axes.iter().enumerate() {
            let p = a.texel_position_at(x[k], c);
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
        let dims = [self.dim(0), self.dim(1), self.dim(2)];
        let d = self.axes.len();
        let nc = self.channels.len();
        let stride = self.strides();
        // the flat offsets of a cell's corners from its first texel (an axis of one texel
        // has no second corner)
        let offsets: Vec<usize> = (0..(1usize << d))
            .map(|corner| {
                (0..d)
                    .filter(|&k| (corner >> k) & 1 == 1 && dims[k] >= 2)
                    .map(|k| stride[k])
                    .sum()
            })
            .collect();
        self.max_over_texels(|idx, out| {
            if (0..d).any(|k| dims[k] >= 2 && idx[k] + 1 >= dims[k]) {
                return;
            }
            let base = self.flat(idx);
            for (c, o) in out.iter_mut().enumerate().take(nc) {
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for off in &offsets {
                    let v = self.data[base + off + c] as f64;
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
                *o = o.max(hi - lo);
            }
        })
    }

    /// The flat index into `data` of channel 0 of texel `idx`.
    fn flat(&self, idx: [usize; 3]) -> usize {
        let (nx, ny) = (self.dim(0), self.dim(1));
        ((idx[2] * ny + idx[1]) * nx + idx[0]) * self.channels.len()
    }

    /// The distance in `data` between neighbouring texels along each axis.
    fn strides(&self) -> [usize; 3] {
        let nc = self.channels.len();
        let (nx, ny) = (self.dim(0), self.dim(1));
        [nc, nx * nc, nx * ny * nc]
    }

    /// Per channel, the largest of what `f` records for each texel (`f` raises the entries
    /// of its second argument to the texel's values): rows of texels in parallel, each row's
    /// maxima then combined — the same bits for any thread count, since max is exact and
    /// order-free.
    fn max_over_texels(&self, f: impl Fn([usize; 3], &mut [f64]) + Sync) -> Vec<f64> {
        use rayon::prelude::*;
        let nc = self.channels.len();
        let dims = [self.dim(0), self.dim(1), self.dim(2)];
        (0..dims[1] * dims[2])
            .into_par_iter()
            .map(|r| {
                let mut m = vec![0.0f64; nc];
                let (y, z) = (r % dims[1], r / dims[1]);
                for x in 0..dims[0] {
                    f([x, y, z], &mut m);
                }
                m
            })
            .reduce(
                || vec![0.0f64; nc],
                |mut a, b| {
                    for (x, y) in a.iter_mut().zip(b) {
                        *x = x.max(y);
                    }
                    a
                },
            )
    }

    /// Per channel: the largest |difference| between neighbouring texels along axis `k`.
    pub fn max_steps(&self, k: usize) -> Vec<f64> {
        let dims = [self.dim(0), self.dim(1), self.dim(2)];
        if dims[k] < 2 {
            return vec![0.0; self.channels.len()];
        }
        let step = self.strides()[k];
        self.max_over_texels(|idx, out| {
            if idx[k] + 1 >= dims[k] {
                return;
            }
            let base = self.flat(idx);
            for (c, o) in out.iter_mut().enumerate() {
                let d = (self.data[base + step + c] as f64 - self.data[base + c] as f64).abs();
                *o = o.max(d);
            }
        })
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
        let d = self.axes.len();
        let stride = self.strides();
        self.max_over_texels(|idx, out| {
            // (no table kind has more than 4 channels; a stack buffer keeps the loop free of
            // allocations, a longer one is allocated)
            let mut buf = [0.0f64; 4];
            let mut heap = Vec::new();
            let sum: &mut [f64] = if nc <= 4 {
                &mut buf[..nc]
            } else {
                heap.resize(nc, 0.0);
                &mut heap
            };
            for k in 0..d {
                if dims[k] < 3 {
                    continue;
                }
                let mut mid = idx;
                mid[k] = idx[k].clamp(1, dims[k] - 2);
                let m = self.flat(mid);
                let (a, b) = (m - stride[k], m + stride[k]);
                for (c, s) in sum.iter_mut().enumerate() {
                    let d2 = self.data[a + c] as f64 - 2.0 * self.data[m + c] as f64
                        + self.data[b + c] as f64;
                    *s += d2.abs() / 8.0;
                }
            }
            for (o, s) in out.iter_mut().zip(sum.iter()) {
                *o = o.max(*s);
            }
        })
    }
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
            warp: Warp::Linear,
            clamp: None,
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
