//! The variables a fit's polynomials take: the table's axes through a warp (√x, x², 2^(kx)),
//! or, for a split sum or an albedo of a microfacet NDF, the *corner* pair.
//!
//! **Why the corner pair.** Near grazing views of smooth surfaces (n·v = μ → 0 and α → 0
//! together) these integrals depend on μ/α alone: the geometry scales with α (the masking
//! layer is α wide). So E, A and B take every value of a curve Φ(μ/α) in any neighbourhood
//! of (0, 0) — height-correlated GGX's albedo dips from 1 to 0.89 and back within μ ≈ α — a
//! point no polynomial in (μ, α), √μ or r resolves: its best error there is half the dip.
//! In polar coordinates of the (√μ, √α) plane, angle a = √(μ/(μ + α)) and radius
//! ρ = √((μ + α)/2), that point is the edge ρ = 0 along which the function is Φ(a²/(1 − a²)):
//! smooth, and polynomials converge. (√ of μ/(μ + α), not the ratio itself: at rough grazing
//! views the integrals go like √μ.)
//!
//! Every variable is mapped affinely onto [−1, 1] (global polynomials) or [0, 1] (cells of a
//! piecewise one) over its values on the validation set; the map's constants are f32, and
//! the f64 evaluation here is the emitted code's, operation for operation.

use super::target::Input;
use crate::approx::program::{Arg, Op, Program};
use crate::lut::Quantity;
use crate::model::RoughnessQuantity;
use serde::{Deserialize, Serialize};

/// How an axis' coordinate x becomes a variable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "warp")]
pub enum Warp {
    /// x.
    Linear,
    /// √x.
    Sqrt,
    /// x² (a perceptual roughness's α).
    Square,
    /// 2^(rate·x).
    Exp2 { rate: f32 },
}

/// One variable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "var")]
pub enum Var {
    /// Axis `axis`'s coordinate through `warp`.
    Axis { axis: usize, warp: Warp },
    /// √(μ/(μ + α + 10⁻²⁰)) of the cosine axis `mu` and the roughness axis `rough` (α = r²
    /// when `square`, else the coordinate itself).
    CornerAngle {
        mu: usize,
        rough: usize,
        square: bool,
    },
    /// √(μ + α) of the same (the map to [−1, 1] divides by √2).
    CornerRadius {
        mu: usize,
        rough: usize,
        square: bool,
    },
}

/// A set of variables with their affine maps `t = x·scale + offset`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VarSet {
    pub vars: Vec<Var>,
    /// Per variable, (scale, offset): onto [−1, 1] or [0, 1] (see [`VarSet::map_to`]).
    pub maps: Vec<(f32, f32)>,
}

/// The smallest denominator term of the corner angle: keeps 0/0 out at μ = α = 0 (f32's
/// smallest normal is 1.2e-38), changes nothing above 1e-19.
const CORNER_EPS: f64 = 1e-20;

impl Var {
    /// A short name for tables: `mu`, `sqrt(mu)`, `exp2(-6.5 mu)`, `corner angle`, …
    pub fn label(&self, inputs: &[Input]) -> String {
        let short = |k: usize| {
            let n = &inputs[k].name;
            match inputs[k].quantity {
                Quantity::Cosine => "mu".to_string(),
                Quantity::Roughness(RoughnessQuantity::Alpha) => "alpha".to_string(),
                Quantity::Roughness(_) => "r".to_string(),
                _ => n.clone(),
            }
        };
        match *self {
            Var::Axis { axis, warp } => match warp {
                Warp::Linear => short(axis),
                Warp::Sqrt => format!("sqrt({})", short(axis)),
                Warp::Square => {
                    if matches!(
                        inputs[axis].quantity,
                        Quantity::Roughness(RoughnessQuantity::Perceptual)
                    ) {
                        "alpha".into()
                    } else {
                        format!("{}^2", short(axis))
                    }
                }
                Warp::Exp2 { rate } => format!("exp2({rate} {})", short(axis)),
            },
            Var::CornerAngle { .. } => "sqrt(mu/(mu+alpha))".into(),
            Var::CornerRadius { .. } => "sqrt(mu+alpha)".into(),
        }
    }

    /// The variable at the (domain-clamped) coordinates `x`, in f64.
    pub fn eval(&self, x: &[f64]) -> f64 {
        let alpha = |k: usize, square: bool| if square { x[k] * x[k] } else { x[k] };
        match *self {
            Var::Axis { axis, warp } => {
                let v = x[axis];
                match warp {
                    Warp::Linear => v,
                    Warp::Sqrt => v.max(0.0).sqrt(),
                    Warp::Square => v * v,
                    Warp::Exp2 { rate } => (rate as f64 * v).exp2(),
                }
            }
            Var::CornerAngle { mu, rough, square } => {
                let d = x[mu] + alpha(rough, square);
                (x[mu] / (d + CORNER_EPS)).sqrt()
            }
            Var::CornerRadius { mu, rough, square } => {
                (x[mu] + alpha(rough, square)).max(0.0).sqrt()
            }
        }
    }
}

/// Whether an input's coordinate needs clamping to the fit's domain in the code: when the
/// domain is narrower than what callers pass (cosines and perceptual roughness or α in [0, 1]).
pub fn needs_clamp(input: &Input) -> bool {
    let natural = match input.quantity {
        Quantity::Cosine
        | Quantity::Roughness(RoughnessQuantity::Perceptual | RoughnessQuantity::Alpha) => {
            Some([0.0, 1.0])
        }
        _ => None,
    };
    natural != Some(input.domain)
}

/// The coordinates clamped to the domain, as the code clamps them (in f32 bounds).
pub fn clamp_inputs(inputs: &[Input], x: &[f64]) -> Vec<f64> {
    inputs
        .iter()
        .zip(x)
        .map(|(i, &v)| {
            let [lo, hi] = i.domain;
            if needs_clamp(i) {
                v.clamp(lo as f32 as f64, hi as f32 as f64)
            } else {
                v.clamp(lo, hi)
            }
        })
        .collect()
}

impl VarSet {
    /// The variables mapped onto `[lo, hi]` (−1..1 or 0..1) over the values they take at
    /// `points` (clamped coordinates).
    pub fn map_to(vars: Vec<Var>, points: &[Vec<f64>], lo: f64, hi: f64) -> VarSet {
        let maps = vars
            .iter()
            .map(|v| {
                let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
                for p in points {
                    let x = v.eval(p);
                    a = a.min(x);
                    b = b.max(x);
                }
                if b <= a {
                    return (1.0, (lo - a) as f32);
                }
                let scale = (hi - lo) / (b - a);
                (scale as f32, (lo - a * scale) as f32)
            })
            .collect();
        VarSet { vars, maps }
    }

    /// The mapped variables at clamped coordinates `x`, as the code computes them (f32
    /// constants, f64 arithmetic).
    pub fn eval(&self, x: &[f64]) -> Vec<f64> {
        self.vars
            .iter()
            .zip(&self.maps)
            .map(|(v, &(s, o))| v.eval(x) * s as f64 + o as f64)
            .collect()
    }

    /// Emits the clamped inputs and the mapped variables (sharing α and μ + α between the
    /// corner pair). `extra`: a factor applied to every map (a piecewise fit's cell count
    /// per variable), or 1.
    pub fn emit(&self, p: &mut Program, inputs: &[Input], extra: &[f32]) -> Vec<Arg> {
        // an input under a square root or a quotient is clamped to its domain even when the
        // domain is the natural one: a caller's n·v slightly below 0 (a normal-mapped
        // back face) would otherwise give NaN; a polynomial extrapolates finitely
        let under_root = |k: usize| {
            self.vars.iter().any(|v| match *v {
                Var::Axis { axis, warp } => axis == k && warp == Warp::Sqrt,
                Var::CornerAngle { mu, rough, .. } | Var::CornerRadius { mu, rough, .. } => {
                    mu == k || rough == k
                }
            })
        };
        let xs: Vec<Arg> = inputs
            .iter()
            .enumerate()
            .map(|(k, i)| {
                if needs_clamp(i) || under_root(k) {
                    p.op(Op::Clamp(
                        Arg::Input(k),
                        i.domain[0] as f32,
                        i.domain[1] as f32,
                    ))
                } else {
                    Arg::Input(k)
                }
            })
            .collect();
        let mut alpha: Option<Arg> = None;
        let mut sum: Option<Arg> = None;
        let mut get_alpha = |p: &mut Program, k: usize, square: bool| {
            *alpha.get_or_insert_with(|| {
                if square {
                    p.op(Op::Mul(xs[k], xs[k]))
                } else {
                    xs[k]
                }
            })
        };
        let mut out = Vec::with_capacity(self.vars.len());
        for (j, (v, &(s, o))) in self.vars.iter().zip(&self.maps).enumerate() {
            let f = extra.get(j).copied().unwrap_or(1.0);
            let raw = match *v {
                Var::Axis { axis, warp } => match warp {
                    Warp::Linear => xs[axis],
                    Warp::Sqrt => p.op(Op::Sqrt(xs[axis])),
                    Warp::Square => get_alpha(p, axis, true),
                    Warp::Exp2 { rate } => {
                        let y = p.op(Op::Mul(xs[axis], Arg::Const(rate)));
                        p.op(Op::Exp2(y))
                    }
                },
                Var::CornerAngle { mu, rough, square }
                | Var::CornerRadius { mu, rough, square } => {
                    let a = get_alpha(p, rough, square);
                    let d = *sum.get_or_insert_with(|| p.op(Op::Add(xs[mu], a)));
                    if matches!(v, Var::CornerAngle { .. }) {
                        let den = p.op(Op::Add(d, Arg::Const(CORNER_EPS as f32)));
                        let q = p.op(Op::Div(xs[mu], den));
                        p.op(Op::Sqrt(q))
                    } else {
                        p.op(Op::Sqrt(d))
                    }
                }
            };
            out.push(p.affine(raw, s * f, o * f));
        }
        out
    }
}

/// The variable sets worth trying for a table with these inputs, simplest first. `corner`:
/// the table's model has the μ/α scaling at grazing smooth views (microfacet NDFs with a
/// smooth limit: `brdfbake fit` takes every table with an NDF).
pub fn candidates(inputs: &[Input], corner: bool) -> Vec<Vec<Var>> {
    let mu = inputs.iter().position(|i| i.quantity == Quantity::Cosine);
    let rough = inputs.iter().position(|i| {
        matches!(
            i.quantity,
            Quantity::Roughness(RoughnessQuantity::Perceptual | RoughnessQuantity::Alpha)
        )
    });
    let lin = |k: usize| Var::Axis {
        axis: k,
        warp: Warp::Linear,
    };
    let mut sets: Vec<Vec<Var>> = vec![(0..inputs.len()).map(lin).collect()];
    if let Some(m) = mu {
        let mut s: Vec<Var> = (0..inputs.len()).map(lin).collect();
        s[m] = Var::Axis {
            axis: m,
            warp: Warp::Sqrt,
        };
        sets.push(s);
    }
    if let Some(r) = rough {
        if matches!(
            inputs[r].quantity,
            Quantity::Roughness(RoughnessQuantity::Perceptual)
        ) {
            let mut s: Vec<Var> = (0..inputs.len()).map(lin).collect();
            s[r] = Var::Axis {
                axis: r,
                warp: Warp::Square,
            };
            sets.push(s);
        }
    }
    if let (Some(m), Some(r), true, 2) = (mu, rough, corner, inputs.len()) {
        let square = matches!(
            inputs[r].quantity,
            Quantity::Roughness(RoughnessQuantity::Perceptual)
        );
        sets.push(vec![
            Var::CornerAngle {
                mu: m,
                rough: r,
                square,
            },
            Var::CornerRadius {
                mu: m,
                rough: r,
                square,
            },
        ]);
    }
    sets
}
