//! Fitted functions (src/fit/, src/encode/function.rs): the emitted code compiles with the
//! real compilers (glslang for GLSL ES 3.00, GLSL 4.50 core and HLSL; naga for WGSL), a
//! fit's f32 evaluation stays within its stated error plus its f32 bound at points the fit
//! never saw, the fit is the same on one thread and on several, and a truncated fit fails
//! `verify`.

#[path = "common/judges.rs"]
mod judges;

use brdfbake::approx::program::Program;
use brdfbake::encode::function;
use brdfbake::fit::form::{Fitted, Form};
use brdfbake::fit::search::{self, Candidate, Weight};
use brdfbake::fit::target::{self, Target};
use brdfbake::fit::vars::{Var, VarSet, Warp};
use brdfbake::fit::{reference, verify};
use std::process::Command;

fn spec(name: &str) -> brdfbake::table::TableSpec {
    let (_, text) = brdfbake::presets::BUILTIN
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap();
    brdfbake::preset::parse(text, name, name).unwrap().tables[0]
        .spec
        .clone()
}

/// The split sum of `karis-envbrdf` shrunk to 32² texels (a 129² validation grid: fast).
fn small_dfg() -> Target {
    let mut s = spec("karis-envbrdf");
    for a in &mut s.axes {
        a.size = 32;
    }
    target::build(&s, None).unwrap()
}

fn exp2_vars(rate: f32) -> Vec<Var> {
    vec![
        Var::Axis {
            axis: 0,
            warp: Warp::Exp2 { rate },
        },
        Var::Axis {
            axis: 1,
            warp: Warp::Linear,
        },
    ]
}

fn degree6(t: &Target) -> Candidate {
    search::fit_polynomial(t, Weight::Absolute, &exp2_vars(-8.0), 6).unwrap()
}

/// A piecewise program (arrays, integer cell indices, loads) with arbitrary coefficients:
/// compiles the parts a global polynomial lacks.
fn piecewise_program(t: &Target) -> Program {
    let pts = search::points(t);
    let vars = VarSet::map_to(
        vec![
            Var::CornerAngle {
                mu: 0,
                rough: 1,
                square: true,
            },
            Var::CornerRadius {
                mu: 0,
                rough: 1,
                square: true,
            },
        ],
        &pts,
        0.0,
        1.0,
    );
    let s = brdfbake::approx::poly::Support::total_degree(2, 2);
    let coef: Vec<Vec<Vec<f32>>> = (0..2)
        .map(|c| {
            (0..9)
                .map(|k| (0..s.len()).map(|j| (c + k + j) as f32 * 0.125).collect())
                .collect()
        })
        .collect();
    Fitted {
        vars,
        form: Form::Piecewise {
            cells: vec![3, 3],
            exponents: s.exponents().to_vec(),
            coef,
        },
    }
    .program(&t.inputs, &t.channels)
}

fn run(cmd: &mut Command, src: &str) -> Result<(), String> {
    let o = cmd.output().map_err(|e| e.to_string())?;
    if o.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{}{}\n{src}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ))
    }
}

/// Every program in GLSL ES 3.00 and 4.50 core (fragment shaders calling it), HLSL (a pixel
/// shader, glslang's HLSL front end) and WGSL (naga: parse and full validation).
#[test]
fn emitted_functions_compile() {
    let t = small_dfg();
    let programs = vec![
        ("karis", reference::karis().program),
        ("sheen", reference::sheen().program),
        ("poly", degree6(&t).fitted.program(&t.inputs, &t.channels)),
        ("cells", piecewise_program(&t)),
    ];
    let dir = tempfile::tempdir().unwrap();
    let glslang = judges::glslang();
    for (name, p) in &programs {
        let n = p.outputs.len();
        let call = |args: &str| format!("{name}_fit({args})");
        // WGSL
        let w = function::encode(&function::Wgsl, &format!("{name}_fit"), p, &["test".into()]);
        let ret = if n == 1 {
            "f32".to_string()
        } else {
            format!("vec{n}<f32>")
        };
        let wsrc = format!(
            "{w}\n@fragment fn main(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {{\n    let v: {ret} = {};\n    return vec4<f32>(f32(v{}), 0.0, 0.0, 1.0);\n}}\n",
            call("uv.x, uv.y"),
            if n == 1 { "" } else { ".x" }
        );
        let module = naga::front::wgsl::parse_str(&wsrc)
            .unwrap_or_else(|e| panic!("{name}: {}\n{wsrc}", e.emit_to_string(&wsrc)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::all(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name}: {e:?}\n{wsrc}"));
        if !glslang {
            continue;
        }
        let g = function::encode(&function::Glsl, &format!("{name}_fit"), p, &[]);
        let x = if n == 1 { "" } else { ".x" };
        for (file, version) in [
            ("es.frag", "#version 300 es"),
            ("c450.frag", "#version 450 core"),
        ] {
            let src = format!(
                "{version}\n{g}\nin highp vec2 uv;\nout highp vec4 color;\nvoid main() {{ color = vec4(float({}{x}), 0.0, 0.0, 1.0); }}\n",
                call("uv.x, uv.y")
            );
            let path = dir.path().join(format!("{name}-{file}"));
            std::fs::write(&path, &src).unwrap();
            run(
                Command::new("glslangValidator")
                    .arg("-S")
                    .arg("frag")
                    .arg(&path),
                &src,
            )
            .unwrap_or_else(|e| panic!("{name} {version}: {e}"));
        }
        let h = function::encode(&function::Hlsl, &format!("{name}_fit"), p, &[]);
        let src = format!(
            "{h}\nfloat4 main(float2 uv : TEXCOORD0) : SV_Target {{ return float4(float({}{x}), 0.0, 0.0, 1.0); }}\n",
            call("uv.x, uv.y")
        );
        let path = dir.path().join(format!("{name}.hlsl"));
        std::fs::write(&path, &src).unwrap();
        run(
            Command::new("glslangValidator")
                .args(["-D", "-V", "-S", "frag", "-e", "main"])
                .arg(&path)
                .arg("-o")
                .arg(dir.path().join(format!("{name}.spv"))),
            &src,
        )
        .unwrap_or_else(|e| panic!("{name} HLSL: {e}"));
    }
}

/// A fit's program in f32 arithmetic (every operation rounded, as the shader runs it) at
/// 200 points it was not fitted on, against the exact integral at tolerance 1e-9: within
/// the fit's stated max error (measured on the validation grid; between grid points a
/// smooth fit's error can exceed it by the curvature over half a grid step — allowed 5%
/// here) plus its f32 bound plus the quadrature tolerance.
#[test]
fn f32_evaluation_is_within_the_stated_error() {
    let t = small_dfg();
    let c = degree6(&t);
    let p = c.fitted.program(&t.inputs, &t.channels);
    let v = verify(&t.spec, &t.inputs, &p, 200, 7, 1e-9).unwrap();
    for ch in 0..t.channels.len() {
        let allowed = 1.05 * c.error[ch] + c.f32_bound[ch] + 1e-9;
        assert!(
            v.error[ch] <= allowed,
            "channel {}: {} at {:?} > {allowed}",
            t.channels[ch],
            v.error[ch],
            v.argmax[ch]
        );
    }
}

/// The same coefficients on one thread and on two: the exchange is sequential, rayon only
/// distributes channels.
#[test]
fn deterministic_across_thread_counts() {
    let t = small_dfg();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| degree6(&t));
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
        .install(|| degree6(&t));
    assert_eq!(one.fitted, two.fitted);
    assert_eq!(one.error, two.error);
}

/// A fit with its constant terms zeroed fails verify against the error the full fit
/// states (the dropped term is far larger than the error).
#[test]
fn a_truncated_fit_fails_verify() {
    let t = small_dfg();
    let c = degree6(&t);
    let mut cut = c.fitted.clone();
    if let Form::Polynomial { channels } = &mut cut.form {
        for ch in channels.iter_mut() {
            // the constant term (exponents all 0): its loss shifts the whole function
            let k = ch
                .exponents
                .iter()
                .position(|e| e.iter().all(|&x| x == 0))
                .unwrap();
            ch.coef[k] = 0.0;
        }
    }
    let p = cut.program(&t.inputs, &t.channels);
    let v = verify(&t.spec, &t.inputs, &p, 50, 7, 1e-9).unwrap();
    let stated: f64 = c.max_total();
    assert!(
        v.error.iter().any(|&e| e > 10.0 * stated),
        "{:?} vs {stated}",
        v.error
    );
}

/// Inputs outside the domain never give NaN or Inf: an input under a square root or a
/// quotient is clamped in the code (a normal-mapped back face passes n·v < 0), and the other
/// forms are polynomials, finite everywhere. Evaluated in f32 as the code runs.
#[test]
fn inputs_outside_the_domain_stay_finite() {
    let t = small_dfg();
    let sqrt_vars = vec![
        Var::Axis {
            axis: 0,
            warp: Warp::Sqrt,
        },
        Var::Axis {
            axis: 1,
            warp: Warp::Linear,
        },
    ];
    let programs = [
        search::fit_polynomial(&t, Weight::Absolute, &sqrt_vars, 3)
            .unwrap()
            .fitted
            .program(&t.inputs, &t.channels),
        degree6(&t).fitted.program(&t.inputs, &t.channels),
        piecewise_program(&t),
    ];
    for p in &programs {
        for x in [
            [-0.5, 0.3],
            [-1e-3, -0.2],
            [1.5, 1.2],
            [0.0, 0.0],
            [-2.0, 3.0],
        ] {
            let y = p.eval_f32(&x);
            assert!(y.iter().all(|v| v.is_finite()), "{x:?} -> {y:?}");
        }
    }
}

/// `brdfbake verify` of a fit's sidecar: passes for the fit as written (exit 0), fails for the
/// same fit with a coefficient off by 0.05 (exit 1, the error named), and refuses a sidecar
/// without its fit (exit 2). The sidecar is the one `brdfbake fit --max-error` writes, made
/// here from a fit of the preset's function on a coarser grid (the same function).
#[test]
fn verify_of_a_fit_sidecar_passes_and_a_changed_fit_fails() {
    let t = small_dfg();
    let c = degree6(&t);
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, fit: serde_json::Value| {
        let doc = serde_json::json!({
            "schema": "brdfbake.fit/1", "preset": "karis-envbrdf", "table": "envbrdf",
            "channels": t.channels, "max_error": c.error, "f32_bound": c.f32_bound, "fit": fit,
        });
        let p = dir.path().join(name);
        std::fs::write(&p, doc.to_string()).unwrap();
        p
    };
    let run = |p: &std::path::Path| {
        Command::new(env!("CARGO_BIN_EXE_brdfbake"))
            .arg("verify")
            .arg(p)
            .output()
            .unwrap()
    };
    let good = run(&write(
        "good.json",
        serde_json::to_value(&c.fitted).unwrap(),
    ));
    assert_eq!(
        good.status.code(),
        Some(0),
        "{}{}",
        String::from_utf8_lossy(&good.stdout),
        String::from_utf8_lossy(&good.stderr)
    );
    let mut changed = c.fitted.clone();
    match &mut changed.form {
        Form::Polynomial { channels } => channels[0].coef[0] += 0.05,
        _ => unreachable!("a global polynomial"),
    }
    let bad = run(&write("bad.json", serde_json::to_value(&changed).unwrap()));
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("misses its stated error"));
    let broken = run(&write("broken.json", serde_json::json!({"vars": 3})));
    assert_eq!(broken.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&broken.stderr).contains("\"fit\""));
}
