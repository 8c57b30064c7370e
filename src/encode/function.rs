//! Fitted functions as source code: a [`Program`] printed as a GLSL, HLSL, WGSL, C or Rust
//! function, statement for statement (so the operation count in its comment is the count of
//! the code below it). One [`Dialect`] per language says how each operation is spelled; the
//! printer is shared. Pure: text in, text out.
//!
//! Constants print as the shortest decimal that reads back as the same f32 (Rust's `{:?}` of
//! an f32), so every compiler sees exactly the coefficients whose error the comment states.

use crate::approx::program::{Arg, IntOp, Op, Program, Stmt};

/// How one language spells the parts of a function.
pub trait Dialect {
    /// The file extension of a source holding the function.
    fn extension(&self) -> &'static str;
    /// `//` (every language here).
    fn comment(&self) -> &'static str {
        "//"
    }
    /// A float literal.
    fn float(&self, v: f32) -> String {
        let s = format!("{v:?}");
        let s = if s.contains(['.', 'e', 'E']) || s.contains("inf") || s.contains("NaN") {
            s
        } else {
            format!("{s}.0")
        };
        if v < 0.0 {
            format!("({s})")
        } else {
            s
        }
    }
    /// The return type for `n` outputs.
    fn ret(&self, n: usize) -> String;
    /// The signature line, up to and including `{`.
    fn signature(&self, name: &str, inputs: &[String], outputs: usize) -> String;
    /// A constant array at module scope.
    fn array(&self, name: &str, values: &[String]) -> String;
    /// `let`/`float` of a float statement.
    fn float_decl(&self, var: &str, expr: &str) -> String;
    /// The same for an integer statement.
    fn int_decl(&self, var: &str, expr: &str) -> String;
    /// A call of a one-argument function (`sqrt`, `exp2`).
    fn call1(&self, f: &str, a: &str) -> String {
        format!("{f}({a})")
    }
    fn min(&self, a: &str, b: &str) -> String {
        format!("min({a}, {b})")
    }
    fn max(&self, a: &str, b: &str) -> String {
        format!("max({a}, {b})")
    }
    fn clamp(&self, a: &str, lo: &str, hi: &str) -> String {
        format!("clamp({a}, {lo}, {hi})")
    }
    fn to_float(&self, i: &str) -> String;
    /// The cell index `min(int(x), cells − 1)` of x ≥ 0.
    fn cell(&self, x: &str, last: usize) -> String;
    /// An array element.
    fn load(&self, array: &str, index: &str, offset: usize) -> String {
        if offset == 0 {
            format!("{array}[{index}]")
        } else {
            format!("{array}[{index} + {offset}]")
        }
    }
    /// The return statement of `vals`.
    fn return_stmt(&self, vals: &[String]) -> String;
}

/// GLSL (ES 3.00 and desktop 3.30+): `highp` everywhere, which ES fragment shaders need.
pub struct Glsl;
/// HLSL (Shader Model 5 style).
pub struct Hlsl;
/// WGSL.
pub struct Wgsl;
/// C99 (`<math.h>`), outputs through a pointer.
pub struct C;
/// Rust (`f32`), outputs as an array.
pub struct Rust;

fn vec_ctor(prefix: &str, vals: &[String]) -> String {
    if vals.len() == 1 {
        vals[0].clone()
    } else {
        format!("{prefix}{}({})", vals.len(), vals.join(", "))
    }
}

impl Dialect for Glsl {
    fn extension(&self) -> &'static str {
        "glsl"
    }
    fn ret(&self, n: usize) -> String {
        if n == 1 {
            "highp float".into()
        } else {
            format!("highp vec{n}")
        }
    }
    fn signature(&self, name: &str, inputs: &[String], outputs: usize) -> String {
        let args: Vec<String> = inputs.iter().map(|i| format!("highp float {i}")).collect();
        format!("{} {name}({}) {{", self.ret(outputs), args.join(", "))
    }
    fn array(&self, name: &str, values: &[String]) -> String {
        format!(
            "const highp float {name}[{n}] = float[{n}]({});",
            values.join(", "),
            n = values.len()
        )
    }
    fn float_decl(&self, var: &str, expr: &str) -> String {
        format!("highp float {var} = {expr};")
    }
    fn int_decl(&self, var: &str, expr: &str) -> String {
        format!("int {var} = {expr};")
    }
    fn to_float(&self, i: &str) -> String {
        format!("float({i})")
    }
    fn cell(&self, x: &str, last: usize) -> String {
        format!("min(int({x}), {last})")
    }
    fn return_stmt(&self, vals: &[String]) -> String {
        format!("return {};", vec_ctor("vec", vals))
    }
}

impl Dialect for Hlsl {
    fn extension(&self) -> &'static str {
        "hlsl"
    }
    fn ret(&self, n: usize) -> String {
        if n == 1 {
            "float".into()
        } else {
            format!("float{n}")
        }
    }
    fn signature(&self, name: &str, inputs: &[String], outputs: usize) -> String {
        let args: Vec<String> = inputs.iter().map(|i| format!("float {i}")).collect();
        format!("{} {name}({}) {{", self.ret(outputs), args.join(", "))
    }
    fn array(&self, name: &str, values: &[String]) -> String {
        format!(
            "static const float {name}[{}] = {{ {} }};",
            values.len(),
            values.join(", ")
        )
    }
    fn float_decl(&self, var: &str, expr: &str) -> String {
        format!("float {var} = {expr};")
    }
    fn int_decl(&self, var: &str, expr: &str) -> String {
        format!("int {var} = {expr};")
    }
    fn to_float(&self, i: &str) -> String {
        format!("float({i})")
    }
    fn cell(&self, x: &str, last: usize) -> String {
        format!("min(int({x}), {last})")
    }
    fn return_stmt(&self, vals: &[String]) -> String {
        format!("return {};", vec_ctor("float", vals))
    }
}

impl Dialect for Wgsl {
    fn extension(&self) -> &'static str {
        "wgsl"
    }
    fn ret(&self, n: usize) -> String {
        if n == 1 {
            "f32".into()
        } else {
            format!("vec{n}<f32>")
        }
    }
    fn signature(&self, name: &str, inputs: &[String], outputs: usize) -> String {
        let args: Vec<String> = inputs.iter().map(|i| format!("{i}: f32")).collect();
        format!("fn {name}({}) -> {} {{", args.join(", "), self.ret(outputs))
    }
    fn array(&self, name: &str, values: &[String]) -> String {
        // a private var: WGSL indexes const arrays by constants only
        format!(
            "var<private> {name}: array<f32, {n}> = array<f32, {n}>({});",
            values.join(", "),
            n = values.len()
        )
    }
    fn float_decl(&self, var: &str, expr: &str) -> String {
        format!("let {var}: f32 = {expr};")
    }
    fn int_decl(&self, var: &str, expr: &str) -> String {
        format!("let {var}: i32 = {expr};")
    }
    fn to_float(&self, i: &str) -> String {
        format!("f32({i})")
    }
    fn cell(&self, x: &str, last: usize) -> String {
        format!("min(i32({x}), {last})")
    }
    fn return_stmt(&self, vals: &[String]) -> String {
        if vals.len() == 1 {
            format!("return {};", vals[0])
        } else {
            format!("return vec{}<f32>({});", vals.len(), vals.join(", "))
        }
    }
}

impl Dialect for C {
    fn extension(&self) -> &'static str {
        "c"
    }
    fn float(&self, v: f32) -> String {
        let s = Glsl.float(v.abs());
        let s = format!("{s}f");
        if v < 0.0 {
            format!("(-{s})")
        } else {
            s
        }
    }
    fn ret(&self, _: usize) -> String {
        "void".into()
    }
    fn signature(&self, name: &str, inputs: &[String], outputs: usize) -> String {
        let args: Vec<String> = inputs.iter().map(|i| format!("float {i}")).collect();
        format!(
            "static void {name}({}, float out[{outputs}]) {{",
            args.join(", ")
        )
    }
    fn array(&self, name: &str, values: &[String]) -> String {
        format!(
            "static const float {name}[{}] = {{ {} }};",
            values.len(),
            values.join(", ")
        )
    }
    fn float_decl(&self, var: &str, expr: &str) -> String {
        format!("const float {var} = {expr};")
    }
    fn int_decl(&self, var: &str, expr: &str) -> String {
        format!("const int {var} = {expr};")
    }
    fn call1(&self, f: &str, a: &str) -> String {
        format!("{f}f({a})")
    }
    fn min(&self, a: &str, b: &str) -> String {
        format!("fminf({a}, {b})")
    }
    fn max(&self, a: &str, b: &str) -> String {
        format!("fmaxf({a}, {b})")
    }
    fn clamp(&self, a: &str, lo: &str, hi: &str) -> String {
        format!("fminf(fmaxf({a}, {lo}), {hi})")
    }
    fn to_float(&self, i: &str) -> String {
        format!("(float){i}")
    }
    fn cell(&self, x: &str, last: usize) -> String {
        format!("((int){x} < {last} ? (int){x} : {last})")
    }
    fn return_stmt(&self, vals: &[String]) -> String {
        vals.iter()
            .enumerate()
            .map(|(k, v)| format!("out[{k}] = {v};"))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

impl Dialect for Rust {
    fn extension(&self) -> &'static str {
        "rs"
    }
    fn float(&self, v: f32) -> String {
        let s = Glsl.float(v.abs());
        let s = format!("{s}_f32");
        if v < 0.0 {
            format!("(-{s})")
        } else {
            s
        }
    }
    fn ret(&self, n: usize) -> String {
        format!("[f32; {n}]")
    }
    fn signature(&self, name: &str, inputs: &[String], outputs: usize) -> String {
        let args: Vec<String> = inputs.iter().map(|i| format!("{i}: f32")).collect();
        format!(
            "pub fn {name}({}) -> {} {{",
            args.join(", "),
            self.ret(outputs)
        )
    }
    fn array(&self, name: &str, values: &[String]) -> String {
        format!(
            "const {}: [f32; {}] = [{}];",
            name.to_uppercase(),
            values.len(),
            values.join(", ")
        )
    }
    fn float_decl(&self, var: &str, expr: &str) -> String {
        format!("let {var}: f32 = {expr};")
    }
    fn int_decl(&self, var: &str, expr: &str) -> String {
        format!("let {var}: usize = {expr};")
    }
    fn call1(&self, f: &str, a: &str) -> String {
        format!("({a}).{f}()")
    }
    fn min(&self, a: &str, b: &str) -> String {
        format!("({a}).min({b})")
    }
    fn max(&self, a: &str, b: &str) -> String {
        format!("({a}).max({b})")
    }
    fn clamp(&self, a: &str, lo: &str, hi: &str) -> String {
        format!("({a}).clamp({lo}, {hi})")
    }
    fn to_float(&self, i: &str) -> String {
        format!("{i} as f32")
    }
    fn cell(&self, x: &str, last: usize) -> String {
        // `as` saturates: a negative x gives 0
        format!("({x} as usize).min({last})")
    }
    fn load(&self, array: &str, index: &str, offset: usize) -> String {
        let a = array.to_uppercase();
        if offset == 0 {
            format!("{a}[{index}]")
        } else {
            format!("{a}[{index} + {offset}]")
        }
    }
    fn return_stmt(&self, vals: &[String]) -> String {
        format!("[{}]", vals.join(", "))
    }
}

/// The dialect of a language name: `glsl`, `hlsl`, `wgsl`, `c`, `rust`.
pub fn dialect(lang: &str) -> Option<Box<dyn Dialect>> {
    Some(match lang {
        "glsl" => Box::new(Glsl),
        "hlsl" => Box::new(Hlsl),
        "wgsl" => Box::new(Wgsl),
        "c" => Box::new(C),
        "rust" => Box::new(Rust),
        _ => return None,
    })
}

/// The languages [`dialect`] knows.
pub const LANGUAGES: [&str; 5] = ["glsl", "hlsl", "wgsl", "c", "rust"];

/// The program as a function `name` of `d`'s language, preceded by `comment` lines (the
/// fit's description, errors and operation count) and its constant arrays.
pub fn encode(d: &dyn Dialect, name: &str, program: &Program, comment: &[String]) -> String {
    let mut out = String::new();
    for l in comment {
        out.push_str(&format!("{} {l}\n", d.comment()));
    }
    let array_name = |k: usize| format!("{name}_c{k}");
    for (k, a) in program.arrays.iter().enumerate() {
        let v: Vec<String> = a.iter().map(|&x| d.float(x)).collect();
        out.push_str(&d.array(&array_name(k), &v));
        out.push('\n');
    }
    out.push_str(&d.signature(name, &program.inputs, program.outputs.len()));
    out.push('\n');
    let (mut nf, mut ni) = (0usize, 0usize);
    let arg = |a: &Arg| -> String {
        match *a {
            Arg::Input(k) => program.inputs[k].clone(),
            Arg::Var(k) => format!("t{k}"),
            Arg::Const(c) => d.float(c),
            Arg::Load {
                array,
                index,
                offset,
            } => d.load(&array_name(array), &format!("i{index}"), offset),
        }
    };
    for s in &program.stmts {
        let line = match s {
            Stmt::Float(op) => {
                let e = match op {
                    Op::Add(a, b) => format!("{} + {}", arg(a), arg(b)),
                    Op::Sub(a, b) => format!("{} - {}", arg(a), arg(b)),
                    Op::Mul(a, b) => format!("{} * {}", arg(a), arg(b)),
                    Op::Fma(a, b, c) => format!("{} * {} + {}", arg(a), arg(b), arg(c)),
                    Op::Div(a, b) => format!("{} / {}", arg(a), arg(b)),
                    Op::Sqrt(a) => d.call1("sqrt", &arg(a)),
                    Op::Exp2(a) => d.call1("exp2", &arg(a)),
                    Op::Min(a, b) => d.min(&arg(a), &arg(b)),
                    Op::Max(a, b) => d.max(&arg(a), &arg(b)),
                    Op::Clamp(a, lo, hi) => d.clamp(&arg(a), &d.float(*lo), &d.float(*hi)),
                    Op::FromInt(k) => d.to_float(&format!("i{k}")),
                };
                nf += 1;
                d.float_decl(&format!("t{}", nf - 1), &e)
            }
            Stmt::Int(op) => {
                let e = match *op {
                    IntOp::Cell { x, cells } => d.cell(&arg(&x), cells - 1),
                    IntOp::MulAdd { a, k, b } => format!("i{a} * {k} + i{b}"),
                    IntOp::Scale { a, k } => format!("i{a} * {k}"),
                };
                ni += 1;
                d.int_decl(&format!("i{}", ni - 1), &e)
            }
        };
        out.push_str("    ");
        out.push_str(&line);
        out.push('\n');
    }
    let vals: Vec<String> = program.outputs.iter().map(|(_, a)| arg(a)).collect();
    out.push_str("    ");
    out.push_str(&d.return_stmt(&vals));
    out.push_str("\n}\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Karis' fit printed in Rust reads as the formula: the literals read back exactly.
    #[test]
    fn literals_read_back_and_every_language_prints() {
        for v in [1.0f32, -0.0275, 1e-20, 0.1, 3.0e7, -1.04] {
            let s = Glsl.float(v);
            let t: f32 = s.trim_matches(['(', ')']).parse().unwrap();
            assert_eq!(t, v, "{s}");
        }
        let p = crate::fit::reference::karis().program;
        for l in LANGUAGES {
            let s = encode(&*dialect(l).unwrap(), "env_brdf", &p, &["test".into()]);
            assert!(s.contains("exp2"), "{l}: {s}");
            assert_eq!(s.matches("t10").count(), 2, "{l}: {s}");
        }
    }
}
