//! The generated lookup functions compile as written with the real compiler of every language
//! they target, for every table of every default preset and for test tables of each shape
//! (1D and 2D tables in a 2D texture, 3D tables in a 3D texture and in a 2D array, 1 to 4
//! channels, a scale):
//!
//! | language | wrapper | compiler |
//! |---|---|---|
//! | GLSL ES 3.00 (WebGL2) | fragment and vertex shader, no `precision` statement | glslangValidator |
//! | GLSL 3.30, 4.10, 4.50, 4.60 core (OpenGL) | fragment shader | glslangValidator |
//! | Vulkan GLSL 4.50 | fragment shader, combined image samplers at set 0 | glslangValidator -V, then spirv-val |
//! | HLSL (Shader Model 5 style) | pixel shader `main` | glslangValidator's HLSL front end (-D -V), then spirv-val |
//! | WGSL | (tests/shader_snippets.rs; the LTC area-light functions here) | naga, parse and full validation |
//!
//! The area-light functions of `ltc` tables (src/encode/shader_ltc.rs) are compiled with both
//! snippets of an LTC preset in one shader, every function called, in GLSL ES 3.00, 3.30 and
//! 4.60 core, Vulkan GLSL, HLSL and WGSL (`ltc_area_light_snippets_compile`).
//!
//! The GLSL ES wrapper declares no default precision: every declaration the snippet makes must
//! carry its own (bare ES 3.00 has none for `sampler3D`/`sampler2DArray` and a fragment shader
//! none for `float`), so a snippet that relied on one fails here. Microsoft's DXC does not
//! install from Debian (no `directx-shader-compiler` package in bookworm), so HLSL is compiled
//! by glslang's HLSL front end only. Chromium's ANGLE (GLSL ES) and Tint (WGSL) compile the
//! snippets too, in tests/gpu_path.rs.

#[path = "common/defaults.rs"]
mod defaults;
#[path = "common/judges.rs"]
mod judges;

use brdfbake::encode::shader::{lookup_function_name, ShaderLang, ShaderSnippet};
use brdfbake::encode::Encoder;
use brdfbake::lut::{Axis, Channel, Convention, Lut, Quantity};
use brdfbake::model::RoughnessQuantity;
use std::path::Path;
use std::process::Command;

/// A table to compile: its name, texels' shape, and the header attributes its snippets get.
struct Case {
    label: String,
    name: String,
    lut: Lut,
    attributes: Vec<(String, String)>,
}

fn axis(name: &str, size: usize, convention: Convention) -> Axis {
    Axis {
        name: name.into(),
        quantity: if name == "roughness" {
            Quantity::Roughness(RoughnessQuantity::Perceptual)
        } else {
            Quantity::Cosine
        },
        size,
        range: [0.0, 1.0],
        convention,
        warp: Default::default(),
        clamp: None,
    }
}

fn test_lut(axes: Vec<Axis>, nc: usize) -> Lut {
    let n: usize = axes.iter().map(|a| a.size).product();
    Lut {
        axes,
        channels: (0..nc)
            .map(|c| Channel {
                name: format!("C{c}"),
                meaning: "test".into(),
            })
            .collect(),
        data: vec![0.25; n * nc],
        error_estimate: vec![0.0; nc],
        evaluations: 0,
    }
}

/// Every default preset's tables, then test tables of the shapes the defaults lack (four
/// channels, a scale, a single-texel axis, an axis named like the texture parameter).
fn cases() -> Vec<Case> {
    let mut v: Vec<Case> = defaults::tables()
        .into_iter()
        .map(|(preset, t)| {
            let lut = defaults::shaped_lut(&t);
            Case {
                label: format!("{preset}/{}", t.spec.name),
                name: t.spec.name.clone(),
                attributes: brdfbake::meta::header_attributes(&preset, &t, &lut),
                lut,
            }
        })
        .collect();
    use Convention::{Centers, Endpoints};
    let tests = [
        (
            "rgba",
            test_lut(
                vec![
                    axis("cos_theta_v", 8, Centers),
                    axis("roughness", 6, Endpoints),
                ],
                4,
            ),
            vec![("scale".to_string(), "0.001".to_string())],
        ),
        (
            "btdf-critical",
            test_lut(
                {
                    use brdfbake::lut::Warp;
                    use brdfbake::model::FresnelQuantity;
                    vec![
                        Axis {
                            quantity: Quantity::Fresnel(FresnelQuantity::Eta),
                            warp: Warp::Square,
                            clamp: Some([1e-4, 1.0]),
                            ..axis("fresnel", 6, Endpoints)
                        },
                        Axis {
                            warp: Warp::CriticalAngle,
                            clamp: Some([1e-4, 0.9999]),
                            ..axis("cos_theta_v", 8, Endpoints)
                        },
                        axis("roughness", 4, Endpoints),
                    ]
                },
                2,
            ),
            vec![],
        ),
        (
            "line",
            test_lut(vec![axis("roughness", 10, Endpoints)], 3),
            vec![],
        ),
        (
            "thin-3d",
            test_lut(
                vec![
                    axis("lut", 4, Endpoints),
                    axis("roughness", 1, Centers),
                    axis("cos_theta_l", 5, Endpoints),
                ],
                4,
            ),
            vec![("scale".to_string(), "1e3".to_string())],
        ),
    ];
    for (name, lut, attributes) in tests {
        v.push(Case {
            label: format!("test table {name}"),
            name: name.into(),
            lut,
            attributes,
        });
    }
    v
}

fn snippet(lang: ShaderLang, c: &Case) -> String {
    let s = ShaderSnippet {
        lang,
        table_name: c.name.clone(),
    };
    String::from_utf8(s.encode(&c.lut, &c.attributes).expect("encodes")).expect("UTF-8")
}

/// The functions of a table's snippet: (name, texture kind: "2d", "3d" or "array").
fn functions(c: &Case) -> Vec<(String, &'static str)> {
    let f = lookup_function_name(&c.name);
    if c.lut.axes.len() == 3 {
        vec![(f.clone(), "3d"), (format!("{f}_array"), "array")]
    } else {
        vec![(f, "2d")]
    }
}

/// `coords.x, coords.y, …`: one argument per axis.
fn axis_args(c: &Case) -> String {
    (0..c.lut.axes.len())
        .map(|k| format!("coords.{}", ["x", "y", "z"][k]))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `v` widened to a 4-vector (`vec4` or `float4`) from the table's channel count.
fn widen(c: &Case, ty: &str, v: &str) -> String {
    match c.lut.channels.len() {
        1 => format!("{ty}({v}, 0.0, 0.0, 1.0)"),
        2 => format!("{ty}({v}, 0.0, 1.0)"),
        3 => format!("{ty}({v}, 1.0)"),
        _ => v.to_string(),
    }
}

/// A GLSL shader calling every function of the snippet. `dialect`: "es-frag", "es-vert",
/// "core-frag" or "vulkan-frag"; `version` the `#version` line.
fn glsl_shader(c: &Case, version: &str, dialect: &str) -> String {
    glsl_shader_of(c, &snippet(ShaderLang::Glsl, c), version, dialect)
}

/// [`glsl_shader`] around the snippet text `src`.
fn glsl_shader_of(c: &Case, src: &str, version: &str, dialect: &str) -> String {
    let es = dialect.starts_with("es");
    let vulkan = dialect == "vulkan-frag";
    let mut s = format!("{version}\n");
    s.push_str(src);
    let q = if es { "highp " } else { "" };
    let mut body = String::new();
    for (i, (f, kind)) in functions(c).iter().enumerate() {
        let ty = match *kind {
            "3d" => "sampler3D",
            "array" => "sampler2DArray",
            _ => "sampler2D",
        };
        let layout = if vulkan {
            format!("layout(set = 0, binding = {i}) ")
        } else {
            String::new()
        };
        s.push_str(&format!("{layout}uniform {q}{ty} tex{i};\n"));
        let call = format!("{f}(tex{i}, {})", axis_args(c));
        body.push_str(&format!("    result += {};\n", widen(c, "vec4", &call)));
    }
    let loc = if vulkan { "layout(location = 0) " } else { "" };
    if dialect == "es-vert" {
        s.push_str(&format!(
            "in {q}vec4 coords;\nout {q}vec4 value;\nvoid main()\n{{\n    {q}vec4 result = vec4(0.0);\n{body}    value = result;\n    gl_Position = coords;\n}}\n"
        ));
    } else {
        s.push_str(&format!(
            "{loc}in {q}vec4 coords;\n{loc}out {q}vec4 color;\nvoid main()\n{{\n    {q}vec4 result = vec4(0.0);\n{body}    color = result;\n}}\n"
        ));
    }
    s
}

/// An HLSL pixel shader calling every function of the snippet.
fn hlsl_shader(c: &Case) -> String {
    let mut s = snippet(ShaderLang::Hlsl, c);
    let mut body = String::from("    float4 result = float4(0.0, 0.0, 0.0, 0.0);\n");
    for (i, (f, kind)) in functions(c).iter().enumerate() {
        let ty = match *kind {
            "3d" => "Texture3D<float4>",
            "array" => "Texture2DArray<float4>",
            _ => "Texture2D<float4>",
        };
        s.push_str(&format!("{ty} tex{i} : register(t{i});\n"));
        let call = format!("{f}(tex{i}, smp, {})", axis_args(c));
        body.push_str(&format!("    result += {};\n", widen(c, "float4", &call)));
    }
    s.push_str(&format!(
        "SamplerState smp : register(s0);\nfloat4 main(float4 coords : TEXCOORD0) : SV_Target\n{{\n{body}    return result;\n}}\n"
    ));
    s
}

/// Runs a compiler; `Err` holds its command line and output.
fn run(cmd: &mut Command) -> Result<(), String> {
    let o = cmd.output().map_err(|e| format!("{cmd:?}: {e}"))?;
    if o.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{cmd:?} failed ({}):\n{}{}",
            o.status,
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ))
    }
}

/// Compiles `source` (written to `dir/file`) with glslangValidator `args`; with `spirv`, the
/// SPIR-V it writes is validated by spirv-val for Vulkan 1.1.
fn glslang(dir: &Path, file: &str, source: &str, args: &[&str], spirv: bool) -> Result<(), String> {
    let path = dir.join(file);
    std::fs::write(&path, source).unwrap();
    let spv = dir.join(format!("{file}.spv"));
    let mut cmd = Command::new("glslangValidator");
    cmd.args(args).arg(&path);
    if spirv {
        cmd.arg("-o").arg(&spv);
    }
    run(&mut cmd).map_err(|e| format!("{e}\n{source}"))?;
    if spirv {
        run(Command::new("spirv-val")
            .args(["--target-env", "vulkan1.1"])
            .arg(&spv))
        .map_err(|e| format!("{e}\n{source}"))?;
    }
    Ok(())
}

#[test]
fn glsl_snippets_compile_in_every_glsl_dialect() {
    if !(judges::glslang() && judges::spirv_val()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut failures = Vec::new();
    let mut compiled = 0;
    for c in cases() {
        let runs = [
            ("es.frag", "#version 300 es", "es-frag"),
            ("es.vert", "#version 300 es", "es-vert"),
            ("c330.frag", "#version 330 core", "core-frag"),
            ("c410.frag", "#version 410 core", "core-frag"),
            ("c450.frag", "#version 450 core", "core-frag"),
            ("c460.frag", "#version 460 core", "core-frag"),
            ("vk.frag", "#version 450", "vulkan-frag"),
        ];
        for (file, version, dialect) in runs {
            let stage = if dialect == "es-vert" { "vert" } else { "frag" };
            let spirv = dialect == "vulkan-frag";
            let args: &[&str] = if spirv {
                &["-V", "--target-env", "vulkan1.1", "-S", stage]
            } else {
                &["-S", stage]
            };
            let src = glsl_shader(&c, version, dialect);
            compiled += 1;
            if let Err(e) = glslang(dir.path(), file, &src, args, spirv) {
                failures.push(format!("{} ({version}, {dialect}): {e}", c.label));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {compiled} GLSL compiles failed:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
    // every default table and the test tables, seven dialects each
    assert!(compiled >= 7 * 24, "{compiled}");
}

#[test]
fn hlsl_snippets_compile_with_glslangs_hlsl_front_end() {
    if !(judges::glslang() && judges::spirv_val()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut failures = Vec::new();
    let mut compiled = 0;
    for c in cases() {
        let src = hlsl_shader(&c);
        compiled += 1;
        let args = [
            "-D",
            "-V",
            "--target-env",
            "vulkan1.1",
            "-e",
            "main",
            "-S",
            "frag",
        ];
        if let Err(e) = glslang(dir.path(), "ps.hlsl", &src, &args, true) {
            failures.push(format!("{}: {e}", c.label));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {compiled} HLSL compiles failed:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
    assert!(compiled >= 24, "{compiled}");
}

/// The check is not vacuous: the snippet as brdfbake generated it before the precision
/// qualifiers (bare `sampler3D`/`sampler2D` parameters and `float` locals) fails in GLSL ES
/// 3.00 with the error users saw, and compiles in GLSL 4.50 core.
#[test]
fn glsl_es_rejects_a_snippet_without_precision_qualifiers() {
    if !judges::glslang() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let c = cases()
        .into_iter()
        .find(|c| c.label == "cook-torrance-1982/vgroove-g")
        .expect("a default 3D table");
    // (the wrapper keeps its own qualifiers: only the snippet is bare)
    let src = snippet(ShaderLang::Glsl, &c).replace("highp ", "");
    let bare = |version: &str, dialect: &str| glsl_shader_of(&c, &src, version, dialect);
    let e = glslang(
        dir.path(),
        "bare.frag",
        &bare("#version 300 es", "es-frag"),
        &["-S", "frag"],
        false,
    )
    .expect_err("bare GLSL ES 3.00 fails");
    assert!(
        e.contains("requires declaration of default precision qualifier")
            || e.contains("No precision specified"),
        "{e}"
    );
    glslang(
        dir.path(),
        "bare450.frag",
        &bare("#version 450 core", "core-frag"),
        &["-S", "frag"],
        false,
    )
    .expect("desktop GLSL needs no precision");
}

/// The two tables of an LTC preset (the matrix, then norm and fresnel) with their snippets'
/// header attributes.
fn ltc_cases(preset: &str) -> Vec<Case> {
    let text = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == preset)
        .expect("an engine preset")
        .1;
    let p = brdfbake::preset::parse(text, preset, preset).expect("parses");
    p.tables
        .iter()
        .map(|t| {
            let lut = defaults::shaped_lut(t);
            Case {
                label: format!("{preset}/{}", t.spec.name),
                name: t.spec.name.clone(),
                attributes: brdfbake::meta::header_attributes(preset, t, &lut),
                lut,
            }
        })
        .collect()
}

/// A GLSL shader calling every area-light function of an LTC preset's two snippets
/// (`src`: both snippets), as [`glsl_shader_of`] wraps a lookup.
fn ltc_glsl_shader(src: &str, version: &str, dialect: &str) -> String {
    let es = dialect.starts_with("es");
    let vulkan = dialect == "vulkan-frag";
    let q = if es { "highp " } else { "" };
    let layout = |what: &str| {
        if vulkan {
            format!("layout({what}) ")
        } else {
            String::new()
        }
    };
    format!(
        "{version}\n{src}\
         {}uniform {q}sampler2D tex0;\n\
         {}uniform {q}sampler2D tex1;\n\
         {}in {q}vec4 coords;\n\
         {}out {q}vec4 color;\n\
         void main()\n{{\n\
         \x20   {q}vec3 n = normalize(coords.xyz);\n\
         \x20   {q}vec3 v = normalize(coords.yzx);\n\
         \x20   {q}float nv = dot(n, v);\n\
         \x20   {q}mat3 m = ltc_1_ltc_minv(tex0, coords.w, nv);\n\
         \x20   {q}float e = ltc_1_ltc_polygon(m, n, v, coords.xyz, coords.xyz, coords.yzx, coords.zxy, coords.xxy);\n\
         \x20   color = vec4(ltc_2_schlick_weight(tex1, coords.w, nv, vec3(0.04), vec3(1.0)) * max(e, 0.0), 1.0);\n\
         }}\n",
        layout("set = 0, binding = 0"),
        layout("set = 0, binding = 1"),
        layout("location = 0"),
        layout("location = 0"),
    )
}

/// An HLSL pixel shader calling every area-light function of an LTC preset's two snippets.
fn ltc_hlsl_shader(src: &str) -> String {
    format!(
        "{src}Texture2D<float4> tex0 : register(t0);\n\
         Texture2D<float4> tex1 : register(t1);\n\
         SamplerState smp : register(s0);\n\
         float4 main(float4 coords : TEXCOORD0) : SV_Target\n{{\n\
         \x20   float3 n = normalize(coords.xyz);\n\
         \x20   float3 v = normalize(coords.yzx);\n\
         \x20   float nv = dot(n, v);\n\
         \x20   float3x3 m = ltc_1_ltc_minv(tex0, smp, coords.w, nv);\n\
         \x20   float e = ltc_1_ltc_polygon(m, n, v, coords.xyz, coords.xyz, coords.yzx, coords.zxy, coords.xxy);\n\
         \x20   return float4(ltc_2_schlick_weight(tex1, smp, coords.w, nv, float3(0.04, 0.04, 0.04), float3(1.0, 1.0, 1.0)) * max(e, 0.0), 1.0);\n\
         }}\n"
    )
}

/// A WGSL fragment shader calling every area-light function of an LTC preset's two snippets.
fn ltc_wgsl_shader(src: &str) -> String {
    format!(
        "{src}@group(0) @binding(0) var tex0: texture_2d<f32>;\n\
         @group(0) @binding(1) var tex1: texture_2d<f32>;\n\
         @group(0) @binding(2) var smp: sampler;\n\
         @fragment\nfn main(@location(0) coords: vec4<f32>) -> @location(0) vec4<f32> {{\n\
         \x20   let n = normalize(coords.xyz);\n\
         \x20   let v = normalize(coords.yzx);\n\
         \x20   let nv = dot(n, v);\n\
         \x20   let m = ltc_1_ltc_minv(tex0, smp, coords.w, nv);\n\
         \x20   let e = ltc_1_ltc_polygon(m, n, v, coords.xyz, coords.xyz, coords.yzx, coords.zxy, coords.xxy);\n\
         \x20   return vec4<f32>(ltc_2_schlick_weight(tex1, smp, coords.w, nv, vec3<f32>(0.04), vec3<f32>(1.0)) * max(e, 0.0), 1.0);\n\
         }}\n"
    )
}

/// naga's full validation of a WGSL module; `Err` holds its message.
fn naga_wgsl(src: &str) -> Result<(), String> {
    let module = naga::front::wgsl::parse_str(src).map_err(|e| e.emit_to_string(src))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map(|_| ())
    .map_err(|e| format!("{e:?}"))
}

/// Compiles an LTC preset's two snippets, concatenated (the function names carry the table
/// names, so they coexist), with every area-light function called: GLSL in the dialects of
/// [`glsl_snippets_compile_in_every_glsl_dialect`], HLSL through glslang's front end, WGSL
/// through naga. Returns the failures and how many compiles were run.
fn compile_ltc(glsl: &str, hlsl: &str, wgsl: &str, dir: &Path) -> (Vec<String>, usize) {
    let mut failures = Vec::new();
    let mut n = 0;
    for (file, version, dialect) in [
        ("ltc-es.frag", "#version 300 es", "es-frag"),
        ("ltc-c330.frag", "#version 330 core", "core-frag"),
        ("ltc-c460.frag", "#version 460 core", "core-frag"),
        ("ltc-vk.frag", "#version 450", "vulkan-frag"),
    ] {
        let spirv = dialect == "vulkan-frag";
        let args: &[&str] = if spirv {
            &["-V", "--target-env", "vulkan1.1", "-S", "frag"]
        } else {
            &["-S", "frag"]
        };
        n += 1;
        if let Err(e) = glslang(
            dir,
            file,
            &ltc_glsl_shader(glsl, version, dialect),
            args,
            spirv,
        ) {
            failures.push(format!("GLSL {dialect} {version}: {e}"));
        }
    }
    n += 1;
    let args = [
        "-D",
        "-V",
        "--target-env",
        "vulkan1.1",
        "-e",
        "main",
        "-S",
        "frag",
    ];
    if let Err(e) = glslang(dir, "ltc.hlsl", &ltc_hlsl_shader(hlsl), &args, true) {
        failures.push(format!("HLSL: {e}"));
    }
    n += 1;
    let w = ltc_wgsl_shader(wgsl);
    if let Err(e) = naga_wgsl(&w) {
        failures.push(format!("WGSL (naga): {e}\n{w}"));
    }
    (failures, n)
}

/// The area-light functions of the LTC presets' snippets (heitz-ltc, threejs-ltc: the
/// matrix table's `ltc_1_ltc_minv`, `ltc_1_ltc_polygon` and helpers, the norm/fresnel
/// table's `ltc_2_schlick_weight`) compile in every language, and the check is not vacuous:
/// the same snippets with one error in the edge term (`cross(a)`: an argument missing) fail in each.
#[test]
fn ltc_area_light_snippets_compile() {
    if !(judges::glslang() && judges::spirv_val()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    for preset in ["heitz-ltc", "threejs-ltc"] {
        let cases = ltc_cases(preset);
        assert_eq!(cases.len(), 2, "{preset}");
        let both = |lang: ShaderLang| -> String {
            cases.iter().map(|c| snippet(lang, c)).collect::<String>()
        };
        let (glsl, hlsl, wgsl) = (
            both(ShaderLang::Glsl),
            both(ShaderLang::Hlsl),
            both(ShaderLang::Wgsl),
        );
        for (src, f) in [
            (&glsl, "ltc_1_ltc_polygon"),
            (&glsl, "ltc_2_schlick_weight"),
            (&hlsl, "ltc_1_ltc_minv"),
            (&wgsl, "ltc_1_ltc_theta_sin"),
        ] {
            assert!(src.contains(f), "{preset}: no {f}");
        }
        let (failures, n) = compile_ltc(&glsl, &hlsl, &wgsl, dir.path());
        assert!(
            failures.is_empty(),
            "{preset}: {} of {n} compiles failed:\n{}",
            failures.len(),
            failures.join("\n\n")
        );
        assert_eq!(n, 6);
        // the negative control: an argument missing in the edge term, in every language
        let broken = |s: &str| {
            assert!(s.contains("cross(a, b)"));
            s.replace("cross(a, b)", "cross(a)")
        };
        let (failures, n) = compile_ltc(&broken(&glsl), &broken(&hlsl), &broken(&wgsl), dir.path());
        assert_eq!(
            failures.len(),
            n,
            "{preset}: the broken snippets compiled somewhere:\n{}",
            failures.join("\n")
        );
    }
}
