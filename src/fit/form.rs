//! A fitted function: its variables and, per channel, a polynomial in them (one global
//! polynomial, or one per cell of a uniform grid of cells). [`Fitted::program`] turns it into
//! the straight-line program that is emitted, evaluated and counted; the sidecar stores this
//! struct, so `verify` rebuilds exactly the code's function from it.

use super::target::Input;
use super::vars::VarSet;
use crate::approx::poly::Support;
use crate::approx::program::{Arg, IntOp, Op, OpCount, Program};
use serde::{Deserialize, Serialize};

/// The unit roundoff of f32.
pub const U32: f64 = f32::EPSILON as f64 / 2.0;

/// One channel's polynomial.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChannelPoly {
    /// Exponents, one tuple per monomial (downward closed).
    pub exponents: Vec<Vec<u8>>,
    /// Monomial coefficients in the mapped variables.
    pub coef: Vec<f32>,
}

/// The polynomial part of a fit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "form")]
pub enum Form {
    /// One polynomial per channel over the whole domain (variables mapped to [−1, 1]).
    Polynomial { channels: Vec<ChannelPoly> },
    /// `cells[v]` uniform cells per variable (mapped to [0, 1]); per cell and channel a
    /// polynomial of the same exponents in the cell's local variables, in [−1, 1].
    Piecewise {
        cells: Vec<usize>,
        exponents: Vec<Vec<u8>>,
        /// Indexed by channel, then cell, then monomial.
        coef: Vec<Vec<Vec<f32>>>,
    },
}

/// A fitted function.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Fitted {
    pub vars: VarSet,
    #[serde(flatten)]
    pub form: Form,
}

impl Fitted {
    /// The program: clamped inputs, variables, polynomials; outputs named `channels`.
    pub fn program(&self, inputs: &[Input], channels: &[String]) -> Program {
        let names: Vec<&str> = inputs.iter().map(|i| i.name.as_str()).collect();
        let mut p = Program::new(&names);
        match &self.form {
            Form::Polynomial { channels: polys } => {
                let t = self.vars.emit(&mut p, inputs, &[]);
                for (name, cp) in channels.iter().zip(polys) {
                    let s = support(&cp.exponents, t.len());
                    let coef: Vec<Arg> = cp.coef.iter().map(|&c| Arg::Const(c)).collect();
                    let v = p.horner(&s, &coef, &t);
                    p.outputs.push((name.clone(), v));
                }
            }
            Form::Piecewise {
                cells,
                exponents,
                coef,
            } => {
                let scale: Vec<f32> = cells.iter().map(|&k| k as f32).collect();
                let xs = self.vars.emit(&mut p, inputs, &scale);
                let s = support(exponents, xs.len());
                let mut idx: Vec<usize> = Vec::new();
                let mut t: Vec<Arg> = Vec::new();
                for (&x, &k) in xs.iter().zip(cells) {
                    if k == 1 {
                        // one cell: x·1 ∈ [0, 1], the local variable 2x − 1
                        t.push(p.affine(x, 2.0, -1.0));
                        continue;
                    }
                    let i = p.int_op(IntOp::Cell { x, cells: k });
                    let fi = p.op(Op::FromInt(i));
                    let d = p.op(Op::Sub(x, fi));
                    t.push(p.affine(d, 2.0, -1.0));
                    idx.push(i);
                }
                // cell number i₀ + k₀·(i₁ + k₁·…) over the split variables, then × monomials
                let split: Vec<usize> = cells.iter().copied().filter(|&k| k > 1).collect();
                let base = if idx.is_empty() {
                    None
                } else {
                    let mut n = idx[idx.len() - 1];
                    for j in (0..idx.len() - 1).rev() {
                        n = p.int_op(IntOp::MulAdd {
                            a: n,
                            k: split[j],
                            b: idx[j],
                        });
                    }
                    Some(p.int_op(IntOp::Scale { a: n, k: s.len() }))
                };
                for (c, name) in channels.iter().enumerate() {
                    let args: Vec<Arg> = match base {
                        Some(b) => {
                            p.arrays.push(
                                coef[c]
                                    .iter()
                                    .flat_map(|cell| cell.iter().copied())
                                    .collect(),
                            );
                            let array = p.arrays.len() - 1;
                            (0..s.len())
                                .map(|k| Arg::Load {
                                    array,
                                    index: b,
                                    offset: k,
                                })
                                .collect()
                        }
                        None => coef[c][0].iter().map(|&v| Arg::Const(v)).collect(),
                    };
                    let v = p.horner(&s, &args, &t);
                    p.outputs.push((name.clone(), v));
                }
            }
        }
        p
    }

    /// Coefficients per channel (all cells).
    pub fn coefficients(&self) -> usize {
        match &self.form {
            Form::Polynomial { channels } => channels.iter().map(|c| c.coef.len()).sum(),
            Form::Piecewise { coef, .. } => coef.iter().flatten().map(|c| c.len()).sum(),
        }
    }

    /// A description for tables: `degree 4 in (sqrt(mu), r)`, `3x3 cells of degree 6 in …`.
    pub fn describe(&self, inputs: &[Input]) -> String {
        let vars: Vec<String> = self.vars.vars.iter().map(|v| v.label(inputs)).collect();
        let vars = format!("({})", vars.join(", "));
        match &self.form {
            Form::Polynomial { channels } => {
                let degs: Vec<String> = channels
                    .iter()
                    .map(|c| {
                        let s = support(&c.exponents, self.vars.vars.len());
                        let full = Support::total_degree(s.nvars(), s.degree());
                        if s == full {
                            format!("{}", s.degree())
                        } else {
                            format!("{}/{}t", s.degree(), s.len())
                        }
                    })
                    .collect();
                let mut d = degs.clone();
                d.dedup();
                if d.len() == 1 {
                    format!("polynomial, degree {} in {vars}", d[0])
                } else {
                    format!("polynomial, degrees {} in {vars}", degs.join("+"))
                }
            }
            Form::Piecewise {
                cells, exponents, ..
            } => {
                let s = support(exponents, self.vars.vars.len());
                let c: Vec<String> = cells.iter().map(|k| k.to_string()).collect();
                format!("{} cells of degree {} in {vars}", c.join("x"), s.degree())
            }
        }
    }

    /// A bound on how far an f32 evaluation of the program (every operation rounded, the
    /// GPU's exp2 and sqrt within 4 ulp) can be from its f64 evaluation, anywhere in the
    /// domain: for each channel's polynomial, u·Σ|c|·2(d + 1) for the Horner steps
    /// (Higham 2002, §5.1) plus Σ|c|·|e|·δt for the variables' own errors δt, each δt
    /// bounded from how the variable is computed; then doubled. `points` (clamped
    /// coordinates) give the variables' largest magnitudes.
    pub fn f32_bound(&self, points: &[Vec<f64>]) -> Vec<f64> {
        let n = self.vars.vars.len();
        // largest |raw variable| per variable
        let mut big = vec![0.0f64; n];
        for x in points {
            for (b, v) in big.iter_mut().zip(&self.vars.vars) {
                *b = b.max(v.eval(x).abs());
            }
        }
        let cells: Vec<f64> = match &self.form {
            Form::Piecewise { cells, .. } => cells.iter().map(|&k| k as f64).collect(),
            Form::Polynomial { .. } => vec![1.0; n],
        };
        let dt: f64 = self
            .vars
            .vars
            .iter()
            .zip(&self.vars.maps)
            .enumerate()
            .map(|(j, (v, &(s, o)))| {
                use super::vars::{Var, Warp};
                // relative error of the raw variable, in units of u
                let k = match v {
                    Var::Axis { warp, .. } => match warp {
                        Warp::Linear => 1.0,
                        Warp::Sqrt | Warp::Square => 5.0,
                        Warp::Exp2 { rate } => 5.0 + (*rate as f64).abs() * 2.0,
                    },
                    Var::CornerAngle { .. } | Var::CornerRadius { .. } => 16.0,
                };
                let dx = k * U32 * big[j];
                let scale = (s as f64 * cells[j]).abs();
                // the map x·s + o (and a cell's 2(x − i) − 1: doubles it, plus 2 roundings)
                let m =
                    scale * dx + 4.0 * U32 * (scale * big[j] + (o as f64 * cells[j]).abs() + 1.0);
                match &self.form {
                    Form::Piecewise { .. } => 2.0 * m + 4.0 * U32 * (cells[j] + 1.0),
                    Form::Polynomial { .. } => m,
                }
            })
            .fold(0.0, f64::max);
        let per_channel = |exps: &[Vec<u8>], coef: &[f32]| {
            let s = support(exps, n);
            let c: Vec<f64> = coef.iter().map(|&v| v as f64).collect();
            2.0 * (U32 * s.rounding_weight(&c) + s.derivative_weight(&c) * dt)
        };
        match &self.form {
            Form::Polynomial { channels } => channels
                .iter()
                .map(|cp| per_channel(&cp.exponents, &cp.coef))
                .collect(),
            Form::Piecewise {
                exponents, coef, ..
            } => coef
                .iter()
                .map(|cells| {
                    cells
                        .iter()
                        .map(|c| per_channel(exponents, c))
                        .fold(0.0, f64::max)
                })
                .collect(),
        }
    }

    /// Whether the fit can be evaluated: its supports are supports of its variables and
    /// every coefficient list matches its support (a sidecar may have been edited).
    pub fn check(&self, ninputs: usize) -> Result<(), String> {
        let n = self.vars.vars.len();
        for v in &self.vars.vars {
            let axes = match *v {
                super::vars::Var::Axis { axis, .. } => vec![axis],
                super::vars::Var::CornerAngle { mu, rough, .. }
                | super::vars::Var::CornerRadius { mu, rough, .. } => vec![mu, rough],
            };
            if let Some(a) = axes.iter().find(|&&a| a >= ninputs) {
                return Err(format!("a variable of input {a}; the table has {ninputs}"));
            }
        }
        if self.vars.maps.len() != n {
            return Err(format!("{} variables but {} maps", n, self.vars.maps.len()));
        }
        let one = |exps: &[Vec<u8>], ncoef: usize| -> Result<(), String> {
            let s = valid_support(exps, n).ok_or_else(|| {
                format!("exponents {exps:?} are not a support of {n} variables (the constant, and closed downward or under lowering by two)")
            })?;
            if s.len() != exps.len() || ncoef != exps.len() {
                return Err(format!(
                    "{} coefficients for {} distinct monomials",
                    ncoef,
                    s.len()
                ));
            }
            Ok(())
        };
        match &self.form {
            Form::Polynomial { channels } => {
                for c in channels {
                    one(&c.exponents, c.coef.len())?;
                }
            }
            Form::Piecewise {
                cells,
                exponents,
                coef,
            } => {
                if cells.len() != n {
                    return Err(format!("{} cell counts for {n} variables", cells.len()));
                }
                let ncells: usize = cells.iter().product();
                for c in coef {
                    if c.len() != ncells {
                        return Err(format!(
                            "{} cells of coefficients, {ncells} expected",
                            c.len()
                        ));
                    }
                    for cell in c {
                        one(exponents, cell.len())?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The program's operation counts.
    pub fn counts(&self, inputs: &[Input], channels: &[String]) -> OpCount {
        self.program(inputs, channels).counts()
    }
}

/// A support from stored exponents, downward closed or sparse (validated where read:
/// [`Fitted::check`], which `verify` runs on a sidecar's fit).
pub fn support(exps: &[Vec<u8>], nvars: usize) -> Support {
    valid_support(exps, nvars).expect("a valid support")
}

/// The support of `exps` if it is one ([`Support::from_exponents`] or [`Support::sparse`]).
fn valid_support(exps: &[Vec<u8>], nvars: usize) -> Option<Support> {
    Support::from_exponents(nvars, exps.to_vec()).or_else(|| Support::sparse(nvars, exps.to_vec()))
}
