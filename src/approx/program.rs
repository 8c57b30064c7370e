//! A straight-line program of scalar operations: what a fitted function *is*, once. The
//! emitted shader and C/Rust code print it (`crate::encode::function`), the fit's errors are
//! measured by interpreting it (in f64, with its f32 constants), its f32 rounding is
//! measured by interpreting it in f32, and its operation count is counted on it — so the
//! numbers in the comment are those of the code beside them.
//!
//! Operation count (the sidecar's `ops`): one per `+ − ×`, fused multiply-add (written
//! `a * b + c`, one instruction on GPUs), `min`, `max`, `clamp`, `/`, `sqrt`, `exp2`, and one
//! per integer operation of a piecewise fit's cell index (float-to-int conversion and clamp,
//! multiply-add, int-to-float conversion). `/`, `sqrt` and `exp2` are also counted as
//! `special` (transcendental units: slower on most GPUs). Constant-array reads are counted
//! as `loads`.

use super::poly::Support;

/// An operand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Arg {
    /// The function's k-th parameter.
    Input(usize),
    /// The value of float statement k.
    Var(usize),
    /// A constant (an f32: the shader's precision; printed so that it reads back exactly).
    Const(f32),
    /// `arrays[array][int var + offset]`.
    Load {
        array: usize,
        index: usize,
        offset: usize,
    },
}

/// One float operation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    Add(Arg, Arg),
    Sub(Arg, Arg),
    Mul(Arg, Arg),
    /// a·b + c.
    Fma(Arg, Arg, Arg),
    Div(Arg, Arg),
    Sqrt(Arg),
    Exp2(Arg),
    Min(Arg, Arg),
    Max(Arg, Arg),
    Clamp(Arg, f32, f32),
    /// The value of int statement k as a float.
    FromInt(usize),
}

/// One integer operation (piecewise fits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IntOp {
    /// `min(int(x), cells − 1)` for x ≥ 0 (truncation is the floor there): a cell index.
    Cell { x: Arg, cells: usize },
    /// `a·k + b` of int statements a and b.
    MulAdd { a: usize, k: usize, b: usize },
    /// `a·k` of int statement a.
    Scale { a: usize, k: usize },
}

#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    Float(Op),
    Int(IntOp),
}

/// A function of named float inputs returning named float outputs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Program {
    pub inputs: Vec<String>,
    pub stmts: Vec<Stmt>,
    /// Constant arrays (piecewise coefficients).
    pub arrays: Vec<Vec<f32>>,
    /// Output channels: (name, value).
    pub outputs: Vec<(String, Arg)>,
}

/// Operation counts of a [`Program`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct OpCount {
    /// Every operation, special ones included.
    pub ops: usize,
    /// Divisions, square roots, exponentials.
    pub special: usize,
    /// Constant-array reads.
    pub loads: usize,
    /// Stored coefficients (inline constants and array entries).
    pub constants: usize,
}

impl Program {
    pub fn new(inputs: &[&str]) -> Program {
        Program {
            inputs: inputs.iter().map(|s| s.to_string()).collect(),
            ..Default::default()
        }
    }

    /// Appends a float operation and returns its value.
    pub fn op(&mut self, op: Op) -> Arg {
        // constant folding keeps trivial steps out of the code and the count
        if let Some(c) = fold(&op) {
            return Arg::Const(c);
        }
        self.stmts.push(Stmt::Float(op));
        Arg::Var(self.float_count() - 1)
    }

    /// Appends an integer operation and returns its statement index.
    pub fn int_op(&mut self, op: IntOp) -> usize {
        self.stmts.push(Stmt::Int(op));
        self.int_count() - 1
    }

    pub fn float_count(&self) -> usize {
        self.stmts
            .iter()
            .filter(|s| matches!(s, Stmt::Float(_)))
            .count()
    }

    pub fn int_count(&self) -> usize {
        self.stmts
            .iter()
            .filter(|s| matches!(s, Stmt::Int(_)))
            .count()
    }

    /// `x·a + b`, folded where a = 1 or b = 0.
    pub fn affine(&mut self, x: Arg, a: f32, b: f32) -> Arg {
        match (a == 1.0, b == 0.0) {
            (true, true) => x,
            (true, false) => self.op(Op::Add(x, Arg::Const(b))),
            (false, true) => self.op(Op::Mul(x, Arg::Const(a))),
            (false, false) => self.op(Op::Fma(x, Arg::Const(a), Arg::Const(b))),
        }
    }

    /// The nested Horner evaluation of the monomial coefficients `coef` (order of
    /// `support`) in the variables `t`: one multiply-add per step (the count is
    /// [`Support::horner_cost`] at most). Coefficients are read from `coef` as given
    /// ([`Arg::Const`] or [`Arg::Load`]).
    pub fn horner(&mut self, support: &Support, coef: &[Arg], t: &[Arg]) -> Arg {
        let items: Vec<(&[u8], Arg)> = support
            .exponents()
            .iter()
            .map(|e| e.as_slice())
            .zip(coef.iter().copied())
            .collect();
        self.horner_rec(&items, t)
    }

    fn horner_rec(&mut self, items: &[(&[u8], Arg)], t: &[Arg]) -> Arg {
        if items.is_empty() {
            return Arg::Const(0.0);
        }
        if items[0].0.is_empty() {
            return items[0].1;
        }
        let d = items.iter().map(|e| e.0[0]).max().unwrap_or(0) as usize;
        let mut parts: Vec<Arg> = Vec::with_capacity(d + 1);
        for i in 0..=d {
            let sub: Vec<(&[u8], Arg)> = items
                .iter()
                .filter(|e| e.0[0] as usize == i)
                .map(|e| (&e.0[1..], e.1))
                .collect();
            parts.push(self.horner_rec(&sub, &t[1..]));
        }
        let mut acc = parts[d];
        for i in (0..d).rev() {
            acc = match parts[i] {
                Arg::Const(0.0) => self.op(Op::Mul(acc, t[0])),
                p => self.op(Op::Fma(acc, t[0], p)),
            };
        }
        acc
    }

    pub fn counts(&self) -> OpCount {
        let mut c = OpCount::default();
        let mut consts = 0;
        let mut arg = |a: &Arg, c: &mut OpCount| match a {
            Arg::Const(_) => consts += 1,
            Arg::Load { .. } => c.loads += 1,
            _ => {}
        };
        for s in &self.stmts {
            c.ops += 1;
            match s {
                Stmt::Float(op) => {
                    if matches!(op, Op::Div(..) | Op::Sqrt(_) | Op::Exp2(_)) {
                        c.special += 1;
                    }
                    for a in op_args(op) {
                        arg(&a, &mut c);
                    }
                }
                Stmt::Int(IntOp::Cell { x, .. }) => {
                    // conversion and clamp
                    c.ops += 1;
                    arg(x, &mut c);
                }
                Stmt::Int(_) => {}
            }
        }
        for (_, a) in &self.outputs {
            arg(a, &mut c);
        }
        c.constants = consts + self.arrays.iter().map(|a| a.len()).sum::<usize>();
        c
    }

    /// Evaluates in f64 (the constants are f32 values: what the code holds).
    pub fn eval(&self, x: &[f64]) -> Vec<f64> {
        self.run(x, |v| v)
    }

    /// Evaluates in f32 arithmetic, each operation rounded (a fused multiply-add as a
    /// multiply and an add, each rounded: the worse of the two ways a compiler may take).
    pub fn eval_f32(&self, x: &[f64]) -> Vec<f64> {
        self.run(x, |v| v as f32 as f64)
    }

    fn run(&self, x: &[f64], round: impl Fn(f64) -> f64) -> Vec<f64> {
        let mut fv: Vec<f64> = Vec::with_capacity(self.stmts.len());
        let mut iv: Vec<usize> = Vec::new();
        let val = |a: &Arg, fv: &[f64], iv: &[usize]| -> f64 {
            match *a {
                Arg::Input(k) => round(x[k]),
                Arg::Var(k) => fv[k],
                Arg::Const(c) => c as f64,
                Arg::Load {
                    array,
                    index,
                    offset,
                } => self.arrays[array][iv[index] + offset] as f64,
            }
        };
        for s in &self.stmts {
            match s {
                Stmt::Float(op) => {
                    let g = |a: &Arg| val(a, &fv, &iv);
                    let v = match op {
                        Op::Add(a, b) => round(g(a) + g(b)),
                        Op::Sub(a, b) => round(g(a) - g(b)),
                        Op::Mul(a, b) => round(g(a) * g(b)),
                        Op::Fma(a, b, c) => round(round(g(a) * g(b)) + g(c)),
                        Op::Div(a, b) => round(g(a) / g(b)),
                        Op::Sqrt(a) => round(g(a).sqrt()),
                        Op::Exp2(a) => round(g(a).exp2()),
                        Op::Min(a, b) => g(a).min(g(b)),
                        Op::Max(a, b) => g(a).max(g(b)),
                        Op::Clamp(a, lo, hi) => g(a).clamp(*lo as f64, *hi as f64),
                        Op::FromInt(k) => iv[*k] as f64,
                    };
                    fv.push(v);
                }
                Stmt::Int(op) => {
                    let v = match *op {
                        IntOp::Cell { x, cells } => {
                            let t = val(&x, &fv, &iv);
                            (t.max(0.0) as usize).min(cells - 1)
                        }
                        IntOp::MulAdd { a, k, b } => iv[a] * k + iv[b],
                        IntOp::Scale { a, k } => iv[a] * k,
                    };
                    iv.push(v);
                }
            }
        }
        self.outputs.iter().map(|(_, a)| val(a, &fv, &iv)).collect()
    }
}

/// The operands of an operation.
pub fn op_args(op: &Op) -> Vec<Arg> {
    match *op {
        Op::Add(a, b)
        | Op::Sub(a, b)
        | Op::Mul(a, b)
        | Op::Div(a, b)
        | Op::Min(a, b)
        | Op::Max(a, b) => {
            vec![a, b]
        }
        Op::Fma(a, b, c) => vec![a, b, c],
        Op::Sqrt(a) | Op::Exp2(a) | Op::Clamp(a, ..) => vec![a],
        Op::FromInt(_) => vec![],
    }
}

/// The value of an operation on constants only, if it is one (in f32, as the shader would).
fn fold(op: &Op) -> Option<f32> {
    let c = |a: &Arg| match a {
        Arg::Const(v) => Some(*v),
        _ => None,
    };
    Some(match op {
        Op::Add(a, b) => c(a)? + c(b)?,
        Op::Sub(a, b) => c(a)? - c(b)?,
        Op::Mul(a, b) => c(a)? * c(b)?,
        Op::Fma(a, b, d) => c(a)? * c(b)? + c(d)?,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn horner_program_matches_support_and_counts() {
        let s = Support::total_degree(2, 3);
        let coef: Vec<f64> = (0..s.len()).map(|k| 0.5 + k as f64 * 0.25).collect();
        let mut p = Program::new(&["x", "y"]);
        let cs: Vec<Arg> = coef.iter().map(|&c| Arg::Const(c as f32)).collect();
        let v = p.horner(&s, &cs, &[Arg::Input(0), Arg::Input(1)]);
        p.outputs.push(("v".into(), v));
        assert_eq!(p.counts().ops, s.horner_cost());
        assert_eq!(p.counts().constants, s.len());
        for t in [[0.3, -0.2], [1.0, 1.0], [-0.7, 0.9]] {
            let want = s.horner(&coef, &t);
            assert!((p.eval(&t)[0] - want).abs() < 1e-12);
            // f32: within the rounding bound of the Horner scheme
            let bound = s.rounding_weight(&coef) * f32::EPSILON as f64 / 2.0;
            assert!((p.eval_f32(&t)[0] - want).abs() <= bound, "{t:?}");
        }
    }

    #[test]
    fn piecewise_loads_and_counts() {
        let mut p = Program::new(&["x"]);
        p.arrays.push(vec![1.0, 2.0, 10.0, 20.0]);
        let xs = p.op(Op::Mul(Arg::Input(0), Arg::Const(2.0)));
        let cell = p.int_op(IntOp::Cell { x: xs, cells: 2 });
        let base = p.int_op(IntOp::Scale { a: cell, k: 2 });
        let a = Arg::Load {
            array: 0,
            index: base,
            offset: 0,
        };
        let b = Arg::Load {
            array: 0,
            index: base,
            offset: 1,
        };
        let v = p.op(Op::Fma(b, Arg::Input(0), a));
        p.outputs.push(("v".into(), v));
        assert_eq!(p.eval(&[0.25]), vec![1.5]);
        assert_eq!(p.eval(&[0.75]), vec![25.0]);
        assert_eq!(p.eval(&[1.0]), vec![30.0]);
        let c = p.counts();
        assert_eq!((c.ops, c.loads, c.constants), (5, 2, 5));
    }
}
